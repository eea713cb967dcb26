//! Solves for a partition near the factorized one with that factorization, bordered by the multipliers
//! that changed sides.
//!
//! # Why
//! The last steps of an active-set solve, and the first step of a QP whose bounds barely moved, change
//! the sides of a handful of multipliers. A new `LDLᵀ` then costs as much as a dozen or more solves with
//! the existing one (the ratio grows with the mesh). Bordering pays one solve per changed multiplier.
//!
//! # The mathematics
//! The scaled matrix `K̃` of a partition `F` differs from `K̃₀`, the factorized one of `F₀`, only in the
//! rows and columns of the multipliers `J = F Δ F₀`. Split `J` into the *freed* ones (fixed in `F₀`,
//! free in `F`) and the *fixed* ones (free in `F₀`, fixed in `F`). The bordered system
//!
//! ```text
//! [ K̃₀  V ] [z]   [b₀]
//! [ Vᵀ  C ] [w] = [b₁]
//! ```
//!
//! has one border column `v_j` per changed multiplier:
//!
//! * fixed `j`: `v_j = e_j`, `C_jj = 0` and `b₁_j = 0`. Its row says `z_j = 0`; its unknown `w_j` absorbs
//!   row `j` of `K̃₀`, the equation `F` no longer has;
//! * freed `j`: `v_j` is column `j` of `K̃` on the displacement rows and on the multipliers free in both
//!   partitions, `C` holds `K̃` among the freed multipliers and `b₁_j = b_j`. Row `j` of `K̃₀` is
//!   decoupled (`−z_j = b₀_j = 0`), so `z_j = 0` and `w_j` is the multiplier.
//!
//! with `b₀ = b` off `J` and `0` on it. Outside `J`, `z` solves the rows of `K̃` there, so `x = z` off `J`,
//! `x_j = w_j` on the freed ones and `x_j = 0` on the fixed ones (the caller's `ν_B` replaces it). With
//! `Y = K̃₀⁻¹ V` (one solve per column, kept while the factorization is), the Schur complement
//! `S = C − Vᵀ Y` (dense, `|J| × |J|`, full-pivoting LU) gives `w = S⁻¹ (b₁ − Vᵀ K̃₀⁻¹ b₀)` and
//! `z = K̃₀⁻¹ b₀ − Y w`: one solve and `|J|` short dot products per right-hand side.
//!
//! The answer is refined against `K̃` of `F` itself, as [`SaddleSystem::solve`] refines against `K̃₀`: the
//! bordered inverse is only the correction, so the accuracy test is the same.

use faer::linalg::solvers::{FullPivLu, Solve};
use faer::Mat;

use super::*;

/// A border column: the changed multiplier, its column `v` (sparse, scaled) and `y = K̃₀⁻¹ v`.
#[derive(Debug)]
struct Column {
    dof: usize,
    v: Vec<(usize, f64)>,
    y: Vec<f64>,
}

/// The border columns computed since the last factorization.
#[derive(Debug, Default)]
pub(super) struct Border {
    columns: Vec<Column>,
}

impl Border {
    fn find(&self, dof: usize, v: &[(usize, f64)]) -> Option<usize> {
        self.columns.iter().position(|c| c.dof == dof && c.v == v)
    }
}

