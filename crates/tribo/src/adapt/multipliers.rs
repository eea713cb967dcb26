//! The multiplier mesh of the next level: T_H is refined where the FE edges under it were, keeping the
//! ratio H/h of the first level, but only where contact is or may be. Multipliers cost solve time, so
//! where the body is surely apart from the obstacle T_H stays as it was.

use crate::contact::ContactBoundary;

/// The ratio H/h of a multiplier mesh over the FE edges of Γ_C: the largest, over the segments of T_H,
/// of the segment's length over the shortest FE edge it overlaps (1 for T_H on the FE edges).
pub(crate) fn ratio(xi: &[f64], contact: &ContactBoundary) -> f64 {
    xi.windows(2)
        .map(|w| w[1] - w[0])
        .zip(xi.windows(2))
        .fold(0.0_f64, |r, (len, w)| r.max(len / shortest_under(contact, w[0], w[1])))
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
