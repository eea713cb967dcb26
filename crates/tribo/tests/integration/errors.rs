//! One rejection test per input rule: bad input is a typed error that says what and where, never a panic.

use std::collections::BTreeMap;
use std::sync::Arc;

use tribo::*;

fn square() -> Mesh {
    rectangle([0.0, 1.0], [0.0, 1.0], 4, 4, Diagonal::Right).unwrap()
}

fn spec() -> ProblemSpec {
    ProblemSpec {
        material: Material { young: 100.0, poisson: 0.3 },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["top".into()],
        supports: vec![],
        body_force: [0.0, -1.0],
        tractions: vec![],
        contact: "bottom".into(),
        obstacle: Obstacle::default(),
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    }
}

fn sets(e: &[(&str, Vec<[usize; 2]>)]) -> BTreeMap<String, Vec<[usize; 2]>> {
    e.iter().map(|(n, v)| (n.to_string(), v.clone())).collect()
}

fn two_triangles() -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    (vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], vec![[0, 1, 2], [0, 2, 3]])
}

fn problem_err(mesh: Mesh, spec: ProblemSpec) -> Error {
    Problem::new(mesh, spec).expect_err("must be rejected")
}

#[test]
fn mesh_rules() {
    let (p, t) = two_triangles();
    assert_eq!(Mesh::new(p.clone(), vec![], sets(&[])).unwrap_err(), Error::EmptyMesh);
    let mut bad = p.clone();
    bad[2][1] = f64::NAN;
    assert!(matches!(Mesh::new(bad, t.clone(), sets(&[])).unwrap_err(), Error::NonFiniteCoordinate { node: 2, .. }));
    assert!(matches!(
        Mesh::new(p.clone(), vec![[0, 1, 7]], sets(&[])).unwrap_err(),
        Error::NodeIndexOutOfRange { element: 0, node: 7, .. }
    ));
    let mut flat = p.clone();
    flat.push([0.5, 0.0]);
    assert!(matches!(
        Mesh::new(flat, vec![[0, 4, 1], [0, 1, 2], [0, 2, 3]], sets(&[])).unwrap_err(),
        Error::DegenerateTriangle { element: 0, .. }
    ));
    assert!(matches!(
        Mesh::new(p.clone(), vec![[0, 1, 2], [0, 3, 2]], sets(&[])).unwrap_err(),
        Error::InvertedTriangle { element: 1, .. }
    ));
    let mut extra = p.clone();
    extra.push([5.0, 5.0]);
    assert_eq!(Mesh::new(extra, t.clone(), sets(&[])).unwrap_err(), Error::UnusedNode { node: 4 });
    assert_eq!(
        Mesh::new(p.clone(), vec![[0, 1, 2], [1, 2, 0], [0, 2, 3]], sets(&[])).unwrap_err(),
        Error::DuplicateTriangle { first: 0, second: 1 }
    );
    let e = Mesh::new(p.clone(), t.clone(), sets(&[("diag", vec![[0, 2]])])).unwrap_err();
    assert!(matches!(&e, Error::NotABoundaryEdge { set, index: 0, a: 0, b: 2 } if set == "diag"), "{e}");
    assert!(e.to_string().contains("'diag'"), "{e}");
    assert!(matches!(Mesh::new(p, t, sets(&[("empty", vec![])])).unwrap_err(), Error::EmptyEdgeSet { .. }));
    let e = square().edge_set("topp").unwrap_err();
    assert!(e.to_string().contains("topp") && e.to_string().contains("bottom"), "{e}");
}

#[test]
fn generator_rules() {
    for r in [
        rectangle([0.0, 1.0], [0.0, 1.0], 0, 3, Diagonal::Right),
        rectangle([1.0, 0.0], [0.0, 1.0], 2, 3, Diagonal::Right),
        rectangle([0.0, f64::NAN], [0.0, 1.0], 2, 3, Diagonal::Right),
        graded_rectangle(
            [0.0, 1.0],
            [0.0, 1.0],
            &Grading { side: Side::Top, segment: [0.2, 0.4], h_min: -1.0, h_max: 0.5, growth: 0.3 },
        ),
        graded_rectangle(
            [0.0, 1.0],
            [0.0, 1.0],
            &Grading { side: Side::Top, segment: [0.2, 3.0], h_min: 0.1, h_max: 0.5, growth: 0.3 },
        ),
    ] {
        assert!(matches!(r.unwrap_err(), Error::BadGenerator { .. }));
    }
}

