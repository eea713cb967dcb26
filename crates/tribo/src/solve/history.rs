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
//! In (3.1), the pair `w_h = (u_hn − g, u_ht − s)` of the static problem (see [`crate::contact::obstacle`]) becomes
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
//! [`crate::fem::supports`]) enter through their lifting: `f̃ = Tᵀ f − Tᵀ A ū` and `d̃ = d − E ū`. A
//! step may move them ([`LoadStep::displacements`], the values of the components `"set.x"`, `"set.y"`
//! of every prescribed displacement): its lifting ū_k differs from the problem's ū by `Δū`, which the
//! step lifts like a load, `f̃_k = f̃ + (α_k − 1) Tᵀ f − Tᵀ A Δū` and `d^k − E Δū`, with one solve for
//! `E A⁻¹ f̃_k`; A, H and Dγ do not change (the supports hold the same dofs, only their values move). The
//! previous step's tangential data is kept as `E_t (u^{k−1} − ū) − Dγ λ_t^{k−1}`, on the problem's ū,
//! so that the data of step k holds `−E_t Δū_k` once, whatever the previous steps did. Moving a body's
//! clamp by a rigid motion is moving the obstacle the other way: the two give one answer, to round-off
//! (the test `moving_the_body_is_moving_the_obstacle`); between two bodies it is how they are pressed
//! together and made to slide. The load factor scales only the applied part of the load, never the
//! lifting.
//!
//! Both readings of the stabilization —
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
//! problem: its data are the static ones bit for bit (`step_load_case`), and so is its
//! answer.
//!
//! A frictionless step does not depend on the path; a Tresca step uses the fixed threshold on the slip
//! increment.
//!
//! # A turned obstacle
//! An obstacle given by its geometry with a rotation ([`crate::ObstacleRotation`]) may turn from step to step
//! ([`LoadStep::rotation`], the total angle θ_k about its centre). Its gap then depends on the step, and its
//! surface's motion along Γ_C is a field, `m_k(x) = s_k + w_k(y) · t` ([`crate::contact::obstacle`]), so the
//! step reads the obstacle turned to θ_k ([`crate::Problem::placement`]):
//!
//! ```text
//! d^k = ( ∫ψ_j (g₀(θ_k) − δ_k),  ∫ψ_j (m_k − m_{k−1}) + (E_t u^{k−1} − Dγ λ_t^{k−1})_j ),
//! ```
//!
//! with `m_0 = 0` at rest (shift 0, angle 0), and the slip increment of Coulomb's law relative to the surface,
//! `u_t^k − u_t^{k−1} − (m_k − m_{k−1})`. Without a rotation `m_k = s_k` and this is the data above. A, H and Dγ do
//! not change, so the contact frame (each edge's `n_e`, oriented to the obstacle when the problem was built) stays
//! the problem's: small rotations. Where the turn moves the surface in its own line (a disc or a hole about its
//! centre) the frame is the turned obstacle's; where it tilts the surface, the traction's direction is off by the
//! angle turned from the problem's own (`tests/integration/turned_obstacle.rs` measures 0.24–0.32 θ in λ).

use std::ops::ControlFlow;
use std::time::Instant;

use crate::error::Result;
pub use crate::problem::load_case::LoadStep;
use crate::problem::Condensed;
use crate::results::{dof_span, ContactState, ErrorEstimate, Solution, SolveStatus};
use crate::settings::friction::Friction;
use crate::settings::SolverSettings;
use crate::solve::increment::{after, step_load_case, PreviousStep};
pub use crate::solve::progress::{StepObserver, StepProgress};

