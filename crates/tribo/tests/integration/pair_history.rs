//! Loading histories with several contact pairs (issue 41, item 4): a step moves the first pair's obstacle and the
//! prescribed displacements, a further pair's obstacle stays where the problem puts it (`solve/increment.rs`).
//!
//! * One step from rest is the static solve, bit for bit, every friction law.
//! * Frictionless, a history is a static solve per step (the answer does not depend on the path).
//! * A foundation that sticks everywhere (its own μ = 5) under the Hertz block is a clamp that moved the bottom by the
//!   foundation's own shift at the first step and holds it there: a punch pressed then dragged over it (partial slip,
//!   the stick zone shrinking as Q grows) is the one-pair history on the block clamped at that displacement, step by
//!   step (its left side moved to x = s_f: only its vertical motion is the contacts'); their vertical forces balance
//!   at every step; Newton to its tolerance, the fixed point to its QPs' accuracy.
//! * Two stacked bodies on a foundation pressed down step by step and released: the uniaxial patch at every step, on
//!   both pairs.
//! * A disc punch turned step by step about its centre over a foundation follows the punch shifted by −θR.

use tribo::*;

use tribo_testkit::{hertz_mesh, hertz_spec};

use crate::bodies_and_pairs::{patch_distance, stacked};
use crate::several_pairs::{block_mesh, foundation, punch, spec, sup, MATERIAL};

fn no_stabilization() -> SolverSettings {
    SolverSettings { stabilization: Stabilization::None, ..SolverSettings::default() }
}

fn converged(history: &History, what: &str) {
    assert_eq!(history.status, SolveStatus::Converged, "{what}: {:?}", history.failed.as_ref().map(|f| &f.report));
}

/// The half block pressed by the punch onto the foundation; the foundation with its own shift and μ.
fn punch_on_foundation(approach: f64, foundation_shift: f64, foundation_mu: Option<f64>) -> Problem {
    let mut two = spec("top", punch(approach));
    let ground = Obstacle { shift: foundation_shift, ..foundation() };
    two.pairs.push(PairSpec {
        mu: foundation_mu,
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        ..PairSpec::new("bottom", ground)
    });
    Problem::new(block_mesh(12), two).expect("two pairs")
}

#[test]
fn one_step_from_rest_is_the_static_solve() {
    for theta in [0.0, 0.5] {
        let settings = SolverSettings { stabilization: Stabilization::Fraction(theta), ..SolverSettings::default() };
        for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
            let mu = matches!(friction, Friction::Coulomb { .. }).then_some(0.5);
            let problem = punch_on_foundation(0.01, 0.001, mu);
            let fixed = problem.solve(&friction, &settings, None).unwrap();
            let history = problem.solve_history(&friction, &[LoadStep::new(0.01, 0.0)], &settings, None).unwrap();
            converged(&history, "one step");
            let step = &history.solutions[0];
            let what = format!("θ = {theta}, {friction:?}");
            assert_eq!(step.displacement, fixed.displacement, "{what}: u");
            assert_eq!((&step.lambda_n, &step.lambda_t), (&fixed.lambda_n, &fixed.lambda_t), "{what}: λ");
            assert_eq!(step.slip, fixed.slip, "{what}: slip");
            assert_eq!(history.pairs.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(), ["top", "bottom"]);
            let [p, q] = history.pair_forces(1);
            assert_eq!((p[0], q[0]), (fixed.pairs[1].normal_force, fixed.pairs[1].tangential_force), "{what}");
        }
    }
}

#[test]
fn a_frictionless_history_is_a_static_solve_per_step() {
    let settings = no_stabilization();
    let friction = Friction::Frictionless;
    let approaches = [0.004, 0.008, 0.012, 0.006];
    let steps: Vec<LoadStep> = approaches.iter().map(|&a| LoadStep::new(a, 0.0)).collect();
    let history = punch_on_foundation(0.004, 0.0, None).solve_history(&friction, &steps, &settings, None).unwrap();
    converged(&history, "frictionless");
    for (k, &a) in approaches.iter().enumerate() {
        let fixed = punch_on_foundation(a, 0.0, None).solve(&friction, &settings, None).unwrap();
        let step = &history.solutions[k];
        let du = step.displacement.iter().zip(&fixed.displacement).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        let dl = step.lambda_n.iter().zip(&fixed.lambda_n).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        eprintln!("approach {a}: |Δu| {du:.1e}, |Δλ_n| {dl:.1e}");
        assert!(du <= 1e-6 * sup(&fixed.displacement) && dl <= 1e-6 * sup(&fixed.lambda_n), "step {k}: {du:e} {dl:e}");
        // The punch's frames follow its circle: its force on the block is tilted by the first edge's angle to it.
        let [punch, ground] = [&step.pairs[0], &step.pairs[1]];
        let p = punch.contact_force[1];
        assert!((p + ground.contact_force[1]).abs() <= 1e-6 * p.abs(), "step {k}: held vertically by the two contacts");
        assert_eq!(history.pair_forces(1)[0][k], ground.normal_force);
    }
}

