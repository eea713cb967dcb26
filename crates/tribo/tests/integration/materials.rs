//! Bodies of several materials ([`Problem::with_materials`]): two layers of one material are the homogeneous
//! body, a layered block compressed through the contact is reproduced exactly (each layer its own strain), the
//! admissible γ0 reads the materials of Γ_C's triangles alone, adaptive refinement keeps every triangle in its
//! layer, and bad regions are refused.

use tribo::*;

/// The layer of each triangle of `mesh`: 1 where its centroid lies above `y`, else 0.
fn layers(mesh: &Mesh, y: f64) -> Vec<usize> {
    (0..mesh.n_triangles()).map(|t| usize::from(mesh.vertices(t).iter().map(|p| p[1]).sum::<f64>() / 3.0 > y)).collect()
}

/// The unit square on the rigid flat (Γ_C its bottom side, n = (0, −1)), clamped on its top side, on rollers on
/// its sides, pushed up by the obstacle's approach `delta`.
fn compressed_square(delta: f64, material: Material, space: MultiplierSpace) -> (Mesh, ProblemSpec) {
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 6, 6, Diagonal::Alternating).expect("valid");
    let spec = ProblemSpec {
        material,
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["top".into()],
        supports: vec![Support::roller("left"), Support::roller("right")],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach: delta, shift: 0.0, rotation: None },
        multiplier_points: MultiplierPoints::Size(0.3),
        multiplier_space: space,
        pairs: Vec::new(),
    };
    (mesh, spec)
}

/// The P-wave (uniaxial strain) modulus λ + 2G = E (1 − ν) / ((1 + ν)(1 − 2ν)).
fn uniaxial(m: &Material) -> f64 {
    m.young * (1.0 - m.poisson) / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson))
}

#[test]
fn two_layers_of_one_material_are_the_homogeneous_body() {
    let mesh = tribo_testkit::hertz_mesh(0.02);
    let spec = tribo_testkit::hertz_spec(0.01, 0.002, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let material = spec.material;
    let regions = layers(&mesh, -0.2);
    assert!(regions.contains(&0) && regions.contains(&1), "test set-up: two layers");
    let homogeneous = Problem::new(mesh.clone(), spec.clone()).expect("valid");
    let layered =
        Problem::with_materials(mesh, spec, Materials { materials: vec![material, material], region: regions })
            .expect("valid");
    assert_eq!(layered.gamma0_bound, homogeneous.gamma0_bound);
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let a = homogeneous.solve(&friction, &settings, None).expect("solves");
    let b = layered.solve(&friction, &settings, None).expect("solves");
    assert_eq!(a.report.status, SolveStatus::Converged);
    // Round-off: the same sums in the same order.
    let close = |x: &[f64], y: &[f64]| {
        let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        x.iter().zip(y).all(|(p, q)| (p - q).abs() <= 1e-13 * scale)
    };
    assert!(close(&a.displacement, &b.displacement));
    assert!(close(&a.lambda_n, &b.lambda_n) && close(&a.lambda_t, &b.lambda_t));
    assert_eq!(a.states, b.states);
    let (ea, eb) = (a.report.estimate, b.report.estimate);
    for (x, y) in
        [(ea.total, eb.total), (ea.traction_relative, eb.traction_relative), (ea.energy_relative, eb.energy_relative)]
    {
        assert!((x - y).abs() <= 1e-13 * x.abs(), "estimate {x} against {y}");
    }
}

/// The square of two layers (the lower, on Γ_C, stiff; the upper soft), compressed by the obstacle between its
/// clamped top and the contact, on rollers: uniaxial strain, σ_yy = −p in both layers, each layer's strain
/// `−p / M_i` (M the uniaxial modulus), so `δ = p (t₁ / M₁ + t₂ / M₂)`; σ_xx = ν_i / (1 − ν_i) σ_yy per layer.
/// P1 holds the piecewise linear displacement exactly: reproduced to the QP's accuracy (as the patch tests),
/// for P0 and P1 multipliers, γ0 = 0 and γ0 > 0, frictionless and Coulomb (it sticks: λ_t = 0).
#[test]
fn a_layered_block_compressed_through_the_contact_is_exact() {
    let delta = 1e-3;
    let (stiff, soft) = (Material { young: 1000.0, poisson: 0.25 }, Material { young: 200.0, poisson: 0.35 });
    let p = delta / (0.5 / uniaxial(&stiff) + 0.5 / uniaxial(&soft));
    for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
        let (mesh, spec) = compressed_square(delta, stiff, space);
        // The contact layer is the second material, not the spec's: a fallback to either would be seen.
        let regions = layers(&mesh, 0.5).iter().map(|l| 1 - l).collect();
        let spec = ProblemSpec { material: soft, ..spec };
        let problem = Problem::with_materials(mesh, spec, Materials { materials: vec![soft, stiff], region: regions })
            .expect("valid");
        assert_eq!(problem.spec.material, stiff, "the contact side's material");
        for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
            let settings = SolverSettings { stabilization: stab, ..Default::default() };
            let condensed = problem.condense(stab).expect("condenses");
            let tol = settings.qp.tol * tribo_testkit::condition_number(&condensed);
            for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
                let what = format!("{space:?} / {stab:?} / {friction:?}");
                let sol = condensed.solve(&friction, &settings, None).expect("solves");
                assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
                for (i, pt) in problem.mesh.points().iter().enumerate() {
                    let y = pt[1];
                    let below = y.min(0.5) / uniaxial(&stiff) + (y - 0.5).max(0.0) / uniaxial(&soft);
                    let exact = delta - p * below;
                    let u = sol.node_displacement(i);
                    let e = (u[0].abs()).max((u[1] - exact).abs()) / delta;
                    assert!(e <= tol, "{what}: node {i} (y = {y}) off by {e:e} > {tol:e}");
                }
                for (t, s) in sol.stress.iter().enumerate() {
                    let m = problem.materials.materials[problem.materials.region[t]];
                    let exact = [-p * m.poisson / (1.0 - m.poisson), -p, 0.0];
                    let e = (0..3).map(|k| (s[k] - exact[k]).abs()).fold(0.0, f64::max) / p;
                    assert!(e <= tol, "{what}: stress of triangle {t} off by {e:e}");
                }
                for (j, (ln, lt)) in sol.lambda_n.iter().zip(&sol.lambda_t).enumerate() {
                    let e = (ln - p).abs().max(lt.abs()) / p;
                    assert!(e <= tol, "{what}: multiplier {j} off by {e:e}");
                }
            }
        }
    }
}

