//! The Γ_C QP: the Tresca subproblem P(g) (3.2), and the frictionless problem as its special case without
//! tangential multipliers, as a convex box-constrained QP over the multipliers, solved with clarabel.
//!
//! # The QP
//! With `A = K − G` (stabilized stiffness, positive definite for admissible γ0), `E = B − Cγ S` (the
//! multiplier–displacement coupling: mortar term minus the γ-weighted stress term, `2q × n`),
//! `Dγ = blockdiag(∫γψψ, ∫γψψ)` and `d = (∫ψ g, ∫ψ s)` (obstacle), the Lagrangian 𝓛_γ of §3.2 reads
//!
//! `𝓛(v, ν) = ½ vᵀ A v − fᵀ v + νᵀ (E v − d) − ½ νᵀ Dγ ν`.
//!
//! Minimising over v gives `v = A⁻¹ (f − Eᵀ ν)`; the saddle point is then the maximiser over the cone
//! `M_H(g) = {ν_n ≥ 0, |ν_t| ≤ g}` of the concave dual, i.e. the QP
//!
//! `min ½ νᵀ H ν + cᵀ ν  s.t.  ν_n ≥ 0, −g ≤ ν_t ≤ g`,   `H = E A⁻¹ Eᵀ + Dγ`,  `c = d − E A⁻¹ f`.
//!
//! Its KKT conditions are exactly (3.2): the v-stationarity `A u + Eᵀ λ = f` is the equation of (3.2)
//! (the γ terms of the first line are the `−G u` and `−Cγᵀ`-parts of `A` and `Eᵀ`), and the first-order
//! condition of the QP over the convex set, `(ν − λ)ᵀ (H λ + c) ≥ 0 ∀ν`, is
//! `(ν − λ)ᵀ (E u − d − Dγ λ) ≤ 0`: the inequality of (3.2), term by term. H is dense but small: it lives
//! on Γ_C (2q unknowns), and it does not depend on g, so the Coulomb fixed point only changes the bounds.
//!
//!
//! # Where each part lives
//! [`QpStatus`] and [`QpOutcome`] (here) are what every method returns. `scaling` non-dimensionalises
//! the QP; `clarabel` is the interior-point reference ([`BoxQp`]), `equality` eliminates the equilibrium rows of
//! the bodies held only by the contact before clarabel sees them; [`active_set`] the primal–dual
//! active-set method, on a dense block of H (`dense`) or on the sparse saddle-point system (`sparse`);
//! [`working_set`] is the front door of every Γ_C QP ([`working_set::ContactQp`]): it picks the method
//! and grows the set of multiplier dofs the QP is solved on.

pub mod active_set;
mod clarabel;
mod dense;
mod equality;
mod scaling;
pub(crate) mod sparse;
pub mod working_set;

pub use clarabel::{BoxQp, DENSE_BYTES_PER_K2};
pub(crate) use scaling::{diagonal, Scaling};

use crate::settings::QpMethod;

/// What a Γ_C QP needs of its load case: the load f on the unknowns, the obstacle moments d and the
/// linear term `c = d − E A⁻¹ f` (all borrowed; see [`crate::LoadCase`]).
#[derive(Debug, Clone, Copy)]
pub struct QpData<'a> {
    /// The load on the unknowns.
    pub f: &'a [f64],
    /// The obstacle moments (2q).
    pub d: &'a [f64],
    /// The linear term (2q).
    pub c: &'a [f64],
    /// For bodies held only by the contact: `E R` (2q × r, column-major) and `Rᵀ f` (r), the equality
    /// `(E R)ᵀ ν = Rᵀ f` of their equilibrium (see `problem/floating.rs`).
    pub rigid: Option<(&'a [f64], &'a [f64])>,
}

/// The tolerance a QP falls back to when it fails at a tighter one.
pub const FALLBACK_TOL: f64 = 1e-10;

/// How one QP solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QpStatus {
    /// Solved to tolerance.
    Solved,
    /// Solved to reduced accuracy: the scaled QP's gap and feasibility residuals meet
    /// `max(tol, FALLBACK_TOL)` but not `tol` (clarabel's "almost solved" with our reduced tolerances,
    /// or a re-solve at [`FALLBACK_TOL`]).
    Inaccurate,
    /// Failed; the string is clarabel's status.
    Failed(&'static str),
}

/// Result of one QP solve.
#[derive(Debug, Clone)]
pub struct QpOutcome {
    /// The multipliers ν = (ν_n, ν_t) (unscaled; ν_t empty for a frictionless QP).
    pub nu: Vec<f64>,
    /// Status.
    pub status: QpStatus,
    /// Iterations of the method that answered (interior-point iterations for clarabel, steps for the
    /// active-set method), including those of a failed attempt before it.
    pub iterations: u32,
    /// Wall time in seconds.
    pub seconds: f64,
    /// The method that produced the answer: [`QpMethod::Clarabel`] or [`QpMethod::ActiveSet`].
    pub method: QpMethod,
    /// Factorizations the active-set method's steps made: dense Cholesky factorizations of the free block,
    /// or sparse LDLᵀ of the saddle-point system; its other steps updated the dense factor or bordered the
    /// sparse one. 0 for clarabel (its KKT factorizations are its iterations).
    pub factorizations: u32,
    /// True when the first method tried did not answer (the active-set method could not certify, or
    /// clarabel failed under [`QpMethod::Auto`]) and the other one did.
    pub fallback: bool,
    /// The rigid motion α of the bodies held only by the contact (the multipliers of the equality of
    /// [`QpData::rigid`]); empty without such bodies.
    pub alpha: Vec<f64>,
}
