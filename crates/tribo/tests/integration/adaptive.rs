//! Adaptive refinement: from a coarse uniform mesh that knows nothing of where contact will be, the loop
//! finds the contact zone and stops at the asked accuracy; bad adaptive settings are typed errors.

use proptest::prelude::*;
use tribo::*;

const CENTER: f64 = 0.3;

/// The Hertz block on an 8 × 4 uniform mesh (h = 0.5) with the cylinder off the centre, between two
/// nodes of Γ_C: the Hertz zone (half-width about 0.07) holds no node, so the first solve sees no contact.
fn off_centre_problem() -> Problem {
    let s = tribo_testkit::hertz_scene();
    let mesh = rectangle(s.x, s.y, 8, 4, Diagonal::Right).expect("valid");
    let mut spec = tribo_testkit::hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle.shape = ObstacleShape::Circle { center: CENTER, radius: s.radius };
    Problem::new(mesh, spec).expect("valid")
}

/// Relative L2 error of λ_n against the Hertz pressure of the computed force, centred at `CENTER`.
fn hertz_error(problem: &Problem, sol: &Solution) -> f64 {
    let (p, a) = tribo_testkit::hertz_pressure(sol.normal_force);
    let mut breaks: Vec<f64> = problem.multipliers.xi.clone();
    breaks.extend([CENTER - a, CENTER + a]);
    breaks.sort_by(f64::total_cmp);
    let (gx, gw) = tribo_testkit::gauss8();
    let (mut num, mut den) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (h, m) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for (x, wt) in gx.iter().zip(&gw) {
            let xi = m + h * x;
            let exact = p(xi - CENTER);
            num += wt * h * (problem.multipliers.evaluate(&sol.lambda_n, xi) - exact).powi(2);
            den += wt * h * exact * exact;
        }
    }
    (num / den).sqrt()
}

#[test]
fn the_loop_finds_an_unknown_contact_zone() {
    let problem = off_centre_problem();
    let first = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert!(first.normal_force == 0.0 && first.report.estimate.contact > 0.0, "no node touches at first");
    // The bound: above the true error (the default stop reads the sharper hierarchical estimate, not a bound).
    let adapt = AdaptSettings { tol: 0.05, max_unknowns: 60_000, stop_on: StopOn::Bound, ..Default::default() };
    let mut seen = Vec::new();
    let mut observer = |level: &Level| {
        seen.push(level.unknowns);
        std::ops::ControlFlow::Continue(())
    };
    let out = problem
        .solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, Some(&mut observer))
        .expect("adapts");
    let last = out.levels.last().expect("levels");
    assert_eq!(seen.len(), out.levels.len(), "the observer hears every level");
    assert_eq!(out.stop, AdaptStop::Tolerance, "{:?}", out.levels);
    assert!(last.relative <= adapt.tol && out.solution.report.status == SolveStatus::Converged);
    let err = hertz_error(&out.problem, &out.solution);
    // The estimate bounds the true error (its effectivity on Hertz is above 1, see the estimator's
    // tests), so the answer meets the asked accuracy.
    assert!(err <= last.relative && err <= adapt.tol, "true error {err}, estimate {}", last.relative);
    // The mesh is fine where the contact is and stays coarse far from it.
    let mesh = &out.problem.mesh;
    let (near, far): (Vec<usize>, Vec<usize>) = (0..mesh.n_triangles()).partition(|&t| {
        let c = mesh.vertices(t).iter().fold([0.0, 0.0], |s, p| [s[0] + p[0] / 3.0, s[1] + p[1] / 3.0]);
        (c[0] - CENTER).hypot(c[1]) < 0.5
    });
    let smallest = |ts: &[usize]| ts.iter().map(|&t| mesh.diameter(t)).fold(f64::INFINITY, f64::min);
    assert!(smallest(&near) * 8.0 < smallest(&far), "near {} far {}", smallest(&near), smallest(&far));
    assert!(out.levels.windows(2).all(|w| w[1].unknowns > w[0].unknowns), "every level refines");
}

#[test]
fn a_level_beyond_max_unknowns_is_not_made() {
    let problem = off_centre_problem();
    let adapt = AdaptSettings { tol: 1e-6, max_unknowns: 2_000, ..Default::default() };
    let out =
        problem.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    assert_eq!(out.stop, AdaptStop::MaxUnknowns);
    assert!(out.levels.iter().all(|l| l.unknowns <= 2_000) && out.levels.len() > 1);
    assert_eq!(out.problem.n_free, out.levels.last().map_or(0, |l| l.unknowns));
}

/// A Tresca threshold acts where nothing touches, so T_H follows the FE edges of Γ_C wherever it is positive, not
/// only where contact is or may be (Coulomb's saving): kept coarse under refined FE edges, the bound of Hertz with a
/// uniform threshold grew from 5.6e-2 at 15k unknowns to 0.46 at 82k, the multipliers held at 551.
#[test]
fn where_a_tresca_threshold_acts_the_multipliers_follow_the_fe_edges_though_nothing_touches() {
    let adapt = AdaptSettings { tol: 1e-6, max_unknowns: 10_000, stop_on: StopOn::Bound, ..Default::default() };
    let run = |friction: &Friction| {
        let coarse = tribo_testkit::hertz_coarse(0.0, friction, MultiplierSpace::P1).expect("valid");
        coarse.solve_adaptive(friction, &SolverSettings::default(), &adapt, None).expect("adapts")
    };
    let tresca = run(&Friction::Tresca(Threshold::Uniform(tribo_testkit::TRESCA_THRESHOLD)));
    assert_eq!(tresca.stop, AdaptStop::MaxUnknowns);
    assert_eq!(tresca.problem.multipliers.xi, tresca.problem.contact.node_xi, "T_H on the FE edges of Γ_C");
    let coulomb = run(&Friction::Coulomb { mu: 0.3 });
    let (t_h, fe) = (coulomb.problem.multipliers.xi.len(), coulomb.problem.contact.node_xi.len());
    assert!(t_h < fe, "Coulomb keeps T_H coarse where the body is surely apart: {t_h} points, {fe} FE nodes");
    // A threshold per dof, positive on the three middle dofs of the 9 (abscissae within 1 of the middle), zero
    // elsewhere: T_H follows the FE edges where it is positive, and is kept where it is zero and the body apart.
    let hat: Vec<f64> = (0..9).map(|k| if (3..=5).contains(&k) { 1.0 } else { 0.0 }).collect();
    let held = run(&Friction::Tresca(Threshold::PerDof(hat)));
    let (xi, nodes) = (&held.problem.multipliers.xi, &held.problem.contact.node_xi);
    let middle = 0.5 * (nodes[0] + nodes[nodes.len() - 1]);
    let on_t_h = |x: f64| xi.iter().any(|p| (p - x).abs() < 1e-9);
    assert!(nodes.iter().filter(|x| (*x - middle).abs() <= 1.0).all(|&x| on_t_h(x)), "T_H on the FE edges held");
    assert!(xi.len() < nodes.len(), "T_H kept where the threshold is 0: {} points, {} FE nodes", xi.len(), nodes.len());
}

/// A Tresca threshold per dof is the W_H function of the first T_H: every level of a history (and its enriched
/// problems, for the hierarchical stop) solves with it carried to the level's dofs, not refused for its length.
#[test]
fn a_threshold_per_dof_is_carried_to_every_level_of_a_history() {
    let f = Friction::Tresca(Threshold::Uniform(1.0));
    let problem = tribo_testkit::hertz_coarse(0.0, &f, MultiplierSpace::P1).expect("valid");
    let hat: Vec<f64> = (0..9).map(|k| if k == 4 { 2.0 } else { 0.0 }).collect();
    let steps: Vec<LoadStep> = [0.002, 0.004].iter().map(|&s| LoadStep::new(0.01, s)).collect();
    let adapt = AdaptSettings { tol: 0.1, max_unknowns: 20_000, ..Default::default() };
    let settings = SolverSettings::default();
    let out = (problem.solve_history_adaptive(
        &Friction::Tresca(Threshold::PerDof(hat)),
        &steps,
        &settings,
        &adapt,
        &[],
        None,
    ))
    .expect("adapts");
    assert_eq!(out.history.status, SolveStatus::Converged);
    assert!(out.levels.len() > 3, "{} levels", out.levels.len());
    // The hat of height 2 on the middle dof, 0 one coarse cell (0.5) away: at the dofs of the last level.
    let s = &out.history.solutions[1];
    let middle = 0.5 * (s.multiplier_abscissae[0] + s.multiplier_abscissae[s.multiplier_abscissae.len() - 1]);
    for (x, g) in s.multiplier_abscissae.iter().zip(&s.friction_threshold) {
        let hat = 2.0 * (1.0 - (x - middle).abs() / 0.5).max(0.0);
        assert!((g - hat).abs() < 1e-12, "threshold {g} at {x}, the hat {hat}");
    }
}

