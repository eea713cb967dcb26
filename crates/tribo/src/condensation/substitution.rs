//! Substitutions with the simplicial Cholesky factor of A that visit only what a sparse right-hand side
//! reaches and what the caller reads.
//!
//! # Why
//! The active-set method on the saddle-point system asks A's factor for the gap `E A⁻¹ (f − Eᵀ ν)` of its
//! certification and for `‖L⁻¹ P Eᵀ ν‖²` (diag H, the curvature along a move). Their right-hand sides live on
//! the dofs of Γ_C in contact, and E reads the displacement on Γ_C only. A full solve reads the whole factor
//! twice: on the graded Hertz mesh of 55k unknowns the forward substitution from a contact zone's dofs
//! reaches 4–17 % of the factor's values, and the dofs E reads (with everything above them in the
//! elimination tree) 73 %.
//!
//! # The mathematics
//! With `A = Pᵀ L Lᵀ P` and `L` stored by columns (the diagonal first), the forward substitution
//! `y ← L⁻¹ y` by columns adds column j's multiples only where `y_j ≠ 0`: a column with `y_j = 0` changes
//! nothing, so skipping it is exact. The entries that become nonzero are the elimination-tree paths above
//! the right-hand side's entries (the parent of column j is the first row below its diagonal).
//!
//! The backward substitution `x_j = (y_j − Σ_{i>j} L_ij x_i) / L_jj` reads only rows `i` of column j's
//! pattern, all ancestors of j in the elimination tree. So the entries of `x` on a set of positions closed
//! under "parent of" (the union of the paths from the asked positions to the root) come from the backward
//! substitution over that set alone, exactly.

use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;

use super::direct::Direct;
use super::Factor;
use crate::error::Result;

impl Factor {
    /// `E u` for the displacement `u = A⁻¹ (f − Eᵀ λ)` of the multipliers λ (2q): what [`Factor::displacement`]
    /// and [`Factor::apply_e`] give, at less cost with the simplicial factor of A. There the forward
    /// substitution visits only what `f − Eᵀ λ` reaches, and the backward one only the dofs E reads and what
    /// lies above them in the elimination tree.
    ///
    /// # Errors
    /// As [`Factor::displacement`].
    pub(crate) fn e_displacement(&self, f: &[f64], lambda: &[f64]) -> Result<Vec<f64>> {
        let Some(s) = self.direct.simplicial() else { return Ok(self.apply_e(&self.displacement(f, lambda)?)) };
        let closed = self.e_closure.get_or_init(|| s.closure(self.e_rows.iter().flatten().map(|&(i, _)| i)));
        let rhs: Vec<f64> = f.iter().zip(self.apply_et(lambda)).map(|(fi, ei)| fi - ei).collect();
        let mut y = s.permuted(&rhs);
        s.forward(&mut y);
        s.backward_on(&mut y, closed);
        Ok(self.e_rows.iter().map(|row| row.iter().map(|&(i, v)| v * y[s.position(i)]).sum()).collect())
    }
}

/// The simplicial Cholesky factor `L` of A (by columns, the diagonal first) and its fill-reducing order.
pub(super) struct Simplicial<'a> {
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
    values: &'a [f64],
    /// `order[new] = old` and its inverse `at[old] = new`, where the factor has an order.
    perm: Option<(&'a [usize], &'a [usize])>,
}

impl Direct {
    /// The factor of A where it is a simplicial Cholesky factor in the fill-reducing ordering.
    pub(super) fn simplicial(&self) -> Option<Simplicial<'_>> {
        let Self::Columns(symbolic, values) = self else { return None };
        let SymbolicCholeskyRaw::Simplicial(s) = symbolic.raw() else { return None };
        let perm = symbolic.perm().map(|p| p.arrays());
        Some(Simplicial { col_ptr: s.col_ptr(), row_idx: s.row_idx(), values, perm })
    }
}

