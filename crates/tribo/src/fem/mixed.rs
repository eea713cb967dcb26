//! The mixed displacement–pressure formulation, for bodies near incompressibility (ν → ½), where P1
//! displacements lock: the volumetric stiffness λ grows without bound against the shear modulus μ, and
//! the few P1 fields whose divergence vanishes on every triangle are far too stiff (study 25, Hertz graded
//! to h_min = 0.0025: λ_n 17 % off at ν = 0.499 and 60 % at 0.4999, where it is 0.75 % off at ν = 0.3).
//!
//! # The mixed form
//! With the pressure `p = −λ div u` an unknown of its own, `σ = 2μ ε(u) − p I`, and the body's equations are
//!
//! `∫ 2μ ε(u):ε(v) − ∫ p div v = ℓ(v)`,  `−∫ q div u − ∫ p q / λ = 0`
//!
//! for all v, q. λ = ∞ is allowed here (the second equation then says div u = 0); the first term sees μ
//! alone. Displacements and pressures are continuous P1 on the same mesh, which alone violates the
//! inf–sup condition (spurious pressure modes); the stabilization below restores it.
//!
//! # MINI, its bubble condensed
//! Arnold–Brezzi–Fortin's MINI element adds to the P1 displacement the cubic bubble `b = 27 λ₁λ₂λ₃` of
//! each triangle T (vector coefficient β_T), which is stable with P1 pressures. The bubble is eliminated
//! triangle by triangle, exactly:
//! - `∫_T 2μ ε(u₁):ε(bβ) = 0` for P1 u₁ (ε(u₁) is constant and `∫_T ∇b = 0`), so the bubble couples to
//!   the pressure only;
//! - `K_b = ∫_T 2μ ε(bβ):ε(bγ) = μ (81/20) |T| (tr S · I + S)`, `S = Σᵢ ∇λᵢ ∇λᵢᵀ` (from
//!   `∫_T ∇b ∇bᵀ = (81/20) |T| S`, which uses `Σᵢ ∇λᵢ = 0`);
//! - `−∫_T q div(bβ) = ∫_T b ∇q · β = (9/20) |T| ∇q · β` (b vanishes on ∂T; `∫_T b = (9/20) |T|`);
//! - the load `∫_T b f · β = (9/20) |T| f · β`.
//!
//! With `X_T = (9/20) |T| G_T` (`G_T` the 3 × 2 matrix of the pressure's hat gradients), eliminating β_T
//! adds `−X_T K_b⁻¹ X_Tᵀ` to the pressure block and `−X_T K_b⁻¹ (9/20) |T| f` to its right-hand side. The
//! system on the P1 unknowns (u, p) is then
//!
//! `[[K_μ, −Bᵀ], [−B, −(M/λ + C)]]`,  `C = Σ_T X_T K_b⁻¹ X_Tᵀ`,
//!
//! a Brezzi–Pitkäranta stabilization (C ≈ h²/μ times a pressure Laplacian) whose weight comes from the
//! bubble, not from a tuned constant. K_μ is positive definite (the supports hold the body) and
//! `M/λ + C` positive definite (C is positive semi-definite and vanishes only on constant pressures, which
//! M/λ holds, or the supports, through B): the matrix is **symmetric quasi-definite**, so an LDLᵀ
//! factorization exists for every symmetric ordering (Vanderbei 1995), with n_u positive and n_p negative
//! pivots ([`crate::condensation`] checks that inertia).
//!
//! # The stress and the Barbosa–Hughes term
//! The discrete stress is `σ_h = 2μ ε(u_h) − p̄_T I`, p̄_T the mean of p_h on T: constant per triangle like
//! the displacement formulation's, so the stabilization's σ_n(v_h, q_h) and σ_t(v_h, q_h) stay constant on
//! each contact edge and every term of [`crate::contact::mortar`] stays exact. They are linear forms of the
//! triangle's 6 displacement and 3 pressure unknowns ([`crate::contact::operators`]), so the
//! stabilization `−γ ∫ (λ − σ_n(u, p))(μ − σ_n(v, q))` acts on the pressure too and stays consistent with
//! σ·n = −λ for the exact (u, p). Since `∫_T p div v = p̄_T |T| div v` for P1 v, the internal forces
//! `Σ_T |T| B_Tᵀ σ_h` are exactly those of the discrete equations: the reactions come from σ_h as before.
//! The bubble is left out of σ_h (it is a stabilization of the pressure, not a displacement users read).
//!
//! # The admissible γ0
//! Write the stabilized system on (u; p, λ) as a saddle point, min over u and max over (p, λ). The
//! stabilization adds `−γ (λ − σ_u(u) − σ_p(p))²`: on (p, λ) with u = 0 it is negative semi-definite, and
//! with `−(M/λ + C)` and `−Dγ` the (p, λ) block is negative definite. On u alone it is `K_μ − G_uu`, the
//! displacement formulation's bound ([`crate::contact::gamma0`]) with the shear part of the law
//! (E' = 2μ, ν' = 0: [`shear_part`]). Below that bound A = K − G is quasi-definite and eliminating u,
//! then p, leaves `H = E A⁻¹ Eᵀ + Dγ` positive definite: the Γ_C QPs stay convex.
//!
//! # Axisymmetry
//! In a solid of revolution ([`crate::fem::axisymmetric`]) `div u = ∂_r u_r + ∂_z u_z + u_r / r`, the hoop strain
//! taken at each triangle's centroid as the displacement element takes it, so div u stays constant per triangle;
//! every body integral gains the measure `2π r_c` (one point, the element's rule): `−∫ q div u` becomes
//! `−2π r_c |T|/3 div_T u` per node (so `∫ p div v = p̄_T 2π r_c |T| div_T v` and the reactions still come from
//! σ_h), the pressure mass `M/λ` and the bubble's `C_T` and load are the plane ones times `2π r_c`. K_μ is the
//! axisymmetric stiffness of the shear part (E' = 2μ, ν' = 0: `2μ` on ε_rr, ε_zz, ε_θθ, `μ` on γ_rz), and
//! `σ_θθ = 2μ ε_θθ − p̄_T`. The bubble is kept as the plane stabilization weighted by `2π r_c`, its hoop strain
//! left out: it vanishes on constant pressures, so every uniform state (the pressed cylinder,
//! `tests/integration/axisymmetric_mixed.rs`) stays exact, and the sphere on rubber and the rubber shrink fit
//! there converge without locking (measured; the inf–sup stability of this choice is not proven here).
//!
//! # How A is factorized, and what it does not take
//! A is factorized by LDLᵀ (its inertia checked) and H formed by its columns, or the QPs solve the
//! saddle-point system `[[A, Eᵀ], [E, −Dγ]]`, quasi-definite too with the pressures' pivots negative
//! (the saddle kernel of `linalg` takes A's negative tail). The partial factorization, a Cholesky
//! kernel, is refused. Two bodies take it ([`crate::ContactPair::formulation`]): each has its own nodes, hence
//! its own pressures.
//!
//! # References
//! D. N. Arnold, F. Brezzi, M. Fortin, A stable finite element for the Stokes equations, Calcolo 21 (1984).
//! F. Brezzi, J. Pitkäranta, On the stabilization of finite element approximations of the Stokes
//! equations (1984). F. Ben Belgacem, Y. Renard, L. Slimane, A mixed formulation for the Signorini problem
//! in nearly incompressible elasticity, Appl. Numer. Math. 54 (2005). R. J. Vanderbei, Symmetric
//! quasidefinite matrices, SIAM J. Optim. 5 (1995).

