//! Isotropic linear elasticity with P1 triangles, in plane strain, plane stress or axisymmetry ([`Model`];
//! the axisymmetric element is in [`crate::fem::axisymmetric`], and the functions here that take a model
//! dispatch to it).
//!
//! Degrees of freedom are interleaved: dof `2 i` is the x displacement of node `i`, dof `2 i + 1` its y
//! displacement. Stresses use Voigt order `(σ_xx, σ_yy, σ_xy)` and strains `(ε_xx, ε_yy, 2 ε_xy)`.
//!
//! # Plane stress through its plane-strain equivalent
//! In plane stress (σ_zz = 0) the in-plane law is `C_σ = E / (1 − ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1 − ν)/2]]`.
//! The plane-strain law of `E' = E (1 + 2ν) / (1 + ν)²` and `ν' = ν / (1 + ν)` is the same matrix: its shear
//! modulus `E' / (2 (1 + ν'))` is `E / (2 (1 + ν))`, its ratio `C₁₂ / C₁₁ = ν' / (1 − ν')` is ν, and its
//! `C₁₁ = E' (1 − ν') / ((1 + ν') (1 − 2ν'))` is `E / (1 − ν²)`. So everything in-plane (the stiffness, the
//! stresses, the Barbosa–Hughes operators and the admissible γ0, the estimates, whose contact modulus
//! `E' / (1 − ν'²)` is then `E`, the plane-stress E* of Hertz) is computed from [`Model::in_plane`]'s material,
//! and only the out-of-plane stress and von Mises read the model ([`Model::sigma_zz`], [`von_mises`]).
//! The equivalent has a positive `E'` only for ν > −1/2: plane stress takes ν in (−1/2, 1/2).

use faer::sparse::{SparseColMat, Triplet};
use nalgebra::{Matrix3, SMatrix, Vector3};

use crate::choice::named_choice;
use crate::error::{Error, Num, Result};
use crate::fem::axisymmetric;
use crate::mesh::Mesh;

/// What the out-of-plane direction is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Model {
    /// Plane strain (ε_zz = 0): a long body, or one held between rigid walls.
    #[default]
    PlaneStrain,
    /// Plane stress (σ_zz = 0): a thin plate loaded in its plane (forces per unit thickness).
    PlaneStress,
    /// A solid of revolution about the y axis (x = r ≥ 0), with the hoop strain u_r / r; forces on the whole
    /// turn ([`crate::fem::axisymmetric`]).
    Axisymmetric,
}

named_choice!(Model, "model", {
    Model::PlaneStrain => "plane_strain",
    Model::PlaneStress => "plane_stress",
    Model::Axisymmetric => "axisymmetric",
});

impl Model {
    /// The plane-strain material with `material`'s in-plane law under this model (the module documentation):
    /// `material` itself in plane strain (and in axisymmetry, whose law is the full one, [`crate::fem::axisymmetric::law`]),
    /// `(E (1 + 2ν) / (1 + ν)², ν / (1 + ν))` in plane stress.
    pub fn in_plane(self, material: Material) -> Material {
        match self {
            Model::PlaneStrain | Model::Axisymmetric => material,
            Model::PlaneStress => {
                let (e, nu) = (material.young, material.poisson);
                Material { young: e * (1.0 + 2.0 * nu) / ((1.0 + nu) * (1.0 + nu)), poisson: nu / (1.0 + nu) }
            }
        }
    }

    /// [`Model::in_plane`] for every region of `materials`.
    pub fn in_plane_all(self, materials: &Materials) -> Materials {
        let in_plane = materials.materials.iter().map(|m| self.in_plane(*m)).collect();
        Materials { materials: in_plane, region: materials.region.clone() }
    }

