//! The contact zone and the stick zone of a solution, and their widths.
//!
//! A zone is read from the contact states of the multiplier dofs ([`Solution::states`]): the dofs a state
//! test accepts, from the first to the last. Between an accepted dof and its rejected neighbour the
//! discrete answer says only that the zone ends somewhere between them, so the zone ends at the **midpoint**
//! of the two (as [`crate::History::stick_slip_boundaries`] places a stick–slip boundary), and it is uncertain
//! by half their distance at each end: [`Zone::resolution`], the sum of both halves. Where the accepted dofs
//! reach the first or last dof, the zone ends at that end of Γ_C (the first or last FE node), and that end
//! is uncertain by the distance from the dof to it. The width is the span `hi − lo` (holes inside a zone,
//! e.g. two separate contact zones, are counted in it).
//!
//! On a closed Γ_C (a loop, [`Solution::closed`]) the abscissae wrap with the loop's length L and there is
//! no first dof: the zone is the shortest arc that holds every accepted dof, the loop less its largest run
//! of rejected dofs (so holes smaller than that run are counted, as on an open side). A zone that crosses
//! the loop's cut begins before Γ_C's start: `lo < start`, the arc from `lo + L` through the cut to `hi`.
//! Where every dof is accepted the zone is the whole loop, placed exactly (resolution 0).

use crate::results::{ContactState, Solution};

/// A zone of Γ_C, as abscissae.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// Where it begins (the midpoint between its first dof and the dof before it).
    pub lo: f64,
    /// Where it ends.
    pub hi: f64,
    /// How far its width may be off from the dofs' spacing alone: half the distance to the neighbouring
    /// dof at each end, summed (see the module documentation).
    pub resolution: f64,
}

impl Zone {
    /// `hi − lo`.
    pub fn width(&self) -> f64 {
        self.hi - self.lo
    }
}

/// The zone of the dofs at `abscissae` (increasing) whose `states` `keep` accepts, on a Γ_C from
/// `ends[0]` to `ends[1]`; `None` when it accepts none. Only the dofs that have both an abscissa and a
/// state are read.
pub fn zone(
    abscissae: &[f64],
    ends: [f64; 2],
    states: &[ContactState],
    keep: impl Fn(ContactState) -> bool,
) -> Option<Zone> {
    let n = abscissae.len().min(states.len());
    let (abscissae, states) = (&abscissae[..n], &states[..n]);
    let first = states.iter().position(|&s| keep(s))?;
    let last = states.iter().rposition(|&s| keep(s))?;
    let (lo, lo_half) = match first.checked_sub(1) {
        Some(before) => {
            let half = 0.5 * (abscissae[first] - abscissae[before]);
            (abscissae[first] - half, half)
        }
        None => (ends[0].min(abscissae[first]), (abscissae[first] - ends[0]).abs()),
    };
    let (hi, hi_half) = match abscissae.get(last + 1) {
        Some(&after) => {
            let half = 0.5 * (after - abscissae[last]);
            (abscissae[last] + half, half)
        }
        None => (ends[1].max(abscissae[last]), (ends[1] - abscissae[last]).abs()),
    };
    Some(Zone { lo, hi, resolution: lo_half + hi_half })
}

/// The shortest arc of a loop that holds every dof `accepted` takes (of `n`, in the order of their
/// abscissae `at`, wrapping with `period`): its first and last dof, the first after the last where it crosses
/// the cut; `None` when none is accepted. The loop less its largest run of rejected dofs, measured between the
/// accepted dofs around it (on a tie, the run across the cut, so that the arc does not cross it; then the first).
pub(crate) fn loop_arc(
    n: usize,
    at: impl Fn(usize) -> f64,
    period: f64,
    accepted: impl Fn(usize) -> bool,
) -> Option<(usize, usize)> {
    let kept: Vec<usize> = (0..n).filter(|&k| accepted(k)).collect();
    let (&first, &last) = (kept.first()?, kept.last()?);
    // The gap after each accepted dof to the next one (circularly); the arc begins after the largest.
    let mut best = (at(first) + period - at(last), last, first);
    for w in kept.windows(2) {
        let gap = at(w[1]) - at(w[0]);
        if gap > best.0 {
            best = (gap, w[0], w[1]);
        }
    }
    Some((best.2, best.1))
}