use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

use crate::choice::named_choice;
use crate::error::{Error, Result};
use crate::fem::assemble::{first_unknowns, node_graph, LinearSystem};
use crate::fem::axisymmetric;
use crate::fem::dofs::Dofs;
use crate::fem::elasticity::{element_dofs, strain_displacement, Material, MaterialField, Materials, Model};
use crate::mesh::Mesh;

/// The Poisson's ratio (in-plane, the largest of a body's materials) from which [`Formulation::Auto`] takes the
/// mixed formulation. Measured in study 25 (`docs/locking.md`, Hertz graded to h_min = 0.01 … 0.000625): at
/// ν = 0.49 the P1 displacements' λ_n is 3.3–5.7 times as far from Hertz as the mixed formulation's on the same
/// mesh, more than the mixed solve's cost (about twice P1's: 1.9–2.6) buys by refining P1 (twice the
/// unknowns lower P1's error about twofold there: it falls about like 1/N); at ν = 0.45 it is 1.3–1.8 times,
/// less than that. It is also where `tribo.check_solution` warns of locking. In axisymmetry (the sphere of
/// `tests/integration/axisymmetric_mixed.rs` graded to a/40 and a/80, one run each) the P1 error is 3.0–3.3 times
/// the mixed one at ν = 0.49 for a solve 2.8–3.0 times as long, 1.6–1.8 times at ν = 0.47 for 2.3 times: the same
/// threshold holds there.
pub const MIXED_FROM_POISSON: f64 = 0.49;