/// γ0's bound is set by Γ_C's triangles, each with its own material: the substrate under a contact layer does
/// not change it, and a Γ_C of two materials side by side takes the smaller of their bounds (the stiffer's).
#[test]
fn the_admissible_gamma0_reads_the_materials_on_the_contact() {
    let (mesh, spec) = compressed_square(1e-3, Material { young: 1.0, poisson: 0.3 }, MultiplierSpace::P1);
    let bound_of = |materials: Vec<Material>, region: Vec<usize>| {
        Problem::with_materials(mesh.clone(), spec.clone(), Materials { materials, region })
            .expect("valid")
            .gamma0_bound
            .value
    };
    let one = |m: Material| bound_of(vec![m], vec![0; mesh.n_triangles()]);
    let coat = Material { young: 50.0, poisson: 0.3 };
    for substrate in [Material { young: 1e-3, poisson: 0.1 }, Material { young: 1e4, poisson: 0.45 }] {
        // The lowest row of triangles (centroids below 1/6) is the coating.
        assert_eq!(bound_of(vec![coat, substrate], layers(&mesh, 1.0 / 6.0)), one(coat));
    }
    let (soft, stiff) = (Material { young: 2.0, poisson: 0.2 }, Material { young: 300.0, poisson: 0.4 });
    let halves: Vec<usize> = (0..mesh.n_triangles())
        .map(|t| usize::from(mesh.vertices(t).iter().map(|p| p[0]).sum::<f64>() > 1.5))
        .collect();
    let both = bound_of(vec![soft, stiff], halves);
    assert_eq!(both, one(soft).min(one(stiff)));
    assert_eq!(both, one(stiff), "the stiffer material sets the bound");
}

/// The adaptive loop bisects a layered Hertz block: every triangle of every level keeps its layer (the
/// interface is a line of the first mesh), and the last level is the problem of its mesh with the regions
/// given anew (two paths to one answer).
#[test]
fn adaptive_levels_keep_every_triangle_in_its_layer() {
    let mesh = tribo_testkit::hertz_mesh(0.05);
    let spec = tribo_testkit::hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    // The block is (−2, 2) × (−2, 0): a layer a quarter thick under Γ_C.
    let interface = -0.25;
    let ys: Vec<f64> = mesh.points().iter().map(|p| p[1]).collect();
    assert!(ys.iter().any(|y| (y - interface).abs() < 1e-12), "test set-up: the interface is a mesh line");
    let (coat, substrate) = (Material { young: 3.0 * spec.material.young, poisson: 0.25 }, spec.material);
    let materials = Materials { materials: vec![substrate, coat], region: layers(&mesh, interface) };
    let problem = Problem::with_materials(mesh, spec.clone(), materials).expect("valid");
    let adapt = AdaptSettings { tol: 0.05, max_levels: 6, ..Default::default() };
    let out = problem.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("runs");
    assert!(out.levels.len() >= 3, "{} levels", out.levels.len());
    for (k, level) in out.levels.iter().enumerate() {
        assert_eq!(level.regions, layers(&level.mesh, interface), "level {k}");
    }
    let last = &out.problem;
    let again = Problem::with_materials(
        last.mesh.clone(),
        ProblemSpec { multiplier_points: MultiplierPoints::Abscissae(last.multipliers.xi.clone()), ..spec },
        Materials { materials: vec![substrate, coat], region: layers(&last.mesh, interface) },
    )
    .expect("valid");
    let sol = again.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    let scale = sol.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = sol.lambda_n.iter().zip(&out.solution.lambda_n).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    // Both converged to the QP's tolerance from different starts.
    assert!(diff <= 1e-6 * scale, "λ_n differs by {diff:e} of {scale:e}");
}

