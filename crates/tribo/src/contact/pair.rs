//! The primary side of a two-body contact pair.
//!
//! # Two bodies
//! Body 1 carries Γ_C, the multiplier mesh T_H and the stabilization (the *secondary* side); body 2 (the
//! *primary* side) meets it along a line Γ_C² that lies on the same straight line with the opposite normal
//! (small sliding: the reference configuration is the one the contact is written in). The projection Π
//! of Γ_C onto Γ_C² is then the identity of the abscissa ξ of [`crate::contact`]'s conventions, taken on the
//! secondary line, and the jump across the interface is
//!
//! `[u](ξ) = u¹(ξ) − u²(Π ξ)`,  `[u]_n = [u]·n`,  `[u]_t = [u]·t`,
//!
//! with n and t the secondary's. The contact law of (3.1) holds for the pair `([u]_n − g₀, [u]_t)` instead
//! of `(u_n − g, u_t − s)`: non-penetration `[u]_n ≤ g₀(ξ)` (g₀ ≥ 0 the initial gap between the two lines,
//! a parabola for two curved profiles, as for the rigid obstacle) and Coulomb's law on the relative slip.
//! The equilibrium of the two bodies with the multiplier reads
//!
//! `a(u, v) − ∫_{Γ_C} λ_n [v]_n + λ_t [v]_t − (γ terms of body 1) = L(v)`,
//!
//! so the only change to the matrices of the one-body method is the coupling `B`: its rows
//! `∫ ψ_j v_n` become `∫ ψ_j [v]_n`, that is, minus the primary term `∫ ψ_j (v² ∘ Π)·n`. The
//! Barbosa–Hughes terms stay on the secondary side (γ = γ0 h_T of body 1's triangles, σ(u¹)), and so do
//! `Dγ`, `Cγ`, `G` and the admissible γ0 (body 1's material and triangles). `A = K − G` is block diagonal
//! over the bodies, `H = E A⁻¹ Eᵀ + Dγ` couples them through E, and the QP, the fixed point and every
//! solver path are those of one body. Action and reaction hold by construction: the primary body is
//! loaded by `+λ` through the same moments with the opposite sign.
//!
//! The primary term is integrated exactly like the secondary one (2-point Gauss on the common refinement
//! of T_H and the primary nodes, whose integrand is of degree 2, 3 with the axisymmetric measure 2π r), so a
//! constant traction passes the patch test on non-matching meshes. The primary line must cover the secondary one: multipliers live on Γ_C and
//! every point of it must face the other body.

use crate::contact::mortar::{common_refinement, Coo, GAUSS2};
use crate::contact::multiplier::MultiplierMesh;
use crate::contact::ContactBoundary;
use crate::error::{Error, Result};
use crate::fem::axisymmetric::radial_weight;
use crate::fem::elasticity::Model;
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::Mesh;

/// The primary side of a contact pair.
#[derive(Debug, Clone)]
pub struct PrimarySide {
    /// The primary contact line Γ_C² (its own normal, opposite to the secondary's).
    pub boundary: ContactBoundary,
    /// Abscissae of `boundary.nodes` on the secondary line (the projection Π), increasing.
    pub xi: Vec<f64>,
    /// `∫_{Γ_C} φ²_i ψ_j` (p₂ × q), φ² the primary's P1 traces.
    pub m2: Coo,
}

