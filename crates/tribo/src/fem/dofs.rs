//! The unknowns the supports leave: the map from the 2N nodal dofs to the unknowns and the lifting ū of
//! the prescribed displacements ([`Dofs`]).
//!
//! # Unknowns: a change of basis, then a lifting
//! Every nodal displacement is written `u_i = T_i x_i + ū_i`:
//! * free node: `T_i = I` (two unknowns, the x and y components), `ū_i = 0`;
//! * sliding node: `T_i = t` (one unknown, the tangential component w), `ū_i = v a`;
//! * fixed node: no unknown, `ū_i` the prescribed displacement.
//!
//! So `u = T x + ū` with T (2N × n) having at most one non-zero per row: each global dof follows at most
//! one unknown, with a coefficient ([`Dofs::unknown`]). For a free node or an axis-aligned roller T is a
//! selection, as the clamped-only code had; a rotated roller's node has one unknown along its tangent, no
//! penalty and no extra multiplier. Every operator is assembled over the 2N dofs and restricted with T:
//! the stiffness `Tᵀ K T` keeps the sparsity of K restricted to the nodes that have unknowns (so its
//! symbolic Cholesky analysis is done once, as before), `−G` becomes `Tᵀ(−G)T` and the rows of E become
//! `E T` (a rotated node's two coefficients merge into one).
//!
//! # How a prescribed displacement enters the condensed problem
//! With `A = K − G` and E over all 2N dofs, the stabilized problem in the unknowns x, for test functions
//! that vanish on Γ_D (`v = T y`), is
//!
//! ```text
//! Tᵀ A T x + Tᵀ Eᵀ λ = Tᵀ f − Tᵀ A ū                       (equilibrium)
//! H λ + c = d − E (T x + ū) + Dγ λ                         (the complementarity quantities of the QP)
//! ```
//!
//! so with `Ã = Tᵀ A T`, `Ẽ = E T`, the lifted load `f̃ = Tᵀ (f − K ū) + Tᵀ G ū` and the lifted obstacle
//! moments `d̃ = d − E ū`, the condensation is the clamped one with `(f, d)` replaced by `(f̃, d̃)`:
//! `x = Ã⁻¹ (f̃ − Ẽᵀ λ)`, `H = Ẽ Ã⁻¹ Ẽᵀ + Dγ`, `c = d̃ − Ẽ Ã⁻¹ f̃`. Both G and E (its stabilization
//! part `−γ0 Cγ S`, the stress of the contact triangles) depend on γ0 and touch the dofs of a contact
//! triangle, some of which may be prescribed: so `Tᵀ G ū` and `E ū` are formed per γ0, when A is
//! factorized ([`crate::Problem::condense_with`]); `Tᵀ K ū` once, in [`crate::Problem::new`]
//! (`Problem::f_free`). The displacement is `T x + ū` ([`crate::Problem::expand`]) and the reactions
//! `(K − G) u − f + Eᵀ λ` on every constrained dof (their component along a roller's normal at a sliding node;
//! [`crate::Solution::reactions`]).
//!

use std::collections::HashSet;

use crate::error::{Error, Result};
use crate::fem::axisymmetric::axis_nodes;
use crate::fem::elasticity::Model;
use crate::fem::rigid_motions::{check_held, pins, FreeMotions};
use crate::fem::supports::{node_supports, slide, NodeSupport, Support};
use crate::mesh::Mesh;

