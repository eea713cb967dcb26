//! The semismooth Newton method for Coulomb friction beside the fixed point (issue 40), the fixed point the
//! reference: both give the same answer wherever both converge (on the random problems of `paths`, and here
//! on Hertz over μ and ν, a body held only by the contact and a history), to the bound the fixed point's
//! contraction gives: an answer whose evaluation of Φ_H moves λ_n by δ lies within δ / (1 − L) of the fixed
//! point, L the contraction measured from the fixed point's last changes. `auto` answers by Newton, and by the
//! fixed point where Newton does not converge, and the report says which; the setting has one flat name.

use std::ops::ControlFlow;

use tribo::*;
use tribo_testkit::{hertz_mesh, hertz_spec, wedge_problem};

fn settings(coulomb: CoulombMethod) -> SolverSettings {
    SolverSettings { coulomb, ..Default::default() }
}

fn norm(v: impl Iterator<Item = f64>) -> f64 {
    v.map(|x| x * x).sum::<f64>().sqrt()
}

/// ‖Φ_H(λ_n) − λ_n‖₂ for the answer `sol` of a Coulomb problem with coefficient `mu`: the change one more
/// fixed-point iteration would make (Φ_H(λ_n) is the λ_n of the Tresca problem with the bounds μ λ_n).
fn change(problem: &Problem, mu: f64, sol: &Solution) -> f64 {
    let bounds = sol.lambda_n.iter().map(|l| mu * l.max(0.0)).collect();
    let phi = problem.solve(&Friction::Tresca(Threshold::PerDof(bounds)), &SolverSettings::default(), None).unwrap();
    assert_eq!(phi.report.status, SolveStatus::Converged);
    norm(phi.lambda_n.iter().zip(&sol.lambda_n).map(|(a, b)| a - b))
}

/// The contraction L of the fixed point estimated from its last two changes (0 after a single iteration).
fn contraction(fixed_point: &Solution) -> f64 {
    match fixed_point.report.residual_history.as_slice() {
        [.., a, b] if *a > 0.0 => b / a,
        _ => 0.0,
    }
}

/// Solves `problem` by both methods and checks the same answer: the Euclidean distance of the multipliers
/// within (δ_N + δ_F) / (1 − L), each δ measured by one more evaluation of Φ_H (plus the QPs' tolerance,
/// `qp_tol` times the size of λ, for the Tresca QP that measures it), and u within that distance's image.
fn same_answer(problem: &Problem, mu: f64, what: &str) -> (Solution, Solution) {
    same_answer_with(problem, mu, what, &settings(CoulombMethod::FixedPoint))
}

