//! What the estimator reads of each contact pair's Γ_C ([`SideInput`]), the weights of the traction estimate near
//! the sides, and the pieces on which the penetration is integrated (see [`crate::results::estimator`]).

use crate::contact::multiplier::MultiplierMesh;
use crate::contact::ContactBoundary;
use crate::mesh::Mesh;
use crate::results::SUBDIVISIONS;

/// What the estimator reads of one contact pair: its side, T_H and the fields on them.
pub(crate) struct SideInput<'a> {
    pub contact: &'a ContactBoundary,
    pub multipliers: &'a MultiplierMesh,
    pub lambda_n: &'a [f64],
    pub lambda_t: &'a [f64],
    pub threshold: &'a [f64],
    /// u_n and the slip at the FE nodes of Γ_C.
    pub u_n: &'a [f64],
    pub slip: &'a [f64],
    /// The displacement at the FE nodes of Γ_C from which the slip is measured (`u^{k−1}` in a history), and
    /// today's (the jump `u¹ − u²∘Π` for two bodies, as both).
    pub previous_u: &'a [[f64; 2]],
    pub contact_u: &'a [[f64; 2]],
    /// The gap g(ξ) of this load case, anywhere on Γ_C.
    pub gap: &'a dyn Fn(f64) -> f64,
    /// The abscissae where the gap may have a local minimum between the FE nodes (the obstacle's lowest
    /// points, [`crate::ObstacleShape::lowest_points`]), sorted.
    pub lowest: &'a [f64],
}

/// The pieces of the FE edge `[x0, x1]` on which the penetration is integrated: [`SUBDIVISIONS`] equal ones,
/// and around each of the obstacle's `lowest` points inside the edge, pieces halving toward it down to
/// 2⁻⁵² of the edge. An obstacle that dips below Γ_C only near its lowest point (a cylinder pushed 1e-6
/// between two nodes of a coarse mesh: a dip 3e-3 wide under an edge of 0.5) is then seen, whatever the
/// width of the dip (defect D28: the equal pieces' Gauss points missed it, the estimate was 0, and the
/// adaptive loop stopped on a mesh that had not found the contact).
pub(crate) fn penetration_pieces(x0: f64, x1: f64, lowest: &[f64]) -> Vec<f64> {
    let h = (x1 - x0) / SUBDIVISIONS as f64;
    let mut out: Vec<f64> = (0..=SUBDIVISIONS).map(|m| x0 + h * m as f64).collect();
    out[SUBDIVISIONS] = x1;
    // `lowest` is sorted: the points inside the edge are one slice (a polyline of many vertices costs
    // each edge a search, not a scan).
    let inside = &lowest[lowest.partition_point(|&c| c <= x0)..lowest.partition_point(|&c| c < x1)];
    for &c in inside {
        out.push(c);
        let mut d = x1 - x0;
        for _ in 0..52 {
            d *= 0.5;
            out.extend([c - d, c + d].into_iter().filter(|&x| x > x0 && x < x1));
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The weight `w_K = h_K² / (h_K + d_K)³` of each triangle in the traction estimate `ζ² = Σ_K w_K η_K²`
/// (see the module documentation): h_K the diameter of K, d_K the distance from K's nearest vertex to
/// the segment Γ_C.
pub(crate) fn traction_weights(mesh: &Mesh, contact: &ContactBoundary) -> Vec<f64> {
    if contact.node_xi.is_empty() {
        return vec![0.0; mesh.n_triangles()];
    }
    // Each node's distance once, shared by its triangles (on a bent Γ_C by a hierarchy of its facets' boxes).
    let distance = contact.distances(mesh.points());
    mesh.triangles()
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let h = mesh.diameter(t);
            let dist = tri.iter().map(|&v| distance[v]).fold(f64::INFINITY, f64::min);
            h * h / (h + dist).powi(3)
        })
        .collect()
}

/// The traction weights near any of the `sides`: the largest of the sides' own ([`traction_weights`]).
pub(crate) fn side_weights(mesh: &Mesh, sides: &[SideInput<'_>]) -> Vec<f64> {
    let near = |w: Vec<f64>, side: &SideInput<'_>| {
        w.iter().zip(traction_weights(mesh, side.contact)).map(|(a, b)| a.max(b)).collect()
    };
    sides.iter().fold(vec![0.0; mesh.n_triangles()], near)
}
