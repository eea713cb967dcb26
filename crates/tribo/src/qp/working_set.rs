//! A working set of multiplier dofs for the Γ_C QP: solve over the dofs that can be in contact, check
//! the optimality conditions of the *whole* QP, grow the set where they fail, repeat.
//!
//! The QP `min ½ νᵀ H ν + cᵀ ν` over `ν_n ≥ 0, |ν_t| ≤ b` is dense in the 2q multiplier unknowns of all
//! of Γ_C, but the contact zone is often a small part of Γ_C. Fixing `ν_n,j = ν_t,j = 0` outside a set S
//! gives a smaller QP (same H, rows and columns of S) whose solution ν_S, extended by zeros, solves the
//! whole QP exactly when the dropped dofs satisfy their optimality conditions:
//!
//! * `(H ν + c)_n,j ≥ 0` — no pressure would appear there (the discrete gap is open), and
//! * `b_j = 0` — the friction bound forces `ν_t,j = 0` (so every dof with a positive bound is kept in S).
//!
//! A dropped dof with `(H ν + c)_n,j < −√tol c_s` (c_s = max |c_n|) is added, with its neighbours, and the
//! QP is solved again. The threshold is the one that separates "zero" from "non-zero" multipliers in the
//! contact states (a dof below it would carry `λ_n ≲ √tol Λ`). S only grows during a solve and across the
//! Coulomb iterations, so the clarabel set-up is reused whenever S did not change. The initial S holds the
//! dofs where the body, without contact forces, would penetrate (`c_n,j < 0`), and their neighbours.
//!
//! # Which method solves the QP on S
//! [`QpMethod::Clarabel`] always uses clarabel. [`QpMethod::Auto`] uses the active-set method
//! ([`crate::qp::active_set`]) from the previous answer (or from zero for the first QP) and clarabel for any QP
//! it cannot certify ([`QpOutcome::fallback`] says so). [`QpMethod::ActiveSet`] uses the active-set method
//! alone: a QP it cannot certify fails.

use std::time::Instant;

use crate::condensation::Factor;
use crate::error::Result;
use crate::linalg::saddle::SaddleSystem;
use crate::qp::active_set::{self, Bounds, Place, Start};
use crate::qp::dense::DenseBlock;
use crate::qp::sparse;
use crate::qp::DENSE_BYTES_PER_K2;
use crate::qp::{BoxQp, QpData, QpOutcome, QpStatus, Scaling};
use crate::settings::friction::check_thresholds;
use crate::settings::{Condensation, QpMethod, QpSettings};

/// Bytes of the active-set method's dense QP over k unknowns, per k²: its copy of the block of H and the factor of
/// its free unknowns' part (at most k² values each), with as much again of margin.
const ACTIVE_SET_BYTES_PER_K2: f64 = 8.0 * 4.0;

/// The Γ_C QP solved over a growing working set; the columns of H come from a [`Factor`], computed when
/// the set first needs them.
#[derive(Debug)]
pub struct ContactQp<'a> {
    condensed: &'a Factor,
    /// The load case's data (f, d and the linear term c).
    data: QpData<'a>,
    q: usize,
    bounds: Option<Vec<f64>>,
    settings: QpSettings,
    set: Vec<usize>,
    /// clarabel's QP on the set (built when first needed, dropped when the set grows).
    qp: Option<BoxQp>,
    /// H and c on the set's unknowns for the active-set method (dropped when the set grows).
    dense: Option<DenseBlock>,
    /// The previous answer (full size): the active-set method's start.
    last: Option<Vec<f64>>,
    /// The places of the previous answer's dofs (full size), when the active-set method found it: the
    /// next QP's first step keeps them ([`Start::places`]).
    places: Option<Vec<Option<Place>>>,
    /// Whether the first QP may start from the whole stick zone ([`Self::stick_places`]).
    stick: bool,
    /// Bytes the dense parts may take.
    budget: usize,
    /// Whether the QPs solve the sparse saddle-point system of a [`Condensation::Saddle`] factor (else
    /// columns of H from its factor of A).
    sparse: bool,
}

