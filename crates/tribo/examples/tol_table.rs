//! Does `tol` mean what it says? (issue 36, item 2: the `tol` table)
//!
//! The adaptive case `CASE` (`tribo_testkit::ADAPTIVE_CASES`: Hertz centred, off-centre, Coulomb, Tresca, with P0
//! multipliers; the block; two-body Hertz, frictionless and Coulomb; `hertz` by default) solved by
//! `solve_adaptive` from its coarse start with `tol` = 5 %, 2 %, 1 %, 0.5 %, stopping on the bound and on
//! the hierarchical estimate. The true error is the relative L²(Γ_C) error of λ against the case's
//! reference (for Hertz a graded mesh of 466k unknowns, study 12's; else, Tresca Hertz's too, the adaptive loop run to
//! 500k unknowns); every level of every run is solved again on its mesh (`Problem::on_level`) to measure it. Printed per run: the asked X, the true error
//! of the answer handed back and its ratio to X, the unknowns, the run's time (the sum of its levels'
//! seconds, the hierarchical solves included), and the cheapest level of the same run whose true error is
//! at most X with the time the run took to reach it; then, per level where the hierarchical estimate was
//! computed, its effectivity (estimate over true error) beside the bound's.
//!
//! `cargo run --release -p tribo --example tol_table [CASE [STOPS [OUT]]]` (a few minutes: the reference solve
//! and the re-solves of the levels are most of it; STOPS a comma-separated list of `bound`, `hierarchical`, both
//! by default). It writes the runs to `OUT/CASE-STOP.csv` and every level of every run to
//! `OUT/CASE-STOP_levels.csv`, one pair per stop (OUT `docs/tol_table` by default), from which
//! `python scripts/plot_tol_table.py` writes `docs/tol_table.md`.
use std::io::Write;

use tribo::adapt::multiplier_difference;
use tribo::*;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let name = std::env::args().nth(1).unwrap_or_else(|| "hertz".into());
    let stops = std::env::args().nth(2).unwrap_or_else(|| "bound,hierarchical".into());
    let stops: Vec<StopOn> = stops.split(',').map(|s| Choice::parse(s.trim())).collect::<Result<_>>()?;
    let out = std::env::args().nth(3).map_or_else(tribo_testkit::tol_table_dir, std::path::PathBuf::from);
    let case = tribo_testkit::adaptive_case(&name)?;
    let (friction, coarse) = (case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    println!("{name}: reference {} ({})", case.reference_source, rsol.report.status);
    let true_error = |p: &Problem, s: &Solution| {
        let (e, n) = multiplier_difference(p, s, &reference, &rsol);
        e / n
    };
    println!("{}", tribo_testkit::TOL_TABLE_HEADER);
    let mut effectivities = Vec::new();
    for stop_on in stops {
        let (mut runs, mut levels) = tribo_testkit::tol_table_files(&out, &name, stop_on)?;
        for tol in [0.05, 0.02, 0.01, 0.005] {
            let adapt = AdaptSettings { tol, stop_on, max_unknowns: 400_000, ..AdaptSettings::default() };
            let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
            let achieved = true_error(&run.problem, &run.solution);
            let total: f64 = run.levels.iter().map(|l| l.seconds).sum();
            let mut cheapest = None;
            let mut elapsed = 0.0;
            for (k, level) in run.levels.iter().enumerate() {
                elapsed += level.seconds;
                let p = coarse.on_level(level)?;
                let sol = p.solve(&friction, &settings, None)?;
                let truth = true_error(&p, &sol);
                if cheapest.is_none() && truth <= tol {
                    cheapest = Some((level.unknowns, elapsed));
                }
                let e = &level.estimate;
                let touching = sol.states.iter().filter(|c| **c != ContactState::Separation).count();
                let row = tribo_testkit::LevelRow {
                    level: k,
                    unknowns: level.unknowns,
                    seconds: level.seconds,
                    step: None,
                    in_contact: touching,
                    true_error: truth,
                    hierarchical: e.traction_hierarchical_relative,
                    bound: e.traction_relative,
                    calibrated: e.traction_calibrated_relative,
                };
                writeln!(levels, "{}", row.csv(&name, stop_on, tol))?;
                let sharp =
                    e.traction_hierarchical_relative.filter(|_| stop_on == StopOn::Hierarchical && tol == 0.005);
                if let Some(sharp) = sharp {
                    effectivities.push((level.unknowns, truth, sharp / truth, e.traction_relative / truth));
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
                tribo_testkit::tol_table_csv(&name, (stop_on, tol), achieved, sizes, cheapest, run.stop)
            )?;
        }
    }
    println!("levels of the hierarchical run at tol 0.005 where it computed the estimate:");
    println!("unknowns true-error hierarchical/true bound/true");
    for (n, truth, h, b) in effectivities {
        println!("{n:>8} {truth:.3e} {h:.3} {b:.2}");
    }
    Ok(())
}
