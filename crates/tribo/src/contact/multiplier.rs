//! The multiplier mesh T_H on Γ_C and the spaces W_0H (P0) and W_1H (continuous P1).
//!
//! T_H is a strictly increasing list of abscissae `x_0 < … < x_N` covering Γ_C exactly; its points need
//! not be FE nodes. Both spaces have box-shaped cones: a P0 or continuous-P1 function is ≥ 0 (or
//! bounded by a P0/P1 threshold) on Γ_C exactly when its dof values are, so `M_Hn` and `M_Ht(g)` are
//! bounds on dof values.

use crate::choice::named_choice;
use crate::contact::ContactBoundary;
use crate::error::{Error, Result};
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::Point;

/// Which multiplier space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MultiplierSpace {
    /// Piecewise constant on T_H (one dof per segment).
    P0,
    /// Continuous piecewise linear on T_H (one dof per point).
    #[default]
    P1,
}

named_choice!(MultiplierSpace, "multiplier space", { MultiplierSpace::P0 => "P0", MultiplierSpace::P1 => "P1" });

/// Largest number of points of T_H: far more than any contact boundary needs, small enough that the
/// vectors of T_H cost at most a few hundred MB (the dense parts of the solve have their own budget,
/// [`crate::SolverSettings::memory_budget`]).
pub const MAX_MULTIPLIER_POINTS: usize = 1_000_000;

fn too_many(count: f64) -> Error {
    Error::BadMultiplierMesh {
        what: format!("{} points asked for, more than the limit of {MAX_MULTIPLIER_POINTS}", crate::error::Num(count)),
    }
}

/// How the points of T_H are given.
#[derive(Debug, Clone, PartialEq)]
pub enum MultiplierPoints {
    /// Strictly increasing abscissae on Γ_C; the first and last must be the ends of Γ_C (up to a
    /// tolerance of `√ε` times the neighbouring segment, within which they are snapped onto the ends).
    Abscissae(Vec<f64>),
    /// Points in the plane, on Γ_C, in order of increasing abscissa.
    Points(Vec<Point>),
    /// Uniform segments of length at most H.
    Size(f64),
    /// Segments of about `ratio` times the local FE edge length: `ratio = k ≥ 1` an integer takes every
    /// k-th FE node of Γ_C, `ratio = 1/k` splits every FE edge into k equal parts, any other ratio walks
    /// along Γ_C with steps of `ratio × h_E`.
    RatioToFe(f64),
}

impl Default for MultiplierPoints {
    fn default() -> Self {
        Self::RatioToFe(1.0)
    }
}

impl MultiplierPoints {
    /// The points another contact side takes when its own are not given: these where they are a size or a ratio
    /// to the FE edges; the default where they are abscissae or points, which lie on one side.
    pub fn for_another_side(&self) -> Self {
        match self {
            Self::Size(_) | Self::RatioToFe(_) => self.clone(),
            Self::Abscissae(_) | Self::Points(_) => Self::default(),
        }
    }
}

/// The multiplier mesh T_H with its space.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiplierMesh {
    /// Abscissae `x_0 < … < x_N`, `x_0` and `x_N` the ends of Γ_C.
    pub xi: Vec<f64>,
    /// The space W_0H or W_1H.
    pub space: MultiplierSpace,
    /// A P1 multiplier on a closed Γ_C ([`ContactBoundary::is_closed`]): its two end points are one point of the
    /// loop and carry one dof, the first (continuous all round; two dofs there would leave the multiplier one
    /// more dof than the FE trace has nodes on the loop, a mode that B does not see).
    pub periodic: bool,
}

impl MultiplierMesh {
    /// The points of T_H on either side of the span `(lo, hi)` (the span's ends at T_H's ends; on a `closed` Γ_C,
    /// the points across the cut, a period before or after, where the span reaches it or crosses it).
    pub fn points_around(&self, (lo, hi): (f64, f64), closed: bool) -> (f64, f64) {
        let xi = &self.xi;
        let last = xi.len() - 1;
        if !closed || last < 2 {
            return (
                xi[xi.partition_point(|&x| x < lo).saturating_sub(1)],
                xi[xi.partition_point(|&x| x <= hi).min(last)],
            );
        }
        // Each end wrapped onto [start, end), its neighbour found there, and moved back by the same periods; a
        // dof a period away comes back up to rounding, so the points are compared within a few ε of the period.
        let (start, period) = (xi[0], xi[last] - xi[0]);
        let tol = 8.0 * f64::EPSILON * (period + start.abs());
        let turns = |x: f64| ((x - start + tol) / period).floor() * period;
        let (lo_turns, hi_turns) = (turns(lo), turns(hi));
        let below = match xi.partition_point(|&x| x < lo - lo_turns - tol) {
            0 => xi[last - 1] - period,
            k => xi[k - 1],
        };
        let above = xi[xi.partition_point(|&x| x <= hi - hi_turns + tol).min(last)];
        (below + lo_turns, above + hi_turns)
    }

