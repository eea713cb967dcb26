//! # tribo — 2D frictional contact with the stabilized Lagrange multiplier method
//!
//! tribo solves the contact of a linear elastic body (plane strain, plane stress or axisymmetric:
//! [`Model`]; small strain, P1 triangles, with P1 pressures beside them for nearly incompressible bodies:
//! [`Formulation`]) with a
//! rigid obstacle along a boundary Γ_C (a straight segment, or any chain of boundary edges, open or closed, against an
//! obstacle given by its geometry: [`ContactBoundary`], [`ObstacleShape`]), with Coulomb friction, by the
//! stabilized Lagrange multiplier method of Barbosa and Hughes as extended to Coulomb friction by V. Lleras.
//! The multipliers λ_H = (λ_Hn, λ_Ht) live on their own 1D mesh T_H of Γ_C (P0 or continuous P1) whose points
//! need not be FE nodes.
//!
//! ## A first solve
//! A block clamped at the bottom, a rigid cylinder pressed into its top and shifted along it, Coulomb
//! friction:
//!
//! ```
//! use tribo::*;
//!
//! let mesh = rectangle([-2.0, 2.0], [-2.0, 0.0], 32, 16, Diagonal::Right)?;
//! let spec = ProblemSpec::new(Material { young: 200.0, poisson: 0.3 }, "top")
//!     .clamped(["bottom"])
//!     .obstacle(ObstacleShape::Circle { center: 0.0, radius: 1.0 })
//!     .approach(0.01)
//!     .shift(0.004);
//! let solution = Problem::new(mesh, spec)?.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None)?;
//! assert_eq!(solution.report.status, SolveStatus::Converged);
//! println!("P = {}, Q = {}, contact width {}", solution.normal_force, solution.tangential_force, solution.contact_width());
//! # Ok::<(), tribo::Error>(())
//! ```
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
//! 1. [`Problem::new`] validates and assembles K, the loads, Γ_C, T_H and the Γ_C matrices
//!    ([`contact::mortar`]).
//! 2. [`Problem::condense`] factorizes `A = K − G` (sparse Cholesky, faer) for the chosen γ0 and condenses
//!    onto the multipliers: `H = E A⁻¹ Eᵀ + Dγ` ([`condensation`]; see [`qp`] for the QP and why its KKT
//!    conditions are (3.2)). The problem keeps that factorization for the next solve with the same γ0.
//! 3. [`Condensed::solve`] ([`solve`]) solves one QP (frictionless, Tresca) or iterates the fixed point
//!    `g ↦ λ_Hn(g)` of Definition 1 (Coulomb), each step a box-constrained QP over 2q unknowns whose
//!    matrix never changes; beside it, a semismooth Newton method solves the Coulomb problem with the
//!    friction bound following λ_n ([`CoulombMethod`]). [`Problem::solve`] does steps 2 and 3 in one call.
//! 4. The displacement is recovered with one more solve; [`Solution`] carries every field, the contact
//!    state per multiplier dof, the discrete KKT residuals, the a posteriori error indicator η_K
//!    ([`results::ErrorEstimate`]: bulk, Γ_C, contact and friction residuals, and the estimated error of
//!    the contact tractions) and a [`Report`] that says how the solve ended.
//! 5. [`Condensed::solve_history`] ([`solve::history`]) solves a quasi-static loading history — press,
//!    drag, unload — step by step on the same factorization: only the QP's linear term (the load case,
//!    [`problem::load_case`]) and the Coulomb bounds change from step to step.
//! 6. [`Problem::solve_adaptive`] ([`adapt`]) refines by itself: solve, estimate, mark, newest-vertex
//!    bisection ([`mesh::refine`]), until the relative estimate meets a tolerance;
//!    [`Problem::solve_history_adaptive`] does so for a whole loading history, marked on its worst steps.
//! 7. [`Problem::two_bodies`] ([`problem::bodies`]) puts two elastic bodies in contact instead of one against
//!    the rigid obstacle: the multipliers and the stabilization on one side, the jump `u¹ − u²∘Π` in the
//!    contact law ([`pair`] derives it); steps 2–5 are unchanged.
//!
//! ## Folders
//! Folders by job, bottom to top; a folder uses only the folders before it, and the two towers in
//! brackets never use each other (a test reads the `crate::` paths of every file and checks the table):
//!
//! * [`error`] (typed errors, [`Num`]) and [`choice`] (the names of every option);
//! * [`settings`]: one struct per stage, the flat-name table, the friction law ([`settings::friction`])
//!   and the γ0 choice ([`Stabilization`]);
//! * the geometry tower: [`mesh`] (the P1 mesh, its generators, the straight-line test, the curves of edge sets,
//!   bisection) → [`fem`]
//!   (elasticity element by element, supports and the unknowns they leave, assembly) → [`contact`] (Γ_C
//!   and its conventions, the obstacle, T_H, the mortar matrices, the Barbosa–Hughes operators, the γ0
//!   bound);
//! * the algebra tower: `linalg` (sparse kernels on faer's factors, no crate imports) →
//!   [`condensation`] ([`Factor`]: A's factorization and the operator H, and the cost model that picks
//!   how H is formed) → [`qp`] (the Γ_C QP: clarabel, the active-set method on a dense block or on the
//!   saddle-point system, and the working set that picks among them);
//! * [`problem`] (a [`Problem`], its condensed form [`Condensed`], the load case) → [`results`]
//!   ([`Solution`], [`Report`], the KKT residuals, the error estimate) → [`solve`] (the entry points, the
//!   driver, the fixed point and the Newton method, histories, progress) → [`adapt`] (adaptive refinement).
//!
//! The module paths of the earlier flat layout (`tribo::mortar`, `tribo::supports`, `tribo::solution`, …)
//! still resolve, hidden from this documentation.
//!
//! ## References
//! * V. Lleras, *A stabilized Lagrange multiplier method for the finite element approximation of
//!   frictional contact problems in elastostatics*, Mathematical Modelling of Natural Phenomena 4(1),
//!   163–182, 2009. The discrete problem (3.1), the Tresca subproblem (3.2) and the fixed point
//!   (Definition 1) cited throughout are that paper's.
//! * H. J. C. Barbosa, T. J. R. Hughes, *The finite element method with Lagrange multipliers on the
//!   boundary: circumventing the Babuška–Brezzi condition*, Computer Methods in Applied Mechanics and
//!   Engineering 85(1), 109–128, 1991: the stabilization.
//! * The semismooth Newton method for Coulomb friction ([`CoulombMethod::Newton`]): S. Hüeber, G. Stadler,
//!   B. I. Wohlmuth, *A primal–dual active set algorithm for three-dimensional contact problems with Coulomb
//!   friction*, SIAM Journal on Scientific Computing 30(2), 572–596, 2008; P. Alart, A. Curnier, *A mixed
//!   formulation for frictional contact problems prone to Newton like solution methods*, Computer Methods in
//!   Applied Mechanics and Engineering 92(3), 353–375, 1991.
//! * The hierarchical traction estimate ([`Problem::estimate_hierarchical`]): R. E. Bank, A. Weiser, *Some a
//!   posteriori error estimators for elliptic partial differential equations*, Mathematics of Computation
//!   44(170), 283–301, 1985; R. E. Bank, R. K. Smith, *A posteriori error estimates based on hierarchical
//!   bases*, SIAM Journal on Numerical Analysis 30(4), 921–935, 1993; W. Dörfler, R. H. Nochetto, *Small
//!   data oscillation implies the saturation assumption*, Numerische Mathematik 91, 1–12, 2002; Q. Zou,
//!   A. Veeser, R. Kornhuber, C. Gräser, *Hierarchical error estimates for the energy functional in obstacle
//!   problems*, Numerische Mathematik 117, 653–677, 2011.
//!
//! ## Conventions
//! Dofs are interleaved (x, y) per node; stresses are `(σ_xx, σ_yy, σ_xy)`; n is the outward normal on
//! Γ_C and `t = (−n₂, n₁)`; abscissae on Γ_C are described in [`contact`]. `λ_n = −σ_n ≥ 0` and
//! `λ_t = −σ_t` (along t); the obstacle moves by `−δ n + s t` ([`Solution::obstacle_motion`]) and exerts
//! `−(N n + T t)` on the body ([`Solution::contact_force`], global axes). Numbers in messages are
//! formatted by [`Num`].
#![warn(missing_docs)]