    /// Checks `material` under this model: [`Material::validate`], and in plane stress `1 + 2ν ≥ √ε` (the
    /// equivalent's E' is positive only for ν > −1/2: the module documentation) and an equivalent whose stiffness
    /// is a normal float, each said in the user's E and ν.
    ///
    /// # Errors
    /// [`Error::BadMaterial`] naming the constant.
    pub fn validate(self, material: &Material) -> Result<()> {
        material.validate()?;
        let (e, nu) = (material.young, material.poisson);
        let margin = f64::EPSILON.sqrt();
        if self == Model::PlaneStress && 1.0 + 2.0 * nu < margin {
            return Err(Error::BadMaterial {
                what: format!(
                    "Poisson's ratio must lie in (-1/2, 1/2) in plane stress (1 + 2ν at least √ε = {}), got {nu}",
                    Num(margin)
                ),
            });
        }
        self.in_plane(*material).validate().map_err(|_| Error::BadMaterial {
            what: format!(
                "Young's modulus {} with ν = {nu} gives a plane-stress stiffness E (1 + 2ν) / (1 + ν)² of {}, \
                 not a positive, finite, normal float",
                Num(e),
                Num(self.in_plane(*material).young)
            ),
        })
    }

    /// The out-of-plane stress of the in-plane stress `s` of `material` in a plane model: `ν (σ_xx + σ_yy)`
    /// in plane strain, 0 in plane stress. In axisymmetry it is the hoop stress, which the in-plane stress
    /// does not give (NaN here): [`element_stresses`] computes it.
    pub fn sigma_zz(self, material: &Material, s: [f64; 3]) -> f64 {
        match self {
            Model::PlaneStrain => material.sigma_zz(s),
            Model::PlaneStress => 0.0,
            Model::Axisymmetric => f64::NAN,
        }
    }

    /// Whether the body is a solid of revolution ([`Model::Axisymmetric`]).
    pub fn is_axisymmetric(self) -> bool {
        self == Model::Axisymmetric
    }
}

/// The von Mises stress of `(σ_xx, σ_yy, σ_xy, σ_zz)`, computed on the stresses divided by the largest of them
/// so that no square overflows.
pub fn von_mises(s: [f64; 4]) -> f64 {
    von_mises_with([s[0], s[1], s[2]], s[3])
}

/// The material of each triangle: a [`Material`] is the same everywhere, [`Materials`] gives each region
/// (the bodies of a two-body problem) its own.
pub trait MaterialField {
    /// The material of triangle `t`.
    fn at(&self, t: usize) -> &Material;
}

impl MaterialField for Material {
    fn at(&self, _t: usize) -> &Material {
        self
    }
}

/// One material per region, and the region of every triangle.
#[derive(Debug, Clone, PartialEq)]
pub struct Materials {
    /// The materials, by region.
    pub materials: Vec<Material>,
    /// The region of every triangle (an index into `materials`).
    pub region: Vec<usize>,
}

impl Materials {
    /// One material on all `n_triangles` triangles.
    pub fn uniform(material: Material, n_triangles: usize) -> Self {
        Self { materials: vec![material], region: vec![0; n_triangles] }
    }

    /// The materials as the keyword surface gives them: pairs (E, ν), and the region of each triangle, or
    /// without one every one of the `n_triangles` triangles of the first material (checked when a problem is
    /// built: [`crate::Problem::with_materials`]).
    pub fn from_pairs(pairs: &[(f64, f64)], region: Option<Vec<usize>>, n_triangles: usize) -> Self {
        let materials = pairs.iter().map(|&(young, poisson)| Material { young, poisson }).collect();
        Self { materials, region: region.unwrap_or_else(|| vec![0; n_triangles]) }
    }
}

impl MaterialField for Materials {
    fn at(&self, t: usize) -> &Material {
        &self.materials[self.region[t]]
    }
}

/// Strain-displacement matrix of one P1 triangle: `ε = B v_T`, with `v_T` the 6 local dofs.
pub type StrainDisplacement = SMatrix<f64, 3, 6>;