    /// Builds T_H on Γ_C.
    ///
    /// # Errors
    /// [`Error::BadMultiplierMesh`], [`Error::MultiplierPointsNotIncreasing`],
    /// [`Error::MultiplierPointOffContact`], [`Error::MultiplierMeshDoesNotCover`].
    pub fn new(contact: &ContactBoundary, points: &MultiplierPoints, space: MultiplierSpace) -> Result<Self> {
        let (start, end) = (contact.start(), contact.end());
        let tol = geometric_tol_rel();
        let xi = match points {
            MultiplierPoints::Abscissae(x) => snap_to_ends(x.clone(), start, end)?,
            MultiplierPoints::Points(p) => {
                let mut x = Vec::with_capacity(p.len());
                for (index, &q) in p.iter().enumerate() {
                    if !(q[0].is_finite() && q[1].is_finite()) {
                        return Err(Error::BadMultiplierMesh { what: format!("point {index} is not finite") });
                    }
                    let distance = contact.distance_to_line(q).abs();
                    if distance > tol * contact.length() {
                        return Err(Error::MultiplierPointOffContact { index, distance, start, end });
                    }
                    x.push(contact.abscissa(q));
                }
                snap_to_ends(x, start, end)?
            }
            MultiplierPoints::Size(h) => {
                if !(h.is_finite() && *h > 0.0) {
                    return Err(Error::BadMultiplierMesh { what: format!("size H must be positive, got {h}") });
                }
                let count = ((end - start) / h * (1.0 - tol)).ceil().max(1.0);
                if count.is_nan() || count >= MAX_MULTIPLIER_POINTS as f64 {
                    return Err(too_many(count + 1.0));
                }
                let n = count as usize;
                (0..=n).map(|k| if k == n { end } else { start + (end - start) * k as f64 / n as f64 }).collect()
            }
            MultiplierPoints::RatioToFe(r) => from_ratio(&contact.node_xi, *r)?,
        };
        // A spacing below the resolution of the abscissae (H of 1e-6 on a Γ_C at ξ ≈ 1e12) repeats points.
        if let Some(index) = (1..xi.len()).find(|&i| xi[i] <= xi[i - 1]) {
            return Err(Error::BadMultiplierMesh {
                what: format!(
                    "points {} and {index} coincide at ξ = {}: the spacing asked for is below the resolution of the abscissae",
                    index - 1,
                    xi[index]
                ),
            });
        }
        Ok(Self { xi, space, periodic: space == MultiplierSpace::P1 && contact.is_closed() })
    }

    /// Number of segments N.
    pub fn n_segments(&self) -> usize {
        self.xi.len() - 1
    }

    /// Number of dofs (N for P0, N + 1 for P1, N for a periodic P1).
    pub fn n_dofs(&self) -> usize {
        match self.space {
            MultiplierSpace::P0 => self.n_segments(),
            MultiplierSpace::P1 => self.xi.len() - usize::from(self.periodic),
        }
    }

    /// Abscissae where the dofs live: segment midpoints (P0) or points (P1; but the last of a periodic one).
    pub fn dof_abscissae(&self) -> Vec<f64> {
        match self.space {
            MultiplierSpace::P0 => self.xi.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect(),
            MultiplierSpace::P1 => self.xi[..self.n_dofs()].to_vec(),
        }
    }

    /// Basis functions of segment `k` that do not vanish there, evaluated at `xi`: up to two
    /// `(dof, value)` pairs.
    pub fn basis(&self, k: usize, xi: f64) -> ([(usize, f64); 2], usize) {
        match self.space {
            MultiplierSpace::P0 => ([(k, 1.0), (k, 0.0)], 1),
            MultiplierSpace::P1 => {
                let s = (xi - self.xi[k]) / (self.xi[k + 1] - self.xi[k]);
                let right = if self.periodic && k + 2 == self.xi.len() { 0 } else { k + 1 };
                ([(k, 1.0 - s), (right, s)], 2)
            }
        }
    }

    /// Value at `xi` of the multiplier with dof values `values` (NaN where `values` lacks a dof it needs: a
    /// vector of another multiplier mesh).
    pub fn evaluate(&self, values: &[f64], xi: f64) -> f64 {
        let k = self.xi.partition_point(|&x| x <= xi).clamp(1, self.n_segments()) - 1;
        let (b, nb) = self.basis(k, xi);
        b[..nb].iter().map(|&(j, v)| v * values.get(j).copied().unwrap_or(f64::NAN)).sum()
    }
}

