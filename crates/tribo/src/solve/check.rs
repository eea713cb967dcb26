//! A Coulomb answer checked by the other method (`SolverSettings::coulomb_check`, issue 40's "non-uniqueness
//! said, not hidden"): where two methods converge to different answers, the report says so.
//!
//! # The bound within which two answers are one
//!
//! Write `Φ(g)` for the λ_n of the Tresca problem P(g) with the bounds μ g⁺ (the paper's Φ_H); a Coulomb solution
//! is a fixed point λ_n = Φ(λ_n), λ_t then the Tresca answer with that bound (unique: H is positive definite).
//! Each answer `a` (the fixed point's, Newton's) meets that only approximately; one more evaluation measures by how
//! much, `δ_a = ‖Φ(a) − a‖`. If Φ contracts with constant L < 1 on a set holding two answers a and b,
//!
//! ```text
//! ‖a − b‖ ≤ ‖a − Φ(a)‖ + ‖Φ(a) − Φ(b)‖ + ‖Φ(b) − b‖ ≤ δ_a + L ‖a − b‖ + δ_b,
//! so      ‖a − b‖ ≤ (δ_a + δ_b) / (1 − L).
//! ```
//!
//! Φ is evaluated by a QP to its tolerance: the computed Φ̃ = Φ + e, so the true δ is at most the measured one
//! plus ‖e‖. The QPs determine λ_n to about `√tol ‖λ_n‖` (`tol` the tolerance they met, `qp.tol` or
//! [`crate::qp::FALLBACK_TOL`]; the accuracy [`crate::Solution::accuracy_bound`] grants a converged answer's
//! KKT residuals, which a degenerate QP may reach), and not below `√tol` times the natural size of λ_n for the
//! load ([`crate::Factor::lambda_scale`], the fixed point's noise floor: λ_n ≈ 0 where nothing touches), written
//! ε_a. The two answers are one when
//!
//! ```text
//! ‖a − b‖ ≤ (δ_a + δ_b + ε_a + ε_b) / (1 − L),
//! ```
//!
//! L estimated as the largest ratio of consecutive changes over the fixed point's last three (an estimate, not a
//! bound: a contraction near an answer need not hold between two). With fewer than two changes (a warm-started
//! step of a history that converged at once) there is no estimate. A relaxed fixed point measures the relaxed map's
//! L_ω; its fixed points are Φ's and its residuals ω δ ≤ δ, so the bound with the plain δ and L_ω holds too.
//!
//! Two answers further apart are two solutions of the discrete problem to the accuracy of their residuals:
//! above a critical μ the discrete Coulomb problem may have several (the paper's §2), or the contraction
//! measured near one answer does not hold between them, and λ is not determined to better than their distance
//! either way. Two answers within `δ_a + δ_b + ε_a + ε_b` of each other cannot be told apart by their own
//! residuals: one answer, whatever L. Where the fixed point shows no contraction (no estimate, or L ≥ 1: its
//! last changes at the QPs' noise) and the two lie further apart than that, where the other method did not converge
//! or was refused, or where a QP evaluating Φ failed, there is no verdict (`undecided`): the check never turns an
//! answer into an error. Where `auto` fell back to the fixed point because Newton did not converge, Newton is not
//! run again: the check is undecided with Newton's status.
//!
//! The ratio `‖Φ(a) − Φ(b)‖ / ‖a − b‖` (the secant) is reported beside the verdict: two fixed points read 1.

use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::qp::QpStatus;
use crate::results::{Agreement, CoulombCheck, Solution, SolveStatus};
use crate::settings::friction::Friction;
use crate::settings::{CoulombMethod, SolverSettings};
use crate::solve::fixed_point::euclidean;

/// Changes of the fixed point over which its contraction is estimated (the largest ratio of consecutive ones).
const CONTRACTION_WINDOW: usize = 3;

/// One more evaluation of Φ at an answer: its λ_n, and the tolerance its QP met.
struct Evaluation {
    phi: Vec<f64>,
    tol: f64,
}

