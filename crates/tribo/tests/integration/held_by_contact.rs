//! Bodies held only by the contact (`problem/floating.rs`): a piece its supports leave free to move
//! rigidly is held by the contact forces, its rigid motion α the multiplier of its equilibrium.
//!
//! * patch test: a block pressed onto a flat foundation by a uniform traction, held in y by nothing but
//!   the contact: the uniform pressure, the uniaxial-stress displacement and a zero gap, to round-off;
//! * with friction the pressure is no longer uniform (friction resists the Poisson expansion): the
//!   contact forces balance the load, the KKT residuals are at round-off, a one-step history is the
//!   static solve bit for bit, and the answer scales with the load;
//! * a block with no support at all is held in x and in rotation by friction;
//! * two bodies: the stacked-blocks patch test with the upper block pushed by a pressure instead of a
//!   displacement; two-body Hertz with the upper block pressed by a traction converges to the Hertz
//!   pressure of the combined modulus;
//! * what the contact cannot hold is said: a frictionless body free to slide, two bodies free to move
//!   together, a body nothing presses against the contact (typed errors), a load that pulls the body off
//!   or exceeds friction (the QP's status);
//! * P0 multipliers and γ0 = 0; a ramped load equals the static solves; a Coulomb fretting history; a
//!   punch refined adaptively from coarse meshes.

use tribo::*;
use tribo_testkit::{combined_modulus, hertz_l2_error_with};

const E: f64 = 100.0;
const NU: f64 = 0.3;

/// A block (0, 2) × (0, 1) on a flat rigid foundation (Γ_C its bottom, touching), loaded by a uniform
/// traction on its top; held only by `supports` (none holds it in y).
fn block_on_foundation(supports: Vec<Support>, traction: [f64; 2]) -> Problem {
    block_on_foundation_meshed(8, supports, traction)
}

