//! The solve driver: frictionless and Tresca problems are one QP each; Coulomb (3.1) is the fixed point
//! of `Φ_H : g ↦ λ_Hn(g)` (Definition 1 of the paper), each evaluation a Tresca QP P(g) whose matrix
//! does not change (only the bounds μ g do). The displacement is recovered at the end with one solve.

use std::ops::ControlFlow;
use std::time::Instant;

use crate::error::{Error, Num, Result};
use crate::friction::Friction;
use crate::loading::Loading;
use crate::problem::{Condensed, Problem};
use crate::qp::{QpOutcome, QpStatus};
use crate::settings::{QpMethod, SolverSettings};
use crate::solution::{Report, Solution, SolveStatus, Timings};
use crate::working_set::WorkingSetQp;

/// Fixed-point iterations without a new smallest change after which the fixed point is declared
/// stagnated: a contraction, however slow, makes a new minimum every iteration.
pub const STAGNATION_WINDOW: usize = 10;

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
    fn qp(factor: &crate::Factor, iteration: usize, change: f64, out: &QpOutcome) -> Self {
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

/// What the QP phase produced: multipliers (2q), the tangential bound used, status, history.
struct QpPhase {
    lambda: Vec<f64>,
    bound: Vec<f64>,
    status: SolveStatus,
    iterations: usize,
    history: Vec<f64>,
    qp_iterations: Vec<u32>,
    /// The active-set method's factorizations in each QP.
    qp_factorizations: Vec<u32>,
    /// The method that answered each QP.
    qp_methods: Vec<QpMethod>,
    /// QPs the active-set method could not certify (clarabel answered them).
    qp_fallbacks: usize,
    /// QPs that met only [`crate::qp::FALLBACK_TOL`], not `qp.tol`.
    qp_inaccurate: usize,
}

impl QpPhase {
    /// Counts a QP's interior-point iterations, time and accuracy.
    fn book(&mut self, out: &QpOutcome) {
        self.qp_iterations.push(out.iterations);
        self.qp_factorizations.push(out.factorizations);
        self.qp_methods.push(out.method);
        self.qp_fallbacks += usize::from(out.fallback);
        self.qp_inaccurate += usize::from(out.status == QpStatus::Inaccurate);
    }

    /// Books a QP solved outside the fixed point (iteration 0): progress, counts, status.
    fn record_single_qp(
        &mut self,
        factor: &crate::Factor,
        out: &QpOutcome,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) {
        let flow = notify(Progress::qp(factor, 0, f64::NAN, out));
        if flow.is_break() {
            self.status = SolveStatus::Interrupted { iteration: 0 };
        }
        self.book(out);
        if let Some(s) = qp_failed(0, out.status) {
            self.status = s;
        }
    }
}

fn qp_failed(iteration: usize, s: QpStatus) -> Option<SolveStatus> {
    match s {
        QpStatus::Solved | QpStatus::Inaccurate => None,
        QpStatus::Failed(reason) => Some(SolveStatus::QpFailed { iteration, reason }),
    }
}

impl Condensed<'_> {
    /// Solves the contact problem with the given friction law on this condensed system.
    ///
    /// # Errors
    /// Bad friction or settings ([`crate::Error::BadSetting`], [`crate::Error::BadThreshold`]); QP set-up
    /// errors. A QP that fails to converge or a fixed point that does not converge is *not* an error: see
    /// [`Solution::report`].
    pub fn solve(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        settings.validate()?;
        friction.validate(self.q())?;
        self.solve_validated(friction, settings, observer)
    }

    fn solve_validated(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let loading = Loading::of_problem(self.problem(), self.factor());
        self.solve_loading(friction, settings, &loading, None, observer)
    }

    /// Solves the load case `loading` (validated friction and settings). `start` (2q), if given, is the
    /// answer of a nearby load case (the previous step of a history): the QPs start from it, and a
    /// Coulomb fixed point starts from its λ_n instead of the frictionless one.
    pub(crate) fn solve_loading(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        loading: &Loading,
        start: Option<&[f64]>,
        mut observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let (problem, factor) = (self.problem(), self.factor());
        let friction = friction.normalized();
        let clock = Instant::now();
        let condensation_before = factor.condensation_seconds();
        let q = self.q();
        let mut notify = |p: Progress| {
            match p.phase {
                Phase::Condensation => {
                    log::info!("condensed onto {} multipliers in {} s", 2 * q, Num(p.condensation_seconds))
                }
                _ => log::debug!(
                    "iteration {} change {} qp {} its {} s",
                    p.iteration,
                    Num(p.change),
                    p.qp_iterations,
                    Num(p.qp_seconds)
                ),
            }
            match observer.as_mut() {
                Some(o) => o(&p),
                None => ControlFlow::Continue(()),
            }
        };
        let mut phase = QpPhase {
            lambda: vec![0.0; 2 * q],
            bound: vec![0.0; q],
            status: SolveStatus::Converged,
            iterations: 0,
            history: Vec::new(),
            qp_iterations: Vec::new(),
            qp_factorizations: Vec::new(),
            qp_methods: Vec::new(),
            qp_fallbacks: 0,
            qp_inaccurate: 0,
        };
        let budget = settings.memory_budget;
        let condensed = Progress {
            phase: Phase::Condensation,
            condensation_seconds: factor.factorization_seconds + factor.condensation_seconds(),
            iteration: 0,
            change: f64::NAN,
            qp_iterations: 0,
            qp_seconds: 0.0,
        };
        let stopped = notify(condensed).is_break();
        match (&friction, start) {
            _ if stopped => phase.status = SolveStatus::Interrupted { iteration: 0 },
            (Friction::Coulomb { .. }, Some(start)) => {
                // A warm start: the fixed point starts from the nearby answer.
                phase.lambda.copy_from_slice(start);
            }
            (Friction::Frictionless | Friction::Coulomb { .. }, _) => {
                // Coulomb starts from the frictionless λ_n.
                let out = WorkingSetQp::new(factor, loading, None, &settings.qp, budget, start)?.solve()?;
                phase.lambda[..q].copy_from_slice(&out.nu);
                phase.record_single_qp(factor, &out, &mut notify);
            }
            (Friction::Tresca(_), _) => {
                phase.bound = friction.tresca_bounds(q);
                let out =
                    WorkingSetQp::new(factor, loading, Some(&phase.bound), &settings.qp, budget, start)?.solve()?;
                phase.lambda.copy_from_slice(&out.nu);
                phase.record_single_qp(factor, &out, &mut notify);
            }
        }
        if let (Friction::Coulomb { mu }, SolveStatus::Converged) = (&friction, phase.status) {
            // (not after an interrupted or failed initial QP)
            self.fixed_point(*mu, settings, loading, &mut phase, &mut notify)?;
        }
        // Columns of H computed on demand during the QPs count as condensation, not QP time.
        let condensation_during = factor.condensation_seconds() - condensation_before;
        let qp_total = clock.elapsed().as_secs_f64() - condensation_during;
        let clock = Instant::now();
        let u = factor.displacement(&loading.f_free, &phase.lambda)?;
        let recovery = clock.elapsed().as_secs_f64();
        let timings = Timings {
            assembly: problem.timings.assembly,
            contact_matrices: problem.timings.contact_matrices,
            factorization: factor.factorization_seconds,
            condensation: factor.condensation_seconds(),
            qp: qp_total,
            recovery,
        };
        let mu = friction.mu();
        let threshold = match mu {
            Some(mu) => phase.lambda[..q].iter().map(|l| mu * l.max(0.0)).collect(),
            None => phase.bound,
        };
        let report = Report {
            status: phase.status,
            friction: friction.law(),
            mu,
            iterations: phase.iterations,
            residual_history: phase.history,
            qp_iterations: phase.qp_iterations,
            qp_factorizations: phase.qp_factorizations,
            qp_methods: phase.qp_methods,
            qp_fallbacks: phase.qp_fallbacks,
            qp_inaccurate: phase.qp_inaccurate,
            gamma0: factor.gamma0,
            gamma0_bound: problem.gamma0_bound.value,
            reused_factorization: self.reused_factorization(),
            condensation: factor.condensation,
            timings,
        };
        let mut solution = Solution::new(self, loading, &u, phase.lambda, threshold, settings.qp.tol, report);
        // The equation of (3.1) is solved directly: a residual that lost half of the digits is a singular
        // stiffness (a mechanism), not a numerical outcome of the contact solve.
        let residual = solution.kkt.equilibrium;
        if residual > f64::EPSILON.sqrt() {
            return Err(Error::SingularStiffness { residual });
        }
        if solution.report.status == SolveStatus::Converged {
            let bound = Solution::accuracy_bound(settings.qp.tol, solution.report.qp_inaccurate, settings.fp.tol);
            if !solution.all_finite() {
                solution.report.status = SolveStatus::NonFinite;
            } else if solution.kkt.max() > bound {
                log::warn!(
                    "KKT residual {} above what the tolerances justify ({})",
                    Num(solution.kkt.max()),
                    Num(bound)
                );
                solution.report.status = SolveStatus::Inaccurate;
            }
        }
        Ok(solution)
    }

    fn fixed_point(
        &self,
        mu: f64,
        settings: &SolverSettings,
        loading: &Loading,
        phase: &mut QpPhase,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<()> {
        let q = self.q();
        let fp = settings.fp;
        let mut g: Vec<f64> = phase.lambda[..q].to_vec();
        let bound: Vec<f64> = g.iter().map(|v| mu * v.max(0.0)).collect();
        // Warm start: the frictionless λ_n with λ_t = 0.
        let mut qp = WorkingSetQp::new(
            self.factor(),
            loading,
            Some(&bound),
            &settings.qp,
            settings.memory_budget,
            Some(&phase.lambda),
        )?;
        phase.status = SolveStatus::MaxIterations;
        let (mut best, mut since_best) = (f64::INFINITY, 0);
        for it in 1..=fp.max_iter {
            let out = qp.solve()?;
            phase.book(&out);
            phase.iterations = it;
            if let Some(s) = qp_failed(it, out.status) {
                phase.status = s;
                break;
            }
            let lam_n = &out.nu[..q];
            let max_diff = lam_n.iter().zip(&g).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            let diff: f64 = lam_n.iter().zip(&g).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
            let norm: f64 = lam_n.iter().map(|a| a * a).sum::<f64>().sqrt();
            let change = if norm > 0.0 { diff / norm } else { diff };
            phase.history.push(change);
            let flow = notify(Progress::qp(self.factor(), it, change, &out));
            phase.bound = g.iter().map(|v| mu * v.max(0.0)).collect();
            phase.lambda = out.nu;
            // Converged when the relative change is small, or when the change is at the QP's own noise
            // level (tol × the natural size of λ): e.g. λ ≡ 0 without contact, where a relative change
            // compares round-off with round-off.
            let noise = settings.qp.tol * self.factor().lambda_scale(&loading.c);
            if change <= fp.tol || max_diff <= noise {
                phase.status = SolveStatus::Converged;
                break;
            }
            if flow.is_break() {
                phase.status = SolveStatus::Interrupted { iteration: it };
                break;
            }
            // A converging fixed point keeps making new minima of the change; one that cycles, or that
            // has reached the accuracy to which the QP determines λ, does not.
            if change < best {
                (best, since_best) = (change, 0);
            } else {
                since_best += 1;
                if since_best >= STAGNATION_WINDOW {
                    phase.status = SolveStatus::Stagnated;
                    break;
                }
            }
            let w = fp.relaxation;
            for (gj, lj) in g.iter_mut().zip(&phase.lambda[..q]) {
                *gj = ((1.0 - w) * *gj + w * lj).max(0.0);
            }
            let bound: Vec<f64> = g.iter().map(|v| mu * v).collect();
            qp.set_bounds(&bound)?;
        }
        Ok(())
    }
}

impl Problem {
    /// Condenses with `settings.stabilization` (or reuses the factorization of the previous solve with
    /// the same γ0) and solves: the one-call entry point.
    ///
    /// # Errors
    /// As [`Problem::condense`] and [`Condensed::solve`].
    pub fn solve(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        settings.validate()?;
        friction.validate(self.n_multipliers())?;
        self.condense_with(settings.stabilization, settings.condensation, settings.memory_budget)?
            .solve_validated(friction, settings, observer)
    }
}
