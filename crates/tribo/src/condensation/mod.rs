//! The stabilized system condensed onto Γ_C: one sparse Cholesky factorization of `A = K − G` (LDLᵀ for
//! the quasi-definite A of the mixed formulation, [`crate::fem::mixed`]), then the
//! multiplier operator `H = E A⁻¹ Eᵀ + Dγ` and the linear term `c = d − E A⁻¹ f` of the QP.
//!
//! This module is linear algebra only: it is handed `K`, `−G`, the rows of `E`, `Dγ`, `f` and `d` (built by
//! [`crate::Problem::condense`] from [`crate::contact::operators`] and [`crate::contact::mortar`]) and knows nothing of
//! meshes or contact.
//!
//! This is the only place that touches all n unknowns (displacements, and a mixed formulation's
//! pressures). `c` costs one solve; a column of H
//! costs one solve with the factor (done in blocks of columns) and is computed only when a QP asks for it
//! and then kept: the working-set QP ([`crate::qp::working_set`]) only needs the columns of the multiplier
//! dofs that can be in contact, so on a long Γ_C with a small contact zone most of H is never formed.
//! Every Tresca QP and every Coulomb fixed-point iteration works with multiplier unknowns only; the
//! displacement is recovered at the end with one more solve (about half a solve on the partial
//! factorization, whose last rows hold `Eᵀ λ`: [`crate::linalg::schur::SchurFactor::solve_from_contact`]).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, Par};

use crate::error::{Error, Num, Result};
use crate::linalg::saddle::SaddleSystem;
use crate::linalg::schur::SchurSymbolic;
use crate::settings::Condensation;

mod choose;
mod diagonal;
mod direct;
mod products;
mod saddle;
mod substitution;

use direct::{analyse, factorize, fits_budget, schur_error, solve, Direct};
use products::{diagonal, dot};
use saddle::{beside, wished, Wish};

pub(crate) use choose::Expected;
use choose::{
    margin_before_factorizing, path_costs, prefer_saddle, prefer_schur, pushed_estimate, quasi_definite,
    saddle_pays_for, touched_dofs, warm_saddle_beats_schur, AFTER_FACTORIZING, BEFORE_FACTORIZING,
};

/// Number of right-hand sides solved together when forming `A⁻¹ Eᵀ`.
const BLOCK: usize = 64;

/// Lazily computed columns of H, and the time spent computing them.
#[derive(Default)]
struct Columns {
    cols: Vec<Option<Vec<f64>>>,
    seconds: f64,
}

