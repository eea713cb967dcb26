//! The QP's KKT conditions are the discrete problem (3.2)/(3.1): checked by evaluating (3.1) *directly*
//! — boundary integrals by composite Gauss quadrature of λ_H, φ_i, σ(u_h) and σ(v_h) on every FE edge
//! split at the multiplier points, independent of the assembled Γ_C matrices and of the condensation —
//! at the solutions of frictionless, Tresca and Coulomb problems on the Hertz scene; plus the solver's
//! own KKT residuals and complementarity.

use nalgebra::{SVector, Vector3};
use tribo::elasticity::{element_dofs, element_stiffness, strain_displacement};
use tribo::stabilization::traction_components;
use tribo::*;

struct Direct {
    /// Residual of the equation of (3.1) per free dof, and the scale of its terms.
    residual: Vec<f64>,
    scale: Vec<f64>,
}

/// Gauss points (3-point rule, exact to degree 5) on every piece of each FE edge of Γ_C split at the
/// multiplier points inside it: (edge index, abscissa, weight).
fn quadrature(problem: &Problem) -> Vec<(usize, f64, f64)> {
    let x = [-(0.6_f64).sqrt(), 0.0, (0.6_f64).sqrt()];
    let w = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut out = Vec::new();
    for (k, pair) in problem.contact.node_xi.windows(2).enumerate() {
        let mut br = vec![pair[0], pair[1]];
        br.extend(problem.multipliers.xi.iter().filter(|&&m| m > pair[0] && m < pair[1]));
        br.sort_by(f64::total_cmp);
        for s in br.windows(2) {
            let (h, m) = (0.5 * (s[1] - s[0]), 0.5 * (s[0] + s[1]));
            for (xq, wq) in x.iter().zip(&w) {
                out.push((k, m + h * xq, wq * h));
            }
        }
    }
    out
}

fn direct_equation(problem: &Problem, sol: &Solution, gamma0: f64) -> Direct {
    let mesh = &problem.mesh;
    let mat = &problem.spec.material;
    let c = mat.elasticity_matrix();
    let n_free = problem.n_free;
    let mut residual = vec![0.0; n_free];
    let mut scale = vec![0.0; n_free];
    let mut add = |dof: usize, v: f64, r: &mut Vec<f64>| {
        if let Some((i, a)) = problem.dofs.unknown(dof) {
            r[i] += a * v;
            scale[i] += (a * v).abs();
        }
    };
    // a(u, v) − L(v).
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let dofs = element_dofs(tri);
        let ut = SVector::<f64, 6>::from_iterator(dofs.iter().map(|&d| sol.displacement[d]));
        let ku = element_stiffness(mesh, t, &c) * ut;
        for (l, &d) in dofs.iter().enumerate() {
            add(d, ku[l], &mut residual);
        }
    }
    for (d, f) in problem.f_full.iter().enumerate() {
        add(d, -f, &mut residual);
    }
    // b(λ, v) − ∫γ (λ_n + σ_n(u)) σ_n(v) − ∫γ (λ_t + σ_t(u)) σ_t(v).
    let (a_n, a_t): (Vector3<f64>, Vector3<f64>) = traction_components(problem.contact.normal, problem.contact.normal);
    let (n, t) = (problem.contact.normal, problem.contact.tangent);
    for (k, xi, w) in quadrature(problem) {
        let e = problem.contact.edges[k];
        let (xl, xr) = (problem.contact.node_xi[k], problem.contact.node_xi[k + 1]);
        let phi = [(e.left, (xr - xi) / (xr - xl)), (e.right, (xi - xl) / (xr - xl))];
        let ln = problem.multipliers.evaluate(&sol.lambda_n, xi);
        let lt = problem.multipliers.evaluate(&sol.lambda_t, xi);
        for &(node, f) in &phi {
            for comp in 0..2 {
                add(2 * node + comp, w * f * (ln * n[comp] + lt * t[comp]), &mut residual);
            }
        }
        let gamma = gamma0 * mesh.diameter(e.triangle);
        if gamma > 0.0 {
            let tri = mesh.triangles()[e.triangle];
            let s = sol.stress[e.triangle];
            let sig = Vector3::new(s[0], s[1], s[2]);
            let (sn, st) = (a_n.dot(&sig), a_t.dot(&sig));
            let cb = c * strain_displacement(mesh, e.triangle);
            for (l, &d) in element_dofs(&tri).iter().enumerate() {
                let sv = cb.column(l);
                let v = -w * gamma * ((ln + sn) * a_n.dot(&sv) + (lt + st) * a_t.dot(&sv));
                add(d, v, &mut residual);
            }
        }
    }
    Direct { residual, scale }
}