/// The first and last abscissae of the dofs `accepted` takes (of those at `x`, increasing), `None` for none; on a
/// closed Γ_C (`period` its length) the shortest arc that holds them ([`loop_arc`]), beginning a period early where
/// it crosses the cut.
pub(crate) fn dof_span(x: &[f64], period: Option<f64>, accepted: impl Fn(usize) -> bool) -> Option<(f64, f64)> {
    if let Some(period) = period {
        return loop_arc(x.len(), |k| x[k], period, accepted)
            .map(|(a, b)| (x[a] - if a > b { period } else { 0.0 }, x[b]));
    }
    let picked = (0..x.len()).filter(|&k| accepted(k)).map(|k| x[k]);
    picked.fold(None, |span, v| Some(span.map_or((v, v), |(lo, hi): (f64, f64)| (lo.min(v), hi.max(v)))))
}

/// The zone of the dofs at `abscissae` (increasing) whose `states` `keep` accepts, on a closed Γ_C from
/// `ends[0]` round to `ends[1]` (the same point; see the module documentation); `None` when it accepts none.
pub fn loop_zone(
    abscissae: &[f64],
    ends: [f64; 2],
    states: &[ContactState],
    keep: impl Fn(ContactState) -> bool,
) -> Option<Zone> {
    let n = abscissae.len().min(states.len());
    let period = ends[1] - ends[0];
    let (first, last) = loop_arc(n, |k| abscissae[k], period, |k| keep(states[k]))?;
    if (0..n).all(|k| keep(states[k])) {
        return Some(Zone { lo: ends[0], hi: ends[1], resolution: 0.0 });
    }
    // The dofs on either side of the arc are rejected; their distance wraps across the cut.
    let before = (first + n - 1) % n;
    let lo_half = 0.5 * (abscissae[first] - abscissae[before]).rem_euclid(period);
    let hi_half = 0.5 * (abscissae[(last + 1) % n] - abscissae[last]).rem_euclid(period);
    let shift = if first > last { period } else { 0.0 };
    let (lo, hi) = (abscissae[first] - shift - lo_half, abscissae[last] + hi_half);
    // An end midway to a dof across the cut may lie beyond Γ_C's end: the arc read a period earlier.
    let back = if hi > ends[1] { period } else { 0.0 };
    Some(Zone { lo: lo - back, hi: hi - back, resolution: lo_half + hi_half })
}

impl Solution {
    /// Γ_C's length where it is a closed loop (the period of its abscissae), `None` on an open side (the first
    /// pair's, [`Solution::pairs`]).
    pub fn loop_length(&self) -> Option<f64> {
        let nodes = self.pairs.first().map_or(0..self.node_abscissae.len(), |p| p.nodes.clone());
        let x = &self.node_abscissae[nodes];
        self.closed.then(|| Some(x.last()? - x.first()?)).flatten()
    }

    /// The zone of the first pair's dofs accepted by `keep` (see the module documentation).
    fn zone_of(&self, keep: impl Fn(ContactState) -> bool) -> Option<Zone> {
        self.pair_zone(0, keep)
    }

    /// The zone of pair `k`'s dofs accepted by `keep`, on its own side ([`crate::PairResult`]; the whole of Γ_C for
    /// a solution without pairs).
    pub fn pair_zone(&self, k: usize, keep: impl Fn(ContactState) -> bool) -> Option<Zone> {
        let (dofs, nodes, closed) = match self.pairs.get(k) {
            Some(p) => (p.multipliers.clone(), p.nodes.clone(), p.closed),
            None if k == 0 => (0..self.states.len(), 0..self.node_abscissae.len(), self.closed),
            None => return None,
        };
        let x = &self.node_abscissae[nodes];
        let ends = [*x.first()?, *x.last()?];
        let (abscissae, states) = (&self.multiplier_abscissae[dofs.clone()], &self.states[dofs]);
        if closed {
            return loop_zone(abscissae, ends, states, keep);
        }
        zone(abscissae, ends, states, keep)
    }

    /// The contact zone of the first pair: the dofs not in separation, from the first to the last (on a closed Γ_C the
    /// shortest arc that holds them, which may begin before the start: the module documentation; `None` when nothing
    /// touches).
    pub fn contact_zone(&self) -> Option<Zone> {
        self.zone_of(|s| s != ContactState::Separation)
    }

    /// The stick zone of the first pair: the dofs that stick, from the first to the last (on a loop, as
    /// [`Solution::contact_zone`]; `None` when none sticks).
    pub fn stick_zone(&self) -> Option<Zone> {
        self.zone_of(|s| s == ContactState::Stick)
    }

