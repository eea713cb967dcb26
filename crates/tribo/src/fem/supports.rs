//! Dirichlet conditions (Γ_D): clamps, rollers (symmetry lines) and prescribed displacements, and the
//! map from the 2N nodal dofs to the unknowns that they leave.
//!
//! # The conditions
//! Each [`Support`] names an edge set and imposes, at every node of it, linear conditions `a · u = v`
//! with a unit vector a:
//! * [`Support::Clamp`]: `u = 0` (a = e_x and a = e_y, v = 0);
//! * [`Support::Roller`]: `u · n = 0` with n the normal of the set, which must be straight (a symmetry
//!   line of any direction); the tangential component is free;
//! * [`Support::Displacement`]: `u_x = ū_x` and/or `u_y = ū_y` (a component left out stays free);
//! * [`Support::Rotation`]: the small rigid rotation θ about a point c, `u = θ (−(y − c_y), x − c_x)` (both
//!   components, each node its own: a shaft turned, a torque applied through a rim).
//!
//! The conditions of all supports that reach a node are combined ([`NodeSupport`]): if their vectors a
//! span the plane the node's displacement is fixed (every condition must then agree with it); if they are
//! all parallel to one unit vector a, the node slides along `t = a⊥` with `u · a = v` (they must agree on
//! v); conditions that contradict each other are [`Error::ConflictingSupports`]. So a corner shared by a
//! clamped side and a symmetry line is simply clamped, two rollers meeting at an angle fix their common
//! node, and `u_y = −0.01` on a face next to a clamped side is refused at the shared corner (the data
//! would be discontinuous there).
//!
//! # Nearly parallel conditions
//! Two conditions `a · u = v₁`, `b · u = v₂` at an angle θ (`|a × b| = sin θ`) fix
//! `u = [a; b]⁻¹ (v₁, v₂)`, whose length can reach `|v| / sin θ`: a roller on a side tilted by 10⁻⁶ from
//! a prescribed `u_x = 0.01` moves the corner by 10⁴. Exactly parallel conditions (within the
//! straightness tolerance) are one condition or a conflict, as above; between them and orthogonal ones
//! the amplification grows without bound. A pair is refused ([`Error::NearlyParallelSupports`], naming
//! the node and the angle) when the displacement it prescribes is both
//! * longer than `√2 max |v|`, the most any two orthogonal conditions on the same data can prescribe (so
//!   the length comes from the angle, not from the data), and
//! * longer than the body (the diagonal of the mesh's bounding box): no reading of the small-displacement
//!   model that tribo solves covers a node moved by more than the body's size.
//!
//! Homogeneous conditions (v = 0) fix the node at 0 whatever their angle and are always accepted, as is a
//! displacement the data prescribe directly, however large.
//! What the conditions leave as unknowns is [`crate::fem::supports::Dofs`]; the check that they hold
//! every piece of the body is in `rigid_motions`.

use std::collections::HashSet;

use crate::error::{Error, Result};
use crate::mesh::line::{geometric_tol_rel, off_line};
use crate::mesh::Mesh;

pub use super::dofs::Dofs;

/// One Dirichlet condition on a named edge set.
#[derive(Debug, Clone, PartialEq)]
pub enum Support {
    /// `u = 0` on the set.
    Clamp {
        /// Edge set name.
        set: String,
    },
    /// `u · n = 0` on the set, which must be straight (n its normal); the tangential component is free.
    Roller {
        /// Edge set name.
        set: String,
    },
    /// `u_x = x` and/or `u_y = y` on the set; a component given as `None` is free.
    Displacement {
        /// Edge set name.
        set: String,
        /// Prescribed x component, or free.
        x: Option<f64>,
        /// Prescribed y component, or free.
        y: Option<f64>,
    },
    /// The small rigid rotation `u = θ (−(y − c_y), x − c_x)` of the set about `center` (θ in radians,
    /// counterclockwise).
    Rotation {
        /// Edge set name.
        set: String,
        /// The centre c.
        center: [f64; 2],
        /// The angle θ.
        angle: f64,
    },
}

