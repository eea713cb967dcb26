//! Solver settings: one struct per stage, each with documented defaults and a range check, validated once
//! at the public entry points ([`crate::Problem::solve`], [`crate::Condensed::solve`]).
//!
//! # One name per setting
//! Every setting has one flat name, its field path with `.` replaced by `_` (`qp.tol` is `qp_tol`,
//! `fp.max_iter` is `fp_max_iter`). That name is the Python keyword, the key of a scene's `[solver]`
//! table and the name an error gives ([`Error::BadSetting`]). [`SolverSettings::set`],
//! [`SolverSettings::get`] and [`SolverSettings::table`] are generated from one table below, so adding
//! a setting means adding its field (with its default and range check) and one line of that table.

use crate::choice::{named_choice, Choice};
use crate::error::{check_setting, Error, Result};
use crate::stabilization::Stabilization;

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
    /// The active-set method ([`crate::active_set`]), warm-started from the previous answer (from zero for
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
    /// The partial factorization where it is the cheaper and fits the memory budget; else the saddle-point
    /// system where the contact zone makes the columns of H and the dense QP dearer; else columns.
    #[default]
    Auto,
    /// One sparse solve per column of H, for the columns the QPs need (a fill-reducing ordering).
    Columns,
    /// All of H from a partial factorization with the Γ_C dofs ordered last ([`crate::schur`]).
    Schur,
    /// H never formed: each active-set step solves the sparse saddle-point system
    /// `[[A, E_Fᵀ], [E_F, −Dγ_FF]]` ([`crate::sparse_qp`]); columns of H only for a QP it cannot certify.
    Saddle,
}

named_choice!(Condensation, "condensation", {
    Condensation::Auto => "auto",
    Condensation::Columns => "columns",
    Condensation::Schur => "schur",
    Condensation::Saddle => "saddle",
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
    /// (see [`crate::working_set`]). Default true; false solves every QP over all of Γ_C.
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
        Self { tol: 1e-8, max_iter: 100, relaxation: 1.0 }
    }
}

impl FixedPointSettings {
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
    /// The Coulomb fixed point.
    pub fp: FixedPointSettings,
    /// Bytes the dense parts of a solve (columns of H, the dense QP) may take. A solve that would need
    /// more is refused with [`Error::MemoryBudget`], which gives the size. Default 4 GiB.
    pub memory_budget: usize,
    /// How H is formed. Default [`Condensation::Auto`].
    pub condensation: Condensation,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            stabilization: Stabilization::default(),
            qp: QpSettings::default(),
            fp: FixedPointSettings::default(),
            memory_budget: 4 << 30,
            condensation: Condensation::default(),
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
        check_setting("memory_budget", b as f64, b >= 1 << 20, "must be at least 1 MiB (1048576 bytes)")
    }
}

/// A setting's value, as the Python binding and the scene files give it.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue {
    /// A boolean.
    Bool(bool),
    /// An integer.
    Int(i64),
    /// A real number.
    Float(f64),
    /// The name of an option.
    Name(String),
}

/// What values a setting takes.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingKind {
    /// A real number.
    Float,
    /// A non-negative integer up to the given maximum.
    Count {
        /// The largest value the field can hold.
        max: u64,
    },
    /// A boolean.
    Bool,
    /// One of these names.
    Choice(Vec<&'static str>),
}

/// One row of the table of solver settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SettingInfo {
    /// The flat name (`qp_tol`).
    pub name: &'static str,
    /// What values it takes.
    pub kind: SettingKind,
    /// Its default.
    pub default: SettingValue,
}

