//! The Γ_C QP solved by clarabel's interior-point method: the reference every faster method is tested
//! against, and the fallback of [`QpMethod::Auto`].

use std::time::Instant;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettings, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT};

use crate::error::{Error, Result};
use crate::qp::equality::Elimination;
use crate::qp::{diagonal, QpOutcome, QpStatus, Scaling, FALLBACK_TOL};
use crate::settings::friction::check_thresholds;
use crate::settings::{QpMethod, QpSettings};

/// Peak bytes of one clarabel solve of a dense QP over k unknowns, per k²: the caller's block of H, the copy
/// [`BoxQp`] keeps, clarabel's upper triangle of it, its equilibrated copy, the KKT matrix and its factor. The
/// example `qp_memory` measures the peak RSS of a solve less the RSS before: 15.1–15.4 × 8 k² with faer's KKT
/// solver and 13.1–13.3 × 8 k² with QDLDL at k = 1,000, 2,000 and 4,000 (a budget counting 4 × 8 k² let an
/// adaptive loop reach 3.45 GB under a budget of 2 GB).
pub const DENSE_BYTES_PER_K2: f64 = 8.0 * 16.0;

/// The box-constrained QP of P(g) (frictional) or of the frictionless problem, set up once; the
/// tangential bounds g can be changed between solves.
///
/// A frictional QP is written in the scaled variables `τ = ν_t / w_t` (see the `scaling` module of [`crate::qp`]) with the box
/// `|τ_j| ≤ g_j / w_t,j`, and `|τ_j| ≤ 1` where `g_j` vanishes (separated dofs, `w_t,j = 0`): the box always
/// has an interior, which a box `−0 ≤ ν_t ≤ 0` would not have. Changing g then changes the values of P, q
/// and b but not their pattern, so clarabel's set-up
/// (symbolic factorization of its KKT matrix) is reused across the whole fixed point.
pub struct BoxQp {
    solver: Option<DefaultSolver<f64>>,
    settings: QpSettings,
    /// The tolerance asked for (`settings.tol` may have fallen back to [`FALLBACK_TOL`]).
    requested_tol: f64,
    h: Vec<f64>,
    c: Vec<f64>,
    q: usize,
    frictional: bool,
    n_scale: f64,
    bounds: Vec<f64>,
    /// Equality constraints `G ν = b` (G r × k row-major, b r): the equilibrium of the bodies held only by
    /// the contact ([`BoxQp::with_equality`]).
    equality: Option<(Vec<f64>, Vec<f64>)>,
    /// The elimination of those rows the solver was built with ([`BoxQp::rebuild`]), `None` where they are kept as
    /// a zero cone (dependent) or there are none.
    elimination: Option<Elimination>,
    /// Whether independent rows are eliminated (always, but in the tests that compare with the zero cone).
    eliminate: bool,
}

impl std::fmt::Debug for BoxQp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BoxQp").field("q", &self.q).field("frictional", &self.frictional).finish()
    }
}

fn status_name(s: SolverStatus) -> &'static str {
    match s {
        SolverStatus::Unsolved => "unsolved",
        SolverStatus::Solved => "solved",
        SolverStatus::PrimalInfeasible => "primal infeasible",
        SolverStatus::DualInfeasible => "dual infeasible (the contact problem has no bounded multiplier)",
        SolverStatus::AlmostSolved => "almost solved",
        SolverStatus::AlmostPrimalInfeasible => "almost primal infeasible",
        SolverStatus::AlmostDualInfeasible => "almost dual infeasible",
        SolverStatus::MaxIterations => "iteration limit",
        SolverStatus::MaxTime => "time limit",
        SolverStatus::NumericalError => "numerical error",
        SolverStatus::InsufficientProgress => "insufficient progress",
        SolverStatus::CallbackTerminated => "stopped by callback",
    }
}

/// clarabel's static regularization of the KKT systems of a QP with inequality rows only: boxes, and the rows of the
/// bodies held only by the contact once eliminated ([`crate::qp::equality`]; where those rows are dependent and kept
/// as a zero cone, clarabel's default 1e-8, which its zero block needs). clarabel solves the
/// regularized system and refines the answer against the exact one; where the scaled H is as ill-conditioned as on fine
/// graded meshes, 1e-8 is more than the refinement corrects, the search directions are inexact and the interior-point
/// method stalls short of `tol`. Measured (Hertz, Coulomb μ = 1, ν = 0, P0, the levels of an adaptive loop, clarabel
/// forced): with 1e-8, 14 of 26 QPs met only `FALLBACK_TOL` at 6.7k unknowns (q = 232), 29 of 40 at 11.5k and 29 of 31
/// at 36k (q = 751), where the fixed point stagnated at changes of 1e-4; with 1e-12, every QP met `tol` = 1e-12 and
/// each fixed point converged (26 to 37 iterations, KKT residuals 1.4e-9 to 5.3e-8), in less time. With 1e-12 for
/// the equality rows kept as a zero cone, 11 tests of bodies held only by the contact failed (`held_by_contact.rs`
/// among them). A QP that fails is solved again at `FALLBACK_TOL` with clarabel's default, as before.
///
/// The eliminated rows, measured on a block (0, 2) × (0, 1) held only by the contact, 40 × 20 to 320 × 160 cells,
/// Coulomb: as a zero cone (1e-8) the first Coulomb QP failed from 160 × 80 cells on at μ = 0.3, ν = 0.3, and 14 of 29
/// and 23 of 36 QPs met only `FALLBACK_TOL` at ν = 0, μ = 1; eliminated, every fixed point converges, with 0 and 5 of
/// 26 and 27 QPs at `FALLBACK_TOL` only there (with 1e-10 instead of 1e-12: 15 of 26 and 17 of 37).
const BOX_REGULARIZATION: f64 = 1e-12;