/// How the body's unknowns are discretized.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Formulation {
    /// [`Formulation::Mixed`] for a plane-strain or axisymmetric body whose Poisson's ratio reaches
    /// [`MIXED_FROM_POISSON`], [`Formulation::Displacement`] otherwise (plane stress never locks, its in-plane
    /// ν' = ν/(1 + ν) stays below ⅓; a body with a material of ν ≤ 0 beside it keeps P1).
    /// For two bodies, either body's materials decide for both. A built problem holds the choice made
    /// (`problem.spec.formulation`).
    #[default]
    Auto,
    /// P1 displacements alone: the paper's method. Locks as ν → ½.
    Displacement,
    /// P1 displacements and P1 pressures with MINI's condensed bubble (the module documentation): free of
    /// locking up to ν = ½ − √ε/2.
    Mixed,
}

named_choice!(Formulation, "formulation", {
    Formulation::Auto => "auto",
    Formulation::Displacement => "displacement",
    Formulation::Mixed => "mixed",
});

impl Formulation {
    /// Whether the pressure is an unknown.
    pub fn is_mixed(self) -> bool {
        self == Formulation::Mixed
    }

    /// The formulation [`Formulation::Auto`] stands for under `model` with `materials` (their in-plane laws);
    /// the others stand for themselves.
    pub fn resolve(self, model: Model, materials: &Materials) -> Self {
        let nu = materials.materials.iter().fold(f64::NEG_INFINITY, |m, x| m.max(x.poisson));
        // (not where the mixed formulation would refuse a material: ν ≤ 0 beside rubber, say)
        let takes = Formulation::Mixed.validate(materials).is_ok();
        match self {
            Formulation::Auto if model != Model::PlaneStress && nu >= MIXED_FROM_POISSON && takes => Formulation::Mixed,
            Formulation::Auto => Formulation::Displacement,
            f => f,
        }
    }

    /// Checks that this formulation takes every material of `materials` (their in-plane laws), under every model.
    /// One pressure per node is continuous across an interface of materials, where the exact p = −λ div u
    /// jumps: the method stays conforming and converges, the pressure smeared over the interface's triangles.
    ///
    /// # Errors
    /// [`Error::BadMaterial`] for a mixed material with ν ≤ 0 (λ ≤ 0: the pressure block is no longer negative
    /// definite, and such a material does not lock).
    pub fn validate(self, materials: &Materials) -> Result<()> {
        if !self.is_mixed() {
            return Ok(());
        }
        if let Some(m) = materials.materials.iter().find(|m| !(m.poisson > 0.0 && lame(m).0.is_normal())) {
            return Err(Error::BadMaterial {
                what: format!(
                    "the mixed formulation needs Poisson's ratio above 0 (λ > 0), got {} (in-plane); \
                     P1 displacements do not lock there: use formulation = 'displacement'",
                    m.poisson
                ),
            });
        }
        Ok(())
    }
}

