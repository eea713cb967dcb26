//! Mesh generators for round shapes, whose contact sides are faceted arcs (a bent Γ_C,
//! [`crate::contact::ContactBoundary`]).
//!
//! [`ring_sector`] meshes the sector of a ring, fine along part of its outer arc: a roller's rim pressed on a
//! flat, clamped on its inner arc. It maps a [`graded_rectangle`] of the unrolled sector (arclength along the
//! outer arc by radius) onto the ring, so every node of the outer arc lies on the circle exactly, and the
//! faceted arc departs from the circle by at most `h² / (8 R)` between its nodes (h the edge length). The
//! triangles are shrunk along the arcs by `r / r_out`: the ratio of the radii bounds their distortion.
//!
//! [`disc`] meshes a solid disc, or a sector of one (a half-disc with its flat side, a quarter), uniformly: nodes
//! on concentric circles `r_k = R k / n` (k = 0 the centre), about `6 k` of them on a whole circle k (the
//! triangles of a hexagonal packing, nearly equilateral at every radius), each ring joined to the next by
//! merging the two by angle. Its rim lies on the circle exactly and carries its curve, so that refinement (an
//! adaptive loop near a contact point) puts new nodes on it.
//!
//! [`plate_with_hole`] meshes a rectangular plate with a circular hole (a pin's bore): an O-grid of `around` nodes
//! round the hole, each joined to a point of the plate's edge by `across` cells, finer at the hole (the first cell
//! as deep as the hole's nodes are apart, the others growing geometrically), the plate's corners nodes of the grid.

use crate::error::{Error, Result};
use crate::mesh::generate::{graded_rectangle, Grading, Side, MAX_CELLS};
use crate::mesh::{Curve, Mesh, Point};

/// The sector of a ring to mesh: radii `r_in ≤ |x − c| ≤ r_out`, angles (radians, counterclockwise from the
/// x axis) from `angles[0]` to `angles[1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingSector {
    /// Centre c.
    pub center: Point,
    /// Inner and outer radii, `0 < r_in < r_out`, with `r_in ≥ r_out / 4` (the triangles are shrunk along the
    /// arcs by up to `r_in / r_out`).
    pub radii: [f64; 2],
    /// First and last angle, increasing, at most a full turn apart: a full turn makes a full ring, whose `outer`
    /// and `inner` sets are closed loops and which has no `start` and `end` (its seam's nodes merged; the mesh
    /// must then be uniform, or graded toward the whole outer arc, so that both sides of the seam match).
    pub angles: [f64; 2],
}

/// Where [`ring_sector`] refines: the arc of the outer circle between two angles, to cells of size `h_min`,
/// growing at `growth` away from it up to `h_max` (as [`Grading`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcGrading {
    /// The refined arc of the outer circle, as angles within the sector's (`[a, a]` grades toward a point).
    pub angles: [f64; 2],
    /// Cell size on the arc.
    pub h_min: f64,
    /// Largest cell size.
    pub h_max: f64,
    /// Growth of the cell size with the distance from the arc.
    pub growth: f64,
}

impl ArcGrading {
    /// The grading toward the arc `angles` with the defaults of [`Grading::new`]: `h_min = h_max / 16`, growth
    /// [`Grading::DEFAULT_GROWTH`].
    pub fn new(angles: [f64; 2], h_max: f64) -> Self {
        Self { angles, h_min: h_max / Grading::DEFAULT_REFINEMENT, h_max, growth: Grading::DEFAULT_GROWTH }
    }
}

/// The point at angle θ of the circle of centre c and radius r, on the axes through c exactly at the quarter turns
/// (where `cos` and `sin` round to 6e-17 and 1.2e-16, not 0), so that the side of a half or quarter model lies on its
/// symmetry line exactly. The generators' angles `t0 + span i / n` carry a few roundings of θ; an angle within 64 ε
/// (in quarter turns, relative) of a quarter turn is taken as one.
fn on_circle(c: Point, r: f64, theta: f64) -> Point {
    let quarter = theta / std::f64::consts::FRAC_PI_2;
    let k = quarter.round();
    if (quarter - k).abs() <= 64.0 * f64::EPSILON * k.abs().max(1.0) {
        let [x, y] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]][k.rem_euclid(4.0) as usize];
        return [c[0] + r * x, c[1] + r * y];
    }
    [c[0] + r * theta.cos(), c[1] + r * theta.sin()]
}

