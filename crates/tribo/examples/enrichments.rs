//! Which enrichment leaves at most a third of the traction error? (issue 36, study 12's last section)
//!
//! The hierarchical estimate `‖λ_H − λ_f‖ / (1 − q₀)` bounds the error `e_H = ‖λ − λ_H‖` where the enrichment
//! leaves `e_f ≤ q₀ e_H` (the saturation assumption), with an effectivity of at most `(1 + q₀) / (1 − q₀)`: 3 for
//! q₀ = ½, 2 for q₀ = ⅓. This example measures `q = e_f / e_H` of five enrichments of every level of an adaptive case
//! (`tribo_testkit::adaptive_case`, adapted on the bound from its coarse start to 60k unknowns), each solved from the
//! level's answer (`Problem::solve_enriched`: the marked triangles bisected on their three edges, T_H halved under
//! them), against the case's reference, on the levels with at least 10 multiplier dofs in contact:
//! - `W`: the whole mesh bisected once;
//! - `WS`: `W`, then on its mesh the strip of half a contact width bisected again (h halved everywhere, quartered
//!   near the contact zone): the enrichment of `Problem::estimate_hierarchical` (`Problem::solve_enriched_twice`);
//! - `S1`: the strip of one contact width bisected once (what `Problem::estimate_hierarchical` enriched until
//!   2026-12-01);
//! - `S1S`: `S1`, then its strip of half a contact width bisected again;
//! - `WW`: the whole mesh bisected twice (on levels of at most `MAX_WW` unknowns, 0 by default).
//!
//! Printed per level and enrichment: `e_f / e_H`, `‖λ_H − λ_f‖ / e_H` and the enriched unknowns; the closing lines
//! give, per enrichment, the range of `e_f / e_H`, how many levels exceed ⅓, and the range of `1.5 ‖λ_H − λ_f‖ / e_H`
//! (the estimate with q₀ = ⅓).
//!
//! `cargo run --release -p tribo --example enrichments [CASE] [MAX_WW]` (CASE as for `tol_table`: `hertz`,
//! `hertz@0.3`, `hertz-coulomb`, `hertz-p0`, `two-body`, `two-body-coulomb`, `block`, `pairs`; 2–10 minutes each).
use tribo::adapt::{multiplier_difference, near_contact};
use tribo::*;

const NAMES: [&str; 5] = ["W", "WS", "S1", "S1S", "WW"];

fn main() -> Result<()> {
    let name = std::env::args().nth(1).unwrap_or_else(|| "hertz".into());
    let max_ww: usize = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    let case = tribo_testkit::adaptive_case(&name)?;
    let (friction, coarse) = (case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    println!("{name}: reference {} ({})", case.reference_source, rsol.report.status);
    let adapt = AdaptSettings { tol: 1e-4, max_unknowns: 60_000, stop_on: StopOn::Bound, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
    println!("level unknowns in-contact e_H | per enrichment (W, WS, S1, S1S, WW): e_f/e_H d/e_H unknowns");
    // Per enrichment, over the levels: (e_f / e_H, d / e_H).
    let mut measured: [Vec<(f64, f64)>; 5] = Default::default();
    for (k, level) in run.levels.iter().enumerate() {
        let p = coarse.on_level(level)?;
        let sol = p.solve(&friction, &settings, None)?;
        let (err, norm) = multiplier_difference(&p, &sol, &reference, &rsol);
        let in_contact = sol.lambda_n.iter().filter(|l| **l > 0.0).count();
        if in_contact < 10 {
            continue;
        }
        let touching: Vec<f64> = (p.multipliers.dof_abscissae().into_iter().zip(&sol.lambda_n))
            .filter(|(_, l)| **l > 0.0)
            .map(|(x, _)| x)
            .collect();
        let width = touching[touching.len() - 1] - touching[0];
        let mut line = format!("{k:>3} {:>7} {in_contact:>4} {:.3e} |", p.n_free, err / norm);
        let mut record = |j: usize, pf: &Problem, sf: &Solution| {
            let (d, _) = multiplier_difference(&p, &sol, pf, sf);
            let (e, _) = multiplier_difference(pf, sf, &reference, &rsol);
            measured[j].push((e / err, d / err));
            format!(" {} {:.3} {:.3} {:>7} |", NAMES[j], e / err, d / err, pf.n_free)
        };
        let all: Vec<usize> = (0..p.mesh.n_triangles()).collect();
        let (pw, sw) = p.solve_enriched(&sol, &all, &friction, &settings)?;
        line += &record(0, &pw, &sw);
        let (pws, sws) = p.solve_enriched_twice(&sol, &all, &friction, &settings)?;
        line += &record(1, &pws, &sws);
        let (ps, ss) = p.solve_enriched(&sol, &near_contact(&p, &sol, width), &friction, &settings)?;
        line += &record(2, &ps, &ss);
        let (pss, sss) = ps.solve_enriched(&ss, &near_contact(&ps, &ss, 0.5 * width), &friction, &settings)?;
        line += &record(3, &pss, &sss);
        if p.n_free <= max_ww {
            let every: Vec<usize> = (0..pw.mesh.n_triangles()).collect();
            let (pww, sww) = pw.solve_enriched(&sw, &every, &friction, &settings)?;
            line += &record(4, &pww, &sww);
        }
        println!("{line}");
    }
    let range = |v: &mut dyn Iterator<Item = f64>| v.fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
    for (j, rows) in measured.iter().enumerate().filter(|(_, rows)| !rows.is_empty()) {
        let (qlo, qhi) = range(&mut rows.iter().map(|r| r.0));
        let (elo, ehi) = range(&mut rows.iter().map(|r| 1.5 * r.1));
        let above = rows.iter().filter(|r| r.0 > 1.0 / 3.0).count();
        println!(
            "{}: {} levels, e_f/e_H {qlo:.3}-{qhi:.3} ({above} above 1/3), 1.5 d/e_H {elo:.3}-{ehi:.3}",
            NAMES[j],
            rows.len()
        );
    }
    Ok(())
}
