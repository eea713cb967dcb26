//! Which triangles to refine: the indicator of each triangle, made of the energy estimate and the traction
//! estimate in equal parts, and Dörfler or maximum marking on it.

use crate::problem::Problem;
use crate::settings::Marking;
use crate::Solution;

/// The marking indicator per triangle: `m_K = η_K² / Σ η² + ζ_K² / Σ ζ²`, where `ζ_K² = η_K² / h_E` on
/// a triangle that owns an edge E of Γ_C (the traction estimate, see [`crate::results::ErrorEstimate`]) and 0
/// elsewhere. Each part is a distribution over the triangles summing to 1, so the energy error and the
/// error of the contact tractions steer the refinement with equal weight, whatever their units; where
/// nothing touches (ζ = 0 everywhere) only the energy part is left.
pub(crate) fn indicators(problem: &Problem, solution: &Solution) -> Vec<f64> {
    let eta2: Vec<f64> = solution.estimator.iter().map(|e| e * e).collect();
    let mut zeta2 = vec![0.0; eta2.len()];
    for e in &problem.contact.edges {
        zeta2[e.triangle] += eta2[e.triangle] / e.length;
    }
    let (se, sz) = (eta2.iter().sum::<f64>(), zeta2.iter().sum::<f64>());
    let part = |v: f64, total: f64| if total > 0.0 { v / total } else { 0.0 };
    eta2.iter().zip(&zeta2).map(|(e, z)| part(*e, se) + part(*z, sz)).collect()
}

/// The triangles to refine, in increasing order: Dörfler's fewest triangles whose indicators reach θ of
/// the total (largest first, ties by index), or every triangle at least θ times the largest. Empty when
/// every indicator is 0.
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
                if sum >= theta * total {
                    break;
                }
                sum += indicators[t];
                out.push(t);
            }
            out
        }
        Marking::Maximum => {
            let max = indicators.iter().copied().fold(0.0, f64::max);
            (0..indicators.len()).filter(|&t| indicators[t] >= theta * max).collect()
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
    fn maximum_takes_every_triangle_near_the_largest() {
        let m = [0.1, 0.4, 0.2, 0.3];
        assert_eq!(mark(&m, 0.5, Marking::Maximum), vec![1, 2, 3]);
        assert_eq!(mark(&m, 0.6, Marking::Maximum), vec![1, 3]);
        assert_eq!(mark(&m, 1.0, Marking::Maximum), vec![1]);
    }
}
