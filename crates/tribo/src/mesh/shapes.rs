//! Mesh generators for round shapes, whose contact sides are faceted arcs (a bent Γ_C,
//! [`crate::contact::ContactBoundary`]).
//!
//! [`ring_sector`] meshes the sector of a ring, fine along part of its outer arc: a roller's rim pressed on a
//! flat, clamped on its inner arc. It maps a [`graded_rectangle`] of the unrolled sector (arclength along the
//! outer arc by radius) onto the ring, so every node of the outer arc lies on the circle exactly, and the
//! faceted arc departs from the circle by at most `h² / (8 R)` between its nodes (h the edge length). The
//! triangles are shrunk along the arcs by `r / r_out`: the ratio of the radii bounds their distortion.

use crate::error::{Error, Result};
use crate::mesh::generate::{graded_rectangle, Grading, Side};
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
    let full = (t1 - t0 - turn).abs() <= 1e-12 * turn;
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
            [sector.center[0] + r * theta.cos(), sector.center[1] + r * theta.sin()]
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

#[cfg(test)]
mod tests {
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
