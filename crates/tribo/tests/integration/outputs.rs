//! What a reader gets back: global force components, the obstacle's motion, the full plane-strain
//! stress, the current gap, numbers in messages formatted for people, and the condensation's progress.

use std::ops::ControlFlow;

use tribo::*;
use tribo_testkit::hertz_problem;

/// A unit square pressed on its `contact` side by a flat obstacle (approach 0.01, shift 0.004), clamped on
/// the opposite side.
fn square(contact: &str, clamped: &str) -> Problem {
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 8, 8, Diagonal::Right).unwrap();
    let spec = ProblemSpec {
        material: Material { young: 1.0, poisson: 0.3 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![clamped.into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: contact.into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach: 0.01, shift: 0.004, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    Problem::new(mesh, spec).unwrap()
}

/// (Fx, Fy) = −(N n + T t) is the force of the obstacle on the body: it balances the reactions of the
/// support, on every side of the square (n along ±x and ±y), and the obstacle's motion is −δ n + s t.
#[test]
fn contact_force_is_global_and_balances_the_reactions() {
    for (contact, clamped, n) in
        [("top", "bottom", [0.0, 1.0]), ("right", "left", [1.0, 0.0]), ("bottom", "top", [0.0, -1.0])]
    {
        let problem = square(contact, clamped);
        let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let t = [-n[1], n[0]];
        assert_eq!(problem.contact.normal.map(|v| v + 0.0), n, "{contact}");
        let (fx, fy) = (sol.contact_force[0], sol.contact_force[1]);
        let expected = [0, 1].map(|i| -(sol.normal_force * n[i] + sol.tangential_force * t[i]));
        assert_eq!([fx, fy], expected, "{contact}");
        // The obstacle pushes the body inward, and friction drags it the way the obstacle moved (+t).
        assert!(fx * n[0] + fy * n[1] < 0.0, "{contact}: ({fx}, {fy})");
        assert!(fx * t[0] + fy * t[1] > 0.0, "{contact}: friction ({fx}, {fy}) against the shift along t");
        let rx: f64 = sol.reactions.iter().step_by(2).sum();
        let ry: f64 = sol.reactions.iter().skip(1).step_by(2).sum();
        // Both sides are sums of O(n) rounded terms: n · 64 ε relative.
        let tol = problem.n_free as f64 * 64.0 * f64::EPSILON * sol.normal_force;
        assert!(
            (rx + fx).abs() <= tol && (ry + fy).abs() <= tol,
            "{contact}: reactions ({rx}, {ry}), force ({fx}, {fy})"
        );
        let motion = [0, 1].map(|i| -0.01 * n[i] + 0.004 * t[i]);
        assert_eq!(sol.obstacle_motion, motion, "{contact}");
    }
}

/// σ_zz = ν (σ_xx + σ_yy) per triangle, and the von Mises stress is that of the full tensor; the
/// current gap is g − u_n, 0 up to the weak non-penetration in contact, its minimum the largest
/// penetration.
#[test]
fn plane_strain_stress_and_current_gap() {
    let problem = hertz_problem(0.02, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).unwrap();
    let nu = problem.spec.material.poisson;
    for ((s, zz), vm) in sol.stress.iter().zip(&sol.stress_zz).zip(&sol.von_mises) {
        assert_eq!(*zz, nu * (s[0] + s[1]));
        let (a, b, c) = (s[0] - s[1], s[1] - zz, zz - s[0]);
        let full = (0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]).sqrt();
        assert!((full - vm).abs() <= 1e-12 * vm.abs().max(f64::MIN_POSITIVE), "{full} vs {vm}");
    }
    let current = sol.current_gap();
    for ((c, g), u) in current.iter().zip(&sol.gap).zip(&sol.u_n) {
        assert_eq!(*c, g - u);
    }
    let min = current.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(-min, sol.max_penetration);
    assert!(current.iter().any(|c| *c > 0.0));
}

/// Numbers in messages: three significant digits, plain decimals between 0.01 and 10⁴, never `0e0`.
#[test]
fn numbers_are_formatted_for_people() {
    let cases = [
        (2.626396615835748e-3, "2.63e-3"),
        (0.2626396615835748, "0.263"),
        (0.0, "0"),
        (-0.0, "0"),
        (200.0, "200"),
        (1234.6, "1235"),
        (12345.0, "1.23e4"),
        (1e-12, "1e-12"),
        (-1.5e7, "-1.5e7"),
        (0.009996, "0.01"),
        (9.9996e3, "1e4"),
        (f64::NAN, "NaN"),
        (f64::INFINITY, "inf"),
        (f64::NEG_INFINITY, "-inf"),
    ];
    for (x, text) in cases {
        assert_eq!(Num(x).to_string(), text, "{x:e}");
    }
    assert_eq!(format!("{:.5}", Num(0.1 + 0.2)), "0.3");
    assert_eq!(format!("{:.6}", Num(2.626396615835748e-3)), "2.6264e-3");
}

/// The core's messages use that format: no `e0`, no sixteen digits.
#[test]
fn error_messages_format_numbers_for_people() {
    let err = Material { young: -2.5, poisson: 0.3 }.validate().unwrap_err().to_string();
    assert!(err.ends_with("got -2.5"), "{err}");
    let err = Material { young: 1.0, poisson: 0.5 - 1e-9 }.validate().unwrap_err().to_string();
    assert!(err.contains("1 − 2ν = 2e-9") && err.contains("√ε = 1.49e-8"), "{err}");
    let problem = square("top", "bottom");
    let bound = problem.gamma0_bound.value;
    let err = problem.condense(Stabilization::Gamma0(1.2 * bound)).unwrap_err().to_string();
    for text in [Num(1.2 * bound), Num(bound)].map(|n| format!("{n:.4}")) {
        assert!(err.contains(&text), "{err} should contain {text}");
    }
    let err = problem.condense(Stabilization::Unchecked(1e3 * bound)).unwrap_err().to_string();
    assert!(err.contains(&format!("admissible bound {}", Num(bound))), "{err}");
    for err in [
        Error::DegenerateTriangle { element: 3, area: 0.0, diameter_sq: 2.626396615835748e-1 },
        Error::SingularStiffness { residual: 0.0 },
        Error::Gamma0TooLarge { gamma0: 0.0, bound: 0.0, element: 1 },
    ] {
        let text = err.to_string();
        assert!(!text.contains("e0") && !text.contains("0.2626396"), "{text}");
    }
}

/// The observer hears of the condensation once, before any QP, with its time; the QP reports carry
/// the condensation time so far (columns of H formed during the QPs count). Stopping at the condensation
/// solves no QP and returns λ = 0 with status interrupted at iteration 0.
#[test]
fn the_condensation_reports_progress() {
    let problem = hertz_problem(0.02, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let mut seen = Vec::new();
    let mut observer = |p: &Progress| {
        seen.push(*p);
        ControlFlow::Continue(())
    };
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), Some(&mut observer)).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert_eq!(seen[0].phase, Phase::Condensation);
    assert!(seen[0].condensation_seconds > 0.0);
    assert!(seen[1..].iter().all(|p| p.phase == Phase::Qp));
    assert_eq!(seen.len(), sol.report.iterations + 2);
    assert!(seen.windows(2).all(|w| w[1].condensation_seconds >= w[0].condensation_seconds));
    let t = &sol.report.timings;
    assert!(seen.last().unwrap().condensation_seconds <= t.factorization + t.condensation);

    let mut stop = |p: &Progress| {
        if p.phase == Phase::Condensation {
            ControlFlow::Break(())
        } else {
            panic!("no QP after a stop at the condensation")
        }
    };
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), Some(&mut stop)).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Interrupted { iteration: 0 });
    assert!(sol.report.qp_iterations.is_empty() && sol.lambda_n.iter().all(|l| *l == 0.0));
}