impl<'a> ContactQp<'a> {
    /// Sets up the QP of P(g) on `condensed` for the load case `data`:
    /// frictionless if `bounds` is `None`, else with the tangential bounds g (one per multiplier dof). `start`, if given, is a starting point (q or 2q values, e.g. the
    /// frictionless answer for the first Coulomb QP). The settings are taken as validated.
    ///
    /// # Errors
    /// [`crate::Error::BadThreshold`].
    pub fn new(
        condensed: &'a Factor,
        data: QpData<'a>,
        bounds: Option<&[f64]>,
        settings: &QpSettings,
        budget: usize,
        start: Option<&[f64]>,
    ) -> Result<Self> {
        let q = condensed.q();
        let k = if bounds.is_some() { 2 * q } else { q };
        let last = start.map(|x| (0..k).map(|i| x.get(i).copied().unwrap_or(0.0)).collect());
        let c = data.c;
        let mut ws = Self {
            condensed,
            data,
            q,
            bounds: None,
            settings: *settings,
            set: Vec::new(),
            qp: None,
            dense: None,
            last,
            places: None,
            stick: false,
            budget,
            sparse: condensed.condensation == Condensation::Saddle,
        };
        if let Some(b) = bounds {
            check_thresholds(b, q)?;
            ws.bounds = Some(b.to_vec());
        }
        let mut initial: Vec<usize> =
            if settings.working_set { (0..q).filter(|&j| c[j] < 0.0).collect() } else { (0..q).collect() };
        if let Some(x) = &ws.last {
            initial.extend((0..q).filter(|&j| x[j] != 0.0));
        }
        ws.grow(&initial);
        Ok(ws)
    }

    /// Adds dofs (and their neighbours) and the dofs with a positive bound to the set; true if it grew.
    fn grow(&mut self, dofs: &[usize]) -> bool {
        let mut member = vec![false; self.q];
        for &j in &self.set {
            member[j] = true;
        }
        let before = self.set.len();
        let add = |j: usize, member: &mut Vec<bool>, set: &mut Vec<usize>| {
            if !member[j] {
                member[j] = true;
                set.push(j);
            }
        };
        for &j in dofs {
            for k in j.saturating_sub(1)..=(j + 1).min(self.q - 1) {
                add(k, &mut member, &mut self.set);
            }
        }
        if let Some(b) = &self.bounds {
            for (j, v) in b.iter().enumerate() {
                if *v > 0.0 {
                    add(j, &mut member, &mut self.set);
                }
            }
        }
        self.set.sort_unstable();
        self.set.len() != before
    }

    /// Replaces the tangential bounds.
    ///
    /// # Errors
    /// [`crate::Error::BadThreshold`]; QP update errors.
    pub fn set_bounds(&mut self, b: &[f64]) -> Result<()> {
        check_thresholds(b, self.q)?;
        self.bounds = Some(b.to_vec());
        if self.grow(&[]) {
            self.qp = None;
            self.dense = None;
        } else if let Some(qp) = self.qp.as_mut() {
            let sub: Vec<f64> = self.set.iter().map(|&j| b[j]).collect();
            qp.set_bounds(&sub)?;
        }
        Ok(())
    }

    /// Indices into the 2q unknowns (ν_n then ν_t) of the current set.
    fn unknowns(&self) -> Vec<usize> {
        let q = self.q;
        if self.bounds.is_some() {
            self.set.iter().copied().chain(self.set.iter().map(|j| q + j)).collect()
        } else {
            self.set.clone()
        }
    }

    /// The dense QP on the set: H and c on its unknowns, the tangential bounds of its dofs.
    fn block(&self) -> (Vec<f64>, Vec<f64>, Option<Vec<f64>>) {
        let idx = self.unknowns();
        let h = self.condensed.h_block(&idx, &idx);
        let c: Vec<f64> = idx.iter().map(|&i| self.data.c[i]).collect();
        (h, c, self.bounds_on_set())
    }

