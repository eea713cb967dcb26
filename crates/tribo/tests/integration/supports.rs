//! Supports beyond clamping: rollers on straight edges of any direction and prescribed displacements.
//!
//! * constant-strain states driven only by prescribed displacements (axis-aligned, and a rotated body held
//!   by rotated rollers) are reproduced to round-off;
//! * half of the Hertz model with a symmetry line (a roller) equals the full model on its half;
//! * the same half model passes the direct check of (3.1) with the lifting in it (see `kkt`);
//! * bad supports are typed errors (the rejection tests are in `errors`).

use std::collections::BTreeMap;

use tribo::*;
use tribo_testkit::{hertz_scene, hertz_spec};

/// The largest |a − b| over two displacement fields, relative to the largest |b|.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

fn spec(supports: Vec<Support>, poisson: f64) -> ProblemSpec {
    ProblemSpec {
        material: Material { young: 100.0, poisson },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![],
        supports,
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "top".into(),
        // A flat obstacle 1 away: nothing touches, λ = 0.
        obstacle: Obstacle { shape: ObstacleShape::Flat, approach: -1.0, shift: 0.0, rotation: None },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    }
}

/// A constant strain reached with round-off only: `u = exact(x)` at every node, to 64 ulps of the
/// displacement times the condition number of K (≈ 1e3 on these 8 × 8 meshes): 64 · 2.2e-16 · 1e3 ≈ 1e-11.
const PATCH_TOL: f64 = 1e-11;

#[test]
fn patch_driven_by_prescribed_displacements() {
    // u_x = e x, u_y = −ν/(1−ν) e y: uniaxial plane-strain tension, σ_yy = σ_xy = 0 on the free top (Γ_C,
    // nothing touching), u_x given on the left (0) and the right (e), u_y = 0 on the bottom (a roller).
    let (e, nu) = (0.01, 0.3);
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 8, 8, Diagonal::Alternating).unwrap();
    let supports = vec![
        Support::displacement("left", Some(0.0), None),
        Support::displacement("right", Some(e), None),
        Support::roller("bottom"),
    ];
    for theta in [0.0, 0.5] {
        let problem = Problem::new(mesh.clone(), spec(supports.clone(), nu)).unwrap();
        let settings = SolverSettings { stabilization: Stabilization::Fraction(theta), ..Default::default() };
        let sol = problem.solve(&Friction::Frictionless, &settings, None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let exact: Vec<f64> = mesh.points().iter().flat_map(|p| [e * p[0], -nu / (1.0 - nu) * e * p[1]]).collect();
        let err = rel_diff(&sol.displacement, &exact);
        eprintln!("axis-aligned patch, θ = {theta}: relative error {err:.2e}");
        assert!(err < PATCH_TOL, "θ = {theta}: relative error {err:.2e}");
        // The reactions balance: the right side pulls with σ_xx × height = E/(1−ν²) e (plane strain, σ_yy
        // = 0), the left pulls back.
        let right: f64 = mesh.edge_set("right").unwrap().iter().flatten().map(|&i| sol.reactions[2 * i]).sum();
        let sigma = 100.0 / (1.0 - nu * nu) * e;
        // Each node of the set is counted once per edge it belongs to: the inner nodes twice.
        let mut nodes: Vec<usize> = mesh.edge_set("right").unwrap().iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        let right_once: f64 = nodes.iter().map(|&i| sol.reactions[2 * i]).sum();
        assert!(right > 0.0);
        assert!((right_once - sigma).abs() < PATCH_TOL * sigma, "reaction {right_once} vs σ_xx h = {sigma}");
    }
}

/// The unit square rotated by `angle` about the origin (same node order, so the edge sets keep their
/// names: "left" is the rotated left side).
fn rotated_square(angle: f64, n: usize) -> Mesh {
    let m = rectangle([0.0, 1.0], [0.0, 1.0], n, n, Diagonal::Alternating).unwrap();
    let (c, s) = (angle.cos(), angle.sin());
    let pts = m.points().iter().map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]).collect();
    Mesh::new(pts, m.triangles().to_vec(), m.edge_sets().clone()).unwrap()
}

