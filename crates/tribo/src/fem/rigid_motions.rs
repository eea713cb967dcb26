//! Floating bodies: every piece of the mesh must be held by the supports.
//!
//! Every piece of the mesh (triangles joined through edges; pieces joined at a single node count as
//! separate) must be held: the conditions at its nodes, rows `(a_x, a_y, (x − x̄) a_y − (y − ȳ) a_x)`
//! against the rigid motions `(α − θ (y − ȳ), β + θ (x − x̄))`, must have rank 3. A piece without any
//! condition is [`Error::FloatingPiece`]; one whose conditions leave a rigid motion free (rollers all
//! parallel, a single held node) is [`Error::RigidMotion`], which says which motion. On a piece connected
//! through edges the kernel of K is exactly the rigid motions, so this test is also sufficient.

use std::collections::HashMap;

use nalgebra::{Matrix3, Vector3};

use crate::error::{Error, Result};
use crate::fem::supports::NodeSupport;
use crate::mesh::line::geometric_tol_rel;
use crate::mesh::Mesh;

/// Every piece of the mesh must be held (see the module documentation).
pub(super) fn check_held(mesh: &Mesh, nodes: &[NodeSupport]) -> Result<()> {
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
        // `r` is one of the map's own keys.
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
