//! Adaptive refinement for a loading history: each level solves the whole history, and the mesh is
//! refined where the largest η_K and ζ_K over the chosen steps are (all steps by default); the history is
//! then the one solved on the last mesh. A stick zone that moves, or a contact zone that grows, is
//! refined for every step it passes through, on one mesh.

use std::time::Instant;

use super::enriched::{estimate_of, EndReduction, Hierarchical};
use super::strip::{end_regions, near_ends, EndRegion};
use super::{multiplier_difference, AdaptStop, Level, LevelObserver, Sharp, Start};
use crate::error::{Error, Num, Result};
use crate::problem::Problem;
use crate::results::{ErrorEstimate, Solution, SolveStatus};
use crate::settings::friction::Friction;
use crate::settings::memory::left_beside;
use crate::settings::{AdaptSettings, SolverSettings};
use crate::solve::history::{History, LoadStep};

/// The result of an adaptive history: the problem on the last mesh, the history solved on it, and
/// every level.
#[derive(Debug, Clone)]
pub struct AdaptiveHistory {
    /// The problem on the last mesh.
    pub problem: Problem,
    /// The history on the last mesh.
    pub history: History,
    /// Every level, the first (the given mesh) included. A level's estimate is that of the step (among
    /// those chosen) with the largest relative estimate.
    pub levels: Vec<Level>,
    /// Why the loop stopped.
    pub stop: AdaptStop,
}

