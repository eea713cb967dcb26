//! Every solver path to one answer, on random problems: each combination of the QP method (auto,
//! clarabel, active set), the condensation (auto, columns, Schur, saddle), the working set (on, off) and
//! clarabel's KKT solver (faer, qdldl), 48 paths, against the reference (clarabel on H by columns over all
//! of Γ_C), on random small blocks pressed by a flat, circular or parabolic obstacle, frictionless,
//! Tresca or Coulomb, P0 or P1 multipliers coarser or finer than the FE edges, γ0 = 0 or a fraction of
//! its bound.
//!
//! # What is unique, and so what is compared
//! Each P(g) is the QP `min ½ νᵀHν + cᵀν` over a box, with `H = E A⁻¹ Eᵀ + Dγ`, A = K − G positive
//! definite and Dγ = ∫γ ψψ positive semidefinite. Two minimizers ν₁, ν₂ of a convex QP have
//! `H(ν₁ − ν₂) = 0`, so with d = ν₁ − ν₂: `‖A^{-1/2} Eᵀ d‖² + dᵀ Dγ d = dᵀ H d = 0`, hence `Eᵀ d = 0` and
//! `Dγ d = 0`.
//! * The displacement u = A⁻¹(f − Eᵀν) (+ the lifting) depends on ν through Eᵀν only: **u is unique**.
//! * With γ0 > 0, γ > 0 on all of Γ_C and Dγ is definite: d = 0, **λ is unique**.
//! * With γ0 = 0, E = B (the mortar coupling ∫ν·v): `Bᵀd = 0` says ∫d·v = 0 for every free v of V_h. The
//!   top corners are free here (only the bottom is clamped), so v = e (a unit vector) on the nodes of
//!   Γ_C is one of them, and the resultant ∫d·e vanishes: **the forces are unique**; λ itself is unique
//!   only where Bᵀ is injective (H nonsingular; not so for T_H finer than the FE edges: the checkerboard
//!   modes), and is compared only there.
//! * Coulomb is the fixed point of g ↦ μ λ_n(g), so its answer is unique only where λ_n is: with γ0 = 0
//!   and a singular H, two paths may pick different λ_n from the same QP, hence different thresholds and a
//!   different u, both exact solutions of (3.1) (found by this test on a 2 × 2 mesh with T_H twice as fine
//!   as the FE edges: u 9 % apart, both converged; this is the campaign's "λ_t 0.5 % off" on a Coulomb
//!   problem). Coulomb answers are compared only where H is nonsingular, and there for μ ≤ 0.3, where the
//!   fixed point contracts (its contraction factor is measured from each run's changes).
//!
//! # How close, and why
//! Each P(g) is solved to a tolerance t (`qp_tol`, or [`tribo::qp::FALLBACK_TOL`] where the report says a
//! QP only met that) on the QP non-dimensionalised as in `qp::scaling` (unknowns ν/w, objective divided
//! by φ = max w_i² H_ii): clarabel stops at a duality gap below `t (1 + |f̃|)` and each scaled unknown
//! within t of its box, and the active-set method certifies its answers in the same units. So an
//! answer's objective `f(ν) = ½ νᵀHν + cᵀν` exceeds the minimum f* by at most
//! `ε = t (φ + |f| + Σ w_i |(Hν + c)_i|)` (the gap, and the objective moved by the box's slack), and, f
//! being convex with Hessian H, `‖ν − ν*‖²_H ≤ 2 (f(ν) − f*) ≤ 2ε` (to first order in t). What each path
//! is held to:
//! * **optimality** (frictionless, Tresca): `f(ν) ≤ f_min + ε + ε_min`, f_min the smallest objective any
//!   path reached: a path that solved another QP, or stopped early, fails here;
//! * **λ** in the norm of H: `‖ν − ν_ref‖_H ≤ √(2ε) + √(2ε_ref)`, whether or not λ is unique (only the
//!   H-seminorm of a difference of minimizers is bounded; it is 0 on the null space); and, with no tolerance
//!   of the QP's in it, `‖ν − ν_ref‖_H ≤ √S + √S_ref`, S the sum of an answer's own unscaled KKT residuals
//!   (`tribo_testkit::energy`; over 1500 random cases the distance was at most 0.11 of that bound);
//! * **u**: `‖u − u_ref‖_A = ‖ν − ν_ref‖_{H − Dγ} ≤ ‖ν − ν_ref‖_H` (u = A⁻¹(f − Eᵀν)), so the bound on λ
//!   bounds u in energy; each path's reported u is checked to be A⁻¹(f − Eᵀν) of its own λ (to round-off),
//!   which the bound then covers;
//! * **forces**: N = wᵀν_n (w_j = ∫ψ_j) and T likewise, and w lies in the range of H (proved above for
//!   γ0 = 0; H is definite otherwise), so `|ΔN| + |ΔT| ≤ (‖w_n‖_{H⁺} + ‖w_t‖_{H⁺}) ‖Δν‖_H`;
//! * **Coulomb** (H nonsingular, the fixed point contracting with factor L < 1 measured from each run's
//!   last changes): each answer's distance to the fixed point is at most its own residual, the QP error
//!   `√(2ε/λ_min(H))` plus the last change δ‖λ_n‖, divided by 1 − L; two answers differ by at most the
//!   sum of the two, in the Euclidean norm of λ.
//!
//! Round-off adds `64 ε_mach √n` relative to the size of what is compared.
//!
//! The semismooth Newton method (`coulomb = newton`, on the default path) is held to the Coulomb bound
//! above where it converges, its own residual measured as the fixed point's is: by one more evaluation of
//! Φ_H, the Tresca problem with the bounds μ λ_n of its answer. Where it does not converge it is only counted
//! (the printout says so per case): study 20 maps where it fails.
//!
//! A path may end `qp_failed` only when the active-set method is forced (it cannot certify a QP whose
//! free block is singular: λ not unique), and a Coulomb fixed point `stagnated` or `max_iterations` only
//! where λ_n is not unique; every other path converges.