#[test]
fn bad_regions_are_refused() {
    let (mesh, spec) = compressed_square(1e-3, Material { young: 1.0, poisson: 0.3 }, MultiplierSpace::P1);
    let n = mesh.n_triangles();
    let m = Material { young: 1.0, poisson: 0.3 };
    for (materials, region, says) in [
        (vec![], vec![0; n], "at least one material"),
        (vec![m], vec![0; n - 1], "regions given for"),
        (vec![m, m], [vec![0; n - 1], vec![2]].concat(), "beyond the 2 materials"),
        (vec![m, Material { young: -1.0, poisson: 0.3 }], vec![1; n], "Young's modulus"),
    ] {
        let e = Problem::with_materials(mesh.clone(), spec.clone(), Materials { materials, region }).unwrap_err();
        assert!(matches!(e, Error::BadMaterial { .. }), "{e:?}");
        assert!(e.to_string().contains(says), "{e}");
    }
}

/// Two bodies in plane stress are two bodies in plane strain with each body's equivalent material
/// ([`Model::in_plane`]): the same answer, bit for bit, as one body (`plane_stress.rs`).
#[test]
fn two_bodies_in_plane_stress_are_plane_strain_with_the_equivalent_materials() {
    let (steel, aluminium) = (Material { young: 200.0, poisson: 0.3 }, Material { young: 70.0, poisson: 0.33 });
    let (bodies, mut pair) = tribo_testkit::two_body_hertz_parts(0.02, steel, aluminium, 0.01);
    pair.model = Model::PlaneStress;
    let stress = Problem::two_bodies(bodies.clone(), pair.clone(), [0.0, 0.0]).expect("valid");
    let equivalent = bodies.map(|mut b| {
        b.materials.materials = b.materials.materials.iter().map(|m| Model::PlaneStress.in_plane(*m)).collect();
        b
    });
    pair.model = Model::PlaneStrain;
    let strain = Problem::two_bodies(equivalent, pair, [0.0, 0.0]).expect("valid");
    assert_eq!(stress.spec.model, Model::PlaneStress);
    let friction = Friction::Coulomb { mu: 0.3 };
    let a = stress.solve(&friction, &SolverSettings::default(), None).expect("solves");
    let b = strain.solve(&friction, &SolverSettings::default(), None).expect("solves");
    assert_eq!(a.report.status, SolveStatus::Converged);
    assert_eq!(a.displacement, b.displacement);
    assert_eq!((&a.lambda_n, &a.lambda_t), (&b.lambda_n, &b.lambda_t));
    assert!(a.stress_zz.iter().all(|s| *s == 0.0) && b.stress_zz.iter().any(|s| *s != 0.0));
}

/// Two-body Hertz in plane stress converges to the pressure of the plane-stress combined modulus
/// 1/E* = 1/E₁ + 1/E₂, at the rate of the plane-strain test (`two_bodies.rs`: h_min divided by 4, the error at
/// least halves), and ends nearer it than the plane-strain modulus's.
#[test]
fn two_body_hertz_in_plane_stress_converges_to_the_combined_modulus_e() {
    let (steel, aluminium) = (Material { young: 200.0, poisson: 0.3 }, Material { young: 70.0, poisson: 0.33 });
    let e_star = 1.0 / (1.0 / steel.young + 1.0 / aluminium.young);
    let mut errors = Vec::new();
    let mut last = None;
    for h_min in [0.04, 0.01, 0.0025] {
        let (bodies, mut pair) = tribo_testkit::two_body_hertz_parts(h_min, steel, aluminium, 0.01);
        pair.model = Model::PlaneStress;
        let problem = Problem::two_bodies(bodies, pair, [0.0, 0.0]).expect("valid");
        let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
        assert_eq!(sol.report.status, SolveStatus::Converged);
        errors.push(tribo_testkit::hertz_l2_error_with(&problem, &sol, e_star));
        last = Some((problem, sol));
    }
    eprintln!("two-body Hertz in plane stress: L2 errors {errors:?}");
    assert!(errors[1] < 0.5 * errors[0] && errors[2] < 0.5 * errors[1], "{errors:?}");
    let (problem, sol) = last.expect("three meshes");
    let strain = tribo_testkit::combined_modulus(&steel, &aluminium);
    assert!(tribo_testkit::hertz_l2_error_with(&problem, &sol, strain) > errors[2]);
}

