//! P1 triangle meshes: points, counter-clockwise triangles and named sets of boundary edges.
//!
//! A [`Mesh`] is validated once, when it is built ([`Mesh::new`]); everything downstream may then rely on
//! its invariants: finite coordinates, indices in range, every triangle counter-clockwise with an area
//! that is not negligible next to its squared diameter, every node used, no duplicate triangle, no two
//! triangles overlapping along an edge (a directed edge used twice: a folded mesh), and every edge of a
//! named set lying on the boundary, once.

pub mod generate;
pub mod line;
pub mod refine;

use std::collections::{BTreeMap, HashMap};

use crate::error::{Error, Result};

/// A 2D point.
pub type Point = [f64; 2];

/// Relative area below which a triangle is called degenerate: `|area| <= DEGENERATE_REL * diameter²`.
///
/// Derived, not tuned: the signed area is a difference of products of coordinates, whose rounding error
/// is a few ulps of `diameter²`; 64 ulps leave a wide margin while still accepting any triangle whose
/// smallest angle exceeds about 1e-13 radians.
pub const DEGENERATE_REL: f64 = 64.0 * f64::EPSILON;

/// A validated P1 triangle mesh.
#[derive(Debug, Clone)]
pub struct Mesh {
    points: Vec<Point>,
    triangles: Vec<[usize; 3]>,
    edge_sets: BTreeMap<String, Vec<[usize; 2]>>,
    /// Boundary edge (sorted node pair) -> the triangle that owns it.
    boundary: HashMap<[usize; 2], usize>,
}

/// Signed area of the triangle (a, b, c): positive when counter-clockwise.
pub fn signed_area(a: Point, b: Point, c: Point) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
}

