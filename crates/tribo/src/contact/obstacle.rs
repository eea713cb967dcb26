//! The rigid obstacle: its shape (initial gap as a function of the abscissa on Γ_C) and its motion.
//!
//! # How the obstacle enters (3.1)
//! The obstacle surface lies at distance `g₀(ξ)` from Γ_C along n. A normal approach δ moves it toward the
//! body and a tangential shift s moves it along t, so non-penetration reads `u_n ≤ g(ξ) := g₀(ξ) − δ` and
//! the slip that friction opposes is the relative one, `u_t − s`. The contact law therefore applies to
//! the shifted pair `w = (u_n − g, u_t − s)`, and only the *inequality* of (3.1) changes:
//!
//! `b(ν_H − λ_H, u_h) − ∫ (ν_Hn − λ_Hn) g − ∫ (ν_Ht − λ_Ht) s + (γ terms) ≤ 0`.
//!
//! The equilibrium equation (first line of (3.1)) and the stabilization terms are unchanged: σ(u_h) does not
//! see a rigid shift. In matrix form the obstacle adds the vector `d = (∫ψ_j g, ∫ψ_j s)` to the
//! QP's linear term (see [`crate::qp`]).
//!
//! # Shapes given by their geometry
//! A gap function of the abscissa suits a straight Γ_C (Hertz's half-space idealization: the gap is measured
//! along Γ_C's normal). A bent Γ_C (a chain of edges, [`crate::contact::ContactBoundary`]) meets an obstacle
//! given by its geometry: a line, a disc, a hole around the body, or any signed distance `d(x)` (positive
//! outside the obstacle). The initial gap at a point x of Γ_C is then `g₀ = d(x)`, the distance to the
//! obstacle's nearest point, and non-penetration is `u · ν ≤ g₀ − δ` with `ν = −∇d`, the obstacle's normal
//! ([`crate::contact::ContactBoundary::orient_to`], taken at each edge's midpoint): the small-sliding
//! linearization of `d(x + u) ≥ 0`. λ_n and λ_t are the components of the traction along ν and its tangent.
//!
//! *Why the obstacle's normal and not the body's.* A frictionless rigid surface can push only along its own
//! normal. The body's normal n_e differs from ν by the angle its surface turns through where it is pressed
//! flat (up to a/R on a roller of contact half-width a): taking λ along n_e would give a frictionless flat a
//! tangential push of that order. On a roller pressed on a flat (tests `curved.rs`, a/R ≈ 0.04) λ_n meets
//! plane-strain Hertz within 0.83 % in L2 along ν, and stalls at 1.4 % along n_e. On a straight Γ_C against a
//! gap function the two are one: ν = n.
//!
//! The approach δ lowers the gap by δ everywhere (a line moves by δ toward the body; a hole shrinks by δ, the
//! interference of a shrink fit) and the shift s moves the obstacle's surface by s along each edge's tangent
//! (a rotation by s/R of a hole around a disc).
//!
//! # A turned obstacle
//! A shape given by its geometry may also be turned by an angle θ about a point c ([`ObstacleRotation`]). Its
//! geometry is turned exactly ([`ObstacleShape::turned`]): the gap and the contact normals are those of the
//! turned shape. Its surface moves by `w(y) = θ ẑ × (y − c)` (the small rotation's displacement) at its point y
//! nearest the body's point x, `y = x − d(x) ∇d(x)`, and that motion along each edge's tangent adds to the shift:
//! `s(x) = s + w(y) · t`. Read at y and not at x, a disc turned about its own centre slides its surface by θR and
//! does not move it toward the body. A gap function of the abscissa has no place in the plane to turn about,
//! and is refused; so are two bodies (no rigid obstacle) and axisymmetry (no rigid rotation of a body of
//! revolution in its meridian plane). A history may turn it step by step ([`crate::LoadStep::rotation`]).

use std::fmt;
use std::sync::Arc;

use crate::contact::ContactBoundary;
use crate::error::{Error, Result};