/// Isotropic material (its law in plane strain; in plane stress through [`Model::in_plane`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E > 0.
    pub young: f64,
    /// Poisson's ratio ν, −1 < ν < 1/2.
    pub poisson: f64,
}

impl Material {
    /// Checks E > 0 (a normal, not subnormal, float whose elasticity matrix is finite) and
    /// −1 + √ε ≤ ν ≤ 1/2 − √ε/2.
    ///
    /// The margins are derived: with `1 − 2ν < √ε` the volumetric stiffness exceeds the shear stiffness
    /// by more than 2/√ε ≈ 1.3e8, so the factorization of K loses every digit of the shear part (and the
    /// method locks long before); `1 + ν < √ε` is the same for the bulk modulus near ν = −1.
    ///
    /// # Errors
    /// [`Error::BadMaterial`] naming the constant.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: String| Err(Error::BadMaterial { what });
        if !(self.young.is_normal() && self.young > 0.0) {
            return bad(format!("Young's modulus must be positive, finite and not subnormal, got {}", Num(self.young)));
        }
        let nu = self.poisson;
        if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
            return bad(format!("Poisson's ratio must lie in (-1, 0.5), got {nu}"));
        }
        let margin = f64::EPSILON.sqrt();
        if 1.0 - 2.0 * nu < margin || 1.0 + nu < margin {
            return bad(format!(
                "Poisson's ratio {nu} is too close to {}: 1 − 2ν = {} and 1 + ν = {} must both be at least √ε = {}, or the stiffness loses all its digits",
                if nu > 0.0 { "1/2" } else { "−1" },
                Num(1.0 - 2.0 * nu),
                Num(1.0 + nu),
                Num(margin)
            ));
        }
        if !self.elasticity_matrix().iter().all(|c| c.is_finite()) {
            return bad(format!("Young's modulus {} overflows the elasticity matrix", Num(self.young)));
        }
        Ok(())
    }

    /// Plane-strain elasticity matrix `C` with `σ = C ε` (Voigt, engineering shear strain).
    pub fn elasticity_matrix(&self) -> Matrix3<f64> {
        let (e, nu) = (self.young, self.poisson);
        let f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        Matrix3::new(f * (1.0 - nu), f * nu, 0.0, f * nu, f * (1.0 - nu), 0.0, 0.0, 0.0, f * (1.0 - 2.0 * nu) / 2.0)
    }

    /// The out-of-plane stress of plane strain (ε_zz = 0): `σ_zz = ν (σ_xx + σ_yy)` for `s = (σ_xx, σ_yy, σ_xy)`.
    pub fn sigma_zz(&self, s: [f64; 3]) -> f64 {
        self.poisson * (s[0] + s[1])
    }

    /// Von Mises stress of a plane-strain stress state (σ_zz = ν (σ_xx + σ_yy)), computed on the stresses
    /// divided by the largest of them so that no square overflows.
    pub fn von_mises(&self, s: [f64; 3]) -> f64 {
        von_mises_with(s, self.sigma_zz(s))
    }
}

/// Von Mises stress of the in-plane stress `s` with the out-of-plane stress `zz`, computed on the stresses
/// divided by the largest of them so that no square overflows.
fn von_mises_with(s: [f64; 3], zz: f64) -> f64 {
    let m = s.iter().fold(zz.abs(), |m, v| m.max(v.abs()));
    if m == 0.0 || !m.is_finite() {
        return if m == 0.0 { 0.0 } else { f64::NAN };
    }
    let [a, b, c] = s.map(|v| v / m);
    let szz = zz / m;
    m * (0.5 * ((a - b).powi(2) + (b - szz).powi(2) + (szz - a).powi(2)) + 3.0 * c * c).sqrt()
}

/// Local dof indices of triangle `tri` (interleaved x, y per node).
pub fn element_dofs(tri: &[usize; 3]) -> [usize; 6] {
    [2 * tri[0], 2 * tri[0] + 1, 2 * tri[1], 2 * tri[1] + 1, 2 * tri[2], 2 * tri[2] + 1]
}