#[test]
fn material_load_and_support_rules() {
    for (young, poisson) in [(0.0, 0.3), (-1.0, 0.3), (f64::NAN, 0.3), (1.0, 0.5), (1.0, -1.0)] {
        let s = ProblemSpec { material: Material { young, poisson }, ..spec() };
        assert!(matches!(problem_err(square(), s), Error::BadMaterial { .. }), "E = {young}, ν = {poisson}");
    }
    let s = ProblemSpec { body_force: [f64::INFINITY, 0.0], ..spec() };
    assert!(matches!(problem_err(square(), s), Error::NonFiniteLoad { .. }));
    let s = ProblemSpec { tractions: vec![("left".into(), [f64::NAN, 0.0].into())], ..spec() };
    assert!(matches!(problem_err(square(), s), Error::NonFiniteLoad { target, .. } if target == "left"));
    let s = ProblemSpec { tractions: vec![("lft".into(), [1.0, 0.0].into())], ..spec() };
    assert!(matches!(problem_err(square(), s), Error::UnknownEdgeSet { name, .. } if name == "lft"));
    // No support at all: the block rests on the foundation under its weight, held by the contact alone;
    // without friction nothing holds it along the foundation, which the solve says by name.
    let s = ProblemSpec { clamped: vec![], ..spec() };
    let resting = Problem::new(square(), s).unwrap();
    assert_eq!(resting.dofs.n_floating(), 3);
    let e = resting.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap_err();
    assert!(
        matches!(&e, Error::HeldOnlyByContact { motion, .. } if motion.contains("translation along (1.000, 0.000)")),
        "{e}"
    );
    assert!(e.to_string().contains("hold that motion with a support"), "{e}");
    let sol = resting.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!((sol.normal_force - 1.0).abs() < 1e-9, "the contact carries the weight: {}", sol.normal_force);
}

#[test]
fn contact_geometry_rules() {
    // An L-shaped set is one chain of edges (a bent Γ_C): accepted, the abscissa its arclength.
    let mut m = square().edge_sets().clone();
    let mut l = m["bottom"].clone();
    l.extend(m["right"].iter().copied());
    m.insert("corner".into(), l);
    let mut loop_ = m["corner"].clone();
    loop_.extend(m["top"].iter().chain(&m["left"]).copied());
    m.insert("loop".into(), loop_);
    let mesh = Mesh::new(square().points().to_vec(), square().triangles().to_vec(), m).unwrap();
    let bent = Problem::new(mesh.clone(), ProblemSpec { contact: "corner".into(), clamped: vec![], ..spec() }).unwrap();
    assert!(!bent.contact.is_straight());
    assert_eq!((bent.contact.start(), bent.contact.length()), (0.0, 2.0));
    // All four sides: a closed loop, accepted (cut at its node of the smallest index), but every support on it
    // overlaps Γ_C.
    let closed = ContactBoundary::new(&mesh, "loop").unwrap();
    assert!(closed.is_closed() && (closed.length() - 4.0).abs() < 1e-12, "{:?}", closed.nodes);
    assert_eq!(Some(&closed.nodes[0]), closed.nodes.iter().min());
    let e = problem_err(mesh, ProblemSpec { contact: "loop".into(), ..spec() });
    assert!(matches!(&e, Error::ContactOverlapsDirichlet { .. }), "{e}");
    // Two separate pieces of the bottom side.
    let mut m = square().edge_sets().clone();
    let b = m["bottom"].clone();
    m.insert("pieces".into(), vec![b[0], b[2]]);
    let mesh = Mesh::new(square().points().to_vec(), square().triangles().to_vec(), m).unwrap();
    assert!(matches!(
        problem_err(mesh, ProblemSpec { contact: "pieces".into(), ..spec() }),
        Error::ContactNotConnected { .. }
    ));
    let s = ProblemSpec { clamped: vec!["bottom".into()], ..spec() };
    assert!(matches!(problem_err(square(), s), Error::ContactOverlapsDirichlet { .. }));
    let s = ProblemSpec { tractions: vec![("bottom".into(), [0.0, 1.0].into())], ..spec() };
    assert!(matches!(problem_err(square(), s), Error::TractionOnContact { .. }));
}

#[test]
fn obstacle_rules() {
    for shape in [
        ObstacleShape::Circle { center: 0.0, radius: 0.0 },
        ObstacleShape::Parabola { center: f64::NAN, radius: 1.0 },
        ObstacleShape::Polyline { xi: vec![0.0, 0.0], gap: vec![0.0, 1.0] },
        ObstacleShape::Polyline { xi: vec![0.0, 1.0], gap: vec![0.0] },
    ] {
        let s = ProblemSpec { obstacle: Obstacle { shape, ..Obstacle::default() }, ..spec() };
        assert!(matches!(problem_err(square(), s), Error::BadObstacle { .. }));
    }
    let s = ProblemSpec { obstacle: Obstacle { approach: f64::NAN, ..Obstacle::default() }, ..spec() };
    assert!(matches!(problem_err(square(), s), Error::BadObstacle { .. }));
    let f = GapFunction(Arc::new(|x: f64| if x > 0.5 { f64::NAN } else { 0.0 }));
    let s = ProblemSpec { obstacle: Obstacle { shape: ObstacleShape::Function(f), ..Obstacle::default() }, ..spec() };
    let e = problem_err(square(), s);
    assert!(matches!(e, Error::BadObstacle { .. }) && e.to_string().contains("abscissa"), "{e}");
}

