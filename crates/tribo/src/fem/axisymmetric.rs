//! Axisymmetric elasticity with P1 triangles: the body is the solid of revolution of the mesh about the y
//! axis, x = r ≥ 0 the radius and y = z the axial coordinate, loaded and supported symmetrically
//! ([`crate::fem::elasticity::Model::Axisymmetric`]).
//!
//! # The strain, the law and the measure
//! The displacement `(u_r, u_z)` has the strains `(ε_rr, ε_zz, γ_rz, ε_θθ) = (∂_r u_r, ∂_z u_z,
//! ∂_z u_r + ∂_r u_z, u_r / r)` and the isotropic law `σ = C₄ ε` with
//! `C₄ = E / ((1 + ν)(1 − 2ν)) [[1 − ν, ν, 0, ν], [ν, 1 − ν, 0, ν], [0, 0, (1 − 2ν)/2, 0], [ν, ν, 0, 1 − ν]]`
//! ([`law`]): the plane-strain law with the hoop strain as a fourth, coupled, component. Every integral
//! over the body is over the solid, `dV = 2π r dA`, and every integral over a boundary (the loads, Γ_C and
//! its multipliers) is over the surface of revolution, `dS = 2π r ds`. So every force tribo reports (the
//! contact force, the reactions) is the force on the **whole turn** (not per radian), a traction is a force
//! per unit area of that surface, and a body force is per unit volume.
//!
//! # One point per triangle
//! The hoop strain `u_r / r` is not constant on a triangle. It is taken at the centroid c of each triangle
//! (`r_c > 0` for every triangle of a mesh in r ≥ 0), and the triangle's measure is `2π r_c |T|`: the
//! element of Zienkiewicz (The Finite Element Method, vol. 1, §5 "axisymmetric stress analysis"). So σ stays
//! constant on every triangle (everything downstream, the Barbosa–Hughes term, the admissible γ0 and the
//! estimator, reads one stress per triangle), and the rule is exact where it matters: for a constant
//! stress σ and any P1 test function v, `∫_T σ : ε(v) r dA = σ : ε(v)(c) r_c |T|`, because `ε_rr, ε_zz,
//! γ_rz` are constant and `ε_θθ(v) r = v_r` is linear. The uniform states (`u_r = a r, u_z = b z`, whose
//! hoop strain `a` is exact at any point) are reproduced exactly: the patch test passes
//! (`tests/integration/axisymmetric.rs`).
//!
//! # The axis
//! A node on the axis (`r` within `√ε` of the mesh's size from 0) has `u_r = 0`: the displacement of a
//! solid of revolution is continuous through its axis. [`axis_nodes`] finds them and the supports add the
//! condition there ([`crate::Dofs::held_by_contact`] with the model). A node at `r < 0` is refused.
//!
//! # The estimate
//! The residual estimator ([`crate::Solution::estimator`]) reads the same measures: each term is integrated
//! with 2π r (at a triangle's centroid, at an edge's midpoint, at the Gauss points on Γ_C), the energy norm is
//! the solid's, and the bulk term holds what a constant stress leaves of `f + div σ`:
//! `(f_r + (σ_rr − σ_θθ) / r, f_z + σ_rz / r)` ([`residual`]). Its constants are the plane estimator's,
//! not derived again for the solid. On the sphere of `tests/integration/axisymmetric.rs` its traction estimate is 8–11
//! times the true error (21k–42k unknowns), as pessimistic as in the plane; its energy estimate is 3.40 and 3.63
//! times the energy error on coarse meshes, where the plane-strain problem on the same meshes gives 3.21 and 3.27
//! (`the_energy_estimate_against_the_energy_error`).
//!
//! # Rigid motions
//! Of the plane's three rigid motions only the axial translation leaves the solid unstrained: a radial
//! translation or a rotation in the meridian plane strains it in the hoop direction. So a body's supports
//! (or the contact) must hold that one motion only.

use nalgebra::{Matrix4, SMatrix, SVector, Vector4};

use crate::error::{Error, Num, Result};
use crate::fem::elasticity::{element_dofs, strain_displacement, Material};
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::Mesh;

/// `(ε_rr, ε_zz, γ_rz, ε_θθ) = B v_T` of one triangle, the hoop strain at its centroid.
pub type HoopStrainDisplacement = SMatrix<f64, 4, 6>;

/// `2π r`: the measure of a point at radius r, per unit of the meridian plane's area or length.
pub fn radial_weight(r: f64) -> f64 {
    std::f64::consts::TAU * r
}

