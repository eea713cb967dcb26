//! Global assembly on the unknowns: the load vector over all 2N dofs (body force and tractions), the
//! stiffness `Tᵀ K T` on the unknowns the supports leave, and the load with the prescribed
//! displacements lifted, `Tᵀ (f − K ū)` (see [`crate::fem::supports`]). The γ0-dependent part of the
//! lifting, through G, is added when A is factorized ([`crate::Problem::condense_with`]).

use faer::sparse::{SparseColMat, SymbolicSparseColMat};

use crate::error::{Error, Result};
use crate::fem::dofs::Dofs;
use crate::fem::elasticity::{
    add_body_force, add_traction, element_dofs, element_stiffness_of, MaterialField, Model, Traction,
};
use crate::fem::supports::NodeSupport;
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
    model: Model,
    mesh: &Mesh,
    material: &impl MaterialField,
    body_force: [f64; 2],
    tractions: &[(String, Traction)],
    dofs: &Dofs,
) -> Result<LinearSystem> {
    let n_dofs = 2 * mesh.n_nodes();
    let given = tractions.iter().map(|(name, t)| (name.clone(), t.components()));
    for (name, f) in [("body".to_string(), body_force)].into_iter().chain(given) {
        if !(f[0].is_finite() && f[1].is_finite()) {
            return Err(Error::NonFiniteLoad { target: name, x: f[0], y: f[1] });
        }
    }
    let mut f_full = vec![0.0; n_dofs];
    add_body_force(model, mesh, body_force, &mut f_full);
    for (set, g) in tractions {
        add_traction(model, mesh, mesh.edge_set(set)?, *g, &mut f_full);
    }
    if let Some(d) = f_full.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteLoad {
            target: format!("the assembled load at dof {d}"),
            x: f_full[d],
            y: f64::NAN,
        });
    }
    let (k_matrix, k_lift) = stiffness_on_unknowns(model, mesh, material, dofs)?;
    let f_lifted: Vec<f64> = f_full.iter().zip(&k_lift).map(|(f, k)| f - k).collect();
    if let Some(d) = f_lifted.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteLoad {
            target: format!("the load with the prescribed displacements lifted, at dof {d}"),
            x: f_lifted[d],
            y: f64::NAN,
        });
    }
    let f_free = dofs.restrict(&f_lifted);
    Ok(LinearSystem { k_matrix, f_free, f_full })
}

