//! How γ0 is chosen: a setting of the solve ([`Stabilization`]). The operators it scales live in
//! [`crate::contact::operators`] and the bound it is checked against in [`crate::contact::gamma0`].

use crate::error::{Error, Result};

/// How γ0 is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stabilization {
    /// γ0 = 0: the classic (unstabilized) mixed method.
    None,
    /// γ0 given directly (units of 1/E); must be below the admissible bound.
    Gamma0(f64),
    /// γ0 as a fraction θ ∈ [0, 1) of the admissible bound.
    Fraction(f64),
    /// γ0 given directly and *not* checked against the admissible bound: for studies of what happens
    /// beyond it. The factorization of `K − G` still refuses an indefinite matrix
    /// ([`Error::NotPositiveDefinite`]).
    Unchecked(f64),
}

impl Default for Stabilization {
    /// Half of the admissible bound.
    fn default() -> Self {
        Self::Fraction(0.5)
    }
}

impl Stabilization {
    /// The choice from keywords: `gamma0` (a value), `fraction` (of the bound) or neither (the default);
    /// `checked = false` takes `gamma0` without the check against the bound ([`Stabilization::Unchecked`]).
    ///
    /// # Errors
    /// [`Error::BadSettingValue`] when both are given, or when `checked` is false without a `gamma0`.
    pub fn from_keywords(gamma0: Option<f64>, fraction: Option<f64>, checked: bool) -> Result<Self> {
        let bad = |what: &str| Err(Error::BadSettingValue { name: "gamma0", what: what.to_string() });
        match (gamma0, fraction, checked) {
            (Some(_), Some(_), _) => bad("give gamma0 or gamma0_fraction, not both"),
            (Some(g), None, true) => Ok(Self::Gamma0(g)),
            (Some(g), None, false) => Ok(Self::Unchecked(g)),
            (None, _, false) => bad("check_gamma0 = false needs an explicit gamma0"),
            (None, Some(f), true) => Ok(Self::Fraction(f)),
            (None, None, true) => Ok(Self::default()),
        }
    }
}
