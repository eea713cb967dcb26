//! How a solve ended: its status (a numerical outcome, never an error), the contact state of each
//! multiplier dof, the wall time of each phase and the [`Report`] that gathers them.

use crate::choice::named_choice;
use crate::results::ErrorEstimate;
use crate::settings::friction::FrictionLaw;
use crate::settings::{Condensation, CoulombMethod, QpMethod};

/// How a solve ended. Not an error: a solve that did not converge still returns its last iterate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SolveStatus {
    /// Every QP solved and (Coulomb) the fixed point converged.
    Converged,
    /// The fixed point (or the Newton method) reached its iteration cap.
    MaxIterations,
    /// The change of λ_n made no new minimum for [`crate::solve::STAGNATION_WINDOW`] iterations: the
    /// fixed point cycles, or it has reached the accuracy to which the QP determines λ (see the residual
    /// history; a tighter `qp.tol` or a finer mesh may help). One whose smallest change is within √tol (`tol` the
    /// QP tolerance its QPs met) and whose last iterate meets Coulomb's law to `fp_tol` (to `max(√tol, fp_tol)`
    /// where clarabel answered its QPs) is [`SolveStatus::Converged`]. The Newton method
    /// ends so when, after its restarts, its merit makes no new minimum for as many steps, or the linear system of
    /// a step is singular (the log says which).
    Stagnated,
    /// The observer asked to stop after the given fixed-point iteration or Newton step (0 = the initial QP).
    Interrupted {
        /// Fixed-point iteration.
        iteration: usize,
    },
    /// A QP failed at the given fixed-point iteration (0 = the initial QP; for Newton, the QP of a restart
    /// after `iteration − 1` steps).
    QpFailed {
        /// Fixed-point iteration.
        iteration: usize,
        /// clarabel's status.
        reason: &'static str,
    },
    /// The solve ran to its end but a reported field or residual is not finite (an overflow).
    NonFinite,
    /// The solve ran to its end but its KKT residuals exceed what the tolerances justify
    /// ([`crate::Solution::accuracy_bound`]).
    Inaccurate,
}

impl SolveStatus {
    /// The names of the statuses, as [`SolveStatus::name`] gives them.
    pub const NAMES: [&'static str; 7] =
        ["converged", "max_iterations", "stagnated", "interrupted", "qp_failed", "non_finite", "inaccurate"];

    /// The status's name (without its data): one of [`SolveStatus::NAMES`].
    pub fn name(&self) -> &'static str {
        match self {
            Self::Converged => "converged",
            Self::MaxIterations => "max_iterations",
            Self::Stagnated => "stagnated",
            Self::Interrupted { .. } => "interrupted",
            Self::QpFailed { .. } => "qp_failed",
            Self::NonFinite => "non_finite",
            Self::Inaccurate => "inaccurate",
        }
    }
}

impl std::fmt::Display for SolveStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Interrupted { iteration } => write!(f, "interrupted after iteration {iteration}"),
            Self::QpFailed { iteration, reason } => write!(f, "qp_failed at iteration {iteration} ({reason})"),
            s => f.write_str(s.name()),
        }
    }
}

/// Contact state of a multiplier dof.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactState {
    /// λ_n = 0.
    Separation,
    /// In contact, |λ_t| below the threshold.
    Stick,
    /// In contact, |λ_t| at the threshold (μ λ_n or the Tresca bound); every contact dof of a
    /// frictionless problem (threshold 0) slips.
    Slip,
}

named_choice!(ContactState, "contact state", {
    ContactState::Separation => "separation",
    ContactState::Stick => "stick",
    ContactState::Slip => "slip",
});

/// What a check of a Coulomb answer by the other method found ([`CoulombCheck::agreement`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Agreement {
    /// The two answers are one: their λ_n lie within the bound their residuals give.
    Agree,
    /// Two answers, each meeting Coulomb's law to its residual, lie further apart than the bound allows: λ is
    /// not unique there (the discrete Coulomb problem may have several solutions above a critical μ), or not
    /// determined to better than their distance.
    Differ,
    /// No verdict: the other method did not converge (or was refused, or a QP of the check failed: the log says
    /// why), or the two answers lie further apart than their residuals and the fixed point's last changes show no
    /// contraction (L ≥ 1, or fewer than two changes), without which the bound is infinite.
    Undecided,
}

