//! Hertz contact, frictionless or with Coulomb friction, on the Hertz scene (`python/tribo/scenes/
//! hertz.toml`): a rigid cylinder (R = 1) pushed δ = 0.01 into the block (−2, 2) × (−2, 0), clamped at the
//! bottom, E = 200, ν = 0.3, on meshes graded toward the contact zone. Prints, per mesh, the contact
//! force, the Hertz half-width, the relative L2 error of λ_n against the plane-strain Hertz pressure
//! (meaningful frictionless), the fixed-point iterations and the time of each phase.
//!
//! `cargo run --release -p tribo --example hertz [MU]` (MU > 0: Coulomb with an obstacle shift 0.004).
use tribo::*;
use tribo_testkit::{hertz_l2_error, hertz_pressure, hertz_problem, hertz_scene};

fn main() -> Result<()> {
    let mu: f64 = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    for h_min in [0.04, 0.02, 0.01, 0.005] {
        let shift = if mu > 0.0 { 0.004 } else { 0.0 };
        let problem =
            hertz_problem(h_min, hertz_scene().approach, shift, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let friction = if mu > 0.0 { Friction::Coulomb { mu } } else { Friction::Frictionless };
        let clock = std::time::Instant::now();
        let sol = problem.solve(&friction, &SolverSettings::default(), None)?;
        let seconds = clock.elapsed().as_secs_f64();
        let (_, a) = hertz_pressure(sol.normal_force);
        let count = |s: ContactState| sol.states.iter().filter(|x| **x == s).count();
        println!(
            "h_min {h_min:<6} unknowns {:>5}  q {:>4}  force {:.5}  a {a:.4}  L2 error vs Hertz {:.3e}  {} after {} iterations  stick {} slip {}  {seconds:.3} s",
            problem.n_free,
            problem.n_multipliers(),
            sol.normal_force,
            hertz_l2_error(&problem, &sol),
            sol.report.status,
            sol.report.iterations,
            count(ContactState::Stick),
            count(ContactState::Slip),
        );
        let t = &sol.report.timings;
        println!(
            "    timings [s]: assembly {:.4}  Γ_C matrices {:.4}  factorization {:.4}  condensation {:.4}  QPs {:.4} ({} QPs, {} only to the fallback tolerance, IPM iterations {:?})  recovery {:.4}",
            t.assembly, t.contact_matrices, t.factorization, t.condensation, t.qp,
            sol.report.qp_iterations.len(), sol.report.qp_inaccurate, sol.report.qp_iterations, t.recovery
        );
    }
    Ok(())
}
