//! The semismooth Newton method for discrete Coulomb friction on Γ_C, beside the fixed point of Φ_H.
//!
//! # The equations
//! The fixed point (`solve/fixed_point.rs`) solves a Tresca QP per iteration with the friction bound frozen at
//! the previous λ_n. Its solution λ = (λ_n, λ_t) satisfies the KKT conditions of that QP with the bound
//! g = μ λ_n of λ itself: with the residual `r = H λ + c` (the QP's gradient, minus the discrete gap and
//! slip, see [`crate::qp`]), at every multiplier dof j
//!
//! * `λ_n,j ≥ 0, r_n,j ≥ 0, λ_n,j r_n,j = 0` (contact), and
//! * `|λ_t,j| ≤ μ λ_n,j`, with `r_t,j = 0` where `|λ_t,j| < μ λ_n,j` (stick) and `λ_t,j r_t,j ≤ 0` where
//!   `|λ_t,j| = μ λ_n,j` (slip, the traction opposing the slip).
//!
//! These are the zeros of the non-smooth function C (Alart–Curnier's, in the multipliers' form that
//! Hüeber, Stadler and Wohlmuth use for their primal–dual active-set method), with `ρ_n,j = 1/H_nn,jj` and
//! `ρ_t,j = 1/H_tt,jj` (so that `λ − ρ r` is a multiplier, whatever the units):
//!
//! `C_n,j = λ_n,j − max(0, N_j)`, `N_j = λ_n,j − ρ_n,j r_n,j`;
//! `C_t,j = λ_t,j − clamp(T_j, −μ max(0, N_j), μ max(0, N_j))`, `T_j = λ_t,j − ρ_t,j r_t,j`.
//!
//! `C(λ) = 0` says exactly the two conditions above: `C_n = 0` is the complementarity of λ_n and r_n, and
//! with it `max(0, N_j) = λ_n,j`, so that `C_t = 0` says that λ_t is the projection of `λ_t − ρ r_t` onto
//! `[−μ λ_n,j, μ λ_n,j]`: `r_t,j = 0` inside, and `r_t,j` of the sign opposite to λ_t at the ends.
//!
//! # The step
//! C is piecewise linear in λ (r is linear), hence semismooth; a generalized Newton step linearizes the piece
//! the current λ lies on. The pieces are the contact states: j is in contact (`N_j > 0`) or not; in contact it
//! sticks (`|T_j| < μ N_j`) or slips with `s_j = sign T_j`. The step solves, for the new λ,
//!
//! * no contact: `λ_n,j = λ_t,j = 0`;
//! * contact: `r_n,j(λ) = 0`;
//! * stick: `r_t,j(λ) = 0`; slip: `λ_t,j = μ s_j λ_n,j`
//!
//! (the slip row of the Newton step is `λ_t − μ s (λ_n − ρ r_n) = 0`, which the contact row makes the one
//! above). With the slip dofs' λ_t eliminated, this is one linear system in λ_n of the contact dofs and λ_t
//! of the sticking ones: rows `r_n` and `r_t` of H, columns H's plus `μ s_j` times the tangential column of
//! a slipping dof. It is not symmetric where dofs slip, so it is solved by a dense LU with partial pivoting
//! (faer), of the size of the contact zone. Where the states of the new λ are those it was solved with, it
//! is a zero of C: the solution, to the round-off of that solve. This is the primal–dual active-set method
//! of Hüeber, Stadler and Wohlmuth (2008) for Coulomb friction, written on the condensed multipliers; as a
//! Newton method it converges locally superlinearly, and in finitely many steps once the states are right.
//!
//! # Globalization
//! Far from the solution the states may cycle. Each step is therefore taken as a direction d from λ and
//! damped by a backtracking line search on the merit `‖C‖₂` (d is a descent direction wherever C is
//! differentiable): the step `α d` with the largest α = 1, ½, ¼, … ≥ 1/64 that decreases the merit; where
//! none does, the full step (its states may still be the right ones). Where the merit stalls (no new minimum
//! for [`STAGNATION_WINDOW`](crate::solve::STAGNATION_WINDOW) steps) or a step's system is singular, the method
//! restarts from one iteration of the fixed point at the point it reached (the Tresca QP with the bounds μ λ_n
//! there, which contracts toward the solution where the fixed point does), up to three times; the QPs are
//! booked in the report with the first one. Before the restarts, study 20's block held only by the contact
//! stalled the method on 19 of its 96 problems that have a solution (all at μ ≤ 0.3, ν ≥ 0.2); with them it
//! converges on all. Where it still does not converge (below), [`crate::CoulombMethod::Auto`] hands the problem
//! to the fixed point.
//!
//! # Where it is solved
//! Only the dofs that can be in contact take part, as in the QPs ([`crate::qp::working_set`]): the dofs
//! where the start presses or the body would penetrate without contact forces (`c_n,j < 0`), with their
//! neighbours; a dof outside with `r_n,j < −√qp_tol · max |c_n|` (a pressure would appear there) joins
//! the set with its neighbours. The residual needs the columns of H of the dofs in the set only (λ is 0
//! elsewhere and H is symmetric), computed once from the factor of A and kept ([`crate::Factor`]).
//!
//! # Stopping
//! The method ends `converged` at a point with `‖C‖₂ ≤ fp_tol ‖λ_n‖₂`, or at the QPs' noise level (`qp_tol`
//! times [`crate::Factor::lambda_scale`]), where no dof outside the set would press. It ends `stagnated` when
//! it stalls after its restarts (its merit made no new minimum, or the linear system of a step is singular: its
//! solution not finite, on the pieces of C and on those of λ), `qp_failed` when a restart's QP fails (as on a
//! problem with no solution, where the fixed point's first QP fails too), and `max_iterations` when the point after
//! `fp_max_iter` steps is not a solution. Each evaluated point's relative
//! merit `‖C‖₂ / ‖λ_n‖₂` is recorded ([`crate::Report::residual_history`]): the last entry is that of the
//! point handed back. The columns of H and the dense system count against `memory_budget`.
//!
//! Reference: S. Hüeber, G. Stadler, B. I. Wohlmuth, *A primal–dual active set algorithm for
//! three-dimensional contact problems with Coulomb friction*, SIAM J. Sci. Comput. 30 (2008) 572–596;
//! P. Alart, A. Curnier, *A mixed formulation for frictional contact problems prone to Newton like solution
//! methods*, Comput. Methods Appl. Mech. Engrg. 92 (1991) 353–375.

