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
pub mod shapes;

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
    /// The exact curves some edge sets lie on ([`Mesh::with_curve`]).
    curves: BTreeMap<String, Curve>,
}

/// The exact curve an edge set lies on, so that refinement puts the new nodes of its edges on the curve
/// rather than on the chords ([`Mesh::with_curve`]). A straight set needs none: the midpoints of its edges
/// are on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Curve {
    /// A circular arc.
    Arc {
        /// Centre.
        center: Point,
        /// Radius.
        radius: f64,
    },
}

impl Curve {
    /// The distance of `p` from the curve.
    pub fn distance(&self, p: Point) -> f64 {
        match *self {
            Self::Arc { center, radius } => ((p[0] - center[0]).hypot(p[1] - center[1]) - radius).abs(),
        }
    }

    /// The point of the curve nearest `p` (`p` itself at an arc's centre, which has none).
    pub fn project(&self, p: Point) -> Point {
        match *self {
            Self::Arc { center, radius } => {
                let r = (p[0] - center[0]).hypot(p[1] - center[1]);
                if r > 0.0 {
                    [center[0] + radius * (p[0] - center[0]) / r, center[1] + radius * (p[1] - center[1]) / r]
                } else {
                    p
                }
            }
        }
    }
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
        // The checks across triangles group lists by a node (a counting sort) and sort each short group,
        // instead of hashing or sorting the whole list: a fraction of the time and memory on millions of
        // triangles. Where several pairs offend, the one met first in mesh order is named, as a scan would.
        let keys = grouped(
            n,
            triangles.iter().enumerate().map(|(element, tri)| {
                let mut key = *tri;
                key.sort_unstable();
                (key[0], ([key[1], key[2]], element))
            }),
        );
        let duplicate = first_pair(&keys);
        if let Some((first, second, _)) = duplicate {
            return Err(Error::DuplicateTriangle { first, second });
        }
        drop(keys);
        // Each directed edge (p → q of a counter-clockwise triangle) may occur once: two triangles on the
        // same side of an edge overlap. An edge whose reverse no triangle has is on the boundary.
        let directed = grouped(
            n,
            triangles.iter().enumerate().flat_map(|(element, tri)| {
                (0..3).map(move |local| (tri[(local + 1) % 3], (tri[(local + 2) % 3], element)))
            }),
        );
        if let Some((first, second, (a, b))) = first_pair(&directed) {
            return Err(Error::OverlappingTriangles { first, second, a, b });
        }
        let (start, out) = &directed;
        let mut boundary: HashMap<[usize; 2], usize> = HashMap::new();
        for p in 0..n {
            for &(q, element) in &out[start[p]..start[p + 1]] {
                if !out[start[q]..start[q + 1]].iter().any(|&(r, _)| r == p) {
                    boundary.insert([p.min(q), p.max(q)], element);
                }
            }
        }
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
        Ok(Self { points, triangles, edge_sets, boundary, curves: BTreeMap::new() })
    }

    /// This mesh with the edge set `set` on `curve`: refinement ([`crate::mesh::refine::bisect`]) then puts
    /// the new nodes of its edges on the curve, so that adaptive levels approach the curve instead of keeping
    /// the first level's chords (whose distance from an arc of radius R is up to `h² / 8R`).
    ///
    /// # Errors
    /// [`Error::UnknownEdgeSet`]; [`Error::BadCurve`] for a radius that is not positive and finite, a centre
    /// that is not finite, or a node of the set farther from the curve than `√ε` times its edge's length.
    pub fn with_curve(mut self, set: &str, curve: Curve) -> Result<Self> {
        let edges = self.edge_set(set)?;
        let Curve::Arc { center, radius } = curve;
        if !(center.iter().all(|c| c.is_finite()) && radius.is_finite() && radius > 0.0) {
            return Err(Error::BadCurve {
                set: set.to_string(),
                what: format!(
                    "an arc needs a finite centre and a positive radius, got ({}, {}) and {radius}",
                    center[0], center[1]
                ),
                node: None,
            });
        }
        let tol = line::geometric_tol_rel();
        for &[a, b] in edges {
            let length = self.edge_length(a, b);
            for node in [a, b] {
                let distance = curve.distance(self.points[node]);
                if distance > tol * length {
                    return Err(Error::BadCurve {
                        set: set.to_string(),
                        what: format!("node {node} lies {distance:e} off the curve (edge length {length:e})"),
                        node: Some(node),
                    });
                }
            }
        }
        self.curves.insert(set.to_string(), curve);
        Ok(self)
    }

    /// This mesh with the curves `curves` (of edge sets on them already: a renumbered or merged copy of meshes
    /// whose curves were checked).
    pub(crate) fn with_curves(mut self, curves: BTreeMap<String, Curve>) -> Self {
        self.curves = curves;
        self
    }

    /// This mesh without the curves of its edge sets: its refinements keep new boundary nodes on the chords.
    pub fn without_curves(&self) -> Self {
        Self { curves: BTreeMap::new(), ..self.clone() }
    }

    /// The curves of the edge sets that have one ([`Mesh::with_curve`]).
    pub fn curves(&self) -> &BTreeMap<String, Curve> {
        &self.curves
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

/// Items keyed by a node (below `n`), grouped by it with a counting sort: the items of node i are
/// `items[start[i]..start[i + 1]]`, each group sorted. Returns `(start, items)`.
pub(crate) fn grouped<T: Ord + Copy>(
    n: usize,
    keyed: impl Iterator<Item = (usize, T)> + Clone,
) -> (Vec<usize>, Vec<T>) {
    let mut start = vec![0usize; n + 1];
    for (i, _) in keyed.clone() {
        start[i + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut items = Vec::with_capacity(start[n]);
    // Every slot is written once below; the first item is a placeholder value for the unwritten ones.
    if let Some((_, first)) = keyed.clone().next() {
        items.resize(start[n], first);
    }
    for (i, item) in keyed {
        items[fill[i]] = item;
        fill[i] += 1;
    }
    for i in 0..n {
        items[start[i]..start[i + 1]].sort_unstable();
    }
    (start, items)
}

/// The first pair, in mesh order of its second element, of items `(key, element)` of one group with the
/// same key: `(first element, second element, (node, key))`.
fn first_pair<K: Ord + Copy>(groups: &(Vec<usize>, Vec<(K, usize)>)) -> Option<(usize, usize, (usize, K))> {
    let (start, items) = groups;
    let mut best: Option<(usize, usize, (usize, K))> = None;
    for node in 0..start.len() - 1 {
        for w in items[start[node]..start[node + 1]].windows(2) {
            if w[0].0 == w[1].0 && best.is_none_or(|b| w[1].1 < b.1) {
                best = Some((w[0].1, w[1].1, (node, w[0].0)));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The offending pair the whole sorted list names (the former implementation): of the items
    /// `((node, key), element)` with equal `(node, key)`, adjacent in sorted order, the pair whose second
    /// element comes first in mesh order.
    fn by_sorting<K: Ord + Copy>(mut all: Vec<((usize, K), usize)>) -> Option<(usize, usize, (usize, K))> {
        all.sort_unstable();
        all.windows(2).filter(|w| w[0].0 == w[1].0).min_by_key(|w| w[1].1).map(|w| (w[0].1, w[1].1, w[0].0))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Grouping by a node and sorting each group finds the duplicate triangles, the overlapping
        /// directed edges and the boundary edges that sorting the whole lists finds (any node triples,
        /// repeats and degenerate ones included: these checks see only indices).
        #[test]
        fn grouping_finds_what_sorting_finds(
            triangles in prop::collection::vec(prop::array::uniform3(0..7usize), 1..24),
        ) {
            let n = 7;
            let sorted_key = |tri: &[usize; 3]| {
                let mut k = *tri;
                k.sort_unstable();
                k
            };
            let keys = grouped(n, triangles.iter().enumerate().map(|(e, t)| {
                let k = sorted_key(t);
                (k[0], ([k[1], k[2]], e))
            }));
            let all = triangles.iter().enumerate().map(|(e, t)| {
                let k = sorted_key(t);
                ((k[0], [k[1], k[2]]), e)
            });
            prop_assert_eq!(first_pair(&keys), by_sorting(all.collect()));
            let edges = |(e, t): (usize, &[usize; 3])| {
                let t = *t;
                (0..3).map(move |l| (t[(l + 1) % 3], t[(l + 2) % 3], e))
            };
            let directed = grouped(n, triangles.iter().enumerate().flat_map(edges).map(|(p, q, e)| (p, (q, e))));
            let all: Vec<((usize, usize), usize)> =
                triangles.iter().enumerate().flat_map(edges).map(|(p, q, e)| ((p, q), e)).collect();
            prop_assert_eq!(first_pair(&directed), by_sorting(all.clone()));
            // A directed edge is on the boundary when no triangle has its reverse.
            let (start, items) = &directed;
            for &((p, q), e) in &all {
                let grouped_says = !items[start[q]..start[q + 1]].iter().any(|&(r, _)| r == p);
                prop_assert_eq!(grouped_says, !all.iter().any(|&((a, b), _)| (a, b) == (q, p)), "edge {} {} of {}", p, q, e);
            }
        }
    }
}