/// `Problem::on_level` solves a level of a run of that problem again, and refuses with a typed error (no
/// panic) a level of another problem on the same body name, and a level whose body ranges were edited.
#[test]
fn a_level_of_another_problem_or_edited_is_refused() {
    let problem = off_centre_problem();
    let adapt = AdaptSettings { tol: 1e-6, max_unknowns: 2_000, ..Default::default() };
    let out =
        problem.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    let last = out.levels.last().expect("levels");
    assert_eq!(problem.on_level(last).expect("its own level").n_free, last.unknowns);
    let s = tribo_testkit::hertz_scene();
    let spec = tribo_testkit::hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let other = Problem::new(rectangle(s.x, s.y, 10, 4, Diagonal::Right).expect("valid"), spec).expect("valid");
    let refused = |p: &Problem, level: &Level| matches!(p.on_level(level), Err(Error::BadMaterial { .. }));
    assert!(refused(&other, last), "a level of another mesh of the same body");
    let edits: [fn(&mut Level); 4] = [
        |l| l.bodies[0].nodes.end += 1,
        |l| l.bodies[0].triangles.end -= 1,
        |l| l.bodies[0].triangles.start = 1,
        |l| l.mesh = rectangle([0.0, 1.0], [0.0, 1.0], 8, 4, Diagonal::Right).expect("valid"),
    ];
    for (k, edit) in edits.iter().enumerate() {
        let mut level = last.clone();
        edit(&mut level);
        assert!(refused(&problem, &level), "edit {k}");
    }
}

#[test]
fn bad_adaptive_settings_are_typed_errors() {
    let problem = off_centre_problem();
    let cases = [
        ("adapt_tol", AdaptSettings { tol: 0.0, ..Default::default() }),
        ("adapt_tol", AdaptSettings { tol: f64::NAN, ..Default::default() }),
        ("adapt_theta", AdaptSettings { theta: 0.0, ..Default::default() }),
        ("adapt_theta", AdaptSettings { theta: 1.5, ..Default::default() }),
        ("adapt_max_levels", AdaptSettings { max_levels: 0, ..Default::default() }),
        ("adapt_algebraic", AdaptSettings { algebraic: 1.0, ..Default::default() }),
        ("adapt_algebraic", AdaptSettings { algebraic: -0.1, ..Default::default() }),
        ("adapt_max_unknowns", AdaptSettings { max_unknowns: 10, ..Default::default() }),
    ];
    for (name, adapt) in cases {
        match problem.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None) {
            Err(Error::BadSetting { name: n, .. }) => assert_eq!(n, name),
            other => panic!("{name}: {other:?}"),
        }
    }
}

/// Stopping on the hierarchical estimate (issue 36): from the 8 × 4 mesh that sees no contact at first,
/// `tol` = 5 % and 2 % end on the tolerance with a true error (against the Hertz pressure) within
/// [tol / 3, tol], as the issue asks, where the bound ends 10 to 30 times below tol with several times the
/// unknowns. The answer carries the estimate it stopped on (the smaller of the hierarchical estimate and
/// the bound, or of the calibrated bound and the bound on the level after); a level after an estimated one whose
/// ratio was below 1 carries the calibrated bound; a level with neither carries NaN and reads the bound.
#[test]
fn stopping_on_the_hierarchical_estimate_ends_near_the_asked_accuracy() {
    let problem = off_centre_problem();
    let (friction, settings) = (Friction::Frictionless, SolverSettings::default());
    for tol in [0.05, 0.02] {
        let adapt = AdaptSettings { tol, stop_on: StopOn::Hierarchical, max_unknowns: 200_000, ..Default::default() };
        let sharp = problem.solve_adaptive(&friction, &settings, &adapt, None).expect("adapts");
        let estimate = sharp.solution.report.estimate;
        let last = sharp.levels.last().expect("levels");
        assert_eq!(sharp.stop, AdaptStop::Tolerance);
        // The answer carries the hierarchical estimate, or the calibrated bound of the level after an estimated one.
        let relative = estimate
            .traction_hierarchical_relative
            .or(estimate.traction_calibrated_relative)
            .expect("the answer carries a sharp estimate");
        // The stop reads the smaller of it and the bound.
        assert_eq!(last.relative, relative.min(estimate.traction_relative));
        assert!(last.relative <= tol);
        assert_eq!(last.estimate, estimate);
        // Not on every level after the first it computed (that one, at the first level with 10 dofs in contact).
        let first = sharp.levels.iter().position(|l| l.estimate.traction_hierarchical_relative.is_some());
        let after = &sharp.levels[first.expect("estimated") + 1..];
        assert!(after.iter().any(|l| l.estimate.traction_hierarchical_relative.is_none()), "computed where needed");
        for (k, level) in sharp.levels.iter().enumerate() {
            let (e, bound) = (&level.estimate, level.estimate.traction_relative);
            // Conversely, the level after one estimated below its bound carries the calibrated bound.
            let calibrating = k.checked_sub(1).map(|j| &sharp.levels[j]).is_some_and(|b| {
                b.estimate.traction_hierarchical_relative.is_some() && b.relative < b.estimate.traction_relative
            });
            assert_eq!(e.traction_calibrated_relative.is_some(), calibrating, "level {k}");
            match (e.traction_hierarchical_relative, e.traction_calibrated_relative) {
                (Some(h), _) => assert_eq!(level.relative, h.min(bound)),
                (None, Some(c)) => {
                    // The bound times the ratio of the level before, where that level was estimated below its bound.
                    let before = &sharp.levels[k - 1];
                    let ratio = before.relative / before.estimate.traction_relative;
                    assert!(before.estimate.traction_hierarchical_relative.is_some() && ratio < 1.0);
                    assert!((c - ratio * bound).abs() <= 1e-12 * c, "{c} against {}", ratio * bound);
                    assert_eq!(level.relative, c.min(bound));
                }
                (None, None) => {
                    assert!(level.relative == bound || (bound.is_nan() && level.relative == e.energy_relative));
                }
            }
        }
        let error = hertz_error(&sharp.problem, &sharp.solution);
        let bounded = AdaptSettings { stop_on: StopOn::Bound, ..adapt };
        let safe = problem.solve_adaptive(&friction, &settings, &bounded, None).expect("adapts");
        let safe_error = hertz_error(&safe.problem, &safe.solution);
        println!(
            "tol {tol}: hierarchical {error:.3e} ({} unknowns, estimate {:.3e}); bound {safe_error:.3e} ({} unknowns)",
            sharp.problem.n_free, relative, safe.problem.n_free
        );
        assert!(error <= tol && error >= tol / 3.0, "tol {tol}: true error {error}");
        assert!(safe_error < tol / 3.0 && safe.problem.n_free > 2 * sharp.problem.n_free, "{safe_error}");
    }
}

/// The enriched answer handed back (`stop_on = "enriched"`) is solved as an estimate, without a check of its own: with
/// `coulomb_check` asked for, it is checked all the same (the levels before it are, as every solve is).
#[test]
fn the_enriched_answer_handed_back_is_checked_when_asked() -> Result<()> {
    let friction = Friction::Coulomb { mu: 0.3 };
    let settings = SolverSettings { coulomb_check: true, ..SolverSettings::default() };
    // The first of these tolerances at which the run hands back an enriched answer.
    let mut runs = [0.05, 0.04, 0.03, 0.02].into_iter().map(|tol| {
        let adapt = AdaptSettings { tol, stop_on: StopOn::Enriched, ..AdaptSettings::default() };
        off_centre_problem().solve_adaptive(&friction, &settings, &adapt, None)
    });
    let out = loop {
        let out = runs.next().expect("an enriched answer handed back")?;
        if out.levels.last().is_some_and(|l| l.enriched) {
            break out;
        }
    };
    let last = out.levels.last().expect("levels");
    assert!(out.stop == AdaptStop::Tolerance && last.seconds == 0.0, "handed back: {:?}", out.stop);
    assert_eq!(out.solution.report.status, SolveStatus::Converged);
    let check = out.solution.report.coulomb_check.as_ref().expect("the answer handed back is checked");
    assert_eq!(check.agreement, Agreement::Agree, "{check:?}");
    Ok(())
}