/// [`block_on_foundation`] on `nx × nx/2` cells.
fn block_on_foundation_meshed(nx: usize, supports: Vec<Support>, traction: [f64; 2]) -> Problem {
    let mesh = rectangle([0.0, 2.0], [0.0, 1.0], nx, nx / 2, Diagonal::Alternating).unwrap();
    let spec = ProblemSpec {
        material: Material { young: E, poisson: NU },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![],
        supports,
        body_force: [0.0, 0.0],
        tractions: vec![("top".into(), traction.into())],
        contact: "bottom".into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach: 0.0, shift: 0.0, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    Problem::new(mesh, spec).unwrap()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// Round-off of these small solves (κ(K) ≈ 1e3), and of clarabel's answer at qp_tol.
const PATCH_TOL: f64 = 1e-9;

#[test]
fn a_block_pressed_onto_a_foundation_and_held_only_by_the_contact_passes_the_patch_test() {
    let p = 2.0;
    // A roller on the left side holds x and the rotation: the contact alone holds the body in y.
    let problem = block_on_foundation(vec![Support::roller("left")], [0.0, -p]);
    assert_eq!(problem.dofs.n_floating(), 1);
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert_eq!(sol.report.qp_methods, vec![QpMethod::Clarabel], "the equality constraint is clarabel's");
    assert!(sol.lambda_n.iter().all(|l| (l - p).abs() <= PATCH_TOL * p), "{:?}", sol.lambda_n);
    // Uniaxial stress σ_yy = −p (σ_xx = 0: the right side is free, the left a roller): u_y = −p (1 − ν²) y / E
    // and u_x = p ν (1 + ν) x / E, with the bottom on the foundation.
    let scale = p / E;
    for (i, pt) in problem.mesh.points().iter().enumerate() {
        let exact = [p * NU * (1.0 + NU) * pt[0] / E, -p * (1.0 - NU * NU) * pt[1] / E];
        for (c, e) in exact.iter().enumerate() {
            assert!((sol.displacement[2 * i + c] - e).abs() <= PATCH_TOL * scale, "node {i}");
        }
    }
    // The pins carry nothing: every reaction (the roller's too) vanishes.
    assert!(max_abs(&sol.reactions) <= PATCH_TOL * p, "{:e}", max_abs(&sol.reactions));
    assert!(sol.kkt.max() < PATCH_TOL);
    // H from the partial factorization gives the same answer; the saddle-point path, which does without
    // H, is refused by name.
    let schur = SolverSettings { condensation: Condensation::Schur, ..Default::default() };
    let again = problem.solve(&Friction::Frictionless, &schur, None).unwrap();
    assert!(again.lambda_n.iter().zip(&sol.lambda_n).all(|(a, b)| (a - b).abs() <= PATCH_TOL * p));
    let saddle = SolverSettings { condensation: Condensation::Saddle, ..Default::default() };
    let r = problem.solve(&Friction::Frictionless, &saddle, None);
    assert!(matches!(r, Err(Error::BadSetting { name: "condensation", .. })), "{:?}", r.map(|s| s.report.status));
}

#[test]
fn with_friction_the_contact_balances_the_load_and_the_answer_scales_with_it() {
    let (p, mu) = (2.0, 0.3);
    let coulomb = Friction::Coulomb { mu };
    let settings = SolverSettings::default();
    let problem = block_on_foundation(vec![Support::roller("left")], [0.0, -p]);
    let sol = problem.solve(&coulomb, &settings, None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.kkt.max() < 1e-8, "{:?}", sol.kkt);
    // Friction resists the Poisson expansion: the pressure is not uniform, but balances the load.
    assert!(max_abs(&sol.lambda_n) > 1.2 * p && sol.lambda_t.iter().any(|t| t.abs() > 0.01 * p));
    assert!((sol.normal_force - 2.0 * p).abs() <= 1e-9 * p, "{}", sol.normal_force);
    // One step of a history is the static solve.
    let step = LoadStep { approach: 0.0, shift: 0.0, load_factor: 1.0, displacements: vec![], rotation: None };
    let history = problem.solve_history(&coulomb, &[step], &settings, None).unwrap();
    assert_eq!(history.solutions[0].lambda_n, sol.lambda_n);
    assert_eq!(history.solutions[0].displacement, sol.displacement);
    // Twice the load, twice the answer (touching at zero gap, Coulomb's law is positively homogeneous).
    let double =
        block_on_foundation(vec![Support::roller("left")], [0.0, -2.0 * p]).solve(&coulomb, &settings, None).unwrap();
    let rel = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - 2.0 * y).abs())) / max_abs(a);
    assert!(rel(&double.lambda_n, &sol.lambda_n) < 1e-8 && rel(&double.displacement, &sol.displacement) < 1e-8);
}

#[test]
fn friction_holds_a_block_without_any_support() {
    let (p, t, mu) = (2.0, 0.4, 0.3);
    let problem = block_on_foundation(vec![], [t, -p]);
    assert_eq!(problem.dofs.n_floating(), 3, "two translations and the rotation");
    let sol = problem.solve(&Friction::Coulomb { mu }, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.kkt.max() < 1e-8, "{:?}", sol.kkt);
    // The contact forces balance the load (2 long): P = 2p, Q = 2t along the tangent.
    assert!((sol.normal_force - 2.0 * p).abs() <= 1e-9 * p);
    assert!((sol.tangential_force.abs() - 2.0 * t).abs() <= 1e-9 * p, "{}", sol.tangential_force);
    assert!(max_abs(&sol.reactions) <= 1e-9 * p, "no support, no reaction");
}

