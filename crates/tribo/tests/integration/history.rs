//! Loading histories: the incremental problem against the static one, path dependence, gross sliding,
//! Cattaneo–Mindlin partial slip, one factorization for the path, interruption and rejected steps.

use std::ops::ControlFlow;

use tribo::{
    ContactState, Error, Friction, History, LoadStep, MultiplierPoints, MultiplierSpace, Solution, SolveStatus,
    SolverSettings, StepProgress, Threshold,
};
use tribo_testkit::{block_problem, hertz_mesh, hertz_problem, hertz_scene, hertz_spec};

const MU: f64 = 0.3;

/// The Hertz problem on a graded mesh with its cylinder pushed `approach` and at rest tangentially.
fn hertz(h_min: f64, shift: f64) -> tribo::Problem {
    let s = hertz_scene();
    hertz_problem(h_min, s.approach, shift, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
}

/// A history of one step from rest is the static problem: the same data bit for bit, hence the same
/// answer bit for bit, for every friction law.
#[test]
fn one_step_from_rest_is_the_static_solve() {
    let problem = hertz(0.02, 0.004);
    let s = hertz_scene();
    let settings = SolverSettings::default();
    for friction in [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(0.2)), Friction::Coulomb { mu: MU }] {
        let fixed = problem.solve(&friction, &settings, None).unwrap();
        let history = problem.solve_history(&friction, &[LoadStep::new(s.approach, 0.004)], &settings, None).unwrap();
        assert_eq!(history.status, SolveStatus::Converged);
        let step = &history.solutions[0];
        assert_eq!(step.displacement, fixed.displacement, "{friction:?}: u");
        assert_eq!(step.lambda_n, fixed.lambda_n, "{friction:?}: λ_n");
        assert_eq!(step.lambda_t, fixed.lambda_t, "{friction:?}: λ_t");
        assert_eq!(step.slip, fixed.slip, "{friction:?}: slip");
        assert_eq!(step.report.iterations, fixed.report.iterations, "{friction:?}: iterations");
    }
}

/// Friction remembers the path. The obstacle's final position reached three ways — pressed and dragged
/// in one step from rest, pressed then dragged in 20 steps, pressed then dragged to twice the distance and
/// back in 20 steps — gives three tangential tractions. The first two differ through the coupling of
/// normal and tangential response (ν = 0.3: pressing with friction locks in inward tractions that the
/// single step never builds); the overshoot reverses the slip at the edges of the contact. The normal
/// force barely depends on the path.
#[test]
fn the_path_matters() {
    let problem = hertz(0.01, 0.0);
    let s = hertz_scene();
    let settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: MU };
    let last = 0.003;
    let drag = |to: &[f64]| {
        let mut steps = vec![LoadStep::new(s.approach, 0.0)];
        steps.extend(to.iter().map(|&x| LoadStep::new(s.approach, x)));
        let h = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
        assert_eq!(h.status, SolveStatus::Converged);
        h.solutions.last().unwrap().clone()
    };
    let direct = problem.solve_history(&coulomb, &[LoadStep::new(s.approach, last)], &settings, None).unwrap();
    let direct = &direct.solutions[0];
    let steps: Vec<f64> = (1..=20).map(|k| last * k as f64 / 20.0).collect();
    let stepped = drag(&steps);
    let over: Vec<f64> = (1..=10)
        .map(|k| 2.0 * last * k as f64 / 10.0)
        .chain((1..=10).map(|k| 2.0 * last - last * k as f64 / 10.0))
        .collect();
    let overshoot = drag(&over);
    let scale = MU * direct.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let dist = |a: &tribo::Solution, b: &tribo::Solution| {
        a.lambda_t.iter().zip(&b.lambda_t).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
    };
    let (coupling, memory) = (dist(direct, &stepped), dist(direct, &overshoot));
    assert!(coupling > 0.1, "pressing first leaves another traction: max |Δλ_t| / max μλ_n = {coupling:e}");
    assert!(memory > 0.1, "the overshoot leaves another traction: max |Δλ_t| / max μλ_n = {memory:e}");
    for sol in [&stepped, &overshoot] {
        let rel = (direct.normal_force - sol.normal_force).abs() / direct.normal_force;
        assert!(rel < 1e-2, "the normal force barely depends on the tangential path: {rel:e}");
        assert!(sol.kkt.friction_bound < 1e-6, "{:?}", sol.kkt);
    }
}

