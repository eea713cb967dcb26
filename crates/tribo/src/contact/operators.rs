//! Barbosa–Hughes stabilization on Γ_C: γ = γ0 h_T on every triangle with an edge on Γ_C, the contact
//! stresses σ_n(v_h), σ_t(v_h) as linear forms of the element dofs, the stabilization part `−G` of
//! `A = K − G` and the coupling `E = B − γ0 Cγ S`. How γ0 is chosen is a setting
//! ([`crate::settings::Stabilization`]); its admissible bound is in [`crate::contact::gamma0`].
//!
//! # Where Γ_C is not in contact
//! The stabilization acts on all of Γ_C: where λ_H = 0 it still adds `−∫γ σ(u_h)·σ(v_h)`. The exact
//! solution has σ·n = 0 there, so the method stays consistent, but the discrete displacement differs from a
//! plain elastic solve by a term of order γ0 (measured 3e-4 in energy on a small scene). A traction on
//! Γ_C itself is rejected ([`crate::Error::TractionOnContact`]): the method takes σ·n = −λ on all of Γ_C.

use faer::sparse::Triplet;
use nalgebra::{SVector, Vector3, Vector4};

use crate::contact::mortar::MortarMatrices;
use crate::contact::pair::PrimarySide;
use crate::contact::ContactBoundary;
use crate::fem::axisymmetric;
use crate::fem::elasticity::{element_dofs, strain_displacement, MaterialField, Model};
use crate::mesh::Mesh;

/// Voigt vectors `a` with `a · σ = σ_n = n · σ m` and `a · σ = σ_t = t · σ m` (σ = (σ_xx, σ_yy, σ_xy)) for the
/// body's outward unit normal `m`, the contact normal `n` and `t = (−n₂, n₁)` (n = m but against an obstacle
/// given by its geometry, [`crate::contact::ContactBoundary::orient_to`]).
pub fn traction_components(m: [f64; 2], n: [f64; 2]) -> (Vector3<f64>, Vector3<f64>) {
    let t = [-n[1], n[0]];
    let a = |v: [f64; 2]| Vector3::new(v[0] * m[0], v[1] * m[1], v[0] * m[1] + v[1] * m[0]);
    (a(n), a(t))
}

/// The contact stresses as linear forms of the displacement, per FE edge of Γ_C: `σ_n(v) = s_n · v_T`,
/// `σ_t(v) = s_t · v_T` with `v_T` the 6 dofs of the owning triangle (interleaved x, y), and in the mixed
/// formulation its 3 pressures after them (`σ = 2μ ε(v) − p̄_T I`, [`crate::fem::mixed`]). Everything
/// here is over all 2N dofs (node i's pressure is dof 2N + i); [`crate::Problem::condense_with`] restricts
/// it to the unknowns and applies it to the lifting of prescribed displacements.
#[derive(Debug, Clone)]
pub struct ContactStress {
    /// `[s_n, s_t]` per contact edge (6 coefficients, or 9 with the pressures).
    pub ops: Vec<[Vec<f64>; 2]>,
    /// The owning triangle's dofs (indices among all 2N dofs, then 2N + node for its pressures).
    pub dofs: Vec<Vec<usize>>,
}

impl ContactStress {
    /// The stress operators of every contact edge, each with the material of its triangle and in its own
    /// frame (n_e, t_e); in axisymmetry the in-plane stress carries the hoop strain's part
    /// ([`crate::fem::axisymmetric`]). With `pressure` (the mixed formulation, `materials` the shear parts
    /// of the laws) the mean pressure of the triangle enters as `−p̄_T I`.
    pub fn new(
        mesh: &Mesh,
        model: Model,
        materials: &impl MaterialField,
        contact: &ContactBoundary,
        pressure: bool,
    ) -> Self {
        let two_n = 2 * mesh.n_nodes();
        let ops = contact
            .edges
            .iter()
            .map(|e| {
                let (a_n, a_t) = traction_components(e.outward, e.normal);
                let [s_n, s_t]: [SVector<f64, 6>; 2] = if model.is_axisymmetric() {
                    let bt = axisymmetric::hoop_strain_displacement(mesh, e.triangle).transpose();
                    let c = axisymmetric::law(materials.at(e.triangle));
                    let four = |a: Vector3<f64>| Vector4::new(a[0], a[1], a[2], 0.0);
                    [bt * (c * four(a_n)), bt * (c * four(a_t))]
                } else {
                    let c = materials.at(e.triangle).elasticity_matrix();
                    let bt = strain_displacement(mesh, e.triangle).transpose();
                    [bt * (c * a_n), bt * (c * a_t)]
                };
                // a · (−p̄, −p̄, 0) = −(a₀ + a₁) p̄, p̄ the mean of the three nodal pressures.
                let with_pressure = |s: SVector<f64, 6>, a: Vector3<f64>| {
                    let mut s = s.as_slice().to_vec();
                    if pressure {
                        s.extend([-(a[0] + a[1]) / 3.0; 3]);
                    }
                    s
                };
                [with_pressure(s_n, a_n), with_pressure(s_t, a_t)]
            })
            .collect();
        let dofs = contact
            .edges
            .iter()
            .map(|e| {
                let tri = &mesh.triangles()[e.triangle];
                let mut d = element_dofs(tri).to_vec();
                if pressure {
                    d.extend(tri.iter().map(|&i| two_n + i));
                }
                d
            })
            .collect();
        Self { ops, dofs }
    }

