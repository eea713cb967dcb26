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
//! 2. [`Problem::condense`] factorizes `A = K − G` (sparse Cholesky, faer) for the chosen γ0 and condenses
//!    onto the multipliers: `H = E A⁻¹ Eᵀ + Dγ` ([`condensation`]; see [`qp`] for the QP and why its KKT
//!    conditions are (3.2)). The problem keeps that factorization for the next solve with the same γ0.
//! 3. [`Condensed::solve`] ([`solve`]) solves one QP (frictionless, Tresca) or iterates the fixed point
//!    `g ↦ λ_Hn(g)` of Definition 1 (Coulomb), each step a box-constrained QP over 2q unknowns whose
//!    matrix never changes. [`Problem::solve`] does steps 2 and 3 in one call.
//! 4. The displacement is recovered with one more solve; [`Solution`] carries every field, the contact
//!    state per multiplier dof, the discrete KKT residuals and a [`Report`] that says how the solve ended.
//! 5. [`Condensed::solve_history`] ([`history`]) solves a quasi-static loading history — press, drag,
//!    unload — step by step on the same factorization: only the QP's linear term ([`loading`]) and the
//!    Coulomb bounds change from step to step.
//!
//! ## Module layout
//! Mathematics first: [`mesh`], [`generate`], [`elasticity`], [`contact`], [`obstacle`], [`multiplier`],
//! [`mortar`], [`stabilization`] (the γ0-dependent operators), [`supports`] (Dirichlet conditions and the
//! lifting of prescribed displacements), [`problem`]; then the solver:
//! [`condensation`] (linear algebra of `A` and `H`), [`qp`] (clarabel), [`working_set`], `sparse_qp` and
//! `saddle` (the QPs without H, on the sparse saddle-point system), [`friction`],
//! [`settings`], [`loading`] (the load case: the QP's linear term), [`solve`] (the driver and the fixed
//! point), [`history`] (loading histories) and [`solution`]. [`choice`] gives every enum
//! of options its names. No module imports one that imports it back (a test reads the `use` lines).
//!
//! ## References
//! * V. Lleras, *A stabilized Lagrange multiplier method for the finite element approximation of
//!   frictional contact problems in elastostatics*, Mathematical Modelling of Natural Phenomena 4(1),
//!   163–182, 2009. The discrete problem (3.1), the Tresca subproblem (3.2) and the fixed point
//!   (Definition 1) cited throughout are that paper's.
//! * H. J. C. Barbosa, T. J. R. Hughes, *The finite element method with Lagrange multipliers on the
//!   boundary: circumventing the Babuška–Brezzi condition*, Computer Methods in Applied Mechanics and
//!   Engineering 85(1), 109–128, 1991: the stabilization.
//!
//! ## Conventions
//! Dofs are interleaved (x, y) per node; stresses are `(σ_xx, σ_yy, σ_xy)`; n is the outward normal on
//! Γ_C and `t = (−n₂, n₁)`; abscissae on Γ_C are described in [`contact`]. `λ_n = −σ_n ≥ 0` and
//! `λ_t = −σ_t` (along t); the obstacle moves by `−δ n + s t` ([`Solution::obstacle_motion`]) and exerts
//! `−(N n + T t)` on the body ([`Solution::contact_force`], global axes). Numbers in messages are
//! formatted by [`Num`].
#![warn(missing_docs)]

pub mod active_set;
pub mod choice;
pub mod condensation;
pub mod contact;
pub mod elasticity;
pub mod error;
pub mod friction;
pub mod generate;
pub mod history;
pub mod loading;
pub mod mesh;
pub mod mortar;
pub mod multiplier;
pub mod obstacle;
pub mod problem;
pub mod qp;
pub(crate) mod saddle;
pub mod schur;
pub mod settings;
pub mod solution;
pub mod solve;
pub(crate) mod sparse_qp;
pub mod stabilization;
pub mod supports;
pub mod working_set;

pub use choice::Choice;
pub use condensation::Factor;
pub use contact::ContactBoundary;
pub use elasticity::Material;
pub use error::{Error, Num, Result};
pub use friction::{Friction, FrictionLaw, Threshold};
pub use generate::{graded_rectangle, rectangle, Diagonal, Grading, Side};
pub use history::{History, StepObserver, StepProgress};
pub use loading::{LoadStep, Loading};
pub use mesh::Mesh;
pub use multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
pub use obstacle::{GapFunction, Obstacle, ObstacleShape};
pub use problem::{Condensed, Problem, ProblemSpec};
pub use qp::{QpOutcome, QpStatus};
pub use settings::{
    Condensation, FixedPointSettings, KktSolver, QpMethod, QpSettings, SettingInfo, SettingKind, SettingValue,
    SolverSettings,
};
pub use solution::{ContactState, KktResiduals, Report, Solution, SolveStatus, Timings};
pub use solve::{Observer, Phase, Progress};
pub use stabilization::{Gamma0Bound, Stabilization};
pub use supports::{Dofs, NodeSupport, Support};

/// The Rust example of README.md, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// Every named choice of the keyword surface (the Python binding, scene files), by the keyword that takes
/// it: `side`, `diagonal`, `space`, `friction`, `state` (in the order of [`Choice::code`]), `status`
/// ([`SolveStatus::NAMES`]) and every choice among the solver settings ([`SolverSettings::table`]), each
/// with its names as [`Choice::parse`] takes them.
///
/// It lives here, above every module, because it names the option enums of all of them (`choice` sits
/// below them all).
pub fn choice_registry() -> Vec<(&'static str, Vec<&'static str>)> {
    let mut out = vec![
        ("side", Side::names()),
        ("diagonal", Diagonal::names()),
        ("space", MultiplierSpace::names()),
        ("friction", FrictionLaw::names()),
        ("state", ContactState::names()),
        ("status", SolveStatus::NAMES.to_vec()),
    ];
    out.extend(SolverSettings::table().into_iter().filter_map(|info| match info.kind {
        SettingKind::Choice(names) => Some((info.name, names)),
        _ => None,
    }));
    out
}