/// Dragging past Q = μP: every contact dof slips, Q = μP to the solver's accuracy, and the history
/// converges (neither a failure nor a hang).
#[test]
fn gross_sliding_holds_q_at_mu_p() {
    let (problem, mu) = block_problem(40, 10);
    let coulomb = Friction::Coulomb { mu };
    let approach = problem.spec.obstacle.approach;
    let steps: Vec<LoadStep> = (0..=8).map(|k| LoadStep::new(approach, 0.01 * k as f64)).collect();
    let history = problem.solve_history(&coulomb, &steps, &SolverSettings::default(), None).unwrap();
    assert_eq!(history.status, SolveStatus::Converged);
    let last = history.solutions.last().unwrap();
    let in_contact = last.states.iter().filter(|&&s| s != ContactState::Separation).count();
    let slipping = last.states.iter().filter(|&&s| s == ContactState::Slip).count();
    assert!(in_contact > 0);
    assert_eq!(slipping, in_contact, "gross sliding: every contact dof slips ({:?})", last.states);
    let sliding = history.gross_sliding();
    assert!(*sliding.last().unwrap() && !sliding[1], "gross sliding reported: {sliding:?}");
    let ratio = last.tangential_force.abs() / (mu * last.normal_force);
    assert!((ratio - 1.0).abs() < 1e-6, "|Q| / μP = {ratio}");
    // Beforehand the drag passed through partial slip.
    let first_drag = &history.solutions[1];
    assert!(first_drag.states.contains(&ContactState::Stick), "the first drag step sticks somewhere");
}

/// One factorization for the whole path: the history reports it, a second history reuses it, and the
/// observer sees every step.
#[test]
fn one_factorization_for_the_path() {
    let problem = hertz(0.04, 0.0);
    let s = hertz_scene();
    let settings = SolverSettings::default();
    let steps: Vec<LoadStep> = (0..5).map(|k| LoadStep::new(s.approach, 0.0005 * k as f64)).collect();
    let mut seen = Vec::new();
    let mut observer = |p: &StepProgress| {
        seen.push((p.step, p.steps));
        ControlFlow::Continue(())
    };
    let coulomb = Friction::Coulomb { mu: MU };
    let first = problem.solve_history(&coulomb, &steps, &settings, Some(&mut observer)).unwrap();
    assert_eq!(first.factorizations, 1);
    assert_eq!(seen, (0..5).map(|k| (k, 5)).collect::<Vec<_>>());
    let again = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    assert_eq!(again.factorizations, 0);
    assert_eq!(again.solutions.len(), 5);
    for (a, b) in first.solutions.iter().zip(&again.solutions) {
        assert_eq!(a.lambda_t, b.lambda_t);
    }
    assert_eq!(first.step_seconds.len(), 5);
    assert_eq!(first.normal_force().len(), 5);
    assert_eq!(first.count(ContactState::Stick).len(), 5);
}

