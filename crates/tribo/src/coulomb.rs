//! Friction laws and the solve drivers: frictionless and Tresca problems are one QP each; Coulomb (3.1)
//! is the fixed point of `Φ_H : g ↦ λ_Hn(g)` (Definition 1), each evaluation a Tresca QP P(g) whose matrix
//! does not change (only the bounds μ g do).

use std::ops::ControlFlow;
use std::time::Instant;

use crate::condensation::Condensed;
use crate::error::{check_setting, Error, Result};
use crate::problem::Problem;
use crate::solution::{Solution, SolveStatus, Timings};
use crate::stabilization::Stabilization;
use crate::tresca::{QpOutcome, QpSettings, QpStatus};
use crate::working_set::WorkingSetQp;

/// The friction model.
#[derive(Debug, Clone, PartialEq)]
pub enum Friction {
    /// μ = 0: no tangential multiplier, one QP.
    Frictionless,
    /// Tresca: a given threshold s ≥ 0 with |λ_t| ≤ s, one QP.
    Tresca(Threshold),
    /// Coulomb with friction coefficient μ ≥ 0 (μ = 0 is solved as frictionless).
    Coulomb {
        /// Friction coefficient.
        mu: f64,
    },
}

/// A Tresca threshold.
#[derive(Debug, Clone, PartialEq)]
pub enum Threshold {
    /// The same threshold at every multiplier dof.
    Uniform(f64),
    /// One threshold per multiplier dof (dof values of a function of W_H).
    PerDof(Vec<f64>),
}

impl Friction {
    /// Checks μ ≥ 0 and thresholds ≥ 0 (finite).
    ///
    /// # Errors
    /// [`Error::BadSetting`] for μ, [`Error::BadThreshold`] for thresholds.
    pub fn validate(&self) -> Result<()> {
        match self {
            Self::Frictionless => Ok(()),
            Self::Coulomb { mu } => check_setting("mu", *mu, *mu >= 0.0, "the friction coefficient must be ≥ 0"),
            Self::Tresca(Threshold::Uniform(s)) => {
                if s.is_finite() && *s >= 0.0 {
                    Ok(())
                } else {
                    Err(Error::BadThreshold { what: format!("the threshold must be finite and ≥ 0, got {s}") })
                }
            }
            Self::Tresca(Threshold::PerDof(v)) => match v.iter().position(|s| !(s.is_finite() && *s >= 0.0)) {
                Some(j) => Err(Error::BadThreshold {
                    what: format!("value {j} is {}; thresholds must be finite and ≥ 0", v[j]),
                }),
                None => Ok(()),
            },
        }
    }
}

/// Settings of the Coulomb fixed point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedPointSettings {
    /// Stop when `‖λ_n^{k+1} − λ_n^k‖₂ ≤ tol_change_rel ‖λ_n^{k+1}‖₂` (or when the change is below the
    /// QP's noise level, `qp.tol` times [`Condensed::lambda_scale`]). Default 1e-8.
    pub tol_change_rel: f64,
    /// Iteration cap. Default 100.
    pub max_iter: usize,
    /// Relaxation ω ∈ (0, 1]: `g ← (1 − ω) g + ω Φ_H(g)`. Default 1 (plain fixed point).
    pub relaxation: f64,
}

impl Default for FixedPointSettings {
    fn default() -> Self {
        Self { tol_change_rel: 1e-8, max_iter: 100, relaxation: 1.0 }
    }
}

impl FixedPointSettings {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`Error::BadSetting`] naming the setting.
    pub fn validate(&self) -> Result<()> {
        let t = self.tol_change_rel;
        check_setting("fixed_point.tol_change_rel", t, t > 0.0 && t < 1.0, "must lie in (0, 1)")?;
        check_setting("fixed_point.max_iter", self.max_iter as f64, self.max_iter >= 1, "must be at least 1")?;
        let w = self.relaxation;
        check_setting("fixed_point.relaxation", w, w > 0.0 && w <= 1.0, "must lie in (0, 1]")
    }
}

/// Fixed-point iterations without a new smallest change after which the fixed point is declared
/// stagnated: a contraction, however slow, makes a new minimum every iteration.
pub const STAGNATION_WINDOW: usize = 10;

/// All solver settings.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverSettings {
    /// γ0. Default: half of the admissible bound.
    pub stabilization: Stabilization,
    /// QP settings.
    pub qp: QpSettings,
    /// Fixed-point settings.
    pub fixed_point: FixedPointSettings,
}

impl SolverSettings {
    /// Checks every setting (γ0 is checked against its bound when the problem is condensed).
    ///
    /// # Errors
    /// [`Error::BadSetting`].
    pub fn validate(&self) -> Result<()> {
        self.qp.validate()?;
        self.fixed_point.validate()
    }
}

/// Progress of a solve, reported after every QP.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Fixed-point iteration (0 for the initial frictionless solve).
    pub iteration: usize,
    /// Relative change of λ_n (NaN for the initial solve).
    pub change: f64,
    /// Interior-point iterations of this QP.
    pub qp_iterations: u32,
    /// Wall time of this QP in seconds.
    pub qp_seconds: f64,
}

/// A progress observer: called after every QP. Returning `ControlFlow::Break(())` stops the solve,
/// which then ends with [`SolveStatus::Interrupted`] and its last iterate.
pub type Observer<'a> = &'a mut dyn FnMut(&Progress) -> ControlFlow<()>;

