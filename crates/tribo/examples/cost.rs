//! Cost per phase of a Coulomb solve, against one sparse Cholesky factorization + solve of K alone (the
//! plain elastic solve a contact solve is compared with).
//!
//! Scenes: Hertz (`python/tribo/scenes/hertz.toml`: rigid cylinder R = 1 pushed δ = 0.01 into
//! (−2, 2) × (−2, 0), clamped at the bottom, E = 200, ν = 0.3, Coulomb μ = 0.3 with an obstacle shift
//! s = 0.004) on two mesh families, `uniform` (rectangle nx × nx/2, right diagonals) and `graded` (graded
//! toward [−0.3, 0.3] on the top side, h_max = 0.5, growth 0.3); and `block`
//! (`python/tribo/scenes/block.toml`: a block (0, 4) × (0, 1) dragged on a flat foundation along its
//! whole bottom edge, μ = 0.3), uniform nx × nx/4. P1 multipliers on T_H = the FE edges, γ0 = 0.5 × its
//! admissible bound, default solver settings (the active-set QP method, H by columns or by the partial
//! factorization as `condensation = auto` chooses; the CSV says which).
//!
//! For every mesh and friction law it prints and writes to `docs/cost.csv` the time of each phase (seconds):
//! `problem_new` = [`Problem::new`] (assembly of K and the loads + Γ_C matrices), `condensed` =
//! [`Problem::condense`] work (numeric factorization of K − G + condensation onto Γ_C, including the
//! columns of H formed on demand by the QPs), `qp` (all QPs of the fixed point), `recovery`, the whole solve
//! `total` (wall clock of `Problem::new` + `solve`), the Cholesky reference (symbolic + numeric sparse
//! Cholesky of K + one solve, best of 3 at small sizes) and the ratio of the two.
//!
//! Every mesh is solved frictionless (one QP) and with Coulomb friction; the Coulomb solve is no longer
//! timed on finer meshes of a family once it did not converge or took more than MAX_SECONDS / 2.
//!
//! `cargo run --release -p tribo --example cost [MAX_SECONDS]`: a family stops growing once one solve
//! took more than MAX_SECONDS (default 30), so the largest run stays under about a minute.
use std::io::Write;
use std::time::Instant;

use faer::linalg::solvers::Solve;
use faer::Mat;
use tribo::*;
use tribo_testkit::{block_problem, hertz_mesh, hertz_scene, hertz_spec};

/// Builds a problem when called (the largest take seconds).
type Build = Box<dyn Fn() -> Result<Problem>>;

/// The problems of a family: the size parameter and the problem's builder.
fn problems(family: &str) -> Vec<(f64, Build)> {
    if family == "block" {
        return [100usize, 200, 400, 800]
            .iter()
            .map(|&nx| -> (f64, Build) { (4.0 / nx as f64, Box::new(move || Ok(block_problem(nx, nx / 4).0))) })
            .collect();
    }
    meshes(family)
        .into_iter()
        .map(|(h, mesh)| -> (f64, Box<dyn Fn() -> Result<Problem>>) {
            (h, Box::new(move || Problem::new(mesh.clone(), spec())))
        })
        .collect()
}

/// One mesh of a family: its label, the size parameter and the mesh.
fn meshes(family: &str) -> Vec<(f64, Mesh)> {
    match family {
        "uniform" => [40usize, 80, 160, 240, 320, 400, 560, 720]
            .iter()
            .map(|&nx| {
                let s = hertz_scene();
                let mesh = rectangle(s.x, s.y, nx, nx / 2, Diagonal::Right).expect("valid");
                (4.0 / nx as f64, mesh)
            })
            .collect(),
        _ => [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125, 0.00015625]
            .iter()
            .map(|&h_min| (h_min, hertz_mesh(h_min)))
            .collect(),
    }
}