#[test]
fn multiplier_rules() -> Result<()> {
    let with = |p: MultiplierPoints| problem_err(square(), ProblemSpec { multiplier_points: p, ..spec() });
    assert!(matches!(
        with(MultiplierPoints::Abscissae(vec![0.0, 0.5, 0.4, 1.0])),
        Error::MultiplierPointsNotIncreasing { index: 2, .. }
    ));
    assert!(matches!(
        with(MultiplierPoints::Abscissae(vec![0.0, 0.5, 1.2])),
        Error::MultiplierPointOffContact { index: 2, .. }
    ));
    assert!(matches!(
        with(MultiplierPoints::Points(vec![[0.0, 0.0], [0.5, 0.1], [1.0, 0.0]])),
        Error::MultiplierPointOffContact { index: 1, .. }
    ));
    assert!(matches!(
        with(MultiplierPoints::Abscissae(vec![0.1, 0.5, 1.0])),
        Error::MultiplierMeshDoesNotCover { which: "first", .. }
    ));
    assert!(matches!(
        with(MultiplierPoints::Abscissae(vec![0.0, 0.5, 0.9])),
        Error::MultiplierMeshDoesNotCover { which: "last", .. }
    ));
    for p in [
        MultiplierPoints::Size(0.0),
        MultiplierPoints::RatioToFe(-1.0),
        MultiplierPoints::Abscissae(vec![0.0]),
        MultiplierPoints::Abscissae(vec![0.0, f64::NAN, 1.0]),
    ] {
        assert!(matches!(with(p), Error::BadMultiplierMesh { .. }));
    }
    // Far from the origin a spacing below the resolution of the abscissae (ξ ≈ 1e12, half an ulp 6e-5)
    // would repeat points, or never advance: refused, whichever way T_H is asked for.
    let far = || rectangle([1e12, 1e12 + 1.0], [0.0, 1.0], 4, 4, Diagonal::Right);
    for p in
        [MultiplierPoints::RatioToFe(1.5e-5), MultiplierPoints::RatioToFe(1.0 / 4096.0), MultiplierPoints::Size(1e-5)]
    {
        let e = problem_err(far()?, ProblemSpec { multiplier_points: p.clone(), ..spec() });
        assert!(matches!(e, Error::BadMultiplierMesh { .. }), "{p:?}: {e}");
    }
    Ok(())
}

#[test]
fn settings_rules() {
    let problem = Problem::new(square(), spec()).unwrap();
    let s = SolverSettings::default();
    let bad = |f: &Friction, s: &SolverSettings| problem.solve(f, s, None).expect_err("must be rejected");
    assert!(matches!(bad(&Friction::Coulomb { mu: -0.1 }, &s), Error::BadSetting { name: "mu", .. }));
    assert!(matches!(bad(&Friction::Coulomb { mu: f64::NAN }, &s), Error::BadSetting { name: "mu", .. }));
    assert!(matches!(bad(&Friction::Tresca(Threshold::Uniform(-1.0)), &s), Error::BadThreshold { .. }));
    assert!(matches!(bad(&Friction::Tresca(Threshold::PerDof(vec![1.0; 2])), &s), Error::BadThreshold { .. }));
    let mut t = s;
    t.qp.tol = 0.0;
    assert!(matches!(bad(&Friction::Frictionless, &t), Error::BadSetting { name: "qp_tol", .. }));
    let mut t = s;
    t.fp.relaxation = 1.5;
    assert!(matches!(bad(&Friction::Frictionless, &t), Error::BadSetting { name: "fp_relaxation", .. }));
    let mut t = s;
    t.fp.max_iter = 0;
    assert!(matches!(bad(&Friction::Frictionless, &t), Error::BadSetting { name: "fp_max_iter", .. }));
    for stab in [Stabilization::Gamma0(-1.0), Stabilization::Fraction(1.0), Stabilization::Fraction(f64::NAN)] {
        let t = SolverSettings { stabilization: stab, ..s };
        assert!(matches!(bad(&Friction::Frictionless, &t), Error::BadSetting { .. }), "{stab:?}");
    }
    let bound = problem.gamma0_bound.value;
    let t = SolverSettings { stabilization: Stabilization::Gamma0(1.5 * bound), ..s };
    let e = bad(&Friction::Frictionless, &t);
    assert!(matches!(e, Error::Gamma0TooLarge { element, .. } if element == problem.gamma0_bound.triangle), "{e}");
    assert!(e.to_string().contains(&format!("γ0 < {:.4}", Num(bound))), "the message states the bound: {e}");
}

/// Far beyond the admissible bound K − G is indefinite: the factorization reports it as an error.
#[test]
fn indefinite_stabilized_stiffness_is_an_error() {
    let problem = Problem::new(square(), spec()).unwrap();
    let e = problem.condense(Stabilization::Unchecked(1e3 * problem.gamma0_bound.value)).expect_err("indefinite");
    assert!(matches!(e, Error::NotPositiveDefinite { .. }), "{e}");
}