/// A field type that a [`SettingValue`] converts to and from.
trait SettingField: Sized {
    fn kind() -> SettingKind;
    fn to_value(&self) -> SettingValue;
    fn from_value(name: &'static str, value: SettingValue) -> Result<Self>;
}

fn wrong_kind(name: &'static str, want: &str, value: &SettingValue) -> Error {
    Error::BadSettingValue { name, what: format!("must be {want}, got {value:?}") }
}

impl SettingField for f64 {
    fn kind() -> SettingKind {
        SettingKind::Float
    }
    fn to_value(&self) -> SettingValue {
        SettingValue::Float(*self)
    }
    fn from_value(name: &'static str, value: SettingValue) -> Result<Self> {
        match value {
            SettingValue::Float(v) => Ok(v),
            SettingValue::Int(v) => Ok(v as f64),
            v => Err(wrong_kind(name, "a number", &v)),
        }
    }
}

macro_rules! count_field {
    ($ty:ty) => {
        impl SettingField for $ty {
            fn kind() -> SettingKind {
                SettingKind::Count { max: <$ty>::MAX as u64 }
            }
            fn to_value(&self) -> SettingValue {
                SettingValue::Int(i64::try_from(*self).unwrap_or(i64::MAX))
            }
            fn from_value(name: &'static str, value: SettingValue) -> Result<Self> {
                match value {
                    SettingValue::Int(v) => <$ty>::try_from(v).map_err(|_| Error::BadSettingValue {
                        name,
                        what: format!("must be an integer in [0, {}], got {v}", <$ty>::MAX),
                    }),
                    v => Err(wrong_kind(name, "an integer", &v)),
                }
            }
        }
    };
}
count_field!(u32);
count_field!(usize);

impl SettingField for bool {
    fn kind() -> SettingKind {
        SettingKind::Bool
    }
    fn to_value(&self) -> SettingValue {
        SettingValue::Bool(*self)
    }
    fn from_value(name: &'static str, value: SettingValue) -> Result<Self> {
        match value {
            SettingValue::Bool(v) => Ok(v),
            v => Err(wrong_kind(name, "true or false", &v)),
        }
    }
}

macro_rules! choice_field {
    ($ty:ty) => {
        impl SettingField for $ty {
            fn kind() -> SettingKind {
                SettingKind::Choice(Self::names())
            }
            fn to_value(&self) -> SettingValue {
                SettingValue::Name(self.as_str().to_string())
            }
            fn from_value(name: &'static str, value: SettingValue) -> Result<Self> {
                match value {
                    SettingValue::Name(s) => Self::parse(&s),
                    v => Err(wrong_kind(name, &format!("one of {}", Self::names().join(", ")), &v)),
                }
            }
        }
    };
}
choice_field!(KktSolver);
choice_field!(QpMethod);
choice_field!(Condensation);

/// The table of settings: flat name, field path, field type.
macro_rules! settings_table {
    ($($name:literal => $($field:ident).+ : $ty:ty;)+) => {
        impl SolverSettings {
            /// The flat names of every setting, in the order of [`SolverSettings::table`].
            pub const NAMES: &'static [&'static str] = &[$($name),+];

            /// Every setting with its kind and default value.
            pub fn table() -> Vec<SettingInfo> {
                let d = Self::default();
                vec![$(SettingInfo { name: $name, kind: <$ty>::kind(), default: d.$($field).+.to_value() }),+]
            }

            /// The value of a setting by its flat name, `None` for an unknown name.
            pub fn get(&self, name: &str) -> Option<SettingValue> {
                match name {
                    $($name => Some(self.$($field).+.to_value()),)+
                    _ => None,
                }
            }

            /// Sets a setting by its flat name. The value's kind is checked here, its range by
            /// [`SolverSettings::validate`].
            ///
            /// # Errors
            /// [`Error::UnknownSetting`], [`Error::BadSettingValue`], [`Error::UnknownChoice`].
            pub fn set(&mut self, name: &str, value: SettingValue) -> Result<()> {
                match name {
                    $($name => self.$($field).+ = <$ty>::from_value($name, value)?,)+
                    _ => {
                        return Err(Error::UnknownSetting {
                            name: name.to_string(),
                            known: Self::NAMES.join(", "),
                        })
                    }
                }
                Ok(())
            }
        }
    };
}

