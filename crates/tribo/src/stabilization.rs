//! Barbosa–Hughes stabilization: γ = γ0 h_T on every triangle with an edge on Γ_C, the contact stresses
//! σ_n(v_h), σ_t(v_h) as linear forms of the element dofs, and the admissible bound on γ0.
//!
//! # Admissible γ0
//! The stabilized stiffness is `A = K − G` with `vᵀ G v = ∫_Γ_C γ (σ_n(v)² + σ_t(v)²)`. For P1, σ = C ε is
//! constant on T, so on a contact triangle T with edge E
//!
//! `vᵀ K_T v − γ0 vᵀ G_T v = |T| εᵀ C ε − γ0 h_T |E| εᵀ C P C ε`,  `P = a_n a_nᵀ + a_t a_tᵀ`,
//!
//! where `a_n · σ = σ_n`, `a_t · σ = σ_t`. Writing `C = L Lᵀ`, this is ≥ 0 for all ε iff
//! `γ0 ≤ γ0_T = |T| / (h_T |E| λ_max(Lᵀ P L))`: a 3 × 3 symmetric eigenproblem per contact triangle.
//! Since `K ⪰ Σ_{T contact} K_T` (the other elements only add) and Dirichlet conditions make K definite,
//! `γ0 < min_T γ0_T` guarantees that K − G is positive definite. The bound is sufficient, not necessary:
//! the global matrix may stay definite somewhat beyond it. γ0 scales like 1/E and like 1/(the shape of
//! the contact triangles); choosing γ0 as a fraction of the bound makes the choice unit free.

//!
//! # Where Γ_C is not in contact
//! The stabilization acts on all of Γ_C: where λ_H = 0 it still adds `−∫γ σ(u_h)·σ(v_h)`. The exact
//! solution has σ·n = 0 there, so the method stays consistent, but the discrete displacement differs from a
//! plain elastic solve by a term of order γ0 (measured 3e-4 in energy on a small scene). A traction on
//! Γ_C itself is rejected ([`crate::Error::TractionOnContact`]): the method takes σ·n = −λ on all of Γ_C.

use faer::sparse::Triplet;
use nalgebra::{Matrix3, SVector, Vector3};

use crate::contact::ContactBoundary;
use crate::elasticity::{element_dofs, strain_displacement, Material};
use crate::error::{check_setting, Error, Result};
use crate::mesh::Mesh;
use crate::mortar::MortarMatrices;

/// How γ0 is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stabilization {
    /// γ0 = 0: the classic (unstabilized) mixed method.
    None,
    /// γ0 given directly (units of 1/E); must be below the admissible bound.
    Gamma0(f64),
    /// γ0 as a fraction θ ∈ [0, 1) of the admissible bound.
    Fraction(f64),
    /// γ0 given directly and *not* checked against the admissible bound: for studies of what happens
    /// beyond it. The factorization of `K − G` still refuses an indefinite matrix
    /// ([`Error::NotPositiveDefinite`]).
    Unchecked(f64),
}

impl Default for Stabilization {
    /// Half of the admissible bound.
    fn default() -> Self {
        Self::Fraction(0.5)
    }
}

impl Stabilization {
    /// The choice from keywords: `gamma0` (a value), `fraction` (of the bound) or neither (the default);
    /// `checked = false` takes `gamma0` without the check against the bound ([`Stabilization::Unchecked`]).
    ///
    /// # Errors
    /// [`Error::BadSettingValue`] when both are given, or when `checked` is false without a `gamma0`.
    pub fn from_keywords(gamma0: Option<f64>, fraction: Option<f64>, checked: bool) -> Result<Self> {
        let bad = |what: &str| Err(Error::BadSettingValue { name: "gamma0", what: what.to_string() });
        match (gamma0, fraction, checked) {
            (Some(_), Some(_), _) => bad("give gamma0 or gamma0_fraction, not both"),
            (Some(g), None, true) => Ok(Self::Gamma0(g)),
            (Some(g), None, false) => Ok(Self::Unchecked(g)),
            (None, _, false) => bad("check_gamma0 = false needs an explicit gamma0"),
            (None, Some(f), true) => Ok(Self::Fraction(f)),
            (None, None, true) => Ok(Self::default()),
        }
    }
}

/// The admissible bound on γ0 and the triangle that sets it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gamma0Bound {
    /// The bound: `K − G` is positive definite for every γ0 below it.
    pub value: f64,
    /// The contact triangle with the smallest bound (an index into the mesh's triangles).
    pub triangle: usize,
}

impl Gamma0Bound {
    /// Resolves a [`Stabilization`] into a value of γ0, checked against the bound.
    ///
    /// # Errors
    /// [`Error::BadSetting`] for a negative or non-finite value or a fraction outside [0, 1);
    /// [`Error::Gamma0TooLarge`] for γ0 at or above the bound.
    pub fn resolve(&self, stab: Stabilization) -> Result<f64> {
        let gamma0 = match stab {
            Stabilization::None => 0.0,
            Stabilization::Gamma0(g) | Stabilization::Unchecked(g) => {
                check_setting("gamma0", g, g >= 0.0, "γ0 must be non-negative")?;
                g
            }
            Stabilization::Fraction(theta) => {
                let ok = (0.0..1.0).contains(&theta);
                check_setting("gamma0_fraction", theta, ok, "the fraction must lie in [0, 1)")?;
                theta * self.value
            }
        };
        if gamma0 > 0.0 && gamma0 >= self.value && !matches!(stab, Stabilization::Unchecked(_)) {
            return Err(Error::Gamma0TooLarge { gamma0, bound: self.value, element: self.triangle });
        }
        Ok(gamma0)
    }
}

