//! Two elastic bodies in contact: each body is a value (mesh, material, supports, tractions), the pair
//! names the secondary side (which carries T_H and the stabilization) and the primary side by
//! `"body.edge_set"`. [`Problem::two_bodies`] joins the two meshes into one (nodes and triangles of the first
//! body first, edge sets renamed `"body.set"`), gives each triangle its material (a body may have several:
//! [`Body::materials`]), takes the pair's model (plane strain or plane stress) for both, and builds the
//! problem of [`crate::contact::pair`]: everything downstream (condensation, QP, fixed point, histories)
//! is that of one body.
//!
//! The bodies move through their prescribed displacements: a loading history moves them step by step
//! ([`crate::LoadStep::displacements`]); an obstacle motion (approach, shift) has no meaning for the pair
//! and a history step that asks for one is refused ([`Error::BadLoadStep`]).
//!
//! Adaptive refinement bisects the joined mesh (`Problem::refined`): a child triangle keeps its
//! parent's body and material, and the nodes are renumbered so that each body's nodes stay one range, its
//! own first ones before its new ones.
//!
//! A body may be held by the contact alone in the motions its supports leave free (a punch pushed down by
//! a load): see `problem/floating.rs`. A piece of a body that neither its supports nor the contact can
//! hold (a piece off the contact line, or one joined to the rest at a single node) is refused with
//! [`Error::ContactPair`], which names the body and the free motion.

use std::collections::BTreeMap;
use std::ops::Range;

use crate::contact::multiplier::{MultiplierPoints, MultiplierSpace};
use crate::contact::obstacle::{Obstacle, ObstacleShape};
use crate::error::{Error, Result};
use crate::fem::elasticity::{Materials, Model, Traction};
use crate::fem::supports::Support;
use crate::mesh::Mesh;
use crate::problem::sides::PairSpec;
use crate::problem::{Problem, ProblemSpec};

/// One elastic body of a two-body problem. Edge set names are the body's own (`"top"`); the problem
/// calls them `"name.top"`.
#[derive(Debug, Clone)]
pub struct Body {
    /// Name (non-empty, without '.').
    pub name: String,
    /// Mesh.
    pub mesh: Mesh,
    /// Its materials and the region of each of its triangles ([`Materials::uniform`] for one material; several
    /// for a coated body, as [`Problem::with_materials`]).
    pub materials: Materials,
    /// Clamped edge sets.
    pub clamped: Vec<String>,
    /// Further supports.
    pub supports: Vec<Support>,
    /// Constant tractions on edge sets.
    pub tractions: Vec<(String, Traction)>,
}

/// The contact pair of a two-body problem.
#[derive(Debug, Clone)]
pub struct ContactPair {
    /// The secondary side, `"body.edge_set"`: it carries the multipliers and the stabilization.
    pub secondary: String,
    /// The primary side, `"body.edge_set"`: on the same line with the opposite normal, or, where either side is
    /// bent, any chain of edges facing the secondary side near it ([`crate::contact::pair`]).
    pub primary: String,
    /// The initial gap g₀(ξ) ≥ 0 between the two lines (abscissa of the secondary line), as the shapes of
    /// the rigid obstacle: [`ObstacleShape::Flat`] for bodies that touch, a parabola for curved profiles.
    /// Between bent sides it adds to the gap their geometry gives.
    pub gap: ObstacleShape,
    /// Points of T_H on the secondary line.
    pub multiplier_points: MultiplierPoints,
    /// Multiplier space.
    pub multiplier_space: MultiplierSpace,
    /// The model of both bodies: plane strain (long bodies) or plane stress (thin plates).
    pub model: Model,
    /// The formulation of both bodies ([`crate::fem::mixed`]): `Auto` takes the mixed one when either body
    /// reaches ν = [`crate::fem::mixed::MIXED_FROM_POISSON`] in plane strain or axisymmetry.
    pub formulation: crate::fem::mixed::Formulation,
}