// The folders, bottom to top; a folder uses only folders before it, and the two towers in brackets never
// use each other (ARCHITECTURE.md; `tests/integration/layout.rs` checks the table of allowed edges):
// error, choice → settings → [mesh → fem → contact] and [linalg → condensation → qp] → problem → results
// → solve → adapt.
pub mod choice;
pub mod error;
pub mod settings;

pub mod contact;
pub mod fem;
pub mod mesh;

pub mod condensation;
pub(crate) mod linalg;
pub mod qp;

pub mod problem;
pub mod results;
pub mod solve;

pub mod adapt;

pub use adapt::{AdaptStop, Adaptive, AdaptiveHistory, Level, LevelObserver};
pub use choice::Choice;
pub use condensation::Factor;
pub use contact::gamma0::Gamma0Bound;
pub use contact::multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
pub use contact::obstacle::{DistanceFunction, GapFunction, Obstacle, ObstacleRotation, ObstacleShape};
pub use contact::ContactBoundary;
pub use error::{Error, Num, Result};
pub use fem::elasticity::{Material, Materials, Model, Traction};
pub use fem::mixed::Formulation;
pub use fem::supports::{Dofs, NodeSupport, Support};
pub use mesh::generate::{graded_rectangle, rectangle, Diagonal, Grading, Side};
pub use mesh::shapes::{disc, plate_with_hole, ring_sector, ArcGrading, DiscSector, PlateWithHole, RingSector};
pub use mesh::{Curve, Mesh};
pub use problem::bodies::{Body, BodyPart, ContactPair};
pub use problem::load_case::LoadCase;
#[allow(deprecated)]
pub use problem::load_case::Loading;
pub use problem::sides::{ContactSide, PairParts, PairSpec};
pub use problem::{Bodies, Condensed, Problem, ProblemKeywords, ProblemSpec};
pub use qp::{QpOutcome, QpStatus};
pub use results::{
    Agreement, ContactState, CoulombCheck, KktResiduals, PairResult, Report, Solution, SolveStatus, Timings,
};
pub use settings::friction::{Friction, FrictionLaw, Threshold};
pub use settings::{
    AdaptKeywords, AdaptSettings, Bisection, Condensation, CoulombMethod, FixedPointSettings, KktSolver, Marking,
    QpMethod, QpSettings, SettingInfo, SettingKind, SettingValue, SolverSettings, Stabilization, StopOn,
};
pub use solve::history::LoadStep;
pub use solve::history::{History, HistoryPair, StepObserver, StepProgress, StepRecord};
pub use solve::{Observer, Phase, Progress};

