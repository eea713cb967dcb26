//! `S_E = E A⁻¹ Eᵀ` by a partial (Schur-complement) sparse Cholesky factorization.
//!
//! # The mathematics
//!
//! `A` is n × n sparse symmetric positive definite, `E` is m × n sparse. Let `C` be the set of columns of
//! `A` that `E` touches (the "contact" dofs, |C| = nc) and `I` its complement. With a symmetric
//! permutation `P` that orders `I` first (by AMD on `A_II`) and `C` last,
//!
//! ```text
//!   P A Pᵀ = L Lᵀ,   L = [ L_II   0    ]
//!                        [ L_CI   L_CC ]
//! ```
//!
//! and `L_CC L_CCᵀ = A_CC − A_CI A_II⁻¹ A_IC` is the Schur complement of `A_II`. Since `(A⁻¹)_CC` is the
//! inverse of that Schur complement, `(A⁻¹)_CC = (L_CC L_CCᵀ)⁻¹`, and because `E` vanishes outside `C`,
//!
//! ```text
//!   S_E = E A⁻¹ Eᵀ = E_C (A⁻¹)_CC E_Cᵀ = Wᵀ W,   W = L_CC⁻¹ E_Cᵀ   (nc × m, dense).
//! ```
//!
//! So one sparse factorization (whose trailing block, the Schur complement, is mostly dense), one
//! forward substitution with m right-hand sides restricted to the nc trailing rows, and one symmetric
//! rank-nc product give all of `S_E`, instead of m forward + backward solves over all n rows. The same
//! factor then solves `A x = b` (its fill is somewhat larger than with plain AMD, see the benchmark).
//!
//! Implementation notes:
//! * `C` is ordered by the first row of `E` that touches each dof, and the columns of `Eᵀ` are processed
//!   by increasing first non-zero `p_j` (under that order). Column j of `W` is zero above `p_j` (forward
//!   substitution keeps leading zeros), so the solve for a block of columns starts at the block's
//!   smallest `p_j`, and a panel of rows `[ra, rb)` of `W` only meets the columns with `p_j < rb`. When
//!   `E` is banded along a boundary (mortar rows) this saves about half of the dense work.
//! * `W = L_CC⁻¹ E_Cᵀ` is computed with the supernodes of the factor that intersect `C` (a supernode
//!   may straddle the boundary between `I` and `C`; its part in `I` multiplies zeros and is skipped), so
//!   no dense copy of `L_CC` is made and sparsity left in `L_CC` is used.
//!
//! Cost model (flops): sparse factorization of the reordered `A` (the plain-AMD cost, plus the extra
//! fill due to the constraint "C last", plus up to `nc³/3` for the trailing block), then `≲ nc² m / 2`
//! for `W` and `≲ nc m² / 2` for `Wᵀ W` — all BLAS-3 — against `≈ 4 nnz(L) m` memory-bound flops for the
//! column-by-column approach.

use std::sync::Arc;

pub use super::llt::{factor_flops, nnz_l, numeric_llt};

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::matmul::triangular::BlockStructure;
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{FaerError, SparseColMat, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par, Side};

/// Errors of the partial factorization.
#[derive(Debug, Clone, PartialEq)]
pub enum SchurError {
    /// The Cholesky factorization met a non-positive pivot at the given dof (index in the caller's
    /// numbering, when it can be mapped back).
    NotPositiveDefinite {
        /// The dof whose pivot was not positive.
        dof: usize,
    },
    /// An allocation failed or would exceed the configured limit.
    TooLarge {
        /// What was being allocated.
        what: &'static str,
        /// Requested size in bytes (saturating).
        bytes: usize,
    },
    /// The input is inconsistent (shape, index out of range, `E` outside the analysed pattern...).
    InvalidInput(String),
}

impl std::fmt::Display for SchurError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SchurError::NotPositiveDefinite { dof } => {
                write!(f, "matrix is not positive definite (pivot at dof {dof})")
            }
            SchurError::TooLarge { what, bytes } => {
                write!(f, "allocation of {what} ({bytes} bytes) failed or is too large")
            }
            SchurError::InvalidInput(s) => write!(f, "invalid input: {s}"),
        }
    }
}

impl std::error::Error for SchurError {}

/// Result alias of this module.
pub type Result<T> = std::result::Result<T, SchurError>;

fn faer_err(what: &'static str, e: FaerError) -> SchurError {
    match e {
        FaerError::OutOfMemory => SchurError::TooLarge { what, bytes: usize::MAX },
        other => SchurError::InvalidInput(format!("{what}: {other:?}")),
    }
}

