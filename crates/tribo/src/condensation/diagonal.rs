//! An estimate of diag H without forming H, for the QPs that do without it (the active-set method on the
//! saddle-point system, [`crate::qp`]): its prediction from a non-Newton start, its projected-gradient
//! safeguard and the scaling of its optimality test need diag H, whose exact value costs a solve per
//! dof. The estimate is `J_i = Σ_k E_ik² / A_kk + Dγ_ii` (the Jacobi approximation of A⁻¹) calibrated by
//! the exact `H_ii` of a few sampled unknowns (their median ratio), each `yᵀ D⁻¹ y + Dγ_ii` (`y = L⁻¹ P E_iᵀ`) by one forward
//! substitution with the LDLᵀ factor of A (`Factor::h_diagonal_of`; the columns of H with
//! another factor). The same substitution gives `νᵀ H ν` for a ν on a few multipliers (`Factor::h_quadratic`),
//! which the active-set method on the saddle-point system uses for the objective at a projected point.

use super::Factor;

/// Unknowns whose exact `H_ii` calibrates the diagonal estimate.
const SAMPLES: usize = 8;

impl Factor {
    /// An estimate of `H_ii` on the unknowns `idx` (see the module documentation); for the leading
    /// unknowns `idx = 0..k` formed once per factorization and number k.
    pub(crate) fn h_diagonal_estimate(&self, idx: &[usize]) -> Vec<f64> {
        let leading = idx.iter().enumerate().all(|(a, &i)| a == i);
        if !leading {
            return estimated(self, idx);
        }
        let mut cache = self.h_diagonal_estimates.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((_, d)) = cache.iter().find(|(k, _)| *k == idx.len()) {
            return d.clone();
        }
        let d = estimated(self, idx);
        cache.push((idx.len(), d.clone()));
        d
    }
}

impl Factor {
    /// The exact `H_jj = E_j A⁻¹ E_jᵀ + Dγ_jj` of the multipliers `cols`: by a forward substitution each with the
    /// LDLᵀ factor of A (half a solve, no column of H formed), else from their columns of H.
    pub(crate) fn h_diagonal_of(&self, cols: &[usize]) -> Vec<f64> {
        let mut rhs = faer::Mat::<f64>::zeros(self.n, cols.len());
        for (b, &j) in cols.iter().enumerate() {
            for &(k, v) in &self.e_rows[j] {
                rhs[(k, b)] += v;
            }
        }
        let d_diag = self.d_diagonal();
        match self.direct.energies(rhs.as_ref()) {
            Some(e) => e.iter().zip(cols).map(|(v, &j)| v + d_diag[j]).collect(),
            None => {
                let (s, h) = (cols.len(), self.h_block(cols, cols));
                (0..s).map(|b| h[b * s + b]).collect()
            }
        }
    }
}

impl Factor {
    /// `νᵀ H ν = yᵀ D⁻¹ y + νᵀ Dγ ν` (`y = L⁻¹ P Eᵀ ν`) for the multipliers `nu` (nonzero entries, 2q indices) by one forward
    /// substitution with the LDLᵀ factor of A; `None` with the partial factor.
    pub(crate) fn h_quadratic(&self, nu: &[(usize, f64)]) -> Option<f64> {
        let mut rhs = faer::Mat::<f64>::zeros(self.n, 1);
        let mut dense = vec![0.0; self.e_rows.len()];
        for &(j, v) in nu {
            dense[j] += v;
            for &(k, e) in &self.e_rows[j] {
                rhs[(k, 0)] += e * v;
            }
        }
        let energy = self.direct.energies(rhs.as_ref())?[0];
        let stabilized: f64 =
            nu.iter().map(|&(j, v)| v * self.d_cols[j].iter().map(|&(i, d)| d * dense[i]).sum::<f64>()).sum();
        Some(energy + stabilized)
    }
}