impl Simplicial<'_> {
    /// The order of A.
    fn n(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// The position in the factor of A's dof `i`.
    pub(super) fn position(&self, i: usize) -> usize {
        self.perm.map_or(i, |(_, at)| at[i])
    }

    /// The dof of A at position `p` of the factor.
    fn dof(&self, p: usize) -> usize {
        self.perm.map_or(p, |(order, _)| order[p])
    }

    /// `y ← L⁻¹ y` (`y` in the factor's order), visiting only the columns where `y` is nonzero.
    pub(super) fn forward(&self, y: &mut [f64]) {
        for j in 0..self.n() {
            if y[j] == 0.0 {
                continue;
            }
            let (start, end) = (self.col_ptr[j], self.col_ptr[j + 1]);
            let yj = y[j] / self.values[start];
            y[j] = yj;
            for (&i, &l) in self.row_idx[start + 1..end].iter().zip(&self.values[start + 1..end]) {
                y[i] -= l * yj;
            }
        }
    }

    /// `y ← L⁻ᵀ y` on the positions `closed` only (increasing, closed under the elimination tree's parent,
    /// [`Self::closure`]): exact there, the other entries of `y` left as they were.
    pub(super) fn backward_on(&self, y: &mut [f64], closed: &[usize]) {
        for &j in closed.iter().rev() {
            let (start, end) = (self.col_ptr[j], self.col_ptr[j + 1]);
            let (rows, l) = (&self.row_idx[start + 1..end], &self.values[start + 1..end]);
            let dot = gather_dot(rows, l, y);
            y[j] = (y[j] - dot) / self.values[start];
        }
    }

    /// The positions of A's dofs `dofs` in the factor and every position above them in the elimination tree,
    /// increasing.
    pub(super) fn closure(&self, dofs: impl Iterator<Item = usize>) -> Vec<usize> {
        let n = self.n();
        let mut seen = vec![false; n];
        let mut out = Vec::new();
        for i in dofs {
            let mut p = self.position(i);
            while !seen[p] {
                seen[p] = true;
                out.push(p);
                let (start, end) = (self.col_ptr[p], self.col_ptr[p + 1]);
                if end - start < 2 {
                    break;
                }
                p = self.row_idx[start + 1];
            }
        }
        out.sort_unstable();
        out
    }

    /// `b` (A's numbering) in the factor's order.
    pub(super) fn permuted(&self, b: &[f64]) -> Vec<f64> {
        (0..self.n()).map(|p| b[self.dof(p)]).collect()
    }
}