use std::ops::ControlFlow;
use std::time::Instant;

use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::Mat;

use crate::error::{Num, Result};
use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::results::SolveStatus;
use crate::settings::SolverSettings;
use crate::solve::driver::qp_failed;
use crate::solve::driver::QpPhase;
use crate::solve::fixed_point::{euclidean, Stagnation};
use crate::solve::progress::{Phase, Progress};

/// The smallest step length the line search tries.
const SMALLEST_STEP: f64 = 1.0 / 64.0;
/// The decrease of the merit a step of length α must make: `(1 − ARMIJO α) ‖C‖`.
const ARMIJO: f64 = 1e-4;
/// How many times a stalled method restarts from one fixed-point iteration before it ends `stagnated`.
const RESTARTS: usize = 3;

/// The contact state a step linearizes at one dof of the set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Piece {
    Open,
    Stick,
    /// Slips, λ_t = μ s λ_n with s = ±1.
    Slip(f64),
}

/// The residual, the merit and the pieces at one point, on the dofs of the set.
struct Point {
    r: Vec<f64>,
    merit: f64,
    pieces: Vec<Piece>,
}

/// What one pass over the set found.
enum Pass {
    /// Dofs outside the set where a pressure would appear.
    Grow(Vec<usize>),
    /// The point is a zero of C to the tolerance: its merit.
    Converged(f64),
    /// The point's merit, above the tolerance, when no step is to be taken (the iteration cap).
    Evaluated(f64),
    /// The damped step's point (λ, then α) and the merit before it, the size of its linear system and the
    /// length taken.
    Step { x: Vec<f64>, merit: f64, size: usize, length: f64 },
    /// The linear system of the step is singular (its solution is not finite): the merit before it.
    Singular(f64),
}

/// The equations of one Coulomb problem: q, μ at each multiplier dof (q), the linear term c (2q) and, for bodies
/// held only by the contact, `E R` (2q × r, column-major) and `Rᵀ f` (r), with the Euclidean norm of each column of
/// `E R`.
struct Equations<'a> {
    q: usize,
    mu: &'a [f64],
    c: &'a [f64],
    rigid: Option<(&'a [f64], &'a [f64])>,
    e_r_norms: Vec<f64>,
}

