//! The discrete KKT residuals of (3.1) at a returned solution, each made dimensionless: what a
//! `converged` status promises is that they are within what the tolerances justify
//! ([`crate::Solution::accuracy_bound`]).

use crate::condensation::Factor;
use crate::problem::load_case::LoadCase;

/// Discrete KKT residuals of (3.1) at the returned solution, each made dimensionless.
///
/// With `r = E u − d − Dγ λ` (the discrete, stabilized gap and slip: `r_n ≤ 0` is non-penetration), `Λ = max(‖λ‖∞,
/// Factor::lambda_scale, ‖bound‖∞)` (the size of the multipliers, tangential ones and a Tresca threshold included) and,
/// per multiplier dof j, `R_j = max(‖E_j‖₁ ‖u‖∞, |d_j|, (Dγ 1)_j ‖λ‖∞)` (`E_j` the row of E): the size of the terms of
/// r_j, so that its round-off is ε R_j. Each r_j is a moment `∫ψ_j (…)` and scales with the length of ψ_j's support:
/// measured against a single R for all dofs, a dof of a cell 1/50 of the largest was judged 50 times too
/// leniently (and every dof as many times as the obstacle's gap far from the contact was larger than near it, through
/// the largest |d_j|). On a graded mesh, an answer 13 % off in λ_t at such a dof (an interior-point QP stopped on too
/// loose a gap) read 5e-11 against one R, and reads 7e-7 against its own R_j: within the 1e-5 that the QP's fallback
/// tolerance allowed it.
/// A residual whose numerator vanishes is 0 whatever its scale:
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct KktResiduals {
    /// `‖A u + Eᵀ λ − f‖_∞ / max(‖f‖_∞, ‖Eᵀ λ‖_∞)`: the equation of (3.1).
    pub equilibrium: f64,
    /// `max(−λ_n)₊ / Λ`.
    pub normal_sign: f64,
    /// `max(r_n / R_j)₊`: penetration in the weak sense of the method.
    pub non_penetration: f64,
    /// `max |λ_n r_n| / (Λ R_j)`.
    pub normal_complementarity: f64,
    /// `max(|λ_t| − bound)₊ / Λ` (bound = μ λ_n, or the Tresca threshold).
    pub friction_bound: f64,
    /// `max (bound − |λ_t|) |r_t| / (Λ R_j)`: no slip below the threshold.
    pub stick: f64,
    /// `max (−λ_t r_t)₊ / (Λ R_j)`: slip in the direction of λ_t.
    pub slip_direction: f64,
}

impl KktResiduals {
    /// Every residual by name, in the order of the fields.
    pub fn named(&self) -> [(&'static str, f64); 7] {
        [
            ("equilibrium", self.equilibrium),
            ("normal_sign", self.normal_sign),
            ("non_penetration", self.non_penetration),
            ("normal_complementarity", self.normal_complementarity),
            ("friction_bound", self.friction_bound),
            ("stick", self.stick),
            ("slip_direction", self.slip_direction),
        ]
    }

    /// Largest residual; NaN if any residual is NaN.
    pub fn max(&self) -> f64 {
        [
            self.equilibrium,
            self.normal_sign,
            self.non_penetration,
            self.normal_complementarity,
            self.friction_bound,
            self.stick,
            self.slip_direction,
        ]
        .into_iter()
        .fold(0.0, nan_max)
    }
}

/// The larger of two values, NaN if either is NaN (`f64::max` drops a NaN).
pub(crate) fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// `num / den`, 0 when `num` is 0 (a residual that vanishes is 0 whatever its scale, even a vanishing
/// one), NaN propagated.
fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else {
        num / den
    }
}