impl CoulombCheck {
    /// No verdict: the other method `method` ended `status` (`None`: refused, or a QP of the check failed).
    pub(crate) fn undecided(method: CoulombMethod, status: Option<SolveStatus>) -> Self {
        Self {
            method,
            status,
            agreement: Agreement::Undecided,
            distance: f64::NAN,
            allowed: f64::NAN,
            contraction: f64::NAN,
            secant: f64::NAN,
        }
    }
}

/// The contraction of a fixed point estimated from its changes (`history`): the largest ratio of consecutive
/// changes over the last [`CONTRACTION_WINDOW`]; NaN with fewer than two.
fn contraction(history: &[f64]) -> f64 {
    let last = &history[history.len().saturating_sub(CONTRACTION_WINDOW)..];
    last.windows(2).map(|w| if w[0] > 0.0 { w[1] / w[0] } else { f64::INFINITY }).fold(f64::NAN, f64::max)
}

impl Condensed<'_> {
    /// Φ at the answer `sol` (its λ_n, the QP started from its λ), or `None` where that QP failed or was refused.
    fn evaluate_phi(
        &self,
        mu: &[f64],
        settings: &SolverSettings,
        loading: &LoadCase,
        sol: &Solution,
    ) -> Option<Evaluation> {
        let start = [sol.lambda_n.as_slice(), sol.lambda_t.as_slice()].concat();
        let bound: Vec<f64> = sol.lambda_n.iter().zip(mu).map(|(l, m)| m * l.max(0.0)).collect();
        let out = self.contact_qp(loading, Some(&bound), settings, Some(&start)).and_then(|mut qp| qp.solve());
        let out = out.map_err(|e| log::warn!("the check's evaluation of Φ_H: {e}")).ok()?;
        let tol = match out.status {
            QpStatus::Solved => settings.qp.tol,
            QpStatus::Inaccurate => settings.qp.tol.max(crate::qp::FALLBACK_TOL),
            QpStatus::Failed(_) => return None,
        };
        Some(Evaluation { phi: out.nu[..self.q()].to_vec(), tol })
    }

    /// Checks the converged Coulomb answer `answer` (of the law `friction`, coefficients `mu` per multiplier dof)
    /// by the other method, solving `loading` again from `start` as the answer was. Never an error: what keeps the
    /// check from a verdict makes it undecided (the log says why).
    pub(super) fn check_coulomb(
        &self,
        (friction, mu): (&Friction, &[f64]),
        settings: &SolverSettings,
        loading: &LoadCase,
        start: Option<&[f64]>,
        answer: &Solution,
    ) -> CoulombCheck {
        let method = match answer.report.coulomb_method {
            Some(CoulombMethod::Newton) => CoulombMethod::FixedPoint,
            _ => CoulombMethod::Newton,
        };
        let other = match self.solve_loading_by(friction, method, settings, loading, start, None) {
            Ok(other) => other,
            Err(e) => {
                log::warn!("the check of the Coulomb answer by {method}: {e}: no verdict");
                return CoulombCheck::undecided(method, None);
            }
        };
        if other.report.status != SolveStatus::Converged {
            log::warn!("the check of the Coulomb answer by {method} ended {}: no verdict", other.report.status);
            return CoulombCheck::undecided(method, Some(other.report.status));
        }
        let (Some(ea), Some(eb)) =
            (self.evaluate_phi(mu, settings, loading, answer), self.evaluate_phi(mu, settings, loading, &other))
        else {
            log::warn!("a QP evaluating Φ_H at the two Coulomb answers failed: no verdict");
            return CoulombCheck::undecided(method, None);
        };
        let (a, b) = (&answer.lambda_n, &other.lambda_n);
        let norm = |v: &[f64]| euclidean(v.iter().copied());
        let minus = |x: &[f64], y: &[f64]| euclidean(x.iter().zip(y).map(|(p, q)| p - q));
        // The natural size of λ_n for this load: the floor of what the QPs determine (nothing touches: λ_n ≈ 0).
        let floor = self.factor().lambda_scale(&loading.c);
        let residuals = minus(&ea.phi, a)
            + minus(&eb.phi, b)
            + ea.tol.sqrt() * norm(a).max(floor)
            + eb.tol.sqrt() * norm(b).max(floor);
        let fixed_point = if method == CoulombMethod::FixedPoint { &other } else { answer };
        let contraction = contraction(&fixed_point.report.residual_history);
        let d = minus(a, b);
        let scale = norm(a).max(norm(b)).max(floor).max(f64::MIN_POSITIVE);
        let contracts = contraction < 1.0; // (false for NaN: no estimate)
        let allowed = if contracts { residuals / (1.0 - contraction) } else { f64::INFINITY };
        let agreement = if d <= residuals || (contracts && d <= allowed) {
            Agreement::Agree
        } else if contracts {
            Agreement::Differ
        } else {
            Agreement::Undecided
        };
        let check = CoulombCheck {
            method,
            status: Some(other.report.status),
            agreement,
            distance: d / scale,
            allowed: allowed / scale,
            contraction,
            secant: if d > 0.0 { minus(&ea.phi, &eb.phi) / d } else { f64::NAN },
        };
        match agreement {
            Agreement::Differ => log::warn!(
                "two Coulomb answers: the answer and the check by {method} lie {} apart in λ_n (relative), \
                 further than their residuals allow ({}): λ is not unique here, or not determined to better than \
                 that",
                crate::error::Num(check.distance),
                crate::error::Num(check.allowed)
            ),
            _ => log::info!("the Coulomb answer checked by {method}: {agreement}"),
        }
        check
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, DVector};

    use crate::mesh::generate::{rectangle, Diagonal};
    use crate::problem::load_case::LoadCase;
    use crate::*;

    /// True when `x` solves the discrete Coulomb problem `min ½ νᵀHν + cᵀν`, ν_n ≥ 0, |ν_t| ≤ μ ν_n in the sense
    /// of (3.1) (the Tresca conditions with the bound μ λ_n of `x` itself), to 1e-7 relative (the fixed point
    /// stops when λ_n changes by less than fp_tol = 1e-8 relative, its λ_t on the bound of the λ_n before): per
    /// dof, λ_n ≥ 0, r_n = (Hx + c)_n ≥ 0 and 0 where λ_n > 0, |λ_t| ≤ μ λ_n, r_t = 0 where |λ_t| < μ λ_n,
    /// r_t ≤ 0 where λ_t = μ λ_n and r_t ≥ 0 where λ_t = −μ λ_n.
    fn satisfies(h: &DMatrix<f64>, c: &DVector<f64>, mu: f64, x: &DVector<f64>) -> bool {
        let q = c.len() / 2;
        let r = h * x + c;
        let (sx, sr) = (1e-7 * x.amax(), 1e-7 * c.amax());
        (0..q).all(|j| {
            let (n, t) = (j, q + j);
            let bound = mu * x[n];
            x[n] >= -sx
                && r[n] >= -sr
                && (x[n] <= sx || r[n].abs() <= sr)
                && x[t].abs() <= bound + sx
                && (x[t] < bound - sx || r[t] <= sr)
                && (x[t] > -bound + sx || r[t] >= -sr)
                && (x[t].abs() >= bound - sx || r[t].abs() <= sr)
        })
    }

    /// The vertices of the solution set of the discrete Coulomb problem ([`satisfies`]), found by trying each dof
    /// in each state (separation, stick, slip forward, slip backward: 4^q linear systems), and whether one of those
    /// systems was singular (the set may then hold a segment besides its vertices).
    fn every_solution(h: &DMatrix<f64>, c: &[f64], mu: f64) -> (Vec<DVector<f64>>, bool) {
        let q = c.len() / 2;
        let c = DVector::from_column_slice(c);
        let (mut found, mut singular): (Vec<DVector<f64>>, bool) = (Vec::new(), false);
        for code in 0..4_usize.pow(q as u32) {
            let state = |j: usize| (code / 4_usize.pow(j as u32)) % 4;
            let (mut m, mut rhs) = (DMatrix::<f64>::zeros(2 * q, 2 * q), DVector::<f64>::zeros(2 * q));
            for j in 0..q {
                let (n, t) = (j, q + j);
                if state(j) == 0 {
                    (m[(n, n)], m[(t, t)]) = (1.0, 1.0);
                    continue;
                }
                m.row_mut(n).copy_from(&h.row(n));
                rhs[n] = -c[n];
                if state(j) == 1 {
                    m.row_mut(t).copy_from(&h.row(t));
                    rhs[t] = -c[t];
                } else {
                    (m[(t, t)], m[(t, n)]) = (1.0, if state(j) == 2 { -mu } else { mu });
                }
            }
            let Some(x) = m.lu().solve(&rhs) else {
                singular = true;
                continue;
            };
            if satisfies(h, &c, mu, &x) && !found.iter().any(|y| (y - &x).amax() <= 1e-7 * x.amax()) {
                found.push(x);
            }
        }
        (found, singular)
    }

    /// The block of the tests below: `nx × ny` cells of `w × 1` (E = 1, ν), clamped at its top, pressed by 0.01
    /// on a rigid flat and shifted by `shift`, with P0 multipliers (one per cell on its bottom).
    fn block(nx: usize, ny: usize, w: f64, nu: f64, shift: f64) -> Problem {
        let mesh = rectangle([0.0, w], [0.0, 1.0], nx, ny, Diagonal::Alternating).expect("a valid block");
        let spec = ProblemSpec::new(Material { young: 1.0, poisson: nu }, "bottom")
            .clamped(["top"])
            .approach(0.01)
            .shift(shift)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P0);
        Problem::new(mesh, spec).expect("a valid problem")
    }

    /// `problem`'s QP with γ0 from `stabilization`: H and c.
    fn qp_of(problem: &Problem, stabilization: Stabilization) -> (DMatrix<f64>, DVector<f64>) {
        let condensed = problem.condense(stabilization).expect("condensed");
        let q = condensed.q();
        let h = DMatrix::from_column_slice(2 * q, 2 * q, &condensed.factor().dense_h());
        (h, DVector::from_column_slice(&LoadCase::of_problem(problem, condensed.factor()).c))
    }

    fn lambda(sol: &Solution) -> DVector<f64> {
        DVector::from_iterator(2 * sol.lambda_n.len(), sol.lambda_n.iter().chain(&sol.lambda_t).copied())
    }

    fn checked(stabilization: Stabilization, coulomb: CoulombMethod) -> SolverSettings {
        SolverSettings { stabilization, coulomb, coulomb_check: true, ..Default::default() }
    }

    /// A genuine non-uniqueness, and the check saying so. Two blocks whose discrete Coulomb problem has several
    /// solutions (found by enumerating the states of their dofs):
    /// - 2 × 1 cells of 1 × 1, ν = 0.4, μ = 0.5, γ0 = 0 (the classic mixed method): the segment between two
    ///   vertices 10 % apart in λ_n (both dofs slip);
    /// - 2 × 2 cells of 0.44 × 1, ν = 0.4, μ = 0.6, shifted by 1e-4, γ0 = ½ bound: three vertices.
    ///
    /// The fixed point and Newton each report `converged` on a solution (checked here on H and c), not the same
    /// one; with `coulomb_check` each says that the other found another answer (`differ`, far beyond the bound),
    /// and the secant of Φ_H between the two is 1, as between two fixed points.
    #[test]
    fn two_methods_find_two_solutions_and_the_check_says_so() {
        for (problem, stabilization, mu, vertices) in [
            (block(2, 1, 1.0, 0.4, 0.0), Stabilization::None, 0.5, 2),
            (block(2, 2, 0.44, 0.4, 1e-4), Stabilization::Fraction(0.5), 0.6, 3),
        ] {
            let (h, c) = qp_of(&problem, stabilization);
            let (solutions, _) = every_solution(&h, c.as_slice(), mu);
            assert_eq!(solutions.len(), vertices, "{stabilization:?}: {solutions:?}");
            let mut answers = Vec::new();
            for coulomb in [CoulombMethod::FixedPoint, CoulombMethod::Newton] {
                let sol =
                    problem.solve(&Friction::Coulomb { mu }, &checked(stabilization, coulomb), None).expect("solved");
                let what = format!("{stabilization:?}, {coulomb}");
                assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
                assert!(satisfies(&h, &c, mu, &lambda(&sol)), "{what}: a solution");
                let check = sol.report.coulomb_check.expect("checked");
                let other =
                    if coulomb == CoulombMethod::Newton { CoulombMethod::FixedPoint } else { CoulombMethod::Newton };
                assert_eq!(check.method, other);
                assert_eq!(
                    (check.status, check.agreement),
                    (Some(SolveStatus::Converged), Agreement::Differ),
                    "{what}"
                );
                assert!(check.distance > 0.01 && check.allowed < 1e-5, "{what}: {check:?}");
                assert!((check.secant - 1.0).abs() < 1e-6, "{what}: two fixed points: {check:?}");
                answers.push(lambda(&sol));
            }
            assert!((&answers[0] - &answers[1]).norm() > 0.01 * answers[0].norm(), "two solutions");
            // Without the check, the report has none.
            let plain = SolverSettings { stabilization, ..Default::default() };
            assert_eq!(
                problem.solve(&Friction::Coulomb { mu }, &plain, None).expect("solved").report.coulomb_check,
                None
            );
        }
    }

    /// Over 384 blocks (1 or 2 rows of 2 cells, four widths, ν from 0 to 0.45, μ from 0.4 to 2, three shifts, γ0 = 0
    /// and ½ bound), each answered by each method and checked by the other, the check is never wrong: where it says
    /// `differ`, both answers solve the problem (checked on H and c); where the enumeration finds one solution and
    /// no segment, it never says `differ`; it is undecided only where the other method did not converge or no
    /// contraction was measured.
    #[test]
    fn the_check_says_differ_only_where_there_are_two_solutions() {
        let mut several = 0;
        let mut verdicts = std::collections::BTreeMap::new();
        for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
            for (ny, w) in [(1, 0.5), (1, 1.0), (2, 0.44), (2, 0.8)] {
                for nu in [0.0, 0.2, 0.4, 0.45] {
                    for mu in [0.4, 0.6, 1.0, 2.0] {
                        for shift in [0.0, 1e-4, -1e-3] {
                            let problem = block(2, ny, w, nu, shift);
                            let (h, c) = qp_of(&problem, stabilization);
                            let (solutions, singular) = every_solution(&h, c.as_slice(), mu);
                            let unique = solutions.len() == 1 && !singular;
                            several += usize::from(solutions.len() > 1);
                            for coulomb in [CoulombMethod::FixedPoint, CoulombMethod::Newton] {
                                let what = format!(
                                    "{stabilization:?} {ny} × 2 cells of {w}, ν {nu}, μ {mu}, shift {shift}, {coulomb}"
                                );
                                let settings = checked(stabilization, coulomb);
                                let sol = problem.solve(&Friction::Coulomb { mu }, &settings, None).expect("solved");
                                let verdict = sol.report.coulomb_check.map(|c| c.agreement);
                                *verdicts.entry((coulomb.as_str(), verdict.map(Agreement::as_str))).or_insert(0) += 1;
                                if sol.report.status != SolveStatus::Converged {
                                    // (the fixed point cycles on a few, Newton stagnates on some: nothing to check)
                                    assert_eq!(verdict, None, "{what}");
                                    continue;
                                }
                                assert!(satisfies(&h, &c, mu, &lambda(&sol)), "{what}: a solution");
                                let check = sol.report.coulomb_check.expect("checked");
                                match check.agreement {
                                    Agreement::Differ => {
                                        assert!(!unique, "{what}: differ on a unique problem");
                                        let by = checked(stabilization, check.method);
                                        let other =
                                            problem.solve(&Friction::Coulomb { mu }, &by, None).expect("solved");
                                        assert!(satisfies(&h, &c, mu, &lambda(&other)), "{what}: the other answer");
                                    }
                                    Agreement::Agree => {}
                                    Agreement::Undecided => assert!(
                                        check.status != Some(SolveStatus::Converged)
                                            || check.contraction.is_nan()
                                            || check.contraction >= 1.0,
                                        "{what}: {check:?}"
                                    ),
                                }
                            }
                        }
                    }
                }
            }
        }
        eprintln!("several vertices in {several} of 384 blocks; verdicts by the method that answered: {verdicts:?}");
        // What the docs quote (docs/measured.md), as lower bounds: the grid does hold non-unique problems, and the
        // check does find two answers on them from either method.
        assert!(several >= 60, "{several}");
        for coulomb in [CoulombMethod::FixedPoint, CoulombMethod::Newton] {
            assert!(verdicts.get(&(coulomb.as_str(), Some("differ"))).is_some_and(|&n| n >= 5), "{verdicts:?}");
        }
    }
}