impl<'a> Equations<'a> {
    fn new(q: usize, mu: &'a [f64], c: &'a [f64], rigid: Option<(&'a [f64], &'a [f64])>) -> Self {
        let mut eq = Self { q, mu, c, rigid, e_r_norms: Vec::new() };
        eq.e_r_norms = (0..eq.r()).map(|m| euclidean(eq.e_r(m).iter().copied())).collect();
        eq
    }

    /// The number r of rigid motions α beside λ.
    fn r(&self) -> usize {
        self.rigid.map_or(0, |(_, load)| load.len())
    }

    /// Column m < r of `E R` (empty without held bodies, where r = 0 and no caller asks).
    fn e_r(&self, m: usize) -> &[f64] {
        let Some((e_r, _)) = self.rigid else { return &[] };
        &e_r[m * 2 * self.q..(m + 1) * 2 * self.q]
    }
}

impl Condensed<'_> {
    /// The Coulomb problem with friction coefficients `mu` (one per multiplier dof) by the semismooth Newton
    /// method, from `phase.lambda` (the first QP's answer, or a nearby problem's) and, for bodies held only by the
    /// contact, `phase.alpha`. Ends with `phase.status` converged, stagnated or max_iterations (or interrupted),
    /// `phase.lambda` and `phase.alpha` its last iterate (the one whose merit ends `phase.history`, but after an
    /// interruption: the step just taken).
    ///
    /// # Errors
    /// [`Error::MemoryBudget`] when the columns of H and the dense system it needs exceed `memory_budget`.
    pub(super) fn newton(
        &self,
        mu: &[f64],
        settings: &SolverSettings,
        loading: &LoadCase,
        phase: &mut QpPhase,
        notify: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<()> {
        let (q, factor) = (self.q(), self.factor());
        let eq = Equations::new(q, mu, &loading.c, loading.qp_data().rigid);
        let noise = settings.qp.tol * factor.lambda_scale(eq.c);
        let c_s = eq.c[..q].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let pressing = settings.qp.tol.sqrt() * c_s;
        let mut x = phase.lambda.clone();
        x.extend((0..eq.r()).map(|m| phase.alpha.get(m).copied().unwrap_or(0.0)));
        let mut member = vec![false; q];
        let mut set = Vec::new();
        let start: Vec<usize> = if eq.rigid.is_some() {
            (0..q).collect() // as the QPs of held bodies: all of Γ_C
        } else {
            (0..q).filter(|&j| x[j] != 0.0 || x[q + j] != 0.0 || eq.c[j] < 0.0).collect()
        };
        grow(&mut set, &mut member, &start);
        phase.status = SolveStatus::MaxIterations;
        let mut stagnation = Stagnation::new();
        let (mut steps, mut restarts) = (0, 0);
        loop {
            let clock = Instant::now();
            let cols: Vec<usize> = set.iter().flat_map(|&j| [j, q + j]).collect();
            // The columns of H it forms (kept by the factor) and its dense system, within the memory budget beside
            // what the factor holds, as the QPs' dense parts are. (The LU copies the k × k system into its
            // factors: twice k² values.)
            let k = cols.len() + eq.r();
            let what =
                || format!("the Newton method's columns of H and its dense system over {k} unknowns (2q = {})", 2 * q);
            factor.fits_beside(what, &cols, 8.0 * 2.0 * (k * k) as f64, settings.memory_budget)?;
            let norm = euclidean(x[..q].iter().copied());
            let relative = |merit: f64| if norm > 0.0 { merit / norm } else { merit };
            let tolerance = (settings.fp.tol * norm).max(noise);
            // At the cap the last point is only evaluated: converged or not.
            let last = steps == settings.fp.max_iter;
            let pass = factor.with_columns(&cols, |all| {
                // `with_columns` has formed every column of `cols` before it calls this (a column solve can fail
                // only on the partial factorization, which forms all of H up front), and `step` asks for no other.
                let col = |k: usize| all[k].as_deref().expect("computed");
                step(&eq, &set, &col, &x, &member, [pressing, tolerance], [steps == 0, last])
            });
            let (next, merit, size, length) = match pass {
                Pass::Grow(dofs) => {
                    log::debug!("newton: {} dofs outside the set would press; the set grows", dofs.len());
                    grow(&mut set, &mut member, &dofs);
                    continue;
                }
                Pass::Converged(merit) => {
                    phase.status = SolveStatus::Converged;
                    phase.history.push(relative(merit));
                    break;
                }
                Pass::Evaluated(merit) => {
                    phase.history.push(relative(merit));
                    break;
                }
                Pass::Singular(merit) => (None, merit, 0, 0.0),
                Pass::Step { x: next, merit, size, length } => (Some(next), merit, size, length),
            };
            phase.history.push(relative(merit));
            // A singular step, or no new smallest merit for STAGNATION_WINDOW steps: a restart from one fixed-point
            // iteration, or the end on the point it has (the merit just recorded is that point's).
            let next = match next {
                Some(next) if !stagnation.stalled(merit) => next,
                stalled => {
                    if restarts < RESTARTS {
                        restarts += 1;
                        let Some(next) = self.fixed_point_step(mu, settings, loading, phase, &x, steps)? else { break };
                        x = next;
                        grow(&mut set, &mut member, &nonzero(q, &x));
                        stagnation = Stagnation::new();
                        continue;
                    }
                    if stalled.is_none() {
                        log::warn!("newton: the linear system of step {} is singular (λ not unique there?)", steps + 1);
                    }
                    phase.status = SolveStatus::Stagnated;
                    break;
                }
            };
            if length < 1.0 {
                log::debug!("newton: step {} damped to {}", steps + 1, Num(length));
            }
            x = next;
            steps += 1;
            phase.iterations = steps;
            let progress = Progress {
                phase: Phase::Newton,
                condensation_seconds: factor.factorization_seconds + factor.condensation_seconds(),
                iteration: steps,
                change: relative(merit),
                qp_iterations: u32::try_from(size).unwrap_or(u32::MAX),
                qp_seconds: clock.elapsed().as_secs_f64(),
            };
            if notify(progress).is_break() {
                phase.status = SolveStatus::Interrupted { iteration: steps };
                break;
            }
        }
        phase.alpha = x.split_off(2 * q);
        phase.bound = x[..q].iter().zip(mu).map(|(v, m)| m * v.max(0.0)).collect();
        phase.lambda = x;
        Ok(())
    }
}

