//! A working set of multiplier dofs for the Γ_C QP: solve over the dofs that can be in contact, check
//! the optimality conditions of the *whole* QP, grow the set where they fail, repeat.
//!
//! The QP `min ½ νᵀ H ν + cᵀ ν` over `ν_n ≥ 0, |ν_t| ≤ b` is dense in the 2q multiplier unknowns of all
//! of Γ_C, but the contact zone is often a small part of Γ_C. Fixing `ν_n,j = ν_t,j = 0` outside a set S
//! gives a smaller QP (same H, rows and columns of S) whose solution ν_S, extended by zeros, solves the
//! whole QP exactly when the dropped dofs satisfy their optimality conditions:
//!
//! * `(H ν + c)_n,j ≥ 0` — no pressure would appear there (the discrete gap is open), and
//! * `b_j = 0` — the friction bound forces `ν_t,j = 0` (so every dof with a positive bound is kept in S).
//!
//! A dropped dof with `(H ν + c)_n,j < −√tol c_s` (c_s = max |c_n|) is added, with its neighbours, and the
//! QP is solved again. The threshold is the one that separates "zero" from "non-zero" multipliers in the
//! contact states (a dof below it would carry `λ_n ≲ √tol Λ`). S only grows during a solve and across the
//! Coulomb iterations, so the clarabel set-up is reused whenever S did not change. The initial S holds the
//! dofs where the body, without contact forces, would penetrate (`c_n,j < 0`), and their neighbours.

use crate::condensation::Factor;
use crate::error::Result;
use crate::friction::check_thresholds;
use crate::qp::{BoxQp, QpOutcome, QpStatus};
use crate::settings::QpSettings;

/// The Γ_C QP solved over a growing working set; the columns of H come from a [`Factor`], computed when
/// the set first needs them.
#[derive(Debug)]
pub struct WorkingSetQp<'a> {
    condensed: &'a Factor,
    q: usize,
    bounds: Option<Vec<f64>>,
    settings: QpSettings,
    set: Vec<usize>,
    qp: Option<BoxQp>,
}

impl<'a> WorkingSetQp<'a> {
    /// Sets up the QP of P(g) on `condensed`: frictionless if `bounds` is `None`, else with the tangential
    /// bounds g (one per multiplier dof). The settings are taken as validated.
    ///
    /// # Errors
    /// [`crate::Error::BadThreshold`].
    pub fn new(condensed: &'a Factor, bounds: Option<&[f64]>, settings: &QpSettings) -> Result<Self> {
        let q = condensed.q();
        let mut ws = Self { condensed, q, bounds: None, settings: *settings, set: Vec::new(), qp: None };
        if let Some(b) = bounds {
            check_thresholds(b, q)?;
            ws.bounds = Some(b.to_vec());
        }
        let c = &condensed.c;
        let initial: Vec<usize> =
            if settings.working_set { (0..q).filter(|&j| c[j] < 0.0).collect() } else { (0..q).collect() };
        ws.grow(&initial);
        Ok(ws)
    }

    /// Adds dofs (and their neighbours) and the dofs with a positive bound to the set; true if it grew.
    fn grow(&mut self, dofs: &[usize]) -> bool {
        let mut member = vec![false; self.q];
        for &j in &self.set {
            member[j] = true;
        }
        let before = self.set.len();
        let add = |j: usize, member: &mut Vec<bool>, set: &mut Vec<usize>| {
            if !member[j] {
                member[j] = true;
                set.push(j);
            }
        };
        for &j in dofs {
            for k in j.saturating_sub(1)..=(j + 1).min(self.q - 1) {
                add(k, &mut member, &mut self.set);
            }
        }
        if let Some(b) = &self.bounds {
            for (j, v) in b.iter().enumerate() {
                if *v > 0.0 {
                    add(j, &mut member, &mut self.set);
                }
            }
        }
        self.set.sort_unstable();
        self.set.len() != before
    }

    /// Replaces the tangential bounds.
    ///
    /// # Errors
    /// [`crate::Error::BadThreshold`]; QP update errors.
    pub fn set_bounds(&mut self, b: &[f64]) -> Result<()> {
        check_thresholds(b, self.q)?;
        self.bounds = Some(b.to_vec());
        if self.grow(&[]) {
            self.qp = None;
        } else if let Some(qp) = self.qp.as_mut() {
            let sub: Vec<f64> = self.set.iter().map(|&j| b[j]).collect();
            qp.set_bounds(&sub)?;
        }
        Ok(())
    }

    /// Indices into the 2q unknowns (ν_n then ν_t) of the current set.
    fn unknowns(&self) -> Vec<usize> {
        let q = self.q;
        if self.bounds.is_some() {
            self.set.iter().copied().chain(self.set.iter().map(|j| q + j)).collect()
        } else {
            self.set.clone()
        }
    }

    fn build(&self) -> Result<BoxQp> {
        let idx = self.unknowns();
        let h = self.condensed.h_block(&idx, &idx);
        let c: Vec<f64> = idx.iter().map(|&i| self.condensed.c[i]).collect();
        let bounds: Option<Vec<f64>> = self.bounds.as_ref().map(|b| self.set.iter().map(|&j| b[j]).collect());
        BoxQp::new(&h, &c, self.set.len(), bounds.as_deref(), &self.settings)
    }

    /// Solves the whole QP; the returned ν has the full size (q, or 2q with friction).
    ///
    /// # Errors
    /// QP set-up errors.
    pub fn solve(&mut self) -> Result<QpOutcome> {
        let q = self.q;
        let frictional = self.bounds.is_some();
        let k = if frictional { 2 * q } else { q };
        let c = &self.condensed.c;
        let c_s = c[..q].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let threshold = -self.settings.tol.sqrt() * c_s;
        let (mut iterations, mut seconds) = (0, 0.0);
        loop {
            if self.qp.is_none() {
                self.qp = Some(self.build()?);
            }
            let out = self.qp.as_mut().expect("built above").solve();
            iterations += out.iterations;
            seconds += out.seconds;
            let s = self.set.len();
            let mut nu = vec![0.0; k];
            for (a, &j) in self.set.iter().enumerate() {
                nu[j] = out.nu[a];
                if frictional {
                    nu[q + j] = out.nu[s + a];
                }
            }
            if matches!(out.status, QpStatus::Failed(_)) || s == q {
                return Ok(QpOutcome { nu, status: out.status, iterations, seconds });
            }
            // Optimality of the dropped dofs: (H ν + c)_n,j ≥ threshold, with ν supported on the set.
            let mut member = vec![false; q];
            for &j in &self.set {
                member[j] = true;
            }
            let support: Vec<usize> = self.unknowns().into_iter().filter(|&i| nu[i] != 0.0).collect();
            let violated: Vec<usize> = self.condensed.with_columns(&support, |cols| {
                (0..q)
                    .filter(|&j| !member[j])
                    .filter(|&j| {
                        let hv: f64 = support.iter().map(|&i| cols[i].as_ref().expect("computed")[j] * nu[i]).sum();
                        hv + c[j] < threshold
                    })
                    .collect()
            });
            if violated.is_empty() {
                return Ok(QpOutcome { nu, status: out.status, iterations, seconds });
            }
            log::debug!("working set: {} dofs violate optimality, growing from {s}", violated.len());
            self.grow(&violated);
            self.qp = None;
        }
    }
}