named_choice!(Agreement, "agreement", {
    Agreement::Agree => "agree",
    Agreement::Differ => "differ",
    Agreement::Undecided => "undecided",
});

/// A Coulomb answer checked by the other method (`SolverSettings::coulomb_check`; derived in
/// `solve/check.rs`). Distances are Euclidean over the multiplier dofs, relative to ‖λ_n‖ of the answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoulombCheck {
    /// The method that checked the answer (the one that did not answer).
    pub method: CoulombMethod,
    /// How that method ended (`None`: it was refused, e.g. by the memory budget; the log says why).
    pub status: Option<SolveStatus>,
    /// The verdict.
    pub agreement: Agreement,
    /// ‖λ_n¹ − λ_n²‖ relative to the larger ‖λ_n‖ (NaN when the other method did not converge or was refused).
    pub distance: f64,
    /// The distance within which the two are one answer, relative alike: (δ₁ + δ₂ + ε₁ + ε₂) / (1 − L), δᵢ the
    /// change one more fixed-point iteration makes to answer i, εᵢ what its QPs determine λ_n to (√qp_tol ‖λ_n‖),
    /// L the fixed point's contraction; infinite where no contraction is measured (L ≥ 1, or no estimate).
    pub allowed: f64,
    /// L, the fixed point's contraction estimated from its last changes (the largest ratio of consecutive ones
    /// over the last three; NaN with fewer than two changes).
    pub contraction: f64,
    /// ‖Φ_H(λ_n¹) − Φ_H(λ_n²)‖ / ‖λ_n¹ − λ_n²‖: near 1 where the two are two fixed points, NaN where they coincide.
    pub secant: f64,
}

/// Wall times per phase, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Stiffness and load assembly.
    pub assembly: f64,
    /// Γ_C geometry, T_H and the Γ_C matrices.
    pub contact_matrices: f64,
    /// Assembling and factorizing A = K − G.
    pub factorization: f64,
    /// Condensing onto the multipliers (H, c).
    pub condensation: f64,
    /// All QPs (including the fixed point), and the check of a Coulomb answer by the other method where
    /// `coulomb_check` asked for it.
    pub qp: f64,
    /// Recovering u.
    pub recovery: f64,
    /// Forming the fields from u and λ: stresses, reactions, the contact fields, the KKT residuals and
    /// the a posteriori estimate.
    pub fields: f64,
}

