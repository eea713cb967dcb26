//! How far an answer of a Tresca (or frictionless) QP can lie from the exact one, read from its own residuals: the
//! bound that says two converged answers of one problem are one answer (issue 40's D25).
//!
//! The QP `min f(ν) = ½ νᵀ H ν + cᵀ ν` over `K(g) = {ν_n ≥ 0, |ν_t| ≤ g}` is strongly convex in the energy norm
//! `‖v‖_H = √(vᵀ H v)`, and its gradient is `H ν + c = −r`, `r = E u − d − Dγ ν` with `u = A⁻¹(f − Eᵀ ν)`. For an
//! answer a and the exact λ*, `‖a − λ*‖_H² = (∇f(a) − ∇f(λ*))ᵀ (a − λ*)`, and `∇f(λ*)ᵀ (v − λ*) ≥ 0` for every v of
//! K(g). With a in K(g) the second part is at most 0, so `‖a − λ*‖_H² ≤ −rᵀ (a − λ*)`, a sum over the dofs j:
//!
//! ```text
//! normal:     −r_n (a_n − λ*_n) ≤ |a_n r_n| + (r_n)₊ λ*_n
//! tangential: −r_t (a_t − λ*_t) ≤ |r_t| g − r_t a_t = (g − |a_t|) |r_t| + 2 (−a_t r_t)₊      (|λ*_t| ≤ g)
//! ```
//!
//! the complementarity, non-penetration, stick and slip-direction residuals of the KKT check, unscaled. An answer a
//! hair outside K(g) (by e, its distance to its projection) adds `|∇f(λ*)|ᵀ e`, with ∇f(λ*) read at a (`|r|ᵀ e`; the
//! two differ by `H (a − λ*)`, far below r where e matters). So `‖a − λ*‖_H ≤ √S(a)` with `S(a)` that sum, and two
//! answers of one problem lie within `√S(a) + √S(b)` of each other, whichever method gave them.
//!
//! Two bounds g_a, g_b (the last QPs of two Coulomb fixed points, `g = μ λ_n`): the exact answers x, y of K(g_a) and
//! K(g_b) satisfy `‖x − y‖_H² ≤ (|r_x| + |r_y|)ᵀ |g_a − g_b|` over the tangential dofs (each optimality condition
//! tested at the other's projection onto its set, which moves it by at most |g_a − g_b|), with r_x, r_y read at the
//! answers as above.

use tribo::*;

/// An answer's residual sum `S` (the module documentation) and its tangential `|r_t|` per dof.
#[derive(Debug, Clone)]
pub struct EnergyResidual {
    /// `S(a)`: the answer lies within `√S` of the exact answer of its QP in the energy norm.
    pub sum: f64,
    /// `|r_t|` per multiplier dof, for the term of two bounds.
    pub slip: Vec<f64>,
    /// `‖a‖_H`.
    pub size: f64,
}

/// The residual sum of the answer `lambda` (λ_n then λ_t, 2q) of the QP with tangential bounds `bound` (q; empty
/// for a frictionless answer) on `problem` condensed with `stabilization`; `lambda_n_max` bounds the exact λ*_n (the
/// tests take the larger of two answers', which bracket λ* to their own accuracy: an estimate, not a bound).
///
/// # Panics
/// If the problem cannot be condensed or solved (test support: the tests' own scenes, see the crate documentation).
pub fn energy_residual(
    problem: &Problem,
    stabilization: Stabilization,
    lambda: &[f64],
    bound: &[f64],
    lambda_n_max: f64,
) -> EnergyResidual {
    let condensed = problem.condense(stabilization).expect("condenses");
    let factor = condensed.factor();
    let q = factor.q();
    let u = factor.displacement(&factor.f, lambda).expect("solves");
    let (eu, dl) = (factor.apply_e(&u), factor.apply_d(lambda));
    let r: Vec<f64> = (0..2 * q).map(|j| eu[j] - factor.d[j] - dl[j]).collect();
    let mut sum = 0.0;
    let mut slip = vec![0.0; q];
    for j in 0..q {
        let (an, rn) = (lambda[j], r[j]);
        sum += (an * rn).abs() + rn.max(0.0) * lambda_n_max + (-an).max(0.0) * rn.abs();
        if let Some(g) = bound.get(j) {
            let (at, rt) = (lambda[q + j], r[q + j]);
            sum += (g - at.abs()).max(0.0) * rt.abs() + 2.0 * (-at * rt).max(0.0) + (at.abs() - g).max(0.0) * rt.abs();
            slip[j] = rt.abs();
        }
    }
    // ‖a‖_H² = aᵀ(H a) = −aᵀ(r + c).
    let size = (-(0..2 * q).map(|j| lambda[j] * (r[j] + factor.c[j])).sum::<f64>()).max(0.0).sqrt();
    EnergyResidual { sum, slip, size }
}

/// `‖a − b‖_H` for two answers (2q each) of `problem` condensed with `stabilization` (one more solve).
///
/// # Panics
/// As [`energy_residual`].
pub fn energy_distance(problem: &Problem, stabilization: Stabilization, a: &[f64], b: &[f64]) -> f64 {
    let condensed = problem.condense(stabilization).expect("condenses");
    let factor = condensed.factor();
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    // H d = E A⁻¹ Eᵀ d + Dγ d: the displacement of the load −Eᵀ d alone is A⁻¹(0 − Eᵀ d).
    let u = factor.displacement(&vec![0.0; factor.f.len()], &d).expect("solves");
    let (eu, dd) = (factor.apply_e(&u), factor.apply_d(&d));
    let quad: f64 = d.iter().zip(eu.iter().zip(&dd)).map(|(x, (e, g))| x * (g - e)).sum();
    quad.max(0.0).sqrt()
}

/// Two Coulomb answers of `problem` (μ uniform, condensed with `stabilization`) in the energy norm: `(apart, bound,
/// size)`, `apart = ‖a − b‖_H`, `bound = √S(a) + √S(b) + √((|r_a| + |r_b|)ᵀ μ |a_n − b_n|)` (each answer within
/// `√S` of the exact answer of the Tresca QP with its own bound μ λ_n, those two within the last term of each other:
/// the module documentation) and `size = ‖a‖_H`.
///
/// # Panics
/// As [`energy_residual`].
pub fn coulomb_apart(problem: &Problem, stabilization: Stabilization, mu: f64, a: &Solution, b: &Solution) -> [f64; 3] {
    let (x, y) = ([a.lambda_n.as_slice(), &a.lambda_t].concat(), [b.lambda_n.as_slice(), &b.lambda_t].concat());
    let lambda_n_max = a.lambda_n.iter().chain(&b.lambda_n).fold(0.0_f64, |m, v| m.max(*v));
    let residual = |l: &[f64], ln: &[f64]| {
        let bound: Vec<f64> = ln.iter().map(|v| mu * v.max(0.0)).collect();
        energy_residual(problem, stabilization, l, &bound, lambda_n_max)
    };
    let (ra, rb) = (residual(&x, &a.lambda_n), residual(&y, &b.lambda_n));
    let bounds_apart: f64 =
        (0..a.lambda_n.len()).map(|j| (ra.slip[j] + rb.slip[j]) * mu * (a.lambda_n[j] - b.lambda_n[j]).abs()).sum();
    let bound = ra.sum.sqrt() + rb.sum.sqrt() + bounds_apart.sqrt();
    [energy_distance(problem, stabilization, &x, &y), bound, ra.size]
}
