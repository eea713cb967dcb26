//! Sparse saddle-point solver for the active-set steps of the Γ_C QP without forming H.
//!
//! # The mathematics
//!
//! With `A` (n × n, SPD, or quasi-definite with a negative tail: [`SaddleOptions::negative`]),
//! `E` (m × n) and `D` (m × m, symmetric positive
//! semi-definite), the QP over the multipliers `ν`
//! `min ½ νᵀHν + cᵀν`, `H = E A⁻¹ Eᵀ + D`, `c = d − E A⁻¹ f`,
//! with the multipliers split into free dofs `F` and fixed dofs `B` (value
//! `ν_B` prescribed) has the Newton/active-set step
//! `H_FF ν_F = −c_F − H_FB ν_B`, `u = A⁻¹ (f − Eᵀ ν)`. Without forming `H` this
//! is the sparse saddle-point system
//!
//! ```text
//! [ A      E_Fᵀ  ] [u  ]   [ f − E_Bᵀ ν_B    ]
//! [ E_F   −D_FF  ] [ν_F] = [ d_F + D_FB ν_B  ]
//! ```
//!
//! To keep one symbolic factorization for every partition, [`SaddleSystem`]
//! works on ONE fixed pattern of size `n + m`, `K = [[A, Eᵀ], [E, −D]]`; for a
//! fixed dof `j ∈ B` the values of row/column `n + j` are replaced by those of
//! `−e_j` (`K_jj = −1`, zero coupling) and the right-hand side entry is 0, so
//! that the solution there is 0 (it is then overwritten with `ν_j`). Only
//! values change, never the pattern.
//!
//! Internally `K` is symmetrically scaled, `K̃ = S K S`, with
//! `S_uu = diag(A)^{-1/2}` and `S_νν = diag(E diag(A)⁻¹ Eᵀ + D)^{-1/2}`, so that
//! the regularization thresholds below are relative.
//!
//! `K̃` is factorized by a sparse `LDLᵀ` without pivoting (faer, supernodal or
//! simplicial). An `LDLᵀ` exists for any symmetric ordering when `K` is
//! quasi-definite (`D_FF` positive definite). When `D_FF` is only
//! semi-definite (e.g. `D = 0`) it exists for orderings in which every
//! multiplier is eliminated after all displacement dofs of its `E` row,
//! provided `E_F` has full row rank: the multiplier pivots are then
//! `−(Schur complement of a negative-definite matrix) < 0`. The default
//! ordering [`SaddleOrdering::ConstrainedAmd`] does exactly that: AMD on the
//! graph of `A + EᵀE` (or the order of A's own factor, [`SaddleSystem::with_order`]),
//! each multiplier inserted right after the last of its displacement dofs
//! (the fill is essentially that of a Cholesky of `A`).
//! As a safety net faer's dynamic regularization is on (expected signs `+1`
//! for `u`, `−1` for `ν`; a pivot of the wrong sign or of modulus `≤ ε` is
//! replaced by `±δ`), and every solve is corrected by iterative refinement
//! against the *unregularized* `K̃` until the blockwise normwise backward
//! error `max_blocks ‖r‖∞ / (‖|K̃||x|‖∞ + ‖b‖∞)` is below `tol` (computed
//! in the scaled variables, which makes the `u` and `ν` equations
//! comparable).
//!
//! A partition that differs from the factorized one in a few multipliers is solved with the same
//! factorization, bordered by them ([`border`]).

// The kernel indexes several parallel arrays by one loop variable, and `!(x > 0.0)` is its NaN test.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]
// Options, diagnostics and the plain AMD ordering serve the kernel's own tests and studies.
#![cfg_attr(not(test), allow(dead_code))]

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};
use faer::{Par, Side};

mod border;
mod ordering;
#[cfg(test)]
mod testgen;

use super::blocks::Blocks;
use border::Border;
use ordering::{constrained_amd, interleaved, inverse_of, rows_within_two_steps};

