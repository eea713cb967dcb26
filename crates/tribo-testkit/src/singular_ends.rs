//! A reference whose λ is singular at the ends of Γ_C: the adaptive loop's answer graded further toward them.
//!
//! On the block (Coulomb friction, the whole bottom in contact) λ is singular at the two bottom corners,
//! `λ ~ r^−s` with s ≈ 0.28: the L² error of a mesh whose end cell has length H is of order `H^(1/2 − s)`, and a
//! halving of that cell removes only 14 % of it. The adaptive loop run to [`crate::REFERENCE_UNKNOWNS`] leaves end
//! cells of about 1e-9, and the error there, about a tenth of a percent of ‖λ‖, was a part of every "true error"
//! measured against it from 30k unknowns on (the hierarchical estimate of the block seemed to grow from 1.86 to 2.05
//! times the truth between 22k and 131k unknowns; against the reference graded here, 1.86–1.88: study 13). So the
//! reference is bisected up to [`ROUNDS`] more times within a radius halved each round around each end: its end
//! cells shrink by 2 each round at a few hundred unknowns, and its error there by about 0.86. The rounds stop where
//! a solve no longer converges: on the block the eighth stagnated (end cells of about 1e-11 at x = 4, where doubles
//! are 9e-16 apart: their geometry is known to 1e-4), so its reference keeps seven.

use tribo::*;

/// The rounds of bisection at the ends, at most.
pub const ROUNDS: usize = 12;

/// `reference` (a solve of `problem` with `friction`) bisected up to [`ROUNDS`] times within a radius that starts at
/// 4 end cells of the first pair's T_H and halves each round, around both ends of the first pair's side, each round
/// solved from the one before; the rounds stop at the first whose problem cannot be made or solved, or whose solve
/// does not converge (its answer is not kept). Returns the graded problem, its answer, the rounds kept and the
/// relative L²(Γ_C) change of λ in the last of them (NaN where none was kept). A T_H of one cell is not graded.
pub fn graded_at_ends(
    (problem, reference): (Problem, Solution),
    friction: &Friction,
) -> (Problem, Solution, usize, f64) {
    let ends = [problem.contact.point_at(0.0), problem.contact.point_at(problem.contact.length())];
    let xi = &problem.multipliers.xi;
    let n = xi.len();
    if n < 3 {
        return (problem, reference, 0, f64::NAN);
    }
    let mut radius = 4.0 * (xi[1] - xi[0]).max(xi[n - 1] - xi[n - 2]);
    let (mut problem, mut reference, mut change) = (problem, reference, f64::NAN);
    for round in 0..ROUNDS {
        let near = |v: usize| {
            let p = problem.mesh.points()[v];
            ends.iter().any(|e| (p[0] - e[0]).hypot(p[1] - e[1]) <= radius)
        };
        let triangles = problem.mesh.triangles().iter().enumerate();
        let marked: Vec<usize> = triangles.filter(|(_, t)| t.iter().any(|&v| near(v))).map(|(i, _)| i).collect();
        let finer = problem.solve_enriched(&reference, &marked, friction, &SolverSettings::default());
        let Ok((finer, answer)) = finer.map_err(|e| eprintln!("round {round} of the grading at the ends: {e}")) else {
            return (problem, reference, round, change);
        };
        if answer.report.status != SolveStatus::Converged {
            return (problem, reference, round, change);
        }
        let (d, n) = adapt::multiplier_difference(&problem, &reference, &finer, &answer);
        change = d / n;
        (problem, reference) = (finer, answer);
        radius *= 0.5;
    }
    (problem, reference, ROUNDS, change)
}