/// Tuning knobs. The defaults are what [`schur_e`] uses.
#[derive(Debug, Clone, Copy)]
pub struct SchurOptions {
    /// Largest dense allocation accepted (bytes) for `L_CC`, `W` and `S_E` together.
    pub max_dense_bytes: usize,
    /// Number of columns of `W` per triangular solve (0: automatic, m/16 clamped to 64..=512).
    pub block: usize,
    /// Number of rows of `W` per rank-k update of `Wᵀ W` (0: automatic, max(nc/12, 256)).
    pub panel: usize,
    /// Solve with a dense copy of `L_CC` instead of the supernodes of the factor (reference/testing).
    pub dense_l_cc: bool,
}

impl Default for SchurOptions {
    fn default() -> Self {
        Self { max_dense_bytes: 16 << 30, block: 0, panel: 0, dense_l_cc: false }
    }
}

/// Ordering options of [`SchurSymbolic::new_with`]. The default tells AMD that all of `C` comes last (one
/// vertex for the whole of `C`, `contact_chunk = usize::MAX`). Measured on the Hertz block against no
/// chunk vertex (flops of the numeric factorization, `factor_flops`): −41 % at 1M unknowns (and 1009 MB of
/// factor values against 1231 MB, fewer than the plain AMD factor's 1070 MB), −16 % at 160k, −15 % at 26k,
/// −9 % on the block at 80k; within ±5 % on graded meshes and two bodies, where the dense trailing block
/// dominates; +23 % only on a 1.6k-unknown mesh (microseconds).
#[derive(Debug, Clone, Copy)]
pub struct SymbolicOptions {
    /// Put the contact dofs without a neighbour in `I` first inside `C` (1D nested dissection along the
    /// boundary), so that only the part of `L_CC` coupled to the interior is dense. Lowers the fill a
    /// little but loses most of the staircase saving in `W` and `Wᵀ W`. Off by default.
    pub split_contact: bool,
    /// If non-zero, AMD orders `I` on the graph of `A_II` augmented by one vertex per `contact_chunk`
    /// consecutive contact dofs (adjacent to their interior neighbours, and to the next chunk vertex), a
    /// stand-in for a constrained AMD that knows `C` comes last; the chunk vertices are then dropped.
    /// Default `usize::MAX`: one vertex for all of `C`.
    pub contact_chunk: usize,
}

impl Default for SymbolicOptions {
    fn default() -> Self {
        Self { split_contact: false, contact_chunk: usize::MAX }
    }
}

/// Wall-clock seconds of the phases of [`schur_e_with`].
#[derive(Debug, Clone, Copy, Default)]
pub struct SchurTimings {
    /// AMD on `A_II` plus the symbolic factorization.
    pub symbolic: f64,
    /// Numeric sparse Cholesky factorization.
    pub numeric: f64,
    /// Copy of `L_CC` out of the supernodal factor and assembly of `E_Cᵀ`.
    pub extract: f64,
    /// Dense triangular solve `W = L_CC⁻¹ E_Cᵀ`.
    pub solve: f64,
    /// Product `Wᵀ W` and symmetrization.
    pub syrk: f64,
}

impl SchurTimings {
    /// Sum of all phases.
    pub fn total(&self) -> f64 {
        self.symbolic + self.numeric + self.extract + self.solve + self.syrk
    }
}

fn try_zeros(nrows: usize, ncols: usize, what: &'static str, limit: usize) -> Result<Mat<f64>> {
    let bytes = nrows.saturating_mul(ncols).saturating_mul(8);
    if bytes > limit {
        return Err(SchurError::TooLarge { what, bytes });
    }
    let mut m = Mat::<f64>::new();
    m.try_reserve(nrows, ncols).map_err(|_| SchurError::TooLarge { what, bytes })?;
    m.resize_with(nrows, ncols, |_, _| 0.0);
    Ok(m)
}

pub(super) fn try_buffer(req: StackReq, what: &'static str) -> Result<MemBuffer> {
    MemBuffer::try_new(req).map_err(|_| SchurError::TooLarge { what, bytes: req.size_bytes() })
}

fn check_e(n: usize, e_rows: &[Vec<(usize, f64)>]) -> Result<()> {
    for (r, row) in e_rows.iter().enumerate() {
        if let Some(&(c, _)) = row.iter().find(|&&(c, _)| c >= n) {
            return Err(SchurError::InvalidInput(format!("row {r} of E has column {c} >= n = {n}")));
        }
    }
    Ok(())
}