/// With `stop_on = "enriched"`, where the answer of a level's enriched problem has an estimate of its own
/// (a third of the level's: `½ ‖λ_H − λ_f‖` against `1.5 ‖λ_H − λ_f‖`, both over `‖λ_f‖`) within `tol`, the loop hands
/// it
/// back as one more level: converged to `fp_tol`, nested in the level before it, solved again alike, closer to
/// Hertz than that level's answer, and reached no later than the hierarchical stop (which never hands it back).
#[test]
fn the_enriched_answer_is_handed_back_where_its_estimate_meets_tol() -> Result<()> {
    let problem = off_centre_problem();
    let (friction, settings) = (Friction::Frictionless, SolverSettings::default());
    let tol = 0.02;
    let adapt = AdaptSettings { tol, stop_on: StopOn::Enriched, max_unknowns: 200_000, ..Default::default() };
    let mut heard = Vec::new();
    let mut observer = |level: &Level| {
        heard.push(level.unknowns);
        std::ops::ControlFlow::Continue(())
    };
    let out = problem.solve_adaptive(&friction, &settings, &adapt, Some(&mut observer))?;
    let [.., coarse, fine] = &out.levels[..] else { panic!("at least two levels") };
    let (h, f) = (coarse.estimate.traction_hierarchical_relative, fine.estimate.traction_hierarchical_relative);
    println!(
        "{} levels: {} unknowns, {h:?}; handed back {} unknowns, {f:?}",
        out.levels.len(),
        coarse.unknowns,
        fine.unknowns
    );
    assert_eq!(out.stop, AdaptStop::Tolerance);
    let (h, f) = (h.expect("the level before is estimated"), f.expect("the enriched answer carries its estimate"));
    assert!(h > tol && f <= tol, "{h} {f}");
    let third = h * tribo::adapt::enriched::SATURATION;
    assert!((f - third).abs() <= 1e-12 * h, "no end of Γ_C touches: a third of the level's estimate");
    assert_eq!((fine.seconds, fine.status, out.problem.n_free), (0.0, SolveStatus::Converged, fine.unknowns));
    assert!(coarse.seconds > 0.0 && fine.unknowns > coarse.unknowns);
    assert_eq!(heard, out.levels.iter().map(|l| l.unknowns).collect::<Vec<_>>(), "the observer heard every level");
    let bound = Solution::accuracy_bound(settings.qp.tol, out.solution.report.qp_inaccurate, settings.fp.tol);
    assert!(out.solution.kkt.max() <= bound, "converged to fp_tol: {:?}", out.solution.kkt);
    // Nested: the enriched mesh begins with the level's nodes; solved again on it, the answer is the same.
    assert_eq!(&fine.mesh.points()[..coarse.mesh.n_nodes()], coarse.mesh.points());
    let again = problem.on_level(fine)?.solve(&friction, &settings, None)?;
    let (d, n) = tribo::adapt::multiplier_difference(&out.problem, &out.solution, &out.problem, &again);
    assert!(d <= 1e-6 * n, "{d} of {n}");
    let before = problem.on_level(coarse)?;
    let at_coarse = before.solve(&friction, &settings, None)?;
    let (e_fine, e_coarse) = (hertz_error(&out.problem, &out.solution), hertz_error(&before, &at_coarse));
    println!("error against Hertz: {e_coarse:.3e} on the level, {e_fine:.3e} handed back");
    assert!(e_fine < e_coarse);
    // The hierarchical stop computes the same levels up to `coarse` and goes on from there.
    let hierarchical = AdaptSettings { stop_on: StopOn::Hierarchical, ..adapt };
    let sharp = problem.solve_adaptive(&friction, &settings, &hierarchical, None)?;
    assert!(
        sharp.levels.len() >= out.levels.len() - 1 && sharp.levels[out.levels.len() - 2].unknowns == coarse.unknowns
    );
    Ok(())
}

