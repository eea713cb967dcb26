//! Mesh generators for axis-aligned rectangles.
//!
//! [`rectangle`] splits a uniform `nx × ny` grid of cells into triangles; [`graded_rectangle`] builds a
//! mesh that is fine along a segment of one side and geometrically coarser away from it, from a
//! 2:1-balanced quadtree. Both name four edge sets, `"bottom"`, `"right"`, `"top"` and `"left"`: every
//! boundary edge on that side, listed by increasing coordinate along the side, each edge from its lower to
//! its higher end.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::f64::consts::PI;

use crate::choice::{named_choice, Choice};
use crate::error::{Error, Result};
use crate::mesh::{Mesh, Point};

/// Largest number of cells a generator agrees to build (estimated beforehand for graded meshes): 16 million
/// triangles (about 16 million unknowns), about 2 GB while the mesh is validated, beyond what the solver can
/// factorize in 24 GB (10 million unknowns take about 20 GB, see docs/scale.md), and refused before anything
/// is allocated.
pub const MAX_CELLS: usize = 8_000_000;

/// Largest lattice index on the finest level: keeps every lattice coordinate exact in an `f64`.
const MAX_LATTICE: u64 = 1 << 52;

/// Diagonal pattern of a uniform rectangle mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Diagonal {
    /// Every cell is split from its lower-left to its upper-right corner.
    #[default]
    Right,
    /// Every cell is split from its lower-right to its upper-left corner.
    Left,
    /// A checkerboard of the two: cell (i, j) is split like [`Diagonal::Right`] when i + j is even.
    Alternating,
}

/// A side of an axis-aligned rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The side y = y_min.
    Bottom,
    /// The side x = x_max.
    Right,
    /// The side y = y_max.
    Top,
    /// The side x = x_min.
    Left,
}

// The name of a side is the name of its edge set.
named_choice!(Side, "side", { Side::Bottom => "bottom", Side::Right => "right", Side::Top => "top", Side::Left => "left" });
named_choice!(Diagonal, "diagonal", {
    Diagonal::Right => "right",
    Diagonal::Left => "left",
    Diagonal::Alternating => "alternating",
});

/// Where and how strongly [`graded_rectangle`] refines.
#[derive(Debug, Clone, PartialEq)]
pub struct Grading {
    /// The side that carries the refined segment.
    pub side: Side,
    /// The refined segment, as a coordinate range along `side`: an x range for [`Side::Bottom`] and
    /// [`Side::Top`], a y range for [`Side::Left`] and [`Side::Right`]. `[a, a]` grades toward a point.
    pub segment: [f64; 2],
    /// Target cell size on the segment: cells there have a size (longer side) of at most `h_min`, and more
    /// than `h_min / 2` unless the base cells are already smaller.
    pub h_min: f64,
    /// Largest cell size, reached far from the segment.
    pub h_max: f64,
    /// Growth rate of the target size with the distance d to the segment:
    /// h(d) = min(h_max, h_min + growth d).
    pub growth: f64,
}

impl Grading {
    /// The default growth rate. The grading itself biases λ_n by an amount set by the growth, not by
    /// `h_min` (Hertz, L2 error of λ_n as h_min → 0, measured: 3.2 % at growth 0.6, 1.4 % at 0.3, 0.65 % at
    /// 0.15, 0.29 % at 0.075, against Hertz; study 6 against a converged reference: growth 0.3 stalls at
    /// 1.3–1.5 % from 8k unknowns on, 0.15 reaches 0.85 % at 13k and 0.61 % at 24k). 0.15 is the largest
    /// of these whose floor is under 1 %, at about 1.7× the unknowns of 0.3 for the same `h_min`; below
    /// 1 %, adaptive refinement (`Problem::solve_adaptive`) needs no grading at all.
    pub const DEFAULT_GROWTH: f64 = 0.15;
    /// The default `h_min` is `h_max` divided by this.
    pub const DEFAULT_REFINEMENT: f64 = 16.0;

    /// The grading toward `segment` of `side` with the defaults: `h_min = h_max / 16`, growth
    /// [`Grading::DEFAULT_GROWTH`].
    pub fn new(side: Side, segment: [f64; 2], h_max: f64) -> Self {
        Self { side, segment, h_min: h_max / Self::DEFAULT_REFINEMENT, h_max, growth: Self::DEFAULT_GROWTH }
    }
}

fn bad(what: impl Into<String>) -> Error {
    Error::BadGenerator { what: what.into() }
}

