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

use nalgebra::{Matrix3, SVector, Vector3};

use crate::contact::ContactBoundary;
use crate::elasticity::{strain_displacement, Material};
use crate::error::{check_setting, Error, Result};
use crate::mesh::Mesh;

/// How γ0 is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stabilization {
    /// γ0 = 0: the classic (unstabilized) mixed method.
    None,
    /// γ0 given directly (units of 1/E); must be below the admissible bound.
    Gamma0(f64),
    /// γ0 as a fraction θ ∈ [0, 1) of the admissible bound.
    Fraction(f64),
}

impl Default for Stabilization {
    /// Half of the admissible bound.
    fn default() -> Self {
        Self::Fraction(0.5)
    }
}

/// Voigt vectors `a` with `a · σ = σ_n` and `a · σ = σ_t` (σ = (σ_xx, σ_yy, σ_xy)).
pub fn traction_components(contact: &ContactBoundary) -> (Vector3<f64>, Vector3<f64>) {
    let (n, t) = (contact.normal, contact.tangent);
    let a_n = Vector3::new(n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]);
    let a_t = Vector3::new(t[0] * n[0], t[1] * n[1], t[0] * n[1] + t[1] * n[0]);
    (a_n, a_t)
}

/// For every contact edge, the 6-vectors `s_n`, `s_t` with `σ_n(v) = s_n · v_T`, `σ_t(v) = s_t · v_T`
/// (v_T the dofs of the owning triangle, interleaved x, y).
pub fn stress_operators(mesh: &Mesh, material: &Material, contact: &ContactBoundary) -> Vec<[SVector<f64, 6>; 2]> {
    let c = material.elasticity_matrix();
    let (a_n, a_t) = traction_components(contact);
    contact
        .edges
        .iter()
        .map(|e| {
            let bt = strain_displacement(mesh, e.triangle).transpose();
            [bt * (c * a_n), bt * (c * a_t)]
        })
        .collect()
}

/// The admissible bound on γ0 and the contact edge (index into `contact.edges`) whose triangle sets it.
pub fn admissible_gamma0(mesh: &Mesh, material: &Material, contact: &ContactBoundary) -> (f64, usize) {
    let c = material.elasticity_matrix();
    let l = c.cholesky().expect("validated material has a positive definite C").l();
    let (a_n, a_t) = traction_components(contact);
    let p: Matrix3<f64> = a_n * a_n.transpose() + a_t * a_t.transpose();
    let m = l.transpose() * p * l;
    let lam = m.symmetric_eigenvalues().max();
    contact
        .edges
        .iter()
        .enumerate()
        .map(|(k, e)| (mesh.area(e.triangle) / (mesh.diameter(e.triangle) * e.length * lam), k))
        .fold((f64::INFINITY, 0), |best, cur| if cur.0 < best.0 { cur } else { best })
}

/// Resolves a [`Stabilization`] into a value of γ0, checked against the admissible `bound`.
///
/// # Errors
/// [`Error::BadSetting`] for a negative or non-finite value or a fraction outside [0, 1);
/// [`Error::Gamma0TooLarge`] for γ0 at or above the bound.
pub fn resolve_gamma0(stab: Stabilization, bound: f64, element: usize) -> Result<f64> {
    let gamma0 = match stab {
        Stabilization::None => 0.0,
        Stabilization::Gamma0(g) => {
            check_setting("gamma0", g, g >= 0.0, "γ0 must be non-negative")?;
            g
        }
        Stabilization::Fraction(theta) => {
            check_setting("gamma0_fraction", theta, (0.0..1.0).contains(&theta), "the fraction must lie in [0, 1)")?;
            theta * bound
        }
    };
    if gamma0 >= bound {
        return Err(Error::Gamma0TooLarge { gamma0, bound, element });
    }
    Ok(gamma0)
}