    /// The tangential bounds of the set's dofs (`None` for a frictionless QP).
    fn bounds_on_set(&self) -> Option<Vec<f64>> {
        self.bounds.as_ref().map(|b| self.set.iter().map(|&j| b[j]).collect())
    }

    /// Starts the next QP from the places of its start point, a nearby load case's answer (the previous step
    /// of a history), as each QP of a fixed point starts from the previous one's (`Start::places`); a tangential
    /// dof within `tol ‖b‖` of its bound counts as on it (`tol` the fixed point's, `b` the bounds). Without them,
    /// its first step predicted each unknown's place from the gradient at that answer: on a fretting history of 101
    /// steps (the example `first_qps`), the first QP of step 50 took 32 steps and 12 factorizations at 55k unknowns;
    /// from the places, 9 and 2.
    pub fn start_from_answer(&mut self, tol: f64) {
        let b = self.bounds.as_deref().unwrap_or(&[]);
        let Some(x) = self.last.as_ref() else { return };
        let mut places = active_set::places(x, &Bounds::contact(self.q, b));
        // The answer met Coulomb's law with the bound of its last QP, μ g with g the λ_n before the last, and its
        // fixed point stopped once ‖λ_n − g‖ ≤ tol ‖λ_n‖: each slip dof sits within tol ‖μ λ_n‖ of this QP's bound
        // μ λ_n, on either side of it.
        let near = tol * b.iter().map(|v| v * v).sum::<f64>().sqrt();
        for (j, &bj) in b.iter().enumerate() {
            let t = x[self.q + j];
            if bj > 0.0 && t.abs() >= bj - near {
                places[self.q + j] = Some(if t > 0.0 { Place::Upper } else { Place::Lower });
            }
        }
        self.places = Some(places);
    }

    /// Lets the next QP start from its start point's places, the whole stick zone from the frictionless answer
    /// (λ_t = 0 wherever its bound is positive), where the saddle-point system takes that first step bordered
    /// (`stick_places`).
    pub fn start_from_stick(&mut self) {
        self.stick = true;
    }

    /// The places `start` holds in the box `bounds` (each unknown strictly inside free, each on a bound kept
    /// on it), where [`Self::start_from_stick`] asked for them and the factorization `saddle` holds answers the
    /// first step from them bordered: that step then costs what the first step from the prediction costs (a
    /// bordered solve), and the stick zone is the answer where the friction holds the whole contact. On two
    /// bodies pressed together (study 8's, 16k and 27k unknowns) the first Coulomb QP took 2 steps instead of
    /// 5 and 7: from the prediction, all of Γ_C slips, and the stick zone grew over the steps. Where the stick
    /// zone would need a factorization (two bodies from 48k unknowns on) the prediction's first step is taken as
    /// before; on the graded Hertz meshes (4.5k–109k unknowns) and the block nothing changed.
    fn stick_places(&self, start: &[f64], bounds: &[f64], saddle: &SaddleSystem) -> Option<Vec<Option<Place>>> {
        if !self.stick || self.places.is_some() || bounds.len() != self.q {
            return None;
        }
        let places = active_set::places(start, &Bounds::contact(self.q, bounds));
        let free: Vec<bool> = places.iter().map(|p| *p == Some(Place::Free)).collect();
        (saddle.is_factorized() && saddle.changed(&free).len() <= saddle.border_limit()).then_some(places)
    }

    /// Keeps `nu` (full size) as the next QP's start, with its places when the active-set method found it.
    fn remember(&mut self, nu: &[f64], by_active_set: bool) {
        self.places = by_active_set
            .then(|| active_set::places(nu, &Bounds::contact(self.q, self.bounds.as_deref().unwrap_or(&[]))));
        self.last = Some(nu.to_vec());
    }