fn dist2(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

impl Mesh {
    /// Builds and validates a mesh.
    ///
    /// `triangles` must list their nodes counter-clockwise. `edge_sets` names sets of boundary edges
    /// (pairs of node indices, in any order) used for supports, loads and the contact boundary.
    ///
    /// # Errors
    /// [`Error::EmptyMesh`], [`Error::NonFiniteCoordinate`], [`Error::NodeIndexOutOfRange`],
    /// [`Error::InvertedTriangle`], [`Error::DegenerateTriangle`], [`Error::UnusedNode`],
    /// [`Error::DuplicateTriangle`], [`Error::EmptyEdgeSet`], [`Error::NotABoundaryEdge`].
    pub fn new(
        points: Vec<Point>,
        triangles: Vec<[usize; 3]>,
        edge_sets: BTreeMap<String, Vec<[usize; 2]>>,
    ) -> Result<Self> {
        if triangles.is_empty() {
            return Err(Error::EmptyMesh);
        }
        for (node, p) in points.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(Error::NonFiniteCoordinate { node, x: p[0], y: p[1] });
            }
        }
        let n = points.len();
        let mut used = vec![false; n];
        for (element, tri) in triangles.iter().enumerate() {
            for &node in tri {
                if node >= n {
                    return Err(Error::NodeIndexOutOfRange { element, node, n_nodes: n });
                }
                used[node] = true;
            }
            let [a, b, c] = tri.map(|i| points[i]);
            let area = signed_area(a, b, c);
            let diameter_sq = dist2(a, b).max(dist2(b, c)).max(dist2(c, a));
            if !(area.is_finite() && diameter_sq.is_finite()) {
                return Err(Error::CoordinatesTooLarge { element, area, diameter_sq });
            }
            if area.abs() <= DEGENERATE_REL * diameter_sq {
                return Err(Error::DegenerateTriangle { element, area, diameter_sq });
            }
            if area < 0.0 {
                return Err(Error::InvertedTriangle { element, area });
            }
        }
        // The checks across triangles sort lists instead of hashing (a fraction of the memory and time
        // of hash maps on millions of triangles). Where several pairs offend, the one met first in mesh
        // order is named, as a scan would.
        let mut keys: Vec<([usize; 3], usize)> = triangles
            .iter()
            .enumerate()
            .map(|(element, tri)| {
                let mut key = *tri;
                key.sort_unstable();
                (key, element)
            })
            .collect();
        keys.sort_unstable();
        let duplicate = keys.windows(2).filter(|w| w[0].0 == w[1].0).min_by_key(|w| w[1].1);
        if let Some(w) = duplicate {
            return Err(Error::DuplicateTriangle { first: w[0].1, second: w[1].1 });
        }
        drop(keys);
        // Each directed edge (p → q of a counter-clockwise triangle) may occur once: two triangles on the
        // same side of an edge overlap. An edge whose reverse no triangle has is on the boundary.
        let mut directed: Vec<([usize; 2], usize)> = Vec::with_capacity(3 * triangles.len());
        for (element, tri) in triangles.iter().enumerate() {
            for local in 0..3 {
                directed.push(([tri[(local + 1) % 3], tri[(local + 2) % 3]], element));
            }
        }
        directed.sort_unstable();
        let overlap = directed.windows(2).filter(|w| w[0].0 == w[1].0).min_by_key(|w| w[1].1);
        if let Some(w) = overlap {
            let [a, b] = w[0].0;
            return Err(Error::OverlappingTriangles { first: w[0].1, second: w[1].1, a, b });
        }
        let boundary: HashMap<[usize; 2], usize> = directed
            .iter()
            .filter(|([p, q], _)| directed.binary_search_by(|probe| probe.0.cmp(&[*q, *p])).is_err())
            .map(|&([p, q], element)| ([p.min(q), p.max(q)], element))
            .collect();
        drop(directed);
        if let Some(node) = used.iter().position(|u| !u) {
            return Err(Error::UnusedNode { node });
        }
        for (set, edges) in &edge_sets {
            if edges.is_empty() {
                return Err(Error::EmptyEdgeSet { name: set.clone() });
            }
            let mut seen = HashMap::with_capacity(edges.len());
            for (index, &[a, b]) in edges.iter().enumerate() {
                if !boundary.contains_key(&[a.min(b), a.max(b)]) {
                    return Err(Error::NotABoundaryEdge { set: set.clone(), index, a, b });
                }
                if let Some(first) = seen.insert([a.min(b), a.max(b)], index) {
                    return Err(Error::DuplicateEdge { set: set.clone(), first, second: index, a, b });
                }
            }
        }
        Ok(Self { points, triangles, edge_sets, boundary })
    }

    /// Node coordinates.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// Triangles (counter-clockwise node indices).
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.points.len()
    }

    /// Number of triangles.
    pub fn n_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Names of the edge sets.
    pub fn edge_set_names(&self) -> impl Iterator<Item = &str> {
        self.edge_sets.keys().map(String::as_str)
    }

    /// All named edge sets.
    pub fn edge_sets(&self) -> &BTreeMap<String, Vec<[usize; 2]>> {
        &self.edge_sets
    }

    /// The edges of a named set.
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`] if there is no such set.
    pub fn edge_set(&self, name: &str) -> Result<&[[usize; 2]]> {
        self.edge_sets.get(name).map(Vec::as_slice).ok_or_else(|| Error::UnknownEdgeSet {
            name: name.to_string(),
            available: self.edge_sets.keys().cloned().collect::<Vec<_>>().join(", "),
        })
    }

    /// The triangle that owns a boundary edge, or `None` if (a, b) is not a boundary edge.
    pub fn boundary_triangle(&self, a: usize, b: usize) -> Option<usize> {
        self.boundary.get(&[a.min(b), a.max(b)]).copied()
    }

    /// All boundary edges as sorted node pairs (in no particular order).
    pub fn boundary_edges(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        self.boundary.keys().copied()
    }

    /// Vertices of triangle `t`.
    pub fn vertices(&self, t: usize) -> [Point; 3] {
        self.triangles[t].map(|i| self.points[i])
    }

    /// Area of triangle `t` (positive).
    pub fn area(&self, t: usize) -> f64 {
        let [a, b, c] = self.vertices(t);
        signed_area(a, b, c)
    }

    /// Diameter h_T of triangle `t` (its longest edge).
    pub fn diameter(&self, t: usize) -> f64 {
        let [a, b, c] = self.vertices(t);
        dist2(a, b).max(dist2(b, c)).max(dist2(c, a)).sqrt()
    }

    /// Largest triangle diameter h.
    pub fn max_diameter(&self) -> f64 {
        (0..self.n_triangles()).map(|t| self.diameter(t)).fold(0.0, f64::max)
    }

    /// Bounding box `[xmin, ymin, xmax, ymax]`.
    pub fn bounding_box(&self) -> [f64; 4] {
        self.points.iter().fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |b, p| {
            [b[0].min(p[0]), b[1].min(p[1]), b[2].max(p[0]), b[3].max(p[1])]
        })
    }

    /// Length of the edge (a, b).
    pub fn edge_length(&self, a: usize, b: usize) -> f64 {
        dist2(self.points[a], self.points[b]).sqrt()
    }
}