/// Strain-displacement matrix `B` of triangle `t` (constant over the triangle).
pub fn strain_displacement(mesh: &Mesh, t: usize) -> StrainDisplacement {
    let [p0, p1, p2] = mesh.vertices(t);
    let two_area = 2.0 * mesh.area(t);
    // Gradients of the barycentric coordinates.
    let b = [p1[1] - p2[1], p2[1] - p0[1], p0[1] - p1[1]];
    let c = [p2[0] - p1[0], p0[0] - p2[0], p1[0] - p0[0]];
    let mut m = StrainDisplacement::zeros();
    for i in 0..3 {
        let (dx, dy) = (b[i] / two_area, c[i] / two_area);
        m[(0, 2 * i)] = dx;
        m[(1, 2 * i + 1)] = dy;
        m[(2, 2 * i)] = dy;
        m[(2, 2 * i + 1)] = dx;
    }
    m
}

/// Element stiffness `|T| Bᵀ C B` (6 × 6).
pub fn element_stiffness(mesh: &Mesh, t: usize, c: &Matrix3<f64>) -> SMatrix<f64, 6, 6> {
    // (√|T| B)ᵀ C (√|T| B): √|T| B is of order one whatever the size of T, so C of 1e300 on a small
    // triangle does not overflow in a product that the area would have brought back in range.
    let b = strain_displacement(mesh, t) * mesh.area(t).sqrt();
    b.transpose() * c * b
}

/// The element stiffness of triangle `t` under `model` (`material` its in-plane law, [`Model::in_plane`]).
pub fn element_stiffness_of(model: Model, mesh: &Mesh, t: usize, material: &Material) -> SMatrix<f64, 6, 6> {
    match model {
        Model::Axisymmetric => axisymmetric::element_stiffness(mesh, t, material),
        _ => element_stiffness(mesh, t, &material.elasticity_matrix()),
    }
}

/// Triplets of the global stiffness matrix of a plane model (2N × 2N, duplicates to be summed).
pub fn stiffness_triplets(mesh: &Mesh, material: &impl MaterialField) -> Vec<Triplet<usize, usize, f64>> {
    let mut trip = Vec::with_capacity(36 * mesh.n_triangles());
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let k = element_stiffness(mesh, t, &material.at(t).elasticity_matrix());
        let dofs = element_dofs(tri);
        for (j, &dj) in dofs.iter().enumerate() {
            for (i, &di) in dofs.iter().enumerate() {
                trip.push(Triplet::new(di, dj, k[(i, j)]));
            }
        }
    }
    trip
}

/// Global stiffness matrix K of a plane model (2N × 2N, all dofs, no support applied).
///
/// # Errors
/// [`Error::Assembly`] if faer cannot build the matrix (index overflow, allocation failure).
pub fn stiffness(mesh: &Mesh, material: &impl MaterialField) -> Result<SparseColMat<usize, f64>> {
    let n = 2 * mesh.n_nodes();
    SparseColMat::try_new_from_triplets(n, n, &stiffness_triplets(mesh, material))
        .map_err(|e| Error::Assembly { matrix: "K", what: format!("{e:?}") })
}

/// Adds the load of a constant body force `f` (per unit volume) under `model` to `rhs`: each node of T gets
/// `|T| f / 3` in a plane model ([`axisymmetric::add_body_force`] in axisymmetry).
pub fn add_body_force(model: Model, mesh: &Mesh, f: [f64; 2], rhs: &mut [f64]) {
    if model.is_axisymmetric() {
        return axisymmetric::add_body_force(mesh, f, rhs);
    }
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let w = mesh.area(t) / 3.0;
        for &i in tri {
            rhs[2 * i] += w * f[0];
            rhs[2 * i + 1] += w * f[1];
        }
    }
}