/// Errors of [`SaddleSystem`].
#[derive(Clone, Debug, PartialEq)]
pub enum SaddleError {
    /// Inconsistent or non-finite input (dimension, index out of range, asymmetric `D`, …).
    InvalidInput(String),
    /// `A_jj ≤ 0` (or not finite): `A` is not SPD.
    NotPositiveDiagonal { index: usize },
    /// The `LDLᵀ` without pivoting broke down (zero/non-finite pivot at the
    /// given position of the permuted matrix): `K` is not quasi-definite for
    /// this ordering and the regularization was switched off.
    ZeroPivot { position: usize },
    /// Iterative refinement did not reach the tolerance (singular `K`, e.g.
    /// `E_F` rank deficient with `D_FF` singular, or regularization too large).
    RefinementNotConverged { steps: usize, backward_error: f64 },
    /// Index overflow or allocation failure.
    TooLarge(String),
    /// The factor would hold more values than [`SaddleOptions::max_factor_len`].
    FactorTooLarge {
        /// Values of the factor.
        values: usize,
    },
    /// `solve` called without a successful `factorize`.
    NotFactorized,
}

impl core::fmt::Display for SaddleError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::InvalidInput(s) => write!(f, "invalid input: {s}"),
            Self::NotPositiveDiagonal { index } => write!(f, "A[{index},{index}] has not the expected sign"),
            Self::ZeroPivot { position } => {
                write!(f, "zero pivot at permuted position {position}: system not quasi-definite")
            }
            Self::RefinementNotConverged { steps, backward_error } => {
                write!(f, "iterative refinement did not converge ({steps} steps, backward error {backward_error:e})")
            }
            Self::TooLarge(s) => write!(f, "problem too large: {s}"),
            Self::FactorTooLarge { values } => write!(f, "the factor would hold {values} values"),
            Self::NotFactorized => write!(f, "no numeric factorization available"),
        }
    }
}
impl std::error::Error for SaddleError {}

/// Fill-reducing ordering of the saddle-point matrix.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum SaddleOrdering {
    /// AMD on the pattern of `A + EᵀE` (or a given order of A's dofs,
    /// [`SaddleSystem::with_order`]), each multiplier placed right after
    /// the last displacement dof of its row. Factorization exists without
    /// regularization for `D_FF ⪰ 0` when `E_F` has full row rank. Default.
    ConstrainedAmd,
    /// Plain AMD on the pattern of `K`. Multipliers may be eliminated before
    /// their displacement dofs: with `D = 0` those pivots are 0 and rely on
    /// the dynamic regularization + refinement (slower convergence).
    Amd,
}

/// Tuning parameters.
#[derive(Copy, Clone, Debug)]
pub struct SaddleOptions {
    pub ordering: SaddleOrdering,
    /// Dynamic regularization value `δ` (scaled system; ≤ 0 disables).
    pub reg_delta: f64,
    /// Dynamic regularization threshold `ε` (scaled system; ≤ 0 disables).
    pub reg_eps: f64,
    /// Target blockwise backward error of the refined solution.
    pub tol: f64,
    /// Maximum number of refinement steps (after the first solve).
    pub max_refinement: usize,
    /// Parallelism of the numeric factorization and of the solves. Default sequential: the fronts of a
    /// 2D mesh are narrow, and on the graded Hertz family (8k–109k unknowns, Coulomb, two cores) faer's
    /// rayon kernels made the whole solve 5–20 % slower (55k: 1.25 s sequential against 1.39–1.53 s).
    pub par: Par,
    /// Supernodal or simplicial factor. Default supernodal: faer's automatic choice took the
    /// simplicial one on these meshes, whose factorization and solves made the QPs of a Coulomb solve
    /// 1.3–1.5 × slower (55k graded unknowns: whole solve 1.9–2.0 s against 1.25 s with the two
    /// defaults together; 8k: 0.13–0.16 s against 0.08 s).
    pub supernodal_threshold: SupernodalThreshold,
    /// The most values the factor may hold: a larger one is refused ([`SaddleError::TooLarge`]) after the
    /// symbolic analysis, before anything of its size is allocated.
    pub max_factor_len: usize,
    /// The number of trailing unknowns of A with a negative diagonal: A is then symmetric quasi-definite
    /// (positive definite on the leading block, negative definite on these: the pressures of a mixed
    /// formulation), and so is K̃, whose expected pivot signs follow (0: A positive definite).
    pub negative: usize,
}

