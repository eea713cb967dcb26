//! The a posteriori estimate: what it sees, and how it tracks the true error. (That it vanishes where the
//! discrete solution is exact is a patch test, `patch::the_estimate_vanishes_on_constant_strain_states`.)

use tribo::*;

/// A coarse mesh where no node touches: a narrow obstacle dips between two nodes of Γ_C. The solve sees
/// no contact at all (λ = 0, no nodal penetration), but the estimate's contact part is positive, and it
/// sits on the triangle under the dip, so an adaptive loop refines there first.
#[test]
fn an_obstacle_penetrating_between_nodes_is_seen() {
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 4, 4, Diagonal::Right).expect("valid");
    let spec = ProblemSpec {
        material: Material { young: 1.0, poisson: 0.3 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["bottom".into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "top".into(),
        obstacle: Obstacle {
            shape: ObstacleShape::Parabola { center: 0.375, radius: 0.01 },
            approach: 1e-3,
            shift: 0.0,
            rotation: None,
        },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    let problem = Problem::new(mesh, spec).expect("valid");
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert!(sol.lambda_n.iter().all(|&l| l == 0.0) && sol.max_penetration == 0.0, "no node touches");
    let est = sol.report.estimate;
    assert!(est.contact > 0.0 && est.bulk == 0.0 && est.gamma_c == 0.0, "{est:?}");
    let worst = (0..problem.mesh.n_triangles()).max_by(|&a, &b| sol.estimator[a].total_cmp(&sol.estimator[b]));
    let worst = worst.expect("triangles");
    let xs = problem.mesh.vertices(worst).map(|p| p[0]);
    let (lo, hi) = (xs.iter().copied().fold(f64::INFINITY, f64::min), xs.iter().copied().fold(0.0, f64::max));
    assert!(lo <= 0.375 && 0.375 <= hi, "the largest η_K is under the dip: triangle {worst} spans x in [{lo}, {hi}]");
    // With the obstacle withdrawn, nothing is left to see.
    let mut far = problem.spec.clone();
    far.obstacle.approach = -1e-3;
    let problem = Problem::new(problem.mesh.clone(), far).expect("valid");
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert_eq!(sol.report.estimate.total, 0.0);
}

/// On the Hertz scene refined by halving h_min and the growth together (the family whose λ_n error keeps
/// falling: at a fixed growth it floors, issue 17), the traction estimate ζ / ‖λ_H‖ bounds the L2 error
/// of λ_n against the plane-strain Hertz pressure (its effectivity index is at least 1; measured 3.2 to
/// 11.7, the estimate falling as h^0.6 where the error falls as h^1.3), and both fall at every step.
#[test]
fn the_traction_estimate_bounds_the_hertz_error_and_falls_with_it() {
    let s = tribo_testkit::hertz_scene();
    let (mut estimates, mut errors) = (Vec::new(), Vec::new());
    for (h_min, growth) in [(0.04, 0.6), (0.02, 0.3), (0.01, 0.15), (0.005, 0.075)] {
        let grading = Grading { side: Side::Top, segment: s.segment, h_min, h_max: s.h_max, growth };
        let mesh = graded_rectangle(s.x, s.y, &grading).expect("valid grading");
        let spec = tribo_testkit::hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).expect("valid");
        let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
        estimates.push(sol.report.estimate.traction_relative);
        errors.push(tribo_testkit::hertz_l2_error(&problem, &sol));
    }
    assert!(estimates.iter().zip(&errors).all(|(e, t)| e >= t), "estimates {estimates:?} errors {errors:?}");
    let falls = |v: &[f64]| v.windows(2).all(|w| w[1] < w[0]);
    assert!(falls(&estimates) && falls(&errors), "estimates {estimates:?} errors {errors:?}");
}

/// The classic method (γ0 = 0) with T_H four times finer than the FE edges checkerboards (study 1a). The
/// estimate must flag it, not hide it: the Γ_C residual λ_H + σ_h n sees the oscillation, and the
/// relative estimate divides by the smaller of ‖λ_H‖ and ‖σ_h n‖, so the oscillation cannot inflate its
/// own denominator. On the same mesh, the estimate of the checkerboard bounds its error and is well above
/// the estimate of the stabilized solve.
#[test]
fn the_estimate_flags_the_checkerboard_of_the_classic_method() {
    let s = tribo_testkit::hertz_scene();
    let problem =
        tribo_testkit::hertz_problem(0.01, s.approach, 0.0, MultiplierPoints::RatioToFe(0.25), MultiplierSpace::P1);
    let mut out = Vec::new();
    for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
        let settings = SolverSettings { stabilization, ..Default::default() };
        let sol = problem.solve(&Friction::Frictionless, &settings, None).expect("solves");
        out.push((sol.report.estimate.traction_relative, tribo_testkit::hertz_l2_error(&problem, &sol)));
    }
    let [(classic, classic_error), (stabilized, stabilized_error)] = out[..] else { unreachable!() };
    assert!(classic_error > 5.0 * stabilized_error, "the classic method checkerboards: {out:?}");
    assert!(classic >= classic_error && stabilized >= stabilized_error, "the estimates bound the errors: {out:?}");
    assert!(classic > 2.0 * stabilized, "the checkerboard shows in the estimate: {out:?}");
}