/// The inequality of (3.1) for a multiplier ν (dof values), evaluated directly: returns the value and the
/// sum of the absolute values of its integrands (its scale).
fn direct_inequality(problem: &Problem, sol: &Solution, gamma0: f64, nu_n: &[f64], nu_t: &[f64]) -> (f64, f64) {
    let mesh = &problem.mesh;
    let (a_n, a_t) = traction_components(problem.contact.normal, problem.contact.normal);
    let (n, t) = (problem.contact.normal, problem.contact.tangent);
    let (mut val, scale);
    val = 0.0;
    let (mut sizes, mut diffs) = (Vec::new(), Vec::new());
    for (k, xi, w) in quadrature(problem) {
        let e = problem.contact.edges[k];
        let (xl, xr) = (problem.contact.node_xi[k], problem.contact.node_xi[k + 1]);
        let (fl, fr) = ((xr - xi) / (xr - xl), (xi - xl) / (xr - xl));
        let u = [0, 1].map(|c| fl * sol.displacement[2 * e.left + c] + fr * sol.displacement[2 * e.right + c]);
        let wn = u[0] * n[0] + u[1] * n[1] - problem.spec.obstacle.gap(&problem.contact, xi).unwrap();
        let wt = u[0] * t[0] + u[1] * t[1] - problem.spec.obstacle.shift;
        let m = &problem.multipliers;
        let (ln, lt) = (m.evaluate(&sol.lambda_n, xi), m.evaluate(&sol.lambda_t, xi));
        let (dn, dt) = (m.evaluate(nu_n, xi) - ln, m.evaluate(nu_t, xi) - lt);
        let s = sol.stress[e.triangle];
        let sig = Vector3::new(s[0], s[1], s[2]);
        let gamma = gamma0 * mesh.diameter(e.triangle);
        let (rn, rt) = (gamma * (ln + a_n.dot(&sig)), gamma * (lt + a_t.dot(&sig)));
        val += w * (dn * (wn - rn) + dt * (wt - rt));
        // Scale: |ν − λ| times a bound on the size of the (stabilized) gap and slip that does not vanish
        // where they do (|u_n| + |g| + |γ (λ_n + σ_n)|, likewise tangentially).
        let size_n = (u[0] * n[0] + u[1] * n[1]).abs()
            + problem.spec.obstacle.gap(&problem.contact, xi).unwrap().abs()
            + rn.abs();
        let size_t = (u[0] * t[0] + u[1] * t[1]).abs() + problem.spec.obstacle.shift.abs() + rt.abs();
        sizes.push(size_n.max(size_t));
        diffs.push(w * (dn.abs() + dt.abs()));
    }
    let r = sizes.iter().fold(0.0_f64, |m, v| m.max(*v));
    scale = diffs.iter().sum::<f64>() * r;
    (val, scale)
}

fn check(friction: Friction, shift: f64, space: MultiplierSpace, points: MultiplierPoints, stab: Stabilization) {
    let problem = tribo_testkit::hertz_problem(0.02, 0.01, shift, points.clone(), space);
    check_problem(&problem, friction, stab, format!("{space:?} {points:?}"));
}

fn check_problem(problem: &Problem, friction: Friction, stab: Stabilization, what: String) {
    let problem = problem.clone();
    let settings = SolverSettings { stabilization: stab, ..Default::default() };
    let condensed = problem.condense(stab).expect("condenses");
    let sol = condensed.solve(&friction, &settings, None).expect("solves");
    let what = format!("{friction:?} {what} {stab:?}");
    assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
    let gamma0 = sol.report.gamma0;
    // The equation is met to round-off: the two evaluations differ only in rounding (a backward-stable
    // Cholesky solve, sums of a few dozen terms per dof); we allow 64 ε √n relative to the largest term.
    let d = direct_equation(&problem, &sol, gamma0);
    let rmax = d.residual.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
    let smax = d.scale.iter().fold(0.0_f64, |m, r| m.max(*r));
    let worst = rmax / smax;
    assert!(worst <= 64.0 * f64::EPSILON * (problem.n_free as f64).sqrt(), "{what}: equation residual {worst:e}");
    // The inequality holds for every ν in the cone, to the accuracy the QP reached times the
    // conditioning of H.
    let tol = tribo_testkit::reached_qp_tol(&settings, &sol) * tribo_testkit::condition_number(&condensed);
    let q = problem.n_multipliers();
    let bound = &sol.friction_threshold;
    let mut seed = 7u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let lmax = sol.lambda_n.iter().fold(0.0_f64, |m, v| m.max(*v));
    let mut trials: Vec<(Vec<f64>, Vec<f64>)> = vec![
        (vec![0.0; q], sol.lambda_t.clone()),
        (sol.lambda_n.iter().map(|l| 2.0 * l).collect(), sol.lambda_t.clone()),
        (sol.lambda_n.clone(), bound.clone()),
        (sol.lambda_n.clone(), bound.iter().map(|b| -b).collect()),
    ];
    for _ in 0..20 {
        let nn = (0..q).map(|_| rnd() * lmax).collect();
        let nt = bound.iter().map(|b| (2.0 * rnd() - 1.0) * b).collect();
        trials.push((nn, nt));
    }
    for (k, (nn, nt)) in trials.iter().enumerate() {
        let (v, s) = direct_inequality(&problem, &sol, gamma0, nn, nt);
        assert!(v <= tol * s, "{what}: inequality of (3.1) violated by trial {k}: {v:e} (scale {s:e})");
    }
    // Complementarity (ν_n = 0 and 2λ_n give both signs): ∫λ_n w_n − ∫γ λ_n (λ_n + σ_n) = 0.
    let (v0, s0) = direct_inequality(&problem, &sol, gamma0, &vec![0.0; q], &sol.lambda_t);
    assert!(v0.abs() <= tol * s0, "{what}: normal complementarity {v0:e} (scale {s0:e})");
    assert!(sol.kkt.max() <= tol, "{what}: solver KKT residuals {:?} above {tol:e}", sol.kkt);
    assert!(sol.lambda_n.iter().all(|l| *l >= -tol * lmax), "{what}: λ_n < 0");
}