/// The factorization of `A = K − G` for one γ0 and the condensed operators it defines: `E`, `Dγ`, `c`,
/// `d` and the columns of H (computed on demand and kept, or all at once by the partial factorization).
pub struct Factor {
    /// The γ0 in use.
    pub gamma0: f64,
    /// How H is formed (never [`Condensation::Auto`]: the choice made).
    pub condensation: Condensation,
    /// Sparse Cholesky factor of A.
    direct: Direct,
    /// Order n of A.
    n: usize,
    /// The diagonal of A.
    a_diag: Vec<f64>,
    /// `−G` on the unknowns (A = K − G): with K, the product A x for the residuals.
    minus_g: Vec<Triplet<usize, usize, f64>>,
    /// Rows of E (2q sparse rows over the unknowns).
    pub e_rows: Vec<Vec<(usize, f64)>>,
    /// Columns of H computed so far (2q of them at most, each of length 2q).
    columns: Mutex<Columns>,
    /// Linear term `c = d − E A⁻¹ f` (2q) of the problem's own load case.
    pub c: Vec<f64>,
    /// `d` (2q): the obstacle's gap and shift moments, minus `E ū` for prescribed displacements ū.
    pub d: Vec<f64>,
    /// `E A⁻¹ f` (2q): the load's part of c, kept so that a scaled load needs no new solve.
    pub e_ainv_f: Vec<f64>,
    /// `A⁻¹ f` on the partial factor when f is not zero (then [`Factor::displacement`] needs half a solve).
    u_f: Option<Vec<f64>>,
    /// The load on the unknowns A was condensed with (`f̃`, with the lifting of prescribed displacements,
    /// see [`crate::fem::supports`]): the `f` of [`Factor::displacement`] and of the equilibrium residual.
    pub f: Vec<f64>,
    /// Dγ by columns over the 2q unknowns (row, value): the q × q block `Dγ` twice on the diagonal.
    d_cols: Vec<Vec<(usize, f64)>>,
    /// Wall time of forming A and its numeric factorization, in seconds.
    pub factorization_seconds: f64,
    /// The sparse saddle-point system of the QPs that do without H ([`Condensation::Saddle`]), analysed
    /// when first needed.
    saddle: Mutex<Option<SaddleSystem>>,
    /// The bytes the saddle-point system holds (the bits of an f64), noted whenever it changes
    /// ([`Factor::note_saddle_bytes`]): read by [`Factor::held_bytes`] without its lock, which a sparse QP
    /// holds while it forms diag H from the columns' lock (the two locks are never taken the other way round).
    saddle_bytes: AtomicU64,
    /// The cost model's estimates of one solve by columns and by the saddle-point system, when
    /// [`Condensation::Auto`] chose the saddle-point system (a loading history may prefer the columns
    /// after all: [`Factor::saddle_for`]); `None` when it was asked for or not chosen.
    auto_saddle: Option<[f64; 2]>,
    /// The estimates of diag H the sparse QPs use, by number k of leading unknowns (`0..k`: q for a
    /// frictionless QP, 2q with friction), formed once rather than for every QP of the fixed point.
    h_diagonal_estimates: Mutex<Vec<(usize, Vec<f64>)>>,
    /// The blocks of the LDLᵀ factor of A holding the dofs E reads, closed under the tree of blocks
    /// ([`Factor::e_displacement`]), found once.
    e_closure: OnceLock<Vec<usize>>,
}

impl std::fmt::Debug for Factor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Factor").field("gamma0", &self.gamma0).field("2q", &self.c.len()).finish()
    }
}