/// Symbolic analysis: the contact set `C`, the ordering "AMD on the interior, `C` last" and the
/// supernodal symbolic factorization of `A` in that order. Depends only on the patterns of `A` and `E`,
/// so it can be reused for every matrix with the same patterns.
#[derive(Debug)]
pub struct SchurSymbolic {
    n: usize,
    /// `C` in elimination order (caller's dof numbers); `contact[k]` is eliminated at position `n0 + k`.
    contact: Vec<usize>,
    /// `pos_in_c[dof]` = k if `contact[k] == dof`, `usize::MAX` otherwise.
    pos_in_c: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    /// Number of stored entries of the analysed `A` (checked by [`SchurSymbolic::factorize`]).
    a_nnz: usize,
}

impl SchurSymbolic {
    /// Analyses the pattern of `A` (n × n, either or both triangles stored) and of the rows of `E`.
    ///
    /// # Errors
    /// [`SchurError::InvalidInput`] if `A` is not square or `E` has a column out of range;
    /// [`SchurError::TooLarge`] if an allocation fails.
    pub fn new(a: SymbolicSparseColMatRef<'_, usize>, e_rows: &[Vec<(usize, f64)>]) -> Result<Arc<Self>> {
        Self::new_with(a, e_rows, SymbolicOptions::default())
    }

    /// [`SchurSymbolic::new`] with ordering options (see [`SymbolicOptions`]).
    ///
    /// # Errors
    /// As [`SchurSymbolic::new`].
    pub fn new_with(
        a: SymbolicSparseColMatRef<'_, usize>,
        e_rows: &[Vec<(usize, f64)>],
        opts: SymbolicOptions,
    ) -> Result<Arc<Self>> {
        let (split_contact, chunk) = (opts.split_contact, opts.contact_chunk);
        let n = a.nrows();
        if a.ncols() != n {
            return Err(SchurError::InvalidInput(format!("A is {} x {}", n, a.ncols())));
        }
        check_e(n, e_rows)?;
        let contact = contact_order(a, e_rows, split_contact);
        let nc = contact.len();
        let n0 = n - nc;
        let mut pos_in_c = vec![usize::MAX; n];
        for (k, &d) in contact.iter().enumerate() {
            pos_in_c[d] = k;
        }

        // Pattern of A_II (interior dofs, renumbered 0..n0).
        let interior: Vec<usize> = (0..n).filter(|&d| pos_in_c[d] == usize::MAX).collect();
        let mut loc = vec![usize::MAX; n];
        for (k, &d) in interior.iter().enumerate() {
            loc[d] = k;
        }
        // Graph for AMD: A_II, plus (if chunk > 0) one vertex per `chunk` consecutive contact dofs,
        // adjacent to the interior neighbours of its dofs and to the next chunk vertex.
        let nch = if chunk == 0 { 0 } else { nc.div_ceil(chunk) };
        let ng = n0 + nch;
        let mut col_ptr = Vec::with_capacity(ng + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0usize);
        let a_rows = a.row_idx();
        for &j in &interior {
            let start = row_idx.len();
            for &i in &a_rows[a.col_range(j)] {
                if loc[i] != usize::MAX {
                    row_idx.push(loc[i]);
                } else if nch > 0 {
                    row_idx.push(n0 + pos_in_c[i] / chunk);
                }
            }
            if nch > 0 {
                row_idx[start..].sort_unstable();
                let mut k = start;
                for r in start..row_idx.len() {
                    if k == start || row_idx[r] != row_idx[k - 1] {
                        row_idx[k] = row_idx[r];
                        k += 1;
                    }
                }
                row_idx.truncate(k);
            }
            col_ptr.push(row_idx.len());
        }
        for k in 0..nch {
            if k + 1 < nch {
                row_idx.push(n0 + k + 1);
            }
            col_ptr.push(row_idx.len());
        }
        let a_ii = SymbolicSparseColMat::<usize>::new_unsorted_checked(ng, ng, col_ptr, None, row_idx);
        let mut p_i = vec![0usize; ng];
        let mut p_inv = vec![0usize; ng];
        {
            let nnz = a_ii.compute_nnz();
            let mut mem = try_buffer(amd::order_maybe_unsorted_scratch::<usize>(ng, nnz), "AMD workspace")?;
            amd::order_maybe_unsorted(
                &mut p_i,
                &mut p_inv,
                a_ii.as_ref(),
                amd::Control::default(),
                MemStack::new(&mut mem),
            )
            .map_err(|e| faer_err("AMD ordering", e))?;
        }
        drop(a_ii);
        let mut fwd: Vec<usize> = p_i.iter().filter(|&&k| k < n0).map(|&k| interior[k]).collect();
        fwd.extend_from_slice(&contact);
        let mut inv = vec![0usize; n];
        for (k, &d) in fwd.iter().enumerate() {
            inv[d] = k;
        }
        let perm = PermRef::new_checked(&fwd, &inv, n);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(a, Side::Lower, SymmetricOrdering::Custom(perm), params)
            .map_err(|e| faer_err("symbolic factorization", e))?;
        Ok(Arc::new(Self { n, contact, pos_in_c, symbolic, a_nnz: a.compute_nnz() }))
    }