/// The supports resolved on the nodes: which unknown each dof follows, and the lifting ū.
#[derive(Debug, Clone)]
pub struct Dofs {
    /// Per node, what the supports leave free.
    pub nodes: Vec<NodeSupport>,
    /// Per dof (2N, interleaved): the unknown it follows and the coefficient, `u_d = coeff · x_k + ū_d`.
    map: Vec<Option<(usize, f64)>>,
    /// Number of unknowns n (displacements, then the pressures of [`Dofs::with_pressure`]).
    pub n_free: usize,
    /// Number of displacement unknowns (n without the pressures).
    pub n_displacement: usize,
    /// The lifting ū (2N): the prescribed part of every dof.
    pub lifting: Vec<f64>,
    /// Edges (sorted node pairs) that carry a support, for the checks against Γ_C.
    pub edges: HashSet<[usize; 2]>,
    /// The pieces held only by the contact: their free rigid motions (`fem/rigid_motions.rs`).
    pub floating: Vec<FreeMotions>,
    /// The pins that hold those motions in the factorized stiffness: per pinned node, its support with
    /// the pins (`u · a = 0` along each pinned direction a), which [`Dofs::lifting_of`] keeps too.
    pub pins: Vec<(usize, NodeSupport)>,
    /// The nodes on the axis of an axisymmetric body, held at `u_r = 0` (empty in a plane model).
    pub axis: Vec<usize>,
}

impl Dofs {
    /// Resolves `supports` on `mesh`.
    ///
    /// # Errors
    /// [`Error::NoDirichlet`] for no support; [`Error::UnknownEdgeSet`]; [`Error::BadSupport`] for a
    /// non-finite or missing prescribed value; [`Error::SupportNotStraight`] for a roller on a set that is
    /// not straight; [`Error::ConflictingSupports`]; [`Error::NearlyParallelSupports`];
    /// [`Error::FloatingPiece`] / [`Error::RigidMotion`]
    /// for a piece that the supports do not hold.
    pub fn new(mesh: &Mesh, supports: &[Support]) -> Result<Self> {
        Self::held_by_contact(mesh, supports, &|_| false, Model::PlaneStrain)
    }

    /// [`Dofs::new`], where a piece that holds a node for which `may_float` is true (a node of a contact
    /// side) may be left free by its supports: its free rigid motions are kept in `floating` and held in
    /// the stiffness by pins (`pins`), chosen off the contact sides (see `fem/rigid_motions.rs`).
    ///
    /// Under [`Model::Axisymmetric`] the nodes on the axis get `u_r = 0` besides their supports, and only the
    /// axial translation is a rigid motion ([`crate::fem::axisymmetric`]).
    ///
    /// # Errors
    /// As [`Dofs::new`]; [`Error::NoDirichlet`] only when no node may float either;
    /// [`Error::BadAxisymmetry`] for an axisymmetric mesh with a node at r < 0.
    pub fn held_by_contact(
        mesh: &Mesh,
        supports: &[Support],
        may_float: &dyn Fn(usize) -> bool,
        model: Model,
    ) -> Result<Self> {
        let n_nodes = mesh.n_nodes();
        let axis = if model.is_axisymmetric() { axis_nodes(mesh)? } else { Vec::new() };
        if supports.is_empty() && !(0..n_nodes).any(may_float) {
            return Err(Error::NoDirichlet);
        }
        let (mut nodes, edges) = node_supports(mesh, supports, &axis)?;
        let floating = check_held(mesh, &nodes, may_float, model.is_axisymmetric())?;
        let mut pinned: Vec<(usize, NodeSupport)> = Vec::new();
        for piece in &floating {
            let chosen = pins(mesh, &nodes, piece, may_float);
            if chosen.len() < piece.motions.len() {
                // Fewer free directions than free motions (a piece of one or two nodes' worth): unpinnable.
                let node = piece.nodes[0];
                let motion = piece.describe(chosen.len());
                return Err(Error::RigidMotion { triangle: piece.triangle, node, triangles: 0, pieces: 0, motion });
            }
            for (node, a) in chosen {
                nodes[node] = pin(nodes[node], a);
                match pinned.iter_mut().find(|(i, _)| *i == node) {
                    Some(entry) => entry.1 = nodes[node],
                    None => pinned.push((node, nodes[node])),
                }
            }
        }
        let mut map = vec![None; 2 * n_nodes];
        let mut n_free = 0;
        for (i, ns) in nodes.iter().enumerate() {
            match *ns {
                NodeSupport::Free => {
                    map[2 * i] = Some((n_free, 1.0));
                    map[2 * i + 1] = Some((n_free + 1, 1.0));
                    n_free += 2;
                }
                NodeSupport::Slide { tangent, .. } => {
                    for c in 0..2 {
                        // An axis-aligned roller leaves one dof untouched by the unknown: no entry.
                        map[2 * i + c] = (tangent[c] != 0.0).then_some((n_free, tangent[c]));
                    }
                    n_free += 1;
                }
                NodeSupport::Fixed { .. } => {}
            }
        }
        let lifting = lifting(&nodes);
        Ok(Self { nodes, map, n_free, n_displacement: n_free, lifting, edges, floating, pins: pinned, axis })
    }