/// The same block on 160 × 80 cells, sheared by half what friction holds. With the equilibrium rows handed to clarabel
/// as a zero cone (regularized by its default 1e-8), its first Coulomb QP failed ("insufficient progress", from
/// 160 × 80 cells on); eliminated (`qp/equality.rs`), the fixed point converges, and the contact forces balance the
/// load.
#[test]
fn friction_holds_a_block_without_any_support_on_a_fine_mesh() {
    let (p, t, mu) = (1.0, 0.15, 0.3);
    let problem = block_on_foundation_meshed(160, vec![], [t, -p]);
    let settings = SolverSettings::default();
    let sol = problem.solve(&Friction::Coulomb { mu }, &settings, None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    let bound = Solution::accuracy_bound(settings.qp.tol, sol.report.qp_inaccurate, settings.fp.tol);
    assert!(sol.kkt.max() <= bound, "{:?} against {bound:e}", sol.kkt);
    assert!((sol.normal_force - 2.0 * p).abs() <= 1e-9 * p, "{}", sol.normal_force);
    assert!((sol.tangential_force.abs() - 2.0 * t).abs() <= 1e-9 * p, "{}", sol.tangential_force);
}

#[test]
fn what_the_contact_cannot_hold_is_said() {
    let p = 2.0;
    // Frictionless, nothing holds x: a mechanism, refused by name.
    let problem = block_on_foundation(vec![], [0.0, -p]);
    match problem.solve(&Friction::Frictionless, &SolverSettings::default(), None) {
        Err(Error::HeldOnlyByContact { body, motion, .. }) => {
            assert_eq!(body, "body");
            assert!(
                motion.contains("translation along (1.000, 0.000)") || motion.contains("translation along (-1.000"),
                "{motion}"
            );
        }
        other => panic!("expected HeldOnlyByContact, got {:?}", other.map(|s| s.report.status)),
    }
    // The foundation pushed 0.01 into a body nothing presses down: the body moves off by any amount of at
    // least 0.01, so its position is undetermined.
    let mut pushed = block_on_foundation(vec![Support::roller("left")], [0.0, 0.0]);
    pushed = Problem::new(
        pushed.mesh.clone(),
        ProblemSpec { obstacle: Obstacle { approach: 0.01, ..pushed.spec.obstacle.clone() }, ..pushed.spec.clone() },
    )
    .unwrap();
    match pushed.solve(&Friction::Frictionless, &SolverSettings::default(), None) {
        Err(Error::HeldOnlyByContact { what, motion, .. }) => {
            assert!(what.contains("undetermined") && motion.contains("translation along (0.000"), "{what}: {motion}");
        }
        other => panic!("expected HeldOnlyByContact, got {:?}", other.map(|s| s.report.status)),
    }
    // A load that pulls the body off the foundation: no contact force can balance it.
    let pulled = block_on_foundation(vec![Support::roller("left")], [0.0, p]);
    let sol = pulled.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
    assert!(matches!(sol.report.status, SolveStatus::QpFailed { .. }), "{:?}", sol.report.status);
    // A tangential load above what friction holds (t > μ p).
    let sliding = block_on_foundation(vec![], [0.7, -p]);
    let sol = sliding.solve(&Friction::Tresca(Threshold::Uniform(0.3 * p)), &SolverSettings::default(), None).unwrap();
    assert!(matches!(sol.report.status, SolveStatus::QpFailed { .. }), "{:?}", sol.report.status);
}

fn body(
    name: &str,
    mesh: Mesh,
    material: Material,
    supports: Vec<Support>,
    tractions: Vec<(String, [f64; 2])>,
) -> Body {
    let materials = Materials::uniform(material, mesh.n_triangles());
    let tractions = tractions.into_iter().map(|(set, t)| (set, t.into())).collect();
    Body { name: name.into(), mesh, materials, clamped: vec![], supports, tractions }
}

fn pair(secondary: &str, primary: &str, gap: ObstacleShape) -> ContactPair {
    ContactPair {
        secondary: secondary.into(),
        primary: primary.into(),
        gap,
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        model: Model::PlaneStrain,
        formulation: Default::default(),
    }
}

/// Plane-strain P-wave modulus: σ_yy / ε_yy in uniaxial strain.
fn p_modulus(m: &Material) -> f64 {
    m.young * (1.0 - m.poisson) / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson))
}