/// The shear part of a material's law, `σ = 2μ ε` (E' = 2μ, ν' = 0: the same μ, λ' = 0).
pub fn shear_part(material: &Material) -> Material {
    Material { young: material.young / (1.0 + material.poisson), poisson: 0.0 }
}

/// [`shear_part`] for every region.
pub fn shear_part_all(materials: &Materials) -> Materials {
    Materials { materials: materials.materials.iter().map(shear_part).collect(), region: materials.region.clone() }
}

/// Lamé's λ and μ of a (plane-strain) material.
fn lame(material: &Material) -> (f64, f64) {
    let (e, nu) = (material.young, material.poisson);
    (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)))
}

/// The gradients of triangle t's hats (rows) and its area.
fn hat_gradients(mesh: &Mesh, t: usize) -> (Matrix3x2, f64) {
    let b = strain_displacement(mesh, t);
    (Matrix3x2::from_fn(|i, c| b[(c, 2 * i + c)]), mesh.area(t))
}

type Matrix3x2 = nalgebra::Matrix3x2<f64>;

/// The weight of triangle t's plane integrals under `model`: 1, or `2π r_c` in axisymmetry (its measure in the
/// solid is `2π r_c |T|`, [`crate::fem::axisymmetric::volume`]).
fn weight(model: Model, mesh: &Mesh, t: usize) -> f64 {
    if model.is_axisymmetric() {
        axisymmetric::radial_weight(axisymmetric::centroid_radius(mesh, t))
    } else {
        1.0
    }
}

/// `div v` of triangle t as a linear form of its 6 displacement dofs (constant on T: in axisymmetry
/// `∂_r v_r + ∂_z v_z + v_r / r` with the hoop strain at the centroid, as the displacement element takes it),
/// and the triangle's measure (`|T|`, or `2π r_c |T|`).
fn divergence_form(model: Model, mesh: &Mesh, t: usize) -> ([f64; 6], f64) {
    let (g, area) = hat_gradients(mesh, t);
    let mut form = [0.0; 6];
    for (l, f) in form.iter_mut().enumerate() {
        *f = g[(l / 2, l % 2)];
    }
    if model.is_axisymmetric() {
        let rc = axisymmetric::centroid_radius(mesh, t);
        (0..3).for_each(|i| form[2 * i] += 1.0 / (3.0 * rc));
    }
    (form, weight(model, mesh, t) * area)
}

/// The bubble's condensed pressure coupling of triangle t: `(C_T, X_T K_b⁻¹)` (3 × 3 and 3 × 2), μ its
/// shear modulus (the module documentation).
fn bubble(g: &Matrix3x2, area: f64, mu: f64) -> (Matrix3<f64>, nalgebra::Matrix3x2<f64>) {
    let s: Matrix2<f64> = g.transpose() * g;
    let k_b = (Matrix2::identity() * s.trace() + s) * (mu * 81.0 / 20.0 * area);
    // K_b is a positive multiple of (tr S) I + S with S positive definite on a non-degenerate triangle.
    let k_inv = k_b.try_inverse().unwrap_or_else(Matrix2::zeros);
    let x = g * (9.0 / 20.0 * area);
    let x_kinv = x * k_inv;
    (x_kinv * x.transpose(), x_kinv)
}

/// `B v` per node (N values): `∫ φ_i div v` for the nodal displacement v (2N), with the measure of `model`
/// (φ_i and div v at each triangle's centroid, as every body integral of the element is taken).
pub fn divergence(model: Model, mesh: &Mesh, v: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; mesh.n_nodes()];
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let (form, measure) = divergence_form(model, mesh, t);
        let div: f64 = element_dofs(tri).iter().zip(form).map(|(&d, f)| f * v[d]).sum();
        for &i in tri {
            out[i] += measure / 3.0 * div;
        }
    }
    out
}