/// A user gap function `ξ ↦ g₀(ξ)`.
#[derive(Clone)]
pub struct GapFunction(pub Arc<dyn Fn(f64) -> f64 + Send + Sync>);

impl fmt::Debug for GapFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("GapFunction(<closure>)")
    }
}

/// A user signed distance `x ↦ d(x)` from the obstacle, positive outside it.
#[derive(Clone)]
pub struct DistanceFunction(pub Arc<dyn Fn([f64; 2]) -> f64 + Send + Sync>);

impl fmt::Debug for DistanceFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("DistanceFunction(<closure>)")
    }
}

/// Shape of the obstacle: the initial gap `g₀(ξ) ≥ 0` between Γ_C and the obstacle, along n, as a function of
/// the abscissa (`Flat` to `Function`), or the obstacle's geometry (`Line` to `Distance`: the module
/// documentation).
#[derive(Debug, Clone, Default)]
pub enum ObstacleShape {
    /// A flat obstacle touching Γ_C: `g₀ = 0`.
    #[default]
    Flat,
    /// A rigid cylinder of radius R whose lowest point touches Γ_C at abscissa `center`:
    /// `g₀ = R − √(R² − (ξ − c)²)` for `|ξ − c| < R`, and `R` beyond (the cylinder never reaches there).
    Circle {
        /// Abscissa of the contact point.
        center: f64,
        /// Radius R > 0.
        radius: f64,
    },
    /// The parabolic (Hertz) approximation of a cylinder: `g₀ = (ξ − c)² / (2R)`.
    Parabola {
        /// Abscissa of the vertex.
        center: f64,
        /// Radius of curvature R > 0.
        radius: f64,
    },
    /// A polyline through `(xi[k], gap[k])`, extended by constants beyond its ends.
    Polyline {
        /// Strictly increasing abscissae (at least one).
        xi: Vec<f64>,
        /// Gap values.
        gap: Vec<f64>,
    },
    /// Any function of the abscissa.
    Function(GapFunction),
    /// A rigid half-plane whose surface is the line through `point` with normal `normal` (pointing out of the
    /// obstacle, toward the body; any length): `g₀(x) = (x − p) · m / |m|`.
    Line {
        /// A point of the line.
        point: [f64; 2],
        /// The normal out of the obstacle.
        normal: [f64; 2],
    },
    /// A rigid disc outside the body: `g₀(x) = |x − c| − R`.
    Disc {
        /// Centre c.
        center: [f64; 2],
        /// Radius R > 0.
        radius: f64,
    },
    /// A rigid hole around the body (the body inside a circle): `g₀(x) = R − |x − c|`.
    Hole {
        /// Centre c.
        center: [f64; 2],
        /// Radius R > 0.
        radius: f64,
    },
    /// A rigid body bounded by the polyline through `points`, lying on its right as one walks from the first
    /// point to the last (the body on its left), its end segments extended to rays: a V-groove, a step, a
    /// profile. `g₀(x)` is the distance to the polyline, signed by the side (at a vertex, by the sum of its two
    /// segments' normals).
    Profile {
        /// The vertices, at least two, consecutive ones distinct.
        points: Vec<[f64; 2]>,
    },
    /// Any signed distance from the obstacle, positive outside it.
    Distance(DistanceFunction),
}

/// A small rigid rotation of an obstacle given by its geometry: by `angle` (radians, counterclockwise) about
/// `center` (the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleRotation {
    /// The point it turns about.
    pub center: [f64; 2],
    /// The angle, radians, counterclockwise.
    pub angle: f64,
}

impl From<([f64; 2], f64)> for ObstacleRotation {
    /// `(center, angle)`.
    fn from((center, angle): ([f64; 2], f64)) -> Self {
        Self { center, angle }
    }
}

impl ObstacleRotation {
    /// The point `p` turned by `sign × angle` about the centre.
    pub fn turn(&self, p: [f64; 2], sign: f64) -> [f64; 2] {
        let (s, c) = (sign * self.angle).sin_cos();
        let d = [p[0] - self.center[0], p[1] - self.center[1]];
        [self.center[0] + c * d[0] - s * d[1], self.center[1] + s * d[0] + c * d[1]]
    }