/// The pieces of the hierarchical traction estimate (`Problem::solve_enriched`,
/// `adapt::multiplier_difference`, `adapt::near_contact`): the difference of a multiplier from itself is
/// 0 and is symmetric; the whole mesh enriched is four times the triangles with T_H halved, and its answer
/// is closer to Hertz; a strip holds only triangles near the contact zone, and none when nothing touches.
#[test]
fn the_enriched_problem_halves_h_and_h_and_its_answer_is_closer() {
    use tribo::adapt::{multiplier_difference, near_contact};
    let problem = tribo_testkit::hertz_problem(0.04, 0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let (friction, settings) = (Friction::Frictionless, SolverSettings::default());
    let sol = problem.solve(&friction, &settings, None).expect("solves");
    let (zero, norm) = multiplier_difference(&problem, &sol, &problem, &sol);
    assert!(zero == 0.0 && norm > 0.0);

    let all: Vec<usize> = (0..problem.mesh.n_triangles()).collect();
    assert_eq!(near_contact(&problem, &sol, f64::INFINITY), all);
    let (fine, fsol) = problem.solve_enriched(&sol, &all, &friction, &settings).expect("solves");
    assert_eq!(fsol.report.status, SolveStatus::Converged);
    assert_eq!(fine.mesh.n_triangles(), 4 * problem.mesh.n_triangles());
    // T_H is halved where contact is or may be (it stays as it was where the body is surely apart, as
    // in the adaptive loop): every coarse point kept, every segment under the contact zone split.
    let (coarse_xi, fine_xi) = (&problem.multipliers.xi, &fine.multipliers.xi);
    assert!(coarse_xi.iter().all(|x| fine_xi.contains(x)) && fine_xi.len() > coarse_xi.len());
    for w in coarse_xi.windows(2).filter(|w| w[1] > -0.12 && w[0] < 0.12) {
        assert!(fine_xi.contains(&(0.5 * (w[0] + w[1]))), "segment {w:?} is not halved");
    }
    let (d, _) = multiplier_difference(&problem, &sol, &fine, &fsol);
    let (back, _) = multiplier_difference(&fine, &fsol, &problem, &sol);
    assert!(d > 0.0 && (d - back).abs() <= 1e-12 * d, "{d} {back}");
    let (coarse_error, fine_error) =
        (tribo_testkit::hertz_l2_error(&problem, &sol), tribo_testkit::hertz_l2_error(&fine, &fsol));
    assert!(fine_error < coarse_error, "enriched {fine_error} against {coarse_error}");

    let strip = near_contact(&problem, &sol, 0.1);
    assert!(!strip.is_empty() && strip.len() < all.len() / 2, "{} of {}", strip.len(), all.len());
    let (lo, hi) = (-0.3, 0.3); // the contact half-width is about 0.1, 0.1 beyond plus one cell of 0.04
    for &t in &strip {
        assert!(problem.mesh.vertices(t).iter().any(|p| p[0] > lo && p[0] < hi && p[1] > -0.3), "triangle {t}");
    }
    let (strip_fine, _) = problem.solve_enriched(&sol, &strip, &friction, &settings).expect("solves");
    assert!(strip_fine.n_free < fine.n_free && strip_fine.n_free > problem.n_free);

    let mut apart = problem.spec.clone();
    apart.obstacle.approach = -0.01;
    let apart = Problem::new(problem.mesh.clone(), apart).expect("valid");
    let none = apart.solve(&friction, &settings, None).expect("solves");
    assert!(near_contact(&apart, &none, f64::INFINITY).is_empty());
}

/// The hierarchical estimate (`Problem::estimate_hierarchical`, 1.5 ‖λ_H − λ_f‖) on the graded Hertz family
/// of `the_traction_estimate_bounds_the_hertz_error_and_falls_with_it`, against the plane-strain Hertz
/// pressure: its effectivity stays within [1, 2] on every mesh (issue 36's target; measured 1.46, 1.21,
/// 1.13), where the bound's grows from 5.8 to 11.9 over the same meshes. The enriched problem is the whole mesh
/// bisected and the strip along the zone again (5.4 times the unknowns here).
#[test]
fn the_hierarchical_estimate_is_within_twice_the_hertz_error() {
    let s = tribo_testkit::hertz_scene();
    let settings = SolverSettings::default();
    for (h_min, growth) in [(0.02, 0.3), (0.01, 0.15), (0.005, 0.075)] {
        let grading = Grading { side: Side::Top, segment: s.segment, h_min, h_max: s.h_max, growth };
        let mesh = graded_rectangle(s.x, s.y, &grading).expect("valid grading");
        let spec = tribo_testkit::hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).expect("valid");
        let sol = problem.solve(&Friction::Frictionless, &settings, None).expect("solves");
        let h = problem.estimate_hierarchical(&sol, &Friction::Frictionless, &settings).expect("estimates");
        let error = tribo_testkit::hertz_l2_error(&problem, &sol);
        let (effectivity, bound) = (h.relative / error, sol.report.estimate.traction_relative / error);
        println!(
            "h_min {h_min}: error {error:.3e}, hierarchical {effectivity:.3}, bound {bound:.2}, {} / {} unknowns",
            h.unknowns, problem.n_free
        );
        assert_eq!(h.status, SolveStatus::Converged);
        assert!(h.end_reductions.is_empty(), "the Hertz zone reaches no end of Γ_C");
        assert!((h.estimate - 1.5 * h.difference).abs() <= 1e-12 * h.estimate && h.relative == h.estimate / h.norm);
        assert!((1.0..=2.0).contains(&effectivity), "h_min {h_min}: effectivity {effectivity} (bound {bound})");
        // The whole mesh bisected (about 4 times the unknowns), the strip along the zone again.
        assert!(h.unknowns > 4 * problem.n_free && h.unknowns < 16 * problem.n_free, "{} unknowns", h.unknowns);
    }
}

