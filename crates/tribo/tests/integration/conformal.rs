//! Conformal contact between two bodies (issue 39): an elastic pin pushed across a hole with clearance in a plate of
//! the same material (`tribo_testkit::PinInHole`), against Persson's problem solved to 1e-9 at the load the
//! answer carries (`tribo_testkit::Persson`, whose documentation derives it). Study 26 follows the meshes further.

use tribo::*;
use tribo_testkit::PinInHole;

/// What one mesh gives against Persson: (the half-angle's relative error, λ_n's relative L² difference, its peak's
/// relative difference, Hertz's half-angle for the same load over Persson's).
fn against_persson(scene: &PinInHole) -> (f64, f64, f64, f64) {
    let problem = scene.problem();
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert_eq!(sol.report.status, SolveStatus::Converged);
    let reference = scene.reference(&sol);
    let alpha = scene.half_angle(&sol);
    let l2 = scene.pressure_error(&problem, &sol, &reference);
    let scale = scene.pressure_unit();
    let peak = sol.lambda_n.iter().copied().fold(0.0, f64::max) / (scale * reference.peak_pressure()) - 1.0;
    let hertz = 2.0 * (reference.load / std::f64::consts::PI).sqrt();
    eprintln!(
        "δ {}, ν {}, {} bisections, {} unknowns: α {:.3}° (Persson {:.3}°, Hertz {:.3}°), L2 {l2:.3e}, \
         peak {peak:+.3e}",
        scene.approach,
        scene.material.poisson,
        scene.refinements,
        problem.n_free,
        alpha.to_degrees(),
        reference.half_angle.to_degrees(),
        hertz.to_degrees()
    );
    (alpha / reference.half_angle - 1.0, l2, peak, hertz / reference.half_angle)
}

/// Contact half-angles of 41° and 71° (ν = 0.3), where Hertz's half-angle for the same load (its semi-width read as
/// the arc) is 17 % and 94 % off, and 61° at ν = 0 (Persson's problem depends on E* alone): on the meshes bisected
/// twice and three times along the arc (42k and 71k unknowns) the half-angle, λ_n in L² and its peak are within 2 % of
/// Persson's (measured: at most 0.8 %, 1.0 % and 1.4 %), and λ_n's difference falls with refinement. Before the plate
/// generator put its nodes at half a turn on y = 0 exactly (they were at R sin π ≈ 1e-16), the symmetry line the
/// scene finds by `y == 0` missed the ray left of the hole, the plate's back was free, and the answers depended on ν:
/// 2.5 % on α and 4.5 % in L² at ν = 0.
#[test]
fn a_pin_in_a_hole_meets_persson_within_two_percent() {
    for (approach, poisson) in [(0.002, 0.3), (0.008, 0.3), (0.004, 0.0)] {
        let mut l2_before = f64::INFINITY;
        for refinements in [2, 3] {
            let mut scene = PinInHole::new(approach, 1.5, refinements);
            scene.material.poisson = poisson;
            let (alpha, l2, peak, hertz) = against_persson(&scene);
            for (what, e) in [("α", alpha), ("λ_n (L²)", l2), ("the peak of λ_n", peak)] {
                assert!(e.abs() < 0.02, "δ {approach}, ν {poisson}, {refinements} bisections: {what} off by {e:.3e}");
            }
            assert!(l2 < l2_before, "δ {approach}: λ_n's L² difference {l2} after {l2_before}");
            assert!(hertz > 1.05, "δ {approach}: Hertz's half-angle only {hertz} times Persson's");
            l2_before = l2;
        }
    }
}

/// Either side may carry the multipliers: with the hole's arc as the secondary side instead of the pin's rim, the
/// same pin (δ = 0.004, α ≈ 60°, 42k unknowns) takes the same load, equal and opposite as the force on the other
/// body, to within the two answers' own discretization errors (each read as the change one more bisection makes:
/// measured 7.8e-9 apart against 1.2e-8), and both answers are within 2 % of Persson's.
#[test]
fn either_side_may_carry_the_multipliers() {
    let force = |on_pin: bool, refinements: usize| {
        let scene = PinInHole { multipliers_on_pin: on_pin, ..PinInHole::new(0.004, 1.5, refinements) };
        let problem = scene.problem();
        let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let reference = scene.reference(&sol);
        let alpha = scene.half_angle(&sol) / reference.half_angle - 1.0;
        let l2 = scene.pressure_error(&problem, &sol, &reference);
        assert!(alpha.abs() < 0.02 && l2 < 0.02, "multipliers on the pin: {on_pin}: α {alpha:.3e}, L2 {l2:.3e}");
        sol.contact_force
    };
    let distance = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let (pin, pin_finer) = (force(true, 2), force(true, 3));
    let (hole, hole_finer) = (force(false, 2).map(|f| -f), force(false, 3).map(|f| -f));
    let (apart, errors) = (distance(pin, hole), distance(pin, pin_finer) + distance(hole, hole_finer));
    eprintln!("{pin:?} against {hole:?}: {apart:e} apart, their refinement changes {errors:e}");
    assert!(apart < errors, "{pin:?} against {hole:?}: {apart:e} apart, their refinement changes {errors:e}");
}