/// Voigt vectors `a` with `a · σ = σ_n` and `a · σ = σ_t` (σ = (σ_xx, σ_yy, σ_xy)).
pub fn traction_components(contact: &ContactBoundary) -> (Vector3<f64>, Vector3<f64>) {
    let (n, t) = (contact.normal, contact.tangent);
    let a_n = Vector3::new(n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]);
    let a_t = Vector3::new(t[0] * n[0], t[1] * n[1], t[0] * n[1] + t[1] * n[0]);
    (a_n, a_t)
}

/// The contact stresses as linear forms of the displacement, per FE edge of Γ_C: `σ_n(v) = s_n · v_T`,
/// `σ_t(v) = s_t · v_T` with `v_T` the 6 dofs of the owning triangle (interleaved x, y). Everything
/// here is over all 2N dofs; [`crate::Problem::condense_with`] restricts it to the unknowns and applies it
/// to the lifting of prescribed displacements.
#[derive(Debug, Clone)]
pub struct ContactStress {
    /// `[s_n, s_t]` per contact edge.
    pub ops: Vec<[SVector<f64, 6>; 2]>,
    /// The owning triangle's dofs (indices among all 2N dofs).
    pub dofs: Vec<[usize; 6]>,
}

impl ContactStress {
    /// The stress operators of every contact edge.
    pub fn new(mesh: &Mesh, material: &Material, contact: &ContactBoundary) -> Self {
        let c = material.elasticity_matrix();
        let (a_n, a_t) = traction_components(contact);
        let ops = contact
            .edges
            .iter()
            .map(|e| {
                let bt = strain_displacement(mesh, e.triangle).transpose();
                [bt * (c * a_n), bt * (c * a_t)]
            })
            .collect();
        let dofs = contact.edges.iter().map(|e| element_dofs(&mesh.triangles()[e.triangle])).collect();
        Self { ops, dofs }
    }

    /// Triplets of `−G` (the stabilization part of `A = K − G`) over all dofs:
    /// `vᵀ G v = γ0 Σ_k h_T |E_k| (σ_n(v)² + σ_t(v)²)`.
    pub fn stiffness_triplets(&self, mortar: &MortarMatrices, gamma0: f64) -> Vec<Triplet<usize, usize, f64>> {
        let mut trip = Vec::new();
        if gamma0 == 0.0 {
            return trip;
        }
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

    /// Rows of the coupling `E = B − γ0 Cγ S` over all dofs: `2q` sparse rows (normal then
    /// tangential), each sorted by dof with duplicates summed. `B` is the mortar term
    /// `∫ ψ_j v_n = Σ_i M2[i, j] (v_i · n)` (and `· t`), `Cγ S` the γ-weighted stress term
    /// `∫ h_T ψ_j σ(v)`.
    pub fn coupling_rows(
        &self,
        contact: &ContactBoundary,
        mortar: &MortarMatrices,
        gamma0: f64,
    ) -> Vec<Vec<(usize, f64)>> {
        let q = mortar.psi_integrals.len();
        let (n, t) = (contact.normal, contact.tangent);
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); 2 * q];
        for &(i, j, m) in &mortar.m2.entries {
            let node = contact.nodes[i];
            for c in 0..2 {
                rows[j].push((2 * node + c, m * n[c]));
                rows[q + j].push((2 * node + c, m * t[c]));
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

/// The admissible bound on γ0 (see the module documentation).
///
/// The eigenproblem is solved for the material scaled to E = 1 (C is proportional to E), so neither a
/// huge nor a tiny Young's modulus overflows it; the bound is then divided by E.
pub fn admissible_gamma0(mesh: &Mesh, material: &Material, contact: &ContactBoundary) -> Gamma0Bound {
    let unit = Material { young: 1.0, poisson: material.poisson };
    let (a_n, a_t) = traction_components(contact);
    let p: Matrix3<f64> = a_n * a_n.transpose() + a_t * a_t.transpose();
    // C(E = 1) is positive definite for a validated ν; its Cholesky factor exists.
    let lam = match unit.elasticity_matrix().cholesky() {
        Some(c) => {
            let l = c.l();
            (l.transpose() * p * l).symmetric_eigenvalues().max()
        }
        None => f64::NAN,
    };
    let (value, triangle) = contact
        .edges
        .iter()
        .map(|e| (mesh.area(e.triangle) / (mesh.diameter(e.triangle) * e.length * lam), e.triangle))
        .fold((f64::INFINITY, 0), |best, cur| if cur.0 < best.0 { cur } else { best });
    Gamma0Bound { value: value / material.young, triangle }
}