/// Checks a coordinate range and returns its (finite, positive) width.
fn check_range(name: &str, r: [f64; 2]) -> Result<f64> {
    let width = r[1] - r[0];
    if r[0].is_finite() && r[1].is_finite() && width.is_finite() && r[0] < r[1] {
        Ok(width)
    } else {
        Err(bad(format!("the {name} range [{}, {}] must be finite, non-empty and increasing", r[0], r[1])))
    }
}

/// Coordinate of lattice index `k` of `n` on the range `r`, exact at both ends.
fn lerp(r: [f64; 2], k: u64, n: u64) -> f64 {
    if k == n {
        r[1]
    } else {
        r[0] + (r[1] - r[0]) * (k as f64 / n as f64)
    }
}

fn side_sets(sides: [Vec<(u64, [usize; 2])>; 4]) -> BTreeMap<String, Vec<[usize; 2]>> {
    [Side::Bottom, Side::Right, Side::Top, Side::Left]
        .into_iter()
        .zip(sides)
        .map(|(side, mut edges)| {
            edges.sort_unstable_by_key(|e| e.0);
            (side.as_str().to_string(), edges.into_iter().map(|e| e.1).collect())
        })
        .collect()
}

/// A uniform mesh of the rectangle `x × y`: `nx × ny` equal cells, each split into 2 triangles along
/// `diagonal`, with `(nx + 1)(ny + 1)` nodes numbered row by row from the lower-left corner.
///
/// # Errors
/// [`Error::BadGenerator`] if a range is not finite or not increasing, if `nx` or `ny` is zero or if the
/// grid has more than 20 million cells; the errors of [`Mesh::new`] if the cells are so thin next to the
/// coordinates that triangles degenerate.
pub fn rectangle(x: [f64; 2], y: [f64; 2], nx: usize, ny: usize, diagonal: Diagonal) -> Result<Mesh> {
    check_range("x", x)?;
    check_range("y", y)?;
    if nx == 0 || ny == 0 {
        return Err(bad(format!("a rectangle needs at least one cell per direction, got nx = {nx}, ny = {ny}")));
    }
    if nx.checked_mul(ny).is_none_or(|cells| cells > MAX_CELLS) {
        return Err(bad(format!("{nx} x {ny} cells is more than the limit of {MAX_CELLS}")));
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let points: Vec<Point> = (0..=ny)
        .flat_map(|j| (0..=nx).map(move |i| [lerp(x, i as u64, nx as u64), lerp(y, j as u64, ny as u64)]))
        .collect();
    let mut triangles = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            let right = match diagonal {
                Diagonal::Right => true,
                Diagonal::Left => false,
                Diagonal::Alternating => (i + j) % 2 == 0,
            };
            if right {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    let sides = [
        (0..nx).map(|i| (i as u64, [id(i, 0), id(i + 1, 0)])).collect(),
        (0..ny).map(|j| (j as u64, [id(nx, j), id(nx, j + 1)])).collect(),
        (0..nx).map(|i| (i as u64, [id(i, ny), id(i + 1, ny)])).collect(),
        (0..ny).map(|j| (j as u64, [id(0, j), id(0, j + 1)])).collect(),
    ];
    Mesh::new(points, triangles, side_sets(sides))
}

/// Validates a grading against the rectangle and returns the segment as a (degenerate) box `[x, y]`.
fn check_grading(x: [f64; 2], y: [f64; 2], g: &Grading) -> Result<[[f64; 2]; 2]> {
    if !(g.h_min.is_finite() && g.h_min > 0.0) {
        return Err(bad(format!("h_min = {} must be finite and positive", g.h_min)));
    }
    if !(g.h_max.is_finite() && g.h_max >= g.h_min) {
        return Err(bad(format!("h_max = {} must be finite and at least h_min = {}", g.h_max, g.h_min)));
    }
    if !(g.growth.is_finite() && g.growth > 0.0) {
        return Err(bad(format!("growth = {} must be finite and positive", g.growth)));
    }
    let [a, b] = g.segment;
    let along = match g.side {
        Side::Bottom | Side::Top => x,
        Side::Left | Side::Right => y,
    };
    if !(a.is_finite() && b.is_finite() && a <= b && along[0] <= a && b <= along[1]) {
        return Err(bad(format!(
            "segment [{a}, {b}] must be finite, increasing and inside the {} side [{}, {}]",
            g.side, along[0], along[1]
        )));
    }
    Ok(match g.side {
        Side::Bottom => [[a, b], [y[0], y[0]]],
        Side::Top => [[a, b], [y[1], y[1]]],
        Side::Left => [[x[0], x[0]], [a, b]],
        Side::Right => [[x[1], x[1]], [a, b]],
    })
}

/// Estimated number of quadtree cells: twice the integral of 1 / h(d)² over the rectangle (cells end up
/// between h/2 and h in size), times `(1 + min(growth, 1))²` (a cell is compared with h at its point
/// closest to the segment, smaller than at its centre by about `growth × size`; the 2:1 balance caps the
/// effective growth near 1), divided by the aspect ratio of the base cells.
///
/// The integral is bounded by integrating over the distance d to the segment, the set at distance d
/// having length at most `seg_len + π d`, up to where h reaches h_max, plus `area / h_max²` beyond.
fn estimate_cells(area: f64, diameter: f64, seg_len: f64, g: &Grading, aspect: f64) -> f64 {
    const PANELS: usize = 64;
    let d1 = ((g.h_max - g.h_min) / g.growth).min(diameter);
    // Substitution h_min + growth d = h_min e^t makes the integrand smooth.
    let dt = (g.growth * d1 / g.h_min).ln_1p() / PANELS as f64;
    let near: f64 = (0..PANELS)
        .map(|k| {
            let t = (k as f64 + 0.5) * dt;
            let d = g.h_min * t.exp_m1() / g.growth;
            (seg_len + PI * d) / (g.h_min * t.exp() * g.growth) * dt
        })
        .sum();
    let integral = (near + area / (g.h_max * g.h_max)).min(area / (g.h_min * g.h_min));
    2.0 * (1.0 + g.growth.min(1.0)).powi(2) * integral / aspect
}

/// Leaves of a quadtree over an `nx × ny` base grid: `levels[l]` holds the leaves (i, j) of level l, whose
/// cells are `[i, i + 1] × [j, j + 1]` in units of the level-l grid (`nx 2^l × ny 2^l` cells).
struct Quadtree {
    levels: Vec<HashSet<(u64, u64)>>,
    nx: u64,
    ny: u64,
    count: usize,
}

impl Quadtree {
    /// The level of the leaf that contains cell (l, i, j), if it is a leaf or lies in a coarser leaf.
    fn covering(&self, l: usize, i: u64, j: u64) -> Option<usize> {
        (0..=l).rev().find(|&lc| self.levels[lc].contains(&(i >> (l - lc), j >> (l - lc))))
    }

    /// Replaces the leaf (l, i, j) by its 4 children.
    fn split(&mut self, l: usize, i: u64, j: u64) {
        self.levels[l].remove(&(i, j));
        self.levels[l + 1].extend([(2 * i, 2 * j), (2 * i + 1, 2 * j), (2 * i, 2 * j + 1), (2 * i + 1, 2 * j + 1)]);
        self.count += 3;
    }

    /// The cells of level l across the bottom, right, top and left edges of (l, i, j), `None` outside.
    fn neighbours(&self, l: usize, i: u64, j: u64) -> [Option<(u64, u64)>; 4] {
        [
            j.checked_sub(1).map(|j| (i, j)),
            (i + 1 < self.nx << l).then_some((i + 1, j)),
            (j + 1 < self.ny << l).then_some((i, j + 1)),
            i.checked_sub(1).map(|i| (i, j)),
        ]
    }
}

/// Nodes keyed by their integer coordinates on the finest lattice, so coincident nodes merge exactly.
struct Nodes {
    index: HashMap<(u64, u64), usize>,
    points: Vec<Point>,
    x: [f64; 2],
    y: [f64; 2],
    n: [u64; 2],
}

impl Nodes {
    fn get(&mut self, (i, j): (u64, u64)) -> usize {
        *self.index.entry((i, j)).or_insert_with(|| {
            self.points.push([lerp(self.x, i, self.n[0]), lerp(self.y, j, self.n[1])]);
            self.points.len() - 1
        })
    }
}

/// A mesh of the rectangle `x × y` that is fine along `grading.segment` and coarser away from it.
///
/// A base grid of `ceil(width / h_max) × ceil(height / h_max)` cells is refined as a quadtree: a cell is
/// split into 4 while its size (longer side) exceeds h(d) = min(h_max, h_min + growth d), d being the
/// distance from the cell to the segment. Neighbouring leaves are then balanced to differ by at most one
/// level across an edge. A leaf along the graded side, or with hanging nodes, becomes a fan of triangles
/// from its centre (so the mesh is conforming, and every edge of the graded side belongs to an isosceles
/// triangle of one shape: λ_n on it is as smooth as on a uniform mesh); any other leaf becomes 2
/// triangles, split along one diagonal before the segment's centre (along the side) and along the other
/// after it, so the mesh is mirror-symmetric about that centre where the quadtree is. A
/// segment that starts or ends at an end of the side is mirrored about that end instead: the mesh of a
/// half model graded toward `[0, b]` is then exactly the right half of the full model's graded toward
/// `[−b, b]`.
///
/// # Errors
/// [`Error::BadGenerator`] if a range is not finite or not increasing, if `h_min`, `h_max` or `growth`
/// is not finite, `h_min` or `growth` not positive, `h_max < h_min`, the segment reversed or not inside the
/// side, or if the mesh would be too large (more than about 20 million cells, or 2^52 finest cells across).
pub fn graded_rectangle(x: [f64; 2], y: [f64; 2], grading: &Grading) -> Result<Mesh> {
    let g = grading;
    let (width, height) = (check_range("x", x)?, check_range("y", y)?);
    let seg = check_grading(x, y, g)?;
    let too_large = |what: String| bad(format!("{what}: the mesh would be too large; raise h_min or growth"));
    let (nxf, nyf) = ((width / g.h_max).ceil().max(1.0), (height / g.h_max).ceil().max(1.0));
    if nxf * nyf > MAX_CELLS as f64 {
        return Err(too_large(format!("the base grid has {nxf} x {nyf} cells")));
    }
    let (dx, dy) = (width / nxf, height / nyf);
    let base = dx.max(dy);
    let seg_len = g.segment[1] - g.segment[0];
    let diameter = width.hypot(height);
    let estimate = estimate_cells(width * height, diameter, seg_len, g, dx.min(dy) / base);
    if estimate.is_nan() || estimate > MAX_CELLS as f64 {
        return Err(too_large(format!(
            "about {} cells estimated, the limit is {MAX_CELLS}",
            crate::error::Num(estimate)
        )));
    }
    let (nx, ny) = (nxf as u64, nyf as u64);
    let mut lmax = 0;
    while base * 0.5f64.powi(lmax as i32) > g.h_min {
        lmax += 1;
        if lmax > 52 || nx.max(ny) > MAX_LATTICE >> lmax {
            return Err(too_large(format!("more than {lmax} levels of refinement from h_max to h_min")));
        }
    }
    let size = |l: usize| base * 0.5f64.powi(l as i32);
    let target = |d: f64| (g.h_min + g.growth * d).min(g.h_max);
    let n = [nx << lmax, ny << lmax];
    let gap = |lo: f64, hi: f64, s: [f64; 2]| (s[0] - hi).max(lo - s[1]).max(0.0);

    // Refinement by distance to the segment.
    let mut tree = Quadtree { levels: vec![HashSet::new(); lmax + 1], nx, ny, count: 0 };
    let mut stack: Vec<(usize, u64, u64)> = (0..ny).flat_map(|j| (0..nx).map(move |i| (0, i, j))).collect();
    while let Some((l, i, j)) = stack.pop() {
        let s = lmax - l;
        let (x0, x1) = (lerp(x, i << s, n[0]), lerp(x, (i + 1) << s, n[0]));
        let (y0, y1) = (lerp(y, j << s, n[1]), lerp(y, (j + 1) << s, n[1]));
        let d = gap(x0, x1, seg[0]).hypot(gap(y0, y1, seg[1]));
        if l < lmax && size(l) > target(d) {
            stack.extend([(l + 1, 2 * i, 2 * j), (l + 1, 2 * i + 1, 2 * j)]);
            stack.extend([(l + 1, 2 * i, 2 * j + 1), (l + 1, 2 * i + 1, 2 * j + 1)]);
        } else {
            tree.levels[l].insert((i, j));
            tree.count += 1;
            if tree.count > MAX_CELLS {
                return Err(too_large(format!("more than {MAX_CELLS} cells")));
            }
        }
    }

    // 2:1 balance across edges, finest level first: splits only create leaves of coarser levels.
    for l in (2..=lmax).rev() {
        let mut cells: Vec<(u64, u64)> = tree.levels[l].iter().copied().collect();
        cells.sort_unstable();
        for (i, j) in cells {
            for (ni, nj) in tree.neighbours(l, i, j).into_iter().flatten() {
                while let Some(lc) = tree.covering(l, ni, nj).filter(|&lc| lc + 1 < l) {
                    tree.split(lc, ni >> (l - lc), nj >> (l - lc));
                }
            }
        }
        if tree.count > MAX_CELLS {
            return Err(too_large(format!("more than {MAX_CELLS} cells")));
        }
    }

    // Triangulation on a lattice twice as fine as the finest cells (so that every cell has a centre node),
    // leaves in row-major order of their lower-left corners.
    //
    // The cells along the graded side are fans of 4 triangles from their centre: the triangle owning an
    // edge of Γ_C is then isosceles, the same shape along all of Γ_C and its own mirror image. With 2
    // triangles per cell the owners alternate (a checkerboard of diagonals: λ_n zig-zagged, 15 changes of
    // direction over 17 dofs in contact on the Hertz scene at h_min = 0.01) or are mirror images of each
    // other on the two sides of a symmetry line (λ_n has a kink there). The other cells without a hanging
    // node are split along one diagonal, mirrored across the line, the diagonals of the two cells beside
    // it meeting at their corner away from the graded side (meeting next to it, λ_n of the Hertz scene
    // dipped by 1 % at the line), so the mesh is the mirror image of itself about that line where the quadtree
    // is: the line is the segment's centre, or the end of the side a segment starts or ends at (a half
    // model's symmetry line: its mesh is then the right or left half of the full model's).
    let n2 = [2 * n[0], 2 * n[1]];
    let (lo, hi, n_along, graded_side) = match g.side {
        Side::Bottom => (x[0], x[1], n2[0], 0),
        Side::Right => (y[0], y[1], n2[1], 1),
        Side::Top => (x[0], x[1], n2[0], 2),
        Side::Left => (y[0], y[1], n2[1], 3),
    };
    let [a, b] = g.segment;
    let mirror = if a == lo && b < hi {
        lo
    } else if b == hi && a > lo {
        hi
    } else {
        0.5 * (a + b)
    };
    // In half units of the lattice: a cell lies before the line when twice its centre's index is at most it.
    let mirror2 = (2.0 * (mirror - lo) / (hi - lo) * n_along as f64).round() as u64;
    // The diagonals of the two cells beside the mirror line meet at a node of the line on the far side of
    // the cells from the graded side: at their lower (left) corners for the top (right) side.
    let meet_low = matches!(g.side, Side::Top | Side::Right);
    let mut leaves: Vec<(usize, u64, u64)> =
        tree.levels.iter().enumerate().flat_map(|(l, set)| set.iter().map(move |&(i, j)| (l, i, j))).collect();
    leaves.sort_unstable_by_key(|&(l, i, j)| (j << (lmax - l), i << (lmax - l), l));
    let mut nodes = Nodes { index: HashMap::new(), points: Vec::new(), x, y, n: n2 };
    let mut triangles = Vec::with_capacity(3 * leaves.len());
    let mut sides: [Vec<(u64, [usize; 2])>; 4] = Default::default();
    for &(l, i, j) in &leaves {
        let s = 2u64 << (lmax - l);
        let (i0, j0, h) = (i * s, j * s, s / 2);
        let centre_along = match graded_side {
            0 | 2 => i0 + h,
            _ => j0 + h,
        };
        let corners = [(i0, j0), (i0 + s, j0), (i0 + s, j0 + s), (i0, j0 + s)];
        let mids = [(i0 + h, j0), (i0 + s, j0 + h), (i0 + h, j0 + s), (i0, j0 + h)];
        let neighbours = tree.neighbours(l, i, j);
        // A neighbour region that no leaf of this level or coarser covers is split: after balancing, its
        // leaves along the shared edge are one level finer and put a node at the edge midpoint.
        let hanging = neighbours.map(|nb| nb.is_some_and(|(ni, nj)| tree.covering(l, ni, nj).is_none()));
        let c = corners.map(|k| nodes.get(k));
        if neighbours[graded_side].is_none() || hanging.iter().any(|&hg| hg) {
            let mut perimeter = Vec::with_capacity(8);
            for k in 0..4 {
                perimeter.push(c[k]);
                if hanging[k] {
                    perimeter.push(nodes.get(mids[k]));
                }
            }
            let centre = nodes.get((i0 + h, j0 + h));
            let m = perimeter.len();
            triangles.extend((0..m).map(|k| [centre, perimeter[k], perimeter[(k + 1) % m]]));
        } else if (2 * centre_along <= mirror2) == meet_low {
            // Lower-right to upper-left.
            triangles.extend([[c[0], c[1], c[3]], [c[1], c[2], c[3]]]);
        } else {
            // Lower-left to upper-right.
            triangles.extend([[c[0], c[1], c[2]], [c[0], c[2], c[3]]]);
        }
        let edges = [(i0, [c[0], c[1]]), (j0, [c[1], c[2]]), (i0, [c[3], c[2]]), (j0, [c[0], c[3]])];
        for (k, edge) in edges.into_iter().enumerate() {
            if neighbours[k].is_none() {
                sides[k].push(edge);
            }
        }
    }
    Mesh::new(nodes.points, triangles, side_sets(sides))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const SIDES: [Side; 4] = [Side::Bottom, Side::Right, Side::Top, Side::Left];

    fn total_area(mesh: &Mesh) -> f64 {
        (0..mesh.n_triangles()).map(|t| mesh.area(t)).sum()
    }

    /// Whether point p lies on `side` of the rectangle (exactly: boundary coordinates are exact).
    fn on_side(p: Point, x: [f64; 2], y: [f64; 2], side: Side) -> bool {
        match side {
            Side::Bottom => p[1] == y[0],
            Side::Right => p[0] == x[1],
            Side::Top => p[1] == y[1],
            Side::Left => p[0] == x[0],
        }
    }

    /// Area sum, conformity (interior edges shared by 2 triangles, boundary edges on the rectangle
    /// boundary, boundary length = perimeter) and the four side sets.
    fn check_mesh(mesh: &Mesh, x: [f64; 2], y: [f64; 2]) {
        let (w, h) = (x[1] - x[0], y[1] - y[0]);
        let rel = |a: f64, b: f64| (a - b).abs() / b;
        assert!(rel(total_area(mesh), w * h) < 1e-12, "area {} vs {}", total_area(mesh), w * h);
        let mut count: HashMap<[usize; 2], usize> = HashMap::new();
        for t in mesh.triangles() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry([a.min(b), a.max(b)]).or_default() += 1;
            }
        }
        let p = mesh.points();
        let mut boundary_length = 0.0;
        for (e, &c) in &count {
            assert!(c <= 2, "edge {e:?} shared by {c} triangles");
            if c == 1 {
                let side = SIDES.iter().find(|&&s| on_side(p[e[0]], x, y, s) && on_side(p[e[1]], x, y, s));
                assert!(side.is_some(), "boundary edge {:?} - {:?} inside the rectangle", p[e[0]], p[e[1]]);
                boundary_length += mesh.edge_length(e[0], e[1]);
            }
        }
        assert!(rel(boundary_length, 2.0 * (w + h)) < 1e-12);
        assert_eq!(mesh.edge_set_names().collect::<Vec<_>>(), ["bottom", "left", "right", "top"]);
        for side in SIDES {
            let edges = mesh.edge_set(side.as_str()).unwrap();
            let length: f64 = edges.iter().map(|e| mesh.edge_length(e[0], e[1])).sum();
            let expected = if matches!(side, Side::Bottom | Side::Top) { w } else { h };
            assert!(rel(length, expected) < 1e-12, "{} has length {length}", side.as_str());
            for e in edges {
                assert!(on_side(p[e[0]], x, y, side) && on_side(p[e[1]], x, y, side));
            }
        }
        assert_eq!(count.values().filter(|&&c| c == 1).count(), mesh.boundary_edges().count());
    }

    fn example(h_min: f64) -> Grading {
        Grading { side: Side::Top, segment: [-0.5, 0.5], h_min, h_max: 0.5, growth: 0.3 }
    }

    #[test]
    fn rectangle_counts_and_sets() {
        let (x, y) = ([-1.0, 2.0], [0.5, 1.25]);
        for diagonal in [Diagonal::Right, Diagonal::Left, Diagonal::Alternating] {
            let mesh = rectangle(x, y, 6, 3, diagonal).unwrap();
            assert_eq!(mesh.n_nodes(), 7 * 4);
            assert_eq!(mesh.n_triangles(), 2 * 6 * 3);
            check_mesh(&mesh, x, y);
            assert_eq!(mesh.edge_set("bottom").unwrap().len(), 6);
            assert_eq!(mesh.edge_set("left").unwrap().len(), 3);
        }
        assert_eq!(Diagonal::default(), Diagonal::Right);
        // Cell (0, 0) has nodes 0, 1, 8, 7: the right diagonal is 0-8, the left one 1-7.
        let has_edge = |m: &Mesh, a, b| m.triangles().iter().any(|t| t.contains(&a) && t.contains(&b));
        let right = rectangle(x, y, 6, 3, Diagonal::Right).unwrap();
        assert!(has_edge(&right, 0, 8) && !has_edge(&right, 1, 7));
        let left = rectangle(x, y, 6, 3, Diagonal::Left).unwrap();
        assert!(has_edge(&left, 1, 7) && !has_edge(&left, 0, 8));
        let alt = rectangle(x, y, 6, 3, Diagonal::Alternating).unwrap();
        assert!(has_edge(&alt, 0, 8) && has_edge(&alt, 2, 8));
        let one = rectangle([0.0, 1.0], [0.0, 1.0], 1, 1, Diagonal::Right).unwrap();
        assert_eq!((one.n_nodes(), one.n_triangles()), (4, 2));
    }

    #[test]
    fn rectangle_rejects_bad_parameters() {
        let ok = [0.0, 1.0];
        let bad_cases = [
            rectangle([1.0, 1.0], ok, 2, 2, Diagonal::Right),
            rectangle([1.0, 0.0], ok, 2, 2, Diagonal::Right),
            rectangle(ok, [f64::NAN, 1.0], 2, 2, Diagonal::Right),
            rectangle(ok, [0.0, f64::INFINITY], 2, 2, Diagonal::Right),
            rectangle([-f64::MAX, f64::MAX], ok, 2, 2, Diagonal::Right),
            rectangle(ok, ok, 0, 2, Diagonal::Right),
            rectangle(ok, ok, 2, 0, Diagonal::Right),
            rectangle(ok, ok, 100_000, 100_000, Diagonal::Right),
            rectangle(ok, ok, usize::MAX, 2, Diagonal::Right),
        ];
        for r in bad_cases {
            assert!(matches!(r, Err(Error::BadGenerator { .. })), "{r:?}");
        }
    }

    #[test]
    fn graded_example() {
        let (x, y) = ([-2.0, 2.0], [-2.0, 0.0]);
        let g = example(0.02);
        let mesh = graded_rectangle(x, y, &g).unwrap();
        check_mesh(&mesh, x, y);
        let p = mesh.points();
        let mut fine = 0;
        for e in mesh.edge_set("top").unwrap() {
            let (a, b) = (p[e[0]], p[e[1]]);
            assert!(a[0] < b[0]);
            if a[0] >= -0.5 && b[0] <= 0.5 {
                let length = mesh.edge_length(e[0], e[1]);
                assert!(length <= g.h_min * (1.0 + 1e-12) && length >= g.h_min / 2.0, "{length}");
                fine += 1;
            }
        }
        assert!(fine >= 50, "{fine} fine edges on the segment");
        let far = (0..mesh.n_triangles())
            .filter(|&t| mesh.vertices(t).iter().all(|v| v[1] <= -1.5 && v[0].abs() >= 1.5))
            .map(|t| mesh.diameter(t))
            .fold(0.0, f64::max);
        assert!(far >= g.h_max / 2.0, "largest far triangle {far}");
        // Far fewer triangles than a uniform mesh of size h_min, besides the 2 more of every fan cell along
        // the graded side.
        let uniform = 2.0 * 8.0 / (g.h_min * g.h_min);
        let fans = 2 * mesh.edge_set("top").unwrap().len();
        assert!(((mesh.n_triangles() - fans) as f64) < 0.05 * uniform, "{} triangles", mesh.n_triangles());
        // Deterministic numbering.
        let again = graded_rectangle(x, y, &g).unwrap();
        assert_eq!(mesh.triangles(), again.triangles());
    }

    #[test]
    fn graded_every_side_point_segment_and_uniform() {
        let (x, y) = ([0.0, 3.0], [1.0, 2.0]);
        for side in SIDES {
            let segment = if matches!(side, Side::Bottom | Side::Top) { [1.0, 1.0] } else { [1.25, 2.0] };
            let g = Grading { side, segment, h_min: 0.01, h_max: 0.4, growth: 0.5 };
            let mesh = graded_rectangle(x, y, &g).unwrap();
            check_mesh(&mesh, x, y);
            let shortest = mesh.edge_set(side.as_str()).unwrap().iter().map(|e| mesh.edge_length(e[0], e[1]));
            assert!(shortest.fold(f64::INFINITY, f64::min) <= g.h_min);
        }
        // h_min = h_max: the base grid, unrefined (3 / 0.5 x 1 / 0.5 cells), the 6 cells along the top
        // fans of 4 triangles around a centre node.
        let g = Grading { side: Side::Top, segment: [0.0, 3.0], h_min: 0.5, h_max: 0.5, growth: 1.0 };
        let mesh = graded_rectangle(x, y, &g).unwrap();
        assert_eq!((mesh.n_nodes(), mesh.n_triangles()), (7 * 3 + 6, 2 * 6 + 4 * 6));
        check_mesh(&mesh, x, y);
    }

    /// The graded mesh is its own mirror image about the segment's centre, on every side: the triangles,
    /// as sets of vertices snapped to a lattice far finer than the cells, map onto each other.
    #[test]
    fn graded_is_mirror_symmetric() {
        let (x, y) = ([-2.0, 2.0], [-1.0, 1.0]);
        for side in SIDES {
            let g = Grading { side, segment: [-0.3, 0.3], h_min: 0.03, h_max: 0.5, growth: 0.3 };
            let mesh = graded_rectangle(x, y, &g).unwrap();
            let vertical = matches!(side, Side::Bottom | Side::Top);
            let key = |p: Point, mirror: bool| {
                let (a, b) = if vertical { (p[0], p[1]) } else { (p[1], p[0]) };
                let a = if mirror { -a } else { a };
                [(a * 1e6).round() as i64, (b * 1e6).round() as i64]
            };
            let tris = |mirror: bool| {
                let mut all: Vec<[[i64; 2]; 3]> = (0..mesh.n_triangles())
                    .map(|t| {
                        let mut v = mesh.vertices(t).map(|p| key(p, mirror));
                        v.sort_unstable();
                        v
                    })
                    .collect();
                all.sort_unstable();
                all
            };
            assert_eq!(tris(false), tris(true), "{side:?}");
        }
    }

    #[test]
    fn grading_defaults_are_the_measured_ones() {
        let g = Grading::new(Side::Top, [-0.3, 0.3], 0.5);
        assert_eq!((g.h_min, g.h_max, g.growth), (0.5 / 16.0, 0.5, 0.15));
        assert!(graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &g).is_ok());
    }

    #[test]
    fn graded_rejects_bad_parameters() {
        let (x, y) = ([-2.0, 2.0], [-2.0, 0.0]);
        let with = |f: &dyn Fn(&mut Grading)| {
            let mut g = example(0.02);
            f(&mut g);
            graded_rectangle(x, y, &g)
        };
        let bad_cases = [
            with(&|g| g.h_min = 0.0),
            with(&|g| g.h_min = -0.1),
            with(&|g| g.h_min = f64::NAN),
            with(&|g| g.h_max = 0.01),
            with(&|g| g.h_max = f64::INFINITY),
            with(&|g| g.growth = 0.0),
            with(&|g| g.growth = -1.0),
            with(&|g| g.growth = f64::NAN),
            with(&|g| g.segment = [0.5, -0.5]),
            with(&|g| g.segment = [-2.5, 0.5]),
            with(&|g| g.segment = [0.5, 2.5]),
            with(&|g| g.segment = [f64::NAN, 0.5]),
            with(&|g| g.side = Side::Left),
            // Runaway sizes: millions of cells along the segment, or too many levels toward a point.
            with(&|g| g.h_min = 1e-8),
            with(&|g| {
                g.segment = [0.0, 0.0];
                g.h_min = 1e-300;
                g.growth = 1.0;
            }),
            graded_rectangle([0.0, 1e9], [0.0, 1e-9], &Grading { segment: [0.0, 1.0], h_max: 1e-3, ..example(1e-3) }),
            graded_rectangle([0.0, 0.0], y, &example(0.02)),
            graded_rectangle(x, [0.0, f64::NAN], &example(0.02)),
        ];
        for (k, r) in bad_cases.into_iter().enumerate() {
            assert!(matches!(r, Err(Error::BadGenerator { .. })), "case {k}: {r:?}");
        }
        // Segments on the ends of the side are fine.
        assert!(with(&|g| g.segment = [-2.0, 2.0]).is_ok());
        assert!(with(&|g| g.segment = [2.0, 2.0]).is_ok());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn graded_is_conforming(
            x0 in -10.0..10.0f64, w in 0.1..10.0f64, y0 in -10.0..10.0f64, aspect in 0.2..5.0f64,
            side in 0..4usize, s0 in 0.0..1.0f64, s1 in 0.0..1.0f64,
            cells in 1.0..8.0f64, ratio in 1.0..12.0f64, growth in 0.2..2.0f64,
        ) {
            let (x, y) = ([x0, x0 + w], [y0, y0 + w * aspect]);
            let side = SIDES[side];
            let along = if matches!(side, Side::Bottom | Side::Top) { x } else { y };
            let at = |s: f64| along[0] + s * (along[1] - along[0]);
            let h_max = w.max(w * aspect) / cells;
            let segment = [at(s0.min(s1)), at(s0.max(s1))];
            let g = Grading { side, segment, h_min: h_max / ratio, h_max, growth };
            let mesh = graded_rectangle(x, y, &g).unwrap();
            check_mesh(&mesh, x, y);
        }
    }
}
