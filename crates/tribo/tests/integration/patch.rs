//! Patch tests: a constant-strain state in contact is reproduced to the QP's accuracy, for P0 and P1 multipliers on matching, coarser and finer non-matching T_H, with γ0 = 0 and
//! γ0 > 0, frictionless, Tresca and Coulomb (stick and slip), on a distorted mesh.
//!
//! Exact state: the unit square clamped on its top side, Γ_C its bottom side (n = (0, −1), t = (1, 0)),
//! `u = (1 − y) (a, b)`: ε_xx = 0, ε_yy = −b, γ_xy = −a, so σ is constant and λ_n = (λ + 2G) b,
//! λ_t = −G a. The sides carry the tractions σ·n of that state.

use tribo::*;

const E: f64 = 1000.0;
const NU: f64 = 0.25;

fn lame() -> (f64, f64) {
    (E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU)), E / (2.0 * (1.0 + NU)))
}

/// Builds the problem for the exact state (a, b), with the obstacle's approach and shift.
fn patch_problem(
    a: f64,
    b: f64,
    approach: f64,
    shift: f64,
    points: MultiplierPoints,
    space: MultiplierSpace,
) -> Problem {
    let (lam, g) = lame();
    let (sxx, sxy) = (-lam * b, -g * a);
    let tractions = vec![("left".to_string(), [-sxx, -sxy].into()), ("right".to_string(), [sxx, sxy].into())];
    let spec = ProblemSpec {
        material: Material { young: E, poisson: NU },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["top".into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions,
        contact: "bottom".into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach, shift, rotation: None },
        multiplier_points: points,
        multiplier_space: space,
        pairs: Vec::new(),
    };
    Problem::new(tribo_testkit::distorted_square(8), spec).expect("valid patch problem")
}

struct Case {
    name: &'static str,
    a: f64,
    b: f64,
    approach: f64,
    shift: f64,
    friction: Friction,
}

fn cases() -> Vec<Case> {
    let (lam, g) = lame();
    let delta = 1e-3;
    let ln = (lam + 2.0 * g) * delta;
    let s = 2e-4;
    let tau = 0.5 * g * s; // below G s: slip
    let mu_slip = 0.05; // μ λ_n < G s
    assert!(mu_slip * ln < g * s, "test set-up: the Coulomb slip case must slip");
    vec![
        Case { name: "frictionless", a: 0.0, b: delta, approach: delta, shift: 0.0, friction: Friction::Frictionless },
        Case {
            name: "Tresca stick",
            a: s,
            b: delta,
            approach: delta,
            shift: s,
            friction: Friction::Tresca(Threshold::Uniform(2.0 * g * s)),
        },
        Case {
            name: "Tresca slip",
            a: tau / g,
            b: delta,
            approach: delta,
            shift: s,
            friction: Friction::Tresca(Threshold::Uniform(tau)),
        },
        Case {
            name: "Coulomb stick",
            a: s,
            b: delta,
            approach: delta,
            shift: s,
            friction: Friction::Coulomb { mu: 1.0 },
        },
        Case {
            name: "Coulomb slip",
            a: mu_slip * ln / g,
            b: delta,
            approach: delta,
            shift: s,
            friction: Friction::Coulomb { mu: mu_slip },
        },
    ]
}

