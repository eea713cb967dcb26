//! The mixed displacement–pressure formulation (issue 41, item 1; `tribo::fem::mixed`): the patch state
//! exact up to ν = 0.4999, with and without stabilization and friction, through a lifting too; Hertz
//! without locking where P1 displacements lock; clarabel and the active-set method to one answer; the
//! quasi-definite factorization's inertia checked; the combinations it does not take refused.

use tribo::*;
use tribo_testkit::{hertz_l2_error_with, hertz_scene, hertz_spec};

const E: f64 = 1000.0;

/// The patch state of `patch.rs` (`u = (1 − y)(a, b)` on the distorted unit square, clamped on top, Γ_C its
/// bottom, the sides loaded by σ·n of the state, the obstacle shifted by a: sticking), for ν and the
/// formulation: `σ_xx = −λ b`, `σ_xy = −G a`,
/// `λ_n = (λ + 2G) b`, `λ_t = −G a`, the pressure `p = −λ div u = λ b`.
fn patch(nu: f64, a: f64, b: f64, formulation: Formulation, space: MultiplierSpace) -> (Problem, [f64; 3]) {
    let (lam, g) = (E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu)));
    let (sxx, sxy) = (-lam * b, -g * a);
    let spec = ProblemSpec::new(Material { young: E, poisson: nu }, "bottom")
        .clamped(["top"])
        .traction("left", [-sxx, -sxy])
        .traction("right", [sxx, sxy])
        .approach(b)
        .shift(a)
        .multipliers(MultiplierPoints::RatioToFe(1.3), space)
        .formulation(formulation);
    let problem = Problem::new(tribo_testkit::distorted_square(8), spec).expect("valid patch problem");
    (problem, [(lam + 2.0 * g) * b, -g * a, lam * b])
}

fn settings(stabilization: Stabilization, qp: QpMethod) -> SolverSettings {
    let mut s = SolverSettings { stabilization, ..SolverSettings::default() };
    s.qp.method = qp;
    s
}

fn worst(v: &[f64], exact: f64) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max((x - exact).abs())) / exact.abs()
}

/// The constant-strain state is in the mixed space (u linear, p constant: the bubble's C p = 0): λ_n, λ_t, p
/// and σ are exact to the QP's accuracy for ν from 0.3 to 0.4999, P0 and P1 multipliers on a non-matching
/// T_H, γ0 = 0 and ½ the bound, frictionless and Coulomb sticking. (A constant strain is in the P1 space too:
/// a patch test cannot show locking; Hertz does.)
#[test]
fn the_patch_state_is_exact_in_the_mixed_formulation() {
    for nu in [0.3, 0.49, 0.4999] {
        for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
            for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
                for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.5 }] {
                    let a = if friction == Friction::Frictionless { 0.0 } else { 1e-4 };
                    let (problem, [ln, lt, p]) = patch(nu, a, 1e-3, Formulation::Mixed, space);
                    let sol = problem.solve(&friction, &settings(stab, QpMethod::Auto), None).expect("solves");
                    let case = format!("ν = {nu}, {space:?}, {stab:?}, {friction:?}");
                    assert_eq!(sol.report.status, SolveStatus::Converged, "{case}");
                    assert!(worst(&sol.lambda_n, ln) < 1e-6, "{case}: λ_n {:?} ≠ {ln}", &sol.lambda_n[..3]);
                    if a != 0.0 {
                        assert!(worst(&sol.lambda_t, lt) < 1e-6, "{case}: λ_t ≠ {lt}");
                    }
                    assert_eq!(sol.pressure.len(), problem.mesh.n_nodes());
                    assert!(worst(&sol.pressure, p) < 1e-6, "{case}: p ≠ {p}");
                    let sxx: Vec<f64> = sol.stress.iter().map(|s| s[0]).collect();
                    assert!(worst(&sxx, -p) < 1e-6, "{case}: σ_xx ≠ {}", -p);
                    assert!(sol.kkt.max() < 1e-6, "{case}: {:?}", sol.kkt);
                }
            }
        }
    }
}

