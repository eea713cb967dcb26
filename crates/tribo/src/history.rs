//! Quasi-static loading histories: the incremental problem, solved step by step on one factorization.
//!
//! # The incremental problem
//! The static Coulomb problem (3.1) is, in the words of the paper (§1), one step of the time-discretized
//! quasi-static problem from rest. A history is a sequence of such steps `k = 1, 2, …`: step k prescribes
//! the obstacle's approach δ_k, its tangential position s_k and a load factor α_k (the body force and the
//! tractions are `α_k f`). Friction depends on the path, so each step starts where the previous one
//! ended:
//!
//! * non-penetration uses the **total** displacement: `u_n^k ≤ g₀ − δ_k`;
//! * Coulomb's law acts on the **slip increment relative to the obstacle**,
//!   `u_t^k − u_t^{k−1} − (s_k − s_{k−1})`, with threshold `μ λ_n^k`.
//!
//! In (3.1), the pair `w_h = (u_hn − g, u_ht − s)` of the static problem (see [`crate::obstacle`]) becomes
//! `w_h^k = (u_hn^k − (g₀ − δ_k), u_ht^k − u_ht^{k−1} − (s_k − s_{k−1}))`. The unknowns of step k are the
//! total `(u_h^k, λ_H^k)`, and the equilibrium line of (3.1) is that of the static problem with the load
//! `α_k f`. In the inequality line, the Barbosa–Hughes term stabilizes the quantity the law acts on, so in
//! its tangential part it acts on the increments, `γ (Δλ_Ht + σ_t(Δu_h))` with `Δ· = ·^k − ·^{k−1}`:
//!
//! ```text
//! b(ν_H − λ_H^k, u_h^k) − ∫ (ν_Hn − λ_Hn^k)(g₀ − δ_k) − ∫ γ (ν_Hn − λ_Hn^k)(λ_Hn^k + σ_n(u_h^k))
//!   − ∫ (ν_Ht − λ_Ht^k)(s_k − s_{k−1} + u_ht^{k−1} − γ (λ_Ht^{k−1} + σ_t(u_h^{k−1})))
//!   − ∫ γ (ν_Ht − λ_Ht^k)(λ_Ht^k + σ_t(u_h^k)) ≤ 0        for all ν_H ∈ M_H(μ λ_Hn^k).
//! ```
//!
//! The terms of step k − 1 are known data: the dependence on `(u_h^k, λ_H^k)` is the static one, so the
//! QP keeps its matrix `H = E A⁻¹ Eᵀ + Dγ` and only its linear term changes:
//!
//! ```text
//! d^k = ( ∫ψ_j (g₀ − δ_k),  ∫ψ_j (s_k − s_{k−1}) + (E_t u^{k−1} − Dγ λ_t^{k−1})_j ),     c^k = d^k − α_k E A⁻¹ f,
//! ```
//!
//! with `E A⁻¹ f` computed once by [`crate::condensation::Factor`]. Prescribed displacements ū (see
//! [`crate::supports`]) keep their lifting: the `−E ū` in d, the same at every step, and the lifted load,
//! of which the load factor scales only the applied part. Both readings of the stabilization —
//! on the increments, or on the totals (`d_t` with `B_t u^{k−1}` only) — are consistent: the term vanishes
//! for the exact solution. They differ at finite γ0: stabilizing the totals leaves the discrete slip
//! measure `γ (λ_t^k + σ_t(u^k))` in a stuck zone, which creeps a little at every step, and a fretting
//! loop then drifts (3e-4 μP per cycle on the Hertz scene at half the γ0 bound). Stabilizing the
//! increments makes a stuck zone stick exactly, and the loop closes to the fixed point's tolerance, as
//! with γ0 = 0 (the test `fretting_loop_closes` checks the closure).
//!
//! So `A`, `H` and `Dγ` never change: one factorization (and one set of H columns, grown as the contact
//! zone needs) serves the whole path, and each Coulomb fixed point starts from the previous step's
//! `λ_n`. A history of one step from rest (`u^0 = 0`, `λ^0 = 0`, `s_0 = 0`) with α = 1 is the static
//! problem: its data are the static ones bit for bit ([`crate::loading::Loading::step`]), and so is its
//! answer.
//!
//! A frictionless step does not depend on the path; a Tresca step uses the fixed threshold on the slip
//! increment.

