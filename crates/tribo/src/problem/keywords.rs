//! A problem from keywords, each left out as `None` (the Python binding's `Problem(...)` and
//! `Problem.two_bodies`): one body, a mesh with its materials, supports, loads and the obstacle's motion; or
//! two bodies, each with its own materials, supports and tractions, which move through their supports.
//!
//! ```
//! use tribo::*;
//!
//! let mesh = rectangle([0.0, 1.0], [0.0, 0.5], 8, 4, Diagonal::default())?;
//! let keywords = ProblemKeywords {
//!     contact: "bottom".into(),
//!     materials: Some(vec![(1.0, 0.3)]),
//!     clamped: Some(vec!["top".into()]),
//!     obstacle: ObstacleShape::Parabola { center: 0.5, radius: 1.0 },
//!     approach: Some(0.01),
//!     ..Default::default()
//! };
//! let p = Problem::from_keywords(Bodies::One(mesh), keywords)?;
//! assert_eq!((p.spec.obstacle.approach, p.spec.material.young), (0.01, 1.0));
//! # Ok::<(), tribo::Error>(())
//! ```

use crate::contact::multiplier::{MultiplierPoints, MultiplierSpace};
use crate::contact::obstacle::{Obstacle, ObstacleShape};
use crate::error::{Error, Result};
use crate::fem::elasticity::{Material, Materials, Model, Traction};
use crate::fem::mixed::Formulation;
use crate::fem::supports::Support;
use crate::mesh::Mesh;
use crate::problem::bodies::{Body, ContactPair};
use crate::problem::sides::PairSpec;
use crate::problem::{Problem, ProblemSpec};

/// The keywords of a problem; see the module documentation. The defaults are [`ProblemSpec::new`]'s.
#[derive(Debug, Clone, Default)]
pub struct ProblemKeywords {
    /// Γ_C: an edge set of one body; of two, the secondary side `"body.edge_set"`.
    pub contact: String,
    /// The primary side of two bodies, `"body.edge_set"`; `None` for one body against a rigid obstacle.
    pub primary: Option<String>,
    /// One body's materials (E, ν) by region.
    pub materials: Option<Vec<(f64, f64)>>,
    /// One body's region of each triangle (`None`: every triangle of the first material).
    pub regions: Option<Vec<usize>>,
    /// One body's clamped edge sets.
    pub clamped: Option<Vec<String>>,
    /// One body's further supports.
    pub supports: Option<Vec<Support>>,
    /// One body's tractions on edge sets.
    pub tractions: Option<Vec<(String, Traction)>>,
    /// The obstacle's shape; between two bodies, the initial gap of the pair ([`ContactPair::gap`]).
    pub obstacle: ObstacleShape,
    /// One body's obstacle: its approach δ, its shift s and its rotation (centre, angle).
    pub approach: Option<f64>,
    /// See `approach`.
    pub shift: Option<f64>,
    /// See `approach`.
    pub rotation: Option<([f64; 2], f64)>,
    /// The body force, on every body.
    pub body_force: [f64; 2],
    /// The model (`None`: plane strain).
    pub model: Option<Model>,
    /// The formulation.
    pub formulation: Formulation,
    /// The points of T_H.
    pub multiplier_points: MultiplierPoints,
    /// The multiplier space.
    pub multiplier_space: MultiplierSpace,
    /// Further contact pairs, each against its own rigid obstacle.
    pub pairs: Vec<PairSpec>,
}

/// The mesh of one body, or the two bodies of a pair.
#[derive(Debug, Clone)]
pub enum Bodies {
    /// One body's mesh; its materials, supports and loads are keywords.
    One(Mesh),
    /// Two bodies, each with its own materials, supports and tractions.
    Two(Box<[Body; 2]>),
}