/// clarabel's settings for our tolerances: presolve off (so data updates work), its KKT solver, and
/// *reduced* tolerances no looser than ours. clarabel stops early ("almost solved") when it cannot make
/// progress but meets its reduced tolerances, 5e-5 (gap) and 1e-4 (feasibility) by default: far too
/// loose for λ (a Tresca QP stopped there was 3 % off). We accept only answers that meet the looser of
/// `tol` and [`FALLBACK_TOL`].
fn clarabel_settings(settings: &QpSettings) -> DefaultSettings<f64> {
    let accepted = settings.tol.max(FALLBACK_TOL);
    DefaultSettings::<f64> {
        verbose: false,
        tol_gap_abs: settings.tol,
        tol_gap_rel: settings.tol,
        tol_feas: settings.tol,
        tol_ktratio: settings.tol.sqrt(),
        reduced_tol_gap_abs: accepted,
        reduced_tol_gap_rel: accepted,
        reduced_tol_feas: accepted,
        reduced_tol_ktratio: accepted.sqrt(),
        max_iter: settings.max_iter,
        presolve_enable: false,
        direct_solve_method: settings.kkt_solver.to_string(),
        ..DefaultSettings::default()
    }
}

impl BoxQp {
    /// Sets up the QP. `h` is the dense symmetric `H` (column-major, `k × k` with `k = q` for a
    /// frictionless QP and `k = 2q` otherwise), `c` the linear term, `bounds` the tangential bounds
    /// (length q) for a frictional QP, `None` for a frictionless one.
    ///
    /// The settings are taken as validated ([`QpSettings::validate`]).
    ///
    /// # Errors
    /// [`Error::QpSetup`] for `h` or `c` of the wrong size, or if clarabel rejects the data;
    /// [`Error::BadThreshold`].
    pub fn new(h: &[f64], c: &[f64], q: usize, bounds: Option<&[f64]>, settings: &QpSettings) -> Result<Self> {
        let frictional = bounds.is_some();
        let k = if frictional { 2 * q } else { q };
        if h.len() != k * k || c.len() != k {
            return Err(Error::QpSetup {
                what: format!("H of {} values and c of {} for {k} unknowns (q = {q})", h.len(), c.len()),
            });
        }
        if let Some(g) = bounds {
            check_thresholds(g, q)?;
        }
        let n_scale = Scaling::normal_scale(&diagonal(h, c.len()), c, q);
        let mut qp = Self {
            solver: None,
            settings: *settings,
            requested_tol: settings.tol,
            h: h.to_vec(),
            c: c.to_vec(),
            q,
            frictional,
            n_scale: n_scale.unwrap_or(0.0),
            bounds: bounds.map_or_else(Vec::new, <[f64]>::to_vec),
            equality: None,
            elimination: None,
            eliminate: true,
        };
        if n_scale.is_none() {
            // Nothing pushes at all (c = 0): λ = 0 solves P(g).
            return Ok(qp);
        }
        qp.rebuild()?;
        Ok(qp)
    }

