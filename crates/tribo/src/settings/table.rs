//! The table of solver settings by flat name: [`SolverSettings::set`], [`SolverSettings::get`] and
//! [`SolverSettings::table`], generated from one declaration (`settings_table!` at the end), and the
//! value types that cross to Python and scene files ([`SettingValue`], [`SettingKind`], [`SettingInfo`]).

use super::{Condensation, CoulombMethod, KktSolver, QpMethod, SolverSettings, Stabilization};
use crate::choice::Choice;
use crate::error::{Error, Result};

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

impl SettingKind {
    /// The kind's name: `float`, `count`, `bool` or `choice`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Float => "float",
            Self::Count { .. } => "count",
            Self::Bool => "bool",
            Self::Choice(_) => "choice",
        }
    }
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
choice_field!(CoulombMethod);

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
    "coulomb" => coulomb: CoulombMethod;
    "coulomb_check" => coulomb_check: bool;
    "memory_budget" => memory_budget: usize;
    "condensation" => condensation: Condensation;
    "keep_every" => keep_every: usize;
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
}
