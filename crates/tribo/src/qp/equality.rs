//! The equality rows of a Γ_C QP eliminated: the equilibrium of the bodies held only by the contact.
//!
//! # Why
//! A body held only by the contact adds r ≤ 3 rows `G̃ x = b̃` to its QP (one per rigid motion the multipliers
//! see; `problem/floating.rs`). Handed to clarabel as a zero cone, they leave a zero block in its KKT systems,
//! which clarabel regularizes by its default 1e-8 (1e-10 and 1e-12 failed at once: "numerical error"). That is
//! more than its iterative refinement corrects as the mesh is refined, and the interior-point method stalls:
//! a block (0, 2) × (0, 1) held only by the contact, pressed by the traction (0.15, −1) with μ = 0.3, ν = 0.3, failed
//! its first Coulomb QP ("insufficient progress", the dual residual stuck at 1e-7) from 160 × 80 cells on, and at
//! ν = 0, μ = 1 half of the QPs met only the fallback tolerance.
//!
//! # The elimination
//! Gauss–Jordan elimination with complete pivoting picks r unknowns `x_p`, one per row, with the largest pivots,
//! and writes the rows as `x_p = x₀ + M x_N` over the other unknowns `x_N`. The QP over `x_N` alone has the
//! objective `½ x_Nᵀ (Tᵀ P T) x_N + (Tᵀ (P t₀ + q))ᵀ x_N` (`x = T x_N + t₀`), its own box rows, and the box rows of
//! the pivots, which become dense rows over `x_N`: a QP with inequality rows only, which clarabel solves with the
//! regularization of the box QPs (`BOX_REGULARIZATION`, 1e-12). The equality rows' duals y (the rigid motions) follow from stationarity at the
//! pivots, `G̃_pᵀ y = −(P x + q + Ãᵀ z)_p`, z the duals of the pivots' box rows.

use nalgebra::{DMatrix, DVector};

/// The smallest pivot, relative to the largest entry of the rows, that the elimination takes: below it the rows
/// are (numerically) dependent and the QP keeps them as a zero cone.
const PIVOT_FLOOR: f64 = 1e-10;

/// The rows `G̃ x = b̃` solved for one unknown each (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct Elimination {
    /// The pivot unknown of each row, in the order of the elimination.
    pub pivots: Vec<usize>,
    /// The other unknowns, increasing.
    pub rest: Vec<usize>,
    /// `x_p = x0 + m x_N`: x0 per pivot.
    pub x0: Vec<f64>,
    /// `m` (r × (k − r)), row by row.
    pub m: Vec<Vec<f64>>,
    /// The original rows' columns at the pivots (`g_p[e][a] = G̃[e][p_a]`), for the duals.
    g_p: Vec<Vec<f64>>,
}

impl Elimination {
    /// Solves the rows `rows` (r × k) with right-hand side `b` for r pivots; `None` if the rows are dependent, not
    /// finite, or leave no unknown over (r ≥ k: the QP keeps them as a zero cone).
    pub(crate) fn new(rows: &[Vec<f64>], b: &[f64]) -> Option<Self> {
        let r = rows.len();
        let k = rows.first().map_or(0, Vec::len);
        if r == 0 || r >= k || !rows.iter().flatten().chain(b).all(|v| v.is_finite()) {
            return None;
        }
        let largest = rows.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        if largest == 0.0 {
            return None;
        }
        let (mut a, mut rhs) = (rows.to_vec(), b.to_vec());
        let mut pivots = Vec::with_capacity(r);
        let mut order = Vec::with_capacity(r);
        for _ in 0..r {
            // The largest entry among the rows not yet used.
            let mut best = (0.0, 0, 0);
            for (e, row) in a.iter().enumerate().filter(|(e, _)| !order.contains(e)) {
                for (j, v) in row.iter().enumerate() {
                    if v.abs() > best.0 {
                        best = (v.abs(), e, j);
                    }
                }
            }
            let (size, e, j) = best;
            if size <= PIVOT_FLOOR * largest {
                return None;
            }
            let p = a[e][j];
            a[e].iter_mut().for_each(|v| *v /= p);
            rhs[e] /= p;
            let (pivot_row, pivot_rhs) = (a[e].clone(), rhs[e]);
            for f in (0..r).filter(|&f| f != e) {
                let factor = a[f][j];
                if factor != 0.0 {
                    a[f].iter_mut().zip(&pivot_row).for_each(|(v, pv)| *v -= factor * pv);
                    rhs[f] -= factor * pivot_rhs;
                }
            }
            pivots.push(j);
            order.push(e);
        }
        let rest: Vec<usize> = (0..k).filter(|j| !pivots.contains(j)).collect();
        let x0 = order.iter().map(|&e| rhs[e]).collect();
        let m = order.iter().map(|&e| rest.iter().map(|&j| -a[e][j]).collect()).collect();
        let g_p = rows.iter().map(|row| pivots.iter().map(|&p| row[p]).collect()).collect();
        Some(Self { pivots, rest, x0, m, g_p })
    }