/// The centroid's radius of triangle `t`.
pub fn centroid_radius(mesh: &Mesh, t: usize) -> f64 {
    let [a, b, c] = mesh.vertices(t);
    (a[0] + b[0] + c[0]) / 3.0
}

/// The measure of triangle `t` in the solid, `2π r_c |T|`.
pub fn volume(mesh: &Mesh, t: usize) -> f64 {
    radial_weight(centroid_radius(mesh, t)) * mesh.area(t)
}

/// The isotropic law `C₄` on `(ε_rr, ε_zz, γ_rz, ε_θθ)` (see the module documentation).
pub fn law(material: &Material) -> Matrix4<f64> {
    let (e, nu) = (material.young, material.poisson);
    let f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let (a, b, g) = (f * (1.0 - nu), f * nu, f * (1.0 - 2.0 * nu) / 2.0);
    Matrix4::new(a, b, 0.0, b, b, a, 0.0, b, 0.0, 0.0, g, 0.0, b, b, 0.0, a)
}

/// `B` of triangle `t` with the hoop strain `u_r / r` at its centroid (each node's shape function is 1/3
/// there).
pub fn hoop_strain_displacement(mesh: &Mesh, t: usize) -> HoopStrainDisplacement {
    let plane = strain_displacement(mesh, t);
    let rc = centroid_radius(mesh, t);
    let mut m = HoopStrainDisplacement::zeros();
    m.fixed_view_mut::<3, 6>(0, 0).copy_from(&plane);
    for i in 0..3 {
        m[(3, 2 * i)] = 1.0 / (3.0 * rc);
    }
    m
}

/// Element stiffness `2π r_c |T| Bᵀ C₄ B` (6 × 6).
pub fn element_stiffness(mesh: &Mesh, t: usize, material: &Material) -> SMatrix<f64, 6, 6> {
    // As the plane element: √(measure) B is of order one, so a huge C does not overflow in the product.
    let b = hoop_strain_displacement(mesh, t) * volume(mesh, t).sqrt();
    b.transpose() * law(material) * b
}

/// The stress `(σ_rr, σ_zz, σ_rz, σ_θθ)` of triangle `t` for its 6 dofs.
pub fn element_stress(mesh: &Mesh, t: usize, material: &Material, dofs: &SVector<f64, 6>) -> [f64; 4] {
    let s: Vector4<f64> = law(material) * (hoop_strain_displacement(mesh, t) * dofs);
    [s[0], s[1], s[2], s[3]]
}

/// The internal forces of triangle `t` under the stress `s`: `2π r_c |T| Bᵀ σ`.
pub fn element_forces(mesh: &Mesh, t: usize, s: &[f64; 4]) -> SVector<f64, 6> {
    hoop_strain_displacement(mesh, t).transpose() * Vector4::from(*s) * volume(mesh, t)
}

/// Adds the load of a constant body force `f` (per unit volume): `∫_T f N_i 2π r dA`, with
/// `∫_T N_i r dA = |T| (r₁ + r₂ + r₃ + r_i) / 12` (exact).
pub fn add_body_force(mesh: &Mesh, f: [f64; 2], rhs: &mut [f64]) {
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let [a, b, c] = mesh.vertices(t);
        let sum = a[0] + b[0] + c[0];
        let area = mesh.area(t);
        for (&i, p) in tri.iter().zip([a, b, c]) {
            let w = radial_weight(area * (sum + p[0]) / 12.0);
            rhs[2 * i] += w * f[0];
            rhs[2 * i + 1] += w * f[1];
        }
    }
}

/// Adds the load of a constant traction `g` (force per unit area of the surface of revolution) on a set of
/// boundary edges: `∫_E g N_i 2π r ds`, with `∫_E N_a r ds = |E| (2 r_a + r_b) / 6` (exact).
pub fn add_traction(mesh: &Mesh, edges: &[[usize; 2]], g: [f64; 2], rhs: &mut [f64]) {
    let pts = mesh.points();
    for &[a, b] in edges {
        let len = mesh.edge_length(a, b);
        for (i, j) in [(a, b), (b, a)] {
            let w = radial_weight(len * (2.0 * pts[i][0] + pts[j][0]) / 6.0);
            rhs[2 * i] += w * g[0];
            rhs[2 * i + 1] += w * g[1];
        }
    }
}

