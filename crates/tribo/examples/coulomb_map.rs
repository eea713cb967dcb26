//! Study 20 (issue 40): which Coulomb method converges where. The fixed point of Φ_H (the reference) and the
//! semismooth Newton method solve the same problems over the friction coefficient μ and a second axis that
//! drives the fixed point's contraction, Poisson's ratio ν (at ν = 0 the normal and tangential problems
//! couple the most), on two scenes:
//!
//! * `hertz`: the Hertz scene (`tribo_testkit::hertz_problem`, graded, h_min 0.01) with the cylinder pushed
//!   0.01 and shifted 0.004: displacement control;
//! * `held block`: a block (0, 2) × (0, 1) held only by the contact, pressed onto a flat foundation by a
//!   traction (τ, −1) on its top: force control, τ a fraction (`load_fraction`) of what holds the block,
//!   min(μ, 1) (friction, and its overturning: the moment τ · 1 · 2 about a bottom corner against the
//!   pressure's 2 · 1). The discrete problem holds less: the P1 multipliers put the pressure at best on the last
//!   dof, whose hat function's centroid lies h/3 from the corner, so no answer exists beyond τ = 1 − h/3
//!   (0.983 on these 40 × 20 meshes, h = 0.05); `solvable` says on which side a problem lies (and that it slides
//!   at τ = μ).
//!
//! * `tall block`: the block (0, 1) × (0, 6), loaded alike, τ a fraction of min(μ, W / (2H)) = min(μ, 1/12)
//!   (its overturning), where the tangential load turns into a moment six times as long.
//!
//! * `wedge`: a wedge of half-angle α forced into a rigid V-groove by a traction on its top
//!   (`tribo_testkit::wedge_problem`, 16 rows, ν = 0.3): force control on a bent Γ_C, α the second axis (in the
//!   `load_fraction` column, in degrees), the fixed point's error multiplied by about −μ cot α while the flanks
//!   slip.
//!
//! * `two bodies`: two-body Hertz (`tribo_testkit::two_body_hertz`, h_min 0.02, the upper block's top pushed
//!   0.01 and held in x), ν = 0 in both, the lower block E = 200, the upper one E = 200, 70, 20, 2: friction from
//!   the mismatch alone, the Dundurs β (0, 0.24, 0.41, 0.49 in plane strain, (1 − 2ν)/(2(1 − ν)) (μ₁ − μ₂)/(μ₁ + μ₂)
//!   with equal ν) the second axis (in the `load_fraction` column), which couples the normal and tangential
//!   problems across the interface.
//!
//! Per problem and method: the status, the iterations (QPs of the fixed point, dense LU solves of Newton),
//! the wall time of the solve (the factorization reused), the forces and KKT residual, and where both
//! converged the largest difference of their multipliers relative to the largest λ_n; and the verdict of
//! `coulomb_check` on the fixed point's answer (`check`: agree, differ, undecided; empty where the fixed point did
//! not converge), with its distance and bound (`check_distance`, `check_allowed`: Euclidean, relative to ‖λ_n‖).
//!
//! `cargo run --release -p tribo --example coulomb_map [OUT.csv]` (default docs/coulomb_map.csv).
use std::io::Write;
use std::time::Instant;

use tribo::*;
use tribo_testkit::{hertz_mesh, hertz_spec, two_body_hertz, wedge_problem};

const MUS: [f64; 9] = [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0];
const HEADER: &str =
    "scene,n_free,q,nu,load_fraction,mu,solvable,method,status,iterations,seconds,normal_force,tangential_force,kkt,lambda_difference,check,check_distance,check_allowed";

fn solve(problem: &Problem, mu: f64, method: CoulombMethod) -> Result<(Solution, f64)> {
    solve_with(problem, mu, SolverSettings { coulomb: method, ..Default::default() })
}

fn solve_with(problem: &Problem, mu: f64, settings: SolverSettings) -> Result<(Solution, f64)> {
    let clock = Instant::now();
    let sol = problem.solve(&Friction::Coulomb { mu }, &settings, None)?;
    Ok((sol, clock.elapsed().as_secs_f64()))
}