/// The holes the fuzzing found (issue D-numbers in the comments): each is a typed error now, or an honest
/// status.
#[test]
fn fuzzing_holes_are_typed_errors() {
    let (p, t) = two_triangles();
    // D13: an edge listed twice in a set would count its traction twice.
    let e = Mesh::new(p.clone(), t.clone(), sets(&[("bottom", vec![[0, 1], [1, 0]])])).unwrap_err();
    assert!(matches!(e, Error::DuplicateEdge { first: 0, second: 1, .. }), "{e}");
    // D20: a folded mesh (two triangles on the same side of the edge 0 → 1).
    let mut folded = p.clone();
    folded.push([0.5, 0.5]);
    let e = Mesh::new(folded, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]], sets(&[])).unwrap_err();
    assert!(matches!(e, Error::OverlappingTriangles { first: 0, second: 2, a: 0, b: 1 }), "{e}");
    // Coordinates whose area overflows (an inverted triangle would pass with a NaN area).
    let huge: Vec<[f64; 2]> = p.iter().map(|q| [q[0] * 1e300, q[1] * 1e300]).collect();
    assert!(matches!(Mesh::new(huge, t.clone(), sets(&[])).unwrap_err(), Error::CoordinatesTooLarge { .. }));
    // D1, D19, D11: moduli outside the normal floats or overflowing C; ν within √ε of its limits.
    for (young, poisson) in
        [(1e-310, 0.3), (5e-324, 0.3), (1e308, 0.3), (1.0, 0.499_999_999_999_999), (1.0, -0.999_999_999_9)]
    {
        let s = ProblemSpec { material: Material { young, poisson }, ..spec() };
        assert!(matches!(problem_err(square(), s), Error::BadMaterial { .. }), "E = {young:e}, ν = {poisson}");
    }
    // D10: a piece joined to the rest at one node moves freely.
    let pts = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]];
    let tris = vec![[0, 1, 2], [0, 2, 3], [2, 4, 5], [2, 5, 6]];
    let mesh = Mesh::new(pts, tris, sets(&[("bottom", vec![[0, 1]]), ("top", vec![[5, 6]])])).unwrap();
    let s = ProblemSpec { clamped: vec!["bottom".into()], contact: "top".into(), ..spec() };
    let e = problem_err(mesh, s);
    assert!(matches!(e, Error::FloatingPiece { triangles: 2, pieces: 2, .. }), "{e}");
    // D12: every node of Γ_C clamped.
    let one = rectangle([0.0, 1.0], [0.0, 1.0], 1, 1, Diagonal::Right).unwrap();
    let s = ProblemSpec { clamped: vec!["left".into(), "right".into()], contact: "top".into(), ..spec() };
    assert!(matches!(problem_err(one, s), Error::ContactFullyClamped { .. }));
    // D4: a load that overflows is refused, or (when only the solution overflows) reported non_finite.
    let s = ProblemSpec { body_force: [f64::MAX, 0.0], ..spec() };
    match Problem::new(square(), s) {
        Err(e) => assert!(matches!(e, Error::NonFiniteLoad { .. }), "{e}"),
        Ok(p) => {
            let sol = p.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
            assert_ne!(sol.report.status, SolveStatus::Converged, "overflowing fields reported converged");
        }
    }
    // D6: a gap function that is NaN only at the nodes of Γ_C.
    let nodes: Vec<f64> = (0..=4).map(|i| i as f64 / 4.0).collect();
    let gap = move |xi: f64| if nodes.iter().any(|x| (x - xi).abs() < 1e-12) { f64::NAN } else { 0.0 };
    let obstacle = Obstacle {
        shape: ObstacleShape::Function(GapFunction(Arc::new(gap))),
        approach: 0.0,
        shift: 0.0,
        rotation: None,
    };
    assert!(matches!(problem_err(square(), ProblemSpec { obstacle, ..spec() }), Error::BadObstacle { .. }));
    // D2, D3: multiplier meshes too fine to build are refused before anything is allocated.
    for points in [MultiplierPoints::RatioToFe(1e-20), MultiplierPoints::Size(1e-300), MultiplierPoints::Size(1e-12)] {
        let e = problem_err(square(), ProblemSpec { multiplier_points: points.clone(), ..spec() });
        assert!(matches!(e, Error::BadMultiplierMesh { .. }) && e.to_string().contains("e"), "{points:?}: {e}");
    }
    // D3: a dense QP beyond the memory budget is refused with the size it would need.
    let fine = MultiplierPoints::Abscissae((0..=20_000).map(|i| i as f64 / 20_000.0).collect());
    let problem = Problem::new(square(), ProblemSpec { multiplier_points: fine, ..spec() }).unwrap();
    let settings = SolverSettings { memory_budget: 64 << 20, ..Default::default() };
    match problem.solve(&Friction::Frictionless, &settings, None).unwrap_err() {
        Error::MemoryBudget { needed, budget, .. } => assert!(needed > budget && budget == (64 << 20) as f64),
        e => panic!("{e}"),
    }
    // D3: the saddle-point path on the same problem: its 20,001 multipliers on the square's few FE edges
    // couple thousands of multiplier unknowns to one displacement dof, a clique of the factor beyond the
    // budget, refused before the symbolic analysis (which took 56 s for 200k multipliers before).
    let settings = SolverSettings { memory_budget: 64 << 20, condensation: Condensation::Saddle, ..Default::default() };
    match problem.solve(&Friction::Frictionless, &settings, None).unwrap_err() {
        Error::MemoryBudget { what, needed, budget } => {
            assert!(needed > budget && what.contains("couple to one displacement dof"), "{what}")
        }
        e => panic!("{e}"),
    }
    // D3: a factorization beyond the memory budget is refused after its symbolic analysis, before its
    // values are allocated, with the size it would need: the plain factor (H by columns) and the partial
    // one (the Γ_C dofs last), on 20,000 unknowns (a factor of about 10 MB) against 4 MiB (more than the dense
    // H of its 202 multipliers needs).
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 100, 100, Diagonal::Right).unwrap();
    let problem = Problem::new(mesh, spec()).unwrap();
    for condensation in [Condensation::Columns, Condensation::Schur] {
        let settings = SolverSettings { memory_budget: 4 << 20, condensation, ..Default::default() };
        match problem.solve(&Friction::Frictionless, &settings, None).unwrap_err() {
            Error::MemoryBudget { what, needed, budget } => {
                assert!(needed > budget && budget == (4 << 20) as f64 && what.contains("factor of A = K − G"), "{what}")
            }
            e => panic!("{condensation:?}: {e}"),
        }
    }
    // The same problem within the default budget (the memory this machine has available) solves.
    let sol = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
}