/// Where a body lies in the problem's mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyPart {
    /// Name.
    pub name: String,
    /// Its nodes.
    pub nodes: Range<usize>,
    /// Its triangles.
    pub triangles: Range<usize>,
    /// Its displacement unknowns (what its supports leave free of its nodes' dofs).
    pub unknowns: usize,
}

impl BodyPart {
    /// The whole mesh as one body (its unknowns are counted when the problem is built).
    pub fn whole(name: &str, mesh: &Mesh) -> Self {
        Self { name: name.to_string(), nodes: 0..mesh.n_nodes(), triangles: 0..mesh.n_triangles(), unknowns: 0 }
    }

    /// `[first node, end, first triangle, end]`.
    pub fn spans(&self) -> [usize; 4] {
        [self.nodes.start, self.nodes.end, self.triangles.start, self.triangles.end]
    }
}

fn renamed(support: &Support, body: &str) -> Support {
    let set = format!("{body}.{}", support.set());
    match support {
        Support::Clamp { .. } => Support::Clamp { set },
        Support::Roller { .. } => Support::Roller { set },
        Support::Displacement { x, y, .. } => Support::Displacement { set, x: *x, y: *y },
        Support::Rotation { center, angle, .. } => Support::Rotation { set, center: *center, angle: *angle },
    }
}

impl Problem {
    /// Two elastic bodies in contact along `pair`, each with its own material, supports and tractions, and
    /// one constant body force on both (see [`crate::contact::pair`] for the formulation).
    ///
    /// # Errors
    /// [`Error::ContactPair`] for body names that are empty, repeated or hold a '.', a pair side that names
    /// no body or no edge set of it, both sides on one body, straight sides that are not one line with
    /// opposite normals, a primary side that does not cover the secondary one, bent sides that do not face
    /// each other or lie beyond the small-sliding range, a piece of a body that neither its
    /// supports nor the contact hold (naming the body and the free motion); [`Error::BadObstacle`] for a gap
    /// given by its geometry ([`crate::ObstacleShape::is_geometry`]); the other errors of [`Problem::new`].
    pub fn two_bodies(bodies: [Body; 2], pair: ContactPair, body_force: [f64; 2]) -> Result<Self> {
        Self::two_bodies_with_pairs(bodies, pair, Vec::new(), body_force)
    }