/// The result of a loading history.
///
/// Every converged step leaves a [`StepRecord`] (its forces, contact states and error estimate), from
/// which the per-step series are derived; its whole [`Solution`] is kept for every `keep_every`-th step
/// ([`SolverSettings::keep_every`]: steps `k` with `k % keep_every == 0`, the first included) and
/// for the last converged one, so a long history's memory is its records plus the solutions asked for.
#[derive(Debug, Clone)]
pub struct History {
    /// The steps asked for.
    pub steps: Vec<LoadStep>,
    /// The solutions kept (see above), in order; `kept` gives their steps.
    pub solutions: Vec<Solution>,
    /// The step (0-based) of each kept solution.
    pub kept: Vec<usize>,
    /// One record per converged step, in order.
    pub records: Vec<StepRecord>,
    /// The abscissae of the multiplier dofs (the same at every step; of every pair, the first first).
    pub multiplier_abscissae: Vec<f64>,
    /// The contact pairs, the problem's own first (one for a problem of one pair).
    pub pairs: Vec<HistoryPair>,
    /// Each pair's `∫ λ_n` and `∫ λ_t` per converged step, the pairs of a step one after the other, where the problem
    /// has several pairs (empty for one: the totals are its; [`History::pair_forces`]).
    pub pair_forces: Vec<[f64; 2]>,
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

/// One contact pair of a history: where its multiplier dofs lie in a step's states, and its side's shape.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryPair {
    /// Its name (its contact edge set).
    pub name: String,
    /// Its multiplier dofs (as [`crate::PairResult::multipliers`]).
    pub multipliers: std::ops::Range<usize>,
    /// The abscissa of its side's first FE node.
    pub start: f64,
    /// Its side's length where the side is a closed loop (the period of its abscissae), else `None`.
    pub period: Option<f64>,
}

impl HistoryPair {
    /// The pairs of a problem.
    pub fn of(problem: &crate::Problem) -> Vec<Self> {
        let offsets = problem.pair_offsets();
        let pair = |(k, p): (usize, crate::problem::sides::PairParts<'_>)| {
            let x = &p.contact.node_xi;
            let (start, end) = (x.first().copied().unwrap_or(0.0), x.last().copied().unwrap_or(0.0));
            let period = p.contact.is_closed().then_some(end - start);
            Self { name: p.name.to_string(), multipliers: offsets[k]..offsets[k + 1], start, period }
        };
        problem.pairs().into_iter().enumerate().map(pair).collect()
    }
}

/// What a history keeps of every converged step, kept or not.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// `∫ λ_n` (over every pair).
    pub normal_force: f64,
    /// `∫ λ_t` (over every pair).
    pub tangential_force: f64,
    /// The state of every multiplier dof.
    pub states: Vec<ContactState>,
    /// The error estimate's totals.
    pub estimate: ErrorEstimate,
}

impl StepRecord {
    /// The record of a solution.
    pub fn of(solution: &Solution) -> Self {
        Self {
            normal_force: solution.normal_force,
            tangential_force: solution.tangential_force,
            states: solution.states.clone(),
            estimate: solution.report.estimate,
        }
    }

    /// Bytes a record of a problem with `q` multiplier dofs takes (its states allocated in words).
    pub fn bytes(q: usize) -> usize {
        size_of::<Self>() + (q * size_of::<ContactState>()).next_multiple_of(8)
    }
}

