//! The stabilized system condensed onto Γ_C: one sparse Cholesky factorization of `A = K − G`, then the
//! dense multiplier operator `H = E A⁻¹ Eᵀ + Dγ` and the linear term `c = d − E A⁻¹ f` of the QP.
//!
//! This is the only place that touches all n displacement unknowns: 2q solves with the factor (in
//! blocks of columns), after which every Tresca QP and every Coulomb fixed-point iteration works with
//! the 2q multiplier unknowns only. The displacement is recovered at the end with one more solve.

use std::time::Instant;

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::stabilization::{resolve_gamma0, Stabilization};

/// Number of right-hand sides solved together when forming `A⁻¹ Eᵀ`.
const BLOCK: usize = 64;

/// Timings of the condensation, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CondensationTimings {
    /// Assembling `A = K − G` and its sparse Cholesky factorization (symbolic + numeric).
    pub factorization: f64,
    /// Forming `H` and `c` (2q solves and products).
    pub schur: f64,
}

/// The condensed problem for one value of γ0.
pub struct Condensed {
    /// The γ0 in use.
    pub gamma0: f64,
    /// Sparse Cholesky factor of A.
    llt: faer::sparse::linalg::solvers::Llt<usize, f64>,
    /// A as a sparse matrix (for residuals).
    a: SparseColMat<usize, f64>,
    /// Rows of E (2q sparse rows over the free dofs).
    pub e_rows: Vec<Vec<(usize, f64)>>,
    /// Dense H (column-major, 2q × 2q).
    pub h: Vec<f64>,
    /// Linear term c (2q).
    pub c: Vec<f64>,
    /// `d` (2q): gap and shift moments.
    pub d: Vec<f64>,
    /// Timings.
    pub timings: CondensationTimings,
}

impl std::fmt::Debug for Condensed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Condensed").field("gamma0", &self.gamma0).field("2q", &self.c.len()).finish()
    }
}

impl Condensed {
    /// Factorizes A and condenses onto the multipliers.
    ///
    /// # Errors
    /// [`Error::BadSetting`] / [`Error::Gamma0TooLarge`] for a bad γ0; [`Error::NotPositiveDefinite`] if
    /// the Cholesky factorization fails.
    pub fn new(problem: &Problem, stabilization: Stabilization) -> Result<Self> {
        let (bound, element) = problem.gamma0_bound;
        let gamma0 = resolve_gamma0(stabilization, bound, element)?;
        Self::with_gamma0(problem, gamma0)
    }

    /// As [`Condensed::new`] with γ0 given and *not* checked against the admissible bound: for studies
    /// of what happens beyond it. The factorization still fails cleanly if A is not definite.
    ///
    /// # Errors
    /// [`Error::NotPositiveDefinite`] if the Cholesky factorization fails.
    pub fn with_gamma0(problem: &Problem, gamma0: f64) -> Result<Self> {
        let clock = Instant::now();
        let n = problem.n_free;
        let mut trip: Vec<Triplet<usize, usize, f64>> = problem.k_free.clone();
        trip.extend(problem.stabilization_triplets(gamma0));
        let a = SparseColMat::try_new_from_triplets(n, n, &trip)
            .map_err(|e| Error::NotPositiveDefinite { what: format!("assembly failed: {e:?}") })?;
        let llt = a.sp_cholesky(Side::Lower).map_err(|e| Error::NotPositiveDefinite {
            what: format!("{e:?} (γ0 = {gamma0:e}, admissible bound {:e})", problem.gamma0_bound.0),
        })?;
        let factorization = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        let e_rows = problem.coupling_rows(gamma0);
        let k = e_rows.len();
        let q = k / 2;
        let mut h = vec![0.0; k * k];
        let mut x = Mat::<f64>::zeros(n, BLOCK.min(k.max(1)));
        for start in (0..k).step_by(BLOCK) {
            let width = BLOCK.min(k - start);
            let mut xb = x.as_mut().subcols_mut(0, width);
            xb.fill(0.0);
            for (col, row) in e_rows[start..start + width].iter().enumerate() {
                for &(d, v) in row {
                    xb[(d, col)] = v;
                }
            }
            llt.solve_in_place(xb.as_mut());
            for (i, row) in e_rows.iter().enumerate() {
                for col in 0..width {
                    h[(start + col) * k + i] = row.iter().map(|&(d, v)| v * xb[(d, col)]).sum();
                }
            }
        }
        // Symmetrize (rounding) and add Dγ on both diagonal blocks.
        for j in 0..k {
            for i in 0..j {
                let s = 0.5 * (h[j * k + i] + h[i * k + j]);
                h[j * k + i] = s;
                h[i * k + j] = s;
            }
        }
        if gamma0 > 0.0 {
            for &(i, j, v) in &problem.mortar.d_h.entries {
                h[j * k + i] += gamma0 * v;
                h[(q + j) * k + q + i] += gamma0 * v;
            }
        }
        let u_f = solve(&llt, &problem.f_free);
        let shift = problem.spec.obstacle.shift;
        let d: Vec<f64> = problem
            .mortar
            .gap_moments
            .iter()
            .copied()
            .chain(problem.mortar.psi_integrals.iter().map(|w| w * shift))
            .collect();
        let c = e_rows.iter().zip(&d).map(|(row, di)| di - dot(row, &u_f)).collect();
        let schur = clock.elapsed().as_secs_f64();
        Ok(Self { gamma0, llt, a, e_rows, h, c, d, timings: CondensationTimings { factorization, schur } })
    }

