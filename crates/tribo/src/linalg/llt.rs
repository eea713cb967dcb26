//! The numeric sparse Cholesky factorization for a symbolic analysis done elsewhere (the plain one of
//! [`crate::condensation`] and the partial one of [`super::schur`] share it), and what a symbolic
//! analysis says of its factor's cost (flops, non-zeros) before any value is computed.

use faer::dyn_stack::MemStack;
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::sparse::SparseColMatRef;
use faer::{Par, Side};

use super::schur::{try_buffer, Result, SchurError};

/// The numeric Cholesky factorization of `a` with the symbolic analysis `symbolic` of its pattern (lower
/// triangle read): the factor's values.
///
/// # Errors
/// [`SchurError::TooLarge`] if the values or the workspace cannot be allocated;
/// [`SchurError::NotPositiveDefinite`] naming the dof (in `a`'s numbering) of a non-positive pivot.
pub fn numeric_llt(
    symbolic: &SymbolicCholesky<usize>,
    a: SparseColMatRef<'_, usize, f64>,
    par: Par,
) -> Result<Vec<f64>> {
    let len = symbolic.len_val();
    let mut values = Vec::new();
    values.try_reserve_exact(len).map_err(|_| SchurError::TooLarge { what: "factor values", bytes: len * 8 })?;
    values.resize(len, 0.0);
    let mut mem =
        try_buffer(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()), "factorization workspace")?;
    let stack = MemStack::new(&mut mem);
    let reg = LltRegularization::default();
    match symbolic.factorize_numeric_llt(&mut values, a, Side::Lower, reg, par, stack, Default::default()) {
        Ok(_) => Ok(values),
        Err(LltError::NonPositivePivot { index }) => Err(SchurError::NotPositiveDefinite {
            dof: symbolic.perm().map_or(index, |p| p.arrays().0.get(index).copied().unwrap_or(index)),
        }),
    }
}

/// Flops of the numeric factorization described by `sym`: `Σ_j c_j²` over the column counts `c_j` of
/// `L` (diagonal included). A cheap predictor of the factorization time once the symbolic analysis is
/// done.
pub fn factor_flops(sym: &SymbolicCholesky<usize>) -> f64 {
    match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => s.col_ptr().windows(2).map(|w| ((w[1] - w[0]) as f64).powi(2)).sum(),
        SymbolicCholeskyRaw::Supernodal(s) => (0..s.n_supernodes())
            .map(|k| {
                let w = s.supernode_end()[k] - s.supernode_begin()[k];
                let p = s.supernode(k).pattern().len();
                (0..w).map(|i| ((w - i + p) as f64).powi(2)).sum::<f64>()
            })
            .sum(),
    }
}

/// Number of structural non-zeros of the Cholesky factor described by `sym` (diagonal included).
pub fn nnz_l(sym: &SymbolicCholesky<usize>) -> usize {
    match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => s.len_val(),
        SymbolicCholeskyRaw::Supernodal(s) => (0..s.n_supernodes())
            .map(|k| {
                let w = s.supernode_end()[k] - s.supernode_begin()[k];
                w * (w + 1) / 2 + w * s.supernode(k).pattern().len()
            })
            .sum(),
    }
}