/// The memory budget bounds the sum of what a solve holds at once, not each dense part on its own: an
/// adaptive loop whose contact zone kept refining was killed by the kernel at 24 GB while its H (held by the
/// partial factorization) and its dense QP each fitted the 22 GB budget.
#[test]
fn the_memory_budget_bounds_the_sum_of_the_dense_parts() {
    // 401 P1 multiplier dofs: all of H (802² values, 5.1 MB) from the partial factorization, and a
    // frictionless QP over every dof (no working set): 4 q² values (5.1 MB) of its own.
    let fine = MultiplierPoints::Abscissae((0..=400).map(|i| i as f64 / 400.0).collect());
    let problem = Problem::new(square(), ProblemSpec { multiplier_points: fine, ..spec() }).unwrap();
    let q = problem.n_multipliers() as f64;
    let qp = QpSettings { working_set: false, ..Default::default() };
    let settings = SolverSettings { condensation: Condensation::Schur, qp, ..Default::default() };
    let sol = problem.solve(&Friction::Frictionless, &settings, None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    // The factorization stays cached: its values and all 2q columns of H.
    let held = problem.held_bytes();
    assert!(held >= 8.0 * (2.0 * q).powi(2), "{held} bytes held");
    // A budget that holds H and the factor, and the QP's dense parts on their own (counted as 8 (2q·q + 4q²)
    // bytes, its columns of H included, they fit: 48 q² ≤ 32 q² + 16 q²), but not both.
    let qp_bytes = 8.0 * 4.0 * q * q;
    for (budget, fits) in [(held + 0.5 * qp_bytes, false), (held + 1.01 * qp_bytes, true)] {
        let settings = SolverSettings { memory_budget: budget as usize, ..settings };
        let result = problem.solve(&Friction::Frictionless, &settings, None);
        match result {
            Ok(sol) if fits => assert_eq!(sol.report.status, SolveStatus::Converged),
            Err(Error::MemoryBudget { what, needed, .. }) if !fits => {
                assert!(what.contains("beside the factor of A"), "{what}");
                assert!((needed - (held + qp_bytes)).abs() <= 1e-9 * needed, "{needed} against {}", held + qp_bytes);
            }
            other => panic!("budget {budget}: {other:?}"),
        }
    }
    // The enriched problem of an estimate is solved beside this problem's factorization: a budget that
    // leaves it less than 1 MiB is refused before anything is built.
    let settings = SolverSettings { memory_budget: (held + 1e5) as usize, ..settings };
    match problem.estimate_hierarchical(&sol, &Friction::Frictionless, &settings).unwrap_err() {
        Error::MemoryBudget { what, .. } => assert!(what.contains("enriched problem"), "{what}"),
        e => panic!("{e}"),
    }
}

/// Under `auto`, a partial factorization (all of H at once) that the memory budget cannot hold leaves H to
/// the plain factor's columns: `auto` never fails where the plain path solves, and asked for, the partial
/// factorization beyond the budget is a typed error.
#[test]
fn auto_falls_back_to_columns_when_the_partial_factor_exceeds_the_budget() {
    // 81 P1 multiplier dofs on an 80 × 80 square pushed all along its base: H is small beside K's factor.
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], 80, 80, Diagonal::Right).unwrap();
    let problem = || Problem::new(mesh.clone(), spec()).unwrap();
    let with = |condensation, memory_budget| SolverSettings { condensation, memory_budget, ..Default::default() };
    let held = |condensation| {
        let p = problem();
        let sol = p.solve(&Friction::Frictionless, &with(condensation, usize::MAX), None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged);
        (p.held_bytes(), sol.report.condensation)
    };
    let (schur, chosen) = held(Condensation::Auto);
    assert_eq!(chosen, Condensation::Schur, "auto forms all of H on a fully pushed side");
    let (plain, _) = held(Condensation::Columns);
    assert!(plain < schur, "{plain} ≥ {schur}");
    let (mut fell_back, mut refused) = (0, 0);
    for i in 0..=24 {
        let budget = (plain * (4.0 * schur / plain).powf(f64::from(i) / 24.0)) as usize;
        let columns = problem().solve(&Friction::Frictionless, &with(Condensation::Columns, budget), None);
        let auto = problem().solve(&Friction::Frictionless, &with(Condensation::Auto, budget), None);
        let asked = problem().solve(&Friction::Frictionless, &with(Condensation::Schur, budget), None);
        match (&columns, &auto) {
            (Ok(c), Ok(a)) => {
                assert_eq!((c.report.status, a.report.status), (SolveStatus::Converged, SolveStatus::Converged));
                let apart = c.lambda_n.iter().zip(&a.lambda_n).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
                assert!(apart <= 1e-6 * c.lambda_n.iter().fold(0.0, |m, x| x.abs().max(m)), "{apart}");
                if a.report.condensation == Condensation::Columns {
                    fell_back += 1;
                }
            }
            (Ok(_), Err(e)) => panic!("budget {budget}: auto failed where the plain path solves: {e}"),
            (Err(Error::MemoryBudget { .. }), _) => {}
            (Err(e), _) => panic!("budget {budget}: {e}"),
        }
        match asked {
            Err(Error::MemoryBudget { .. }) => refused += 1,
            Ok(sol) => assert_eq!(sol.report.status, SolveStatus::Converged),
            Err(e) => panic!("budget {budget}: {e}"),
        }
    }
    assert!(fell_back > 0 && refused > 0, "{fell_back} fallbacks, {refused} refusals of the partial factorization");
}