    /// Adds the equality constraints `G ν = b` (G r × k row-major over the QP's k unknowns, b r): the
    /// equilibrium of the bodies held only by the contact (`problem/floating.rs`). The answer's
    /// [`QpOutcome::alpha`] holds their multipliers α, with stationarity `H ν + c − Gᵀ α ∈ −N(ν)`.
    ///
    /// # Errors
    /// [`Error::QpSetup`] for `g` of the wrong size, or if clarabel rejects the data.
    pub fn with_equality(mut self, g: Vec<f64>, b: Vec<f64>) -> Result<Self> {
        let k = self.c.len();
        if g.len() != k * b.len() {
            return Err(Error::QpSetup { what: format!("G of {} values for {} rows of {k}", g.len(), b.len()) });
        }
        if self.n_scale == 0.0 {
            // Nothing pushes through c: the size of ν that balances the load.
            let (b_max, g_max) =
                (b.iter().fold(0.0_f64, |m, v| m.max(v.abs())), g.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
            if b_max > 0.0 && g_max > 0.0 {
                self.n_scale = b_max / g_max;
            }
        }
        self.equality = Some((g, b));
        if self.n_scale > 0.0 {
            self.rebuild()?;
        }
        Ok(self)
    }

    /// The equality rows in the scaled unknowns, each divided by its largest entry: the rows (r × k) and
    /// the divisors ρ.
    fn scaled_equality(&self, w: &[f64]) -> (Vec<Vec<f64>>, Vec<f64>) {
        let Some((g, b)) = &self.equality else { return (Vec::new(), Vec::new()) };
        let k = w.len();
        let mut rows = Vec::with_capacity(b.len());
        let mut rho = Vec::with_capacity(b.len());
        for row in g.chunks_exact(k) {
            let scaled: Vec<f64> = row.iter().zip(w).map(|(gi, wi)| gi * wi).collect();
            let m = scaled.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let r = if m > 0.0 { 1.0 / m } else { 1.0 };
            rows.push(scaled.iter().map(|v| v * r).collect());
            rho.push(r);
        }
        (rows, rho)
    }

    /// The equality rows solved for one unknown each, in the scaled unknowns of `scaling` (`None` without rows or
    /// where they are dependent).
    fn elimination(&self, scaling: &Scaling) -> Option<Elimination> {
        let (_, eq_b) = self.equality.as_ref().filter(|_| self.eliminate)?;
        let (rows, rho) = self.scaled_equality(&scaling.w);
        Elimination::new(&rows, &eq_b.iter().zip(&rho).map(|(v, r)| v * r).collect::<Vec<_>>())
    }

    /// Builds clarabel's solver for the current data and settings, with the elimination it was built with; on an
    /// error both stay as they were.
    fn rebuild(&mut self) -> Result<()> {
        let scaling = self.scaling();
        let elimination = self.elimination(&scaling);
        let solver = match &elimination {
            Some(e) => self.setup_eliminated(e, &scaling)?,
            None => self.setup()?,
        };
        (self.solver, self.elimination) = (Some(solver), elimination);
        Ok(())
    }

    /// Builds clarabel's solver for the current data and settings, the equality rows (if any) as a zero cone.
    fn setup(&self) -> Result<DefaultSolver<f64>> {
        let scaling = self.scaling();
        let (q, frictional) = (self.q, self.frictional);
        let k = if frictional { 2 * q } else { q };
        let (p, qv, mut b) = self.scaled_data();
        let (eq_rows, rho) = self.scaled_equality(&scaling.w);
        if let Some((_, eq_b)) = &self.equality {
            b.extend(eq_b.iter().zip(&rho).map(|(v, r)| v * r));
        }
        // Upper triangle of P in CSC.
        let mut colptr = Vec::with_capacity(k + 1);
        let mut rowval = Vec::with_capacity(k * (k + 1) / 2);
        colptr.push(0);
        for j in 0..k {
            rowval.extend(0..=j);
            colptr.push(rowval.len());
        }
        let p = CscMatrix::new(k, k, colptr, rowval, p);
        // Constraints A x + s = b, s ≥ 0:  −ν_n ≤ 0;  τ ≤ 1;  −τ ≤ 1.
        // Then the equality rows G̃ x = b̃ (zero cone).
        let m = if frictional { 3 * q } else { q };
        let r = eq_rows.len();
        let mut colptr = Vec::with_capacity(k + 1);
        let (mut rowval, mut nzval) = (Vec::with_capacity(m + r * k), Vec::with_capacity(m + r * k));
        colptr.push(0);
        for j in 0..k {
            if j < q {
                rowval.push(j);
                nzval.push(-1.0);
            } else {
                rowval.extend([j, q + j]);
                nzval.extend([1.0, -1.0]);
            }
            for (e, row) in eq_rows.iter().enumerate() {
                if row[j] != 0.0 {
                    rowval.push(m + e);
                    nzval.push(row[j]);
                }
            }
            colptr.push(rowval.len());
        }
        let a = CscMatrix::new(m + r, k, colptr, rowval, nzval);
        let cones = if r > 0 { vec![NonnegativeConeT(m), ZeroConeT(r)] } else { vec![NonnegativeConeT(m)] };
        let cs = self.solver_settings((r == 0).then_some(BOX_REGULARIZATION));
        DefaultSolver::new(&p, &qv, &a, &b, &cones, cs).map_err(|e| Error::QpSetup { what: e.to_string() })
    }

    /// clarabel's settings for this QP, with the static regularization `regularization` (`None`: clarabel's
    /// default), except on the retry of a QP that failed ([`BoxQp::solve`]), which keeps clarabel's default, the
    /// pair (1e-8, [`FALLBACK_TOL`]) that answered such QPs before.
    fn solver_settings(&self, regularization: Option<f64>) -> DefaultSettings<f64> {
        let mut cs = clarabel_settings(&self.settings);
        if let Some(value) = regularization.filter(|_| self.settings.tol <= self.requested_tol) {
            cs.static_regularization_constant = value;
        }
        cs
    }

    /// The box row of unknown `i` (a normal or a tangential one, `tbox` the scaled tangential boxes) as
    /// (coefficient, right-hand side) pairs: `−x ≤ 0`, or `x ≤ box` and `−x ≤ box`.
    fn box_rows(&self, i: usize, tbox: &[f64]) -> Vec<(f64, f64)> {
        if i < self.q {
            vec![(-1.0, 0.0)]
        } else {
            vec![(1.0, tbox[i - self.q]), (-1.0, tbox[i - self.q])]
        }
    }

    /// Builds clarabel's solver for the QP over the unknowns left by `elimination`: their box rows, then those of
    /// the pivots, `c (x₀ + m x_N) ≤ β` written `c m x_N ≤ β − c x₀` (see [`crate::qp::equality`]).
    fn setup_eliminated(&self, elimination: &Elimination, scaling: &Scaling) -> Result<DefaultSolver<f64>> {
        let (upper, qv, _) = self.scaled_data();
        let at = |i: usize, j: usize| upper[if i <= j { j * (j + 1) / 2 + i } else { i * (i + 1) / 2 + j }];
        let (p, qn) = elimination.reduce(at, &qv);
        drop(upper);
        let tbox = scaling.tangential_box(self.q, &self.bounds);
        let (rest, pivots) = (&elimination.rest, &elimination.pivots);
        let own: Vec<Vec<(f64, f64)>> = rest.iter().map(|&i| self.box_rows(i, &tbox)).collect();
        let theirs: Vec<Vec<(f64, f64)>> = pivots.iter().map(|&i| self.box_rows(i, &tbox)).collect();
        let n = rest.len();
        let first_pivot_row: usize = own.iter().map(Vec::len).sum();
        let rows = first_pivot_row + theirs.iter().map(Vec::len).sum::<usize>();
        let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
        let mut row = 0;
        for (ii, own_rows) in own.iter().enumerate() {
            for (coefficient, _) in own_rows {
                rowval.push(row);
                nzval.push(*coefficient);
                row += 1;
            }
            let mut pivot_row = first_pivot_row;
            for (a, pivot_rows) in theirs.iter().enumerate() {
                for (coefficient, _) in pivot_rows {
                    if elimination.m[a][ii] != 0.0 {
                        rowval.push(pivot_row);
                        nzval.push(coefficient * elimination.m[a][ii]);
                    }
                    pivot_row += 1;
                }
            }
            colptr.push(rowval.len());
        }
        let b: Vec<f64> = own
            .iter()
            .flatten()
            .map(|(_, beta)| *beta)
            .chain(theirs.iter().zip(&elimination.x0).flat_map(|(r, x0)| r.iter().map(move |(c, beta)| beta - c * x0)))
            .collect();
        let mut pcol = vec![0];
        let mut prow = Vec::with_capacity(p.len());
        for j in 0..n {
            prow.extend(0..=j);
            pcol.push(prow.len());
        }
        let p = CscMatrix::new(n, n, pcol, prow, p);
        let a = CscMatrix::new(rows, n, colptr, rowval, nzval);
        let cs = self.solver_settings(Some(BOX_REGULARIZATION));
        DefaultSolver::new(&p, &qn, &a, &b, &[NonnegativeConeT(rows)], cs)
            .map_err(|e| Error::QpSetup { what: e.to_string() })
    }

    /// Values of the upper triangle of the scaled P (column by column) and the scaled q, for the current
    /// bounds: variables `x = (ν_n / s, τ)`, objective divided by the largest diagonal entry, and further where the
    /// answer's would be small ([`BoxQp::scaling`]).
    fn scaled_data(&self) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let scaling = self.scaling();
        // Rows: −x_n ≤ 0, then x_t ≤ box, then −x_t ≤ box.
        let tbox = scaling.tangential_box(self.q, &self.bounds);
        let b: Vec<f64> =
            std::iter::repeat_n(0.0, self.q).chain(tbox.iter().copied()).chain(tbox.iter().copied()).collect();
        let Scaling { r, root_phi, .. } = scaling;
        let k = r.len();
        let mut p = Vec::with_capacity(k * (k + 1) / 2);
        for j in 0..k {
            for i in 0..=j {
                p.push(r[i] * self.h[j * k + i] * r[j]);
            }
        }
        let qv = (0..k).map(|i| r[i] * self.c[i] / root_phi).collect();
        (p, qv, b)
    }

