//! Where the hierarchical estimate ([`crate::adapt::enriched`]) enriches: the strip of triangles along each contact
//! pair's contact zone, and the regions at the ends of a pair's side that the zone reaches (where the reduction is
//! measured). Every pair is read on its own side, from its own multiplier dofs of a solution ([`crate::PairResult`]).

use crate::problem::sides::PairParts;
use crate::problem::Problem;
use crate::results::{dof_span, ContactState, Solution};

/// The region R of an end of a pair's side where its contact zone reaches it: the two T_H cells at that end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct EndRegion {
    /// The pair (in the order of [`Problem::pairs`]).
    pub(super) pair: usize,
    /// The abscissae of R on the pair's side.
    pub(super) span: [f64; 2],
    /// The abscissa of the end.
    pub(super) end: f64,
}

impl EndRegion {
    /// This region shrunk toward its end to `factor` of its length: where the third enrichment at an end is made
    /// (a quarter: the second quartered the cells there, the third quarters them again within a quartered radius).
    pub(super) fn toward_end(self, factor: f64) -> Self {
        let length = factor * (self.span[1] - self.span[0]);
        let span = if self.end <= self.span[0] { [self.end, self.end + length] } else { [self.end - length, self.end] };
        Self { span, ..self }
    }
}

/// Each pair of `problem` with its part of the multiplier states of `solution` (empty where the solution has fewer).
fn pairs_and_states<'a>(problem: &'a Problem, solution: &'a Solution) -> Vec<(PairParts<'a>, &'a [ContactState])> {
    let offsets = problem.pair_offsets();
    let states = |k: usize| solution.states.get(offsets[k]..offsets[k + 1]).unwrap_or(&[]);
    problem.pairs().into_iter().enumerate().map(|(k, pair)| (pair, states(k))).collect()
}

/// The first and last abscissae of a pair's multiplier dofs not in separation (`states`, the pair's part of
/// [`Solution::states`]: an interior-point answer has no exact zeros), `None` when none touches. On a closed side
/// the shortest arc that holds them, beginning before its start where it crosses the cut.
fn touching_span(pair: &PairParts<'_>, states: &[ContactState]) -> Option<(f64, f64)> {
    let period = pair.contact.is_closed().then(|| pair.contact.length());
    let touching = |k: usize| states.get(k).is_some_and(|&c| c != ContactState::Separation);
    dof_span(&pair.multipliers.dof_abscissae(), period, touching)
}

/// The span of the first pair's multiplier dofs not in separation in `solution` (see [`touching_span`]).
pub(super) fn first_pair_span(problem: &Problem, solution: &Solution) -> Option<(f64, f64)> {
    let (pair, states) = pairs_and_states(problem, solution).into_iter().next()?;
    touching_span(&pair, states)
}

/// The contact zone of pair `k` in `solution`: the span of its multiplier dofs not in separation, out to the T_H
/// points on either side of it ([`touching_span`], [`neighbouring_points`]); `None` where none touches.
pub(super) fn pair_span(problem: &Problem, solution: &Solution, k: usize) -> Option<(f64, f64)> {
    let (pair, states) = pairs_and_states(problem, solution).into_iter().nth(k)?;
    touching_span(&pair, states).map(|span| neighbouring_points(&pair, span))
}

/// The T_H points of a pair on either side of the span `(lo, hi)` of its multiplier dofs
/// ([`crate::MultiplierMesh::points_around`]).
fn neighbouring_points(pair: &PairParts<'_>, span: (f64, f64)) -> (f64, f64) {
    pair.multipliers.points_around(span, pair.contact.is_closed())
}

/// The width of the strip along a pair's contact zone `span`: the span itself ([`Solution::contact_width`] less the
/// half cells at its ends), or where one dof touches, the span of the T_H points on either side of it (a window of
/// two cells).
fn strip_width(pair: &PairParts<'_>, (lo, hi): (f64, f64)) -> f64 {
    if hi > lo {
        return hi - lo;
    }
    let (below, above) = neighbouring_points(pair, (lo, hi));
    above - below
}

/// Marks the triangles of `problem` within `width` of a pair's contact zone `span` (reaching the neighbouring T_H
/// points, where a P1 multiplier is not yet zero), the distance taken from a triangle's nearest vertex to that part
/// of the pair's side.
fn mark_near(problem: &Problem, pair: &PairParts<'_>, span: (f64, f64), width: f64, marked: &mut [bool]) {
    mark_within(problem, pair.contact, neighbouring_points(pair, span), width, marked);
}

