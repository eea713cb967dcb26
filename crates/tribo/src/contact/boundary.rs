//! Geometry of the contact boundary Γ_C: a named set of boundary edges forming one chain, open or closed (a straight
//! segment, or a polyline: the faceted arc of a curved boundary), the normal and tangent of each edge and
//! the abscissae of its nodes (the conventions are those of [`crate::contact`]).

use std::collections::HashMap;

use crate::contact::obstacle::ObstacleShape;
use crate::error::{Error, Result};
use crate::mesh::line::{geometric_tol_rel, off_line};
use crate::mesh::{Mesh, Point};

/// One FE edge of Γ_C, oriented by increasing abscissa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEdge {
    /// Node at the smaller abscissa.
    pub left: usize,
    /// Node at the larger abscissa.
    pub right: usize,
    /// The triangle that owns the edge (σ(u_h) on the edge is that triangle's constant stress).
    pub triangle: usize,
    /// Length |E|.
    pub length: f64,
    /// The normal n_e of the contact on this edge, along which λ_n acts: the body's outward normal, or the
    /// obstacle's where it is given by its geometry ([`ContactBoundary::orient_to`]).
    pub normal: [f64; 2],
    /// The tangent t_e = (−n_e₂, n_e₁) of the contact on this edge, along which λ_t acts.
    pub tangent: [f64; 2],
    /// The body's outward unit normal on this edge (σ(u_h) n on the edge is σ(u_h) times it).
    pub outward: [f64; 2],
}

/// The contact boundary Γ_C.
///
/// # A chain of edges
/// Every edge carries its own outward normal and its contact frame `n_e`, `t_e = (−n_e₂, n_e₁)` (the outward
/// normal, or the obstacle's: [`ContactBoundary::orient_to`]). The abscissa ξ is
/// the arclength, counted from the start of the chain at the projection of its first node on the
/// direction of the chord between its ends (so that a straight chain has the abscissa of its line, up to
/// rounding). The chain runs from the end with the smaller x toward the other one (the smaller y when the
/// chord is vertical), as a straight Γ_C does. Where the set is straight to the tolerance of
/// [`crate::contact::geometric_tol_rel`], every edge has the normal of the first one exactly, and the
/// abscissa is the projection on the line of Γ_C, as it always was.
///
/// A quantity at a node (`u_n`, the slip) reads the node's frame: the normalized mean of the contact normals
/// of its two edges (that of its only edge at an end). Everything integrated on Γ_C reads
/// each edge's own frame (see [`crate::contact::mortar`] and [`crate::contact::operators`]).
#[derive(Debug, Clone)]
pub struct ContactBoundary {
    /// Name of the edge set.
    pub set: String,
    /// Outward unit normal n (of the first edge; of all of Γ_C when it is straight).
    pub normal: [f64; 2],
    /// Tangent t = (−n₂, n₁) (of the first edge).
    pub tangent: [f64; 2],
    /// Unit direction d of increasing abscissa on the first edge (±t).
    pub direction: [f64; 2],
    /// Origin o of the abscissa on the line of the first edge (foot of the perpendicular from (0, 0)).
    pub origin: Point,
    /// Edges sorted by abscissa.
    pub edges: Vec<ContactEdge>,
    /// Nodes of Γ_C sorted by abscissa (`edges.len() + 1` of them).
    pub nodes: Vec<usize>,
    /// Abscissae of `nodes`.
    pub node_xi: Vec<f64>,
    /// Coordinates of `nodes`.
    pub node_points: Vec<Point>,
    /// Where the chain leaves the line of its first edge, as `(node, distance, edge length)`; `None` when
    /// Γ_C is straight.
    pub bend: Option<(usize, f64, f64)>,
    /// Whether every edge has the contact frame of the first (`normal`, `tangent`): a straight Γ_C whose
    /// obstacle is a gap function of the abscissa.
    pub one_frame: bool,
    /// The exact curve of the edge set, if it carries one ([`crate::Mesh::with_curve`]): the gap to an obstacle
    /// given by its geometry is measured from it ([`ContactBoundary::surface_point`]).
    pub curve: Option<crate::mesh::Curve>,
}

/// The edges of Γ_C in order, with the frame of its abscissa (as the fields of [`ContactBoundary`]).
struct Chain {
    normal: [f64; 2],
    direction: [f64; 2],
    origin: Point,
    edges: Vec<ContactEdge>,
    nodes: Vec<usize>,
    node_xi: Vec<f64>,
}