/// What the QP phase produced: multipliers (2q), the tangential bound used, status, history.
pub(crate) struct QpPhase {
    pub lambda: Vec<f64>,
    pub bound: Vec<f64>,
    pub mu: Option<f64>,
    pub status: SolveStatus,
    pub iterations: usize,
    pub history: Vec<f64>,
    pub qp_iterations: Vec<u32>,
    /// QPs that met only [`crate::tresca::FALLBACK_TOL`], not `qp.tol`.
    pub qp_inaccurate: usize,
    pub qp_seconds: f64,
}

impl QpPhase {
    /// Counts a QP's interior-point iterations, time and accuracy.
    fn book(&mut self, out: &QpOutcome) {
        self.qp_iterations.push(out.iterations);
        self.qp_seconds += out.seconds;
        self.qp_inaccurate += usize::from(out.status == QpStatus::Inaccurate);
    }

    /// Books a QP solved outside the fixed point (iteration 0): progress, counts, status.
    fn record_single_qp(&mut self, out: &QpOutcome, notify: &mut dyn FnMut(Progress) -> ControlFlow<()>) {
        let flow =
            notify(Progress { iteration: 0, change: f64::NAN, qp_iterations: out.iterations, qp_seconds: out.seconds });
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

impl Condensed {
    /// Solves the contact problem with the given friction law on this condensed system.
    ///
    /// # Errors
    /// Bad friction or settings ([`Error::BadSetting`], [`Error::BadThreshold`]); QP set-up errors.
    /// A QP that fails to converge or a fixed point that does not converge is *not* an error: see
    /// [`Solution::report`].
    pub fn solve(
        &self,
        problem: &Problem,
        friction: &Friction,
        settings: &SolverSettings,
        mut observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        friction.validate()?;
        settings.validate()?;
        let clock = Instant::now();
        let condensation_before = self.condensation_seconds();
        let q = self.q();
        let mut notify = |p: Progress| {
            log::debug!(
                "iteration {} change {:e} qp {} its {:.3} s",
                p.iteration,
                p.change,
                p.qp_iterations,
                p.qp_seconds
            );
            match observer.as_mut() {
                Some(o) => o(&p),
                None => ControlFlow::Continue(()),
            }
        };
        let mut phase = QpPhase {
            lambda: vec![0.0; 2 * q],
            bound: vec![0.0; q],
            mu: None,
            status: SolveStatus::Converged,
            iterations: 0,
            history: Vec::new(),
            qp_iterations: Vec::new(),
            qp_inaccurate: 0,
            qp_seconds: 0.0,
        };
        let frictionless = matches!(friction, Friction::Frictionless | Friction::Coulomb { mu: 0.0 });
        if frictionless || matches!(friction, Friction::Coulomb { .. }) {
            let out = WorkingSetQp::new(self, None, &settings.qp)?.solve()?;
            phase.lambda[..q].copy_from_slice(&out.nu);
            phase.record_single_qp(&out, &mut notify);
        }
        match friction {
            Friction::Frictionless | Friction::Coulomb { mu: 0.0 } => {}
            Friction::Tresca(th) => {
                phase.bound = match th {
                    Threshold::Uniform(s) => vec![*s; q],
                    Threshold::PerDof(v) => v.clone(),
                };
                let out = WorkingSetQp::new(self, Some(&phase.bound), &settings.qp)?.solve()?;
                phase.lambda.copy_from_slice(&out.nu);
                phase.record_single_qp(&out, &mut notify);
            }
            Friction::Coulomb { mu } if phase.status == SolveStatus::Converged => {
                // (not after an interrupted or failed initial QP)
                self.fixed_point(*mu, settings, &mut phase, &mut notify)?;
            }
            Friction::Coulomb { .. } => {}
        }
        // Columns of H computed on demand during the QPs count as condensation, not QP time.
        let condensation_during = self.condensation_seconds() - condensation_before;
        let qp_total = clock.elapsed().as_secs_f64() - condensation_during;
        let clock = Instant::now();
        let u = self.displacement(&problem.f_free, &phase.lambda);
        let recovery = clock.elapsed().as_secs_f64();
        let timings = Timings {
            assembly: problem.timings.assembly,
            contact_matrices: problem.timings.contact_matrices,
            factorization: self.timings.factorization,
            condensation: self.condensation_seconds(),
            qp: qp_total,
            recovery,
        };
        Ok(Solution::new(problem, self, u, phase, settings, timings))
    }

    fn fixed_point(
        &self,
        mu: f64,
        settings: &SolverSettings,
        phase: &mut QpPhase,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<()> {
        let q = self.q();
        let fp = settings.fixed_point;
        phase.mu = Some(mu);
        let mut g: Vec<f64> = phase.lambda[..q].to_vec();
        let bound: Vec<f64> = g.iter().map(|v| mu * v.max(0.0)).collect();
        let mut qp = WorkingSetQp::new(self, Some(&bound), &settings.qp)?;
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
            let flow =
                notify(Progress { iteration: it, change, qp_iterations: out.iterations, qp_seconds: out.seconds });
            phase.bound = g.iter().map(|v| mu * v.max(0.0)).collect();
            phase.lambda = out.nu;
            // Converged when the relative change is small, or when the change is at the QP's own noise
            // level (tol × the natural size of λ): e.g. λ ≡ 0 without contact, where a relative change
            // compares round-off with round-off.
            let noise = settings.qp.tol * self.lambda_scale();
            if change <= fp.tol_change_rel || max_diff <= noise {
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
    /// Condenses with `settings.stabilization` and solves: the one-call entry point.
    ///
    /// # Errors
    /// As [`Condensed::new`] and [`Condensed::solve`].
    pub fn solve(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        settings.validate()?;
        friction.validate()?;
        let condensed = Condensed::new(self, settings.stabilization)?;
        condensed.solve(self, friction, settings, observer)
    }
}
