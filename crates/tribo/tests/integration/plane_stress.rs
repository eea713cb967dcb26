//! Plane stress (issue 41, item 2): two paths to one answer (plane stress with (E, ν) is plane strain with
//! `(E (1 + 2ν) / (1 + ν)², ν / (1 + ν))` in-plane, `tribo::fem::elasticity`'s derivation), σ_zz = 0, and Hertz
//! with the plane-stress contact modulus E* = E.

use tribo::*;
use tribo_testkit::{hertz_l2_error_with, hertz_mesh, hertz_scene, hertz_spec};

fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn worst_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / largest(a)
}

/// The Hertz problem on the graded mesh of h_min = 0.02, Coulomb with a shift (partial slip), under `model`
/// with `material`.
fn hertz(model: Model, material: Material) -> Problem {
    let spec = hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    Problem::new(hertz_mesh(0.02), ProblemSpec { material, ..spec }.model(model)).expect("valid")
}

/// The equivalent material's plane-strain law is the plane-stress law written out,
/// `E / (1 − ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1 − ν) / 2]]`, to a few ulps, for ν from −0.45 to 0.49.
#[test]
fn the_equivalent_material_has_the_plane_stress_law() {
    for nu in [-0.45, -0.2, 0.0, 0.25, 0.3, 0.45, 0.49] {
        let material = Material { young: 7.0, poisson: nu };
        let c = Model::PlaneStress.in_plane(material).elasticity_matrix();
        let f = 7.0 / (1.0 - nu * nu);
        let written = [[f, f * nu, 0.0], [f * nu, f, 0.0], [0.0, 0.0, f * (1.0 - nu) / 2.0]];
        for (i, row) in written.iter().enumerate() {
            for (j, w) in row.iter().enumerate() {
                assert!((c[(i, j)] - w).abs() <= 8.0 * f64::EPSILON * f, "ν = {nu}: C[{i}][{j}] = {} ≠ {w}", c[(i, j)]);
            }
        }
        assert_eq!(Model::PlaneStrain.in_plane(material), material);
    }
}