impl Condensed<'_> {
    /// One iteration of the fixed point from the point `x` (λ, then α): the Tresca QP with the bounds μ λ_n of
    /// `x`, started from it; returns its answer as the new point, or `None` when the QP failed (after `steps`
    /// Newton steps: `phase.status` says so, as the fixed point's would, at iteration `steps + 1`).
    fn fixed_point_step(
        &self,
        mu: &[f64],
        settings: &SolverSettings,
        loading: &LoadCase,
        phase: &mut QpPhase,
        x: &[f64],
        steps: usize,
    ) -> Result<Option<Vec<f64>>> {
        let q = self.q();
        let bound: Vec<f64> = x[..q].iter().zip(mu).map(|(v, m)| m * v.max(0.0)).collect();
        let out = self.contact_qp(loading, Some(&bound), settings, Some(&x[..2 * q]))?.solve()?;
        phase.book(&out);
        log::debug!("newton: stalled after {steps} steps; one fixed-point iteration restarts it");
        if let Some(failed) = qp_failed(steps + 1, out.status) {
            phase.status = failed;
            return Ok(None);
        }
        let mut next = out.nu;
        next.resize(2 * q, 0.0);
        next.extend(x[2 * q..].iter().enumerate().map(|(m, a)| out.alpha.get(m).copied().unwrap_or(*a)));
        Ok(Some(next))
    }
}

/// The multiplier dofs where the point `x` is not zero.
fn nonzero(q: usize, x: &[f64]) -> Vec<usize> {
    (0..q).filter(|&j| x[j] != 0.0 || x[q + j] != 0.0).collect()
}

