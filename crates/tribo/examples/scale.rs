//! Where the time and the memory of one large solve go: the uniform Hertz block of the cost study
//! (`python/tribo/scenes/hertz.toml`: (−2, 2) × (−2, 0), nx × nx/2 cells, right diagonals, rigid cylinder
//! R = 1 pushed δ = 0.01, Coulomb μ = 0.3 with an obstacle shift s = 0.004, P1 multipliers on the FE edges),
//! one size per process so that each peak resident memory is its own.
//!
//! For each phase it prints the wall time and the peak resident memory after it (Linux's VmHWM): the mesh
//! generation, `Problem::new` (assembly of K and the loads, Γ_C matrices), the solve (with the report's
//! factorization, condensation, QP and recovery times, and what is in none of them), then one sparse
//! Cholesky of K with one solve (the plain elastic solve a contact solve is compared with), once the
//! contact solve's factor is freed.
//!
//! `cargo run --release -p tribo --example scale -- NX [frictionless|coulomb] [auto|columns|schur|saddle]` (NX = 1000 gives about
//! one million unknowns, 1414 two million).
use std::time::Instant;

use faer::linalg::solvers::Solve;
use faer::Mat;
use tribo::*;
use tribo_testkit::{hertz_scene, hertz_spec, peak_mb};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let nx: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1000);
    let coulomb = args.get(2).map(String::as_str) != Some("frictionless");
    let mut settings = SolverSettings::default();
    if let Some(name) = args.get(3) {
        settings.condensation = match name.as_str() {
            "columns" => Condensation::Columns,
            "schur" => Condensation::Schur,
            "saddle" => Condensation::Saddle,
            _ => Condensation::Auto,
        };
    }
    let s = hertz_scene();
    let clock = Instant::now();
    let mesh = rectangle(s.x, s.y, nx, nx / 2, Diagonal::Right)?;
    let t_mesh = clock.elapsed().as_secs_f64();
    let mb_mesh = peak_mb();
    let clock = Instant::now();
    let problem =
        Problem::new(mesh, hertz_spec(s.approach, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1))?;
    let t_problem = clock.elapsed().as_secs_f64();
    let mb_problem = peak_mb();
    let law = if coulomb { Friction::Coulomb { mu: 0.3 } } else { Friction::Frictionless };
    let clock = Instant::now();
    let sol = problem.solve(&law, &settings, None)?;
    let t_solve = clock.elapsed().as_secs_f64();
    let mb_solve = peak_mb();
    let n = problem.n_free;
    let t = &sol.report.timings;
    let accounted = t.factorization + t.condensation + t.qp + t.recovery + t.fields;
    let (t, status, condensation) = (*t, sol.report.status.name(), sol.report.condensation);
    // The reference factorizes K alone: the contact solve's factor is freed first.
    drop(sol);
    problem.forget_factorization();
    let clock = Instant::now();
    let llt = problem
        .k_matrix
        .sp_cholesky(faer::Side::Lower)
        .map_err(|e| Error::Assembly { matrix: "K", what: format!("the reference Cholesky failed: {e:?}") })?;
    let mut x = Mat::from_fn(n, 1, |i, _| ((i % 7) as f64) - 3.0);
    llt.solve_in_place(x.as_mut());
    let t_chol = clock.elapsed().as_secs_f64();
    std::hint::black_box(&x);
    let total = t_mesh + t_problem + t_solve;
    // The size of the Cholesky factor's values: the floor of any solve that factorizes K.
    let symbolic = faer::sparse::linalg::cholesky::factorize_symbolic_cholesky(
        problem.k_matrix.symbolic(),
        faer::Side::Lower,
        Default::default(),
        Default::default(),
    )
    .map_err(|e| Error::Assembly { matrix: "K", what: format!("the symbolic Cholesky failed: {e:?}") })?;
    let l_mb = symbolic.len_val() as f64 * 8.0 / 1048576.0;
    let k_mb = problem.k_matrix.compute_nnz() as f64 * 16.0 / 1048576.0;
    println!("unknowns {n}, multipliers {}, status {}, H by {:?}", problem.n_multipliers(), status, condensation);
    println!("{:<34} {:>9} {:>10}", "phase", "seconds", "peak MB");
    println!("{:<34} {t_mesh:>9.3} {mb_mesh:>10.0}", "mesh generation");
    println!("{:<34} {t_problem:>9.3} {mb_problem:>10.0}", "Problem::new");
    println!("{:<34} {:>9.3}", "  of which assembly", t.assembly);
    println!("{:<34} {:>9.3}", "  of which contact matrices", t.contact_matrices);
    println!("{:<34} {t_solve:>9.3} {mb_solve:>10.0}", "solve");
    println!("{:<34} {:>9.3}", "  of which factorization", t.factorization);
    println!("{:<34} {:>9.3}", "  of which condensation", t.condensation);
    println!("{:<34} {:>9.3}", "  of which QPs", t.qp);
    println!("{:<34} {:>9.3}", "  of which recovery", t.recovery);
    println!("{:<34} {:>9.3}", "  of which fields", t.fields);
    println!("{:<34} {:>9.3}", "  in none of them", t_solve - accounted);
    println!("{:<34} {t_chol:>9.3} {:>10.0}", "Cholesky of K + one solve", peak_mb());
    println!(
        "K: {k_mb:.0} MB ({:.2} kB per unknown); the values of its Cholesky factor L: {l_mb:.0} MB ({:.2} kB per unknown)",
        k_mb * 1024.0 / n as f64,
        l_mb * 1024.0 / n as f64
    );
    println!(
        "whole run {total:.3} s = {:.2} x the Cholesky; peak {:.0} MB = {:.2} kB per unknown (before the Cholesky)",
        total / t_chol,
        mb_solve,
        mb_solve * 1024.0 / n as f64
    );
    Ok(())
}
