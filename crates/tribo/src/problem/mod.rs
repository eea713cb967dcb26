//! A contact problem: mesh, material, supports, loads, contact boundary, obstacle and multiplier mesh,
//! assembled once into everything that does not depend on γ0 or on friction; and its condensed form for
//! one γ0 ([`Condensed`]), which borrows the problem it was built from.
//!
//! The problem keeps the factorization of its last [`Problem::condense`] (one entry, keyed by γ0), so
//! solving it again with the same γ0 (another friction law, other solver settings) costs no
//! factorization: [`crate::Report::reused_factorization`] says when that happened.

pub mod bodies;
pub mod floating;
pub mod keywords;
pub mod load_case;
pub mod sides;

mod condense;
mod spec;

pub use condense::Condensed;
pub use keywords::{Bodies, ProblemKeywords};

use std::sync::OnceLock;
use std::time::Instant;

use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::SparseColMat;

use crate::contact::gamma0::{admissible_gamma0, Gamma0Bound};
use crate::contact::mortar::MortarMatrices;
use crate::contact::multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
use crate::contact::obstacle::Obstacle;
use crate::contact::operators::ContactStress;
use crate::contact::pair::PrimarySide;
use crate::contact::ContactBoundary;
use crate::error::{Error, Result};
use crate::fem::assemble::{assemble, LinearSystem};
use crate::fem::elasticity::{Material, Materials, Model, Traction};
use crate::fem::mixed::{self, Formulation};
use crate::fem::supports::{Dofs, NodeSupport, Support};
use crate::mesh::Mesh;
use condense::FactorCache;
use sides::{ContactSide, PairSpec};

/// Everything that defines a contact problem besides the mesh. [`ProblemSpec::new`] takes the two parts
/// without a default (the material and the contact edge set) and sets the others by name.
#[derive(Debug, Clone)]
pub struct ProblemSpec {
    /// Material.
    pub material: Material,
    /// Plane strain, plane stress or axisymmetry ([`Model`], plane strain by default).
    pub model: Model,
    /// P1 displacements, or displacements and pressures for ν → ½ ([`Formulation`]; by default `Auto`, the
    /// mixed one from ν = [`crate::fem::mixed::MIXED_FROM_POISSON`] in plane strain and axisymmetry). A built
    /// problem's spec holds the choice made.
    pub formulation: Formulation,
    /// Names of the clamped edge sets (u = 0): shorthand for [`Support::Clamp`] entries of `supports`.
    pub clamped: Vec<String>,
    /// Further Dirichlet conditions: rollers (symmetry lines) and prescribed displacements (see
    /// [`crate::fem::supports`]). Γ_D is the union of these and `clamped`.
    pub supports: Vec<Support>,
    /// Constant body force f (per unit area).
    pub body_force: [f64; 2],
    /// Tractions (per unit length) on named edge sets (Γ_N): constant vectors, or pressures along each edge's
    /// outward normal.
    pub tractions: Vec<(String, Traction)>,
    /// Name of the contact edge set Γ_C.
    pub contact: String,
    /// The rigid obstacle.
    pub obstacle: Obstacle,
    /// Points of the multiplier mesh T_H.
    pub multiplier_points: MultiplierPoints,
    /// Multiplier space (of every pair).
    pub multiplier_space: MultiplierSpace,
    /// Further contact pairs, each a contact edge set against its own rigid obstacle ([`sides`]); empty for
    /// one pair.
    pub pairs: Vec<sides::PairSpec>,
}

/// Timings of the set-up phases, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SetupTimings {
    /// Stiffness and load assembly (the symbolic Cholesky factorization of K's pattern is formed by the
    /// first condensation that needs it, and timed with it).
    pub assembly: f64,
    /// Contact geometry, multiplier mesh and Γ_C matrices.
    pub contact_matrices: f64,
}

