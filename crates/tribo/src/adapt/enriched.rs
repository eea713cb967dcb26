//! The hierarchical estimate of the traction error: the difference of a solve's multipliers from those of
//! the same problem enriched near the contact zone.
//!
//! # The estimate
//! Let λ_H be the answer, λ_f the answer of the same problem on the mesh whose triangles within one
//! contact width of the contact zone are bisected on their three edges (h halved there, with the
//! conforming closure) and whose T_H is halved where the FE edges under it were, and
//! `d = ‖λ_H − λ_f‖_{L²(Γ_C)}` (normal and tangential together). By the triangle inequality,
//! `(1 − q) e_H ≤ d ≤ (1 + q) e_H` with `e_H = ‖λ − λ_H‖` and `q = e_f / e_H` the reduction of the error by
//! the enrichment. The *saturation assumption* of hierarchical estimators (Bank and Weiser 1985; Bank and
//! Smith 1993; Dörfler and Nochetto 2002 on when it holds; for obstacle problems Zou, Veeser, Kornhuber
//! and Gräser 2011) is that q stays below a constant q₀ < 1; then `d / (1 − q₀)` bounds e_H, with an
//! effectivity in `[1, (1 + q₀) / (1 − q₀)]`. Here `q₀ = 1/2`: the L² error of a P1 (or P0) multiplier
//! converges like h near the edge of a contact zone, where λ behaves like a square root (the best
//! approximation of `√x` on a cell of size h has an L² error of order h over that cell), so halving h
//! halves it; on the smooth part it falls faster. Hence the estimate
//!
//! `η_hier = 2 ‖λ_H − λ_f‖_{L²(Γ_C)}`, relative to `‖λ_f‖`.
//!
//! It is no guaranteed bound: where the enrichment removes less than half of the error (a contact edge
//! that the enriched mesh still places in the wrong cell, on the coarsest meshes), it falls below the truth.
//! Measured against a reference of 466k unknowns on adaptive Hertz (study 12, `docs/hierarchical.md`,
//! levels with at least 10 multiplier dofs in contact, 320–74k unknowns): 0.98–2.22 times the true error
//! (28 of 30 levels in [1, 2]), without the drift of the residual bound ζ (effectivity 4 → 20 over the same
//! levels). The strip of one contact width gives the differences of the whole mesh within 11 % at about
//! two thirds of its unknowns (2.6 times the level's).

use crate::contact::mortar::GAUSS2;
use crate::error::Result;
use crate::mesh::refine::bisect;
use crate::problem::Problem;
use crate::results::Solution;
use crate::results::{ContactState, SolveStatus};
use crate::settings::friction::{Friction, Threshold};
use crate::settings::{Bisection, SolverSettings};

/// The hierarchical estimate of one solve ([`Problem::estimate_hierarchical`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hierarchical {
    /// `‖λ_H − λ_f‖` in L²(Γ_C), normal and tangential together.
    pub difference: f64,
    /// `‖λ_f‖` in L²(Γ_C).
    pub norm: f64,
    /// The estimate `2 ‖λ_H − λ_f‖` (the module documentation derives the factor).
    pub estimate: f64,
    /// `estimate / ‖λ_f‖` (NaN when nothing touches in the enriched answer).
    pub relative: f64,
    /// The enriched problem's unknowns.
    pub unknowns: usize,
    /// How the enriched solve ended (the estimate means something only when it converged).
    pub status: SolveStatus,
    /// Wall time of building and solving the enriched problem.
    pub seconds: f64,
}

/// The L²(Γ_C) norms of `λ_a − λ_b` and of `λ_b`, normal and tangential together, for the multipliers
/// of two problems on one Γ_C line (each on its own T_H): Gauss on the union of both T_H's points,
/// exact for piecewise linear multipliers. Beyond a T_H a multiplier is 0.
pub fn multiplier_difference(a: &Problem, sa: &Solution, b: &Problem, sb: &Solution) -> (f64, f64) {
    let (xa, xb) = (&a.multipliers.xi, &b.multipliers.xi);
    let mut breaks: Vec<f64> = xa.iter().chain(xb).copied().collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let at = |p: &Problem, v: &[f64], x: f64| {
        let xi = &p.multipliers.xi;
        if xi.is_empty() || x < xi[0] || x > xi[xi.len() - 1] {
            0.0
        } else {
            p.multipliers.evaluate(v, x)
        }
    };
    let (mut diff, mut norm) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[0] + w[1]));
        for &(g, wg) in &GAUSS2 {
            let x = mid + half * g;
            let (na, ta) = (at(a, &sa.lambda_n, x), at(a, &sa.lambda_t, x));
            let (nb, tb) = (at(b, &sb.lambda_n, x), at(b, &sb.lambda_t, x));
            diff += wg * half * ((na - nb).powi(2) + (ta - tb).powi(2));
            norm += wg * half * (nb * nb + tb * tb);
        }
    }
    (diff.sqrt(), norm.sqrt())
}