/// A mesh of a ring sector, fine along `grading.angles` of its outer arc (module documentation). The edge
/// sets are `"outer"` and `"inner"` (the arcs, each with its [`Curve`], so that refinement stays on the
/// circles) and `"start"` and `"end"` (the radial sides at the first and the last angle).
///
/// # Errors
/// [`Error::BadGenerator`] for radii or angles that are not finite, not increasing, out of the bounds of
/// [`RingSector`], or a refined arc outside the sector; the errors of [`graded_rectangle`] for the sizes.
pub fn ring_sector(sector: &RingSector, grading: &ArcGrading) -> Result<Mesh> {
    let bad = |what: String| Err(Error::BadGenerator { what });
    let ([r_in, r_out], [t0, t1]) = (sector.radii, sector.angles);
    if !sector.center.iter().all(|v| v.is_finite()) {
        return bad(format!("the centre ({}, {}) must be finite", sector.center[0], sector.center[1]));
    }
    if !(r_in.is_finite() && r_out.is_finite() && 0.0 < r_in && r_in < r_out && 4.0 * r_in >= r_out) {
        return bad(format!("radii [{r_in}, {r_out}] must be finite, with 0 < r_out / 4 ≤ r_in < r_out"));
    }
    let turn = 2.0 * std::f64::consts::PI;
    let full = (t1 - t0 - turn).abs() <= 1e-12 * t0.abs().max(t1.abs()).max(turn);
    if !(t0.is_finite() && t1.is_finite() && t0 < t1 && (t1 - t0 < turn || full)) {
        return bad(format!("angles [{t0}, {t1}] must be finite, increasing and at most a full turn apart"));
    }
    let [a, b] = grading.angles;
    if !(a.is_finite() && b.is_finite() && t0 <= a && a <= b && b <= t1) {
        return bad(format!(
            "the refined arc [{a}, {b}] must be finite, increasing and inside the sector [{t0}, {t1}]"
        ));
    }
    // The unrolled sector: s = r_out (t1 − θ) along the outer arc (decreasing θ keeps the triangles
    // counterclockwise), y = r the radius.
    let width = r_out * (t1 - t0);
    let segment = [r_out * (t1 - b), r_out * (t1 - a)].map(|s| s.clamp(0.0, width));
    let flat = graded_rectangle(
        [0.0, width],
        [r_in, r_out],
        &Grading { side: Side::Top, segment, h_min: grading.h_min, h_max: grading.h_max, growth: grading.growth },
    )?;
    let points: Vec<Point> = flat
        .points()
        .iter()
        .map(|&[s, r]| {
            // The ends of the outer arc on the circle exactly, whatever the rounding of s.
            let theta = if s == 0.0 {
                t1
            } else if s == width {
                t0
            } else {
                t1 - s / r_out
            };
            on_circle(sector.center, r, theta)
        })
        .collect();
    let names = [("top", "outer"), ("bottom", "inner"), ("left", "end"), ("right", "start")];
    let sets = names
        .iter()
        .map(|&(from, to)| Ok((to.to_string(), flat.edge_set(from)?.to_vec())))
        .collect::<Result<std::collections::BTreeMap<_, _>>>()?;
    let (points, triangles, sets) =
        if full { closed(&flat, points, sets)? } else { (points, flat.triangles().to_vec(), sets) };
    Mesh::new(points, triangles, sets)?
        .with_curve("outer", Curve::Arc { center: sector.center, radius: r_out })?
        .with_curve("inner", Curve::Arc { center: sector.center, radius: r_in })
}