impl SetupTimings {
    /// Every phase by name, in the order of the fields.
    pub fn named(&self) -> [(&'static str, f64); 2] {
        [("assembly", self.assembly), ("contact_matrices", self.contact_matrices)]
    }
}

/// An assembled contact problem (independent of γ0 and friction).
#[derive(Debug, Clone)]
pub struct Problem {
    /// The mesh.
    pub mesh: Mesh,
    /// The specification it was built from.
    pub spec: ProblemSpec,
    /// Γ_C.
    pub contact: ContactBoundary,
    /// T_H.
    pub multipliers: MultiplierMesh,
    /// The Γ_C matrices.
    pub mortar: MortarMatrices,
    /// The supports resolved on the nodes: the unknown each dof follows and the lifting ū
    /// (`u = T x + ū`, see [`crate::fem::supports`]).
    pub dofs: Dofs,
    /// Number of unknowns n.
    pub n_free: usize,
    /// Stiffness on the unknowns, `Tᵀ K T` (CSC, both triangles). Its pattern is also the pattern of
    /// the stabilized `A = K − G` (G couples the dofs of one triangle only).
    pub k_matrix: SparseColMat<usize, f64>,
    /// Symbolic Cholesky factorization of that pattern (fill-reducing ordering, elimination tree),
    /// computed by the first condensation that factorizes A by it (H by columns, or the saddle-point
    /// system's gradients; the partial factorization has its own ordering) and reused for every γ0.
    pub symbolic: OnceLock<std::sync::Arc<SymbolicCholesky<usize>>>,
    /// Load on the unknowns with the lifting through K, `Tᵀ (f − K ū)`; the part through G, which
    /// depends on γ0, is added when A is factorized ([`crate::Factor::f`]).
    pub f_free: Vec<f64>,
    /// Full load vector (all 2N dofs), for reactions.
    pub f_full: Vec<f64>,
    /// The gap `g = g₀ − δ` at the FE nodes of Γ_C (in the order of `contact.nodes`).
    pub contact_gap: Vec<f64>,
    /// σ_n(v), σ_t(v) on each contact edge as linear forms of the unknowns.
    pub contact_stress: ContactStress,
    /// Admissible bound on γ0 and the triangle that sets it (of every pair's triangles).
    pub gamma0_bound: Gamma0Bound,
    /// The further contact pairs (`spec.pairs`, [`sides`]); the fields above are the first pair's.
    pub sides: Vec<sides::ContactSide>,
    /// The material of every triangle, by region (`spec.material` everywhere for [`Problem::new`]; as given to
    /// [`Problem::with_materials`]; for two bodies the first body's materials, then the second's).
    pub materials: Materials,
    /// The plane-strain materials with their in-plane law under `spec.model` ([`Model::in_plane`]): the
    /// stiffness, the stresses and the estimates read these; `materials` themselves under plane strain.
    pub in_plane: Materials,
    /// The primary side of a two-body contact pair ([`crate::contact::pair`]); `None` against the rigid
    /// obstacle.
    pub primary: Option<PrimarySide>,
    /// The bodies: their names and where their nodes and triangles lie in `mesh` (one body, `"body"`,
    /// holding everything, for a one-body problem).
    pub bodies: Vec<bodies::BodyPart>,
    /// Set-up timings.
    pub timings: SetupTimings,
    /// The factorization of the last [`Problem::condense`].
    factor_cache: FactorCache,
}

impl Problem {
    /// Validates the specification against the mesh and assembles the problem.
    ///
    /// # Errors
    /// Any input error: material, unknown edge sets, no support, bad or conflicting supports, a piece the
    /// supports do not hold, non-finite loads, Γ_C not one chain of edges (open or closed) or overlapping Γ_D, bad
    /// obstacle, bad multiplier points.
    pub fn new(mesh: Mesh, spec: ProblemSpec) -> Result<Self> {
        let materials = Materials::uniform(spec.material, mesh.n_triangles());
        let bodies = vec![bodies::BodyPart::whole("body", &mesh)];
        Self::build(mesh, spec, materials, None, bodies)
    }