    /// Solves the QP on the set with clarabel.
    fn solve_clarabel(&mut self) -> Result<QpOutcome> {
        let qp = match self.qp.take() {
            Some(qp) => qp,
            None => {
                // The active-set method's block (a QP it could not certify) is dropped first: not held beside.
                self.dense = None;
                self.check_budget(DENSE_BYTES_PER_K2)?;
                let (h, c, bounds) = self.block();
                BoxQp::new(&h, &c, self.set.len(), bounds.as_deref(), &self.settings)?
            }
        };
        Ok(self.qp.insert(qp).solve())
    }

    /// Solves the QP on the set with the active-set method from `start` (on the set's unknowns); `None`
    /// if it cannot certify its answer.
    fn solve_active_set(&mut self, start: Start<'_>) -> Option<QpOutcome> {
        let clock = Instant::now();
        let s = self.set.len();
        let b = self.bounds_on_set().unwrap_or_default();
        let (tol, max_iter) = (self.settings.tol, self.settings.max_iter);
        let op = match self.dense.take() {
            Some(op) => op,
            None => {
                let (h, c, _) = self.block();
                DenseBlock::new(h, c)
            }
        };
        let op = self.dense.insert(op);
        let c = op.linear_term().to_vec();
        let done = |nu: Vec<f64>, iterations: u32, factorizations: u32| QpOutcome {
            nu,
            status: QpStatus::Solved,
            iterations,
            seconds: clock.elapsed().as_secs_f64(),
            method: QpMethod::ActiveSet,
            factorizations,
            fallback: false,
            alpha: Vec::new(),
        };
        let diag = crate::qp::diagonal(op.matrix(), c.len());
        let Some(n_scale) = Scaling::normal_scale(&diag, &c, s) else {
            // Nothing pushes at all (c = 0): λ = 0 (as on clarabel's path).
            return Some(done(vec![0.0; c.len()], 0, 0));
        };
        let scaling = Scaling::new(&diag, &c, s, n_scale, &b);
        let (factorizations, updates) = (op.factorizations, op.updates);
        let out = active_set::solve(op, &c, &Bounds::contact(s, &b), start, &scaling, tol, max_iter);
        log::debug!(
            "active set on {} unknowns: certified {}, {} Newton steps ({} factorizations, {} updates), {} gradient steps",
            c.len(),
            out.certified,
            out.newton_steps,
            op.factorizations - factorizations,
            op.updates - updates,
            out.gradient_steps
        );
        out.certified.then(|| done(out.x, out.newton_steps + out.gradient_steps, op.factorizations - factorizations))
    }

    /// Refuses a set whose dense parts exceed the budget beside what the factor holds
    /// ([`Factor::fits_beside`]): its columns of H not formed yet (each 2q long), and the dense QP on it,
    /// `per_k2` bytes per k² (k the set's unknowns): clarabel's [`crate::qp::DENSE_BYTES_PER_K2`],
    /// or the active-set method's copy of the block and its factor (4 × 8).
    fn check_budget(&self, per_k2: f64) -> Result<()> {
        let unknowns = self.unknowns();
        let k = unknowns.len();
        let what = || format!("the dense Γ_C QP over {k} multiplier unknowns (2q = {})", self.condensed.e_rows.len());
        self.condensed.fits_beside(what, &unknowns, per_k2 * (k * k) as f64, self.budget)
    }

    /// Solves the QP on the set with the method the settings ask for (see the module documentation).
    fn solve_on_set(&mut self) -> Result<QpOutcome> {
        if self.settings.method == QpMethod::Clarabel {
            return self.solve_clarabel();
        }
        let idx = self.unknowns();
        let start: Vec<f64> = match &self.last {
            Some(x) => idx.iter().map(|&i| x[i]).collect(),
            None => vec![0.0; idx.len()],
        };
        let places: Option<Vec<Option<Place>>> = self.places.as_ref().map(|p| idx.iter().map(|&i| p[i]).collect());
        // clarabel's set-up on this set, if a QP fell back to it, is held beside the active-set method's block.
        let beside = if self.qp.is_some() { DENSE_BYTES_PER_K2 } else { 0.0 };
        self.check_budget(ACTIVE_SET_BYTES_PER_K2 + beside)?;
        let clock = Instant::now();
        if let Some(out) = self.solve_active_set(Start { x: &start, places: places.as_deref() }) {
            return Ok(out);
        }
        if self.settings.method == QpMethod::ActiveSet {
            return Ok(QpOutcome {
                nu: start,
                status: QpStatus::Failed("the active-set method could not certify its answer"),
                iterations: self.settings.max_iter,
                seconds: clock.elapsed().as_secs_f64(),
                method: QpMethod::ActiveSet,
                factorizations: 0,
                fallback: false,
                alpha: Vec::new(),
            });
        }
        log::info!("the active-set method could not certify a QP on {} dofs: clarabel solves it", self.set.len());
        let mut out = self.solve_clarabel()?;
        out.fallback = true;
        Ok(out)
    }