/// A full ring from the sector of a full turn: the nodes of its `start` side (θ = t0) merged with those of its
/// `end` side (θ = t1 = t0 + 2π), at the same radii; `start` and `end` become interior and are dropped, `outer`
/// and `inner` closed loops.
///
/// # Errors
/// [`Error::BadGenerator`] when the two sides do not have their nodes at the same radii (a ring graded toward an
/// arc, whose cells differ at the two ends of the unrolled sector): the seam would not be conforming.
#[allow(clippy::type_complexity)]
fn closed(
    flat: &Mesh,
    mut points: Vec<Point>,
    mut sets: std::collections::BTreeMap<String, Vec<[usize; 2]>>,
) -> Result<(Vec<Point>, Vec<[usize; 3]>, std::collections::BTreeMap<String, Vec<[usize; 2]>>)> {
    let side = |name: &str| -> Result<Vec<usize>> {
        let mut nodes: Vec<usize> = sets[name].iter().flatten().copied().collect();
        nodes.sort_by(|&a, &b| flat.points()[a][1].total_cmp(&flat.points()[b][1]));
        nodes.dedup();
        Ok(nodes)
    };
    let (start, end) = (side("start")?, side("end")?);
    let radii = |nodes: &[usize]| nodes.iter().map(|&i| flat.points()[i][1]).collect::<Vec<f64>>();
    let (ra, rb) = (radii(&start), radii(&end));
    let r_out = rb.last().copied().unwrap_or(1.0);
    let differ = ra.iter().zip(&rb).find(|(a, b)| (*a - *b).abs() > 1e-12 * r_out);
    if ra.len() != rb.len() || differ.is_some() {
        let what = match differ {
            Some((a, b)) if ra.len() == rb.len() => format!("a node at radius {a} against one at {b}"),
            _ => format!("{} nodes against {}", ra.len(), rb.len()),
        };
        return Err(Error::BadGenerator {
            what: format!(
                "a full ring needs the same nodes on both sides of its seam, not {what} (grade it toward the whole \
                 outer arc, or make it uniform)"
            ),
        });
    }
    // Each start node becomes its end twin; the others are renumbered in order.
    let mut index: Vec<usize> = (0..points.len()).collect();
    for (&a, &b) in start.iter().zip(&end) {
        index[a] = b;
    }
    let mut kept = vec![usize::MAX; points.len()];
    let mut n = 0;
    for i in 0..points.len() {
        if index[i] == i {
            kept[i] = n;
            n += 1;
        }
    }
    let new = |i: usize| kept[index[i]];
    let mut k = 0;
    points.retain(|_| {
        k += 1;
        index[k - 1] == k - 1
    });
    let triangles = flat.triangles().iter().map(|t| t.map(new)).collect();
    sets.remove("start");
    sets.remove("end");
    for edges in sets.values_mut() {
        edges.iter_mut().for_each(|e| *e = e.map(new));
    }
    Ok((points, triangles, sets))
}

/// A disc, or the sector of one, to mesh by [`disc`]: centre, radius and angles (radians, counterclockwise from
/// the x axis; a full turn for the whole disc, `[π, 2π]` for a half-disc whose flat side is on top).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscSector {
    /// Centre c.
    pub center: Point,
    /// Radius R > 0.
    pub radius: f64,
    /// First and last angle, increasing, at most a full turn apart.
    pub angles: [f64; 2],
}

/// A uniform mesh of a disc or of the sector of one (module documentation), with `rings` circles of nodes
/// around its centre: cells of about `R / rings`. Its edge sets are `"rim"`, on the circle (with its [`Curve`]; a
/// closed loop for a whole disc), and for a sector `"start"` and `"end"`, the radii at its first and last angle.
///
/// # Errors
/// [`Error::BadGenerator`] for a centre, radius or angles that are not finite, a radius not positive, angles not
/// increasing or more than a full turn apart, or no rings, or so many that the disc would have more triangles
/// than [`crate::mesh::generate::MAX_CELLS`] (checked before anything is allocated).
pub fn disc(sector: &DiscSector, rings: usize) -> Result<Mesh> {
    let bad = |what: String| Err(Error::BadGenerator { what });
    let (r, [t0, t1], c) = (sector.radius, sector.angles, sector.center);
    if !(c.iter().all(|v| v.is_finite()) && r.is_finite() && r > 0.0) {
        return bad(format!("a disc needs a finite centre and a finite radius > 0, got ({}, {}) and {r}", c[0], c[1]));
    }
    let turn = 2.0 * std::f64::consts::PI;
    let full = (t1 - t0 - turn).abs() <= 1e-12 * t0.abs().max(t1.abs()).max(turn);
    if !(t0.is_finite() && t1.is_finite() && t0 < t1 && (t1 - t0 < turn || full)) {
        return bad(format!("angles [{t0}, {t1}] must be finite, increasing and at most a full turn apart"));
    }
    // Ring k: its intervals (about 6 k on a whole turn, at least one per 60°), its nodes' indices and angles;
    // about 6 k² (span / turn) triangles within ring k.
    let span = if full { turn } else { t1 - t0 };
    let triangles = 6.0 * (rings as f64).powi(2) * span / turn + 12.0 * rings as f64;
    if rings == 0 || triangles > MAX_CELLS as f64 {
        return bad(format!(
            "a disc needs at least 1 ring of nodes and at most about {MAX_CELLS} triangles, got {rings} rings (about \
             {triangles:.3e} triangles)"
        ));
    }
    let mut points: Vec<Point> = vec![c];
    let mut ring: Vec<(usize, f64)> = vec![(0, t0)];
    let mut triangles: Vec<[usize; 3]> = Vec::new();
    let mut sides: [Vec<usize>; 2] = [vec![0], vec![0]];
    for k in 1..=rings {
        let intervals = ((6 * k) as f64 * span / turn).round().max((span / (turn / 6.0)).ceil()) as usize;
        let radius = r * k as f64 / rings as f64;
        let count = if full { intervals } else { intervals + 1 };
        let next: Vec<(usize, f64)> = (0..count)
            .map(|i| {
                let theta = if i == intervals { t1 } else { t0 + span * i as f64 / intervals as f64 };
                points.push(on_circle(c, radius, theta));
                (points.len() - 1, theta)
            })
            .collect();
        merge(&ring, &next, full, span, &mut triangles);
        sides[0].push(next[0].0);
        sides[1].push(next[next.len() - 1].0);
        ring = next;
    }
    let mut sets = std::collections::BTreeMap::new();
    let mut rim: Vec<[usize; 2]> = ring.windows(2).map(|w| [w[0].0, w[1].0]).collect();
    if full {
        rim.push([ring[ring.len() - 1].0, ring[0].0]);
    } else {
        // (the sector's sides from its centre outward, and inward at its end: the boundary runs counterclockwise)
        sets.insert("start".to_string(), sides[0].windows(2).map(|w| [w[0], w[1]]).collect());
        sets.insert("end".to_string(), sides[1].windows(2).rev().map(|w| [w[1], w[0]]).collect());
    }
    sets.insert("rim".to_string(), rim);
    Mesh::new(points, triangles, sets)?.with_curve("rim", Curve::Arc { center: c, radius: r })
}

