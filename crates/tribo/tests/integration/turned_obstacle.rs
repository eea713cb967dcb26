//! A rigid obstacle turned about a point (issue 39, item 2: obstacles that move by a rotation,
//! [`ObstacleRotation`]): its geometry turned exactly, its surface sliding by `w(y) · t` at its point y nearest
//! the body.
//!
//! * **A hole turned about its centre** drags a full ring clamped inside as the shift `s = θR` does: the same hole,
//!   every dof slipping, so the same answer to round-off, and the slip torque `μ p 2π b²`.
//! * **A flat turned about a point of its surface** is the flat placed there: the same gap, and no tangential
//!   motion (the surface turns in its own line), with friction too.
//! * **A disc turned about its own centre on a block** slides its surface by θR under the contact and does not
//!   move toward it: against the shift `s = −θR` (t = −x on the block's top), in partial slip, the tractions agree
//!   to the second order of the angle the contact zone subtends.
//! * Refused: a gap function of the abscissa, two bodies, axisymmetry, a history.

use std::f64::consts::PI;

use tribo::*;

const MU: f64 = 0.3;

fn full_ring_in_hole(motion: impl Fn(ProblemSpec) -> ProblemSpec) -> Problem {
    let sector = RingSector { center: [0.0, 0.0], radii: [0.5, 1.0], angles: [0.0, 2.0 * PI] };
    let grading = ArcGrading { angles: [0.0, 2.0 * PI], h_min: 0.04, h_max: 0.04, growth: 0.15 };
    let mesh = ring_sector(&sector, &grading).expect("a full ring");
    let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "outer")
        .clamped(["inner"])
        .obstacle(ObstacleShape::Hole { center: [0.0, 0.0], radius: 1.0 })
        .approach(1e-3);
    Problem::new(mesh, motion(spec)).expect("a ring in a hole")
}

