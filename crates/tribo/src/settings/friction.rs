//! Friction laws: frictionless, Tresca (a given threshold g, problem (3.2)) and Coulomb (μ, problem
//! (3.1), the fixed point of `g ↦ λ_Hn(g)`).
//!
//! The rules that turn what a user gives into a law live here, once: μ = 0 is frictionless, and the
//! keyword form (a law name, a μ, a threshold) used by the Python binding and the scene files is resolved
//! by [`Friction::from_keywords`].

use crate::choice::named_choice;
use crate::error::{check_setting, Error, Result};

/// The friction model.
#[derive(Debug, Clone, PartialEq)]
pub enum Friction {
    /// μ = 0: no tangential multiplier, one QP.
    Frictionless,
    /// Tresca: a given threshold g ≥ 0 with |λ_t| ≤ g, one QP.
    Tresca(Threshold),
    /// Coulomb with friction coefficient μ ≥ 0 (μ = 0 is solved as frictionless).
    Coulomb {
        /// Friction coefficient.
        mu: f64,
    },
}

/// A Tresca threshold.
#[derive(Debug, Clone, PartialEq)]
pub enum Threshold {
    /// The same threshold at every multiplier dof.
    Uniform(f64),
    /// One threshold per multiplier dof (dof values of a function of W_H).
    PerDof(Vec<f64>),
}

/// The name of a friction law, as reports, the Python binding and scene files give it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionLaw {
    /// No friction.
    Frictionless,
    /// A given threshold.
    Tresca,
    /// Coulomb's law.
    Coulomb,
}

named_choice!(FrictionLaw, "friction law", {
    FrictionLaw::Frictionless => "frictionless",
    FrictionLaw::Tresca => "tresca",
    FrictionLaw::Coulomb => "coulomb",
});

impl Friction {
    /// The law from keywords: a law name (optional), a coefficient μ and a threshold. Without a name,
    /// μ means Coulomb, a threshold Tresca, and neither frictionless; μ and a threshold exclude each other.
    ///
    /// # Errors
    /// [`Error::BadFriction`] for a contradictory or incomplete combination.
    pub fn from_keywords(law: Option<FrictionLaw>, mu: Option<f64>, threshold: Option<Threshold>) -> Result<Self> {
        let bad = |what: &str| Err(Error::BadFriction { what: what.to_string() });
        match (law, mu, threshold) {
            (_, Some(_), Some(_)) => bad("give mu (Coulomb) or threshold (Tresca), not both"),
            (None | Some(FrictionLaw::Coulomb), Some(mu), None) => Ok(Self::Coulomb { mu }),
            (None | Some(FrictionLaw::Tresca), None, Some(t)) => Ok(Self::Tresca(t)),
            (None | Some(FrictionLaw::Frictionless), None, None) => Ok(Self::Frictionless),
            (Some(FrictionLaw::Coulomb), None, _) => bad("friction 'coulomb' needs mu"),
            (Some(FrictionLaw::Tresca), _, None) => bad("friction 'tresca' needs a threshold"),
            (Some(FrictionLaw::Frictionless), _, _) => bad("friction 'frictionless' takes neither mu nor a threshold"),
        }
    }

    /// The law as it is solved: Coulomb with μ = 0 is frictionless (no fixed point is needed).
    pub fn normalized(&self) -> Self {
        match self {
            Self::Coulomb { mu } if *mu == 0.0 => Self::Frictionless,
            other => other.clone(),
        }
    }

    /// The name of the law as it is solved ([`Friction::normalized`]).
    pub fn law(&self) -> FrictionLaw {
        match self.normalized() {
            Self::Frictionless => FrictionLaw::Frictionless,
            Self::Tresca(_) => FrictionLaw::Tresca,
            Self::Coulomb { .. } => FrictionLaw::Coulomb,
        }
    }

    /// The Coulomb coefficient, if the law is Coulomb with μ > 0.
    pub fn mu(&self) -> Option<f64> {
        match self.normalized() {
            Self::Coulomb { mu } => Some(mu),
            _ => None,
        }
    }

    /// Checks μ ≥ 0 (finite) and thresholds ≥ 0 (finite), one per multiplier dof when given per dof.
    ///
    /// # Errors
    /// [`Error::BadSetting`] for μ, [`Error::BadThreshold`] for thresholds.
    pub fn validate(&self, q: usize) -> Result<()> {
        match self {
            Self::Frictionless => Ok(()),
            Self::Coulomb { mu } => check_setting("mu", *mu, *mu >= 0.0, "the friction coefficient must be ≥ 0"),
            Self::Tresca(Threshold::Uniform(s)) => check_thresholds(&[*s], 1),
            Self::Tresca(Threshold::PerDof(v)) => check_thresholds(v, q),
        }
    }

    /// The Tresca threshold per multiplier dof (empty for the other laws).
    pub(crate) fn tresca_bounds(&self, q: usize) -> Vec<f64> {
        match self {
            Self::Tresca(Threshold::Uniform(s)) => vec![*s; q],
            Self::Tresca(Threshold::PerDof(v)) => v.clone(),
            _ => Vec::new(),
        }
    }
}

/// Checks a vector of friction thresholds: `len` values, each finite and ≥ 0.
///
/// # Errors
/// [`Error::BadThreshold`] saying which value is wrong.
pub(crate) fn check_thresholds(values: &[f64], len: usize) -> Result<()> {
    if values.len() != len {
        return Err(Error::BadThreshold { what: format!("{} values given, {len} multiplier dofs", values.len()) });
    }
    match values.iter().position(|s| !(s.is_finite() && *s >= 0.0)) {
        Some(j) => Err(Error::BadThreshold {
            what: format!("value {j} is {}; thresholds must be finite and ≥ 0", values[j]),
        }),
        None => Ok(()),
    }
}