/// An observer that stops the history keeps the steps done; a bad step is refused before any solve.
#[test]
fn interrupted_and_refused_histories() {
    let problem = hertz(0.04, 0.0);
    let s = hertz_scene();
    let steps: Vec<LoadStep> = (0..6).map(|k| LoadStep::new(s.approach, 0.0005 * k as f64)).collect();
    let mut stop_after_two =
        |p: &StepProgress| if p.step == 1 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) };
    let coulomb = Friction::Coulomb { mu: MU };
    let h = problem.solve_history(&coulomb, &steps, &SolverSettings::default(), Some(&mut stop_after_two)).unwrap();
    assert!(matches!(h.status, SolveStatus::Interrupted { .. }), "{:?}", h.status);
    assert_eq!((h.solutions.len(), h.ended_at), (2, Some(1)));
    let mut bad = steps.clone();
    bad[3].shift = f64::NAN;
    let e = problem.solve_history(&coulomb, &bad, &SolverSettings::default(), None).unwrap_err();
    assert!(matches!(e, Error::BadLoadStep { step: 3, .. }), "{e}");
    let e = problem.solve_history(&coulomb, &[], &SolverSettings::default(), None).unwrap_err();
    assert!(matches!(e, Error::BadLoadStep { .. }), "{e}");
    // By default every step's solution is kept: a history that cannot fit the memory budget is refused
    // before any step (a million steps abort the process otherwise), and so is one just over a small
    // budget. Keeping every k-th solution (and the last) fits it.
    let long = vec![LoadStep::new(s.approach, 0.0); 1_000_000];
    let e = problem.solve_history(&coulomb, &long, &SolverSettings::default(), None).unwrap_err();
    assert!(matches!(e, Error::MemoryBudget { .. }), "{e}");
    // A step keeping its solution: the solution, its record, its step and its series.
    let per_step = History::estimated_bytes(&problem, &long[..1], 1);
    let record = tribo::StepRecord::bytes(problem.n_multipliers()) as f64;
    assert!(per_step > Solution::estimated_bytes(&problem) as f64 + record);
    let budget = SolverSettings { memory_budget: 1 << 20, ..Default::default() };
    let fit = ((1 << 20) as f64 / per_step) as usize;
    let many = vec![LoadStep::new(s.approach, 0.0); fit + 1];
    let e = problem.solve_history(&coulomb, &many, &budget, None).unwrap_err();
    let needed = History::estimated_bytes(&problem, &many, 1);
    assert!(needed == (fit + 1) as f64 * per_step && needed > (1 << 20) as f64);
    assert!(matches!(e, Error::MemoryBudget { needed: n, .. } if n == needed), "{e}");
    assert!(problem.solve_history(&coulomb, &many[..fit], &budget, None).is_ok());
    let sparse = SolverSettings { keep_every: fit + 1, ..budget };
    let h = problem.solve_history(&coulomb, &many, &sparse, None).unwrap();
    assert_eq!((h.kept.as_slice(), h.records.len()), ([0, fit].as_slice(), fit + 1));
    // D21: the estimate counts what the finished history holds and what a reader takes from it at once.
    let (n, state) = (h.records.len(), size_of::<ContactState>());
    let records: usize = h.records.iter().map(|r| size_of::<tribo::StepRecord>() + r.states.len() * state).sum();
    let series: usize = h.series().iter().map(|(_, v)| 8 * v.len()).sum::<usize>() + 3 * 8 * n + 2 * 16 * n + n;
    let (at, x) = h.stick_slip_table();
    let held =
        (h.solutions.len() * Solution::estimated_bytes(&problem) + records + 2 * many.len() * size_of::<LoadStep>())
            + 8 * h.step_seconds.len()
            + series
            + 8 * (at.len() + x.len());
    let estimate = History::estimated_bytes(&problem, &many, fit + 1);
    assert!(estimate >= held as f64 && estimate <= 1.5 * held as f64, "{estimate} for {held} bytes held");
    // The estimate is the size of a solution's fields (a step's report adds a few hundred bytes).
    let h = problem.solve_history(&coulomb, &steps[..1], &SolverSettings::default(), None).unwrap();
    let sol = &h.solutions[0];
    let floats = sol.displacement.len()
        + 3 * sol.stress.len()
        + 3 * sol.nodal_stress.len()
        + sol.reactions.len()
        + sol.vectors().iter().map(|(_, v)| v.len()).sum::<usize>();
    let solution = Solution::estimated_bytes(&problem);
    assert!((8 * floats + 512..8 * floats + 4096).contains(&solution), "{solution} for {floats} floats");
}

