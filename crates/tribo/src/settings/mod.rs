//! Solver settings: one struct per stage, each with documented defaults and a range check, validated once
//! at the public entry points ([`crate::Problem::solve`], [`crate::Condensed::solve`]).
//!
//! # One name per setting
//! Every setting has one flat name, its field path with `.` replaced by `_` (`qp.tol` is `qp_tol`,
//! `fp.max_iter` is `fp_max_iter`). That name is the Python keyword, the key of a scene's `[solver]`
//! table and the name an error gives ([`Error::BadSetting`]). [`SolverSettings::set`],
//! [`SolverSettings::get`] and [`SolverSettings::table`] are generated from one table ([`table`](self) module), so adding
//! a setting means adding its field (with its default and range check) and one line of that table.

pub mod adapt;
pub mod friction;
pub(crate) mod memory;
mod stabilization;
mod table;

pub use adapt::{AdaptKeywords, AdaptSettings, Bisection, Marking, StopOn};
pub use memory::{available_memory, default_memory_budget};
pub use stabilization::Stabilization;
pub use table::{SettingInfo, SettingKind, SettingValue};

use crate::choice::named_choice;
use crate::error::{check_setting, Error, Result};

/// Which sparse direct solver clarabel uses for its KKT systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KktSolver {
    /// clarabel's built-in QDLDL.
    Qdldl,
    /// clarabel's faer-based supernodal solver (cargo feature `faer-qp`, on by default).
    Faer,
}

named_choice!(KktSolver, "KKT solver", { KktSolver::Faer => "faer", KktSolver::Qdldl => "qdldl" });

impl Default for KktSolver {
    /// [`KktSolver::Faer`] when compiled in (the faster on our dense QPs), else [`KktSolver::Qdldl`].
    fn default() -> Self {
        if cfg!(feature = "faer-qp") {
            Self::Faer
        } else {
            Self::Qdldl
        }
    }
}

/// Which method solves the Γ_C QPs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum QpMethod {
    /// The active-set method ([`crate::qp::active_set`]), warm-started from the previous answer (from zero for
    /// the first QP of a solve), and clarabel for any QP it cannot certify. Measured as robust as clarabel
    /// on cold QPs (every QP of the test suite, the fuzzing and study 1c), and 4–10× cheaper there.
    #[default]
    Auto,
    /// clarabel's interior-point method for every QP (the reference).
    Clarabel,
    /// The active-set method alone: a QP it cannot certify ends the solve with status `qp_failed`.
    ActiveSet,
}

named_choice!(QpMethod, "QP method", {
    QpMethod::Auto => "auto",
    QpMethod::Clarabel => "clarabel",
    QpMethod::ActiveSet => "active_set",
});

/// How the multiplier operator H is formed (see [`crate::condensation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Condensation {
    /// The partial factorization where it is the cheaper and fits the memory budget (its dense trailing
    /// block of the Γ_C dofs weighed against the multipliers the load pushes, and against a Coulomb fixed
    /// point's several QPs, which make the saddle-point system dearer); else the saddle-point
    /// system where the contact zone makes the columns of H and the dense QP dearer; else columns.
    /// Measured against every path forced: `scripts/study_paths.py` (docs/paths.md).
    #[default]
    Auto,
    /// One sparse solve per column of H, for the columns the QPs need (a fill-reducing ordering).
    Columns,
    /// All of H from a partial factorization with the Γ_C dofs ordered last ([`crate::linalg::schur`]); a
    /// Cholesky kernel, refused for the mixed formulation's quasi-definite A ([`crate::fem::mixed`]).
    Schur,
    /// H never formed: each active-set step solves the sparse saddle-point system
    /// `[[A, E_Fᵀ], [E_F, −Dγ_FF]]` (`qp::sparse`); columns of H only for a QP it cannot certify.
    Saddle,
}

