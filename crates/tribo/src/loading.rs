//! The load case of a solve: everything the QP and the fields depend on besides `A` and `H`.
//!
//! For a condensed problem, a load case is the load `f`, the obstacle moments `d` and the QP's linear
//! term `c = d − E A⁻¹ f` (see [`crate::condensation`]), with the gap and the origin of slip at the FE
//! nodes of Γ_C for the reported fields. A static solve has one, built from the problem's own data
//! ([`Loading::of_problem`]). A step of a loading history has its own ([`Loading::step`], derived in
//! [`crate::history`]). Neither changes `A`, `H` or `Dγ`, so every load case of a problem shares one
//! factorization.

use crate::condensation::Factor;
use crate::error::{Error, Result};
use crate::problem::Problem;

/// One load case of a condensed problem.
#[derive(Debug, Clone)]
pub struct Loading {
    /// Load on the free dofs.
    pub f_free: Vec<f64>,
    /// Load on all 2N dofs (for the reactions).
    pub f_full: Vec<f64>,
    /// `d` (2q): the gap moments `∫ψ_j g`, then the tangential data the slip is measured from.
    pub d: Vec<f64>,
    /// `c = d − E A⁻¹ f` (2q), the QP's linear term.
    pub c: Vec<f64>,
    /// The gap `g = g₀ − δ` at the FE nodes of Γ_C.
    pub gap: Vec<f64>,
    /// The obstacle's approach δ and tangential position s.
    pub approach: f64,
    /// See `approach`.
    pub shift: f64,
    /// At the FE nodes of Γ_C, the tangential displacement from which slip is measured: the shift s of a
    /// static solve, `u_t^{k−1} + s_k − s_{k−1}` in step k of a history.
    pub slip_origin: Vec<f64>,
}

/// Where a history stands before a step: the tangential displacement at rest is 0 and the obstacle at
/// shift 0.
#[derive(Debug, Clone)]
pub(crate) struct PreviousStep {
    /// `(E_t u^{k−1} − Dγ λ_t^{k−1})_j` (q values) on the unknowns: the previous step's stabilized
    /// tangential displacement, `∫ ψ_j u_t^{k−1} − ∫ γ ψ_j (λ_t^{k−1} + σ_t(u^{k−1}))` without the part of
    /// the prescribed displacements (the same at every step, it cancels in the increment).
    pub tangential: Vec<f64>,
    /// `u_t^{k−1}` at the FE nodes of Γ_C.
    pub u_t_nodes: Vec<f64>,
    /// `s_{k−1}`.
    pub shift: f64,
}

impl PreviousStep {
    /// The state at rest: the body undeformed (u = 0, also where a support prescribes ū: the first step
    /// moves it there), the obstacle at shift 0. Its tangential data is then `−(E ū)_t`, the tangential
    /// part of the lifting in the problem's own `d` (exactly 0 without prescribed displacements).
    pub fn rest(problem: &Problem, factor: &Factor) -> Self {
        let q = problem.n_multipliers();
        let shift = problem.spec.obstacle.shift;
        let tangential = problem.mortar.psi_integrals.iter().zip(&factor.d[q..]).map(|(w, d)| d - w * shift).collect();
        Self { tangential, u_t_nodes: vec![0.0; problem.contact.nodes.len()], shift: 0.0 }
    }
}

impl Loading {
    /// The problem's own load case (the static solve).
    pub fn of_problem(problem: &Problem, factor: &Factor) -> Self {
        let shift = problem.spec.obstacle.shift;
        Self {
            f_free: factor.f.clone(),
            f_full: problem.f_full.clone(),
            d: factor.d.clone(),
            c: factor.c.clone(),
            gap: problem.contact_gap.clone(),
            approach: problem.spec.obstacle.approach,
            shift,
            slip_origin: vec![shift; problem.contact.nodes.len()],
        }
    }

    /// The load case of one step of a history (see [`crate::history`] for the derivation): loads
    /// `α f` (the lifting of prescribed displacements is not scaled), gap moments `∫ψ_j (g₀ − δ_k)`,
    /// tangential data `∫ψ_j (s_k − s_{k−1}) + (E_t u^{k−1} − Dγ λ_t^{k−1})_j`. From rest with α = 1 and
    /// the problem's own approach, this is bit for bit the static load case.
    ///
    /// # Errors
    /// [`crate::Error::MemoryBudget`] if the solve for a scaled load cannot allocate its workspace.
    pub(crate) fn step(problem: &Problem, factor: &Factor, step: &LoadStep, previous: &PreviousStep) -> Result<Self> {
        let alpha = step.load_factor;
        let q = problem.n_multipliers();
        let w = &problem.mortar.psi_integrals;
        // g_k = g₀ − δ_k = (g₀ − δ) + (δ − δ_k): the problem's gap moved by the change of approach.
        let moved = problem.spec.obstacle.approach - step.approach;
        let ds = step.shift - previous.shift;
        let d: Vec<f64> = factor.d[..q]
            .iter()
            .zip(w)
            .map(|(m, w)| m + moved * w)
            .chain(w.iter().zip(&previous.tangential).map(|(w, t)| w * ds + t))
            .collect();
        let (f_free, c) = if alpha == 1.0 {
            let c = d.iter().zip(&factor.e_ainv_f).map(|(d, e)| d - e).collect();
            (factor.f.clone(), c)
        } else {
            // f̃ + (α − 1) Tᵀ f: the load scaled, its lifting kept; one more solve for E A⁻¹ f.
            let load = problem.dofs.restrict(&problem.f_full);
            let f: Vec<f64> = factor.f.iter().zip(&load).map(|(f, l)| f + (alpha - 1.0) * l).collect();
            let u = factor.displacement(&f, &vec![0.0; d.len()])?;
            let c = d.iter().zip(factor.apply_e(&u)).map(|(d, e)| d - e).collect();
            (f, c)
        };
        Ok(Self {
            f_free,
            f_full: problem.f_full.iter().map(|f| alpha * f).collect(),
            d,
            c,
            gap: problem.contact_gap.iter().map(|g| g + moved).collect(),
            approach: step.approach,
            shift: step.shift,
            slip_origin: previous.u_t_nodes.iter().map(|u| u + ds).collect(),
        })
    }
}

/// One step of a loading history: where the obstacle is and how much of the load acts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadStep {
    /// Normal approach δ_k of the obstacle toward the body (the total, not an increment).
    pub approach: f64,
    /// Tangential position s_k of the obstacle along t (the total, not an increment).
    pub shift: f64,
    /// Factor α_k on the body force and the tractions.
    pub load_factor: f64,
}

impl LoadStep {
    /// A step to approach δ and shift s under the full load.
    pub fn new(approach: f64, shift: f64) -> Self {
        Self { approach, shift, load_factor: 1.0 }
    }

    /// Checks that every value is finite.
    ///
    /// # Errors
    /// [`Error::BadLoadStep`] naming the step (`index`) and the value.
    pub fn validate(&self, index: usize) -> Result<()> {
        for (name, v) in [("approach", self.approach), ("shift", self.shift), ("load_factor", self.load_factor)] {
            if !v.is_finite() {
                return Err(Error::BadLoadStep { step: index, what: format!("{name} must be finite, got {v}") });
            }
        }
        Ok(())
    }
}
