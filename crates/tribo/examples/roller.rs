//! Study 22: a roller on a rigid flat against plane-strain Hertz and against a reference of its own (issue 39).
//!
//! The roller of `tribo_testkit::roller_problem` (radius 1, a bent Γ_C: the faceted rim of a ring sector, the
//! contact along the flat's normal) is pressed to contact half-widths a/R from 0.014 to 0.083. For each,
//! it is solved on meshes graded over ±2.5a at growth 0.075 to h = a/20, a/40 and a/80, and on a reference graded
//! at growth 0.0375 to a/160. Each row gives the relative L2 error of λ_n against Hertz's pressure of the computed force,
//! the second-moment contact width over Hertz's, and the relative L2 difference from the reference (read at the
//! same horizontal position). Hertz's half-space leaves out what grows with a/R (the roller's curvature and
//! finite size, the rotation of its surface where it is pressed flat): the reference measures the mesh's part.
//!
//! ```bash
//! cargo run --release -p tribo --example roller          # ~8 min on two cores: docs/roller.csv
//! cargo run --release -p tribo --example roller quick    # one a/R, coarser: a smoke run
//! python scripts/plot_roller.py                          # docs/roller.{md,png}
//! ```

use std::io::Write;
use std::time::Instant;

use tribo::{Friction, Problem, Solution, SolveStatus, SolverSettings};
use tribo_testkit::{roller_against_hertz, roller_against_reference, roller_graded};

/// The roller graded to `h_min` over ±`arc` rad, solved, and the seconds it took.
fn solve(
    h_min: f64,
    growth: f64,
    arc: f64,
    approach: f64,
) -> Result<(Problem, Solution, f64), Box<dyn std::error::Error>> {
    let clock = Instant::now();
    let problem = roller_graded(h_min, growth, arc, [1.0, 0.0], [0.0, 0.0], approach, 0.0);
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None)?;
    if sol.report.status != SolveStatus::Converged {
        return Err(format!("h_min {h_min}, approach {approach}: {}", sol.report.status).into());
    }
    Ok((problem, sol, clock.elapsed().as_secs_f64()))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let quick = std::env::args().nth(1).as_deref() == Some("quick");
    let approaches: &[f64] = if quick { &[0.0035] } else { &[0.0005, 0.002, 0.0035, 0.006, 0.012] };
    let (fractions, reference): (&[f64], f64) =
        if quick { (&[20.0, 40.0], 80.0) } else { (&[20.0, 40.0, 80.0], 160.0) };
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/roller.csv");
    let partial = path.with_extension("csv.partial");
    let mut out = std::fs::File::create(&partial)?;
    writeln!(out, "approach,a_over_r,h_over_a,growth,unknowns,seconds,force,l2_hertz,width_hertz,l2_reference")?;
    for &approach in approaches {
        // The half-width first, on a mesh of h = 0.005, to size the others, graded over ±2.5a.
        let (p0, s0, _) = solve(0.005, 0.075, 0.1, approach)?;
        let (_, _, a) = roller_against_hertz(&p0, &s0);
        let (pr, sr, tr) = solve(a / reference, 0.0375, 2.5 * a, approach)?;
        let mut rows = Vec::new();
        for &f in fractions {
            rows.push((f, 0.075, solve(a / f, 0.075, 2.5 * a, approach)?));
        }
        rows.push((reference, 0.0375, (pr.clone(), sr.clone(), tr)));
        for (f, growth, (p, s, seconds)) in rows {
            let (l2, width, a_r) = roller_against_hertz(&p, &s);
            let l2_ref = roller_against_reference(&p, &s, (&pr, &sr));
            writeln!(
                out,
                "{approach},{a_r:.6},{f},{growth},{},{seconds:.3},{:.9e},{l2:.6e},{width:.6},{l2_ref:.6e}",
                p.n_free, s.normal_force
            )?;
            println!(
                "approach {approach}: a/R {a_r:.4}, h = a/{f}, {} unknowns, {seconds:.2} s: λ_n against Hertz {l2:.3e}, \
                 width {width:.5}, against the reference {l2_ref:.3e}",
                p.n_free
            );
        }
    }
    drop(out);
    std::fs::rename(partial, &path)?;
    println!("wrote {}", path.display());
    Ok(())
}