/// Where a level meets the tolerance itself, it is handed back, not its enriched answer (which meets it too): the
/// first answer within `tol`, at the same cost, on fewer unknowns. Over a range of tolerances on centred Hertz with
/// Coulomb friction (study 13's `hertz-coulomb`, which ended at 0.27 `tol` at 2 % before the rule), an enriched
/// answer only follows a level outside `tol`, and some runs end on a level within it (the rule is not idle: at
/// 21 % the first estimated level, 464 unknowns, is within `tol` by its own estimate, 20.3 %).
#[test]
fn a_level_within_tol_is_handed_back_itself() -> Result<()> {
    let s = tribo_testkit::hertz_scene();
    let mut spec = tribo_testkit::hertz_spec(s.approach, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle.shape = ObstacleShape::Circle { center: 0.0, radius: s.radius };
    let problem = Problem::new(rectangle(s.x, s.y, 8, 4, Diagonal::Right)?, spec)?;
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let mut own = 0;
    for tol in [0.25, 0.21, 0.1, 0.05, 0.03, 0.02, 0.015, 0.01] {
        let adapt = AdaptSettings { tol, stop_on: StopOn::Enriched, ..Default::default() };
        let run = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
        let [.., before, last] = &run.levels[..] else { panic!("levels") };
        let within = last.relative <= tol && (!last.enriched || before.relative > tol);
        let read = |l: &Level| (l.unknowns, l.enriched, l.relative, l.estimate.traction_hierarchical_relative);
        let levels: Vec<_> = run.levels.iter().map(read).collect();
        assert!(run.stop == AdaptStop::Tolerance && within, "tol {tol}: {:?} {levels:?}", run.stop);
        let h = last.estimate.traction_hierarchical_relative;
        own += usize::from(!last.enriched && h.is_some_and(|h| h * tribo::adapt::enriched::SATURATION <= tol));
    }
    assert!(own > 0, "no run ended on a level whose enriched answer met the tolerance too");
    Ok(())
}

/// The hierarchical estimate is computed where it may stop the loop, or the next level on the calibrated bound: after
/// the first, on a level whose reading (the bound, or the calibrated bound right after an estimate) is above `tol`,
/// where the last measured ratio r of the stop's reading to the bound is below the bound's last reduction (and 1) and r
/// times the level's bound is within `3 × 1.6^(s−1)` times what the stop reads (`s` the levels since r was measured;
/// `tol` for the level's own estimate, `3 tol` where an enriched answer, whose estimate is a third of the level's, may
/// be handed back), or where the unknowns have grown fourfold; not where the bound, falling as it did from the level
/// before, meets `tol` on the next level. Checked from the levels alone over a range of tolerances, with some levels
/// between 3 and 9 `tol` estimated (where the margin of `tol` alone skipped a level whose enriched answer met `tol`:
/// study 13's Cattaneo–Mindlin history at 5 %, 3.5 times the time of the cheapest adequate level, 1.0 since).
#[test]
fn the_estimate_is_due_where_what_the_stop_reads_may_meet_tol() -> Result<()> {
    let problem = off_centre_problem();
    let (friction, settings) = (Friction::Frictionless, SolverSettings::default());
    let mut in_margin = 0; // Enriched levels estimated only on the margin of `3 tol`
    let (third, growth) = (tribo::adapt::enriched::SATURATION, tribo::adapt::PESSIMISM_GROWTH);
    for (stop_on, reads) in [(StopOn::Enriched, 1.0 / third), (StopOn::Hierarchical, 1.0)] {
        for tol in [0.05, 0.03, 0.02, 0.01] {
            let adapt = AdaptSettings { tol, stop_on, ..Default::default() };
            let run = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
            let mut measured: Option<(f64, usize, usize)> = None;
            for (k, level) in run.levels.iter().enumerate().filter(|(_, l)| !l.enriched) {
                let (h, bound) = (level.estimate.traction_hierarchical_relative, level.estimate.traction_relative);
                if let Some((ratio, unknowns, at)) = measured {
                    let margin = 3.0 * growth.powi(i32::try_from(k - at - 1).unwrap_or(i32::MAX));
                    // What the level read before any estimate of its own: the calibrated bound right after one.
                    let reading = level.estimate.traction_calibrated_relative.map_or(bound, |c| c.min(bound));
                    // Not where the bound, falling as it did from the level before, meets tol on the next level.
                    let before = run.levels[k - 1].estimate.traction_relative;
                    let bound_stops_next = before.is_finite() && bound < before && bound * bound / before <= tol;
                    let fall = if before.is_finite() && bound < before { bound / before } else { 1.0 };
                    let due = reading > tol
                        && !bound_stops_next
                        && ((ratio < fall && ratio * bound <= margin * reads * tol) || level.unknowns >= 4 * unknowns);
                    assert_eq!(
                        h.is_some(),
                        due,
                        "{stop_on:?} {tol}: level {k}, {} unknowns, ratio {ratio} measured at {at}, bound {bound}, \
                         reading {reading}",
                        level.unknowns
                    );
                    let beyond = ratio < fall && ratio * bound > margin * tol && level.unknowns < 4 * unknowns;
                    in_margin += usize::from(stop_on == StopOn::Enriched && h.is_some() && beyond);
                }
                if h.is_some() {
                    measured = Some((level.relative / bound, level.unknowns, k));
                }
            }
            assert!(measured.is_some(), "{stop_on:?} {tol}: never estimated");
        }
    }
    assert!(in_margin > 0, "no level estimated beyond the margin of tol alone");
    Ok(())
}

/// The hierarchical estimate is never computed on a level that meets `tol` by its bound already: the level stops there
/// and is handed back itself. The block (full contact, its corners singular) is such a case: its bound, about twice the
/// truth, is about as sharp as the estimate there, and at 5 % it meets `tol` on a level where the estimate is due
/// otherwise (the unknowns grown fourfold since the last). Nor where the last ratio of the estimate to the bound is not
/// below the bound's last reduction (the block's 0.9–1 against 0.8–0.9 a level): each estimate after the first comes by
/// the fourfold growth alone (with the estimate through λ_ff at the ends and without that rule, one on every level near
/// the stop: 2.55 times the cheapest adequate level's time at 5 %).
#[test]
fn no_estimate_where_the_bound_meets_tol_already() -> Result<()> {
    // As study 13's block case (`tribo_testkit::adaptive_case("block")`), without its reference.
    let (problem, _) = tribo_testkit::block_problem(8, 2);
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    for stop_on in [StopOn::Enriched, StopOn::Hierarchical] {
        let adapt = AdaptSettings { tol: 0.05, stop_on, ..Default::default() };
        let run = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
        assert_eq!(run.stop, AdaptStop::Tolerance);
        let last = run.levels.last().expect("levels");
        let (h, bound) = (last.estimate.traction_hierarchical_relative, last.estimate.traction_relative);
        assert!(!last.enriched && bound <= adapt.tol && h.is_none(), "{stop_on:?}: {bound} {h:?}");
        assert!(last.relative <= adapt.tol, "{stop_on:?}: the level handed back meets tol itself (strict answer)");
        // The fourfold growth since the last estimate would have made it due.
        let estimated = run.levels.iter().rev().find(|l| l.estimate.traction_hierarchical_relative.is_some());
        assert!(estimated.is_some_and(|l| last.unknowns >= 4 * l.unknowns), "{stop_on:?}: not a stale estimate");
        let estimated: Vec<usize> = run
            .levels
            .iter()
            .filter(|l| l.estimate.traction_hierarchical_relative.is_some())
            .map(|l| l.unknowns)
            .collect();
        assert!(estimated.len() >= 2 && estimated.windows(2).all(|w| w[1] >= 4 * w[0]), "{stop_on:?}: {estimated:?}");
        assert!(run
            .levels
            .iter()
            .all(|l| l.estimate.traction_relative > adapt.tol || l.estimate.traction_hierarchical_relative.is_none()));
    }
    Ok(())
}

/// Nor where the bound, falling as it did from the level before, will meet `tol` on the next level: the estimate
/// could then only stop the loop one level sooner, at the price of an enriched solve of 8–9 times the level's
/// unknowns. The block at 2 % (study 13) computed one there, by the fourfold growth, at 29k unknowns: 11 s of its
/// 13.7 s, 6.2 times the time of the cheapest adequate level.
#[test]
fn no_estimate_where_the_bound_will_meet_tol_on_the_next_level() -> Result<()> {
    let (problem, _) = tribo_testkit::block_problem(8, 2);
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let adapt = AdaptSettings { tol: 0.02, ..Default::default() };
    let run = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
    assert_eq!(run.stop, AdaptStop::Tolerance);
    let bounds: Vec<f64> = run.levels.iter().map(|l| l.estimate.traction_relative).collect();
    let mut skipped = 0;
    for (k, level) in run.levels.iter().enumerate().skip(1) {
        let (bound, before) = (bounds[k], bounds[k - 1]);
        if before.is_finite() && bound < before && bound * bound / before <= adapt.tol && bound > adapt.tol {
            assert!(level.estimate.traction_hierarchical_relative.is_none(), "level {k}: {} unknowns", level.unknowns);
            skipped += 1;
        }
    }
    assert!(skipped > 0, "no level where the bound was about to stop the loop");
    Ok(())
}

/// The enriched answer is not handed back beyond `max_unknowns` or `max_levels`, nor with P0 multipliers
/// (first order everywhere: no margin); an observer that stops the loop at the level before it gets that level,
/// and is not called again.
#[test]
fn the_enriched_answer_keeps_to_the_limits_and_the_observer() -> Result<()> {
    let problem = off_centre_problem();
    let (friction, settings) = (Friction::Frictionless, SolverSettings::default());
    let adapt = AdaptSettings { tol: 0.02, stop_on: StopOn::Enriched, max_unknowns: 200_000, ..Default::default() };
    let free = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
    let [.., coarse, fine] = &free.levels[..] else { panic!("levels") };
    assert!(fine.enriched && fine.seconds == 0.0, "handed back");
    assert!(free.levels.iter().rev().skip(1).all(|l| !l.enriched && l.seconds > 0.0), "only the last is enriched");
    // Limits just below what the hand-back needs: the loop goes on as the default stop does.
    let wide = [
        AdaptSettings { max_unknowns: fine.unknowns, ..adapt },
        AdaptSettings { max_levels: free.levels.len(), ..adapt },
    ];
    for limited in wide {
        let out = problem.solve_adaptive(&friction, &settings, &limited, None)?;
        assert_eq!(
            (out.levels.len(), out.problem.n_free),
            (free.levels.len(), fine.unknowns),
            "at the limits: handed back"
        );
    }
    let narrow = [
        AdaptSettings { max_unknowns: fine.unknowns - 1, ..adapt },
        AdaptSettings { max_levels: free.levels.len() - 1, ..adapt },
    ];
    for limited in narrow {
        let out = problem.solve_adaptive(&friction, &settings, &limited, None)?;
        assert!(
            out.levels.iter().all(|l| !l.enriched && l.seconds > 0.0) && out.problem.n_free <= limited.max_unknowns
        );
        assert!(out.levels.len() <= limited.max_levels, "{} levels", out.levels.len());
    }
    // P0 multipliers: never handed back.
    let mut spec = tribo_testkit::hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P0);
    spec.obstacle.shape = ObstacleShape::Circle { center: CENTER, radius: 1.0 };
    let p0 = Problem::new(rectangle([-2.0, 2.0], [-2.0, 0.0], 8, 4, Diagonal::Right)?, spec)?;
    let out = p0.solve_adaptive(&friction, &settings, &adapt, None)?;
    assert!(out.levels.iter().all(|l| !l.enriched && l.seconds > 0.0) && out.stop == AdaptStop::Tolerance);
    // The last estimated level's enriched answer had an estimate (a third of the level's) within tol: P1 would have
    // handed it back (P0 stops on it, or on the calibrated bound of the level after).
    let h = out.levels.iter().rev().find_map(|l| l.estimate.traction_hierarchical_relative).expect("estimated");
    assert!(h * tribo::adapt::enriched::SATURATION <= adapt.tol, "{h}");
    // Stopped by the observer at the level whose enriched answer would have been handed back.
    let mut calls = 0;
    let mut observer = |level: &Level| {
        calls += 1;
        if level.unknowns == coarse.unknowns {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    };
    let out = problem.solve_adaptive(&friction, &settings, &adapt, Some(&mut observer))?;
    assert_eq!(
        (calls, out.levels.len(), out.problem.n_free),
        (free.levels.len() - 1, free.levels.len() - 1, coarse.unknowns)
    );
    // An enriched answer follows only a level outside the tolerance.
    assert!(out.stop == AdaptStop::Interrupted && coarse.relative > adapt.tol);
    Ok(())
}

/// A Coulomb loop stopping on the hierarchical estimate that hits `max_unknowns` hands back the level it
/// estimated, with the estimate: that level's answer was converged to `fp_tol` before its enriched solve, so
/// it is not solved again (which dropped the estimate). The observer heard the level that is handed back.
#[test]
fn a_stop_on_max_unknowns_keeps_the_hierarchical_estimate() {
    let problem = off_centre_problem();
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let adapt = AdaptSettings { tol: 1e-4, stop_on: StopOn::Hierarchical, max_unknowns: 15_000, ..Default::default() };
    let mut heard = Vec::new();
    let mut observer = |level: &Level| {
        heard.push(level.estimate);
        std::ops::ControlFlow::Continue(())
    };
    let out = problem.solve_adaptive(&friction, &settings, &adapt, Some(&mut observer)).expect("adapts");
    assert_eq!(out.stop, AdaptStop::MaxUnknowns);
    let last = out.levels.last().expect("levels");
    let sharp = last.estimate.traction_hierarchical_relative;
    println!("{} levels, last {} unknowns, hierarchical {sharp:?}", out.levels.len(), last.unknowns);
    assert!(sharp.is_some(), "the last level (4 times the unknowns of the one before it estimated) is estimated");
    assert_eq!(out.solution.report.estimate, last.estimate, "the answer carries the level's estimate");
    assert_eq!(heard.last(), Some(&last.estimate), "the observer heard the level handed back");
    let bound = Solution::accuracy_bound(settings.qp.tol, out.solution.report.qp_inaccurate, settings.fp.tol);
    assert!(out.solution.kkt.max() <= bound, "converged to fp_tol: {:?}", out.solution.kkt);
}

/// A level whose solve would exceed the memory budget stops the loop with the level before (`memory_budget`),
/// solved to `fp_tol` like every answer handed back short of the tolerance; the same level solved on its own
/// within that budget gives the same answer. (The loop used to return the error and lose every level; an
/// adaptive run on two contact pairs to 500k unknowns was killed by the kernel at 24 GB.)
#[test]
fn a_level_beyond_the_memory_budget_stops_the_loop_with_the_level_before() -> Result<()> {
    let problem = off_centre_problem();
    let friction = Friction::Coulomb { mu: 0.3 };
    // 6 MiB: a dense QP of clarabel over about 200 unknowns (16 × 8 k² bytes), reached after a few levels.
    let settings = SolverSettings { memory_budget: 6 << 20, ..Default::default() };
    let adapt = AdaptSettings { tol: 1e-6, stop_on: StopOn::Bound, max_unknowns: 400_000, ..Default::default() };
    let out = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
    assert_eq!(out.stop, AdaptStop::MemoryBudget, "{:?}", out.levels.iter().map(|l| l.unknowns).collect::<Vec<_>>());
    let last = out.levels.last().expect("levels");
    assert!(out.levels.len() > 3 && last.unknowns == out.problem.n_free, "{} levels", out.levels.len());
    assert_eq!(out.solution.report.status, SolveStatus::Converged);
    let bound = Solution::accuracy_bound(settings.qp.tol, out.solution.report.qp_inaccurate, settings.fp.tol);
    assert!(out.solution.kkt.max() <= bound, "converged to fp_tol: {:?}", out.solution.kkt);
    // The problem handed back is the last level's (rebuilt from it): solved again within the budget, it gives
    // the answer handed back.
    let again = problem.on_level(last)?.solve(&friction, &settings, None)?;
    let (d, n) = adapt::multiplier_difference(&out.problem, &out.solution, &out.problem, &again);
    assert!(d <= 10.0 * settings.fp.tol * n, "{d:e} of {n:e}");
    Ok(())
}

/// A history of one step from rest is the static problem (its data bit for bit): its hierarchical estimate
/// is the static one, to the accuracy of the solves, on adaptive Hertz with Coulomb friction (no end of Γ_C
/// touches) and on an adaptive level of the block (both ends touch: the second enrichment measures the
/// reduction there).
#[test]
fn a_one_step_history_is_estimated_as_the_static_problem() -> Result<()> {
    let hertz = off_centre_problem();
    let adapt = AdaptSettings { tol: 0.2, max_unknowns: 3_000, ..Default::default() };
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let settings = SolverSettings::default();
    let level = hertz.solve_adaptive(&coulomb, &settings, &adapt, None)?;
    let (block, mu) = tribo_testkit::block_problem(8, 2);
    let block_friction = Friction::Coulomb { mu };
    let adapt = AdaptSettings { tol: 1e-6, max_unknowns: 1_200, ..Default::default() };
    let block = block.solve_adaptive(&block_friction, &settings, &adapt, None)?;
    for (problem, friction, ends) in [(&level.problem, coulomb, 0), (&block.problem, block_friction, 2)] {
        let obstacle = &problem.spec.obstacle;
        let steps = [LoadStep::new(obstacle.approach, obstacle.shift)];
        let solution = problem.solve(&friction, &settings, None)?;
        let history = problem.solve_history(&friction, &steps, &settings, None)?;
        let one = problem.estimate_hierarchical(&solution, &friction, &settings)?;
        let each = problem.estimate_history_hierarchical(&history, &friction, &settings)?;
        println!("static {one:?}\nhistory {each:?}");
        assert_eq!(each.len(), 1);
        let h = &each[0];
        assert_eq!((h.status, one.status), (SolveStatus::Converged, SolveStatus::Converged));
        assert_eq!((h.unknowns, h.end_reductions.len(), one.end_reductions.len()), (one.unknowns, ends, ends));
        assert!(one.relative.is_finite() && one.relative > 0.0, "{one:?}");
        assert!((h.relative - one.relative).abs() <= 1e-6 * one.relative, "{} against {}", h.relative, one.relative);
        for (a, b) in h.end_reductions.iter().zip(&one.end_reductions) {
            assert!((a - b).abs() <= 1e-6 * b.abs(), "reductions {a} and {b}");
        }
    }
    Ok(())
}

/// A solve (or a step of a history) with one multiplier dof touching has no contact width to enrich within: the
/// estimate's second bisection takes the two T_H cells around that dof, for a solve and a history alike (a history's
/// step got no strip of its own).
#[test]
fn one_dof_touching_enriches_the_two_cells_around_it() -> Result<()> {
    // The problem's own approach is the step's: one step from rest is the static problem.
    let problem = tribo_testkit::hertz_problem(0.04, 1e-3, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    let steps = [LoadStep::new(1e-3, 0.0)];
    let history = problem.solve_history(&friction, &steps, &settings, None)?;
    let touching = |s: &Solution| s.states.iter().filter(|c| **c != ContactState::Separation).count();
    assert_eq!(touching(&history.solutions[0]), 1);
    let one = problem.estimate_hierarchical(&history.solutions[0], &friction, &settings)?;
    let all: Vec<usize> = (0..problem.mesh.n_triangles()).collect();
    let (whole, _) = problem.solve_enriched(&history.solutions[0], &all, &friction, &settings)?;
    let each = problem.estimate_history_hierarchical(&history, &friction, &settings)?;
    // The whole mesh bisected, then a few triangles around the dof again.
    assert!(whole.n_free < one.unknowns && one.unknowns < whole.n_free + whole.n_free / 10, "{one:?}");
    assert_eq!(each[0].unknowns, one.unknowns);
    assert!((each[0].relative - one.relative).abs() <= 1e-6 * one.relative, "{each:?} {one:?}");
    // With a step of wider contact after it, the history's strip is that step's (the window lies in it).
    let wider = [LoadStep::new(1e-3, 0.0), LoadStep::new(0.01, 0.0)];
    let history = problem.solve_history(&friction, &wider, &settings, None)?;
    assert!(touching(&history.solutions[1]) >= 5);
    let pressed = tribo_testkit::hertz_problem(0.04, 0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let strip = pressed.estimate_hierarchical(&history.solutions[1], &friction, &settings)?;
    let each = problem.estimate_history_hierarchical(&history, &friction, &settings)?;
    assert!(each.iter().all(|h| h.unknowns == strip.unknowns), "{each:?} {strip:?}");
    Ok(())
}

/// Defect D27 on the hierarchical path: the L²(Γ_C) difference of two multipliers scales with them at any
/// magnitude (its squares are taken in units of the largest |λ|; they overflowed beyond about 1e154).
#[test]
fn the_multiplier_difference_scales_with_the_multipliers() -> Result<()> {
    let problem = tribo_testkit::hertz_problem(0.02, 0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let solution = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None)?;
    let scaled = |s: &Solution, by: f64| {
        let mut s = s.clone();
        s.lambda_n.iter_mut().chain(s.lambda_t.iter_mut()).for_each(|v| *v *= by);
        s
    };
    let other = scaled(&solution, 1.1);
    let (d, n) = tribo::adapt::multiplier_difference(&problem, &solution, &problem, &other);
    assert!(d > 0.0 && (d / n - 0.1 / 1.1).abs() < 1e-12, "{d} {n}");
    for by in [1e-300, 1e-200, 1e200, 1e300] {
        let (ds, ns) =
            tribo::adapt::multiplier_difference(&problem, &scaled(&solution, by), &problem, &scaled(&other, by));
        assert!((ds / (by * d) - 1.0).abs() < 1e-12 && (ns / (by * n) - 1.0).abs() < 1e-12, "× {by}: {ds} {ns}");
    }
    Ok(())
}

/// A Cattaneo–Mindlin history (pressed, then dragged under partial slip) stops on the hierarchical
/// estimate: the levels where the loop computed it read the smaller of it and the bound, every kept step
/// and its record carry it, and the run ends on fewer unknowns than the same run stopping on the bound.
#[test]
fn a_history_stops_on_the_hierarchical_estimate() -> Result<()> {
    let problem = off_centre_problem();
    let steps: Vec<LoadStep> = [0.0, 0.001, 0.002].iter().map(|&s| LoadStep::new(0.01, s)).collect();
    let friction = Friction::Coulomb { mu: 0.3 };
    let settings = SolverSettings::default();
    let mut runs = Vec::new();
    for stop_on in [StopOn::Hierarchical, StopOn::Bound] {
        let adapt = AdaptSettings { tol: 0.05, max_unknowns: 200_000, stop_on, ..Default::default() };
        runs.push(problem.solve_history_adaptive(&friction, &steps, &settings, &adapt, &[], None)?);
    }
    let (sharp, bound) = (&runs[0], &runs[1]);
    assert_eq!((sharp.stop, bound.stop), (AdaptStop::Tolerance, AdaptStop::Tolerance));
    let last = sharp.levels.last().expect("levels");
    let estimated: Vec<&Level> =
        sharp.levels.iter().filter(|l| l.estimate.traction_hierarchical_relative.is_some()).collect();
    println!(
        "{} levels, {} estimated, last {} unknowns (bound: {})",
        sharp.levels.len(),
        estimated.len(),
        last.unknowns,
        bound.problem.n_free
    );
    assert!(!estimated.is_empty() && last.relative <= 0.05);
    for l in estimated {
        let e = &l.estimate;
        let r = e.traction_hierarchical_relative.expect("estimated");
        assert!(r.is_finite() && r > 0.0 && l.relative == r.min(e.traction_relative), "{e:?}");
    }
    for (solution, &k) in sharp.history.solutions.iter().zip(&sharp.history.kept) {
        let e = &solution.report.estimate;
        assert_eq!(&sharp.history.records[k].estimate, e, "step {k}: the record carries the step's estimate");
        // Estimated, or calibrated on the level after an estimated one.
        let sharp = e.traction_hierarchical_relative.or(e.traction_calibrated_relative);
        assert!(sharp.is_some_and(f64::is_finite), "step {k}: {e:?}");
    }
    assert!(sharp.problem.n_free < bound.problem.n_free, "{} against {}", sharp.problem.n_free, bound.problem.n_free);
    let named = AdaptKeywords { stop_on: Some("sharpest".into()), ..Default::default() };
    assert!(matches!(AdaptSettings::from_keywords(named), Err(Error::UnknownChoice { .. })));
    Ok(())
}

/// Coulomb friction, with coarse fixed points stopped at a tenth of the previous level's estimate and
/// with every level converged to `fp_tol`: both stop on the tolerance, the answer handed back is
/// converged to `fp_tol` in both, and the two answers are one: their λ_n, on meshes that differ by the
/// marking of the coarse levels, agree in L²(Γ_C) to within the two estimated errors (each below tol;
/// measured 1e-3), and both agree with Hertz alike (about 8 %: the finite block against the half-space).
#[test]
fn coarse_fixed_points_may_stop_early_and_the_answer_does_not_change() -> Result<()> {
    let problem = off_centre_problem();
    let friction = Friction::Coulomb { mu: 0.3 };
    let settings = SolverSettings::default();
    let tol = 0.05;
    let mut answers = Vec::new();
    for algebraic in [0.1, 0.0] {
        let adapt = AdaptSettings { tol, max_unknowns: 60_000, algebraic, ..Default::default() };
        let out = problem.solve_adaptive(&friction, &settings, &adapt, None)?;
        assert_eq!(out.stop, AdaptStop::Tolerance, "algebraic {algebraic}: {:?}", out.levels);
        let last = out.solution.report.residual_history.last().copied().unwrap_or(0.0);
        assert!(last <= settings.fp.tol || out.solution.report.iterations <= 1, "converged to fp_tol: {last}");
        answers.push(out);
    }
    let errors: Vec<f64> = answers.iter().map(|a| hertz_error(&a.problem, &a.solution)).collect();
    assert!(errors.iter().all(|&e| e <= 2.0 * tol), "λ_n errors against Hertz {errors:?}");
    // ‖λ₁ − λ₂‖ / ‖λ₁‖ on Γ_C (8-point Gauss on the union of both T_H).
    let (a, b) = (&answers[0], &answers[1]);
    let mut breaks: Vec<f64> = a.problem.multipliers.xi.iter().chain(&b.problem.multipliers.xi).copied().collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let (gx, gw) = tribo_testkit::gauss8();
    let (mut num, mut den) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (h, m) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for (x, wt) in gx.iter().zip(&gw) {
            let la = a.problem.multipliers.evaluate(&a.solution.lambda_n, m + h * x);
            let lb = b.problem.multipliers.evaluate(&b.solution.lambda_n, m + h * x);
            num += wt * h * (la - lb).powi(2);
            den += wt * h * la * la;
        }
    }
    let difference = (num / den).sqrt();
    assert!(difference <= 2.0 * tol, "the two answers differ by {difference:e} in L²(Γ_C)");
    Ok(())
}

/// A loading history adapts on one mesh for all its steps: pressed, then dragged (Coulomb, partial
/// slip), from the coarse mesh where no node touches. Every level solves the whole history; the loop
/// stops on the tolerance with the largest relative estimate over the steps, the history on the last
/// mesh converges at every step, and its stick zone (which shrinks as the drag grows) holds enough
/// multiplier dofs to be measured at every step.
#[test]
fn a_history_adapts_on_its_worst_step() {
    let problem = off_centre_problem();
    let friction = Friction::Coulomb { mu: 0.3 };
    let steps: Vec<LoadStep> =
        (0..6).map(|k| LoadStep::new(problem.spec.obstacle.approach, 0.0008 * k as f64)).collect();
    // The bound (a fine enough last mesh for the stick zones; the hierarchical stop has its own test).
    let adapt = AdaptSettings { tol: 0.2, max_unknowns: 60_000, stop_on: StopOn::Bound, ..Default::default() };
    let out = problem
        .solve_history_adaptive(&friction, &steps, &SolverSettings::default(), &adapt, &[], None)
        .expect("adapts");
    assert_eq!(out.stop, AdaptStop::Tolerance, "{:?}", out.levels);
    assert_eq!(out.history.status, SolveStatus::Converged);
    assert_eq!(out.history.solutions.len(), steps.len());
    let worst = out.history.solutions.iter().map(|s| s.report.estimate.traction_relative).fold(0.0, f64::max);
    let last = out.levels.last().expect("levels");
    assert_eq!(last.relative, worst, "a level reports its worst step");
    assert!(worst <= adapt.tol && out.problem.n_free == last.unknowns);
    let stick = |s: &Solution| s.states.iter().filter(|&&c| c == ContactState::Stick).count();
    assert!(
        out.history.solutions[1..].iter().all(|s| stick(s) >= 10),
        "{:?}",
        out.history.solutions.iter().map(stick).collect::<Vec<_>>()
    );
    // The last level's loose history was solved again to fp_tol, every step from its own loose answer:
    // every step converged to fp_tol, and the forces are those of the history solved from rest on the
    // last mesh, within what two answers converged to fp_tol may differ (2 · 2 fp_tol per step, summed
    // over the steps, for a contraction L ≤ 1/2; see `history.rs`).
    let settings = SolverSettings::default();
    for s in &out.history.solutions {
        let change = s.report.residual_history.last().copied().unwrap_or(0.0);
        assert!(change <= settings.fp.tol || s.report.iterations <= 1, "converged to fp_tol: {change}");
    }
    let fresh = out.problem.solve_history(&friction, &steps, &settings, None).expect("solves");
    for (a, b) in out.history.solutions.iter().zip(&fresh.solutions) {
        let allowed = 4.0 * settings.fp.tol * steps.len() as f64 * b.normal_force.abs();
        assert!((a.normal_force - b.normal_force).abs() <= allowed, "{} {}", a.normal_force, b.normal_force);
        assert!((a.tangential_force - b.tangential_force).abs() <= allowed);
    }
    // Adapting on the press alone stops earlier: the drag's slip zones need their own refinement.
    let press = problem
        .solve_history_adaptive(&friction, &steps, &SolverSettings::default(), &adapt, &[0], None)
        .expect("adapts");
    assert!(press.levels.last().map_or(0, |l| l.unknowns) < last.unknowns);
    match problem.solve_history_adaptive(&friction, &steps, &SolverSettings::default(), &adapt, &[6], None) {
        Err(Error::BadSetting { name, .. }) => assert_eq!(name, "adapt_steps"),
        other => panic!("{other:?}"),
    }
}

/// A level whose QPs start from the coarser level's multipliers weighs the saddle-point system at its warm
/// cost (one LDLᵀ and a few bordered steps): on the off-centre run's level of 13k unknowns, where a cold
/// solve of the same problem forms all of H by the partial factorization, the loop solves on the
/// saddle-point system (measured: 0.11 s against 0.16 s for that level), and both reach one answer.
#[test]
fn a_warm_level_takes_the_saddle_point_system() {
    let settings = SolverSettings::default();
    // Stopping on the bound: the last level is large enough for the choice to matter.
    let adapt = AdaptSettings { tol: 0.08, stop_on: StopOn::Bound, ..Default::default() };
    let out = off_centre_problem().solve_adaptive(&Friction::Frictionless, &settings, &adapt, None).expect("adapts");
    assert!(out.problem.n_free > 10_000, "the level is large enough for the choice to matter");
    assert_eq!(out.solution.report.condensation, Condensation::Saddle);
    let mut spec = out.problem.spec.clone();
    spec.multiplier_points = MultiplierPoints::Abscissae(out.problem.multipliers.xi.clone());
    let cold = Problem::new(out.problem.mesh.clone(), spec).expect("valid");
    assert_eq!((cold.n_free, cold.n_multipliers()), (out.problem.n_free, out.problem.n_multipliers()));
    let again = cold.solve(&Friction::Frictionless, &settings, None).expect("solves");
    assert_eq!(again.report.condensation, Condensation::Schur);
    // Two QPs, each determining λ to about qp_tol · κ(H), agree to twice that.
    let kappa = tribo_testkit::condition_number(&cold.condense(settings.stabilization).expect("condenses"));
    let tol = (tribo_testkit::reached_qp_tol(&settings, &out.solution)
        + tribo_testkit::reached_qp_tol(&settings, &again))
        * kappa;
    let scale = again.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = again.lambda_n.iter().zip(&out.solution.lambda_n).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff <= tol * scale, "λ_n differs by {diff:e} of {scale:e} (qp_tol · κ(H) = {tol:e})");
}

/// The law weighs the choice: on an adaptive mesh whose dense block is a little too large for one
/// frictionless QP (the saddle-point system), a Coulomb fixed point, whose several QPs cost the
/// saddle-point system about twice as much, takes the partial factorization; the two paths agree on its
/// answer.
#[test]
fn a_coulomb_fixed_point_weighs_the_partial_factorization_higher() {
    let settings = SolverSettings::default();
    // Stopping on the bound: a last level whose dense block is a little too large for the saddle point.
    let adapt = AdaptSettings { tol: 0.06, stop_on: StopOn::Bound, ..Default::default() };
    let out = off_centre_problem().solve_adaptive(&Friction::Frictionless, &settings, &adapt, None).expect("adapts");
    let mut spec = out.problem.spec.clone();
    spec.multiplier_points = MultiplierPoints::Abscissae(out.problem.multipliers.xi.clone());
    let cold = || Problem::new(out.problem.mesh.clone(), spec.clone()).expect("valid");
    let frictionless = cold().solve(&Friction::Frictionless, &settings, None).expect("solves");
    assert_eq!(frictionless.report.condensation, Condensation::Saddle);
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let by_auto = cold().solve(&coulomb, &settings, None).expect("solves");
    assert_eq!(by_auto.report.condensation, Condensation::Schur);
    let saddle = SolverSettings { condensation: Condensation::Saddle, ..settings };
    let by_saddle = cold().solve(&coulomb, &saddle, None).expect("solves");
    assert_eq!(by_saddle.report.condensation, Condensation::Saddle);
    assert_eq!(by_auto.report.status, SolveStatus::Converged);
    assert_eq!(by_saddle.report.status, SolveStatus::Converged);
    // Two fixed points, each stopped at fp_tol and with QPs determining λ to about qp_tol · κ(H).
    let kappa = tribo_testkit::condition_number(&cold().condense(settings.stabilization).expect("condenses"));
    let tol = (tribo_testkit::reached_qp_tol(&settings, &by_auto)
        + tribo_testkit::reached_qp_tol(&settings, &by_saddle))
        * kappa
        + 2.0 * settings.fp.tol;
    let scale = by_auto.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = by_auto.lambda_n.iter().zip(&by_saddle.lambda_n).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff <= tol * scale, "λ_n differs by {diff:e} of {scale:e} (allowed {tol:e})");
}

