//! Floating bodies: every piece of the mesh must be held, by the supports or by the contact.
//!
//! Every piece of the mesh (triangles joined through edges; pieces joined at a single node count as
//! separate) must be held: the conditions at its nodes, rows `(a_x, a_y, (x − x̄) a_y − (y − ȳ) a_x)`
//! against the rigid motions `(α − θ (y − ȳ), β + θ (x − x̄))`, must have rank 3. A piece without any
//! condition is [`Error::FloatingPiece`]; one whose conditions leave a rigid motion free (rollers all
//! parallel, a single held node) is [`Error::RigidMotion`], which says which motion. On a piece connected
//! through edges the kernel of K is exactly the rigid motions, so this test is also sufficient.
//!
//! # Held by the contact
//! A piece that holds a node of a contact side (and shares no node with another piece) may be left free
//! by its supports (a punch pushed down by a
//! load and held only by the contact): its free motions ([`FreeMotions`]) are then returned instead of
//! refused, and [`pins`] chooses as many extra conditions as it has free motions, at nodes off the contact
//! sides, that hold them exactly (pivoted Gram–Schmidt on the candidate rows). With those pins the
//! stiffness is positive definite; the pins carry no force once the piece is in equilibrium, which the
//! contact QP imposes ([`crate::Dofs`]).

use nalgebra::{Matrix3, Vector3};

use crate::error::{Error, Result};
use crate::fem::supports::NodeSupport;
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::{grouped, Mesh};

/// A piece of the mesh its supports leave free to move rigidly, to be held by the contact.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeMotions {
    /// A triangle of the piece.
    pub triangle: usize,
    /// The piece's nodes, sorted.
    pub nodes: Vec<usize>,
    /// The centre x̄ and size L of the piece's nodes.
    pub centre: [f64; 2],
    /// See `centre`.
    pub scale: f64,
    /// Orthonormal free motions `(α, β, θ)`: the displacement `(α − θ (y − ȳ)/L, β + θ (x − x̄)/L)`.
    pub motions: Vec<[f64; 3]>,
}

impl FreeMotions {
    /// The displacement of motion `k` at `point`.
    pub fn at(&self, k: usize, point: [f64; 2]) -> [f64; 2] {
        let [alpha, beta, theta] = self.motions[k];
        let (x, y) = ((point[0] - self.centre[0]) / self.scale, (point[1] - self.centre[1]) / self.scale);
        [alpha - theta * y, beta + theta * x]
    }

    /// Motion `k` in words (a translation along a direction, or a rotation about a point).
    pub fn describe(&self, k: usize) -> String {
        describe_motion(self.motions[k], self.centre, self.scale)
    }
}

