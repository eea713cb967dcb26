//! Study 26: Persson's pin in a hole, conformal contact between two bodies with clearance (issue 39).
//!
//! The scene of `tribo_testkit::PinInHole`: a pin of radius 1 − ΔR (ΔR = 10⁻³) in a hole of radius 1 of a square
//! plate of half-width 80, one material (E = 1, ν = 0.3; at one δ also ν = 0 and 0.45), plane strain, frictionless,
//! the upper half by symmetry;
//! the pin's small core (radius 0.025) is moved across by δ, the plate clamped on its outer sides; both meshes
//! bisected 1 to 5 times along the contact arc. Each run gives the load P the contact carries, the contact
//! half-angle α, the relative L2 difference of λ_n from Persson's pressure at that load
//! (`tribo_testkit::Persson`, the problem solved to 1e-9) and of its peak, and the half-angle Hertz's
//! formula would give for that load. `persson_pin_pressure.csv` holds λ_n along the rim on the finest mesh of
//! each δ with Persson's and Hertz's pressures at the same angles; `persson_curve.csv` Persson's and Hertz's
//! loads by half-angle.
//!
//! ```bash
//! cargo run --release -p tribo --example persson_pin          # ~1 min on two cores: docs/persson_pin*.csv
//! cargo run --release -p tribo --example persson_pin quick    # one δ, three meshes: a smoke run
//! python scripts/plot_persson_pin.py                          # docs/persson_pin.{md,png}
//! ```

use std::f64::consts::PI;
use std::io::Write;
use std::time::Instant;

use tribo::{Friction, SolveStatus, SolverSettings};
use tribo_testkit::{Persson, PinInHole, MAX_HALF_ANGLE};

/// Hertz's half-angle for a load P̂ = P / (E* ΔR): the semi-width `b = 2R √(P̂ / π)` of the curvature ΔR / R², read
/// as the arc R α.
fn hertz_half_angle(load: f64) -> f64 {
    2.0 * (load / PI).sqrt()
}

/// Hertz's pressure over E* ΔR / R at θ for a load P̂: `(2P / π a²) √(a² − θ²)`, a the Hertz half-angle.
fn hertz_pressure(load: f64, theta: f64) -> f64 {
    let a = hertz_half_angle(load);
    if theta.abs() >= a {
        return 0.0;
    }
    2.0 * load / (PI * a * a) * (a * a - theta * theta).sqrt()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let quick = std::env::args().nth(1).as_deref() == Some("quick");
    // (δ, ν): six contact angles at ν = 0.3, and one at ν = 0 and 0.45 (Persson's problem depends on E* alone)
    let cases: Vec<(f64, f64)> = if quick {
        vec![(0.004, 0.3)]
    } else {
        let mut cases: Vec<(f64, f64)> = [0.0011, 0.0014, 0.002, 0.004, 0.008, 0.016].map(|d| (d, 0.3)).to_vec();
        cases.extend([(0.004, 0.0), (0.004, 0.45)]);
        cases
    };
    let refinements = if quick { 1..=3 } else { 1..=5 };
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
    let path = docs.join("persson_pin.csv");
    let partial = path.with_extension("csv.partial");
    let mut out = std::fs::File::create(&partial)?;
    writeln!(
        out,
        "approach,poisson,refinements,unknowns,seconds,load,alpha,alpha_persson,alpha_hertz,l2_persson,peak_persson"
    )?;
    let mut profile = vec!["approach,poisson,angle,lambda_n,persson,hertz".to_string()];
    let settings = SolverSettings::default();
    for &(approach, poisson) in &cases {
        for refine in refinements.clone() {
            let mut scene = PinInHole::new(approach, 1.5, refine);
            scene.material.poisson = poisson;
            let clock = Instant::now();
            let problem = scene.problem();
            let sol = problem.solve(&Friction::Frictionless, &settings, None)?;
            let seconds = clock.elapsed().as_secs_f64();
            if sol.report.status != SolveStatus::Converged {
                return Err(format!("δ {approach}, ν {poisson}, {refine} bisections: {}", sol.report.status).into());
            }
            let reference = scene.reference(&sol);
            let (alpha, scale) = (scene.half_angle(&sol), scene.pressure_unit());
            let l2 = scene.pressure_error(&problem, &sol, &reference);
            let peak = sol.lambda_n.iter().copied().fold(0.0, f64::max) / (scale * reference.peak_pressure()) - 1.0;
            let load = reference.load;
            writeln!(
                out,
                "{approach},{poisson},{refine},{},{seconds:.3},{load:.9e},{alpha:.9},{:.9},{:.9},{l2:.6e},{peak:.6e}",
                problem.n_free,
                reference.half_angle,
                hertz_half_angle(load)
            )?;
            println!(
                "δ {approach}, ν {poisson}, {refine} bisections: {} unknowns, {seconds:.2} s: P/(E*ΔR) {load:.4}, \
                 α {:.3}° (Persson {:.3}°, Hertz {:.3}°), λ_n against Persson {l2:.3e} (L2), {peak:+.3e} (peak)",
                problem.n_free,
                alpha.to_degrees(),
                reference.half_angle.to_degrees(),
                hertz_half_angle(load).to_degrees()
            );
            if refine == *refinements.end() {
                // every k-th multiplier node up to 1.15 α: about 150 points a case
                let last = 1.15 * reference.half_angle;
                let nodes: Vec<(usize, f64)> = (0..problem.multipliers.xi.len())
                    .map(|j| {
                        let q = problem.contact.point_at(problem.multipliers.xi[j]);
                        (j, q[1].atan2(q[0]))
                    })
                    .filter(|&(_, theta)| theta <= last)
                    .collect();
                let every = nodes.len().div_ceil(150).max(1);
                for &(j, theta) in nodes.iter().step_by(every) {
                    profile.push(format!(
                        "{approach},{poisson},{theta:.6},{:.6e},{:.6e},{:.6e}",
                        sol.lambda_n[j] / scale,
                        reference.pressure(theta),
                        hertz_pressure(load, theta)
                    ));
                }
            }
        }
    }
    drop(out);
    std::fs::rename(partial, &path)?;
    std::fs::write(docs.join("persson_pin_pressure.csv"), profile.join("\n") + "\n")?;
    let mut curve = vec!["alpha,persson,hertz".to_string()];
    for i in 1..=56 {
        let alpha = MAX_HALF_ANGLE * i as f64 / 56.0;
        let p = Persson::at_half_angle(alpha);
        curve.push(format!("{alpha:.9},{:.9e},{:.9e}", p.load, PI * alpha * alpha / 4.0));
    }
    std::fs::write(docs.join("persson_curve.csv"), curve.join("\n") + "\n")?;
    println!("wrote {}, persson_pin_pressure.csv and persson_curve.csv", path.display());
    Ok(())
}