/// The unknowns of every level of an adaptive solve (tol out of reach, so the loop refines to
/// `max_unknowns`).
fn adapted_levels(problem: &Problem, friction: &Friction) -> (Vec<usize>, AdaptStop) {
    let adapt = AdaptSettings { tol: 1e-6, max_unknowns: 4_000, ..Default::default() };
    let out = problem.solve_adaptive(friction, &SolverSettings::default(), &adapt, None).expect("adapts");
    (out.levels.iter().map(|l| l.unknowns).collect(), out.stop)
}

/// Defect D27: the marking squared each indicator, so beyond about 1e154 (E = 1e300, or an approach of
/// 1e300) the squares overflowed, nothing was marked and the loop solved its first mesh again until
/// `max_levels`. A change of units (stress by E, lengths of the motion by δ and s) changes no level.
#[test]
fn scaled_problems_adapt_alike() {
    let (base, mu) = tribo_testkit::block_problem(8, 2);
    let friction = Friction::Coulomb { mu };
    let scaled = |young: f64, motion: f64| {
        let mut spec = base.spec.clone();
        spec.material.young *= young;
        spec.obstacle.approach *= motion;
        spec.obstacle.shift *= motion;
        Problem::new(base.mesh.clone(), spec).expect("valid")
    };
    let (reference, stop) = adapted_levels(&base, &friction);
    assert_eq!(stop, AdaptStop::MaxUnknowns);
    assert!(reference.len() >= 5 && reference.windows(2).all(|w| w[1] > w[0]), "{reference:?}");
    for (young, motion) in [(1e300, 1.0), (1.0, 1e300), (1e150, 1e150), (1e-150, 1e-150), (1e-300, 1.0)] {
        let (levels, stop) = adapted_levels(&scaled(young, motion), &friction);
        assert_eq!((levels, stop), (reference.clone(), AdaptStop::MaxUnknowns), "E × {young:e}, motion × {motion:e}");
    }
}