/// The Hertz block without its clamp, its left side moved to x = `s_f` (so that nothing floats but the vertical
/// motion, which the contacts hold), pressed by the cylinder from above onto a foundation of its own μ = 5 and its own
/// shift `s_f`, then dragged; against the block clamped at `(s_f, 0)` on its bottom.
///
/// Newton gives the one-pair answer to its tolerance (measured: 3e-13 in the static solve, 5e-9 over the history). The
/// fixed point gives it to the accuracy of its QPs, which clarabel solves on a body held by the contact (the active set
/// does not take the rigid motion's equality), its answers carrying `tol · κ(H)` of noise, below which the fixed point
/// stops (measured over this history: u 3e-6, P and Q 7e-7, λ_t 1.5e-4 of max λ_n at one dof next to the stick–slip
/// boundary; the one-pair fixed point and Newton agree to 2e-11). With the block floating along x too (no support on
/// its left side), its QPs determine it less well still (8.5e-5 in λ_t in the static solve; up to 5e-3 over the
/// history).
#[test]
fn a_foundation_that_sticks_everywhere_is_a_clamp_the_first_step_moved() {
    let s_f = 0.001;
    let base = || {
        let mut spec = hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        spec.clamped.clear();
        spec.support(Support::displacement("left", Some(s_f), None))
    };
    let ground =
        Obstacle { shape: ObstacleShape::Line { point: [0.0, -2.0], normal: [0.0, 1.0] }, shift: s_f, ..foundation() };
    let mut two = base();
    two.pairs.push(PairSpec {
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        ..PairSpec::new("bottom", ground).with_mu(5.0)
    });
    let two = Problem::new(hertz_mesh(0.01), two).unwrap();
    assert!(!two.dofs.floating.is_empty(), "held vertically by the contacts alone");
    let one =
        Problem::new(hertz_mesh(0.01), base().support(Support::displacement("bottom", Some(s_f), Some(0.0)))).unwrap();
    let friction = Friction::Coulomb { mu: 0.3 };
    let mut steps = vec![LoadStep::new(0.005, 0.0), LoadStep::new(0.01, 0.0)];
    steps.extend((1..=6).map(|k| LoadStep::new(0.01, 0.0004 * k as f64)));
    let h1 = one.solve_history(&friction, &steps, &no_stabilization(), None).unwrap();
    converged(&h1, "one pair");
    let newton = SolverSettings { coulomb: CoulombMethod::Newton, ..no_stabilization() };
    for settings in [no_stabilization(), newton] {
        let h2 = two.solve_history(&friction, &steps, &settings, None).unwrap();
        let what = format!("{:?}", settings.coulomb);
        converged(&h2, &what);
        let [p1, q1] = h1.pair_forces(0);
        let [p2, q2] = h2.pair_forces(0);
        for (k, (s2, s1)) in h2.solutions.iter().zip(&h1.solutions).enumerate() {
            let [top, bottom] = [&s2.pairs[0], &s2.pairs[1]];
            // The foundation touches and sticks everywhere, its side where the clamp holds the one-pair block's. (At the
            // corner on the left side, whose x the support prescribes, the foundation's λ_t is not unique: the support
            // takes what it does not. Newton finds it at the bound there, the fixed point inside.)
            let states = &s2.states[bottom.multipliers.clone()];
            let first = two.pairs()[1].contact.nodes[0];
            assert!(two.mesh.points()[first][0] == -2.0, "the foundation's first dof is at the left corner");
            assert!(states[1..].iter().all(|&s| s == ContactState::Stick), "{what} step {k}: {states:?}");
            assert_ne!(states[0], ContactState::Separation, "{what} step {k}");
            let side = &two.contact_displacements(&s2.displacement)[bottom.nodes.clone()];
            let off = side.iter().map(|u| (u[0] - s_f).abs().max(u[1].abs())).fold(0.0, f64::max);
            let du = s2.displacement.iter().zip(&s1.displacement).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            let top_t = &s2.lambda_t[top.multipliers.clone()];
            let dl = top_t.iter().zip(&s1.lambda_t).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            let (dp, dq) = ((p2[k] - p1[k]).abs() / p1[k], (q2[k] - q1[k]).abs() / p1[k]);
            eprintln!(
                "{what} step {k}: bottom off the clamp {off:.1e}, |Δu| {:.1e}, ΔP {dp:.1e}, ΔQ {dq:.1e}, |Δλ_t| {:.1e}",
                du / sup(&s1.displacement),
                dl / sup(&s1.lambda_n)
            );
            assert!(off <= 1e-7 * s_f, "{what} step {k}: the foundation's side is {off:e} off the clamp");
            // Newton to its stopping tolerance, fp_tol (relative, with a factor 10 for the norms compared); the fixed
            // point to the accuracy of its QPs (see above).
            let tol = if settings.coulomb == CoulombMethod::Newton { 10.0 * settings.fp.tol } else { 1e-5 };
            assert!(du <= tol * sup(&s1.displacement), "{what} step {k}: |Δu| {du:e}");
            assert!(dp <= tol && dq <= tol, "{what} step {k}: ΔP {dp:e}, ΔQ {dq:e}");
            if settings.coulomb == CoulombMethod::Newton {
                assert!(dl <= tol * sup(&s1.lambda_n), "{what} step {k}: |Δλ_t| {dl:e}");
            }
            // The contacts alone hold the block vertically: their forces balance along y.
            let sum = top.contact_force[1] + bottom.contact_force[1];
            assert!(sum.abs() <= 1e-6 * top.normal_force, "{what} step {k}: {sum:e}");
        }
        // Cattaneo–Mindlin under the punch: Q grows toward μP, the stick zone shrinks.
        let stick = h2.pair_extent(0, |s| s == ContactState::Stick);
        let width = |z: &[f64; 2]| z[1] - z[0];
        // (From the first drag on: the drag's first step turns the pressing's inward slip at one end of the zone.)
        for k in 2..steps.len() - 1 {
            assert!(
                q2[k].abs() > q2[k - 1].abs() && q2[k + 1].abs() < 0.3 * p2[k + 1],
                "{what} step {k}: Q {q2:?}, P {p2:?}"
            );
            assert!(width(&stick[k + 1]) <= width(&stick[k]), "{what} step {k}: stick zone {stick:?}");
        }
        assert!(width(&stick[steps.len() - 1]) < 0.5 * width(&stick[2]), "{what}: the stick zone shrank: {stick:?}");
        assert!(h2.pair_gross_sliding(1).iter().all(|&g| !g), "{what}: the foundation never slides");
    }
}