    /// [`Problem::two_bodies`] with further contact `pairs`, each an edge set of either body (`"body.edge_set"`)
    /// against its own rigid obstacle ([`crate::problem::sides`]): a block pressed by a second body onto a
    /// foundation.
    ///
    /// # Errors
    /// As [`Problem::two_bodies`] and, for the further pairs, as [`Problem::new`]'s (an edge set of two pairs, or one
    /// on the primary side: [`Error::SeveralPairs`]).
    pub fn two_bodies_with_pairs(
        bodies: [Body; 2],
        pair: ContactPair,
        pairs: Vec<PairSpec>,
        body_force: [f64; 2],
    ) -> Result<Self> {
        let bad = |what: String| Error::ContactPair {
            secondary: pair.secondary.clone(),
            primary: pair.primary.clone(),
            what,
        };
        for b in &bodies {
            if b.name.is_empty() || b.name.contains('.') {
                return Err(bad(format!("body name '{}' must be non-empty and without '.'", b.name)));
            }
        }
        if bodies[0].name == bodies[1].name {
            return Err(bad(format!("both bodies are named '{}'", bodies[0].name)));
        }
        for b in &bodies {
            Self::check_regions(&b.materials, b.mesh.n_triangles()).map_err(|e| match e {
                Error::BadMaterial { what } => Error::BadMaterial { what: format!("body '{}': {what}", b.name) },
                other => other,
            })?;
        }
        let side = |full: &str| -> Result<usize> {
            let (body, set) = full.split_once('.').ok_or_else(|| bad(format!("'{full}' is not 'body.edge_set'")))?;
            let k = bodies.iter().position(|b| b.name == body).ok_or_else(|| {
                bad(format!("no body named '{body}' (the bodies are '{}' and '{}')", bodies[0].name, bodies[1].name))
            })?;
            bodies[k].mesh.edge_set(set)?;
            Ok(k)
        };
        let (s, p) = (side(&pair.secondary)?, side(&pair.primary)?);
        if s == p {
            return Err(bad("both sides are on one body".to_string()));
        }
        // One mesh: the first body's nodes and triangles, then the second's.
        let mut points = Vec::new();
        let mut triangles = Vec::new();
        let mut edge_sets = BTreeMap::new();
        if pair.gap.is_geometry() {
            return Err(Error::BadObstacle {
                what: format!(
                    "the gap between two bodies is a function of the abscissa on the secondary side (flat, circle, \
                     parabola, polyline or function), not a shape given by its geometry ({})",
                    pair.gap.kind()
                ),
            });
        }
        let mut parts = Vec::new();
        let mut region = Vec::new();
        for (k, b) in bodies.iter().enumerate() {
            let (n0, t0) = (points.len(), triangles.len());
            points.extend_from_slice(b.mesh.points());
            triangles.extend(b.mesh.triangles().iter().map(|t| t.map(|i| i + n0)));
            for (name, edges) in b.mesh.edge_sets() {
                edge_sets.insert(format!("{}.{name}", b.name), edges.iter().map(|e| e.map(|i| i + n0)).collect());
            }
            // Each body's regions index the materials of both, the first body's first.
            let offset = if k == 0 { 0 } else { bodies[0].materials.materials.len() };
            region.extend(b.materials.region.iter().map(|r| r + offset));
            let (nodes, triangles) = (n0..points.len(), t0..triangles.len());
            parts.push(BodyPart { name: b.name.clone(), nodes, triangles, unknowns: 0 });
        }
        // Each body's curves, under its sets' new names.
        let curves = bodies
            .iter()
            .flat_map(|b| b.mesh.curves().iter().map(|(set, c)| (format!("{}.{set}", b.name), *c)))
            .collect();
        let mesh = Mesh::new(points, triangles, edge_sets)?.with_curves(curves);
        // The secondary side's material: that under its first edge (as a body of several materials has it).
        let secondary = &bodies[s];
        let set = &pair.secondary[secondary.name.len() + 1..];
        let first = secondary.mesh.edge_set(set)?.first().and_then(|&[a, b]| secondary.mesh.boundary_triangle(a, b));
        let spec = ProblemSpec {
            material: secondary.materials.materials[first.map_or(0, |t| secondary.materials.region[t])],
            model: pair.model,
            formulation: pair.formulation,
            clamped: bodies.iter().flat_map(|b| b.clamped.iter().map(|c| format!("{}.{c}", b.name))).collect(),
            supports: bodies.iter().flat_map(|b| b.supports.iter().map(|x| renamed(x, &b.name))).collect(),
            body_force,
            tractions: bodies
                .iter()
                .flat_map(|b| b.tractions.iter().map(|(set, g)| (format!("{}.{set}", b.name), *g)))
                .collect(),
            contact: pair.secondary.clone(),
            obstacle: Obstacle { shape: pair.gap.clone(), ..Obstacle::default() },
            multiplier_points: pair.multiplier_points.clone(),
            multiplier_space: pair.multiplier_space,
            pairs,
        };
        let materials =
            Materials { materials: bodies.iter().flat_map(|b| b.materials.materials.clone()).collect(), region };
        let spans: Vec<(String, Range<usize>)> = parts.iter().map(|p| (p.name.clone(), p.triangles.clone())).collect();
        Self::build(mesh, spec, materials, Some(&pair.primary), parts).map_err(|e| {
            // A piece neither its supports nor the contact hold: name the body and the free motion.
            let (triangle, motion) = match &e {
                Error::RigidMotion { triangle, motion, .. } => (*triangle, motion.clone()),
                Error::FloatingPiece { triangle, .. } => (*triangle, "every rigid motion (it has no support)".into()),
                _ => return e,
            };
            let Some((name, _)) = spans.iter().find(|(_, r)| r.contains(&triangle)) else { return e };
            bad(format!(
                "body '{name}' has a piece that neither its supports nor the contact hold, free in {motion}: hold \
                 that motion with a support ({e})"
            ))
        })
    }

