//! Study 24: a shrink fit, two bodies with a bent interface, against Lamé (issue 39).
//!
//! The quarter ring of `tribo_testkit::ShrinkFit` (radii 0.5–1.001, E = 1, ν = 0.3) shrunk into a quarter ring
//! (radii 1–2, E = 2, ν = 0.25), plane strain, rollers on the axes, non-matching faceted arcs, P1 multipliers on the
//! secondary's FE edges. Both rings are meshed uniformly, the outer one coarser along its inner arc by 7/8; each
//! mesh is solved with the gap between the arcs' circles (`curves`) and between the facets. Each row gives the
//! relative L2 error of λ_n against Lamé's uniform pressure (the closed form as posed, in the fixture's docs),
//! the force on the inner quarter against `−p (b + δ) (1, 1)`, and the two traction estimates tribo reports: the
//! residual bound and the hierarchical estimate. `shrink_fit_pressure.csv` holds λ_n along the arc on the second
//! mesh, with and without the circles.
//!
//! ```bash
//! cargo run --release -p tribo --example shrink_fit          # ~2 min on two cores: docs/shrink_fit*.csv
//! cargo run --release -p tribo --example shrink_fit quick    # three meshes: a smoke run
//! python scripts/plot_shrink_fit.py                          # docs/shrink_fit.{md,png}
//! ```

use std::io::Write;
use std::time::Instant;

use tribo::{Friction, SolveStatus, SolverSettings};
use tribo_testkit::{uniform_pressure_error, ShrinkFit};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let quick = std::env::args().nth(1).as_deref() == Some("quick");
    let sizes: &[f64] = if quick { &[0.08, 0.04, 0.02] } else { &[0.08, 0.04, 0.02, 0.01, 0.005] };
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
    let (path, profile_path) = (docs.join("shrink_fit.csv"), docs.join("shrink_fit_pressure.csv"));
    let partial = path.with_extension("csv.partial");
    let mut out = std::fs::File::create(&partial)?;
    writeln!(out, "h_inner,h_outer,curves,unknowns,seconds,pressure,l2_lame,force_error,bound,hierarchical")?;
    let mut profile = vec!["curves,angle,lambda_n".to_string()];
    let settings = SolverSettings::default();
    for (k, &h) in sizes.iter().enumerate() {
        for curves in [true, false] {
            let fit = ShrinkFit { curves, ..ShrinkFit::new([h, 1.75 * h]) };
            let clock = Instant::now();
            let problem = fit.problem();
            let sol = problem.solve(&Friction::Frictionless, &settings, None)?;
            let seconds = clock.elapsed().as_secs_f64();
            if sol.report.status != SolveStatus::Converged {
                return Err(format!("h {h}, curves {curves}: {}", sol.report.status).into());
            }
            let p = fit.lame_pressure();
            let l2 = uniform_pressure_error(&problem, &sol.lambda_n, p);
            let force = -p * (fit.radii[1] + fit.interference);
            let force_error = sol.contact_force.iter().map(|f| (f - force).abs()).fold(0.0, f64::max) / force.abs();
            let hierarchical = problem.estimate_hierarchical(&sol, &Friction::Frictionless, &settings)?;
            let bound = sol.report.estimate.traction_relative;
            writeln!(
                out,
                "{h},{},{curves},{},{seconds:.3},{p:.9e},{l2:.6e},{force_error:.6e},{bound:.6e},{:.6e}",
                1.75 * h,
                problem.n_free,
                hierarchical.relative
            )?;
            println!(
                "h {h}, curves {curves}: {} unknowns, {seconds:.2} s: λ_n against Lamé {l2:.3e}, force {force_error:.2e}, \
                 estimates {bound:.3e} (bound) {:.3e} (hierarchical)",
                problem.n_free, hierarchical.relative
            );
            if k == 1 {
                let c = &problem.contact;
                for (j, &xi) in problem.multipliers.xi.iter().enumerate() {
                    let q = c.point_at(xi);
                    profile.push(format!("{curves},{:.9},{:.9e}", q[1].atan2(q[0]), sol.lambda_n[j]));
                }
            }
        }
    }
    drop(out);
    std::fs::rename(partial, &path)?;
    std::fs::write(&profile_path, profile.join("\n") + "\n")?;
    println!("wrote {} and {}", path.display(), profile_path.display());
    Ok(())
}