/// `keep_every = k` keeps the solutions of steps 0, k, 2k, … and the last, each bit for bit that of the
/// history that keeps them all; the per-step series (forces, states, zones, estimates) cover every step
/// and equal the full history's. A history ended early keeps its last converged step.
#[test]
fn keep_every_keeps_what_is_asked() {
    let problem = hertz(0.04, 0.0);
    let approach = hertz_scene().approach;
    // Partial slip growing, then a jump to gross sliding at the last step.
    let shift = |k: usize| if k < 9 { 0.0004 * k as f64 } else { 0.03 };
    let steps: Vec<LoadStep> = (0..10).map(|k| LoadStep::new(approach, shift(k))).collect();
    let coulomb = Friction::Coulomb { mu: MU };
    let full = problem.solve_history(&coulomb, &steps, &SolverSettings::default(), None).unwrap();
    let every = SolverSettings { keep_every: 4, ..Default::default() };
    let sparse = problem.solve_history(&coulomb, &steps, &every, None).unwrap();
    assert_eq!((full.status, sparse.status), (SolveStatus::Converged, SolveStatus::Converged));
    assert_eq!(full.kept, (0..10).collect::<Vec<_>>());
    assert_eq!(sparse.kept, vec![0, 4, 8, 9]);
    assert_eq!(sparse.records, full.records);
    for ((name, a), (_, b)) in sparse.series().iter().zip(full.series().iter()) {
        if *name != "step_seconds" {
            assert!(a.iter().zip(b).all(|(x, y)| x == y || (x.is_nan() && y.is_nan())), "{name}");
        }
    }
    assert_eq!(sparse.stick_slip_boundaries(), full.stick_slip_boundaries());
    assert!(sparse.stick_slip_boundaries()[4].len() == 2, "{:?}", sparse.stick_slip_boundaries()[4]);
    // The same boundaries as one table, in step order.
    let (at, x) = sparse.stick_slip_table();
    let of = |k: usize| at.iter().zip(&x).filter(|(&s, _)| s == k).map(|(_, &v)| v).collect::<Vec<_>>();
    assert_eq!((0..10).map(of).collect::<Vec<_>>(), sparse.stick_slip_boundaries());
    assert!(at.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(sparse.gross_sliding(), [vec![false; 9], vec![true]].concat());
    for (sol, &k) in sparse.solutions.iter().zip(&sparse.kept) {
        assert_eq!(sol.displacement, full.solutions[k].displacement, "step {k}");
        assert_eq!(sparse.solution_of(k).map(|s| &s.lambda_t), Some(&full.solutions[k].lambda_t));
    }
    assert!(sparse.solution_of(5).is_none());
    // Stopped after step 5: steps 0 and 4 kept, and 5, the last converged.
    let mut stop = |p: &StepProgress| if p.step == 5 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) };
    let h = problem.solve_history(&coulomb, &steps, &every, Some(&mut stop)).unwrap();
    assert_eq!((h.kept.as_slice(), h.records.len(), h.ended_at), ([0, 4, 5].as_slice(), 6, Some(5)));
    assert_eq!(h.solutions[2].lambda_n, full.solutions[5].lambda_n);
    let e = problem.solve_history(&coulomb, &steps, &SolverSettings { keep_every: 0, ..Default::default() }, None);
    assert!(matches!(e, Err(Error::BadSetting { name: "keep_every", .. })), "{e:?}");
}

