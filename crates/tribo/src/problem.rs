//! A contact problem: mesh, material, supports, loads, contact boundary, obstacle and multiplier mesh,
//! assembled once into everything that does not depend on γ0 or on friction.

use std::time::Instant;

use faer::sparse::linalg::solvers::SymbolicLlt;
use faer::sparse::{SparseColMat, Triplet};
use faer::Side;
use nalgebra::SVector;

use crate::contact::ContactBoundary;
use crate::elasticity::{body_force_vector, element_dofs, stiffness_triplets, traction_vector, Material};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::mortar::MortarMatrices;
use crate::multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
use crate::obstacle::Obstacle;
use crate::stabilization::{admissible_gamma0, stress_operators};

/// Everything that defines a contact problem besides the mesh.
#[derive(Debug, Clone)]
pub struct ProblemSpec {
    /// Material.
    pub material: Material,
    /// Names of the clamped edge sets (Γ_D, u = 0).
    pub clamped: Vec<String>,
    /// Constant body force f (per unit area).
    pub body_force: [f64; 2],
    /// Constant tractions (per unit length) on named edge sets (Γ_N).
    pub tractions: Vec<(String, [f64; 2])>,
    /// Name of the contact edge set Γ_C.
    pub contact: String,
    /// The rigid obstacle.
    pub obstacle: Obstacle,
    /// Points of the multiplier mesh T_H.
    pub multiplier_points: MultiplierPoints,
    /// Multiplier space.
    pub multiplier_space: MultiplierSpace,
}

/// Timings of the set-up phases, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SetupTimings {
    /// Stiffness and load assembly, and the symbolic Cholesky factorization of K's pattern.
    pub assembly: f64,
    /// Contact geometry, multiplier mesh and Γ_C matrices.
    pub contact_matrices: f64,
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
    /// `free[dof]` = index among the unknowns, or `None` for a clamped dof.
    pub free: Vec<Option<usize>>,
    /// Number of unknowns (free dofs).
    pub n_free: usize,
    /// Stiffness K restricted to the free dofs (CSC, both triangles). Its pattern is also the pattern of
    /// the stabilized `A = K − G` (G couples the dofs of one triangle only).
    pub k_matrix: SparseColMat<usize, f64>,
    /// Symbolic Cholesky factorization of that pattern (fill-reducing ordering, elimination tree),
    /// computed once and reused for every γ0.
    pub symbolic: SymbolicLlt<usize>,
    /// Load vector on free dofs.
    pub f_free: Vec<f64>,
    /// Full load vector (all 2N dofs), for reactions.
    pub f_full: Vec<f64>,
    /// Per contact edge: σ_n, σ_t as 6-vectors over the owning triangle's dofs.
    pub stress_ops: Vec<[SVector<f64, 6>; 2]>,
    /// Diameter h_T of the triangle owning each contact edge.
    pub h_t: Vec<f64>,
    /// Admissible bound on γ0 and the triangle that sets it.
    pub gamma0_bound: (f64, usize),
    /// Set-up timings.
    pub timings: SetupTimings,
}

impl Problem {
    /// Validates the specification against the mesh and assembles the problem.
    ///
    /// # Errors
    /// Any input error: material, unknown edge sets, no clamped set, non-finite loads, Γ_C not straight
    /// or not connected or overlapping Γ_D, bad obstacle, bad multiplier points.
    pub fn new(mesh: Mesh, spec: ProblemSpec) -> Result<Self> {
        let clock = Instant::now();
        spec.material.validate()?;
        spec.obstacle.validate()?;
        if spec.clamped.is_empty() {
            return Err(Error::NoDirichlet);
        }
        let n_dofs = 2 * mesh.n_nodes();
        let mut free = vec![Some(0); n_dofs];
        let mut clamped_edges = std::collections::HashSet::new();
        for set in &spec.clamped {
            for &[a, b] in mesh.edge_set(set)? {
                clamped_edges.insert([a.min(b), a.max(b)]);
                for node in [a, b] {
                    free[2 * node] = None;
                    free[2 * node + 1] = None;
                }
            }
        }
        let mut n_free = 0;
        for slot in free.iter_mut().filter(|s| s.is_some()) {
            *slot = Some(n_free);
            n_free += 1;
        }
        for (name, f) in [("body".to_string(), spec.body_force)].iter().chain(&spec.tractions) {
            if !(f[0].is_finite() && f[1].is_finite()) {
                return Err(Error::NonFiniteLoad { target: name.clone(), x: f[0], y: f[1] });
            }
        }
        let mut f_full = vec![0.0; n_dofs];
        body_force_vector(&mesh, spec.body_force, &mut f_full);
        for (set, g) in &spec.tractions {
            traction_vector(&mesh, mesh.edge_set(set)?, *g, &mut f_full);
        }
        let f_free = restrict(&free, &f_full, n_free);
        let k_free: Vec<_> = stiffness_triplets(&mesh, &spec.material)
            .into_iter()
            .filter_map(|t| Some(Triplet::new(free[t.row]?, free[t.col]?, t.val)))
            .collect();
        let k_matrix = SparseColMat::try_new_from_triplets(n_free, n_free, &k_free)
            .map_err(|e| Error::NotPositiveDefinite { what: format!("assembly failed: {e:?}") })?;
        drop(k_free);
        let symbolic = SymbolicLlt::try_new(k_matrix.symbolic(), Side::Lower)
            .map_err(|e| Error::NotPositiveDefinite { what: format!("symbolic factorization failed: {e:?}") })?;
        let assembly = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        let contact = ContactBoundary::new(&mesh, &spec.contact)?;
        let contact_edges: std::collections::HashSet<[usize; 2]> =
            contact.edges.iter().map(|e| [e.left.min(e.right), e.left.max(e.right)]).collect();
        for e in &contact.edges {
            if clamped_edges.contains(&[e.left.min(e.right), e.left.max(e.right)]) {
                return Err(Error::ContactOverlapsDirichlet { set: spec.contact.clone(), a: e.left, b: e.right });
            }
        }
        for (traction_set, _) in &spec.tractions {
            for &[a, b] in mesh.edge_set(traction_set)? {
                if contact_edges.contains(&[a.min(b), a.max(b)]) {
                    return Err(Error::TractionOnContact {
                        set: spec.contact.clone(),
                        traction_set: traction_set.clone(),
                        a,
                        b,
                    });
                }
            }
        }
        let multipliers = MultiplierMesh::new(&contact, &spec.multiplier_points, spec.multiplier_space)?;
        let h_t: Vec<f64> = contact.edges.iter().map(|e| mesh.diameter(e.triangle)).collect();
        let mortar = MortarMatrices::new(&contact, &multipliers, &h_t, &spec.obstacle)?;
        let stress_ops = stress_operators(&mesh, &spec.material, &contact);
        let (bound, edge) = admissible_gamma0(&mesh, &spec.material, &contact);
        let gamma0_bound = (bound, contact.edges[edge].triangle);
        let contact_matrices = clock.elapsed().as_secs_f64();
        Ok(Self {
            mesh,
            spec,
            contact,
            multipliers,
            mortar,
            free,
            n_free,
            k_matrix,
            symbolic,
            f_free,
            f_full,
            stress_ops,
            h_t,
            gamma0_bound,
            timings: SetupTimings { assembly, contact_matrices },
        })
    }

