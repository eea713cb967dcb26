//! Dirichlet conditions (Γ_D): clamps, rollers (symmetry lines) and prescribed displacements, and the
//! map from the 2N nodal dofs to the unknowns that they leave.
//!
//! # The conditions
//! Each [`Support`] names an edge set and imposes, at every node of it, linear conditions `a · u = v`
//! with a unit vector a:
//! * [`Support::Clamp`]: `u = 0` (a = e_x and a = e_y, v = 0);
//! * [`Support::Roller`]: `u · n = 0` with n the normal of the set, which must be straight (a symmetry
//!   line of any direction); the tangential component is free;
//! * [`Support::Displacement`]: `u_x = ū_x` and/or `u_y = ū_y` (a component left out stays free).
//!
//! The conditions of all supports that reach a node are combined ([`NodeSupport`]): if their vectors a
//! span the plane the node's displacement is fixed (every condition must then agree with it); if they are
//! all parallel to one unit vector a, the node slides along `t = a⊥` with `u · a = v` (they must agree on
//! v); conditions that contradict each other are [`Error::ConflictingSupports`]. So a corner shared by a
//! clamped side and a symmetry line is simply clamped, two rollers meeting at an angle fix their common
//! node, and `u_y = −0.01` on a face next to a clamped side is refused at the shared corner (the data
//! would be discontinuous there).
//!
//! # Unknowns: a change of basis, then a lifting
//! Every nodal displacement is written `u_i = T_i x_i + ū_i`:
//! * free node: `T_i = I` (two unknowns, the x and y components), `ū_i = 0`;
//! * sliding node: `T_i = t` (one unknown, the tangential component w), `ū_i = v a`;
//! * fixed node: no unknown, `ū_i` the prescribed displacement.
//!
//! So `u = T x + ū` with T (2N × n) having at most one non-zero per row: each global dof follows at most
//! one unknown, with a coefficient ([`Dofs::unknown`]). For a free node or an axis-aligned roller T is a
//! selection, as the clamped-only code had; a rotated roller's node has one unknown along its tangent, no
//! penalty and no extra multiplier. Every operator is assembled over the 2N dofs and restricted with T:
//! the stiffness `Tᵀ K T` keeps the sparsity of K restricted to the nodes that have unknowns (so its
//! symbolic Cholesky analysis is done once, as before), `−G` becomes `Tᵀ(−G)T` and the rows of E become
//! `E T` (a rotated node's two coefficients merge into one).
//!
//! # How a prescribed displacement enters the condensed problem
//! With `A = K − G` and E over all 2N dofs, the stabilized problem in the unknowns x, for test functions
//! that vanish on Γ_D (`v = T y`), is
//!
//! ```text
//! Tᵀ A T x + Tᵀ Eᵀ λ = Tᵀ f − Tᵀ A ū                       (equilibrium)
//! H λ + c = d − E (T x + ū) + Dγ λ                         (the complementarity quantities of the QP)
//! ```
//!
//! so with `Ã = Tᵀ A T`, `Ẽ = E T`, the lifted load `f̃ = Tᵀ (f − K ū) + Tᵀ G ū` and the lifted obstacle
//! moments `d̃ = d − E ū`, the condensation is the clamped one with `(f, d)` replaced by `(f̃, d̃)`:
//! `x = Ã⁻¹ (f̃ − Ẽᵀ λ)`, `H = Ẽ Ã⁻¹ Ẽᵀ + Dγ`, `c = d̃ − Ẽ Ã⁻¹ f̃`. Both G and E (its stabilization
//! part `−γ0 Cγ S`, the stress of the contact triangles) depend on γ0 and touch the dofs of a contact
//! triangle, some of which may be prescribed: so `Tᵀ G ū` and `E ū` are formed per γ0, when A is
//! factorized ([`crate::Problem::condense_with`]); `Tᵀ K ū` once, in [`crate::Problem::new`]
//! (`Problem::f_free`). The displacement is `T x + ū` ([`crate::Problem::expand`]) and the reactions
//! `K u − f` on every constrained dof (their component along a roller's normal at a sliding node).
//!
//! # Floating bodies
//! Every piece of the mesh (triangles joined through edges; pieces joined at a single node count as
//! separate) must be held: the conditions at its nodes, rows `(a_x, a_y, (x − x̄) a_y − (y − ȳ) a_x)`
//! against the rigid motions `(α − θ (y − ȳ), β + θ (x − x̄))`, must have rank 3. A piece without any
//! condition is [`Error::FloatingPiece`]; one whose conditions leave a rigid motion free (rollers all
//! parallel, a single held node) is [`Error::RigidMotion`], which says which motion. On a piece connected
//! through edges the kernel of K is exactly the rigid motions, so this test is also sufficient.

