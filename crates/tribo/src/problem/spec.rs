//! A [`ProblemSpec`] from its two required parts, the rest at the documented defaults and set by name.
//!
//! ```
//! use tribo::*;
//!
//! let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top")
//!     .clamped(["bottom"])
//!     .obstacle(ObstacleShape::Circle { center: 0.5, radius: 1.0 })
//!     .approach(0.01);
//! assert_eq!((spec.clamped.len(), spec.obstacle.approach, spec.obstacle.shift), (1, 0.01, 0.0));
//! ```

use crate::contact::multiplier::{MultiplierPoints, MultiplierSpace};
use crate::contact::obstacle::{Obstacle, ObstacleShape};
use crate::fem::elasticity::{Material, Model, Traction};
use crate::fem::mixed::Formulation;
use crate::fem::supports::Support;
use crate::problem::ProblemSpec;

impl ProblemSpec {
    /// A body of `material` whose edge set `contact` is Γ_C, with the defaults of every other part: nothing
    /// clamped and no other support, no body force and no traction, a flat obstacle touching Γ_C (approach
    /// and shift 0), and the default multipliers ([`MultiplierPoints::default`]: T_H on the FE edges of
    /// Γ_C; [`MultiplierSpace::default`]: continuous P1). The methods below set the others; a problem
    /// built from it checks them all ([`crate::Problem::new`]).
    pub fn new(material: Material, contact: impl Into<String>) -> Self {
        Self {
            material,
            model: Model::default(),
            formulation: Formulation::default(),
            clamped: Vec::new(),
            supports: Vec::new(),
            body_force: [0.0, 0.0],
            tractions: Vec::new(),
            contact: contact.into(),
            obstacle: Obstacle::default(),
            multiplier_points: MultiplierPoints::default(),
            multiplier_space: MultiplierSpace::default(),
            pairs: Vec::new(),
        }
    }

    /// Sets the model: plane strain (the default), plane stress or axisymmetry.
    #[must_use]
    pub fn model(mut self, model: Model) -> Self {
        self.model = model;
        self
    }

    /// Sets the formulation: P1 displacements, the mixed displacement–pressure one for bodies near
    /// incompressibility ([`crate::fem::mixed`]), or `Auto` (the default) to choose by ν.
    #[must_use]
    pub fn formulation(mut self, formulation: Formulation) -> Self {
        self.formulation = formulation;
        self
    }

    /// Clamps the edge sets `sets` too (u = 0 there).
    #[must_use]
    pub fn clamped<S: Into<String>>(mut self, sets: impl IntoIterator<Item = S>) -> Self {
        self.clamped.extend(sets.into_iter().map(Into::into));
        self
    }

    /// Adds a support (a roller, a prescribed displacement, a clamp).
    #[must_use]
    pub fn support(mut self, support: Support) -> Self {
        self.supports.push(support);
        self
    }

    /// Sets the constant body force f (per unit area).
    #[must_use]
    pub fn body_force(mut self, force: [f64; 2]) -> Self {
        self.body_force = force;
        self
    }

    /// Adds a constant traction (per unit length) on the edge set `set`.
    #[must_use]
    pub fn traction(mut self, set: impl Into<String>, traction: impl Into<Traction>) -> Self {
        self.tractions.push((set.into(), traction.into()));
        self
    }

    /// Sets the obstacle's shape (its initial gap), keeping its approach and shift.
    #[must_use]
    pub fn obstacle(mut self, shape: ObstacleShape) -> Self {
        self.obstacle.shape = shape;
        self
    }

    /// Sets the obstacle's normal approach δ toward the body.
    #[must_use]
    pub fn approach(mut self, approach: f64) -> Self {
        self.obstacle.approach = approach;
        self
    }

    /// Sets the obstacle's tangential shift s along t.
    #[must_use]
    pub fn shift(mut self, shift: f64) -> Self {
        self.obstacle.shift = shift;
        self
    }

    /// Turns the obstacle (one given by its geometry) by `angle` radians counterclockwise about `center`
    /// ([`crate::contact::obstacle`]).
    pub fn obstacle_rotation(mut self, center: [f64; 2], angle: f64) -> Self {
        self.obstacle.rotation = Some(crate::ObstacleRotation { center, angle });
        self
    }

    /// Sets the points of the multiplier mesh T_H and the multiplier space.
    #[must_use]
    pub fn multipliers(mut self, points: MultiplierPoints, space: MultiplierSpace) -> Self {
        self.multiplier_points = points;
        self.multiplier_space = space;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The builder gives the specification written out field by field.
    #[test]
    fn the_builder_spells_out_the_literal() {
        let material = Material { young: 200.0, poisson: 0.3 };
        let built = ProblemSpec::new(material, "top")
            .clamped(["bottom"])
            .support(Support::roller("left"))
            .body_force([0.0, -1.0])
            .traction("right", [0.5, 0.0])
            .obstacle(ObstacleShape::Parabola { center: 0.1, radius: 2.0 })
            .approach(0.01)
            .shift(0.002)
            .multipliers(MultiplierPoints::RatioToFe(2.0), MultiplierSpace::P0)
            .model(Model::PlaneStress);
        let literal = ProblemSpec {
            material,
            model: Model::PlaneStress,
            formulation: Formulation::Auto,
            clamped: vec!["bottom".into()],
            supports: vec![Support::roller("left")],
            body_force: [0.0, -1.0],
            tractions: vec![("right".into(), [0.5, 0.0].into())],
            contact: "top".into(),
            obstacle: Obstacle {
                shape: ObstacleShape::Parabola { center: 0.1, radius: 2.0 },
                approach: 0.01,
                shift: 0.002,
                rotation: None,
            },
            multiplier_points: MultiplierPoints::RatioToFe(2.0),
            multiplier_space: MultiplierSpace::P0,
            pairs: Vec::new(),
        };
        assert_eq!(format!("{built:?}"), format!("{literal:?}"));
        let plain = ProblemSpec::new(material, "top");
        assert!(plain.clamped.is_empty() && plain.supports.is_empty() && plain.tractions.is_empty());
        assert_eq!((plain.obstacle.approach, plain.obstacle.shift, plain.body_force), (0.0, 0.0, [0.0, 0.0]));
        assert!(matches!(plain.obstacle.shape, ObstacleShape::Flat) && plain.model == Model::PlaneStrain);
    }
}