    /// Number of multiplier dofs per component.
    pub fn q(&self) -> usize {
        self.e_rows.len() / 2
    }

    /// A natural size of λ_n for this problem, `max |c_n| / max diag H_nn`: the multiplier at which the
    /// quadratic and linear terms of the QP balance. It is non-zero even when the solution is λ = 0, so it
    /// serves as the scale of tolerances on λ.
    pub fn lambda_scale(&self) -> f64 {
        let (k, q) = (2 * self.q(), self.q());
        let h = (0..q).map(|i| self.h[i * k + i]).fold(0.0, f64::max);
        let c = self.c[..q].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if h > 0.0 {
            c / h
        } else {
            0.0
        }
    }

    /// The normal-normal block `H_nn` (column-major q × q).
    pub fn h_normal(&self) -> Vec<f64> {
        let (k, q) = (2 * self.q(), self.q());
        (0..q).flat_map(|j| self.h[j * k..j * k + q].iter().copied()).collect()
    }

    /// The displacement (free dofs) for multipliers λ (2q): `u = A⁻¹ (f − Eᵀ λ)`.
    pub fn displacement(&self, f: &[f64], lambda: &[f64]) -> Vec<f64> {
        let mut rhs = f.to_vec();
        for (row, l) in self.e_rows.iter().zip(lambda) {
            for &(d, v) in row {
                rhs[d] -= v * l;
            }
        }
        solve(&self.llt, &rhs)
    }

    /// `A x` (free dofs).
    pub fn apply_a(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        let a = self.a.as_ref();
        for (j, xj) in x.iter().enumerate() {
            for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
                y[i] += v * xj;
            }
        }
        y
    }

    /// `E u` (2q).
    pub fn apply_e(&self, u: &[f64]) -> Vec<f64> {
        self.e_rows.iter().map(|row| dot(row, u)).collect()
    }

    /// `Eᵀ λ` (free dofs).
    pub fn apply_et(&self, lambda: &[f64], n: usize) -> Vec<f64> {
        let mut y = vec![0.0; n];
        for (row, l) in self.e_rows.iter().zip(lambda) {
            for &(d, v) in row {
                y[d] += v * l;
            }
        }
        y
    }
}

fn dot(row: &[(usize, f64)], x: &[f64]) -> f64 {
    row.iter().map(|&(d, v)| v * x[d]).sum()
}

fn solve(llt: &faer::sparse::linalg::solvers::Llt<usize, f64>, b: &[f64]) -> Vec<f64> {
    let mut x = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
    llt.solve_in_place(x.as_mut());
    (0..b.len()).map(|i| x[(i, 0)]).collect()
}