/// A body of two bodies may be coated: its two layers of one material are the homogeneous body to round-off,
/// and its regions are checked (naming the body).
#[test]
fn a_body_of_a_pair_may_have_several_materials() {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let (bodies, pair) = tribo_testkit::two_body_hertz_parts(0.02, steel, steel, 0.01);
    let plain = Problem::two_bodies(bodies.clone(), pair.clone(), [0.0, 0.0]).expect("valid");
    let mut coated = bodies.clone();
    coated[0].materials = Materials { materials: vec![steel, steel], region: layers(&coated[0].mesh, -0.25) };
    assert!(coated[0].materials.region.contains(&1), "test set-up: a layer");
    let layered = Problem::two_bodies(coated.clone(), pair.clone(), [0.0, 0.0]).expect("valid");
    assert_eq!(layered.materials.materials.len(), 3);
    let a = plain.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    let b = layered.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    let scale = a.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(a.lambda_n.iter().zip(&b.lambda_n).all(|(x, y)| (x - y).abs() <= 1e-13 * scale));
    coated[1].materials.region.pop();
    let e = Problem::two_bodies(coated, pair, [0.0, 0.0]).unwrap_err();
    assert!(matches!(&e, Error::BadMaterial { what } if what.contains("body 'upper'")), "{e}");
}

/// A Γ_C of two materials side by side (its left half stiff, its right half soft, γ0 > 0): the stabilization's
/// contact stresses are each edge's own triangle's, σ_n(u_h) of the solution's element stresses to round-off,
/// and the relative energy estimate weighs each triangle's η_K² by its own E*: `(Σ η_K² / E*_K)^½ / ‖u‖_A`.
#[test]
fn the_contact_stresses_and_the_estimate_read_each_triangles_material() {
    let mesh = tribo_testkit::hertz_mesh(0.02);
    let spec = tribo_testkit::hertz_spec(0.01, 0.002, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let (soft, stiff) = (Material { young: 50.0, poisson: 0.35 }, Material { young: 600.0, poisson: 0.2 });
    let halves: Vec<usize> = (0..mesh.n_triangles())
        .map(|t| usize::from(mesh.vertices(t).iter().map(|p| p[0]).sum::<f64>() < 0.0))
        .collect();
    let problem =
        Problem::with_materials(mesh, spec, Materials { materials: vec![soft, stiff], region: halves }).expect("valid");
    let regions_on_contact: Vec<usize> =
        problem.contact.edges.iter().map(|e| problem.materials.region[e.triangle]).collect();
    assert!(regions_on_contact.contains(&0) && regions_on_contact.contains(&1), "test set-up: Γ_C of both");
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).expect("solves");
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.report.gamma0 > 0.0);
    let scale = sol.sigma_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (k, (ops, dofs)) in problem.contact_stress.ops.iter().zip(&problem.contact_stress.dofs).enumerate() {
        let sigma_n: f64 = dofs.iter().zip(ops[0].iter()).map(|(&d, s)| s * sol.displacement[d]).sum();
        assert!((sigma_n - sol.sigma_n[k]).abs() <= 1e-12 * scale, "edge {k}: {sigma_n} against {}", sol.sigma_n[k]);
    }
    let star = |m: &Material| m.young / (1.0 - m.poisson * m.poisson);
    let weighted: f64 = (0..problem.mesh.n_triangles())
        .map(|t| sol.estimator[t].powi(2) / star(&problem.in_plane.materials[problem.in_plane.region[t]]))
        .sum();
    let energy =
        tribo::elasticity::energy_norm(problem.spec.model, &problem.mesh, &problem.in_plane, &sol.displacement);
    let expected = weighted.sqrt() / energy;
    let got = sol.report.estimate.energy_relative;
    assert!((got - expected).abs() <= 1e-12 * expected, "energy_relative {got} against {expected}");
    // Not the secondary material's E* for all: the two differ here.
    let single = (0..problem.mesh.n_triangles()).map(|t| sol.estimator[t].powi(2)).sum::<f64>().sqrt()
        / (star(&problem.spec.material).sqrt() * energy);
    assert!((got - single).abs() > 1e-3 * got, "{got} against one E*: {single}");
}