/// A Tresca threshold given per multiplier dof is carried to the enriched T_H as the function it defines:
/// the same threshold given uniformly and per dof gives the same estimate; nothing touching gives a
/// zero difference over the whole mesh enriched.
#[test]
fn a_per_dof_threshold_is_estimated_as_its_function() {
    let problem =
        tribo_testkit::hertz_problem(0.02, 0.01, 0.002, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let settings = SolverSettings::default();
    let uniform = Friction::Tresca(Threshold::Uniform(0.5));
    let per_dof = Friction::Tresca(Threshold::PerDof(vec![0.5; problem.n_multipliers()]));
    let estimates: Vec<f64> = [uniform, per_dof]
        .iter()
        .map(|f| {
            let sol = problem.solve(f, &settings, None).expect("solves");
            problem.estimate_hierarchical(&sol, f, &settings).expect("estimates").estimate
        })
        .collect();
    assert!(estimates[0] > 0.0 && (estimates[0] - estimates[1]).abs() <= 1e-9 * estimates[0], "{estimates:?}");
    // The same where the zone reaches the ends of Γ_C, whose second enrichment carries the threshold again.
    let (block, _) = tribo_testkit::block_problem(16, 4);
    let threshold = 0.3 * block.spec.material.young * block.spec.obstacle.approach;
    let per_dof = vec![threshold; block.n_multipliers()];
    let estimates: Vec<(f64, Vec<f64>)> = [Threshold::Uniform(threshold), Threshold::PerDof(per_dof)]
        .into_iter()
        .map(|t| {
            let f = Friction::Tresca(t);
            let sol = block.solve(&f, &settings, None).expect("solves");
            let h = block.estimate_hierarchical(&sol, &f, &settings).expect("estimates");
            (h.estimate, h.end_reductions)
        })
        .collect();
    // (Measured: one end's reduction above 1 on this coarse mesh, so the estimate is infinite: it says
    // nothing, and the adaptive stop reads the bound.)
    let [(a, qa), (b, qb)] = &estimates[..] else { panic!("two estimates") };
    assert_eq!(qa.len(), 2, "both ends touch: {estimates:?}");
    let close = |x: f64, y: f64| x == y || (x - y).abs() <= 1e-9 * x.abs();
    assert!(close(*a, *b) && qa.iter().zip(qb).all(|(x, y)| close(*x, *y)), "{estimates:?}");

    let mut apart = problem.spec.clone();
    apart.obstacle.approach = -0.01;
    let apart = Problem::new(problem.mesh.clone(), apart).expect("valid");
    let none = apart.solve(&Friction::Frictionless, &settings, None).expect("solves");
    let h = apart.estimate_hierarchical(&none, &Friction::Frictionless, &settings).expect("estimates");
    assert!(h.difference == 0.0 && h.relative.is_nan() && h.unknowns > 3 * apart.n_free, "{h:?}");
}

/// Where the contact zone reaches an end of Γ_C, λ need not vanish there (issue 36): on the block (Coulomb,
/// the whole bottom in contact and slipping at its corners) the traction is singular at the corners, a
/// bisection removes only about 14 % of the error there, and `2 ‖λ_H − λ_f‖` of the strip bisected once was 0.85–0.99
/// times the true error on every level (the changelog; `1.5 ‖λ_H − λ_f‖` of the enrichment since, 0.96–1.02: study 12).
/// The reduction is measured at each touching end instead of assumed (studies 14 and 15, `docs/error_bars.md`): both
/// ends measured (above the ⅓ the rest of Γ_C assumes), and the estimate within [1, 2] times the true error against
/// an adaptive reference of 60–120k unknowns (measured: 1.85 times it, where the bound is 1.91 times; reductions 0.75
/// and 0.73; through the answer enriched once at the ends, until 2026-12-01, 2.5 times).
#[test]
fn at_the_ends_of_gamma_c_in_contact_the_reduction_is_measured() {
    use tribo::adapt::multiplier_difference;
    let (coarse, mu) = tribo_testkit::block_problem(8, 2);
    let (friction, settings) = (Friction::Coulomb { mu }, SolverSettings::default());
    let adapt = AdaptSettings { tol: 1e-9, max_unknowns: 120_000, stop_on: StopOn::Bound, ..Default::default() };
    let reference = coarse.solve_adaptive(&friction, &settings, &adapt, None).expect("adapts");
    let level = reference.levels.iter().find(|l| l.unknowns >= 1_000).expect("a level of 1000 unknowns");
    let problem = coarse.on_level(level).expect("the level's problem");
    let sol = problem.solve(&friction, &settings, None).expect("solves");
    let (error, norm) = multiplier_difference(&problem, &sol, &reference.problem, &reference.solution);
    let truth = error / norm;
    let h = problem.estimate_hierarchical(&sol, &friction, &settings).expect("estimates");
    println!(
        "{} unknowns: true {truth:.3e}, hierarchical {:.2} (1.5 d: {:.2}), bound {:.2}, reductions {:?}",
        problem.n_free,
        h.relative / truth,
        1.5 * h.difference / h.norm / truth,
        sol.report.estimate.traction_relative / truth,
        h.end_reductions
    );
    assert_eq!(h.end_reductions.len(), 2);
    let assumed = tribo::adapt::enriched::SATURATION;
    assert!(h.end_reductions.iter().all(|q| (assumed..1.0).contains(q)), "{:?}", h.end_reductions);
    assert!(h.relative >= truth && h.relative <= 2.0 * truth, "{} against {truth}", h.relative);
}

/// On a uniform mesh the first (global) enrichment's difference at the block's singular corners is a smaller part of
/// the error than a local enrichment's, so the reduction read between the first two enrichments overstated the true one
/// (0.88 where the first enrichment's true reduction is 0.78 and a local one's 0.74, study 15b) and the estimate was
/// 3.6–5.4 times the truth; read between the second and third, both local and alike, it is the local one's (0.742, as
/// on adaptive levels).
#[test]
fn on_a_uniform_mesh_the_reduction_is_read_between_two_local_enrichments() {
    let (block, mu) = tribo_testkit::block_problem(32, 8);
    let (friction, settings) = (Friction::Coulomb { mu }, SolverSettings::default());
    let sol = block.solve(&friction, &settings, None).expect("solves");
    let h = block.estimate_hierarchical(&sol, &friction, &settings).expect("estimates");
    assert_eq!(h.end_reductions.len(), 2, "{:?}", h.end_reductions);
    // Measured 0.742 at x = 0 and 0.777 at x = 4 (0.882 and 0.889 between the first two).
    assert!(h.end_reductions.iter().all(|q| (0.7..0.8).contains(q)), "{:?}", h.end_reductions);
    // Measured 1.03 times the bound (2.06 times with the reduction between the first two).
    assert!(h.relative.is_finite() && h.relative < 1.2 * sol.report.estimate.traction_relative, "{h:?}");
}