pub(crate) fn kkt_residuals(
    c: &Factor,
    k: faer::sparse::SparseColMatRef<'_, usize, f64>,
    loading: &LoadCase,
    u: &[f64],
    lambda: &[f64],
    bound: &[f64],
    n_u: usize,
) -> KktResiduals {
    let q = c.q();
    let au = c.apply_a(k, u);
    let etl = c.apply_et(lambda);
    let inf = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| nan_max(m, x.abs()));
    let res: Vec<f64> = au.iter().zip(&etl).zip(&loading.f_free).map(|((a, e), f)| a + e - f).collect();
    let eq_scale = inf(&loading.f_free[..n_u]).max(inf(&etl[..n_u]));
    // A mixed formulation's pressure rows (after the n_u displacement unknowns) are constraints, not forces:
    // each is judged against the size of its own terms, |K| |x| and its load.
    let mut terms = loading.f_free[n_u..].iter().map(|f| f.abs()).collect::<Vec<f64>>();
    for (j, xj) in u.iter().enumerate() {
        for (i, v) in k.row_idx_of_col(j).zip(k.val_of_col(j)).filter(|(i, _)| *i >= n_u) {
            terms[i - n_u] += (v * xj).abs();
        }
    }
    let pressure_rows = inf(&res[n_u..]) / inf(&terms).max(f64::MIN_POSITIVE);
    let eu = c.apply_e(u);
    // r = E u − d − Dγ λ.
    let dl = c.apply_d(lambda);
    let r: Vec<f64> = eu.iter().zip(&loading.d).zip(&dl).map(|((a, b), dl)| a - b - dl).collect();
    // The scales: Λ the size of λ_n (never 0 when something pushes), R_j the size of the terms of r_j (its
    // round-off is ε R_j), which stays positive when the terms cancel. ‖E_j‖₁ ‖u‖∞ and (Dγ 1)_j ‖λ‖∞ rather than
    // Σ_k |E_jk u_k|: the round-off of a solve is relative to the size of its answer, not to each entry (u_n is 0
    // up to ε ‖u‖ where a flat body rests on a flat obstacle). The displacements and a mixed formulation's
    // pressures apart: their units differ. Dγ's entries are ∫γψψ ≥ 0 (P0, P1), so (Dγ 1)_j ‖λ‖∞ ≥ |(Dγ λ)_j|.
    let lam = inf(lambda).max(c.lambda_scale(&loading.c)).max(inf(bound));
    let (u_max, p_max, lambda_max) = (inf(&u[..n_u]), inf(&u[n_u..]), inf(lambda));
    let d_ones = c.apply_d(&vec![1.0; lambda.len()]);
    let gap_scale: Vec<f64> = (0..r.len())
        .map(|j| {
            let row =
                |part: &dyn Fn(usize) -> bool| c.e_rows[j].iter().filter(|e| part(e.0)).map(|e| e.1.abs()).sum::<f64>();
            let terms = (row(&|k| k < n_u) * u_max).max(row(&|k| k >= n_u) * p_max);
            terms.max(loading.d[j].abs()).max(d_ones[j] * lambda_max)
        })
        .collect();
    let equilibrium = nan_max(ratio(inf(&res[..n_u]), eq_scale), pressure_rows);
    let mut k = KktResiduals { equilibrium, ..Default::default() };
    // Positive parts and maxima propagate NaN (`f64::max` would drop it); products of two ratios never
    // underflow to 0/0.
    let pos = |x: f64| nan_max(x, 0.0);
    for j in 0..q {
        let (ln, lt) = (ratio(lambda[j], lam), ratio(lambda[q + j], lam));
        let (rn, rt) = (ratio(r[j], gap_scale[j]), ratio(r[q + j], gap_scale[q + j]));
        let b = ratio(bound[j], lam);
        k.normal_sign = nan_max(k.normal_sign, pos(-ln));
        k.non_penetration = nan_max(k.non_penetration, pos(rn));
        k.normal_complementarity = nan_max(k.normal_complementarity, (ln * rn).abs());
        k.friction_bound = nan_max(k.friction_bound, pos(lt.abs() - b));
        k.stick = nan_max(k.stick, pos(b - lt.abs()) * rt.abs());
        k.slip_direction = nan_max(k.slip_direction, pos(-lt * rt));
    }
    k
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::contact::obstacle::GapFunction;
    use crate::{
        graded_rectangle, Friction, Grading, Material, MultiplierPoints, MultiplierSpace, ObstacleShape, Problem,
        ProblemSpec, QpMethod, QpSettings, Side, SolverSettings, Threshold,
    };

    /// Hertz with a Tresca threshold of 1 on a mesh graded from cells of 0.25 to 0.005 at the contact (the obstacle
    /// `shape`), and the stick residual of its exact answer moved by 0.01 in λ_t at the stick dof nearest the
    /// centre (u = A⁻¹(f − Eᵀλ) of the moved λ), with the old residual beside it: the same product against one
    /// scale for all dofs, `max(‖E‖ ‖u‖, ‖d‖, ‖Dγ λ‖)`.
    fn moved_stick_residual(shape: ObstacleShape) -> (f64, f64) {
        let grading = Grading { side: Side::Top, segment: [-0.2, 0.2], h_min: 0.005, h_max: 0.25, growth: 0.3 };
        let mesh = graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading).expect("valid mesh");
        let spec = ProblemSpec::new(Material { young: 200.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .obstacle(shape)
            .approach(0.01)
            .shift(0.004)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).expect("valid problem");
        let friction = Friction::Tresca(Threshold::Uniform(1.0));
        let settings = SolverSettings {
            qp: QpSettings { method: QpMethod::ActiveSet, ..Default::default() },
            ..Default::default()
        };
        let exact = problem.solve(&friction, &settings, None).expect("solves");
        let condensed = problem.condense(settings.stabilization).expect("condenses");
        let (factor, q) = (condensed.factor(), exact.lambda_n.len());
        let loading = LoadCase::of_problem(&problem, factor);
        let j = (0..q)
            .filter(|&j| exact.lambda_t[j].abs() < 0.5 && exact.lambda_n[j] > 0.0)
            .min_by(|&a, &b| exact.multiplier_abscissae[a].abs().total_cmp(&exact.multiplier_abscissae[b].abs()))
            .expect("a dof sticks");
        let mut lambda = [exact.lambda_n.as_slice(), exact.lambda_t.as_slice()].concat();
        lambda[q + j] += 0.01;
        let u = factor.displacement(&loading.f_free, &lambda).expect("solves");
        let k = kkt_residuals(factor, problem.k_matrix.as_ref(), &loading, &u, &lambda, &vec![1.0; q], u.len());
        // What the old measure read at j: the same product over the one scale instead of R_j.
        let inf = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let row = |i: usize| factor.e_rows[i].iter().map(|e| e.1.abs()).sum::<f64>();
        let r_j = (row(q + j) * inf(&u))
            .max(loading.d[q + j].abs())
            .max(factor.apply_d(&vec![1.0; 2 * q])[q + j] * inf(&lambda));
        let e_max = (0..2 * q).map(row).fold(0.0, f64::max);
        let one = (e_max * inf(&u)).max(inf(&loading.d)).max(inf(&factor.apply_d(&lambda)));
        (k.stick, k.stick * r_j / one)
    }

    /// The residual at a dof reads its own terms: where the obstacle lies 1000 times further away far from the
    /// contact (the same circle within |ξ| < 0.5, where the contact is 0.1 wide), the answer is the same, and so is
    /// the stick residual of a move of λ_t at a fine dof (to 1e-6). Against one scale for all dofs, that of the
    /// largest gap moment far away, the same move read 500 times smaller, and a move of that size at a fine dof of
    /// a graded mesh passed as converged (an interior-point answer 13 % off in λ_t at one dof read 5e-11).
    #[test]
    fn a_residual_at_a_dof_does_not_depend_on_the_gap_far_away() {
        let circle = |x: f64| 1.0 - (1.0 - x * x).max(0.0).sqrt();
        let far = move |x: f64| circle(x) + 1000.0 * (x.abs() - 0.5).max(0.0).powi(2);
        let (near, old_near) = moved_stick_residual(ObstacleShape::Function(GapFunction(Arc::new(circle))));
        let (away, old_away) = moved_stick_residual(ObstacleShape::Function(GapFunction(Arc::new(far))));
        assert!(near > 0.0 && ((away - near) / near).abs() < 1e-6, "{near:e} and {away:e}");
        assert!(old_near / old_away > 100.0, "one scale for all: {old_near:e} and {old_away:e}");
    }
}