    /// Order n of `A`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The contact dofs `C` in elimination order (they are eliminated last).
    pub fn contact_dofs(&self) -> &[usize] {
        &self.contact
    }

    /// The symbolic Cholesky factorization (supernodal, with the "C last" permutation).
    pub fn symbolic(&self) -> &SymbolicCholesky<usize> {
        &self.symbolic
    }

    /// Length of the value array of the factor (supernodal storage, upper parts of diagonal blocks
    /// included).
    pub fn len_val(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Number of structural non-zeros of `L` (lower triangle, diagonal included).
    pub fn nnz_l(&self) -> usize {
        nnz_l(&self.symbolic)
    }

    /// Numeric factorization of `A`, which must have the analysed pattern (either or both triangles
    /// stored, as analysed; the lower triangle is read).
    ///
    /// # Errors
    /// [`SchurError::NotPositiveDefinite`], [`SchurError::TooLarge`], [`SchurError::InvalidInput`] on a shape mismatch.
    pub fn factorize(self: &Arc<Self>, a: SparseColMatRef<'_, usize, f64>, par: Par) -> Result<SchurFactor> {
        if a.nrows() != self.n || a.ncols() != self.n {
            return Err(SchurError::InvalidInput(format!("A is {} x {}, analysed {}", a.nrows(), a.ncols(), self.n)));
        }
        if a.compute_nnz() != self.a_nnz {
            return Err(SchurError::InvalidInput(format!(
                "A has {} stored entries, the analysed pattern {}",
                a.compute_nnz(),
                self.a_nnz
            )));
        }
        let values = numeric_llt(&self.symbolic, a, par)?;
        Ok(SchurFactor { symbolic: Arc::clone(self), values })
    }
}

/// The order of `C` (see [`SchurSymbolic::new_with`]).
///
/// Base order: by the first row of `E` that touches each dof, then by dof (for mortar rows along a
/// boundary this follows the boundary and makes `E_Cᵀ` a "staircase"). With `split`, `C = C₀ ∪ C₁` where
/// `C₁` are the dofs with a neighbour in `I`: eliminating `I` makes the Schur complement dense on `C₁`
/// only, while on `C₀` it keeps the pattern of `A_C₀C₀`. `C₀` is put first, ordered by 1D nested
/// dissection of its base sequence (separators are windows as wide as the bandwidth of `A_C₀C₀` in that
/// sequence), which keeps the fill of `L_C₀C₀` and `L_C₁C₀` small; `C₁` follows in base order.
fn contact_order(a: SymbolicSparseColMatRef<'_, usize>, e_rows: &[Vec<(usize, f64)>], split: bool) -> Vec<usize> {
    let n = a.nrows();
    let mut first_row = vec![usize::MAX; n];
    for (r, row) in e_rows.iter().enumerate() {
        for &(c, _) in row {
            first_row[c] = first_row[c].min(r);
        }
    }
    let mut contact: Vec<usize> = (0..n).filter(|&d| first_row[d] != usize::MAX).collect();
    contact.sort_by_key(|&d| (first_row[d], d));
    if !split {
        return contact;
    }
    let in_c = |d: usize| first_row[d] != usize::MAX;
    // C₁: contact dofs adjacent to an interior dof (either triangle of A may be stored).
    let mut adjacent = vec![false; n];
    for j in 0..n {
        for &i in &a.row_idx()[a.col_range(j)] {
            match (in_c(i), in_c(j)) {
                (true, false) => adjacent[i] = true,
                (false, true) => adjacent[j] = true,
                _ => {}
            }
        }
    }
    let c0: Vec<usize> = contact.iter().copied().filter(|&d| !adjacent[d]).collect();
    if c0.is_empty() {
        return contact;
    }
    let mut pos0 = vec![usize::MAX; n];
    for (k, &d) in c0.iter().enumerate() {
        pos0[d] = k;
    }
    let mut band = 0usize;
    for &j in &c0 {
        for &i in &a.row_idx()[a.col_range(j)] {
            if pos0[i] != usize::MAX {
                band = band.max(pos0[i].abs_diff(pos0[j]));
            }
        }
    }
    let mut order = Vec::with_capacity(contact.len());
    nd_1d(&c0, band, &mut order);
    order.extend(contact.iter().copied().filter(|&d| adjacent[d]));
    order
}

/// 1D nested dissection of a sequence whose graph has bandwidth `w`: both halves, then the separating
/// window of `w` entries.
fn nd_1d(seq: &[usize], w: usize, out: &mut Vec<usize>) {
    if w == 0 || seq.len() <= 2 * w + 2 {
        out.extend_from_slice(seq);
        return;
    }
    let mid = (seq.len() - w) / 2;
    nd_1d(&seq[..mid], w, out);
    nd_1d(&seq[mid + w..], w, out);
    out.extend_from_slice(&seq[mid..mid + w]);
}

/// The numeric factor `P A Pᵀ = L Lᵀ` with `C` last. Solves `A x = b` and forms `E A⁻¹ Eᵀ`.
#[derive(Debug)]
pub struct SchurFactor {
    symbolic: Arc<SchurSymbolic>,
    values: Vec<f64>,
}

impl SchurFactor {
    /// Number of values the factor holds (supernodal storage).
    pub fn len_values(&self) -> usize {
        self.values.len()
    }