#[test]
fn constant_strain_states_are_reproduced() {
    let (lam, g) = lame();
    let mut worst: f64 = 0.0;
    for case in cases() {
        for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
            for (mesh_name, points) in [
                ("matching", MultiplierPoints::RatioToFe(1.0)),
                ("coarser", MultiplierPoints::Size(0.3)),
                (
                    "finer",
                    MultiplierPoints::Abscissae(vec![0.0, 0.05, 0.13, 0.2, 0.31, 0.37, 0.5, 0.52, 0.66, 0.8, 0.9, 1.0]),
                ),
            ] {
                for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
                    let problem = patch_problem(case.a, case.b, case.approach, case.shift, points.clone(), space);
                    let settings = SolverSettings { stabilization: stab, ..Default::default() };
                    let condensed = problem.condense(stab).expect("condenses");
                    let sol = condensed.solve(&case.friction, &settings, None).expect("solves");
                    // The QP is solved to a relative accuracy `qp.tol`; its solution inherits at most that
                    // times the condition number of H (on its range).
                    let tol = settings.qp.tol * tribo_testkit::condition_number(&condensed);
                    let what = format!("{} / {space:?} / {mesh_name} / {stab:?}", case.name);
                    // λ is unique only for γ0 > 0 or an inf-sup stable pair (T_H not finer than T_h); with a
                    // non-unique λ_n the Coulomb fixed point has no reason to settle.
                    let unique = stab != Stabilization::None || mesh_name != "finer";
                    let coulomb = matches!(case.friction, Friction::Coulomb { .. });
                    if !unique && coulomb && sol.report.status != SolveStatus::Converged {
                        continue;
                    }
                    assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
                    let scale = case.a.abs().max(case.b.abs());
                    let mut err_u: f64 = 0.0;
                    for (i, p) in problem.mesh.points().iter().enumerate() {
                        let exact = [(1.0 - p[1]) * case.a, (1.0 - p[1]) * case.b];
                        let u = sol.node_displacement(i);
                        err_u = err_u.max((u[0] - exact[0]).abs().max((u[1] - exact[1]).abs()) / scale);
                    }
                    assert!(err_u <= tol, "{what}: displacement error {err_u:e} > {tol:e}");
                    worst = worst.max(err_u / tol);
                    if unique {
                        let (ln, lt) = ((lam + 2.0 * g) * case.b, -g * case.a);
                        let lscale = (lam + 2.0 * g) * case.b.abs();
                        for j in 0..problem.n_multipliers() {
                            let e = (sol.lambda_n[j] - ln).abs().max((sol.lambda_t[j] - lt).abs()) / lscale;
                            assert!(e <= tol, "{what}: multiplier {j} error {e:e}");
                            worst = worst.max(e / tol);
                        }
                    }
                    // σ_n(u_h), σ_t(u_h) are the exact constant stresses.
                    let (sn, st) = (-(lam + 2.0 * g) * case.b, g * case.a);
                    for (k, (a, b)) in sol.sigma_n.iter().zip(&sol.sigma_t).enumerate() {
                        let e = ((a - sn).abs().max((b - st).abs())) / ((lam + 2.0 * g) * case.b.abs());
                        assert!(e <= tol, "{what}: contact stress on edge {k} off by {e:e}");
                    }
                    let expected_state = match (case.name.contains("slip"), case.name.contains("stick")) {
                        (true, _) => Some(ContactState::Slip),
                        (_, true) => Some(ContactState::Stick),
                        _ => None,
                    };
                    if let (Some(state), true) = (expected_state, unique) {
                        assert!(sol.states.iter().all(|s| *s == state), "{what}: states {:?}", sol.states);
                    }
                }
            }
        }
    }
    eprintln!("patch tests: worst error / (qp.tol · κ(H)) = {worst:.3}");
}

