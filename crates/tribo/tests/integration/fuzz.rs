//! Hostile input fuzzed through the core (proptest): generated meshes (degenerate, folded, out-of-range
//! indices, huge and tiny coordinates), materials, loads, obstacles, multiplier meshes, friction laws and
//! solver settings with NaN, ±∞, subnormals and ±1e300 among the values. The only acceptable outcomes:
//! a typed error, or a solution whose status is honest (`converged` means every field finite and the KKT
//! residuals within what the tolerances justify). A panic fails the test.
//!
//! The default budget is small (CI); `PROPTEST_CASES=N` (proptest's own variable) runs N cases per test.

use std::collections::BTreeMap;

use proptest::prelude::*;
use tribo::*;

/// Hostile and ordinary floats.
fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -10.0f64..10.0,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(0.0),
        1 => Just(-0.0),
        1 => Just(5e-324),
        1 => Just(1e-310),
        1 => Just(1e300),
        1 => Just(-1e300),
        1 => Just(f64::MAX),
        1 => (-300i32..300).prop_map(|e| 10f64.powi(e)),
    ]
}

/// A valid value (from `valid`) four times in five, a hostile one otherwise: so that a case has a few hostile
/// values and reaches the solve often enough.
fn mostly(valid: std::ops::Range<f64>) -> impl Strategy<Value = f64> {
    prop_oneof![6 => valid, 1 => any_f64()]
}

/// A mesh from arrays: a perturbed grid, or arbitrary points and triangles (most of which are refused).
fn any_mesh() -> impl Strategy<Value = Result<Mesh>> {
    let grid = (1usize..5, 1usize..4, mostly(0.1..10.0), 0.0f64..0.3, any::<u64>()).prop_map(
        |(nx, ny, scale, jitter, seed)| {
            let m = rectangle([0.0, 1.0], [-1.0, 0.0], nx, ny, Diagonal::Alternating).expect("valid");
            let mut s = seed | 1;
            let pts = m
                .points()
                .iter()
                .map(|p| {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    let r = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                    [scale * (p[0] + jitter * r / nx as f64), scale * (p[1] + jitter * r / ny as f64)]
                })
                .collect();
            Mesh::new(pts, m.triangles().to_vec(), m.edge_sets().clone())
        },
    );
    let arbitrary = (
        prop::collection::vec((any_f64(), any_f64()), 0..8),
        prop::collection::vec((0usize..10, 0usize..10, 0usize..10), 0..6),
        prop::collection::vec((0usize..10, 0usize..10), 0..4),
    )
        .prop_map(|(pts, tris, edges)| {
            let pts = pts.into_iter().map(|(x, y)| [x, y]).collect();
            let tris = tris.into_iter().map(|(a, b, c)| [a, b, c]).collect();
            let mut sets = BTreeMap::new();
            sets.insert("top".to_string(), edges.iter().map(|&(a, b)| [a, b]).collect());
            Mesh::new(pts, tris, sets)
        });
    prop_oneof![6 => grid, 1 => arbitrary]
}

fn any_points() -> impl Strategy<Value = MultiplierPoints> {
    prop_oneof![
        1 => any_f64().prop_map(MultiplierPoints::RatioToFe),
        1 => any_f64().prop_map(MultiplierPoints::Size),
        1 => prop::collection::vec(any_f64(), 0..6).prop_map(MultiplierPoints::Abscissae),
        1 => (0.3f64..3.0).prop_map(MultiplierPoints::RatioToFe),
        4 => Just(MultiplierPoints::RatioToFe(1.0)),
    ]
}

fn any_friction() -> impl Strategy<Value = Friction> {
    prop_oneof![
        Just(Friction::Frictionless),
        mostly(0.0..2.0).prop_map(|mu| Friction::Coulomb { mu }),
        mostly(0.0..5.0).prop_map(|s| Friction::Tresca(Threshold::Uniform(s))),
    ]
}