#[test]
fn stacked_blocks_pushed_by_a_pressure_pass_the_patch_test() {
    let (lower_m, upper_m) = (Material { young: 100.0, poisson: 0.3 }, Material { young: 300.0, poisson: 0.2 });
    let p = 0.5;
    for lower_secondary in [true, false] {
        let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 5, 3, Diagonal::Alternating).unwrap();
        let upper = rectangle([0.0, 2.0], [0.0, 0.5], 7, 2, Diagonal::Right).unwrap();
        let rollers = |extra: Option<Support>| {
            [Support::roller("left"), Support::roller("right")].into_iter().chain(extra).collect::<Vec<_>>()
        };
        let bodies = [
            body("lower", lower, lower_m, rollers(Some(Support::roller("bottom"))), vec![]),
            body("upper", upper, upper_m, rollers(None), vec![("top".into(), [0.0, -p])]),
        ];
        let (s, q) = if lower_secondary { ("lower.top", "upper.bottom") } else { ("upper.bottom", "lower.top") };
        let problem = Problem::two_bodies(bodies, pair(s, q, ObstacleShape::Flat), [0.0, 0.0]).unwrap();
        assert_eq!(problem.dofs.n_floating(), 1, "the upper block is free in y");
        for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
            let sol = problem.solve(&friction, &SolverSettings::default(), None).unwrap();
            assert_eq!(sol.report.status, SolveStatus::Converged);
            assert!(sol.lambda_n.iter().all(|l| (l - p).abs() <= PATCH_TOL * p), "{:?}", sol.lambda_n);
            // Uniaxial strain in series: the upper top goes down by p (h₁/M₁ + h₂/M₂).
            let drop = p * (1.0 / p_modulus(&lower_m) + 0.5 / p_modulus(&upper_m));
            let top = problem.mesh.points().iter().position(|x| x[1] == 0.5).unwrap();
            assert!(
                (sol.displacement[2 * top + 1] + drop).abs() <= PATCH_TOL * drop,
                "lower secondary {lower_secondary}"
            );
        }
    }
}

#[test]
fn two_bodies_free_to_move_together_are_refused() {
    let m = Material { young: 100.0, poisson: 0.3 };
    let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 4, 2, Diagonal::Right).unwrap();
    let upper = rectangle([0.0, 2.0], [0.0, 1.0], 4, 2, Diagonal::Right).unwrap();
    let rollers = vec![Support::roller("left"), Support::roller("right")];
    let bodies = [
        body("lower", lower, m, rollers.clone(), vec![]),
        body("upper", upper, m, rollers, vec![("top".into(), [0.0, -1.0])]),
    ];
    let problem =
        Problem::two_bodies(bodies, pair("lower.top", "upper.bottom", ObstacleShape::Flat), [0.0, 0.0]).unwrap();
    assert_eq!(problem.dofs.n_floating(), 2);
    for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
        let r = problem.solve(&friction, &SolverSettings::default(), None);
        assert!(
            matches!(&r, Err(Error::HeldOnlyByContact { motion, .. }) if motion.contains("translation along (0.000")),
            "{:?}",
            r.map(|s| s.report.status)
        );
    }
}

/// Two-body Hertz with the upper block (−2, 2) × (0, 2) held in x by a roller on its left side and pushed
/// down by a uniform traction on its top, held in y by the contact alone: the contact carries the load and
/// the pressure approaches the Hertz pressure of the combined modulus as the meshes are refined (measured
/// 11.7 %, 8.0 %, 2.6 %; the displacement-driven pair of two_bodies.rs, whose top is held rigid, reaches
/// 1.7 % on the finest: a finite block under a uniform traction is not the half-space Hertz assumes).
#[test]
fn a_punch_pushed_by_a_load_converges_to_two_body_hertz() {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let mut errors = Vec::new();
    for h_min in [0.04, 0.01, 0.0025] {
        let half = |upper: bool| {
            let (side, y) = if upper { (Side::Bottom, [0.0, 2.0]) } else { (Side::Top, [-2.0, 0.0]) };
            let grading = Grading { side, segment: [-0.15, 0.15], h_min, h_max: 0.5, growth: 0.15 };
            graded_rectangle([-2.0, 2.0], y, &grading).unwrap()
        };
        let bodies = [
            body("lower", half(false), steel, vec![Support::clamp("bottom")], vec![]),
            body("upper", half(true), steel, vec![Support::roller("left")], vec![("top".into(), [0.0, -0.07])]),
        ];
        let gap = ObstacleShape::Parabola { center: 0.0, radius: 1.0 };
        let problem = Problem::two_bodies(bodies, pair("lower.top", "upper.bottom", gap), [0.0, 0.0]).unwrap();
        let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged);
        assert!((sol.normal_force - 0.28).abs() <= 1e-9, "the contact carries the load: {}", sol.normal_force);
        errors.push(hertz_l2_error_with(&problem, &sol, combined_modulus(&steel, &steel)));
    }
    eprintln!("punch pushed by a load: L2 errors against Hertz {errors:?}");
    assert!(errors[2] < errors[1] && errors[1] < errors[0], "{errors:?}");
}

