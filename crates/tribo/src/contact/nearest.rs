//! The distance of many points to Γ_C, by a hierarchy of bounding boxes over runs of consecutive facets: a query
//! visits the nearer box first and skips every box farther than the nearest facet found, so a point costs about
//! log n facet tests where the chain is not folded on itself, instead of one per facet. The traction estimate's
//! weights read the distance of every node of the mesh ([`crate::results`]' estimator).

use super::boundary::segment_distance;
use super::ContactBoundary;
use crate::mesh::Point;

/// Facets per leaf of the hierarchy.
const LEAF: usize = 4;

/// A box of the hierarchy: its bounds (x0, y0, x1, y1), the facets it holds (`lo..hi`, facet k from node k to
/// node k + 1) and its two halves (none for a leaf).
struct Node {
    bounds: [f64; 4],
    facets: std::ops::Range<usize>,
    halves: Option<[usize; 2]>,
}

/// The hierarchy over the facets of a chain of points.
struct Hierarchy<'a> {
    points: &'a [Point],
    nodes: Vec<Node>,
}

impl<'a> Hierarchy<'a> {
    fn new(points: &'a [Point]) -> Self {
        let mut tree = Self { points, nodes: Vec::with_capacity(2 * points.len() / LEAF + 2) };
        if points.len() >= 2 {
            tree.build(0..points.len() - 1);
        }
        tree
    }

    /// Adds the box of `facets` and, beyond a leaf, its two halves; returns its index.
    fn build(&mut self, facets: std::ops::Range<usize>) -> usize {
        let mut bounds = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
        for p in &self.points[facets.start..=facets.end] {
            bounds = [bounds[0].min(p[0]), bounds[1].min(p[1]), bounds[2].max(p[0]), bounds[3].max(p[1])];
        }
        let index = self.nodes.len();
        self.nodes.push(Node { bounds, facets: facets.clone(), halves: None });
        if facets.len() > LEAF {
            let middle = facets.start + facets.len() / 2;
            let halves = [self.build(facets.start..middle), self.build(middle..facets.end)];
            self.nodes[index].halves = Some(halves);
        }
        index
    }

    /// The distance from `p` to the nearest facet.
    fn distance(&self, p: Point) -> f64 {
        let to_box = |n: usize| {
            let b = self.nodes[n].bounds;
            (b[0] - p[0]).max(p[0] - b[2]).max(0.0).hypot((b[1] - p[1]).max(p[1] - b[3]).max(0.0))
        };
        let mut best = f64::INFINITY;
        let mut stack = if self.nodes.is_empty() { vec![] } else { vec![(0, to_box(0))] };
        while let Some((n, near)) = stack.pop() {
            if near >= best {
                continue;
            }
            match self.nodes[n].halves {
                None => {
                    for k in self.nodes[n].facets.clone() {
                        best = best.min(segment_distance(p, self.points[k], self.points[k + 1]));
                    }
                }
                Some([a, b]) => {
                    let (da, db) = (to_box(a), to_box(b));
                    // (the nearer half last, so that it is visited first)
                    if da <= db {
                        stack.extend([(b, db), (a, da)]);
                    } else {
                        stack.extend([(a, da), (b, db)]);
                    }
                }
            }
        }
        best
    }
}

impl ContactBoundary {
    /// The distance of each of `points` to Γ_C (its facets, from its first node to its last), as
    /// [`ContactBoundary::distance_to_span`] over all of Γ_C gives it.
    pub(crate) fn distances(&self, points: &[Point]) -> Vec<f64> {
        let (Some(&lo), Some(&hi)) = (self.node_xi.first(), self.node_xi.last()) else {
            return vec![f64::INFINITY; points.len()];
        };
        if self.is_straight() {
            return points.iter().map(|&p| self.distance_to_span(p, lo, hi)).collect();
        }
        let tree = Hierarchy::new(&self.node_points);
        points.iter().map(|&p| tree.distance(p)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a folded chain (a zigzag spiral) and on a closed loop, the hierarchy's distance is the smallest distance
    /// to the facets for points inside, on and far outside the chain.
    #[test]
    fn the_hierarchy_finds_the_nearest_facet() {
        let spiral: Vec<Point> = (0..300)
            .map(|k| {
                let t = 0.1 * k as f64;
                let r = 1.0 + 0.05 * t + if k % 2 == 0 { 0.02 } else { -0.02 };
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        let circle: Vec<Point> = (0..=64)
            .map(|k| {
                let t = std::f64::consts::TAU * (k % 64) as f64 / 64.0;
                [t.cos(), t.sin()]
            })
            .collect();
        for chain in [&spiral, &circle] {
            let tree = Hierarchy::new(chain);
            for i in 0..400 {
                let t = 0.37 * i as f64;
                let p = [(0.01 * i as f64) * t.cos() * 5.0, (0.01 * i as f64) * t.sin() * 5.0 - 0.3];
                let brute = chain.windows(2).map(|w| segment_distance(p, w[0], w[1])).fold(f64::INFINITY, f64::min);
                assert_eq!(tree.distance(p), brute, "{p:?}");
            }
            assert_eq!(tree.distance(chain[7]), 0.0);
        }
    }
}
