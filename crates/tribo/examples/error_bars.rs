//! How good are the error bars of P, Q and the zone widths, and the traction estimates? (issue 36, items 1
//! and 3; studies 14 and 15)
//!
//! An adaptive case (`CASE`, one of `tribo_testkit::ADAPTIVE_CASES`: Hertz centred (the default), at
//! `hertz@X`, Coulomb, with P0 multipliers; the block; two-body Hertz, frictionless and Coulomb) adapted from
//! its coarse start to `MAX_UNKNOWNS` (80k by default). Every level with at least 10 multiplier dofs in
//! contact is solved again on its mesh (`Problem::on_level`), its error bars computed
//! (`Problem::estimate_error_bars`, the same enrichment as the hierarchical estimate: the whole mesh bisected and the
//! strip of half a contact width again; with `STRIP` = 1, the strip of one contact width bisected, then its half
//! again, without the rest of the mesh), and each error bar (`tribo::results::ErrorBars`) compared with the true
//! error of its quantity against the case's reference (for Hertz a graded mesh of 466k unknowns, study 12's;
//! else the adaptive loop run to 500k unknowns): the normal force P, the tangential force Q, the width of the
//! contact zone and of the stick zone. The traction estimates are compared with the true relative L²(Γ_C)
//! error of λ: the hierarchical estimate the adaptive stop computes (`Problem::estimate_hierarchical`), the same
//! from the enriched solve of the bars (the same solve; the strip's with `STRIP` = 1), the bound
//! (`traction_relative`), and the smaller of the hierarchical estimate and the bound (what the adaptive stop reads).
//! Printed per level: each true error and the effectivity (estimate over true error); then per quantity the
//! smallest and largest effectivity, and the levels where it fell below 1. The reference's own errors bound
//! how small a true error can be read: a true error below twice the reference's resolution of that quantity
//! is marked `~` (not counted): the zone resolution of a width, the change of a force when the reference's whole mesh
//! is bisected once (4 times its unknowns; skipped, and the floor of the forces taken as 0, with `SKIP` = 1).
//!
//! `cargo run --release -p tribo --example error_bars [CASE] [MAX_UNKNOWNS] [STRIP] [SKIP] [OUT]` (a few
//! minutes: the reference solve and the re-solves of the levels are most of it). Every level counted is also
//! written to `OUT/CASE.csv` (`OUT/CASE-strip.csv` with `STRIP` = 1; OUT `docs/error_bars` by default; the
//! file takes its name only when the run completes), from which `python scripts/plot_error_bars.py` writes
//! `docs/error_bars.md` (studies 14 and 15).
use std::io::Write;

use tribo::adapt::{multiplier_difference, near_contact};
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