    /// Solves on the sparse saddle-point system only if `sparse` (and the factor has one; see
    /// [`crate::Condensed::sparse_qps`]).
    #[must_use]
    pub fn with_sparse(mut self, sparse: bool) -> Self {
        self.sparse &= sparse;
        self
    }

    /// Solves the whole QP; the returned ν has the full size (q, or 2q with friction).
    ///
    /// # Errors
    /// QP set-up errors.
    pub fn solve(&mut self) -> Result<QpOutcome> {
        if let Some((e_r, load)) = self.data.rigid {
            return self.solve_held_by_contact(e_r, load);
        }
        if self.sparse && self.settings.method != QpMethod::Clarabel {
            if let Some(out) = self.solve_sparse()? {
                return Ok(out);
            }
            log::info!("the sparse active-set method could not certify a QP: the dense path solves it");
            let mut out = self.solve_dense()?;
            out.fallback = true;
            return Ok(out);
        }
        self.solve_dense()
    }

    /// Solves the whole QP with the equilibrium of the bodies held only by the contact, `(E R)ᵀ ν = Rᵀ f`
    /// (`e_r` 2q × r column-major, `load` r), with clarabel on all of Γ_C: its equality multipliers are the
    /// rigid motion α (see `problem/floating.rs`).
    fn solve_held_by_contact(&mut self, e_r: &[f64], load: &[f64]) -> Result<QpOutcome> {
        let q = self.q;
        let k = if self.bounds.is_some() { 2 * q } else { q };
        if self.set.len() < q {
            self.set = (0..q).collect();
        }
        self.check_budget(DENSE_BYTES_PER_K2)?;
        let (h, c, bounds) = self.block();
        let g: Vec<f64> = (0..load.len()).flat_map(|m| e_r[m * 2 * q..m * 2 * q + k].iter().copied()).collect();
        // Without friction (the start of a Coulomb solve) only the motions the normal multipliers see
        // are balanced: the others (a tangential load) wait for the friction of the next QPs.
        let r = load.len();
        let (g, load, basis) = if bounds.is_none() { seen_motions(g, load, k) } else { (g, load.to_vec(), None) };
        let mut qp = BoxQp::new(&h, &c, q, bounds.as_deref(), &self.settings)?.with_equality(g, load)?;
        let mut out = qp.solve();
        if let Some(v) = basis {
            // Gᵀ α = (Vᵀ G)ᵀ α̃: the multipliers of the kept combinations, back on every motion.
            out.alpha = (0..r).map(|m| v.iter().zip(&out.alpha).map(|(col, a)| col[m] * a).sum()).collect();
        }
        self.remember(&out.nu, false);
        Ok(out)
    }