impl Support {
    /// A clamp on `set`.
    pub fn clamp(set: impl Into<String>) -> Self {
        Self::Clamp { set: set.into() }
    }

    /// A roller (symmetry line) on `set`.
    pub fn roller(set: impl Into<String>) -> Self {
        Self::Roller { set: set.into() }
    }

    /// A prescribed displacement on `set`, per component (`None` = free).
    pub fn displacement(set: impl Into<String>, x: Option<f64>, y: Option<f64>) -> Self {
        Self::Displacement { set: set.into(), x, y }
    }

    /// A small rigid rotation of `set` by `angle` (radians, counterclockwise) about `center`.
    pub fn rotation(set: impl Into<String>, center: [f64; 2], angle: f64) -> Self {
        Self::Rotation { set: set.into(), center, angle }
    }

    /// The edge set it acts on.
    pub fn set(&self) -> &str {
        match self {
            Self::Clamp { set }
            | Self::Roller { set }
            | Self::Displacement { set, .. }
            | Self::Rotation { set, .. } => set,
        }
    }

    /// Checks the support's own data: a prescribed displacement needs a component, and finite values.
    ///
    /// # Errors
    /// [`Error::BadSupport`].
    pub fn validate(&self) -> Result<()> {
        if let Self::Rotation { set, center, angle } = self {
            if !(center.iter().all(|c| c.is_finite()) && angle.is_finite()) {
                let what = format!("the centre ({}, {}) and the angle {angle} must be finite", center[0], center[1]);
                return Err(Error::BadSupport { set: set.clone(), what });
            }
        }
        if let Self::Displacement { set, x, y } = self {
            let bad = |what: String| Err(Error::BadSupport { set: set.clone(), what });
            if x.is_none() && y.is_none() {
                return bad("a prescribed displacement needs x, y or both".into());
            }
            for (name, v) in [("x", x), ("y", y)] {
                if let Some(v) = v.filter(|v| !v.is_finite()) {
                    return bad(format!("the {name} component {v} is not finite"));
                }
                if let Some(v) = v.filter(|v| v.is_subnormal()) {
                    return bad(crate::error::subnormal(&format!("the {name} component"), v));
                }
            }
        }
        Ok(())
    }

    /// The kind's name, as scene files and Python spell it: `clamp`, `roller` or `displacement`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Clamp { .. } => "clamp",
            Self::Roller { .. } => "roller",
            Self::Displacement { .. } => "displacement",
            Self::Rotation { .. } => "rotation",
        }
    }
}

/// What the supports leave of one node's displacement `u_i = T_i x_i + ū_i`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeSupport {
    /// No condition: two unknowns, the x and y components.
    Free,
    /// `u · normal = value`; one unknown, the component along `tangent` (`normal⊥`).
    Slide {
        /// Unit vector of the condition.
        normal: [f64; 2],
        /// Unit direction of the unknown.
        tangent: [f64; 2],
        /// Prescribed `u · normal`.
        value: f64,
    },
    /// Both components prescribed.
    Fixed {
        /// The prescribed displacement.
        value: [f64; 2],
    },
}

/// The sliding node `u · a = value` (a a unit vector). The unknown's direction is a⊥ with its largest
/// component positive (e_y for a = e_x, e_x for a = e_y), so that an axis-aligned slide's unknown is a plain
/// displacement component.
pub(super) fn slide(a: [f64; 2], value: f64) -> NodeSupport {
    let mut t = [-a[1], a[0]];
    let largest = if t[0].abs() >= t[1].abs() { t[0] } else { t[1] };
    if largest < 0.0 {
        t = [-t[0], -t[1]];
    }
    NodeSupport::Slide { normal: a, tangent: t, value }
}

/// The `support` of the axis's condition `u_r = 0` (not one of the user's supports).
const AXIS: usize = usize::MAX;

/// The name of condition source `k`: its support's edge set, or the axis.
fn source(supports: &[Support], k: usize) -> String {
    supports.get(k).map_or_else(|| "the axis (r = 0)".to_string(), |s| s.set().to_string())
}