    /// The scaling of the current data and bounds, its objective divided further where the answer's would be
    /// small in those units ([`Scaling::with_objective_at_least_one`]). With the equality of bodies held only by
    /// the contact, the point below need not satisfy it: its objective then only sets a size, not a bound on the
    /// answer's, and the gap clarabel stops on is still never looser than in the units before (the divisor only
    /// enlarges the objective, by 1/√ε at most). Measured: a history shearing a punch held by the contact has its
    /// stick residual at 6e-7 without it, below 1e-8 with it.
    fn scaling(&self) -> Scaling {
        let scaling = Scaling::new(&diagonal(&self.h, self.c.len()), &self.c, self.q, self.n_scale, &self.bounds);
        let tbox = scaling.tangential_box(self.q, &self.bounds);
        let (k, r, root_phi) = (self.c.len(), &scaling.r, scaling.root_phi);
        // The feasible direction of steepest descent in the scaled unknowns: −q̃ where the normal unknowns
        // may grow, −q̃ on the tangential ones whose box is open.
        let d: Vec<f64> = (0..k)
            .map(|i| {
                let qi = r[i] * self.c[i] / root_phi;
                if i < self.q {
                    (-qi).max(0.0)
                } else if self.bounds[i - self.q] > 0.0 {
                    -qi
                } else {
                    0.0
                }
            })
            .collect();
        let pd: Vec<f64> = (0..k).map(|i| (0..k).map(|j| r[i] * self.h[j * k + i] * r[j] * d[j]).sum()).collect();
        let dpd: f64 = d.iter().zip(&pd).map(|(a, b)| a * b).sum();
        let dd: f64 = d.iter().map(|a| a * a).sum();
        let reach =
            (self.q..k).filter(|&i| d[i] != 0.0).map(|i| tbox[i - self.q] / d[i].abs()).fold(f64::INFINITY, f64::min);
        let t = if dpd > 0.0 { (dd / dpd).min(reach) } else { reach };
        let estimate = t * (0.5 * t * dpd - dd);
        scaling.with_objective_at_least_one(estimate)
    }