/// The header of `OUT/CASE.csv`: per level, the true relative error of λ and its estimates (relative), then
/// per quantity its true error (absolute), its bar and how well the reference knows it (`floor`).
/// `traction_strip` is the hierarchical estimate (`Problem::estimate_hierarchical`; the name is that of the enrichment
/// it had before 2026-12-01), `traction_whole` the estimate of the bars' enriched solve: the same, or the strip's with
/// `STRIP` = 1.
const HEADER: &str = "case,level,unknowns,in_contact,solve_seconds,enriched_seconds,traction_true,\
                      traction_strip,traction_whole,traction_bound,P_true,P_bar,P_floor,Q_true,Q_bar,Q_floor,\
                      contact_width_true,contact_width_bar,contact_width_floor,stick_width_true,stick_width_bar,\
                      stick_width_floor";

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let arg = |k: usize, default: f64| std::env::args().nth(k).and_then(|s| s.parse().ok()).unwrap_or(default);
    let name = std::env::args().nth(1).unwrap_or_else(|| "hertz".into());
    let max_unknowns = arg(2, 80_000.0) as usize;
    let strip = arg(3, 0.0) > 0.0;
    let skip_reference_bars = arg(4, 0.0) > 0.0;
    let dir = || std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/error_bars");
    let out = std::env::args().nth(5).map_or_else(dir, std::path::PathBuf::from);
    let case = tribo_testkit::adaptive_case(&name)?;
    // Written under a temporary name, renamed when the run completes: a run cut short leaves no CSV to plot.
    std::fs::create_dir_all(&out)?;
    let done = out.join(format!("{name}{}.csv", if strip { "-strip" } else { "" }));
    let partial = done.with_extension("csv.partial");
    let mut csv = std::fs::File::create(&partial)?;
    writeln!(csv, "{HEADER}")?;
    let (friction, coarse) = (case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    let exact: Vec<f64> = QUANTITIES.iter().map(|(_, f)| f(&rsol)).collect();
    // How well the reference itself knows each quantity: the widths to its zones' resolution; the forces to
    // their change when the reference's whole mesh is bisected once.
    let rh = if skip_reference_bars {
        None
    } else {
        let all: Vec<usize> = (0..reference.mesh.n_triangles()).collect();
        Some(reference.solve_enriched(&rsol, &all, &friction, &settings)?.1)
    };
    let floor = [
        rh.as_ref().map_or(0.0, |r| (r.normal_force - rsol.normal_force).abs()),
        rh.as_ref().map_or(0.0, |r| (r.tangential_force - rsol.tangential_force).abs()),
        rsol.contact_zone().map_or(0.0, |z| z.resolution),
        rsol.stick_zone().map_or(0.0, |z| z.resolution),
    ];
    println!("{name}: reference {} ({})", case.reference_source, rsol.report.status);
    for (k, (name, _)) in QUANTITIES.iter().enumerate() {
        println!("  {name} = {:.6e}, known to about {:.1e}", exact[k], floor[k]);
    }
    let adapt = AdaptSettings { tol: 1e-5, max_unknowns, stop_on: StopOn::Bound, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
    let mut header = "level unknowns in-contact seconds(solve, enriched) | tractions: true error, hierarchical/true \
                      bars'/true bound/true smaller/true"
        .to_string();
    for (name, _) in QUANTITIES {
        header += &format!(" | {name}: true error, bar/true");
    }
    println!("{header}");
    let mut ratios: Vec<Vec<(usize, f64)>> = vec![Vec::new(); QUANTITIES.len()];
    let mut tractions: Vec<Vec<(usize, f64)>> = vec![Vec::new(); 4];
    for (level, l) in run.levels.iter().enumerate() {
        let p = coarse.on_level(l)?;
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
        let bars = h.error_bars.ok_or("the whole mesh or the strip gives bars")?;
        let mut line = format!("{level:>3} {:>7} {in_contact:>5} {solve_seconds:.2} {:.2}", p.n_free, h.seconds);
        let (e, norm) = multiplier_difference(&p, &sol, &reference, &rsol);
        let truth = e / norm;
        // The same enrichment as the bars' unless STRIP: not solved twice.
        let sharp = if strip { p.estimate_hierarchical(&sol, &friction, &settings)?.relative } else { h.relative };
        let bound = sol.report.estimate.traction_relative;
        let estimates = [sharp, h.relative, bound, sharp.min(bound)];
        line += &format!(" | {truth:.2e}");
        let mut row = format!("{name},{level},{},{in_contact},{solve_seconds:.6},{:.6}", p.n_free, h.seconds);
        for v in [truth, sharp, h.relative, bound] {
            row += &format!(",{v:.6e}");
        }
        for (k, estimate) in estimates.iter().enumerate() {
            tractions[k].push((level, estimate / truth));
            line += &format!(" {:>5.2}", estimate / truth);
        }
        for (k, (_, value)) in QUANTITIES.iter().enumerate() {
            let truth = (value(&sol) - exact[k]).abs();
            let b = bar(&bars, k);
            row += &format!(",{truth:.6e},{b:.6e},{:.6e}", floor[k]);
            if truth <= 2.0 * floor[k] {
                line += &format!(" | {truth:.2e} ~ {b:.2e}");
            } else {
                let ratio = b / truth;
                ratios[k].push((level, ratio));
                line += &format!(" | {truth:.2e} {ratio:>6.2}");
            }
        }
        println!("{line}");
        writeln!(csv, "{row}")?;
    }
    drop(csv);
    std::fs::rename(&partial, &done)?;
    let traction_names = [
        "tractions, hierarchical",
        "tractions, hierarchical (the bars' solve)",
        "tractions, bound",
        "tractions, the smaller of the hierarchical estimate and the bound (what the adaptive stop reads)",
    ];
    let names = traction_names.iter().copied().chain(QUANTITIES.iter().map(|(name, _)| *name));
    for (name, r) in names.zip(tractions.iter().chain(&ratios)) {
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