/// Defect D28: with the cylinder pushed 1e-6 between two nodes of the 8 × 4 mesh, the dip (3e-3 wide
/// under edges of 0.5) fell between the estimator's Gauss points: the estimate was exactly 0, its 0 / 0
/// was read as "tolerance reached", and the loop stopped at level 0 with no contact. It must find it.
#[test]
fn a_coarse_mesh_that_misses_a_shallow_contact_refines_until_it_finds_it() {
    let problem = off_centre_problem();
    let mut spec = problem.spec.clone();
    spec.obstacle.approach = 1e-6;
    let shallow = Problem::new(problem.mesh.clone(), spec).expect("valid");
    let first = shallow.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect("solves");
    assert!(first.normal_force == 0.0, "no node touches at first");
    assert!(first.report.estimate.contact > 0.0, "the estimate sees the dip between the nodes");
    let adapt = AdaptSettings { tol: 0.2, max_unknowns: 200_000, ..Default::default() };
    let out =
        shallow.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    assert_eq!(out.stop, AdaptStop::Tolerance, "{:?}", out.levels.iter().map(|l| l.unknowns).collect::<Vec<_>>());
    assert!(out.solution.normal_force > 0.0 && out.levels.len() > 5);
}

/// The other half of D28: an obstacle that touches nowhere has an estimate of exactly 0; the loop says
/// so (`Exact`), it does not report the tolerance as reached.
#[test]
fn an_obstacle_that_touches_nowhere_stops_exact_not_on_the_tolerance() {
    let problem = off_centre_problem();
    let mut spec = problem.spec.clone();
    spec.obstacle.approach = -0.01;
    let apart = Problem::new(problem.mesh.clone(), spec).expect("valid");
    let adapt = AdaptSettings { tol: 0.2, ..Default::default() };
    let out = apart.solve_adaptive(&Friction::Frictionless, &SolverSettings::default(), &adapt, None).expect("adapts");
    assert_eq!(out.stop, AdaptStop::Exact);
    assert_eq!((out.levels.len(), out.solution.normal_force), (1, 0.0));
}