/// One condition `a · u = v` at a node, with the support it comes from.
#[derive(Clone, Copy)]
struct Condition {
    a: [f64; 2],
    v: f64,
    support: usize,
}

/// What the supports leave of every node ([`NodeSupport`], see the module documentation), and the edges
/// of Γ_D (each as `[min, max]` node pair).
///
/// # Errors
/// [`Error::UnknownEdgeSet`]; [`Error::BadSupport`]; [`Error::SupportNotStraight`];
/// [`Error::ConflictingSupports`]; [`Error::NearlyParallelSupports`].
/// The nodes of `axis` (an axisymmetric body's, [`crate::fem::axisymmetric::axis_nodes`]) get `u_x = 0`
/// besides, named "the axis" where it conflicts with a support.
pub(super) fn node_supports(
    mesh: &Mesh,
    supports: &[Support],
    axis: &[usize],
) -> Result<(Vec<NodeSupport>, HashSet<[usize; 2]>)> {
    let n_nodes = mesh.n_nodes();
    let mut conditions: Vec<Vec<Condition>> = vec![Vec::new(); n_nodes];
    for &node in axis {
        conditions[node].push(Condition { a: [1.0, 0.0], v: 0.0, support: AXIS });
    }
    let mut edges = HashSet::new();
    for (k, support) in supports.iter().enumerate() {
        let set = support.set();
        let raw = mesh.edge_set(set)?;
        support.validate()?;
        let conds: Vec<([f64; 2], f64)> = match support {
            Support::Clamp { .. } | Support::Rotation { .. } => vec![([1.0, 0.0], 0.0), ([0.0, 1.0], 0.0)],
            Support::Roller { .. } => vec![(straight_normal(mesh, set, raw)?, 0.0)],
            Support::Displacement { x, y, .. } => {
                let mut c = Vec::new();
                if let Some(v) = x {
                    c.push(([1.0, 0.0], *v));
                }
                if let Some(v) = y {
                    c.push(([0.0, 1.0], *v));
                }
                c
            }
        };
        for &[a, b] in raw {
            edges.insert([a.min(b), a.max(b)]);
            for node in [a, b] {
                for &(dir, v) in &conds {
                    // A rotation's value is each node's own: θ (−(y − c_y), x − c_x) along e_x and e_y.
                    let v = match support {
                        Support::Rotation { center, angle, .. } => {
                            let p = mesh.points()[node];
                            angle * (dir[1] * (p[0] - center[0]) - dir[0] * (p[1] - center[1]))
                        }
                        _ => v,
                    };
                    // A node shared by two edges of one set gets the set's conditions once.
                    let list = &mut conditions[node];
                    if !list.iter().any(|c| c.support == k && c.a == dir) {
                        list.push(Condition { a: dir, v, support: k });
                    }
                }
            }
        }
    }
    let [x0, y0, x1, y1] = mesh.bounding_box();
    let size = (x1 - x0).hypot(y1 - y0);
    let mut nodes = Vec::with_capacity(n_nodes);
    for (node, list) in conditions.iter().enumerate() {
        nodes.push(resolve(node, list, supports, size)?);
    }
    Ok((nodes, edges))
}

/// The unit normal of a straight edge set (from its first edge), checking that every node lies on that
/// line within `√ε` of the local edge length (the tolerance of Γ_C, [`crate::mesh::line::off_line`]).
fn straight_normal(mesh: &Mesh, set: &str, raw: &[[usize; 2]]) -> Result<[f64; 2]> {
    let pts = mesh.points();
    let [a0, b0] = raw[0];
    let (pa, pb) = (pts[a0], pts[b0]);
    let len0 = mesh.edge_length(a0, b0);
    let normal = [(pb[1] - pa[1]) / len0, -(pb[0] - pa[0]) / len0];
    match off_line(mesh, raw, normal) {
        Some((node, distance, length)) => {
            Err(Error::SupportNotStraight { set: set.to_string(), node, distance, length })
        }
        None => Ok(normal),
    }
}