/// Obstacles and supports name themselves as the Python calls that build them, and a support gives its
/// prescribed components per axis.
#[test]
fn obstacles_and_supports_name_themselves() {
    let shapes = [
        (ObstacleShape::Flat, "flat", "flat()"),
        (ObstacleShape::Circle { center: 0.5, radius: 2.0 }, "circle", "circle(radius=2, center=0.5)"),
        (ObstacleShape::Parabola { center: 0.0, radius: 1.5 }, "parabola", "parabola(radius=1.5, center=0)"),
        (ObstacleShape::Polyline { xi: vec![0.0, 1.0], gap: vec![0.0, 0.1] }, "polyline", "polyline(<2 points>)"),
        (ObstacleShape::Function(GapFunction(std::sync::Arc::new(|x| x))), "function", "function(<closure>)"),
    ];
    for (shape, kind, shown) in shapes {
        assert_eq!((shape.kind(), shape.to_string().as_str()), (kind, shown));
    }
    let supports = [
        (Support::clamp("base"), r#"clamp("base")"#, [Some(0.0), Some(0.0)]),
        (Support::roller("axis"), r#"roller("axis")"#, [None, None]),
        (
            Support::displacement("top", None, Some(-0.01)),
            r#"displacement("top", x=None, y=-0.01)"#,
            [None, Some(-0.01)],
        ),
    ];
    for (support, shown, components) in supports {
        assert_eq!((support.to_string().as_str(), support.components()), (shown, components));
    }
}

/// The registry of choices names every option enum by its keyword, with the names each one parses, the
/// contact states in the order of their codes, and the solver settings' choices as the table gives them.
#[test]
fn the_choice_registry_lists_every_option() {
    let registry: std::collections::BTreeMap<_, _> = choice_registry().into_iter().collect();
    let keys: Vec<&str> = registry.keys().copied().collect();
    let expected = [
        "bisection",
        "condensation",
        "coulomb",
        "diagonal",
        "formulation",
        "friction",
        "marking",
        "model",
        "qp_kkt_solver",
        "qp_method",
        "side",
        "space",
        "state",
        "status",
        "stop_on",
    ];
    assert_eq!(keys, expected);
    assert_eq!(registry["state"], ContactState::ALL.iter().map(|s| s.as_str()).collect::<Vec<_>>());
    assert_eq!(registry["state"][ContactState::Slip.code()], "slip");
    assert_eq!(registry["status"], SolveStatus::NAMES);
    assert_eq!(registry["qp_method"], QpMethod::names());
    assert_eq!(registry["bisection"], ["all_edges", "refinement_edge"]);
    assert_eq!(registry["marking"], Marking::names());
    assert_eq!(registry["stop_on"], ["bound", "hierarchical", "enriched"]);
    assert_eq!(registry["model"], ["plane_strain", "plane_stress", "axisymmetric"]);
    assert_eq!(registry["coulomb"], ["fixed_point", "newton", "auto"]);
    assert_eq!(registry["formulation"], ["auto", "displacement", "mixed"]);
    for name in &registry["condensation"] {
        assert_eq!(Condensation::parse(name).map(Condensation::as_str), Ok(*name));
    }
}

/// The defaults of the keywords a problem is built from give back the default multiplier points, space,
/// model and formulation.
#[test]
fn problem_keyword_defaults_give_back_the_defaults() {
    let defaults = ProblemSpec::keyword_defaults();
    let ratio = match defaults.as_slice() {
        [("multiplier_ratio", SettingValue::Float(r)), ("space", SettingValue::Name(space)), ("model", SettingValue::Name(model)), ("formulation", SettingValue::Name(formulation))] =>
        {
            assert_eq!(MultiplierSpace::parse(space), Ok(MultiplierSpace::default()));
            assert_eq!(Model::parse(model), Ok(Model::default()));
            assert_eq!(Formulation::parse(formulation), Ok(Formulation::Auto));
            *r
        }
        other => panic!("{other:?}"),
    };
    assert_eq!(MultiplierPoints::from_keywords(Some(ratio), None, None), Ok(MultiplierPoints::default()));
}
