//! Global assembly on the unknowns: the load vector over all 2N dofs (body force and tractions), the
//! stiffness `Tᵀ K T` on the unknowns the supports leave, and the load with the prescribed
//! displacements lifted, `Tᵀ (f − K ū)` (see [`crate::fem::supports`]). The γ0-dependent part of the
//! lifting, through G, is added when A is factorized ([`crate::Problem::condense_with`]).

use faer::sparse::{SparseColMat, Triplet};

use crate::error::{Error, Result};
use crate::fem::dofs::Dofs;
use crate::fem::elasticity::{add_body_force, add_traction, stiffness_triplets, MaterialField};
use crate::mesh::Mesh;

/// The assembled linear system of the body before contact.
#[derive(Debug, Clone)]
pub struct LinearSystem {
    /// `Tᵀ K T` (CSC, both triangles).
    pub k_matrix: SparseColMat<usize, f64>,
    /// `Tᵀ (f − K ū)`.
    pub f_free: Vec<f64>,
    /// The load f on all 2N dofs.
    pub f_full: Vec<f64>,
}

/// Assembles the load and the stiffness on the unknowns of `dofs`.
///
/// # Errors
/// [`Error::NonFiniteLoad`] for a non-finite load (as given, assembled or lifted); [`Error::Assembly`]
/// for a non-finite stiffness entry or a matrix faer cannot build.
pub fn assemble(
    mesh: &Mesh,
    material: &impl MaterialField,
    body_force: [f64; 2],
    tractions: &[(String, [f64; 2])],
    dofs: &Dofs,
) -> Result<LinearSystem> {
    let n_dofs = 2 * mesh.n_nodes();
    let n_free = dofs.n_free;
    for (name, f) in [("body".to_string(), body_force)].iter().chain(tractions) {
        if !(f[0].is_finite() && f[1].is_finite()) {
            return Err(Error::NonFiniteLoad { target: name.clone(), x: f[0], y: f[1] });
        }
    }
    let mut f_full = vec![0.0; n_dofs];
    add_body_force(mesh, body_force, &mut f_full);
    for (set, g) in tractions {
        add_traction(mesh, mesh.edge_set(set)?, *g, &mut f_full);
    }
    if let Some(d) = f_full.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteLoad {
            target: format!("the assembled load at dof {d}"),
            x: f_full[d],
            y: f64::NAN,
        });
    }
    // K over all dofs, then `Tᵀ K T` (faer sums the duplicates a rotated node's two dofs give) and
    // the lifting `K ū` of the prescribed displacements.
    let k_full = stiffness_triplets(mesh, material);
    let mut k_lift = vec![0.0; n_dofs];
    let mut k_free = Vec::with_capacity(k_full.len());
    for t in &k_full {
        if !t.val.is_finite() {
            return Err(Error::Assembly { matrix: "K", what: format!("entry ({}, {}) is {}", t.row, t.col, t.val) });
        }
        k_lift[t.row] += t.val * dofs.lifting[t.col];
        if let (Some((i, a)), Some((j, b))) = (dofs.unknown(t.row), dofs.unknown(t.col)) {
            k_free.push(Triplet::new(i, j, a * b * t.val));
        }
    }
    drop(k_full);
    let f_lifted: Vec<f64> = f_full.iter().zip(&k_lift).map(|(f, k)| f - k).collect();
    if let Some(d) = f_lifted.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteLoad {
            target: format!("the load with the prescribed displacements lifted, at dof {d}"),
            x: f_lifted[d],
            y: f64::NAN,
        });
    }
    let f_free = dofs.restrict(&f_lifted);
    let k_matrix = SparseColMat::try_new_from_triplets(n_free, n_free, &k_free)
        .map_err(|e| Error::Assembly { matrix: "K", what: format!("{e:?}") })?;
    drop(k_free);
    Ok(LinearSystem { k_matrix, f_free, f_full })
}