impl Problem {
    /// Solves the loading history `steps` adaptively from this problem's mesh: every level solves the
    /// whole history ([`Problem::solve_history`]) and is marked on the largest η_K and ζ_K over the steps
    /// `on` (0-based; empty: all of them); the loop stops when the largest relative estimate over those
    /// steps meets `adapt.tol` (see the [module documentation](crate::adapt) for the rest). Levels start
    /// their steps as a history does, not from the previous level.
    ///
    /// # Errors
    /// As [`Problem::solve_adaptive`] and [`Problem::solve_history`]; [`Error::BadSetting`] named
    /// `adapt_steps` when a step of `on` is not in the history.
    pub fn solve_history_adaptive(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        adapt: &AdaptSettings,
        on: &[usize],
        observer: Option<LevelObserver<'_>>,
    ) -> Result<AdaptiveHistory> {
        self.check_adaptive(friction, settings, adapt)?;
        if settings.keep_every != 1 {
            return Err(Error::BadSetting {
                name: "keep_every",
                value: settings.keep_every as f64,
                what: "must be 1 in an adaptive history: every level marks on the solutions of its steps".into(),
            });
        }
        if let Some(&k) = on.iter().find(|&&k| k >= steps.len()) {
            return Err(Error::BadSetting {
                name: "adapt_steps",
                value: k as f64,
                what: format!("is not a step of the history (0 to {})", steps.len().saturating_sub(1)),
            });
        }
        // A Tresca threshold given per dof is carried to each level's T_H as the W_H function it defines.
        let on_level = |p: &Problem| self.carried_friction(friction, p);
        // A loose answer solved again to fp_tol starts every step from its own (a history from rest would
        // cost a whole history again); the coarser level's multipliers are not carried over.
        let solve = |p: &Problem, s: &SolverSettings, start: Start<'_, History>| match start {
            Start::Answer(h) => {
                let starts: Vec<Vec<f64>> = h.solutions.iter().map(Solution::multipliers).collect();
                // This level's problem holds its factorization: condensing again takes it from the cache.
                p.condense_with(s.stabilization, s.condensation, s.memory_budget)?.solve_history_from(
                    &on_level(p),
                    steps,
                    s,
                    None,
                    &starts,
                )
            }
            Start::Rest | Start::Lambda(_) => p.solve_history(&on_level(p), steps, s, None),
        };
        let read = super::reader(|h: &History| {
            if on.is_empty() {
                h.solutions.iter().collect()
            } else {
                on.iter().filter_map(|&k| h.solutions.get(k)).collect()
            }
        });
        let ended = |h: &History| (h.status, h.solutions.iter().map(|s| s.report.iterations).sum());
        let estimate = |p: &Problem, h: &History| p.history_hierarchical_and_enriched(h, &on_level(p), settings);
        // Only the finite estimates: a step without one reads its bound.
        let store_with = |h: &mut History, estimates: &[Hierarchical], enriched: bool| {
            // Estimate i is of kept step i; both histories keep every step (keep_every is 1 here, and 1 in the
            // enriched history): estimates that do not fit them are not written.
            if h.kept.len() != estimates.len() {
                log::warn!("{} estimates for {} kept steps: not stored", estimates.len(), h.kept.len());
                return;
            }
            if !enriched {
                // A step without a finite estimate reads its bound, not the calibrated bound of the level before: the
                // ratio this level passes on is measured on this level's estimates alone.
                each_kept_estimate(h, |e| e.traction_calibrated_relative = None);
            }
            for (i, e) in estimates.iter().enumerate() {
                let (Some(&k), Some(solution)) = (h.kept.get(i), h.solutions.get_mut(i)) else { continue };
                match enriched {
                    false if e.relative.is_finite() => e.store(solution),
                    true if e.enriched_relative.is_finite() => e.store_enriched(solution),
                    _ => continue,
                }
                if let Some(record) = h.records.get_mut(k) {
                    record.estimate = solution.report.estimate;
                }
            }
        };
        let store = |h: &mut History, estimates: &[Hierarchical]| store_with(h, estimates, false);
        let store_enriched = |h: &mut History, estimates: &[Hierarchical]| store_with(h, estimates, true);
        let calibrate =
            |h: &mut History, ratio: f64| each_kept_estimate(h, |e| super::calibration::calibrate(e, ratio));
        let sharp =
            Sharp { estimate: &estimate, store: &store, store_enriched: &store_enriched, calibrate: &calibrate };
        let (problem, history, levels, stop) =
            self.adapt_loop(settings, adapt, observer, &solve, &read, &ended, Some(&sharp))?;
        Ok(AdaptiveHistory { problem, history, levels, stop })
    }

    /// The hierarchical estimate of the traction error of every kept step of `history`, a history of this
    /// problem solved with `friction` (in the order of [`History::kept`]): as [`Problem::estimate_hierarchical`]
    /// for one solve, with the whole history solved on the enriched mesh (friction depends on the path, so a
    /// step cannot be enriched alone). The whole mesh is bisected, then the triangles within half a contact width of
    /// the contact zone of every kept step again (for a step with one multiplier dof touching, within the two T_H cells
    /// around it; nothing more when no step touches); where an end of Γ_C touches in a step, the history is solved
    /// twice more on the mesh enriched again at the ends, and that step's reduction there is measured between those
    /// two. Each step's enriched solve starts from its own multipliers when every step was kept. The steps solved are
    /// the converged ones of `history`; the estimates carry the enriched history's status, and a step it did not reach
    /// has a NaN estimate. Every step of the enriched
    /// histories is kept (8–9 times the unknowns of `history`'s): each must fit the memory budget less
    /// the histories already held ([`History::estimated_bytes`]), or the estimate is refused with
    /// [`Error::MemoryBudget`] (the adaptive loop then reads the bound). No estimate for a history
    /// without a converged step.
    ///
    /// # Errors
    /// [`Error::BadSetting`] named `history` or `solution` when `history` is not a history of this problem;
    /// those of [`crate::mesh::refine::bisect`], of the enriched problem and of its history
    /// ([`Problem::solve_history`]).
    pub fn estimate_history_hierarchical(
        &self,
        history: &History,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Vec<Hierarchical>> {
        Ok(self.history_hierarchical_and_enriched(history, friction, settings)?.0)
    }

    /// [`Problem::estimate_history_hierarchical`], with the enriched problem and its history (`None` for a
    /// history without records).
    pub(super) fn history_hierarchical_and_enriched(
        &self,
        history: &History,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<super::Estimated<History>> {
        let clock = Instant::now();
        if history.records.is_empty() {
            return Ok((Vec::new(), None));
        }
        self.check_history_of(history)?;
        // The whole mesh, then the strip of every step again (a step with one dof touching: the cells around it).
        let all: Vec<usize> = (0..self.mesh.n_triangles()).collect();
        // The enriched histories keep every step while this one is held: each must fit what the budget leaves.
        let steps = &history.steps[..history.records.len()];
        // (And this problem's factorization, held by the adaptive loop's level.)
        let held = History::estimated_bytes(self, steps, 1) + self.held_bytes();
        let build = |p: &Problem, s: &[&Solution]| p.enriched_twice(s, &all);
        let (enriched, answer) = self.solve_enriched_history(history, build, friction, settings, held)?;
        // Each step's ends where the difference concentrates (a step without its enriched answer keeps them all).
        let ends_of = |(i, s): (usize, &Solution)| {
            let regions = end_regions(self, s);
            match answer.solution_of(history.kept[i]) {
                Some(fine) => self.concentrated(&regions, s, (&enriched, fine)),
                None => regions,
            }
        };
        let regions: Vec<Vec<EndRegion>> = history.solutions.iter().enumerate().map(ends_of).collect();
        let mut union: Vec<EndRegion> = regions.iter().flatten().copied().collect();
        union.sort_by(|a, b| a.pair.cmp(&b.pair).then(a.span[0].total_cmp(&b.span[0])));
        union.dedup();
        let twice = if answer.status == SolveStatus::Converged && !union.is_empty() {
            let near = near_ends(self, &enriched, &union);
            let friction = self.carried_friction(friction, &enriched);
            // The first enrichment's factorization is not needed again: the second history does not hold both.
            enriched.forget_factorization();
            let held = held + History::estimated_bytes(&enriched, steps, 1);
            let build = |p: &Problem, s: &[&Solution]| p.enriched_at_ends(s, &near, self, &union);
            let twice = enriched.solve_enriched_history(&answer, build, &friction, settings, held);
            Some(twice.inspect_err(|e| {
                log::warn!("the second enrichment at the ends of Γ_C failed ({e}): no estimate there");
            }))
        } else {
            None
        };
        // The third, at the ends again: the reduction is read between the two alike (`enriched`'s documentation).
        let thrice = match &twice {
            Some(Ok((p2, h2))) if h2.status == SolveStatus::Converged => {
                p2.forget_factorization();
                let inner: Vec<EndRegion> = union.iter().map(|r| r.toward_end(0.25)).collect();
                let (near, friction) = (near_ends(self, p2, &inner), self.carried_friction(friction, p2));
                let held =
                    held + History::estimated_bytes(&enriched, steps, 1) + History::estimated_bytes(p2, steps, 1);
                let build = |p: &Problem, s: &[&Solution]| p.enriched_at_ends(s, &near, self, &inner);
                let third = p2.solve_enriched_history(h2, build, &friction, settings, held);
                third.inspect_err(|e| log::warn!("the third enrichment at the ends of Γ_C failed ({e})")).ok()
            }
            _ => None,
        };
        let seconds = clock.elapsed().as_secs_f64();
        let estimate = |(i, &k): (usize, &usize)| {
            let solution = &history.solutions[i];
            let unknowns = enriched.n_free;
            let Some(fine) = answer.solution_of(k) else {
                let (difference, norm, estimate, relative) = (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
                let (status, end_reductions, error_bars) = (answer.status, Vec::new(), None);
                return Hierarchical {
                    difference,
                    norm,
                    estimate,
                    relative,
                    enriched_estimate: f64::NAN,
                    enriched_relative: f64::NAN,
                    unknowns,
                    status,
                    seconds,
                    end_reductions,
                    error_bars,
                };
            };
            let (difference, norm) = multiplier_difference(self, solution, &enriched, fine);
            let ends = match &twice {
                None => Vec::new(),
                // Not measured where this step touches an end: no estimate there.
                Some(Err(_)) if !regions[i].is_empty() => {
                    vec![EndReduction::unmeasured()]
                }
                Some(Err(_)) => Vec::new(),
                Some(Ok((p, h))) => {
                    let again = h.solution_of(k).filter(|_| h.status == SolveStatus::Converged);
                    let third = thrice.as_ref().filter(|(_, h3)| h3.status == SolveStatus::Converged);
                    let third = third.and_then(|(p3, h3)| h3.solution_of(k).map(|s| (p3, s)));
                    self.reductions(&regions[i], (solution, (&enriched, fine)), again.map(|a| (p, a)), third)
                }
            };
            let [(estimate, relative), (enriched_estimate, enriched_relative)] =
                estimate_of(difference, norm, &ends, settings.fp.tol);
            Hierarchical {
                difference,
                norm,
                estimate,
                relative,
                enriched_estimate,
                enriched_relative,
                unknowns,
                status: answer.status,
                seconds,
                end_reductions: ends.iter().map(|e| e.reduction).collect(),
                error_bars: None,
            }
        };
        let estimates = history.kept.iter().enumerate().map(estimate).collect();
        Ok((estimates, Some((enriched, answer))))
    }

    /// Refuses a history that is not of this problem: its solutions ([`Problem::check_solution_of`]), and
    /// its records, kept steps and solutions as many as one another say.
    fn check_history_of(&self, history: &History) -> Result<()> {
        let kept_fit =
            history.kept.len() == history.solutions.len() && history.kept.iter().all(|&k| k < history.records.len());
        if history.records.len() > history.steps.len() || !kept_fit {
            return Err(Error::BadSetting {
                name: "history",
                value: history.records.len() as f64,
                what: format!(
                    "is not a history as solve_history returns it: {} records of {} steps, {} kept steps for {} \
                     solutions",
                    history.records.len(),
                    history.steps.len(),
                    history.kept.len(),
                    history.solutions.len()
                ),
            });
        }
        history.solutions.iter().try_for_each(|s| self.check_solution_of(s))
    }

    /// The converged steps of `history` solved on the problem that `build` makes of this one and the steps'
    /// solutions (this problem enriched: `Problem::enriched_twice`, `Problem::enriched_at_ends`), every step kept;
    /// step k starts from step k's multipliers when every step was kept.
    /// The memory budget is what `settings` gives less the `held` bytes of the histories kept meanwhile.
    fn solve_enriched_history(
        &self,
        history: &History,
        build: impl FnOnce(&Problem, &[&Solution]) -> Result<Problem>,
        friction: &Friction,
        settings: &SolverSettings,
        held: f64,
    ) -> Result<(Problem, History)> {
        let solutions: Vec<&Solution> = history.solutions.iter().collect();
        let enriched = build(self, &solutions)?;
        let steps = &history.steps[..history.records.len()];
        let carry =
            |s: &&Solution| [self.carried(&s.lambda_n, &enriched), self.carried(&s.lambda_t, &enriched)].concat();
        let starts: Vec<Vec<f64>> =
            if history.kept.len() == steps.len() { solutions.iter().map(carry).collect() } else { Vec::new() };
        let friction = self.carried_friction(friction, &enriched);
        let memory_budget = left_beside(settings.memory_budget, held, || {
            format!("the enriched history, beside the histories and factorization held ({} bytes),", Num(held))
        })?;
        let every = SolverSettings { keep_every: 1, memory_budget, ..*settings };
        let condensed = enriched.condense_with(every.stabilization, every.condensation, every.memory_budget)?;
        let answer = condensed.solve_history_from(&friction, steps, &every, None, &starts)?;
        drop(condensed);
        Ok((enriched, answer))
    }
}

/// Applies `f` to the estimate of every kept step's solution of `h` (solution i is of step `h.kept[i]`), and writes it
/// into that step's record alike.
fn each_kept_estimate(h: &mut History, f: impl Fn(&mut ErrorEstimate)) {
    for (i, solution) in h.solutions.iter_mut().enumerate() {
        f(&mut solution.report.estimate);
        if let Some(record) = h.kept.get(i).and_then(|&k| h.records.get_mut(k)) {
            record.estimate = solution.report.estimate;
        }
    }
}