    /// This problem on a mesh made from its own by relabelling or bisecting it, with `spec` (its own but
    /// for the multiplier points): `parent[t]` is the triangle of `self.mesh` that triangle t of `mesh`
    /// lies in, `midpoints` the coarse edge of each new node (node `n + i` for entry i, n the coarse nodes;
    /// see [`crate::mesh::refine::Refinement`]). Each triangle keeps its parent's material and body; for
    /// two bodies the nodes are renumbered so that each body's stay one range (its old nodes in their
    /// order, then its new ones).
    ///
    /// # Errors
    /// The errors of [`Problem::new`] on the new mesh.
    pub(crate) fn refined(
        &self,
        mesh: Mesh,
        parent: &[usize],
        midpoints: &[[usize; 2]],
        spec: ProblemSpec,
    ) -> Result<Self> {
        let body_of = |ranges: &dyn Fn(&BodyPart) -> &Range<usize>, i: usize| {
            self.bodies.iter().position(|b| ranges(b).contains(&i)).unwrap_or(0)
        };
        let n_bodies = self.bodies.len();
        let mut node_body: Vec<usize> = (0..self.mesh.n_nodes()).map(|i| body_of(&|b| &b.nodes, i)).collect();
        let new: Vec<usize> = midpoints.iter().map(|&[a, _]| node_body[a]).collect();
        node_body.extend(new);
        let triangle_body: Vec<usize> = parent.iter().map(|&t| body_of(&|b| &b.triangles, t)).collect();
        let region = parent.iter().map(|&t| self.materials.region[t]).collect();
        let materials = Materials { materials: self.materials.materials.clone(), region };
        let mesh = if n_bodies == 1 {
            mesh
        } else {
            // Stable: each body's old nodes keep their order, its new ones follow.
            let mut order: Vec<usize> = (0..node_body.len()).collect();
            order.sort_by_key(|&i| node_body[i]);
            let mut index = vec![0; order.len()];
            for (k, &i) in order.iter().enumerate() {
                index[i] = k;
            }
            let renumber = |e: &[usize; 2]| e.map(|i| index[i]);
            Mesh::new(
                order.iter().map(|&i| mesh.points()[i]).collect(),
                mesh.triangles().iter().map(|t| t.map(|i| index[i])).collect(),
                mesh.edge_sets().iter().map(|(k, v)| (k.clone(), v.iter().map(renumber).collect())).collect(),
            )?
            .with_curves(mesh.curves().clone())
        };
        // Children are listed parent by parent, so each body's triangles stay one range too.
        let (mut node0, mut triangle0) = (0, 0);
        let parts = (0..n_bodies)
            .map(|k| {
                let nodes = node0..node0 + node_body.iter().filter(|&&b| b == k).count();
                let triangles = triangle0..triangle0 + triangle_body.iter().filter(|&&b| b == k).count();
                (node0, triangle0) = (nodes.end, triangles.end);
                BodyPart { name: self.bodies[k].name.clone(), nodes, triangles, unknowns: 0 }
            })
            .collect();
        let primary = self.primary.as_ref().map(|p| p.boundary.set.clone());
        Self::build(mesh, spec, materials, primary.as_deref(), parts)
    }