    /// [`Problem::new`] for a body of several materials (a coating on a substrate, layers, a bonded insert):
    /// triangle `t` is of `materials.materials[materials.region[t]]`. The stiffness, the stresses, the contact
    /// stresses of the stabilization and the admissible γ0 (each contact triangle's with its own material,
    /// [`crate::contact::gamma0`]) and the estimates read each triangle's material; adaptive refinement gives
    /// the halves of a triangle its material. An interface between materials should follow edges of the
    /// mesh: a triangle has one material. `spec.material` is replaced by the material under Γ_C's first edge
    /// (the contact side's, as a two-body problem's is its secondary's).
    ///
    /// # Errors
    /// [`Error::BadMaterial`] for no material, a region per triangle missing, or a region beyond the
    /// materials; each material checked under `spec.model`; as [`Problem::new`].
    pub fn with_materials(mesh: Mesh, mut spec: ProblemSpec, materials: Materials) -> Result<Self> {
        Self::check_regions(&materials, mesh.n_triangles())?;
        let regions = &materials.region;
        if let Some(&[a, b]) = mesh.edge_set(&spec.contact).ok().and_then(|edges| edges.first()) {
            if let Some(t) = mesh.boundary_triangle(a, b) {
                spec.material = materials.materials[regions[t]];
            }
        }
        let bodies = vec![bodies::BodyPart::whole("body", &mesh)];
        Self::build(mesh, spec, materials, None, bodies)
    }

    /// That `materials` has a material and a region in range for each of `n_triangles` triangles.
    ///
    /// # Errors
    /// [`Error::BadMaterial`] saying which fails.
    pub(crate) fn check_regions(materials: &Materials, n_triangles: usize) -> Result<()> {
        let (n, regions) = (materials.materials.len(), &materials.region);
        let refuse = |what: String| Err(Error::BadMaterial { what });
        if n == 0 {
            return refuse("a body of several materials needs at least one material".to_string());
        }
        if regions.len() != n_triangles {
            return refuse(format!("{} regions given for {n_triangles} triangles (one per triangle)", regions.len()));
        }
        if let Some((t, r)) = regions.iter().enumerate().find(|(_, &r)| r >= n) {
            return refuse(format!("triangle {t} is of region {r}, beyond the {n} materials given"));
        }
        Ok(())
    }

