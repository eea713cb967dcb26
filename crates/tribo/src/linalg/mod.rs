//! Sparse kernels on faer's factorizations, with no knowledge of the rest of the crate (no `crate::`
//! import; they own their error types, and [`crate::condensation`] maps them in one place):
//!
//! * [`schur`]: a partial Cholesky factorization with the multiplier-coupled dofs ordered last, whose
//!   trailing block gives all of `E A⁻¹ Eᵀ` at once;
//! * `llt`: the numeric Cholesky factorization for a given symbolic analysis, and the flops and non-zeros
//!   a symbolic analysis predicts (re-exported by [`schur`]);
//! * `blocks`: an LDLᵀ factor read block by block (simplicial columns or supernodes), and its substitutions
//!   restricted to what a sparse right-hand side reaches and what the caller reads;
//! * `saddle`: the sparse LDLᵀ of the saddle-point system `[[A, E_Fᵀ], [E_F, −Dγ_FF]]` on one pattern,
//!   with bordered solves near the factorized partition;
//! * [`gram_split`]: which combinations of a few vectors a set of rows sees (the rigid motions of bodies
//!   held only by the contact).
//!
//! These files may hold up to 800 lines of code (the crate's limit is 600): a supernodal sweep, its
//! symbolic analysis and its refinement read best in one place.

pub(crate) mod blocks;
mod llt;
pub(crate) mod saddle;
pub mod schur;

/// The Gram matrix `G[a][b] = Σ_i col(a)[i] col(b)[i]` (over `rows`) of `r` columns, split by its
/// eigenvalues: the eigenvectors above `tiny(λ_max)` (the combinations the rows see) and those at or
/// below it (the combinations they miss), each as a vector of `r` coefficients.
pub(crate) fn gram_split(
    r: usize,
    rows: &[usize],
    col: impl Fn(usize, usize) -> f64,
    tiny: impl Fn(f64) -> f64,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let gram = nalgebra::DMatrix::from_fn(r, r, |a, b| rows.iter().map(|&i| col(a, i) * col(b, i)).sum::<f64>());
    let eig = gram.symmetric_eigen();
    let limit = tiny(eig.eigenvalues.max());
    let vector = |k: usize| eig.eigenvectors.column(k).iter().copied().collect::<Vec<f64>>();
    let (seen, missed): (Vec<usize>, Vec<usize>) = (0..r).partition(|&k| eig.eigenvalues[k] > limit);
    (seen.into_iter().map(vector).collect(), missed.into_iter().map(vector).collect())
}