// The module paths of the flat layout that the folders replaced: they keep resolving, so that code
// written against them does not break (hidden from the documentation, which shows the folders).
#[doc(hidden)]
pub use contact::{mortar, multiplier, obstacle, pair};
#[doc(hidden)]
pub use fem::{elasticity, supports};
#[doc(hidden)]
pub use linalg::schur;
#[doc(hidden)]
pub use mesh::generate;
#[doc(hidden)]
pub use qp::{active_set, working_set};
#[doc(hidden)]
pub use settings::friction;
#[doc(hidden)]
pub use solve::history;
/// The old path of [`results`].
#[doc(hidden)]
pub mod solution {
    pub use crate::results::*;
}
/// The old path of the γ0 setting, its bound and the Γ_C operators.
#[doc(hidden)]
pub mod stabilization {
    pub use crate::contact::gamma0::*;
    pub use crate::contact::operators::*;
    pub use crate::settings::Stabilization;
}
/// The old path of [`problem::load_case`].
#[doc(hidden)]
pub mod loading {
    pub use crate::problem::load_case::*;
    pub use crate::solve::history::LoadStep;
}

/// The Rust example of README.md, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The example of the Rust guide (`docs/guide/rust.md`), compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/guide/rust.md")]
pub struct RustGuideDoctests;

/// The Rust example of the two-body guide (`docs/guide/two-bodies.md`), compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/guide/two-bodies.md")]
pub struct TwoBodiesGuideDoctests;

/// Every named choice of the keyword surface (the Python binding, scene files), by the keyword that takes
/// it: `side`, `diagonal`, `space`, `friction`, `state` (in the order of [`Choice::code`]), `status`
/// ([`SolveStatus::NAMES`]), `marking` ([`Marking`]), `bisection` ([`Bisection`]), `stop_on` ([`StopOn`]) and every choice among the solver settings ([`SolverSettings::table`]), each
/// with its names as [`Choice::parse`] takes them.
///
/// It lives here, above every module, because it names the option enums of all of them (`choice` sits
/// below them all).
pub fn choice_registry() -> Vec<(&'static str, Vec<&'static str>)> {
    let mut out = vec![
        ("side", Side::names()),
        ("diagonal", Diagonal::names()),
        ("space", MultiplierSpace::names()),
        ("model", Model::names()),
        ("formulation", Formulation::names()),
        ("friction", FrictionLaw::names()),
        ("state", ContactState::names()),
        ("status", SolveStatus::NAMES.to_vec()),
        ("marking", Marking::names()),
        ("bisection", Bisection::names()),
        ("stop_on", StopOn::names()),
    ];
    out.extend(SolverSettings::table().into_iter().filter_map(|info| match info.kind {
        SettingKind::Choice(names) => Some((info.name, names)),
        _ => None,
    }));
    out
}