    /// [`Problem::new`] with per-triangle materials and, for two bodies, the primary contact set.
    fn build(
        mesh: Mesh,
        mut spec: ProblemSpec,
        materials: Materials,
        primary: Option<&str>,
        bodies: Vec<bodies::BodyPart>,
    ) -> Result<Self> {
        let clock = Instant::now();
        for m in &materials.materials {
            spec.model.validate(m)?;
        }
        spec.model.validate(&spec.material)?;
        let in_plane = spec.model.in_plane_all(&materials);
        spec.formulation = spec.formulation.resolve(spec.model, &in_plane);
        spec.formulation.validate(&in_plane)?;
        let mixed = spec.formulation.is_mixed();
        // The mixed formulation's K_μ, contact stresses and γ0 bound read the shear part of each law.
        let shear_of_mixed = mixed.then(|| mixed::shear_part_all(&in_plane));
        let shear = shear_of_mixed.as_ref().unwrap_or(&in_plane);
        spec.obstacle.validate()?;
        // A piece that holds a node of a contact side may be held by the contact alone.
        let mut on_contact = vec![false; mesh.n_nodes()];
        for set in
            std::iter::once(spec.contact.as_str()).chain(primary).chain(spec.pairs.iter().map(|p| p.contact.as_str()))
        {
            for &[a, b] in mesh.edge_set(set)? {
                on_contact[a] = true;
                on_contact[b] = true;
            }
        }
        let dofs = Dofs::held_by_contact(&mesh, &spec.all_supports(None), &|i| on_contact[i], spec.model)?;
        let mut bodies = bodies;
        for part in &mut bodies {
            let count = |n: &NodeSupport| match n {
                NodeSupport::Free => 2,
                NodeSupport::Slide { .. } => 1,
                NodeSupport::Fixed { .. } => 0,
            };
            part.unknowns = dofs.nodes[part.nodes.clone()].iter().map(count).sum();
        }
        let mut system = assemble(spec.model, &mesh, shear, spec.body_force, &spec.tractions, &dofs)?;
        let dofs = if mixed { dofs.with_pressure(mesh.n_nodes()) } else { dofs };
        if mixed {
            system = mixed::assemble_mixed(spec.model, &mesh, &in_plane, spec.body_force, system, &dofs)?;
        }
        let (n_free, LinearSystem { k_matrix, f_free, f_full }) = (dofs.n_free, system);
        let assembly = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        // The first pair is built as every pair is (`sides.rs`); the problem keeps its parts in its own fields.
        let first = PairSpec {
            contact: spec.contact.clone(),
            obstacle: spec.obstacle.clone(),
            multiplier_points: spec.multiplier_points.clone(),
            mu: None,
        };
        let ContactSide { contact, multipliers, mut mortar, gap: mut contact_gap, stress: contact_stress, .. } =
            ContactSide::new(&mesh, spec.model, shear, mixed, &dofs, &first, spec.multiplier_space)?;
        let contact_edges: std::collections::HashSet<[usize; 2]> =
            contact.edges.iter().map(|e| [e.left.min(e.right), e.left.max(e.right)]).collect();
        let primary_edges: std::collections::HashSet<[usize; 2]> = match primary {
            Some(set) => mesh.edge_set(set)?.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect(),
            None => Default::default(),
        };
        for (traction_set, _) in &spec.tractions {
            for &[a, b] in mesh.edge_set(traction_set)? {
                let key = [a.min(b), a.max(b)];
                if contact_edges.contains(&key) || primary_edges.contains(&key) {
                    return Err(Error::TractionOnContact {
                        set: if contact_edges.contains(&key) {
                            spec.contact.clone()
                        } else {
                            primary.unwrap_or("").to_string()
                        },
                        traction_set: traction_set.clone(),
                        a,
                        b,
                    });
                }
            }
        }
        let primary =
            primary.map(|set| PrimarySide::new(&mesh, &contact, set, &multipliers, spec.model)).transpose()?;
        // A bent pair's gap from the geometry adds to the pair's gap shape.
        if let Some(geometry) = primary.as_ref().and_then(|p| p.geometry.as_ref()) {
            mortar.gap_moments.iter_mut().zip(&geometry.gap_moments).for_each(|(m, g)| *m += g);
            contact_gap.iter_mut().zip(&geometry.node_gap).for_each(|(m, g)| *m += g);
        }
        let gamma0_bound = admissible_gamma0(&mesh, spec.model, shear, &contact);
        let shear_for_sides = shear.clone();
        let contact_matrices = clock.elapsed().as_secs_f64();
        let mut problem = Self {
            mesh,
            spec,
            contact,
            multipliers,
            mortar,
            dofs,
            n_free,
            k_matrix,
            symbolic: OnceLock::new(),
            f_free,
            f_full,
            contact_gap,
            contact_stress,
            gamma0_bound,
            sides: Vec::new(),
            materials,
            in_plane,
            primary,
            bodies,
            timings: SetupTimings { assembly, contact_matrices },
            factor_cache: FactorCache::default(),
        };
        let clock = Instant::now();
        problem.build_sides(&shear_for_sides)?;
        problem.timings.contact_matrices += clock.elapsed().as_secs_f64();
        if problem.spec.obstacle.shift != 0.0 {
            problem.check_axisymmetric_shift()?;
        }
        if problem.spec.obstacle.rotation.is_some() {
            problem.check_rotation()?;
        }
        Ok(problem)
    }

    /// The most unknowns per node: 2 displacements, and a pressure in the mixed formulation.
    pub(crate) fn unknowns_per_node(&self) -> usize {
        2 + usize::from(self.spec.formulation.is_mixed())
    }

    /// The unknowns of a displacement `v` (2N, `Tᵀ v`) and, in the mixed formulation, the nodal `pressure`.
    pub(crate) fn unknowns_of(&self, v: &[f64], pressure: &[f64]) -> Vec<f64> {
        let mut x = self.dofs.restrict(v);
        x[self.dofs.n_displacement..].iter_mut().zip(pressure).for_each(|(x, p)| *x = *p);
        x
    }