    /// The vector `v` turned by `sign × angle`.
    pub fn turn_vector(&self, v: [f64; 2], sign: f64) -> [f64; 2] {
        let (s, c) = (sign * self.angle).sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }
}

/// The rigid obstacle: shape and prescribed motion.
#[derive(Debug, Clone, Default)]
pub struct Obstacle {
    /// Initial gap.
    pub shape: ObstacleShape,
    /// Normal approach δ of the obstacle toward the body.
    pub approach: f64,
    /// Tangential shift s of the obstacle along t.
    pub shift: f64,
    /// A small rotation of a shape given by its geometry (none by default).
    pub rotation: Option<ObstacleRotation>,
}

impl Obstacle {
    /// The obstacle of `shape` moved by the keywords given (approach δ, shift s, a rotation), the others at
    /// their defaults (0: touching, not shifted, not turned).
    pub fn from_keywords(
        shape: ObstacleShape,
        approach: Option<f64>,
        shift: Option<f64>,
        rotation: Option<ObstacleRotation>,
    ) -> Self {
        let d = Self::default();
        Self { shape, approach: approach.unwrap_or(d.approach), shift: shift.unwrap_or(d.shift), rotation }
    }

    /// The obstacle as the contact meets it: its shape turned by its rotation, if any
    /// ([`ObstacleShape::turned`]), the rotation kept for the motion of its surface (so it is placed once: placed
    /// again, it would turn again).
    pub fn placed(&self) -> Self {
        match &self.rotation {
            Some(r) => Self { shape: self.shape.turned(r), ..self.clone() },
            None => self.clone(),
        }
    }

    /// How far the surface of the placed obstacle ([`Obstacle::placed`]) moves along `t` facing the body's point
    /// `x`: the shift s, plus where it is turned, `w(y) · t` at its point y nearest x (the module documentation).
    pub fn tangential_motion(&self, x: [f64; 2], t: [f64; 2], length: f64) -> f64 {
        let Some(r) = &self.rotation else {
            return self.shift;
        };
        let (d, g) = (self.shape.distance(x), self.shape.distance_gradient(x, length));
        let norm = g[0].hypot(g[1]);
        let y = if norm > 0.0 { [x[0] - d * g[0] / norm, x[1] - d * g[1] / norm] } else { x };
        let w = [-r.angle * (y[1] - r.center[1]), r.angle * (y[0] - r.center[0])];
        self.shift + w[0] * t[0] + w[1] * t[1]
    }

