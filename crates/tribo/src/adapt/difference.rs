//! The L²(Γ_C) difference of the multipliers of two problems on the same contact sides, each on its own T_H: what
//! the hierarchical estimate ([`crate::adapt::enriched`]) and the studies' true errors measure. With several contact
//! pairs, Γ_C is every pair's side: the squares add over the pairs, each pair's difference taken on its own side. In
//! axisymmetry the norm is over the surface of revolution (`2π r ds`), as every Γ_C integral is.

use crate::contact::mortar::GAUSS2;
use crate::fem::axisymmetric::radial_weight;
use crate::problem::sides::PairParts;
use crate::problem::Problem;
use crate::results::Solution;

/// The L²(Γ_C) norms of `λ_a − λ_b` and of `λ_b`, normal and tangential together, for the multipliers of two
/// problems on the same contact sides (each on its own T_H): Gauss on the union of both T_H's points, exact for
/// piecewise linear multipliers, summed in squares over the contact pairs. Beyond a T_H a multiplier is 0. NaN (both)
/// where a solution is not of its problem (not as many multiplier values as the problem's dofs), or where the
/// problems' pairs differ (not as many, or, with several, not on the same edge sets).
pub fn multiplier_difference(a: &Problem, sa: &Solution, b: &Problem, sb: &Solution) -> (f64, f64) {
    let parts: Vec<(f64, f64)> =
        (0..a.pairs().len()).map(|k| pair_difference_on(a, sa, b, sb, k, f64::NEG_INFINITY, f64::INFINITY)).collect();
    if let [one] = parts[..] {
        return one;
    }
    // Added in units of the largest, so that no unit of stress overflows or underflows the squares (defect D27).
    let scale = parts.iter().fold(0.0_f64, |m, (d, n)| m.max(d.abs()).max(n.abs()));
    let scale = if scale > 0.0 && scale.is_finite() { scale } else { 1.0 };
    let sum = |f: fn(&(f64, f64)) -> f64| scale * parts.iter().map(|p| (f(p) / scale).powi(2)).sum::<f64>().sqrt();
    (sum(|p| p.0), sum(|p| p.1))
}

/// [`multiplier_difference`] on the part `[lo, hi]` of the first contact pair's side (the problem's own Γ_C).
pub fn multiplier_difference_on(
    a: &Problem,
    sa: &Solution,
    b: &Problem,
    sb: &Solution,
    lo: f64,
    hi: f64,
) -> (f64, f64) {
    pair_difference_on(a, sa, b, sb, 0, lo, hi)
}

/// [`multiplier_difference`] on the part `[lo, hi]` of pair `pair`'s side (in the order of [`Problem::pairs`]).
pub fn pair_difference_on(
    a: &Problem,
    sa: &Solution,
    b: &Problem,
    sb: &Solution,
    pair: usize,
    lo: f64,
    hi: f64,
) -> (f64, f64) {
    // A solution of another problem (its multipliers not as many as the problem's) has no difference here, nor
    // have problems whose pairs are not on the same edge sets.
    let fits =
        |p: &Problem, s: &Solution| s.lambda_n.len() == p.n_multipliers() && s.lambda_t.len() == p.n_multipliers();
    let (pa, pb) = (a.pairs(), b.pairs());
    // One pair each: one side, whatever its name (a problem and its reference may name it differently).
    let same = pa.len() == pb.len() && (pa.len() == 1 || pa.iter().zip(&pb).all(|(x, y)| x.name == y.name));
    if !fits(a, sa) || !fits(b, sb) || !same || pair >= pa.len() {
        return (f64::NAN, f64::NAN);
    }
    let values = |p: &Problem, s: &Solution| {
        let o = p.pair_offsets();
        let dofs = o[pair]..o[pair + 1];
        (s.lambda_n[dofs.clone()].to_vec(), s.lambda_t[dofs].to_vec())
    };
    let radial = b.spec.model.is_axisymmetric();
    on_side((&pa[pair], values(a, sa)), (&pb[pair], values(b, sb)), radial, lo, hi)
}

/// The difference and norm of [`pair_difference_on`] for one pair's side, from each problem's part of it and its
/// normal and tangential multiplier values.
fn on_side(
    (a, (na, ta)): (&PairParts<'_>, (Vec<f64>, Vec<f64>)),
    (b, (nb, tb)): (&PairParts<'_>, (Vec<f64>, Vec<f64>)),
    radial: bool,
    lo: f64,
    hi: f64,
) -> (f64, f64) {
    let (xa, xb) = (&a.multipliers.xi, &b.multipliers.xi);
    // In axisymmetry the measure 2π r is linear on each FE edge of b's side: its nodes are breakpoints too.
    let fe: &[f64] = if radial { &b.contact.node_xi } else { &[] };
    let mut breaks: Vec<f64> = xa.iter().chain(xb).chain(fe).copied().filter(|x| *x > lo && *x < hi).collect();
    breaks.extend([lo, hi].into_iter().filter(|x| x.is_finite()));
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let at = |p: &PairParts<'_>, v: &[f64], x: f64| {
        let xi = &p.multipliers.xi;
        if xi.is_empty() || x < xi[0] || x > xi[xi.len() - 1] {
            0.0
        } else {
            p.multipliers.evaluate(v, x)
        }
    };
    // Squared in units of the largest |λ|, so that no unit of stress overflows or underflows the squares
    // (defect D27); the values are linear in λ.
    let scale = [&na, &ta, &nb, &tb].iter().flat_map(|v| v.iter()).fold(0.0_f64, |m, x| m.max(x.abs()));
    let scale = if scale > 0.0 && scale.is_finite() { scale } else { 1.0 };
    let (mut diff, mut norm) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[0] + w[1]));
        for &(g, wg) in &GAUSS2 {
            let x = mid + half * g;
            let wg = if radial { wg * radial_weight(b.contact.point_at(x)[0]) } else { wg };
            let (ua, va) = (at(a, &na, x) / scale, at(a, &ta, x) / scale);
            let (ub, vb) = (at(b, &nb, x) / scale, at(b, &tb, x) / scale);
            diff += wg * half * ((ua - ub).powi(2) + (va - vb).powi(2));
            norm += wg * half * (ub * ub + vb * vb);
        }
    }
    (scale * diff.sqrt(), scale * norm.sqrt())
}