/// The same body numbered backwards: the pins fall on other nodes, the answer is the same (the pins carry
/// no force). A block with no support, under a tangential load that friction holds (three free motions).
#[test]
fn the_answer_does_not_depend_on_where_the_pins_are() {
    let forward = block_on_foundation(vec![], [0.4, -2.0]);
    let mesh = &forward.mesh;
    let n = mesh.n_nodes();
    let back = |i: usize| n - 1 - i;
    let points: Vec<[f64; 2]> = (0..n).map(|i| mesh.points()[back(i)]).collect();
    let triangles = mesh.triangles().iter().map(|t| t.map(back)).collect();
    let sets = mesh.edge_sets().iter().map(|(k, v)| (k.clone(), v.iter().map(|e| e.map(back)).collect())).collect();
    let backward = Problem::new(Mesh::new(points, triangles, sets).unwrap(), forward.spec.clone()).unwrap();
    let pinned = |p: &Problem, map: &dyn Fn(usize) -> usize| {
        let mut nodes: Vec<usize> = p.dofs.pins.iter().map(|(i, _)| map(*i)).collect();
        nodes.sort_unstable();
        nodes
    };
    assert_ne!(pinned(&forward, &|i| i), pinned(&backward, &back), "other pins");
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let (a, b) = [&forward, &backward].map(|p| p.solve(&coulomb, &SolverSettings::default(), None).unwrap()).into();
    let scale = max_abs(&a.displacement);
    for i in 0..n {
        for c in 0..2 {
            let diff = (a.displacement[2 * i + c] - b.displacement[2 * back(i) + c]).abs();
            assert!(diff <= 1e-8 * scale, "node {i}: {diff:e} of {scale:e}");
        }
    }
    let diff = a.lambda_n.iter().zip(&b.lambda_n).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(diff <= 1e-8 * max_abs(&a.lambda_n), "λ_n differs by {diff:e}");
}

/// Fretting with a punch held in y by the contact alone: the upper block is pushed down by a uniform
/// traction and moved along x by its top (which leaves it a rotation about a point of that line, held by
/// the pressure too). Every step converges with its KKT residuals at round-off, the contact carries the
/// load at every step, and the friction force follows the shear below μ P and changes sign with it.
#[test]
fn a_history_shears_a_punch_held_by_the_contact() {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let half = |upper: bool| {
        let (side, y) = if upper { (Side::Bottom, [0.0, 1.0]) } else { (Side::Top, [-2.0, 0.0]) };
        let grading = Grading { side, segment: [-0.3, 0.3], h_min: 0.02, h_max: 0.5, growth: 0.15 };
        graded_rectangle([-2.0, 2.0], y, &grading).unwrap()
    };
    let top = Support::displacement("top", Some(0.0), None);
    let bodies = [
        body("lower", half(false), steel, vec![Support::clamp("bottom")], vec![]),
        body("upper", half(true), steel, vec![top], vec![("top".into(), [0.0, -0.07])]),
    ];
    let gap = ObstacleShape::Parabola { center: 0.0, radius: 1.0 };
    let problem = Problem::two_bodies(bodies, pair("lower.top", "upper.bottom", gap), [0.0, 0.0]).unwrap();
    assert_eq!(problem.dofs.n_floating(), 2, "y, and a rotation about a point of the top");
    let mu = 0.3;
    let xs = [0.0, 0.0005, 0.001, 0.0, -0.001];
    let steps: Vec<LoadStep> = xs
        .iter()
        .map(|&x| LoadStep { approach: 0.0, shift: 0.0, load_factor: 1.0, displacements: vec![x], rotation: None })
        .collect();
    let history = problem.solve_history(&Friction::Coulomb { mu }, &steps, &SolverSettings::default(), None).unwrap();
    assert_eq!(history.status, SolveStatus::Converged);
    let q: Vec<f64> = history.solutions.iter().map(|s| s.tangential_force).collect();
    for s in &history.solutions {
        assert!(s.kkt.max() < 1e-8, "{:?}", s.kkt);
        assert!((s.normal_force - 0.28).abs() <= 1e-9, "{}", s.normal_force);
        assert!(s.tangential_force.abs() < mu * s.normal_force);
    }
    eprintln!("Q over the steps: {q:?}");
    assert!(q[1] > q[0] && q[2] > q[1], "loading: {q:?}");
    assert!(q[3] < q[2] && q[4] < 0.0 && q[4] * q[2] < 0.0, "unloading and reversed: {q:?}");
}