/// The triangles within `width` of the contact zone of `solution` (the span of the multiplier dofs not in
/// separation), the distance taken from a triangle's nearest vertex to that segment of the Γ_C line. All
/// triangles when `width` is infinite; none when nothing touches.
pub fn near_contact(problem: &Problem, solution: &Solution, width: f64) -> Vec<usize> {
    let m = &problem.multipliers;
    let Some((lo, hi)) = touching_span(problem, solution) else {
        return Vec::new();
    };
    // The zone reaches the neighbouring T_H points (a P1 multiplier is not zero up to them).
    let lo = m.xi[m.xi.partition_point(|&x| x < lo).saturating_sub(1)];
    let hi = m.xi[m.xi.partition_point(|&x| x <= hi).min(m.xi.len() - 1)];
    let pts = problem.mesh.points();
    let distance = |v: usize| problem.contact.distance_to_span(pts[v], lo, hi);
    problem
        .mesh
        .triangles()
        .iter()
        .enumerate()
        .filter(|(_, tri)| tri.iter().any(|&v| distance(v) <= width))
        .map(|(t, _)| t)
        .collect()
}

/// The first and last abscissae of the multiplier dofs of `solution` not in separation
/// ([`Solution::states`]: an interior-point answer has no exact zeros), `None` when nothing touches.
fn touching_span(problem: &Problem, solution: &Solution) -> Option<(f64, f64)> {
    let dofs = problem.multipliers.dof_abscissae();
    let touching = dofs.iter().zip(&solution.states).filter(|(_, c)| **c != ContactState::Separation);
    touching.fold(None, |span, (&x, _)| Some(span.map_or((x, x), |(lo, hi): (f64, f64)| (lo.min(x), hi.max(x)))))
}

/// The width of the contact zone of `solution` (the span of the multiplier dofs not in separation), 0 when
/// nothing touches.
pub fn contact_width(problem: &Problem, solution: &Solution) -> f64 {
    touching_span(problem, solution).map_or(0.0, |(lo, hi)| hi - lo)
}

impl Problem {
    /// The hierarchical estimate of the traction error of `solution`, a solve of this problem with
    /// `friction` (see the module documentation): the problem enriched within one contact width of the
    /// contact zone (the whole mesh when fewer than two multiplier dofs touch), solved with `settings`
    /// from `solution`'s multipliers. A Tresca threshold given per dof is carried to the enriched T_H as
    /// the W_H function it defines.
    ///
    /// # Errors
    /// Those of [`Problem::solve_enriched`].
    pub fn estimate_hierarchical(
        &self,
        solution: &Solution,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Hierarchical> {
        let clock = std::time::Instant::now();
        let width = contact_width(self, solution);
        let marked =
            if width > 0.0 { near_contact(self, solution, width) } else { (0..self.mesh.n_triangles()).collect() };
        let (enriched, answer) = self.solve_enriched(solution, &marked, friction, settings)?;
        let (difference, norm) = multiplier_difference(self, solution, &enriched, &answer);
        let estimate = 2.0 * difference;
        Ok(Hierarchical {
            difference,
            norm,
            estimate,
            relative: if norm > 0.0 { estimate / norm } else { f64::NAN },
            unknowns: enriched.n_free,
            status: answer.report.status,
            seconds: clock.elapsed().as_secs_f64(),
        })
    }

    /// This problem with the triangles `marked` bisected on all three edges (and the conforming closure),
    /// T_H refined where the FE edges under it were (keeping this problem's ratio H/h), solved from
    /// `solution`'s multipliers.
    ///
    /// # Errors
    /// Those of [`crate::mesh::refine::bisect`], of the new problem and of its solve.
    pub fn solve_enriched(
        &self,
        solution: &Solution,
        marked: &[usize],
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<(Problem, Solution)> {
        let ratio = super::multipliers::ratio(&self.multipliers.xi, &self.contact);
        let refined = bisect(&self.mesh, marked, Bisection::AllEdges)?;
        let enriched = super::next_problem(self, &[solution], refined, ratio)?;
        let dofs = enriched.multipliers.dof_abscissae();
        let at = |v: &[f64]| dofs.iter().map(|&x| self.multipliers.evaluate(v, x)).collect::<Vec<_>>();
        let start = [at(&solution.lambda_n), at(&solution.lambda_t)].concat();
        let friction = match friction {
            Friction::Tresca(Threshold::PerDof(g)) => Friction::Tresca(Threshold::PerDof(at(g))),
            other => other.clone(),
        };
        let answer = super::solve_level(&enriched, &friction, settings, Some(&start))?;
        Ok((enriched, answer))
    }
}
