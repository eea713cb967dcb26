//! Two-body Hertz (`tribo_testkit::two_body_hertz`): the Hertz block under an elastic block, a parabolic gap
//! of radius 1 between them, the upper block's top pushed down by δ = 0.01, both graded toward the contact
//! (growth 0.15, h_min 0.04 → 0.000625). Pairs: equal materials (E = 200, ν = 0.3 on both), dissimilar
//! (E = 200, ν = 0.3 under E = 70, ν = 0.33) and a primary 1000 times stiffer. Per mesh and pair: the
//! unknowns, the contact force, the relative L2 error of λ_n against the plane-strain Hertz pressure of the
//! combined modulus 1/E* = Σ (1 − ν_i²)/E_i for that force, and the wall time of a fresh frictionless and a
//! fresh Coulomb (μ = 0.3) solve; beside them, the same solves of the one-body problem on the lower mesh
//! alone against the rigid parabola (the cost of one body of about half the unknowns).
//!
//! `cargo run --release -p tribo --example two_bodies [OUT.csv]` (default docs/two_bodies.csv), then
//! `python scripts/plot_two_bodies.py` draws docs/two_bodies.{png,md}.
use std::io::Write;
use std::time::Instant;

use tribo::*;
use tribo_testkit::{combined_modulus, hertz_l2_error_with, hertz_spec, two_body_hertz};

fn timed(problem: &Problem, friction: &Friction) -> Result<(Solution, f64)> {
    problem.forget_factorization();
    let clock = Instant::now();
    let sol = problem.solve(friction, &SolverSettings::default(), None)?;
    Ok((sol, clock.elapsed().as_secs_f64()))
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "docs/two_bodies.csv".into());
    let steel = Material { young: 200.0, poisson: 0.3 };
    let pairs = [
        ("equal", steel),
        ("dissimilar", Material { young: 70.0, poisson: 0.33 }),
        ("stiff primary", Material { young: 2e5, poisson: 0.3 }),
    ];
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let mut csv = std::fs::File::create(&out)?;
    writeln!(csv, "pair,h_min,n_free,q,force,hertz_l2,frictionless_s,coulomb_s,coulomb_status,one_body_n,one_body_frictionless_s,one_body_coulomb_s")?;
    for h_min in [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625] {
        // One body on the lower mesh against the rigid parabola: the cost of half of the two-body problem.
        let mut spec = hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        spec.obstacle.shape = ObstacleShape::Parabola { center: 0.0, radius: 1.0 };
        let lower = two_body_hertz(h_min, steel, steel, false, 0.01);
        let part = &lower.bodies[0];
        let grading = Grading { side: Side::Top, segment: [-0.15, 0.15], h_min, h_max: 0.5, growth: 0.15 };
        let one = Problem::new(graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading)?, spec)?;
        assert_eq!(one.mesh.n_nodes(), part.nodes.len());
        let (_, one_f) = timed(&one, &Friction::Frictionless)?;
        let (_, one_c) = timed(&one, &coulomb)?;
        for (name, upper) in pairs {
            let problem = two_body_hertz(h_min, steel, upper, false, 0.01);
            let (sol, t_f) = timed(&problem, &Friction::Frictionless)?;
            let err = hertz_l2_error_with(&problem, &sol, combined_modulus(&steel, &upper));
            let (sol_c, t_c) = timed(&problem, &coulomb)?;
            println!(
                "{name:>13} h_min {h_min:<8} n {:>6}  force {:.5}  L2 vs Hertz {err:.3e}  frictionless {t_f:.3} s ({})  \
                 Coulomb {t_c:.3} s ({})  | one body n {:>6}: {one_f:.3} s, {one_c:.3} s",
                problem.n_free, sol.normal_force, sol.report.condensation, sol_c.report.status, one.n_free
            );
            writeln!(
                csv,
                "{name},{h_min},{},{},{},{err},{t_f},{t_c},{},{},{one_f},{one_c}",
                problem.n_free,
                problem.n_multipliers(),
                sol.normal_force,
                sol_c.report.status,
                one.n_free
            )?;
        }
    }
    Ok(())
}