    /// Checks the shape's parameters and the motion.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] saying which parameter is wrong.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: String| Err(Error::BadObstacle { what });
        if !self.approach.is_finite() {
            return bad(format!("approach δ must be finite, got {}", self.approach));
        }
        if !self.shift.is_finite() {
            return bad(format!("tangential shift s must be finite, got {}", self.shift));
        }
        for (name, v) in [("approach δ", self.approach), ("tangential shift s", self.shift)] {
            if v.is_subnormal() {
                return bad(crate::error::subnormal(name, v));
            }
        }
        if let Some(r) = &self.rotation {
            if !(r.angle.is_finite() && !r.angle.is_subnormal() && r.center.iter().all(|v| v.is_finite())) {
                return bad(format!(
                    "the rotation's angle and centre must be finite (the angle not subnormal), got {} about ({}, {})",
                    r.angle, r.center[0], r.center[1]
                ));
            }
            if !self.shape.is_geometry() {
                return bad(format!(
                    "a rotation turns an obstacle given by its geometry (line, disc, hole, profile, signed distance); \
                     a {} is a gap function of the abscissa, with no place in the plane to turn about",
                    self.shape.kind()
                ));
            }
        }
        match &self.shape {
            ObstacleShape::Flat | ObstacleShape::Function(_) | ObstacleShape::Distance(_) => Ok(()),
            ObstacleShape::Profile { points } => {
                if points.len() < 2 {
                    return bad(format!("a profile needs at least two points, got {}", points.len()));
                }
                if let Some(k) = points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
                    return bad(format!("profile point {k} is not finite: ({}, {})", points[k][0], points[k][1]));
                }
                if let Some(k) = (1..points.len()).find(|&k| points[k] == points[k - 1]) {
                    return bad(format!("profile points {} and {k} coincide: a segment needs two points", k - 1));
                }
                match profile_crossing(points) {
                    Some((a, b)) => bad(format!(
                        "the profile's segments {a} and {b} cross or fold back onto each other (its end segments \
                         extended): the obstacle would not have one side"
                    )),
                    None => Ok(()),
                }
            }
            ObstacleShape::Line { point, normal } => {
                if !point.iter().all(|v| v.is_finite()) {
                    bad(format!("the line's point must be finite, got ({}, {})", point[0], point[1]))
                } else if !(normal.iter().all(|v| v.is_finite()) && normal[0].hypot(normal[1]) > 0.0) {
                    bad(format!("the line's normal must be finite and not zero, got ({}, {})", normal[0], normal[1]))
                } else {
                    Ok(())
                }
            }
            ObstacleShape::Disc { center, radius } | ObstacleShape::Hole { center, radius } => {
                if !center.iter().all(|v| v.is_finite()) {
                    bad(format!("the centre must be finite, got ({}, {})", center[0], center[1]))
                } else if !(radius.is_finite() && *radius > 0.0) {
                    bad(format!("radius must be positive and finite, got {radius}"))
                } else {
                    Ok(())
                }
            }
            ObstacleShape::Circle { center, radius } | ObstacleShape::Parabola { center, radius } => {
                if !center.is_finite() {
                    bad(format!("center must be finite, got {center}"))
                } else if !(radius.is_finite() && *radius > 0.0) {
                    bad(format!("radius must be positive and finite, got {radius}"))
                } else {
                    Ok(())
                }
            }
            ObstacleShape::Polyline { xi, gap } => {
                if xi.is_empty() || xi.len() != gap.len() {
                    return bad(format!(
                        "polyline needs as many gaps as abscissae (at least one): {} abscissae, {} gaps",
                        xi.len(),
                        gap.len()
                    ));
                }
                if let Some(k) = xi.iter().chain(gap).position(|v| !v.is_finite()) {
                    return bad(format!("polyline value {k} is not finite"));
                }
                if let Some(k) = (1..xi.len()).find(|&k| xi[k] <= xi[k - 1]) {
                    return bad(format!(
                        "polyline abscissae must increase strictly: point {k} ({}) <= {}",
                        xi[k],
                        xi[k - 1]
                    ));
                }
                Ok(())
            }
        }
    }

    /// Initial gap `g₀` at abscissa `xi` of `contact`: the gap function's value, or the signed distance of
    /// the point of Γ_C there (on its curve, where its edge set carries one: [`ContactBoundary::surface_point`])
    /// from a shape given by its geometry.
    pub fn initial_gap_on(&self, contact: &ContactBoundary, xi: f64) -> f64 {
        if self.shape.is_geometry() {
            self.shape.distance(contact.surface_point(xi))
        } else {
            self.initial_gap(xi)
        }
    }

    /// Initial gap `g₀(ξ)` of a gap function of the abscissa (NaN at a non-finite abscissa, and for a shape
    /// given by its geometry: [`Obstacle::initial_gap_on`] places it).
    pub fn initial_gap(&self, xi: f64) -> f64 {
        if !xi.is_finite() {
            return f64::NAN;
        }
        match &self.shape {
            ObstacleShape::Flat => 0.0,
            ObstacleShape::Circle { center, radius } => {
                let d = xi - center;
                if d.abs() < *radius {
                    // R − √(R² − d²) written without cancellation.
                    d * d / (radius + (radius * radius - d * d).sqrt())
                } else {
                    *radius
                }
            }
            ObstacleShape::Parabola { center, radius } => (xi - center).powi(2) / (2.0 * radius),
            ObstacleShape::Polyline { xi: xs, gap } => {
                let k = xs.partition_point(|&x| x <= xi);
                if k == 0 {
                    gap[0]
                } else if k == xs.len() {
                    gap[k - 1]
                } else {
                    let s = (xi - xs[k - 1]) / (xs[k] - xs[k - 1]);
                    gap[k - 1] + s * (gap[k] - gap[k - 1])
                }
            }
            ObstacleShape::Function(f) => (f.0)(xi),
            ObstacleShape::Line { .. }
            | ObstacleShape::Disc { .. }
            | ObstacleShape::Hole { .. }
            | ObstacleShape::Profile { .. }
            | ObstacleShape::Distance(_) => f64::NAN,
        }
    }

    /// Gap after the approach at abscissa `xi` of `contact`: `g(ξ) = g₀(ξ) − δ`; non-penetration is `u_n ≤ g`.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] if a user function returns a non-finite value.
    pub fn gap(&self, contact: &ContactBoundary, xi: f64) -> Result<f64> {
        let g = self.initial_gap_on(contact, xi) - self.approach;
        if g.is_finite() {
            Ok(g)
        } else {
            Err(Error::BadObstacle { what: format!("the gap function returned {g} at abscissa {xi}") })
        }
    }
}

