//! Conforming newest-vertex bisection (NVB) of a [`Mesh`], for adaptive refinement.
//!
//! # The convention: the vertex order is the whole state
//!
//! A triangle `[v0, v1, v2]` (counter-clockwise) has the *refinement edge* `(v1, v2)`, opposite its
//! *newest vertex* `v0`. Bisecting it at `m`, the midpoint of `(v1, v2)`, gives the two children
//!
//! ```text
//!            v0                       [m, v0, v1]   refinement edge (v0, v1)
//!           /|\                       [m, v2, v0]   refinement edge (v2, v0)
//!          / | \
//!        v1--m--v2
//! ```
//!
//! both counter-clockwise, each with `m` as its newest vertex and so with its refinement edge opposite
//! `m`. No other data is kept: a mesh produced by [`bisect`] can be bisected again as it is.
//! [`Mesh::new`] keeps the vertex order it is given (it checks orientation, it never reorders), so the
//! state survives validation.
//!
//! # The initial labelling
//!
//! A mesh that did not come from [`bisect`] (a generator, a file) carries no meaningful labelling. Call
//! [`label_longest_edge`] once on it: every triangle is rotated (which keeps it counter-clockwise) so that
//! its longest edge is its refinement edge. [`bisect`] itself never relabels, because relabelling a mesh
//! that it produced would break the sequence of bisections and with it the bound on the shapes below; the
//! two steps are separate so that each call says what it does. Any labelling gives a conforming result;
//! the longest-edge one gives the best angles, and is *compatible* (the refinement edge of both
//! triangles of an edge is that edge) on the meshes of [`crate::mesh::generate::rectangle`], so that
//! refining every triangle twice splits each into exactly 4.
//!
//! # The closure
//!
//! 1. The refinement edge of every marked triangle is marked ([`Bisection::RefinementEdge`], p1afem's
//!    `bisec1`), or all three of its edges ([`Bisection::AllEdges`], `bisec3`: the marked triangle
//!    becomes four, as by two bisections of it and its children).
//! 2. Repeatedly, a triangle with a marked edge gets its refinement edge marked (a worklist over edges;
//!    it stops because edges are only ever marked).
//! 3. Every triangle is bisected by its marked edges: none (kept), its refinement edge only (2 children),
//!    its refinement edge and one other (3), or all three (4). The first bisection is by the refinement
//!    edge; a marked second or third edge is then the refinement edge of the child that holds it.
//!
//! Every marked edge is bisected in both triangles that share it, so the result has no hanging node.
//!
//! # Shape regularity
//!
//! The descendants of one initial triangle under NVB fall into at most 4 similarity classes, whatever the
//! sequence of refinements (Sewell 1972; Mitchell 1991; Stevenson 2008): the angles of any refined mesh
//! are bounded below by a constant that depends on the initial mesh only, never on the number of
//! refinements. With the longest-edge labelling the smallest angle stays above half the initial one: the
//! children of a bisection by the longest edge have no angle below half the parent's smallest (Rosenberg
//! and Stenger 1975); the only other class, found among the grandchildren, has for angles the children's
//! two angles at `v0` and the sum of the parent's angles at `v1` and `v2`.
//!
//! # What is inherited
//!
//! Old nodes keep their indices; the new nodes (one per bisected edge) follow, numbered by the sorted
//! node pair of the edge they bisect, and [`Refinement::midpoints`] lists that pair: a P1 field
//! prolongates exactly by `u_m = (u_a + u_b) / 2` ([`Refinement::prolongate`]). New triangles are listed
//! parent by parent, in the order of the coarse triangles ([`Refinement::parent`]). Every named edge set
//! is inherited: a bisected boundary edge `[a, b]` becomes `[a, m]` and `[m, b]` at its place in the set,
//! so its orientation and order along a side are kept. The output depends on the mesh and on the *set*
//! of marked triangles only (not on the order or repetition of the marks, nor on any hash order).
//!
//! # Complexity
//!
//! One call costs O(n log n) for n triangles (sorting the edges once), the closure O(n). Over a sequence
//! of refinements, the number of triangles created is bounded by a constant times the number of
//! triangles marked in all calls (Binev, Dahmen and DeVore 2004 for compatible labellings; Karkulik,
//! Pavlicek and Praetorius 2013 for any initial labelling in 2D): refining toward a point adds O(1)
//! triangles per level, not a geometric growth.
//!
//! # References
//!
//! * E. G. Sewell, *Automatic generation of triangulations for piecewise polynomial approximation*,
//!   PhD thesis, Purdue University, 1972.
//! * I. G. Rosenberg, F. Stenger, *A lower bound on the angles of triangles constructed by bisecting the
//!   longest side*, Math. Comp. 29 (1975) 390–395.
//! * W. F. Mitchell, *Adaptive refinement for arbitrary finite-element spaces with hierarchical bases*,
//!   J. Comput. Appl. Math. 36 (1991) 65–78.
//! * P. Binev, W. Dahmen, R. DeVore, *Adaptive finite element methods with convergence rates*, Numer.
//!   Math. 97 (2004) 219–268.
//! * R. Stevenson, *The completion of locally refined simplicial partitions created by bisection*, Math.
//!   Comp. 77 (2008) 227–241.
//! * M. Karkulik, D. Pavlicek, D. Praetorius, *On 2D newest vertex bisection: optimality of mesh-closure
//!   and H¹-stability of L₂-projection*, Constr. Approx. 38 (2013) 213–234.

