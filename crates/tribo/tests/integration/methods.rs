//! Two paths to one answer: every QP solved by clarabel (the reference) and by the active-set method give
//! the same displacement (1e-8 relative) and multipliers (1e-7 relative), KKT residuals no worse than
//! clarabel's and the same number of fixed-point iterations, on the scenes of this suite: Hertz (P0 and
//! P1, matching, coarser and finer T_H), the distorted patch square and the checkerboard mesh; γ0 = 0
//! where λ is unique and γ0 > 0; frictionless, Tresca and Coulomb.
//!
//! A Tresca QP is degenerate (multipliers on their bound with a vanishing slip at the edges of the stick
//! zone), and an interior-point answer to such a QP is accurate only to about the square root of its
//! complementarity residual, not to `tol · κ(H)`: measured here, clarabel's Tresca λ is 1e-5 to 2e-3 off
//! the exact QP solution, while the active-set answer satisfies the discrete problem to 1e-14. For
//! Tresca the test therefore requires the active-set answer to satisfy (3.2) to `qp_tol` (clarabel's
//! does not) and to lie within `√r · κ(H)` of clarabel's, r clarabel's KKT residual.

use tribo::*;
use tribo_testkit::{distorted_square, hertz_problem};

fn sup(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn sup_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Solves with each method and compares; returns how many QPs the active-set method answered.
fn compare(name: &str, problem: &Problem, friction: &Friction, stabilization: Stabilization) -> usize {
    let settings = |method| SolverSettings {
        stabilization,
        qp: QpSettings { method, ..Default::default() },
        ..Default::default()
    };
    let reference = problem.solve(friction, &settings(QpMethod::Clarabel), None).expect("clarabel solves");
    assert_eq!(reference.report.status, SolveStatus::Converged, "{name}: clarabel");
    assert!(reference.report.qp_methods.iter().all(|m| *m == QpMethod::Clarabel), "{name}");
    let mut answered = 0;
    let mut answered_with_fallback = false;
    for method in [QpMethod::Auto, QpMethod::ActiveSet] {
        let sol = problem.solve(friction, &settings(method), None).expect("solves");
        let what = format!("{name}, {friction:?}, {stabilization:?}, {method}");
        if method == QpMethod::ActiveSet && matches!(sol.report.status, SolveStatus::QpFailed { .. }) {
            // Alone, the active-set method fails where auto needed clarabel (a singular free block: λ
            // not unique, T_H finer than the FE mesh with γ0 = 0), and only there.
            assert!(answered_with_fallback, "{what}: failed where auto did not fall back");
            continue;
        }
        assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
        assert_eq!(sol.report.iterations, reference.report.iterations, "{what}: fixed-point iterations");
        let du = sup_diff(&sol.displacement, &reference.displacement) / sup(&reference.displacement);
        let lam = sup(&reference.lambda_n).max(f64::MIN_POSITIVE);
        let dl = sup_diff(&sol.lambda_n, &reference.lambda_n).max(sup_diff(&sol.lambda_t, &reference.lambda_t)) / lam;
        let (k, k_ref) = (sol.kkt.max(), reference.kkt.max());
        let (tol_u, tol_l, floor) = match friction {
            Friction::Tresca(_) => {
                let kappa = tribo_testkit::condition_number(&problem.condense(stabilization).expect("condenses"));
                let t = k_ref.sqrt() * kappa;
                (t.max(1e-8), t.max(1e-7), QpSettings::default().tol)
            }
            // At the Coulomb fixed point the residuals of Coulomb's law are set by the fixed point's
            // stopping rule (fp_tol), not by the QP.
            Friction::Coulomb { .. } => (1e-8, 1e-7, FixedPointSettings::default().tol),
            // Both answers are exact to round-off: the floor of the equilibrium residual (as in `kkt`).
            Friction::Frictionless => (1e-8, 1e-7, 64.0 * f64::EPSILON * (problem.n_free as f64).sqrt()),
        };
        assert!(du <= tol_u, "{what}: u differs by {du:e} relative (allowed {tol_u:e})");
        assert!(dl <= tol_l, "{what}: λ differs by {dl:e} relative (allowed {tol_l:e})");
        assert!(k <= k_ref.max(floor), "{what}: KKT residual {k:e} against clarabel's {k_ref:e}");
        let active = sol.report.qp_methods.iter().filter(|m| **m == QpMethod::ActiveSet).count();
        if method == QpMethod::Auto {
            assert_eq!(active + sol.report.qp_fallbacks, sol.report.qp_methods.len(), "{what}: every QP tried");
            answered_with_fallback = sol.report.qp_fallbacks > 0;
            answered += active;
        }
        eprintln!(
            "{what}: du {du:.1e} dλ {dl:.1e} KKT {k:.1e} (clarabel {k_ref:.1e}, {} QPs at the fallback tolerance), {active} of {} QPs by active set, {} fallbacks",
            reference.report.qp_inaccurate,
            sol.report.qp_methods.len(),
            sol.report.qp_fallbacks
        );
    }
    answered
}

#[test]
fn active_set_and_clarabel_agree_on_hertz() {
    let mut answered = 0;
    for (points, space) in [
        (MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1),
        (MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P0),
        (MultiplierPoints::RatioToFe(2.0), MultiplierSpace::P1),
        (MultiplierPoints::Size(0.013), MultiplierSpace::P1),
    ] {
        let problem = hertz_problem(0.02, 0.01, 0.004, points.clone(), space);
        for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
            for friction in
                [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(0.5)), Friction::Coulomb { mu: 0.3 }]
            {
                answered += compare(&format!("hertz {points:?} {space}"), &problem, &friction, stabilization);
            }
        }
    }
    assert!(answered > 0, "the active-set method answered no QP");
}

