//! The discrete KKT residuals of (3.1) at a returned solution, each made dimensionless: what a
//! `converged` status promises is that they are within what the tolerances justify
//! ([`crate::Solution::accuracy_bound`]).

use crate::condensation::Factor;
use crate::problem::load_case::LoadCase;

/// Discrete KKT residuals of (3.1) at the returned solution, each made dimensionless.
///
/// With `r = E u − d − Dγ λ` (the discrete, stabilized gap and slip: `r_n ≤ 0` is non-penetration),
/// `Λ = max(‖λ‖∞, Factor::lambda_scale, ‖bound‖∞)` (the size of the multipliers, tangential ones and a
/// Tresca threshold included) and `R = max(‖E‖ ‖u‖, ‖d‖, ‖Dγ λ‖)` (∞-norms; the size of the
/// terms of r, so that its round-off is ε R). A residual whose numerator vanishes is 0 whatever its scale:
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct KktResiduals {
    /// `‖A u + Eᵀ λ − f‖_∞ / max(‖f‖_∞, ‖Eᵀ λ‖_∞)`: the equation of (3.1).
    pub equilibrium: f64,
    /// `max(−λ_n)₊ / Λ`.
    pub normal_sign: f64,
    /// `max(r_n)₊ / R`: penetration in the weak sense of the method.
    pub non_penetration: f64,
    /// `max |λ_n r_n| / (Λ R)`.
    pub normal_complementarity: f64,
    /// `max(|λ_t| − bound)₊ / Λ` (bound = μ λ_n, or the Tresca threshold).
    pub friction_bound: f64,
    /// `max (bound − |λ_t|) |r_t| / (Λ R)`: no slip below the threshold.
    pub stick: f64,
    /// `max (−λ_t r_t)₊ / (Λ R)`: slip in the direction of λ_t.
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
    // The scales: Λ the size of λ_n (never 0 when something pushes), R the size of the terms of r (its
    // round-off is ε R): ‖E‖ ‖u‖ bounds ‖E u‖ and stays positive when the terms cancel.
    let lam = inf(lambda).max(c.lambda_scale(&loading.c)).max(inf(bound));
    // (‖E‖ ‖x‖ over the displacements and over a mixed formulation's pressures apart: units differ.)
    let e_norm = |part: &dyn Fn(usize) -> bool| {
        c.e_rows.iter().map(|row| row.iter().filter(|e| part(e.0)).map(|e| e.1.abs()).sum::<f64>()).fold(0.0, f64::max)
    };
    let (e_u, e_p) = (e_norm(&|k| k < n_u), e_norm(&|k| k >= n_u));
    let gap_scale = (e_u * inf(&u[..n_u])).max(e_p * inf(&u[n_u..])).max(inf(&loading.d)).max(inf(&dl));
    let equilibrium = nan_max(ratio(inf(&res[..n_u]), eq_scale), pressure_rows);
    let mut k = KktResiduals { equilibrium, ..Default::default() };
    // Positive parts and maxima propagate NaN (`f64::max` would drop it); products of two ratios never
    // underflow to 0/0.
    let pos = |x: f64| nan_max(x, 0.0);
    for j in 0..q {
        let (ln, lt) = (ratio(lambda[j], lam), ratio(lambda[q + j], lam));
        let (rn, rt) = (ratio(r[j], gap_scale), ratio(r[q + j], gap_scale));
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