#[test]
fn frictionless_solutions_satisfy_the_discrete_problem() {
    for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
        for points in
            [MultiplierPoints::RatioToFe(1.0), MultiplierPoints::Size(0.0173), MultiplierPoints::RatioToFe(2.0)]
        {
            for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
                check(Friction::Frictionless, 0.0, space, points.clone(), stab);
            }
        }
    }
}

#[test]
fn tresca_solutions_satisfy_the_discrete_problem() {
    for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
        check(
            Friction::Tresca(Threshold::Uniform(0.5)),
            0.004,
            space,
            MultiplierPoints::RatioToFe(1.0),
            Stabilization::Fraction(0.5),
        );
        check(
            Friction::Tresca(Threshold::Uniform(2.0)),
            0.004,
            space,
            MultiplierPoints::Size(0.0173),
            Stabilization::None,
        );
    }
}

#[test]
fn coulomb_solutions_satisfy_the_discrete_problem() {
    for space in [MultiplierSpace::P0, MultiplierSpace::P1] {
        check(
            Friction::Coulomb { mu: 0.3 },
            0.004,
            space,
            MultiplierPoints::RatioToFe(1.0),
            Stabilization::Fraction(0.5),
        );
        check(Friction::Coulomb { mu: 0.3 }, 0.004, space, MultiplierPoints::RatioToFe(2.0), Stabilization::None);
    }
}

/// A thin slab pressed onto a flat foundation by a prescribed displacement of its top, held on one side
/// by a roller, the whole rotated by 0.3 rad: the contact triangles touch prescribed and rotated dofs, so
/// the lifting enters E, G and the load. (3.1), evaluated directly with the full displacement, holds.
#[test]
fn a_slab_pressed_by_a_prescribed_displacement_satisfies_the_discrete_problem() {
    let angle = 0.3_f64;
    let (c, s) = (angle.cos(), angle.sin());
    let m = rectangle([0.0, 1.0], [0.0, 0.125], 8, 1, Diagonal::Right).unwrap();
    let pts = m.points().iter().map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]).collect();
    let mesh = Mesh::new(pts, m.triangles().to_vec(), m.edge_sets().clone()).unwrap();
    let push = 0.002;
    let spec = ProblemSpec {
        material: Material { young: 200.0, poisson: 0.3 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![],
        supports: vec![Support::roller("left"), Support::displacement("top", Some(push * s), Some(-push * c))],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach: 0.0, shift: 0.0005, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    let problem = Problem::new(mesh, spec).unwrap();
    // One QP each (the direct checks hold to the QP's accuracy; a Coulomb fixed point adds its own).
    for friction in [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(1.0))] {
        for stab in [Stabilization::None, Stabilization::Fraction(0.5)] {
            check_problem(&problem, friction.clone(), stab, "slab".into());
        }
    }
    // Not a trivial scene: the slab touches, and under Tresca part of it slips.
    let sol = problem.solve(&Friction::Tresca(Threshold::Uniform(1.0)), &SolverSettings::default(), None).unwrap();
    eprintln!("slab: F_n = {:.4}, states {:?}", sol.normal_force, sol.states);
    assert!(sol.normal_force > 0.0 && sol.states.contains(&ContactState::Slip));
}
