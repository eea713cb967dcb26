//! The L²(Γ_C) difference of the multipliers of two problems on one Γ_C line, each on its own T_H: what the
//! hierarchical estimate ([`crate::adapt::enriched`]) and the studies' true errors measure. In axisymmetry
//! the norm is over the surface of revolution (`2π r ds`), as every Γ_C integral is.

use crate::contact::mortar::GAUSS2;
use crate::fem::axisymmetric::radial_weight;
use crate::problem::Problem;
use crate::results::Solution;

/// The L²(Γ_C) norms of `λ_a − λ_b` and of `λ_b`, normal and tangential together, for the multipliers
/// of two problems on one Γ_C line (each on its own T_H): Gauss on the union of both T_H's points,
/// exact for piecewise linear multipliers. Beyond a T_H a multiplier is 0. NaN (both) where a solution is not of
/// its problem (not as many multiplier values as the problem's dofs), or where a problem has several contact pairs
/// (their sides are not one line).
pub fn multiplier_difference(a: &Problem, sa: &Solution, b: &Problem, sb: &Solution) -> (f64, f64) {
    multiplier_difference_on(a, sa, b, sb, f64::NEG_INFINITY, f64::INFINITY)
}

/// [`multiplier_difference`] on the part `[lo, hi]` of the Γ_C line.
pub fn multiplier_difference_on(
    a: &Problem,
    sa: &Solution,
    b: &Problem,
    sb: &Solution,
    lo: f64,
    hi: f64,
) -> (f64, f64) {
    // A solution of another problem (its multipliers not as many as the problem's) has no difference here.
    let fits =
        |p: &Problem, s: &Solution| s.lambda_n.len() == p.n_multipliers() && s.lambda_t.len() == p.n_multipliers();
    if !fits(a, sa) || !fits(b, sb) || !a.sides.is_empty() || !b.sides.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let (xa, xb) = (&a.multipliers.xi, &b.multipliers.xi);
    // In axisymmetry the measure 2π r is linear on each FE edge of b's Γ_C: its nodes are breakpoints too.
    let radial = b.spec.model.is_axisymmetric();
    let fe: &[f64] = if radial { &b.contact.node_xi } else { &[] };
    let mut breaks: Vec<f64> = xa.iter().chain(xb).chain(fe).copied().filter(|x| *x > lo && *x < hi).collect();
    breaks.extend([lo, hi].into_iter().filter(|x| x.is_finite()));
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
    // Squared in units of the largest |λ|, so that no unit of stress overflows or underflows the squares
    // (defect D27); the values are linear in λ.
    let values = [&sa.lambda_n, &sa.lambda_t, &sb.lambda_n, &sb.lambda_t];
    let scale = values.iter().flat_map(|v| v.iter()).fold(0.0_f64, |m, x| m.max(x.abs()));
    let scale = if scale > 0.0 && scale.is_finite() { scale } else { 1.0 };
    let (mut diff, mut norm) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[0] + w[1]));
        for &(g, wg) in &GAUSS2 {
            let x = mid + half * g;
            let wg = if radial { wg * radial_weight(b.contact.point_at(x)[0]) } else { wg };
            let (na, ta) = (at(a, &sa.lambda_n, x) / scale, at(a, &sa.lambda_t, x) / scale);
            let (nb, tb) = (at(b, &sb.lambda_n, x) / scale, at(b, &sb.lambda_t, x) / scale);
            diff += wg * half * ((na - nb).powi(2) + (ta - tb).powi(2));
            norm += wg * half * (nb * nb + tb * tb);
        }
    }
    (scale * diff.sqrt(), scale * norm.sqrt())
}
