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

impl Solution {
    /// The zone of the dofs accepted by `keep` (see the module documentation).
    fn zone_of(&self, keep: impl Fn(ContactState) -> bool) -> Option<Zone> {
        let ends = match (self.node_abscissae.first(), self.node_abscissae.last()) {
            (Some(&a), Some(&b)) => [a, b],
            _ => return None,
        };
        zone(&self.multiplier_abscissae, ends, &self.states, keep)
    }

    /// The contact zone: the dofs not in separation, from the first to the last (`None` when nothing
    /// touches).
    pub fn contact_zone(&self) -> Option<Zone> {
        self.zone_of(|s| s != ContactState::Separation)
    }

    /// The stick zone: the dofs that stick, from the first to the last (`None` when none sticks).
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
    fn a_zone_that_reaches_an_end_of_the_contact_side_ends_there() {
        // P0 dofs at cell midpoints: the zone reaches the side's end, uncertain by the half cell to it.
        let x = [0.5, 1.5, 2.5];
        let z = zone(&x, [0.0, 3.0], &[S, S, O], |s| s != O).unwrap();
        assert_eq!((z.lo, z.hi, z.resolution), (0.0, 2.0, 1.0));
        let all = zone(&x, [0.0, 3.0], &[S, L, S], |s| s != O).unwrap();
        assert_eq!((all.width(), all.resolution), (3.0, 1.0));
    }
}