/// Two stacked blocks on a foundation (`bodies_and_pairs.rs`), the upper one's top pressed down step by step and
/// released: at every step the uniaxial patch, λ_n = δ_k / (h₁/M₁ + h₂/M₂) at every multiplier dof of both pairs,
/// frictionless and Coulomb (the foundation with its own μ), at γ0 = 0 and ½ bound.
#[test]
fn stacked_blocks_on_a_foundation_pressed_step_by_step() {
    let deltas = [0.005, 0.01, 0.003];
    let steps: Vec<LoadStep> = deltas.iter().map(|&d| LoadStep::new(0.0, 0.0).with_displacements(vec![-d])).collect();
    for (friction, mu) in [(Friction::Frictionless, None), (Friction::Coulomb { mu: 0.3 }, Some(0.5))] {
        let (problem, p) = stacked(true, MultiplierSpace::P1, mu);
        assert_eq!(problem.spec.prescribed_components().len(), 1);
        for theta in [0.0, 0.5] {
            let settings = SolverSettings { stabilization: Stabilization::Fraction(theta), ..Default::default() };
            let history = problem.solve_history(&friction, &steps, &settings, None).unwrap();
            let what = format!("θ = {theta}, {friction:?}");
            converged(&history, &what);
            for (k, (s, &d)) in history.solutions.iter().zip(&deltas).enumerate() {
                let p_k = p * d / 0.01;
                // As the static patch test (`bodies_and_pairs.rs`): round-off in λ_n, √qp_tol in a sticking λ_t, at
                // γ0 = 0 in the energy norm, where alone it is determined (`patch_distance`).
                let tol_t = if mu.is_some() { settings.qp.tol.sqrt() * p_k } else { 1e-10 * p_k };
                let kernel = theta == 0.0 && mu.is_some();
                if kernel {
                    let (apart, size) = patch_distance(&problem, s, settings.stabilization, p_k);
                    assert!(apart <= settings.qp.tol.sqrt() * size, "{what} step {k}: {apart:e} of {size:e}");
                }
                for (pair, r) in s.pairs.iter().enumerate() {
                    let worst = s.lambda_n[r.multipliers.clone()].iter().fold(0.0_f64, |m, l| m.max((l - p_k).abs()));
                    let slip = sup(&s.lambda_t[r.multipliers.clone()]);
                    let sticks = kernel || slip <= tol_t;
                    assert!(worst <= 1e-10 * p_k && sticks, "{what} step {k} pair {pair}: {worst:e} {slip:e}");
                    assert!((history.pair_forces(pair)[0][k] - 2.0 * p_k).abs() <= 2e-10 * p_k, "{what} step {k}");
                }
            }
        }
    }
}

