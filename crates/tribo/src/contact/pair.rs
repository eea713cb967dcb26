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
//!
//! # Bent interfaces
//! Either side may be a chain of edges (the faceted arcs of a shrink fit, a pin in a hole). Then:
//! - **Π** maps each primary node to the abscissa of its nearest point on the secondary chain (its end edges
//!   extended), and `u² ∘ Π` is the primary trace interpolated linearly in that abscissa between consecutive
//!   primary nodes. As h → 0 this is the normal projection of the secondary side onto the primary one
//!   (the two differ by the curvature times the gap times h); on coinciding straight lines it is the
//!   identity, as above.
//! - **The frames** are the secondary edges': `B`'s primary term is integrated edge by edge of the secondary
//!   chain, `−Σ_e Σ_i M2²_e[i, j] (v²_i · n_e)` (and `· t_e`), on the common refinement of the secondary
//!   nodes, the projected primary nodes and T_H.
//! - **The initial gap comes from the geometry**, `g₀(ξ) = ±|y − x|` with `x` the secondary point at ξ and
//!   `y` the primary point facing it, positive where `y − x` points along the secondary normal n_e (a
//!   clearance) and negative where the two bodies overlap (an interference fit). Where both edge sets carry
//!   their exact curves ([`crate::Curve`]), x is the point of the secondary curve nearest the facet point and
//!   y the point of the primary curve nearest x: concentric circles of radii R and R + δ then have the gap
//!   −δ everywhere, whatever the two facetings. Without curves, `y = x²(Π ξ)` on the primary facets and the
//!   gap is `(y − x) · n_e`: the facets' departure from the true surfaces, up to `h²/(8R)` on each side,
//!   enters the gap, which on a conforming interface is a pressure error of order `h/(8δ)` relative (so
//!   give conforming sides their curves). A gap shape given with the pair adds to this gap.
//! - **Small sliding.** The reference configuration is the one the contact is written in: a primary node
//!   farther than a tenth of the secondary side's length from it, or a primary edge that does not face the
//!   secondary side (its outward normal along the secondary's), is refused.

use std::collections::HashMap;

use crate::contact::mortar::{common_refinement, Coo, GAUSS2, GAUSS4};
use crate::contact::multiplier::MultiplierMesh;
use crate::contact::{ContactBoundary, ContactEdge};
use crate::error::{Error, Result};
use crate::fem::axisymmetric::radial_weight;
use crate::fem::elasticity::Model;
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::{Curve, Mesh, Point};

/// `(primary node, multiplier dof, secondary edge, value)`: a part of M2² on one secondary edge.
pub type EdgeEntry = (usize, usize, usize, f64);

/// The primary side of a contact pair.
#[derive(Debug, Clone)]
pub struct PrimarySide {
    /// The primary contact line Γ_C² (its own normal, opposite to the secondary's), its nodes in the order
    /// of `xi`.
    pub boundary: ContactBoundary,
    /// Abscissae of `boundary.nodes` on the secondary side (the projection Π), increasing.
    pub xi: Vec<f64>,
    /// `∫_{Γ_C} φ²_i ψ_j` (p₂ × q), φ² the primary's P1 traces.
    pub m2: Coo,
    /// On a bent secondary side, `m2` edge by edge of it: `(i, j, secondary edge, ∫_{E_e} φ²_i ψ_j)`; empty
    /// where the secondary side is straight.
    pub m2_edges: Vec<EdgeEntry>,
    /// The gap from the two sides' geometry where either is bent (module documentation); `None` for two
    /// straight sides on one line.
    pub geometry: Option<PairGeometry>,
}

/// The initial gap between two sides, from their geometry.
#[derive(Debug, Clone)]
pub struct PairGeometry {
    /// The exact curves of the secondary and the primary side, when both edge sets carry one.
    pub curves: Option<[Curve; 2]>,
    /// `∫_{Γ_C} ψ_j g₀` (q).
    pub gap_moments: Vec<f64>,
    /// g₀ at the secondary side's nodes (in the order of its `nodes`, along each node's normal).
    pub node_gap: Vec<f64>,
}

