//! Test-matrix generator: P1 plane-strain elasticity on a structured
//! triangulated rectangle, clamped on the top side, with mortar-like contact
//! rows on the bottom side.
//!
//! Geometry: `nx × ny` square cells of size `h = 1/ny` (the height is 1, the
//! width `nx/ny`), each split into two triangles. Nodes `(i, j)`,
//! `0 ≤ i ≤ nx`, `0 ≤ j ≤ ny`; the nodes of the top row `j = ny` are clamped
//! (their dofs are removed), so `n = 2 (nx+1) ny` with dof `2 (j (nx+1) + i) + c`
//! (`c = 0` for x, `1` for y).
//!
//! Contact rows: for each bottom node `i` two multipliers, `2i` (normal, outward
//! normal `(0,-1)`) and `2i+1` (tangential, `(1,0)`), so `m = 2 (nx+1)`. The
//! row has the P1 boundary-mass weights `h/6, 2h/3, h/6` on the nodes
//! `i-1, i, i+1` (`h/3` on the end node itself at the two corners).
//! `D = γ0 M ⊗ I₂` with `M` the same P1 boundary mass matrix and
//! `γ0 = 1e-4 h` (or `D = 0`).

use faer::sparse::{SparseColMat, Triplet};

/// Young's modulus of the generated problems.
pub const YOUNG: f64 = 200.0;
/// Poisson ratio of the generated problems.
pub const POISSON: f64 = 0.3;

/// A generated contact test problem.
pub struct ContactProblem {
    /// SPD stiffness, `n × n`, both triangles stored.
    pub a: SparseColMat<usize, f64>,
    /// Rows of `E` (`m` rows, sorted by column).
    pub e_rows: Vec<Vec<(usize, f64)>>,
    /// Entries `(i, j, v)` of `D` (both triangles; empty when `D = 0`).
    pub d: Vec<(usize, usize, f64)>,
    pub n: usize,
    pub m: usize,
    pub h: f64,
}

/// P1 boundary mass weight between bottom nodes `i` and `k` (`|i-k| ≤ 1`).
fn bmass(nx: usize, h: f64, i: usize, k: usize) -> f64 {
    if i != k {
        h / 6.0
    } else if i == 0 || i == nx {
        h / 3.0
    } else {
        2.0 * h / 3.0
    }
}

/// Generates the problem described in the module docs. `with_d = false` gives `D = 0`.
///
/// Panics if `nx == 0 || ny == 0` (test helper).
pub fn contact_problem(nx: usize, ny: usize, with_d: bool) -> ContactProblem {
    assert!(nx > 0 && ny > 0);
    let h = 1.0 / ny as f64;
    let n = 2 * (nx + 1) * ny;
    let m = 2 * (nx + 1);
    let (e, nu) = (YOUNG, POISSON);
    let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let c = [[lam + 2.0 * mu, lam, 0.0], [lam, lam + 2.0 * mu, 0.0], [0.0, 0.0, mu]];
    let node = |i: usize, j: usize| j * (nx + 1) + i;
    let dof = |nd: usize, comp: usize| -> Option<usize> {
        if nd / (nx + 1) == ny {
            None
        } else {
            Some(2 * nd + comp)
        }
    };
    let xy = |nd: usize| ((nd % (nx + 1)) as f64 * h, (nd / (nx + 1)) as f64 * h);

    let mut trip = Vec::with_capacity(nx * ny * 2 * 36);
    for j in 0..ny {
        for i in 0..nx {
            let tris =
                [[node(i, j), node(i + 1, j), node(i + 1, j + 1)], [node(i, j), node(i + 1, j + 1), node(i, j + 1)]];
            for t in tris {
                let p = t.map(xy);
                let mut b = [0.0; 3];
                let mut cc = [0.0; 3];
                for k in 0..3 {
                    let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                    b[k] = p[k1].1 - p[k2].1;
                    cc[k] = p[k2].0 - p[k1].0;
                }
                let area2 = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
                let area = 0.5 * area2;
                // B (3 × 6)
                let mut bm = [[0.0; 6]; 3];
                for k in 0..3 {
                    bm[0][2 * k] = b[k] / area2;
                    bm[1][2 * k + 1] = cc[k] / area2;
                    bm[2][2 * k] = cc[k] / area2;
                    bm[2][2 * k + 1] = b[k] / area2;
                }
                for r in 0..6 {
                    let Some(gr) = dof(t[r / 2], r % 2) else { continue };
                    for s in 0..6 {
                        let Some(gs) = dof(t[s / 2], s % 2) else { continue };
                        let mut v = 0.0;
                        for p_ in 0..3 {
                            for q in 0..3 {
                                v += bm[p_][r] * c[p_][q] * bm[q][s];
                            }
                        }
                        trip.push(Triplet::new(gr, gs, area * v));
                    }
                }
            }
        }
    }
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip).expect("assembly");

    let mut e_rows = vec![Vec::new(); m];
    for i in 0..=nx {
        let lo = i.saturating_sub(1);
        let hi = (i + 1).min(nx);
        for k in lo..=hi {
            let w = bmass(nx, h, i, k);
            let nd = node(k, 0);
            e_rows[2 * i].push((2 * nd + 1, -w));
            e_rows[2 * i + 1].push((2 * nd, w));
        }
    }
    for r in e_rows.iter_mut() {
        r.sort_by_key(|&(cidx, _)| cidx);
    }
    let mut d = Vec::new();
    if with_d {
        let g0 = 1e-4 * h;
        for i in 0..=nx {
            for k in i.saturating_sub(1)..=(i + 1).min(nx) {
                let w = g0 * bmass(nx, h, i, k);
                d.push((2 * i, 2 * k, w));
                d.push((2 * i + 1, 2 * k + 1, w));
            }
        }
    }
    ContactProblem { a, e_rows, d, n, m, h }
}