#[test]
fn patch_on_a_rotated_body_held_by_rotated_rollers() {
    // ν = 0: uniaxial tension along the rotated x' axis, u = e x' e1', with no lateral contraction, so the
    // right side moves rigidly by e e1' (a displacement with both components), the left side slides along
    // its own line (u · e1' = 0, a roller of normal e1') and the bottom along its own (u · e2' = 0).
    let (e, angle) = (0.01_f64, std::f64::consts::FRAC_PI_6);
    let (c, s) = (angle.cos(), angle.sin());
    let mesh = rotated_square(angle, 8);
    let supports = vec![
        Support::roller("left"),
        Support::roller("bottom"),
        Support::displacement("right", Some(e * c), Some(e * s)),
    ];
    let problem = Problem::new(mesh.clone(), spec(supports, 0.0)).unwrap();
    // A rotated roller's node has one unknown: of the 81 nodes, the 9 on the right and the corner of the
    // two rollers are fixed, 8 more on the left and 7 more on the bottom slide (one unknown each).
    assert_eq!(problem.n_free, 2 * (81 - 10 - 15) + 15);
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    let exact: Vec<f64> = mesh
        .points()
        .iter()
        .flat_map(|p| {
            let xp = c * p[0] + s * p[1];
            [e * xp * c, e * xp * s]
        })
        .collect();
    let err = rel_diff(&sol.displacement, &exact);
    eprintln!("rotated patch: relative error {err:.2e}");
    assert!(err < PATCH_TOL, "relative error {err:.2e}");
    // The roller reactions are normal to their lines.
    for i in mesh.edge_set("left").unwrap().iter().flatten().copied() {
        let r = [sol.reactions[2 * i], sol.reactions[2 * i + 1]];
        assert!((r[0] * -s + r[1] * c).abs() <= 1e-12 * (r[0].hypot(r[1]) + 1.0), "node {i}: {r:?}");
    }
}

/// The stiffness on the unknowns, assembled straight into compressed columns from the mesh graph, equals
/// `Tᵀ K T` assembled the plain way (every element's triplets over all dofs, then each dof replaced by
/// the unknown it follows, duplicates summed by faer), entry by entry to round-off: on a body held by
/// rotated rollers (nodes with one unknown and two coefficients), fixed and free nodes.
#[test]
fn the_stiffness_on_the_unknowns_equals_t_transpose_k_t() {
    use faer::sparse::{SparseColMat, Triplet};
    use tribo::fem::elasticity::stiffness_triplets;
    let mesh = rotated_square(std::f64::consts::FRAC_PI_6, 8);
    let supports =
        vec![Support::roller("left"), Support::roller("bottom"), Support::displacement("right", Some(0.01), None)];
    let problem = Problem::new(mesh.clone(), spec(supports, 0.3)).unwrap();
    let material = Material { young: 100.0, poisson: 0.3 };
    let plain: Vec<Triplet<usize, usize, f64>> = stiffness_triplets(&mesh, &material)
        .into_iter()
        .filter_map(|t| {
            let ((i, a), (j, b)) = (problem.dofs.unknown(t.row)?, problem.dofs.unknown(t.col)?);
            Some(Triplet::new(i, j, a * b * t.val))
        })
        .collect();
    let n = problem.n_free;
    let reference = SparseColMat::try_new_from_triplets(n, n, &plain).unwrap();
    let (k, r) = (problem.k_matrix.to_dense(), reference.to_dense());
    let scale = (0..n).map(|i| r[(i, i)].abs()).fold(0.0_f64, f64::max);
    let worst = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .map(|(i, j)| (k[(i, j)] - r[(i, j)]).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 64.0 * f64::EPSILON * scale, "largest difference {worst:e} against {scale:e}");
    // The same pattern: no entry stored that the triplets do not give, none missing.
    assert_eq!(problem.k_matrix.compute_nnz(), reference.compute_nnz());
}