impl Default for SaddleOptions {
    fn default() -> Self {
        Self {
            ordering: SaddleOrdering::ConstrainedAmd,
            reg_delta: 1e-9,
            reg_eps: 1e-13,
            tol: 1e-12,
            max_refinement: 30,
            par: Par::Seq,
            supernodal_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            max_factor_len: usize::MAX,
            negative: 0,
        }
    }
}

/// Result of [`SaddleSystem::solve`].
#[derive(Clone, Debug)]
pub struct SaddleSolution {
    /// Displacements, length `n`.
    pub u: Vec<f64>,
    /// All `m` multipliers, `ν_B` equal to the prescribed values.
    pub nu: Vec<f64>,
    /// Number of refinement steps after the first solve.
    pub refinement_steps: usize,
    /// Final blockwise backward error (scaled system).
    pub backward_error: f64,
}

/// Symbolic `LDLᵀ` of the fixed pattern `[[A, Eᵀ], [E, −D]]` plus the
/// numeric factor of the current partition. See the crate docs for the math.
pub struct SaddleSystem {
    n: usize,
    m: usize,
    opts: SaddleOptions,
    /// Lower triangle of the scaled `K̃` with the values of the current partition.
    k: SparseColMat<usize, f64>,
    /// Scaling `S` (length `n + m`).
    scale: Vec<f64>,
    /// `(index in k, multiplier r, scaled E_rc)`.
    e_dyn: Vec<(usize, usize, f64)>,
    /// Per multiplier `r`: `(index in k, scaled −D_rr)`.
    diag_dyn: Vec<(usize, f64)>,
    /// `(index in k, multiplier i, multiplier r, scaled −D_ir)`, `i > r`.
    d_dyn: Vec<(usize, usize, usize, f64)>,
    /// Unscaled, merged rows of `E`.
    e_rows: Vec<Vec<(usize, f64)>>,
    /// Unscaled, merged rows of `D` (both triangles).
    d_rows: Vec<Vec<(usize, f64)>>,
    signs: Vec<i8>,
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    factor_mem: MemBuffer,
    /// Bytes of `factor_mem`.
    factor_mem_bytes: usize,
    free: Vec<bool>,
    factorized: bool,
    regularized: usize,
    /// Border columns for nearby partitions ([`border`]), valid for the current factorization.
    border: Border,
}

fn too_large<E: core::fmt::Debug>(e: E) -> SaddleError {
    SaddleError::TooLarge(format!("{e:?}"))
}

fn try_zeroed<T: Clone + Default>(len: usize) -> Result<Vec<T>, SaddleError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(too_large)?;
    v.resize(len, T::default());
    Ok(v)
}

/// Sorts by index and sums duplicates.
fn merge_sorted(list: &mut Vec<(usize, f64)>) {
    list.sort_by_key(|&(i, _)| i);
    let mut out: Vec<(usize, f64)> = Vec::with_capacity(list.len());
    for &(i, v) in list.iter() {
        match out.last_mut() {
            Some(last) if last.0 == i => last.1 += v,
            _ => out.push((i, v)),
        }
    }
    *list = out;
}

impl SaddleSystem {
    /// Symbolic analysis with default options. `a`: `n × n` SPD (or quasi-definite with
    /// [`SaddleOptions::negative`]), both triangles stored; `e_rows`: the `m` rows of `E` as `(column, value)`;
    /// `d`: entries `(i, j, v)` of `D`, both triangles (may be empty: `D = 0`).
    pub fn new(
        a: SparseColMatRef<'_, usize, f64>,
        e_rows: &[Vec<(usize, f64)>],
        d: &[(usize, usize, f64)],
    ) -> Result<Self, SaddleError> {
        Self::with_options(a, e_rows, d, SaddleOptions::default())
    }