/// Without active contact: ν = 0, the square clamped on its left side and pulled on its right side,
/// Γ_C (bottom) traction free at a positive gap. Exact: u = (c x, 0), σ = (E c, 0, 0), λ = 0.
#[test]
fn constant_strain_without_contact_is_reproduced() {
    let c = 1e-3;
    for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
        for points in [MultiplierPoints::RatioToFe(1.0), MultiplierPoints::Size(0.3), MultiplierPoints::RatioToFe(0.25)]
        {
            for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
                let spec = ProblemSpec {
                    material: Material { young: E, poisson: 0.0 },
                    model: Model::PlaneStrain,
                    formulation: Default::default(),
                    clamped: vec!["left".into()],
                    supports: vec![],
                    body_force: [0.0, 0.0],
                    tractions: vec![("right".to_string(), [E * c, 0.0].into())],
                    contact: "bottom".into(),
                    obstacle: Obstacle { shape: ObstacleShape::Flat, approach: -0.01, shift: 0.0, rotation: None },
                    multiplier_points: points.clone(),
                    multiplier_space: space,
                    pairs: Vec::new(),
                };
                let problem = Problem::new(tribo_testkit::distorted_square(8), spec).expect("valid");
                let settings = SolverSettings { stabilization: stab, ..Default::default() };
                let condensed = problem.condense(stab).expect("condenses");
                let tol = settings.qp.tol * tribo_testkit::condition_number(&condensed);
                for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
                    let sol = condensed.solve(&friction, &settings, None).expect("solves");
                    let what = format!("{space:?} / {points:?} / {stab:?} / {friction:?}");
                    assert_eq!(sol.report.status, SolveStatus::Converged, "{what}: {:?}", sol.report);
                    for (i, p) in problem.mesh.points().iter().enumerate() {
                        let u = sol.node_displacement(i);
                        let e = ((u[0] - c * p[0]).abs().max(u[1].abs())) / c;
                        assert!(e <= tol, "{what}: node {i} off by {e:e}");
                    }
                    assert!(sol.lambda_n.iter().chain(&sol.lambda_t).all(|l| l.abs() <= tol * E * c), "{what}");
                    assert!(sol.states.iter().all(|s| *s == ContactState::Separation), "{what}: {:?}", sol.states);
                }
            }
        }
    }
}

/// The internal forces computed element by element from the stresses (how a solution gets its reactions)
/// equal `K u` with K assembled, for a displacement with no structure: two paths to one answer, to
/// round-off relative to `|K| |u|`, in plane strain and in axisymmetry (the hoop row in both).
#[test]
fn internal_forces_equal_the_assembled_stiffness_applied() {
    let mesh = tribo_testkit::distorted_square(6);
    let material = Material { young: E, poisson: NU };
    let n = 2 * mesh.n_nodes();
    let u: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5).collect();
    for model in [Model::PlaneStrain, Model::Axisymmetric] {
        let stresses = elasticity::element_stresses(model, &mesh, &material, &u);
        let forces = elasticity::internal_forces(model, &mesh, &stresses);
        let mut ku = vec![0.0; n];
        let mut scale = vec![0.0_f64; n];
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let k = elasticity::element_stiffness_of(model, &mesh, t, &material);
            let dofs = elasticity::element_dofs(tri);
            for (a, &da) in dofs.iter().enumerate() {
                for (b, &db) in dofs.iter().enumerate() {
                    ku[da] += k[(a, b)] * u[db];
                    scale[da] += (k[(a, b)] * u[db]).abs();
                }
            }
        }
        for i in 0..n {
            let err = (forces[i] - ku[i]).abs();
            assert!(
                err <= 64.0 * f64::EPSILON * scale[i],
                "{model:?} dof {i}: {} against {} (scale {})",
                forces[i],
                ku[i],
                scale[i]
            );
        }
    }
}

/// The a posteriori estimate vanishes where the discrete solution is exact: every residual of the
/// estimator (jumps, Neumann, `λ_H + σ_h n`, penetration, complementarity, cone, dissipation) is zero for
/// the constant-strain states, to what the QP's accuracy leaves. The squared terms are then of the order
/// `tol λ`; the complementarity and the dissipation enter unsquared (they are energies), `E* |∫ λ (g − u_n)|
/// ≤ E* λ |Γ_C| tol δ ≈ (tol) λ²` here (E* δ ≈ λ_n, |Γ_C| = 1), so each contributes at most `√tol λ` to η:
/// the bound is `3 √tol λ` (two such terms and the squared ones, which are smaller).
#[test]
fn the_estimate_vanishes_on_constant_strain_states() {
    for case in cases() {
        for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
            for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
                let problem =
                    patch_problem(case.a, case.b, case.approach, case.shift, MultiplierPoints::Size(0.3), space);
                let settings = SolverSettings { stabilization: stab, ..Default::default() };
                let condensed = problem.condense(stab).expect("condenses");
                let sol = condensed.solve(&case.friction, &settings, None).expect("solves");
                let tol = settings.qp.tol * tribo_testkit::condition_number(&condensed);
                let lam = sol.lambda_n.iter().chain(&sol.lambda_t).fold(0.0_f64, |m, v| m.max(v.abs()));
                let est = sol.report.estimate;
                let what = format!("{} / {space:?} / {stab:?}: {est:?}", case.name);
                assert!(est.total <= 3.0 * tol.sqrt() * lam, "{what}");
                assert!(est.bulk + est.gamma_c <= 3.0 * tol * lam, "{what}");
                assert_eq!(sol.estimator.len(), problem.mesh.n_triangles());
            }
        }
    }
}

