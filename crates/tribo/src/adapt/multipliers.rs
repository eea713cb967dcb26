//! The multiplier mesh of the next level: T_H is refined where the FE edges under it were, keeping the
//! ratio H/h of the first level, but only where contact is or may be. Multipliers cost solve time, so
//! where the body is surely apart from the obstacle T_H stays as it was (not where a Tresca threshold acts:
//! it acts there too).

use crate::contact::multiplier::MultiplierPoints;
use crate::contact::ContactBoundary;
use crate::error::Result;
use crate::mesh::refine::Refinement;
use crate::problem::Problem;
use crate::results::Solution;
use crate::settings::friction::FrictionLaw;

/// The problem of the next level: the refined mesh, and the first pair's T_H refined where contact is or may be in
/// any of the solutions ([`refine_onto`], keeping its ratio `ratio`), given by its abscissae. A further pair's T_H
/// follows its refined FE edges as its points say (the first pair's ratio or size: a level's problem is made again
/// from its mesh and the first pair's T_H alone, [`Problem::on_level`]).
pub(crate) fn next_problem(
    problem: &Problem,
    solutions: &[&Solution],
    refined: Refinement,
    ratio: f64,
) -> Result<Problem> {
    next_problem_with(problem, refined, ratio, &surely_apart(problem, solutions))
}

/// Whether the segment `(a, b)` of `problem`'s first Γ_C (abscissae) is surely apart in every one of `solutions`:
/// every node of the segment has a current gap beyond the largest displacement on Γ_C (of every pair; the first
/// pair's nodes come first in its fields). The abscissae stay valid on `problem` refined or enriched (the same
/// arclength). Nor is a segment that holds a dof of a positive Tresca threshold ([`tresca_held`]): it acts where
/// nothing touches, and λ_t lives there (on Hertz with a uniform threshold, T_H kept coarse there while the FE mesh
/// was refined under it, the bound grew from 5.6e-2 at 15k unknowns to 0.46 at 82k with the multipliers held at 551,
/// and the loop's memory grew beyond 24 GB).
pub(crate) fn surely_apart<'a>(problem: &'a Problem, solutions: &[&Solution]) -> impl Fn(f64, f64) -> bool + 'a {
    let held = tresca_held(solutions);
    let old = &problem.contact.node_xi;
    let views: Vec<(f64, Vec<f64>)> = solutions
        .iter()
        .map(|s| (s.u_n.iter().chain(&s.slip).fold(0.0_f64, |m, v| m.max(v.abs())), s.current_gap()))
        .collect();
    move |a: f64, b: f64| {
        let lo = old.partition_point(|&x| x < a).saturating_sub(1);
        let hi = old.partition_point(|&x| x <= b).min(old.len() - 1);
        !holds_any(&held, a, b) && views.iter().all(|(scale, gap)| (lo..=hi).all(|k| gap[k] > *scale) && *scale > 0.0)
    }
}

/// The abscissae (sorted) of the first pair's multiplier dofs where the Tresca threshold of any of `solutions` is
/// positive: it acts there whether or not the body touches, and λ_t lives there. None under Coulomb or no friction.
pub(crate) fn tresca_held(solutions: &[&Solution]) -> Vec<f64> {
    let mut held: Vec<f64> = (solutions.iter().filter(|s| s.report.friction == FrictionLaw::Tresca))
        .flat_map(|s| {
            let first = s.pairs.first().map_or(0..s.multiplier_abscissae.len(), |p| p.multipliers.clone());
            first.filter(|&j| s.friction_threshold[j] > 0.0).map(|j| s.multiplier_abscissae[j])
        })
        .collect();
    held.sort_by(f64::total_cmp);
    held
}

/// Whether one of the sorted abscissae `held` lies in `[a, b]`.
pub(crate) fn holds_any(held: &[f64], a: f64, b: f64) -> bool {
    held.get(held.partition_point(|&x| x < a)).is_some_and(|&x| x <= b)
}

