//! The driver of one solve: the initial QP (frictionless or Tresca), the Coulomb fixed point
//! ([`super::fixed_point`]) when asked, the displacement by one more solve, the report and the status a
//! converged answer must earn (finite fields, KKT residuals within what the tolerances justify).

use std::ops::ControlFlow;
use std::time::Instant;

use crate::error::{Error, Num, Result};
use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::qp::working_set::ContactQp;
use crate::qp::{QpOutcome, QpStatus};
use crate::results::{CoulombCheck, ErrorEstimate, Report, Solution, SolveStatus, Timings};
use crate::settings::friction::Friction;
use crate::settings::{Condensation, CoulombMethod, QpMethod, SolverSettings};
use crate::solve::fixed_point::settled;
use crate::solve::progress::{Observer, Phase, Progress};

/// What the QP phase produced: multipliers (2q), the tangential bound used, status, history.
pub(super) struct QpPhase {
    pub(super) lambda: Vec<f64>,
    pub(super) bound: Vec<f64>,
    pub(super) status: SolveStatus,
    pub(super) iterations: usize,
    pub(super) history: Vec<f64>,
    pub(super) qp_iterations: Vec<u32>,
    /// The active-set method's factorizations in each QP.
    pub(super) qp_factorizations: Vec<u32>,
    /// The method that answered each QP.
    pub(super) qp_methods: Vec<QpMethod>,
    /// QPs the active-set method could not certify (clarabel answered them).
    pub(super) qp_fallbacks: usize,
    /// QPs that met only [`crate::qp::FALLBACK_TOL`], not `qp.tol`.
    pub(super) qp_inaccurate: usize,
    /// The rigid motion of the bodies held only by the contact, of the last QP (empty without them).
    pub(super) alpha: Vec<f64>,
    /// Whether `lambda` is a nearby load case's Coulomb answer (the previous step of a history) rather than
    /// the frictionless start.
    pub(super) neighbour: bool,
}

impl QpPhase {
    /// Counts a QP's interior-point iterations, time and accuracy.
    pub(super) fn book(&mut self, out: &QpOutcome) {
        self.qp_iterations.push(out.iterations);
        self.qp_factorizations.push(out.factorizations);
        self.qp_methods.push(out.method);
        self.qp_fallbacks += usize::from(out.fallback);
        self.qp_inaccurate += usize::from(out.status == QpStatus::Inaccurate);
        self.alpha.clone_from(&out.alpha);
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

impl Condensed<'_> {
    /// The Γ_C QP of `loading` with the tangential `bounds` (none: frictionless), started from `start`, on this
    /// condensation's path (the saddle-point system or columns of H): the one constructor of every QP a solve
    /// makes (the first one, the fixed point's, Newton's restarts).
    ///
    /// # Errors
    /// [`Error::BadThreshold`] for bad bounds.
    pub(super) fn contact_qp<'s>(
        &'s self,
        loading: &'s LoadCase,
        bounds: Option<&[f64]>,
        settings: &SolverSettings,
        start: Option<&[f64]>,
    ) -> Result<ContactQp<'s>> {
        let qp = ContactQp::new(self.factor(), loading.qp_data(), bounds, &settings.qp, settings.memory_budget, start)?;
        Ok(qp.with_sparse(self.sparse_qps()))
    }

    /// The Coulomb problem from `phase.lambda` by `method` (the fixed point or Newton).
    ///
    /// # Errors
    /// QP errors of the fixed point; [`Error::MemoryBudget`] from Newton.
    fn coulomb(
        &self,
        mu: &[f64],
        method: CoulombMethod,
        settings: &SolverSettings,
        loading: &LoadCase,
        phase: &mut QpPhase,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<()> {
        if method == CoulombMethod::Newton {
            self.newton(mu, settings, loading, phase, notify)
        } else {
            self.fixed_point(mu, settings, loading, phase, notify)
        }
    }
}

pub(super) fn qp_failed(iteration: usize, s: QpStatus) -> Option<SolveStatus> {
    match s {
        QpStatus::Solved | QpStatus::Inaccurate => None,
        QpStatus::Failed(reason) => Some(SolveStatus::QpFailed { iteration, reason }),
    }
}