#[test]
fn active_set_and_clarabel_agree_on_the_patch_and_the_checkerboard_mesh() {
    // The patch square pushed onto a flat obstacle and dragged (stick and slip along the edge).
    let spec = ProblemSpec {
        material: Material { young: 1000.0, poisson: 0.25 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["top".into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: Obstacle {
            shape: ObstacleShape::Parabola { center: 0.5, radius: 2.0 },
            approach: 1e-3,
            shift: 2e-4,
            rotation: None,
        },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    let patch = Problem::new(distorted_square(8), spec).expect("valid");
    for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
        for friction in
            [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(0.05)), Friction::Coulomb { mu: 0.3 }]
        {
            compare("patch", &patch, &friction, stabilization);
        }
    }
    // T_H finer than T_h: λ is unique only with γ0 > 0.
    let fine = tribo_testkit::checkerboard_problem(0.5, 0.05, 0.01);
    for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
        compare("checkerboard mesh H = h/2", &fine, &friction, Stabilization::Fraction(0.5));
    }
}

/// Two ways to form H (one solve per column, or all of it from a partial factorization with the Γ_C dofs
/// last) give the same answers: to round-off amplified by κ(H), far below the QP's accuracy.
#[test]
fn schur_and_columns_agree() {
    let (block, mu) = tribo_testkit::block_problem(40, 10);
    let hertz = hertz_problem(0.02, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    for (name, problem) in [("block", &block), ("hertz", &hertz)] {
        for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
            let friction = Friction::Coulomb { mu };
            let solve = |condensation| {
                let s = SolverSettings { stabilization, condensation, ..Default::default() };
                problem.solve(&friction, &s, None).expect("solves")
            };
            let (a, b) = (solve(Condensation::Columns), solve(Condensation::Schur));
            assert_eq!(a.report.condensation, Condensation::Columns);
            assert_eq!(b.report.condensation, Condensation::Schur);
            assert_eq!(a.report.status, SolveStatus::Converged, "{name}");
            assert_eq!(b.report.status, SolveStatus::Converged, "{name}");
            assert_eq!(a.report.iterations, b.report.iterations, "{name}: fixed-point iterations");
            let du = sup_diff(&a.displacement, &b.displacement) / sup(&a.displacement);
            let dl = sup_diff(&a.lambda_n, &b.lambda_n).max(sup_diff(&a.lambda_t, &b.lambda_t)) / sup(&a.lambda_n);
            eprintln!("{name} {stabilization:?}: columns vs schur du {du:.1e} dλ {dl:.1e}");
            assert!(du <= 1e-8 && dl <= 1e-7, "{name} {stabilization:?}: du {du:e} dλ {dl:e}");
        }
    }
}

