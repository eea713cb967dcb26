//! Sparse kernels on faer's factorizations, with no knowledge of the rest of the crate (no `crate::`
//! import; they own their error types, and [`crate::condensation`] maps them in one place):
//!
//! * [`schur`]: a partial Cholesky factorization with the multiplier-coupled dofs ordered last, whose
//!   trailing block gives all of `E A⁻¹ Eᵀ` at once;
//! * `llt`: the numeric Cholesky factorization for a given symbolic analysis, and the flops and non-zeros
//!   a symbolic analysis predicts (re-exported by [`schur`]);
//! * `saddle`: the sparse LDLᵀ of the saddle-point system `[[A, E_Fᵀ], [E_F, −Dγ_FF]]` on one pattern,
//!   with bordered solves near the factorized partition.
//!
//! These files may hold up to 800 lines of code (the crate's limit is 600): a supernodal sweep, its
//! symbolic analysis and its refinement read best in one place.

mod llt;
pub(crate) mod saddle;
pub mod schur;
