//! The Γ_C QP without H: the active-set method of [`crate::qp::active_set`] on the sparse saddle-point system.
//!
//! # Why
//! On a mesh refined toward a large contact zone, the dofs in contact grow like the unknowns n. Forming
//! the columns of H they need costs one sparse solve each (~ n² in all) and the dense active-set steps
//! cost a Cholesky of the free block (~ n³): the dense path loses its advantage exactly where accurate
//! answers live. Here H is never formed.
//!
//! # The operator
//! The active-set method needs of H only the gradient and the Newton point ([`QpOperator`]):
//!
//! * the gradient `H ν + c = −E u(ν) + Dγ ν + d`, with `u(ν) = A⁻¹ (f − Eᵀ ν)` — one solve with the
//!   Cholesky factor of A (the gradient is minus the stabilized gap and slip `r = E u − d − Dγ ν`), of which
//!   only `E u` is formed ([`Factor::e_displacement`]: the substitutions visit what `Eᵀ ν` reaches and
//!   what E reads, 4.9 ms instead of 7.5 ms for the full solve at 55k);
//! * the Newton point for a free set F, `H_FF ν_F = −c_F − H_FB ν_B`, which is the sparse saddle-point
//!   system `A u + E_Fᵀ ν_F = f − E_Bᵀ ν_B`, `E_F u − Dγ_FF ν_F = d_F + Dγ_FB ν_B` ([`crate::linalg::saddle`]):
//!   one sparse LDLᵀ of about the cost of a Cholesky of A, on a pattern analysed once per problem. When
//!   F differs from the factorized partition in few multipliers (the last steps of a QP, and the first
//!   step of the next fixed-point QP, which starts from the previous places), the factorization held is
//!   bordered by them instead ([`SaddleSystem::solve_near`]): one solve, plus a short forward
//!   substitution per changed multiplier, up to [`SaddleSystem::border_limit`] of them (measured on the
//!   graded Hertz family: 5–7 LDLᵀ and 40–45 bordered steps per Coulomb solve instead of 49–66 LDLᵀ).
//!
//! Where the free set crawls, the front of a Newton point ([`QpOperator::front`]) is resolved with
//! `[H_FF⁻¹]_JJ` from the same bordered factorization ([`SaddleSystem::inverse_block`]): a forward
//! substitution along one path of the elimination tree per unknown of J and the products between
//! them, 1–2 ms at 55k against 7–8 ms for a bordered solve.
//!
//! From a zone much too large, the operator lists the unknowns in order along Γ_C (normal, then tangential,
//! consecutive multipliers neighbours) for the rule that moves each edge twice as far
//! ([`active_set::beyond_edges`]). Where T_H has several pieces (several contact pairs or sides),
//! the last multiplier of one and the first of the next count as neighbours: a zone there may be read as one
//! and its edges moved less well, never wrongly (each step is an ordinary Newton step).
//!
//! The method also uses diag H (its prediction from a non-Newton start, the projected-gradient safeguard
//! and the scaling of the optimality test). Its exact value costs a solve per dof, so it is estimated
//! ([`Factor::h_diagonal_estimate`]). The estimate enters the certification only through the
//! unit of the test (`φ`, `w`): the test itself — every free unknown's gradient and every active bound's
//! multiplier checked — is the one of [`crate::qp::active_set`]. What it does not certify, the dense path
//! solves (the caller's fallback).
//!
//! # Round-off
//! The gradient `d − E u + Dγ ν` cancels terms of the size of `d`, each carrying the error of a solve with
//! A (≈ ε κ(A) relative): on a mesh graded to 3e-4 of its size that is far above `qp_tol`, and it is not the
//! round-off of the Newton point, which comes from another factorization. The dense path does not see
//! it: its H and c carry the same errors, but its gradient and Newton point share them. So the test
//! here asks for no less than twice the gradient's size on the free unknowns of the last Newton point,
//! where it is zero in exact arithmetic: the signs of the active bounds' multipliers are checked to the
//! accuracy the arithmetic gives, as the dense path's answer is exact only to that accuracy too. That
//! measurement needs the gradient at the Newton point by a solve with A; on the steps where the answer
//! cannot be near (the projection moved the point and the free set changed), the Newton point's gradient
//! only predicts the next free set, and it is formed from the saddle-point solve's own displacement
//! (`E u` from `u` of the bordered solve: no solve with A). One solve with A per step instead of two:
//! 55k graded unknowns, Coulomb, 1.17 → 1.09 s. On those steps the objective at the projected point, which
//! the safeguard compares, comes from that gradient too, with the curvature `dᵀ H d` along the move d of the
//! unknowns that left their box (`Factor::h_quadratic`: one forward substitution with the factor of A, half a
//! solve); the gradient at the projected point is formed only when the step is refused.

use crate::condensation::Factor;
use crate::linalg::saddle::SaddleSystem;
use crate::qp::active_set::{self, Bounds, QpOperator, Start};
use crate::qp::Scaling;