    /// Number of multiplier dofs q (per component).
    pub fn n_multipliers(&self) -> usize {
        self.multipliers.n_dofs()
    }

    /// Free-dof indices of the owning triangle of contact edge `k` (`None` for clamped dofs).
    pub fn edge_triangle_dofs(&self, k: usize) -> [Option<usize>; 6] {
        let tri = &self.mesh.triangles()[self.contact.edges[k].triangle];
        element_dofs(tri).map(|d| self.free[d])
    }

    /// Expands a vector of free dofs to all 2N dofs (zeros on clamped dofs).
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        self.free.iter().map(|s| s.map_or(0.0, |i| x[i])).collect()
    }

    /// Rows of the coupling `E = B − γ0 Cγ S` over free dofs: `2q` sparse rows, normal then tangential.
    pub fn coupling_rows(&self, gamma0: f64) -> Vec<Vec<(usize, f64)>> {
        let q = self.n_multipliers();
        let (n, t) = (self.contact.normal, self.contact.tangent);
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); 2 * q];
        // B: ∫ ψ_j v_n = Σ_i M2[i, j] (v_i · n).
        for &(i, j, m) in &self.mortar.m2.entries {
            let node = self.contact.nodes[i];
            for c in 0..2 {
                if let Some(d) = self.free[2 * node + c] {
                    rows[j].push((d, m * n[c]));
                    rows[q + j].push((d, m * t[c]));
                }
            }
        }
        // −γ0 Cγ S: −γ0 ∫ h_T ψ_j χ_k σ(v)|_k.
        if gamma0 > 0.0 {
            for &(j, k, c) in &self.mortar.c_h.entries {
                let dofs = self.edge_triangle_dofs(k);
                for (comp, row) in [j, q + j].into_iter().enumerate() {
                    let s = &self.stress_ops[k][comp];
                    for (l, d) in dofs.iter().enumerate() {
                        if let Some(d) = *d {
                            rows[row].push((d, -gamma0 * c * s[l]));
                        }
                    }
                }
            }
        }
        for r in &mut rows {
            r.sort_by_key(|e| e.0);
            let mut out: Vec<(usize, f64)> = Vec::with_capacity(r.len());
            for &(d, v) in r.iter() {
                match out.last_mut() {
                    Some(l) if l.0 == d => l.1 += v,
                    _ => out.push((d, v)),
                }
            }
            *r = out;
        }
        rows
    }

    /// Triplets of `−G` (the stabilization part of `A = K − G`) over free dofs.
    pub fn stabilization_triplets(&self, gamma0: f64) -> Vec<Triplet<usize, usize, f64>> {
        let mut trip = Vec::new();
        if gamma0 == 0.0 {
            return trip;
        }
        for k in 0..self.contact.n_edges() {
            let dofs = self.edge_triangle_dofs(k);
            let w = gamma0 * self.mortar.g_h[k];
            for s in &self.stress_ops[k] {
                for (a, da) in dofs.iter().enumerate() {
                    for (b, db) in dofs.iter().enumerate() {
                        if let (Some(da), Some(db)) = (da, db) {
                            trip.push(Triplet::new(*da, *db, -w * s[a] * s[b]));
                        }
                    }
                }
            }
        }
        trip
    }
}

fn restrict(free: &[Option<usize>], full: &[f64], n_free: usize) -> Vec<f64> {
    let mut out = vec![0.0; n_free];
    for (d, s) in free.iter().enumerate() {
        if let Some(i) = s {
            out[*i] = full[d];
        }
    }
    out
}