/// [`next_problem`] with the segments where T_H stays as it was given by `apart` ([`surely_apart`]).
pub(crate) fn next_problem_with(
    problem: &Problem,
    refined: Refinement,
    ratio: f64,
    apart: &dyn Fn(f64, f64) -> bool,
) -> Result<Problem> {
    let mut spec = problem.spec.clone();
    let contact = ContactBoundary::new(refined.mesh(), &spec.contact)?;
    let xi = refine_onto(&problem.contact, &problem.multipliers.xi, &contact, ratio, apart);
    spec.multiplier_points = MultiplierPoints::Abscissae(xi);
    let (mesh, parent, midpoints) = refined.into_parts();
    problem.refined(mesh, &parent, &midpoints, spec)
}

/// The multipliers `lambda` (2q, stacked over the pairs) of `old` as W_H functions, at the multiplier dofs of `new`
/// (the next level's problem, or `old` enriched), stacked alike: a start for `new`'s solve.
pub(crate) fn carried_start(old: &Problem, new: &Problem, lambda: &[f64]) -> Vec<f64> {
    let q = old.n_multipliers();
    [carried(old, new, &lambda[..q]), carried(old, new, &lambda[q..])].concat()
}

/// Values `v` at `old`'s q multiplier dofs (stacked over the pairs) as the W_H function of each pair, at the
/// multiplier dofs of `new` (each pair's dofs taken back to its side on `old` where refinement moved them), stacked
/// alike.
pub(crate) fn carried(old: &Problem, new: &Problem, v: &[f64]) -> Vec<f64> {
    let offsets = old.pair_offsets();
    let mut out = Vec::with_capacity(new.n_multipliers());
    for (k, (from, to)) in old.pairs().iter().zip(new.pairs()).enumerate() {
        let dofs = abscissae_back(from.contact, to.contact, &to.multipliers.dof_abscissae());
        // Values not as many as the dofs (a user's threshold per dof, say) give NaN, which the solve refuses.
        let own = v.get(offsets[k]..offsets[k + 1]).unwrap_or(&[]);
        out.extend(dofs.iter().map(|&x| from.multipliers.evaluate(own, x)));
    }
    out
}

/// The ratio H/h of a multiplier mesh over the FE edges of Γ_C: the largest, over the segments of T_H,
/// of the segment's length over the shortest FE edge it overlaps (1 for T_H on the FE edges).
pub(crate) fn ratio(xi: &[f64], contact: &ContactBoundary) -> f64 {
    ratio_over(xi, contact, |_, _| true)
}

/// [`ratio`] over the segments `(a, b)` of T_H that `keep` accepts (all where it accepts none).
pub(crate) fn ratio_over(xi: &[f64], contact: &ContactBoundary, keep: impl Fn(f64, f64) -> bool) -> f64 {
    let of = |w: &[f64]| (w[1] - w[0]) / shortest_under(contact, w[0], w[1]);
    let kept = xi.windows(2).filter(|w| keep(w[0], w[1])).fold(f64::NAN, |r, w| r.max(of(w)));
    if kept.is_nan() {
        xi.windows(2).fold(0.0_f64, |r, w| r.max(of(w)))
    } else {
        kept
    }
}

/// The shortest FE edge of Γ_C that overlaps `(a, b)`.
fn shortest_under(contact: &ContactBoundary, a: f64, b: f64) -> f64 {
    let x = &contact.node_xi;
    x.windows(2).filter(|e| e[1] > a && e[0] < b).map(|e| e[1] - e[0]).fold(f64::INFINITY, f64::min)
}

/// The abscissae of the next T_H: every segment of `xi` that is not `apart` is bisected until it is no
/// longer than `ratio` times the shortest FE edge of the refined Γ_C under it (with a relative slack of
/// 1e-9, so a segment that matches its FE edges is not split by round-off); segments `apart` are kept.
pub(crate) fn refine(xi: &[f64], contact: &ContactBoundary, ratio: f64, apart: impl Fn(f64, f64) -> bool) -> Vec<f64> {
    let mut out = vec![xi[0]];
    let mut stack: Vec<(f64, f64)> = Vec::new();
    for w in xi.windows(2) {
        stack.push((w[0], w[1]));
        while let Some((a, b)) = stack.pop() {
            let limit = ratio * shortest_under(contact, a, b) * (1.0 + 1e-9);
            if b - a > limit && !apart(a, b) {
                let m = 0.5 * (a + b);
                // Left half first: the right half waits below it on the stack.
                stack.push((m, b));
                stack.push((a, m));
            } else {
                out.push(b);
            }
        }
    }
    out
}