/// The QP operator of the saddle-point system on the unknowns `idx` (indices into the 2q multipliers).
pub(crate) struct SaddleOperator<'a> {
    factor: &'a Factor,
    saddle: &'a mut SaddleSystem,
    f: &'a [f64],
    d: &'a [f64],
    idx: &'a [usize],
    diag: Vec<f64>,
    /// The last Newton point and its gradient formed from the saddle-point solve's displacement.
    newton: Option<(Vec<f64>, Vec<f64>)>,
    /// LDLᵀ factorizations done.
    pub factorizations: u32,
    /// Newton points solved with the factorization of a nearby partition, bordered.
    pub bordered: u32,
    /// The most changed multipliers a bordered solve takes ([`SaddleSystem::border_limit`]).
    border_limit: usize,
    /// The last gradient and the point it was taken at: the method asks again for the one at a Newton
    /// point it accepts, and each costs a solve.
    last_gradient: std::cell::RefCell<Option<(Vec<f64>, Vec<f64>)>>,
}

impl<'a> SaddleOperator<'a> {
    /// The operator of the load case (`f`, `d`) on the unknowns `idx`.
    pub(crate) fn new(
        factor: &'a Factor,
        saddle: &'a mut SaddleSystem,
        f: &'a [f64],
        d: &'a [f64],
        idx: &'a [usize],
    ) -> Self {
        let diag = factor.h_diagonal_estimate(idx);
        let border_limit = saddle.border_limit();
        Self {
            factor,
            saddle,
            f,
            d,
            idx,
            diag,
            newton: None,
            factorizations: 0,
            bordered: 0,
            border_limit,
            last_gradient: Default::default(),
        }
    }

    /// `H ν + c = −E u + Dγ ν + d` on the unknowns, for the displacement `u` of the multipliers `nu` (2q).
    fn gradient_from(&self, u: &[f64], nu: &[f64]) -> Vec<f64> {
        self.gradient_from_e_u(&self.factor.apply_e(u), nu)
    }

    /// The same from `E u` (2q).
    fn gradient_from_e_u(&self, eu: &[f64], nu: &[f64]) -> Vec<f64> {
        let dnu = self.factor.apply_d(nu);
        self.idx.iter().map(|&i| dnu[i] + self.d[i] - eu[i]).collect()
    }

    /// The free set on the multipliers (2q) from the free set `free` on the unknowns (the others fixed).
    fn free_multipliers(&self, free: &[bool]) -> Vec<bool> {
        let mut all = vec![false; self.factor.e_rows.len()];
        for (&i, &f) in self.idx.iter().zip(free) {
            all[i] = f;
        }
        all
    }

    /// The multipliers (2q) with `x` on the unknowns and 0 elsewhere.
    fn expand(&self, x: &[f64]) -> Vec<f64> {
        let mut nu = vec![0.0; self.factor.e_rows.len()];
        for (&i, &v) in self.idx.iter().zip(x) {
            nu[i] = v;
        }
        nu
    }
}

impl QpOperator for SaddleOperator<'_> {
    fn gradient(&self, x: &[f64]) -> Vec<f64> {
        if let Some((at, g)) = self.last_gradient.borrow().as_ref() {
            if at == x {
                return g.clone();
            }
        }
        let nu = self.expand(x);
        let Ok(eu) = self.factor.e_displacement(self.f, &nu) else {
            return vec![f64::NAN; x.len()];
        };
        let g = self.gradient_from_e_u(&eu, &nu);
        *self.last_gradient.borrow_mut() = Some((x.to_vec(), g.clone()));
        g
    }

    fn newton_point(&mut self, free: &[bool], x: &[f64]) -> Option<Vec<f64>> {
        let free_all = self.free_multipliers(free);
        let fixed = self.expand(x);
        // Near the factorized partition, border it; else factorize this one.
        let near = self.saddle.is_factorized() && self.saddle.changed(&free_all).len() <= self.border_limit;
        let bordered = if near { self.saddle.solve_near(&free_all, self.f, self.d, &fixed).ok() } else { None };
        let sol = match bordered {
            Some(sol) => {
                self.bordered += 1;
                sol
            }
            None => {
                self.factorizations += 1;
                self.saddle.factorize(&free_all).ok()?;
                self.saddle.solve(self.f, self.d, &fixed).ok()?
            }
        };
        let x: Vec<f64> = self.idx.iter().map(|&i| sol.nu[i]).collect();
        self.newton = Some((x.clone(), self.gradient_from(&sol.u, &sol.nu)));
        Some(x)
    }

    fn newton_gradient(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.newton.as_ref().filter(|(at, _)| at == x).map(|(_, g)| g.clone())
    }

    fn diagonal(&self) -> &[f64] {
        &self.diag
    }

    fn measures_round_off(&self) -> bool {
        true
    }

    fn curvature(&self, d: &[(usize, f64)]) -> Option<f64> {
        let nu: Vec<(usize, f64)> = d.iter().map(|&(a, v)| (self.idx[a], v)).collect();
        self.factor.h_quadratic(&nu)
    }

    fn beyond(&self, free: &[bool], xn: &[f64], bounds: &Bounds) -> Vec<(usize, active_set::Place)> {
        let [normal, tangential] = self.lines();
        active_set::beyond_edges(&[&normal, &tangential], free, xn, bounds)
    }

    /// J: the unknowns outside their box and the free unknowns of the same kind (normal or tangential)
    /// within [`FRONT_REACH`] multipliers of them along Γ_C, at most [`FRONT_MAX`]; `[H_FF⁻¹]_JJ` from the
    /// bordered factorization of F ([`SaddleSystem::inverse_block`]), which the Newton point just used.
    fn front(&mut self, free: &[bool], outside: &[usize]) -> Option<(Vec<usize>, Vec<f64>)> {
        let k = self.idx.len();
        let m = self.factor.e_rows.len();
        let q = m / 2;
        // The multipliers are ν_n (0..q) then ν_t (q..2q), each along Γ_C: the kind and the place of an
        // unknown along Γ_C.
        let kind = |a: usize| self.idx[a] / q.max(1);
        let mut member = vec![false; k];
        for &a in outside {
            let lo = a.saturating_sub(FRONT_REACH);
            for b in lo..(a + FRONT_REACH + 1).min(k) {
                member[b] |= free[b] && kind(b) == kind(a) && self.idx[b].abs_diff(self.idx[a]) <= FRONT_REACH;
            }
        }
        let dofs: Vec<usize> = (0..k).filter(|&a| member[a]).collect();
        if dofs.len() > FRONT_MAX {
            return None;
        }
        let free_all = self.free_multipliers(free);
        let multipliers: Vec<usize> = dofs.iter().map(|&a| self.idx[a]).collect();
        let inverse = self.saddle.inverse_block(&free_all, &multipliers).ok()?;
        Some((dofs, inverse))
    }
}