/// Combines the conditions at one node (see the module documentation).
///
/// Two unit vectors count as parallel when `|a × b| ≤ 4√ε` (two straight sets on one line have normals
/// that agree to the straightness tolerance `√ε`, twice, with margin); two values agree when they differ
/// by at most `√ε` times the largest of them (user data given by different formulas). Two conditions
/// that fix the node are refused when they move it by more than `√2 max |v|` and more than `size`, the
/// body's (see the module documentation).
fn resolve(node: usize, list: &[Condition], supports: &[Support], size: f64) -> Result<NodeSupport> {
    let Some(first) = list.first() else {
        return Ok(NodeSupport::Free);
    };
    let tol_dir = 4.0 * geometric_tol_rel();
    let vmax = list.iter().fold(0.0_f64, |m, c| m.max(c.v.abs()));
    let tol_v = geometric_tol_rel() * vmax;
    let conflict = |c: &Condition, what: String| Error::ConflictingSupports {
        node,
        first: source(supports, first.support),
        second: source(supports, c.support),
        what,
    };
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    match list.iter().find(|c| cross(first.a, c.a).abs() > tol_dir) {
        None => {
            // All parallel: one condition u · a = v.
            let a = first.a;
            for c in &list[1..] {
                let s = (a[0] * c.a[0] + a[1] * c.a[1]).signum();
                if (s * c.v - first.v).abs() > tol_v {
                    return Err(conflict(
                        c,
                        format!("u·({:.3}, {:.3}) = {:e} and = {:e}", a[0], a[1], first.v, s * c.v),
                    ));
                }
            }
            Ok(slide(a, first.v))
        }
        Some(second) => {
            // Two independent conditions fix the node; every other one must agree.
            let (a, b) = (first.a, second.a);
            let det = cross(a, b);
            let value = [(first.v * b[1] - second.v * a[1]) / det, (a[0] * second.v - b[0] * first.v) / det];
            let displacement = value[0].hypot(value[1]);
            if displacement > std::f64::consts::SQRT_2 * vmax && displacement > size {
                return Err(Error::NearlyParallelSupports {
                    node,
                    first: source(supports, first.support),
                    second: source(supports, second.support),
                    angle_degrees: det.abs().min(1.0).asin().to_degrees(),
                    displacement,
                    data: vmax,
                    size,
                });
            }
            for c in list {
                let got = c.a[0] * value[0] + c.a[1] * value[1];
                if (got - c.v).abs() > tol_v {
                    return Err(conflict(
                        c,
                        format!(
                            "the other conditions fix u = ({:e}, {:e}), which gives u·({:.3}, {:.3}) = {:e}, not {:e}",
                            value[0], value[1], c.a[0], c.a[1], got, c.v
                        ),
                    ));
                }
            }
            Ok(NodeSupport::Fixed { value })
        }
    }
}

impl Support {
    /// The prescribed (x, y) components, `None` where free: `(0, 0)` for a clamp, `(None, None)` for a
    /// roller (its condition is along the normal, not along an axis), the given ones for a displacement.
    pub fn components(&self) -> [Option<f64>; 2] {
        match self {
            Self::Clamp { .. } => [Some(0.0), Some(0.0)],
            Self::Roller { .. } | Self::Rotation { .. } => [None, None],
            Self::Displacement { x, y, .. } => [*x, *y],
        }
    }
}

/// The support as the call that builds it in Python: `clamp("base")`, `roller("axis")`,
/// `displacement("top", x=None, y=-0.01)`.
impl std::fmt::Display for Support {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let set = self.set();
        match self {
            Self::Displacement { x, y, .. } => {
                let v = |v: &Option<f64>| v.map_or("None".to_string(), |v| v.to_string());
                write!(f, "displacement({set:?}, x={}, y={})", v(x), v(y))
            }
            Self::Rotation { center, angle, .. } => {
                write!(f, "rotation({set:?}, center=({}, {}), angle={angle})", center[0], center[1])
            }
            s => write!(f, "{}({set:?})", s.kind()),
        }
    }
}