/// The first two segments of a profile (the first and the last extended to rays) that cross, or two consecutive
/// ones that fold back onto each other (antiparallel), as their indices; None for a simple profile.
fn profile_crossing(points: &[[f64; 2]]) -> Option<(usize, usize)> {
    let m = points.len() - 1;
    let cross = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
    let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
    // Parameter ranges of each segment: the first reaches back to −∞, the last forward to +∞.
    let range = |k: usize| (if k == 0 { f64::NEG_INFINITY } else { 0.0 }, if k == m - 1 { f64::INFINITY } else { 1.0 });
    for k in 1..m {
        let (u, v) = (sub(points[k], points[k - 1]), sub(points[k + 1], points[k]));
        if cross(u, v) == 0.0 && u[0] * v[0] + u[1] * v[1] < 0.0 {
            return Some((k - 1, k));
        }
    }
    for a in 0..m {
        for b in a + 2..m {
            let (p, r) = (points[a], sub(points[a + 1], points[a]));
            let (q, s) = (points[b], sub(points[b + 1], points[b]));
            let denom = cross(r, s);
            if denom == 0.0 {
                continue; // parallel: they meet only if collinear, which the fold check and the others catch
            }
            let (t, w) = (cross(sub(q, p), s) / denom, cross(sub(q, p), r) / denom);
            let ((ta, tb), (wa, wb)) = (range(a), range(b));
            if t >= ta && t <= tb && w >= wa && w <= wb {
                return Some((a, b));
            }
        }
    }
    None
}

impl ObstacleShape {
    /// The shape turned by `rotation` (exactly): a line's point and normal, a disc's or a hole's centre, a
    /// profile's points; a signed distance read at the point turned back. A gap function of the abscissa is
    /// returned as it is (it cannot be turned: [`Obstacle::validate`] refuses a rotation of it).
    pub fn turned(&self, rotation: &ObstacleRotation) -> Self {
        let r = *rotation;
        match self {
            Self::Line { point, normal } => {
                Self::Line { point: r.turn(*point, 1.0), normal: r.turn_vector(*normal, 1.0) }
            }
            Self::Disc { center, radius } => Self::Disc { center: r.turn(*center, 1.0), radius: *radius },
            Self::Hole { center, radius } => Self::Hole { center: r.turn(*center, 1.0), radius: *radius },
            Self::Profile { points } => Self::Profile { points: points.iter().map(|&p| r.turn(p, 1.0)).collect() },
            Self::Distance(f) => {
                let f = f.0.clone();
                Self::Distance(DistanceFunction(Arc::new(move |x| f(r.turn(x, -1.0)))))
            }
            other => other.clone(),
        }
    }