use proptest::prelude::*;
use tribo::choice::Choice;
use tribo::*;

fn sup(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn sup_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// A random problem of the campaign's kind: a small block (−2, 2) × (−1, 0) clamped at the bottom, Γ_C
/// its top, an obstacle pushed in, and the friction law and γ0 fraction to solve it with.
#[derive(Debug, Clone)]
struct Case {
    nx: usize,
    ny: usize,
    diagonal: usize,
    young: f64,
    poisson: f64,
    shape: usize,
    radius: f64,
    center: f64,
    approach: f64,
    shift: f64,
    p0: bool,
    ratio: f64,
    theta: f64,
    friction: usize,
    amount: f64,
}

fn any_case() -> impl Strategy<Value = Case> {
    (
        (2usize..9, 1usize..5, 0usize..3, 1.0f64..1e3, -0.5f64..0.49),
        (0usize..3, 0.5f64..5.0, -1.0f64..1.0, 1e-3f64..0.05, -0.01f64..0.01),
        (any::<bool>(), prop::sample::select(vec![0.5, 1.0, 2.0]), prop::sample::select(vec![0.0, 0.1, 0.5, 0.9])),
        (0usize..3, 0.0f64..1.0),
    )
        .prop_map(
            |(
                (nx, ny, diagonal, young, poisson),
                (shape, radius, center, approach, shift),
                (p0, ratio, theta),
                (friction, amount),
            )| {
                Case {
                    nx,
                    ny,
                    diagonal,
                    young,
                    poisson,
                    shape,
                    radius,
                    center,
                    approach,
                    shift,
                    p0,
                    ratio,
                    theta,
                    friction,
                    amount,
                }
            },
        )
}

impl Case {
    fn problem(&self) -> Problem {
        let diagonal = [Diagonal::Right, Diagonal::Left, Diagonal::Alternating][self.diagonal];
        let mesh = rectangle([-2.0, 2.0], [-1.0, 0.0], self.nx, self.ny, diagonal).expect("valid rectangle");
        let shape = match self.shape {
            0 => ObstacleShape::Flat,
            1 => ObstacleShape::Circle { center: self.center, radius: self.radius },
            _ => ObstacleShape::Parabola { center: self.center, radius: self.radius },
        };
        let spec = ProblemSpec {
            material: Material { young: self.young, poisson: self.poisson },
            model: Model::PlaneStrain,
            formulation: Default::default(),
            clamped: vec!["bottom".into()],
            supports: vec![],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle { shape, approach: self.approach, shift: self.shift, rotation: None },
            multiplier_points: MultiplierPoints::RatioToFe(self.ratio),
            multiplier_space: if self.p0 { MultiplierSpace::P0 } else { MultiplierSpace::P1 },
            pairs: Vec::new(),
        };
        Problem::new(mesh, spec).expect("a valid problem")
    }

    fn friction(&self) -> Friction {
        match self.friction {
            0 => Friction::Frictionless,
            // Thresholds up to the contact pressures' scale (E × approach over the block's depth).
            1 => Friction::Tresca(Threshold::Uniform(self.amount * self.young * self.approach)),
            _ => Friction::Coulomb { mu: 0.3 * self.amount },
        }
    }

    fn stabilization(&self) -> Stabilization {
        if self.theta == 0.0 {
            Stabilization::None
        } else {
            Stabilization::Fraction(self.theta)
        }
    }
}

/// Every path: QP method × condensation × working set × clarabel's KKT solver.
fn paths() -> Vec<QpSettingsAndCondensation> {
    let mut out = Vec::new();
    for method in [QpMethod::Auto, QpMethod::Clarabel, QpMethod::ActiveSet] {
        for condensation in [Condensation::Auto, Condensation::Columns, Condensation::Schur, Condensation::Saddle] {
            for working_set in [true, false] {
                for kkt_solver in [KktSolver::Faer, KktSolver::Qdldl] {
                    out.push((QpSettings { method, working_set, kkt_solver, ..Default::default() }, condensation));
                }
            }
        }
    }
    out
}

type QpSettingsAndCondensation = (QpSettings, Condensation);

/// The scaling of a QP as `qp::scaling` documents it, recomputed from that formula: the weights w_i of
/// the unknowns (the normal scale s = max|c_n| / max H_nn; min(g_j, s_t) on a tangential one) and φ =
/// max w_i² H_ii, the objective's unit.
fn scaling(h: &[f64], c: &[f64], bounds: Option<&[f64]>) -> (Vec<f64>, f64) {
    let k = c.len();
    let q = k / 2;
    let diag: Vec<f64> = (0..k).map(|i| h[i * k + i]).collect();
    let ratio = |r: std::ops::Range<usize>| {
        let h_s = r.clone().map(|i| diag[i]).fold(0.0, f64::max);
        let c_s = c[r].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        (c_s > 0.0 && h_s > 0.0).then(|| c_s / h_s)
    };
    let Some(s) = ratio(0..q).or_else(|| ratio(0..k)) else { return (vec![0.0; k], 0.0) };
    let h_st = (q..k).map(|i| diag[i]).fold(0.0, f64::max);
    let c_st = c[q..].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let s_t = if h_st > 0.0 { s.max(c_st / h_st) } else { s };
    let w: Vec<f64> = (0..k).map(|i| if i < q { s } else { bounds.map_or(0.0, |b| b[i - q].min(s_t)) }).collect();
    let phi = (0..k).map(|i| (w[i] * diag[i].max(0.0).sqrt()).powi(2)).fold(0.0, f64::max);
    (w, phi)
}

/// One path's answer as the test reads it.
struct Answer {
    nu: Vec<f64>,
    objective: f64,
    /// ε: how far above the minimum its tolerance lets the objective be.
    slack: f64,
}

fn quad(h: &[f64], x: &[f64]) -> f64 {
    let k = x.len();
    (0..k).map(|i| x[i] * (0..k).map(|j| h[i * k + j] * x[j]).sum::<f64>()).sum()
}

proptest! {
    #![proptest_config(crate::reproducible(96))]

    #[test]
    fn every_path_gives_the_unique_answer(case in any_case()) {
        let problem = case.problem();
        let friction = case.friction();
        let stabilization = case.stabilization();
        let settings = |(qp, condensation): QpSettingsAndCondensation| SolverSettings {
            stabilization, qp, condensation, ..Default::default()
        };
        let reference_path = (
            QpSettings { method: QpMethod::Clarabel, working_set: false, ..Default::default() },
            Condensation::Columns,
        );
        let reference = problem.solve(&friction, &settings(reference_path), None).expect("the reference solves");
        prop_assume!(reference.report.status == SolveStatus::Converged);
        let condensed = problem.condense(stabilization).expect("condenses");
        let factor = condensed.factor();
        let load = LoadCase::of_problem(&problem, factor);
        let k = 2 * condensed.q();
        let h = factor.dense_h();
        let eigen = nalgebra::DMatrix::from_column_slice(k, k, &h).symmetric_eigen();
        let max = eigen.eigenvalues.iter().fold(0.0_f64, |a, v| a.max(*v));
        let zero = k as f64 * f64::EPSILON * max;
        let lambda_unique = eigen.eigenvalues.iter().all(|v| *v > zero);
        let min = eigen.eigenvalues.iter().fold(f64::INFINITY, |a, v| a.min(*v));
        prop_assert!(case.theta == 0.0 || lambda_unique, "γ0 > 0 but H is singular: {case:?}");
        // ‖w‖_{H⁺} for the force weights of the normal and tangential halves.
        let dual_norm = |half: usize| {
            let q = condensed.q();
            let w: Vec<f64> = (0..k).map(|i| if i / q == half { problem.mortar.psi_integrals[i % q] } else { 0.0 }).collect();
            (0..k).filter(|&i| eigen.eigenvalues[i] > zero).map(|i| {
                let v = eigen.eigenvectors.column(i);
                let p: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
                p * p / eigen.eigenvalues[i]
            }).sum::<f64>().sqrt()
        };
        let force_factor = dual_norm(0) + dual_norm(1);
        let coulomb = matches!(friction, Friction::Coulomb { .. });
        // Coulomb with a singular H: no unique answer to compare (see above), only honest statuses.
        let unique = lambda_unique || !coulomb;
        let floor = 64.0 * f64::EPSILON * (problem.n_free as f64).sqrt();
        let answer = |sol: &Solution, path: &QpSettingsAndCondensation| -> Answer {
            let nu = [sol.lambda_n.as_slice(), sol.lambda_t.as_slice()].concat();
            let nu = if nu.len() == k { nu } else { [nu, vec![0.0; k / 2]].concat() };
            let bounds: Option<Vec<f64>> = match &friction {
                Friction::Frictionless => None,
                Friction::Tresca(Threshold::Uniform(t)) => Some(vec![*t; k / 2]),
                Friction::Tresca(Threshold::PerDof(t)) => Some(t.clone()),
                Friction::Coulomb { mu } => Some(sol.lambda_n.iter().map(|l| mu * l.max(0.0)).collect()),
            };
            let c = if bounds.is_some() { load.c.clone() } else { [&load.c[..k / 2], &vec![0.0; k / 2][..]].concat() };
            let objective = 0.5 * quad(&h, &nu) + c.iter().zip(&nu).map(|(a, b)| a * b).sum::<f64>();
            let tol = tribo_testkit::reached_qp_tol(&settings(*path), sol);
            // The gap part, and the feasibility part: clarabel stops when the violation of A x̃ + s̃ = b̃
            // (x̃ = ν / w the scaled unknowns, b̃ their boxes, s̃ ≥ 0 the slacks) is at most
            // tol · max(1, ‖b̃‖∞ + ‖x̃‖∞ + ‖s̃‖∞) (its `res_primal`), and ‖s̃‖∞ ≤ ‖b̃‖∞ + ‖x̃‖∞; so each scaled
            // unknown may lie up to tol · max(1, 2 (‖b̃‖∞ + ‖x̃‖∞)) outside its box, which moves the objective
            // by at most that times Σ w_i |(Hν + c)_i|.
            let (w, phi) = scaling(&h, &c, bounds.as_deref());
            let moved: f64 = (0..k).map(|i| w[i] * ((0..k).map(|j| h[i * k + j] * nu[j]).sum::<f64>() + c[i]).abs()).sum();
            let x_max = (0..k).filter(|&i| w[i] > 0.0).map(|i| (nu[i] / w[i]).abs()).fold(0.0, f64::max);
            let b_max = bounds.as_deref().map_or(0.0, |b| (0..k / 2).filter(|&j| w[k / 2 + j] > 0.0)
                .map(|j| b[j] / w[k / 2 + j]).fold(0.0, f64::max));
            let feasibility = (2.0 * (b_max + x_max)).max(1.0);
            let slack = tol * (phi + objective.abs() + feasibility * moved);
            Answer { nu, objective, slack }
        };
        let reference_answer = answer(&reference, &reference_path);
        let mut answers = Vec::new();
        let mut refused = 0;
        for path in paths() {
            let sol = problem.solve(&friction, &settings(path), None).expect("solves");
            let what = format!("{path:?} on {case:?}");
            if path.0.method == QpMethod::ActiveSet && matches!(sol.report.status, SolveStatus::QpFailed { .. }) {
                prop_assert!(!lambda_unique, "the forced active set refused a QP whose λ is unique: {}", what);
                refused += 1;
                continue;
            }
            if !unique && matches!(sol.report.status, SolveStatus::Stagnated | SolveStatus::MaxIterations) {
                // A Coulomb fixed point whose λ_n is not unique may wander between the QP's answers: it
                // says so (found with clarabel on T_H twice as fine as the FE edges, γ0 = 0).
                refused += 1;
                continue;
            }
            prop_assert_eq!(sol.report.status, SolveStatus::Converged, "{}", what);
            // The reported u is A⁻¹(f − Eᵀλ) of the reported λ.
            let a = answer(&sol, &path);
            let u = problem.expand(&factor.displacement(&load.f_free, &a.nu).expect("solves"));
            let scale = sup(&sol.displacement).max(f64::MIN_POSITIVE);
            let off = sup_diff(&u, &sol.displacement) / scale;
            prop_assert!(off <= floor, "u is not A⁻¹(f − Eᵀλ): {}", what);
            answers.push((what, sol, a));
        }
        let f_min = answers.iter().map(|(_, _, a)| a.objective).fold(reference_answer.objective, f64::min);
        let eps_min = answers.iter().filter(|(_, _, a)| a.objective == f_min).map(|(_, _, a)| a.slack)
            .fold(reference_answer.slack, f64::min);
        let lambda_ref = &reference_answer.nu;
        let size_h = quad(&h, lambda_ref).max(0.0).sqrt();
        let mut worst = [0.0_f64; 4];
        for (what, sol, a) in &answers {
            if !unique {
                continue;
            }
            let d: Vec<f64> = a.nu.iter().zip(lambda_ref).map(|(x, y)| x - y).collect();
            let dist_h = quad(&h, &d).max(0.0).sqrt();
            if coulomb {
                let contraction = |s: &Solution| {
                    let r = &s.report.residual_history;
                    if r.len() >= 2 && r[r.len() - 2] > 0.0 { r[r.len() - 1] / r[r.len() - 2] } else { 0.0 }
                };
                let l = contraction(sol).max(contraction(&reference));
                prop_assume!(l < 1.0);
                let residual = |s: &Solution, e: &Answer| {
                    (2.0 * e.slack / min).sqrt() + s.report.residual_history.last().copied().unwrap_or(0.0) * sup(&s.lambda_n) * (k as f64).sqrt()
                };
                let allowed = (residual(sol, a) + residual(&reference, &reference_answer)) / (1.0 - l)
                    + floor * sup(lambda_ref) * (k as f64).sqrt();
                let dist = d.iter().map(|v| v * v).sum::<f64>().sqrt();
                prop_assert!(dist <= allowed, "Coulomb λ differ by {:e} (allowed {:e}): {}", dist, allowed, what);
                worst[1] = worst[1].max(dist / allowed);
                continue;
            }
            prop_assert!(a.objective <= f_min + a.slack + eps_min + floor * a.objective.abs(),
                "objective {:e} above the minimum {:e} by more than {:e}: {}", a.objective, f_min, a.slack + eps_min, what);
            worst[0] = worst[0].max((a.objective - f_min) / (a.slack + eps_min).max(f64::MIN_POSITIVE));
            let allowed = (2.0 * a.slack).sqrt() + (2.0 * reference_answer.slack).sqrt() + floor * size_h;
            prop_assert!(dist_h <= allowed, "λ differ by {:e} in the H-norm (allowed {:e}): {}", dist_h, allowed, what);
            worst[1] = worst[1].max(dist_h / allowed);
            // The same distance bounded by the answers' own residuals, no tolerance of the QP's in it
            // (`tribo_testkit::energy`): each lies within √S of a minimizer in the H-(semi)norm.
            let thresholds = match &friction {
                Friction::Tresca(Threshold::Uniform(t)) => vec![*t; k / 2],
                Friction::Tresca(Threshold::PerDof(t)) => t.clone(),
                _ => Vec::new(),
            };
            let lambda_n_max = sup(&sol.lambda_n).max(sup(&reference.lambda_n));
            let root_s = |nu: &[f64]| {
                tribo_testkit::energy_residual(&problem, stabilization, nu, &thresholds, lambda_n_max).sum.sqrt()
            };
            let from_residuals = root_s(&a.nu) + root_s(lambda_ref) + floor * size_h;
            prop_assert!(dist_h <= from_residuals, "λ differ by {:e} in the H-norm, their residuals allow {:e}: {}",
                dist_h, from_residuals, what);
            worst[3] = worst[3].max(dist_h / from_residuals.max(f64::MIN_POSITIVE));
            let df = (sol.normal_force - reference.normal_force).abs() + (sol.tangential_force - reference.tangential_force).abs();
            let allowed_f = force_factor * allowed + floor * (reference.normal_force.abs() + reference.tangential_force.abs());
            prop_assert!(df <= allowed_f, "forces differ by {:e} (allowed {:e}): {}", df, allowed_f, what);
            worst[2] = worst[2].max(df / allowed_f.max(f64::MIN_POSITIVE));
        }
        // The semismooth Newton method beside the fixed point (issue 40), on the default path. Its answer λ_N
        // is held to the fixed point's bound: its own residual is measured as the fixed point's is, by one more
        // evaluation of Φ_H: the Tresca problem with the bounds μ λ_N,n, whose λ_n is Φ_H(λ_N,n).
        let mut newton = "";
        if let (Friction::Coulomb { mu }, true) = (&friction, coulomb && unique) {
            let path = (QpSettings::default(), Condensation::Auto);
            let nw_settings = SolverSettings { coulomb: CoulombMethod::Newton, ..settings(path) };
            let sol = problem.solve(&friction, &nw_settings, None).expect("solves");
            prop_assert_eq!(sol.report.coulomb_method, Some(CoulombMethod::Newton));
            newton = "Newton did not converge";
            if sol.report.status == SolveStatus::Converged {
                newton = "Newton converged";
                let bounds: Vec<f64> = sol.lambda_n.iter().map(|l| mu * l.max(0.0)).collect();
                let phi = problem.solve(&Friction::Tresca(Threshold::PerDof(bounds)), &settings(path), None)
                    .expect("solves");
                prop_assert_eq!(phi.report.status, SolveStatus::Converged);
                let a = answer(&sol, &path);
                let change = phi.lambda_n.iter().zip(&sol.lambda_n).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
                let l = {
                    let r = &reference.report.residual_history;
                    if r.len() >= 2 && r[r.len() - 2] > 0.0 { r[r.len() - 1] / r[r.len() - 2] } else { 0.0 }
                };
                prop_assume!(l < 1.0);
                let own = (2.0 * answer(&phi, &path).slack / min).sqrt() + change;
                let theirs = (2.0 * reference_answer.slack / min).sqrt()
                    + reference.report.residual_history.last().copied().unwrap_or(0.0) * sup(&reference.lambda_n) * (k as f64).sqrt();
                let allowed = (own + theirs) / (1.0 - l) + floor * sup(lambda_ref) * (k as f64).sqrt();
                let dist = a.nu.iter().zip(lambda_ref).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
                prop_assert!(dist <= allowed, "Newton's λ differs by {:e} (allowed {:e}) on {:?}", dist, allowed, case);
                worst[1] = worst[1].max(dist / allowed);
            }
        }
        eprintln!(
            "{newton} {} q = {}, λ unique: {lambda_unique}: {} paths, {refused} refused (forced active set) or not converged (λ_n not unique); largest \
             (difference / allowed): objective {:.1e}, λ {:.1e}, forces {:.1e}, λ by the residuals {:.1e}",
            friction.law().as_str(), condensed.q(), answers.len(), worst[0], worst[1], worst[2], worst[3]
        );
    }
}

/// The answer of a linear problem does not depend on its units (issue 21): a block pressed onto a flat
/// obstacle by the approach δ, or by a prescribed displacement of its base, from 1e-300 to 1e300, with E
/// from 1e-300 to 1e300. The problem is homogeneous: u scales with δ and λ with E δ, so the scaled answers
/// must be the same, to the accuracy `qp_tol · κ(H)` a QP determines λ to (`QpSettings::tol`), on the
/// active-set path and on clarabel, and so must the relative error estimates. Before the QP's scaling
/// avoided forming φ = w² H (which underflows for data below about 1e-160), every approach below 1e-200
/// ended `qp_failed`; before the fixed point's change and the estimator scaled their sums of squares,
/// Coulomb stopped after one iteration there (a change of 0/0) and the relative estimates read 0 and NaN.
#[test]
fn the_answer_does_not_depend_on_the_units() {
    let mesh = rectangle([-1.0, 1.0], [-1.0, 0.0], 6, 3, Diagonal::Right).expect("valid");
    let problem = |young: f64, approach: f64, base: f64| {
        let spec = ProblemSpec {
            material: Material { young, poisson: 0.3 },
            model: Model::PlaneStrain,
            formulation: Default::default(),
            clamped: vec![],
            supports: vec![Support::displacement("bottom", Some(0.0), Some(base))],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle { shape: ObstacleShape::Flat, approach, shift: 0.3 * (approach + base), rotation: None },
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            multiplier_space: MultiplierSpace::P1,
            pairs: Vec::new(),
        };
        Problem::new(mesh.clone(), spec).expect("a valid problem")
    };
    for method in [QpMethod::Auto, QpMethod::Clarabel] {
        for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
            let settings = SolverSettings { qp: QpSettings { method, ..Default::default() }, ..Default::default() };
            // The unit problems: pushed by the approach, and by the base.
            let units = [problem(1.0, 1.0, 0.0), problem(1.0, 0.0, 1.0)];
            let references = units.each_ref().map(|p| p.solve(&friction, &settings, None).expect("solves"));
            assert!(references.iter().all(|r| r.report.status == SolveStatus::Converged));
            let kappa = tribo_testkit::condition_number(&units[0].condense(settings.stabilization).expect("condenses"));
            let tol = tribo_testkit::reached_qp_tol(&settings, &references[0]) * kappa;
            let mut cases: Vec<(f64, f64, f64)> = [-300, -250, -200, -150, -100, -50, 0, 50, 100, 150, 200, 250, 300]
                .iter()
                .map(|&e| (1.0, 10f64.powi(e), 0.0))
                .collect();
            cases.extend([(1e-300, 1e150, 0.0), (1e300, 1e-150, 0.0), (1e-150, 1e-150, 0.0), (1e150, 1e150, 0.0)]);
            // Pushed by the base instead of the approach.
            cases.extend([(1.0, 0.0, 1e-300), (1.0, 0.0, 1e-200), (1.0, 0.0, 1e200), (1.0, 0.0, 1e300)]);
            // Relative to the reference's size (where the reference is 0, as λ_t without friction: absolute).
            let same = |a: &[f64], b: &[f64], scale: f64| {
                a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x / scale - y).abs()))
                    / if sup(b) > 0.0 { sup(b) } else { 1.0 }
            };
            for (young, approach, base) in cases {
                let what = format!("{method} {friction:?} E = {young:e}, δ = {approach:e}, base {base:e}");
                let p = problem(young, approach, base);
                let sol = p.solve(&friction, &settings, None).expect("solves");
                assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
                let d = approach + base;
                let reference = &references[usize::from(base != 0.0)];
                let du = same(&sol.displacement, &reference.displacement, d);
                let dl = same(&sol.lambda_n, &reference.lambda_n, young * d);
                let dt = same(&sol.lambda_t, &reference.lambda_t, young * d);
                assert!(
                    du <= tol && dl <= tol && dt <= tol,
                    "{what}: u {du:e}, λ_n {dl:e}, λ_t {dt:e} (allowed {tol:e})"
                );
                // The relative error estimates are dimensionless: the same numbers in any units.
                let (e, r) = (&sol.report.estimate, &reference.report.estimate);
                for (got, want) in [(e.energy_relative, r.energy_relative), (e.traction_relative, r.traction_relative)]
                {
                    assert!((got - want).abs() <= tol * want, "{what}: relative estimate {got} against {want}");
                }
            }
        }
    }
}