use std::collections::{HashMap, HashSet};

use nalgebra::{Matrix3, Vector3};

use crate::contact::{geometric_tol_rel, off_line};
use crate::error::{Error, Result};
use crate::mesh::Mesh;

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

    /// The edge set it acts on.
    pub fn set(&self) -> &str {
        match self {
            Self::Clamp { set } | Self::Roller { set } | Self::Displacement { set, .. } => set,
        }
    }

    /// Checks the support's own data: a prescribed displacement needs a component, and finite values.
    ///
    /// # Errors
    /// [`Error::BadSupport`].
    pub fn validate(&self) -> Result<()> {
        if let Self::Displacement { set, x, y } = self {
            let bad = |what: String| Err(Error::BadSupport { set: set.clone(), what });
            if x.is_none() && y.is_none() {
                return bad("a prescribed displacement needs x, y or both".into());
            }
            for (name, v) in [("x", x), ("y", y)] {
                if let Some(v) = v.filter(|v| !v.is_finite()) {
                    return bad(format!("the {name} component {v} is not finite"));
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

/// The supports resolved on the nodes: which unknown each dof follows, and the lifting ū.
#[derive(Debug, Clone)]
pub struct Dofs {
    /// Per node, what the supports leave free.
    pub nodes: Vec<NodeSupport>,
    /// Per dof (2N, interleaved): the unknown it follows and the coefficient, `u_d = coeff · x_k + ū_d`.
    map: Vec<Option<(usize, f64)>>,
    /// Number of unknowns n.
    pub n_free: usize,
    /// The lifting ū (2N): the prescribed part of every dof.
    pub lifting: Vec<f64>,
    /// Edges (sorted node pairs) that carry a support, for the checks against Γ_C.
    pub edges: HashSet<[usize; 2]>,
}

/// One condition `a · u = v` at a node, with the support it comes from.
#[derive(Clone, Copy)]
struct Condition {
    a: [f64; 2],
    v: f64,
    support: usize,
}

impl Dofs {
    /// Resolves `supports` on `mesh`.
    ///
    /// # Errors
    /// [`Error::NoDirichlet`] for no support; [`Error::UnknownEdgeSet`]; [`Error::BadSupport`] for a
    /// non-finite or missing prescribed value; [`Error::SupportNotStraight`] for a roller on a set that is
    /// not straight; [`Error::ConflictingSupports`]; [`Error::FloatingPiece`] / [`Error::RigidMotion`]
    /// for a piece that the supports do not hold.
    pub fn new(mesh: &Mesh, supports: &[Support]) -> Result<Self> {
        if supports.is_empty() {
            return Err(Error::NoDirichlet);
        }
        let n_nodes = mesh.n_nodes();
        let mut conditions: Vec<Vec<Condition>> = vec![Vec::new(); n_nodes];
        let mut edges = HashSet::new();
        for (k, support) in supports.iter().enumerate() {
            let set = support.set();
            let raw = mesh.edge_set(set)?;
            support.validate()?;
            let conds: Vec<([f64; 2], f64)> = match support {
                Support::Clamp { .. } => vec![([1.0, 0.0], 0.0), ([0.0, 1.0], 0.0)],
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
                        // A node shared by two edges of one set gets the set's conditions once.
                        let list = &mut conditions[node];
                        if !list.iter().any(|c| c.support == k && c.a == dir) {
                            list.push(Condition { a: dir, v, support: k });
                        }
                    }
                }
            }
        }
        let mut nodes = Vec::with_capacity(n_nodes);
        for (node, list) in conditions.iter().enumerate() {
            nodes.push(resolve(node, list, supports)?);
        }
        check_held(mesh, &nodes)?;
        let mut map = vec![None; 2 * n_nodes];
        let mut lifting = vec![0.0; 2 * n_nodes];
        let mut n_free = 0;
        for (i, ns) in nodes.iter().enumerate() {
            match *ns {
                NodeSupport::Free => {
                    map[2 * i] = Some((n_free, 1.0));
                    map[2 * i + 1] = Some((n_free + 1, 1.0));
                    n_free += 2;
                }
                NodeSupport::Slide { normal, tangent, value } => {
                    for c in 0..2 {
                        // An axis-aligned roller leaves one dof untouched by the unknown: no entry.
                        map[2 * i + c] = (tangent[c] != 0.0).then_some((n_free, tangent[c]));
                        lifting[2 * i + c] = value * normal[c];
                    }
                    n_free += 1;
                }
                NodeSupport::Fixed { value } => {
                    lifting[2 * i] = value[0];
                    lifting[2 * i + 1] = value[1];
                }
            }
        }
        Ok(Self { nodes, map, n_free, lifting, edges })
    }

    /// The unknown that dof `d` follows and its coefficient (`u_d = coeff · x_k + ū_d`), or `None` for
    /// a prescribed dof.
    pub fn unknown(&self, d: usize) -> Option<(usize, f64)> {
        self.map[d]
    }

    /// True when no support prescribes a non-zero displacement.
    pub fn homogeneous(&self) -> bool {
        self.lifting.iter().all(|v| *v == 0.0)
    }

    /// `u = T x + ū` (all 2N dofs) from the unknowns x.
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        self.map.iter().zip(&self.lifting).map(|(m, l)| m.map_or(0.0, |(k, a)| a * x[k]) + l).collect()
    }

    /// `Tᵀ v` (n) for a vector v over all 2N dofs.
    pub fn restrict(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_free];
        for (m, vd) in self.map.iter().zip(v) {
            if let Some((k, a)) = m {
                out[*k] += a * vd;
            }
        }
        out
    }

    /// Sparse rows over all 2N dofs as rows over the unknowns (`row · T`), sorted with duplicates summed.
    pub fn restrict_rows(&self, rows: &[Vec<(usize, f64)>]) -> Vec<Vec<(usize, f64)>> {
        rows.iter()
            .map(|row| {
                let mut r: Vec<(usize, f64)> =
                    row.iter().filter_map(|&(d, v)| self.map[d].map(|(k, a)| (k, a * v))).collect();
                r.sort_by_key(|e| e.0);
                let mut out: Vec<(usize, f64)> = Vec::with_capacity(r.len());
                for (k, v) in r {
                    match out.last_mut() {
                        Some(l) if l.0 == k => l.1 += v,
                        _ => out.push((k, v)),
                    }
                }
                out
            })
            .collect()
    }

    /// Keeps the part of the nodal forces `r` (2N) that the supports take: all of it at a fixed node, the
    /// component along the condition at a sliding node, nothing at a free node.
    pub fn keep_reactions(&self, r: &mut [f64]) {
        for (i, ns) in self.nodes.iter().enumerate() {
            match *ns {
                NodeSupport::Free => {
                    r[2 * i] = 0.0;
                    r[2 * i + 1] = 0.0;
                }
                NodeSupport::Slide { normal, .. } => {
                    let rn = r[2 * i] * normal[0] + r[2 * i + 1] * normal[1];
                    r[2 * i] = rn * normal[0];
                    r[2 * i + 1] = rn * normal[1];
                }
                NodeSupport::Fixed { .. } => {}
            }
        }
    }
}