/// The QPs' path over a history: where `auto` solves one static Coulomb problem on the saddle-point
/// system, a history of many steps forms columns of H from the same factor of A instead (its later steps
/// cost a twentieth of the first by columns, half by the saddle-point system: `condensation::choose`);
/// the report says which, one step keeps the static choice, and the answers are those of the forced
/// saddle-point path.
#[test]
fn a_long_history_uses_columns_where_one_solve_uses_the_saddle_point_system() {
    let problem = hertz(0.0025, 0.0);
    let approach = hertz_scene().approach;
    let coulomb = Friction::Coulomb { mu: MU };
    let settings = SolverSettings::default();
    let fresh = || hertz(0.0025, 0.0);
    let static_path = fresh().solve(&coulomb, &settings, None).unwrap().report.condensation;
    assert_eq!(static_path, tribo::Condensation::Saddle, "the static choice on this mesh");
    let steps: Vec<LoadStep> = (0..11).map(|k| LoadStep::new(approach, 0.00045 * k as f64)).collect();
    let one = fresh().solve_history(&coulomb, &steps[..1], &settings, None).unwrap();
    assert_eq!(one.solutions[0].report.condensation, tribo::Condensation::Saddle);
    let auto = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    let forced = SolverSettings { condensation: tribo::Condensation::Saddle, ..settings };
    let saddle = fresh().solve_history(&coulomb, &steps, &forced, None).unwrap();
    assert_eq!((auto.status, saddle.status), (SolveStatus::Converged, SolveStatus::Converged));
    for (a, b) in auto.solutions.iter().zip(&saddle.solutions) {
        assert_eq!(
            (a.report.condensation, b.report.condensation),
            (tribo::Condensation::Columns, tribo::Condensation::Saddle)
        );
        // Each path stops its fixed point at a relative change of λ_n below fp_tol, so each answer lies
        // within fp_tol / (1 − L) of its step's fixed point (L ≤ 1/2, the contraction at μ = 0.3 measured
        // in `paths.rs`), and a step's error enters the next through its slip memory: the two differ by at
        // most 2 · 2 fp_tol per step, summed over the steps.
        let allowed = 4.0 * settings.fp.tol * steps.len() as f64 * b.normal_force.abs();
        let dn = (a.normal_force - b.normal_force).abs();
        let dt = (a.tangential_force - b.tangential_force).abs();
        assert!(dn <= allowed && dt <= allowed, "ΔN {dn:e}, ΔT {dt:e}, allowed {allowed:e}");
    }
}

/// A fretting cycle — drag to +s, then three times back to −s and again to +s — settles on a closed
/// hysteresis loop: the change from one cycle to the next falls at least tenfold per cycle (measured:
/// 5e-4 μP, then 8e-6 μP), the way back differs from the way out, and the obstacle does positive work
/// on the body per cycle (the energy friction dissipates). A nearly incompressible body (ν = 0.49, P1
/// displacements as measured) keeps normal and tangential responses nearly apart, so the loop settles fast.
/// It needs the stabilization to act on increments: stabilizing the totals instead made a loop drift by
/// 3e-4 μP per cycle (γ0 at half its bound; see `tribo::history`).
#[test]
fn fretting_loop_closes() {
    let mut spec = hertz_spec(hertz_scene().approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.material.poisson = 0.49;
    let problem = tribo::Problem::new(hertz_mesh(0.01), spec.formulation(tribo::Formulation::Displacement)).unwrap();
    let settings = SolverSettings::default();
    let (amp, n) = (0.003, 8);
    let mut path = vec![0.0];
    path.extend((1..=n).map(|k| amp * k as f64 / n as f64));
    for _ in 0..3 {
        path.extend((1..=2 * n).map(|k| amp - 2.0 * amp * k as f64 / (2 * n) as f64));
        path.extend((1..=2 * n).map(|k| -amp + 2.0 * amp * k as f64 / (2 * n) as f64));
    }
    let steps: Vec<LoadStep> = path.iter().map(|&x| LoadStep::new(hertz_scene().approach, x)).collect();
    let h = problem.solve_history(&Friction::Coulomb { mu: MU }, &steps, &settings, None).unwrap();
    assert_eq!(h.status, SolveStatus::Converged);
    let q = h.tangential_force();
    let mu_p = MU * h.normal_force()[n];
    let cycle = 4 * n;
    let retrace = (0..=cycle).fold(0.0_f64, |m, k| m.max((q[n + k] - q[n + cycle + k]).abs()));
    let retrace2 = (0..=cycle).fold(0.0_f64, |m, k| m.max((q[n + cycle + k] - q[n + 2 * cycle + k]).abs()));
    assert!(
        retrace2 < 0.1 * retrace,
        "the loop shakes down: max |ΔQ| / μP from cycle 1 to 2 {:e}, from 2 to 3 {:e}",
        retrace / mu_p,
        retrace2 / mu_p
    );
    // At s = 0 the way back and the way out have tangential forces of opposite signs.
    let (back, out) = (q[n + cycle + n], q[n + cycle + 3 * n]);
    assert!(back * out < 0.0, "hysteresis at s = 0: {back:e} and {out:e}");
    // The work of the obstacle over the last cycle, −∮ Q ds (trapezoids), is positive.
    let work: f64 = (n + cycle..n + 2 * cycle).map(|k| -0.5 * (q[k] + q[k + 1]) * (path[k + 1] - path[k])).sum();
    assert!(work > 0.0, "the cycle dissipates: {work:e}");
}

/// A step that does not converge ends the history with its status; the steps before it are kept, and
/// its last iterate is there to look at. (On this path the jump to gross sliding needs 7 fixed-point
/// iterations where the others need 5–6: a cap of 6 stops the history there.)
#[test]
fn a_failed_step_ends_the_history_and_keeps_the_others() {
    let problem = hertz(0.04, 0.0);
    let approach = hertz_scene().approach;
    let steps: Vec<LoadStep> = [0.0, 0.0005, 0.001, 0.03].iter().map(|&s| LoadStep::new(approach, s)).collect();
    let mut settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: MU };
    let full = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    assert_eq!(full.status, SolveStatus::Converged);
    let needed: Vec<usize> = full.solutions.iter().map(|s| s.report.iterations).collect();
    let last = *needed.last().unwrap();
    assert!(needed[..3].iter().all(|&n| n < last), "the jump needs the most iterations: {needed:?}");
    settings.fp.max_iter = last - 1;
    let capped = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    assert_eq!(capped.status, SolveStatus::MaxIterations);
    assert_eq!((capped.solutions.len(), capped.ended_at), (3, Some(3)));
    assert_eq!(capped.failed.as_ref().map(|s| s.report.status), Some(SolveStatus::MaxIterations));
    for (a, b) in capped.solutions.iter().zip(&full.solutions) {
        assert_eq!(a.lambda_t, b.lambda_t, "the steps before the failure are those of the full history");
    }
}