/// A mesh and its mirror image about x = 0, glued along x = 0 (nodes on it merged): the full mesh of a
/// model whose right half is `half`. Edge sets: "bottom" and "top" over both halves.
fn mirrored(half: &Mesh) -> Mesh {
    let pts = half.points();
    let mut points: Vec<[f64; 2]> = pts.to_vec();
    let mut image = vec![0usize; pts.len()];
    for (i, p) in pts.iter().enumerate() {
        if p[0] == 0.0 {
            image[i] = i;
        } else {
            image[i] = points.len();
            points.push([-p[0], p[1]]);
        }
    }
    let mut triangles = half.triangles().to_vec();
    // The mirror reverses orientation: list each image triangle's nodes the other way round.
    triangles.extend(half.triangles().iter().map(|t| [image[t[0]], image[t[2]], image[t[1]]]));
    let mut sets: BTreeMap<String, Vec<[usize; 2]>> = BTreeMap::new();
    for name in ["bottom", "top"] {
        let e = half.edge_set(name).unwrap();
        let mut all = e.to_vec();
        all.extend(e.iter().map(|&[a, b]| [image[a], image[b]]));
        sets.insert(name.into(), all);
    }
    Mesh::new(points, triangles, sets).unwrap()
}

#[test]
fn half_hertz_with_a_symmetry_line_equals_the_full_model() {
    let s = hertz_scene();
    let grading =
        Grading { side: Side::Top, segment: [0.0, s.segment[1]], h_min: s.h_min, h_max: s.h_max, growth: s.growth };
    let half_mesh = graded_rectangle([0.0, s.x[1]], s.y, &grading).unwrap();
    let full_mesh = mirrored(&half_mesh);
    let base = hertz_spec(s.approach, 0.0, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    let half_spec = ProblemSpec { supports: vec![Support::roller("left")], ..base.clone() };
    let half = Problem::new(half_mesh.clone(), half_spec).unwrap();
    let full = Problem::new(full_mesh, base).unwrap();
    let settings = SolverSettings::default();
    let hs = half.solve(&Friction::Frictionless, &settings, None).unwrap();
    let fs = full.solve(&Friction::Frictionless, &settings, None).unwrap();
    assert_eq!((hs.report.status, fs.report.status), (SolveStatus::Converged, SolveStatus::Converged));
    // The half's nodes are the first nodes of the full mesh; its multiplier dofs (P1 at the FE nodes of
    // Γ_C) are the full model's at abscissae ≥ 0.
    let n = half_mesh.n_nodes();
    let du = rel_diff(&hs.displacement, &fs.displacement[..2 * n]);
    let full_lambda: Vec<f64> =
        fs.multiplier_abscissae.iter().zip(&fs.lambda_n).filter(|(xi, _)| **xi >= 0.0).map(|(_, l)| *l).collect();
    let dl = rel_diff(&hs.lambda_n, &full_lambda);
    let df = (2.0 * hs.normal_force - fs.normal_force).abs() / fs.normal_force;
    eprintln!(
        "half Hertz vs full: {} vs {} unknowns, displacement {du:.2e}, λ_n {dl:.2e}, force 2 × {:.6} vs {:.6} ({df:.2e})",
        half.n_free, full.n_free, hs.normal_force, fs.normal_force
    );
    // The two discrete problems are equivalent (the full one's solution is symmetric, and its equations at
    // x ≥ 0 are the half's, doubled on the symmetry line), so they differ by what the QPs resolve:
    // √qp_tol relative, the KKT tolerance of a converged solve.
    let tol = settings.qp.tol.sqrt();
    assert!(du < tol && dl < tol && df < tol, "displacement {du:.2e}, λ_n {dl:.2e}, force {df:.2e} (tol {tol:.1e})");
}