/// Adds `dofs` and their neighbours to the set (kept ascending).
fn grow(set: &mut Vec<usize>, member: &mut [bool], dofs: &[usize]) {
    let q = member.len();
    for &j in dofs {
        let first = j.saturating_sub(1);
        for (k, m) in member.iter_mut().enumerate().take((j + 2).min(q)).skip(first) {
            if !*m {
                *m = true;
                set.push(k);
            }
        }
    }
    set.sort_unstable();
}

/// One pass at the point `x` (λ, then α): the residual `r = H λ + c − (E R) α` and the merit, the dofs outside
/// the set that would press (`r_n` below `−pressing`), and, unless the merit is within `tolerance`, the damped
/// Newton step. `col(k)` is column k of H (2q), for k a normal or tangential unknown of the set.
fn step<'c>(
    eq: &Equations<'_>,
    set: &[usize],
    col: &impl Fn(usize) -> &'c [f64],
    x: &[f64],
    member: &[bool],
    [pressing, tolerance]: [f64; 2],
    [first, last]: [bool; 2],
) -> Pass {
    let (q, mu, r_count) = (eq.q, eq.mu, eq.r());
    let unknowns: Vec<usize> = set.iter().flat_map(|&j| [j, q + j]).collect();
    // (H λ − (E R) α) for a point or a direction (λ zero outside the set).
    let apply = |v: &[f64]| {
        let mut y = vec![0.0; 2 * q];
        for &k in &unknowns {
            if v[k] != 0.0 {
                y.iter_mut().zip(col(k)).for_each(|(yi, h)| *yi += h * v[k]);
            }
        }
        for m in 0..r_count {
            y.iter_mut().zip(eq.e_r(m)).for_each(|(yi, e)| *yi -= e * v[2 * q + m]);
        }
        y
    };
    let r: Vec<f64> = apply(x).iter().zip(eq.c).map(|(a, b)| a + b).collect();
    let outside: Vec<usize> = (0..q).filter(|&j| !member[j] && r[j] < -pressing).collect();
    if !outside.is_empty() {
        return Pass::Grow(outside);
    }
    let rho: Vec<[f64; 2]> = set.iter().map(|&j| [1.0 / col(j)[j], 1.0 / col(q + j)[q + j]]).collect();
    let here = point(eq, set, &rho, x, r);
    if here.merit <= tolerance {
        return Pass::Converged(here.merit);
    }
    if last {
        return Pass::Evaluated(here.merit);
    }
    // The pieces of the point itself: in contact where λ presses, sticking where λ_t is inside the bound. The
    // first step of a body held only by the contact takes them (a frictionless start's r_t does not yet feel
    // friction, the body's tangential motion not yet balanced: it would slip everywhere, its system singular),
    // and so does any step whose pieces of C leave the linear system singular (a held body slipping
    // everywhere, or touching at one dof).
    let own: Vec<Piece> = set
        .iter()
        .map(|&j| {
            if x[j] <= 0.0 {
                Piece::Open
            } else if x[q + j].abs() < mu[j] * x[j] {
                Piece::Stick
            } else {
                Piece::Slip(x[q + j].signum())
            }
        })
        .collect();
    let solved = if first && eq.rigid.is_some() { None } else { linearized(eq, set, col, &here.pieces) };
    let Some((next, m)) = solved.or_else(|| linearized(eq, set, col, &own)) else {
        return Pass::Singular(here.merit);
    };
    let d: Vec<f64> = next.iter().zip(x).map(|(a, b)| a - b).collect();
    // The line search along d: r(x + α d) = r + α (H d_λ − (E R) d_α).
    let hd = apply(&d);
    let mut length = 1.0;
    while length >= SMALLEST_STEP {
        let trial: Vec<f64> = x.iter().zip(&d).map(|(l, v)| l + length * v).collect();
        let r: Vec<f64> = here.r.iter().zip(&hd).map(|(a, b)| a + length * b).collect();
        if point(eq, set, &rho, &trial, r).merit <= (1.0 - ARMIJO * length) * here.merit {
            return Pass::Step { x: trial, merit: here.merit, size: m, length };
        }
        length *= 0.5;
    }
    Pass::Step { x: next, merit: here.merit, size: m, length: 1.0 }
}