/// `Σ_k l_k y_{rows_k}`, in four independent sums (a single sum waits on each addition in turn), from the last
/// term to the first: [`Simplicial::backward_on`] takes the columns from the last, so the pass then goes down
/// through memory (about 3.7 ms instead of 7 ms at 55k, reading each column upward).
fn gather_dot(rows: &[usize], l: &[f64], y: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (rc, lc) = (rows.rchunks_exact(4), l.rchunks_exact(4));
    let tail: f64 = rc.remainder().iter().zip(lc.remainder()).map(|(&i, &v)| v * y[i]).sum();
    for (r, v) in rc.zip(lc) {
        for k in (0..4).rev() {
            acc[k] += v[k] * y[r[k]];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2D Laplacian-like SPD matrix on an nx × ny grid (5-point stencil plus a shift).
    fn grid(nx: usize, ny: usize) -> Result<faer::sparse::SparseColMat<usize, f64>, String> {
        let id = |i: usize, j: usize| i * ny + j;
        let mut t = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                t.push(faer::sparse::Triplet::new(id(i, j), id(i, j), 4.5 + 0.01 * ((i * 7 + j * 3) % 5) as f64));
                if i + 1 < nx {
                    t.push(faer::sparse::Triplet::new(id(i + 1, j), id(i, j), -1.0));
                    t.push(faer::sparse::Triplet::new(id(i, j), id(i + 1, j), -1.0));
                }
                if j + 1 < ny {
                    t.push(faer::sparse::Triplet::new(id(i, j + 1), id(i, j), -1.0));
                    t.push(faer::sparse::Triplet::new(id(i, j), id(i, j + 1), -1.0));
                }
            }
        }
        faer::sparse::SparseColMat::try_new_from_triplets(nx * ny, nx * ny, &t).map_err(|e| format!("{e:?}"))
    }

    #[test]
    fn restricted_substitutions_give_the_full_solve_where_asked() -> Result<(), String> {
        use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams};
        let a = grid(30, 20)?;
        let n = a.nrows();
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: faer::sparse::linalg::SupernodalThreshold::FORCE_SIMPLICIAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            faer::Side::Lower,
            faer::sparse::linalg::cholesky::SymmetricOrdering::Amd,
            params,
        )
        .map_err(|e| format!("{e:?}"))?;
        let values =
            crate::linalg::schur::numeric_llt(&symbolic, a.as_ref(), faer::Par::Seq).map_err(|e| format!("{e:?}"))?;
        let direct = Direct::Columns(std::sync::Arc::new(symbolic), values);
        let s = direct.simplicial().ok_or("not simplicial")?;
        // A right-hand side on a few dofs of one edge, and the dofs of another edge asked for.
        let mut b = vec![0.0; n];
        for (k, i) in [3usize, 4, 5, 9].iter().enumerate() {
            b[*i] = 1.0 + k as f64;
        }
        let full = super::super::direct::solve(&direct, &b).map_err(|e| e.to_string())?;
        let asked: Vec<usize> = (0..30).map(|i| i * 20 + 19).collect();
        let closed = s.closure(asked.iter().copied());
        assert!(closed.len() < n, "the closure of one edge is not the whole factor");
        let mut y = s.permuted(&b);
        s.forward(&mut y);
        s.backward_on(&mut y, &closed);
        let scale = full.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for &i in &asked {
            let got = y[s.position(i)];
            assert!((got - full[i]).abs() <= 1e-13 * scale, "dof {i}: {got} against {}", full[i]);
        }
        // The forward substitution alone gives ‖L⁻¹ P b‖² = bᵀ A⁻¹ b.
        let energy: f64 = {
            let mut y = s.permuted(&b);
            s.forward(&mut y);
            y.iter().map(|v| v * v).sum()
        };
        let exact: f64 = b.iter().zip(&full).map(|(x, y)| x * y).sum();
        assert!((energy - exact).abs() <= 1e-13 * exact, "{energy} against {exact}");
        Ok(())
    }

    /// Two paths to `E A⁻¹ (f − Eᵀ λ)` on a graded Hertz problem with a load: the restricted substitutions and
    /// the full solve followed by E.
    #[test]
    fn e_displacement_is_e_of_the_displacement() -> Result<(), String> {
        use crate::settings::Condensation;
        use crate::{
            graded_rectangle, Grading, Material, MultiplierPoints, MultiplierSpace, ObstacleShape, Problem,
            ProblemSpec, Side, Stabilization,
        };
        let grading = Grading { side: Side::Top, segment: [-0.2, 0.2], h_min: 0.01, h_max: 0.25, growth: 0.3 };
        let mesh = graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading).map_err(|e| e.to_string())?;
        let spec = ProblemSpec::new(Material { young: 200.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .obstacle(ObstacleShape::Circle { center: 0.0, radius: 1.0 })
            .approach(0.01)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).map_err(|e| e.to_string())?;
        let condensed = problem
            .condense_with(Stabilization::Fraction(0.5), Condensation::Columns, usize::MAX)
            .map_err(|e| e.to_string())?;
        let factor = condensed.factor();
        if factor.direct.simplicial().is_none() {
            return Err("the factor of A is not simplicial: the restricted path is not tested".into());
        }
        let m = 2 * condensed.q();
        // λ on a stretch of the multipliers only, as in a contact zone, and λ everywhere; with and without f.
        let zone: Vec<f64> = (0..m).map(|j| if j % (m / 2) < m / 6 { (j as f64 * 0.3).sin() } else { 0.0 }).collect();
        let everywhere: Vec<f64> = (0..m).map(|j| (j as f64 * 0.7).cos()).collect();
        let load: Vec<f64> = (0..factor.n).map(|i| ((i % 7) as f64 - 3.0) * 1e-3).collect();
        for lambda in [&zone, &everywhere] {
            for f in [&factor.f, &load] {
                let fast = factor.e_displacement(f, lambda).map_err(|e| e.to_string())?;
                let full = factor.apply_e(&factor.displacement(f, lambda).map_err(|e| e.to_string())?);
                let scale = full.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
                for (j, (a, b)) in fast.iter().zip(&full).enumerate() {
                    assert!((a - b).abs() <= 1e-12 * scale, "multiplier {j}: {a} against {b} (of {scale})");
                }
            }
        }
        Ok(())
    }
}
