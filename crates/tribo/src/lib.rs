//! # tribo — 2D frictional contact with the stabilized Lagrange multiplier method
//!
//! tribo solves the contact of a linear elastic body (plane strain, small strain, P1 triangles) with a
//! rigid obstacle along a straight boundary Γ_C, with Coulomb friction, by the stabilized Lagrange
//! multiplier method of Barbosa and Hughes as extended to Coulomb friction by V. Lleras. The multipliers
//! λ_H = (λ_Hn, λ_Ht) live on their own 1D mesh T_H of Γ_C (P0 or continuous P1) whose points need not be
//! FE nodes.
//!
//! ## The discrete problem (3.1)
//! Find `u_h ∈ V_h`, `λ_H ∈ M_H(μ λ_Hn)` with
//!
//! ```text
//! a(u_h, v_h) + b(λ_H, v_h) − ∫_Γ_C γ (λ_Hn + σ_n(u_h)) σ_n(v_h) − ∫_Γ_C γ (λ_Ht + σ_t(u_h)) σ_t(v_h) = L(v_h)
//! b(ν_H − λ_H, w_h) − ∫_Γ_C γ (ν_Hn − λ_Hn)(λ_Hn + σ_n(u_h)) − ∫_Γ_C γ (ν_Ht − λ_Ht)(λ_Ht + σ_t(u_h)) ≤ 0
//! ```
//!
//! for all `v_h`, `ν_H ∈ M_H(μ λ_Hn)`, with `γ = γ0 h_T` and `w_h = (u_hn − g, u_ht − s)` the
//! displacement relative to the obstacle (gap g, tangential shift s; see [`obstacle`]). γ0 = 0 is the
//! classic mixed method.
//!
//! ## How it is solved
//! 1. [`Problem::new`] validates and assembles K, the loads, Γ_C, T_H and the Γ_C matrices ([`mortar`]).
//! 2. [`Condensed::new`] factorizes `A = K − G` once (sparse Cholesky, faer) and condenses onto the
//!    multipliers: `H = E A⁻¹ Eᵀ + Dγ` (see [`tresca`] for the QP and why its KKT conditions are (3.2)).
//! 3. [`Condensed::solve`] solves one QP (frictionless, Tresca) or iterates the fixed point
//!    `g ↦ λ_Hn(g)` of Definition 1 (Coulomb, [`coulomb`]), each step a clarabel QP over 2q unknowns
//!    whose matrix never changes.
//! 4. The displacement is recovered with one more solve; [`Solution`] carries every field, the contact
//!    state per multiplier dof, the discrete KKT residuals and a [`Report`].
//!
//! ## Conventions
//! Dofs are interleaved (x, y) per node; stresses are `(σ_xx, σ_yy, σ_xy)`; n is the outward normal on
//! Γ_C and `t = (−n₂, n₁)`; abscissae on Γ_C are described in [`contact`].
#![warn(missing_docs)]

pub mod condensation;
pub mod contact;
pub mod coulomb;
pub mod elasticity;
pub mod error;
pub mod generate;
pub mod mesh;
pub mod mortar;
pub mod multiplier;
pub mod obstacle;
pub mod problem;
pub mod solution;
pub mod stabilization;
pub mod tresca;
pub mod working_set;

pub use condensation::Condensed;
pub use contact::ContactBoundary;
pub use coulomb::{FixedPointSettings, Friction, Observer, Progress, SolverSettings, Threshold};
pub use elasticity::Material;
pub use error::{Error, Result};
pub use generate::{graded_rectangle, rectangle, Diagonal, Grading, Side};
pub use mesh::Mesh;
pub use multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
pub use obstacle::{GapFunction, Obstacle, ObstacleShape};
pub use problem::{Problem, ProblemSpec};
pub use solution::{ContactState, KktResiduals, Report, Solution, SolveStatus, Timings};
pub use stabilization::Stabilization;
pub use tresca::{KktSolver, QpSettings, QpStatus};

/// The Rust example of README.md, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
