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
//! Cholesky of K + one solve with faer's defaults, best of 3 at small sizes) and the ratio of the two; then
//! the same with faer's supernodal Cholesky, sequential (`cholesky_supernodal`, `ratio_supernodal`): the analysis
//! tribo's own factor of A takes, faster than faer's automatic choice on these meshes.
//!
//! `two_bodies`: study 8's two-body Hertz with equal materials (`tribo_testkit::two_body_hertz`: the Hertz
//! block under an elastic block (−2, 2) × (0, 1) pushed down 0.01, a parabolic gap, both graded at growth
//! 0.15), no shift (two bodies move through their supports).
//!
//! Memory: every case (family, mesh, friction law) runs in a fresh process (the example runs itself with
//! `--case FAMILY INDEX FRICTION`), so its peak resident memory (Linux's VmHWM; NaN elsewhere) is its own:
//! `setup_mb` after the problem is built, `peak_mb` after the solve (the problem included, the Cholesky
//! reference after it): what a run needs at most.
//!
//! Every mesh is solved frictionless (one QP) and with Coulomb friction, by the fixed point (`coulomb`) and by
//! the semismooth Newton method (`coulomb_newton`, issue 40), each in its own process (so each
//! pays for its own assembly and factorization); the Coulomb solve is no longer timed on finer meshes of a
//! family once it did not converge or took more than MAX_SECONDS / 2.
//!
//! `cargo run --release -p tribo --example cost [MAX_SECONDS]`: a family stops growing once one solve
//! took more than MAX_SECONDS (default 30), so the largest run stays under about a minute.
use std::io::Write;
use std::time::Instant;

use faer::linalg::solvers::Solve;
use faer::Mat;
use tribo::*;
use tribo_testkit::{block_problem, hertz_mesh, hertz_scene, hertz_spec, peak_mb, two_body_hertz};

/// Builds a problem when called (the largest take seconds).
type Build = Box<dyn Fn() -> Result<Problem>>;

/// The problems of a family: the size parameter and the problem's builder.
fn problems(family: &str) -> Vec<(f64, Build)> {
    if family == "two_bodies" {
        let steel = Material { young: 200.0, poisson: 0.3 };
        return [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125]
            .iter()
            .map(|&h: &f64| -> (f64, Build) { (h, Box::new(move || Ok(two_body_hertz(h, steel, steel, false, 0.01)))) })
            .collect();
    }
    if family == "block" {
        return [100usize, 200, 400, 800]
            .iter()
            .map(|&nx| -> (f64, Build) { (4.0 / nx as f64, Box::new(move || Ok(block_problem(nx, nx / 4).0))) })
            .collect();
    }
    // The meshes are made when a case builds its problem (a case runs in its own process and must not
    // hold the family's other meshes: they would count in its peak memory).
    if family == "uniform" {
        return [40usize, 80, 160, 240, 320, 400, 560, 720]
            .iter()
            .map(|&nx| -> (f64, Build) {
                let build = move || {
                    let s = hertz_scene();
                    Problem::new(rectangle(s.x, s.y, nx, nx / 2, Diagonal::Right)?, spec())
                };
                (4.0 / nx as f64, Box::new(build))
            })
            .collect();
    }
    [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125, 0.00015625]
        .iter()
        .map(|&h_min: &f64| -> (f64, Build) { (h_min, Box::new(move || Problem::new(hertz_mesh(h_min), spec()))) })
        .collect()
}