settings_table! {
    "qp_tol" => qp.tol: f64;
    "qp_max_iter" => qp.max_iter: u32;
    "qp_kkt_solver" => qp.kkt_solver: KktSolver;
    "qp_working_set" => qp.working_set: bool;
    "qp_method" => qp.method: QpMethod;
    "fp_tol" => fp.tol: f64;
    "fp_max_iter" => fp.max_iter: usize;
    "fp_relaxation" => fp.relaxation: f64;
    "memory_budget" => memory_budget: usize;
    "condensation" => condensation: Condensation;
}

impl SolverSettings {
    /// The defaults of the solve's keywords, as the Python binding and the scene files name them: how γ0
    /// is chosen (`gamma0_fraction`, or `gamma0` when the default gives a value) and every setting of
    /// [`SolverSettings::table`].
    pub fn keyword_defaults() -> Vec<(&'static str, SettingValue)> {
        let gamma0 = match Self::default().stabilization {
            Stabilization::Fraction(f) => ("gamma0_fraction", SettingValue::Float(f)),
            Stabilization::Gamma0(g) | Stabilization::Unchecked(g) => ("gamma0", SettingValue::Float(g)),
            Stabilization::None => ("gamma0", SettingValue::Float(0.0)),
        };
        std::iter::once(gamma0).chain(Self::table().into_iter().map(|info| (info.name, info.default))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every setting of the table reads back what was set, and every range check names the setting by
    /// the flat name of the table.
    #[test]
    fn the_table_sets_gets_and_names_every_setting() {
        let mut s = SolverSettings::default();
        for info in SolverSettings::table() {
            assert_eq!(s.get(info.name), Some(info.default.clone()), "{}", info.name);
            s.set(info.name, info.default.clone()).expect("the default is a valid value");
        }
        assert_eq!(s, SolverSettings::default());
        for (name, bad) in [
            ("qp_tol", SettingValue::Float(2.0)),
            ("qp_max_iter", SettingValue::Int(0)),
            ("fp_tol", SettingValue::Float(0.0)),
            ("fp_max_iter", SettingValue::Int(0)),
            ("fp_relaxation", SettingValue::Float(1.5)),
        ] {
            let mut s = SolverSettings::default();
            s.set(name, bad).expect("right kind");
            match s.validate() {
                Err(Error::BadSetting { name: n, .. }) => assert_eq!(n, name),
                other => panic!("{name}: {other:?}"),
            }
        }
        let mut s = SolverSettings::default();
        assert!(matches!(s.set("qp_max_iter", SettingValue::Int(1 << 32)), Err(Error::BadSettingValue { .. })));
        assert!(matches!(s.set("qp_max_iter", SettingValue::Int(-1)), Err(Error::BadSettingValue { .. })));
        assert!(matches!(s.set("qp_tol", SettingValue::Bool(true)), Err(Error::BadSettingValue { .. })));
        assert!(matches!(s.set("qp_kkt_solver", SettingValue::Name("mumps".into())), Err(Error::UnknownChoice { .. })));
        assert!(matches!(s.set("fp_tolerance", SettingValue::Float(1e-6)), Err(Error::UnknownSetting { .. })));
    }

    /// The keyword defaults name γ0's default by the keyword that gives it back, then every setting of
    /// the table with its default.
    #[test]
    fn keyword_defaults_give_back_the_default_settings() {
        let defaults = SolverSettings::keyword_defaults();
        let stabilization = match &defaults[0] {
            ("gamma0_fraction", SettingValue::Float(f)) => Stabilization::from_keywords(None, Some(*f), true),
            ("gamma0", SettingValue::Float(g)) => Stabilization::from_keywords(Some(*g), None, true),
            other => panic!("{other:?}"),
        };
        assert_eq!(stabilization.expect("the default is valid"), SolverSettings::default().stabilization);
        let table: Vec<_> = SolverSettings::table().into_iter().map(|i| (i.name, i.default)).collect();
        assert_eq!(defaults[1..], table[..]);
    }
}
