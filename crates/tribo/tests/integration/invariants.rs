//! Invariants as property tests: rigid-body modes in ker K, M1 row sums, the P1 multiplier basis sums to
//! one, the common refinement covers Γ_C exactly (also with nearly coincident breakpoints).

use proptest::prelude::*;
use tribo::mortar::{common_refinement, MortarMatrices};
use tribo::*;

/// A rectangle mesh with random size, resolution and diagonal pattern.
fn any_mesh() -> impl Strategy<Value = Mesh> {
    (0.5f64..3.0, 0.5f64..3.0, 1usize..9, 1usize..9, 0usize..3).prop_map(|(w, h, nx, ny, d)| {
        let diag = [Diagonal::Right, Diagonal::Left, Diagonal::Alternating][d];
        rectangle([-w / 2.0, w / 2.0], [-h, 0.0], nx, ny, diag).expect("valid")
    })
}

proptest! {
    // The regression file beside this one is read (its cases run first).
    #![proptest_config(ProptestConfig { failure_persistence: ProptestConfig::default().failure_persistence, ..crate::reproducible(48) })]

    /// K r = 0 for the three rigid-body modes, up to round-off: |K r| ≤ 8 ε ‖K‖₁ ‖r‖∞ (a sum of at most
    /// 8 products per entry per element, each exact to ε).
    #[test]
    fn rigid_body_modes_are_in_the_kernel(mesh in any_mesh(), young in 1e-3f64..1e6, poisson in -0.9f64..0.49) {
        let k = elasticity::stiffness(&mesh, &Material { young, poisson }).expect("assembles");
        let n = 2 * mesh.n_nodes();
        let modes: Vec<Vec<f64>> = vec![
            (0..n).map(|d| if d % 2 == 0 { 1.0 } else { 0.0 }).collect(),
            (0..n).map(|d| if d % 2 == 1 { 1.0 } else { 0.0 }).collect(),
            (0..n).map(|d| { let p = mesh.points()[d / 2]; if d % 2 == 0 { -p[1] } else { p[0] } }).collect(),
        ];
        let k = k.as_ref();
        let mut norm1: f64 = 0.0;
        for j in 0..n {
            norm1 = norm1.max(k.val_of_col(j).iter().map(|v| v.abs()).sum());
        }
        for r in &modes {
            let rmax = r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let mut kr = vec![0.0; n];
            for (j, rj) in r.iter().enumerate() {
                for (i, v) in k.row_idx_of_col(j).zip(k.val_of_col(j)) {
                    kr[i] += v * rj;
                }
            }
            let res = kr.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            prop_assert!(res <= 8.0 * f64::EPSILON * norm1 * rmax, "|K r| = {res:e}, ‖K‖ = {norm1:e}");
        }
    }

    /// Row sums of M1 are ∫φ_i (half the lengths of the edges at node i), so they add up to |Γ_C|;
    /// M2 and M3 row sums equal them too (ψ_j and χ_k are partitions of unity); column sums of M2 are ∫ψ_j.
    #[test]
    fn mortar_row_sums(mesh in any_mesh(), pts in proptest::collection::vec(0.0f64..1.0, 0..12), p0 in any::<bool>()) {
        let contact = ContactBoundary::new(&mesh, "top").expect("straight");
        let (a, b) = (contact.start(), contact.end());
        let mut xi: Vec<f64> = pts.iter().map(|t| a + t * (b - a)).collect();
        xi.extend([a, b]);
        xi.sort_by(f64::total_cmp);
        xi.dedup_by(|x, y| (*x - *y).abs() < 1e-9 * (b - a));
        let space = if p0 { MultiplierSpace::P0 } else { MultiplierSpace::P1 };
        let mult = MultiplierMesh::new(&contact, &MultiplierPoints::Abscissae(xi), space).expect("valid T_H");
        let h_t: Vec<f64> = contact.edges.iter().map(|e| mesh.diameter(e.triangle)).collect();
        let m = MortarMatrices::new(&contact, &mult, &h_t, &Obstacle::default(), Model::PlaneStrain).expect("integrates");
        let tol = 16.0 * f64::EPSILON * contact.length();
        let expected: Vec<f64> = (0..contact.nodes.len())
            .map(|i| {
                let l = if i > 0 { contact.edges[i - 1].length } else { 0.0 };
                let r = if i < contact.n_edges() { contact.edges[i].length } else { 0.0 };
                0.5 * (l + r)
            })
            .collect();
        for sums in [m.m1.row_sums(), m.m2.row_sums(), m.m3.row_sums()] {
            for (s, e) in sums.iter().zip(&expected) {
                prop_assert!((s - e).abs() <= tol, "row sum {s} vs {e}");
            }
        }
        prop_assert!((m.m1.row_sums().iter().sum::<f64>() - contact.length()).abs() <= tol);
        let mut col = vec![0.0; mult.n_dofs()];
        for &(_, j, v) in &m.m2.entries {
            col[j] += v;
        }
        for (c, w) in col.iter().zip(&m.psi_integrals) {
            prop_assert!((c - w).abs() <= tol);
        }
    }

    /// The P1 multiplier basis sums to one everywhere on Γ_C, and the P0 one too.
    #[test]
    fn multiplier_basis_is_a_partition_of_unity(pts in proptest::collection::vec(0.0f64..1.0, 0..20), t in 0.0f64..1.0) {
        let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 4, 4, Diagonal::Right).expect("valid");
        let contact = ContactBoundary::new(&mesh, "bottom").expect("straight");
        let mut xi: Vec<f64> = pts;
        xi.extend([0.0, 1.0]);
        xi.sort_by(f64::total_cmp);
        xi.dedup_by(|x, y| (*x - *y).abs() < 1e-9);
        for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
            let mult = MultiplierMesh::new(&contact, &MultiplierPoints::Abscissae(xi.clone()), space).expect("valid");
            let ones = vec![1.0; mult.n_dofs()];
            let v = mult.evaluate(&ones, t);
            prop_assert!((v - 1.0).abs() <= 4.0 * f64::EPSILON, "sum of basis functions at {t} is {v}");
        }
    }

    /// The pieces of the common refinement tile [start, end] with no gap and no overlap, each piece lies
    /// in its FE edge and (up to the merging tolerance √ε h_E) in its multiplier cell, and none is a sliver
    /// (shorter than √ε h_E) — also when multiplier points are within a few ulps of FE nodes or of each
    /// other.
    #[test]
    fn common_refinement_covers_the_contact_boundary(
        n_fe in 1usize..30,
        pts in proptest::collection::vec(0.0f64..1.0, 0..30),
        jitter in proptest::collection::vec(-4i32..5, 0..30),
    ) {
        let fe: Vec<f64> = (0..=n_fe).map(|i| i as f64 / n_fe as f64).collect();
        // Multiplier points: random ones plus FE nodes moved by a few ulps.
        let mut xi: Vec<f64> = pts;
        for (k, j) in jitter.iter().enumerate() {
            let node = fe[k % fe.len()];
            xi.push(node + *j as f64 * f64::EPSILON * node.max(1e-300));
            // and a second point a few ulps from the first
            xi.push(node + (*j + 2) as f64 * f64::EPSILON * node.max(1e-300));
        }
        xi.retain(|x| *x > 0.0 && *x < 1.0);
        xi.extend([0.0, 1.0]);
        xi.sort_by(f64::total_cmp);
        xi.dedup();
        let pieces = common_refinement(&fe, &xi);
        prop_assert_eq!(pieces[0].a, 0.0);
        prop_assert_eq!(pieces.last().unwrap().b, 1.0);
        let tol = f64::EPSILON.sqrt();
        let mut total = 0.0;
        for (k, p) in pieces.iter().enumerate() {
            if k > 0 {
                prop_assert_eq!(p.a, pieces[k - 1].b, "pieces must be contiguous");
            }
            prop_assert!(p.b > p.a, "empty piece {:?}", p);
            let (e0, e1) = (fe[p.edge], fe[p.edge + 1]);
            let (c0, c1) = (xi[p.cell], xi[p.cell + 1]);
            let local = e1 - e0;
            prop_assert!(p.a >= e0 && p.b <= e1, "piece {:?} outside its FE edge", p);
            prop_assert!(p.a >= c0 - tol * local && p.b <= c1 + tol * local, "piece {:?} outside its cell", p);
            prop_assert!(p.b - p.a > tol * local, "sliver {:?}", p);
            total += p.b - p.a;
        }
        prop_assert!((total - 1.0).abs() <= 4.0 * f64::EPSILON * pieces.len() as f64);
    }
}