/// H never formed (each active-set step on the sparse saddle-point system) against H by columns: the same
/// answers to 1e-8 (u) and 1e-7 (λ) relative, the same fixed-point iterations, KKT residuals no worse,
/// for frictionless, Tresca and Coulomb, γ0 = 0 and > 0, P0 and P1 — and every QP certified by the
/// sparse path, none handed to the dense one. The Coulomb solves take some of their steps on a bordered
/// factorization (fewer LDLᵀ than steps), so both ways to a Newton point are compared.
#[test]
fn saddle_and_columns_agree() {
    let (block, mu) = tribo_testkit::block_problem(40, 10);
    let p1 = hertz_problem(0.02, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let p0 = hertz_problem(0.02, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P0);
    for (name, problem) in [("block", &block), ("hertz P1", &p1), ("hertz P0", &p0)] {
        for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
            for friction in
                [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(0.5)), Friction::Coulomb { mu }]
            {
                let solve = |condensation| {
                    let s = SolverSettings { stabilization, condensation, ..Default::default() };
                    problem.solve(&friction, &s, None).expect("solves")
                };
                let (a, b) = (solve(Condensation::Columns), solve(Condensation::Saddle));
                let what = format!("{name} {stabilization:?} {friction:?}");
                assert_eq!(b.report.condensation, Condensation::Saddle, "{what}");
                assert_eq!(
                    (a.report.status, b.report.status),
                    (SolveStatus::Converged, SolveStatus::Converged),
                    "{what}"
                );
                assert_eq!(a.report.iterations, b.report.iterations, "{what}: fixed-point iterations");
                assert_eq!(b.report.qp_fallbacks, 0, "{what}: every QP certified by the sparse path");
                if let Friction::Coulomb { .. } = friction {
                    let (steps, factorizations) =
                        (b.report.qp_iterations.iter().sum::<u32>(), b.report.qp_factorizations.iter().sum::<u32>());
                    eprintln!("{what}: {steps} active-set steps, {factorizations} LDLᵀ");
                    assert!(factorizations < steps, "{what}: no step bordered a factorization");
                }
                let du = sup_diff(&a.displacement, &b.displacement) / sup(&a.displacement);
                let lam = sup(&a.lambda_n).max(f64::MIN_POSITIVE);
                let dl = sup_diff(&a.lambda_n, &b.lambda_n).max(sup_diff(&a.lambda_t, &b.lambda_t)) / lam;
                // As in `compare`: Coulomb's residuals are set by the fixed point's stopping rule.
                let floor = match friction {
                    Friction::Coulomb { .. } => FixedPointSettings::default().tol,
                    _ => 64.0 * f64::EPSILON * (problem.n_free as f64).sqrt(),
                };
                eprintln!(
                    "{what}: columns vs saddle du {du:.1e} dλ {dl:.1e}, KKT {:.1e} vs {:.1e}",
                    a.kkt.max(),
                    b.kkt.max()
                );
                assert!(du <= 1e-8 && dl <= 1e-7, "{what}: du {du:e} dλ {dl:e}");
                assert!(
                    b.kkt.max() <= a.kkt.max().max(floor),
                    "{what}: KKT {:e} against {:e}",
                    b.kkt.max(),
                    a.kkt.max()
                );
            }
        }
    }
}

/// `auto` takes the saddle-point system only where its steps can be factorized: on a mesh where it wins
/// (8k graded unknowns), with T_H twice as fine as the FE edges, it does with γ0 > 0 (Dγ makes the
/// system quasi-definite) and does not with γ0 = 0 (E_F rank deficient: every LDLᵀ would break down and
/// the dense path answer after all).
#[test]
fn auto_takes_the_saddle_system_only_where_it_factorizes() {
    let problem = hertz_problem(0.0025, 0.01, 0.0, MultiplierPoints::RatioToFe(0.5), MultiplierSpace::P1);
    for (stabilization, expected) in
        [(Stabilization::Fraction(0.5), Condensation::Saddle), (Stabilization::None, Condensation::Columns)]
    {
        let s = SolverSettings { stabilization, ..Default::default() };
        let sol = problem.solve(&Friction::Frictionless, &s, None).expect("solves");
        assert_eq!(sol.report.condensation, expected, "{stabilization:?}");
        assert_eq!(sol.report.status, SolveStatus::Converged, "{stabilization:?}");
    }
}