/// Defect D29: where nothing touches, the penetration term was `E*² × 0`, which is NaN for E ≥ 1e155:
/// a solve with u = 0 and λ = 0 ended `non_finite`.
#[test]
fn nothing_touching_at_a_huge_modulus_converges() {
    let problem = off_centre_problem();
    for young in [1e150, 1e200, 1e300] {
        let mut spec = problem.spec.clone();
        spec.obstacle.approach = -0.01;
        spec.material.young = young;
        let apart = Problem::new(problem.mesh.clone(), spec).expect("valid");
        let sol = apart.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).expect("solves");
        assert_eq!(sol.report.status, SolveStatus::Converged, "E = {young:e}");
        assert_eq!((sol.report.estimate.total, sol.normal_force), (0.0, 0.0), "E = {young:e}");
    }
}

/// Defect D34: a level is solved with the loose fixed-point stop meant for coarse levels; when the loop
/// stopped on `max_unknowns` that loose answer was handed back as `converged` (the demo: KKT 1.3e-5 against
/// the promised 1e-6, 28 stick and 26 slip dofs where the same mesh solved again has 14 and 40). The answer
/// handed back on every stop is converged to `fp_tol`: its KKT residuals within the promise, and the same
/// answer as the last mesh solved afresh.
#[test]
fn a_stop_on_max_unknowns_hands_back_an_answer_converged_to_fp_tol() {
    let problem =
        tribo_testkit::hertz_problem(0.01, 0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let (friction, settings) = (Friction::Coulomb { mu: 0.3 }, SolverSettings::default());
    // The bound: no level computes the hierarchical estimate, which solves a level strictly before it.
    let adapt = AdaptSettings { tol: 1e-3, max_unknowns: 5_000, stop_on: StopOn::Bound, ..Default::default() };
    let out = problem.solve_adaptive(&friction, &settings, &adapt, None).expect("adapts");
    assert_eq!(out.stop, AdaptStop::MaxUnknowns);
    let sol = &out.solution;
    let bound = Solution::accuracy_bound(settings.qp.tol, sol.report.qp_inaccurate, settings.fp.tol);
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.kkt.max() <= bound, "KKT {:?} above {bound:e}", sol.kkt);
    let fresh = out.problem.solve(&friction, &settings, None).expect("solves");
    assert_eq!(sol.states, fresh.states, "the handed-back states are those of the last mesh solved afresh");
    let last = out.levels.last().expect("levels");
    assert_eq!((last.status, last.estimate), (sol.report.status, sol.report.estimate), "the level is the answer's");
}