    /// The load on the unknowns without the lifting, `Tᵀ f`, and in the mixed formulation the pressure rows'
    /// part of the body force ([`mixed::bubble_load`]): what a load factor scales.
    pub(crate) fn load_on_unknowns(&self) -> Vec<f64> {
        let mut load = self.dofs.restrict(&self.f_full);
        if self.spec.formulation.is_mixed() {
            let bubble = mixed::bubble_load(self.spec.model, &self.mesh, &self.in_plane, self.spec.body_force);
            load[self.dofs.n_displacement..].iter_mut().zip(bubble).for_each(|(l, b)| *l += b);
        }
        load
    }

    /// A turned obstacle needs a rigid obstacle in the plane (not two bodies, not a solid of revolution).
    ///
    /// # Errors
    /// [`Error::BadObstacle`] for two bodies, [`Error::BadAxisymmetry`] in axisymmetry.
    fn check_rotation(&self) -> Result<()> {
        if self.spec.model.is_axisymmetric() {
            return Err(Error::BadAxisymmetry {
                what: "the obstacle turns: a body of revolution has no rigid rotation in its meridian plane".into(),
            });
        }
        if self.primary.is_some() {
            return Err(Error::BadObstacle { what: "two bodies have no rigid obstacle to turn".into() });
        }
        Ok(())
    }

    /// In axisymmetry the obstacle, a solid of revolution, may shift along the axis only: a shift along a
    /// tangent with a radial component (on an edge of Γ_C that is not parallel to the axis) would move it
    /// radially, which no rigid body of revolution does.
    ///
    /// # Errors
    /// [`Error::BadAxisymmetry`] naming the first such edge.
    pub fn check_axisymmetric_shift(&self) -> Result<()> {
        if !self.spec.model.is_axisymmetric() {
            return Ok(());
        }
        let tol = crate::mesh::line::geometric_tol_rel();
        match self.contact.edges.iter().find(|e| e.tangent[0].abs() > tol) {
            None => Ok(()),
            Some(e) => Err(Error::BadAxisymmetry {
                what: format!(
                    "the obstacle shifts along the tangent ({:.4}, {:.4}) of the contact edge ({}, {}), which has a radial component: a body of revolution can only slide along its axis (y); shift it on a contact side parallel to the axis, or not at all",
                    e.tangent[0], e.tangent[1], e.left, e.right
                ),
            }),
        }
    }

    /// `d = (∫ψ_j g, ∫ψ_j s)` (2q): the obstacle's gap and tangential shift tested with the multiplier
    /// basis, the part of the QP's linear term that the obstacle contributes (see [`crate::contact::obstacle`]).
    pub fn obstacle_moments(&self) -> Vec<f64> {
        let per_pair = self.pairs().into_iter().map(|p| {
            let shift = p.obstacle.shift;
            let tangential: Vec<f64> = if p.mortar.shift_moments.is_empty() {
                p.mortar.psi_integrals.iter().map(|w| w * shift).collect()
            } else {
                p.mortar.shift_moments.clone()
            };
            p.mortar.gap_moments.iter().copied().chain(tangential).collect()
        });
        sides::stack(per_pair.collect())
    }

    /// Where the placed `obstacle` moves along Γ_C at each of its FE nodes, along the node's tangent: the shift s,
    /// or where it turns, `s + w(y) · t` ([`Obstacle::tangential_motion`]).
    pub fn slip_origin_of(&self, obstacle: &Obstacle) -> Vec<f64> {
        slip_origin_on(&self.contact, obstacle)
    }

    /// Number of multiplier dofs q (per component).
    pub fn n_multipliers(&self) -> usize {
        self.multipliers.n_dofs() + self.sides.iter().map(|s| s.multipliers.n_dofs()).sum::<usize>()
    }

    /// The displacement on all 2N dofs from the unknowns: `u = T x + ū` (prescribed values included).
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        self.dofs.expand(x)
    }