    /// Symbolic analysis (ordering + symbolic factorization), done once.
    pub fn with_options(
        a: SparseColMatRef<'_, usize, f64>,
        e_rows: &[Vec<(usize, f64)>],
        d: &[(usize, usize, f64)],
        opts: SaddleOptions,
    ) -> Result<Self, SaddleError> {
        Self::with_order(a, e_rows, d, opts, None)
    }

    /// [`Self::with_options`], with [`SaddleOrdering::ConstrainedAmd`] taking the displacement dofs in the
    /// fill-reducing order `order` of A (`order[new] = old`, the one A's own Cholesky factor was analysed with)
    /// instead of running AMD on the pattern of `A + EᵀE`: the multipliers are placed as usual, each right after
    /// the last displacement dof of its row. Where every row of `E` couples only dofs within two steps of each
    /// other in A's graph (the neighbours along Γ_C one multiplier sees on one body), `E` adds nothing A's
    /// order has not seen, and it serves the saddle-point factor as well: on the graded Hertz family it fills
    /// it less than AMD on `A + EᵀE` (8k, 28k, 55k, 109k unknowns: 9 %, 1 %, 7 %, 10 % fewer values), and
    /// the AMD it saves took 14–25 ms at 55k. Elsewhere (two bodies, whose dofs E couples and A does not; a
    /// T_H coarser than the FE edges) the AMD of `A + EᵀE` orders them: with A's order, study 8's two bodies
    /// at 10k unknowns filled 4.6 times A's factor instead of 1.7, and from 16k on beyond the saddle path's
    /// limit.
    ///
    /// # Errors
    /// As [`Self::with_options`]; [`SaddleError::InvalidInput`] when `order` is not a permutation of A's dofs.
    pub fn with_order(
        a: SparseColMatRef<'_, usize, f64>,
        e_rows: &[Vec<(usize, f64)>],
        d: &[(usize, usize, f64)],
        opts: SaddleOptions,
        order: Option<&[usize]>,
    ) -> Result<Self, SaddleError> {
        let n = a.nrows();
        let m = e_rows.len();
        if a.ncols() != n {
            return Err(SaddleError::InvalidInput(format!("A is {} x {}", n, a.ncols())));
        }
        if n == 0 {
            return Err(SaddleError::InvalidInput("A is empty".into()));
        }
        let nk = n.checked_add(m).ok_or_else(|| too_large("n + m"))?;
        let ar = a;

        // --- A: lower part per column (flat; sorted and merged), diagonal
        let mut al_ptr: Vec<usize> = Vec::with_capacity(n + 1);
        let mut al: Vec<(usize, f64)> = Vec::new();
        al.try_reserve_exact(ar.compute_nnz() / 2 + n).map_err(too_large)?;
        let mut diag_a = try_zeroed::<f64>(n)?;
        al_ptr.push(0);
        let mut tmp: Vec<(usize, f64)> = Vec::new();
        for j in 0..n {
            let start = al.len();
            al.extend(
                ar.symbolic()
                    .row_idx_of_col_raw(j)
                    .iter()
                    .zip(ar.val_of_col(j))
                    .filter(|(&i, _)| i >= j)
                    .map(|(&i, &v)| (i, v)),
            );
            if al[start..].windows(2).any(|w| w[0].0 >= w[1].0) {
                tmp.clear();
                tmp.extend_from_slice(&al[start..]);
                merge_sorted(&mut tmp);
                al.truncate(start);
                al.extend_from_slice(&tmp);
            }
            if al[start..].iter().any(|&(_, v)| !v.is_finite()) {
                return Err(SaddleError::InvalidInput(format!("non-finite entry in column {j} of A")));
            }
            diag_a[j] = al.get(start).filter(|&&(i, _)| i == j).map_or(0.0, |&(_, v)| v);
            // The negative tail's diagonal is kept by its magnitude: the scaling reads |A_jj|.
            let sign = if j + opts.negative >= n { -1.0 } else { 1.0 };
            diag_a[j] *= sign;
            if !(diag_a[j] > 0.0) {
                return Err(SaddleError::NotPositiveDiagonal { index: j });
            }
            al_ptr.push(al.len());
        }

        // --- E rows (merged) and E^T columns
        let mut e_merged: Vec<Vec<(usize, f64)>> = e_rows.to_vec();
        let mut et: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (r, row) in e_merged.iter_mut().enumerate() {
            merge_sorted(row);
            for &(c, v) in row.iter() {
                if c >= n || !v.is_finite() {
                    return Err(SaddleError::InvalidInput(format!("E[{r}] has entry ({c}, {v})")));
                }
                et[c].push((r, v));
            }
        }

        // --- D rows (merged, symmetric check)
        let mut d_rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        for &(i, j, v) in d {
            if i >= m || j >= m || !v.is_finite() {
                return Err(SaddleError::InvalidInput(format!("D entry ({i}, {j}, {v})")));
            }
            d_rows[i].push((j, v));
        }
        d_rows.iter_mut().for_each(merge_sorted);
        for i in 0..m {
            for &(j, v) in &d_rows[i] {
                let vt = d_rows[j].binary_search_by_key(&i, |&(k, _)| k).map_or(0.0, |p| d_rows[j][p].1);
                if (v - vt).abs() > 1e-12 * v.abs().max(vt.abs()) {
                    return Err(SaddleError::InvalidInput(format!("D not symmetric at ({i}, {j})")));
                }
            }
        }
        let d_diag: Vec<f64> =
            (0..m).map(|r| d_rows[r].binary_search_by_key(&r, |&(k, _)| k).map_or(0.0, |p| d_rows[r][p].1)).collect();
        if d_diag.iter().any(|&v| v < 0.0) {
            return Err(SaddleError::InvalidInput("D has a negative diagonal entry".into()));
        }

        // --- scaling
        let mut scale = try_zeroed::<f64>(nk)?;
        for j in 0..n {
            scale[j] = 1.0 / diag_a[j].sqrt();
        }
        for r in 0..m {
            let w: f64 = e_merged[r].iter().map(|&(c, v)| v * v / diag_a[c]).sum::<f64>() + d_diag[r];
            scale[n + r] = if w > 0.0 && w.is_finite() { 1.0 / w.sqrt() } else { 1.0 };
        }

        // --- lower pattern of K with scaled values (all multipliers free)
        let nnz_est = al.len() + e_merged.iter().map(Vec::len).sum::<usize>() + m + d.len();
        let mut col_ptr: Vec<usize> = Vec::with_capacity(nk + 1);
        let mut row_idx: Vec<usize> = Vec::new();
        let mut vals: Vec<f64> = Vec::new();
        row_idx.try_reserve_exact(nnz_est).map_err(too_large)?;
        vals.try_reserve_exact(nnz_est).map_err(too_large)?;
        let mut e_dyn = Vec::new();
        let mut diag_dyn = Vec::with_capacity(m);
        let mut d_dyn = Vec::new();
        col_ptr.push(0);
        for j in 0..n {
            for &(i, v) in &al[al_ptr[j]..al_ptr[j + 1]] {
                row_idx.push(i);
                vals.push(v * scale[i] * scale[j]);
            }
            for &(r, v) in &et[j] {
                let base = v * scale[n + r] * scale[j];
                e_dyn.push((row_idx.len(), r, base));
                row_idx.push(n + r);
                vals.push(base);
            }
            col_ptr.push(row_idx.len());
        }
        drop(al);
        drop(et);
        for r in 0..m {
            let sr = scale[n + r];
            let base = -d_diag[r] * sr * sr;
            diag_dyn.push((row_idx.len(), base));
            row_idx.push(n + r);
            vals.push(base);
            for &(i, v) in d_rows[r].iter().filter(|&&(i, _)| i > r) {
                let base = -v * scale[n + i] * sr;
                d_dyn.push((row_idx.len(), i, r, base));
                row_idx.push(n + i);
                vals.push(base);
            }
            col_ptr.push(row_idx.len());
        }
        let k = SparseColMat::new(SymbolicSparseColMat::new_checked(nk, nk, col_ptr, None, row_idx), vals);

        // --- ordering + symbolic factorization
        let params =
            CholeskySymbolicParams { supernodal_flop_ratio_threshold: opts.supernodal_threshold, ..Default::default() };
        let symbolic = match opts.ordering {
            SaddleOrdering::Amd => {
                factorize_symbolic_cholesky(k.symbolic(), Side::Lower, SymmetricOrdering::Amd, params)
                    .map_err(too_large)?
            }
            SaddleOrdering::ConstrainedAmd => {
                let given = order.map(|order| inverse_of(order, n).map(|inverse| (order, inverse))).transpose()?;
                let (fwd, inv) = match given {
                    Some((order, inverse)) if rows_within_two_steps(ar, &e_merged) => {
                        interleaved(order, &inverse, &e_merged)
                    }
                    _ => constrained_amd(ar, &e_merged)?,
                };
                let perm = PermRef::new_checked(&fwd, &inv, nk);
                factorize_symbolic_cholesky(k.symbolic(), Side::Lower, SymmetricOrdering::Custom(perm), params)
                    .map_err(too_large)?
            }
        };
        if symbolic.len_val() > opts.max_factor_len {
            return Err(SaddleError::FactorTooLarge { values: symbolic.len_val() });
        }
        let l_values = try_zeroed::<f64>(symbolic.len_val())?;
        let scratch = symbolic.factorize_numeric_ldlt_scratch::<f64>(opts.par, Default::default());
        let factor_mem = MemBuffer::try_new(scratch).map_err(too_large)?;
        let signs: Vec<i8> = (0..nk).map(|i| if i + opts.negative < n { 1 } else { -1 }).collect();
        Ok(Self {
            n,
            m,
            opts,
            k,
            scale,
            e_dyn,
            diag_dyn,
            d_dyn,
            e_rows: e_merged,
            d_rows,
            signs,
            symbolic,
            l_values,
            factor_mem,
            factor_mem_bytes: scratch.size_bytes(),
            free: vec![true; m],
            factorized: false,
            regularized: 0,
            border: Border::default(),
        })
    }