impl Timings {
    /// Every phase by name, in the order of the fields.
    pub fn named(&self) -> [(&'static str, f64); 7] {
        [
            ("assembly", self.assembly),
            ("contact_matrices", self.contact_matrices),
            ("factorization", self.factorization),
            ("condensation", self.condensation),
            ("qp", self.qp),
            ("recovery", self.recovery),
            ("fields", self.fields),
        ]
    }
}

/// Report of a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// How it ended.
    pub status: SolveStatus,
    /// The friction law solved (Coulomb with μ = 0 on every contact pair is solved, and reported, as frictionless).
    pub friction: FrictionLaw,
    /// The Coulomb coefficient μ (`None` unless the law is Coulomb): the law's, the first pair's (a further pair's
    /// own in [`crate::PairResult::mu`]).
    pub mu: Option<f64>,
    /// Iterations of the Coulomb method that answered: fixed-point iterations (one QP each) or Newton steps
    /// (one dense LU each); 0 for frictionless and Tresca.
    pub iterations: usize,
    /// After each iteration: the relative change of λ_n (fixed point) or the relative merit `‖C‖ / ‖λ_n‖`
    /// of each point Newton evaluated (before each step, at each restart, and the point it ended on: `iterations`
    /// + restarts + 1 entries, the restarts' QPs booked in `qp_methods` after the first).
    pub residual_history: Vec<f64>,
    /// The Coulomb method that answered ([`CoulombMethod::FixedPoint`] or [`CoulombMethod::Newton`]); `None`
    /// for frictionless and Tresca.
    pub coulomb_method: Option<CoulombMethod>,
    /// True when [`CoulombMethod::Auto`] tried Newton, which did not converge, and the fixed point answered.
    pub coulomb_fallback: bool,
    /// Iterations of each QP: interior-point iterations (clarabel) or steps (active set), including a
    /// failed active-set attempt before clarabel.
    pub qp_iterations: Vec<u32>,
    /// Factorizations among the active-set steps of each QP (see [`crate::QpOutcome::factorizations`]):
    /// the other steps updated the dense factor or bordered the sparse one. 0 for a clarabel answer.
    pub qp_factorizations: Vec<u32>,
    /// The method that answered each QP ([`QpMethod::Clarabel`] or [`QpMethod::ActiveSet`]).
    pub qp_methods: Vec<QpMethod>,
    /// How many QPs the first method tried did not answer, so that the other one did (see
    /// [`crate::QpOutcome::fallback`]).
    pub qp_fallbacks: usize,
    /// How many of those QPs met only [`crate::qp::FALLBACK_TOL`] (1e-10), not `qp.tol`: their λ is
    /// determined to about `FALLBACK_TOL · κ(H)` instead of `qp.tol · κ(H)`.
    pub qp_inaccurate: usize,
    /// γ0 used.
    pub gamma0: f64,
    /// Admissible bound on γ0.
    pub gamma0_bound: f64,
    /// True when the factorization of `K − G` was reused from an earlier solve of the same problem with
    /// the same γ0 (the `factorization` timing is then that earlier one).
    pub reused_factorization: bool,
    /// How H was formed: [`Condensation::Columns`] or [`Condensation::Schur`].
    pub condensation: Condensation,
    /// Timings per phase.
    pub timings: Timings,
    /// The a posteriori error estimate of the answer (see [`crate::results::ErrorEstimate`]).
    pub estimate: ErrorEstimate,
    /// The check of a converged Coulomb answer by the other method, where `coulomb_check` asked for it.
    pub coulomb_check: Option<CoulombCheck>,
}

/// One scalar of a [`Report`], for bindings and files.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scalar {
    /// Not applicable (the iteration of an interruption that did not happen).
    Missing,
    /// A flag.
    Bool(bool),
    /// A count or an index.
    Count(usize),
    /// A number.
    Float(f64),
    /// A name.
    Name(&'static str),
}

impl Report {
    /// The report's scalars by name, as the Python binding and summary files name them.
    pub fn scalars(&self) -> [(&'static str, Scalar); 17] {
        use crate::choice::Choice;
        use Scalar::{Bool, Count, Float, Missing, Name};
        let (interrupted, failed, reason) = match self.status {
            SolveStatus::Interrupted { iteration } => (Count(iteration), Missing, Missing),
            SolveStatus::QpFailed { iteration, reason } => (Missing, Count(iteration), Name(reason)),
            _ => (Missing, Missing, Missing),
        };
        let check = self.coulomb_check;
        let float = |f: fn(&CoulombCheck) -> f64| check.as_ref().map_or(Missing, |c| Float(f(c)));
        [
            ("status", Name(self.status.name())),
            ("interrupted_iteration", interrupted),
            ("failed_iteration", failed),
            ("failure_reason", reason),
            ("iterations", Count(self.iterations)),
            ("coulomb_method", self.coulomb_method.map_or(Missing, |m| Name(m.as_str()))),
            ("coulomb_fallback", Bool(self.coulomb_fallback)),
            ("qp_fallbacks", Count(self.qp_fallbacks)),
            ("condensation", Name(self.condensation.as_str())),
            ("qp_inaccurate", Count(self.qp_inaccurate)),
            ("gamma0", Float(self.gamma0)),
            ("gamma0_bound", Float(self.gamma0_bound)),
            ("reused_factorization", Bool(self.reused_factorization)),
            ("coulomb_check", check.map_or(Missing, |c| Name(c.agreement.as_str()))),
            ("check_status", check.and_then(|c| c.status).map_or(Missing, |s| Name(s.name()))),
            ("check_distance", float(|c| c.distance)),
            ("check_allowed", float(|c| c.allowed)),
        ]
    }
}