/// A disc punch turned step by step about its centre on a block resting on a foundation (a roller on its left side,
/// the foundation with its own μ = 0.5): its surface slides by θR under the contact, so the history follows the one
/// that shifts it by −θR (t = −x on the top), at every step, to the second order of the contact half-angle (as for
/// one pair, `turned_obstacle.rs`). The punch's tractions and the displacement are compared (the foundation's λ_t at
/// the roller's corner node is not unique).
#[test]
fn a_punch_turned_step_by_step_over_a_foundation_follows_its_shift() {
    let (radius, approach, centre) = (1.0, 2e-3, [0.5, 1.5]);
    let problem = |turns: bool| {
        let grading = Grading { side: Side::Top, segment: [0.4, 0.6], h_min: 0.004, h_max: 0.1, growth: 0.15 };
        let mesh = graded_rectangle([0.0, 1.0], [0.0, 0.5], &grading).expect("a block");
        let disc = ObstacleShape::Disc { center: centre, radius };
        let mut spec =
            ProblemSpec::new(MATERIAL, "top").support(Support::roller("left")).approach(approach).obstacle(disc);
        if turns {
            spec = spec.obstacle_rotation(centre, 0.0);
        }
        spec.pairs.push(PairSpec::new("bottom", foundation()).with_mu(0.5));
        Problem::new(mesh, spec).expect("a punch on a foundation")
    };
    let angles = [0.0, 1e-4, 2e-4, 1e-4];
    let turned: Vec<LoadStep> = angles.iter().map(|&a| LoadStep::new(approach, 0.0).with_rotation(a)).collect();
    let shifted: Vec<LoadStep> = angles.iter().map(|&a| LoadStep::new(approach, -a * radius)).collect();
    let (coulomb, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let a = problem(true).solve_history(&coulomb, &turned, &settings, None).unwrap();
    let b = problem(false).solve_history(&coulomb, &shifted, &settings, None).unwrap();
    converged(&a, "turned");
    converged(&b, "shifted");
    for (k, (x, y)) in a.solutions.iter().zip(&b.solutions).enumerate() {
        let punch = x.pairs[0].multipliers.clone();
        let scale = sup(&x.lambda_n[punch.clone()]);
        let dl = x.lambda_n[punch.clone()].iter().zip(&y.lambda_n[punch.clone()]);
        let dl = dl.chain(x.lambda_t[punch.clone()].iter().zip(&y.lambda_t[punch])).map(|(p, q)| (p - q).abs());
        let dl = dl.fold(0.0, f64::max) / scale;
        let du = x.displacement.iter().zip(&y.displacement).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let half_angle = 0.5 * x.contact_width() / radius;
        eprintln!("step {k}: λ {dl:.1e}, u {:.1e} (half-angle² {:.1e})", du / sup(&y.displacement), half_angle.powi(2));
        assert!(dl < 2.0 * half_angle * half_angle, "step {k}: {dl:e}");
        assert!(du < 2.0 * half_angle * half_angle * sup(&y.displacement), "step {k}: {du:e}");
    }
    let q = a.pair_forces(0)[1].clone();
    assert!(q[1].abs() > 0.0 && q[1] * q[3] > 0.0 && q[2].abs() > q[3].abs(), "the punch's friction follows: {q:?}");
}
