//! How good are the error bars of P, Q and the zone widths? (issue 36, item 3; study 14)
//!
//! The Hertz block (E = 200, ν = 0.3, R = 1, δ = 0.01) with the cylinder at `CENTER`, frictionless or
//! Coulomb (`MU` > 0, the obstacle shifted 0.004: partial slip), adapted from the 8 × 4 mesh to
//! `MAX_UNKNOWNS` (80k by default). Every level with at least 10 multiplier dofs in contact is solved again
//! on its mesh, its error bars computed (`Problem::estimate_error_bars`: the whole mesh enriched; with
//! `STRIP` = 1, the strip of one contact width that the adaptive stop enriches), and each error bar
//! (`tribo::results::ErrorBars`) compared with the true error of its quantity against the reference on a graded
//! mesh of 466k unknowns (study 12's): the normal force P, the tangential force Q, the width of the contact
//! zone and of the stick zone. Printed per level: each true error and the effectivity (bar over true
//! error); then per quantity the smallest and largest effectivity, and the levels where the bar fell below
//! the true error. The reference's own errors bound how small a true error can be read: a true error below
//! twice the reference's resolution of that quantity is marked `~` (not counted): the zone resolution of a
//! width, half the error bar of a force on the reference (its own enriched solve, 1.9M unknowns; skipped,
//! and the floor of the forces taken as 0, with `SKIP` = 1).
//!
//! `cargo run --release -p tribo --example error_bars [CENTER] [MU] [MAX_UNKNOWNS] [STRIP] [SKIP]` (a few minutes: the
//! reference solve and the re-solves of the levels are most of it).
use tribo::adapt::near_contact;
use tribo::results::ErrorBars;
use tribo::*;

/// How a quantity is read from a solution.
type Read = fn(&Solution) -> f64;

/// The quantities the bars are for, with their values in a solution.
const QUANTITIES: [(&str, Read); 4] = [
    ("P", |s| s.normal_force),
    ("Q", |s| s.tangential_force),
    ("contact width", |s| s.contact_width()),
    ("stick width", |s| s.stick_width()),
];

fn bar(b: &ErrorBars, k: usize) -> f64 {
    [b.normal_force, b.tangential_force, b.contact_width, b.stick_width][k]
}

fn main() -> Result<()> {
    let arg = |k: usize, default: f64| std::env::args().nth(k).and_then(|s| s.parse().ok()).unwrap_or(default);
    let (center, mu, max_unknowns) = (arg(1, 0.0), arg(2, 0.0), arg(3, 80_000.0) as usize);
    let strip = arg(4, 0.0) > 0.0;
    let skip_reference_bars = arg(5, 0.0) > 0.0;
    let case = tribo_testkit::adaptive_hertz_case(center, mu)?;
    let (spec, friction, coarse) = (case.spec, case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    let exact: Vec<f64> = QUANTITIES.iter().map(|(_, f)| f(&rsol)).collect();
    // How well the reference itself knows each quantity: the widths to its zones' resolution; the forces
    // to their change from the reference's own hierarchical estimate, halved (its error bar over 2).
    let rh =
        if skip_reference_bars { None } else { reference.estimate_error_bars(&rsol, &friction, &settings)?.error_bars };
    let floor = [
        rh.map_or(0.0, |b| 0.5 * b.normal_force),
        rh.map_or(0.0, |b| 0.5 * b.tangential_force),
        rsol.contact_zone().map_or(0.0, |z| z.resolution),
        rsol.stick_zone().map_or(0.0, |z| z.resolution),
    ];
    println!("reference: {} unknowns, {}", reference.n_free, rsol.report.status);
    for (k, (name, _)) in QUANTITIES.iter().enumerate() {
        println!("  {name} = {:.6e}, known to about {:.1e}", exact[k], floor[k]);
    }
    let adapt = AdaptSettings { tol: 1e-5, max_unknowns, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
    let mut header = "level unknowns in-contact seconds(solve, enriched)".to_string();
    for (name, _) in QUANTITIES {
        header += &format!(" | {name}: true error, bar/true");
    }
    println!("{header}");
    let mut ratios: Vec<Vec<(usize, f64)>> = vec![Vec::new(); QUANTITIES.len()];
    for (level, l) in run.levels.iter().enumerate() {
        let mut s = spec.clone();
        s.multiplier_points = MultiplierPoints::Abscissae(l.multiplier_mesh.clone());
        let p = Problem::new(l.mesh.clone(), s)?;
        let clock = std::time::Instant::now();
        let sol = p.solve(&friction, &settings, None)?;
        let solve_seconds = clock.elapsed().as_secs_f64();
        let in_contact = sol.states.iter().filter(|c| **c != ContactState::Separation).count();
        if in_contact < 10 {
            continue;
        }
        let h = if strip {
            let marked = near_contact(&p, &sol, sol.contact_width());
            p.estimate_hierarchical_on(&sol, &marked, &friction, &settings)?
        } else {
            p.estimate_error_bars(&sol, &friction, &settings)?
        };
        let bars = h.error_bars.expect("the whole mesh or the strip, with bars");
        let mut line = format!("{level:>3} {:>7} {in_contact:>5} {solve_seconds:.2} {:.2}", p.n_free, h.seconds);
        for (k, (_, value)) in QUANTITIES.iter().enumerate() {
            let truth = (value(&sol) - exact[k]).abs();
            let b = bar(&bars, k);
            if truth <= 2.0 * floor[k] {
                line += &format!(" | {truth:.2e} ~ {b:.2e}");
            } else {
                let ratio = b / truth;
                ratios[k].push((level, ratio));
                line += &format!(" | {truth:.2e} {ratio:>6.2}");
            }
        }
        println!("{line}");
    }
    for (k, (name, _)) in QUANTITIES.iter().enumerate() {
        let r = &ratios[k];
        if r.is_empty() {
            println!("{name}: no level with a true error above the reference's resolution");
            continue;
        }
        let min = r.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
        let max = r.iter().map(|x| x.1).fold(0.0, f64::max);
        let below: Vec<String> = r.iter().filter(|x| x.1 < 1.0).map(|(l, x)| format!("{l} ({x:.2})")).collect();
        let within = r.iter().filter(|x| (1.0..=2.0).contains(&x.1)).count();
        println!(
            "{name}: effectivity {min:.2}-{max:.2} over {} levels, {within} in [1, 2]; below 1: {}",
            r.len(),
            if below.is_empty() { "none".to_string() } else { below.join(", ") }
        );
    }
    Ok(())
}
