//! Does `tol` mean what it says for a loading history? (issue 36: the Cattaneo–Mindlin row of the `tol` and
//! effectivity tables)
//!
//! Hertz (centred, the 8 × 4 start of the other adaptive cases), Coulomb μ = 0.3: the cylinder pressed by
//! δ = 0.01, then dragged to s = 0.001, 0.002, 0.003, 0.004 (partial slip growing from both edges of the
//! contact zone; 0.004 is the shift of the static case `hertz-coulomb`). `solve_history_adaptive` from the
//! coarse start with `tol` = 5 %, 2 %, 1 %, 0.5 %, stopping on the bound and on the hierarchical estimate.
//! A history's error is that of its worst step: the true error is the largest over the steps of the relative
//! L²(Γ_C) error of λ against the same history on the 466k-unknown graded mesh of the Hertz cases.
//!
//! Printed per run: the asked X, the true error and its ratio to X, the unknowns, the run's time (the sum of
//! its levels' seconds), and the cheapest level of the same run whose true error is at most X with the time
//! the run took to reach it (levels solved again on their meshes, `Problem::on_level`, until it is found);
//! then, for the run at X = 0.5 % stopping on the hierarchical estimate, every level where the loop computed
//! the estimate: the effectivity of the level's estimate (its worst step's) and, per step, of the hierarchical
//! estimate and of the bound (`Problem::estimate_history_hierarchical` on the level solved again).
//!
//! `cargo run --release -p tribo --example history_tol [SHIFTS [STOPS]]` (SHIFTS: comma-separated, after the
//! first step at s = 0, or `default`; STOPS: `bound,hierarchical` by default). The hierarchical runs take a
//! few minutes on two cores; the bound's go to 300k–400k unknowns at 1 % and 0.5 % (half an hour). It writes
//! the runs to `OUT/hertz-coulomb-history-STOP.csv` and the levels solved again (with every step's estimates
//! where they were computed) to `OUT/hertz-coulomb-history-STOP_levels.csv`, one pair per stop (`history_tol
//! SHIFTS STOPS OUT`, OUT `docs/tol_table` by default), read by `python scripts/plot_tol_table.py`.
use std::io::Write;

use tribo::adapt::multiplier_difference;
use tribo::*;

