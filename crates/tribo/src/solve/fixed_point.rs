//! The Coulomb fixed point `Φ_H : g ↦ λ_Hn(g)` (Definition 1 of the paper): each evaluation a Tresca QP
//! P(g) whose matrix does not change (only the bounds μ g do), relaxed, stopped when the relative change
//! of λ_n is below `fp_tol` (or at the QP's noise level), and declared stagnated when it makes no new
//! minimum for [`STAGNATION_WINDOW`] iterations.

use std::ops::ControlFlow;

use crate::error::Result;
use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::results::{Solution, SolveStatus};
use crate::settings::SolverSettings;
use crate::solve::driver::{qp_failed, QpPhase};
use crate::solve::progress::Progress;

/// Fixed-point iterations without a new smallest change after which the fixed point is declared
/// stagnated: a contraction, however slow, makes a new minimum every iteration.
pub const STAGNATION_WINDOW: usize = 10;

/// Watches a sequence (the changes of a fixed point, the merits of Newton's steps) for [`STAGNATION_WINDOW`]
/// values in a row without a new smallest one.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stagnation {
    best: f64,
    since: usize,
}

impl Stagnation {
    pub(super) fn new() -> Self {
        Self { best: f64::INFINITY, since: 0 }
    }

    /// Takes the next value; true when the last [`STAGNATION_WINDOW`] made no new minimum.
    pub(super) fn stalled(&mut self, value: f64) -> bool {
        if value < self.best {
            (self.best, self.since) = (value, 0);
        } else {
            self.since += 1;
        }
        self.since >= STAGNATION_WINDOW
    }
}

/// Whether a fixed point that stagnated (no new smallest change for [`STAGNATION_WINDOW`] iterations) may still
/// end on its last iterate, and if so its smallest change and the limit its KKT residuals met.
///
/// It may when it stagnated within what its QPs resolve of λ: its smallest change at most `√tol`, `tol` the QP
/// tolerance its QPs met ([`Solution::reached_qp_tol`]: `FALLBACK_TOL` when some met only that), the accuracy
/// `converged` grants the KKT residuals; and when its last iterate meets Coulomb's law with its own λ_n (the KKT
/// residuals take the friction bound μ λ_n of the answer, not the frozen bound of its QP) to within `fp_tol`,
/// or, where clarabel answered a QP of the fixed point (`clarabel`), to within what an interior-point answer is
/// determined to ([`Solution::accuracy_bound`], the limit of every converged answer: its complementarity is about
/// `tol`, so where the QP is degenerate its λ_n is determined to about `√tol` relative, as `solve/check.rs` reads
/// it, and the friction bound μ λ_n of the answer with it). The change of λ_n between two QPs then measures the
/// QPs' noise, not a distance from a solution. The smallest change is read over the whole history: one that
/// dipped and then cycled must still meet Coulomb's law at its last iterate. Seen: D30 (a block held only by the
/// contact, dragged by the obstacle in a history: such QPs are clarabel's) stagnated at changes of 3e-8 to 2e-6
/// with KKT residuals of 5e-12; with clarabel forced, the demo scene at μ = 1 stagnated at changes of 3e-8 to
/// 4e-7 with its friction bound met to 5.5e-8, and an adaptive level of it where four QPs met only
/// `FALLBACK_TOL` at changes of 1.1e-6.
pub(super) fn settled(
    history: &[f64],
    qp_inaccurate: usize,
    clarabel: bool,
    kkt: f64,
    settings: &SolverSettings,
) -> Option<(f64, f64)> {
    let smallest = history.iter().copied().fold(f64::INFINITY, f64::min);
    let resolved = Solution::reached_qp_tol(settings.qp.tol, qp_inaccurate).sqrt();
    let met = if clarabel {
        Solution::accuracy_bound(settings.qp.tol, qp_inaccurate, settings.fp.tol)
    } else {
        settings.fp.tol
    };
    (smallest <= resolved && kkt <= met).then_some((smallest, met))
}