    /// Replaces the tangential bounds g (length q) without rebuilding the solver (with equality
    /// constraints, whose scaled rows follow the bounds, it is rebuilt).
    ///
    /// # Errors
    /// [`Error::BadThreshold`] for a wrong length or a negative value; [`Error::QpSetup`] on a
    /// frictionless QP, or if clarabel refuses the update.
    pub fn set_bounds(&mut self, g: &[f64]) -> Result<()> {
        if !self.frictional {
            return Err(Error::QpSetup { what: "tangential bounds for a frictionless QP".into() });
        }
        check_thresholds(g, self.q)?;
        self.bounds.copy_from_slice(g);
        if self.equality.is_some() {
            if self.solver.is_some() {
                self.rebuild()?;
            }
            return Ok(());
        }
        let (p, qv, b) = self.scaled_data();
        if let Some(solver) = self.solver.as_mut() {
            solver.update_b(&b).map_err(|e| Error::QpSetup { what: format!("{e:?}") })?;
            solver.update_P(&p).map_err(|e| Error::QpSetup { what: format!("{e:?}") })?;
            solver.update_q(&qv).map_err(|e| Error::QpSetup { what: format!("{e:?}") })?;
        }
        Ok(())
    }

    /// Solves the QP. If it fails at a tolerance tighter than [`FALLBACK_TOL`], it is solved again at
    /// that tolerance (and stays there for later solves with new bounds): clarabel cannot always reach
    /// 1e-12 on a badly conditioned H, and an answer to 1e-10 beats none. Every answer that meets only
    /// the fallback tolerance is reported as [`QpStatus::Inaccurate`].
    pub fn solve(&mut self) -> QpOutcome {
        let out = self.solve_once();
        if !matches!(out.status, QpStatus::Failed(_)) || self.settings.tol >= FALLBACK_TOL {
            return out;
        }
        log::warn!(
            "QP failed ({:?}) at tol {}: solving again at {}",
            out.status,
            crate::error::Num(self.settings.tol),
            crate::error::Num(FALLBACK_TOL)
        );
        self.settings.tol = FALLBACK_TOL;
        if self.rebuild().is_err() {
            return out;
        }
        let mut again = self.solve_once();
        again.iterations += out.iterations;
        again.seconds += out.seconds;
        again
    }