use std::collections::{BTreeMap, HashMap};

use crate::error::{Error, Result};
use crate::mesh::generate::MAX_CELLS;
use crate::mesh::{dist2, Curve, Mesh, Point};
use crate::settings::Bisection;

/// The result of [`bisect`]: the refined mesh and how it relates to the coarse one.
#[derive(Debug, Clone)]
pub struct Refinement {
    mesh: Mesh,
    parent: Vec<usize>,
    midpoints: Vec<[usize; 2]>,
}

impl Refinement {
    /// The refined mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The refined mesh with `curves` for its edge sets, its nodes where they are (a mesh refined on the chords
    /// of curves that its sets still name: the gap of a bent pair reads them, [`crate::contact::pair`]).
    pub(crate) fn with_curves(mut self, curves: std::collections::BTreeMap<String, crate::mesh::Curve>) -> Self {
        self.mesh = self.mesh.with_curves(curves);
        self
    }

    /// The refined mesh, by value.
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }

    /// The refined mesh, [`Refinement::parent`] and [`Refinement::midpoints`], by value.
    pub fn into_parts(self) -> (Mesh, Vec<usize>, Vec<[usize; 2]>) {
        (self.mesh, self.parent, self.midpoints)
    }

    /// For each triangle of the refined mesh, the index of the coarse triangle it lies in.
    pub fn parent(&self) -> &[usize] {
        &self.parent
    }

    /// For each new node (node `n_coarse + i` for entry `i`), the coarse edge `[a, b]` (`a < b`, coarse
    /// node indices) whose midpoint it is.
    pub fn midpoints(&self) -> &[[usize; 2]] {
        &self.midpoints
    }

    /// Number of nodes of the coarse mesh: the refined mesh's first nodes.
    pub fn n_coarse_nodes(&self) -> usize {
        self.mesh.n_nodes() - self.midpoints.len()
    }

    /// Prolongates a nodal vector of the coarse mesh to the refined one, exactly for P1 fields: old nodes
    /// keep their values, a new node takes the mean of the two ends of the edge it bisects.
    ///
    /// `components` values per node, interleaved (2 for displacements `[u0x, u0y, u1x, …]`).
    ///
    /// # Errors
    /// [`Error::NodalValuesLength`] if `coarse_nodal` does not hold `components` values per coarse node.
    pub fn prolongate(&self, coarse_nodal: &[f64], components: usize) -> Result<Vec<f64>> {
        let n_coarse = self.n_coarse_nodes();
        if n_coarse.checked_mul(components) != Some(coarse_nodal.len()) {
            return Err(Error::NodalValuesLength { len: coarse_nodal.len(), n_nodes: n_coarse, components });
        }
        let mut fine = Vec::with_capacity(self.mesh.n_nodes() * components);
        fine.extend_from_slice(coarse_nodal);
        for &[a, b] in &self.midpoints {
            for c in 0..components {
                fine.push(0.5 * (coarse_nodal[a * components + c] + coarse_nodal[b * components + c]));
            }
        }
        Ok(fine)
    }
}

/// Relative difference of squared lengths below which two edges count as equally long in
/// [`label_longest_edge`]: a squared length is a sum of two squared differences, each with a rounding
/// error of a few ulps, so edges of one geometric length computed from different coordinates agree to
/// 8 ulps.
const TIE_REL: f64 = 8.0 * f64::EPSILON;

/// Labels a mesh for [`bisect`]: rotates every triangle so that its longest edge is its refinement edge
/// `(v1, v2)`, i.e. its newest vertex `v0` is opposite its longest edge.
///
/// A rotation keeps the triangle counter-clockwise and its edges, so the mesh stays valid and triangle
/// indices, nodes and edge sets are unchanged. Edges whose squared lengths agree to 8 ulps count as equally
/// long; among those the edge with the smallest sorted node pair wins, a choice that depends on the edge
/// only, so both triangles of a tied edge decide alike.
pub fn label_longest_edge(mesh: &Mesh) -> Mesh {
    let triangles = mesh
        .triangles
        .iter()
        .map(|&tri| {
            let len2 = |k: usize| dist2(mesh.points[tri[(k + 1) % 3]], mesh.points[tri[(k + 2) % 3]]);
            let key = |k: usize| sorted(tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let longest = len2(0).max(len2(1)).max(len2(2));
            let k = (0..3).filter(|&k| len2(k) >= longest * (1.0 - TIE_REL)).min_by_key(|&k| key(k)).unwrap_or(0);
            [tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]]
        })
        .collect();
    // A rotation changes nothing `Mesh::new` checked, nor the boundary map (same edges, same owners). Every
    // field is listed, so that a new one must be thought about here.
    Mesh {
        points: mesh.points.clone(),
        triangles,
        edge_sets: mesh.edge_sets.clone(),
        boundary: mesh.boundary.clone(),
        curves: mesh.curves.clone(),
    }
}