use std::ops::ControlFlow;
use std::time::Instant;

use crate::error::{Error, Result};
use crate::friction::Friction;
use crate::loading::{LoadStep, Loading, PreviousStep};
use crate::problem::{Condensed, Problem};
use crate::settings::SolverSettings;
use crate::solution::{ContactState, Solution, SolveStatus};

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

/// The result of a loading history.
#[derive(Debug, Clone)]
pub struct History {
    /// The steps asked for.
    pub steps: Vec<LoadStep>,
    /// The solutions of the steps that converged, in order.
    pub solutions: Vec<Solution>,
    /// [`SolveStatus::Converged`] when every step converged; otherwise the status of the step that ended
    /// the history ([`SolveStatus::Interrupted`] when the observer stopped it).
    pub status: SolveStatus,
    /// The step that ended the history early (0-based), if any.
    pub ended_at: Option<usize>,
    /// The last iterate of a step that did not converge (it is not in `solutions`).
    pub failed: Option<Box<Solution>>,
    /// Wall time of each step solved (the converged ones, then the failed one), in seconds.
    pub step_seconds: Vec<f64>,
    /// Factorizations of `A = K − G` done for the history: 1, or 0 when the problem's cached one served.
    pub factorizations: usize,
    /// Wall time of the factorization and condensation set-up, in seconds (0 when reused).
    pub setup_seconds: f64,
}

impl History {
    /// Total normal force `∫ λ_n` per converged step.
    pub fn normal_force(&self) -> Vec<f64> {
        self.solutions.iter().map(|s| s.normal_force).collect()
    }

    /// Total tangential force `∫ λ_t` per converged step.
    pub fn tangential_force(&self) -> Vec<f64> {
        self.solutions.iter().map(|s| s.tangential_force).collect()
    }

    /// Number of multiplier dofs in `state` per converged step.
    pub fn count(&self, state: ContactState) -> Vec<usize> {
        self.solutions.iter().map(|s| s.states.iter().filter(|&&x| x == state).count()).collect()
    }

    /// Per converged step, the smallest interval of abscissae holding the multiplier dofs whose state
    /// `keep` accepts (NaN, NaN when there are none): e.g. the contact zone or the stick zone.
    pub fn extent(&self, keep: impl Fn(ContactState) -> bool) -> Vec<[f64; 2]> {
        self.solutions
            .iter()
            .map(|s| {
                let xs = s.states.iter().zip(&s.multiplier_abscissae).filter(|(st, _)| keep(**st)).map(|(_, x)| *x);
                xs.fold([f64::NAN, f64::NAN], |[a, b], x| [a.min(x), b.max(x)])
            })
            .collect()
    }

    /// Per converged step, whether the contact slides as a whole: something touches and every multiplier
    /// dof in contact slips (then `|Q| = μP` for Coulomb friction).
    pub fn gross_sliding(&self) -> Vec<bool> {
        self.solutions
            .iter()
            .map(|s| {
                let touching = s.states.iter().filter(|&&x| x != ContactState::Separation);
                touching.clone().count() > 0 && touching.into_iter().all(|&x| x == ContactState::Slip)
            })
            .collect()
    }

    /// Per converged step, the stick–slip boundaries: the midpoints between neighbouring multiplier dofs
    /// of which one sticks and the other slips.
    pub fn stick_slip_boundaries(&self) -> Vec<Vec<f64>> {
        self.solutions
            .iter()
            .map(|s| {
                let pairs = s.states.windows(2).zip(s.multiplier_abscissae.windows(2));
                pairs
                    .filter(|(st, _)| {
                        matches!(
                            (st[0], st[1]),
                            (ContactState::Stick, ContactState::Slip) | (ContactState::Slip, ContactState::Stick)
                        )
                    })
                    .map(|(_, x)| 0.5 * (x[0] + x[1]))
                    .collect()
            })
            .collect()
    }
}