    fn solve_once(&mut self) -> QpOutcome {
        let q = self.q;
        let k = if self.frictional { 2 * q } else { q };
        let scaling = self.scaling();
        let (_, rho) = self.scaled_equality(&scaling.w);
        let elimination = self.elimination.clone();
        let Some(solver) = self.solver.as_mut() else {
            // Nothing pushes (c = 0, no load on a body held by the contact): ν = 0, α = 0.
            return QpOutcome {
                nu: vec![0.0; k],
                status: QpStatus::Solved,
                iterations: 0,
                seconds: 0.0,
                method: QpMethod::Clarabel,
                factorizations: 0,
                fallback: false,
                alpha: vec![0.0; rho.len()],
            };
        };
        let clock = Instant::now();
        solver.solve();
        let sol = &solver.solution;
        let (sol_x, sol_z, iterations) = (sol.x.clone(), sol.z.clone(), sol.iterations);
        let status = match sol.status {
            SolverStatus::Solved if self.settings.tol <= self.requested_tol => QpStatus::Solved,
            SolverStatus::Solved | SolverStatus::AlmostSolved => QpStatus::Inaccurate,
            s => QpStatus::Failed(status_name(s)),
        };
        // The scaled unknowns x, and the equality rows' duals y: where the rows were eliminated, from stationarity
        // at their pivots (`crate::qp::equality`), else clarabel's own duals of its zero cone.
        let (x, y) = match elimination {
            Some(elimination) => {
                let x = elimination.expand(&sol_x);
                let y = self.eliminated_duals(&elimination, &scaling, &x, &sol_z);
                (x, y)
            }
            None => {
                let m = if self.frictional { 3 * q } else { q };
                (sol_x[..k].to_vec(), (0..rho.len()).map(|e| sol_z[m + e]).collect())
            }
        };
        let nu = (0..k).map(|i| x[i] * scaling.w[i]).collect();
        // Stationarity of the scaled QP, multiplied by φ / w_i, reads H ν + c + Gᵀ (φ ρ y) + … = 0, so α = −φ ρ y
        // (φ = root_phi², formed as two products).
        let alpha = rho.iter().zip(&y).map(|(r, y)| -(scaling.root_phi * (scaling.root_phi * r * y))).collect();
        QpOutcome {
            nu,
            status,
            iterations,
            seconds: clock.elapsed().as_secs_f64(),
            method: QpMethod::Clarabel,
            factorizations: 0,
            fallback: false,
            alpha,
        }
    }
}

impl BoxQp {
    /// The duals of the eliminated equality rows at the scaled answer `x` (all k unknowns), `z` the duals of the
    /// reduced QP's rows (the pivots' box rows last): `G̃_pᵀ y = −(P̃ x + q̃ + Ãᵀ z)_p`. NaN if `G̃_p` is singular
    /// (it is not: the elimination took its largest pivots).
    fn eliminated_duals(&self, elimination: &Elimination, scaling: &Scaling, x: &[f64], z: &[f64]) -> Vec<f64> {
        let (k, r, root_phi) = (x.len(), &scaling.r, scaling.root_phi);
        let tbox = scaling.tangential_box(self.q, &self.bounds);
        let mut row: usize = elimination.rest.iter().map(|&i| self.box_rows(i, &tbox).len()).sum();
        let s_p: Vec<f64> = elimination
            .pivots
            .iter()
            .map(|&p| {
                let px: f64 = (0..k).map(|j| r[p] * self.h[j * k + p] * r[j] * x[j]).sum();
                let az: f64 = self.box_rows(p, &tbox).iter().map(|(c, _)| c * z[post_inc(&mut row)]).sum();
                px + r[p] * self.c[p] / root_phi + az
            })
            .collect();
        elimination.duals(&s_p).unwrap_or_else(|| vec![f64::NAN; elimination.pivots.len()])
    }
}