    /// The width of [`Solution::contact_zone`] (0 when nothing touches).
    pub fn contact_width(&self) -> f64 {
        self.contact_zone().map_or(0.0, |z| z.width())
    }

    /// The width of [`Solution::stick_zone`] (0 when none sticks).
    pub fn stick_width(&self) -> f64 {
        self.stick_zone().map_or(0.0, |z| z.width())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ContactState::{Separation as O, Slip as L, Stick as S};

    #[test]
    fn a_zone_ends_midway_to_the_first_dof_outside_it() {
        let x = [0.0, 1.0, 2.0, 4.0, 5.0, 6.0];
        let z = zone(&x, [0.0, 6.0], &[O, L, S, S, L, O], |s| s != O).unwrap();
        assert_eq!((z.lo, z.hi, z.resolution), (0.5, 5.5, 1.0));
        let stick = zone(&x, [0.0, 6.0], &[O, L, S, S, L, O], |s| s == S).unwrap();
        assert_eq!((stick.lo, stick.hi, stick.width(), stick.resolution), (1.5, 4.5, 3.0, 1.0));
        assert!(zone(&x, [0.0, 6.0], &[O; 6], |s| s != O).is_none());
    }

    #[test]
    fn a_zone_on_a_loop_may_cross_its_cut() {
        // Dofs at 0, 1, …, 7 on a loop of length 8: the zone 6, 7, 0, 1 crosses the cut at 0 ≡ 8.
        let x: Vec<f64> = (0..8).map(f64::from).collect();
        let z = loop_zone(&x, [0.0, 8.0], &[S, L, O, O, O, O, L, S], |s| s != O).unwrap();
        assert_eq!((z.lo, z.hi, z.width(), z.resolution), (-2.5, 1.5, 4.0, 1.0));
        // As an open side it would read the whole side.
        assert_eq!(zone(&x, [0.0, 8.0], &[S, L, O, O, O, O, L, S], |s| s != O).unwrap().width(), 8.0);
        // Not crossing the cut, it reads as on an open side; a small hole is counted, the largest is not.
        let inner = loop_zone(&x, [0.0, 8.0], &[O, L, S, O, S, O, O, O], |s| s != O).unwrap();
        assert_eq!((inner.lo, inner.hi, inner.resolution), (0.5, 4.5, 1.0));
        // The zone's first dof at the cut: its lower end lies across it.
        let at_cut = loop_zone(&x, [0.0, 8.0], &[S, S, O, O, O, O, O, O], |s| s != O).unwrap();
        assert_eq!((at_cut.lo, at_cut.hi), (-0.5, 1.5));
        // Every dof touching: the whole loop, exactly.
        let all = loop_zone(&x, [0.0, 8.0], &[S; 8], |s| s != O).unwrap();
        assert_eq!((all.lo, all.hi, all.resolution), (0.0, 8.0, 0.0));
        assert!(loop_zone(&x, [0.0, 8.0], &[O; 8], |s| s != O).is_none());
        // The last dof alone, its neighbour across the cut far: the zone's end lies beyond Γ_C's end, so the arc is
        // read a period earlier.
        let far = loop_zone(&[1.5, 2.0, 3.0, 4.5], [0.0, 5.0], &[O, O, O, S], |s| s != O).unwrap();
        assert_eq!((far.lo, far.hi, far.width()), (-1.25, 0.5, 1.75));
        // A tie between the run across the cut and another: the arc does not cross the cut.
        assert_eq!(dof_span(&[0.0, 1.0, 2.0, 3.0], Some(4.0), |_| true), Some((0.0, 3.0)));
        assert_eq!(dof_span(&[0.0, 1.0, 2.0, 3.0], Some(4.0), |k| k != 1), Some((2.0 - 4.0, 0.0)));
    }

    #[test]
    fn a_zone_that_reaches_an_end_of_the_contact_side_ends_there() {
        // P0 dofs at cell midpoints: the zone reaches the side's end, uncertain by the half cell to it.
        let x = [0.5, 1.5, 2.5];
        let z = zone(&x, [0.0, 3.0], &[S, S, O], |s| s != O).unwrap();
        assert_eq!((z.lo, z.hi, z.resolution), (0.0, 2.0, 1.0));
        let all = zone(&x, [0.0, 3.0], &[S, L, S], |s| s != O).unwrap();
        assert_eq!((all.width(), all.resolution), (3.0, 1.0));
    }
}