/// The patch test with P0 multipliers and with the classic mixed method (γ0 = 0): the equilibrium
/// equality does not depend on the multiplier space or the stabilization.
#[test]
fn the_patch_test_holds_for_p0_multipliers_and_without_stabilization() {
    let p = 2.0;
    let mut problem = block_on_foundation(vec![Support::roller("left")], [0.0, -p]);
    problem = Problem::new(
        problem.mesh.clone(),
        ProblemSpec { multiplier_space: MultiplierSpace::P0, ..problem.spec.clone() },
    )
    .unwrap();
    for stabilization in [Stabilization::Gamma0(0.0), Stabilization::default()] {
        let settings = SolverSettings { stabilization, ..Default::default() };
        let sol = problem.solve(&Friction::Frictionless, &settings, None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged, "{stabilization:?}");
        assert!(sol.lambda_n.iter().all(|l| (l - p).abs() <= PATCH_TOL * p), "{stabilization:?}: {:?}", sol.lambda_n);
    }
}

/// Defect D31: a Coulomb history that unloads a block held only by the contact (load factor 1 → 0) says
/// what the static solve of the unloaded block says (nothing presses it against the contact: its position
/// is undetermined), naming the motion; it ended `stagnated` with no reason. The loaded step alone converges.
#[test]
fn a_history_that_unloads_a_body_held_by_the_contact_says_why_it_stops() {
    let problem = block_on_foundation(vec![], [0.0, -0.1]);
    let (coulomb, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let step = |load_factor| LoadStep { approach: 0.0, shift: 0.0, load_factor, displacements: vec![], rotation: None };
    let loaded = problem.solve_history(&coulomb, &[step(1.0)], &settings, None).unwrap();
    assert_eq!(loaded.status, SolveStatus::Converged);
    let unloaded = block_on_foundation(vec![], [0.0, 0.0]);
    let static_error = unloaded.solve(&coulomb, &settings, None).map(|s| s.report.status).unwrap_err();
    match problem.solve_history(&coulomb, &[step(1.0), step(0.0)], &settings, None) {
        Err(e @ Error::HeldOnlyByContact { .. }) => {
            let (Error::HeldOnlyByContact { what, motion, .. }, Error::HeldOnlyByContact { motion: m, .. }) =
                (&e, &static_error)
            else {
                unreachable!()
            };
            assert!(what.contains("undetermined") && motion == m, "{e}; the static solve: {static_error}");
        }
        other => panic!("expected HeldOnlyByContact, got {:?}", other.map(|h| h.status)),
    }
}

/// Defect D30: a block held only by the contact (pressed by a traction, no support), dragged by the obstacle
/// (μ = 0.3, no tangential load), follows the obstacle in one static solve; as a history of two or three steps
/// its last step ended `stagnated`, the change of λ_n between two QPs at clarabel's noise (3e-8 to 2e-6) while
/// the iterate met Coulomb's law to 5e-12. It converges now, to the static answer; a fixed point that cycles
/// is still reported (`coulomb_newton.rs`, the wedge forced into a groove).
#[test]
fn a_history_drags_a_body_held_by_the_contact_as_the_static_solve_does() {
    let problem = block_on_foundation(vec![], [0.0, -2.0]);
    let (coulomb, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let dragged = |s: f64| LoadStep::new(0.0, s);
    let static_problem = Problem::new(
        problem.mesh.clone(),
        ProblemSpec { obstacle: Obstacle { shift: 0.002, ..problem.spec.obstacle.clone() }, ..problem.spec.clone() },
    )
    .unwrap();
    let alone = static_problem.solve(&coulomb, &settings, None).unwrap();
    assert_eq!(alone.report.status, SolveStatus::Converged);
    let mean_ux = |s: &Solution| s.displacement.iter().step_by(2).sum::<f64>() / (s.displacement.len() / 2) as f64;
    assert!((mean_ux(&alone) - 0.002).abs() <= 1e-9, "the block follows the obstacle: {}", mean_ux(&alone));
    for shifts in [vec![0.0, 0.002], vec![0.0, 0.001, 0.002]] {
        let steps: Vec<LoadStep> = shifts.iter().map(|&s| dragged(s)).collect();
        let history = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
        assert_eq!(history.status, SolveStatus::Converged, "{shifts:?}");
        let last = history.solutions.last().unwrap();
        assert!(last.kkt.max() <= settings.fp.tol, "{:?}", last.kkt);
        assert!((mean_ux(last) - 0.002).abs() <= 1e-9, "{shifts:?}: {}", mean_ux(last));
        let scale = max_abs(&alone.lambda_n);
        for (a, b) in [(&last.lambda_n, &alone.lambda_n), (&last.lambda_t, &alone.lambda_t)] {
            let d = a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(d <= 1e-5 * scale, "{shifts:?}: λ differs from the static answer by {d:e}");
        }
    }
}

/// A frictionless history that ramps the load is path independent: each step equals the static solve of
/// its load (the equilibrium's load scales with the step's load factor).
#[test]
fn a_ramped_load_gives_the_static_answer_at_every_step() {
    let problem = block_on_foundation(vec![Support::roller("left")], [0.3, -2.0]);
    let settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let steps: Vec<LoadStep> = [0.25, 0.5, 1.0]
        .iter()
        .map(|&load_factor| LoadStep { approach: 0.0, shift: 0.0, load_factor, displacements: vec![], rotation: None })
        .collect();
    let history = problem.solve_history(&Friction::Frictionless, &steps, &settings, None).unwrap();
    assert_eq!(history.status, SolveStatus::Converged);
    for (step, sol) in steps.iter().zip(&history.solutions) {
        let scaled =
            block_on_foundation(vec![Support::roller("left")], [0.3 * step.load_factor, -2.0 * step.load_factor]);
        let alone = scaled.solve(&Friction::Frictionless, &settings, None).unwrap();
        let diff = sol.displacement.iter().zip(&alone.displacement).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(diff <= 1e-9 * max_abs(&alone.displacement), "load factor {}: {diff:e}", step.load_factor);
    }
    // With friction the ramp converges at every step, the contact carrying the load.
    let history = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    assert_eq!(history.status, SolveStatus::Converged);
    for (step, sol) in steps.iter().zip(&history.solutions) {
        assert!((sol.normal_force - 4.0 * step.load_factor).abs() <= 1e-9 * 4.0);
    }
}

/// A punch held by the contact refines adaptively from coarse uniform meshes of both blocks: every level
/// keeps it free in y (pinned afresh on the refined mesh), the contact carries the load at the last one,
/// and the loop stops at the tolerance.
#[test]
fn a_punch_held_by_the_contact_refines_adaptively() {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let lower = rectangle([-2.0, 2.0], [-2.0, 0.0], 8, 4, Diagonal::Right).unwrap();
    let upper = rectangle([-2.0, 2.0], [0.0, 2.0], 8, 4, Diagonal::Left).unwrap();
    let bodies = [
        body("lower", lower, steel, vec![Support::clamp("bottom")], vec![]),
        body("upper", upper, steel, vec![Support::roller("left")], vec![("top".into(), [0.0, -0.07])]),
    ];
    let gap = ObstacleShape::Parabola { center: 0.0, radius: 1.0 };
    let problem = Problem::two_bodies(bodies, pair("lower.top", "upper.bottom", gap), [0.0, 0.0]).unwrap();
    // Stopping on the bound, which refines deep enough for the loop's work to show.
    let adapt = AdaptSettings { tol: 0.15, max_unknowns: 100_000, stop_on: StopOn::Bound, ..Default::default() };
    let out = problem.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).unwrap();
    assert_eq!(out.stop, AdaptStop::Tolerance);
    assert_eq!(out.problem.dofs.n_floating(), 1);
    assert!(out.levels.len() > 5 && out.problem.n_free > 10 * out.levels[0].unknowns);
    assert!((out.solution.normal_force - 0.28).abs() <= 1e-9, "{}", out.solution.normal_force);
}