/// The unit normal of a straight edge set (from its first edge), checking that every node lies on that
/// line within `√ε` of the local edge length (the tolerance of Γ_C, [`crate::contact::off_line`]).
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
/// by at most `√ε` times the largest of them (user data given by different formulas).
fn resolve(node: usize, list: &[Condition], supports: &[Support]) -> Result<NodeSupport> {
    let Some(first) = list.first() else {
        return Ok(NodeSupport::Free);
    };
    let tol_dir = 4.0 * geometric_tol_rel();
    let vmax = list.iter().fold(0.0_f64, |m, c| m.max(c.v.abs()));
    let tol_v = geometric_tol_rel() * vmax;
    let conflict = |c: &Condition, what: String| Error::ConflictingSupports {
        node,
        first: supports[first.support].set().to_string(),
        second: supports[c.support].set().to_string(),
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
            // The unknown's direction: a⊥ with its largest component positive (e_y for a = e_x, e_x
            // for a = e_y), so that an axis-aligned slide's unknown is a plain displacement component.
            let mut t = [-a[1], a[0]];
            let largest = if t[0].abs() >= t[1].abs() { t[0] } else { t[1] };
            if largest < 0.0 {
                t = [-t[0], -t[1]];
            }
            Ok(NodeSupport::Slide { normal: a, tangent: t, value: first.v })
        }
        Some(second) => {
            // Two independent conditions fix the node; every other one must agree.
            let (a, b) = (first.a, second.a);
            let det = cross(a, b);
            let value = [(first.v * b[1] - second.v * a[1]) / det, (a[0] * second.v - b[0] * first.v) / det];
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

/// Every piece of the mesh must be held (see the module documentation).
fn check_held(mesh: &Mesh, nodes: &[NodeSupport]) -> Result<()> {
    let n = mesh.n_triangles();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut t: usize) -> usize {
        while parent[t] != t {
            parent[t] = parent[parent[t]];
            t = parent[t];
        }
        t
    }
    let mut owner: HashMap<[usize; 2], usize> = HashMap::with_capacity(2 * n);
    for (t, tri) in mesh.triangles().iter().enumerate() {
        for local in 0..3 {
            let (a, b) = (tri[local], tri[(local + 1) % 3]);
            if let Some(&other) = owner.get(&[a.min(b), a.max(b)]) {
                let (ra, rb) = (root(&mut parent, t), root(&mut parent, other));
                parent[ra] = rb;
            } else {
                owner.insert([a.min(b), a.max(b)], t);
            }
        }
    }
    let roots: Vec<usize> = (0..n).map(|t| root(&mut parent, t)).collect();
    let pieces = (0..n).filter(|&t| roots[t] == t).count();
    // Per piece: its triangles, its nodes (a node shared by pieces counts in each), the centroid and size
    // of its nodes, then the Gram matrix of its conditions against the rigid motions.
    let mut size = vec![0usize; n];
    let mut piece_nodes: HashMap<usize, Vec<usize>> = HashMap::new();
    for (t, tri) in mesh.triangles().iter().enumerate() {
        size[roots[t]] += 1;
        piece_nodes.entry(roots[t]).or_default().extend_from_slice(tri);
    }
    let pts = mesh.points();
    let mut order: Vec<usize> = piece_nodes.keys().copied().collect();
    order.sort_unstable();
    for r in order {
        let list = piece_nodes.get_mut(&r).expect("key");
        list.sort_unstable();
        list.dedup();
        let floating = Error::FloatingPiece { triangle: r, node: mesh.triangles()[r][0], triangles: size[r], pieces };
        let held: Vec<usize> = list.iter().copied().filter(|&i| nodes[i] != NodeSupport::Free).collect();
        if held.is_empty() {
            return Err(floating);
        }
        let m = list.len() as f64;
        let centre = list.iter().fold([0.0, 0.0], |c, &i| [c[0] + pts[i][0] / m, c[1] + pts[i][1] / m]);
        let scale = list
            .iter()
            .map(|&i| (pts[i][0] - centre[0]).hypot(pts[i][1] - centre[1]))
            .fold(0.0_f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut gram = Matrix3::<f64>::zeros();
        let mut rows = 0usize;
        for &i in &held {
            let (x, y) = ((pts[i][0] - centre[0]) / scale, (pts[i][1] - centre[1]) / scale);
            let dirs: Vec<[f64; 2]> = match nodes[i] {
                NodeSupport::Slide { normal, .. } => vec![normal],
                _ => vec![[1.0, 0.0], [0.0, 1.0]],
            };
            for a in dirs {
                let row = Vector3::new(a[0], a[1], x * a[1] - y * a[0]);
                gram += row * row.transpose();
                rows += 1;
            }
        }
        // The Gram matrix of `rows` unit-size rows is formed to about `rows · ε` of its norm: an
        // eigenvalue below 16 times that is a rigid motion the conditions do not see.
        let eig = gram.symmetric_eigen();
        let (imin, lmin) =
            eig.eigenvalues.iter().enumerate().fold((0, f64::INFINITY), |b, (k, &v)| if v < b.1 { (k, v) } else { b });
        let lmax = eig.eigenvalues.max();
        if lmin <= 16.0 * rows as f64 * f64::EPSILON * lmax {
            let v = eig.eigenvectors.column(imin);
            let motion = describe_motion([v[0], v[1], v[2]], centre, scale);
            return Err(Error::RigidMotion { triangle: r, node: held[0], triangles: size[r], pieces, motion });
        }
    }
    Ok(())
}

/// Words for the rigid motion `(α − θ (y − ȳ)/L, β + θ (x − x̄)/L)`: a translation when θ is negligible,
/// else a rotation about its centre.
fn describe_motion(v: [f64; 3], centre: [f64; 2], scale: f64) -> String {
    let [alpha, beta, theta] = v;
    let tr = alpha.hypot(beta);
    if theta.abs() <= geometric_tol_rel() * tr {
        format!("a translation along ({:.3}, {:.3})", alpha / tr, beta / tr)
    } else {
        // u = 0 at x − x̄ = −β L/θ, y − ȳ = α L/θ.
        let c = [centre[0] - beta * scale / theta, centre[1] + alpha * scale / theta];
        format!("a rotation about ({:.4e}, {:.4e})", c[0], c[1])
    }
}

impl Support {
    /// The prescribed (x, y) components, `None` where free: `(0, 0)` for a clamp, `(None, None)` for a
    /// roller (its condition is along the normal, not along an axis), the given ones for a displacement.
    pub fn components(&self) -> [Option<f64>; 2] {
        match self {
            Self::Clamp { .. } => [Some(0.0), Some(0.0)],
            Self::Roller { .. } => [None, None],
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
            s => write!(f, "{}({set:?})", s.kind()),
        }
    }
}