/// The estimate of `H_ii` on the unknowns `idx` (see the module documentation).
fn estimated(factor: &Factor, idx: &[usize]) -> Vec<f64> {
    let (a_diag, d_diag) = (factor.a_diagonal(), factor.d_diagonal());
    // (over A's positive diagonal entries: a mixed formulation's pressures have negative ones)
    let row = |i: usize| factor.e_rows[i].iter().filter(|e| a_diag[e.0] > 0.0).map(|&(k, v)| v * v / a_diag[k]);
    let jacobi: Vec<f64> = idx.iter().map(|&i| row(i).sum::<f64>()).collect();
    let step = (idx.len() / SAMPLES).max(1);
    let sample: Vec<usize> = (0..idx.len()).step_by(step).filter(|&a| jacobi[a] > 0.0).collect();
    let cols: Vec<usize> = sample.iter().map(|&a| idx[a]).collect();
    let exact = factor.h_diagonal_of(&cols);
    let mut ratios: Vec<f64> =
        sample.iter().enumerate().map(|(b, &a)| (exact[b] - d_diag[idx[a]]) / jacobi[a]).collect();
    ratios.retain(|r| r.is_finite() && *r > 0.0);
    ratios.sort_by(f64::total_cmp);
    let kappa = ratios.get(ratios.len() / 2).copied().unwrap_or(1.0);
    idx.iter().zip(&jacobi).map(|(&i, j)| kappa * j + d_diag[i]).collect()
}

#[cfg(test)]
mod tests {
    use crate::settings::Condensation;
    use crate::{
        graded_rectangle, Grading, Material, MultiplierPoints, MultiplierSpace, ObstacleShape, Problem, ProblemSpec,
        Side, Stabilization,
    };

    /// Two paths to `H_jj`: the forward substitution with the LDLᵀ factor of A and the columns of H, on a
    /// graded Hertz problem, normal and tangential multipliers, with and without the stabilization's Dγ.
    #[test]
    fn the_forward_substitution_gives_the_diagonal_of_h() {
        let grading = Grading { side: Side::Top, segment: [-0.2, 0.2], h_min: 0.01, h_max: 0.25, growth: 0.3 };
        let mesh = graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading).expect("valid mesh");
        let spec = ProblemSpec::new(Material { young: 200.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .obstacle(ObstacleShape::Circle { center: 0.0, radius: 1.0 })
            .approach(0.01)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).expect("valid problem");
        for stabilization in [Stabilization::Fraction(0.5), Stabilization::None] {
            let condensed = problem.condense_with(stabilization, Condensation::Columns, usize::MAX).expect("condenses");
            let factor = condensed.factor();
            assert!(factor.direct.energies(faer::Mat::<f64>::zeros(factor.n, 1).as_ref()).is_some(), "LDLᵀ");
            let cols: Vec<usize> = (0..2 * condensed.q()).step_by(3).collect();
            let (fast, s) = (factor.h_diagonal_of(&cols), cols.len());
            let h = factor.h_block(&cols, &cols);
            for (b, v) in fast.iter().enumerate() {
                let exact = h[b * s + b];
                assert!((v - exact).abs() <= 1e-12 * exact.abs(), "column {}: {v} against {exact}", cols[b]);
            }
            // νᵀ H ν for a ν on a few of them, by the same forward substitution and by the block of H.
            let nu: Vec<(usize, f64)> =
                cols.iter().take(9).enumerate().map(|(b, &j)| (j, (b as f64 * 0.7).sin())).collect();
            let exact: f64 = (0..nu.len())
                .flat_map(|a| (0..nu.len()).map(move |b| (a, b)))
                .map(|(a, b)| nu[a].1 * h[b * s + a] * nu[b].1)
                .sum();
            let fast = factor.h_quadratic(&nu).expect("the LDLᵀ factor");
            assert!((fast - exact).abs() <= 1e-12 * exact.abs(), "{fast} against {exact}");
        }
    }
}
