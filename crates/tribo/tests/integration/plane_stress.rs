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

/// The same displacements, multipliers and forces to round-off; σ_zz is 0 in plane stress and ν' (σ_xx + σ_yy)
/// in its plane-strain equivalent, and von Mises follows each.
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
    for (a, b) in [
        (&stress.displacement, &strain.displacement),
        (&stress.lambda_n, &strain.lambda_n),
        (&stress.lambda_t, &strain.lambda_t),
    ] {
        assert!(worst_difference(a, b) < 1e-10, "{}", worst_difference(a, b));
    }
    assert!((stress.normal_force - strain.normal_force).abs() < 1e-10 * strain.normal_force);
    assert!(stress.stress_zz.iter().all(|s| *s == 0.0));
    let sxx_syy: Vec<f64> = strain.stress.iter().map(|s| equivalent.poisson * (s[0] + s[1])).collect();
    assert!(worst_difference(&strain.stress_zz, &sxx_syy) < 1e-14);
    for (k, s) in stress.stress.iter().enumerate() {
        assert!(
            (stress.von_mises[k] - Model::PlaneStress.von_mises(&material, *s)).abs()
                <= 1e-12 * largest(&stress.von_mises)
        );
    }
    assert!(worst_difference(&stress.von_mises, &strain.von_mises) > 1e-3, "σ_zz counts in von Mises");
}

/// Adapted to 0.5 %, λ_n is within 1 % of Hertz's pressure with the plane-stress contact modulus E* = E, and
/// several percent off the plane-strain one, E / (1 − ν²).
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
    assert!(stress < 0.01 && strain > 0.03, "against E* = E: {stress}, against E / (1 − ν²): {strain}");
}

/// Plane stress takes ν in (−1/2, 1/2): its plane-strain equivalent has E' > 0 only there.
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
    let plain = ProblemSpec {
        material: Material { young: 1.0, poisson: -0.7 },
        ..hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
    };
    assert!(Problem::new(hertz_mesh(0.04), plain).is_ok(), "plane strain takes ν = −0.7");
}