/// The pressure rows' part of the body force `f` (N values): `−X_T K_b⁻¹ (9/20) |T| f` of each triangle's
/// condensed bubble (the module documentation; times `2π r_c` in axisymmetry). It scales with the load, as the
/// displacement rows' does.
pub fn bubble_load(model: Model, mesh: &Mesh, in_plane: &impl MaterialField, body_force: [f64; 2]) -> Vec<f64> {
    let mut out = vec![0.0; mesh.n_nodes()];
    let f = Vector2::new(body_force[0], body_force[1]);
    if body_force == [0.0, 0.0] {
        return out;
    }
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let (g, area) = hat_gradients(mesh, t);
        let (_, x_kinv) = bubble(&g, area, lame(in_plane.at(t)).1);
        let load = x_kinv * (f * (9.0 / 20.0 * area * weight(model, mesh, t)));
        tri.iter().enumerate().for_each(|(a, &i)| out[i] -= load[a]);
    }
    out
}

/// The mixed system on the unknowns of `dofs` (displacements, then one pressure per node:
/// [`Dofs::with_pressure`]) from the assembled shear part `shear` (`K_μ` and its lifted load, of the
/// materials' [`shear_part_all`]): the blocks −B, −Bᵀ and −(M/λ + C), and the pressure rows' load (the
/// bubble's body force and `B ū` of the prescribed displacements).
///
/// # Errors
/// [`Error::Assembly`] for a non-finite entry or a matrix faer cannot build.
pub fn assemble_mixed(
    model: Model,
    mesh: &Mesh,
    in_plane: &impl MaterialField,
    body_force: [f64; 2],
    shear: LinearSystem,
    dofs: &Dofs,
) -> Result<LinearSystem> {
    let (n_u, n, n_nodes) = (dofs.n_displacement, dofs.n_free, mesh.n_nodes());
    let first = first_unknowns(dofs);
    let (adj_ptr, adj) = node_graph(mesh);
    // Every column of node i (its displacement unknowns and its pressure) has the same rows, straight into
    // compressed columns from the mesh graph as K is (`fem::assemble`): the displacement unknowns of i's
    // neighbours (K_μ's rows there, in its order), then their pressures.
    let u_rows = |i: usize| adj[adj_ptr[i]..adj_ptr[i + 1]].iter().map(|&m| first[m as usize + 1] - first[m as usize]);
    let count = |i: usize| u_rows(i).sum::<usize>() + (adj_ptr[i + 1] - adj_ptr[i]);
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0usize);
    let columns = (0..n_nodes).flat_map(|i| std::iter::repeat_n(i, first[i + 1] - first[i])).chain(0..n_nodes);
    for i in columns.clone() {
        col_ptr.push(col_ptr.last().copied().unwrap_or(0) + count(i));
    }
    let mut row_idx = Vec::with_capacity(col_ptr[n]);
    for i in columns {
        let list = &adj[adj_ptr[i]..adj_ptr[i + 1]];
        list.iter().for_each(|&m| row_idx.extend(first[m as usize]..first[m as usize + 1]));
        row_idx.extend(list.iter().map(|&m| n_u + m as usize));
    }
    let mut values = vec![0.0; col_ptr[n]];
    let k = shear.k_matrix.as_ref();
    for j in 0..n_u {
        let v = k.val_of_col(j);
        values[col_ptr[j]..col_ptr[j] + v.len()].copy_from_slice(v);
    }
    // The entry of row `r` in column `c` (both in the triangle's pattern).
    let at = |c: usize, r: usize| col_ptr[c] + row_idx[col_ptr[c]..col_ptr[c + 1]].binary_search(&r).unwrap_or(0);
    let mut f_p = bubble_load(model, mesh, in_plane, body_force);
    let lifted = divergence(model, mesh, &dofs.lifting);
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let (g, area) = hat_gradients(mesh, t);
        let (form, measure) = divergence_form(model, mesh, t);
        let w = weight(model, mesh, t);
        let (lambda, mu) = lame(in_plane.at(t));
        let (c, _) = bubble(&g, area, mu);
        for (a, &i) in tri.iter().enumerate() {
            let p = n_u + i;
            for (l, &d) in element_dofs(tri).iter().enumerate() {
                // −∫ φ_i div(φ_d e_c) = −|T|/3 ∂_c φ_j (and the hoop strain's part of a radial dof).
                if let Some((col, coeff)) = dofs.unknown(d) {
                    let v = -measure / 3.0 * form[l] * coeff;
                    values[at(col, p)] += v;
                    values[at(p, col)] += v;
                }
            }
            for (b, &j) in tri.iter().enumerate() {
                let mass = area / 12.0 * if a == b { 2.0 } else { 1.0 };
                values[at(n_u + j, p)] -= w * (mass / lambda + c[(a, b)]);
            }
        }
    }
    // −B ū moved to the right: the pressure rows' load is B ū (the lifting's divergence).
    f_p.iter_mut().zip(&lifted).for_each(|(fp, l)| *fp += l);
    if let Some(e) = values.iter().position(|v| !v.is_finite()) {
        return Err(Error::Assembly { matrix: "the mixed system", what: format!("non-finite entry {e}") });
    }
    if let Some(i) = f_p.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteLoad { target: format!("the pressure row of node {i}"), x: f_p[i], y: f64::NAN });
    }
    // faer's checks hold by construction: col_ptr adds counts, and each column's rows increase (the
    // neighbour lists are sorted, the displacement unknowns numbered node by node, the pressures after them).
    let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    let mut f_free = shear.f_free;
    f_free.extend(f_p);
    Ok(LinearSystem { k_matrix: SparseColMat::new(pattern, values), f_free, f_full: shear.f_full })
}