    /// The displacement that the contact law reads at the `i`-th FE node of Γ_C, from the nodal
    /// displacement `u` (all 2N dofs): `u¹` against the rigid obstacle, the jump `u¹ − u²∘Π` between two
    /// bodies ([`crate::contact::pair`]).
    pub fn contact_displacement(&self, i: usize, u: &[f64]) -> [f64; 2] {
        let node = self.contact.nodes[i];
        let own = [u[2 * node], u[2 * node + 1]];
        match &self.primary {
            None => own,
            Some(p) => {
                let other = p.displacement_at(self.contact.node_xi[i], u);
                [own[0] - other[0], own[1] - other[1]]
            }
        }
    }
}

impl ProblemSpec {
    /// Every support: the clamped sets, then `supports`, with the prescribed values replaced by `values`
    /// (in the order of [`ProblemSpec::prescribed_components`]) when given.
    pub fn all_supports(&self, values: Option<&[f64]>) -> Vec<Support> {
        let mut values = values.map(|v| v.iter());
        let mut next = |v: Option<f64>| v.map(|v| values.as_mut().and_then(Iterator::next).copied().unwrap_or(v));
        let clamps = self.clamped.iter().map(|set| Support::clamp(set.as_str()));
        let others = self.supports.iter().map(|s| match s {
            Support::Displacement { set, x, y } => {
                let x = next(*x);
                Support::Displacement { set: set.clone(), x, y: next(*y) }
            }
            other => other.clone(),
        });
        clamps.chain(others.collect::<Vec<_>>()).collect()
    }

    /// The prescribed displacement components a loading history may move ([`crate::LoadStep::displacements`]):
    /// `"set.x"` and `"set.y"` of every [`Support::Displacement`] that gives them, in order, with their
    /// values in this specification.
    pub fn prescribed_components(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        for s in &self.supports {
            if let Support::Displacement { set, x, y } = s {
                out.extend(x.map(|v| (format!("{set}.x"), v)));
                out.extend(y.map(|v| (format!("{set}.y"), v)));
            }
        }
        out
    }

    /// The defaults of the keywords a problem is built from, besides the required ones, as the Python
    /// binding and the scene files name them: the multiplier points (`multiplier_ratio`, or
    /// `multiplier_size`; see [`MultiplierPoints::from_keywords`]), the multiplier `space`, the `model` and the
    /// `formulation`.
    pub fn keyword_defaults() -> Vec<(&'static str, crate::settings::SettingValue)> {
        use crate::choice::Choice;
        use crate::settings::SettingValue;
        let points = match MultiplierPoints::default() {
            MultiplierPoints::RatioToFe(r) => Some(("multiplier_ratio", SettingValue::Float(r))),
            MultiplierPoints::Size(h) => Some(("multiplier_size", SettingValue::Float(h))),
            MultiplierPoints::Abscissae(_) | MultiplierPoints::Points(_) => None,
        };
        let space = ("space", SettingValue::Name(MultiplierSpace::default().as_str().to_string()));
        let model = ("model", SettingValue::Name(Model::default().as_str().to_string()));
        let formulation = ("formulation", SettingValue::Name(Formulation::default().as_str().to_string()));
        points.into_iter().chain([space, model, formulation]).collect()
    }
}

/// Where the placed `obstacle` ([`Obstacle::placed`]) moves along the contact side `c` at each of its FE
/// nodes, along the node's tangent: the shift s, or where it turns, `s + w(y) · t` ([`Obstacle::tangential_motion`]).
pub(crate) fn slip_origin_on(c: &ContactBoundary, obstacle: &Obstacle) -> Vec<f64> {
    if obstacle.rotation.is_none() {
        return vec![obstacle.shift; c.nodes.len()];
    }
    (0..c.nodes.len())
        .map(|k| {
            let length = c.edges[k.min(c.edges.len() - 1)].length;
            obstacle.tangential_motion(c.surface_point(c.node_xi[k]), c.node_tangent(k), length)
        })
        .collect()
}
