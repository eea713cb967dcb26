//! The solve driver: frictionless and Tresca problems are one QP each; Coulomb (3.1) is the fixed point
//! of `Φ_H : g ↦ λ_Hn(g)` (Definition 1 of the paper), each evaluation a Tresca QP P(g) whose matrix
//! does not change (only the bounds μ g do). The displacement is recovered at the end with one solve.
//!
//! The four public entry points are here, each validating its input once: [`Condensed::solve`],
//! [`Problem::solve`], [`Condensed::solve_history`] and [`Problem::solve_history`]. The driver of one
//! solve is `driver`, the fixed point `fixed_point`, the semismooth Newton method beside it [`newton`] (its
//! derivation), the check of a Coulomb answer by the other method [`check`], histories [`history`], and the
//! progress reports [`Progress`] and [`StepProgress`].

pub mod check;
mod driver;
mod fixed_point;
pub mod history;
pub mod increment;
pub mod newton;
mod progress;

pub use fixed_point::STAGNATION_WINDOW;
pub use history::{History, HistoryPair, StepObserver, StepProgress};
pub use progress::{Observer, Phase, Progress};

use crate::condensation::Expected;
use crate::error::{Error, Result};
use crate::problem::{Condensed, Problem};
use crate::results::Solution;
use crate::settings::friction::Friction;
use crate::settings::SolverSettings;
use history::LoadStep;

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
        let problem = self.problem();
        problem.check_prescribed_contact(&problem.contact_gap, &problem.dofs.lifting, None)?;
        self.solve_validated(friction, settings, observer)
    }

    /// Solves the loading history `steps` from rest with one factorization (this one): step k starts
    /// from the state of step k − 1 (see [`history`] for the incremental problem).
    ///
    /// # Errors
    /// [`Error::BadLoadStep`] (before any solve), bad friction or settings, QP set-up errors. A step that
    /// does not converge is not an error: it ends the history with its status (see [`History`]).
    pub fn solve_history(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        observer: Option<StepObserver<'_>>,
    ) -> Result<History> {
        self.solve_history_from(friction, steps, settings, observer, &[])
    }

    /// [`Condensed::solve_history`], step k's fixed point starting from `starts[k]` (2q values) where
    /// given, else from the previous step's answer.
    pub(crate) fn solve_history_from(
        &self,
        friction: &Friction,
        steps: &[LoadStep],
        settings: &SolverSettings,
        observer: Option<StepObserver<'_>>,
        starts: &[Vec<f64>],
    ) -> Result<History> {
        settings.validate()?;
        friction.validate(self.q())?;
        if steps.is_empty() {
            return Err(Error::BadLoadStep { step: 0, what: "a history needs at least one step".to_string() });
        }
        for (k, s) in steps.iter().enumerate() {
            s.validate(k)?;
        }
        increment::check_steps(self.problem(), steps)?;
        history_fits(self.problem(), steps, settings)?;
        self.run_history(friction, steps, settings, observer, starts)
    }
}

/// A history's bytes ([`History::estimated_bytes`](history::History::estimated_bytes)) must fit the memory
/// budget before any step runs.
fn history_fits(problem: &Problem, steps: &[LoadStep], settings: &SolverSettings) -> Result<()> {
    let needed = history::History::estimated_bytes(problem, steps, settings.keep_every);
    if needed > settings.memory_budget as f64 {
        let kept = history::kept_solutions(steps.len(), settings.keep_every);
        let solution = Solution::estimated_bytes(problem);
        let per_step = (needed - (kept * solution) as f64) / steps.len() as f64;
        return Err(Error::MemoryBudget {
            what: format!(
                "a history of {} steps keeping {kept} solutions (about {solution} bytes each on this mesh, \
                 keep_every = {}) and about {per_step:.0} bytes per step (its record, step and series)",
                steps.len(),
                settings.keep_every,
            ),
            needed,
            budget: settings.memory_budget as f64,
        });
    }
    Ok(())
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
        self.check_prescribed_contact(&self.contact_gap, &self.dofs.lifting, None)?;
        let expected = Expected::solving(self.friction_law_as_solved(friction), false);
        self.condense_for(settings.stabilization, settings.condensation, settings.memory_budget, expected)?
            .solve_validated(friction, settings, observer)
    }

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
        history_fits(self, steps, settings)?;
        let expected = Expected::solving(self.friction_law_as_solved(friction), false);
        self.condense_for(settings.stabilization, settings.condensation, settings.memory_budget, expected)?
            .solve_history(friction, steps, settings, observer)
    }
}