/// Every piece of the mesh must be held (see the module documentation): by its supports, or, for a piece
/// holding a node for which `may_float` is true (a node of a contact side), by the contact, whose free
/// motions are returned.
///
/// A solid of revolution (`axisymmetric`) has one rigid motion, the axial translation β: the radial
/// translation and the rotation strain it in the hoop direction ([`crate::fem::axisymmetric`]), so they
/// count as held.
pub(super) fn check_held(
    mesh: &Mesh,
    nodes: &[NodeSupport],
    may_float: &dyn Fn(usize) -> bool,
    axisymmetric: bool,
) -> Result<Vec<FreeMotions>> {
    let n = mesh.n_triangles();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut t: usize) -> usize {
        while parent[t] != t {
            parent[t] = parent[parent[t]];
            t = parent[t];
        }
        t
    }
    // Triangles sharing an edge join: the edges grouped by their smaller node (a counting sort, no
    // hashing), each group sorted, so that the entries of one edge are adjacent.
    let n_nodes = mesh.n_nodes();
    let (start, ends) = grouped(
        n_nodes,
        mesh.triangles().iter().enumerate().flat_map(|(t, tri)| {
            (0..3).map(move |l| {
                let (a, b) = (tri[l], tri[(l + 1) % 3]);
                (a.min(b), (a.max(b), t))
            })
        }),
    );
    for i in 0..n_nodes {
        for w in ends[start[i]..start[i + 1]].windows(2) {
            if w[0].0 == w[1].0 {
                let (ra, rb) = (root(&mut parent, w[1].1), root(&mut parent, w[0].1));
                parent[ra] = rb;
            }
        }
    }
    drop(ends);
    // Each piece is named by its first triangle: the union-find's roots depend on the order of the unions.
    let mut roots: Vec<usize> = (0..n).map(|t| root(&mut parent, t)).collect();
    let mut first = vec![usize::MAX; n];
    for (t, &r) in roots.iter().enumerate() {
        first[r] = first[r].min(t);
    }
    for r in &mut roots {
        *r = first[*r];
    }
    drop(first);
    let pieces = (0..n).filter(|&t| roots[t] == t).count();
    // Per piece: its triangles, its nodes (a node shared by pieces counts in each), the centroid and size
    // of its nodes, then the Gram matrix of its conditions against the rigid motions.
    let mut size = vec![0usize; n];
    for &r in &roots {
        size[r] += 1;
    }
    // A node in two pieces joins them at a point: such a piece is hinged, not free, and cannot float.
    let mut first_piece: Vec<Option<usize>> = vec![None; n_nodes];
    let mut shared = vec![false; n_nodes];
    for (t, tri) in mesh.triangles().iter().enumerate() {
        for &v in tri {
            match first_piece[v] {
                None => first_piece[v] = Some(roots[t]),
                Some(r) if r != roots[t] => shared[v] = true,
                Some(_) => {}
            }
        }
    }
    // The pieces in the order of their root triangles (the error names the first one met), each with its
    // nodes in increasing order: a node of one piece is listed by its piece, a shared node by each of its.
    let mut index = vec![usize::MAX; n];
    let mut by_root: Vec<(usize, Vec<usize>)> = Vec::with_capacity(pieces);
    for t in (0..n).filter(|&t| roots[t] == t) {
        index[t] = by_root.len();
        by_root.push((t, Vec::new()));
    }
    for (v, piece) in first_piece.iter().enumerate() {
        if let (Some(r), false) = (piece, shared[v]) {
            by_root[index[*r]].1.push(v);
        }
    }
    if shared.iter().any(|&s| s) {
        for (t, tri) in mesh.triangles().iter().enumerate() {
            for &v in tri.iter().filter(|&&v| shared[v]) {
                by_root[index[roots[t]]].1.push(v);
            }
        }
        for (_, list) in &mut by_root {
            list.sort_unstable();
            list.dedup();
        }
    }
    drop(index);
    let pts = mesh.points();
    let mut free = Vec::new();
    for (r, list) in by_root {
        let floats = list.iter().any(|&i| may_float(i)) && !list.iter().any(|&i| shared[i]);
        let m = list.len() as f64;
        let centre = list.iter().fold([0.0, 0.0], |c, &i| [c[0] + pts[i][0] / m, c[1] + pts[i][1] / m]);
        let scale = list
            .iter()
            .map(|&i| (pts[i][0] - centre[0]).hypot(pts[i][1] - centre[1]))
            .fold(0.0_f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let held: Vec<usize> = list.iter().copied().filter(|&i| nodes[i] != NodeSupport::Free).collect();
        if held.is_empty() {
            if !floats {
                return Err(Error::FloatingPiece {
                    triangle: r,
                    node: mesh.triangles()[r][0],
                    triangles: size[r],
                    pieces,
                });
            }
            let motions = if axisymmetric {
                vec![[0.0, 1.0, 0.0]]
            } else {
                vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            };
            free.push(FreeMotions { triangle: r, nodes: list, centre, scale, motions });
            continue;
        }
        let mut gram = Matrix3::<f64>::zeros();
        let mut rows = 0usize;
        if axisymmetric {
            // The hoop strain holds the radial translation and the rotation.
            gram[(0, 0)] += 1.0;
            gram[(2, 2)] += 1.0;
            rows += 2;
        }
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
        let lmax = eig.eigenvalues.max();
        let small: Vec<usize> =
            (0..3).filter(|&k| eig.eigenvalues[k] <= 16.0 * rows as f64 * f64::EPSILON * lmax).collect();
        let motion = |k: usize| {
            let v = eig.eigenvectors.column(k);
            [v[0], v[1], v[2]]
        };
        match small.first() {
            None => {}
            Some(_) if floats => {
                free.push(FreeMotions {
                    triangle: r,
                    nodes: list,
                    centre,
                    scale,
                    motions: small.iter().map(|&k| motion(k)).collect(),
                });
            }
            Some(&k) => {
                let motion = describe_motion(motion(k), centre, scale);
                return Err(Error::RigidMotion { triangle: r, node: held[0], triangles: size[r], pieces, motion });
            }
        }
    }
    Ok(free)
}

/// The pins of a piece's free motions: as many conditions `u_i · a = 0` as it has free motions, at nodes
/// off the contact sides where any (`may_float` false) and along directions the node's supports leave
/// free, chosen by pivoted Gram–Schmidt on their rows `(motion_k(x_i) · a)_k` so that they hold the free
/// motions as well as any such choice can. Returns `(node, a)` per pin.
pub(super) fn pins(
    mesh: &Mesh,
    nodes: &[NodeSupport],
    piece: &FreeMotions,
    may_float: &dyn Fn(usize) -> bool,
) -> Vec<(usize, [f64; 2])> {
    let r = piece.motions.len();
    let off_contact: Vec<usize> = piece.nodes.iter().copied().filter(|&i| !may_float(i)).collect();
    let candidates = if off_contact.is_empty() { piece.nodes.clone() } else { off_contact };
    let mut rows: Vec<(usize, [f64; 2], Vec<f64>)> = Vec::new();
    for &i in &candidates {
        let dirs: Vec<[f64; 2]> = match nodes[i] {
            NodeSupport::Free => vec![[1.0, 0.0], [0.0, 1.0]],
            NodeSupport::Slide { tangent, .. } => vec![tangent],
            NodeSupport::Fixed { .. } => vec![],
        };
        for a in dirs {
            let row = (0..r)
                .map(|k| {
                    let u = piece.at(k, mesh.points()[i]);
                    u[0] * a[0] + u[1] * a[1]
                })
                .collect();
            rows.push((i, a, row));
        }
    }
    let mut chosen = Vec::with_capacity(r);
    for _ in 0..r {
        let norm2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        let Some(best) = (0..rows.len()).max_by(|&a, &b| norm2(&rows[a].2).total_cmp(&norm2(&rows[b].2))) else {
            break;
        };
        let (node, a, pivot) = rows.swap_remove(best);
        let p2 = norm2(&pivot);
        if p2 == 0.0 {
            break;
        }
        for (_, _, v) in &mut rows {
            let dot: f64 = v.iter().zip(&pivot).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(&pivot).for_each(|(x, y)| *x -= dot / p2 * y);
        }
        chosen.push((node, a));
    }
    chosen
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