/// [`same_answer`] with the fixed point's own settings (a relaxed one: its contraction L is then the relaxed
/// iteration's, and one plain evaluation of Φ_H measures δ at least as large as a relaxed one would).
fn same_answer_with(problem: &Problem, mu: f64, what: &str, fixed_point: &SolverSettings) -> (Solution, Solution) {
    let coulomb = Friction::Coulomb { mu };
    let fp = problem.solve(&coulomb, fixed_point, None).unwrap();
    let nw = problem.solve(&coulomb, &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!(fp.report.status, SolveStatus::Converged, "{what}: the fixed point");
    assert_eq!(nw.report.status, SolveStatus::Converged, "{what}: Newton");
    assert_eq!(fp.report.coulomb_method, Some(CoulombMethod::FixedPoint));
    assert_eq!(nw.report.coulomb_method, Some(CoulombMethod::Newton));
    assert!(!fp.report.coulomb_fallback && !nw.report.coulomb_fallback);
    let l = contraction(&fp);
    assert!(l < 1.0, "{what}: the fixed point contracts ({l})");
    let size = norm(fp.lambda_n.iter().chain(&fp.lambda_t).copied());
    // What a QP determines λ to: the tolerance it met times κ(H), relative (`QpSettings::tol`).
    let kappa = tribo_testkit::condition_number(&problem.condense(Stabilization::default()).unwrap());
    let qp = |s: &Solution, c: CoulombMethod| tribo_testkit::reached_qp_tol(&settings(c), s) * kappa * size;
    let allowed = (change(problem, mu, &nw)
        + change(problem, mu, &fp)
        + qp(&nw, CoulombMethod::Newton)
        + tribo_testkit::reached_qp_tol(fixed_point, &fp) * kappa * size)
        / (1.0 - l);
    let dist =
        norm(fp.lambda_n.iter().zip(&nw.lambda_n).chain(fp.lambda_t.iter().zip(&nw.lambda_t)).map(|(a, b)| a - b));
    assert!(dist <= allowed, "{what}: λ differ by {dist:e} (allowed {allowed:e})");
    let du = fp.displacement.iter().zip(&nw.displacement).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    let u = fp.displacement.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    eprintln!(
        "{what}: fixed point {} iterations, Newton {} steps; λ differ by {dist:.1e} (allowed {allowed:.1e}), u by {:.1e}",
        fp.report.iterations,
        nw.report.iterations,
        du / u
    );
    (fp, nw)
}

#[test]
fn newton_and_the_fixed_point_agree_on_hertz_over_mu_and_nu() {
    for nu in [0.0, 0.3, 0.45] {
        let mut spec = hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        spec.material.poisson = nu;
        let problem = Problem::new(hertz_mesh(0.04), spec).unwrap();
        for mu in [0.1, 0.3, 1.0, 2.0] {
            let (fp, nw) = same_answer(&problem, mu, &format!("Hertz ν = {nu}, μ = {mu}"));
            // Newton's history: the relative merit before each step and the one it ended on.
            assert_eq!(nw.report.residual_history.len(), nw.report.iterations + 1);
            assert!(nw.report.residual_history.last().unwrap() <= &FixedPointSettings::default().tol);
            assert_eq!(nw.states.len(), fp.states.len());
        }
    }
}

/// A block (0, 2) × (0, 1) held only by the contact, pressed onto a flat foundation by a traction (τ, −1).
fn held_block(nu: f64, tau: f64) -> Problem {
    let mesh = rectangle([0.0, 2.0], [0.0, 1.0], 20, 10, Diagonal::Alternating).unwrap();
    let spec = ProblemSpec::new(Material { young: 100.0, poisson: nu }, "bottom").traction("top", [tau, -1.0]);
    Problem::new(mesh, spec).unwrap()
}

#[test]
fn newton_solves_a_body_held_only_by_the_contact() {
    // Force control: the rigid motion α is an unknown of Newton's system beside λ, the body's equilibrium
    // (E R)ᵀ λ = Rᵀ f a row of it.
    let problem = held_block(0.3, 0.15);
    let (_, nw) = same_answer(&problem, 0.3, "held block");
    assert!(nw.states.contains(&ContactState::Stick) && nw.states.contains(&ContactState::Slip), "partial slip");
}

#[test]
fn newton_checks_the_point_it_reaches_at_its_cap_and_its_memory() {
    let problem =
        Problem::new(hertz_mesh(0.04), hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1))
            .unwrap();
    let coulomb = Friction::Coulomb { mu: 1.0 };
    let free = problem.solve(&coulomb, &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!(free.report.status, SolveStatus::Converged);
    let n = free.report.iterations;
    // Capped at the steps it needs, the point the last step reaches is evaluated, and it is the answer.
    let mut capped = settings(CoulombMethod::Newton);
    capped.fp.max_iter = n;
    let at_cap = problem.solve(&coulomb, &capped, None).unwrap();
    assert_eq!((at_cap.report.status, at_cap.report.iterations), (SolveStatus::Converged, n));
    assert_eq!(at_cap.lambda_t, free.lambda_t);
    capped.fp.max_iter = n - 1;
    let short = problem.solve(&coulomb, &capped, None).unwrap();
    assert_eq!(short.report.status, SolveStatus::MaxIterations);
    assert_eq!(short.report.residual_history.len(), n, "the merit of every point, the one handed back last");
    // Its columns of H and dense system count against the memory budget, beside what the factor holds: a strip
    // clamped on top and pressed flat along 301 multiplier dofs needs all 602 columns and a 602 × 602 system
    // with its LU, 8.7 MB with the factor, where the frictionless QP it starts from needs less (the active-set
    // method's count: the columns of its working set and four blocks of its size).
    let long = Problem::new(
        rectangle([0.0, 30.0], [0.0, 1.0], 300, 2, Diagonal::Alternating).unwrap(),
        ProblemSpec::new(Material { young: 100.0, poisson: 0.3 }, "bottom").clamped(["top"]).approach(0.01),
    )
    .unwrap();
    let tight = SolverSettings { memory_budget: 6_000_000, ..settings(CoulombMethod::Newton) };
    match long.solve(&Friction::Coulomb { mu: 0.3 }, &tight, None) {
        Err(Error::MemoryBudget { what, needed, .. }) => {
            // Held: the factor and the columns the QPs formed; to form: the others, and the dense system.
            let held = long.held_bytes();
            let (system, columns) = (8.0 * 2.0 * 602.0 * 602.0, 8.0 * 602.0 * 602.0);
            assert!(
                what.contains("Newton") && needed > held + system && needed <= held + system + columns,
                "{what}: {needed}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn newton_restarts_from_a_fixed_point_iteration_where_it_stalls() {
    // On this held block at ν = 0.3 and μ = 0.05 Newton's damped steps stall (its states cycle at the ends of a
    // small stick zone); one fixed-point iteration from where it stalled restarts it, and it converges to the
    // fixed point's answer. The restart's QP is booked with the others.
    let problem = held_block(0.3, 0.045);
    let (_, nw) = same_answer(&problem, 0.05, "held block, μ = 0.05");
    let restarts = nw.report.qp_methods.len() - 1;
    assert!(restarts >= 1, "the first QP and at least one restart: {:?}", nw.report.qp_methods);
    assert_eq!(nw.report.residual_history.len(), nw.report.iterations + restarts + 1, "a merit per point evaluated");
}

#[test]
fn auto_takes_the_fixed_point_where_newton_does_not_converge_and_says_so() {
    // Beyond the discrete overturning limit (τ = 0.99 against 1 − h/3 = 0.967 on this mesh) the block has no
    // equilibrium: Newton's restart QP is infeasible, auto hands the problem to the fixed point, whose first QP
    // is infeasible too, and the report says both.
    let problem = held_block(0.3, 0.99);
    let coulomb = Friction::Coulomb { mu: 1.0 };
    let newton = problem.solve(&coulomb, &settings(CoulombMethod::Newton), None).unwrap();
    assert!(matches!(newton.report.status, SolveStatus::QpFailed { .. }), "{:?}", newton.report.status);
    assert_eq!(newton.report.coulomb_method, Some(CoulombMethod::Newton));
    let auto = problem.solve(&coulomb, &settings(CoulombMethod::Auto), None).unwrap();
    let fixed_point = problem.solve(&coulomb, &settings(CoulombMethod::FixedPoint), None).unwrap();
    assert!(matches!(fixed_point.report.status, SolveStatus::QpFailed { .. }), "{:?}", fixed_point.report.status);
    assert_eq!((auto.report.coulomb_method, auto.report.coulomb_fallback), (Some(CoulombMethod::FixedPoint), true));
    assert_eq!(auto.report.status, fixed_point.report.status, "the fixed point from the same start");
    assert_eq!(auto.lambda_n, fixed_point.lambda_n);
    // Where Newton converges, auto is Newton.
    let hertz =
        Problem::new(hertz_mesh(0.04), hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1))
            .unwrap();
    let friction = Friction::Coulomb { mu: 0.3 };
    let auto = hertz.solve(&friction, &settings(CoulombMethod::Auto), None).unwrap();
    let newton = hertz.solve(&friction, &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!((auto.report.coulomb_method, auto.report.coulomb_fallback), (Some(CoulombMethod::Newton), false));
    assert_eq!(auto.lambda_t, newton.lambda_t);
    // Where the QPs solve the saddle-point system (H not formed), auto takes the fixed point.
    let saddle = SolverSettings { condensation: Condensation::Saddle, ..settings(CoulombMethod::Auto) };
    let on_saddle = hertz.solve(&friction, &saddle, None).unwrap();
    assert_eq!(on_saddle.report.condensation, Condensation::Saddle);
    assert_eq!(
        (on_saddle.report.coulomb_method, on_saddle.report.coulomb_fallback),
        (Some(CoulombMethod::FixedPoint), false)
    );
    // Frictionless and Tresca name no Coulomb method.
    let tresca =
        hertz.solve(&Friction::Tresca(Threshold::Uniform(0.1)), &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!((tresca.report.coulomb_method, tresca.report.iterations), (None, 0));
}

#[test]
fn a_history_by_newton_follows_the_fixed_point_step_by_step() {
    // Against a fixed point run to fp_tol = 1e-13. Were both steps k solved from the same state, each answer would
    // lie within its δ / (1 − L_k) of that step's solution (δ its last change, or Newton's merit ‖C‖, L_k the fixed
    // point's contraction), plus what the QPs determine (the tolerance met times κ(H)). Their states differ by the
    // previous steps' difference, which enters step k's data (the slip reference); the test takes the step's answer
    // to move by at most κ(H) times that. This last factor is an estimate, not a proof: the history map is not
    // shown to be Lipschitz with that constant.
    let problem =
        Problem::new(hertz_mesh(0.04), hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1))
            .unwrap();
    let steps: Vec<LoadStep> =
        [0.0, 0.002, 0.004, 0.002, -0.002, -0.004].iter().map(|&s| LoadStep::new(0.01, s)).collect();
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let kappa = tribo_testkit::condition_number(&problem.condense(Stabilization::default()).unwrap());
    let mut tight = settings(CoulombMethod::FixedPoint);
    tight.fp.tol = 1e-13;
    let fp = problem.solve_history(&coulomb, &steps, &tight, None).unwrap();
    let nw = problem.solve_history(&coulomb, &steps, &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!((fp.solutions.len(), nw.solutions.len()), (steps.len(), steps.len()));
    let mut before = 0.0;
    for (k, (a, b)) in fp.solutions.iter().zip(&nw.solutions).enumerate() {
        assert_eq!((a.report.status, b.report.status), (SolveStatus::Converged, SolveStatus::Converged), "step {k}");
        assert_eq!(b.report.coulomb_method, Some(CoulombMethod::Newton));
        let l = contraction(a);
        assert!(l < 1.0, "step {k}: the fixed point contracts ({l})");
        let size = norm(a.lambda_n.iter().chain(&a.lambda_t).copied());
        let own = |s: &Solution, set: &SolverSettings| {
            s.report.residual_history.last().copied().unwrap_or(0.0) * norm(s.lambda_n.iter().copied())
                + tribo_testkit::reached_qp_tol(set, s) * kappa * size
        };
        let allowed = (own(a, &tight) + own(b, &settings(CoulombMethod::Newton))) / (1.0 - l) + kappa * before;
        let dist =
            norm(a.lambda_n.iter().zip(&b.lambda_n).chain(a.lambda_t.iter().zip(&b.lambda_t)).map(|(x, y)| x - y));
        assert!(dist <= allowed, "step {k}: λ differ by {dist:e} (allowed {allowed:e})");
        eprintln!("step {k}: λ differ by {dist:.1e} (allowed {allowed:.1e}), Newton {} steps", b.report.iterations);
        before = dist;
    }
}

#[test]
fn auto_falls_back_to_the_fixed_point_and_converges_where_newton_runs_out_of_steps() {
    // On the held block of study 20 at ν = 0.45, μ = 0.05, τ = 0.025 the fixed point converges in 6 iterations
    // and Newton needs 16 steps: capped at 8, Newton ends max_iterations and auto answers by the fixed point.
    let mesh = rectangle([0.0, 2.0], [0.0, 1.0], 40, 20, Diagonal::Alternating).unwrap();
    let spec = ProblemSpec::new(Material { young: 100.0, poisson: 0.45 }, "bottom").traction("top", [0.025, -1.0]);
    let problem = Problem::new(mesh, spec).unwrap();
    let coulomb = Friction::Coulomb { mu: 0.05 };
    let capped = |c: CoulombMethod| {
        let mut s = settings(c);
        s.fp.max_iter = 8;
        s
    };
    let newton = problem.solve(&coulomb, &capped(CoulombMethod::Newton), None).unwrap();
    assert_eq!(newton.report.status, SolveStatus::MaxIterations);
    let auto = problem.solve(&coulomb, &capped(CoulombMethod::Auto), None).unwrap();
    let fixed_point = problem.solve(&coulomb, &capped(CoulombMethod::FixedPoint), None).unwrap();
    assert_eq!(fixed_point.report.status, SolveStatus::Converged);
    assert_eq!(
        (auto.report.status, auto.report.coulomb_method),
        (SolveStatus::Converged, Some(CoulombMethod::FixedPoint))
    );
    assert!(auto.report.coulomb_fallback);
    assert_eq!(auto.lambda_t, fixed_point.lambda_t, "the fixed point from the same start");
}

/// Where Newton stagnates and the fixed point converges (study 20's tall block: (0, 1) × (0, 6) held only by the
/// contact, μ = 0.1, τ = 0.075, near sliding (τ/μ = 0.75) and overturning (0.9 of W / (2H)) at once; every ν):
/// Newton says `stagnated`, and `auto` answers by the fixed point, saying so.
#[test]
fn on_the_tall_block_newton_stagnates_and_auto_answers_by_the_fixed_point() {
    let mesh = rectangle([0.0, 1.0], [0.0, 6.0], 20, 120, Diagonal::Alternating).unwrap();
    let spec = ProblemSpec::new(Material { young: 100.0, poisson: 0.0 }, "bottom").traction("top", [0.075, -1.0]);
    let problem = Problem::new(mesh, spec).unwrap();
    let coulomb = Friction::Coulomb { mu: 0.1 };
    let newton = problem.solve(&coulomb, &settings(CoulombMethod::Newton), None).unwrap();
    assert_eq!(newton.report.status, SolveStatus::Stagnated);
    let fixed_point = problem.solve(&coulomb, &settings(CoulombMethod::FixedPoint), None).unwrap();
    assert_eq!(fixed_point.report.status, SolveStatus::Converged);
    let auto = problem.solve(&coulomb, &settings(CoulombMethod::Auto), None).unwrap();
    assert_eq!(
        (auto.report.status, auto.report.coulomb_method),
        (SolveStatus::Converged, Some(CoulombMethod::FixedPoint))
    );
    assert!(auto.report.coulomb_fallback);
    assert!((auto.tangential_force.abs() - 0.075).abs() <= 1e-9, "it holds the load: {}", auto.tangential_force);
}

#[test]
fn the_setting_has_one_name_and_newton_reports_its_steps() {
    let mut s = SolverSettings::default();
    assert_eq!(s.get("coulomb"), Some(SettingValue::Name("fixed_point".into())));
    s.set("coulomb", SettingValue::Name("newton".into())).unwrap();
    assert_eq!(s.coulomb, CoulombMethod::Newton);
    let e = s.set("coulomb", SettingValue::Name("newtons".into())).unwrap_err();
    assert!(e.to_string().contains("fixed_point, newton, auto"), "{e}");
    let info = SolverSettings::table().into_iter().find(|i| i.name == "coulomb").unwrap();
    assert_eq!(info.kind, SettingKind::Choice(vec!["fixed_point", "newton", "auto"]));
    // Each step is reported to the observer, which may stop the solve.
    let problem =
        Problem::new(hertz_mesh(0.04), hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1))
            .unwrap();
    let mut seen = Vec::new();
    let mut observer = |p: &Progress| {
        if p.phase == Phase::Newton {
            seen.push((p.iteration, p.change));
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    };
    let sol = problem.solve(&Friction::Coulomb { mu: 1.0 }, &s, Some(&mut observer)).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Interrupted { iteration: 1 });
    assert_eq!(seen.len(), 1);
    assert_eq!(seen[0], (1, sol.report.residual_history[0]));
}

/// The hidden campaign's D25 (issues 37, 40): forced clarabel and the active-set method gave two `converged`
/// Coulomb answers 0.48 % apart on a problem with P0 multipliers, ν = 0 and γ0 = ½ bound. On that configuration
/// (Hertz, ν = 0, P0, γ0 = ½ bound, μ up to 2, the shift up to 0.008) three paths give one answer today: the
/// fixed point with every QP by clarabel, the fixed point by the active-set method, and Newton, each within the
/// contraction bound of the others (δ of each answer measured by one more evaluation of Φ_H; measured: at most
/// 1.6e-9 apart relative in Q over this grid and over 400 random small blocks of the path test's kind), and
/// `coulomb_check` says `agree` on each. (The check finds two answers on coarser blocks with ν ≥ 0.36 or μ = 2,
/// where the discrete problem has several solutions: the unit tests of `solve/check.rs`.)
#[test]
fn d25_three_paths_give_one_answer() {
    for h_min in [0.04, 0.02] {
        for (mu, shift) in [(0.3, 0.004), (1.0, 0.008), (2.0, 0.004)] {
            let mut spec = hertz_spec(0.01, shift, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P0);
            spec.material.poisson = 0.0;
            let problem = Problem::new(hertz_mesh(h_min), spec).unwrap();
            let friction = Friction::Coulomb { mu };
            let with = |method: QpMethod, coulomb: CoulombMethod| SolverSettings {
                stabilization: Stabilization::Fraction(0.5),
                qp: QpSettings { method, ..Default::default() },
                coulomb,
                coulomb_check: true,
                ..Default::default()
            };
            let answers: Vec<Solution> = [
                with(QpMethod::Clarabel, CoulombMethod::FixedPoint),
                with(QpMethod::ActiveSet, CoulombMethod::FixedPoint),
                with(QpMethod::Auto, CoulombMethod::Newton),
            ]
            .iter()
            .map(|s| problem.solve(&friction, s, None).unwrap())
            .collect();
            let what = format!("h_min {h_min}, μ {mu}, shift {shift}");
            assert!(answers.iter().all(|s| s.report.status == SolveStatus::Converged), "{what}");
            // Each checked by the other Coulomb method: one answer (`solve/check.rs`).
            for s in &answers {
                let check = s.report.coulomb_check.expect("checked");
                assert_eq!(check.agreement, Agreement::Agree, "{what}: {check:?}");
            }
            let l = contraction(&answers[0]).max(contraction(&answers[1]));
            assert!(l < 1.0, "{what}: the fixed point contracts ({l})");
            let kappa = tribo_testkit::condition_number(&problem.condense(Stabilization::Fraction(0.5)).unwrap());
            let size = norm(answers[0].lambda_n.iter().chain(&answers[0].lambda_t).copied());
            let settings_of = [
                with(QpMethod::Clarabel, CoulombMethod::FixedPoint),
                with(QpMethod::ActiveSet, CoulombMethod::FixedPoint),
                with(QpMethod::Auto, CoulombMethod::Newton),
            ];
            let delta: Vec<f64> = answers
                .iter()
                .zip(&settings_of)
                .map(|(s, set)| change(&problem, mu, s) + tribo_testkit::reached_qp_tol(set, s) * kappa * size)
                .collect();
            for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                let (a, b) = (&answers[i], &answers[j]);
                let dist = norm(
                    a.lambda_n.iter().zip(&b.lambda_n).chain(a.lambda_t.iter().zip(&b.lambda_t)).map(|(x, y)| x - y),
                );
                let allowed = (delta[i] + delta[j]) / (1.0 - l);
                assert!(dist <= allowed, "{what}: answers {i} and {j} differ by {dist:e} (allowed {allowed:e})");
            }
        }
    }
}

/// A wedge of half-angle 20° forced into a rigid V-groove (`tribo_testkit::wedge_problem`, issue 40's "where the
/// fixed point fails"): sliding in, the frozen friction bound multiplies the fixed point's error by about
/// −μ cot α = −1.37 at μ = 0.5, and the plain fixed point two-cycles: its changes stop falling and alternate, and
/// it ends `stagnated`. Newton converges (and `auto` answers by it, no fallback), and so does the fixed point
/// relaxed by ω = ½ (error factor 1 − ω (1 + μ cot α) ≈ −0.19), to the same answer within the contraction bound.
/// At 45° (μ cot α = 0.5) both converge plainly and agree.
#[test]
fn on_a_wedge_forced_into_a_groove_the_fixed_point_cycles_and_newton_converges() {
    let (mu, coulomb) = (0.5, Friction::Coulomb { mu: 0.5 });
    let wedge = wedge_problem(16, 20.0, 0.3);
    let mut plain = settings(CoulombMethod::FixedPoint);
    plain.fp.max_iter = 400;
    let fp = wedge.solve(&coulomb, &plain, None).unwrap();
    // It detects that it makes no progress (before its cap of 400).
    assert_eq!(fp.report.status, SolveStatus::Stagnated, "the plain fixed point cycles");
    let r = &fp.report.residual_history;
    let n = r.len();
    assert!((40..400).contains(&n), "it ran {n} iterations");
    // A two-cycle, not a slow convergence: the iterates alternate between two states, so the change of each
    // iteration stays the distance between them, of a few per mille of λ_n, and does not fall over its last 40
    // iterations (a contraction of 0.999 would have shrunk it by 4 %).
    let tail = &r[n - 40..];
    assert!(tail.iter().all(|&c| c > 1e-3), "the changes stay large: {tail:?}");
    assert!(tail[39] / tail[0] > 0.99, "the changes do not fall: {} then {}", tail[0], tail[39]);
    let auto = wedge.solve(&coulomb, &settings(CoulombMethod::Auto), None).unwrap();
    assert_eq!(auto.report.status, SolveStatus::Converged);
    assert_eq!((auto.report.coulomb_method, auto.report.coulomb_fallback), (Some(CoulombMethod::Newton), false));
    let mut relaxed = settings(CoulombMethod::FixedPoint);
    relaxed.fp.relaxation = 0.5;
    let (fp, nw) = same_answer_with(&wedge, mu, "wedge 20°, μ = 0.5, the fixed point relaxed by ½", &relaxed);
    assert!(fp.states.iter().filter(|s| **s != ContactState::Separation).all(|s| *s == ContactState::Slip));
    assert!(nw.report.iterations < fp.report.iterations);
    same_answer(&wedge_problem(16, 45.0, 0.3), mu, "wedge 45°, μ = 0.5");
}