/// The outward unit normal of the boundary edge (a, b), from the interior vertex of its triangle.
///
/// Internal invariant, not reachable from user input: (a, b) comes from a named edge set of `mesh`, and
/// [`Mesh::new`] refused any set edge that is not a boundary edge, so it has its one owning triangle, whose
/// third vertex is not on it (a triangle has three distinct nodes: degenerate ones are refused too).
fn outward_normal(mesh: &Mesh, a: usize, b: usize) -> ([f64; 2], usize) {
    let pts = mesh.points();
    let t = mesh.boundary_triangle(a, b).expect("validated boundary edge");
    let (pa, pb) = (pts[a], pts[b]);
    let len = mesh.edge_length(a, b);
    let e = [(pb[0] - pa[0]) / len, (pb[1] - pa[1]) / len];
    let mut normal = [e[1], -e[0]];
    let inner = mesh.triangles()[t].iter().copied().find(|&i| i != a && i != b).expect("triangle");
    let to_inner = [pts[inner][0] - pa[0], pts[inner][1] - pa[1]];
    if normal[0] * to_inner[0] + normal[1] * to_inner[1] > 0.0 {
        normal = [-normal[0], -normal[1]];
    }
    (normal, t)
}

/// The distance from `p` to the segment [a, b].
pub(super) fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let s = if l2 > 0.0 { (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p[0] - a[0] - s * d[0]).hypot(p[1] - a[1] - s * d[1])
}