impl SaddleOperator<'_> {
    /// The unknowns in order along Γ_C: the normal ones, then the tangential ones (`idx` is increasing, normal
    /// multipliers first).
    fn lines(&self) -> [Vec<usize>; 2] {
        let q = self.factor.e_rows.len() / 2;
        let normal: Vec<usize> = (0..self.idx.len()).filter(|&a| self.idx[a] < q).collect();
        let tangential: Vec<usize> = (0..self.idx.len()).filter(|&a| self.idx[a] >= q).collect();
        [normal, tangential]
    }
}

/// How far along Γ_C (in multipliers) a front reaches beyond the unknowns that left their box.
const FRONT_REACH: usize = 4;

/// The largest front resolved: its `[H_FF⁻¹]_JJ` costs a forward substitution per unknown and the
/// products between them.
const FRONT_MAX: usize = 160;

/// Solves the QP `min ½ νᵀHν + cᵀν` on the unknowns `idx` (normal ones first: the first `q_n` of `idx`
/// are normal, the rest tangential with the bounds `bounds`) from `start`, with the active-set method on
/// the saddle-point system. Returns the answer on `idx`, the steps taken and the LDLᵀ factorizations
/// among them, or `None` when it could not certify it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve(
    factor: &Factor,
    saddle: &mut SaddleSystem,
    (f, d, c): (&[f64], &[f64], &[f64]),
    idx: &[usize],
    q_n: usize,
    bounds: &[f64],
    start: Start<'_>,
    (tol, max_steps): (f64, u32),
) -> Option<(Vec<f64>, u32, u32)> {
    let c_idx: Vec<f64> = idx.iter().map(|&i| c[i]).collect();
    let mut op = SaddleOperator::new(factor, saddle, f, d, idx);
    let k = idx.len();
    // The scaling of the optimality test is that of the dense path, whose QP holds the dofs the load
    // pushes, those of the start and those with a friction bound (and their neighbours): over all of Γ_C,
    // the coarse dofs far from contact (large H_ii, large positive c) would loosen it.
    let mut relevant = vec![false; q_n];
    for j in 0..q_n {
        let pushed = c_idx[j] < 0.0 || start.x[j] != 0.0 || bounds.get(j).is_some_and(|b| *b > 0.0);
        if pushed {
            for r in &mut relevant[j.saturating_sub(1)..(j + 2).min(q_n)] {
                *r = true;
            }
        }
    }
    let keep = |a: usize| relevant[if a < q_n { a } else { a - q_n }];
    let diag_s: Vec<f64> = (0..k).map(|a| if keep(a) { op.diag[a] } else { 0.0 }).collect();
    let c_s: Vec<f64> = (0..k).map(|a| if keep(a) { c_idx[a] } else { 0.0 }).collect();
    let Some(n_scale) = Scaling::normal_scale(&diag_s, &c_s, q_n) else {
        return Some((vec![0.0; idx.len()], 0, 0));
    };
    let scaling = Scaling::new(&diag_s, &c_s, q_n, n_scale, bounds);
    let out = active_set::solve(&mut op, &c_idx, &Bounds::contact(q_n, bounds), start, &scaling, tol, max_steps);
    log::debug!(
        "sparse active set on {k} unknowns: certified {}, {} Newton steps ({} LDLᵀ, {} bordered), {} gradient steps",
        out.certified,
        out.newton_steps,
        op.factorizations,
        op.bordered,
        out.gradient_steps
    );
    out.certified.then_some((out.x, out.newton_steps + out.gradient_steps, op.factorizations))
}
