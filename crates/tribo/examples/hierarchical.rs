//! How sharp is a hierarchical estimate of the traction error? (issue 36, the second route it names)
//!
//! An adaptive case (`tribo_testkit::ADAPTIVE_CASES`; by default the Hertz block, E = 200, ν = 0.3, R = 1,
//! δ = 0.01, the cylinder centred) adapted from its coarse start to 80k unknowns. Each level with at least
//! 3 multiplier dofs in contact is solved again and compared with the case's reference (for Hertz a graded
//! mesh of 466k unknowns, h_min 1.5625e-4, growth 0.02), and with three enriched solves of the same
//! level (`Problem::solve_enriched`: triangles bisected on all three edges, T_H halved under them): the
//! whole mesh, and the triangles within 1, 0.5 and 0.25 contact widths of the contact zone. Printed per
//! level: the true relative L²(Γ_C) error of λ, the effectivity of today's bound (`traction_relative`
//! over the true error), the enriched difference ‖λ_H − λ_f‖ over the true error, e_f / e_H for the whole
//! mesh, the enriched sizes and time; and the difference of each level from the next adaptive level over
//! the true error (free in the adaptive loop). On levels of at most `MAX_TWICE` unknowns (40k by default),
//! the strip of half a contact width is enriched twice: the reduction q = ‖λ_f − λ_ff‖ / ‖λ_H − λ_f‖ is
//! measured, and the extrapolated estimate ‖λ_H − λ_f‖ / (1 − q) compared with the true error; and the twice-enriched
//! answer taken as the enrichment: ‖λ_H − λ_ff‖ and its own error e_ff, each over the true error of λ_H.
//!
//! `cargo run --release -p tribo --example hierarchical [CASE] [MAX_TWICE]` (`hertz@0.3`: the cylinder at
//! x = 0.3; about 1–3 minutes, the reference solve most of it).
use tribo::adapt::{multiplier_difference, near_contact};
use tribo::*;

fn main() -> Result<()> {
    let arg = |k: usize, default: f64| std::env::args().nth(k).and_then(|s| s.parse().ok()).unwrap_or(default);
    let name = std::env::args().nth(1).unwrap_or_else(|| "hertz".into());
    // The twice-enriched strip has about 5 times a level's unknowns: measured up to this size.
    let max_twice = arg(2, 40_000.0) as usize;
    let case = tribo_testkit::adaptive_case(&name)?;
    let (friction, coarse) = (case.friction, case.coarse);
    let (reference, rsol) = case.reference;
    let settings = SolverSettings::default();
    println!("{name}: reference {} ({})", case.reference_source, rsol.report.status);
    let adapt = AdaptSettings { tol: 1e-4, max_unknowns: 80_000, stop_on: StopOn::Bound, ..AdaptSettings::default() };
    let run = coarse.solve_adaptive(&friction, &settings, &adapt, None)?;
    println!(
        "level unknowns in-contact true-error bound/true | whole mesh: d/true e_f/e_H unknowns seconds | \
         strips of 1, 0.5, 0.25 contact widths: d/true unknowns"
    );
    let mut previous: Option<(Problem, Solution, f64)> = None;
    for (k, level) in run.levels.iter().enumerate() {
        let p = coarse.on_level(level)?;
        let sol = p.solve(&friction, &settings, None)?;
        let (err, norm) = multiplier_difference(&p, &sol, &reference, &rsol);
        if let Some((pp, ps, perr)) = previous.take() {
            let (d, _) = multiplier_difference(&pp, &ps, &p, &sol);
            println!(
                "    level {} against level {k}: d/true {:.3} (e_{k}/e_{} {:.3})",
                k - 1,
                d / perr,
                k - 1,
                err / perr
            );
        }
        previous = Some((p.clone(), sol.clone(), err));
        let in_contact = sol.lambda_n.iter().filter(|l| **l > 0.0).count();
        if in_contact < 3 {
            continue;
        }
        let truth = err / norm;
        let clock = std::time::Instant::now();
        let all: Vec<usize> = (0..p.mesh.n_triangles()).collect();
        let (pf, sf) = p.solve_enriched(&sol, &all, &friction, &settings)?;
        let seconds = clock.elapsed().as_secs_f64();
        let (d, _) = multiplier_difference(&p, &sol, &pf, &sf);
        let (ef, _) = multiplier_difference(&pf, &sf, &reference, &rsol);
        let mut line = format!(
            "{k:>3} {:>7} {in_contact:>4} {truth:.3e} {:>6.2} | {:.3} {:.3} {:>7} {seconds:.3} |",
            p.n_free,
            sol.report.estimate.traction_relative / truth,
            d / err,
            ef / err,
            pf.n_free
        );
        let touching: Vec<f64> = p
            .multipliers
            .dof_abscissae()
            .into_iter()
            .zip(&sol.lambda_n)
            .filter(|(_, l)| **l > 0.0)
            .map(|(x, _)| x)
            .collect();
        let width = touching[touching.len() - 1] - touching[0];
        for fraction in [1.0, 0.5, 0.25] {
            let marked = near_contact(&p, &sol, fraction * width);
            let (pf, sf) = p.solve_enriched(&sol, &marked, &friction, &settings)?;
            let (d, _) = multiplier_difference(&p, &sol, &pf, &sf);
            line += &format!(" {:.3} {:>7}", d / err, pf.n_free);
        }
        // Two enrichments of the strip of half a contact width: the reduction q = ‖λ_f − λ_ff‖ / ‖λ_H − λ_f‖
        // measured, and the extrapolated estimate ‖λ_H − λ_f‖ / (1 − q).
        if p.n_free <= max_twice {
            let marked = near_contact(&p, &sol, 0.5 * width);
            let (pf, sf) = p.solve_enriched(&sol, &marked, &friction, &settings)?;
            let marked_f = near_contact(&pf, &sf, 0.5 * width);
            let (pff, sff) = pf.solve_enriched(&sf, &marked_f, &friction, &settings)?;
            let (d1, _) = multiplier_difference(&p, &sol, &pf, &sf);
            let (d2, _) = multiplier_difference(&pf, &sf, &pff, &sff);
            let q = d2 / d1;
            line += &format!(" | q {q:.3} extrapolated/true {:.3} ({} unknowns)", d1 / (1.0 - q) / err, pff.n_free);
            // The twice-enriched answer as the enrichment: its difference from λ_H and its own error, over e_H.
            let (dff, _) = multiplier_difference(&p, &sol, &pff, &sff);
            let (eff, _) = multiplier_difference(&pff, &sff, &reference, &rsol);
            line += &format!(" | d(H,ff)/true {:.3} e_ff/e_H {:.3}", dff / err, eff / err);
        }
        println!("{line}");
    }
    Ok(())
}