/// A load on an edge set (Γ_N): per unit length in a plane model, per unit area of the surface of revolution in
/// axisymmetry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Traction {
    /// A constant traction vector `(t_x, t_y)` in global axes.
    Vector([f64; 2]),
    /// A pressure p: the traction `−p n` on each edge, n its outward normal (p > 0 presses on the body). On a
    /// faceted arc each facet is pressed along its own normal, so that a constant stress `−p I` meets it exactly.
    Pressure(f64),
}

impl From<[f64; 2]> for Traction {
    fn from(v: [f64; 2]) -> Self {
        Self::Vector(v)
    }
}

impl TryFrom<&[f64]> for Traction {
    type Error = Error;
    /// `[p]` a pressure, `[t_x, t_y]` a vector.
    fn try_from(v: &[f64]) -> Result<Self> {
        match *v {
            [p] => Ok(Self::Pressure(p)),
            [x, y] => Ok(Self::Vector([x, y])),
            _ => Err(Error::BadSetting {
                name: "traction",
                value: v.len() as f64,
                what: "a pressure [p] or a vector [tx, ty] (the value is how many numbers were given)".into(),
            }),
        }
    }
}

impl Traction {
    /// The traction on an edge of outward normal `n`.
    pub fn on(&self, n: [f64; 2]) -> [f64; 2] {
        match *self {
            Self::Vector(v) => v,
            Self::Pressure(p) => [-p * n[0], -p * n[1]],
        }
    }

    /// The load times `k` (a load factor, or a change of units).
    #[must_use]
    pub fn scaled(&self, k: f64) -> Self {
        match *self {
            Self::Vector(v) => Self::Vector(v.map(|x| k * x)),
            Self::Pressure(p) => Self::Pressure(k * p),
        }
    }

    /// Its numbers: the vector, or the pressure and 0.
    pub fn components(&self) -> [f64; 2] {
        match *self {
            Self::Vector(v) => v,
            Self::Pressure(p) => [p, 0.0],
        }
    }
}

/// The outward unit normal of the boundary edge `(a, b)`: away from the third vertex of its triangle (of the
/// edge's left-hand side `(d_y, −d_x)` turned when it points inward; as it is for an edge on no triangle).
pub fn outward_normal(mesh: &Mesh, a: usize, b: usize) -> [f64; 2] {
    let pts = mesh.points();
    let (pa, pb) = (pts[a], pts[b]);
    let len = mesh.edge_length(a, b);
    let n = [(pb[1] - pa[1]) / len, -(pb[0] - pa[0]) / len];
    let third = mesh.boundary_triangle(a, b).and_then(|t| mesh.triangles()[t].into_iter().find(|&v| v != a && v != b));
    match third {
        Some(c) if (pts[c][0] - pa[0]) * n[0] + (pts[c][1] - pa[1]) * n[1] > 0.0 => [-n[0], -n[1]],
        _ => n,
    }
}

/// Adds the load of a traction (force per unit length in a plane model, per unit area of the surface of
/// revolution in axisymmetry: [`axisymmetric::add_traction`]) on a set of boundary edges to `rhs`: a constant
/// vector, or a pressure along each edge's outward normal ([`Traction`]).
pub fn add_traction(model: Model, mesh: &Mesh, edges: &[[usize; 2]], traction: Traction, rhs: &mut [f64]) {
    for &[a, b] in edges {
        let g =
            traction.on(if matches!(traction, Traction::Pressure(_)) { outward_normal(mesh, a, b) } else { [0.0; 2] });
        if model.is_axisymmetric() {
            axisymmetric::add_traction(mesh, &[[a, b]], g, rhs);
            continue;
        }
        let w = 0.5 * mesh.edge_length(a, b);
        for i in [a, b] {
            rhs[2 * i] += w * g[0];
            rhs[2 * i + 1] += w * g[1];
        }
    }
}

