//! What a long solve tells its caller while it runs: a [`Progress`] report after the condensation and
//! after every QP of a solve, a [`StepProgress`] report after every step of a history, and the observer
//! types that receive them (returning `ControlFlow::Break(())` stops the work, keeping what was done).

use std::ops::ControlFlow;

use crate::qp::QpOutcome;
use crate::results::SolveStatus;

/// The phase of a solve a [`Progress`] report comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Phase {
    /// Reported once, before the first QP: `A = K − G` is factorized (or reused) and `c` formed, and
    /// with the partial factorization all of H (the column path forms columns of H during the QPs, and
    /// [`Progress::condensation_seconds`] counts them in every later report).
    Condensation,
    /// A QP answered: the initial one (iteration 0) or a fixed-point iteration.
    Qp,
    /// A step of the semismooth Newton method ([`crate::CoulombMethod::Newton`]): `iteration` is the step,
    /// `change` the relative merit `‖C‖ / ‖λ_n‖` before it, `qp_iterations` the size of its linear system and
    /// `qp_seconds` its wall time.
    Newton,
}

/// Progress of a solve, reported once after the condensation and after every QP.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// The phase reported.
    pub phase: Phase,
    /// Wall time spent so far on the factorization of A and on forming `c` and columns of H.
    pub condensation_seconds: f64,
    /// Fixed-point iteration (0 for the initial frictionless solve).
    pub iteration: usize,
    /// Relative change of λ_n (NaN for the initial solve).
    pub change: f64,
    /// Interior-point iterations of this QP.
    pub qp_iterations: u32,
    /// Wall time of this QP in seconds.
    pub qp_seconds: f64,
}

impl Progress {
    /// A report of [`Phase::Qp`].
    pub(super) fn qp(factor: &crate::Factor, iteration: usize, change: f64, out: &QpOutcome) -> Self {
        Self {
            phase: Phase::Qp,
            condensation_seconds: factor.factorization_seconds + factor.condensation_seconds(),
            iteration,
            change,
            qp_iterations: out.iterations,
            qp_seconds: out.seconds,
        }
    }
}

/// A progress observer: called after the condensation and after every QP. Returning `ControlFlow::Break(())` stops the solve,
/// which then ends with [`SolveStatus::Interrupted`] and its last iterate.
pub type Observer<'a> = &'a mut dyn FnMut(&Progress) -> ControlFlow<()>;

/// Progress of a history, reported after every step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepProgress {
    /// The step just solved (0-based).
    pub step: usize,
    /// Number of steps asked for.
    pub steps: usize,
    /// How the step ended.
    pub status: SolveStatus,
    /// Its fixed-point iterations.
    pub iterations: usize,
    /// Its wall time in seconds.
    pub seconds: f64,
    /// Its total normal force `∫ λ_n`.
    pub normal_force: f64,
    /// Its total tangential force `∫ λ_t`.
    pub tangential_force: f64,
}

/// A history observer, called after every step. Returning `ControlFlow::Break(())` ends the history
/// after that step, with status [`SolveStatus::Interrupted`]; the steps done are kept.
pub type StepObserver<'a> = &'a mut dyn FnMut(&StepProgress) -> ControlFlow<()>;