/// Refines every marked triangle by newest-vertex bisection, with the conforming closure (see the [module
/// documentation](self) for the convention, the closure and what is inherited): at least once, by its
/// refinement edge ([`Bisection::RefinementEdge`]), or by all three edges, into at least four
/// ([`Bisection::AllEdges`]).
///
/// `mesh` must be labelled: its vertex order is the refinement state (a mesh from [`bisect`], or one passed
/// once through [`label_longest_edge`]); any order gives a conforming mesh. `marked` lists coarse triangle
/// indices, in any order, repeats allowed; none gives the same mesh.
///
/// # Errors
/// [`Error::MarkedTriangleOutOfRange`] for a marked index that is not a triangle;
/// [`Error::RefinementTooLarge`] if the refined mesh would have more than
/// [`MAX_CELLS`] triangles (checked before it is built); the errors of
/// [`Mesh::new`] if a child degenerates (only for triangles already degenerate to round-off), or is inverted
/// by a new node moved onto the curve of its edge set ([`Mesh::with_curve`]: a triangle much wider than the
/// curve's radius allows).
pub fn bisect(mesh: &Mesh, marked: &[usize], bisection: Bisection) -> Result<Refinement> {
    bisect_within(mesh, marked, bisection, MAX_CELLS)
}

/// [`bisect`] with a limit on the number of triangles of the result.
fn bisect_within(mesh: &Mesh, marked: &[usize], bisection: Bisection, limit: usize) -> Result<Refinement> {
    let n_triangles = mesh.n_triangles();
    if let Some((position, &triangle)) = marked.iter().enumerate().find(|(_, &t)| t >= n_triangles) {
        return Err(Error::MarkedTriangleOutOfRange { position, triangle, n_triangles });
    }
    let edges = Edges::new(mesh.triangles());
    let is_marked = edges.closure(marked, bisection);
    let n_children: usize = edges.of_triangle.iter().map(|e| 1 + e.iter().filter(|&&e| is_marked[e]).count()).sum();
    if n_children > limit {
        return Err(Error::RefinementTooLarge { triangles: n_children, limit });
    }

    // New nodes, one per marked edge, in edge order (sorted node pairs).
    let n_coarse = mesh.n_nodes();
    let mut midpoint_of: Vec<Option<usize>> = vec![None; edges.nodes.len()];
    let mut midpoints = Vec::new();
    let mut points = mesh.points().to_vec();
    // The edges of sets on a curve: their new nodes go onto it.
    let on_curve: HashMap<[usize; 2], &Curve> = mesh
        .curves
        .iter()
        .filter_map(|(set, c)| mesh.edge_sets.get(set).map(|edges| (edges, c)))
        .flat_map(|(edges, c)| edges.iter().map(move |&[a, b]| (sorted(a, b), c)))
        .collect();
    for (e, &[a, b]) in edges.nodes.iter().enumerate() {
        if is_marked[e] {
            midpoint_of[e] = Some(n_coarse + midpoints.len());
            midpoints.push([a, b]);
            let m = midpoint(points[a], points[b]);
            points.push(on_curve.get(&sorted(a, b)).map_or(m, |c| c.project(m)));
        }
    }

    let mut triangles = Vec::with_capacity(n_children);
    let mut parent = Vec::with_capacity(n_children);
    for (t, (&[v0, v1, v2], e)) in mesh.triangles().iter().zip(&edges.of_triangle).enumerate() {
        let [m0, m1, m2] = e.map(|e| midpoint_of[e]);
        let before = triangles.len();
        match m0 {
            None => {
                debug_assert!(m1.is_none() && m2.is_none(), "bug: the closure left triangle {t} unmarked");
                triangles.push([v0, v1, v2]);
            }
            Some(m0) => {
                // [m0, v0, v1], whose refinement edge (v0, v1) carries m2.
                match m2 {
                    Some(m2) => triangles.extend([[m2, m0, v0], [m2, v1, m0]]),
                    None => triangles.push([m0, v0, v1]),
                }
                // [m0, v2, v0], whose refinement edge (v2, v0) carries m1.
                match m1 {
                    Some(m1) => triangles.extend([[m1, m0, v2], [m1, v0, m0]]),
                    None => triangles.push([m0, v2, v0]),
                }
            }
        }
        parent.resize(parent.len() + triangles.len() - before, t);
    }

    let edge_sets: BTreeMap<String, Vec<[usize; 2]>> = mesh
        .edge_sets()
        .iter()
        .map(|(name, set)| {
            let mut refined = Vec::with_capacity(set.len());
            for &[a, b] in set {
                match edges.find(a, b).and_then(|e| midpoint_of[e]) {
                    Some(m) => refined.extend([[a, m], [m, b]]),
                    None => refined.push([a, b]),
                }
            }
            (name.clone(), refined)
        })
        .collect();
    let curves = mesh.curves.clone();
    let moved = !on_curve.is_empty();
    let mut mesh = Mesh::new(points, triangles, edge_sets).map_err(|e| match e {
        // Only a node moved onto a curve can invert a child of a valid triangle.
        Error::InvertedTriangle { .. } | Error::DegenerateTriangle { .. } if moved => Error::BadCurve {
            set: curves.keys().cloned().collect::<Vec<_>>().join(", "),
            what: format!(
                "a new node moved onto the curve leaves a triangle inverted or flat ({e}): the mesh is too coarse \
                 next to the curve's radius there; refine it first"
            ),
            node: None,
        },
        e => e,
    })?;
    mesh.curves = curves;
    Ok(Refinement { mesh, parent, midpoints })
}