    /// Triplets of `−G` (the stabilization part of `A = K − G`) over all dofs:
    /// `vᵀ G v = γ0 Σ_k h_T |E_k| (σ_n(v)² + σ_t(v)²)` (`h_T ∫_{E_k} 2π r` for `|E_k|` in axisymmetry: σ is
    /// constant on the edge).
    pub fn stiffness_triplets(&self, mortar: &MortarMatrices, gamma0: f64) -> Vec<Triplet<usize, usize, f64>> {
        if gamma0 == 0.0 {
            return Vec::new();
        }
        let mut trip = Vec::with_capacity(self.triplet_count());
        for ((ops, dofs), g_h) in self.ops.iter().zip(&self.dofs).zip(&mortar.g_h) {
            let w = gamma0 * g_h;
            for s in ops {
                for (a, &da) in dofs.iter().enumerate() {
                    for (b, &db) in dofs.iter().enumerate() {
                        trip.push(Triplet::new(da, db, -w * s[a] * s[b]));
                    }
                }
            }
        }
        trip
    }

    /// The number of triplets [`Self::stiffness_triplets`] makes (at γ0 ≠ 0).
    pub fn triplet_count(&self) -> usize {
        self.ops.iter().zip(&self.dofs).map(|(ops, dofs)| ops.len() * dofs.len() * dofs.len()).sum()
    }

    /// `out += −G x` on the dofs below `out.len()`, `x` read at each dof by `x`: the product with the matrix of
    /// [`Self::stiffness_triplets`] without forming it, one stress component of one edge at a time
    /// (`−G = −Σ w s sᵀ`): 12 products per component instead of 36 triplets.
    pub fn add_minus_g_times(&self, mortar: &MortarMatrices, gamma0: f64, x: impl Fn(usize) -> f64, out: &mut [f64]) {
        if gamma0 == 0.0 {
            return;
        }
        for ((ops, dofs), g_h) in self.ops.iter().zip(&self.dofs).zip(&mortar.g_h) {
            let w = gamma0 * g_h;
            for s in ops {
                let sx: f64 = s.iter().zip(dofs).map(|(sb, &db)| sb * x(db)).sum();
                for (sa, &da) in s.iter().zip(dofs) {
                    if let Some(o) = out.get_mut(da) {
                        *o -= w * sa * sx;
                    }
                }
            }
        }
    }

    /// Rows of the coupling `E = B − γ0 Cγ S` over all dofs: `2q` sparse rows (normal then
    /// tangential), each sorted by dof with duplicates summed. `B` is the mortar term
    /// `∫ ψ_j v_n = Σ_i M2[i, j] (v_i · n)` (and `· t`; on a bent Γ_C edge by edge, `Σ_e Σ_i M2_e[i, j]
    /// (v_i · n_e)`), `Cγ S` the γ-weighted stress term
    /// `∫ h_T ψ_j σ(v)`. With a `primary` side (two bodies), `B` tests the jump: `∫ ψ_j [v]_n`, the primary
    /// term `−Σ_i M2²[i, j] (v²_i · n)` added ([`crate::contact::pair`]).
    pub fn coupling_rows(
        &self,
        contact: &ContactBoundary,
        mortar: &MortarMatrices,
        primary: Option<&PrimarySide>,
        gamma0: f64,
    ) -> Vec<Vec<(usize, f64)>> {
        let q = mortar.psi_integrals.len();
        let (n, t) = (contact.normal, contact.tangent);
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); 2 * q];
        let secondary = mortar.m2.entries.iter().map(|&(i, j, m)| (contact.nodes[i], j, m));
        if contact.one_frame {
            let primary =
                primary.into_iter().flat_map(|p| p.m2.entries.iter().map(|&(i, j, m)| (p.boundary.nodes[i], j, -m)));
            for (node, j, m) in secondary.chain(primary) {
                for c in 0..2 {
                    rows[j].push((2 * node + c, m * n[c]));
                    rows[q + j].push((2 * node + c, m * t[c]));
                }
            }
        } else {
            // Each edge's part of M2 in its own frame, the primary term in the frame of the secondary edge
            // it faces.
            let secondary = mortar.m2_edges.iter().map(|&(i, j, k, m)| (contact.nodes[i], j, k, m));
            let primary = primary
                .into_iter()
                .flat_map(|p| p.m2_edges.iter().map(|&(i, j, k, m)| (p.boundary.nodes[i], j, k, -m)));
            for (node, j, k, m) in secondary.chain(primary) {
                let e = &contact.edges[k];
                for c in 0..2 {
                    rows[j].push((2 * node + c, m * e.normal[c]));
                    rows[q + j].push((2 * node + c, m * e.tangent[c]));
                }
            }
        }
        if gamma0 > 0.0 {
            for &(j, k, c) in &mortar.c_h.entries {
                for (comp, row) in [j, q + j].into_iter().enumerate() {
                    let s = &self.ops[k][comp];
                    for (l, &d) in self.dofs[k].iter().enumerate() {
                        rows[row].push((d, -gamma0 * c * s[l]));
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
}
