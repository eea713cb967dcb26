//! The rigid obstacle: its shape (initial gap as a function of the abscissa on Γ_C) and its motion.
//!
//! # How the obstacle enters (3.1)
//! The obstacle surface lies at distance `g₀(ξ)` from Γ_C along n. A normal approach δ moves it toward the
//! body and a tangential shift s moves it along t, so non-penetration reads `u_n ≤ g(ξ) := g₀(ξ) − δ` and
//! the slip that friction opposes is the relative one, `u_t − s`. The contact law therefore applies to
//! the shifted pair `w = (u_n − g, u_t − s)`, and only the *inequality* of (3.1) changes:
//!
//! `b(ν_H − λ_H, u_h) − ∫ (ν_Hn − λ_Hn) g − ∫ (ν_Ht − λ_Ht) s + (γ terms) ≤ 0`.
//!
//! The equilibrium equation (first line of (3.1)) and the stabilization terms are unchanged: σ(u_h) does not
//! see a rigid shift. In matrix form the obstacle adds the vector `d = (∫ψ_j g, ∫ψ_j s)` to the
//! QP's linear term (see [`crate::qp`]).

use std::fmt;
use std::sync::Arc;

use crate::error::{Error, Result};

/// A user gap function `ξ ↦ g₀(ξ)`.
#[derive(Clone)]
pub struct GapFunction(pub Arc<dyn Fn(f64) -> f64 + Send + Sync>);

impl fmt::Debug for GapFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("GapFunction(<closure>)")
    }
}

/// Shape of the obstacle: the initial gap `g₀(ξ) ≥ 0` between Γ_C and the obstacle, along n.
#[derive(Debug, Clone, Default)]
pub enum ObstacleShape {
    /// A flat obstacle touching Γ_C: `g₀ = 0`.
    #[default]
    Flat,
    /// A rigid cylinder of radius R whose lowest point touches Γ_C at abscissa `center`:
    /// `g₀ = R − √(R² − (ξ − c)²)` for `|ξ − c| < R`, and `R` beyond (the cylinder never reaches there).
    Circle {
        /// Abscissa of the contact point.
        center: f64,
        /// Radius R > 0.
        radius: f64,
    },
    /// The parabolic (Hertz) approximation of a cylinder: `g₀ = (ξ − c)² / (2R)`.
    Parabola {
        /// Abscissa of the vertex.
        center: f64,
        /// Radius of curvature R > 0.
        radius: f64,
    },
    /// A polyline through `(xi[k], gap[k])`, extended by constants beyond its ends.
    Polyline {
        /// Strictly increasing abscissae (at least one).
        xi: Vec<f64>,
        /// Gap values.
        gap: Vec<f64>,
    },
    /// Any function of the abscissa.
    Function(GapFunction),
}

/// The rigid obstacle: shape and prescribed motion.
#[derive(Debug, Clone, Default)]
pub struct Obstacle {
    /// Initial gap.
    pub shape: ObstacleShape,
    /// Normal approach δ of the obstacle toward the body.
    pub approach: f64,
    /// Tangential shift s of the obstacle along t.
    pub shift: f64,
}

impl Obstacle {
    /// The obstacle of `shape` moved by the keywords given (approach δ, shift s), the others at their
    /// defaults (0: touching, not shifted).
    pub fn from_keywords(shape: ObstacleShape, approach: Option<f64>, shift: Option<f64>) -> Self {
        let d = Self::default();
        Self { shape, approach: approach.unwrap_or(d.approach), shift: shift.unwrap_or(d.shift) }
    }