impl History {
    /// The per-step series of numbers by name: the approach, shift, load factor and obstacle angle (NaN for
    /// the problem's own) of every step asked for, the total forces, the error estimate η, the relative
    /// traction estimate (the bound), the hierarchical one (NaN where it was not computed: an adaptive history stopping
    /// on it computes it on some levels) and the calibrated bound (NaN where the loop did not form it: the level after
    /// an estimated one) of the converged steps, and the wall time of each step solved.
    pub fn series(&self) -> [(&'static str, Vec<f64>); 11] {
        let step = |f: fn(&LoadStep) -> f64| self.steps.iter().map(f).collect();
        let record = |f: fn(&StepRecord) -> f64| self.records.iter().map(f).collect();
        [
            ("approach", step(|s| s.approach)),
            ("shift", step(|s| s.shift)),
            ("load_factor", step(|s| s.load_factor)),
            ("rotation", step(|s| s.rotation.unwrap_or(f64::NAN))),
            ("normal_force", self.normal_force()),
            ("tangential_force", self.tangential_force()),
            ("error_estimate", record(|r| r.estimate.total)),
            ("traction_error", record(|r| r.estimate.traction_relative)),
            ("traction_error_hierarchical", record(|r| r.estimate.traction_hierarchical_relative.unwrap_or(f64::NAN))),
            ("traction_error_calibrated", record(|r| r.estimate.traction_calibrated_relative.unwrap_or(f64::NAN))),
            ("step_seconds", self.step_seconds.clone()),
        ]
    }

    /// Total normal force `∫ λ_n` per converged step.
    pub fn normal_force(&self) -> Vec<f64> {
        self.records.iter().map(|s| s.normal_force).collect()
    }

    /// Total tangential force `∫ λ_t` per converged step.
    pub fn tangential_force(&self) -> Vec<f64> {
        self.records.iter().map(|s| s.tangential_force).collect()
    }

    /// Pair `k`'s `∫ λ_n` and `∫ λ_t` per converged step (the totals for a problem of one pair; empty for a pair
    /// it does not have).
    pub fn pair_forces(&self, k: usize) -> [Vec<f64>; 2] {
        if self.pairs.len() <= 1 {
            return if k == 0 { [self.normal_force(), self.tangential_force()] } else { [Vec::new(), Vec::new()] };
        }
        let m = self.pairs.len();
        let component = |c: usize| self.pair_forces.iter().skip(k).step_by(m).map(|f| f[c]).collect();
        [component(0), component(1)]
    }

    /// Pair `k`'s forces per converged step by name, `normal_force` and `tangential_force`, where the history has
    /// several pairs (none for one: the totals are its).
    pub fn pair_series(&self, k: usize) -> Vec<(&'static str, Vec<f64>)> {
        if self.pairs.len() <= 1 {
            return Vec::new();
        }
        let [p, q] = self.pair_forces(k);
        vec![("normal_force", p), ("tangential_force", q)]
    }

    /// Number of multiplier dofs in `state` per converged step (over every pair).
    pub fn count(&self, state: ContactState) -> Vec<usize> {
        self.records.iter().map(|s| s.states.iter().filter(|&&x| x == state).count()).collect()
    }

    /// Per converged step, the smallest interval of abscissae holding the first pair's multiplier dofs whose state
    /// `keep` accepts (NaN, NaN when there are none): e.g. the contact zone or the stick zone. On a closed
    /// Γ_C ([`Solution::closed`]) the shortest arc, which begins before Γ_C's start where it crosses the cut
    /// (as [`Solution::contact_zone`]).
    pub fn extent(&self, keep: impl Fn(ContactState) -> bool) -> Vec<[f64; 2]> {
        self.pair_extent(0, keep)
    }

    /// [`History::extent`] of pair `k` (on its own side; empty for a pair the history does not have).
    pub fn pair_extent(&self, k: usize, keep: impl Fn(ContactState) -> bool) -> Vec<[f64; 2]> {
        let Some(pair) = self.pairs.get(k) else { return Vec::new() };
        let x = self.multiplier_abscissae.get(pair.multipliers.clone()).unwrap_or_default();
        let span = |s: &StepRecord| {
            let states = &s.states[pair.multipliers.clone()];
            dof_span(x, pair.period, |k| keep(states[k]))
        };
        self.records.iter().map(|s| span(s).map_or([f64::NAN; 2], |(a, b)| [a, b])).collect()
    }

    /// Per converged step, whether the first pair's contact slides as a whole: something touches and every
    /// multiplier dof in contact slips (then `|Q| = μP` for Coulomb friction).
    pub fn gross_sliding(&self) -> Vec<bool> {
        self.pair_gross_sliding(0)
    }

    /// [`History::gross_sliding`] of pair `k` (empty for a pair the history does not have).
    pub fn pair_gross_sliding(&self, k: usize) -> Vec<bool> {
        let Some(pair) = self.pairs.get(k) else { return Vec::new() };
        self.records
            .iter()
            .map(|s| {
                let touching = s.states[pair.multipliers.clone()].iter().filter(|&&x| x != ContactState::Separation);
                touching.clone().count() > 0 && touching.into_iter().all(|&x| x == ContactState::Slip)
            })
            .collect()
    }

    /// Per converged step, the stick–slip boundaries of the first pair: the midpoints between neighbouring
    /// multiplier dofs of which one sticks and the other slips (on a closed Γ_C, the last dof and the first across
    /// the cut too, the midpoint then wrapped onto Γ_C).
    pub fn stick_slip_boundaries(&self) -> Vec<Vec<f64>> {
        self.pair_stick_slip_boundaries(0)
    }

    /// [`History::stick_slip_boundaries`] of pair `k` (empty for a pair the history does not have).
    pub fn pair_stick_slip_boundaries(&self, k: usize) -> Vec<Vec<f64>> {
        let Some(pair) = self.pairs.get(k) else { return Vec::new() };
        self.records.iter().map(|r| self.boundaries_of(pair, r).collect()).collect()
    }

    /// The first pair's stick–slip boundaries of every converged step as one table, in step order: the step
    /// (0-based) of each boundary and its abscissa (as [`History::stick_slip_boundaries`] places it). Two arrays
    /// whatever the number of steps, as the bindings hand them over.
    pub fn stick_slip_table(&self) -> (Vec<usize>, Vec<f64>) {
        let Some(pair) = self.pairs.first() else { return (Vec::new(), Vec::new()) };
        let rows = self.records.iter().enumerate().flat_map(|(k, r)| self.boundaries_of(pair, r).map(move |x| (k, x)));
        rows.unzip()
    }

    fn boundaries_of<'a>(&'a self, pair: &'a HistoryPair, record: &'a StepRecord) -> impl Iterator<Item = f64> + 'a {
        let boundary = |a: ContactState, b: ContactState| {
            matches!((a, b), (ContactState::Stick, ContactState::Slip) | (ContactState::Slip, ContactState::Stick))
        };
        let (x, states) =
            (&self.multiplier_abscissae[pair.multipliers.clone()], &record.states[pair.multipliers.clone()]);
        let pairs = states.windows(2).zip(x.windows(2));
        let inner = pairs.filter(move |(st, _)| boundary(st[0], st[1])).map(|(_, x)| 0.5 * (x[0] + x[1]));
        // Across a loop's cut: the last dof and the first, a period apart.
        let n = x.len();
        let across = pair.period.map(|period| (pair.start, period));
        let across = across.filter(|_| n > 1 && boundary(states[n - 1], states[0])).map(|(start, period)| {
            let mid = 0.5 * (x[n - 1] + x[0] + period);
            if mid >= start + period {
                (Some(mid - period), None) // wrapped onto the start: the first boundary
            } else {
                (None, Some(mid)) // before the end: the last
            }
        });
        let (first, last) = across.unwrap_or((None, None));
        first.into_iter().chain(inner).chain(last)
    }

    /// About how many bytes a history of `steps` on `problem` holds when it ends, keeping the solution of
    /// every `keep_every`-th step and of the last ([`SolverSettings::keep_every`]): those solutions
    /// ([`Solution::estimated_bytes`]), and per step its [`StepRecord`] (the states included), its
    /// [`LoadStep`] twice (the caller's and the history's copy), its wall time, and the per-step series a
    /// reader takes from it at once, as the bindings and the files do: the ten of [`History::series`],
    /// the three counts, the two zones' ends, the gross-sliding flag and two stick–slip boundaries (a step
    /// has as many as its stick zone has ends); with several pairs, each pair's forces (kept, and as series), the
    /// ends of its zones and its flag. The memory budget of a history is checked against it
    /// before any step runs (`docs/history_memory.md` measures it against the peak of long histories).
    pub fn estimated_bytes(problem: &crate::Problem, steps: &[LoadStep], keep_every: usize) -> f64 {
        let kept = kept_solutions(steps.len(), keep_every);
        let load_steps: usize = steps.iter().map(|s| size_of::<LoadStep>() + 8 * s.displacements.len()).sum();
        // 11 series + 3 counts + 4 zone ends + 2 × (step, abscissa) of the boundaries, and the flag.
        // With several pairs, each pair's forces and their series, zones' ends and gross-sliding flag besides.
        let pairs = if problem.sides.is_empty() { 0 } else { problem.sides.len() + 1 };
        let per_step =
            StepRecord::bytes(problem.n_multipliers()) + 8 + (11 + 3 + 4 + 4) * 8 + 1 + pairs * (16 + 48 + 1);
        Solution::estimated_bytes(problem) as f64 * kept as f64
            + 2.0 * load_steps as f64
            + per_step as f64 * steps.len() as f64
    }

    /// The kept solution of step `k` (0-based), if it was kept.
    pub fn solution_of(&self, k: usize) -> Option<&Solution> {
        self.kept.binary_search(&k).ok().map(|i| &self.solutions[i])
    }
}

