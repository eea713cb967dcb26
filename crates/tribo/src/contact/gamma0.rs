//! The admissible bound on γ0: below it, the stabilized stiffness `A = K − G` is positive definite.
//!
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

use nalgebra::{Matrix3, Matrix4};

use crate::contact::operators::traction_components;
use crate::contact::ContactBoundary;
use crate::error::{check_setting, Error, Result};
use crate::fem::axisymmetric;
use crate::fem::elasticity::{Material, MaterialField, Model};
use crate::mesh::Mesh;
use crate::settings::Stabilization;

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

/// The admissible bound on γ0 (see the module documentation).
///
/// Each contact triangle has its own material (a coated body's differ): its bound is computed with its
/// C. The eigenproblem is solved for the material scaled to E = 1 (C is proportional to E), so neither a
/// huge nor a tiny Young's modulus overflows it; each triangle's bound is then divided by its E, and γ0
/// (one constant on Γ_C) must stay below the smallest.
///
/// In axisymmetry the strain has the hoop component and the measures are the solid's and the surface's:
/// `vᵀ K_T v = 2π r_c |T| εᵀ C₄ ε` and `vᵀ G_T v = γ0 h_T ∫_E 2π r (σ_n² + σ_t²)`, so the bound is
/// `γ0_T = r_c |T| / (h_T |E| r_E λ_max(L₄ᵀ P₄ L₄))`, r_E the radius of the edge's midpoint and P₄ the P above
/// with a zero row and column for σ_θθ (which the traction does not read). The four strains are taken as
/// independent, so the bound is again sufficient.
pub fn admissible_gamma0(
    mesh: &Mesh,
    model: Model,
    materials: &impl MaterialField,
    contact: &ContactBoundary,
) -> Gamma0Bound {
    let bounds = edge_bounds(mesh, model, materials, contact);
    let (value, triangle) =
        bounds.into_iter().fold((f64::INFINITY, 0), |best, cur| if cur.0 < best.0 { cur } else { best });
    Gamma0Bound { value, triangle }
}

/// Each contact edge's bound with its triangle, `(γ0_T, T)` ([`admissible_gamma0`] is the smallest). Several
/// contact pairs whose sides meet at a triangle add their terms of G there: its bound is then `1 / Σ 1/γ0_T` over
/// the pairs (`crate::problem::sides`).
pub fn edge_bounds(
    mesh: &Mesh,
    model: Model,
    materials: &impl MaterialField,
    contact: &ContactBoundary,
) -> Vec<(f64, usize)> {
    // |σ m|² = σ_n² + σ_t² does not depend on the direction of m for an isotropic C, nor on the frame (n, t)
    // it is split in: one normal serves every edge of a bent Γ_C.
    let (a_n, a_t) = traction_components(contact.normal, contact.normal);
    let p: Matrix3<f64> = a_n * a_n.transpose() + a_t * a_t.transpose();
    let radial = model.is_axisymmetric();
    // λ_max(Lᵀ P L) of C(E = 1), by Poisson's ratio: the materials of Γ_C's triangles are few.
    let mut by_poisson: Vec<(f64, f64)> = Vec::new();
    let mut lam = |poisson: f64| {
        if let Some(&(_, l)) = by_poisson.iter().find(|(nu, _)| *nu == poisson) {
            return l;
        }
        // C(E = 1) is positive definite for a validated ν; its Cholesky factor exists.
        let unit = Material { young: 1.0, poisson };
        let l = if radial {
            let mut p4 = Matrix4::<f64>::zeros();
            p4.fixed_view_mut::<3, 3>(0, 0).copy_from(&p);
            match axisymmetric::law(&unit).cholesky() {
                Some(c) => {
                    let l = c.l();
                    (l.transpose() * p4 * l).symmetric_eigenvalues().max()
                }
                None => f64::NAN,
            }
        } else {
            match unit.elasticity_matrix().cholesky() {
                Some(c) => {
                    let l = c.l();
                    (l.transpose() * p * l).symmetric_eigenvalues().max()
                }
                None => f64::NAN,
            }
        };
        by_poisson.push((poisson, l));
        l
    };
    contact
        .edges
        .iter()
        .map(|e| {
            let m = materials.at(e.triangle);
            let mut shape = mesh.area(e.triangle) / (mesh.diameter(e.triangle) * e.length * lam(m.poisson));
            if radial {
                // An edge on the axis (refused as Γ_C by the problem) has no measure and no bound.
                let pts = mesh.points();
                let r_edge = 0.5 * (pts[e.left][0] + pts[e.right][0]);
                shape = if r_edge > 0.0 {
                    shape * axisymmetric::centroid_radius(mesh, e.triangle) / r_edge
                } else {
                    f64::INFINITY
                };
            }
            (shape / m.young, e.triangle)
        })
        .collect()
}