    /// Checks the shape's parameters and the motion.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] saying which parameter is wrong.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: String| Err(Error::BadObstacle { what });
        if !self.approach.is_finite() {
            return bad(format!("approach δ must be finite, got {}", self.approach));
        }
        if !self.shift.is_finite() {
            return bad(format!("tangential shift s must be finite, got {}", self.shift));
        }
        for (name, v) in [("approach δ", self.approach), ("tangential shift s", self.shift)] {
            if v.is_subnormal() {
                return bad(crate::error::subnormal(name, v));
            }
        }
        match &self.shape {
            ObstacleShape::Flat | ObstacleShape::Function(_) => Ok(()),
            ObstacleShape::Circle { center, radius } | ObstacleShape::Parabola { center, radius } => {
                if !center.is_finite() {
                    bad(format!("center must be finite, got {center}"))
                } else if !(radius.is_finite() && *radius > 0.0) {
                    bad(format!("radius must be positive and finite, got {radius}"))
                } else {
                    Ok(())
                }
            }
            ObstacleShape::Polyline { xi, gap } => {
                if xi.is_empty() || xi.len() != gap.len() {
                    return bad(format!(
                        "polyline needs as many gaps as abscissae (at least one): {} abscissae, {} gaps",
                        xi.len(),
                        gap.len()
                    ));
                }
                if let Some(k) = xi.iter().chain(gap).position(|v| !v.is_finite()) {
                    return bad(format!("polyline value {k} is not finite"));
                }
                if let Some(k) = (1..xi.len()).find(|&k| xi[k] <= xi[k - 1]) {
                    return bad(format!(
                        "polyline abscissae must increase strictly: point {k} ({}) <= {}",
                        xi[k],
                        xi[k - 1]
                    ));
                }
                Ok(())
            }
        }
    }

    /// Initial gap `g₀(ξ)` (NaN at a non-finite abscissa).
    pub fn initial_gap(&self, xi: f64) -> f64 {
        if !xi.is_finite() {
            return f64::NAN;
        }
        match &self.shape {
            ObstacleShape::Flat => 0.0,
            ObstacleShape::Circle { center, radius } => {
                let d = xi - center;
                if d.abs() < *radius {
                    // R − √(R² − d²) written without cancellation.
                    d * d / (radius + (radius * radius - d * d).sqrt())
                } else {
                    *radius
                }
            }
            ObstacleShape::Parabola { center, radius } => (xi - center).powi(2) / (2.0 * radius),
            ObstacleShape::Polyline { xi: xs, gap } => {
                let k = xs.partition_point(|&x| x <= xi);
                if k == 0 {
                    gap[0]
                } else if k == xs.len() {
                    gap[k - 1]
                } else {
                    let s = (xi - xs[k - 1]) / (xs[k] - xs[k - 1]);
                    gap[k - 1] + s * (gap[k] - gap[k - 1])
                }
            }
            ObstacleShape::Function(f) => (f.0)(xi),
        }
    }

    /// Gap after the approach: `g(ξ) = g₀(ξ) − δ`; non-penetration is `u_n ≤ g`.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] if a user function returns a non-finite value.
    pub fn gap(&self, xi: f64) -> Result<f64> {
        let g = self.initial_gap(xi) - self.approach;
        if g.is_finite() {
            Ok(g)
        } else {
            Err(Error::BadObstacle { what: format!("the gap function returned {g} at abscissa {xi}") })
        }
    }
}

impl ObstacleShape {
    /// The radius R and the abscissa of the lowest point of a circle or a parabola, else None.
    pub fn radius_center(&self) -> Option<(f64, f64)> {
        match *self {
            Self::Circle { center, radius } | Self::Parabola { center, radius } => Some((radius, center)),
            _ => None,
        }
    }

    /// The abscissae, sorted, where the initial gap may have a local minimum between two points at which
    /// it is sampled: the lowest point of a circle or a parabola, the vertices of a polyline; none for a
    /// flat obstacle or a function (whose minima are not known). The estimator integrates the penetration
    /// finely around them.
    pub fn lowest_points(&self) -> Vec<f64> {
        match self {
            Self::Circle { center, .. } | Self::Parabola { center, .. } => vec![*center],
            Self::Polyline { xi, .. } => xi.clone(),
            Self::Flat | Self::Function(_) => Vec::new(),
        }
    }

    /// The shape's name, as scene files and Python spell it: `flat`, `circle`, `parabola`, `polyline` or
    /// `function`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::Circle { .. } => "circle",
            Self::Parabola { .. } => "parabola",
            Self::Polyline { .. } => "polyline",
            Self::Function(_) => "function",
        }
    }
}

/// The shape as the call that builds it in Python: `flat()`, `circle(radius=2, center=0)`,
/// `parabola(radius=2, center=0)`, `polyline(<5 points>)`, `function(<closure>)`.
impl fmt::Display for ObstacleShape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Circle { center, radius } | Self::Parabola { center, radius } => {
                write!(f, "{}(radius={radius}, center={center})", self.kind())
            }
            Self::Polyline { xi, .. } => write!(f, "polyline(<{} points>)", xi.len()),
            Self::Function(_) => f.write_str("function(<closure>)"),
            Self::Flat => f.write_str("flat()"),
        }
    }
}