/// A Solution reports the gap, von Mises and KKT residuals that do not overflow or divide by a
/// vanishing scale.
#[test]
fn results_stay_finite_at_the_limits() {
    // D5: von Mises of huge stresses without overflow.
    let m = Material { young: 1.0, poisson: 0.3 };
    let v = m.von_mises([1e300, -1e300, 1e300]);
    assert!(v.is_finite() && v > 1e300, "{v:e}");
    assert_eq!(m.von_mises([0.0; 3]), 0.0);
    // E = 1e300: H ~ 1/E, the normal scale ~ E; the scaling of the QP must not overflow (an overflowed
    // scaling once certified λ = 0 at once).
    let obstacle = Obstacle { approach: 0.01, ..Obstacle::default() };
    let s = ProblemSpec { material: Material { young: 1e300, poisson: 0.3 }, obstacle, ..spec() };
    let sol = Problem::new(square(), s).unwrap().solve(&Friction::Frictionless, &SolverSettings::default(), None);
    let sol = sol.unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert!(sol.von_mises.iter().all(|v| v.is_finite()) && sol.von_mises.iter().any(|v| *v > 1e290));
    // Nothing in contact: λ = 0, every residual 0 (it was NaN = 0/0).
    let s = ProblemSpec { body_force: [0.0, 0.0], ..spec() };
    let sol = Problem::new(square(), s).unwrap().solve(&Friction::Frictionless, &SolverSettings::default(), None);
    let sol = sol.unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert_eq!(sol.kkt.max(), 0.0, "{:?}", sol.kkt);
    // A Tresca threshold 1e38 times the multiplier (a shift of 1e-39), nothing pushing normally: λ_t
    // follows the shift. clarabel makes no progress on a box 1e38 times the answer (an honest qp_failed);
    // the active-set method solves it, and under auto it takes over from clarabel.
    let s =
        ProblemSpec { body_force: [0.0, 0.0], obstacle: Obstacle { shift: 1e-39, ..Obstacle::default() }, ..spec() };
    let problem = Problem::new(square(), s).unwrap();
    for method in [QpMethod::Clarabel, QpMethod::ActiveSet, QpMethod::Auto] {
        let settings = SolverSettings { qp: QpSettings { method, ..Default::default() }, ..Default::default() };
        let sol = problem.solve(&Friction::Tresca(Threshold::Uniform(1.0)), &settings, None).unwrap();
        if method == QpMethod::Clarabel && matches!(sol.report.status, SolveStatus::QpFailed { .. }) {
            continue;
        }
        assert_eq!(sol.report.status, SolveStatus::Converged, "{method}: {:?}", sol.kkt);
        assert!(sol.kkt.max() < 1e-6 && sol.lambda_t.iter().any(|l| *l != 0.0), "{method}: {:?}", sol.kkt);
    }
}