/// The case's name in the `tol` table's files.
const CASE: &str = "hertz-coulomb-history";

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let shifts: Vec<f64> = match std::env::args().nth(1).filter(|s| s != "default") {
        Some(s) => s.split(',').map(|x| x.trim().parse().expect("shifts are numbers")).collect(),
        None => vec![0.001, 0.002, 0.003, 0.004],
    };
    let stops = std::env::args().nth(2).unwrap_or_else(|| "bound,hierarchical".into());
    let stops: Vec<StopOn> = stops.split(',').map(|s| Choice::parse(s.trim())).collect::<Result<_>>()?;
    let out = std::env::args().nth(3).map_or_else(tribo_testkit::tol_table_dir, std::path::PathBuf::from);
    let steps: Vec<LoadStep> = std::iter::once(0.0).chain(shifts).map(|s| LoadStep::new(0.01, s)).collect();
    let case = tribo_testkit::adaptive_hertz_case(0.0, Friction::Coulomb { mu: 0.3 }, MultiplierSpace::P1)?;
    let (friction, coarse, reference) = (case.friction, case.coarse, case.reference.0);
    let settings = SolverSettings::default();
    let clock = std::time::Instant::now();
    let rhist = reference.solve_history(&friction, &steps, &settings, None)?;
    println!(
        "reference: {} ({} steps, {}, {:.1} s)",
        case.reference_source,
        steps.len(),
        rhist.status,
        clock.elapsed().as_secs_f64()
    );
    // The true error of each step of a history on problem p.
    let step_errors = |p: &Problem, h: &History| -> Vec<f64> {
        let pairs = h.solutions.iter().zip(&rhist.solutions);
        pairs.map(|(s, r)| multiplier_difference(p, s, &reference, r)).map(|(e, n)| e / n).collect()
    };
    let worst = |errors: &[f64]| errors.iter().copied().fold(0.0, f64::max);
    println!("{}", tribo_testkit::TOL_TABLE_HEADER);
    let mut estimated = Vec::new();
    for stop_on in stops {
        let (mut runs, mut levels) = tribo_testkit::tol_table_files(&out, CASE, stop_on)?;
        for tol in [0.05, 0.02, 0.01, 0.005] {
            let adapt = AdaptSettings { tol, stop_on, max_unknowns: 400_000, ..AdaptSettings::default() };
            let run = coarse.solve_history_adaptive(&friction, &steps, &settings, &adapt, &[], None)?;
            let achieved = worst(&step_errors(&run.problem, &run.history));
            let total: f64 = run.levels.iter().map(|l| l.seconds).sum();
            let (mut cheapest, mut elapsed) = (None, 0.0);
            let keep = stop_on == StopOn::Hierarchical && tol == 0.005;
            for (k, level) in run.levels.iter().enumerate() {
                elapsed += level.seconds;
                let sharp = level.estimate.traction_hierarchical_relative;
                if cheapest.is_some() && !(keep && sharp.is_some()) {
                    continue;
                }
                let p = coarse.on_level(level)?;
                let h = p.solve_history(&friction, &steps, &settings, None)?;
                let errors = step_errors(&p, &h);
                if cheapest.is_none() && worst(&errors) <= tol {
                    cheapest = Some((level.unknowns, elapsed));
                }
                let touching = |s: &Solution| s.states.iter().filter(|c| **c != ContactState::Separation).count();
                let row = tribo_testkit::LevelRow {
                    level: k,
                    unknowns: level.unknowns,
                    seconds: level.seconds,
                    step: None,
                    in_contact: h.solutions.iter().map(touching).max().unwrap_or(0),
                    true_error: worst(&errors),
                    hierarchical: sharp,
                    bound: level.estimate.traction_relative,
                    calibrated: level.estimate.traction_calibrated_relative,
                };
                writeln!(levels, "{}", row.csv(CASE, stop_on, tol))?;
                if let (true, Some(sharp)) = (keep, sharp) {
                    let each = p.estimate_history_hierarchical(&h, &friction, &settings)?;
                    for (i, ((e, s), t)) in each.iter().zip(&h.solutions).zip(&errors).enumerate() {
                        let row = tribo_testkit::LevelRow {
                            step: Some(i),
                            in_contact: touching(s),
                            true_error: *t,
                            hierarchical: Some(e.relative),
                            bound: s.report.estimate.traction_relative,
                            calibrated: s.report.estimate.traction_calibrated_relative,
                            ..row
                        };
                        writeln!(levels, "{}", row.csv(CASE, stop_on, tol))?;
                    }
                    let ratios: Vec<(f64, f64)> = (each.iter().zip(&h.solutions).zip(&errors))
                        .map(|((e, s), t)| (e.relative / t, s.report.estimate.traction_relative / t))
                        .collect();
                    estimated.push((level.unknowns, worst(&errors), sharp / worst(&errors), ratios));
                }
            }
            println!(
                "{}",
                tribo_testkit::tol_table_row((stop_on, tol), achieved, (run.problem.n_free, total), cheapest, run.stop)
            );
            let sizes = (run.problem.n_free, total, run.levels.len());
            writeln!(
                runs,
                "{}",
                tribo_testkit::tol_table_csv(CASE, (stop_on, tol), achieved, sizes, cheapest, run.stop)
            )?;
        }
    }
    println!("levels of the hierarchical run at tol 0.005 where it computed the estimate:");
    println!("unknowns worst-true level-estimate/worst-true | per step: hierarchical/true (bound/true)");
    for (n, truth, level, ratios) in estimated {
        let steps: Vec<String> = ratios.iter().map(|(h, b)| format!("{h:.2} ({b:.1})")).collect();
        println!("{n:>8} {truth:.3e} {level:.3} | {}", steps.join(" "));
    }
    Ok(())
}