    /// The symbolic analysis this factor was computed with.
    pub fn symbolic(&self) -> &Arc<SchurSymbolic> {
        &self.symbolic
    }

    /// The supernodal structure ([`SchurSymbolic`] forces a supernodal factorization, so this never
    /// fails on a factor it built).
    fn supernodal(&self) -> Result<&SymbolicSupernodalCholesky<usize>> {
        match self.symbolic.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => Ok(s),
            SymbolicCholeskyRaw::Simplicial(_) => Err(SchurError::InvalidInput("a simplicial factor".to_string())),
        }
    }

    /// Solves `A X = B` in place for the columns of `rhs` (n × k).
    ///
    /// # Errors
    /// [`SchurError::InvalidInput`] if `rhs` does not have n rows; [`SchurError::TooLarge`] if the workspace cannot
    /// be allocated.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>, par: Par) -> Result<()> {
        let sym = &self.symbolic.symbolic;
        if rhs.nrows() != sym.nrows() {
            return Err(SchurError::InvalidInput(format!("rhs has {} rows, expected {}", rhs.nrows(), sym.nrows())));
        }
        let mut mem = try_buffer(sym.solve_in_place_scratch::<f64>(rhs.ncols(), par), "solve workspace")?;
        LltRef::new(sym, &self.values).solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
        Ok(())
    }

    /// Solves `A x = b` for one right-hand side.
    ///
    /// # Errors
    /// As [`SchurFactor::solve_in_place`].
    pub fn solve(&self, b: &[f64], par: Par) -> Result<Vec<f64>> {
        let mut x = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
        self.solve_in_place(x.as_mut(), par)?;
        Ok((0..b.len()).map(|i| x[(i, 0)]).collect())
    }

    /// Solves `A x = b` for a `b` that vanishes off the contact dofs C, such as `Eᵀ λ`. C is eliminated
    /// last, so `L y = P b` leaves the rows before C at zero and runs over the trailing block only; the
    /// backward substitution runs over the whole factor. The solve reads the factor about once where
    /// [`Self::solve`] reads it twice.
    ///
    /// # Errors
    /// [`SchurError::InvalidInput`] if `b` does not have n rows or does not vanish off C;
    /// [`SchurError::TooLarge`] if the workspace cannot be allocated.
    pub fn solve_from_contact(&self, b: &[f64], par: Par) -> Result<Vec<f64>> {
        let (n, contact) = (self.symbolic.n, &self.symbolic.contact);
        let pos = &self.symbolic.pos_in_c;
        if b.len() != n || b.iter().zip(pos).any(|(v, &k)| *v != 0.0 && k == usize::MAX) {
            return Err(SchurError::InvalidInput("b has the wrong length or does not vanish off C".to_string()));
        }
        let (nc, n0) = (contact.len(), n - contact.len());
        let mut y = try_zeros(n, 1, "solve vector", usize::MAX)?;
        for (k, &d) in contact.iter().enumerate() {
            y[(n0 + k, 0)] = b[d];
        }
        let first = contact.iter().position(|&d| b[d] != 0.0).unwrap_or(nc);
        self.forward_solve_c(y.as_mut().subrows_mut(n0, nc), &[first], 1, par)?;
        let s = self.supernodal()?;
        let mut mem = try_buffer(s.solve_in_place_scratch::<f64>(1, par), "solve workspace")?;
        SupernodalLltRef::<usize, f64>::new(s, &self.values).l_transpose_solve_with_conj(
            Conj::No,
            y.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
        let mut x = vec![0.0; n];
        match self.symbolic.symbolic.perm() {
            Some(p) => p.arrays().0.iter().enumerate().for_each(|(i, &d)| x[d] = y[(i, 0)]),
            None => x.iter_mut().enumerate().for_each(|(i, xi)| *xi = y[(i, 0)]),
        }
        Ok(x)
    }

    /// Forward substitution `W ← L_CC⁻¹ W` with the supernodes of the trailing block, by blocks of `bs`
    /// columns; the rows of `W` above `first[k0]` are zero for the block starting at column k0 and are
    /// skipped (whole supernodes, or the leading part of a supernode).
    fn forward_solve_c(&self, mut w: MatMut<'_, f64>, first: &[usize], bs: usize, par: Par) -> Result<()> {
        let s = self.supernodal()?;
        let n = self.symbolic.n;
        let nc = self.symbolic.contact.len();
        let n0 = n - nc;
        let m = w.ncols();
        let f = SupernodalLltRef::<usize, f64>::new(s, &self.values);
        let ends = s.supernode_end();
        let max_pat =
            (0..s.n_supernodes()).filter(|&k| ends[k] > n0).map(|k| s.supernode(k).pattern().len()).max().unwrap_or(0);
        let mut tmp = try_zeros(max_pat, bs.min(m), "forward-solve workspace", usize::MAX)?;
        for k0 in (0..m).step_by(bs) {
            let k1 = (k0 + bs).min(m);
            let kb = k1 - k0;
            let r0 = first[k0];
            if r0 >= nc {
                break;
            }
            let lo_global = n0 + r0;
            let s_first = ends.partition_point(|&e| e <= lo_global);
            for (si, &e) in ends.iter().enumerate().skip(s_first) {
                let sn = f.supernode(si);
                let b = s.supernode_begin()[si];
                let lo = b.max(lo_global);
                let (off, size) = (lo - b, e - lo);
                let ls = sn.val();
                let width = e - b;
                let pattern = sn.pattern();
                let mut wb = w.as_mut().submatrix_mut(0, k0, nc, kb);
                faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                    ls.submatrix(off, off, size, size),
                    wb.as_mut().subrows_mut(lo - n0, size),
                    par,
                );
                if pattern.is_empty() {
                    continue;
                }
                let mut t = tmp.as_mut().submatrix_mut(0, 0, pattern.len(), kb);
                faer::linalg::matmul::matmul(
                    t.as_mut(),
                    Accum::Replace,
                    ls.submatrix(width, off, pattern.len(), size),
                    wb.as_ref().subrows(lo - n0, size),
                    1.0,
                    par,
                );
                for k in 0..kb {
                    let src = t.as_ref().col(k);
                    let mut dst = wb.as_mut().col_mut(k);
                    for (p, &row) in pattern.iter().enumerate() {
                        dst[row - n0] -= src[p];
                    }
                }
            }
        }
        Ok(())
    }

    /// The dense trailing block `L_CC` (nc × nc, lower triangular), rows and columns in the order of
    /// [`SchurSymbolic::contact_dofs`]. `L_CC L_CCᵀ` is the Schur complement of `A` onto `C`.
    ///
    /// # Errors
    /// [`SchurError::TooLarge`] if nc² doubles exceed `max_bytes` or cannot be allocated.
    pub fn l_cc(&self, max_bytes: usize) -> Result<Mat<f64>> {
        let s = self.supernodal()?;
        let n = self.symbolic.n;
        let nc = self.symbolic.contact.len();
        let n0 = n - nc;
        let mut lcc = try_zeros(nc, nc, "L_CC", max_bytes)?;
        let f = SupernodalLltRef::<usize, f64>::new(s, &self.values);
        for si in 0..s.n_supernodes() {
            let (b, e) = (s.supernode_begin()[si], s.supernode_end()[si]);
            if e <= n0 {
                continue;
            }
            let sn = f.supernode(si);
            let ls = sn.val();
            let w = e - b;
            for jj in 0..w {
                let j = b + jj;
                if j < n0 {
                    continue;
                }
                let jc = j - n0;
                let src = ls.col(jj);
                let mut dst = lcc.as_mut().col_mut(jc);
                for ii in jj..w {
                    dst[b + ii - n0] = src[ii];
                }
                for (p, &row) in sn.pattern().iter().enumerate() {
                    dst[row - n0] = src[w + p];
                }
            }
        }
        Ok(lcc)
    }

    /// `S_E = E A⁻¹ Eᵀ` (m × m, full symmetric), for rows of `E` whose columns lie in the analysed
    /// contact set (the values may differ from those given to [`SchurSymbolic::new`]).
    ///
    /// # Errors
    /// [`SchurError::InvalidInput`] if a row of `E` touches a dof outside `C`; [`SchurError::TooLarge`].
    pub fn schur(&self, e_rows: &[Vec<(usize, f64)>], par: Par) -> Result<Mat<f64>> {
        self.schur_with(e_rows, par, &SchurOptions::default(), &mut SchurTimings::default())
    }

    /// [`SchurFactor::schur`] with options, accumulating the phase times into `t`.
    ///
    /// # Errors
    /// As [`SchurFactor::schur`].
    pub fn schur_with(
        &self,
        e_rows: &[Vec<(usize, f64)>],
        par: Par,
        opts: &SchurOptions,
        t: &mut SchurTimings,
    ) -> Result<Mat<f64>> {
        let clock = std::time::Instant::now();
        let n = self.symbolic.n;
        check_e(n, e_rows)?;
        let m = e_rows.len();
        let nc = self.symbolic.contact.len();
        let pos = &self.symbolic.pos_in_c;
        let l_cc_len = if opts.dense_l_cc { nc.saturating_mul(nc) } else { 0 };
        let need = l_cc_len
            .saturating_add(nc.saturating_mul(m))
            .saturating_add(m.saturating_mul(m).saturating_mul(2))
            .saturating_mul(8);
        if need > opts.max_dense_bytes {
            return Err(SchurError::TooLarge { what: "dense blocks W, S_E (and L_CC)", bytes: need });
        }
        // First non-zero (position in C) of each column of E_Cᵀ; columns processed by increasing p.
        let mut first = Vec::with_capacity(m);
        for (r, row) in e_rows.iter().enumerate() {
            let mut p = nc;
            for &(c, _) in row {
                let k = pos[c];
                if k == usize::MAX {
                    return Err(SchurError::InvalidInput(format!(
                        "row {r} of E touches dof {c}, not in the analysed C"
                    )));
                }
                p = p.min(k);
            }
            first.push(p);
        }
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by_key(|&r| (first[r], r));
        let mut w = try_zeros(nc, m, "W", usize::MAX)?;
        for (k, &r) in order.iter().enumerate() {
            for &(c, v) in &e_rows[r] {
                w[(pos[c], k)] += v;
            }
        }
        // first non-zero row of each column of W, in processing order (non-decreasing)
        let first_sorted: Vec<usize> = order.iter().map(|&r| first[r]).collect();
        t.extract += clock.elapsed().as_secs_f64();

        // W = L_CC⁻¹ E_Cᵀ by blocks of columns, each starting at the block's first non-zero row.
        let clock = std::time::Instant::now();
        let bs = if opts.block == 0 { (m / 16).clamp(64, 512) } else { opts.block };
        if opts.dense_l_cc {
            // reference path: dense copy of L_CC and one dense triangular solve per block
            let lcc = self.l_cc(usize::MAX)?;
            for k0 in (0..m).step_by(bs) {
                let k1 = (k0 + bs).min(m);
                let r0 = first_sorted[k0];
                if r0 >= nc {
                    break;
                }
                faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                    lcc.as_ref().submatrix(r0, r0, nc - r0, nc - r0),
                    w.as_mut().submatrix_mut(r0, k0, nc - r0, k1 - k0),
                    par,
                );
            }
        } else {
            self.forward_solve_c(w.as_mut(), &first_sorted, bs, par)?;
        }
        t.solve += clock.elapsed().as_secs_f64();

        // H = Wᵀ W by panels of rows of W: rows [ra, rb) are non-zero only in the first k columns
        // (those with first non-zero < rb), so each panel is a rank-(rb − ra) update of H[..k, ..k].
        let clock = std::time::Instant::now();
        let mut h = try_zeros(m, m, "S_E", usize::MAX)?;
        let panel = if opts.panel == 0 { (nc / 12).max(256) } else { opts.panel };
        for ra in (0..nc).step_by(panel) {
            let rb = (ra + panel).min(nc);
            let k = first_sorted.partition_point(|&p| p < rb);
            if k == 0 {
                continue;
            }
            let wp = w.as_ref().submatrix(ra, 0, rb - ra, k);
            faer::linalg::matmul::triangular::matmul(
                h.as_mut().submatrix_mut(0, 0, k, k),
                BlockStructure::TriangularLower,
                Accum::Add,
                wp.transpose(),
                BlockStructure::Rectangular,
                wp,
                BlockStructure::Rectangular,
                1.0,
                par,
            );
        }
        drop(w);
        let s = unpermute_lower(h.as_ref(), &order)?;
        t.syrk += clock.elapsed().as_secs_f64();
        Ok(s)
    }
}

