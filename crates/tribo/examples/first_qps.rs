//! How the first QP of a Coulomb fixed point starts, counted: steps and factorizations (issue 40).
//!
//! * `fretting`: a fretting history of 101 steps on the graded Hertz meshes (the fretting scene's path, ν = 0.45,
//!   μ = 0.3: the cylinder pressed δ = 0.01, then moved to s = 0.0045 in 20 steps, back to −0.0045 in 40 and to
//!   0.0045 again in 40). Each step's fixed point starts from the step before: its first QP from that answer's
//!   places (`ContactQp::start_from_answer`). Printed per mesh: the QPs, their active-set steps and
//!   factorizations over the history, the first QP of step 50, the QPs' seconds and the tangential force at step 50.
//! * `two_bodies`: study 8's two equal bodies pressed together (`tribo_testkit::two_body_hertz`), Coulomb μ = 0.3
//!   from the frictionless answer: the steps and factorizations of each QP. The first Coulomb QP starts from the
//!   whole stick zone where the saddle-point system takes that step bordered (`ContactQp::start_from_stick`).
//!
//! `cargo run --release -p tribo --example first_qps [fretting|two_bodies] [H_MIN,...]` (default: both, h_min
//! 0.005, 0.00125, 0.000625 for the history, 0.0025, 0.00125, 0.000625 for the bodies; the history at 0.0003125,
//! 55k unknowns, takes about a minute).
use std::time::Instant;

use tribo::*;
use tribo_testkit::{hertz_mesh, hertz_scene, hertz_spec, two_body_hertz};

fn fretting(h_min: f64) -> Result<()> {
    let mut spec = hertz_spec(hertz_scene().approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.material.poisson = 0.45;
    let problem = Problem::new(hertz_mesh(h_min), spec)?;
    let amp = 0.0045;
    let mut path = vec![0.0];
    path.extend((1..=20).map(|k| amp * k as f64 / 20.0));
    path.extend((1..=40).map(|k| amp - 2.0 * amp * k as f64 / 40.0));
    path.extend((1..=40).map(|k| -amp + 2.0 * amp * k as f64 / 40.0));
    let steps: Vec<LoadStep> = path.iter().map(|&s| LoadStep::new(hertz_scene().approach, s)).collect();
    let clock = Instant::now();
    let history = problem.solve_history(&Friction::Coulomb { mu: 0.3 }, &steps, &SolverSettings::default(), None)?;
    let seconds = clock.elapsed().as_secs_f64();
    let reports: Vec<&Report> = history.solutions.iter().map(|s| &s.report).collect();
    let total = |f: fn(&Report) -> u32| reports.iter().map(|r| f(r)).sum::<u32>();
    let step_50 = &history.solutions[50].report;
    println!(
        "fretting h_min {h_min} ({} unknowns): {}, {} QPs, {} steps, {} factorizations; step 50's first QP {} steps, {} \
         factorizations; QPs {:.3} s, whole {seconds:.3} s; Q at step 50 {:.12e}",
        problem.n_free,
        history.status.name(),
        reports.iter().map(|r| r.qp_iterations.len()).sum::<usize>(),
        total(|r| r.qp_iterations.iter().sum()),
        total(|r| r.qp_factorizations.iter().sum()),
        step_50.qp_iterations[0],
        step_50.qp_factorizations[0],
        reports.iter().map(|r| r.timings.qp).sum::<f64>(),
        history.tangential_force()[50],
    );
    Ok(())
}

fn two_bodies(h_min: f64) -> Result<()> {
    let steel = Material { young: 200.0, poisson: 0.3 };
    let problem = two_body_hertz(h_min, steel, steel, false, 0.01);
    let solution = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None)?;
    let r = &solution.report;
    println!(
        "two bodies h_min {h_min} ({} unknowns): {}, QP steps {:?}, factorizations {:?}, QPs {:.3} s",
        problem.n_free,
        r.status.name(),
        r.qp_iterations,
        r.qp_factorizations,
        r.timings.qp
    );
    Ok(())
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("both", String::as_str);
    let sizes = |default: &[f64]| -> Vec<f64> {
        args.get(2).map_or(default.to_vec(), |s| s.split(',').filter_map(|v| v.parse().ok()).collect())
    };
    if which != "two_bodies" {
        for h in sizes(&[0.005, 0.00125, 0.000625]) {
            fretting(h)?;
        }
    }
    if which != "fretting" {
        for h in sizes(&[0.0025, 0.00125, 0.000625]) {
            two_bodies(h)?;
        }
    }
    Ok(())
}