impl SaddleSystem {
    /// A factorization's flops in units of a solve's: `Σ_j c_j²` against `4 nnz(L)`, `c_j` the column
    /// counts of L. Deterministic (from the symbolic analysis), unlike a timing.
    pub fn factorization_in_solves(&self) -> f64 {
        let sq = |c: usize| (c * c) as f64;
        let (flops, len) = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let cp = s.col_ptr();
                ((0..self.n + self.m).map(|j| sq(cp[j + 1] - cp[j])).sum::<f64>(), s.len_val())
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let (begin, end, rows) = (s.supernode_begin(), s.supernode_end(), s.col_ptr_for_row_idx());
                let flops = (0..s.n_supernodes())
                    .map(|k| {
                        let (w, p) = (end[k] - begin[k], rows[k + 1] - rows[k]);
                        (1..=w).map(|i| sq(i + p)).sum::<f64>()
                    })
                    .sum::<f64>();
                (flops, s.len_val())
            }
        };
        flops / (4.0 * len.max(1) as f64)
    }

    /// The most changed multipliers [`Self::solve_near`] should take: beyond, a new factorization costs
    /// fewer flops than the border columns ([`Self::factorization_in_solves`]), or the columns, read at
    /// every solve, outweigh the factor itself (`nnz(L) / (n + m)` of them).
    pub fn border_limit(&self) -> usize {
        let by_memory = self.symbolic.len_val() / (self.n + self.m);
        (self.factorization_in_solves().floor() as usize).min(by_memory)
    }

    /// Whether a factorization is held (of the partition last given to [`Self::factorize`]).
    pub fn is_factorized(&self) -> bool {
        self.factorized
    }

    /// The multipliers whose side (free or fixed) differs between `free` and the factorized partition.
    pub fn changed(&self, free: &[bool]) -> Vec<usize> {
        (0..self.m.min(free.len())).filter(|&j| free[j] != self.free[j]).collect()
    }

    /// Solves with a new factorization needed by [`Self::solve_near`] for `free`: the border columns it
    /// has not computed yet.
    pub fn border_solves(&self, free: &[bool]) -> usize {
        self.changed(free).into_iter().filter(|&j| self.border.find(j, &self.border_vector(free, j)).is_none()).count()
    }

    /// The border column of the changed multiplier `j` for the partition `free` (module documentation).
    fn border_vector(&self, free: &[bool], j: usize) -> Vec<(usize, f64)> {
        let n = self.n;
        if self.free[j] {
            return vec![(n + j, 1.0)];
        }
        let s = self.scale[n + j];
        let mut v: Vec<(usize, f64)> = self.e_rows[j].iter().map(|&(c, e)| (c, e * self.scale[c] * s)).collect();
        v.extend(
            self.d_rows[j]
                .iter()
                .filter(|&&(i, _)| i != j && self.free[i] && free[i])
                .map(|&(i, d)| (n + i, -d * self.scale[n + i] * s)),
        );
        v
    }

    /// `K̃_ij` of the partition `free` between the freed multipliers `i` and `j` (0 when one is fixed).
    fn freed_entry(&self, free: &[bool], i: usize, j: usize) -> f64 {
        if self.free[i] || self.free[j] || !free[i] || !free[j] {
            return 0.0;
        }
        let d = self.d_rows[i].binary_search_by_key(&j, |&(k, _)| k).map_or(0.0, |p| self.d_rows[i][p].1);
        -d * self.scale[self.n + i] * self.scale[self.n + j]
    }

    /// Solves the saddle-point system of the partition `free` (arguments as in [`Self::solve`]) with the
    /// factorization of the current partition, bordered by the multipliers that changed sides (module
    /// documentation). The border columns are kept for later calls until the next factorization.
    ///
    /// # Errors
    /// As [`Self::solve`]; [`SaddleError::RefinementNotConverged`] when the border is singular (the
    /// partition `free` has no solution) or too ill-conditioned to refine.
    pub fn solve_near(
        &mut self,
        free: &[bool],
        f: &[f64],
        d_rhs: &[f64],
        nu_fixed: &[f64],
    ) -> Result<SaddleSolution, SaddleError> {
        if !self.factorized {
            return Err(SaddleError::NotFactorized);
        }
        let b = self.rhs(free, f, d_rhs, nu_fixed)?;
        let changed = self.changed(free);
        if changed.is_empty() {
            return self.solve(f, d_rhs, nu_fixed);
        }
        // The residual of the refinement is that of K̃ of `free`: its values stand in `self.k` meanwhile.
        self.set_values(free);
        let out = self.solve_bordered(free, &changed, &b, nu_fixed);
        let reference = std::mem::take(&mut self.free);
        self.set_values(&reference);
        self.free = reference;
        out
    }

    /// [`Self::solve_near`] once `self.k` holds the values of `free`.
    fn solve_bordered(
        &mut self,
        free: &[bool],
        changed: &[usize],
        b: &[f64],
        nu_fixed: &[f64],
    ) -> Result<SaddleSolution, SaddleError> {
        let (n, nk) = (self.n, self.n + self.m);
        let vectors: Vec<Vec<(usize, f64)>> = changed.iter().map(|&j| self.border_vector(free, j)).collect();
        let par = self.opts.par;
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, par)).map_err(too_large)?;
        let ldlt = LdltRef::new(&self.symbolic, &self.l_values);
        let solve = |x: &mut [f64], mem: &mut MemBuffer| {
            ldlt.solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(x, nk, 1),
                par,
                MemStack::new(mem),
            );
        };
        // The new border columns, solved together (one pass over the factor for all of them).
        let mut at: Vec<Option<usize>> = changed.iter().zip(&vectors).map(|(&j, v)| self.border.find(j, v)).collect();
        let new: Vec<usize> = (0..changed.len()).filter(|&a| at[a].is_none()).collect();
        if !new.is_empty() {
            let mut y = try_zeroed::<f64>(nk.checked_mul(new.len()).ok_or_else(|| too_large("border columns"))?)?;
            for (b, &a) in new.iter().enumerate() {
                for &(i, val) in &vectors[a] {
                    y[b * nk + i] = val;
                }
            }
            let mut mem =
                MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(new.len(), par)).map_err(too_large)?;
            ldlt.solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(&mut y, nk, new.len()),
                par,
                MemStack::new(&mut mem),
            );
            for (b, &a) in new.iter().enumerate() {
                let y = y[b * nk..(b + 1) * nk].to_vec();
                at[a] = Some(self.border.columns.len());
                self.border.columns.push(Column { dof: changed[a], v: vectors[a].clone(), y });
            }
        }
        let cols: Vec<&Column> = at.iter().flatten().map(|&p| &self.border.columns[p]).collect();
        let r = changed.len();
        let s = Mat::from_fn(r, r, |a, c| {
            let va_yc: f64 = cols[a].v.iter().map(|&(i, val)| val * cols[c].y[i]).sum();
            self.freed_entry(free, changed[a], changed[c]) - va_yc
        });
        let lu = FullPivLu::new(s.as_ref());
        let freed: Vec<bool> = changed.iter().map(|&j| !self.free[j]).collect();
        let correct = |x: &mut [f64]| {
            let b1: Vec<f64> = changed.iter().zip(&freed).map(|(&j, &fr)| if fr { x[n + j] } else { 0.0 }).collect();
            for &j in changed {
                x[n + j] = 0.0;
            }
            solve(x, &mut mem);
            let mut t = Mat::from_fn(r, 1, |a, _| b1[a] - cols[a].v.iter().map(|&(i, val)| val * x[i]).sum::<f64>());
            lu.solve_in_place(t.as_mut());
            for (a, col) in cols.iter().enumerate() {
                let w = t[(a, 0)];
                for (xi, yi) in x.iter_mut().zip(&col.y) {
                    *xi -= w * yi;
                }
            }
            for (a, &j) in changed.iter().enumerate() {
                x[n + j] = if freed[a] { t[(a, 0)] } else { 0.0 };
            }
            Ok(())
        };
        self.refine(free, b, nu_fixed, correct)
    }
}