impl Factor {
    /// Factorizes `A = K + minus_g` (on K's pattern, with K's symbolic factorization, formed into
    /// `symbolic` if it is still empty and this path needs it) and forms `c`.
    ///
    /// `e_rows` are the 2q rows of E over the unknowns, `d_gamma` the entries `(i, j, v)` of the q × q
    /// block Dγ (the same block acts on the normal and on the tangential multipliers), `f` the load and
    /// `d` the obstacle moments (2q). `condensation` chooses how H is formed ([`Condensation::Auto`]: the
    /// partial factorization where it is cheaper and fits `budget` bytes, see [`crate::linalg::schur`]);
    /// `expected` says what the solves will do: QPs that start from the multipliers of a nearby problem
    /// make the saddle-point system cheaper (the cost model's `WARM_SADDLE`); a Coulomb fixed point makes
    /// it dearer against the partial factorization (`FIXED_POINT_BEFORE_FACTORIZING`). With `pressures`
    /// (the last unknowns are the pressures of the mixed formulation, [`crate::fem::mixed`]) A is
    /// quasi-definite: it is factorized by LDLᵀ, and H formed by columns or not at all (the saddle-point
    /// system), never by the partial factorization.
    ///
    /// # Errors
    /// [`Error::NotPositiveDefinite`] if the Cholesky factorization fails; [`Error::Assembly`] if `−G`
    /// does not lie in the pattern of K; [`Error::MemoryBudget`] if the partial factorization is asked
    /// for and its dense parts exceed `budget`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        k: &SparseColMat<usize, f64>,
        symbolic: &OnceLock<Arc<SymbolicCholesky<usize>>>,
        minus_g: &[Triplet<usize, usize, f64>],
        e_rows: Vec<Vec<(usize, f64)>>,
        d_gamma: Vec<(usize, usize, f64)>,
        f: &[f64],
        d: Vec<f64>,
        gamma0: f64,
        condensation: Condensation,
        budget: usize,
        expected: Expected,
        pressures: usize,
    ) -> Result<Self> {
        let warm = expected.warm;
        // The partial factorization's kernel is a Cholesky one: a quasi-definite A takes the other two.
        if condensation == Condensation::Schur && pressures > 0 {
            return Err(Error::BadSetting {
                name: "condensation",
                value: f64::NAN,
                what: "'schur' (the partial Cholesky factorization) needs a positive definite A, and the mixed \
                       formulation's is quasi-definite: use 'auto' or 'columns' (or formulation = 'displacement')"
                    .to_string(),
            });
        }
        let clock = Instant::now();
        // A = K − G on K's pattern (G couples the dofs of one triangle, all present in K), factorized
        // with the symbolic analysis of K: only values change with γ0.
        let (pattern, k_values) = k.parts();
        let mut values = k_values.to_vec();
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        for t in minus_g {
            let range = col_ptr[t.col]..col_ptr[t.col + 1];
            let Ok(pos) = row_idx[range.clone()].binary_search(&t.row) else {
                return Err(Error::Assembly {
                    matrix: "K − G",
                    what: format!("({}, {}) is not in K's pattern", t.row, t.col),
                });
            };
            values[range.start + pos] += t.val;
        }
        // A view with K's pattern and A's values: no copy of the pattern; the values are dropped once A
        // is factorized (A x is K x − G x afterwards, see [`Factor::apply_a`]).
        let a = SparseColMatRef::new(pattern, &values);
        let nnz_k = k.compute_nnz();
        let (m, q) = (e_rows.len(), e_rows.len() / 2);
        let n_c = touched_dofs(&e_rows);
        let schur_pays = |w: usize, margin: f64| prefer_schur(nnz_k, m, n_c, w, margin, budget);
        let bytes = schur_pays(q, BEFORE_FACTORIZING).1;
        // Auto: with no load on the free dofs the pushed multipliers are known now (c = d); with a load
        // they are known once A is factorized, so a partial factorization that could pay (it does at most
        // when all q are pushed) is decided after the plain one ([`choose::prefer_schur`]).
        let loaded = f.iter().any(|&v| v != 0.0);
        // The Γ_C dofs, E's rows and Dγ decide whether the saddle-point system can do without pivoting.
        let mut d_cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        for &(i, j, v) in &d_gamma {
            d_cols[j].push((i, v));
            d_cols[q + j].push((q + i, v));
        }
        let definite = quasi_definite(&e_rows, n_c, &d_cols);
        let warm_saddle = warm && definite && warm_saddle_beats_schur(nnz_k, m, n_c);
        let mut use_schur = match condensation {
            Condensation::Columns | Condensation::Saddle => false,
            Condensation::Schur => true,
            Condensation::Auto => {
                let w = pushed_estimate(f, &d, q);
                let pays = schur_pays(w, margin_before_factorizing(expected, definite, nnz_k, w)).0;
                pressures == 0 && !loaded && !warm_saddle && pays
            }
        };
        let undecided = pressures == 0
            && condensation == Condensation::Auto
            && loaded
            && !warm_saddle
            && schur_pays(q, AFTER_FACTORIZING).0;
        if condensation == Condensation::Schur && bytes > budget as f64 {
            return Err(Error::MemoryBudget {
                what: "the partial factorization's dense trailing block and E A⁻¹ Eᵀ".to_string(),
                needed: bytes,
                budget: budget as f64,
            });
        }
        let mut cols = vec![None; m];
        // The partial factorization and all of H from it within `budget` bytes: (the factor, its seconds, H's seconds).
        let partial = |cols: &mut Vec<Option<Vec<f64>>>, budget: usize| -> Result<(Direct, f64, f64)> {
            let clock = Instant::now();
            let sym = SchurSymbolic::new(a.symbolic(), &e_rows).map_err(schur_error)?;
            let req = sym.symbolic().factorize_numeric_llt_scratch::<f64>(Par::rayon(0), Default::default());
            let what = "the partial Cholesky factor of A = K − G (the Γ_C dofs last) and the dense H";
            fits_budget(what, sym.len_val(), req, bytes, a.nrows(), budget)?;
            let factor = sym.factorize(a, Par::rayon(0)).map_err(schur_error)?;
            let factorization_seconds = clock.elapsed().as_secs_f64();
            let clock = Instant::now();
            let s_e = factor.schur(&e_rows, Par::rayon(0)).map_err(schur_error)?;
            for (j, col) in cols.iter_mut().enumerate() {
                let mut h: Vec<f64> = (0..m).map(|i| s_e[(i, j)]).collect();
                for &(r, v) in &d_cols[j] {
                    h[r] += v;
                }
                *col = Some(h);
            }
            Ok((Direct::Schur(factor), factorization_seconds, clock.elapsed().as_secs_f64()))
        };
        // Chosen by `auto`, a partial factor whose values and H exceed the budget (known after its symbolic
        // analysis) leaves H to the plain factor's columns; asked for, it is an error.
        let or_plain = |r: Result<(Direct, f64, f64)>| match r {
            Err(Error::MemoryBudget { what, .. }) if condensation == Condensation::Auto => {
                log::info!("{what}: beyond the memory budget, H is formed by columns");
                Ok(None)
            }
            r => r.map(Some),
        };
        let schur = if use_schur { or_plain(partial(&mut cols, budget))? } else { None };
        use_schur = schur.is_some();
        // The saddle-point system asked for, or preferred by `auto` where the partial factorization is not used.
        let wish = |use_schur: bool, pushed: usize| match condensation {
            Condensation::Saddle => Wish::Asked,
            Condensation::Auto if !use_schur && prefer_saddle(nnz_k, pushed, warm) && definite => Wish::Preferred,
            _ => Wish::No,
        };
        // Built beside the numeric factorization of A where it is known before it (`early`, below).
        let mut early_saddle = None;
        let (mut direct, mut factorization_seconds, mut schur_seconds) = if let Some((direct, _, schur_seconds)) = schur
        {
            // The factorization's time counts from the start (A's values included), as for the plain one.
            (direct, clock.elapsed().as_secs_f64() - schur_seconds, schur_seconds)
        } else {
            let symbolic = match symbolic.get() {
                Some(s) => s,
                None => {
                    let s = analyse(k.symbolic())?;
                    symbolic.get_or_init(|| Arc::new(s))
                }
            };
            // The saddle-point system needs only A's order: where it is known to be wanted before A's numeric
            // factorization (asked for, or preferred by `auto` on a problem without load, whose c is d and A
            // stays factorized as it is), its analysis runs beside it on a second thread (55k graded unknowns:
            // 40 ms and 34 ms, each sequential).
            let early = match condensation {
                Condensation::Saddle => Wish::Asked,
                Condensation::Auto if !loaded => wish(false, d[..q].iter().filter(|v| **v < 0.0).count()),
                _ => Wish::No,
            };
            let order = symbolic.perm().map(|p| p.arrays().0);
            let factor_bytes = 8.0 * (symbolic.len_val() + a.nrows()) as f64;
            let build = || wished(early, a, &e_rows, &d_cols, beside(budget, factor_bytes), pressures, nnz_k, order);
            let (values, d_inv) = if early == Wish::No {
                factorize(symbolic, a, pressures, budget)?
            } else {
                let (factored, built) = std::thread::scope(|s| {
                    let beside_a = std::thread::Builder::new().name("tribo-saddle".into()).spawn_scoped(s, build);
                    let factored = factorize(symbolic, a, pressures, budget);
                    let built = match beside_a {
                        Ok(handle) => handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
                        // No second thread: one after the other.
                        Err(_) => build(),
                    };
                    (factored, built)
                });
                early_saddle = Some(built);
                factored?
            };
            let direct = Direct::Ldlt(symbolic.clone(), values, d_inv);
            (direct, clock.elapsed().as_secs_f64(), 0.0)
        };
        let clock = Instant::now();
        // A⁻¹ 0 = 0: a body pressed only by the obstacle (no load on the free dofs) needs no solve here.
        let u_f = if loaded { solve(&direct, f)? } else { vec![0.0; f.len()] };
        let e_ainv_f: Vec<f64> = e_rows.iter().map(|row| dot(row, &u_f)).collect();
        let c: Vec<f64> = d.iter().zip(&e_ainv_f).map(|(di, ei)| di - ei).collect();
        let pushed = c[..q].iter().filter(|v: &&f64| **v < 0.0).count();
        let mut c_seconds = clock.elapsed().as_secs_f64();
        if undecided && schur_pays(pushed, AFTER_FACTORIZING).0 {
            // The load pushes enough of Γ_C for all of H to pay: factorize again, C last (c stands), beside the
            // plain factor held until then (a try beyond the budget counts in the factorization's time).
            let (clock, held) = (Instant::now(), direct.value_bytes() as usize);
            match or_plain(partial(&mut cols, budget.saturating_sub(held)))? {
                Some((partial_direct, seconds, h_seconds)) => {
                    (direct, use_schur) = (partial_direct, true);
                    factorization_seconds += seconds;
                    schur_seconds = h_seconds;
                    c_seconds = 0.0;
                }
                None => factorization_seconds += clock.elapsed().as_secs_f64(),
            }
        }
        let columns = Mutex::new(Columns { cols, seconds: schur_seconds + c_seconds });
        // The saddle-point system, if asked for or preferred ([`Wish`]), beside the factor of A held with it.
        let saddle = match early_saddle {
            Some(built) => built?,
            None => {
                let beside = beside(budget, direct.value_bytes());
                wished(wish(use_schur, pushed), a, &e_rows, &d_cols, beside, pressures, nnz_k, direct.order())?
            }
        };
        let auto_saddle = (condensation == Condensation::Auto && saddle.is_some()).then(|| path_costs(nnz_k, pushed));
        let condensation = if use_schur {
            Condensation::Schur
        } else if saddle.is_some() {
            Condensation::Saddle
        } else {
            Condensation::Columns
        };
        log::info!(
            "factorized A = K − G ({} unknowns) in {} s; {}",
            a.nrows(),
            Num(factorization_seconds),
            match condensation {
                Condensation::Schur => format!("formed all of the {m} × {m} H in {} s", Num(schur_seconds)),
                Condensation::Saddle => "H not formed: the QPs solve the sparse saddle-point system".to_string(),
                _ => "formed c; columns of H as the QPs need them".to_string(),
            }
        );
        Ok(Self {
            gamma0,
            condensation,
            direct,
            n: a.nrows(),
            a_diag: diagonal(a),
            minus_g: minus_g.to_vec(),
            e_rows,
            d_cols,
            c,
            d,
            e_ainv_f,
            u_f: (use_schur && loaded).then_some(u_f),
            f: f.to_vec(),
            columns,
            factorization_seconds,
            saddle_bytes: AtomicU64::new(saddle.as_ref().map_or(0.0, SaddleSystem::held_bytes).to_bits()),
            saddle: Mutex::new(saddle),
            h_diagonal_estimates: Mutex::new(Vec::new()),
            e_closure: OnceLock::new(),
            auto_saddle,
        })
    }

    /// Whether the QPs of `load_cases` solves on this factorization (the steps of a loading history) use
    /// the saddle-point system: always when it was asked for; when [`Condensation::Auto`] chose it for
    /// one solve, only while it stays the cheaper path over all of them (the cost model of
    /// `condensation/choose.rs`: a later step costs a twentieth of the first by columns, half by the
    /// saddle-point system); otherwise they form columns of H from the same factor of A.
    pub fn saddle_for(&self, load_cases: usize) -> bool {
        self.condensation == Condensation::Saddle && self.auto_saddle.is_none_or(|c| saddle_pays_for(c, load_cases))
    }

    /// Number of multiplier dofs per component.
    pub fn q(&self) -> usize {
        self.e_rows.len() / 2
    }

    /// A natural size of λ_n for the linear term `c` (2q), `|c_j| / H_jj` at the normal dof j that pushes
    /// hardest (`c_j < 0` most negative; where none pushes by more than √ε of the largest `|c_n|`, the dof where
    /// `|c_n|` is largest): the multiplier at which the quadratic and linear terms of the QP balance there. It is
    /// non-zero even when the solution is λ = 0, so it serves as the scale of tolerances on λ. A dof that does not
    /// push is left out where one does: its `c_j` is the gap far from the contact, as large as the obstacle is far,
    /// and says nothing of λ. A push at round-off of that gap is none: it would make the scale round-off too.
    pub fn lambda_scale(&self, c: &[f64]) -> f64 {
        let q = self.q();
        let floor = -(f64::EPSILON.sqrt() * c[..q].iter().fold(0.0_f64, |m, v| m.max(v.abs())));
        let pushing =
            c[..q].iter().enumerate().filter(|(_, v)| **v < floor).max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
        let Some((j, cj)) =
            pushing.or_else(|| c[..q].iter().enumerate().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs())))
        else {
            return 0.0;
        };
        let hjj = self.with_columns(&[j], |cols| cols[j].as_ref().expect("computed")[j]);
        if hjj > 0.0 {
            cj.abs() / hjj
        } else {
            0.0
        }
    }

    /// Runs `f` on the column cache after making sure the columns `idx` of H are computed.
    pub(crate) fn with_columns<R>(&self, idx: &[usize], f: impl FnOnce(&[Option<Vec<f64>>]) -> R) -> R {
        let mut guard = self.columns.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let missing: Vec<usize> = idx.iter().copied().filter(|&i| guard.cols[i].is_none()).collect();
        if !missing.is_empty() {
            let clock = Instant::now();
            let n = self.n;
            let mut x = Mat::<f64>::zeros(n, BLOCK.min(missing.len()));
            for chunk in missing.chunks(BLOCK) {
                let mut xb = x.as_mut().subcols_mut(0, chunk.len());
                xb.fill(0.0);
                for (col, &i) in chunk.iter().enumerate() {
                    for &(d, v) in &self.e_rows[i] {
                        xb[(d, col)] = v;
                    }
                }
                if let Err(e) = self.direct.solve_in_place(xb.as_mut()) {
                    // Only the partial factorization's solve can fail (its workspace), and it never asks
                    // for columns: they are all formed with it.
                    log::error!("column solve failed: {e}");
                }
                for (col, &i) in chunk.iter().enumerate() {
                    let mut h: Vec<f64> =
                        self.e_rows.iter().map(|row| row.iter().map(|&(d, v)| v * xb[(d, col)]).sum()).collect();
                    for &(r, v) in &self.d_cols[i] {
                        h[r] += v;
                    }
                    guard.cols[i] = Some(h);
                }
            }
            let seconds = clock.elapsed().as_secs_f64();
            guard.seconds += seconds;
            let formed = guard.cols.iter().filter(|c| c.is_some()).count();
            log::debug!(
                "formed {} columns of H in {} s ({formed} of {} so far)",
                missing.len(),
                Num(seconds),
                guard.cols.len()
            );
        }
        f(&guard.cols)
    }

    /// Bytes this factorization holds now: the factor's values, the columns of H formed so far (all of them
    /// with the partial factorization) and the saddle-point system, if any.
    pub fn held_bytes(&self) -> f64 {
        let guard = self.columns.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        self.held_with(&guard)
    }

    /// [`Factor::held_bytes`] with the column cache locked by the caller.
    fn held_with(&self, columns: &Columns) -> f64 {
        let formed = columns.cols.iter().filter(|c| c.is_some()).count();
        let saddle = f64::from_bits(self.saddle_bytes.load(Ordering::Relaxed));
        self.direct.value_bytes() + 8.0 * (formed * self.e_rows.len()) as f64 + saddle
    }

    /// Checks that dense parts of `dense` bytes, and the columns `idx` of H they need that are not formed
    /// yet, fit `budget` beside what this factorization holds ([`Factor::held_bytes`]): the memory budget
    /// bounds their sum, not each part on its own (an adaptive loop whose contact zone kept refining was
    /// killed at 24 GB while its H and its QP each fitted).
    ///
    /// # Errors
    /// [`Error::MemoryBudget`] naming `what` and the bytes held.
    pub(crate) fn fits_beside(
        &self,
        what: impl FnOnce() -> String,
        idx: &[usize],
        dense: f64,
        budget: usize,
    ) -> Result<()> {
        let (held, missing) = {
            let guard = self.columns.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            let missing = idx.iter().filter(|&&i| guard.cols.get(i).is_some_and(Option::is_none)).count();
            (self.held_with(&guard), missing)
        };
        let needed = held + 8.0 * (missing * self.e_rows.len()) as f64 + dense;
        if needed > budget as f64 {
            return Err(Error::MemoryBudget {
                what: format!(
                    "{} beside the factor of A and the columns of H already formed ({} bytes)",
                    what(),
                    Num(held)
                ),
                needed,
                budget: budget as f64,
            });
        }
        Ok(())
    }

    /// The sub-matrix `H[rows, cols]` (column-major), computing the columns it needs.
    pub fn h_block(&self, rows: &[usize], cols: &[usize]) -> Vec<f64> {
        self.with_columns(cols, |all| {
            cols.iter()
                .flat_map(|&j| {
                    let col = all[j].as_ref().expect("computed");
                    rows.iter().map(move |&i| col[i])
                })
                .collect()
        })
    }

    /// The whole dense H (column-major 2q × 2q): all 2q columns.
    pub fn dense_h(&self) -> Vec<f64> {
        let all: Vec<usize> = (0..self.e_rows.len()).collect();
        self.h_block(&all, &all)
    }

    /// Seconds spent so far forming `c` and columns of H.
    pub fn condensation_seconds(&self) -> f64 {
        self.columns.lock().unwrap_or_else(std::sync::PoisonError::into_inner).seconds
    }

    /// The displacement (free dofs) for multipliers λ (2q): `u = A⁻¹ (f − Eᵀ λ)` (about half a solve on
    /// the partial factorization when f is zero or the load `c` was formed with).
    ///
    /// # Errors
    /// [`Error::MemoryBudget`] if the solve's workspace cannot be allocated.
    pub fn displacement(&self, f: &[f64], lambda: &[f64]) -> Result<Vec<f64>> {
        direct::displacement(&self.direct, &self.e_rows, f, lambda, self.u_f.as_ref().filter(|_| f == self.f))
    }

    /// The saddle-point system `[[A, Eᵀ], [E, −Dγ]]` of the QPs that do without H, locked for the
    /// caller (`None` unless H is [`Condensation::Saddle`]).
    pub(crate) fn saddle_system(&self) -> std::sync::MutexGuard<'_, Option<SaddleSystem>> {
        self.saddle.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Notes what the saddle-point system holds after a solve on it grew its border.
    pub(crate) fn note_saddle_bytes(&self, saddle: &SaddleSystem) {
        self.saddle_bytes.store(saddle.held_bytes().to_bits(), Ordering::Relaxed);
    }
}
