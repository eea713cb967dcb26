//! Adaptive refinement for a loading history: each level solves the whole history, and the mesh is
//! refined where the largest η_K and ζ_K over the chosen steps are (all steps by default); the history is
//! then the one solved on the last mesh. A stick zone that moves, or a contact zone that grows, is
//! refined for every step it passes through, on one mesh.

use super::{AdaptStop, Level, LevelObserver, Start};
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::results::Solution;
use crate::settings::friction::Friction;
use crate::settings::{AdaptSettings, SolverSettings, StopOn};
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
        if adapt.stop_on == StopOn::Hierarchical {
            return Err(Error::BadSettingValue {
                name: "adapt_stop_on",
                what: "'hierarchical' is not yet available for a loading history: it stops on 'bound'".into(),
            });
        }
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
        // A loose answer solved again to fp_tol starts every step from its own (a history from rest would
        // cost a whole history again); the coarser level's multipliers are not carried over.
        let solve = |p: &Problem, s: &SolverSettings, start: Start<'_, History>| match start {
            Start::Answer(h) => {
                let starts: Vec<Vec<f64>> = h.solutions.iter().map(Solution::multipliers).collect();
                // This level's problem holds its factorization: condensing again takes it from the cache.
                p.condense_with(s.stabilization, s.condensation, s.memory_budget)?
                    .solve_history_from(friction, steps, s, None, &starts)
            }
            Start::Rest | Start::Lambda(_) => p.solve_history(friction, steps, s, None),
        };
        let read = super::reader(|h: &History| {
            if on.is_empty() {
                h.solutions.iter().collect()
            } else {
                on.iter().filter_map(|&k| h.solutions.get(k)).collect()
            }
        });
        let ended = |h: &History| (h.status, h.solutions.iter().map(|s| s.report.iterations).sum());
        let (problem, history, levels, stop) =
            self.adapt_loop(settings, adapt, observer, &solve, &read, &ended, None)?;
        Ok(AdaptiveHistory { problem, history, levels, stop })
    }
}