impl Condensed<'_> {
    pub(super) fn solve_validated(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let loading = LoadCase::of_problem(self.problem(), self.factor());
        self.solve_loading(friction, settings, &loading, None, observer)
    }

    /// Solves the load case `loading` (validated friction and settings). `start` (2q), if given, is the
    /// answer of a nearby load case (the previous step of a history): the QPs start from it, and a
    /// Coulomb fixed point starts from its λ_n instead of the frictionless one.
    ///
    /// A Coulomb problem is solved by the method `settings.coulomb` names. [`CoulombMethod::Auto`] takes the fixed
    /// point where the QPs solve the sparse saddle-point system (H not formed: Newton would form the columns of H
    /// the contact zone needs, 5–11 times the fixed point's time on the graded meshes of 55k–109k unknowns in
    /// study 4), and elsewhere Newton and, where its answer is not `converged`
    /// once checked (its KKT residuals and fields, below) or it exceeds the memory budget, the fixed point
    /// solving the load case again. With `settings.coulomb_check`, a converged Coulomb answer is checked by the
    /// other method ([`super::check`]).
    pub(crate) fn solve_loading(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        loading: &LoadCase,
        start: Option<&[f64]>,
        mut observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let method = match settings.coulomb {
            CoulombMethod::Auto if self.sparse_qps() => CoulombMethod::FixedPoint,
            CoulombMethod::FixedPoint => CoulombMethod::FixedPoint,
            CoulombMethod::Newton | CoulombMethod::Auto => CoulombMethod::Newton,
        };
        // A reborrow of the observer for the first attempt (the `dyn`'s lifetime shortened with it).
        #[allow(clippy::option_as_ref_deref)]
        let again = observer.as_mut().map(|o| -> Observer<'_> { &mut **o });
        let first = self.solve_loading_by(friction, method, settings, loading, start, again);
        let auto = settings.coulomb == CoulombMethod::Auto;
        let fell = match &first {
            Ok(s) => {
                s.report.coulomb_method == Some(CoulombMethod::Newton)
                    && !matches!(s.report.status, SolveStatus::Converged | SolveStatus::Interrupted { .. })
            }
            Err(Error::MemoryBudget { what, .. }) => {
                method == CoulombMethod::Newton && what.starts_with("the Newton method")
            }
            Err(_) => false,
        };
        // Where Newton did not converge and the fixed point answers, how Newton ended (`None`: refused).
        let newton_failed = (auto && fell).then(|| first.as_ref().ok().map(|s| s.report.status));
        let mut solution = if auto && fell {
            match &first {
                Ok(s) => log::info!(
                    "newton ended {} after {} steps: the fixed point solves the problem from the same start",
                    s.report.status,
                    s.report.iterations
                ),
                Err(e) => log::info!("newton: {e}: the fixed point solves the problem"),
            }
            let mut solution =
                self.solve_loading_by(friction, CoulombMethod::FixedPoint, settings, loading, start, observer)?;
            solution.report.coulomb_fallback = true;
            solution
        } else {
            first?
        };
        if let (true, Some(_), SolveStatus::Converged) =
            (settings.coulomb_check, solution.report.mu, solution.report.status)
        {
            let clock = Instant::now();
            let (_, mu) = self.problem().friction_as_solved(friction)?;
            solution.report.coulomb_check = Some(match newton_failed {
                // Newton did not converge from this start: it is not run again.
                Some(status) => CoulombCheck::undecided(CoulombMethod::Newton, status),
                None => self.check_coulomb((friction, &mu), settings, loading, start, &solution),
            });
            solution.report.timings.qp += clock.elapsed().as_secs_f64();
        }
        Ok(solution)
    }

    /// [`Condensed::solve_loading`] with the Coulomb method `method` (the fixed point or Newton).
    pub(super) fn solve_loading_by(
        &self,
        friction: &Friction,
        method: CoulombMethod,
        settings: &SolverSettings,
        loading: &LoadCase,
        start: Option<&[f64]>,
        mut observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let (problem, factor) = (self.problem(), self.factor());
        // Coulomb's μ at each multiplier dof (each pair's own, `Problem::friction_as_solved`).
        let (friction, mu) = problem.friction_as_solved(friction)?;
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
            alpha: vec![0.0; loading.rigid.load.len()],
            neighbour: false,
        };
        // The tangential rows hold a motion where the dof's pair has friction (a pair's own μ = 0 has none).
        let frictional = |j: usize| match friction {
            Friction::Frictionless => false,
            Friction::Coulomb { .. } => mu[j] > 0.0,
            Friction::Tresca(_) => true,
        };
        problem.check_held_by_contact(&loading.rigid, &frictional)?;
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
                phase.neighbour = true;
            }
            (Friction::Frictionless | Friction::Coulomb { .. }, _) => {
                // Coulomb starts from the frictionless λ_n.
                let out = self.contact_qp(loading, None, settings, start)?.solve()?;
                phase.lambda[..q].copy_from_slice(&out.nu);
                phase.record_single_qp(factor, &out, &mut notify);
            }
            (Friction::Tresca(_), _) => {
                phase.bound = friction.tresca_bounds(q);
                let out = self.contact_qp(loading, Some(&phase.bound), settings, start)?.solve()?;
                phase.lambda.copy_from_slice(&out.nu);
                phase.record_single_qp(factor, &out, &mut notify);
            }
        }
        let coulomb_method = matches!(friction, Friction::Coulomb { .. }).then_some(method);
        if let (Friction::Coulomb { .. }, SolveStatus::Converged) = (&friction, phase.status) {
            // (not after an interrupted or failed initial QP)
            self.coulomb(&mu, method, settings, loading, &mut phase, &mut notify)?;
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
            fields: 0.0,
        };
        let threshold = match friction {
            Friction::Coulomb { .. } => phase.lambda[..q].iter().zip(&mu).map(|(l, m)| m * l.max(0.0)).collect(),
            _ => phase.bound,
        };
        let report = Report {
            status: phase.status,
            friction: problem.friction_law_as_solved(&friction),
            mu: if let Friction::Coulomb { mu } = friction { Some(mu) } else { None },
            iterations: phase.iterations,
            residual_history: phase.history,
            coulomb_method,
            coulomb_fallback: false,
            qp_iterations: phase.qp_iterations,
            qp_factorizations: phase.qp_factorizations,
            qp_methods: phase.qp_methods,
            qp_fallbacks: phase.qp_fallbacks,
            qp_inaccurate: phase.qp_inaccurate,
            gamma0: factor.gamma0,
            gamma0_bound: problem.gamma0_bound.value,
            reused_factorization: self.reused_factorization(),
            condensation: if factor.condensation == Condensation::Saddle && !self.sparse_qps() {
                Condensation::Columns
            } else {
                factor.condensation
            },
            timings,
            estimate: ErrorEstimate::default(),
            coulomb_check: None,
        };
        let clock = Instant::now();
        // A body held only by the contact moves rigidly by α besides u (`problem/floating.rs`); the contact
        // forces must determine it. A fixed point that stagnated or ran out of iterations on such a body is
        // checked too: where nothing presses the body against the contact (a history unloading it), the
        // undetermined position is why it did not converge, and that is the answer to give (defect D31).
        // (Newton's last iterate of a solve that did not converge need not be near the answer: it proves nothing.)
        let undecided = matches!(phase.status, SolveStatus::Stagnated | SolveStatus::MaxIterations)
            && coulomb_method != Some(CoulombMethod::Newton);
        if phase.status == SolveStatus::Converged || (undecided && !loading.rigid.load.is_empty()) {
            let bound = (!matches!(friction, Friction::Frictionless)).then_some(threshold.as_slice());
            // The scale of λ: the answer's and the linear term's; for a fixed point that did not converge, also
            // the nearby answer's it started from (a history step that unloads the body has λ ≈ 0 and c ≈ 0:
            // the previous step sets the scale).
            let earlier = if undecided { start.unwrap_or_default() } else { &[] };
            let largest = phase.lambda.iter().chain(earlier).fold(0.0_f64, |m, l| m.max(l.abs()));
            let noise = settings.qp.tol * factor.lambda_scale(&loading.c).max(largest);
            problem.check_rigid_motion_determined(&loading.rigid, &phase.lambda, bound, noise)?;
        }
        let moved;
        let loading = if phase.alpha.is_empty() {
            loading
        } else {
            moved = loading.with_rigid_motion(problem, &phase.alpha);
            &moved
        };
        let mut solution = Solution::new(self, loading, &u, phase.lambda, threshold, settings.qp.tol, report);
        if let Friction::Coulomb { mu: law } = friction {
            solution.pairs.iter_mut().zip(problem.pairs()).for_each(|(r, p)| r.mu = Some(p.mu.unwrap_or(law)));
        }
        solution.report.timings.fields = clock.elapsed().as_secs_f64();
        // The equation of (3.1) is solved directly: a residual that lost half of the digits is a singular
        // stiffness (a mechanism), not a numerical outcome of the contact solve.
        let residual = solution.kkt.equilibrium;
        if residual > f64::EPSILON.sqrt() {
            return Err(Error::SingularStiffness { residual });
        }
        // A fixed point that stagnated within what its QPs resolve of λ may still end on an answer
        // (`fixed_point::settled`; the fixed point's only: Newton's merit at the point it hands back is already its
        // last entry). A fixed point that cycles makes larger changes, and one stopped by its cap
        // (`max_iterations`) was still progressing: both are reported as they ended.
        // The fixed point's own QPs (the last `iterations`; not a frictionless start, whose noise it does not carry).
        let report = &solution.report;
        let own = &report.qp_methods[report.qp_methods.len().saturating_sub(report.iterations)..];
        let clarabel = own.contains(&QpMethod::Clarabel);
        let settled = (report.status == SolveStatus::Stagnated && method == CoulombMethod::FixedPoint)
            .then(|| settled(&report.residual_history, report.qp_inaccurate, clarabel, solution.kkt.max(), settings))
            .flatten();
        if let Some((smallest, met)) = settled.filter(|_| solution.all_finite()) {
            log::info!(
                "the fixed point stagnated after {} iterations (smallest change {}), its last iterate meeting \
                 Coulomb's law to {} ({}): converged",
                report.iterations,
                Num(smallest),
                Num(solution.kkt.max()),
                Num(met)
            );
            solution.report.status = SolveStatus::Converged;
        }
        let bound = Solution::accuracy_bound(settings.qp.tol, solution.report.qp_inaccurate, settings.fp.tol);
        if solution.report.status == SolveStatus::Converged {
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
}
