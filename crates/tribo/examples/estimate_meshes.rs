//! Is the hierarchical estimate as sharp on uniform and graded meshes as on adaptive ones? (issue 36, item 1:
//! "uniform, graded and adaptive meshes"; study 15b)
//!
//! Studies 13–15 measure the traction estimates on the levels of the adaptive loop. Here the same estimate
//! (`Problem::estimate_hierarchical`: the whole mesh bisected, the strip of half a contact width again, the reduction
//! measured at the ends of Γ_C in contact) is measured on meshes a user makes without the loop, against the references
//! of `tribo_testkit::adaptive_case`: Hertz (centred, frictionless; Coulomb μ = 0.3 with a shift; Tresca with a shift;
//! P0 multipliers) on uniform meshes of the (−2, 2) × (−2, 0) block (`nx × nx/2`, right diagonals) and on meshes graded
//! toward [−0.2, 0.2] of its top (`h_min`, growth 0.3, h_max 0.25); the block (Coulomb, the whole bottom in contact) on
//! uniform meshes (`nx × nx/4`) and on meshes graded toward its bottom (`h_min`, growth 0.3, h_max 0.25); two-body
//! Hertz (steel on aluminium, frictionless) on the scene's graded blocks (`tribo_testkit::two_body_hertz`, `h_min`).
//! Every mesh with at least 10 multiplier dofs in contact is counted (the threshold). Printed and written per
//! mesh: the unknowns, the dofs in contact, the true relative L²(Γ_C) error of λ, the hierarchical estimate and the
//! bound (`traction_relative`) over it, and the seconds of the solve and of the estimate.
//!
//! `cargo run --release -p tribo --example estimate_meshes [CASES [OUT]]` (CASES comma-separated, all six by
//! default: `hertz,hertz-coulomb,hertz-tresca,hertz-p0,block,two-body`; about 20 minutes, the references and the
//! Tresca estimates most of it) writes
//! `OUT/estimate_meshes.csv` (OUT `docs` by default), from which `python scripts/plot_estimate_meshes.py` writes
//! `docs/estimate_meshes.md`.
use std::io::Write;

use tribo::adapt::multiplier_difference;
use tribo::mesh::generate::{graded_rectangle, rectangle, Diagonal, Grading, Side};
use tribo::*;

/// The meshes of a case: (kind, size parameter, problem).
type Meshes = Vec<(&'static str, f64, Problem)>;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let names =
        std::env::args().nth(1).unwrap_or_else(|| "hertz,hertz-coulomb,hertz-tresca,hertz-p0,block,two-body".into());
    let docs = || std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
    let out = std::env::args().nth(2).map_or_else(docs, std::path::PathBuf::from);
    let (done, partial) = (out.join("estimate_meshes.csv"), out.join("estimate_meshes.csv.partial"));
    let mut csv = std::fs::File::create(&partial)?;
    writeln!(csv, "case,mesh,size,unknowns,in_contact,true_error,hierarchical,bound,solve_seconds,estimate_seconds")?;
    for name in names.split(',').map(str::trim) {
        let case = tribo_testkit::adaptive_case(name)?;
        let (reference, rsol) = &case.reference;
        println!("{name}: reference {}", case.reference_source);
        println!("mesh     size unknowns contact true-error hierarchical/true bound/true solve-s estimate-s");
        let settings = SolverSettings::default();
        for (kind, size, problem) in meshes(name, &case.coarse)? {
            let clock = std::time::Instant::now();
            let sol = problem.solve(&case.friction, &settings, None)?;
            let solve = clock.elapsed().as_secs_f64();
            let in_contact = sol.states.iter().filter(|c| **c != ContactState::Separation).count();
            if sol.report.status != SolveStatus::Converged || in_contact < 10 {
                println!(
                    "{kind:>8} {size:<6} {:>8} {in_contact:>4} (not counted: {})",
                    problem.n_free, sol.report.status
                );
                continue;
            }
            let (e, n) = multiplier_difference(&problem, &sol, reference, rsol);
            let truth = e / n;
            let clock = std::time::Instant::now();
            let h = problem.estimate_hierarchical(&sol, &case.friction, &settings)?;
            let estimate = clock.elapsed().as_secs_f64();
            let bound = sol.report.estimate.traction_relative;
            println!(
                "{kind:>8} {size:<6} {:>8} {in_contact:>4} {truth:.3e} {:>6.2} {:>6.2} {solve:>7.2} {estimate:>7.2}",
                problem.n_free,
                h.relative / truth,
                bound / truth
            );
            writeln!(
                csv,
                "{name},{kind},{size},{},{in_contact},{truth:.6e},{:.6e},{bound:.6e},{solve:.4},{estimate:.4}",
                problem.n_free, h.relative
            )?;
        }
    }
    drop(csv);
    std::fs::rename(&partial, &done)?;
    Ok(())
}

/// The uniform and graded meshes of case `name`, with the specification of its coarse start.
fn meshes(name: &str, coarse: &Problem) -> Result<Meshes> {
    let with = |mesh: Mesh| Problem::new(mesh, coarse.spec.clone());
    let mut out: Meshes = Vec::new();
    if name == "two-body" {
        let (steel, aluminium) = (Material { young: 200.0, poisson: 0.3 }, Material { young: 70.0, poisson: 0.33 });
        for h_min in [0.02, 0.01, 0.005, 0.0025] {
            out.push(("graded", h_min, tribo_testkit::two_body_hertz(h_min, steel, aluminium, false, 0.01)));
        }
        return Ok(out);
    }
    let block = name == "block";
    let (x, y, side, segment) = if block {
        ([0.0, 4.0], [0.0, 1.0], Side::Bottom, [0.0, 4.0])
    } else {
        ([-2.0, 2.0], [-2.0, 0.0], Side::Top, [-0.2, 0.2])
    };
    let (sizes, rows): (&[usize], usize) = if block { (&[32, 64, 128, 256], 4) } else { (&[362, 512], 2) };
    for &nx in sizes {
        out.push(("uniform", nx as f64, with(rectangle(x, y, nx, nx / rows, Diagonal::Right)?)?));
    }
    let h_mins: &[f64] =
        if block { &[0.02, 0.01, 0.005] } else { &[0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125, 0.00015625] };
    for &h_min in h_mins {
        let grading = Grading { side, segment, h_min, h_max: 0.25, growth: 0.3 };
        out.push(("graded", h_min, with(graded_rectangle(x, y, &grading)?)?));
    }
    Ok(out)
}