/// Marks the triangles of `problem` with a vertex within `width` of the part `(lo, hi)` of the side `contact`.
fn mark_within(
    problem: &Problem,
    contact: &crate::contact::ContactBoundary,
    (lo, hi): (f64, f64),
    width: f64,
    marked: &mut [bool],
) {
    let pts = problem.mesh.points();
    let near = |v: usize| contact.distance_to_span(pts[v], lo, hi) <= width;
    for (t, tri) in problem.mesh.triangles().iter().enumerate() {
        marked[t] |= tri.iter().any(|&v| near(v));
    }
}

/// The marked triangles, in order.
fn marked_list(marked: &[bool]) -> Vec<usize> {
    (0..marked.len()).filter(|&t| marked[t]).collect()
}

/// The triangles within `width` of the contact zone of any contact pair of `solution` (the span of the pair's
/// multiplier dofs not in separation), the distance taken from a triangle's nearest vertex to that part of the
/// pair's side. All triangles when `width` is infinite; none when nothing touches.
pub fn near_contact(problem: &Problem, solution: &Solution, width: f64) -> Vec<usize> {
    let mut marked = vec![false; problem.mesh.n_triangles()];
    for (pair, states) in pairs_and_states(problem, solution) {
        if let Some(span) = touching_span(&pair, states) {
            mark_near(problem, &pair, span, width, &mut marked);
        }
    }
    marked_list(&marked)
}

/// The triangles of `target` (`problem` enriched: the same sides, the same arclength) within `fraction` of the strip
/// width ([`strip_width`]) of each pair's contact zone in any of `solutions` (solutions of `problem`): the second
/// bisection of the hierarchical estimate's enrichment ([`crate::adapt::enriched`]). None when nothing touches.
pub(super) fn strip_on(problem: &Problem, solutions: &[&Solution], target: &Problem, fraction: f64) -> Vec<usize> {
    let mut marked = vec![false; target.mesh.n_triangles()];
    let sides = target.pairs();
    for s in solutions {
        for (k, (pair, states)) in pairs_and_states(problem, s).into_iter().enumerate() {
            if let (Some(span), Some(side)) = (touching_span(&pair, states), sides.get(k)) {
                let width = fraction * strip_width(&pair, span);
                mark_within(target, side.contact, neighbouring_points(&pair, span), width, &mut marked);
            }
        }
    }
    marked_list(&marked)
}

/// The regions R (the two cells of T_H at an end of a pair's side) at each end whose multiplier dof touches in
/// `solution` (not in separation); none on a T_H of fewer than 4 cells, nor on a closed side (a loop has no end:
/// its cut is not one).
pub(super) fn end_regions(problem: &Problem, solution: &Solution) -> Vec<EndRegion> {
    let mut out = Vec::new();
    for (k, (pair, states)) in pairs_and_states(problem, solution).into_iter().enumerate() {
        let xi = &pair.multipliers.xi;
        let dofs = pair.multipliers.dof_abscissae();
        let touches = |x: f64| {
            let nearest = dofs.iter().enumerate().min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()));
            nearest.is_some_and(|(d, _)| states.get(d).is_some_and(|c| *c != ContactState::Separation))
        };
        // Two cells at each end, apart from each other (a T_H of fewer than 4 cells is not measured).
        let n = xi.len();
        if n < 5 || pair.contact.is_closed() {
            continue;
        }
        let ends = [(xi[0], [xi[0], xi[2]]), (xi[n - 1], [xi[n - 3], xi[n - 1]])];
        out.extend(ends.into_iter().filter(|(end, _)| touches(*end)).map(|(end, span)| EndRegion {
            pair: k,
            span,
            end,
        }));
    }
    out
}

/// The triangles of `enriched` (`problem` enriched) within a region's length of its end, for the regions of
/// [`end_regions`].
pub(super) fn near_ends(problem: &Problem, enriched: &Problem, regions: &[EndRegion]) -> Vec<usize> {
    let pairs = problem.pairs();
    let ends: Vec<([f64; 2], f64)> =
        regions.iter().map(|r| (pairs[r.pair].contact.point_at(r.end), r.span[1] - r.span[0])).collect();
    let near_an_end = |v: usize| {
        let p = enriched.mesh.points()[v];
        ends.iter().any(|(end, length)| (p[0] - end[0]).hypot(p[1] - end[1]) <= *length)
    };
    let triangles = enriched.mesh.triangles().iter().enumerate();
    triangles.filter(|(_, t)| t.iter().any(|&v| near_an_end(v))).map(|(t, _)| t).collect()
}