/// The constant stress `(σ_xx, σ_yy, σ_xy, σ_zz)` of every triangle, `2μ ε(u) − p̄_T I` (p̄_T the mean of
/// the nodal pressure p on T), σ_zz = −p̄_T in plane strain and 0 in plane stress; in axisymmetry
/// `(σ_rr, σ_zz, σ_rz, σ_θθ)` with σ_θθ = 2μ ε_θθ − p̄_T (the hoop strain at the centroid).
pub fn element_stresses(
    model: Model,
    mesh: &Mesh,
    in_plane: &impl MaterialField,
    u: &[f64],
    p: &[f64],
) -> Vec<[f64; 4]> {
    mesh.triangles()
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let ut = nalgebra::SVector::<f64, 6>::from_fn(|l, _| u[element_dofs(tri)[l]]);
            let mean = tri.iter().map(|&i| p[i]).sum::<f64>() / 3.0;
            if model.is_axisymmetric() {
                let s = axisymmetric::element_stress(mesh, t, &shear_part(in_plane.at(t)), &ut);
                return [s[0] - mean, s[1] - mean, s[2], s[3] - mean];
            }
            let s: Vector3<f64> = shear_part(in_plane.at(t)).elasticity_matrix() * (strain_displacement(mesh, t) * ut);
            let zz = if model == Model::PlaneStrain { -mean } else { 0.0 };
            [s[0] - mean, s[1] - mean, s[2], zz]
        })
        .collect()
}

/// The energy norm of the mixed formulation, `sqrt(∫ 2μ ε(u):ε(u) + ∫ p²/λ)` (the second term exact for P1 p in
/// the plane: `∫_T p² = |T|/12 ((Σ pᵢ)² + Σ pᵢ²)`, times `2π r_c` in axisymmetry, as the pressure block's mass),
/// `materials` the in-plane laws. The displacement formulation's
/// `∫ ε:C ε` would read λ (div u)², which the mixed formulation does not make small pointwise.
pub fn energy_norm(model: Model, mesh: &Mesh, in_plane: &Materials, u: &[f64], p: &[f64]) -> f64 {
    let shear = crate::fem::elasticity::energy_norm(model, mesh, &shear_part_all(in_plane), u);
    let volumetric: f64 = mesh
        .triangles()
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let (sum, squares) = tri.iter().fold((0.0, 0.0), |(s, q), &i| (s + p[i], q + p[i] * p[i]));
            weight(model, mesh, t) * mesh.area(t) / 12.0 * (sum * sum + squares) / lame(in_plane.at(t)).0
        })
        .sum();
    (shear * shear + volumetric).sqrt()
}
