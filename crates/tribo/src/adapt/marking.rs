//! Which triangles to refine: the indicator of each triangle, made of the energy estimate and the traction
//! estimate in equal parts, and Dörfler or maximum marking on it.

use crate::settings::Marking;
use crate::Solution;

/// The marking indicator per triangle: `m_K = η_K² / Σ η² + ζ_K² / Σ ζ²`, with η_K and ζ_K the largest over
/// `solutions` (one, or the steps of a history) and ζ_K the triangle's part
/// of the traction estimate ([`Solution::traction_estimator`], whose weight falls with the distance to
/// Γ_C, see [`crate::results::ErrorEstimate`]). Each part is a distribution over the triangles summing
/// to 1, so the energy error and the error of the contact tractions steer the refinement with equal
/// weight, whatever their units; where ζ = 0 only the energy part is left. Measured (study 6): marking
/// on ζ alone leaves the far field too coarse and needs more unknowns for 1 % in λ_n than equal parts.
pub(crate) fn indicators(solutions: &[&Solution]) -> Vec<f64> {
    // The largest η_K and ζ_K over the solutions (the steps of a history), over the largest of all and
    // then squared: the parts are ratios, so this changes none of them, and η_K of 1e200 (E = 1e300) or
    // 1e-200 no longer overflows or underflows when squared (defect D27: nothing was marked).
    let largest = |f: fn(&Solution) -> &[f64]| -> Vec<f64> {
        let n = solutions.first().map_or(0, |s| f(s).len());
        let per: Vec<f64> = (0..n).map(|k| solutions.iter().map(|s| f(s)[k]).fold(0.0, f64::max)).collect();
        let top = per.iter().copied().fold(0.0, f64::max);
        if top > 0.0 && top.is_finite() {
            per.iter().map(|v| (v / top).powi(2)).collect()
        } else {
            per.iter().map(|v| v.powi(2)).collect()
        }
    };
    let eta2 = largest(|s| &s.estimator);
    let zeta2 = largest(|s| &s.traction_estimator);
    let (se, sz) = (eta2.iter().sum::<f64>(), zeta2.iter().sum::<f64>());
    let part = |v: f64, total: f64| if total > 0.0 { v / total } else { 0.0 };
    eta2.iter().zip(&zeta2).map(|(e, z)| part(*e, se) + part(*z, sz)).collect()
}

/// Indicators within this relative distance of each other are ties. Two computations of one indicator
/// that differ only in rounding (a mirror image of the mesh, or the problem in other units, D27) differ by
/// a few ε per operation of the sums behind them; 1e-9 leaves room for sums of millions of terms and is
/// far below any difference the marking means to see.
const TIE: f64 = 1e-9;

/// The triangles to refine, in increasing order: Dörfler's fewest triangles whose indicators reach θ of
/// the total (largest first), or every triangle at least θ times the largest; in both, every triangle tied
/// ([`TIE`]) with the smallest marked one too, so that the marking does not depend on rounding (a symmetric
/// problem is refined symmetrically, the same problem in other units alike). Empty when every indicator
/// is 0.
pub(crate) fn mark(indicators: &[f64], theta: f64, marking: Marking) -> Vec<usize> {
    let total: f64 = indicators.iter().sum();
    if total <= 0.0 || !total.is_finite() {
        return Vec::new();
    }
    let mut marked: Vec<usize> = match marking {
        Marking::Dorfler => {
            let mut order: Vec<usize> = (0..indicators.len()).collect();
            order.sort_by(|&a, &b| indicators[b].total_cmp(&indicators[a]).then(a.cmp(&b)));
            let mut sum = 0.0;
            let mut out = Vec::new();
            for t in order {
                let tied = out.last().is_some_and(|&last: &usize| indicators[t] >= indicators[last] * (1.0 - TIE));
                // The cut is protected from rounding like the ties: a sum that reaches θ of the total
                // only up to rounding (0.5 + 0.3 · (1 − 1e-15) of 1.0 at θ = 0.8) reaches it.
                if sum >= theta * total * (1.0 - TIE) && !tied {
                    break;
                }
                sum += indicators[t];
                out.push(t);
            }
            out
        }
        Marking::Maximum => {
            let max = indicators.iter().copied().fold(0.0, f64::max);
            (0..indicators.len()).filter(|&t| indicators[t] >= theta * max * (1.0 - TIE)).collect()
        }
    };
    marked.sort_unstable();
    marked
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dorfler_takes_the_fewest_largest_that_reach_theta() {
        let m = [0.1, 0.4, 0.2, 0.3];
        assert_eq!(mark(&m, 0.5, Marking::Dorfler), vec![1, 3]);
        assert_eq!(mark(&m, 0.7, Marking::Dorfler), vec![1, 3]);
        assert_eq!(mark(&m, 0.71, Marking::Dorfler), vec![1, 2, 3]);
        assert_eq!(mark(&m, 1.0, Marking::Dorfler), vec![0, 1, 2, 3]);
        assert_eq!(mark(&[0.0, 0.0], 0.5, Marking::Dorfler), Vec::<usize>::new());
    }

    #[test]
    fn ties_are_marked_together_whatever_their_rounding() {
        // One 0.4 reaches θ of the total alone, but the two equal to it up to rounding go with it.
        let m = [0.1, 0.4 * (1.0 - 1e-15), 0.1, 0.4, 0.4 * (1.0 + 1e-15)];
        assert_eq!(mark(&m, 0.25, Marking::Dorfler), vec![1, 3, 4]);
        assert_eq!(mark(&[0.3, 0.3, 0.3, 0.1], 0.2, Marking::Dorfler), vec![0, 1, 2]);
        // A sum that reaches θ of the total up to rounding reaches it: 0.5 + 0.3 is 0.8 of the total.
        assert_eq!(mark(&[0.3, 0.2, 0.5], 0.8, Marking::Dorfler), vec![0, 2]);
        assert_eq!(mark(&[0.3 * (1.0 - 1e-15), 0.2, 0.5], 0.8, Marking::Dorfler), vec![0, 2]);
        assert_eq!(mark(&[0.2, 0.5 * (1.0 - 1e-15), 1.0], 0.5, Marking::Maximum), vec![1, 2]);
    }

    #[test]
    fn maximum_takes_every_triangle_near_the_largest() {
        let m = [0.1, 0.4, 0.2, 0.3];
        assert_eq!(mark(&m, 0.5, Marking::Maximum), vec![1, 2, 3]);
        assert_eq!(mark(&m, 0.6, Marking::Maximum), vec![1, 3]);
        assert_eq!(mark(&m, 1.0, Marking::Maximum), vec![1]);
    }
}