impl ContactBoundary {
    /// Extracts Γ_C from the edge set `set` of `mesh`.
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`]; [`Error::ContactNotConnected`] when the edges are not one chain, open or
    /// closed (a gap, a branch, several pieces, a node visited twice). A closed loop is cut at its node of the
    /// smallest index, which is then its first and its last node ([`ContactBoundary::is_closed`]).
    pub fn new(mesh: &Mesh, set: &str) -> Result<Self> {
        let raw = mesh.edge_set(set)?;
        let (normal, _) = outward_normal(mesh, raw[0][0], raw[0][1]);
        let bend = off_line(mesh, raw, normal);
        let c = match bend {
            None => Self::straight(mesh, set, raw, normal)?,
            Some(_) => Self::chain(mesh, set, raw)?,
        };
        let node_points = c.nodes.iter().map(|&i| mesh.points()[i]).collect();
        Ok(Self {
            set: set.to_string(),
            normal: c.normal,
            tangent: [-c.normal[1], c.normal[0]],
            direction: c.direction,
            origin: c.origin,
            edges: c.edges,
            nodes: c.nodes,
            node_xi: c.node_xi,
            node_points,
            bend,
            one_frame: bend.is_none(),
            curve: mesh.curves().get(set).copied(),
        })
    }

    /// Turns the contact frame of every edge to the normal of an obstacle given by its geometry
    /// ([`ObstacleShape::is_geometry`]): `n_e = −∇d / |∇d|` at the edge's midpoint, d the obstacle's signed
    /// distance ([`ObstacleShape::distance_gradient`]). A frictionless rigid surface pushes
    /// along its own normal only; on the body's side the two normals agree to the angle the surface turns
    /// through where it is pressed flat, a/R on a roller (see [`crate::contact::obstacle`]). Where the
    /// gradient is not defined (at a disc's centre, a flat spot of a signed distance), the edge keeps the
    /// body's normal. Other shapes leave the frames as they are.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] when a signed distance is not finite near an edge's midpoint.
    pub fn orient_to(&mut self, shape: &ObstacleShape) -> Result<()> {
        if !shape.is_geometry() {
            return Ok(());
        }
        for (k, e) in self.edges.iter_mut().enumerate() {
            let (a, b) = (self.node_points[k], self.node_points[k + 1]);
            let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
            let grad = shape.distance_gradient(mid, e.length);
            if !grad.iter().all(|g| g.is_finite()) {
                return Err(Error::BadObstacle {
                    what: format!(
                        "the signed distance is not finite near ({}, {}), the midpoint of contact edge ({}, {})",
                        mid[0], mid[1], e.left, e.right
                    ),
                });
            }
            let norm = grad[0].hypot(grad[1]);
            if norm > 0.0 {
                e.normal = [-grad[0] / norm, -grad[1] / norm];
                e.tangent = [-e.normal[1], e.normal[0]];
            }
        }
        self.one_frame = false;
        Ok(())
    }

    /// A straight Γ_C: ordered by the projection on its line, every edge with the normal of the first.
    fn straight(mesh: &Mesh, set: &str, raw: &[[usize; 2]], normal: [f64; 2]) -> Result<Chain> {
        let pts = mesh.points();
        let pa = pts[raw[0][0]];
        let tangent = [-normal[1], normal[0]];
        let tol = geometric_tol_rel();
        let direction = if tangent[0] > tol || (tangent[0].abs() <= tol && tangent[1] > 0.0) {
            tangent
        } else {
            [-tangent[0], -tangent[1]]
        };
        let offset = pa[0] * normal[0] + pa[1] * normal[1];
        let origin = [offset * normal[0], offset * normal[1]];
        let xi_of = |p: Point| (p[0] - origin[0]) * direction[0] + (p[1] - origin[1]) * direction[1];
        let mut edges = Vec::with_capacity(raw.len());
        for &[a, b] in raw {
            let length = mesh.edge_length(a, b);
            let (left, right) = if xi_of(pts[a]) < xi_of(pts[b]) { (a, b) } else { (b, a) };
            let triangle = mesh.boundary_triangle(a, b).expect("validated boundary edge");
            edges.push(ContactEdge { left, right, triangle, length, normal, tangent, outward: normal });
        }
        edges.sort_by(|p, q| xi_of(pts[p.left]).total_cmp(&xi_of(pts[q.left])));
        for w in edges.windows(2) {
            if w[0].right != w[1].left {
                return Err(Error::ContactNotConnected {
                    set: set.to_string(),
                    what: format!(
                        "edge ({}, {}) is followed by edge ({}, {}): they do not share a node (gap or overlap)",
                        w[0].left, w[0].right, w[1].left, w[1].right
                    ),
                });
            }
        }
        let mut nodes: Vec<usize> = edges.iter().map(|e| e.left).collect();
        nodes.push(edges.last().expect("non-empty set").right);
        let node_xi: Vec<f64> = nodes.iter().map(|&i| xi_of(pts[i])).collect();
        let mut check = nodes.clone();
        check.sort_unstable();
        check.dedup();
        if check.len() != nodes.len() {
            return Err(Error::ContactNotConnected {
                set: set.to_string(),
                what: "a node is visited twice (the edges fold back on themselves)".to_string(),
            });
        }
        Ok(Chain { normal, direction, origin, edges, nodes, node_xi })
    }

    /// A bent Γ_C: the edges walked as one open chain (a loop handed to [`ContactBoundary::looped`]), each with
    /// its own normal, abscissae by arclength.
    fn chain(mesh: &Mesh, set: &str, raw: &[[usize; 2]]) -> Result<Chain> {
        let pts = mesh.points();
        let bad = |what: String| Err(Error::ContactNotConnected { set: set.to_string(), what });
        let mut around: HashMap<usize, Vec<usize>> = HashMap::new();
        for (k, &[a, b]) in raw.iter().enumerate() {
            around.entry(a).or_default().push(k);
            around.entry(b).or_default().push(k);
        }
        if let Some((node, e)) = around.iter().filter(|(_, e)| e.len() > 2).min_by_key(|(n, _)| **n) {
            return bad(format!("the edges branch at node {node} ({} edges of the set meet there)", e.len()));
        }
        let mut ends: Vec<usize> = around.iter().filter(|(_, e)| e.len() == 1).map(|(n, _)| *n).collect();
        ends.sort_unstable();
        if ends.is_empty() {
            return Self::looped(mesh, set, raw, &around);
        }
        if ends.len() > 2 {
            return bad(format!(
                "the edges form {} separate chains (ends at nodes {:?}): Γ_C must be one chain",
                ends.len() / 2,
                ends
            ));
        }
        // From the end with the smaller x (the smaller y when the chord is vertical), as a straight Γ_C.
        let (p, q) = (pts[ends[0]], pts[ends[1]]);
        let chord = [q[0] - p[0], q[1] - p[1]];
        let span = chord[0].hypot(chord[1]);
        let tol = geometric_tol_rel();
        let forward = chord[0] > tol * span || (chord[0].abs() <= tol * span && chord[1] > 0.0);
        let (first, last) = if forward { (ends[0], ends[1]) } else { (ends[1], ends[0]) };
        let unit = if span > 0.0 {
            let s = if forward { 1.0 } else { -1.0 };
            [s * chord[0] / span, s * chord[1] / span]
        } else {
            [1.0, 0.0]
        };
        let mut edges = Vec::with_capacity(raw.len());
        let mut nodes = vec![first];
        let mut used = vec![false; raw.len()];
        let mut at = first;
        while let Some(&k) = around[&at].iter().find(|&&k| !used[k]) {
            used[k] = true;
            let [a, b] = raw[k];
            let next = if a == at { b } else { a };
            let (normal, triangle) = outward_normal(mesh, a, b);
            let tangent = [-normal[1], normal[0]];
            edges.push(ContactEdge {
                left: at,
                right: next,
                triangle,
                length: mesh.edge_length(a, b),
                normal,
                tangent,
                outward: normal,
            });
            nodes.push(next);
            at = next;
        }
        if at != last || edges.len() != raw.len() {
            return bad(format!("the edges from node {first} do not reach every edge of the set: it is not one chain"));
        }
        // The walk runs along +t or −t on every edge alike: the body stays on one side of the chain.
        let sign = |e: &ContactEdge| {
            let (a, b) = (pts[e.left], pts[e.right]);
            (b[0] - a[0]) * e.tangent[0] + (b[1] - a[1]) * e.tangent[1] > 0.0
        };
        if let Some(w) = edges.windows(2).find(|w| sign(&w[0]) != sign(&w[1])) {
            return bad(format!(
                "the body changes side of the chain at node {} (the outward normals of its two edges point to \
                 opposite sides of the walk)",
                w[0].right
            ));
        }
        let mut node_xi = Vec::with_capacity(nodes.len());
        node_xi.push(pts[first][0] * unit[0] + pts[first][1] * unit[1]);
        for e in &edges {
            node_xi.push(node_xi[node_xi.len() - 1] + e.length);
        }
        let e0 = edges[0];
        let (normal, tangent) = (e0.normal, e0.tangent);
        let direction = if sign(&e0) { tangent } else { [-tangent[0], -tangent[1]] };
        let offset = pts[first][0] * normal[0] + pts[first][1] * normal[1];
        let origin = [offset * normal[0], offset * normal[1]];
        Ok(Chain { normal, direction, origin, edges, nodes, node_xi })
    }

    /// A closed Γ_C (a hole's rim, a full ring): cut at its node of the smallest index and walked along the
    /// tangent t of its first edge, back to that node, which is then both the first and the last of `nodes`.
    /// Bisection keeps the coarse nodes' indices and numbers new nodes after them, so the cut stays where it is
    /// on every refinement and the abscissae of the coarse nodes with it (a cut at the leftmost node would move
    /// where a new node on a curve lies further left).
    fn looped(mesh: &Mesh, set: &str, raw: &[[usize; 2]], around: &HashMap<usize, Vec<usize>>) -> Result<Chain> {
        let pts = mesh.points();
        let Some(&first) = around.keys().min() else {
            let what = "the edge set is empty".to_string();
            return Err(Error::ContactNotConnected { set: set.to_string(), what });
        };
        let forward = |k: usize| {
            let [a, b] = raw[k];
            let next = if a == first { b } else { a };
            let (normal, _) = outward_normal(mesh, a, b);
            (pts[next][0] - pts[first][0]) * -normal[1] + (pts[next][1] - pts[first][1]) * normal[0] > 0.0
        };
        let mut used = vec![false; raw.len()];
        let start = around[&first].iter().copied().find(|&k| forward(k)).unwrap_or(around[&first][0]);
        let (mut nodes, mut edges, mut at, mut next_edge) = (vec![first], Vec::new(), first, Some(start));
        while let Some(k) = next_edge {
            used[k] = true;
            let [a, b] = raw[k];
            let next = if a == at { b } else { a };
            let (normal, triangle) = outward_normal(mesh, a, b);
            let tangent = [-normal[1], normal[0]];
            let length = mesh.edge_length(a, b);
            edges.push(ContactEdge { left: at, right: next, triangle, length, normal, tangent, outward: normal });
            nodes.push(next);
            at = next;
            next_edge = around[&at].iter().copied().find(|&k| !used[k]);
        }
        if at != first || edges.len() != raw.len() {
            return Err(Error::ContactNotConnected {
                set: set.to_string(),
                what: format!("the edges from node {first} do not close into one loop through every edge of the set"),
            });
        }
        if let Some(w) = edges.windows(2).find(|w| {
            let along = |e: &ContactEdge| {
                let (a, b) = (pts[e.left], pts[e.right]);
                (b[0] - a[0]) * e.tangent[0] + (b[1] - a[1]) * e.tangent[1] > 0.0
            };
            along(&w[0]) != along(&w[1])
        }) {
            return Err(Error::ContactNotConnected {
                set: set.to_string(),
                what: format!("the body changes side of the loop at node {}", w[0].right),
            });
        }
        let mut node_xi = vec![pts[first][0]];
        for e in &edges {
            node_xi.push(node_xi[node_xi.len() - 1] + e.length);
        }
        let (normal, tangent) = (edges[0].normal, edges[0].tangent);
        let offset = pts[first][0] * normal[0] + pts[first][1] * normal[1];
        let origin = [offset * normal[0], offset * normal[1]];
        Ok(Chain { normal, direction: tangent, origin, edges, nodes, node_xi })
    }

    /// Whether Γ_C is a closed loop (its first node is its last).
    pub fn is_closed(&self) -> bool {
        self.nodes.len() > 2 && self.nodes[0] == self.nodes[self.nodes.len() - 1]
    }

    /// Whether Γ_C is one straight segment (every edge with the same normal).
    pub fn is_straight(&self) -> bool {
        self.bend.is_none()
    }

    /// `d · t`: +1 when the abscissa increases along t, −1 otherwise (t the body's tangent of the first edge; the
    /// walk has the same sign against every edge's outward tangent).
    pub fn tangent_sign(&self) -> f64 {
        self.direction[0] * self.tangent[0] + self.direction[1] * self.tangent[1]
    }

    /// The contact normal at node `k` of Γ_C (an index into `nodes`): the normalized mean of its edges'.
    pub fn node_normal(&self, k: usize) -> [f64; 2] {
        if self.one_frame {
            return self.normal;
        }
        let last = self.edges.len() - 1;
        let (a, b) = if self.is_closed() && (k == 0 || k > last) {
            (self.edges[last].normal, self.edges[0].normal) // the cut of a loop: its two edges
        } else {
            (self.edges[k.saturating_sub(1).min(last)].normal, self.edges[k.min(last)].normal)
        };
        let m = [a[0] + b[0], a[1] + b[1]];
        let norm = m[0].hypot(m[1]);
        if norm > 0.0 {
            [m[0] / norm, m[1] / norm]
        } else {
            b
        }
    }

    /// The tangent `(−n₂, n₁)` at node `k` of Γ_C.
    pub fn node_tangent(&self, k: usize) -> [f64; 2] {
        let n = self.node_normal(k);
        [-n[1], n[0]]
    }

    /// The contact normal at abscissa `xi`: a node's ([`ContactBoundary::node_normal`]) within `√ε` of an
    /// edge length of it, else the normal of the edge that holds `xi`.
    pub fn normal_at(&self, xi: f64) -> [f64; 2] {
        if self.one_frame {
            return self.normal;
        }
        let k = self.edge_at(xi);
        let tol = crate::contact::geometric_tol_rel() * self.edges[k].length;
        match [k, k + 1].into_iter().find(|&j| (self.node_xi[j] - xi).abs() <= tol) {
            Some(j) => self.node_normal(j),
            None => self.edges[k].normal,
        }
    }

    /// The contact frame `(n_e, t_e)` of the edge that holds abscissa `xi`.
    pub fn frame_at(&self, xi: f64) -> ([f64; 2], [f64; 2]) {
        let e = &self.edges[self.edge_at(xi)];
        (e.normal, e.tangent)
    }

    /// The edge that holds abscissa `xi` (the first or the last edge beyond the ends).
    pub fn edge_at(&self, xi: f64) -> usize {
        self.node_xi.partition_point(|&y| y <= xi).clamp(1, self.edges.len()) - 1
    }

    /// Abscissa of a point: its projection on the line of a straight Γ_C; on a chain, the abscissa of the
    /// nearest point of the chain, the end edges extended beyond the ends (not those of a closed loop).
    pub fn abscissa(&self, p: Point) -> f64 {
        if self.is_straight() {
            return (p[0] - self.origin[0]) * self.direction[0] + (p[1] - self.origin[1]) * self.direction[1];
        }
        // A loop has no ends to extend.
        let (last, open) = (self.edges.len() - 1, !self.is_closed());
        let mut best = (f64::INFINITY, 0.0);
        for (k, e) in self.edges.iter().enumerate() {
            let (a, b) = (self.node_points[k], self.node_points[k + 1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let mut s = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (e.length * e.length);
            let (lo, hi) = (
                if k == 0 && open { f64::NEG_INFINITY } else { 0.0 },
                if k == last && open { f64::INFINITY } else { 1.0 },
            );
            s = s.clamp(lo, hi);
            let distance = (p[0] - a[0] - s * d[0]).hypot(p[1] - a[1] - s * d[1]);
            if distance < best.0 {
                best = (distance, self.node_xi[k] + s * e.length);
            }
        }
        best.1
    }

    /// Distance of a point from the part `[lo, hi]` (abscissae) of Γ_C (of its line when straight; the end
    /// edges of a chain extended beyond its ends). On a closed loop the span may cross the cut: `lo` before
    /// the start or `hi` beyond the end stand for the abscissae a period later or earlier.
    pub fn distance_to_span(&self, p: Point, lo: f64, hi: f64) -> f64 {
        if self.is_straight() {
            let xi = self.abscissa(p);
            return (lo - xi).max(xi - hi).max(0.0).hypot(self.distance_to_line(p));
        }
        let (start, end, period) = (self.start(), self.end(), self.length());
        let (lo, hi) = if self.is_closed() && hi - lo >= period { (start, end) } else { (lo, hi) };
        if self.is_closed() && lo < start {
            return self.distance_to_span(p, lo + period, end).min(self.distance_to_span(p, start, hi));
        }
        if self.is_closed() && hi > end {
            return self.distance_to_span(p, lo, end).min(self.distance_to_span(p, start, hi - period));
        }
        let (last, open) = (self.edges.len() - 1, !self.is_closed());
        let mut best = f64::INFINITY;
        for k in 0..=last {
            let a = lo.max(if k == 0 && open { f64::NEG_INFINITY } else { self.node_xi[k] });
            let b = hi.min(if k == last && open { f64::INFINITY } else { self.node_xi[k + 1] });
            if a <= b {
                best = best.min(segment_distance(p, self.point_at(a), self.point_at(b)));
            }
        }
        best
    }

    /// Signed distance of a point from Γ_C along n: from the line of a straight Γ_C; on a chain, from its
    /// nearest point, along the normal of the nearest edge.
    pub fn distance_to_line(&self, p: Point) -> f64 {
        if self.is_straight() {
            return (p[0] - self.origin[0]) * self.normal[0] + (p[1] - self.origin[1]) * self.normal[1];
        }
        let xi = self.abscissa(p);
        let (q, n) = (self.point_at(xi), self.edges[self.edge_at(xi)].outward);
        let d = (p[0] - q[0]).hypot(p[1] - q[1]);
        if (p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] < 0.0 {
            -d
        } else {
            d
        }
    }

    /// The point of Γ_C at abscissa `xi` (of its line when straight; on the end edges extended beyond the
    /// ends of a chain).
    pub fn point_at(&self, xi: f64) -> Point {
        if self.is_straight() {
            return [self.origin[0] + xi * self.direction[0], self.origin[1] + xi * self.direction[1]];
        }
        let k = self.edge_at(xi);
        let s = (xi - self.node_xi[k]) / self.edges[k].length;
        let (a, b) = (self.node_points[k], self.node_points[k + 1]);
        [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
    }

    /// The point of the body's true surface at abscissa `xi`: on the edge set's curve, nearest the facet's point
    /// ([`ContactBoundary::point_at`]), where the set carries one; the facet's point otherwise. The facets of an
    /// arc stand inside it by up to h²/8R between nodes: measured from them, the gap to a hole of the arc's
    /// radius would be that sag, of the order of a shrink fit's interference.
    pub fn surface_point(&self, xi: f64) -> Point {
        let p = self.point_at(xi);
        self.curve.map_or(p, |c| c.project(p))
    }

    /// Abscissa of the start of Γ_C.
    pub fn start(&self) -> f64 {
        self.node_xi[0]
    }

    /// Abscissa of the end of Γ_C.
    pub fn end(&self) -> f64 {
        *self.node_xi.last().expect("non-empty")
    }

    /// Length of Γ_C.
    pub fn length(&self) -> f64 {
        self.end() - self.start()
    }

    /// Number of FE edges on Γ_C.
    pub fn n_edges(&self) -> usize {
        self.edges.len()
    }
}