/// A random adaptive case: the block `(−w/2, w/2) × (−h, 0)` on an `nx × ny` mesh, clamped at the bottom,
/// pushed on its top by a cylinder or a flat obstacle, frictionless, Tresca or Coulomb, with random
/// adaptive settings; every length is multiplied by `length` and E (and a Tresca threshold) by `stress`.
#[derive(Debug, Clone)]
struct RandomCase {
    w: f64,
    h: f64,
    nx: usize,
    ny: usize,
    young: f64,
    poisson: f64,
    /// Centre and radius of the cylinder (None: flat).
    cylinder: Option<(f64, f64)>,
    approach: f64,
    shift: f64,
    /// 0 frictionless, 1 Tresca, 2 Coulomb, with its coefficient (μ, or the threshold over E).
    law: (usize, f64),
    adapt: AdaptSettings,
}

impl RandomCase {
    fn problem(&self, length: f64, stress: f64) -> (Problem, Friction) {
        let (w, h) = (self.w * length, self.h * length);
        let mesh = rectangle([-w / 2.0, w / 2.0], [-h, 0.0], self.nx, self.ny, Diagonal::Right).expect("valid");
        let shape = self.cylinder.map_or(ObstacleShape::Flat, |(center, radius)| ObstacleShape::Circle {
            center: center * length,
            radius: radius * length,
        });
        let material = Material { young: self.young * stress, poisson: self.poisson };
        let spec = ProblemSpec::new(material, "top")
            .clamped(["bottom"])
            .obstacle(shape)
            .approach(self.approach * length)
            .shift(self.shift * length);
        let friction = match self.law {
            (0, _) => Friction::Frictionless,
            (1, t) => Friction::Tresca(Threshold::Uniform(t * self.young * stress)),
            (_, mu) => Friction::Coulomb { mu },
        };
        (Problem::new(mesh, spec).expect("valid"), friction)
    }
}

fn any_case() -> impl Strategy<Value = RandomCase> {
    let geometry = (1.0f64..4.0, 0.5f64..2.0, 2usize..9, 1usize..5, -1.0f64..1.0, 0.3f64..5.0, any::<bool>());
    let physics = (-3i32..4, 0.0f64..0.45, 1e-3f64..2e-2, 0.0f64..1.0, 0usize..3, 0.05f64..0.8);
    let adapt = (0.01f64..0.5, 500usize..4000, 1usize..7, any::<bool>());
    (geometry, physics, adapt).prop_map(
        |((w, h, nx, ny, c, r, flat), (e, nu, d, s, law, k), (tol, n, levels, sharp))| RandomCase {
            w,
            h,
            nx,
            ny,
            young: 10f64.powi(e),
            poisson: nu,
            cylinder: (!flat).then_some((0.25 * c * w, r)),
            approach: d * h,
            shift: s * d * h,
            law: (law, if law == 1 { 1e-3 * k } else { k }),
            adapt: AdaptSettings {
                tol,
                max_unknowns: n,
                max_levels: levels,
                stop_on: if sharp { StopOn::Hierarchical } else { StopOn::Bound },
                ..AdaptSettings::default()
            },
        },
    )
}

proptest! {
    #![proptest_config(crate::reproducible(16))]

    /// Issue 37: whatever the loop stops on, the answer it hands back is what its status says: `converged`
    /// means finite fields and KKT residuals within the bound the tolerances justify, the loop stops as not
    /// converged exactly when the answer is not, and the last level is the answer's. The same problem in
    /// other units (lengths by 10^±2, E and the threshold by 10^±3) goes through the same levels to the same
    /// stop.
    #[test]
    fn every_adaptive_stop_hands_back_what_it_says(case in any_case(), length in -2i32..3, stress in -3i32..4) {
        let settings = SolverSettings::default();
        let (problem, friction) = case.problem(1.0, 1.0);
        let adapt = AdaptSettings { max_unknowns: case.adapt.max_unknowns.max(problem.n_free), ..case.adapt };
        let out = problem.solve_adaptive(&friction, &settings, &adapt, None).expect("a valid case adapts");
        let sol = &out.solution;
        let converged = sol.report.status == SolveStatus::Converged;
        prop_assert_eq!(out.stop == AdaptStop::NotConverged, !converged, "{:?} with {}", out.stop, sol.report.status);
        if converged {
            let bound = Solution::accuracy_bound(settings.qp.tol, sol.report.qp_inaccurate, settings.fp.tol);
            prop_assert!(sol.all_finite(), "a converged answer with non-finite fields");
            prop_assert!(sol.kkt.max() <= bound, "KKT {:?} above {bound:e}", sol.kkt);
        }
        let last = out.levels.last().expect("one level at least");
        prop_assert_eq!((last.unknowns, last.status), (out.problem.n_free, sol.report.status));
        let (scaled, friction) = case.problem(10f64.powi(length), 10f64.powi(stress));
        let again = scaled.solve_adaptive(&friction, &settings, &adapt, None).expect("a valid case adapts");
        let sizes = |a: &Adaptive| a.levels.iter().map(|l| l.unknowns).collect::<Vec<_>>();
        prop_assert_eq!((sizes(&out), out.stop), (sizes(&again), again.stop), "lengths × 1e{}, E × 1e{}", length, stress);
    }
}
