//! Straight lines through mesh nodes: the one geometric tolerance of the crate for "on a line"
//! (Γ_C's straightness, multiplier points snapped to its ends, rollers on straight edges) and the test
//! that a set of edges lies on one line.

use crate::mesh::Mesh;

/// Relative geometric tolerance on Γ_C (straightness, snapping of multiplier points): `√ε`.
pub fn geometric_tol_rel() -> f64 {
    f64::EPSILON.sqrt()
}

/// The first node of `edges` that lies off the line of the first edge (unit normal `normal`) by more than
/// `√ε` times the local edge length (the shorter of its own edge and the first one), as
/// `(node, distance, length of its edge)`; `None` when the edges are straight. `edges` is not empty.
pub(crate) fn off_line(mesh: &Mesh, edges: &[[usize; 2]], normal: [f64; 2]) -> Option<(usize, f64, f64)> {
    let pts = mesh.points();
    let [a0, b0] = edges[0];
    let (pa, len0) = (pts[a0], mesh.edge_length(a0, b0));
    let tol = geometric_tol_rel();
    edges.iter().find_map(|&[a, b]| {
        let length = mesh.edge_length(a, b);
        [a, b].into_iter().find_map(|node| {
            let p = pts[node];
            let distance = ((p[0] - pa[0]) * normal[0] + (p[1] - pa[1]) * normal[1]).abs();
            (distance > tol * length.min(len0)).then_some((node, distance, length))
        })
    })
}