    /// The number of free rigid motions the contact must hold.
    pub fn n_floating(&self) -> usize {
        self.floating.iter().map(|p| p.motions.len()).sum()
    }

    /// Each free rigid motion as a displacement of all 2N dofs (zero off its piece).
    pub fn rigid_fields(&self, mesh: &Mesh) -> Vec<Vec<f64>> {
        let mut out = Vec::new();
        for piece in &self.floating {
            for k in 0..piece.motions.len() {
                let mut field = vec![0.0; 2 * mesh.n_nodes()];
                for &i in &piece.nodes {
                    let u = piece.at(k, mesh.points()[i]);
                    field[2 * i] = u[0];
                    field[2 * i + 1] = u[1];
                }
                out.push(field);
            }
        }
        out
    }

    /// The lifting ū (2N) of `supports`, the supports these dofs were resolved from with other prescribed
    /// values (a step of a loading history that moves them).
    ///
    /// # Errors
    /// [`Error::BadSupport`] for a non-finite value; [`Error::ConflictingSupports`] where the new values
    /// disagree at a node that several supports reach; [`Error::NearlyParallelSupports`] where they move
    /// a node held by nearly parallel conditions beyond the body's size; [`Error::BadSupport`] if the supports do not leave
    /// the same unknowns as these dofs (they must differ only in their values).
    pub fn lifting_of(&self, mesh: &Mesh, supports: &[Support]) -> Result<Vec<f64>> {
        let (mut nodes, _) = node_supports(mesh, supports, &self.axis)?;
        for &(node, pinned) in &self.pins {
            nodes[node] = keep_value(pinned, nodes[node]);
        }
        let same_kind = |a: &NodeSupport, b: &NodeSupport| match (a, b) {
            (NodeSupport::Slide { normal: n, .. }, NodeSupport::Slide { normal: m, .. }) => n == m,
            _ => std::mem::discriminant(a) == std::mem::discriminant(b),
        };
        if let Some(node) = nodes.iter().zip(&self.nodes).position(|(a, b)| !same_kind(a, b)) {
            let set = supports.first().map_or("", |s| s.set()).to_string();
            return Err(Error::BadSupport {
                set,
                what: format!("the supports leave other unknowns at node {node} than those the problem was built with"),
            });
        }
        Ok(lifting(&nodes))
    }

    /// The unknown that dof `d` follows and its coefficient (`u_d = coeff · x_k + ū_d`), or `None` for
    /// a prescribed dof.
    pub fn unknown(&self, d: usize) -> Option<(usize, f64)> {
        self.map[d]
    }

    /// These unknowns with one pressure per node after the displacements (the mixed formulation,
    /// [`crate::fem::mixed`]): node i's pressure is dof `2N + i` of [`Dofs::unknown`] and unknown
    /// `n_displacement + i`. [`Dofs::expand`] still gives the 2N displacements; [`Dofs::restrict`] of a
    /// vector of 3N dofs gives all n unknowns.
    pub fn with_pressure(mut self, n_nodes: usize) -> Self {
        let first = self.n_displacement;
        self.map.truncate(2 * n_nodes);
        self.map.extend((0..n_nodes).map(|i| Some((first + i, 1.0))));
        self.n_free = first + n_nodes;
        self
    }