/// `Tᵀ K T` straight into compressed columns, and `K ū` (2N) on the way.
///
/// The pattern comes from the mesh graph: the unknowns are numbered node by node (two at a free node, one
/// at a sliding node, none at a fixed one), so column k of node i holds, in increasing order, the unknowns
/// of every node that shares a triangle with i. The element matrices are then added in place, triangle by
/// triangle in mesh order, so that each entry is summed in one fixed order (the matrix does not depend on
/// the thread count). No triplet list of the whole matrix is ever held: the memory is K's own plus the
/// node graph.
///
/// # Errors
/// [`Error::Assembly`] for a non-finite element entry or a mesh too large for 32-bit node indices.
fn stiffness_on_unknowns(
    model: Model,
    mesh: &Mesh,
    material: &impl MaterialField,
    dofs: &Dofs,
) -> Result<(SparseColMat<usize, f64>, Vec<f64>)> {
    let n_nodes = mesh.n_nodes();
    let n_free = dofs.n_free;
    let too_large = || Error::Assembly { matrix: "K", what: format!("{n_nodes} nodes: more than 2³² − 1") };
    u32::try_from(n_nodes).map_err(|_| too_large())?;
    let first = first_unknowns(dofs);
    debug_assert_eq!(first[n_nodes], n_free);
    let (adj_ptr, adj) = node_graph(mesh);
    // Per entry p of node i's neighbour list: the offset, in each column of node i, of the first row of
    // that neighbour's unknowns.
    let mut offset = vec![0usize; adj.len()];
    let mut col_ptr = Vec::with_capacity(n_free + 1);
    col_ptr.push(0usize);
    for i in 0..n_nodes {
        let mut o = 0;
        for p in adj_ptr[i]..adj_ptr[i + 1] {
            offset[p] = o;
            let m = adj[p] as usize;
            o += first[m + 1] - first[m];
        }
        for _ in first[i]..first[i + 1] {
            col_ptr.push(col_ptr.last().copied().unwrap_or(0) + o);
        }
    }
    let nnz = col_ptr[n_free];
    let mut row_idx = Vec::with_capacity(nnz);
    for i in 0..n_nodes {
        for _ in first[i]..first[i + 1] {
            for &m in &adj[adj_ptr[i]..adj_ptr[i + 1]] {
                row_idx.extend(first[m as usize]..first[m as usize + 1]);
            }
        }
    }
    let mut values = vec![0.0; nnz];
    let mut k_lift = vec![0.0; 2 * n_nodes];
    let lifted = !dofs.homogeneous();
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let k = element_stiffness_of(model, mesh, t, material.at(t));
        let el = element_dofs(tri);
        if let Some(e) = k.iter().position(|v| !v.is_finite()) {
            let (r, c) = (e % 6, e / 6);
            return Err(Error::Assembly { matrix: "K", what: format!("entry ({}, {}) is {}", el[r], el[c], k[e]) });
        }
        if lifted {
            for (c, &dc) in el.iter().enumerate() {
                let u = dofs.lifting[dc];
                if u != 0.0 {
                    for (r, &dr) in el.iter().enumerate() {
                        k_lift[dr] += k[(r, c)] * u;
                    }
                }
            }
        }
        // The unknowns of the triangle's six dofs, looked up once (the scatter below is most of the assembly's
        // time: 27 → 19 ms at 55k unknowns with this and the linear search).
        let unknowns: [Option<(usize, f64)>; 6] = std::array::from_fn(|l| dofs.unknown(el[l]));
        for (b, &nb) in tri.iter().enumerate() {
            // The column's node nb; each row node's place in nb's neighbour list (na shares triangle t with nb,
            // so it is in nb's list: a short one, searched in order).
            let list = &adj[adj_ptr[nb]..adj_ptr[nb + 1]];
            for (a, &na) in tri.iter().enumerate() {
                let p = adj_ptr[nb] + list.iter().position(|&m| m == na as u32).unwrap_or(0);
                for cb in 0..2 {
                    let Some((kj, wb)) = unknowns[2 * b + cb] else { continue };
                    let column = col_ptr[kj] + offset[p];
                    for ca in 0..2 {
                        let Some((ki, wa)) = unknowns[2 * a + ca] else { continue };
                        values[column + (ki - first[na])] += wa * wb * k[(2 * a + ca, 2 * b + cb)];
                    }
                }
            }
        }
    }
    // faer's checks hold by construction, whatever the mesh: col_ptr starts at 0 and never decreases (it
    // adds counts), and each column's rows are below n_free and increasing (the neighbour lists are
    // sorted and deduplicated, and the unknowns are numbered node by node).
    let pattern = SymbolicSparseColMat::new_checked(n_free, n_free, col_ptr, None, row_idx);
    Ok((SparseColMat::new(pattern, values), k_lift))
}

/// The first displacement unknown of each node, and their count after the last: the unknowns of node i are
/// `first[i]..first[i + 1]` (numbered node by node).
pub(crate) fn first_unknowns(dofs: &Dofs) -> Vec<usize> {
    let mut first = Vec::with_capacity(dofs.nodes.len() + 1);
    first.push(0usize);
    for ns in &dofs.nodes {
        let count = match ns {
            NodeSupport::Free => 2,
            NodeSupport::Slide { .. } => 1,
            NodeSupport::Fixed { .. } => 0,
        };
        first.push(first.last().copied().unwrap_or(0) + count);
    }
    first
}

/// The nodes that share a triangle with each node (itself included), sorted: node i's are
/// `adj[ptr[i]..ptr[i + 1]]` (32-bit indices, checked by the caller).
pub(crate) fn node_graph(mesh: &Mesh) -> (Vec<usize>, Vec<u32>) {
    let n = mesh.n_nodes();
    let mut ptr = vec![0usize; n + 1];
    for tri in mesh.triangles() {
        for &a in tri {
            ptr[a + 1] += 3;
        }
    }
    for i in 0..n {
        ptr[i + 1] += ptr[i];
    }
    let mut fill = ptr.clone();
    let mut all = vec![0u32; ptr[n]];
    for tri in mesh.triangles() {
        for &a in tri {
            for &b in tri {
                all[fill[a]] = b as u32;
                fill[a] += 1;
            }
        }
    }
    drop(fill);
    // Sort and deduplicate each list, compacting in place.
    let mut write = 0;
    let mut start = 0;
    for i in 0..n {
        let end = ptr[i + 1];
        all[start..end].sort_unstable();
        let begin = write;
        for r in start..end {
            if write == begin || all[r] != all[write - 1] {
                all[write] = all[r];
                write += 1;
            }
        }
        ptr[i] = begin;
        start = end;
    }
    ptr[n] = write;
    all.truncate(write);
    all.shrink_to_fit();
    (ptr, all)
}