impl PrimarySide {
    /// The primary side `set` of `mesh` against the secondary line `secondary` and its multiplier mesh.
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`] and the errors of [`ContactBoundary::new`]; [`Error::ContactNotStraight`] when
    /// either side is not straight; [`Error::ContactPair`] when
    /// the two lines are not one line with opposite normals, or the primary does not cover the secondary.
    pub fn new(
        mesh: &Mesh,
        secondary: &ContactBoundary,
        set: &str,
        mult: &MultiplierMesh,
        model: Model,
    ) -> Result<Self> {
        let boundary = ContactBoundary::new(mesh, set)?;
        for side in [secondary, &boundary] {
            if let Some((node, distance, length)) = side.bend {
                return Err(Error::ContactNotStraight { set: side.set.clone(), node, distance, length });
            }
        }
        let bad =
            |what: String| Error::ContactPair { secondary: secondary.set.clone(), primary: set.to_string(), what };
        let tol = geometric_tol_rel();
        let (n1, n2) = (secondary.normal, boundary.normal);
        let misalignment = (n1[0] + n2[0]).hypot(n1[1] + n2[1]);
        if misalignment > tol {
            return Err(bad(format!(
                "the normals ({:.6}, {:.6}) and ({:.6}, {:.6}) are not opposite: the two contact lines must be one line, \
                 the bodies on either side of it",
                n1[0], n1[1], n2[0], n2[1]
            )));
        }
        let pts = mesh.points();
        let scale = boundary.edges.iter().map(|e| e.length).fold(0.0, f64::max).max(secondary.length());
        for &node in &boundary.nodes {
            let off = secondary.distance_to_line(pts[node]);
            if off.abs() > tol * scale {
                return Err(bad(format!(
                    "primary node {node} lies {off:.3e} off the secondary line (the lines must coincide in the \
                     reference configuration; give an initial gap with the gap shape instead)"
                )));
            }
        }
        let xi: Vec<f64> = boundary.nodes.iter().map(|&node| secondary.abscissa(pts[node])).collect();
        if xi.windows(2).any(|w| w[1] <= w[0]) {
            return Err(bad("the primary nodes are not ordered along the secondary line".to_string()));
        }
        let (start, end) = (secondary.start(), secondary.end());
        let (lo, hi) = (xi[0], xi[xi.len() - 1]);
        let slack = tol * scale;
        if lo > start + slack || hi < end - slack {
            return Err(bad(format!(
                "the primary line [{lo}, {hi}] does not cover the secondary line [{start}, {end}] (abscissae on the \
                 secondary line): every point of Γ_C must face the other body"
            )));
        }
        // The measure at abscissa x: 1, or 2π r on the (straight) secondary line.
        let measure = |x: f64| if model.is_axisymmetric() { radial_weight(secondary.point_at(x)[0]) } else { 1.0 };
        let m2 = primary_mortar(&xi, start, end, mult, &measure);
        Ok(Self { boundary, xi, m2 })
    }

    /// The primary edge at abscissa `x` and the barycentric weight of its right node.
    fn locate(&self, x: f64) -> (usize, f64) {
        let k = self.xi.partition_point(|&y| y <= x).clamp(1, self.xi.len() - 1) - 1;
        (k, ((x - self.xi[k]) / (self.xi[k + 1] - self.xi[k])).clamp(0.0, 1.0))
    }

    /// The primary body's displacement `u²(Π ξ)` at abscissa `xi` of the secondary line, from the nodal
    /// displacement `u` over all 2N dofs.
    pub fn displacement_at(&self, xi: f64, u: &[f64]) -> [f64; 2] {
        let (k, s) = self.locate(xi);
        let (a, b) = (self.boundary.nodes[k], self.boundary.nodes[k + 1]);
        [0, 1].map(|c| (1.0 - s) * u[2 * a + c] + s * u[2 * b + c])
    }
}

/// `∫_{[start, end]} φ²_i ψ_j` (with the measure `measure(ξ)`) on the common refinement of T_H and the primary
/// nodes inside Γ_C.
fn primary_mortar(xi: &[f64], start: f64, end: f64, mult: &MultiplierMesh, measure: &dyn Fn(f64) -> f64) -> Coo {
    let mut fe: Vec<f64> = vec![start];
    fe.extend(xi.iter().copied().filter(|&x| x > start && x < end));
    fe.push(end);
    let mut m2 = Coo::new(xi.len(), mult.n_dofs());
    let n = xi.len();
    for pc in common_refinement(&fe, &mult.xi) {
        let (half, mid) = (0.5 * (pc.b - pc.a), 0.5 * (pc.a + pc.b));
        // The primary edge holding the whole piece (primary nodes are breakpoints).
        let k = xi.partition_point(|&y| y <= mid).clamp(1, n - 1) - 1;
        for &(t, w) in &GAUSS2 {
            let x = mid + half * t;
            let s = (x - xi[k]) / (xi[k + 1] - xi[k]);
            let (psi, npsi) = mult.basis(pc.cell, x);
            for (i, fi) in [(k, 1.0 - s), (k + 1, s)] {
                for &(j, pj) in &psi[..npsi] {
                    m2.entries.push((i, j, w * half * measure(x) * fi * pj));
                }
            }
        }
    }
    m2.compress()
}