named_choice!(Condensation, "condensation", {
    Condensation::Auto => "auto",
    Condensation::Columns => "columns",
    Condensation::Schur => "schur",
    Condensation::Saddle => "saddle",
});

/// Which method solves the Coulomb problem (3.1) once its first QP is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CoulombMethod {
    /// The fixed point of Φ_H (Definition 1 of the paper, `solve/fixed_point.rs`): one Tresca QP per
    /// iteration, the friction bound frozen at the previous λ_n. The reference.
    #[default]
    FixedPoint,
    /// The semismooth Newton method on Γ_C (`solve/newton.rs`, derived there): the friction bound follows λ_n
    /// inside each step, each step a dense LU solve on the dofs in contact, restarting from one fixed-point
    /// iteration where it stalls. Measured in study 20 (`docs/coulomb_map.md`): fewer iterations than the fixed
    /// point on Hertz, as many on a body held only by the contact; it forms the columns of H the contact zone
    /// needs, which the fixed point's saddle-point path does not (study 4).
    Newton,
    /// The fixed point where H is not formed (the QPs solve the sparse saddle-point system: Newton would form
    /// the columns of H, measured 5–11 times the fixed point's time in study 4); elsewhere Newton, and the fixed
    /// point from the same start where Newton does not converge (the report says which answered:
    /// [`crate::Report::coulomb_method`]).
    Auto,
}

named_choice!(CoulombMethod, "Coulomb method", {
    CoulombMethod::FixedPoint => "fixed_point",
    CoulombMethod::Newton => "newton",
    CoulombMethod::Auto => "auto",
});

/// Settings of the QP solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QpSettings {
    /// Tolerance on the scaled QP (gap, feasibility). Default 1e-12: λ is determined to about
    /// `tol · κ(H)` (κ ~ 1e5 on contact meshes), and the Coulomb fixed point cannot settle below that;
    /// a QP that fails at 1e-12 is solved again at [`crate::qp::FALLBACK_TOL`].
    pub tol: f64,
    /// Iteration cap of clarabel's interior-point method, and of the active-set method's steps.
    /// Default 200.
    pub max_iter: u32,
    /// KKT solver. Default [`KktSolver::default`].
    pub kkt_solver: KktSolver,
    /// Solve over a working set of multiplier dofs grown until the KKT conditions of the whole QP hold
    /// (see [`crate::qp::working_set`]). Default true; false solves every QP over all of Γ_C.
    pub working_set: bool,
    /// The QP method. Default [`QpMethod::Auto`].
    pub method: QpMethod,
}

impl Default for QpSettings {
    fn default() -> Self {
        Self {
            tol: 1e-12,
            max_iter: 200,
            kkt_solver: KktSolver::default(),
            working_set: true,
            method: QpMethod::default(),
        }
    }
}

impl QpSettings {
    /// Checks the ranges: `0 < tol < 1`, `max_iter ≥ 1`, and that the KKT solver is compiled in.
    ///
    /// # Errors
    /// [`Error::BadSetting`] naming the setting.
    pub fn validate(&self) -> Result<()> {
        check_setting("qp_tol", self.tol, self.tol > 0.0 && self.tol < 1.0, "must lie in (0, 1)")?;
        check_setting("qp_max_iter", f64::from(self.max_iter), self.max_iter >= 1, "must be at least 1")?;
        if self.kkt_solver == KktSolver::Faer && !cfg!(feature = "faer-qp") {
            return Err(Error::BadSettingValue {
                name: "qp_kkt_solver",
                what: "the faer KKT solver needs tribo built with the cargo feature `faer-qp`".to_string(),
            });
        }
        Ok(())
    }
}

/// Settings of the Coulomb fixed point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedPointSettings {
    /// Stop when `‖λ_n^{k+1} − λ_n^k‖₂ ≤ tol ‖λ_n^{k+1}‖₂` (or when the change is below the QP's noise
    /// level, `qp.tol` times [`crate::condensation::Factor::lambda_scale`]). Default 1e-8.
    pub tol: f64,
    /// Iteration cap. Default 100.
    pub max_iter: usize,
    /// Relaxation ω ∈ (0, 1]: `g ← (1 − ω) g + ω Φ_H(g)`. Default 1 (plain fixed point).
    pub relaxation: f64,
}