/// `S[order[a], order[b]] = H[max(a,b), min(a,b)]` : full symmetric matrix from the lower triangle of
/// `H` given in the permuted order.
fn unpermute_lower(h: MatRef<'_, f64>, order: &[usize]) -> Result<Mat<f64>> {
    let m = order.len();
    let mut s = try_zeros(m, m, "S_E", usize::MAX)?;
    for b in 0..m {
        for a in b..m {
            let v = h[(a, b)];
            s[(order[a], order[b])] = v;
            s[(order[b], order[a])] = v;
        }
    }
    Ok(s)
}

/// Partial factorization of `A` with the dofs touched by `E` last, and `S_E = E A⁻¹ Eᵀ`.
///
/// `a`: n × n SPD (both triangles or the lower one stored); `e_rows`: the m rows of `E` as sorted
/// `(column, value)` lists. Returns the factor (which solves `A x = b`) and the dense symmetric `S_E`.
///
/// # Errors
/// [`SchurError::NotPositiveDefinite`], [`SchurError::TooLarge`], [`SchurError::InvalidInput`].
pub fn schur_e(
    a: &SparseColMat<usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
    par: Par,
) -> Result<(SchurFactor, Mat<f64>)> {
    schur_e_with(a, e_rows, par, &SchurOptions::default()).map(|(f, s, _)| (f, s))
}