    /// This problem on another mesh of the same bodies, with `spec` (its own but for the multiplier
    /// points): `region[t]` is the index into this problem's materials of triangle t, `parts` where each
    /// body lies in `mesh` (each body's nodes and triangles one range, as [`Problem::refined`] makes them).
    ///
    /// # Errors
    /// [`Error::BadMaterial`] when `region` does not give every triangle one of this problem's materials,
    /// or `parts` do not name this problem's bodies or do not make `mesh` a refinement of this problem's
    /// mesh ([`Problem::check_refines`]); the errors of [`Problem::new`] on the mesh.
    pub(crate) fn on_mesh(
        &self,
        mesh: Mesh,
        region: Vec<usize>,
        parts: Vec<BodyPart>,
        spec: ProblemSpec,
    ) -> Result<Self> {
        let n = self.materials.materials.len();
        if region.len() != mesh.n_triangles() || region.iter().any(|&r| r >= n) {
            return Err(Error::BadMaterial {
                what: format!(
                    "{} regions for {} triangles, or one beyond this problem's {n} materials: not a mesh of \
                     this problem's bodies",
                    region.len(),
                    mesh.n_triangles()
                ),
            });
        }
        let names = |p: &[BodyPart]| p.iter().map(|b| b.name.clone()).collect::<Vec<_>>();
        if names(&parts) != names(&self.bodies) {
            return Err(Error::BadMaterial {
                what: format!("bodies {:?} are not this problem's {:?}", names(&parts), names(&self.bodies)),
            });
        }
        self.check_refines(&mesh, &parts)?;
        let materials = Materials { materials: self.materials.materials.clone(), region };
        let primary = self.primary.as_ref().map(|p| p.boundary.set.clone());
        Self::build(mesh, spec, materials, primary.as_deref(), parts)
    }

    /// That `parts` split `mesh` into one range of nodes and one of triangles per body, in order, each
    /// triangle on nodes of its own body, and that each body's range begins with this problem's nodes of
    /// that body at their places (as [`Problem::refined`] keeps them). That is what a refinement of this
    /// problem's mesh keeps; it does not check that each triangle lies in a triangle of this mesh.
    ///
    /// # Errors
    /// [`Error::BadMaterial`] saying which of these fails.
    fn check_refines(&self, mesh: &Mesh, parts: &[BodyPart]) -> Result<()> {
        let refuse = |what: String| Err(Error::BadMaterial { what });
        let (mut node0, mut triangle0) = (0, 0);
        for (part, own) in parts.iter().zip(&self.bodies) {
            let (nodes, triangles) = (&part.nodes, &part.triangles);
            if nodes.start != node0 || triangles.start != triangle0 || nodes.is_empty() || triangles.is_empty() {
                return refuse(format!(
                    "body '{}' is empty or does not begin where the body before it ends",
                    part.name
                ));
            }
            (node0, triangle0) = (nodes.end, triangles.end);
            if node0 > mesh.n_nodes() || triangle0 > mesh.n_triangles() {
                return refuse(format!("body '{}' reaches beyond the mesh", part.name));
            }
            if let Some(t) = triangles.clone().find(|&t| mesh.triangles()[t].iter().any(|v| !nodes.contains(v))) {
                return refuse(format!("triangle {t} of body '{}' has a node of another body", part.name));
            }
            let kept = own.nodes.len();
            let same = nodes.len() >= kept
                && mesh.points()[nodes.start..nodes.start + kept] == self.mesh.points()[own.nodes.clone()];
            if !same {
                return refuse(format!(
                    "the nodes of body '{}' do not begin with this problem's: not a refinement of its mesh",
                    part.name
                ));
            }
        }
        if node0 != mesh.n_nodes() || triangle0 != mesh.n_triangles() {
            return refuse(format!(
                "the bodies cover {node0} of {} nodes and {triangle0} of {} triangles",
                mesh.n_nodes(),
                mesh.n_triangles()
            ));
        }
        Ok(())
    }

    /// Whether this problem is two bodies in contact (a primary side) rather than one against the obstacle.
    pub fn is_two_bodies(&self) -> bool {
        self.primary.is_some()
    }
}