#[test]
fn support_rules() {
    // spec(): clamped on the top, contact on the bottom; here the supports replace the clamp.
    let with = |supports: Vec<Support>| ProblemSpec { clamped: vec![], supports, ..spec() };
    // An unknown set.
    let e = problem_err(square(), with(vec![Support::roller("lft")]));
    assert!(matches!(&e, Error::UnknownEdgeSet { name, .. } if name == "lft"), "{e}");
    // A roller on an L-shaped (not straight) set.
    let mut m = square().edge_sets().clone();
    let mut l = m["top"].clone();
    l.extend(m["right"].iter().copied());
    m.insert("corner".into(), l);
    let corner = Mesh::new(square().points().to_vec(), square().triangles().to_vec(), m).unwrap();
    let e = problem_err(corner, with(vec![Support::roller("corner")]));
    assert!(matches!(&e, Error::SupportNotStraight { set, .. } if set == "corner"), "{e}");
    // A displacement without a component, or with a non-finite one.
    for (x, y) in [(None, None), (Some(f64::NAN), None), (None, Some(f64::INFINITY))] {
        let e = problem_err(square(), with(vec![Support::displacement("top", x, y)]));
        assert!(matches!(&e, Error::BadSupport { set, .. } if set == "top"), "{e}");
    }
    // Conflicting conditions at a corner: the top clamped, the left side pushed down (node 20 is (0, 1)).
    let s = with(vec![Support::clamp("top"), Support::displacement("left", None, Some(-0.01))]);
    let e = problem_err(square(), s);
    assert!(
        matches!(&e, Error::ConflictingSupports { node: 20, first, second, .. } if first == "top" && second == "left"),
        "{e}"
    );
    // Nearly parallel conditions at a corner: u_x = 0.01 on the top and a roller on the right side
    // tilted by atan θ from the vertical (x = 1 + θ y) fix the corner (1 + θ, 1) at u = (0.01, ±0.01 / θ). At θ = 1e-6
    // that is 1e4 on a body of size √2: refused, naming the node and the angle. At θ = 0.01 the corner
    // moves by 1 (within the body: accepted), exactly parallel conditions conflict, and homogeneous ones
    // (the top clamped) fix the corner at 0 whatever the angle.
    let tilted = |theta: f64| {
        let m = square();
        let pts = m.points().iter().map(|p| if p[0] == 1.0 { [1.0 + theta * p[1], p[1]] } else { *p }).collect();
        Mesh::new(pts, m.triangles().to_vec(), m.edge_sets().clone()).unwrap()
    };
    let pushed = || with(vec![Support::displacement("top", Some(0.01), None), Support::roller("right")]);
    let e = problem_err(tilted(1e-6), pushed());
    assert!(
        matches!(&e, Error::NearlyParallelSupports { node: 24, first, second, angle_degrees, displacement, size, .. }
            if first == "top" && second == "right" && (angle_degrees.to_radians() / 1e-6 - 1.0).abs() < 1e-6
                && (displacement / 1e4 - 1.0).abs() < 1e-6 && (size - 2f64.sqrt()).abs() < 1e-5),
        "{e}"
    );
    assert!(e.to_string().contains("node 24") && e.to_string().contains("5.730e-5°"), "{e}");
    let sol = Problem::new(tilted(0.01), pushed()).unwrap();
    let corner = &sol.dofs.lifting[48..50];
    assert!((corner[0] - 0.01).abs() < 1e-15 && (corner[1].abs() - 1.0).abs() < 1e-12, "{corner:?}");
    assert!(matches!(problem_err(tilted(0.0), pushed()), Error::ConflictingSupports { node: 24, .. }));
    let clamped = with(vec![Support::clamp("top"), Support::roller("right")]);
    assert!(Problem::new(tilted(1e-6), clamped).is_ok());
    // The same with compatible values is accepted: a roller along the left side and the top clamped.
    let s = with(vec![Support::clamp("top"), Support::roller("left")]);
    assert!(Problem::new(square(), s).is_ok());
    // Two parallel rollers leave a translation along them free: held by the contact (Γ_C the bottom), under
    // the body's weight. Off the contact, the same rollers leave a piece free: refused, naming the motion.
    let held = Problem::new(square(), with(vec![Support::roller("left"), Support::roller("right")])).unwrap();
    assert_eq!(held.dofs.n_floating(), 1);
    let sol = held.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap();
    assert!(sol.report.status == SolveStatus::Converged && (sol.normal_force - 1.0).abs() < 1e-9);
    let pts = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.0], [3.0, 0.0], [3.0, 1.0], [2.0, 1.0]];
    let tris = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let two = sets(&[("top", vec![[3, 2]]), ("bottom", vec![[0, 1]]), ("l2", vec![[7, 4]]), ("r2", vec![[5, 6]])]);
    let mesh = Mesh::new(pts, tris, two).unwrap();
    let s = ProblemSpec {
        clamped: vec!["top".into()],
        supports: vec![Support::roller("l2"), Support::roller("r2")],
        ..spec()
    };
    let e = problem_err(mesh, s);
    assert!(
        matches!(&e, Error::RigidMotion { triangles: 2, pieces: 2, motion, .. } if motion.contains("translation along (0")),
        "{e}"
    );
    // One roller on the top leaves the translation along it free, which only friction could hold; with a
    // roller on the left it is held.
    let along = Problem::new(square(), with(vec![Support::roller("top")])).unwrap();
    let e = along.solve(&Friction::Frictionless, &SolverSettings::default(), None).unwrap_err();
    assert!(matches!(&e, Error::HeldOnlyByContact { .. }), "{e}");
    assert!(Problem::new(square(), with(vec![Support::roller("top"), Support::roller("left")])).is_ok());
    // A piece held at a single node turns about it: two squares joined at node 2 = (1, 1), the first
    // clamped on its bottom and its right side, which fixes node 2 but no other node of the second.
    let pts = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]];
    let tris = vec![[0, 1, 2], [0, 2, 3], [2, 4, 5], [2, 5, 6]];
    let joined = sets(&[("bottom", vec![[0, 1]]), ("side", vec![[1, 2]]), ("top", vec![[5, 6]])]);
    let mesh = Mesh::new(pts, tris, joined).unwrap();
    let s = ProblemSpec { clamped: vec!["bottom".into(), "side".into()], contact: "top".into(), ..spec() };
    let e = problem_err(mesh, s);
    assert!(
        matches!(&e, Error::RigidMotion { node: 2, triangles: 2, pieces: 2, motion, .. } if motion == "a rotation about (1.0000e0, 1.0000e0)"),
        "{e}"
    );
    // A support on Γ_C.
    let e = problem_err(square(), with(vec![Support::clamp("top"), Support::roller("bottom")]));
    assert!(matches!(e, Error::ContactOverlapsDirichlet { .. }), "{e}");
}