/// With a prescribed displacement (a block pressed down by its top, dragged on a flat foundation), one
/// step from rest is still the static solve (the lifting enters both alike, to round-off), and a history
/// that reaches the same position in steps converges with the lifting kept at every step.
#[test]
fn histories_keep_the_lifting_of_prescribed_displacements() {
    let mesh = tribo::rectangle([0.0, 2.0], [0.0, 1.0], 16, 8, tribo::Diagonal::Right).unwrap();
    let spec = tribo::ProblemSpec {
        material: tribo::Material { young: 1.0, poisson: 0.3 },
        model: tribo::Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![],
        supports: vec![tribo::Support::displacement("top", Some(0.0), Some(-0.01))],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: tribo::Obstacle { shape: tribo::ObstacleShape::Flat, approach: 0.0, shift: 0.004, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    let problem = tribo::Problem::new(mesh, spec).unwrap();
    let settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: MU };
    let fixed = problem.solve(&coulomb, &settings, None).unwrap();
    let one = problem.solve_history(&coulomb, &[LoadStep::new(0.0, 0.004)], &settings, None).unwrap();
    assert_eq!((fixed.report.status, one.status), (SolveStatus::Converged, SolveStatus::Converged));
    let step = &one.solutions[0];
    let sup = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let diff = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(diff(&step.displacement, &fixed.displacement) <= 1e-12 * sup(&fixed.displacement));
    assert!(diff(&step.lambda_t, &fixed.lambda_t) <= 1e-10 * sup(&fixed.lambda_n));
    assert!(fixed.normal_force > 0.0 && fixed.tangential_force != 0.0, "pressed and dragged");
    let steps: Vec<LoadStep> = (0..=4).map(|k| LoadStep::new(0.0, 0.001 * k as f64)).collect();
    let h = problem.solve_history(&coulomb, &steps, &settings, None).unwrap();
    assert_eq!(h.status, SolveStatus::Converged);
    // The press is held at every step: the normal force stays that of the pressed block.
    for s in &h.solutions {
        assert!((s.normal_force - fixed.normal_force).abs() < 1e-2 * fixed.normal_force);
    }
}