/// Subnormal data (below 2.2e-308) keep only a few digits, so the answer would too: a typed error naming
/// the datum, before any work, for the approach, the shift, a prescribed displacement and a history step.
#[test]
fn subnormal_data_are_refused_by_name() {
    let mesh = rectangle([-1.0, 1.0], [-1.0, 0.0], 4, 2, Diagonal::Right).expect("valid");
    let spec = |approach: f64, shift: f64, base: f64| ProblemSpec {
        material: Material { young: 1.0, poisson: 0.3 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![],
        supports: vec![Support::displacement("bottom", Some(0.0), Some(base))],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "top".into(),
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach, shift, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    for (approach, shift, base, name) in [
        (1e-320, 0.0, 0.0, "approach δ"),
        (0.01, -5e-324, 0.0, "tangential shift s"),
        (0.0, 0.0, 1e-310, "the y component"),
    ] {
        let err = Problem::new(mesh.clone(), spec(approach, shift, base)).expect_err("subnormal data");
        let text = err.to_string();
        assert!(text.contains(name) && text.contains("subnormal"), "{text}");
    }
    // The smallest normal data are solved (the_answer_does_not_depend_on_the_units: down to 1e-300).
    let p = Problem::new(mesh, spec(f64::MIN_POSITIVE, 0.0, 0.0)).expect("normal data");
    let sol = p.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.normal_force > 0.0);
    let step = LoadStep::new(1e-320, 0.0);
    let err = p.solve_history(&Friction::Frictionless, &[step], &SolverSettings::default(), None).expect_err("refused");
    assert!(err.to_string().contains("approach") && err.to_string().contains("subnormal"), "{err}");
}