/// `*i`, then `*i += 1`.
fn post_inc(i: &mut usize) -> usize {
    *i += 1;
    *i - 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small frictional QP (q = 2) with both normal multipliers active and one tangential bound hit.
    fn small_qp(settings: &QpSettings) -> BoxQp {
        #[rustfmt::skip]
        let h = [
            4.0, 1.0, 0.5, 0.0,
            1.0, 3.0, 0.0, 0.5,
            0.5, 0.0, 2.0, 0.3,
            0.0, 0.5, 0.3, 2.0,
        ];
        let c = [-2.0, -1.5, 1.0, -0.1];
        BoxQp::new(&h, &c, 2, Some(&[0.2, 0.2]), settings).expect("valid QP")
    }

    /// Random frictional QPs (q = 3 to 6) with 1 to 3 dense equality rows through a point inside the box: the answer
    /// with the rows eliminated is the one with them as a zero cone, and its rigid-motion multipliers α satisfy
    /// stationarity, `H ν + c − Gᵀ α` zero on the free unknowns, of the right sign on the bounds. Two answers of a
    /// strictly convex QP that each meet a relative gap ε lie within `√(2 ε max(1, |f|) / λ_min)` of the optimum in
    /// the scaled unknowns; H here has λ_min ≥ 1e-3 (measured: 2.4e-10 apart, stationarity to 5.6e-10).
    #[test]
    fn eliminated_rows_give_the_zero_cone_answer_and_its_multipliers() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let settings = QpSettings::default();
        let (mut worst_apart, mut worst_stationarity) = (0.0_f64, 0.0_f64);
        let (mut pivots_on_bounds, mut unknowns_on_bounds) = (0, 0);
        for case in 0..40 {
            let q = 3 + case % 4;
            let (k, r) = (2 * q, 1 + case % 3);
            let b_mat: Vec<f64> = (0..k * k).map(|_| rnd() - 0.5).collect();
            let mut h = vec![0.0; k * k];
            for i in 0..k {
                for j in 0..k {
                    h[j * k + i] = (0..k).map(|l| b_mat[l * k + i] * b_mat[l * k + j]).sum::<f64>();
                }
                h[i * k + i] += 1e-3;
            }
            let c: Vec<f64> = (0..k).map(|_| 2.0 * rnd() - 1.0).collect();
            let g: Vec<f64> = (0..q).map(|_| 0.1 + rnd()).collect();
            let inside: Vec<f64> = (0..k).map(|i| if i < q { 0.1 + rnd() } else { (rnd() - 0.5) * g[i - q] }).collect();
            let rows: Vec<f64> = (0..r * k).map(|_| 2.0 * rnd() - 1.0).collect();
            let rhs: Vec<f64> = rows.chunks(k).map(|row| row.iter().zip(&inside).map(|(a, b)| a * b).sum()).collect();
            let qp = BoxQp::new(&h, &c, q, Some(&g), &settings).unwrap();
            let mut eliminated = qp.with_equality(rows.clone(), rhs.clone()).unwrap();
            assert!(eliminated.elimination.is_some(), "case {case}: independent rows are eliminated");
            let mut kept =
                BoxQp::new(&h, &c, q, Some(&g), &settings).unwrap().with_equality(rows.clone(), rhs).unwrap();
            kept.eliminate = false;
            kept.rebuild().unwrap();
            assert!(kept.elimination.is_none());
            let pivots = eliminated.elimination.as_ref().unwrap().pivots.clone();
            let (a, b) = (eliminated.solve(), kept.solve());
            let on_bound =
                |i: usize| if i < q { a.nu[i].abs() < 1e-9 } else { (a.nu[i].abs() - g[i - q]).abs() < 1e-9 };
            pivots_on_bounds += pivots.iter().filter(|&&p| on_bound(p)).count();
            unknowns_on_bounds += (0..k).filter(|&i| on_bound(i)).count();
            assert!(a.status == QpStatus::Solved && b.status == QpStatus::Solved, "case {case}: {a:?} {b:?}");
            let size = a.nu.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            let apart = a.nu.iter().zip(&b.nu).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / size;
            worst_apart = worst_apart.max(apart);
            // Stationarity with the eliminated answer's α, unknown by unknown.
            let (lo, hi): (Vec<f64>, Vec<f64>) =
                (0..k).map(|i| if i < q { (0.0, f64::INFINITY) } else { (-g[i - q], g[i - q]) }).unzip();
            let gradient_size = c.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            for i in 0..k {
                let hv: f64 = (0..k).map(|j| h[j * k + i] * a.nu[j]).sum();
                let s = hv + c[i] - (0..r).map(|e| a.alpha[e] * rows[e * k + i]).sum::<f64>();
                let near = |bound: f64| (a.nu[i] - bound).abs() <= 1e-6 * size;
                let violation = if near(lo[i]) {
                    (-s).max(0.0)
                } else if near(hi[i]) {
                    s.max(0.0)
                } else {
                    s.abs()
                };
                worst_stationarity = worst_stationarity.max(violation / gradient_size);
            }
        }
        // ε = 1e-12, |f| = O(1), λ_min = 1e-3: 4.5e-5.
        let bound = (2.0 * settings.tol / 1e-3_f64).sqrt();
        assert!(worst_apart <= bound, "the two answers {worst_apart:e} apart (bound {bound:e})");
        assert!(worst_stationarity <= bound, "stationarity violated by {worst_stationarity:e}");
        // The cases reach the pivots' dense rows too (measured: 16 of the 80 pivots on a bound, 168 of 360 unknowns).
        assert!(
            pivots_on_bounds > 0 && unknowns_on_bounds > pivots_on_bounds,
            "{pivots_on_bounds} {unknowns_on_bounds}"
        );
    }

    #[test]
    fn almost_solved_is_never_looser_than_the_fallback_tolerance() {
        for tol in [1e-14, 1e-12, FALLBACK_TOL, 1e-8, 1e-6] {
            let cs = clarabel_settings(&QpSettings { tol, ..Default::default() });
            let accepted = tol.max(FALLBACK_TOL);
            for (name, v) in [
                ("gap_abs", cs.reduced_tol_gap_abs),
                ("gap_rel", cs.reduced_tol_gap_rel),
                ("feas", cs.reduced_tol_feas),
            ] {
                assert!(v <= accepted, "tol {tol:e}: reduced {name} = {v:e} accepts answers worse than {accepted:e}");
            }
            assert!(cs.reduced_tol_ktratio <= accepted.sqrt(), "tol {tol:e}: reduced κ/τ ratio");
        }
    }

    /// After a fallback a QP stays at FALLBACK_TOL for later solves (new bounds), and each of those
    /// answers is reported as Inaccurate, not Solved; the same QP asked for FALLBACK_TOL is Solved.
    #[test]
    fn answers_after_a_fallback_are_reported_inaccurate() {
        let strict = QpSettings { tol: 1e-12, ..Default::default() };
        let mut qp = small_qp(&strict);
        assert_eq!(qp.solve().status, QpStatus::Solved, "a well-conditioned QP reaches 1e-12");
        // What solve() does when clarabel fails at the requested tolerance.
        qp.settings.tol = FALLBACK_TOL;
        qp.rebuild().expect("set up");
        for bounds in [[0.2, 0.2], [0.1, 0.3]] {
            qp.set_bounds(&bounds).expect("valid bounds");
            assert_eq!(qp.solve().status, QpStatus::Inaccurate, "bounds {bounds:?}");
        }
        let mut loose = small_qp(&QpSettings { tol: FALLBACK_TOL, ..Default::default() });
        assert_eq!(loose.solve().status, QpStatus::Solved);
    }

    /// A QP whose answer is small against its data, as on a graded mesh: a coarse dof far from the contact, where
    /// the gap is large (c = 1, H = 1), sets the scales; the fine dofs that touch have 2e-6 on H's diagonal and are
    /// pushed by about 1e-9 (λ ≈ 3e-4, the objective about −1e-13 per dof in the scaled units). clarabel's relative
    /// gap is the gap over max(1, |objective|): in those units an absolute one, and λ came back 2.1e-3 off
    /// (relative) at tol 1e-12. With the objective brought to 1 it is the exact answer to 5e-14.
    #[test]
    fn a_small_objective_is_solved_to_the_relative_tolerance() {
        let k = 9;
        let mut h = vec![0.0; k * k];
        h[0] = 1.0;
        for i in 1..k {
            h[i * k + i] = 2e-6;
            // Neighbours coupled, as the multipliers of one contact zone are (H stays diagonally dominant).
            if i + 1 < k {
                h[(i + 1) * k + i] = 0.5e-6;
                h[i * k + i + 1] = 0.5e-6;
            }
        }
        let c: Vec<f64> = (0..k).map(|i| if i == 0 { 1.0 } else { -1e-9 * (1.0 + 0.1 * i as f64) }).collect();
        let settings = QpSettings { tol: 1e-12, ..Default::default() };
        let out = BoxQp::new(&h, &c, k, None, &settings).expect("valid QP").solve();
        assert_eq!(out.status, QpStatus::Solved);
        // Every multiplier of the fine dofs is positive here: they solve H_FF λ_F = −c_F exactly.
        let h_ff = nalgebra::DMatrix::from_fn(k - 1, k - 1, |i, j| h[(j + 1) * k + i + 1]);
        let free = h_ff
            .cholesky()
            .expect("H_FF is positive definite")
            .solve(&nalgebra::DVector::from_fn(k - 1, |i, _| -c[i + 1]));
        let worst = (1..k).map(|i| (out.nu[i] - free[i - 1]).abs() / free[i - 1]).fold(0.0, f64::max);
        assert!(
            free.iter().all(|l| *l > 0.0) && out.nu[0].abs() < 1e-12,
            "the fine dofs touch, the coarse one does not"
        );
        assert!(worst < 1e-8, "λ {worst:e} off (relative)");
    }

    /// A contact pushed only by round-off of the gap far away (a body unloaded off a curved obstacle): the objective
    /// of a feasible point is 1e-34 of the data's units. Divided by that, clarabel was handed data of 1e34 and failed
    /// ("numerical error"); it is divided by √ε at most, and the QP is solved. Its answer is 0 to the QP's accuracy
    /// in the data's units (λ of size 1 balances the coarse dof): within √tol of the exact 4e-12.
    #[test]
    fn a_push_at_round_off_is_not_blown_up() {
        let (k, push) = (3, -1e-17);
        let h = [1.0, 0.0, 0.0, 0.0, 2e-6, 0.5e-6, 0.0, 0.5e-6, 2e-6];
        let c = [1.0, push, push];
        let out = BoxQp::new(&h, &c, k, None, &QpSettings::default()).expect("valid QP").solve();
        assert!(!matches!(out.status, QpStatus::Failed(_)), "{:?}", out.status);
        assert!(out.nu.iter().all(|v| v.is_finite() && *v >= -1e-30), "{:?}", out.nu);
        // The exact answer: λ_0 = 0, the fine pair solves H_FF λ = −c_F: −push / 2.5e-6 each.
        let (exact, tol) = (-push / 2.5e-6, QpSettings::default().tol);
        assert!(out.nu[1..].iter().all(|v| (v - exact).abs() <= tol.sqrt()), "{:?} against {exact:e}", out.nu);
    }
}
