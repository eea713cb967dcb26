//! The Coulomb fixed point `Φ_H : g ↦ λ_Hn(g)` (Definition 1 of the paper): each evaluation a Tresca QP
//! P(g) whose matrix does not change (only the bounds μ g do), relaxed, stopped when the relative change
//! of λ_n is below `fp_tol` (or at the QP's noise level), and declared stagnated when it makes no new
//! minimum for [`STAGNATION_WINDOW`] iterations.

use std::ops::ControlFlow;

use crate::error::Result;
use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::results::SolveStatus;
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
        // Warm start: the frictionless λ_n with λ_t = 0.
        let mut qp = self.contact_qp(loading, Some(&bound), settings, Some(&phase.lambda))?;
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
