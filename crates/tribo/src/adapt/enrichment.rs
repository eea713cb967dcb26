//! The enriched problem of the hierarchical estimate ([`crate::adapt::enriched`]): the triangles to enrich bisected on
//! their three edges (and the conforming closure), T_H refined where the FE edges under it were, keeping the level's
//! ratio H/h where contact is and T_H as it was where the body is surely apart (and no Tresca threshold acts); the
//! enrichment that bisects the whole mesh and then the strip along the contact zone again; the same twice at the ends
//! of Γ_C; and the solve of such a problem from the coarse answer's multipliers.

use super::strip::{first_pair_span, near_ends, strip_on, EndRegion};
use crate::error::{Error, Result};
use crate::mesh::refine::bisect;
use crate::problem::Problem;
use crate::results::Solution;
use crate::settings::friction::{Friction, Threshold};
use crate::settings::{Bisection, SolverSettings};

/// The strip bisected again, in contact widths ([`Problem::enriched_twice`]).
const STRIP_AGAIN: f64 = 0.5;

impl Problem {
    /// This problem with the triangles `marked` bisected on all three edges (and the conforming closure),
    /// T_H refined where the FE edges under it were (keeping this problem's ratio H/h), solved from
    /// `solution`'s multipliers.
    ///
    /// # Errors
    /// [`Error::BadSetting`] named `solution` when `solution` is not of this problem; those of
    /// [`Friction::validate`] for this problem's dofs; [`Error::MemoryBudget`] when the factorization this
    /// problem holds ([`Problem::held_bytes`]) leaves less than 1 MiB of `settings.memory_budget` (the
    /// enriched solve has the rest); those of [`crate::mesh::refine::bisect`], of the new problem and of
    /// its solve.
    pub fn solve_enriched(
        &self,
        solution: &Solution,
        marked: &[usize],
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<(Problem, Solution)> {
        self.solve_built(solution, friction, settings, |p| p.enriched(&[solution], marked))
    }

    /// [`Problem::solve_enriched`] with the enrichment of the hierarchical estimate ([`crate::adapt::enriched`]):
    /// the triangles `first` bisected (all of them for the estimate), then the triangles within half a contact width
    /// of `solution`'s contact zone on that mesh bisected again (nothing more where nothing touches).
    ///
    /// # Errors
    /// Those of [`Problem::solve_enriched`].
    pub fn solve_enriched_twice(
        &self,
        solution: &Solution,
        first: &[usize],
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<(Problem, Solution)> {
        self.solve_built(solution, friction, settings, |p| p.enriched_twice(&[solution], first))
    }

    /// Builds the enriched problem with `build` and solves it from `solution`'s multipliers (the checks and the
    /// budget of [`Problem::solve_enriched`]).
    pub(super) fn solve_built(
        &self,
        solution: &Solution,
        friction: &Friction,
        settings: &SolverSettings,
        build: impl FnOnce(&Problem) -> Result<Problem>,
    ) -> Result<(Problem, Solution)> {
        self.check_solution_of(solution)?;
        friction.validate(self.n_multipliers())?;
        // This problem's factorization stays held beside the enriched one's: the budget bounds their sum.
        let held = self.held_bytes();
        let memory_budget = crate::settings::memory::left_beside(settings.memory_budget, held, || {
            format!(
                "the enriched problem, beside the factorization this problem holds ({} bytes),",
                crate::error::Num(held)
            )
        })?;
        let enriched = build(self)?;
        let start = [self.carried(&solution.lambda_n, &enriched), self.carried(&solution.lambda_t, &enriched)].concat();
        let friction = self.carried_friction(friction, &enriched);
        // (the enriched answer measures the error of `solution`: no check of its own by a second Coulomb method)
        let settings = SolverSettings { coulomb_check: false, memory_budget, ..*settings };
        let answer = super::solve_level(&enriched, &friction, &settings, Some(&start))?;
        Ok((enriched, answer))
    }

    /// Refuses `solution` when it is not a solution of this problem (its multiplier dofs, Γ_C nodes or
    /// displacements are not as many as this problem's): the estimates read it at this problem's dofs.
    ///
    /// # Errors
    /// [`Error::BadSetting`] named `solution`.
    pub(super) fn check_solution_of(&self, solution: &Solution) -> Result<()> {
        let nodes = *self.pair_node_offsets().last().unwrap_or(&0);
        let (q, dofs) = (self.n_multipliers(), 2 * self.mesh.n_nodes());
        let multipliers = [solution.lambda_n.len(), solution.lambda_t.len(), solution.states.len()];
        if multipliers.iter().all(|&n| n == q)
            && solution.node_abscissae.len() == nodes
            && solution.displacement.len() == dofs
        {
            return Ok(());
        }
        Err(Error::BadSetting {
            name: "solution",
            value: solution.lambda_n.len() as f64,
            what: format!(
                "is not a solution of this problem: it has {} multiplier dofs, {} Γ_C nodes and {} displacements, \
                 the problem {q}, {nodes} and {dofs}",
                solution.lambda_n.len(),
                solution.node_abscissae.len(),
                solution.displacement.len()
            ),
        })
    }

    /// This problem with the triangles `marked` bisected on all three edges (and the conforming closure), T_H
    /// refined where the FE edges under it were (keeping this problem's ratio H/h) where any of `solutions`
    /// touches or may touch. The new nodes stay on the chords of a curved edge set ([`crate::Mesh::with_curve`]):
    /// the enriched Γ_C keeps this problem's arclength, so that λ_H and λ_f are compared at the same abscissae;
    /// the sag that leaves, h²/8R of the finer edges, is of second order next to the error measured. The sets
    /// keep their curves all the same: the gap of a bent pair is that of its curves on both meshes (on the
    /// chords' new nodes it would take their sag, of the order of a shrink fit's interference).
    pub(super) fn enriched(&self, solutions: &[&Solution], marked: &[usize]) -> Result<Problem> {
        let apart = super::multipliers::surely_apart(self, solutions);
        self.bisected(self, marked, self.level_ratio(solutions), &apart)
    }

    /// This problem with the triangles `first` bisected ([`Problem::enriched`]), then, on that mesh, the strip of
    /// half a contact width of `solutions` ([`strip_on`]) bisected again, T_H refined alike both times (this
    /// problem's ratio H/h, not where `solutions` are surely apart): the enrichment of the hierarchical estimate
    /// (the module documentation). Where nothing touches, `first` bisected once.
    pub(super) fn enriched_twice(&self, solutions: &[&Solution], first: &[usize]) -> Result<Problem> {
        let (ratio, apart) = (self.level_ratio(solutions), super::multipliers::surely_apart(self, solutions));
        let once = self.bisected(self, first, ratio, &apart)?;
        let second = strip_on(self, solutions, &once, STRIP_AGAIN);
        if second.is_empty() {
            return Ok(once);
        }
        self.bisected(&once, &second, ratio, &apart)
    }

    /// This problem (an enriched one, with `solutions` its answers) with the triangles `near` the ends of Γ_C bisected
    /// and then those near the same ends (`regions` of `base`, the problem it enriched) bisected again: the ends are
    /// bisected twice, as the first enrichment bisected them, so that the two reductions compare alike.
    pub(super) fn enriched_at_ends(
        &self,
        solutions: &[&Solution],
        near: &[usize],
        base: &Problem,
        regions: &[EndRegion],
    ) -> Result<Problem> {
        let once = self.enriched(solutions, near)?;
        let again = near_ends(base, &once, regions);
        let apart = super::multipliers::surely_apart(self, solutions);
        self.bisected(&once, &again, self.level_ratio(solutions), &apart)
    }

    /// The level's ratio H/h where contact is in any of `solutions`, or a Tresca threshold acts: a T_H kept where the
    /// body is surely apart may be coarser than the FE edges refined under it there, and their ratio would leave T_H
    /// unhalved in the strip.
    pub(super) fn level_ratio(&self, solutions: &[&Solution]) -> f64 {
        let spans: Vec<(f64, f64)> = solutions.iter().filter_map(|s| first_pair_span(self, s)).collect();
        let held = super::multipliers::tresca_held(solutions);
        let period = if self.contact.is_closed() { self.contact.length() } else { f64::INFINITY };
        // A segment holds a span it overlaps, or a single touching dof at one of its ends (a point span).
        let holds = |a: f64, b: f64, lo: f64, hi: f64| if lo < hi { b > lo && a < hi } else { b >= lo && a <= hi };
        let overlaps =
            |a: f64, b: f64, (lo, hi): (f64, f64)| holds(a, b, lo, hi) || holds(a, b, lo + period, hi + period);
        let in_contact = |a: f64, b: f64| {
            spans.iter().any(|&span| overlaps(a, b, span)) || super::multipliers::holds_any(&held, a, b)
        };
        super::multipliers::ratio_over(&self.multipliers.xi, &self.contact, in_contact)
    }

    /// `of` (this problem, or this problem enriched) with the triangles `marked` bisected on their three edges,
    /// its T_H refined where the FE edges under it were, keeping `ratio`, except where `apart` (abscissae of this
    /// problem's Γ_C, which `of` keeps). The new nodes stay on the chords of a curved edge set
    /// ([`Problem::enriched`]).
    pub(super) fn bisected(
        &self,
        of: &Problem,
        marked: &[usize],
        ratio: f64,
        apart: &dyn Fn(f64, f64) -> bool,
    ) -> Result<Problem> {
        let refined =
            bisect(&of.mesh.without_curves(), marked, Bisection::AllEdges)?.with_curves(of.mesh.curves().clone());
        super::multipliers::next_problem_with(of, refined, ratio, apart)
    }

    /// The W_H function of each pair of this problem's dof values `v` (stacked over the pairs) at the multiplier
    /// dofs of `to` (this problem refined or enriched), stacked alike.
    pub(super) fn carried(&self, v: &[f64], to: &Problem) -> Vec<f64> {
        super::multipliers::carried(self, to, v)
    }

    /// `friction` for the problem `to`: a Tresca threshold given per dof carried as the W_H function it
    /// defines.
    pub(super) fn carried_friction(&self, friction: &Friction, to: &Problem) -> Friction {
        match friction {
            Friction::Tresca(Threshold::PerDof(g)) => Friction::Tresca(Threshold::PerDof(self.carried(g, to))),
            other => other.clone(),
        }
    }
}
