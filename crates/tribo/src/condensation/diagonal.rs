//! An estimate of diag H without forming H, for the QPs that do without it (the active-set method on the
//! saddle-point system, [`crate::qp`]): its prediction from a non-Newton start, its projected-gradient
//! safeguard and the scaling of its optimality test need diag H, whose exact value costs a solve per
//! dof. The estimate is `J_i = Σ_k E_ik² / A_kk + Dγ_ii` (the Jacobi approximation of A⁻¹) calibrated by
//! the exact `H_ii` of a few sampled unknowns (their median ratio).

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

/// The estimate of `H_ii` on the unknowns `idx` (see the module documentation).
fn estimated(factor: &Factor, idx: &[usize]) -> Vec<f64> {
    let (a_diag, d_diag) = (factor.a_diagonal(), factor.d_diagonal());
    // (over A's positive diagonal entries: a mixed formulation's pressures have negative ones)
    let row = |i: usize| factor.e_rows[i].iter().filter(|e| a_diag[e.0] > 0.0).map(|&(k, v)| v * v / a_diag[k]);
    let jacobi: Vec<f64> = idx.iter().map(|&i| row(i).sum::<f64>()).collect();
    let step = (idx.len() / SAMPLES).max(1);
    let sample: Vec<usize> = (0..idx.len()).step_by(step).filter(|&a| jacobi[a] > 0.0).collect();
    let cols: Vec<usize> = sample.iter().map(|&a| idx[a]).collect();
    let exact = factor.h_block(&cols, &cols);
    let s = cols.len();
    let mut ratios: Vec<f64> =
        sample.iter().enumerate().map(|(b, &a)| (exact[b * s + b] - d_diag[idx[a]]) / jacobi[a]).collect();
    ratios.retain(|r| r.is_finite() && *r > 0.0);
    ratios.sort_by(f64::total_cmp);
    let kappa = ratios.get(ratios.len() / 2).copied().unwrap_or(1.0);
    idx.iter().zip(&jacobi).map(|(&i, j)| kappa * j + d_diag[i]).collect()
}
