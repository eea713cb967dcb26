//! Histories that move prescribed displacements: moving a body's support by a rigid motion is moving the
//! obstacle the other way (two paths, one answer); a moved step is the static problem with those values;
//! bad steps are refused before any solve, naming the step.

use tribo::{
    Error, Friction, LoadStep, MultiplierPoints, MultiplierSpace, Problem, Solution, SolveStatus, SolverSettings,
    Stabilization, Support,
};
use tribo_testkit::{hertz_mesh, hertz_scene, hertz_spec};

const MU: f64 = 0.3;

/// The Hertz block with its bottom held by a prescribed displacement at `(x, y)` instead of a clamp, the
/// cylinder at rest (approach 0, shift 0), plus `extra` supports.
fn held_at(x: f64, y: f64, extra: Vec<Support>) -> Problem {
    held_on(hertz_mesh(0.02), x, y, extra)
}

/// [`held_at`] on another mesh of a body whose top is Γ_C.
fn held_on(mesh: tribo::Mesh, x: f64, y: f64, extra: Vec<Support>) -> Problem {
    let mut spec = hertz_spec(0.0, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.clamped.clear();
    spec.supports = [Support::displacement("bottom", Some(x), Some(y))].into_iter().chain(extra).collect();
    Problem::new(mesh, spec).unwrap()
}

/// A strip one cell thick under the cylinder: every contact triangle has nodes on the moved bottom, so the
/// stabilization term of the contact law (`E Δū`, the stress of the contact triangles) sees the motion.
fn thin_strip() -> tribo::Mesh {
    tribo::rectangle([-2.0, 2.0], [-0.05, 0.0], 160, 1, tribo::Diagonal::Right).unwrap()
}

fn sup(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// A fretting path of the cylinder: pressed to δ in 3 steps, then its shift 0 → s → −s → s.
fn fretting_path() -> Vec<(f64, f64)> {
    let (delta, s, n) = (hertz_scene().approach, 0.003, 6);
    let mut path: Vec<(f64, f64)> = (1..=3).map(|k| (delta * k as f64 / 3.0, 0.0)).collect();
    path.extend((1..=n).map(|k| (delta, s * k as f64 / n as f64)));
    path.extend((1..=2 * n).map(|k| (delta, s - 2.0 * s * k as f64 / (2 * n) as f64)));
    path.extend((1..=2 * n).map(|k| (delta, -s + 2.0 * s * k as f64 / (2 * n) as f64)));
    path
}

/// The obstacle moved by `−δ n + s t` (on the top face n = e_y, t = −e_x: `(−s, −δ)`) and the body's
/// support moved by `(s, δ)` are one relative motion: along a whole fretting path with Coulomb friction,
/// the multipliers and the states agree step by step, and the displacements differ by the rigid motion,
/// to round-off; for the stabilized method (γ0 at half its bound) and the classic one (γ0 = 0), on the
/// graded Hertz block and on a strip one cell thick (where the moved dofs are in the contact triangles).
#[test]
fn moving_the_body_is_moving_the_obstacle() {
    let problem = held_at(0.0, 0.0, vec![]);
    assert_eq!(
        problem.spec.prescribed_components(),
        vec![("bottom.x".to_string(), 0.0), ("bottom.y".to_string(), 0.0)]
    );
    let coulomb = Friction::Coulomb { mu: MU };
    let cases = [(problem, 1.0), (held_on(thin_strip(), 0.0, 0.0, vec![]), 0.1)];
    for ((problem, scale), stabilization) in
        cases.iter().flat_map(|c| [Stabilization::Fraction(0.5), Stabilization::None].map(|s| (c, s)))
    {
        let path: Vec<(f64, f64)> = fretting_path().iter().map(|&(d, s)| (scale * d, scale * s)).collect();
        let by_obstacle: Vec<LoadStep> = path.iter().map(|&(d, s)| LoadStep::new(d, s)).collect();
        let by_body: Vec<LoadStep> =
            path.iter().map(|&(d, s)| LoadStep::new(0.0, 0.0).with_displacements(vec![s, d])).collect();
        let settings = SolverSettings { stabilization, ..Default::default() };
        let a = problem.solve_history(&coulomb, &by_obstacle, &settings, None).unwrap();
        let b = problem.solve_history(&coulomb, &by_body, &settings, None).unwrap();
        assert_eq!((a.status, b.status), (SolveStatus::Converged, SolveStatus::Converged));
        let scale = sup(&a.solutions[3].lambda_n);
        let u_scale = sup(&a.solutions[3].displacement);
        for (k, ((x, y), &(d, s))) in a.solutions.iter().zip(&b.solutions).zip(&path).enumerate() {
            assert_eq!(x.states, y.states, "{stabilization:?} step {k}: states");
            let dl = diff(&x.lambda_n, &y.lambda_n).max(diff(&x.lambda_t, &y.lambda_t));
            assert!(dl <= 1e-9 * scale, "{stabilization:?} step {k}: λ differs by {dl:e} of {scale:e}");
            let moved: Vec<f64> = x.displacement.chunks(2).flat_map(|u| [u[0] + s, u[1] + d]).collect::<Vec<_>>();
            let du = diff(&moved, &y.displacement);
            assert!(du <= 1e-9 * u_scale, "{stabilization:?} step {k}: u differs by {du:e} of {u_scale:e}");
            assert!(diff(&x.slip, &y.slip) <= 1e-9 * u_scale, "{stabilization:?} step {k}: slip");
            assert!((x.tangential_force - y.tangential_force).abs() <= 1e-9 * scale);
        }
        // The path did slide and stick: a fretting loop, not a trivial one.
        let q = b.tangential_force();
        assert!(q.iter().any(|&v| v > 0.0) && q.iter().any(|&v| v < 0.0), "{q:?}");
    }
}

/// One step from rest that moves the support to `(x, y)` is the static problem built with those values,
/// to round-off; a step that keeps the problem's own values is that problem's static solve bit for bit.
#[test]
fn a_moved_step_is_the_static_problem_with_those_values() {
    let (x, y) = (0.002, hertz_scene().approach);
    let moved = held_at(0.0, 0.0, vec![]);
    let target = held_at(x, y, vec![]);
    let settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: MU };
    let fixed = target.solve(&coulomb, &settings, None).unwrap();
    let step = LoadStep::new(0.0, 0.0).with_displacements(vec![x, y]);
    let h = moved.solve_history(&coulomb, std::slice::from_ref(&step), &settings, None).unwrap();
    let one = &h.solutions[0];
    let scale = sup(&fixed.lambda_n);
    assert!(fixed.normal_force > 0.0 && fixed.tangential_force != 0.0, "pressed and dragged");
    assert!(diff(&one.lambda_n, &fixed.lambda_n) <= 1e-10 * scale);
    assert!(diff(&one.lambda_t, &fixed.lambda_t) <= 1e-10 * scale);
    assert!(diff(&one.displacement, &fixed.displacement) <= 1e-10 * sup(&fixed.displacement));
    assert!(diff(&one.reactions, &fixed.reactions) <= 1e-9 * sup(&fixed.reactions));
    assert!(one.kkt.max() < 1e-6, "{:?}", one.kkt);
    let own = target.solve_history(&coulomb, &[step], &settings, None).unwrap();
    let same: &Solution = &own.solutions[0];
    assert_eq!(same.lambda_t, fixed.lambda_t);
    assert_eq!(same.displacement, fixed.displacement);
}

/// Bad steps are refused before any solve, naming the step: a wrong number of values, a non-finite
/// value, values that contradict another support where they meet (the clamped left side shares the
/// bottom-left corner), and an obstacle motion on two bodies.
#[test]
fn bad_moved_steps_are_refused() {
    let problem = held_at(0.0, 0.0, vec![Support::clamp("left")]);
    let settings = SolverSettings::default();
    let law = Friction::Frictionless;
    let run = |steps: &[LoadStep]| problem.solve_history(&law, steps, &settings, None).unwrap_err();
    let rest = LoadStep::new(0.0, 0.0);
    let e = run(&[rest.clone(), LoadStep::new(0.0, 0.0).with_displacements(vec![0.0])]);
    assert!(matches!(&e, Error::BadLoadStep { step: 1, what } if what.contains("bottom.x, bottom.y")), "{e}");
    let e = run(&[rest.clone(), LoadStep::new(0.0, 0.0).with_displacements(vec![f64::NAN, 0.0])]);
    assert!(matches!(e, Error::BadLoadStep { step: 1, .. }), "{e}");
    // u_y = 0.01 at the clamped corner: the clamp says 0.
    let e =
        run(&[rest.clone(), rest.clone().with_displacements(vec![0.0, 0.0]), rest.with_displacements(vec![0.0, 0.01])]);
    assert!(matches!(&e, Error::BadLoadStep { step: 2, what } if what.contains("left")), "{e}");
    assert!(matches!(LoadStep::from_row(3, &[0.0, 0.0]), Err(Error::BadLoadStep { step: 3, .. })));
    let two = tribo_testkit::two_body_hertz(0.04, hertz_scene().material, hertz_scene().material, true, 0.001);
    let e = two.solve_history(&law, &[LoadStep::new(0.001, 0.0)], &settings, None).unwrap_err();
    assert!(matches!(&e, Error::BadLoadStep { step: 0, what } if what.contains("prescribed displacements")), "{e}");
}

/// Supports that prescribe a node of Γ_C into the obstacle make the contact condition impossible there:
/// refused before any work, naming the node (and the step of a history), where before the solve said
/// `converged` with the node inside the obstacle. Touching exactly is allowed.
#[test]
fn supports_that_push_gamma_c_into_the_obstacle_are_refused() {
    // A flat foundation pushed 0.01 into the bottom of a block whose sides are clamped: the bottom
    // corners are held at u = 0, 0.01 inside the obstacle.
    let mesh = tribo::rectangle([0.0, 2.0], [0.0, 1.0], 8, 4, tribo::Diagonal::Right).unwrap();
    let spec = |approach: f64| tribo::ProblemSpec {
        material: tribo::Material { young: 1.0, poisson: 0.3 },
        model: tribo::Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["left".into(), "right".into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: tribo::Obstacle { shape: tribo::ObstacleShape::Flat, approach, shift: 0.0, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    let pushed = Problem::new(mesh.clone(), spec(0.01)).unwrap();
    let settings = SolverSettings::default();
    let corner = |e: &Error| {
        matches!(e, Error::PrescribedPenetration { node, u_n, gap, .. }
        if pushed.contact.nodes.first() == Some(node) && *u_n == 0.0 && (*gap + 0.01).abs() < 1e-15)
    };
    let e = pushed.solve(&Friction::Frictionless, &settings, None).unwrap_err();
    assert!(corner(&e) && matches!(e, Error::PrescribedPenetration { step: None, .. }), "{e}");
    assert!(e.to_string().contains("into the obstacle"), "{e}");
    let e = pushed.condense(settings.stabilization).unwrap().solve(&Friction::Frictionless, &settings, None);
    assert!(matches!(e, Err(Error::PrescribedPenetration { .. })), "{e:?}");
    // Touching (approach 0) is fine; a history that pushes the obstacle in at step 2 is refused up front.
    let touching = Problem::new(mesh, spec(0.0)).unwrap();
    assert!(touching.solve(&Friction::Frictionless, &settings, None).is_ok());
    let steps: Vec<LoadStep> = [0.0, 0.0, 0.01].iter().map(|&d| LoadStep::new(d, 0.0)).collect();
    let e = touching.solve_history(&Friction::Frictionless, &steps, &settings, None).unwrap_err();
    assert!(matches!(e, Error::PrescribedPenetration { step: Some(2), .. }), "{e}");
    // A moved support that lifts a corner of Γ_C into a touching obstacle: the right side of a block whose
    // top touches a flat obstacle (its left side on a roller), moved up 0.01 at step 1 (the top-right corner
    // is on both).
    let mesh = tribo::rectangle([0.0, 2.0], [0.0, 1.0], 8, 4, tribo::Diagonal::Right).unwrap();
    let mut side = spec(0.0);
    side.clamped = vec![];
    side.contact = "top".into();
    side.supports = vec![Support::roller("left"), Support::displacement("right", Some(0.0), Some(0.0))];
    let lifted = Problem::new(mesh, side).unwrap();
    let rest = LoadStep::new(0.0, 0.0);
    let up = rest.clone().with_displacements(vec![0.0, 0.01]);
    let e = lifted.solve_history(&Friction::Frictionless, &[rest, up], &settings, None).unwrap_err();
    assert!(matches!(e, Error::PrescribedPenetration { step: Some(1), u_n, .. } if (u_n - 0.01).abs() < 1e-15), "{e}");
}