/// Constant stress `(σ_xx, σ_yy, σ_xy, σ_zz)` in every triangle for the nodal displacement `u` (length 2N)
/// under `model`, `material` the in-plane law ([`Model::in_plane`]): σ_zz is `ν (σ_xx + σ_yy)` in plane
/// strain, 0 in plane stress and the hoop stress σ_θθ in axisymmetry.
pub fn element_stresses(model: Model, mesh: &Mesh, material: &impl MaterialField, u: &[f64]) -> Vec<[f64; 4]> {
    mesh.triangles()
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let ut = axisymmetric::local(tri, u);
            if model.is_axisymmetric() {
                return axisymmetric::element_stress(mesh, t, material.at(t), &ut);
            }
            let s: Vector3<f64> = material.at(t).elasticity_matrix() * (strain_displacement(mesh, t) * ut);
            let s = [s[0], s[1], s[2]];
            [s[0], s[1], s[2], model.sigma_zz(material.at(t), s)]
        })
        .collect()
}

/// The recovered nodal stress: at each node the area-weighted mean of the constant stresses of the
/// triangles around it (the simplest Zienkiewicz–Zhu-type recovery). It is exact for a constant stress,
/// and for a linear one at an interior node whose patch is point-symmetric (a uniform mesh); elsewhere it
/// smooths the P1 cell stress's jumps (the checkerboard near the fans of a graded mesh). It is a
/// post-processed field for plots and files: the solve, the reactions and the estimator use the cell
/// stress.
pub fn recovered_stress<const N: usize>(mesh: &Mesh, stresses: &[[f64; N]]) -> Vec<[f64; N]> {
    let mut sum = vec![[0.0; N]; mesh.n_nodes()];
    let mut weight = vec![0.0; mesh.n_nodes()];
    for (t, (tri, s)) in mesh.triangles().iter().zip(stresses).enumerate() {
        let area = mesh.area(t);
        for &v in tri {
            weight[v] += area;
            for (acc, si) in sum[v].iter_mut().zip(s) {
                *acc += area * si;
            }
        }
    }
    // Every node of a validated mesh belongs to a triangle, so its weight is positive.
    sum.iter().zip(&weight).map(|(s, w)| s.map(|x| x / w)).collect()
}

/// The internal forces `K u` on all 2N dofs from the element stresses of `u` ([`element_stresses`]),
/// element by element: `K_T u_T = |T| Bᵀ σ_T` (`2π r_c |T| Bᵀ σ_T` with the hoop row in axisymmetry), so no
/// matrix is assembled (the reactions of every solve and history step come from here).
pub fn internal_forces(model: Model, mesh: &Mesh, stresses: &[[f64; 4]]) -> Vec<f64> {
    let mut out = vec![0.0; 2 * mesh.n_nodes()];
    for (t, (tri, s)) in mesh.triangles().iter().zip(stresses).enumerate() {
        let f = if model.is_axisymmetric() {
            axisymmetric::element_forces(mesh, t, s)
        } else {
            strain_displacement(mesh, t).transpose() * Vector3::new(s[0], s[1], s[2]) * mesh.area(t)
        };
        for (&d, fd) in element_dofs(tri).iter().zip(f.iter()) {
            out[d] += fd;
        }
    }
    out
}

/// Elastic energy norm `sqrt(uᵀ K u)` of a nodal displacement, element by element.
pub fn energy_norm(model: Model, mesh: &Mesh, material: &impl MaterialField, u: &[f64]) -> f64 {
    let mut e = 0.0;
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let ut = axisymmetric::local(tri, u);
        if model.is_axisymmetric() {
            let b = axisymmetric::hoop_strain_displacement(mesh, t);
            let eps = b * ut;
            e += axisymmetric::volume(mesh, t) * eps.dot(&(axisymmetric::law(material.at(t)) * eps));
            continue;
        }
        let eps = strain_displacement(mesh, t) * ut;
        e += mesh.area(t) * eps.dot(&(material.at(t).elasticity_matrix() * eps));
    }
    e.sqrt()
}