/// [`schur_e`] with options, also returning the phase timings.
///
/// # Errors
/// As [`schur_e`].
pub fn schur_e_with(
    a: &SparseColMat<usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
    par: Par,
    opts: &SchurOptions,
) -> Result<(SchurFactor, Mat<f64>, SchurTimings)> {
    let mut t = SchurTimings::default();
    let clock = std::time::Instant::now();
    let sym = SchurSymbolic::new(a.symbolic(), e_rows)?;
    t.symbolic = clock.elapsed().as_secs_f64();
    let clock = std::time::Instant::now();
    let f = sym.factorize(a.as_ref(), par)?;
    t.numeric = clock.elapsed().as_secs_f64();
    let s = f.schur_with(e_rows, par, opts, &mut t)?;
    Ok((f, s, t))
}

/// The former names of [`SchurError`], [`SchurOptions`] and [`SchurTimings`].
#[deprecated(note = "renamed SchurError")]
pub type Error = SchurError;
/// See [`SchurOptions`].
#[deprecated(note = "renamed SchurOptions")]
pub type Options = SchurOptions;
/// See [`SchurTimings`].
#[deprecated(note = "renamed SchurTimings")]
pub type Timings = SchurTimings;

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::Triplet;

    type Rows = Vec<Vec<(usize, f64)>>;
    type TestResult = std::result::Result<(), Box<dyn std::error::Error>>;

    /// A 5-point Laplacian plus a multiple of the identity on an `nx × nx` grid, and rows of `E` that
    /// couple neighbouring dofs of its last grid row (a contact line).
    fn grid(nx: usize) -> std::result::Result<(SparseColMat<usize, f64>, Rows), faer::sparse::CreationError> {
        let id = |i: usize, j: usize| j * nx + i;
        let mut t = Vec::new();
        for j in 0..nx {
            for i in 0..nx {
                t.push(Triplet::new(id(i, j), id(i, j), 4.5 + 0.01 * i as f64));
                for (a, b) in [(i + 1, j), (i, j + 1)] {
                    if a < nx && b < nx {
                        t.push(Triplet::new(id(i, j), id(a, b), -1.0));
                        t.push(Triplet::new(id(a, b), id(i, j), -1.0));
                    }
                }
            }
        }
        let a = SparseColMat::try_new_from_triplets(nx * nx, nx * nx, &t)?;
        let e = (0..nx - 1).map(|i| vec![(id(i, nx - 1), 0.5), (id(i + 1, nx - 1), 0.5 + 0.1 * i as f64)]).collect();
        Ok((a, e))
    }

    /// The half solve from the contact dofs gives the full solve's answer, for a right-hand side that
    /// starts anywhere on C, and refuses one that does not vanish off C.
    #[test]
    fn a_right_hand_side_on_the_contact_dofs_solves_as_a_full_solve() -> TestResult {
        let (a, e) = grid(14)?;
        let n = a.nrows();
        let (factor, _) = schur_e(&a, &e, Par::Seq)?;
        for skip in [0, 3, 12] {
            let mut b = vec![0.0; n];
            for (r, row) in e.iter().enumerate().skip(skip) {
                for &(d, v) in row {
                    b[d] += v * (1.0 + r as f64).sin();
                }
            }
            let (half, full) = (factor.solve_from_contact(&b, Par::Seq)?, factor.solve(&b, Par::Seq)?);
            let size = full.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert!(size > 0.0);
            for (h, f) in half.iter().zip(&full) {
                assert!((h - f).abs() <= 1e-14 * size, "{h} against {f}");
            }
        }
        let mut off = vec![0.0; n];
        off[0] = 1.0;
        assert!(matches!(factor.solve_from_contact(&off, Par::Seq), Err(SchurError::InvalidInput(_))));
        assert!(matches!(factor.solve_from_contact(&[1.0], Par::Seq), Err(SchurError::InvalidInput(_))));
        Ok(())
    }
}