impl PrimarySide {
    /// The primary side `set` of `mesh` against the secondary side `secondary` and its multiplier mesh.
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`] and the errors of [`ContactBoundary::new`]; [`Error::ContactPair`] when two
    /// straight sides are not one line with opposite normals, when the primary does not cover the secondary,
    /// when its nodes are not ordered along it, and, for a bent side, when a primary edge does not face the
    /// secondary side or a primary node lies beyond the small-sliding range (module documentation).
    pub fn new(
        mesh: &Mesh,
        secondary: &ContactBoundary,
        set: &str,
        mult: &MultiplierMesh,
        model: Model,
    ) -> Result<Self> {
        let mut boundary = ContactBoundary::new(mesh, set)?;
        let bad =
            |what: String| Error::ContactPair { secondary: secondary.set.clone(), primary: set.to_string(), what };
        let tol = geometric_tol_rel();
        let pts = mesh.points();
        let scale = boundary.edges.iter().map(|e| e.length).fold(0.0, f64::max).max(secondary.length());
        if secondary.is_closed() != boundary.is_closed() {
            let (closed, open) = if secondary.is_closed() { (secondary, &boundary) } else { (&boundary, secondary) };
            return Err(bad(format!(
                "the side '{}' is a closed loop and '{}' is not: two bodies take two open sides or two loops",
                closed.set, open.set
            )));
        }
        let straight = secondary.is_straight() && boundary.is_straight();
        if straight {
            let (n1, n2) = (secondary.normal, boundary.normal);
            let misalignment = (n1[0] + n2[0]).hypot(n1[1] + n2[1]);
            if misalignment > tol {
                return Err(bad(format!(
                    "the normals ({:.6}, {:.6}) and ({:.6}, {:.6}) are not opposite: the two contact lines must be one \
                     line, the bodies on either side of it",
                    n1[0], n1[1], n2[0], n2[1]
                )));
            }
            for &node in &boundary.nodes {
                let off = secondary.distance_to_line(pts[node]);
                if off.abs() > tol * scale {
                    return Err(bad(format!(
                        "primary node {node} lies {off:.3e} off the secondary line (two straight sides must \
                         coincide in the reference configuration; give an initial gap with the gap shape instead)"
                    )));
                }
            }
        }
        let mut xi: Vec<f64> = boundary.nodes.iter().map(|&node| secondary.abscissa(pts[node])).collect();
        if boundary.is_closed() {
            xi = unroll(&mut boundary, xi, secondary.start(), secondary.length()).ok_or_else(|| {
                bad("the primary loop's nodes do not go round the secondary loop in one turn".to_string())
            })?;
        } else if !straight && xi[0] > xi[xi.len() - 1] {
            reverse(&mut boundary);
            xi.reverse();
        }
        if xi.windows(2).any(|w| w[1] <= w[0]) {
            return Err(bad("the primary nodes are not ordered along the secondary side".to_string()));
        }
        let mut slack = tol * scale;
        if !straight {
            let reach = 0.1 * secondary.length();
            for &node in &boundary.nodes {
                let off = secondary.distance_to_line(pts[node]).abs();
                if off > reach {
                    return Err(bad(format!(
                        "primary node {node} lies {off:.3e} from the secondary side, beyond the small-sliding range \
                         (a tenth of its length, {reach:.3e}): the contact is written in the reference configuration, \
                         where the two sides must nearly touch"
                    )));
                }
                slack = slack.max(tol * scale + off);
            }
            for e in &boundary.edges {
                let (a, b) = (pts[e.left], pts[e.right]);
                let x = secondary.abscissa([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
                let n1 = secondary.edges[secondary.edge_at(x)].outward;
                if e.outward[0] * n1[0] + e.outward[1] * n1[1] >= 0.0 {
                    return Err(bad(format!(
                        "the primary edge ({}, {}) does not face the secondary side: its outward normal ({:.4}, \
                         {:.4}) points the way of the secondary's ({:.4}, {:.4}) (is it the side of the other body \
                         that touches?)",
                        e.left, e.right, e.outward[0], e.outward[1], n1[0], n1[1]
                    )));
                }
            }
        }
        let (start, end) = (secondary.start(), secondary.end());
        let (lo, hi) = (xi[0], xi[xi.len() - 1]);
        if lo > start + slack || hi < end - slack {
            return Err(bad(format!(
                "the primary side [{lo}, {hi}] does not cover the secondary side [{start}, {end}] (abscissae on the \
                 secondary side): every point of Γ_C must face the other body"
            )));
        }
        let curves = match (mesh.curves().get(&secondary.set), mesh.curves().get(set)) {
            (Some(a), Some(b)) if !straight => Some([*a, *b]),
            _ => None,
        };
        // The measure at abscissa x: 1, or 2π r on the secondary side.
        let measure = |x: f64| if model.is_axisymmetric() { radial_weight(secondary.point_at(x)[0]) } else { 1.0 };
        let mut side = Self { boundary, xi, m2: Coo::default(), m2_edges: Vec::new(), geometry: None };
        let gap = |x: f64, n: [f64; 2]| geometric_gap(&side, secondary, curves.as_ref(), x, n);
        let (m2, m2_edges, gap_moments) = primary_mortar(&side.xi, secondary, mult, &measure, !straight, &gap);
        let geometry = (!straight).then(|| {
            let node_gap = (0..secondary.nodes.len())
                .map(|k| {
                    geometric_gap(&side, secondary, curves.as_ref(), secondary.node_xi[k], secondary.node_normal(k))
                })
                .collect();
            PairGeometry { curves, gap_moments, node_gap }
        });
        side.m2 = m2;
        side.m2_edges = m2_edges;
        side.geometry = geometry;
        Ok(side)
    }

    /// The primary edge at abscissa `x` and the barycentric weight of its right node.
    fn locate(&self, x: f64) -> (usize, f64) {
        let k = self.xi.partition_point(|&y| y <= x).clamp(1, self.xi.len() - 1) - 1;
        (k, ((x - self.xi[k]) / (self.xi[k + 1] - self.xi[k])).clamp(0.0, 1.0))
    }

    /// The primary body's displacement `u²(Π ξ)` at abscissa `xi` of the secondary side, from the nodal
    /// displacement `u` over all 2N dofs.
    pub fn displacement_at(&self, xi: f64, u: &[f64]) -> [f64; 2] {
        let (k, s) = self.locate(xi);
        let (a, b) = (self.boundary.nodes[k], self.boundary.nodes[k + 1]);
        [0, 1].map(|c| (1.0 - s) * u[2 * a + c] + s * u[2 * b + c])
    }

    /// Each primary edge (as its `[min, max]` node pair) with the abscissae it spans on the secondary side: one
    /// span, but two for the edge of a loop that straddles the cut (its ends of the turn, each clipped to it).
    pub fn edge_spans(&self, secondary: &ContactBoundary) -> HashMap<[usize; 2], Vec<[f64; 2]>> {
        let (start, end, closed) = (secondary.start(), secondary.end(), secondary.is_closed());
        let mut spans: HashMap<[usize; 2], Vec<[f64; 2]>> = HashMap::new();
        for (w, x) in self.boundary.nodes.windows(2).zip(self.xi.windows(2)) {
            let (a, b) = if closed { (x[0].max(start), x[1].min(end)) } else { (x[0], x[1]) };
            if a < b {
                spans.entry([w[0].min(w[1]), w[0].max(w[1])]).or_default().push([a, b]);
            }
        }
        spans
    }

    /// The primary side's point `x²(Π ξ)` facing abscissa `xi` of the secondary side (on its facets).
    pub fn point_at(&self, xi: f64) -> Point {
        let (k, s) = self.locate(xi);
        let (a, b) = (self.boundary.node_points[k], self.boundary.node_points[k + 1]);
        [0, 1].map(|c| (1.0 - s) * a[c] + s * b[c])
    }

    /// The initial gap from the geometry at abscissa `xi` of `secondary` (0 for two straight sides on one
    /// line, whose gap is the pair's gap shape alone).
    pub fn gap_at(&self, secondary: &ContactBoundary, xi: f64) -> f64 {
        match &self.geometry {
            Some(g) => geometric_gap(self, secondary, g.curves.as_ref(), xi, secondary.normal_at(xi)),
            None => 0.0,
        }
    }
}

/// The mean over a primary contact edge `[xa, xb]` (abscissae on the secondary side, `contact`) of
/// `|σ² n² − (λ_n n + λ_t t)|²`, the body's traction `s = σ² n²` against the reaction of the multiplier
/// (zero beyond Γ_C; n, t of the secondary edge facing each point), by 2-point Gauss on the pieces T_H cuts it into (exact: λ is piecewise linear).
pub fn traction_residual(
    contact: &ContactBoundary,
    mult: &MultiplierMesh,
    [lambda_n, lambda_t]: [&[f64]; 2],
    s: [f64; 2],
    [xa, xb]: [f64; 2],
) -> f64 {
    // The T_H points strictly inside the edge (mult.xi is increasing): a slice, not a scan of all of T_H.
    let inside = &mult.xi[mult.xi.partition_point(|&x| x <= xa)..mult.xi.partition_point(|&x| x < xb)];
    let mut breaks = vec![xa];
    breaks.extend_from_slice(inside);
    breaks.push(xb);
    let nc = mult.xi.len() - 1;
    let mut sum = 0.0;
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[0] + w[1]));
        for &(g, wg) in &GAUSS2 {
            let x = mid + half * g;
            let (ln, lt) = if x < mult.xi[0] || x > mult.xi[nc] {
                (0.0, 0.0)
            } else {
                let cell = mult.xi.partition_point(|&y| y <= x).clamp(1, nc) - 1;
                let (b, nb) = mult.basis(cell, x);
                b[..nb].iter().fold((0.0, 0.0), |acc, &(j, v)| (acc.0 + v * lambda_n[j], acc.1 + v * lambda_t[j]))
            };
            let (n, t) = if contact.one_frame { (contact.normal, contact.tangent) } else { contact.frame_at(x) };
            let r = [s[0] - ln * n[0] - lt * t[0], s[1] - ln * n[1] - lt * t[1]];
            sum += wg * half * (r[0] * r[0] + r[1] * r[1]);
        }
    }
    sum / (xb - xa)
}

/// A primary loop unrolled along the secondary loop `[start, start + length)`: its nodes from the one of the
/// smallest abscissa `xi` (taken in that turn) round the loop in the secondary's direction, with the node before
/// it first (at its abscissa less `length`) and that node again last (at its own plus `length`), so that the
/// abscissae increase and cover the secondary's whole turn; its edges follow the nodes. `None` when they do not
/// increase one way round.
fn unroll(boundary: &mut ContactBoundary, xi: Vec<f64>, start: f64, length: f64) -> Option<Vec<f64>> {
    let m = boundary.nodes.len() - 1;
    let xi: Vec<f64> = xi.iter().map(|&x| x - length * ((x - start) / length).floor()).collect();
    let k0 = (0..m).min_by(|&a, &b| xi[a].total_cmp(&xi[b]))?;
    // The way round: the steps from node to node, each taken the short way across the seam, add up to ±length.
    let wrapped = |d: f64| d - length * (d / length).round();
    let forward: f64 = (0..m).map(|k| wrapped(xi[(k + 1) % m] - xi[k])).sum();
    let step: usize = if forward > 0.0 { 1 } else { m - 1 };
    let order: Vec<usize> = (0..m).map(|j| (k0 + j * step) % m).collect();
    let last = order[m - 1];
    let mut at: Vec<(usize, f64)> = vec![(last, xi[last] - length)];
    at.extend(order.iter().map(|&k| (k, xi[k])));
    at.push((k0, xi[k0] + length));
    if at.windows(2).any(|w| w[1].1 <= w[0].1) {
        return None;
    }
    let (nodes, points) = (boundary.nodes.clone(), boundary.node_points.clone());
    let edges: std::collections::HashMap<[usize; 2], ContactEdge> =
        boundary.edges.iter().map(|e| ([e.left.min(e.right), e.left.max(e.right)], *e)).collect();
    boundary.nodes = at.iter().map(|&(k, _)| nodes[k]).collect();
    boundary.node_points = at.iter().map(|&(k, _)| points[k]).collect();
    boundary.node_xi = at.iter().map(|&(_, x)| x).collect();
    boundary.edges = boundary
        .nodes
        .windows(2)
        .map(|w| {
            let e = edges.get(&[w[0].min(w[1]), w[0].max(w[1])]).copied()?;
            Some(ContactEdge { left: w[0], right: w[1], ..e })
        })
        .collect::<Option<Vec<_>>>()?;
    Some(boundary.node_xi.clone())
}

/// The primary side in the order of the secondary's abscissa: nodes, points and edges reversed.
fn reverse(boundary: &mut ContactBoundary) {
    boundary.nodes.reverse();
    boundary.node_points.reverse();
    boundary.node_xi.reverse();
    boundary.edges.reverse();
    for e in &mut boundary.edges {
        std::mem::swap(&mut e.left, &mut e.right);
    }
}

/// The gap at abscissa `x` of the secondary side along its normal `n` there (module documentation).
fn geometric_gap(
    side: &PrimarySide,
    secondary: &ContactBoundary,
    curves: Option<&[Curve; 2]>,
    x: f64,
    n: [f64; 2],
) -> f64 {
    let facet = secondary.point_at(x);
    let (from, to) = match curves {
        Some([own, other]) => {
            let from = own.project(facet);
            (from, other.project(from))
        }
        None => (facet, side.point_at(x)),
    };
    let d = [to[0] - from[0], to[1] - from[1]];
    let along = d[0] * n[0] + d[1] * n[1];
    if curves.is_some() {
        d[0].hypot(d[1]).copysign(along)
    } else {
        along
    }
}

/// `∫_{Γ_C} φ²_i ψ_j` (with the measure `measure(ξ)`) on the common refinement of T_H and the primary
/// nodes inside Γ_C, and, where `bent`, also of the secondary nodes: then also its parts edge by edge of the
/// secondary side and the gap moments `∫ ψ_j gap(ξ, n_e)` (4-point Gauss: the gap between two curves is not
/// polynomial).
fn primary_mortar(
    xi: &[f64],
    secondary: &ContactBoundary,
    mult: &MultiplierMesh,
    measure: &dyn Fn(f64) -> f64,
    bent: bool,
    gap: &dyn Fn(f64, [f64; 2]) -> f64,
) -> (Coo, Vec<EdgeEntry>, Vec<f64>) {
    let (start, end) = (secondary.start(), secondary.end());
    let mut fe: Vec<f64> = vec![start];
    fe.extend(xi.iter().copied().filter(|&x| x > start && x < end));
    fe.push(end);
    if bent {
        // The secondary nodes too (a piece inside one secondary edge has one frame); near-coincident points
        // merged as T_H's are.
        let pieces = common_refinement(&fe, &secondary.node_xi);
        fe = pieces.iter().map(|p| p.a).chain(std::iter::once(end)).collect();
    }
    let q = mult.n_dofs();
    let mut m2 = Coo::new(xi.len(), q);
    let mut by_edge = Vec::new();
    let mut gap_moments = vec![0.0; q];
    let n = xi.len();
    for pc in common_refinement(&fe, &mult.xi) {
        let (half, mid) = (0.5 * (pc.b - pc.a), 0.5 * (pc.a + pc.b));
        // The primary edge holding the whole piece (primary nodes are breakpoints).
        let k = xi.partition_point(|&y| y <= mid).clamp(1, n - 1) - 1;
        let e = secondary.edge_at(mid);
        for &(t, w) in &GAUSS2 {
            let x = mid + half * t;
            let s = (x - xi[k]) / (xi[k + 1] - xi[k]);
            let (psi, npsi) = mult.basis(pc.cell, x);
            for (i, fi) in [(k, 1.0 - s), (k + 1, s)] {
                for &(j, pj) in &psi[..npsi] {
                    let m = w * half * measure(x) * fi * pj;
                    m2.entries.push((i, j, m));
                    if bent {
                        by_edge.push((i, j, e, m));
                    }
                }
            }
        }
        if bent {
            let normal = secondary.edges[e].normal;
            for &(t, w) in &GAUSS4 {
                let x = mid + half * t;
                let g = gap(x, normal);
                let (psi, npsi) = mult.basis(pc.cell, x);
                for &(j, pj) in &psi[..npsi] {
                    gap_moments[j] += w * half * measure(x) * pj * g;
                }
            }
        }
    }
    by_edge.sort_by_key(|v| (v.0, v.1, v.2));
    let mut summed: Vec<EdgeEntry> = Vec::with_capacity(by_edge.len());
    for v in by_edge {
        match summed.last_mut() {
            Some(l) if (l.0, l.1, l.2) == (v.0, v.1, v.2) => l.3 += v.3,
            _ => summed.push(v),
        }
    }
    if secondary.one_frame {
        summed.clear();
    }
    (m2.compress(), summed, gap_moments)
}