#[test]
fn a_floating_piece_is_named() {
    // Two disjoint squares, only the first one supported: refused at the door, naming the second piece
    // (its first triangle and its size), never as a failed factorization that blames the stabilization.
    let pts = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.0], [3.0, 0.0], [3.0, 1.0], [2.0, 1.0]];
    let tris = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let mesh = Mesh::new(pts, tris, sets(&[("bottom", vec![[0, 1]]), ("top", vec![[3, 2]])])).unwrap();
    let s = ProblemSpec { clamped: vec!["bottom".into()], contact: "top".into(), ..spec() };
    let e = problem_err(mesh, s);
    assert_eq!(e, Error::FloatingPiece { triangle: 2, node: 4, triangles: 2, pieces: 2 });
    assert!(e.to_string().contains("has no support"), "{e}");
}

/// The multiplier points come from one keyword at most: every pair of `multiplier_ratio`,
/// `multiplier_size` and `multiplier_points` (and all three) is refused by the core with a typed error,
/// and one alone (or none) gives its points.
#[test]
fn multiplier_keywords_exclude_each_other() {
    let points = || Some(MultiplierPoints::Abscissae(vec![0.0, 0.5, 1.0]));
    for (ratio, size, explicit) in [
        (Some(1.0), Some(0.1), None),
        (Some(1.0), None, points()),
        (None, Some(0.1), points()),
        (Some(1.0), Some(0.1), points()),
    ] {
        let e = MultiplierPoints::from_keywords(ratio, size, explicit).expect_err("two keywords");
        assert!(matches!(&e, Error::BadMultiplierMesh { what } if what.contains("at most one")), "{e}");
        assert_eq!(e.category(), error::ErrorCategory::ContactGeometry);
    }
    assert_eq!(MultiplierPoints::from_keywords(Some(2.0), None, None), Ok(MultiplierPoints::RatioToFe(2.0)));
    assert_eq!(MultiplierPoints::from_keywords(None, Some(0.1), None), Ok(MultiplierPoints::Size(0.1)));
    assert_eq!(MultiplierPoints::from_keywords(None, None, points()), Ok(points().unwrap()));
    assert_eq!(MultiplierPoints::from_keywords(None, None, None), Ok(MultiplierPoints::default()));
}

/// A gap function that turns NaN after the set-up, except at the FE nodes of Γ_C: the error estimate
/// evaluates it between the points the set-up checked, and a solve whose estimate is not finite is not
/// reported converged.
#[test]
fn a_gap_that_fails_between_the_checked_points_is_not_converged() -> Result<()> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let broken = Arc::new(AtomicBool::new(false));
    let flag = broken.clone();
    let gap = move |x: f64| {
        // The bottom of the unit square, 4 edges: nodes at multiples of 1/4.
        let at_node = ((4.0 * x) - (4.0 * x).round()).abs() < 1e-12;
        if flag.load(Ordering::Relaxed) && !at_node {
            f64::NAN
        } else {
            0.01 * (x - 0.5).powi(2)
        }
    };
    let obstacle = Obstacle {
        shape: ObstacleShape::Function(GapFunction(Arc::new(gap))),
        approach: 0.01,
        shift: 0.0,
        rotation: None,
    };
    let problem = Problem::new(square(), ProblemSpec { obstacle, ..spec() })?;
    let settings = SolverSettings::default();
    let sound = problem.solve(&Friction::Frictionless, &settings, None)?;
    assert_eq!(sound.report.status, SolveStatus::Converged);
    assert!(sound.report.estimate.total.is_finite() && sound.report.estimate.total > 0.0);
    broken.store(true, Ordering::Relaxed);
    let sol = problem.solve(&Friction::Frictionless, &settings, None)?;
    assert!(sol.report.estimate.total.is_nan(), "the estimate read the gap between the nodes");
    assert_eq!(sol.report.status, SolveStatus::NonFinite);
    Ok(())
}

/// The public `BoxQp` refuses data of the wrong size with a typed error (its sizes were debug
/// assertions: a release build indexed out of range).
#[test]
fn a_box_qp_of_the_wrong_size_is_an_error() -> Result<()> {
    let s = QpSettings::default();
    let h = [2.0, 0.0, 0.0, 2.0];
    assert!(matches!(tribo::qp::BoxQp::new(&h[..3], &[-1.0, -1.0], 2, None, &s), Err(Error::QpSetup { .. })));
    assert!(matches!(tribo::qp::BoxQp::new(&h, &[-1.0], 2, None, &s), Err(Error::QpSetup { .. })));
    let mut frictionless = tribo::qp::BoxQp::new(&h, &[-1.0, -1.0], 2, None, &s)?;
    assert!(matches!(frictionless.set_bounds(&[1.0, 1.0]), Err(Error::QpSetup { .. })));
    let one = tribo::qp::BoxQp::new(&h, &[-1.0, 0.5], 1, Some(&[1.0]), &s)?;
    assert!(matches!(one.with_equality(vec![1.0; 3], vec![0.0]), Err(Error::QpSetup { .. })));
    Ok(())
}