/// The triangles between two rings of nodes (index, angle), `inner` and `outer`, each increasing in angle from the
/// sector's first; on a whole turn (`full`) both close up, the first node following the last a turn later. Each
/// step takes the next node of the ring whose next angle comes first: the two rings merge by angle.
fn merge(inner: &[(usize, f64)], outer: &[(usize, f64)], full: bool, span: f64, triangles: &mut Vec<[usize; 3]>) {
    // (a whole turn goes round once more, back to its first nodes, a turn on)
    let around = |ring: &[(usize, f64)], i: usize| {
        if i < ring.len() {
            ring[i]
        } else {
            let (n, a) = ring[i - ring.len()];
            (n, a + span)
        }
    };
    let n = if full { outer.len() + 1 } else { outer.len() };
    // The centre (an inner ring of one node): a fan.
    let m = if inner.len() == 1 {
        1
    } else if full {
        inner.len() + 1
    } else {
        inner.len()
    };
    let (mut i, mut j) = (0, 0);
    while i + 1 < m || j + 1 < n {
        let (a, b) = (around(inner, i), around(outer, j));
        let take_outer = i + 1 >= m || (j + 1 < n && around(outer, j + 1).1 <= around(inner, i + 1).1);
        if take_outer {
            triangles.push([a.0, b.0, around(outer, j + 1).0]);
            j += 1;
        } else {
            triangles.push([a.0, b.0, around(inner, i + 1).0]);
            i += 1;
        }
    }
}

/// A rectangular plate with a circular hole, to mesh by [`plate_with_hole`]: the plate `[cx − a, cx + a] × [cy − b,
/// cy + b]` around the hole's centre c, of radius R < min(a, b).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateWithHole {
    /// The hole's centre c, the plate's too.
    pub center: Point,
    /// The hole's radius R.
    pub radius: f64,
    /// The plate's half-widths (a, b) along x and y.
    pub half_widths: [f64; 2],
}

