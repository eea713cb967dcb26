//! Geometry of the contact boundary Γ_C: a named set of boundary edges forming one straight segment, its
//! normal, tangent and abscissae (the conventions are those of [`crate::contact`]).

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
}

/// The contact boundary Γ_C.
#[derive(Debug, Clone)]
pub struct ContactBoundary {
    /// Name of the edge set.
    pub set: String,
    /// Outward unit normal n.
    pub normal: [f64; 2],
    /// Tangent t = (−n₂, n₁).
    pub tangent: [f64; 2],
    /// Unit direction d of increasing abscissa (±t).
    pub direction: [f64; 2],
    /// Origin o of the abscissa (foot of the perpendicular from (0, 0)).
    pub origin: Point,
    /// Edges sorted by abscissa.
    pub edges: Vec<ContactEdge>,
    /// Nodes of Γ_C sorted by abscissa (`edges.len() + 1` of them).
    pub nodes: Vec<usize>,
    /// Abscissae of `nodes`.
    pub node_xi: Vec<f64>,
}

impl ContactBoundary {
    /// Extracts Γ_C from the edge set `set` of `mesh`.
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`], [`Error::ContactNotStraight`], [`Error::ContactNotConnected`].
    pub fn new(mesh: &Mesh, set: &str) -> Result<Self> {
        let raw = mesh.edge_set(set)?;
        let pts = mesh.points();
        // Normal from the first edge and the interior vertex of its triangle.
        let [a0, b0] = raw[0];
        let t0 = mesh.boundary_triangle(a0, b0).expect("validated boundary edge");
        let (pa, pb) = (pts[a0], pts[b0]);
        let len0 = mesh.edge_length(a0, b0);
        let e = [(pb[0] - pa[0]) / len0, (pb[1] - pa[1]) / len0];
        let mut normal = [e[1], -e[0]];
        let inner = mesh.triangles()[t0].iter().copied().find(|&i| i != a0 && i != b0).expect("triangle");
        let to_inner = [pts[inner][0] - pa[0], pts[inner][1] - pa[1]];
        if normal[0] * to_inner[0] + normal[1] * to_inner[1] > 0.0 {
            normal = [-normal[0], -normal[1]];
        }
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

        if let Some((node, distance, length)) = off_line(mesh, raw, normal) {
            return Err(Error::ContactNotStraight { set: set.to_string(), node, distance, length });
        }
        let mut edges = Vec::with_capacity(raw.len());
        for &[a, b] in raw {
            let length = mesh.edge_length(a, b);
            let (left, right) = if xi_of(pts[a]) < xi_of(pts[b]) { (a, b) } else { (b, a) };
            let triangle = mesh.boundary_triangle(a, b).expect("validated boundary edge");
            edges.push(ContactEdge { left, right, triangle, length });
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
        Ok(Self { set: set.to_string(), normal, tangent, direction, origin, edges, nodes, node_xi })
    }

    /// `d · t`: +1 when the abscissa increases along t, −1 otherwise.
    pub fn tangent_sign(&self) -> f64 {
        self.direction[0] * self.tangent[0] + self.direction[1] * self.tangent[1]
    }

    /// Abscissa of a point (its projection on the line of Γ_C).
    pub fn abscissa(&self, p: Point) -> f64 {
        (p[0] - self.origin[0]) * self.direction[0] + (p[1] - self.origin[1]) * self.direction[1]
    }

    /// Distance of a point from the segment `[lo, hi]` (abscissae) of the line of Γ_C.
    pub fn distance_to_span(&self, p: Point, lo: f64, hi: f64) -> f64 {
        let xi = self.abscissa(p);
        (lo - xi).max(xi - hi).max(0.0).hypot(self.distance_to_line(p))
    }

    /// Signed distance of a point from the line of Γ_C (along n).
    pub fn distance_to_line(&self, p: Point) -> f64 {
        (p[0] - self.origin[0]) * self.normal[0] + (p[1] - self.origin[1]) * self.normal[1]
    }

    /// The point of Γ_C's line at abscissa `xi`.
    pub fn point_at(&self, xi: f64) -> Point {
        [self.origin[0] + xi * self.direction[0], self.origin[1] + xi * self.direction[1]]
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
