//! Named choices: every enum of options (a side of a rectangle, a multiplier space, a QP solver, a
//! contact state…) parses and prints itself here, so the Python binding, the scene files and the error
//! messages all use one table of names per enum.

use crate::error::{Error, Result};

/// An enum of named options.
pub trait Choice: Copy + PartialEq + Sized + 'static {
    /// What the option chooses, for error messages (`"multiplier space"`).
    const WHAT: &'static str;
    /// Every option, in a fixed order (the order of [`Choice::names`]).
    const ALL: &'static [Self];

    /// The option's name.
    fn as_str(self) -> &'static str;

    /// The names of every option, in the order of [`Choice::ALL`].
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|c| c.as_str()).collect()
    }

    /// The option with this name (ASCII case ignored).
    ///
    /// # Errors
    /// [`Error::UnknownChoice`] listing the options.
    fn parse(name: &str) -> Result<Self> {
        Self::ALL.iter().copied().find(|c| c.as_str().eq_ignore_ascii_case(name)).ok_or_else(|| Error::UnknownChoice {
            what: Self::WHAT,
            got: name.to_string(),
            options: Self::names().join(", "),
        })
    }

    /// Position of the option in [`Choice::ALL`] (a small integer code, e.g. for numpy arrays).
    fn code(self) -> usize {
        Self::ALL.iter().position(|c| *c == self).unwrap_or(usize::MAX)
    }
}

/// Implements [`Choice`], `Display` and `FromStr` for a fieldless enum from one table of names.
macro_rules! named_choice {
    ($ty:ty, $what:literal, { $($variant:path => $name:literal),+ $(,)? }) => {
        impl $crate::choice::Choice for $ty {
            const WHAT: &'static str = $what;
            const ALL: &'static [Self] = &[$($variant),+];
            fn as_str(self) -> &'static str {
                match self {
                    $($variant => $name),+
                }
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str($crate::choice::Choice::as_str(*self))
            }
        }
        impl std::str::FromStr for $ty {
            type Err = $crate::error::Error;
            fn from_str(s: &str) -> $crate::error::Result<Self> {
                <Self as $crate::choice::Choice>::parse(s)
            }
        }
    };
}
pub(crate) use named_choice;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ContactState, Diagonal, FrictionLaw, KktSolver, MultiplierSpace, Side};

    fn round_trip<C: Choice + std::fmt::Debug>() {
        for &c in C::ALL {
            assert_eq!(C::parse(c.as_str()).expect("own name"), c);
            assert_eq!(C::parse(&c.as_str().to_ascii_uppercase()).expect("case ignored"), c);
            assert_eq!(C::ALL[c.code()], c);
        }
        let e = C::parse("no such option").expect_err("unknown name");
        assert!(e.to_string().contains(&C::names().join(", ")), "{e}");
    }

    #[test]
    fn every_choice_parses_its_own_names_and_refuses_others() {
        round_trip::<Side>();
        round_trip::<Diagonal>();
        round_trip::<MultiplierSpace>();
        round_trip::<KktSolver>();
        round_trip::<ContactState>();
        round_trip::<FrictionLaw>();
    }
}