fn sup_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Solves `problem` with both methods and writes their rows; a solve that returns an error is a row with
/// the error's kind as its status.
fn compare(
    csv: &mut impl Write,
    scene: &str,
    problem: &Problem,
    [nu, fraction, mu]: [f64; 3],
    solvable: bool,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let _ = solve(problem, mu, CoulombMethod::FixedPoint); // the factorization, once
    let runs: Vec<(&str, Result<(Solution, f64)>)> =
        [("fixed_point", CoulombMethod::FixedPoint), ("newton", CoulombMethod::Newton)]
            .into_iter()
            .map(|(name, method)| (name, solve(problem, mu, method)))
            .collect();
    let converged = |r: &Result<(Solution, f64)>| matches!(r, Ok((s, _)) if s.report.status == SolveStatus::Converged);
    let diff = match (&runs[0].1, &runs[1].1) {
        (Ok((a, _)), Ok((b, _))) if converged(&runs[0].1) && converged(&runs[1].1) => {
            let scale = a.lambda_n.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
            sup_diff(&a.lambda_n, &b.lambda_n).max(sup_diff(&a.lambda_t, &b.lambda_t)) / scale
        }
        _ => f64::NAN,
    };
    // The fixed point's answer checked by Newton (one more solve of each, and two QPs).
    let checked = SolverSettings { coulomb_check: true, ..Default::default() };
    let check = match solve_with(problem, mu, checked) {
        Ok((s, _)) => s.report.coulomb_check,
        Err(_) => None,
    };
    let (verdict, distance, allowed) =
        check.map_or((String::new(), f64::NAN, f64::NAN), |c| (c.agreement.to_string(), c.distance, c.allowed));
    for (name, run) in &runs {
        let (status, its, t, p, qf, kkt) = match run {
            Ok((s, t)) => (
                s.report.status.name().to_string(),
                s.report.iterations,
                *t,
                s.normal_force,
                s.tangential_force,
                s.kkt.max(),
            ),
            Err(e) => (format!("error: {}", e.kind()), 0, f64::NAN, f64::NAN, f64::NAN, f64::NAN),
        };
        println!(
            "{scene:>10} ν {nu:<4} τ {fraction:<4} μ {mu:<4} {name:>11}: {status:>14} {its:>3} its {t:.4} s  P {p:.6} Q {qf:.6} KKT {kkt:.1e} dλ {diff:.1e} {verdict}"
        );
        writeln!(
            csv,
            "{scene},{},{},{nu},{fraction},{mu},{solvable},{name},{status},{its},{t},{p},{qf},{kkt},{diff},{verdict},{distance},{allowed}",
            problem.n_free,
            problem.n_multipliers()
        )?;
    }
    Ok(())
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "docs/coulomb_map.csv".into());
    let partial = format!("{out}.partial");
    let mut csv = std::io::BufWriter::new(std::fs::File::create(&partial)?);
    writeln!(csv, "{HEADER}")?;
    for nu in [0.0, 0.2, 0.3, 0.45] {
        let mut spec = hertz_spec(0.01, 0.004, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        spec.material.poisson = nu;
        let hertz = Problem::new(hertz_mesh(0.01), spec)?;
        for mu in MUS {
            compare(&mut csv, "hertz", &hertz, [nu, f64::NAN, mu], true)?;
        }
    }
    for nu in [0.0, 0.2, 0.3, 0.45] {
        for fraction in [0.5, 0.9, 0.99] {
            for mu in MUS {
                let (nx, ny) = (40, 20);
                let mesh = rectangle([0.0, 2.0], [0.0, 1.0], nx, ny, Diagonal::Alternating)?;
                let spec = ProblemSpec::new(Material { young: 100.0, poisson: nu }, "bottom")
                    .traction("top", [fraction * mu.min(1.0), -1.0]);
                let tau = fraction * mu.min(1.0);
                let h = 2.0 / nx as f64; // the FE edges along Γ_C, and T_H with them
                let solvable = tau < 1.0 - h / 3.0; // (τ < μ too: the fractions are below 1)
                compare(&mut csv, "held block", &Problem::new(mesh, spec)?, [nu, fraction, mu], solvable)?;
            }
        }
    }
    // The tall block: (0, 1) × (0, 6), the same loading, τ a fraction of min(μ, W / (2H)) (it overturns sooner);
    // the discrete problem has an answer for τ < (W / 2 − h / 3) / H (the pressure's resultant at most h/3 from the
    // corner): 0.0806 on these meshes, above 0.9 · W / (2H) = 0.075.
    for nu in [0.0, 0.2, 0.3, 0.45] {
        for fraction in [0.5, 0.9] {
            for mu in MUS {
                let (nx, ny, width, height) = (20, 120, 1.0, 6.0);
                let mesh = rectangle([0.0, width], [0.0, height], nx, ny, Diagonal::Alternating)?;
                let tau = fraction * mu.min(width / (2.0 * height));
                let spec =
                    ProblemSpec::new(Material { young: 100.0, poisson: nu }, "bottom").traction("top", [tau, -1.0]);
                let h = width / nx as f64;
                let solvable = tau < (width / 2.0 - h / 3.0) / height;
                compare(&mut csv, "tall block", &Problem::new(mesh, spec)?, [nu, fraction, mu], solvable)?;
            }
        }
    }
    // The wedge: α in the load_fraction column; it always has an answer (the groove holds it).
    for alpha in [15.0, 20.0, 30.0, 45.0] {
        let wedge = wedge_problem(16, alpha, 0.3);
        for mu in MUS {
            compare(&mut csv, "wedge", &wedge, [0.3, alpha, mu], true)?;
        }
    }
    // Two bodies: β in the load_fraction column.
    for upper in [200.0, 70.0, 20.0, 2.0] {
        let (e1, e2) = (200.0_f64, upper);
        // Equal ν = 0: β = (1 − 2ν)/(2(1 − ν)) (μ₁ − μ₂)/(μ₁ + μ₂) with μ_i = E_i / 2.
        let beta = 0.5 * (e1 - e2) / (e1 + e2);
        let pair = two_body_hertz(
            0.02,
            Material { young: e1, poisson: 0.0 },
            Material { young: e2, poisson: 0.0 },
            true,
            0.01,
        );
        for mu in MUS {
            compare(&mut csv, "two bodies", &pair, [0.0, beta, mu], true)?;
        }
    }
    csv.flush()?;
    drop(csv);
    std::fs::rename(&partial, &out)?;
    Ok(())
}
