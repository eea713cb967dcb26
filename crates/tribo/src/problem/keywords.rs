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
    /// Two bodies, each with its own materials, supports and tractions, and the primary side of their pair,
    /// `"body.edge_set"` (the secondary side is `contact`).
    Two {
        /// The bodies.
        bodies: Box<[Body; 2]>,
        /// The primary side.
        primary: String,
    },
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
            Bodies::Two { bodies, primary } => {
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
                    primary,
                    gap: k.obstacle,
                    multiplier_points: k.multiplier_points,
                    multiplier_space: k.multiplier_space,
                    model: k.model.unwrap_or_default(),
                    formulation: k.formulation,
                };
                Self::two_bodies_with_pairs(*bodies, pair, k.pairs, k.body_force)
            }
            Bodies::One(mesh) => {
                let none =
                    || Error::BadMaterial { what: "none given (materials by region, or young and poisson)".into() };
                let pairs = k.materials.ok_or_else(none)?;
                let materials = Materials::from_pairs(&pairs, k.regions, mesh.n_triangles());
                // Where the list is empty, `with_materials` says so.
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

    fn body(name: &str, y: [f64; 2], nx: usize, material: Material, clamped: &str) -> Result<Body> {
        let mesh = rectangle([0.0, 1.0], y, nx, 2, Diagonal::default())?;
        let materials = Materials::uniform(material, mesh.n_triangles());
        Ok(Body {
            name: name.into(),
            mesh,
            materials,
            clamped: vec![clamped.into()],
            supports: vec![],
            tractions: vec![],
        })
    }

    /// Two bodies of their own meshes and materials.
    fn bodies() -> Result<[Body; 2]> {
        let (a, b) = (Material { young: 1.0, poisson: 0.3 }, Material { young: 3.0, poisson: 0.2 });
        Ok([body("a", [0.0, 1.0], 4, a, "bottom")?, body("b", [1.0, 2.0], 6, b, "top")?])
    }

    fn two() -> Result<Bodies> {
        Ok(Bodies::Two { bodies: Box::new(bodies()?), primary: "b.bottom".into() })
    }

    /// What `Debug` prints of a problem's set-up: its specification, bodies, unknowns and T_H.
    fn fingerprint(p: &Problem) -> String {
        format!("{:?} {:?} {} {:?} {:?}", p.spec, p.bodies, p.n_free, p.multipliers.xi, p.multipliers.space)
    }

    /// Two bodies from keywords are `two_bodies_with_pairs`'s, every keyword of the pair passed on.
    #[test]
    fn two_bodies_from_keywords_are_the_pair_given() -> Result<()> {
        let k = ProblemKeywords {
            contact: "a.top".into(),
            obstacle: ObstacleShape::Parabola { center: 0.5, radius: 4.0 },
            body_force: [0.0, -0.5],
            model: Some(Model::PlaneStress),
            formulation: Formulation::Displacement,
            multiplier_points: MultiplierPoints::RatioToFe(2.0),
            multiplier_space: MultiplierSpace::P0,
            ..Default::default()
        };
        let p = Problem::from_keywords(two()?, k.clone())?;
        let pair = ContactPair {
            secondary: "a.top".into(),
            primary: "b.bottom".into(),
            gap: k.obstacle.clone(),
            multiplier_points: MultiplierPoints::RatioToFe(2.0),
            multiplier_space: MultiplierSpace::P0,
            model: Model::PlaneStress,
            formulation: Formulation::Displacement,
        };
        let q = Problem::two_bodies_with_pairs(bodies()?, pair, vec![], [0.0, -0.5])?;
        assert_eq!(fingerprint(&p), fingerprint(&q));
        assert_eq!((p.bodies.len(), p.spec.model, p.multipliers.space), (2, Model::PlaneStress, MultiplierSpace::P0));
        assert_eq!((p.multipliers.xi.len(), p.spec.body_force), (3, [0.0, -0.5]), "H = 2h on a.top's 4 edges");
        Ok(())
    }

    /// A keyword of one body given with two is refused, naming why, each of them.
    #[test]
    fn two_bodies_take_no_keyword_of_one_body() -> Result<()> {
        let k = ProblemKeywords { contact: "a.top".into(), ..Default::default() };
        Problem::from_keywords(two()?, k.clone())?;
        let one_body = [
            ProblemKeywords { materials: Some(vec![(1.0, 0.3)]), ..k.clone() },
            ProblemKeywords { regions: Some(vec![0; 16]), ..k.clone() },
            ProblemKeywords { clamped: Some(vec!["a.bottom".into()]), ..k.clone() },
            ProblemKeywords { supports: Some(vec![Support::roller("a.left")]), ..k.clone() },
            ProblemKeywords { tractions: Some(vec![("b.top".into(), [0.0, -1.0].into())]), ..k.clone() },
            ProblemKeywords { approach: Some(0.01), ..k.clone() },
            ProblemKeywords { shift: Some(0.01), ..k.clone() },
            ProblemKeywords { rotation: Some(([0.0, 0.0], 0.1)), ..k.clone() },
        ];
        for k in one_body {
            let refused = Problem::from_keywords(two()?, k);
            let per_body = |e: &Error| e.to_string().contains("per body");
            assert!(matches!(&refused, Err(e @ Error::BadSettingValue { name: "primary", .. }) if per_body(e)));
        }
        Ok(())
    }

    /// One body from keywords is `with_materials`'s, every keyword passed on; without a material it is refused.
    #[test]
    fn one_body_from_keywords_is_the_spec_given() -> Result<()> {
        let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 4, 4, Diagonal::default())?;
        let regions: Vec<usize> = (0..mesh.n_triangles()).map(|t| t % 2).collect();
        let k = ProblemKeywords {
            contact: "top".into(),
            materials: Some(vec![(1.0, 0.3), (2.0, 0.25)]),
            regions: Some(regions.clone()),
            clamped: Some(vec!["bottom".into()]),
            supports: Some(vec![Support::roller("left")]),
            tractions: Some(vec![("right".into(), [0.5, 0.0].into())]),
            obstacle: ObstacleShape::Parabola { center: 0.5, radius: 2.0 },
            approach: Some(0.01),
            shift: Some(0.002),
            body_force: [0.0, -1.0],
            model: Some(Model::PlaneStress),
            formulation: Formulation::Displacement,
            multiplier_points: MultiplierPoints::RatioToFe(2.0),
            multiplier_space: MultiplierSpace::P0,
            ..Default::default()
        };
        let p = Problem::from_keywords(Bodies::One(mesh.clone()), k.clone())?;
        let spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .support(Support::roller("left"))
            .traction("right", [0.5, 0.0])
            .obstacle(ObstacleShape::Parabola { center: 0.5, radius: 2.0 })
            .approach(0.01)
            .shift(0.002)
            .body_force([0.0, -1.0])
            .model(Model::PlaneStress)
            .formulation(Formulation::Displacement)
            .multipliers(MultiplierPoints::RatioToFe(2.0), MultiplierSpace::P0);
        let materials = Materials::from_pairs(&[(1.0, 0.3), (2.0, 0.25)], Some(regions), mesh.n_triangles());
        let q = Problem::with_materials(mesh.clone(), spec, materials)?;
        assert_eq!(fingerprint(&p), fingerprint(&q));
        assert_eq!((p.spec.obstacle.approach, p.spec.obstacle.shift, p.materials.materials.len()), (0.01, 0.002, 2));
        let none = ProblemKeywords { materials: None, regions: None, ..k };
        let refused = Problem::from_keywords(Bodies::One(mesh), none);
        assert!(matches!(&refused, Err(e @ Error::BadMaterial { .. }) if e.to_string().contains("none given")));
        Ok(())
    }
}