/// [`refine`] from the T_H `xi` of Γ_C `old` onto the refined Γ_C `new`. On a bent Γ_C whose nodes went onto
/// its curve, T_H is refined in the old abscissae (the new nodes taken there) and carried to the new
/// arclength through the old nodes.
pub(crate) fn refine_onto(
    old: &ContactBoundary,
    xi: &[f64],
    new: &ContactBoundary,
    ratio: f64,
    apart: impl Fn(f64, f64) -> bool,
) -> Vec<f64> {
    let Some(pairs) = moved_abscissae(old, new) else {
        return refine(xi, new, ratio, apart);
    };
    let mut in_old = new.clone();
    in_old.node_xi.iter_mut().for_each(|x| *x = remap(&pairs, *x, false));
    let mut out = refine(xi, &in_old, ratio, apart);
    out.iter_mut().for_each(|x| *x = remap(&pairs, *x, true));
    let last = out.len() - 1;
    (out[0], out[last]) = (new.start(), new.end());
    out
}

/// The abscissae `xi` on the refined Γ_C `new`, taken back to Γ_C `old` (the same where nothing moved).
pub(crate) fn abscissae_back(old: &ContactBoundary, new: &ContactBoundary, xi: &[f64]) -> Vec<f64> {
    let pairs = moved_abscissae(old, new);
    xi.iter().map(|&x| pairs.as_ref().map_or(x, |p| remap(p, x, false))).collect()
}

/// Where refinement moved the nodes of a bent Γ_C (onto its curve, [`crate::Mesh::with_curve`]: its
/// arclength grows), the abscissae of the old nodes on the old and on the new Γ_C, as `(old, new)` pairs in
/// order; `None` on a straight Γ_C, whose abscissae do not move.
pub(crate) fn moved_abscissae(old: &ContactBoundary, new: &ContactBoundary) -> Option<Vec<(f64, f64)>> {
    if new.is_straight() {
        return None;
    }
    // A loop's cut, its first and last node, stays its node of the smallest index: the first maps to the first,
    // the last to the last.
    let (closed, last) = (new.is_closed(), old.nodes.len() - 1);
    let kept = new.nodes.len() - usize::from(closed);
    let index: std::collections::HashMap<usize, usize> =
        new.nodes[..kept].iter().enumerate().map(|(k, &n)| (n, k)).collect();
    // Bisection keeps the coarse nodes and their indices: every old node of Γ_C is a node of the new one.
    let pairs = old.nodes.iter().zip(&old.node_xi).enumerate().filter_map(|(k, (n, &x))| {
        Some((x, if closed && k == last { new.end() } else { new.node_xi[*index.get(n)?] }))
    });
    Some(pairs.collect())
}

/// The piecewise-linear map through `pairs` (increasing in both), from the first coordinate to the second
/// (`forward`) or back, extended beyond the ends with slope 1.
pub(crate) fn remap(pairs: &[(f64, f64)], x: f64, forward: bool) -> f64 {
    let at = |k: usize| if forward { pairs[k] } else { (pairs[k].1, pairs[k].0) };
    let n = pairs.len();
    if n < 2 {
        return pairs.first().map_or(x, |_| x - at(0).0 + at(0).1);
    }
    let k = pairs.partition_point(|p| if forward { p.0 <= x } else { p.1 <= x }).clamp(1, n - 1) - 1;
    let ((x0, y0), (x1, y1)) = (at(k), at(k + 1));
    if x < x0 {
        y0 + (x - x0)
    } else if x > x1 {
        y1 + (x - x1)
    } else {
        y0 + (x - x0) * (y1 - y0) / (x1 - x0)
    }
}