impl Condensed<'_> {
    /// Solves the loading history `steps` from rest with one factorization (this one): step k starts
    /// from the state of step k − 1 (see the module documentation for the incremental problem).
    ///
    /// # Errors
    /// [`Error::BadLoadStep`] (before any solve), bad friction or settings, QP set-up errors. A step that
    /// does not converge is not an error: it ends the history with its status (see [`History`]).
    pub fn solve_history(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        mut observer: Option<StepObserver<'_>>,
    ) -> Result<History> {
        settings.validate()?;
        friction.validate(self.q())?;
        if steps.is_empty() {
            return Err(Error::BadLoadStep { step: 0, what: "a history needs at least one step".to_string() });
        }
        for (k, s) in steps.iter().enumerate() {
            s.validate(k)?;
        }
        let (problem, factor) = (self.problem(), self.factor());
        let mut previous = PreviousStep::rest(problem, factor);
        let mut history = History {
            steps: steps.to_vec(),
            solutions: Vec::with_capacity(steps.len()),
            status: SolveStatus::Converged,
            ended_at: None,
            failed: None,
            step_seconds: Vec::with_capacity(steps.len()),
            factorizations: usize::from(!self.reused_factorization()),
            setup_seconds: if self.reused_factorization() { 0.0 } else { factor.factorization_seconds },
        };
        let mut start: Option<Vec<f64>> = None;
        for (k, step) in steps.iter().enumerate() {
            let clock = Instant::now();
            let loading = Loading::step(problem, factor, step, &previous)?;
            let solution = self.solve_loading(friction, settings, &loading, start.as_deref(), None)?;
            let seconds = clock.elapsed().as_secs_f64();
            history.step_seconds.push(seconds);
            let status = solution.report.status;
            log::info!(
                "step {}/{}: {status}, {} fixed-point iterations, {seconds:.3} s",
                k + 1,
                steps.len(),
                solution.report.iterations
            );
            let progress = StepProgress {
                step: k,
                steps: steps.len(),
                status,
                iterations: solution.report.iterations,
                seconds,
                normal_force: solution.normal_force,
                tangential_force: solution.tangential_force,
            };
            if status != SolveStatus::Converged {
                history.status = status;
                history.ended_at = Some(k);
                history.failed = Some(Box::new(solution));
                break;
            }
            previous = after(self, &solution, step.shift);
            start = Some(solution.lambda_n.iter().chain(&solution.lambda_t).copied().collect());
            history.solutions.push(solution);
            let flow = observer.as_mut().map_or(ControlFlow::Continue(()), |o| o(&progress));
            if flow.is_break() && k + 1 < steps.len() {
                history.status = SolveStatus::Interrupted { iteration: progress.iterations };
                history.ended_at = Some(k);
                break;
            }
        }
        Ok(history)
    }
}

/// The state a converged step leaves for the next: `E_t u^k − Dγ λ_t^k`, `u_t^k` at the FE nodes of Γ_C
/// and s_k.
fn after(condensed: &Condensed<'_>, solution: &Solution, shift: f64) -> PreviousStep {
    let (problem, factor) = (condensed.problem(), condensed.factor());
    let q = condensed.q();
    // The unknowns x = Tᵀ (u − ū) (T has orthonormal columns: a node's unknowns are its free directions).
    let relative: Vec<f64> = solution.displacement.iter().zip(&problem.dofs.lifting).map(|(u, l)| u - l).collect();
    let u_free = problem.dofs.restrict(&relative);
    let lambda: Vec<f64> = solution.lambda_n.iter().chain(&solution.lambda_t).copied().collect();
    let (eu, dl) = (factor.apply_e(&u_free), factor.apply_d(&lambda));
    let tangential = (q..2 * q).map(|j| eu[j] - dl[j]).collect();
    let t = problem.contact.tangent;
    let u_t = |node: usize| solution.displacement[2 * node] * t[0] + solution.displacement[2 * node + 1] * t[1];
    PreviousStep { tangential, u_t_nodes: problem.contact.nodes.iter().map(|&n| u_t(n)).collect(), shift }
}

impl Problem {
    /// Condenses with `settings.stabilization` (or reuses the cached factorization) and solves the
    /// loading history `steps`: the one-call entry point of [`Condensed::solve_history`].
    ///
    /// # Errors
    /// As [`Problem::condense`] and [`Condensed::solve_history`].
    pub fn solve_history(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        observer: Option<StepObserver<'_>>,
    ) -> Result<History> {
        settings.validate()?;
        self.condense_with(settings.stabilization, settings.condensation, settings.memory_budget)?
            .solve_history(friction, steps, settings, observer)
    }
}
