//! Can the reduction `q = e_f / e_H` of the hierarchical estimate's enrichment be measured? (issue 36)
//!
//! Until 2026-12-01 (the strip enrichment), `stop_on = "enriched"` bounded the enriched answer's error by `‖λ_H − λ_f‖`
//! (q ≤ ½ assumed); where the enrichment removed more than half of the error (two bodies) that overestimated up to 7
//! times. (This example enriches the strip as then: `docs/measured_reduction.csv` is that measurement.) Measuring q
//! as at the ends of Γ_C (`tribo::adapt::enriched`'s module documentation) would sharpen it: the enriched
//! problem enriched once more, `q̂ = ‖λ_f − λ_ff‖ / ‖λ_H − λ_f‖`. This example measures on every level of an
//! adaptive run (to 0.3 %, at most 150k unknowns) from 10 multiplier dofs in contact: the true errors e_H and
//! e_f against the case's reference (`tribo_testkit::adaptive_case`), the true q = e_f / e_H, and q̂ from a
//! second enrichment (a) local, within a cell's length of the T_H cells that carry half of `‖λ_H − λ_f‖²`,
//! and (b) of the whole strip again (below 40k unknowns), with `d q̂ / (1 − q̂)` over e_f (the effectivity the
//! enriched answer's estimate would have).
//!
//! `cargo run --release -p tribo --example measured_reduction [CASES [OUT]]` (CASES comma-separated,
//! `hertz,two-body` by default; about a minute each) writes all of them into `OUT/measured_reduction.csv` (OUT
//! `docs` by default).
use std::io::Write;

use tribo::adapt::{multiplier_difference, multiplier_difference_on, near_contact};
use tribo::*;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let names = std::env::args().nth(1).unwrap_or_else(|| "hertz,two-body".into());
    let docs = || std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs");
    let out = std::env::args().nth(2).map_or_else(docs, std::path::PathBuf::from);
    // Every case into one file, renamed when all are done: a run cut short leaves the last complete file.
    let (done, partial) = (out.join("measured_reduction.csv"), out.join("measured_reduction.csv.partial"));
    let mut csv = std::fs::File::create(&partial)?;
    writeln!(csv, "case,unknowns,true_error,enriched_true_error,q_true,difference,q_local,q_strip")?;
    for name in names.split(',') {
        println!("{name}");
        probe(name.trim(), &mut csv)?;
    }
    drop(csv);
    std::fs::rename(&partial, &done)?;
    Ok(())
}

/// Half of `‖λ_H − λ_f‖²`: the share of the difference the local second enrichment is made around.
const SHARE: f64 = 0.5;

fn probe(name: &str, csv: &mut std::fs::File) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let case = tribo_testkit::adaptive_case(name)?;
    let (friction, coarse) = (case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    let true_error = |p: &Problem, s: &Solution| {
        let (e, n) = multiplier_difference(p, s, &reference, &rsol);
        e / n
    };
    // The levels as the study measured them: no enriched answer handed back as a last level.
    let adapt =
        AdaptSettings { tol: 0.003, max_unknowns: 150_000, stop_on: StopOn::Hierarchical, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
    println!("unknowns eH ef q_true d/norm qS_local qS_full estf(qS)/ef estf(qfull)/ef cells");
    for level in &run.levels {
        let p = coarse.on_level(level)?;
        let sol = p.solve(&friction, &settings, None)?;
        let dofs = p.multipliers.dof_abscissae();
        let touching: Vec<f64> =
            dofs.iter().zip(&sol.states).filter(|(_, c)| **c != ContactState::Separation).map(|(x, _)| *x).collect();
        if touching.len() < 10 {
            continue;
        }
        let (lo, hi) = (touching[0], touching[touching.len() - 1]);
        let marked = near_contact(&p, &sol, hi - lo);
        let (pf, sf) = p.solve_enriched(&sol, &marked, &friction, &settings)?;
        let (eh, ef) = (true_error(&p, &sol), true_error(&pf, &sf));
        let (d, norm) = multiplier_difference(&p, &sol, &pf, &sf);
        let regions = largest_cells(&p, &sol, (&pf, &sf), SHARE * d * d);
        let near = near_regions(&pf, &regions);
        pf.forget_factorization();
        let (pff, sff) = pf.solve_enriched(&sf, &near, &friction, &settings)?;
        let (mut d1s, mut d2s) = (0.0, 0.0);
        for r in &regions {
            d1s += multiplier_difference_on(&p, &sol, &pf, &sf, r[0], r[1]).0.powi(2);
            d2s += multiplier_difference_on(&pf, &sf, &pff, &sff, r[0], r[1]).0.powi(2);
        }
        let qs = (d2s / d1s).sqrt();
        let mut qfull = f64::NAN;
        if p.n_free < 40_000 {
            let marked2 = near_contact(&pf, &sf, hi - lo);
            pff.forget_factorization();
            let (p3, s3) = pf.solve_enriched(&sf, &marked2, &friction, &settings)?;
            qfull = multiplier_difference(&pf, &sf, &p3, &s3).0 / d;
        }
        let est = |q: f64| d * q / (1.0 - q) / norm / ef;
        println!(
            "{:>7} {:.3e} {:.3e} {:.3} {:.3e} {:.3} {:.3} {:.2} {:.2} {}",
            p.n_free,
            eh,
            ef,
            ef / eh,
            d / norm,
            qs,
            qfull,
            est(qs),
            est(qfull),
            regions.len()
        );
        let row = [p.n_free as f64, eh, ef, ef / eh, d / norm, qs, qfull].map(|v| format!("{v:.6e}")).join(",");
        writeln!(csv, "{name},{row}")?;
    }
    Ok(())
}

/// The T_H cells of `p` with the largest `‖λ_H − λ_f‖²`, as many as carry `share` of it, largest first.
fn largest_cells(p: &Problem, sol: &Solution, (pf, sf): (&Problem, &Solution), share: f64) -> Vec<[f64; 2]> {
    let xi = &p.multipliers.xi;
    let mut cells: Vec<(f64, [f64; 2])> =
        xi.windows(2).map(|w| (multiplier_difference_on(p, sol, pf, sf, w[0], w[1]).0.powi(2), [w[0], w[1]])).collect();
    cells.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut sum = 0.0;
    cells
        .into_iter()
        .take_while(|(d2, _)| {
            let before = sum;
            sum += d2;
            before < share
        })
        .map(|(_, cell)| cell)
        .collect()
}

/// The triangles of `pf` within a region's length of one of `regions` (spans of the Γ_C line).
fn near_regions(pf: &Problem, regions: &[[f64; 2]]) -> Vec<usize> {
    let near = |v: usize| {
        let pt = pf.mesh.points()[v];
        regions.iter().any(|r| pf.contact.distance_to_span(pt, r[0], r[1]) <= r[1] - r[0])
    };
    let triangles = pf.mesh.triangles().iter().enumerate();
    triangles.filter(|(_, t)| t.iter().any(|&v| near(v))).map(|(t, _)| t).collect()
}