fn spec() -> ProblemSpec {
    hertz_spec(hertz_scene().approach, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
}

/// Symbolic + numeric sparse Cholesky of K and one solve with faer's defaults (its automatic choice between the
/// simplicial and the supernodal factor; simplicial on these meshes), and with the supernodal factor, sequential
/// (the analysis tribo's factor of A takes): the two times in seconds (each the best of `reps`, alternated).
fn cholesky_seconds(problem: &Problem, reps: usize) -> [f64; 2] {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef};
    use faer::sparse::linalg::SupernodalThreshold;
    let n = problem.n_free;
    let k = problem.k_matrix.as_ref();
    let f: Vec<f64> = (0..n).map(|i| ((i % 7) as f64) - 3.0).collect();
    let mut best = [f64::INFINITY; 2];
    for _ in 0..reps {
        let clock = Instant::now();
        let llt = problem.k_matrix.sp_cholesky(faer::Side::Lower).expect("K is positive definite");
        let mut x = Mat::from_fn(n, 1, |i, _| f[i]);
        llt.solve_in_place(x.as_mut());
        best[0] = best[0].min(clock.elapsed().as_secs_f64());
        std::hint::black_box(&x);
        let clock = Instant::now();
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(k.symbolic(), faer::Side::Lower, Default::default(), params)
            .expect("K's pattern is valid");
        let mut values = vec![0.0; symbolic.len_val()];
        let par = faer::Par::Seq;
        let mut mem = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        symbolic
            .factorize_numeric_llt(
                &mut values,
                k,
                faer::Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .expect("K is positive definite");
        let mut x = Mat::from_fn(n, 1, |i, _| f[i]);
        let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
        LltRef::new(&symbolic, &values).solve_in_place_with_conj(
            faer::Conj::No,
            x.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
        best[1] = best[1].min(clock.elapsed().as_secs_f64());
        std::hint::black_box(&x);
    }
    best
}

/// One case in this process (`--case FAMILY INDEX FRICTION`): builds the problem, solves it, reads the
/// peak memory, then times the Cholesky reference; prints the CSV row after `ROW ` and the readable line.
fn case(family: &str, index: usize, friction: &str) -> Result<()> {
    let Some((h, build)) = problems(family).into_iter().nth(index) else { return Ok(()) };
    let clock = Instant::now();
    let problem = build()?;
    let setup = clock.elapsed().as_secs_f64();
    let setup_mb = peak_mb();
    let law = if friction.starts_with("coulomb") { Friction::Coulomb { mu: 0.3 } } else { Friction::Frictionless };
    // `coulomb_newton`: the semismooth Newton method instead of the fixed point (issue 40).
    let coulomb = if friction == "coulomb_newton" { CoulombMethod::Newton } else { CoulombMethod::FixedPoint };
    let settings = SolverSettings { coulomb, ..Default::default() };
    let clock = Instant::now();
    let sol = problem.solve(&law, &settings, None)?;
    let total = setup + clock.elapsed().as_secs_f64();
    let solve_mb = peak_mb();
    let [chol, chol_supernodal] = cholesky_seconds(&problem, if problem.n_free < 50_000 { 3 } else { 1 });
    let t = &sol.report.timings;
    let status = sol.report.status.name();
    let cols = [t.assembly + t.contact_matrices, t.factorization + t.condensation, t.qp, t.recovery, total, chol];
    println!(
        "{family:<10} {h:>9.6} {:>7} {:>5} {friction:>12} {status:>13} {:>4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>6.1} {solve_mb:>7.0} {:>6.1}",
        problem.n_free,
        problem.n_multipliers(),
        sol.report.iterations,
        cols[0], cols[1], cols[2], cols[3], cols[4], cols[5], total / chol, total / chol_supernodal
    );
    let by = |m: QpMethod| sol.report.qp_methods.iter().filter(|x| **x == m).count();
    let cols: Vec<String> = cols.iter().chain([&(total / chol)]).map(|v| format!("{v:.6}")).collect();
    let supernodal = [chol_supernodal, total / chol_supernodal].map(|v| format!("{v:.6}"));
    println!(
        "ROW {family},{h},{},{},{friction},{status},{},{},{},{},{},{setup_mb:.1},{solve_mb:.1},{}",
        problem.n_free,
        problem.n_multipliers(),
        sol.report.iterations,
        sol.report.condensation,
        by(QpMethod::ActiveSet),
        by(QpMethod::Clarabel),
        cols.join(","),
        supernodal.join(",")
    );
    Ok(())
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("--case") {
        let index = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(usize::MAX);
        return case(&args[2], index, args.get(4).map_or("frictionless", String::as_str));
    }
    let max_seconds: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(30.0);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cost.csv");
    std::fs::create_dir_all(path.parent().unwrap()).expect("docs/ is writable");
    let mut csv = std::fs::File::create(&path).expect("docs/cost.csv is writable");
    writeln!(
        csv,
        "family,h,n_free,q,friction,status,iterations,condensation,qp_active_set,qp_clarabel,problem_new,condensed,qp,recovery,total,cholesky,ratio,setup_mb,peak_mb,cholesky_supernodal,ratio_supernodal"
    )
    .unwrap();
    println!(
        "{:<10} {:>9} {:>7} {:>5} {:>12} {:>13} {:>4} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>6} {:>7} {:>6}",
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
        "ratio",
        "peak MB",
        "× sn"
    );
    let me = std::env::current_exe().expect("the running example has a path");
    for family in ["uniform", "graded", "block", "two_bodies"] {
        let mut coulomb_on = true;
        for index in 0..problems(family).len() {
            let mut slowest: f64 = 0.0;
            let frictions: &[&str] =
                if coulomb_on { &["frictionless", "coulomb", "coulomb_newton"] } else { &["frictionless"] };
            for friction in frictions {
                // Each case in a fresh process: its own factorization, and a peak memory of its own.
                let out = std::process::Command::new(&me)
                    .args(["--case", family, &index.to_string(), friction])
                    .output()
                    .expect("the example runs itself");
                let text = String::from_utf8_lossy(&out.stdout);
                let Some(row) = text.lines().find_map(|l| l.strip_prefix("ROW ")) else {
                    println!("{family} {index} {friction}: failed ({})", String::from_utf8_lossy(&out.stderr));
                    coulomb_on = false;
                    continue;
                };
                text.lines().filter(|l| !l.starts_with("ROW ")).for_each(|l| println!("{l}"));
                writeln!(csv, "{row}").unwrap();
                csv.flush().unwrap();
                let fields: Vec<&str> = row.split(',').collect();
                let total: f64 = fields[14].parse().unwrap_or(f64::INFINITY);
                slowest = slowest.max(total);
                if friction.starts_with("coulomb") && (fields[5] != "converged" || total > max_seconds / 2.0) {
                    println!("{family}: the Coulomb solve is not timed on finer meshes ({}, {total:.1} s)", fields[5]);
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