/// The point that solves the equations of the pieces (λ, then α), and the size of that linear system; `None`
/// where it is singular (its solution is not finite).
fn linearized<'c>(
    eq: &Equations<'_>,
    set: &[usize],
    col: &impl Fn(usize) -> &'c [f64],
    pieces: &[Piece],
) -> Option<(Vec<f64>, usize)> {
    let (q, mu, r_count) = (eq.q, eq.mu, eq.r());
    // Unknowns λ_n of the dofs in contact, λ_t of those that stick and α; rows r_n of the dofs in contact, r_t of
    // those that stick and the held bodies' equilibrium.
    let contact: Vec<(usize, Piece)> =
        set.iter().zip(pieces).filter(|(_, p)| **p != Piece::Open).map(|(&j, &p)| (j, p)).collect();
    let mut rows: Vec<usize> = contact.iter().map(|&(j, _)| j).collect();
    rows.extend(contact.iter().filter(|(_, p)| *p == Piece::Stick).map(|&(j, _)| q + j));
    let k = rows.len();
    let m = k + r_count;
    let mut next = vec![0.0; 2 * q + r_count];
    if m == 0 {
        return Some((next, 0));
    }
    // Column a of the system at row `row` of H (or of a column of E R: the equilibrium's rows are E R's columns).
    let lambda_column = |a: usize, value: &dyn Fn(usize) -> f64| -> f64 {
        if a < contact.len() {
            let (j, piece) = contact[a];
            let slip = if let Piece::Slip(s) = piece { mu[j] * s * value(q + j) } else { 0.0 };
            value(j) + slip
        } else {
            value(rows[a])
        }
    };
    let entry = |i: usize, a: usize| -> f64 {
        match (i < k, a < k) {
            (true, true) => lambda_column(a, &|u| col(u)[rows[i]]),
            (true, false) => -eq.e_r(a - k)[rows[i]],
            (false, true) => lambda_column(a, &|u| eq.e_r(i - k)[u]),
            (false, false) => 0.0,
        }
    };
    let matrix = Mat::<f64>::from_fn(m, m, entry);
    let load = |i: usize| eq.rigid.map_or(0.0, |(_, b)| b[i - k]);
    let mut sol = Mat::<f64>::from_fn(m, 1, |i, _| if i < k { -eq.c[rows[i]] } else { load(i) });
    PartialPivLu::new(matrix.as_ref()).solve_in_place(sol.as_mut());
    if (0..m).any(|i| !sol[(i, 0)].is_finite()) {
        return None;
    }
    for (i, &u) in rows.iter().enumerate() {
        next[u] = sol[(i, 0)];
    }
    for (a, v) in next[2 * q..].iter_mut().enumerate() {
        *v = sol[(k + a, 0)];
    }
    for &(j, piece) in &contact {
        if let Piece::Slip(s) = piece {
            next[q + j] = mu[j] * s * next[j];
        }
    }
    Some((next, m))
}

/// C at the point `x` on the set (residual `r`), its Euclidean norm with the held bodies' equilibrium (each
/// row `(E R)ᵀ λ − Rᵀ f` divided by the norm of its column of E R: a multiplier), and the piece of each dof.
fn point(eq: &Equations<'_>, set: &[usize], rho: &[[f64; 2]], x: &[f64], r: Vec<f64>) -> Point {
    let (q, mu) = (eq.q, eq.mu);
    let mut parts = Vec::with_capacity(2 * set.len() + eq.r());
    let mut pieces = Vec::with_capacity(set.len());
    for (&j, [rn, rt]) in set.iter().zip(rho) {
        let n = x[j] - rn * r[j];
        let b = mu[j] * n.max(0.0);
        let t = x[q + j] - rt * r[q + j];
        parts.push(x[j] - n.max(0.0));
        parts.push(x[q + j] - t.clamp(-b, b));
        pieces.push(if n <= 0.0 {
            Piece::Open
        } else if t.abs() < b {
            Piece::Stick
        } else {
            Piece::Slip(t.signum())
        });
    }
    if let Some((_, load)) = eq.rigid {
        for (m, b) in load.iter().enumerate() {
            let (g, size) = (eq.e_r(m), eq.e_r_norms[m]);
            let held: f64 = g.iter().zip(&x[..2 * q]).map(|(e, l)| e * l).sum();
            parts.push(if size > 0.0 { (held - b) / size } else { 0.0 });
        }
    }
    Point { r, merit: euclidean(parts.into_iter()), pieces }
}