    /// Solves the whole QP without H, on the saddle-point system ([`crate::qp::sparse`]); `None` if the
    /// answer could not be certified.
    fn solve_sparse(&mut self) -> Result<Option<QpOutcome>> {
        let clock = Instant::now();
        let q = self.q;
        let bounds = self.bounds.clone().unwrap_or_default();
        let idx: Vec<usize> = (0..q + bounds.len()).collect();
        let start = self.last.clone().unwrap_or_else(|| vec![0.0; idx.len()]);
        let mut guard = self.condensed.saddle_system();
        let Some(saddle) = guard.as_mut() else { return Ok(None) };
        let places = self.places.clone().or_else(|| self.stick_places(&start, &bounds, saddle));
        let data = (self.data.f, self.data.d, self.data.c);
        let answer = sparse::solve(
            self.condensed,
            saddle,
            data,
            &idx,
            q,
            &bounds,
            Start { x: &start, places: places.as_deref() },
            (self.settings.tol, self.settings.max_iter),
        );
        self.condensed.note_saddle_bytes(saddle);
        Ok(answer.map(|(nu, steps, factorizations)| {
            self.remember(&nu, true);
            QpOutcome {
                nu,
                status: QpStatus::Solved,
                iterations: steps,
                seconds: clock.elapsed().as_secs_f64(),
                method: QpMethod::ActiveSet,
                factorizations,
                fallback: false,
                alpha: Vec::new(),
            }
        }))
    }

    /// Solves the whole QP on the growing working set with the dense H.
    fn solve_dense(&mut self) -> Result<QpOutcome> {
        let q = self.q;
        let frictional = self.bounds.is_some();
        let k = if frictional { 2 * q } else { q };
        let c = self.data.c;
        let c_s = c[..q].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let threshold = -self.settings.tol.sqrt() * c_s;
        let (mut iterations, mut seconds, mut fallback, mut factorizations) = (0, 0.0, false, 0);
        loop {
            let out = self.solve_on_set()?;
            iterations += out.iterations;
            seconds += out.seconds;
            factorizations += out.factorizations;
            fallback |= out.fallback;
            let s = self.set.len();
            let mut nu = vec![0.0; k];
            for (a, &j) in self.set.iter().enumerate() {
                nu[j] = out.nu[a];
                if frictional {
                    nu[q + j] = out.nu[s + a];
                }
            }
            let done = |nu: Vec<f64>| QpOutcome { nu, iterations, seconds, fallback, factorizations, ..out.clone() };
            if matches!(out.status, QpStatus::Failed(_)) {
                return Ok(done(nu));
            }
            self.remember(&nu, out.method == QpMethod::ActiveSet && !out.fallback);
            if s == q {
                return Ok(done(nu));
            }
            // Optimality of the dropped dofs: (H ν + c)_n,j ≥ threshold, with ν supported on the set.
            let mut member = vec![false; q];
            for &j in &self.set {
                member[j] = true;
            }
            let support: Vec<usize> = self.unknowns().into_iter().filter(|&i| nu[i] != 0.0).collect();
            let violated: Vec<usize> = self.condensed.with_columns(&support, |cols| {
                (0..q)
                    .filter(|&j| !member[j])
                    .filter(|&j| {
                        let hv: f64 = support.iter().filter_map(|&i| cols[i].as_ref().map(|col| col[j] * nu[i])).sum();
                        hv + c[j] < threshold
                    })
                    .collect()
            });
            if violated.is_empty() {
                return Ok(done(nu));
            }
            log::debug!("working set: {} dofs violate optimality, growing from {s}", violated.len());
            self.grow(&violated);
            // The dofs that joined are predicted, not kept off contact as in the last answer.
            if let Some(places) = &mut self.places {
                for &j in self.set.iter().filter(|&&j| !member[j]) {
                    places[j] = None;
                }
            }
            self.qp = None;
            self.dense = None;
        }
    }
}