    /// All k unknowns from the others `x_rest`.
    pub(crate) fn expand(&self, x_rest: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.rest.len() + self.pivots.len()];
        for (&j, v) in self.rest.iter().zip(x_rest) {
            x[j] = *v;
        }
        for (a, &p) in self.pivots.iter().enumerate() {
            x[p] = self.x0[a] + self.m[a].iter().zip(x_rest).map(|(m, v)| m * v).sum::<f64>();
        }
        x
    }

    /// The reduced QP's P (its upper triangle, column by column) and q, for the full QP's P (entry by entry,
    /// symmetric) and q.
    pub(crate) fn reduce(&self, p: impl Fn(usize, usize) -> f64, q: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (k, n) = (q.len(), self.rest.len());
        // u[a][j] = P(p_a, j) over all j; w[a][i] = Σ_b P(p_a, p_b) m[b][i] over the rest.
        let u: Vec<Vec<f64>> = self.pivots.iter().map(|&pa| (0..k).map(|j| p(pa, j)).collect()).collect();
        let w: Vec<Vec<f64>> = (0..self.pivots.len())
            .map(|a| {
                (0..n).map(|i| self.pivots.iter().enumerate().map(|(b, &pb)| u[a][pb] * self.m[b][i]).sum()).collect()
            })
            .collect();
        let mut upper = Vec::with_capacity(n * (n + 1) / 2);
        for (jj, &j) in self.rest.iter().enumerate() {
            for (ii, &i) in self.rest.iter().enumerate().take(jj + 1) {
                let mut v = p(i, j);
                for (a, m) in self.m.iter().enumerate() {
                    v += m[ii] * u[a][j] + u[a][i] * m[jj] + m[ii] * w[a][jj];
                }
                upper.push(v);
            }
        }
        // Tᵀ (P t₀ + q), t₀ the pivots at x0 and 0 elsewhere: at i, P(i, p) x0 + q_i + Σ_a m[a][i] (P(p_a, p) x0 + q_p_a).
        let pt0 = |i: usize| self.pivots.iter().zip(&self.x0).map(|(&pb, x)| p(i, pb) * x).sum::<f64>();
        let at_pivots: Vec<f64> = self.pivots.iter().map(|&pa| pt0(pa) + q[pa]).collect();
        let reduced_q = self
            .rest
            .iter()
            .enumerate()
            .map(|(ii, &i)| pt0(i) + q[i] + self.m.iter().zip(&at_pivots).map(|(m, v)| m[ii] * v).sum::<f64>())
            .collect();
        (upper, reduced_q)
    }

    /// The duals y of the original rows from stationarity at the pivots, `G̃_pᵀ y = −s_p`, `s_p` the gradient of
    /// the Lagrangian without the rows at each pivot (`(P x + q + Ãᵀ z)_p`). `None` if `G̃_p` is singular.
    pub(crate) fn duals(&self, s_p: &[f64]) -> Option<Vec<f64>> {
        let r = self.pivots.len();
        let gt = DMatrix::from_fn(r, r, |a, e| self.g_p[e][a]);
        let y = gt.lu().solve(&DVector::from_iterator(r, s_p.iter().map(|v| -v)))?;
        Some(y.iter().copied().collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two rows over five unknowns: the expansion meets them for any x_N, and the reduced objective is the full one
    /// along the affine set.
    #[test]
    fn the_reduced_qp_is_the_full_one_on_the_rows() {
        let rows = vec![vec![0.0, 2.0, -1.0, 0.5, 0.0], vec![1.0, 0.0, 3.0, 0.0, -0.25]];
        let b = vec![1.0, -2.0];
        let e = Elimination::new(&rows, &b).expect("independent rows");
        assert_eq!(e.pivots, vec![2, 1], "the largest pivot first (3), then the largest left in the other row (2)");
        let p = |i: usize, j: usize| if i == j { 2.0 + i as f64 } else { 0.3 / (1.0 + i as f64 + j as f64) };
        let q = [0.5, -1.0, 0.25, 2.0, -0.75];
        let (upper, rq) = e.reduce(p, &q);
        let full = |x: &[f64]| {
            let quad: f64 = (0..5).flat_map(|i| (0..5).map(move |j| (i, j))).map(|(i, j)| x[i] * p(i, j) * x[j]).sum();
            0.5 * quad + q.iter().zip(x).map(|(a, b)| a * b).sum::<f64>()
        };
        let n = e.rest.len();
        let at = |i: usize, j: usize| if i <= j { upper[j * (j + 1) / 2 + i] } else { upper[i * (i + 1) / 2 + j] };
        let reduced = |y: &[f64]| {
            let quad: f64 = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).map(|(i, j)| y[i] * at(i, j) * y[j]).sum();
            0.5 * quad + rq.iter().zip(y).map(|(a, b)| a * b).sum::<f64>()
        };
        let constant = full(&e.expand(&[0.0, 0.0, 0.0]));
        for y in [[0.0, 0.0, 0.0], [1.0, -2.0, 0.5], [-0.3, 0.7, 4.0]] {
            let x = e.expand(&y);
            for (row, bi) in rows.iter().zip(&b) {
                let g: f64 = row.iter().zip(&x).map(|(a, b)| a * b).sum();
                assert!((g - bi).abs() < 1e-14, "{g} against {bi}");
            }
            assert!((full(&x) - (reduced(&y) + constant)).abs() < 1e-12);
        }
    }

    /// Dependent rows are refused (the QP keeps them as a zero cone), and so are no rows, rows that leave no unknown
    /// over and rows that are not finite.
    #[test]
    fn dependent_rows_are_refused() {
        assert!(Elimination::new(&[vec![1.0, 2.0, 0.0], vec![2.0, 4.0, 0.0]], &[1.0, 2.0]).is_none());
        assert!(Elimination::new(&[], &[]).is_none());
        assert!(Elimination::new(&[vec![0.0, 0.0]], &[1.0]).is_none());
        assert!(Elimination::new(&[vec![1.0, 0.0], vec![0.0, 1.0]], &[1.0, 2.0]).is_none());
        assert!(Elimination::new(&[vec![1.0, f64::NAN, 0.0]], &[1.0]).is_none());
        assert!(Elimination::new(&[vec![1.0, 2.0, 0.0]], &[f64::INFINITY]).is_none());
        assert!(Elimination::new(&[vec![1.0, 2.0, 0.0]], &[1.0]).is_some());
    }

    /// The duals solve stationarity at the pivots: with s_p = −G̃_pᵀ y for a known y, y comes back.
    #[test]
    fn the_duals_come_back() {
        let rows = vec![vec![0.0, 2.0, -1.0, 0.5], vec![1.0, 0.0, 3.0, 0.0]];
        let e = Elimination::new(&rows, &[0.0, 0.0]).unwrap();
        let y = [0.7, -1.3];
        let s: Vec<f64> = e.pivots.iter().map(|&p| -(rows[0][p] * y[0] + rows[1][p] * y[1])).collect();
        let back = e.duals(&s).unwrap();
        assert!((back[0] - y[0]).abs() < 1e-14 && (back[1] - y[1]).abs() < 1e-14, "{back:?}");
    }
}