/// A mesh of a plate with a hole (module documentation): `around` nodes round the hole (a multiple of 8, so that
/// the plate's corners are nodes), `across` cells from the hole to the plate's edge. Its edge sets are `"hole"` (a
/// closed loop on its circle, with its [`Curve`]) and the plate's sides `"right"`, `"top"`, `"left"`, `"bottom"`.
///
/// # Errors
/// [`Error::BadGenerator`] for values that are not finite, a radius not positive or not below both half-widths,
/// `around` not a positive multiple of 8, no cells across, or more triangles than
/// [`crate::mesh::generate::MAX_CELLS`] (checked before anything is allocated).
pub fn plate_with_hole(plate: &PlateWithHole, around: usize, across: usize) -> Result<Mesh> {
    let bad = |what: String| Err(Error::BadGenerator { what });
    let (c, r, [a, b]) = (plate.center, plate.radius, plate.half_widths);
    if !([c[0], c[1], r, a, b].iter().all(|v| v.is_finite()) && r > 0.0 && r < a.min(b)) {
        return bad(format!(
            "a plate with a hole needs finite values and 0 < R < min(a, b), got R = {r}, a = {a}, b = {b}"
        ));
    }
    if around == 0
        || !around.is_multiple_of(8)
        || across == 0
        || 2.0 * (around as f64) * (across as f64) > MAX_CELLS as f64
    {
        return bad(format!(
            "a plate with a hole needs a positive multiple of 8 nodes around and cells across, at most {MAX_CELLS} \
             triangles, got {around} around and {across} across"
        ));
    }
    let (n, m) = (around, across);
    let turn = 2.0 * std::f64::consts::PI;
    // The point of the plate's edge for node i: the loop from (a, 0) counterclockwise, each eighth of it a half-side.
    let edge = |i: usize| -> Point {
        let s = 8.0 * i as f64 / n as f64; // (0 to 8: the corners at 1, 3, 5, 7)
        let [x, y] = match s {
            s if s < 1.0 => [a, b * s],
            s if s < 3.0 => [a * (2.0 - s), b],
            s if s < 5.0 => [-a, b * (4.0 - s)],
            s if s < 7.0 => [a * (s - 6.0), -b],
            s => [a, b * (s - 8.0)],
        };
        [c[0] + x, c[1] + y]
    };
    // The cells across, geometric: the first as deep as the hole's nodes are apart (or uniform where that is finer).
    let (depth, first) = (a.min(b) - r, turn * r / n as f64);
    let fraction = |q: f64| if q == 1.0 { 1.0 / m as f64 } else { (q - 1.0) / (q.powi(m as i32) - 1.0) };
    let q = if fraction(1.0) * depth <= first {
        1.0
    } else {
        // (the fraction falls from 1/m at q = 1 as q grows: bisection on [1, 2^k])
        let (mut lo, mut hi) = (1.0_f64, 2.0_f64);
        while fraction(hi) * depth > first && hi < 1e6 {
            hi *= 2.0;
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if fraction(mid) * depth > first {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    };
    let t: Vec<f64> = (0..=m)
        .map(|j| if q == 1.0 { j as f64 / m as f64 } else { (q.powi(j as i32) - 1.0) / (q.powi(m as i32) - 1.0) })
        .collect();
    let mut points = Vec::with_capacity(n * (m + 1));
    for &tj in &t {
        for i in 0..n {
            let theta = turn * i as f64 / n as f64;
            let (h, e) = (on_circle(c, r, theta), edge(i));
            points.push(if tj == 1.0 { e } else { [h[0] + tj * (e[0] - h[0]), h[1] + tj * (e[1] - h[1])] });
        }
    }
    let node = |i: usize, j: usize| j * n + i % n;
    let mut triangles = Vec::with_capacity(2 * n * m);
    for j in 0..m {
        for i in 0..n {
            // (the quad's counterclockwise corners: (i + 1, j), (i, j), (i, j + 1), (i + 1, j + 1))
            triangles.push([node(i + 1, j), node(i, j), node(i, j + 1)]);
            triangles.push([node(i + 1, j), node(i, j + 1), node(i + 1, j + 1)]);
        }
    }
    let side = |from: usize, to: usize| (from..to).map(|i| [node(i, m), node(i + 1, m)]).collect::<Vec<_>>();
    let mut sets = std::collections::BTreeMap::new();
    sets.insert("hole".to_string(), (0..n).rev().map(|i| [node(i + 1, 0), node(i, 0)]).collect());
    sets.insert("right".to_string(), [side(7 * n / 8, n), side(0, n / 8)].concat());
    sets.insert("top".to_string(), side(n / 8, 3 * n / 8));
    sets.insert("left".to_string(), side(3 * n / 8, 5 * n / 8));
    sets.insert("bottom".to_string(), side(5 * n / 8, 7 * n / 8));
    Mesh::new(points, triangles, sets)?.with_curve("hole", Curve::Arc { center: c, radius: r })
}

#[cfg(test)]
mod tests {

    /// A plate with a hole: its area the plate's less the polygon of the hole's nodes, every triangle counterclockwise,
    /// the corners nodes, each side's edges on its line, the hole a loop on its circle; the first cells at the hole
    /// about as deep as its nodes are apart.
    #[test]
    fn a_plate_with_a_hole_tiles_the_plate_less_the_hole() {
        let plate = PlateWithHole { center: [1.0, 2.0], radius: 0.5, half_widths: [3.0, 2.0] };
        let (n, m) = (32, 12);
        let mesh = plate_with_hole(&plate, n, m).unwrap();
        let p = mesh.points();
        let area = |t: &[usize; 3]| {
            let (a, b, c) = (p[t[0]], p[t[1]], p[t[2]]);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        };
        assert!(mesh.triangles().iter().all(|t| area(t) > 0.0));
        let total: f64 = mesh.triangles().iter().map(area).sum();
        let hole = 0.5 * n as f64 * 0.25 * (2.0 * std::f64::consts::PI / n as f64).sin();
        assert!((total - (24.0 - hole)).abs() < 1e-12 * total, "{total}");
        for (name, axis, value) in [("right", 0, 4.0), ("top", 1, 4.0), ("left", 0, -2.0), ("bottom", 1, 0.0)] {
            let edges = mesh.edge_set(name).unwrap();
            assert_eq!(edges.len(), n / 4, "{name}");
            assert!(edges.iter().flatten().all(|&v| (p[v][axis] - value).abs() < 1e-12), "{name}");
        }
        let corners = [[4.0, 4.0], [-2.0, 4.0], [-2.0, 0.0], [4.0, 0.0]];
        assert!(corners.iter().all(|c| p.iter().any(|q| (q[0] - c[0]).abs() + (q[1] - c[1]).abs() < 1e-12)));
        let ring = mesh.edge_set("hole").unwrap();
        assert_eq!(ring.len(), n);
        assert!(ring.iter().flatten().all(|&v| ((p[v][0] - 1.0).hypot(p[v][1] - 2.0) - 0.5).abs() < 1e-14));
        // The first layer where the plate is narrowest (θ = 90°, toward its top): the node on the hole and the next
        // outward, against the hole's spacing 2π R / n.
        let depth = p[n + n / 4][1] - p[n / 4][1];
        assert!((depth / (2.0 * std::f64::consts::PI * 0.5 / n as f64) - 1.0).abs() < 1e-9, "{depth}");
        let ok = plate;
        for (plate, around, across) in [
            (PlateWithHole { radius: 2.0, ..ok }, 32, 4),
            (PlateWithHole { radius: 0.0, ..ok }, 32, 4),
            (PlateWithHole { half_widths: [f64::INFINITY, 2.0], ..ok }, 32, 4),
            (ok, 12, 4),
            (ok, 32, 0),
            (ok, 8_000_000, 8),
        ] {
            assert!(matches!(plate_with_hole(&plate, around, across), Err(Error::BadGenerator { .. })), "{plate:?}");
        }
    }

    /// The nodes at quarter turns lie on the axes through the centre exactly (`sin π` is 1.2e-16, not 0): a half
    /// model's symmetry line found by testing `y == c_y` holds the plate's whole cut and the half-disc's diameter.
    #[test]
    fn nodes_at_quarter_turns_lie_on_the_axes_exactly() {
        let plate = plate_with_hole(&PlateWithHole { center: [0.0, 0.0], radius: 1.0, half_widths: [5.0, 5.0] }, 64, 6)
            .unwrap();
        let on_axis = plate.points().iter().filter(|p| p[1] == 0.0).count();
        assert_eq!(on_axis, 2 * 7, "both rays of nodes from the hole at θ = 0 and π");
        let half =
            disc(&DiscSector { center: [0.0, 0.0], radius: 1.0, angles: [0.0, std::f64::consts::PI] }, 8).unwrap();
        let diameter = half.edge_sets()["start"].iter().chain(&half.edge_sets()["end"]).flatten().copied();
        assert!(diameter.map(|v| half.points()[v][1]).all(|y| y == 0.0));
        let pi = std::f64::consts::PI;
        assert_eq!(on_circle([1.0, 2.0], 3.0, 1.5 * pi), [1.0, -1.0]);
        assert_eq!(on_circle([1.0, 2.0], 3.0, -0.5 * pi), [1.0, -1.0]);
        assert_eq!(on_circle([1.0, 2.0], 3.0, 0.5 * pi), [1.0, 5.0]);
        assert_eq!(on_circle([1.0, 2.0], 3.0, 2.0 * pi + 2.0 * pi * 3.0 / 12.0 - 2.0 * pi / 4.0), [4.0, 2.0]);
        let near = on_circle([1.0, 2.0], 3.0, 0.5 * pi + 1e-9);
        assert!(near[0] != 1.0 && (near[0] - 1.0).abs() < 4e-9, "an angle off a quarter turn is kept: {near:?}");
    }

    /// A whole disc, a half-disc and a quarter: the triangles tile the polygon of the rim's nodes and the centre
    /// (their areas equal), every one counterclockwise and well shaped (no angle below 30° on the whole and the
    /// half disc, 28° on the quarter), the rim's nodes on the circle; a sector's `start` and `end` one edge per ring.
    #[test]
    fn a_disc_and_a_half_disc_are_tiled_by_well_shaped_triangles() {
        let pi = std::f64::consts::PI;
        let cases =
            [([0.0, 2.0 * pi], 12), ([-3.0, -3.0 + 2.0 * pi], 7), ([pi, 2.0 * pi], 9), ([0.3, 0.3 + pi / 2.0], 5)];
        for (angles, rings) in cases {
            let mesh = disc(&DiscSector { center: [1.0, -2.0], radius: 2.0, angles }, rings).unwrap();
            let p = mesh.points();
            let area = |t: &[usize; 3]| {
                let (a, b, c) = (p[t[0]], p[t[1]], p[t[2]]);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            };
            let total: f64 = mesh.triangles().iter().map(area).sum();
            let rim = mesh.edge_set("rim").unwrap();
            let mut smallest = 180.0_f64;
            // The polygon of the rim's nodes and the centre: the sector's area less the segments' sag.
            let polygon: f64 = rim
                .iter()
                .map(|e| {
                    let (a, b) = (p[e[0]], p[e[1]]);
                    0.5 * ((a[0] - 1.0) * (b[1] + 2.0) - (a[1] + 2.0) * (b[0] - 1.0))
                })
                .sum();
            assert!((total - polygon).abs() < 1e-12 * total, "{angles:?}: {total} against {polygon}");
            assert!(total < 2.0 * (angles[1] - angles[0]) && total > 0.98 * 2.0 * (angles[1] - angles[0]));
            for t in mesh.triangles() {
                assert!(area(t) > 0.0);
                for c in 0..3 {
                    let (a, b, o) = (p[t[c]], p[t[(c + 1) % 3]], p[t[(c + 2) % 3]]);
                    let (u, v) = ([a[0] - o[0], a[1] - o[1]], [b[0] - o[0], b[1] - o[1]]);
                    let cos = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
                    smallest = smallest.min(cos.acos().to_degrees());
                }
            }
            // The hexagonal packing's 30° on a whole disc and a half-disc (measured: 30.0°), less where the rounding
            // of a ring's intervals to the sector's span shears them (measured 28.7° on the quarter).
            let least = if angles[1] - angles[0] >= pi { 29.99 } else { 28.0 };
            assert!(smallest > least, "{angles:?}: an angle of {smallest}°");
            for e in rim {
                for &n in e {
                    assert!(((p[n][0] - 1.0).hypot(p[n][1] + 2.0) - 2.0).abs() < 1e-14);
                }
            }
            let full = (angles[1] - angles[0] - 2.0 * pi).abs() < 1e-12;
            assert_eq!(mesh.edge_set("start").is_ok(), !full);
            if !full {
                for side in ["start", "end"] {
                    assert_eq!(mesh.edge_set(side).unwrap().len(), rings, "{side}");
                }
            }
        }
        // Refused: a radius not positive, angles beyond a turn, no rings.
        let ok = DiscSector { center: [0.0, 0.0], radius: 1.0, angles: [0.0, pi] };
        for (sector, rings) in [
            (DiscSector { radius: 0.0, ..ok }, 4),
            (DiscSector { angles: [0.0, 7.0], ..ok }, 4),
            (DiscSector { angles: [1.0, 1.0], ..ok }, 4),
            (DiscSector { center: [f64::NAN, 0.0], ..ok }, 4),
            (ok, 0),
            (ok, 1_000_000),
        ] {
            assert!(matches!(disc(&sector, rings), Err(Error::BadGenerator { .. })), "{sector:?} {rings}");
        }
    }
    use super::*;
    use crate::contact::ContactBoundary;
    use std::f64::consts::FRAC_PI_2;

    fn roller() -> Mesh {
        let sector = RingSector { center: [0.0, 1.0], radii: [0.5, 1.0], angles: [-FRAC_PI_2 - 0.6, -FRAC_PI_2 + 0.6] };
        let grading = ArcGrading { angles: [-FRAC_PI_2 - 0.1, -FRAC_PI_2 + 0.1], h_min: 0.01, h_max: 0.1, growth: 0.3 };
        ring_sector(&sector, &grading).unwrap()
    }

    #[test]
    fn the_outer_arc_is_a_chain_on_the_circle_with_outward_normals() {
        let mesh = roller();
        let c = ContactBoundary::new(&mesh, "outer").unwrap();
        assert!(!c.is_straight());
        for p in &c.node_points {
            assert!(((p[0]).hypot(p[1] - 1.0) - 1.0).abs() < 1e-14, "{p:?}");
        }
        for (k, e) in c.edges.iter().enumerate() {
            // The outward normal of a chord points away from the centre, along its midpoint's radius.
            let (a, b) = (c.node_points[k], c.node_points[k + 1]);
            let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]) - 1.0];
            let r = m[0].hypot(m[1]);
            assert!((e.normal[0] - m[0] / r).abs() < 1e-12 && (e.normal[1] - m[1] / r).abs() < 1e-12);
        }
        // The arclength abscissae: the chain's length is that of its chords, just under the arc's 1.2 (a chord
        // under an arc s is 2R sin(s / 2R) > s (1 − s² / 24R²), s ≤ h_max = 0.1).
        assert!(c.length() < 1.2 && c.length() > 1.2 * (1.0 - 0.01 / 24.0), "{}", c.length());
        // The area is the ring sector's, less the segments the chords cut off.
        let area: f64 = (0..mesh.n_triangles()).map(|t| mesh.area(t)).sum();
        assert!((area - 0.5 * 1.2 * (1.0 - 0.25)).abs() < 1e-3, "{area}");
    }

    #[test]
    fn a_full_turn_is_a_full_ring_with_closed_arcs() {
        let turn = 2.0 * std::f64::consts::PI;
        let sector = RingSector { center: [1.0, 2.0], radii: [0.5, 1.0], angles: [0.3, 0.3 + turn] };
        let mesh = ring_sector(&sector, &ArcGrading { angles: [0.3, 0.3 + turn], h_min: 0.1, h_max: 0.1, growth: 0.3 })
            .unwrap();
        assert!(mesh.edge_set("start").is_err() && mesh.edge_set("end").is_err());
        for set in ["outer", "inner"] {
            let c = ContactBoundary::new(&mesh, set).unwrap();
            assert!(c.is_closed(), "{set}");
        }
        // The annulus's area, less the segments the chords cut off; no node twice.
        let area: f64 = (0..mesh.n_triangles()).map(|t| mesh.area(t)).sum();
        assert!((area - 0.5 * turn * (1.0 - 0.25)).abs() < 2e-2, "{area}");
        let mut pts: Vec<[i64; 2]> =
            mesh.points().iter().map(|p| [(p[0] * 1e9).round() as i64, (p[1] * 1e9).round() as i64]).collect();
        pts.sort_unstable();
        pts.dedup();
        assert_eq!(pts.len(), mesh.n_nodes());
        // Graded toward part of the arc, the two sides of the seam differ: refused.
        let graded = ArcGrading { angles: [0.3, 1.0], h_min: 0.01, h_max: 0.1, growth: 0.3 };
        let e = ring_sector(&sector, &graded).unwrap_err();
        assert!(matches!(&e, Error::BadGenerator { what } if what.contains("seam")), "{e}");
    }

    #[test]
    fn bad_sectors_are_refused_by_name() {
        let g = ArcGrading { angles: [0.1, 0.2], h_min: 0.05, h_max: 0.1, growth: 0.3 };
        for (radii, angles, what) in [
            ([0.1, 1.0], [0.0, 1.0], "radii"),
            ([0.5, 0.5], [0.0, 1.0], "radii"),
            ([0.5, 1.0], [1.0, 0.0], "angles"),
            ([0.5, 1.0], [0.0, 7.0], "angles"),
            ([0.5, 1.0], [0.15, 1.0], "refined arc"),
        ] {
            let e = ring_sector(&RingSector { center: [0.0, 0.0], radii, angles }, &g).unwrap_err();
            assert!(matches!(&e, Error::BadGenerator { .. }), "{e}");
            assert!(e.to_string().contains(what), "{e}");
        }
    }
}