/// The equality `G ν = b` (G r × k row-major) restricted to the range of G: the combinations of its
/// rows that are not zero (to `16 k ε` of the largest, in the Gram matrix), with their loads. A row
/// combination that vanishes is a motion the unknowns cannot hold (a tangential translation seen by the
/// normal multipliers alone).
/// Returns the kept rows, their loads and (when a combination was dropped) the kept combinations.
#[allow(clippy::type_complexity)]
fn seen_motions(g: Vec<f64>, b: &[f64], k: usize) -> (Vec<f64>, Vec<f64>, Option<Vec<Vec<f64>>>) {
    let r = b.len();
    let all: Vec<usize> = (0..k).collect();
    let (basis, missed) =
        crate::linalg::gram_split(r, &all, |m, i| g[m * k + i], |lmax| 16.0 * k as f64 * f64::EPSILON * lmax);
    if missed.is_empty() {
        return (g, b.to_vec(), None);
    }
    let mut rows = Vec::with_capacity(basis.len() * k);
    let mut loads = Vec::with_capacity(basis.len());
    for v in &basis {
        rows.extend((0..k).map(|i| (0..r).map(|m| v[m] * g[m * k + i]).sum::<f64>()));
        loads.push((0..r).map(|m| v[m] * b[m]).sum::<f64>());
    }
    (rows, loads, Some(basis))
}

/// The former name of [`ContactQp`].
#[deprecated(note = "renamed ContactQp: the front door of every Γ_C QP")]
pub type WorkingSetQp<'a> = ContactQp<'a>;

#[cfg(test)]
mod tests {
    use crate::mesh::generate::{rectangle, Diagonal};
    use crate::problem::load_case::LoadCase;
    use crate::*;

    /// A history step's first QP ([`super::ContactQp::start_from_answer`]): a block pressed on a flat and shifted
    /// (slip at both ends, stick between), its Coulomb answer, and the QP with that answer's bounds μ λ_n started
    /// from it. The answer's slip dofs sit on the bounds of the λ_n one iteration before, within the fixed point's
    /// tolerance of the new ones, on either side (here two of them 3e-8 relative inside). From its places with them
    /// on their bounds, one step reaches the QP's answer; from its places as they fall (a slip dof just inside its
    /// new bound is free) it takes more. Both end on the answer the prediction from the gradient finds.
    #[test]
    fn a_qp_started_from_a_nearby_answer_keeps_its_slip_dofs_on_their_bounds() -> Result<()> {
        let mesh = rectangle([0.0, 4.0], [0.0, 1.0], 40, 10, Diagonal::Alternating)?;
        let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "bottom")
            .clamped(["top"])
            .approach(0.01)
            .shift(0.002)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec)?;
        let (mu, settings) = (0.3, SolverSettings::default());
        let sol = problem.solve(&Friction::Coulomb { mu }, &settings, None)?;
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let q = sol.lambda_n.len();
        let answer: Vec<f64> = sol.lambda_n.iter().chain(&sol.lambda_t).copied().collect();
        let bounds: Vec<f64> = sol.lambda_n.iter().map(|l| mu * l.max(0.0)).collect();
        let slipping = (0..q).filter(|&j| bounds[j] > 0.0 && sol.lambda_t[j].abs() >= bounds[j] * (1.0 - 1e-6)).count();
        let sticking = (0..q).filter(|&j| sol.lambda_t[j].abs() < bounds[j] * (1.0 - 1e-6)).count();
        assert!(slipping >= 4 && sticking >= 4, "partial slip: {slipping} slipping, {sticking} sticking");
        let condensed = problem.condense(Stabilization::default())?;
        let loading = LoadCase::of_problem(&problem, condensed.factor());
        let solve = |tol: Option<f64>| {
            let mut qp = super::ContactQp::new(
                condensed.factor(),
                loading.qp_data(),
                Some(&bounds),
                &settings.qp,
                settings.memory_budget,
                Some(&answer),
            )?;
            if let Some(tol) = tol {
                qp.start_from_answer(tol);
            }
            qp.solve()
        };
        let (snapped, as_they_fall, predicted) = (solve(Some(settings.fp.tol))?, solve(Some(0.0))?, solve(None)?);
        assert_eq!(snapped.iterations, 1, "from the answer's places, its slip dofs on their bounds");
        assert!(as_they_fall.iterations > 1, "{} steps from the places as they fall", as_they_fall.iterations);
        let scale = answer.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for other in [&as_they_fall, &predicted] {
            let diff = other.nu.iter().zip(&snapped.nu).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(diff <= 1e-9 * scale, "the same answer: {diff:e} of {scale:e}");
        }
        Ok(())
    }
}