fn snap_to_ends(mut x: Vec<f64>, start: f64, end: f64) -> Result<Vec<f64>> {
    if x.len() < 2 {
        return Err(Error::BadMultiplierMesh { what: format!("at least two points are needed, got {}", x.len()) });
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(Error::BadMultiplierMesh { what: format!("point {index} is not finite") });
    }
    for index in 1..x.len() {
        if x[index] <= x[index - 1] {
            return Err(Error::MultiplierPointsNotIncreasing { index, value: x[index], previous: x[index - 1] });
        }
    }
    let tol = geometric_tol_rel();
    let n = x.len();
    let (first_seg, last_seg) = (x[1] - x[0], x[n - 1] - x[n - 2]);
    if (x[0] - start).abs() <= tol * first_seg {
        x[0] = start;
    }
    if (x[n - 1] - end).abs() <= tol * last_seg {
        x[n - 1] = end;
    }
    for (index, &v) in x.iter().enumerate() {
        if v < start || v > end {
            let distance = if v < start { start - v } else { v - end };
            return Err(Error::MultiplierPointOffContact { index, distance, start, end });
        }
    }
    if x[0] != start {
        return Err(Error::MultiplierMeshDoesNotCover { which: "first", value: x[0], expected: start });
    }
    if x[n - 1] != end {
        return Err(Error::MultiplierMeshDoesNotCover { which: "last", value: x[n - 1], expected: end });
    }
    Ok(x)
}

fn from_ratio(fe: &[f64], r: f64) -> Result<Vec<f64>> {
    if !(r.is_finite() && r > 0.0) {
        return Err(Error::BadMultiplierMesh { what: format!("ratio H/h must be positive, got {r}") });
    }
    let tol = geometric_tol_rel();
    let n = fe.len() - 1;
    // Points of T_H: about n / r.
    let count = n as f64 / r + 1.0;
    if count.is_nan() || count >= MAX_MULTIPLIER_POINTS as f64 {
        return Err(too_many(count));
    }
    let k = r.round();
    let inv = (1.0 / r).round();
    if (r - k).abs() <= tol * r && k >= 1.0 {
        let k = k as usize;
        let mut x: Vec<f64> = fe.iter().step_by(k).copied().collect();
        if !n.is_multiple_of(k) {
            // The last segment would be shorter than k FE edges: end there, merging a stub of less than
            // half a segment into the previous one.
            if n % k < k.div_ceil(2) && x.len() > 1 {
                x.pop();
            }
            x.push(fe[n]);
        }
        Ok(x)
    } else if (1.0 / r - inv).abs() <= tol / r && inv >= 1.0 {
        let k = inv as usize;
        let mut x = Vec::with_capacity(n * k + 1);
        for w in fe.windows(2) {
            for j in 0..k {
                x.push(w[0] + (w[1] - w[0]) * j as f64 / k as f64);
            }
        }
        x.push(fe[n]);
        Ok(x)
    } else {
        let mut x = vec![fe[0]];
        let mut e = 0;
        loop {
            let cur = *x.last().expect("non-empty");
            while e < n - 1 && fe[e + 1] <= cur {
                e += 1;
            }
            let next = cur + r * (fe[e + 1] - fe[e]);
            if next >= fe[n] - 0.5 * r * (fe[e + 1] - fe[e]) {
                x.push(fe[n]);
                break;
            }
            if next <= cur || x.len() as f64 > 2.0 * count {
                // The step is below the resolution of the abscissae: the points would repeat forever.
                return Err(Error::BadMultiplierMesh {
                    what: format!("ratio H/h = {r} gives steps below the resolution of the abscissae near ξ = {cur}"),
                });
            }
            x.push(next);
        }
        Ok(x)
    }
}

impl MultiplierPoints {
    /// The points from keywords, as the Python binding and the scene files give them: `ratio` (H/h,
    /// [`MultiplierPoints::RatioToFe`]), `size` (H, [`MultiplierPoints::Size`]) or explicit `points`
    /// ([`MultiplierPoints::Abscissae`] or [`MultiplierPoints::Points`]); they exclude each other, and
    /// none gives the default. The values themselves are checked by [`MultiplierMesh::new`].
    ///
    /// # Errors
    /// [`Error::BadMultiplierMesh`] when more than one is given.
    pub fn from_keywords(ratio: Option<f64>, size: Option<f64>, points: Option<Self>) -> Result<Self> {
        match (ratio, size, points) {
            (None, None, None) => Ok(Self::default()),
            (Some(r), None, None) => Ok(Self::RatioToFe(r)),
            (None, Some(h), None) => Ok(Self::Size(h)),
            (None, None, Some(p)) => Ok(p),
            _ => Err(Error::BadMultiplierMesh {
                what: "give at most one of multiplier_ratio (H/h), multiplier_size (H) and multiplier_points".into(),
            }),
        }
    }
}