impl Problem {
    /// The problem the keywords give: [`Problem::with_materials`] for one body, [`Problem::two_bodies_with_pairs`]
    /// for two.
    ///
    /// # Errors
    /// Theirs; for two bodies, [`Error::BadSettingValue`] where a keyword of one body was given (materials,
    /// supports and tractions are each body's, and the bodies move through their supports); for one body,
    /// [`Error::BadMaterial`] where no material was given.
    pub fn from_keywords(bodies: Bodies, k: ProblemKeywords) -> Result<Self> {
        match bodies {
            Bodies::Two(bodies) => {
                let given = [k.materials.is_some(), k.regions.is_some(), k.clamped.is_some(), k.supports.is_some()];
                let moved = [k.tractions.is_some(), k.approach.or(k.shift).is_some(), k.rotation.is_some()];
                if given.into_iter().chain(moved).any(|g| g) {
                    return Err(Error::BadSettingValue {
                        name: "primary",
                        what: "with two bodies, materials, supports and tractions are per body, and the bodies \
                               move through their supports (no approach, shift or rotation)"
                            .into(),
                    });
                }
                let pair = ContactPair {
                    secondary: k.contact,
                    primary: k.primary.unwrap_or_default(),
                    gap: k.obstacle,
                    multiplier_points: k.multiplier_points,
                    multiplier_space: k.multiplier_space,
                    model: k.model.unwrap_or_default(),
                    formulation: k.formulation,
                };
                Self::two_bodies_with_pairs(*bodies, pair, k.pairs, k.body_force)
            }
            Bodies::One(mesh) => {
                let pairs = k.materials.unwrap_or_default();
                let materials = Materials::from_pairs(&pairs, k.regions, mesh.n_triangles());
                // Where none is given, `with_materials` says so.
                let material =
                    materials.materials.first().copied().unwrap_or(Material { young: f64::NAN, poisson: 0.0 });
                let spec = ProblemSpec {
                    material,
                    model: k.model.unwrap_or_default(),
                    formulation: k.formulation,
                    clamped: k.clamped.unwrap_or_default(),
                    supports: k.supports.unwrap_or_default(),
                    body_force: k.body_force,
                    tractions: k.tractions.unwrap_or_default(),
                    contact: k.contact,
                    obstacle: Obstacle::from_keywords(k.obstacle, k.approach, k.shift, k.rotation.map(Into::into)),
                    pairs: k.pairs,
                    multiplier_points: k.multiplier_points,
                    multiplier_space: k.multiplier_space,
                };
                Self::with_materials(mesh, spec, materials)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{rectangle, Diagonal};

    fn body(name: &str, y: [f64; 2], clamped: &str) -> Body {
        let mesh = rectangle([0.0, 1.0], y, 4, 2, Diagonal::default()).unwrap();
        let materials = Materials::uniform(Material { young: 1.0, poisson: 0.3 }, mesh.n_triangles());
        Body { name: name.into(), mesh, materials, clamped: vec![clamped.into()], supports: vec![], tractions: vec![] }
    }

    fn two() -> Bodies {
        Bodies::Two(Box::new([body("a", [0.0, 1.0], "bottom"), body("b", [1.0, 2.0], "top")]))
    }

    /// Two bodies from keywords are `two_bodies_with_pairs`'s; a keyword of one body is refused, naming why.
    #[test]
    fn two_bodies_take_no_keyword_of_one_body() {
        let k = ProblemKeywords { contact: "a.top".into(), primary: Some("b.bottom".into()), ..Default::default() };
        let p = Problem::from_keywords(two(), k.clone()).unwrap();
        let pair = ContactPair {
            secondary: "a.top".into(),
            primary: "b.bottom".into(),
            gap: ObstacleShape::Flat,
            multiplier_points: MultiplierPoints::default(),
            multiplier_space: MultiplierSpace::default(),
            model: Model::default(),
            formulation: Formulation::default(),
        };
        let [a, b] = [body("a", [0.0, 1.0], "bottom"), body("b", [1.0, 2.0], "top")];
        let q = Problem::two_bodies_with_pairs([a, b], pair, vec![], [0.0, 0.0]).unwrap();
        assert_eq!((p.n_free, p.n_multipliers(), p.bodies.len()), (q.n_free, q.n_multipliers(), 2));
        let one_body = [
            ProblemKeywords { materials: Some(vec![(1.0, 0.3)]), ..k.clone() },
            ProblemKeywords { clamped: Some(vec!["a.bottom".into()]), ..k.clone() },
            ProblemKeywords { approach: Some(0.01), ..k.clone() },
            ProblemKeywords { rotation: Some(([0.0, 0.0], 0.1)), ..k.clone() },
        ];
        for k in one_body {
            let e = Problem::from_keywords(two(), k).unwrap_err();
            assert!(matches!(e, Error::BadSettingValue { name: "primary", .. }) && e.to_string().contains("per body"));
        }
    }

    /// One body without a material is refused as such, not solved with a placeholder.
    #[test]
    fn one_body_needs_a_material() {
        let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 4, 2, Diagonal::default()).unwrap();
        let k = ProblemKeywords { contact: "top".into(), clamped: Some(vec!["bottom".into()]), ..Default::default() };
        assert!(matches!(Problem::from_keywords(Bodies::One(mesh), k), Err(Error::BadMaterial { .. })));
    }
}