fn any_settings() -> impl Strategy<Value = SolverSettings> {
    (any_f64(), 0u32..300, any_f64(), 0usize..50, any_f64(), 0usize..3, 0usize..3).prop_map(
        |(qp_tol, qp_max_iter, fp_tol, fp_max_iter, theta, method, condensation)| {
            let mut s = SolverSettings::default();
            // Half of the cases keep the default tolerances, so that solves reach their end.
            if qp_tol.is_finite() && qp_tol.abs() < 1.0 && qp_tol != 0.0 {
                s.qp.tol = qp_tol.abs();
            }
            s.qp.max_iter = qp_max_iter;
            if fp_tol.abs() < 1e-3 {
                s.fp.tol = fp_tol;
            }
            s.fp.max_iter = fp_max_iter;
            s.qp.method = [QpMethod::Auto, QpMethod::Clarabel, QpMethod::ActiveSet][method];
            s.condensation = [Condensation::Auto, Condensation::Columns, Condensation::Schur][condensation];
            s.stabilization = if theta.is_finite() && (0.0..1.0).contains(&theta) {
                Stabilization::Fraction(theta)
            } else {
                Stabilization::Fraction(theta.abs().fract())
            };
            s
        },
    )
}

/// Reports how a case ended when `TRIBO_FUZZ_VERBOSE` is set (to see what the generators reach).
fn note(what: &str) {
    if std::env::var("TRIBO_FUZZ_VERBOSE").is_ok() {
        eprintln!("fuzz outcome: {what}");
    }
}

/// Any of the models: plane strain (most often), plane stress, axisymmetry.
fn any_model() -> impl Strategy<Value = Model> {
    prop_oneof![2 => Just(Model::PlaneStrain), 1 => Just(Model::PlaneStress), 1 => Just(Model::Axisymmetric)]
}

/// The promise: a converged solution is finite throughout, with KKT residuals within the tolerances.
fn assert_honest(sol: &Solution, settings: &SolverSettings) {
    if sol.report.status == SolveStatus::Converged {
        assert!(sol.all_finite(), "converged with non-finite fields: {:?}", sol.kkt);
        let bound = Solution::accuracy_bound(settings.qp.tol, sol.report.qp_inaccurate, settings.fp.tol);
        assert!(sol.kkt.max() <= bound, "converged with KKT {:?} above {bound:e}", sol.kkt);
    }
}