fn spec() -> ProblemSpec {
    hertz_spec(hertz_scene().approach, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
}

/// Symbolic + numeric sparse Cholesky of K and one solve; returns the time in seconds (best of `reps`).
fn cholesky_seconds(problem: &Problem, reps: usize) -> f64 {
    let n = problem.n_free;
    let f: Vec<f64> = (0..n).map(|i| ((i % 7) as f64) - 3.0).collect();
    let mut best = f64::INFINITY;
    for _ in 0..reps {
        let clock = Instant::now();
        let llt = problem.k_matrix.sp_cholesky(faer::Side::Lower).expect("K is positive definite");
        let mut x = Mat::from_fn(n, 1, |i, _| f[i]);
        llt.solve_in_place(x.as_mut());
        best = best.min(clock.elapsed().as_secs_f64());
        std::hint::black_box(&x);
    }
    best
}

fn main() -> Result<()> {
    let max_seconds: f64 = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(30.0);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cost.csv");
    std::fs::create_dir_all(path.parent().unwrap()).expect("docs/ is writable");
    let mut csv = std::fs::File::create(&path).expect("docs/cost.csv is writable");
    writeln!(
        csv,
        "family,h,n_free,q,friction,status,iterations,condensation,qp_active_set,qp_clarabel,problem_new,condensed,qp,recovery,total,cholesky,ratio"
    )
    .unwrap();
    println!(
        "{:<8} {:>9} {:>7} {:>5} {:>12} {:>13} {:>4} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>6}",
        "family",
        "h",
        "n_free",
        "q",
        "friction",
        "status",
        "it",
        "new [s]",
        "cond [s]",
        "QPs [s]",
        "rec [s]",
        "total[s]",
        "chol [s]",
        "ratio"
    );
    for family in ["uniform", "graded", "block"] {
        let mut coulomb_on = true;
        for (h, build) in problems(family) {
            let clock = Instant::now();
            let problem = build()?;
            let setup = clock.elapsed().as_secs_f64();
            let reps = if problem.n_free < 50_000 { 3 } else { 1 };
            let chol = cholesky_seconds(&problem, reps);
            let mut slowest: f64 = 0.0;
            let frictions: &[(&str, Friction)] = if coulomb_on {
                &[("frictionless", Friction::Frictionless), ("coulomb", Friction::Coulomb { mu: 0.3 })]
            } else {
                &[("frictionless", Friction::Frictionless)]
            };
            // (μ = 0.3 in both scene files.)
            for (name, friction) in frictions {
                // Each solve pays for its own factorization (the problem would reuse the previous one).
                problem.forget_factorization();
                let clock = Instant::now();
                let sol = problem.solve(friction, &SolverSettings::default(), None)?;
                let total = setup + clock.elapsed().as_secs_f64();
                slowest = slowest.max(total);
                let t = &sol.report.timings;
                let status = sol.report.status.name();
                let cols = [
                    t.assembly + t.contact_matrices,
                    t.factorization + t.condensation,
                    t.qp,
                    t.recovery,
                    total,
                    chol,
                    total / chol,
                ];
                println!(
                    "{family:<8} {h:>9.6} {:>7} {:>5} {name:>12} {status:>13} {:>4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>6.1}",
                    problem.n_free,
                    problem.n_multipliers(),
                    sol.report.iterations,
                    cols[0], cols[1], cols[2], cols[3], cols[4], cols[5], cols[6]
                );
                let cols: Vec<String> = cols.iter().map(|v| format!("{v:.6}")).collect();
                let by = |m: QpMethod| sol.report.qp_methods.iter().filter(|x| **x == m).count();
                writeln!(
                    csv,
                    "{family},{h},{},{},{name},{status},{},{},{},{},{}",
                    problem.n_free,
                    problem.n_multipliers(),
                    sol.report.iterations,
                    sol.report.condensation,
                    by(QpMethod::ActiveSet),
                    by(QpMethod::Clarabel),
                    cols.join(",")
                )
                .unwrap();
                csv.flush().unwrap();
                if *name == "coulomb" && (sol.report.status != SolveStatus::Converged || total > max_seconds / 2.0) {
                    println!("{family}: the Coulomb solve is not timed on finer meshes ({status}, {total:.1} s)");
                    coulomb_on = false;
                }
            }
            if slowest > max_seconds {
                println!("{family}: one solve took {slowest:.1} s > {max_seconds} s, stopping this family");
                break;
            }
        }
    }
    println!("wrote {}", path.display());
    Ok(())
}