/// The midpoint of a segment, symmetric in its ends (the same point from either side).
fn midpoint(a: Point, b: Point) -> Point {
    [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
}

fn sorted(a: usize, b: usize) -> [usize; 2] {
    [a.min(b), a.max(b)]
}

/// The edges of a mesh, numbered by their sorted node pairs.
struct Edges {
    /// Sorted node pair of each edge, increasing.
    nodes: Vec<[usize; 2]>,
    /// The one or two triangles of each edge.
    triangles: Vec<[Option<usize>; 2]>,
    /// The edges of each triangle, local edge k opposite vertex k: the refinement edge first.
    of_triangle: Vec<[usize; 3]>,
}

impl Edges {
    fn new(triangles: &[[usize; 3]]) -> Self {
        let mut slots: Vec<([usize; 2], usize)> = triangles
            .iter()
            .enumerate()
            .flat_map(|(t, tri)| (0..3).map(move |k| (sorted(tri[(k + 1) % 3], tri[(k + 2) % 3]), 3 * t + k)))
            .collect();
        slots.sort_unstable();
        let mut edges = Self { nodes: Vec::new(), triangles: Vec::new(), of_triangle: vec![[0; 3]; triangles.len()] };
        for (key, slot) in slots {
            let (t, k) = (slot / 3, slot % 3);
            if edges.nodes.last() != Some(&key) {
                edges.nodes.push(key);
                edges.triangles.push([Some(t), None]);
            } else if let Some(last) = edges.triangles.last_mut() {
                // A valid mesh has at most two triangles per edge (one per side).
                last[1] = Some(t);
            }
            edges.of_triangle[t][k] = edges.nodes.len() - 1;
        }
        edges
    }

    /// The index of the edge (a, b), if it is one.
    fn find(&self, a: usize, b: usize) -> Option<usize> {
        self.nodes.binary_search(&sorted(a, b)).ok()
    }

    /// The marked edges after the conforming closure of the marked triangles' refinement edges (and of
    /// their other two edges for [`Bisection::AllEdges`]).
    fn closure(&self, marked: &[usize], bisection: Bisection) -> Vec<bool> {
        let edges_of_marked = match bisection {
            Bisection::AllEdges => 3,
            Bisection::RefinementEdge => 1,
        };
        let mut is_marked = vec![false; self.nodes.len()];
        let mut work = Vec::new();
        let mut mark = |e: usize, work: &mut Vec<usize>| {
            if !is_marked[e] {
                is_marked[e] = true;
                work.push(e);
            }
        };
        for &t in marked {
            for &e in &self.of_triangle[t][..edges_of_marked] {
                mark(e, &mut work);
            }
        }
        while let Some(e) = work.pop() {
            for t in self.triangles[e].into_iter().flatten() {
                mark(self.of_triangle[t][0], &mut work);
            }
        }
        is_marked
    }
}

#[cfg(test)]
mod tests {
    // The `unwrap`s on `bisect` below hold by construction: every test mesh is a valid generator output (or
    // a bisection of one) and every mark is an index below its triangle count, the only inputs `bisect`
    // refuses (`bad_input_is_a_typed_error` checks those refusals without unwrapping).
    use super::*;
    use crate::mesh::generate::{rectangle, Diagonal};
    use crate::mesh::signed_area;
    use crate::settings::Bisection::{AllEdges, RefinementEdge};
    use proptest::prelude::*;

    const DIAGONALS: [Diagonal; 3] = [Diagonal::Right, Diagonal::Left, Diagonal::Alternating];

    fn labelled(x: [f64; 2], y: [f64; 2], nx: usize, ny: usize, diagonal: Diagonal) -> Mesh {
        label_longest_edge(&rectangle(x, y, nx, ny, diagonal).unwrap())
    }

    fn total_area(mesh: &Mesh) -> f64 {
        (0..mesh.n_triangles()).map(|t| mesh.area(t)).sum()
    }

    fn set_length(mesh: &Mesh, name: &str) -> f64 {
        mesh.edge_set(name).unwrap().iter().map(|e| mesh.edge_length(e[0], e[1])).sum()
    }

    fn edge_counts(mesh: &Mesh) -> BTreeMap<[usize; 2], usize> {
        let mut count = BTreeMap::new();
        for t in mesh.triangles() {
            for k in 0..3 {
                *count.entry(sorted(t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        count
    }

    fn boundary_length(mesh: &Mesh) -> f64 {
        edge_counts(mesh).iter().filter(|(_, &c)| c == 1).map(|(e, _)| mesh.edge_length(e[0], e[1])).sum()
    }

    fn min_angle(mesh: &Mesh) -> f64 {
        let angle = |a: Point, b: Point, c: Point| {
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
            (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]).abs()
        };
        (0..mesh.n_triangles())
            .map(|t| {
                let [a, b, c] = mesh.vertices(t);
                angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
    }

    /// Conformity and conservation of a refinement of `coarse`: the refined mesh is valid (and kept in the
    /// order given), no edge has more than two triangles and no node lies inside an edge, the boundary,
    /// the area, each edge set's length and each parent's area are those of the coarse mesh, and every
    /// new node is the midpoint of a coarse edge that is gone.
    fn check(coarse: &Mesh, r: &Refinement) {
        let fine = r.mesh();
        let again = Mesh::new(fine.points().to_vec(), fine.triangles().to_vec(), fine.edge_sets().clone()).unwrap();
        assert_eq!(again.triangles(), fine.triangles(), "Mesh::new reordered");
        let count = edge_counts(fine);
        assert!(count.values().all(|&c| c <= 2));
        let p = fine.points();
        let scale = p.iter().map(|q| q[0].abs().max(q[1].abs())).fold(0.0, f64::max);
        for &[a, b] in count.keys() {
            let (d, l2) = ([p[b][0] - p[a][0], p[b][1] - p[a][1]], dist2(p[a], p[b]));
            for (i, q) in p.iter().enumerate() {
                let w = [q[0] - p[a][0], q[1] - p[a][1]];
                let s = (d[0] * w[0] + d[1] * w[1]) / l2;
                let off = (d[0] * w[1] - d[1] * w[0]).abs() / l2.sqrt();
                let inside = i != a && i != b && s > 1e-9 && s < 1.0 - 1e-9 && off <= 64.0 * f64::EPSILON * scale;
                assert!(!inside, "node {i} hangs on edge ({a}, {b})");
            }
        }
        assert!(close(boundary_length(fine), boundary_length(coarse)));
        assert!(close(total_area(fine), total_area(coarse)));
        for name in coarse.edge_set_names() {
            assert!(close(set_length(fine, name), set_length(coarse, name)), "edge set {name}");
        }
        assert_eq!(r.parent().len(), fine.n_triangles());
        let mut children_area = vec![0.0; coarse.n_triangles()];
        for (t, &parent) in r.parent().iter().enumerate() {
            children_area[parent] += fine.area(t);
        }
        for (t, &area) in children_area.iter().enumerate() {
            assert!(close(area, coarse.area(t)), "triangle {t}: {area} vs {}", coarse.area(t));
        }
        assert_eq!(r.n_coarse_nodes(), coarse.n_nodes());
        assert_eq!(&p[..coarse.n_nodes()], coarse.points());
        for (i, &[a, b]) in r.midpoints().iter().enumerate() {
            assert!(a < b && b < coarse.n_nodes() && !count.contains_key(&[a, b]));
            assert_eq!(p[coarse.n_nodes() + i], midpoint(p[a], p[b]));
        }
    }

    /// The triangles whose closed region holds p.
    fn touching(mesh: &Mesh, p: Point) -> Vec<usize> {
        (0..mesh.n_triangles())
            .filter(|&t| {
                let [a, b, c] = mesh.vertices(t);
                signed_area(a, b, p) >= 0.0 && signed_area(b, c, p) >= 0.0 && signed_area(c, a, p) >= 0.0
            })
            .collect()
    }

    #[test]
    fn labelling_puts_the_longest_edge_opposite_v0_and_mesh_new_keeps_it() {
        for diagonal in DIAGONALS {
            let mesh = rectangle([0.0, 3.0], [0.0, 1.0], 4, 3, diagonal).unwrap();
            let labelled = label_longest_edge(&mesh);
            for (t, (old, new)) in mesh.triangles().iter().zip(labelled.triangles()).enumerate() {
                assert!((0..3).any(|k| [old[k], old[(k + 1) % 3], old[(k + 2) % 3]] == *new), "not a rotation");
                let l = |i: usize, j: usize| labelled.edge_length(new[i], new[j]);
                assert!(l(1, 2) >= l(0, 1) && l(1, 2) >= l(2, 0), "triangle {t}");
            }
            let again =
                Mesh::new(labelled.points().to_vec(), labelled.triangles().to_vec(), labelled.edge_sets().clone());
            assert_eq!(again.unwrap().triangles(), labelled.triangles());
            assert_eq!(labelled.boundary_triangle(0, 1), mesh.boundary_triangle(0, 1));
        }
        // An equilateral triangle: three tied edges, the smallest node pair (0, 1) wins from any rotation.
        let points = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 0.75f64.sqrt()]];
        for tri in [[0, 1, 2], [1, 2, 0], [2, 0, 1]] {
            let mesh = Mesh::new(points.clone(), vec![tri], BTreeMap::new()).unwrap();
            assert_eq!(label_longest_edge(&mesh).triangles(), [[2, 0, 1]]);
        }
    }

    #[test]
    fn one_bisection_follows_the_convention() {
        let points = vec![[0.0, 1.0], [-1.0, 0.0], [1.0, 0.0]];
        let sets = BTreeMap::from([("base".to_string(), vec![[1, 2]]), ("side".to_string(), vec![[2, 0]])]);
        let mesh = Mesh::new(points, vec![[0, 1, 2]], sets).unwrap();
        let r = bisect(&mesh, &[0], RefinementEdge).unwrap();
        check(&mesh, &r);
        assert_eq!(r.mesh().triangles(), [[3, 0, 1], [3, 2, 0]]);
        assert_eq!(r.mesh().points()[3], [0.0, 0.0]);
        assert_eq!((r.parent(), r.midpoints()), (&[0, 0][..], &[[1, 2]][..]));
        assert_eq!(r.mesh().edge_set("base").unwrap(), [[1, 3], [3, 2]]);
        assert_eq!(r.mesh().edge_set("side").unwrap(), [[2, 0]]);
        // Marking both children bisects both legs: 4 triangles, each with its newest vertex first.
        let r2 = bisect(r.mesh(), &[0, 1], RefinementEdge).unwrap();
        check(r.mesh(), &r2);
        assert_eq!(r2.mesh().triangles(), [[4, 3, 0], [4, 1, 3], [5, 3, 2], [5, 0, 3]]);
        assert_eq!(r2.midpoints(), [[0, 1], [0, 2]]);
        assert_eq!(r2.mesh().edge_set("side").unwrap(), [[2, 5], [5, 0]]);
        // Nothing marked: the same mesh.
        let none = bisect(&mesh, &[], RefinementEdge).unwrap();
        assert_eq!((none.mesh().triangles(), none.parent(), none.midpoints().len()), (mesh.triangles(), &[0][..], 0));
    }

    #[test]
    fn area_edge_sets_and_parents_are_conserved() {
        for diagonal in DIAGONALS {
            let (x, y) = ([-1.0, 2.0], [0.5, 1.75]);
            let mut mesh = labelled(x, y, 5, 3, diagonal);
            let rounds: [(Vec<usize>, _); 5] = [
                (vec![0, 7, 29], RefinementEdge),
                (vec![3], AllEdges),
                ((0..10).collect(), RefinementEdge),
                (vec![2, 2, 40], AllEdges),
                (vec![5, 61], RefinementEdge),
            ];
            for (marked, bisection) in rounds {
                let r = bisect(&mesh, &marked, bisection).unwrap();
                check(&mesh, &r);
                // The sides stay chains from their lower to their higher end.
                for (name, set) in r.mesh().edge_sets() {
                    assert!(set.windows(2).all(|w| w[0][1] == w[1][0]), "{name} is no longer a chain");
                    assert_eq!([set[0][0], set[set.len() - 1][1]], {
                        let old = mesh.edge_set(name).unwrap();
                        [old[0][0], old[old.len() - 1][1]]
                    });
                }
                mesh = r.into_mesh();
            }
        }
    }

    #[test]
    fn prolongation_is_exact_for_linear_fields() {
        let f = |p: Point| [0.3 - 1.7 * p[0] + 2.9 * p[1], -4.0 + 0.25 * p[0] - 1.5 * p[1]];
        let mut mesh = labelled([-2.0, 3.0], [1.0, 2.5], 4, 3, Diagonal::Alternating);
        for level in 0..6 {
            let marked: Vec<usize> = (0..mesh.n_triangles()).filter(|t| (t * 7 + level) % 5 == 0).collect();
            let r = bisect(&mesh, &marked, RefinementEdge).unwrap();
            let coarse: Vec<f64> = mesh.points().iter().flat_map(|&p| f(p)).collect();
            let fine = r.prolongate(&coarse, 2).unwrap();
            let exact: Vec<f64> = r.mesh().points().iter().flat_map(|&p| f(p)).collect();
            assert_eq!(fine.len(), exact.len());
            for (i, (u, v)) in fine.iter().zip(&exact).enumerate() {
                // Round-off of a few operations on values below 20.
                assert!((u - v).abs() <= 64.0 * f64::EPSILON * 20.0, "value {i}: {u} vs {v}");
            }
            let first: Vec<f64> = coarse.iter().step_by(2).copied().collect();
            let scalar = r.prolongate(&first, 1).unwrap();
            assert!(scalar.iter().zip(fine.iter().step_by(2)).all(|(a, b)| a == b));
            // Nested: every child lies in its parent.
            for (t, &parent) in r.parent().iter().enumerate() {
                let [a, b, c] = mesh.vertices(parent);
                for p in r.mesh().vertices(t) {
                    let tol = -1e-14 * mesh.area(parent);
                    assert!(signed_area(a, b, p) >= tol && signed_area(b, c, p) >= tol && signed_area(c, a, p) >= tol);
                }
            }
            mesh = r.into_mesh();
        }
    }

    /// A labelled 4 x 3 mesh of [0, 2] x [0, 1] with its interior nodes moved (deterministically) by up to
    /// a fifth of a cell, so that no two triangles are alike.
    fn perturbed(diagonal: Diagonal) -> Mesh {
        let mesh = rectangle([0.0, 2.0], [0.0, 1.0], 4, 3, diagonal).unwrap();
        let mut points = mesh.points().to_vec();
        for (i, p) in points.iter_mut().enumerate() {
            if p[0] > 0.0 && p[0] < 2.0 && p[1] > 0.0 && p[1] < 1.0 {
                let s = i as f64;
                p[0] += 0.1 * (7.0 * s).sin();
                p[1] += 0.066 * (11.0 * s).cos();
            }
        }
        label_longest_edge(&Mesh::new(points, mesh.triangles().to_vec(), mesh.edge_sets().clone()).unwrap())
    }

    #[test]
    fn refining_toward_a_point_keeps_angles_and_grows_linearly() {
        for diagonal in DIAGONALS {
            for initial_mesh in [labelled([0.0, 2.0], [0.0, 1.0], 4, 3, diagonal), perturbed(diagonal)] {
                // A corner, a node on a side, a point inside a triangle, an interior node (unperturbed).
                for p in [[0.0, 0.0], [1.0, 0.0], [1.236_067_977, 0.414_213_562], [0.5, 1.0 / 3.0]] {
                    let mut mesh = initial_mesh.clone();
                    let initial = min_angle(&mesh);
                    let mut counts = vec![mesh.n_triangles()];
                    for _ in 0..20 {
                        let marked = touching(&mesh, p);
                        let r = bisect(&mesh, &marked, RefinementEdge).unwrap();
                        check(&mesh, &r);
                        for &t in &marked {
                            assert!(r.parent().iter().filter(|&&q| q == t).count() >= 2, "{t} not refined");
                        }
                        mesh = r.into_mesh();
                        counts.push(mesh.n_triangles());
                    }
                    let smallest = min_angle(&mesh);
                    assert!(smallest >= initial / 2.0, "{diagonal:?} {p:?}: {smallest} < {initial} / 2");
                    // Linear growth: O(1) new triangles per level (Binev-Dahmen-DeVore; at most 34 here, and
                    // 38 in 50 levels), where a closure that spreads would add a multiple of the mesh.
                    let added = counts.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0);
                    assert!(added <= 48, "{diagonal:?} {p:?}: counts {counts:?}");
                    let diameter = touching(&mesh, p).iter().map(|&t| mesh.diameter(t)).fold(0.0, f64::max);
                    assert!(diameter < 1e-2, "{diagonal:?} {p:?}: triangles at the point still {diameter} wide");
                }
            }
        }
    }

    #[test]
    fn every_mark_is_refined_and_uniform_twice_quadruples() {
        for diagonal in DIAGONALS {
            let mesh = labelled([0.0, 1.5], [-1.0, 1.0], 3, 4, diagonal);
            let n = mesh.n_triangles();
            let once = bisect(&mesh, &(0..n).collect::<Vec<_>>(), RefinementEdge).unwrap();
            check(&mesh, &once);
            assert_eq!(once.mesh().n_triangles(), 2 * n);
            let all: Vec<usize> = (0..2 * n).collect();
            let twice = bisect(once.mesh(), &all, RefinementEdge).unwrap();
            check(once.mesh(), &twice);
            assert_eq!(twice.mesh().n_triangles(), 4 * n);
            // The two levels: 4 congruent children per coarse triangle.
            assert!(close(min_angle(twice.mesh()), min_angle(&mesh)));
            // All three edges at once: the same triangles as two levels of the refinement edge (node
            // numbers differ: each call numbers its own new nodes).
            // A valid mesh and marks in range: the bisection cannot fail.
            let all_edges = bisect(&mesh, &(0..n).collect::<Vec<_>>(), AllEdges).unwrap();
            check(&mesh, &all_edges);
            let shapes = |m: &Mesh| {
                let mut s: Vec<Vec<[u64; 2]>> = (0..m.n_triangles())
                    .map(|t| {
                        let mut v: Vec<[u64; 2]> = m.vertices(t).iter().map(|p| p.map(f64::to_bits)).collect();
                        v.sort_unstable();
                        v
                    })
                    .collect();
                s.sort_unstable();
                s
            };
            assert_eq!(shapes(all_edges.mesh()), shapes(twice.mesh()));
        }
        // Unlabelled generator output refines too (conforming, more closure).
        let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 3, 3, Diagonal::Right).unwrap();
        let r = bisect(&mesh, &[4], RefinementEdge).unwrap();
        check(&mesh, &r);
    }

    #[test]
    fn output_depends_on_the_set_of_marks_only() {
        let mesh = labelled([0.0, 2.0], [0.0, 1.0], 4, 2, Diagonal::Alternating);
        let a = bisect(&mesh, &[9, 1, 9, 4], RefinementEdge).unwrap();
        let b = bisect(&mesh, &[1, 4, 9], RefinementEdge).unwrap();
        assert_eq!((a.mesh().points(), a.mesh().triangles()), (b.mesh().points(), b.mesh().triangles()));
        assert_eq!(
            (a.parent(), a.midpoints(), a.mesh().edge_sets()),
            (b.parent(), b.midpoints(), b.mesh().edge_sets())
        );
    }

    #[test]
    fn bad_input_is_a_typed_error() {
        let mesh = labelled([0.0, 1.0], [0.0, 1.0], 2, 2, Diagonal::Right);
        assert_eq!(
            bisect(&mesh, &[0, 8, 3], RefinementEdge).unwrap_err(),
            Error::MarkedTriangleOutOfRange { position: 1, triangle: 8, n_triangles: 8 }
        );
        assert!(matches!(bisect(&mesh, &[usize::MAX], RefinementEdge), Err(Error::MarkedTriangleOutOfRange { .. })));
        let all: Vec<usize> = (0..8).collect();
        assert_eq!(
            bisect_within(&mesh, &all, RefinementEdge, 15).unwrap_err(),
            Error::RefinementTooLarge { triangles: 16, limit: 15 }
        );
        assert!(bisect_within(&mesh, &all, RefinementEdge, 16).is_ok());
        let r = bisect(&mesh, &[0], RefinementEdge).unwrap();
        for (len, components) in [(9, 2), (19, 2), (0, 1), (18, 0)] {
            assert_eq!(
                r.prolongate(&vec![0.0; len], components).unwrap_err(),
                Error::NodalValuesLength { len, n_nodes: 9, components }
            );
        }
        assert_eq!(r.prolongate(&[], 0).unwrap(), Vec::<f64>::new());
        let e = Error::MarkedTriangleOutOfRange { position: 1, triangle: 8, n_triangles: 8 };
        assert_eq!((e.kind(), e.category()), ("MarkedTriangleOutOfRange", crate::error::ErrorCategory::Mesh));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn random_refinements_conform(
            x0 in -10.0..10.0f64, w in 0.1..10.0f64, y0 in -10.0..10.0f64, aspect in 0.2..5.0f64,
            nx in 1..6usize, ny in 1..6usize, diagonal in 0..3usize, label in any::<bool>(),
            rounds in prop::collection::vec(prop::collection::vec(any::<usize>(), 0..8), 1..4),
            all_edges in any::<bool>(),
        ) {
            let mesh = rectangle([x0, x0 + w], [y0, y0 + w * aspect], nx, ny, DIAGONALS[diagonal]).unwrap();
            let mut mesh = if label { label_longest_edge(&mesh) } else { mesh };
            for marks in rounds {
                let marked: Vec<usize> = marks.iter().map(|m| m % mesh.n_triangles()).collect();
                let (bisection, children) = if all_edges { (AllEdges, 4) } else { (RefinementEdge, 2) };
                let r = bisect(&mesh, &marked, bisection).unwrap();
                check(&mesh, &r);
                for &t in &marked {
                    prop_assert!(r.parent().iter().filter(|&&q| q == t).count() >= children);
                }
                mesh = r.into_mesh();
            }
        }
    }

    /// The new nodes of a set on an arc go onto the arc, those of other sets and of the interior onto the
    /// midpoints; the curve goes with the refined mesh, so that a second refinement keeps to it too.
    #[test]
    fn new_nodes_of_a_curved_set_go_onto_its_arc() {
        use crate::mesh::shapes::{ring_sector, ArcGrading, RingSector};
        let sector = RingSector { center: [1.0, -2.0], radii: [0.5, 1.0], angles: [0.0, 1.0] };
        let coarse = ring_sector(&sector, &ArcGrading { angles: [0.0, 1.0], h_min: 0.2, h_max: 0.2, growth: 0.3 })
            .expect("a ring sector");
        let all: Vec<usize> = (0..coarse.n_triangles()).collect();
        let once = bisect(&label_longest_edge(&coarse), &all, Bisection::AllEdges).unwrap().into_mesh();
        let all_once: Vec<usize> = (0..once.n_triangles()).collect();
        let twice = bisect(&once, &all_once, Bisection::AllEdges).unwrap().into_mesh();
        assert_eq!(twice.curves(), coarse.curves());
        let radius = |p: Point| (p[0] - 1.0).hypot(p[1] + 2.0);
        for (name, r) in [("outer", 1.0), ("inner", 0.5)] {
            let set = twice.edge_set(name).unwrap();
            assert_eq!(set.len(), 2 * once.edge_set(name).unwrap().len(), "{name}: every edge bisected");
            for &[a, b] in set {
                for p in [twice.points()[a], twice.points()[b]] {
                    assert!((radius(p) - r).abs() < 1e-15, "{p:?} off the arc of radius {r}");
                }
            }
        }
        // The radial side at angle 0 is straight, without a curve: its new nodes are midpoints, on it.
        for &[a, b] in twice.edge_set("start").unwrap() {
            assert!([a, b].iter().all(|&n| (twice.points()[n][1] + 2.0).abs() < 1e-15));
        }
    }

    /// A node moved onto a curve that inverts a triangle (a chord long next to the radius, the arc bulging past
    /// the opposite vertex) is a typed error naming the curved set, not an index of the mesh never handed out.
    #[test]
    fn a_node_moved_onto_a_curve_past_the_opposite_vertex_is_refused() {
        use crate::mesh::Curve;
        let points = vec![[-1.0, 0.0], [1.0, 0.0], [0.0, 0.1]];
        let sets = BTreeMap::from([("arc".to_string(), vec![[0, 1]])]);
        let mesh = Mesh::new(points, vec![[0, 1, 2]], sets)
            .unwrap()
            .with_curve("arc", Curve::Arc { center: [0.0, -0.5], radius: 1.25_f64.sqrt() })
            .unwrap();
        let e = bisect(&label_longest_edge(&mesh), &[0], Bisection::AllEdges).unwrap_err();
        assert!(matches!(&e, Error::BadCurve { set, .. } if set == "arc"), "{e}");
        // Without the curve the same bisection is fine.
        assert!(bisect(&label_longest_edge(&mesh.without_curves()), &[0], Bisection::AllEdges).is_ok());
    }

    /// A curve the set's nodes are not on, or one that is not an arc, is refused naming the set (and the node).
    #[test]
    fn a_curve_off_the_nodes_is_refused() {
        use crate::mesh::Curve;
        let mesh =
            crate::mesh::generate::rectangle([0.0, 1.0], [0.0, 1.0], 2, 2, crate::mesh::generate::Diagonal::Right)
                .unwrap();
        let e = mesh.clone().with_curve("top", Curve::Arc { center: [0.5, 0.0], radius: 1.0 }).unwrap_err();
        assert!(matches!(&e, Error::BadCurve { set, node: Some(_), .. } if set == "top"), "{e}");
        let e = mesh.clone().with_curve("top", Curve::Arc { center: [0.5, 0.0], radius: -1.0 }).unwrap_err();
        assert!(matches!(&e, Error::BadCurve { node: None, .. }), "{e}");
        let e = mesh.with_curve("lid", Curve::Arc { center: [0.5, 0.0], radius: 1.0 }).unwrap_err();
        assert!(matches!(&e, Error::UnknownEdgeSet { .. }), "{e}");
    }
}