/// A lifting: the body moved down by a prescribed displacement of its top (approach 0) is the clamped body
/// pressed by the obstacle's approach, translated; the pressure rows carry `B ū` and the stabilization's
/// action on ū (two paths to one answer).
#[test]
fn a_prescribed_displacement_is_the_obstacle_moved_in_the_mixed_formulation() {
    let (clamped, _) = patch(0.4999, 0.0, 1e-3, Formulation::Mixed, MultiplierSpace::P1);
    let lifted = Problem::new(
        clamped.mesh.clone(),
        ProblemSpec {
            clamped: vec![],
            supports: vec![Support::displacement("top", Some(0.0), Some(-1e-3))],
            ..clamped.spec.clone().approach(0.0)
        },
    )
    .expect("valid");
    let s = settings(Stabilization::Fraction(0.5), QpMethod::Auto);
    let (a, b) = (
        clamped.solve(&Friction::Frictionless, &s, None).expect("solves"),
        lifted.solve(&Friction::Frictionless, &s, None).expect("solves"),
    );
    assert_eq!((a.report.status, b.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    let scale = a.lambda_n.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(a.lambda_n.iter().zip(&b.lambda_n).all(|(x, y)| (x - y).abs() < 1e-8 * scale));
    assert!(a.pressure.iter().zip(&b.pressure).all(|(x, y)| (x - y).abs() < 1e-8 * scale));
    for (i, (x, y)) in a.displacement.chunks(2).zip(b.displacement.chunks(2)).enumerate() {
        assert!((x[0] - y[0]).abs() < 1e-10 && (x[1] - 1e-3 - y[1]).abs() < 1e-10, "node {i}: {x:?} against {y:?}");
    }
}

/// The Hertz problem from the coarse 8 × 4 mesh, adapted to `tol`, at ν with the formulation: the run and the
/// relative L² error of λ_n against Hertz's pressure of the computed force (E* = E / (1 − ν²)).
fn adaptive_hertz(nu: f64, formulation: Formulation, tol: f64) -> (Adaptive, f64) {
    let s = hertz_scene();
    let material = Material { young: s.material.young, poisson: nu };
    let spec =
        ProblemSpec { material, ..hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1) }
            .formulation(formulation);
    let coarse = Problem::new(rectangle(s.x, s.y, 8, 4, Diagonal::Right).expect("valid"), spec).expect("valid");
    let adapt = AdaptSettings { tol, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    let e = hertz_l2_error_with(&run.problem, &run.solution, s.material.young / (1.0 - nu * nu));
    (run, e)
}

/// Locking removed (issue 41's bar): adapted to 2 %, the displacement formulation at ν = 0.3 and the mixed one
/// at ν = 0.499 and 0.4999 are within 2 % of Hertz; on the mixed run's last mesh at ν = 0.4999 the
/// displacement formulation is far off (locking).
#[test]
fn hertz_does_not_lock_in_the_mixed_formulation() {
    let (_, p1) = adaptive_hertz(0.3, Formulation::Displacement, 0.02);
    assert!(p1 < 0.02, "P1 at ν = 0.3: {p1}");
    for nu in [0.499, 0.4999] {
        let (run, mixed) = adaptive_hertz(nu, Formulation::Mixed, 0.02);
        assert_eq!(run.solution.report.status, SolveStatus::Converged);
        assert!(mixed < 0.02, "mixed at ν = {nu}: {mixed} (P1 at ν = 0.3: {p1})");
        let spec = ProblemSpec { formulation: Formulation::Displacement, ..run.problem.spec.clone() };
        let locked = Problem::new(run.problem.mesh.clone(), spec).expect("valid");
        let sol = locked.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
        let e_star = hertz_scene().material.young / (1.0 - nu * nu);
        let error = hertz_l2_error_with(&locked, &sol, e_star);
        assert!(error > 5.0 * mixed.max(0.01), "ν = {nu}: P1 {error} against {mixed}");
    }
}

/// clarabel (the reference) and the active-set method give one answer on the mixed formulation's QPs (H is
/// positive definite: the module's argument), Coulomb with partial slip on Hertz at ν = 0.4999, and so do the
/// columns of H and the quasi-definite saddle-point system (the pressures' pivots negative).
#[test]
fn clarabel_and_the_active_set_agree_on_the_mixed_formulation() {
    let s = hertz_scene();
    let spec = ProblemSpec {
        material: Material { young: s.material.young, poisson: 0.4999 },
        ..hertz_spec(s.approach, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
    }
    .formulation(Formulation::Mixed);
    let problem = Problem::new(tribo_testkit::hertz_mesh(0.02), spec).expect("valid");
    let friction = Friction::Coulomb { mu: 0.3 };
    let stab = Stabilization::Fraction(0.5);
    let reference = problem.solve(&friction, &settings(stab, QpMethod::Clarabel), None).expect("solves");
    let active = problem.solve(&friction, &settings(stab, QpMethod::ActiveSet), None).expect("solves");
    assert_eq!((reference.report.status, active.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    assert!(reference.states.contains(&ContactState::Slip) && reference.states.contains(&ContactState::Stick));
    let scale = reference.lambda_n.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let apart = reference.lambda_n.iter().zip(&active.lambda_n).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(apart < 1e-4 * scale, "λ_n apart by {apart} of {scale}");
    for condensation in [Condensation::Columns, Condensation::Saddle] {
        let mut s = settings(stab, QpMethod::ActiveSet);
        s.condensation = condensation;
        let sol = problem.solve(&friction, &s, None).expect("solves");
        assert_eq!(sol.report.condensation, condensation);
        let apart = sol.lambda_n.iter().zip(&active.lambda_n).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(apart < 1e-6 * scale, "{condensation:?}: λ_n apart by {apart} of {scale}");
    }
    // Equilibrium of the whole body: the reactions balance the contact force.
    let reaction: f64 = active.reactions.iter().skip(1).step_by(2).sum();
    assert!(
        (reaction + active.contact_force[1]).abs() < 1e-8 * active.normal_force,
        "{reaction} against {:?}",
        active.contact_force
    );
}

/// What the mixed formulation does not take is refused: ν ≤ 0, the partial factorization (a
/// Cholesky kernel); a γ0 beyond the bound forced unchecked ends in an error naming the inertia, not
/// in a wrong H.
#[test]
fn the_mixed_formulation_refuses_what_it_does_not_take() {
    let (problem, _) = patch(0.4, 0.0, 1e-3, Formulation::Mixed, MultiplierSpace::P1);
    let spec = problem.spec.clone();
    for nu in [0.0, -0.3] {
        let e = Problem::new(
            problem.mesh.clone(),
            ProblemSpec { material: Material { young: E, poisson: nu }, ..spec.clone() },
        );
        assert!(matches!(&e, Err(Error::BadMaterial { what }) if what.contains("mixed")), "ν = {nu}: {e:?}");
    }
    let s = SolverSettings { condensation: Condensation::Schur, ..SolverSettings::default() };
    let e = problem.solve(&Friction::Frictionless, &s, None);
    assert!(matches!(&e, Err(Error::BadSetting { name: "condensation", .. })), "{e:?}");
    let beyond = Stabilization::Unchecked(1e3 * problem.gamma0_bound.value);
    let e = problem.solve(&Friction::Frictionless, &settings(beyond, QpMethod::Auto), None);
    assert!(matches!(&e, Err(Error::NotPositiveDefinite { what }) if what.contains("quasi-definite")), "{e:?}");
}

/// A history in the mixed formulation: the patch state pressed in three steps, then sheared by the obstacle's
/// shift with Coulomb friction (stick), ends at the exact state; and the body pressed by moving a prescribed
/// displacement of its top step by step (the lifting's change through the pressure rows) ends where the
/// static solve of its last step does.
#[test]
fn a_history_in_the_mixed_formulation_ends_at_the_static_answer() {
    let (a, b) = (1e-4, 1e-3);
    let (problem, [ln, lt, p]) = patch(0.4999, a, b, Formulation::Mixed, MultiplierSpace::P1);
    let friction = Friction::Coulomb { mu: 0.5 };
    let s = settings(Stabilization::Fraction(0.5), QpMethod::Auto);
    let steps =
        [LoadStep::new(b / 3.0, 0.0), LoadStep::new(2.0 * b / 3.0, 0.0), LoadStep::new(b, 0.0), LoadStep::new(b, a)];
    let history = problem.solve_history(&friction, &steps, &s, None).expect("solves");
    assert_eq!(history.status, SolveStatus::Converged);
    let last = history.solutions.last().expect("kept");
    assert!(worst(&last.lambda_n, ln) < 1e-6 && worst(&last.lambda_t, lt) < 1e-6 && worst(&last.pressure, p) < 1e-6);
    let spec = ProblemSpec {
        clamped: vec![],
        supports: vec![Support::displacement("top", Some(0.0), Some(-b))],
        tractions: vec![],
        ..problem.spec.clone().approach(0.0).shift(0.0)
    };
    let lifted = Problem::new(problem.mesh.clone(), spec).expect("valid");
    let steps: Vec<LoadStep> = [-b / 3.0, -2.0 * b / 3.0, -b]
        .iter()
        .map(|&y| LoadStep::new(0.0, 0.0).with_displacements(vec![0.0, y]))
        .collect();
    let history = lifted.solve_history(&friction, &steps, &s, None).expect("solves");
    let direct = lifted.solve(&friction, &s, None).expect("solves");
    let last = history.solutions.last().expect("kept");
    assert_eq!(history.status, SolveStatus::Converged);
    let scale = direct.pressure.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let apart = last.pressure.iter().zip(&direct.pressure).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(apart < 1e-6 * scale, "pressure apart by {apart} of {scale}");
    assert!(last.lambda_n.iter().zip(&direct.lambda_n).all(|(x, y)| (x - y).abs() < 1e-6 * scale));
}

/// Two layers of one material are the homogeneous body, in the mixed formulation too (each triangle's material
/// read through its region, the same bits).
#[test]
fn two_layers_of_one_material_are_one_body_in_the_mixed_formulation() {
    let (problem, _) = patch(0.499, 1e-4, 1e-3, Formulation::Mixed, MultiplierSpace::P1);
    let mesh = problem.mesh.clone();
    let region: Vec<usize> = (0..mesh.n_triangles()).map(|t| usize::from(mesh.vertices(t)[0][1] > 0.5)).collect();
    let material = problem.spec.material;
    let layered =
        Problem::with_materials(mesh, problem.spec.clone(), Materials { materials: vec![material; 2], region })
            .expect("valid");
    let s = settings(Stabilization::Fraction(0.5), QpMethod::Auto);
    let friction = Friction::Coulomb { mu: 0.5 };
    let (one, two) =
        (problem.solve(&friction, &s, None).expect("solves"), layered.solve(&friction, &s, None).expect("solves"));
    assert_eq!(one.lambda_n, two.lambda_n);
    assert_eq!(one.pressure, two.pressure);
    assert_eq!(one.displacement, two.displacement);
}

/// `Auto`, the default, is mixed from ν = 0.49 in plane strain and P1 displacements below it, in plane stress,
/// and beside a material of ν ≤ 0 (which the mixed formulation refuses); the built problem's spec says which it
/// took.
#[test]
fn auto_takes_the_mixed_formulation_from_nu_0_49_in_plane_strain() {
    let (problem, _) = patch(0.3, 0.0, 1e-3, Formulation::Auto, MultiplierSpace::P1);
    let chosen = |nu: f64, model: Model| {
        let spec = ProblemSpec { material: Material { young: E, poisson: nu }, ..problem.spec.clone() }.model(model);
        Problem::new(problem.mesh.clone(), spec.formulation(Formulation::Auto)).expect("valid").spec.formulation
    };
    assert_eq!(problem.spec.formulation, Formulation::Displacement);
    assert_eq!(chosen(0.48, Model::PlaneStrain), Formulation::Displacement);
    assert_eq!(chosen(tribo::fem::mixed::MIXED_FROM_POISSON, Model::PlaneStrain), Formulation::Mixed);
    assert_eq!(chosen(0.4999, Model::PlaneStrain), Formulation::Mixed);
    assert_eq!(chosen(0.4999, Model::PlaneStress), Formulation::Displacement);
    assert_eq!(ProblemSpec::new(Material { young: E, poisson: 0.3 }, "bottom").formulation, Formulation::Auto);
    // A rubber layer on a cork one: the mixed formulation refuses ν = 0, so auto keeps P1 (no error).
    let mesh = problem.mesh.clone();
    let region: Vec<usize> = (0..mesh.n_triangles()).map(|t| usize::from(mesh.vertices(t)[0][1] > 0.5)).collect();
    let materials = vec![Material { young: E, poisson: 0.0 }, Material { young: E, poisson: 0.4999 }];
    let layered = Problem::with_materials(mesh, problem.spec.clone(), Materials { materials, region });
    assert_eq!(layered.expect("valid").spec.formulation, Formulation::Displacement);
}

/// A load factor scales the pressure rows' part of the body force too (the condensed bubble's): a history step
/// at half the load is the static problem with half the body force (no other load; frictionless, so
/// path-independent).
#[test]
fn a_load_factor_scales_the_bubble_load() {
    let (problem, _) = patch(0.4999, 0.0, 1e-3, Formulation::Mixed, MultiplierSpace::P1);
    let heavy = |g: f64| {
        let spec = ProblemSpec { body_force: [0.3 * g, -50.0 * g], tractions: vec![], ..problem.spec.clone() };
        Problem::new(problem.mesh.clone(), spec).expect("valid")
    };
    let s = settings(Stabilization::Fraction(0.5), QpMethod::Auto);
    let steps = [LoadStep { load_factor: 0.5, ..LoadStep::new(1e-3, 0.0) }];
    let history = heavy(1.0).solve_history(&Friction::Frictionless, &steps, &s, None).expect("solves");
    let direct = heavy(0.5).solve(&Friction::Frictionless, &s, None).expect("solves");
    let step = &history.solutions[0];
    let scale = direct.pressure.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let apart = step.pressure.iter().zip(&direct.pressure).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(apart < 1e-8 * scale, "pressure apart by {apart} of {scale}");
    assert!(step.lambda_n.iter().zip(&direct.lambda_n).all(|(x, y)| (x - y).abs() < 1e-8 * scale));
}

/// A history step that repeats the last one changes nothing: the state a step leaves for the next reads the
/// stabilization's pressure part too. Against a rigid disc given by its geometry the contact normal turns
/// away from the body's outward normal, so σ_t(v, q) reads the pressure (Coulomb, partial slip, ν = 0.4999).
#[test]
fn a_repeated_history_step_changes_nothing_in_the_mixed_formulation() {
    let s = hertz_scene();
    let spec = ProblemSpec {
        material: Material { young: s.material.young, poisson: 0.4999 },
        ..hertz_spec(0.0, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
    }
    .obstacle(ObstacleShape::Disc { center: [0.0, 1.0], radius: 1.0 })
    .formulation(Formulation::Mixed);
    let problem = Problem::new(tribo_testkit::hertz_mesh(0.02), spec).expect("valid");
    let step = LoadStep::new(s.approach, 0.003);
    let settings = settings(Stabilization::Fraction(0.5), QpMethod::Auto);
    let history = problem.solve_history(&Friction::Coulomb { mu: 0.3 }, &[step.clone(), step], &settings, None);
    let history = history.expect("solves");
    assert_eq!(history.status, SolveStatus::Converged);
    let (first, second) = (&history.solutions[0], &history.solutions[1]);
    assert!(first.states.contains(&ContactState::Slip) && first.states.contains(&ContactState::Stick));
    let scale = first.lambda_n.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let moved = first.lambda_t.iter().zip(&second.lambda_t).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(moved < 1e-6 * scale, "λ_t moved by {moved} of {scale}");
}

/// The KKT residuals do not depend on the units: a mixed formulation's pressures (in stress units) do not
/// enter the scale of the gap residuals, nor its constraint rows the force scale of equilibrium. Hertz at
/// ν = 0.4999 with E = 200 and with E = 2e8 (the same problem in other units of stress).
#[test]
fn the_kkt_residuals_of_the_mixed_formulation_do_not_depend_on_units() {
    let s = hertz_scene();
    let residuals = |young: f64| {
        let spec = ProblemSpec {
            material: Material { young, poisson: 0.4999 },
            ..hertz_spec(s.approach, 0.002, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
        }
        .formulation(Formulation::Mixed);
        let problem = Problem::new(tribo_testkit::hertz_mesh(0.02), spec).expect("valid");
        // Loose tolerances (clarabel's interior point stops short), so that the residuals are well above
        // round-off and their scales show.
        let mut settings = SolverSettings::default();
        (settings.fp.tol, settings.qp.tol, settings.qp.method) = (1e-3, 1e-5, QpMethod::Clarabel);
        let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &settings, None).expect("solves");
        sol.kkt
    };
    let (a, b) = (residuals(200.0), residuals(2e8));
    // The gap residuals are read against the size of E u: well above round-off here (measured 2.8e-11 and 6.2e-11).
    assert!(a.normal_complementarity.min(a.stick) > 1e-13, "{a:?}");
    for ((name, x), (_, y)) in a.named().into_iter().zip(b.named()) {
        assert!(x.max(y) < 1e-14 || (x / y).max(y / x) < 10.0, "{name}: {x:e} against {y:e}");
    }
}

/// Two bodies take the mixed formulation too (both bodies' pressures, each its own nodes): two-body Hertz, a
/// rubber block (ν = 0.4999) under a steel one, against Hertz of the combined modulus. `auto` chooses it; it is
/// as close as P1 displacements are for a compressible block (ν = 0.3) on the same meshes, and P1 displacements
/// on the rubber lock.
#[test]
fn a_rubber_body_under_a_steel_one_does_not_lock() {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let error = |lower: Material, formulation: Formulation| {
        let (bodies, pair) = tribo_testkit::two_body_hertz_parts(0.0025, lower, steel, 0.01);
        let problem = Problem::two_bodies(bodies, ContactPair { formulation, ..pair }, [0.0, 0.0]).expect("valid");
        let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let e_star = tribo_testkit::combined_modulus(&lower, &steel);
        (problem.spec.formulation, hertz_l2_error_with(&problem, &sol, e_star))
    };
    let rubber = Material { young: 200.0, poisson: 0.4999 };
    let ((chosen, mixed), (_, locked)) = (error(rubber, Formulation::Auto), error(rubber, Formulation::Displacement));
    let (_, compressible) = error(Material { young: 200.0, poisson: 0.3 }, Formulation::Displacement);
    assert_eq!(chosen, Formulation::Mixed);
    assert!(mixed < 1.5 * compressible && locked > 5.0 * mixed, "mixed {mixed}, P1 {locked}, ν = 0.3 {compressible}");
}
