//! The enriched problem of a solve and the difference of two multipliers on Γ_C: the pieces of a
//! hierarchical estimate of the traction error (`‖λ_H − λ_f‖`, λ_f the answer of the same problem on a
//! mesh bisected near the contact zone, with T_H halved there).

use crate::contact::mortar::GAUSS2;
use crate::error::Result;
use crate::mesh::refine::bisect;
use crate::problem::Problem;
use crate::results::Solution;
use crate::settings::friction::Friction;
use crate::settings::{Bisection, SolverSettings};

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

/// The triangles within `width` of the contact zone of `solution` (the span of T_H cells where λ_n ≠ 0),
/// the distance taken from a triangle's nearest vertex to that segment of the Γ_C line. All triangles
/// when `width` is infinite; none when nothing touches.
pub fn near_contact(problem: &Problem, solution: &Solution, width: f64) -> Vec<usize> {
    let m = &problem.multipliers;
    let dofs = m.dof_abscissae();
    let touching: Vec<f64> = dofs.iter().zip(&solution.lambda_n).filter(|(_, l)| **l != 0.0).map(|(x, _)| *x).collect();
    let (Some(lo), Some(hi)) = (touching.iter().copied().reduce(f64::min), touching.iter().copied().reduce(f64::max))
    else {
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

impl Problem {
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
        let answer = super::solve_level(&enriched, friction, settings, Some(&start))?;
        Ok((enriched, answer))
    }
}