    /// Whether the shape is given by its geometry (a line, a disc, a hole, a signed distance) rather than as a
    /// gap function of the abscissa.
    pub fn is_geometry(&self) -> bool {
        matches!(
            self,
            Self::Line { .. } | Self::Disc { .. } | Self::Hole { .. } | Self::Profile { .. } | Self::Distance(_)
        )
    }

    /// The signed distance of `x` from a profile's polyline and its gradient (see [`ObstacleShape::Profile`]):
    /// the nearest point over the segments (the first and the last extended to rays); on a segment the distance
    /// along its left normal, at a vertex `±|x − v|` signed by the sum of its two segments' left normals.
    fn profile_distance(points: &[[f64; 2]], x: [f64; 2]) -> (f64, [f64; 2]) {
        if points.len() < 2 {
            return (f64::NAN, [f64::NAN, f64::NAN]); // refused by `Obstacle::validate`
        }
        let m = points.len() - 1;
        let mut best = (f64::INFINITY, 0usize, 0.0);
        for k in 0..m {
            let (a, b) = (points[k], points[k + 1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let t = ((x[0] - a[0]) * d[0] + (x[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
            let lo = if k == 0 { f64::NEG_INFINITY } else { 0.0 };
            let t = t.clamp(lo, if k == m - 1 { f64::INFINITY } else { 1.0 });
            let r = (x[0] - a[0] - t * d[0]).hypot(x[1] - a[1] - t * d[1]);
            if r < best.0 {
                best = (r, k, t);
            }
        }
        let left = |k: usize| {
            let (a, b) = (points[k], points[k + 1]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            [-(b[1] - a[1]) / l, (b[0] - a[0]) / l]
        };
        let (r, k, t) = best;
        // At an inner vertex (t = 0 of a segment after the first, or t = 1 of one before the last).
        let vertex = if t <= 0.0 && k > 0 {
            Some(k)
        } else if t >= 1.0 && k < m - 1 {
            Some(k + 1)
        } else {
            None
        };
        match vertex {
            Some(v) if r > 0.0 => {
                let (n1, n2) = (left(v - 1), left(v));
                let p = points[v];
                let s =
                    if (x[0] - p[0]) * (n1[0] + n2[0]) + (x[1] - p[1]) * (n1[1] + n2[1]) >= 0.0 { 1.0 } else { -1.0 };
                (s * r, [s * (x[0] - p[0]) / r, s * (x[1] - p[1]) / r])
            }
            _ => {
                let n = left(k);
                let a = points[k];
                ((x[0] - a[0]) * n[0] + (x[1] - a[1]) * n[1], n)
            }
        }
    }

    /// The gradient of [`ObstacleShape::distance`] at `x`: exact for a line, a disc and a hole, by central
    /// differences for a signed distance (the step ε^⅓ times the largest of |x|, |d(x)| and `length`, the size
    /// of the mesh there); NaN for a gap function, zero where it is not defined (a disc's centre).
    pub fn distance_gradient(&self, x: [f64; 2], length: f64) -> [f64; 2] {
        let radial = |c: &[f64; 2], sign: f64| {
            let r = (x[0] - c[0]).hypot(x[1] - c[1]);
            if r > 0.0 {
                [sign * (x[0] - c[0]) / r, sign * (x[1] - c[1]) / r]
            } else {
                [0.0, 0.0]
            }
        };
        match self {
            Self::Line { normal, .. } => {
                let m = normal[0].hypot(normal[1]);
                [normal[0] / m, normal[1] / m]
            }
            Self::Disc { center, .. } => radial(center, 1.0),
            Self::Hole { center, .. } => radial(center, -1.0),
            Self::Profile { points } => Self::profile_distance(points, x).1,
            Self::Distance(f) => {
                let d = |dx: f64, dy: f64| (f.0)([x[0] + dx, x[1] + dy]);
                let step = f64::EPSILON.cbrt() * x[0].abs().max(x[1].abs()).max(d(0.0, 0.0).abs()).max(length);
                [(d(step, 0.0) - d(-step, 0.0)) / (2.0 * step), (d(0.0, step) - d(0.0, -step)) / (2.0 * step)]
            }
            _ => [f64::NAN, f64::NAN],
        }
    }

    /// The signed distance of point `x` from a shape given by its geometry (NaN for a gap function).
    pub fn distance(&self, x: [f64; 2]) -> f64 {
        match self {
            Self::Line { point, normal } => {
                ((x[0] - point[0]) * normal[0] + (x[1] - point[1]) * normal[1]) / normal[0].hypot(normal[1])
            }
            Self::Disc { center, radius } => (x[0] - center[0]).hypot(x[1] - center[1]) - radius,
            Self::Hole { center, radius } => radius - (x[0] - center[0]).hypot(x[1] - center[1]),
            Self::Profile { points } => Self::profile_distance(points, x).0,
            Self::Distance(f) => (f.0)(x),
            _ => f64::NAN,
        }
    }

    /// The radius R and the abscissa of the lowest point of a circle or a parabola, else None.
    pub fn radius_center(&self) -> Option<(f64, f64)> {
        match *self {
            Self::Circle { center, radius } | Self::Parabola { center, radius } => Some((radius, center)),
            _ => None,
        }
    }

    /// The abscissae, sorted, where the initial gap may have a local minimum between two points at which
    /// it is sampled: the lowest point of a circle or a parabola, the vertices of a polyline; none for a
    /// flat obstacle or a function (whose minima are not known). The estimator integrates the penetration
    /// finely around them.
    pub fn lowest_points(&self) -> Vec<f64> {
        match self {
            Self::Circle { center, .. } | Self::Parabola { center, .. } => vec![*center],
            Self::Polyline { xi, .. } => xi.clone(),
            _ => Vec::new(),
        }
    }

    /// The shape's name, as scene files and Python spell it: `flat`, `circle`, `parabola`, `polyline`,
    /// `function`, `line`, `disc`, `hole`, `profile` or `distance`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::Circle { .. } => "circle",
            Self::Parabola { .. } => "parabola",
            Self::Polyline { .. } => "polyline",
            Self::Function(_) => "function",
            Self::Line { .. } => "line",
            Self::Disc { .. } => "disc",
            Self::Hole { .. } => "hole",
            Self::Profile { .. } => "profile",
            Self::Distance(_) => "distance",
        }
    }
}

/// The shape as the call that builds it in Python: `flat()`, `circle(radius=2, center=0)`,
/// `parabola(radius=2, center=0)`, `polyline(<5 points>)`, `function(<closure>)`.
impl fmt::Display for ObstacleShape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Circle { center, radius } | Self::Parabola { center, radius } => {
                write!(f, "{}(radius={radius}, center={center})", self.kind())
            }
            Self::Polyline { xi, .. } => write!(f, "polyline(<{} points>)", xi.len()),
            Self::Function(_) => f.write_str("function(<closure>)"),
            Self::Flat => f.write_str("flat()"),
            Self::Line { point, normal } => {
                write!(f, "line(point=({}, {}), normal=({}, {}))", point[0], point[1], normal[0], normal[1])
            }
            Self::Disc { center, radius } | Self::Hole { center, radius } => {
                write!(f, "{}(center=({}, {}), radius={radius})", self.kind(), center[0], center[1])
            }
            Self::Profile { points } => write!(f, "profile(<{} points>)", points.len()),
            Self::Distance(_) => f.write_str("distance(<closure>)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The central differences of a signed distance given as a closure meet the exact gradients of the
    /// line, the disc and the hole it copies, to the differences' truncation (ε^⅔ relative).
    #[test]
    fn a_signed_distance_has_the_gradient_of_the_shape_it_copies() {
        let shapes = [
            ObstacleShape::Line { point: [0.3, -2.0], normal: [1.0, 2.0] },
            ObstacleShape::Disc { center: [12.0, -3.0], radius: 0.7 },
            ObstacleShape::Hole { center: [0.5, 0.25], radius: 4.0 },
        ];
        for shape in shapes {
            let copy = shape.clone();
            let closure = ObstacleShape::Distance(DistanceFunction(Arc::new(move |x| copy.distance(x))));
            for x in [[0.0, 0.0], [13.5, -2.0], [1.0, 3.0]] {
                let (exact, numeric) = (shape.distance_gradient(x, 0.01), closure.distance_gradient(x, 0.01));
                assert_eq!(shape.distance(x), closure.distance(x));
                let off = (exact[0] - numeric[0]).hypot(exact[1] - numeric[1]);
                assert!(off < 1e-8, "{shape}: at {x:?} {exact:?} against {numeric:?}");
                assert!((exact[0].hypot(exact[1]) - 1.0).abs() < 1e-15, "a unit gradient");
            }
        }
        // A profile: a V-groove of half-angle 30° (the body above it) against the same groove as the smaller of
        // its two lines' distances (outside the groove: above both lines), and its gradient against central
        // differences, on segments, on the rays beyond the ends and around the vertex.
        let (sin, cos) = (0.5_f64, 0.75_f64.sqrt());
        let groove = ObstacleShape::Profile { points: vec![[-sin, cos], [0.0, 0.0], [sin, cos]] };
        let lines = |x: [f64; 2]| (cos * x[0] + sin * x[1]).min(-cos * x[0] + sin * x[1]);
        let closure = ObstacleShape::Distance(DistanceFunction(Arc::new(groove_copy)));
        fn groove_copy(x: [f64; 2]) -> f64 {
            ObstacleShape::Profile { points: vec![[-0.5, 0.75_f64.sqrt()], [0.0, 0.0], [0.5, 0.75_f64.sqrt()]] }
                .distance(x)
        }
        for x in [[0.0, 0.3], [0.1, 0.2], [-0.3, 0.9], [2.0, 5.0], [-3.0, 4.0], [0.4, 0.2]] {
            assert!(
                (groove.distance(x) - lines(x)).abs() < 1e-15,
                "{x:?}: {} against {}",
                groove.distance(x),
                lines(x)
            );
        }
        for x in [[0.02, 0.3], [0.4, 0.2], [0.01, -0.2], [0.05, -0.3], [-2.0, 0.5], [3.0, 7.0]] {
            let (exact, numeric) = (groove.distance_gradient(x, 0.01), closure.distance_gradient(x, 0.01));
            assert!((exact[0] - numeric[0]).hypot(exact[1] - numeric[1]) < 1e-8, "{x:?}: {exact:?} {numeric:?}");
        }
        // A profile that crosses itself, or whose end rays cross a segment, or that folds back, is refused.
        let refused = |points: Vec<[f64; 2]>| {
            Obstacle { shape: ObstacleShape::Profile { points }, ..Default::default() }.validate().is_err()
        };
        assert!(refused(vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]), "a bow tie");
        assert!(refused(vec![[0.0, 0.0], [1.0, 0.0], [0.5, 0.0]]), "a fold");
        assert!(refused(vec![[0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 2.0]]), "the last ray crosses");
        assert!(!refused(vec![[-1.0, 1.0], [0.0, 0.0], [1.0, 1.0]]) && !refused(vec![[0.0, 0.0], [1.0, 0.0]]));
        assert!(!refused(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), "collinear, going on");
        // Below the tip the groove's solid: negative, its distance the tip's.
        assert!((groove.distance([0.0, -0.2]) + 0.2).abs() < 1e-15);
        // No gradient at a disc's centre; none for a gap function.
        let disc = ObstacleShape::Disc { center: [1.0, 1.0], radius: 1.0 };
        assert_eq!(disc.distance_gradient([1.0, 1.0], 0.1), [0.0, 0.0]);
        assert!(ObstacleShape::Flat.distance_gradient([0.0, 0.0], 0.1)[0].is_nan());
        assert!(!ObstacleShape::Flat.is_geometry() && disc.is_geometry());
    }
}