fn largest_difference(a: &Solution, b: &Solution) -> f64 {
    let scale = a.lambda_n.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let d = a.lambda_n.iter().zip(&b.lambda_n).chain(a.lambda_t.iter().zip(&b.lambda_t));
    d.map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

#[test]
fn a_hole_turned_about_its_centre_drags_a_ring_as_its_shift_does() {
    let theta = 0.02;
    let turned = full_ring_in_hole(|s| s.obstacle_rotation([0.0, 0.0], theta));
    let shifted = full_ring_in_hole(|s| s.shift(theta));
    let settings = SolverSettings::default();
    let a = turned.solve(&Friction::Coulomb { mu: MU }, &settings, None).expect("solves");
    let b = shifted.solve(&Friction::Coulomb { mu: MU }, &settings, None).expect("solves");
    assert_eq!((a.report.status, b.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    assert!(a.states.iter().all(|s| *s == ContactState::Slip), "the whole rim slips");
    let diff = largest_difference(&a, &b);
    eprintln!("hole turned by θ against shifted by θR: λ differ by {diff:.1e}, torque {:.6e}", a.tangential_force);
    assert!(diff < 1e-9, "{diff:e}");
    // Its sense: turned counterclockwise, the hole drags the rim counterclockwise, as the positive shift does.
    assert!(a.tangential_force * b.tangential_force > 0.0);
    let mean_p = a.lambda_n.iter().sum::<f64>() / a.lambda_n.len() as f64;
    let slip = MU * mean_p * 2.0 * PI;
    assert!((a.tangential_force.abs() / slip - 1.0).abs() < 0.01, "{} against μ p 2π b² = {slip}", a.tangential_force);
}

#[test]
fn a_flat_turned_about_a_point_of_its_surface_is_the_flat_placed_there() {
    let theta: f64 = 0.01;
    let base = tribo_testkit::roller_problem(0.004, 0.15, [1.0, 0.0], [0.0, 0.0], 2e-4, 0.0);
    let with = |obstacle: Obstacle| {
        Problem::new(base.mesh.clone(), ProblemSpec { obstacle, ..base.spec.clone() }).expect("a roller on a flat")
    };
    let flat = ObstacleShape::Line { point: [0.0, 0.0], normal: [0.0, 1.0] };
    let turned = with(Obstacle {
        shape: flat,
        approach: 2e-4,
        shift: 0.0,
        rotation: Some(ObstacleRotation { center: [0.0, 0.0], angle: theta }),
    });
    let placed = with(Obstacle {
        shape: ObstacleShape::Line { point: [0.0, 0.0], normal: [-theta.sin(), theta.cos()] },
        approach: 2e-4,
        shift: 0.0,
        rotation: None,
    });
    for friction in [Friction::Frictionless, Friction::Coulomb { mu: MU }] {
        let a = turned.solve(&friction, &SolverSettings::default(), None).expect("solves");
        let b = placed.solve(&friction, &SolverSettings::default(), None).expect("solves");
        assert_eq!((a.report.status, b.report.status), (SolveStatus::Converged, SolveStatus::Converged));
        let diff = largest_difference(&a, &b);
        // The error estimate reads the turned flat's gap too.
        let eta = a.estimator.iter().zip(&b.estimator).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        let top = b.estimator.iter().fold(0.0_f64, |m, x| m.max(*x));
        eprintln!("flat turned against placed, {friction:?}: λ differ by {diff:.1e}, η_K by {:.1e}", eta / top);
        assert!(diff < 1e-10, "{friction:?}: {diff:e}");
        assert!(eta <= 1e-10 * top, "{friction:?}: η_K differ by {eta:e} of {top:e}");
        assert!(a.normal_force > 0.0);
    }
}

#[test]
fn a_disc_turned_about_its_centre_on_a_block_slides_its_surface_by_theta_r() {
    let (radius, approach, theta) = (1.0, 2e-3, 2e-4);
    let grading = Grading { side: Side::Top, segment: [0.4, 0.6], h_min: 0.004, h_max: 0.1, growth: 0.15 };
    let mesh = graded_rectangle([0.0, 1.0], [0.0, 0.5], &grading).expect("a block");
    let disc = ObstacleShape::Disc { center: [0.5, 0.5 + radius], radius };
    let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top").clamped(["bottom"]).approach(approach);
    let turned =
        Problem::new(mesh.clone(), spec.clone().obstacle(disc.clone()).obstacle_rotation([0.5, 0.5 + radius], theta))
            .expect("a disc on a block");
    let shifted = Problem::new(mesh, spec.obstacle(disc).shift(-theta * radius)).expect("a disc on a block");
    let a = turned.solve(&Friction::Coulomb { mu: MU }, &SolverSettings::default(), None).expect("solves");
    let b = shifted.solve(&Friction::Coulomb { mu: MU }, &SolverSettings::default(), None).expect("solves");
    assert_eq!((a.report.status, b.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    let (stick, slip) = (
        a.states.iter().filter(|s| **s == ContactState::Stick).count(),
        a.states.iter().filter(|s| **s == ContactState::Slip).count(),
    );
    let diff = largest_difference(&a, &b);
    let half_angle = 0.5 * a.contact_width() / radius;
    eprintln!(
        "disc turned by θ against shifted by −θR: λ differ by {diff:.1e} (half-angle² {:.1e}); {stick} stick, {slip} slip, Q = {:.4e}",
        half_angle * half_angle,
        a.tangential_force
    );
    assert!(stick > 0 && slip > 0, "partial slip");
    assert!(diff < 2.0 * half_angle * half_angle, "{diff:e}");
}

#[test]
fn a_rotation_is_refused_where_nothing_can_turn() {
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 4, 4, Diagonal::Right).expect("a square");
    let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top").clamped(["bottom"]);
    // A gap function of the abscissa has no place in the plane.
    let flat = Problem::new(mesh.clone(), spec.clone().obstacle_rotation([0.0, 0.0], 0.01)).expect_err("refused");
    assert!(matches!(&flat, Error::BadObstacle { what } if what.contains("gap function")), "{flat}");
    let line = ObstacleShape::Line { point: [0.0, 1.0], normal: [0.0, -1.0] };
    let bad = Problem::new(mesh.clone(), spec.clone().obstacle(line.clone()).obstacle_rotation([0.0, 0.0], f64::NAN));
    assert!(matches!(bad, Err(Error::BadObstacle { .. })));
    // Axisymmetry.
    let axi = spec.clone().obstacle(line.clone()).obstacle_rotation([0.0, 0.0], 0.01).model(Model::Axisymmetric);
    assert!(matches!(Problem::new(mesh.clone(), axi), Err(Error::BadAxisymmetry { .. })));
    // A history.
    let problem = Problem::new(mesh, spec.obstacle(line).obstacle_rotation([0.0, 1.0], 0.01)).expect("turned");
    let steps = [LoadStep::new(0.0, 0.0)];
    let e =
        problem.solve_history(&Friction::Frictionless, &steps, &SolverSettings::default(), None).expect_err("refused");
    assert!(matches!(&e, Error::BadLoadStep { step: 0, what } if what.contains("rotation")), "{e}");
    let adapt = AdaptSettings::default();
    let e = problem
        .solve_history_adaptive(&Friction::Frictionless, &steps, &SolverSettings::default(), &adapt, &[], None)
        .expect_err("refused");
    assert!(matches!(&e, Error::BadLoadStep { step: 0, .. }), "{e}");
}