impl Condensed<'_> {
    pub(super) fn fixed_point(
        &self,
        mu: &[f64],
        settings: &SolverSettings,
        loading: &LoadCase,
        phase: &mut QpPhase,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<()> {
        let q = self.q();
        let fp = settings.fp;
        let mut g: Vec<f64> = phase.lambda[..q].to_vec();
        let bound: Vec<f64> = g.iter().zip(mu).map(|(v, m)| m * v.max(0.0)).collect();
        // Warm start: the frictionless λ_n with λ_t = 0, or the previous step's answer in a history. The first QP
        // starts from the places of that answer (a fretting history of 101 steps at 15k, 28k and 55k unknowns, the
        // example `first_qps`: 108, 116 and 129 factorizations instead of 318, 376 and 493), or from the whole stick
        // zone where the saddle-point system takes that step bordered.
        let mut qp = self.contact_qp(loading, Some(&bound), settings, Some(&phase.lambda))?;
        if phase.neighbour {
            qp.start_from_answer(fp.tol);
        } else {
            qp.start_from_stick();
        }
        phase.status = SolveStatus::MaxIterations;
        let mut stagnation = Stagnation::new();
        for it in 1..=fp.max_iter {
            let out = qp.solve()?;
            phase.book(&out);
            phase.iterations = it;
            if let Some(s) = qp_failed(it, out.status) {
                phase.status = s;
                break;
            }
            let lam_n = &out.nu[..q];
            let max_diff = lam_n.iter().zip(&g).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            let diff = euclidean(lam_n.iter().zip(&g).map(|(a, b)| a - b));
            let norm = euclidean(lam_n.iter().copied());
            let change = if norm > 0.0 { diff / norm } else { diff };
            phase.history.push(change);
            let flow = notify(Progress::qp(self.factor(), it, change, &out));
            phase.bound = g.iter().zip(mu).map(|(v, m)| m * v.max(0.0)).collect();
            phase.lambda = out.nu;
            // Converged when the relative change is small, or when the change is at the QP's own noise
            // level (tol × the natural size of λ): e.g. λ ≡ 0 without contact, where a relative change
            // compares round-off with round-off.
            let noise = settings.qp.tol * self.factor().lambda_scale(&loading.c);
            if change <= fp.tol || max_diff <= noise {
                phase.status = SolveStatus::Converged;
                break;
            }
            if flow.is_break() {
                phase.status = SolveStatus::Interrupted { iteration: it };
                break;
            }
            // A converging fixed point keeps making new minima of the change; one that cycles, or that
            // has reached the accuracy to which the QP determines λ, does not.
            if stagnation.stalled(change) {
                phase.status = SolveStatus::Stagnated;
                break;
            }
            let w = fp.relaxation;
            for (gj, lj) in g.iter_mut().zip(&phase.lambda[..q]) {
                *gj = ((1.0 - w) * *gj + w * lj).max(0.0);
            }
            let bound: Vec<f64> = g.iter().zip(mu).map(|(v, m)| m * v).collect();
            qp.set_bounds(&bound)?;
        }
        Ok(())
    }
}

/// The Euclidean norm, scaled by the largest entry first so that its squares neither underflow (λ of
/// 1e-200, where every square is 0 and a relative change would read 0) nor overflow.
pub(super) fn euclidean(v: impl Iterator<Item = f64> + Clone) -> f64 {
    let m = v.clone().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.map(|x| (x / m).powi(2)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The answers a stagnated fixed point may end on: within what its QPs resolve (`√tol` of the tolerance they
    /// met) and meeting Coulomb's law to fp_tol, or to `accuracy_bound` where clarabel answered a QP.
    #[test]
    fn a_stagnated_fixed_point_settles_within_what_its_qps_resolve() {
        let s = SolverSettings::default(); // qp_tol 1e-12, fp_tol 1e-8
        let noisy = [9.3e-4, 4.0e-8, 2.9e-7, 3.7e-7, 4.7e-8, 2.7e-8];
        // The active-set method's answers are exact on their active sets: Coulomb's law must hold to fp_tol.
        assert_eq!(settled(&noisy, 0, false, 5e-12, &s), Some((2.7e-8, 1e-8)));
        assert_eq!(settled(&noisy, 0, false, 5.5e-8, &s), None);
        // clarabel's λ_n is determined to about √qp_tol = 1e-6 relative, and the friction bound with it.
        assert_eq!(settled(&noisy, 0, true, 5.5e-8, &s), Some((2.7e-8, 1e-6)));
        assert_eq!(settled(&noisy, 0, true, 2e-6, &s), None);
        // Changes of 1.1e-6 are beyond √qp_tol, and within √FALLBACK_TOL = 1e-5 once a QP met only that.
        let fallback = [1e-3, 1.1e-6, 3e-6];
        assert_eq!(settled(&fallback, 0, true, 2e-9, &s), None);
        let got = settled(&fallback, 4, true, 2e-9, &s);
        assert!(got.is_some_and(|(smallest, met)| smallest == 1.1e-6 && (met - 1e-5).abs() < 1e-18), "{got:?}");
        assert_eq!(settled(&fallback, 4, false, 2e-9, &s), Some((1.1e-6, 1e-8)));
        // A two-cycle's changes stay large: never settled, whatever its residuals.
        assert_eq!(settled(&[3e-3, 2.9e-3, 3e-3], 4, true, 0.0, &s), None);
        assert_eq!(settled(&[], 0, true, 0.0, &s), None);
    }
}