/// The equilibrium residual `f + div σ` of a triangle of constant stress `s = (σ_rr, σ_zz, σ_rz)` and hoop
/// stress `hoop` under the body force `f`: `div σ` keeps `((σ_rr − σ_θθ) / r, σ_rz / r)`, taken at the
/// centroid, and the triangle's measure `2π r_c |T|` (for the estimator's bulk term).
pub fn residual(mesh: &Mesh, t: usize, s: &[f64; 3], hoop: f64, f: [f64; 2]) -> ([f64; 2], f64) {
    let rc = centroid_radius(mesh, t);
    ([f[0] + (s[0] - hoop) / rc, f[1] + s[2] / rc], volume(mesh, t))
}

/// The nodes on the axis (`|r|` at most `√ε` times the mesh's size), which get `u_r = 0`.
///
/// # Errors
/// [`Error::BadAxisymmetry`] for a node at `r < 0` beyond that tolerance, naming it.
pub fn axis_nodes(mesh: &Mesh) -> Result<Vec<usize>> {
    let [x0, y0, x1, y1] = mesh.bounding_box();
    let tol = geometric_tol_rel() * (x1 - x0).hypot(y1 - y0);
    let mut axis = Vec::new();
    for (i, p) in mesh.points().iter().enumerate() {
        if p[0] < -tol {
            return Err(Error::BadAxisymmetry {
                what: format!(
                    "node {i} lies at r = x = {} < 0: the mesh of an axisymmetric body is its meridian section, \
                     in x ≥ 0 (the axis is x = 0)",
                    Num(p[0])
                ),
            });
        }
        if p[0] <= tol {
            axis.push(i);
        }
    }
    Ok(axis)
}

/// The 6 dofs of triangle `tri` taken from the nodal vector `u`.
pub(crate) fn local(tri: &[usize; 3], u: &[f64]) -> SVector<f64, 6> {
    SVector::<f64, 6>::from_iterator(element_dofs(tri).iter().map(|&d| u[d]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_law_restricted_to_plane_strain_is_the_plane_strain_law() {
        let m = Material { young: 3.0, poisson: 0.3 };
        let c4 = law(&m);
        assert_eq!(c4.fixed_view::<3, 3>(0, 0).into_owned(), m.elasticity_matrix());
        // σ_θθ of a plane strain state (ε_θθ = 0) is ν (σ_rr + σ_zz).
        let s = c4 * Vector4::new(1e-3, -2e-3, 5e-4, 0.0);
        assert!((s[3] - m.sigma_zz([s[0], s[1], s[2]])).abs() < 1e-15);
    }

    #[test]
    fn the_loads_integrate_the_radius_exactly() {
        // One triangle (1, 0), (3, 0), (1, 2): ∫ r dA = r_c |T| = 5/3 · 2; the loads of f = (1, 0) add to
        // 2π ∫ r dA, those of g = (0, 1) on the edge (1, 0)–(3, 0) to 2π ∫ r ds = 2π · 4.
        let mesh = Mesh::new(
            vec![[1.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
            vec![[0, 1, 2]],
            [("bottom".to_string(), vec![[0, 1]])].into(),
        )
        .expect("a triangle");
        let mut rhs = vec![0.0; 6];
        add_body_force(&mesh, [1.0, 0.0], &mut rhs);
        let total: f64 = rhs.iter().step_by(2).sum();
        assert!(
            (total - volume(&mesh, 0)).abs() < 1e-13 && (volume(&mesh, 0) - radial_weight(10.0 / 3.0)).abs() < 1e-13
        );
        let mut rhs = vec![0.0; 6];
        add_traction(&mesh, &[[0, 1]], [0.0, 1.0], &mut rhs);
        assert!((rhs.iter().skip(1).step_by(2).sum::<f64>() - radial_weight(4.0)).abs() < 1e-13);
        // Node 0 at r = 1 takes ∫ N_0 r ds = 2 (2 + 3) / 6 of the edge.
        assert!((rhs[1] - radial_weight(10.0 / 6.0)).abs() < 1e-13);
    }

    #[test]
    fn a_node_left_of_the_axis_is_refused_and_the_axis_is_found() {
        let pts = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let mesh = Mesh::new(pts, vec![[0, 1, 2]], [("b".to_string(), vec![[0, 1]])].into()).expect("a triangle");
        assert_eq!(axis_nodes(&mesh).expect("in r ≥ 0"), vec![0, 2]);
        let pts = vec![[-0.5, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let mesh = Mesh::new(pts, vec![[0, 1, 2]], [("b".to_string(), vec![[0, 1]])].into()).expect("a triangle");
        let err = axis_nodes(&mesh).expect_err("r < 0");
        assert!(err.to_string().contains("node 0"), "{err}");
    }
}