impl Default for FixedPointSettings {
    fn default() -> Self {
        Self { tol: Self::DEFAULT_TOL, max_iter: 100, relaxation: 1.0 }
    }
}

impl FixedPointSettings {
    /// The default `tol` (`fp_tol`).
    pub const DEFAULT_TOL: f64 = 1e-8;

    /// Checks the ranges.
    ///
    /// # Errors
    /// [`Error::BadSetting`] naming the setting.
    pub fn validate(&self) -> Result<()> {
        check_setting("fp_tol", self.tol, self.tol > 0.0 && self.tol < 1.0, "must lie in (0, 1)")?;
        check_setting("fp_max_iter", self.max_iter as f64, self.max_iter >= 1, "must be at least 1")?;
        let w = self.relaxation;
        check_setting("fp_relaxation", w, w > 0.0 && w <= 1.0, "must lie in (0, 1]")
    }
}

/// All solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// γ0. Default: half of the admissible bound.
    pub stabilization: Stabilization,
    /// The QP solver.
    pub qp: QpSettings,
    /// The Coulomb fixed point; its `tol` and `max_iter` are Newton's too.
    pub fp: FixedPointSettings,
    /// The Coulomb method. Default [`CoulombMethod::FixedPoint`].
    pub coulomb: CoulombMethod,
    /// Checks a converged Coulomb answer by solving the problem again by the other method (Newton after the
    /// fixed point, the fixed point after Newton) and comparing the two: [`crate::Report::coulomb_check`] says
    /// whether they are one answer, within the bound their residuals and the fixed point's contraction give,
    /// or two (λ is not unique there, or not determined to better than their distance). It costs the other
    /// method's solve and one Tresca QP per answer. Default false.
    pub coulomb_check: bool,
    /// Bytes a solve may take for its factorization (the sparse Cholesky factor of A and its workspace,
    /// checked after the symbolic analysis, before anything of that size is allocated) and, each on its
    /// own, for its dense parts (columns of H, the dense QP) and for the solutions a loading history
    /// keeps. A solve that would need more is refused with [`Error::MemoryBudget`], which gives the size.
    /// Default: the memory this process may still allocate when the settings are made (the smallest
    /// headroom of the machine, its memory cgroup and its address-space limit: [`default_memory_budget`]).
    pub memory_budget: usize,
    /// How H is formed. Default [`Condensation::Auto`].
    pub condensation: Condensation,
    /// A loading history keeps the whole solution of every `keep_every`-th step (steps k with
    /// `k % keep_every == 0`, the first included) and of its last converged step; every step leaves its forces, states
    /// and estimate ([`crate::solve::history::StepRecord`]). Default 1: every step. A static solve
    /// ignores it.
    pub keep_every: usize,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            stabilization: Stabilization::default(),
            qp: QpSettings::default(),
            fp: FixedPointSettings::default(),
            coulomb: CoulombMethod::default(),
            coulomb_check: false,
            memory_budget: default_memory_budget(),
            condensation: Condensation::default(),
            keep_every: 1,
        }
    }
}

impl SolverSettings {
    /// Checks every setting (γ0 is checked against its bound when the problem is condensed).
    ///
    /// # Errors
    /// [`Error::BadSetting`], [`Error::BadSettingValue`].
    pub fn validate(&self) -> Result<()> {
        self.qp.validate()?;
        self.fp.validate()?;
        let b = self.memory_budget;
        check_setting("memory_budget", b as f64, b >= 1 << 20, "must be at least 1 MiB (1048576 bytes)")?;
        check_setting("keep_every", self.keep_every as f64, self.keep_every >= 1, "must be at least 1")
    }
}