/// How many solutions a history of `steps` steps keeps at most: steps 0, k, 2k, … (`k = keep_every`) and
/// the last.
pub(crate) fn kept_solutions(steps: usize, keep_every: usize) -> usize {
    (steps.div_ceil(keep_every.max(1)) + 1).min(steps)
}

impl Condensed<'_> {
    /// The step loop of [`Condensed::solve_history`], on validated friction, steps and settings; step k
    /// starts from `starts[k]` where given, else from the previous step's answer.
    pub(crate) fn run_history(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        mut observer: Option<StepObserver<'_>>,
        starts: &[Vec<f64>],
    ) -> Result<History> {
        // The QPs' path over all the steps: an automatic saddle-point path may give way to columns of H.
        let this = self.for_load_cases(steps.len());
        let (problem, factor) = (self.problem(), self.factor());
        let mut previous = PreviousStep::rest(problem, factor);
        let every = settings.keep_every.max(1);
        let mut history = History {
            steps: steps.to_vec(),
            solutions: Vec::with_capacity(steps.len().div_ceil(every) + 1),
            kept: Vec::with_capacity(steps.len().div_ceil(every) + 1),
            records: Vec::with_capacity(steps.len()),
            multiplier_abscissae: Vec::new(),
            pairs: HistoryPair::of(problem),
            pair_forces: Vec::with_capacity(if problem.sides.is_empty() {
                0
            } else {
                steps.len() * (problem.sides.len() + 1)
            }),
            status: SolveStatus::Converged,
            ended_at: None,
            failed: None,
            step_seconds: Vec::with_capacity(steps.len()),
            factorizations: usize::from(!self.reused_factorization()),
            setup_seconds: if self.reused_factorization() { 0.0 } else { factor.factorization_seconds },
        };
        let mut start: Option<Vec<f64>> = None;
        // The last converged step's solution while it is not one to keep: kept if the history ends there.
        let mut latest: Option<(usize, Solution)> = None;
        for (k, step) in steps.iter().enumerate() {
            let clock = Instant::now();
            let (loading, placed) = step_load_case(problem, factor, step, &previous)?;
            let from = starts.get(k).map(Vec::as_slice).or(start.as_deref());
            let solution = this.solve_loading(friction, settings, &loading, from, None)?;
            let seconds = clock.elapsed().as_secs_f64();
            history.step_seconds.push(seconds);
            let status = solution.report.status;
            log::info!(
                "step {}/{}: {status}, {} iterations of the Coulomb method, {seconds:.3} s",
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
            previous = after(self, &solution, &loading, placed);
            start = Some(solution.multipliers());
            history.records.push(StepRecord::of(&solution));
            if solution.pairs.len() > 1 {
                history.pair_forces.extend(solution.pairs.iter().map(|p| [p.normal_force, p.tangential_force]));
            }
            if history.multiplier_abscissae.is_empty() {
                history.multiplier_abscissae.clone_from(&solution.multiplier_abscissae);
            }
            if k % every == 0 {
                history.kept.push(k);
                history.solutions.push(solution);
                latest = None;
            } else {
                latest = Some((k, solution));
            }
            let flow = observer.as_mut().map_or(ControlFlow::Continue(()), |o| o(&progress));
            if flow.is_break() && k + 1 < steps.len() {
                history.status = SolveStatus::Interrupted { iteration: progress.iterations };
                history.ended_at = Some(k);
                break;
            }
        }
        if let Some((k, solution)) = latest {
            history.kept.push(k);
            history.solutions.push(solution);
        }
        Ok(history)
    }
}