proptest! {
    #![proptest_config(crate::reproducible(256))]

    /// Any mesh, material, load, obstacle, multiplier mesh, friction law, settings, model and formulation: a typed
    /// error or an honest solution.
    #[test]
    fn hostile_input_is_an_error_or_an_honest_status(
        mesh in any_mesh(),
        young in mostly(1.0..1e4),
        poisson in mostly(-0.5..0.49),
        load in (mostly(-5.0..5.0), mostly(-5.0..5.0)),
        approach in mostly(-0.01..0.05),
        shift in mostly(-0.01..0.01),
        points in any_points(),
        space in prop_oneof![Just(MultiplierSpace::P0), Just(MultiplierSpace::P1)],
        friction in any_friction(),
        settings in any_settings(),
        model in any_model(),
        formulation in prop_oneof![Just(Formulation::Auto), Just(Formulation::Displacement), Just(Formulation::Mixed)],
    ) {
        let Ok(mesh) = mesh else {
            note("mesh refused");
            return Ok(());
        };
        // (an arbitrary mesh has only a "top" set: it is refused for the missing "bottom")
        let (contact, clamped) = ("bottom", "top");
        let spec = ProblemSpec {
            material: Material { young, poisson },
            model,
            formulation,
            clamped: vec![clamped.into()],
            supports: vec![],
            body_force: [load.0, load.1],
            tractions: vec![],
            contact: contact.into(),
            obstacle: Obstacle { shape: ObstacleShape::Flat, approach, shift, rotation: None },
            multiplier_points: points,
            multiplier_space: space,
            pairs: Vec::new(),
        };
        let Ok(problem) = Problem::new(mesh, spec) else {
            note("problem refused");
            return Ok(());
        };
        match problem.solve(&friction, &settings, None) {
            Ok(sol) => {
                note(sol.report.status.name());
                assert_honest(&sol, &settings);
            }
            Err(_) => note("solve refused"),
        }
    }

    /// A body of several materials (issue 41): hostile materials (any number, hostile E and ν) and regions (any
    /// length, indices in and out of range), any friction law and settings: a typed error or an honest solution.
    #[test]
    fn several_materials_are_an_error_or_an_honest_status(
        materials in proptest::collection::vec((mostly(1.0..1e4), mostly(-0.5..0.49)), 0..4),
        length in prop_oneof![6 => Just(32usize), 1 => 0usize..40],
        raw in proptest::collection::vec(any::<u64>(), 40),
        stray in prop_oneof![3 => Just(None), 1 => (0usize..40, prop_oneof![Just(usize::MAX), 3usize..10]).prop_map(Some)],
        friction in any_friction(),
        settings in any_settings(),
    ) {
        let mesh = rectangle([-2.0, 2.0], [-1.0, 0.0], 4, 4, Diagonal::Right).expect("valid");
        let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .obstacle(ObstacleShape::Parabola { center: 0.0, radius: 1.0 })
            .approach(0.01);
        // Regions in range of the materials drawn, but one stray index now and then.
        let n = materials.len().max(1) as u64;
        let mut region: Vec<usize> = raw.iter().map(|r| (r % n) as usize).take(length).collect();
        if let Some((at, value)) = stray.filter(|(at, _)| *at < region.len()) {
            region[at] = value;
        }
        let materials = Materials {
            materials: materials.into_iter().map(|(young, poisson)| Material { young, poisson }).collect(),
            region,
        };
        let Ok(problem) = Problem::with_materials(mesh, spec, materials) else {
            note("materials: problem refused");
            return Ok(());
        };
        match problem.solve(&friction, &settings, None) {
            Ok(sol) => {
                note(&format!("materials: {}", sol.report.status.name()));
                assert_honest(&sol, &settings);
            }
            Err(_) => note("materials: solve refused"),
        }
    }

    /// Valid scenes with extreme but representable data (E from 1e-200 to 1e200, approaches and shifts
    /// over many decades, any μ, any model): every run ends in an honest status.
    #[test]
    fn extreme_valid_data_gives_honest_statuses(
        young_exp in -200i32..200,
        poisson in -0.9f64..0.49,
        approach_exp in -12i32..0,
        shift_exp in -14i32..0,
        mu in prop_oneof![Just(0.0), 0.0f64..3.0, Just(1e8)],
        nx in 2usize..8,
        model in any_model(),
    ) {
        // A solid of revolution is not shifted radially (refused on this top face): its extreme data are the others.
        let shift = if model.is_axisymmetric() { 0.0 } else { 10f64.powi(shift_exp) };
        let mesh = rectangle([0.0, 1.0], [-1.0, 0.0], nx, nx, Diagonal::Right).expect("valid");
        let spec = ProblemSpec {
            material: Material { young: 10f64.powi(young_exp), poisson },
            model,
            formulation: Default::default(),
            clamped: vec!["bottom".into()],
            supports: vec![],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle {
                shape: ObstacleShape::Parabola { center: 0.5, radius: 1.0 },
                approach: 10f64.powi(approach_exp),
                shift,
                rotation: None,
            },
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            multiplier_space: MultiplierSpace::P1,
            pairs: Vec::new(),
        };
        let Ok(problem) = Problem::new(mesh, spec) else {
            note("valid: problem refused");
            return Ok(());
        };
        let settings = SolverSettings::default();
        match problem.solve(&Friction::Coulomb { mu }, &settings, None) {
            Ok(sol) => {
                note(&format!("valid: {}", sol.report.status.name()));
                assert_honest(&sol, &settings);
            }
            Err(_) => note("valid: solve refused"),
        }
    }
}