    /// Bytes this system holds: its matrix (values and row indices), the factor's values and workspace, and
    /// the border columns computed since the last factorization.
    pub fn held_bytes(&self) -> f64 {
        let values = self.l_values.len() + self.border.held_values() + 2 * self.k.compute_nnz();
        8.0 * values as f64 + self.factor_mem_bytes as f64
    }

    /// Whether faer chose the supernodal factorization.
    pub fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
    }
    /// Number of pivots replaced by `±δ` in the last factorization.
    pub fn regularized_pivots(&self) -> usize {
        self.regularized
    }

    /// Writes the values of `K̃` of the partition `free` into `self.k`.
    fn set_values(&mut self, free: &[bool]) {
        let vals = self.k.val_mut();
        for &(idx, r, base) in &self.e_dyn {
            vals[idx] = if free[r] { base } else { 0.0 };
        }
        for (r, &(idx, base)) in self.diag_dyn.iter().enumerate() {
            vals[idx] = if free[r] { base } else { -1.0 };
        }
        for &(idx, i, r, base) in &self.d_dyn {
            vals[idx] = if free[i] && free[r] { base } else { 0.0 };
        }
    }

    /// Numeric `LDLᵀ` for the partition `free` (length `m`; `true` = free,
    /// `false` = fixed/prescribed). Same pattern for every partition.
    pub fn factorize(&mut self, free: &[bool]) -> Result<(), SaddleError> {
        if free.len() != self.m {
            return Err(SaddleError::InvalidInput(format!("free has length {}, expected {}", free.len(), self.m)));
        }
        self.factorized = false;
        self.border.reset(&[]);
        self.free.copy_from_slice(free);
        self.set_values(free);
        let reg = LdltRegularization {
            dynamic_regularization_signs: Some(&self.signs),
            dynamic_regularization_delta: self.opts.reg_delta.max(0.0),
            dynamic_regularization_epsilon: self.opts.reg_eps.max(0.0),
        };
        let res = self.symbolic.factorize_numeric_ldlt(
            &mut self.l_values,
            self.k.as_ref(),
            Side::Lower,
            reg,
            self.opts.par,
            MemStack::new(&mut self.factor_mem),
            Default::default(),
        );
        match res {
            Ok(_) => {}
            Err(LdltError::ZeroPivot { index }) => return Err(SaddleError::ZeroPivot { position: index }),
        }
        // count regularized pivots, check finiteness of D
        // The pivots D: none may be zero or non-finite; those equal to ±δ were regularized.
        let d = Blocks::new(&self.symbolic, &self.l_values).diagonal();
        let delta = self.opts.reg_delta;
        let finite = d.iter().all(|v| v.is_finite() && *v != 0.0);
        let count = if delta > 0.0 { d.iter().filter(|v| v.abs() == delta).count() } else { 0 };
        if !finite {
            return Err(SaddleError::ZeroPivot { position: usize::MAX });
        }
        self.border.reset(&d);
        self.regularized = count;
        self.factorized = true;
        Ok(())
    }

    /// Solves the saddle-point system of the current partition:
    /// `A u + E_Fᵀ ν_F = f − E_Bᵀ ν_B`, `E_F u − D_FF ν_F = d_F + D_FB ν_B`.
    /// `f`: length `n`; `d_rhs`: length `m` (entries in `B` ignored);
    /// `nu_fixed`: length `m` (entries in `F` ignored). Returns `u` and the full
    /// `ν` (`ν_B = nu_fixed_B`), refined to backward error `≤ tol`.
    pub fn solve(&self, f: &[f64], d_rhs: &[f64], nu_fixed: &[f64]) -> Result<SaddleSolution, SaddleError> {
        if !self.factorized {
            return Err(SaddleError::NotFactorized);
        }
        let b = self.rhs(&self.free, f, d_rhs, nu_fixed)?;
        self.refine(&self.free, &b, nu_fixed, |r| {
            self.substitute(r);
            Ok(())
        })
    }

    /// The scaled right-hand side `S b` of the partition `free` (see [`Self::solve`] for the arguments).
    fn rhs(&self, free: &[bool], f: &[f64], d_rhs: &[f64], nu_fixed: &[f64]) -> Result<Vec<f64>, SaddleError> {
        let (n, m) = (self.n, self.m);
        if f.len() != n || d_rhs.len() != m || nu_fixed.len() != m || free.len() != m {
            return Err(SaddleError::InvalidInput(format!(
                "rhs lengths ({}, {}, {}, {}), expected ({n}, {m}, {m}, {m})",
                f.len(),
                d_rhs.len(),
                nu_fixed.len(),
                free.len()
            )));
        }
        let mut b = try_zeroed::<f64>(n + m)?;
        b[..n].copy_from_slice(f);
        for r in 0..m {
            if !free[r] {
                for &(c, v) in &self.e_rows[r] {
                    b[c] -= v * nu_fixed[r];
                }
            } else {
                b[n + r] = d_rhs[r]
                    + self.d_rows[r].iter().filter(|&&(i, _)| !free[i]).map(|&(i, v)| v * nu_fixed[i]).sum::<f64>();
            }
        }
        for (bi, si) in b.iter_mut().zip(&self.scale) {
            *bi *= si;
        }
        if b.iter().any(|v| !v.is_finite()) {
            return Err(SaddleError::InvalidInput("non-finite right-hand side".into()));
        }
        Ok(b)
    }

    /// Iterative refinement of `K̃ x = b` (`K̃` as held in `self.k`, of the partition `free`) with the
    /// approximate inverse `correct` (in place: residual in, correction out), to backward error `≤ tol`;
    /// the unscaled `u` and `ν` (`ν_B = nu_fixed_B`).
    fn refine(
        &self,
        free: &[bool],
        b: &[f64],
        nu_fixed: &[f64],
        mut correct: impl FnMut(&mut [f64]) -> Result<(), SaddleError>,
    ) -> Result<SaddleSolution, SaddleError> {
        let (n, m) = (self.n, self.m);
        let nk = n + m;
        let mut x = try_zeroed::<f64>(nk)?;
        let mut r = b.to_vec();
        let mut absk = try_zeroed::<f64>(nk)?;
        let mut steps = 0usize;
        let mut eta_prev = f64::INFINITY;
        loop {
            if steps > 0 {
                self.residual(b, &x, &mut r, &mut absk);
            }
            let eta = backward_error(n, b, &r, &absk);
            if eta <= self.opts.tol {
                let mut u = x[..n].to_vec();
                for (ui, si) in u.iter_mut().zip(&self.scale[..n]) {
                    *ui *= si;
                }
                let nu: Vec<f64> =
                    (0..m).map(|j| if free[j] { x[n + j] * self.scale[n + j] } else { nu_fixed[j] }).collect();
                return Ok(SaddleSolution { u, nu, refinement_steps: steps.saturating_sub(1), backward_error: eta });
            }
            // stop when out of steps, diverging/stagnating, or non-finite
            if steps > self.opts.max_refinement || !eta.is_finite() || (steps >= 2 && eta > 0.9 * eta_prev) {
                return Err(SaddleError::RefinementNotConverged {
                    steps: steps.saturating_sub(1),
                    backward_error: eta,
                });
            }
            eta_prev = eta;
            correct(&mut r)?;
            for (xi, di) in x.iter_mut().zip(&r) {
                *xi += di;
            }
            steps += 1;
        }
    }

    /// `r = b − K̃ x` and `absk = |K̃| |x|` with the unregularized scaled matrix
    /// of the current partition (lower triangle stored).
    fn residual(&self, b: &[f64], x: &[f64], r: &mut [f64], absk: &mut [f64]) {
        r.copy_from_slice(b);
        absk.fill(0.0);
        let k = self.k.as_ref();
        for j in 0..self.n + self.m {
            let xj = x[j];
            // Row j's part from the column's entries below the diagonal, summed here and written once.
            // The column's rows are sorted: its diagonal entry, where stored, comes first.
            let (mut rows, mut vals) = (k.symbolic().row_idx_of_col_raw(j), k.val_of_col(j));
            if rows.first() == Some(&j) {
                let t = vals[0] * xj;
                r[j] -= t;
                absk[j] += t.abs();
                (rows, vals) = (&rows[1..], &vals[1..]);
            }
            let (mut rj, mut aj) = (0.0, 0.0);
            for (&i, &v) in rows.iter().zip(vals) {
                let t = v * xj;
                r[i] -= t;
                absk[i] += t.abs();
                let s = v * x[i];
                rj += s;
                aj += s.abs();
            }
            r[j] -= rj;
            absk[j] += aj;
        }
    }
}

/// Blockwise (u rows, ν rows) normwise backward error.
fn backward_error(n: usize, b: &[f64], r: &[f64], absk: &[f64]) -> f64 {
    let block = |lo: usize, hi: usize| {
        let mut rn = 0.0f64;
        let mut den = 0.0f64;
        let mut bn = 0.0f64;
        for i in lo..hi {
            rn = rn.max(r[i].abs());
            den = den.max(absk[i]);
            bn = bn.max(b[i].abs());
        }
        if rn.is_nan() {
            f64::INFINITY
        } else if rn == 0.0 {
            0.0
        } else {
            rn / (den + bn)
        }
    };
    block(0, n).max(block(n, b.len()))
}

#[cfg(test)]
mod tests;