/// Solved as plane stress, and as plane strain with the equivalent material: the in-plane materials are the
/// same bits, so everything in-plane (displacements, multipliers, forces, the error estimates) is identical,
/// which it is only if every in-plane computation reads the equivalent; σ_zz is 0 in plane stress and
/// ν' (σ_xx + σ_yy) in the other, and von Mises follows each.
#[test]
fn plane_stress_is_plane_strain_with_the_equivalent_material() {
    let material = Material { young: 200.0, poisson: 0.3 };
    let equivalent = Model::PlaneStress.in_plane(material);
    assert!((equivalent.poisson - 0.3 / 1.3).abs() < 1e-15 && (equivalent.young - 200.0 * 1.6 / 1.69).abs() < 1e-12);
    let (settings, friction) = (SolverSettings::default(), Friction::Coulomb { mu: 0.3 });
    let stress = hertz(Model::PlaneStress, material).solve(&friction, &settings, None).expect("solves");
    let strain = hertz(Model::PlaneStrain, equivalent).solve(&friction, &settings, None).expect("solves");
    assert_eq!((stress.report.status, strain.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    assert!(stress.states.contains(&ContactState::Slip), "partial slip");
    assert_eq!(stress.displacement, strain.displacement);
    assert_eq!((&stress.lambda_n, &stress.lambda_t), (&strain.lambda_n, &strain.lambda_t));
    assert_eq!((stress.normal_force, stress.tangential_force), (strain.normal_force, strain.tangential_force));
    assert_eq!(format!("{:?}", stress.report.estimate), format!("{:?}", strain.report.estimate));
    assert!(stress.stress_zz.iter().all(|s| *s == 0.0));
    let sxx_syy: Vec<f64> = strain.stress.iter().map(|s| equivalent.poisson * (s[0] + s[1])).collect();
    assert!(worst_difference(&strain.stress_zz, &sxx_syy) < 1e-14);
    for (k, s) in stress.stress.iter().enumerate() {
        assert!(
            (stress.von_mises[k] - tribo::fem::elasticity::von_mises([s[0], s[1], s[2], 0.0])).abs()
                <= 1e-12 * largest(&stress.von_mises)
        );
    }
    assert!(worst_difference(&stress.von_mises, &strain.von_mises) > 1e-3, "σ_zz counts in von Mises");
}

/// Adapted to 0.5 %, λ_n is within 1 % of Hertz's pressure with the plane-stress contact modulus E* = E (issue
/// 41's bar), and therefore off the plane-strain one, E / (1 − ν²), by at least the distance between the two
/// Hertz pressures of the same force less that 1 % (the triangle inequality; the distance computed here).
#[test]
fn plane_stress_hertz_has_the_contact_modulus_e() {
    let s = hertz_scene();
    let spec =
        hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1).model(Model::PlaneStress);
    let coarse = Problem::new(rectangle(s.x, s.y, 8, 4, Diagonal::Right).expect("valid"), spec).expect("valid");
    let adapt = AdaptSettings { tol: 0.005, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    assert_eq!(run.solution.report.status, SolveStatus::Converged);
    let (e, nu) = (s.material.young, s.material.poisson);
    let stress = hertz_l2_error_with(&run.problem, &run.solution, e);
    let strain = hertz_l2_error_with(&run.problem, &run.solution, e / (1.0 - nu * nu));
    // ‖p_E − p_E'‖ / ‖p_E'‖ and ‖p_E‖ / ‖p_E'‖ for the computed force, on a fine uniform grid over the wider zone.
    let (p_stress, a) = tribo_testkit::hertz_pressure_with(run.solution.normal_force, e);
    let (p_strain, _) = tribo_testkit::hertz_pressure_with(run.solution.normal_force, e / (1.0 - nu * nu));
    let x = (0..=20_000).map(|k| a * (-1.0 + k as f64 / 10_000.0));
    let sums = x.fold([0.0; 3], |[d, s, t], x| {
        [d + (p_stress(x) - p_strain(x)).powi(2), s + p_stress(x).powi(2), t + p_strain(x).powi(2)]
    });
    let (apart, ratio) = ((sums[0] / sums[2]).sqrt(), (sums[1] / sums[2]).sqrt());
    assert!(stress < 0.01, "against E* = E: {stress}");
    // 1e-3 for the grid sums (their error at the square-root edges is below 1e-5 with 10⁴ cells per a).
    assert!(strain >= apart - stress * ratio - 1e-3, "against E / (1 − ν²): {strain}, the two apart by {apart}");
}

/// Plane stress takes ν in (−1/2, 1/2): its plane-strain equivalent has E' > 0 only there; a stiffness the
/// equivalent cannot hold is said in the user's E and ν.
#[test]
fn plane_stress_refuses_a_poisson_ratio_of_minus_one_half_or_below() {
    for nu in [-0.5, -0.7] {
        let e = Problem::new(
            hertz_mesh(0.04),
            hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1),
        )
        .and_then(|p| {
            let spec = ProblemSpec { material: Material { young: 1.0, poisson: nu }, ..p.spec.clone() };
            Problem::new(p.mesh.clone(), spec.model(Model::PlaneStress))
        });
        assert!(matches!(&e, Err(Error::BadMaterial { what }) if what.contains("plane stress")), "{nu}: {e:?}");
    }
    let tiny = ProblemSpec {
        material: Material { young: 1e-307, poisson: -0.49 },
        ..hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
    };
    let e = Problem::new(hertz_mesh(0.04), tiny.model(Model::PlaneStress));
    assert!(matches!(&e, Err(Error::BadMaterial { what }) if what.contains("plane-stress stiffness")), "{e:?}");
    let plain = ProblemSpec {
        material: Material { young: 1.0, poisson: -0.7 },
        ..hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
    };
    assert!(Problem::new(hertz_mesh(0.04), plain).is_ok(), "plane strain takes ν = −0.7");
}