    /// The pressure unknowns' part of x (empty without them).
    pub fn pressure<'a>(&self, x: &'a [f64]) -> &'a [f64] {
        x.get(self.n_displacement..self.n_free).unwrap_or(&[])
    }

    /// True when no support prescribes a non-zero displacement.
    pub fn homogeneous(&self) -> bool {
        self.lifting.iter().all(|v| *v == 0.0)
    }

    /// `u = T x + ū` (all 2N dofs) from the unknowns x.
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        self.expand_with(x, &self.lifting)
    }

    /// `u = T x + ū` (all 2N dofs) from the unknowns x and another lifting ū (of [`Dofs::lifting_of`]).
    pub fn expand_with(&self, x: &[f64], lifting: &[f64]) -> Vec<f64> {
        self.map.iter().zip(lifting).map(|(m, l)| m.map_or(0.0, |(k, a)| a * x[k]) + l).collect()
    }

    /// `Tᵀ v` (n) for a vector v over all 2N dofs.
    pub fn restrict(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_free];
        for (m, vd) in self.map.iter().zip(v) {
            if let Some((k, a)) = m {
                out[*k] += a * vd;
            }
        }
        out
    }

    /// Sparse rows over all 2N dofs as rows over the unknowns (`row · T`), sorted with duplicates summed.
    pub fn restrict_rows(&self, rows: &[Vec<(usize, f64)>]) -> Vec<Vec<(usize, f64)>> {
        rows.iter()
            .map(|row| {
                let mut r: Vec<(usize, f64)> =
                    row.iter().filter_map(|&(d, v)| self.map[d].map(|(k, a)| (k, a * v))).collect();
                r.sort_by_key(|e| e.0);
                let mut out: Vec<(usize, f64)> = Vec::with_capacity(r.len());
                for (k, v) in r {
                    match out.last_mut() {
                        Some(l) if l.0 == k => l.1 += v,
                        _ => out.push((k, v)),
                    }
                }
                out
            })
            .collect()
    }

    /// Keeps the part of the nodal forces `r` (2N) that the supports take: all of it at a fixed node, the
    /// component along the condition at a sliding node, nothing at a free node.
    pub fn keep_reactions(&self, r: &mut [f64]) {
        for (i, ns) in self.nodes.iter().enumerate() {
            match *ns {
                NodeSupport::Free => {
                    r[2 * i] = 0.0;
                    r[2 * i + 1] = 0.0;
                }
                NodeSupport::Slide { normal, .. } => {
                    let rn = r[2 * i] * normal[0] + r[2 * i + 1] * normal[1];
                    r[2 * i] = rn * normal[0];
                    r[2 * i + 1] = rn * normal[1];
                }
                NodeSupport::Fixed { .. } => {}
            }
        }
    }
}

/// A node's support with the pin `u · a = 0` added (a a direction its support leaves free, a unit vector).
fn pin(support: NodeSupport, a: [f64; 2]) -> NodeSupport {
    match support {
        NodeSupport::Free => slide(a, 0.0),
        NodeSupport::Slide { normal, value, .. } => {
            NodeSupport::Fixed { value: [value * normal[0], value * normal[1]] }
        }
        fixed @ NodeSupport::Fixed { .. } => fixed,
    }
}

/// The pinned support `pinned` of a node with the prescribed values of `support`, the node's support of
/// other prescribed values (a history's step): a pin only adds `u · a = 0`.
fn keep_value(pinned: NodeSupport, support: NodeSupport) -> NodeSupport {
    match (pinned, support) {
        (NodeSupport::Fixed { .. }, NodeSupport::Slide { normal, value, .. }) => {
            NodeSupport::Fixed { value: [value * normal[0], value * normal[1]] }
        }
        (pinned, _) => pinned,
    }
}

/// The lifting ū (2N) of resolved node supports: the prescribed part of every dof.
fn lifting(nodes: &[NodeSupport]) -> Vec<f64> {
    let mut lifting = vec![0.0; 2 * nodes.len()];
    for (i, ns) in nodes.iter().enumerate() {
        match *ns {
            NodeSupport::Free => {}
            NodeSupport::Slide { normal, value, .. } => {
                lifting[2 * i] = value * normal[0];
                lifting[2 * i + 1] = value * normal[1];
            }
            NodeSupport::Fixed { value } => lifting[2 * i..2 * i + 2].copy_from_slice(&value),
        }
    }
    lifting
}