/// The recovered nodal stress (area-weighted mean of the cell stresses around a node) reproduces a
/// constant stress everywhere and a linear one at the interior nodes of a uniform mesh (point-symmetric
/// patches), where the P1 cell stress is off by O(h); the solve's own recovered field is the constant
/// state of the patch test.
#[test]
fn the_recovered_stress_is_exact_for_linear_stress_fields_on_uniform_meshes() {
    use tribo::fem::elasticity::{element_stresses, recovered_stress};
    let material = Material { young: E, poisson: NU };
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 8, 8, Diagonal::Right).expect("valid");
    // u = (x², x y): a stress linear in x and y.
    let u: Vec<f64> = mesh.points().iter().flat_map(|p| [p[0] * p[0], p[0] * p[1]]).collect();
    let exact = |p: [f64; 2]| {
        let (lam, g) = lame();
        let (exx, eyy, gxy) = (2.0 * p[0], p[0], p[1]);
        [(lam + 2.0 * g) * exx + lam * eyy, lam * exx + (lam + 2.0 * g) * eyy, g * gxy]
    };
    let cells: Vec<[f64; 3]> =
        element_stresses(Model::PlaneStrain, &mesh, &material, &u).iter().map(|s| [s[0], s[1], s[2]]).collect();
    let nodal = recovered_stress(&mesh, &cells);
    let interior = |p: [f64; 2]| p.iter().all(|&c| c > 1e-9 && c < 1.0 - 1e-9);
    let scale = exact([1.0, 1.0]).iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let (mut worst_node, mut worst_cell) = (0.0_f64, 0.0_f64);
    for (v, p) in mesh.points().iter().enumerate().filter(|(_, p)| interior(**p)) {
        let e = exact(*p);
        worst_node = worst_node.max((0..3).map(|k| (nodal[v][k] - e[k]).abs()).fold(0.0, f64::max));
    }
    for (t, s) in cells.iter().enumerate() {
        // The cell stress against the exact one at the triangle's first vertex.
        let e = exact(mesh.vertices(t)[0]);
        worst_cell = worst_cell.max((0..3).map(|k| (s[k] - e[k]).abs()).fold(0.0, f64::max));
    }
    assert!(worst_node <= 1e-12 * scale, "recovered {worst_node} against {scale}");
    assert!(worst_cell > 1e-2 * scale, "the cell stress is off by O(h): {worst_cell}");
    // The patch test's constant state, as a solve reproduces it (to the QP's accuracy): the recovered
    // field is a mean of the cell stresses, so it stays within their spread, component by component, up to
    // the rounding of an area-weighted mean (a few units in the last place of the largest value).
    let problem = patch_problem(0.01, 0.02, 0.0, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    for k in 0..3 {
        let spread = sol.stress.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s[k]), b.max(s[k])));
        let out = sol.nodal_stress.iter().map(|s| (spread.0 - s[k]).max(s[k] - spread.1)).fold(f64::MIN, f64::max);
        let ulps = 4.0 * f64::EPSILON * spread.0.abs().max(spread.1.abs());
        assert!(out <= ulps, "component {k}: {out:e} outside {spread:?}");
    }
    assert!(sol
        .nodal_von_mises
        .iter()
        .zip(&sol.nodal_stress)
        .all(|(v, s)| (v - material.von_mises(*s)).abs() <= 1e-9 * v.abs().max(1.0)));
}
