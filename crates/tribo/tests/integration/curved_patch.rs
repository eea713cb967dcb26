//! Patch tests across a circular interface (issue 39): a uniform pressure passes a faceted arc exactly.
//!
//! A constant stress `σ = −p I` meets every facet of a faceted arc with the traction `−p n_f`, each facet along its
//! own normal, so it is in the discrete space whatever the facets: P1 displacements `u = −e x` (plane strain,
//! `e = p / (2 (λ + μ))`), P0 or P1 multipliers `λ_n = p`, `λ_t = 0`, and the Barbosa–Hughes term `λ + σ(u) n`
//! zero. On uniform facets of an arc of radius R each facet lies at `d = R cos(Δθ/2)` from the centre, so
//! `u · n_f = −e d` is the same on all of them: one constant gap closes them all at once.
//!
//! * **One body**: a quarter ring (radii 0.5–1, rollers on its radial sides) pressed into a rigid hole of its
//!   outer radius by δ (the gap measured from the ring's circle: −δ everywhere), its inner arc under the pressure
//!   `p = 2 (λ + μ) δ / d` of that closure ([`Traction::Pressure`]). The answer is the uniform state to round-off,
//!   with γ0 = 0 and the default, P0 and P1; with Coulomb friction too for P0 multipliers (below for P1).
//! * **A full ring held by the contact alone** (no supports; frictionless contact cannot hold its rotation and is
//!   refused), with Coulomb friction: a closed loop has no ends, and P1 is exact too.
//! * **Two bodies**: that ring inside a quarter ring (radii 1–1.5) whose inner arc has the same nodes, touching,
//!   both under the pressure p on their free arcs, of two materials with one plane-strain bulk modulus
//!   `E / ((1 + ν)(1 − 2ν))` (so that `−p I` strains both alike and the interface stays closed): exact, P0 and P1,
//!   frictionless and with Coulomb friction.
//!
//! **With friction, P1 and an open chain against a rigid obstacle, the test does not pass, and it says why**: each
//! end node of an open bent chain moves along the radius, which is not its one edge's normal (they differ by half
//! the facet's angle), so `u · t_e` there reads a slip of about `e R sin(Δθ/2)` that the continuum does not have;
//! holding it back takes a traction of the order of p, so the end dofs slip at `λ_t = μ λ_n` (measured: 0.30 p at
//! μ = 0.3, whatever h), and the answer departs inward from there. At interior nodes of uniform facets the two
//! edges' readings cancel, and a P0 cell reads one facet, over which `u · t_e` is odd about its middle. The test
//! below measures this so that a fix (the curve's normal at a chain's end node) shows.
//!
//! **Two bodies with a gap or an interference between them** cannot carry `−p I` exactly either: the mortar hands
//! the secondary side's `∫ ψ λ` to the primary, whose arc is longer by `(R + δ)/R`, so the primary sees `p R/(R + δ)`
//! (measured 8e-4 off at δ/R = 1e-3). That is the small-strain model's own O(δ/R), not an error of the discretization.
//!
//! Non-matching faceted arcs cannot carry a uniform pressure exactly (their facets are not parallel); the shrink
//! fit against Lamé (`bent_pair.rs`) converges instead.

use std::f64::consts::FRAC_PI_2;

use tribo::*;

const NU: f64 = 0.3;

/// `2 (λ + μ)` of plane strain: the modulus of `σ = −p I` against `ε = −e I`.
fn bulk(young: f64) -> f64 {
    let (lambda, mu) = (young * NU / ((1.0 + NU) * (1.0 - 2.0 * NU)), young / (2.0 * (1.0 + NU)));
    2.0 * (lambda + mu)
}

/// A quarter ring from angle 0.3, uniform at `h` along its outer arc (angles `h / r_out` apart on every arc),
/// its arcs on their circles, on rollers on its radial sides.
fn quarter_ring(radii: [f64; 2], h: f64) -> Mesh {
    let sector = RingSector { center: [0.0, 0.0], radii, angles: [0.3, 0.3 + FRAC_PI_2] };
    ring_sector(&sector, &ArcGrading { angles: sector.angles, h_min: h, h_max: h, growth: 0.1 }).expect("a ring")
}

/// The facets' distance from the centre on the arc of `radius` of `mesh` (`set`), checked equal on all of them.
fn facet_distance(mesh: &Mesh, set: &str) -> f64 {
    let pts = mesh.points();
    let d: Vec<f64> = mesh
        .edge_set(set)
        .expect("the set")
        .iter()
        .map(|&[a, b]| {
            let (pa, pb) = (pts[a], pts[b]);
            ((pa[0] * pb[1] - pa[1] * pb[0]) / (pb[0] - pa[0]).hypot(pb[1] - pa[1])).abs()
        })
        .collect();
    let spread = d.iter().fold(0.0_f64, |m, x| m.max((x - d[0]).abs()));
    assert!(spread <= 1e-14, "uniform facets on {set}: spread {spread:e}");
    d[0]
}

/// The largest departure of `sol` from the uniform state `−p I`, `u = −e x`, relative to p and to e.
fn departure(mesh: &Mesh, sol: &Solution, p: f64, e: f64) -> f64 {
    let stress = sol.stress.iter().map(|s| (s[0] + p).abs().max((s[1] + p).abs()).max(s[2].abs()) / p);
    let u = mesh.points().iter().enumerate().map(|(i, x)| {
        let v = sol.node_displacement(i);
        (v[0] + e * x[0]).abs().max((v[1] + e * x[1]).abs()) / e
    });
    let lambda = sol.lambda_n.iter().map(|l| (l - p).abs() / p).chain(sol.lambda_t.iter().map(|l| l.abs() / p));
    stress.chain(u).chain(lambda).fold(0.0, f64::max)
}

#[test]
fn a_uniform_pressure_passes_a_faceted_arc_against_a_rigid_hole_exactly() {
    let (young, delta) = (1.0, 1e-3);
    let mesh = quarter_ring([0.5, 1.0], 0.05);
    let d = facet_distance(&mesh, "outer");
    let (e, p) = (delta / d, bulk(young) * delta / d);
    for space in [MultiplierSpace::P1, MultiplierSpace::P0] {
        let spec = ProblemSpec::new(Material { young, poisson: NU }, "outer")
            .support(Support::roller("start"))
            .support(Support::roller("end"))
            .traction("inner", Traction::Pressure(p))
            .obstacle(ObstacleShape::Hole { center: [0.0, 0.0], radius: 1.0 })
            .approach(delta)
            .multipliers(MultiplierPoints::RatioToFe(1.0), space);
        let problem = Problem::new(mesh.clone(), spec).expect("a ring in a hole");
        for stabilization in [Stabilization::None, Stabilization::default()] {
            let settings = SolverSettings { stabilization, ..SolverSettings::default() };
            let sol = problem.solve(&Friction::Frictionless, &settings, None).expect("solves");
            assert_eq!(sol.report.status, SolveStatus::Converged);
            let off = departure(&problem.mesh, &sol, p, e);
            eprintln!("one body, {space:?}, {stabilization:?}: off the uniform state by {off:.1e}");
            assert!(off < 1e-10, "{space:?} {stabilization:?}: {off:e}");
        }
        // With friction: P0 exact (each cell one facet, over which u · t_e is odd about its middle); P1 slips at the
        // ends of the chain (the module documentation), and from there inward.
        let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).expect("solves");
        assert_eq!(sol.report.status, SolveStatus::Converged);
        let slipping: Vec<usize> = (0..sol.lambda_t.len()).filter(|&j| sol.lambda_t[j].abs() > 1e-6 * p).collect();
        let last = sol.lambda_t.len() - 1;
        let off = departure(&problem.mesh, &sol, p, e);
        eprintln!("one body, {space:?}, Coulomb: off by {off:.1e}, λ_t ≠ 0 at dofs {slipping:?} of 0..={last}");
        if space == MultiplierSpace::P0 {
            assert!(off < 1e-10, "P0, Coulomb: {off:e}");
        } else {
            assert!(slipping.contains(&0) && slipping.contains(&last), "the ends slip: {slipping:?}");
            assert!((sol.lambda_t[0].abs() / sol.lambda_n[0] - 0.3).abs() < 1e-6, "at μ λ_n");
        }
    }
}

#[test]
fn a_uniform_pressure_passes_a_curved_interface_between_two_bodies_exactly() {
    // Two materials of one plane-strain bulk modulus E / ((1 + ν)(1 − 2ν)): −p I strains both alike.
    let (inner, outer) =
        (Material { young: 1.0, poisson: NU }, Material { young: 1.25 * 0.5 / (1.3 * 0.4), poisson: 0.25 });
    let bulk_of = |m: Material| m.young / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
    assert!((bulk_of(inner) / bulk_of(outer) - 1.0).abs() < 1e-14);
    let (b, c, h, p) = (1.0, 1.5, 0.05, 1e-3);
    let e = p / bulk_of(inner);
    let inner_mesh = quarter_ring([0.5, b], h);
    // The outer ring's divisions along its outer arc: as many as the inner ring's, so that its inner arc has the
    // inner ring's nodes.
    let outer_mesh = quarter_ring([b, c], h * c / b);
    let arc_nodes = |mesh: &Mesh, set: &str| {
        let mut x: Vec<[f64; 2]> =
            mesh.edge_set(set).expect("the set").iter().flatten().map(|&i| mesh.points()[i]).collect();
        x.sort_by(|u, v| u[1].atan2(u[0]).total_cmp(&v[1].atan2(v[0])));
        x.dedup();
        x
    };
    let (ai, ao) = (arc_nodes(&inner_mesh, "outer"), arc_nodes(&outer_mesh, "inner"));
    assert_eq!(ai.len(), ao.len());
    let apart = ai.iter().zip(&ao).map(|(u, v)| (u[0] - v[0]).hypot(u[1] - v[1])).fold(0.0, f64::max);
    assert!(apart < 1e-14, "the arcs' nodes coincide: {apart:e}");
    let body = |name: &str, mesh: Mesh, material: Material, pressed: &str| Body {
        name: name.into(),
        materials: Materials::uniform(material, mesh.n_triangles()),
        mesh,
        clamped: vec![],
        supports: vec![Support::roller("start"), Support::roller("end")],
        tractions: vec![(pressed.into(), Traction::Pressure(p))],
    };
    for space in [MultiplierSpace::P1, MultiplierSpace::P0] {
        let pair = ContactPair {
            secondary: "inner.outer".into(),
            primary: "outer.inner".into(),
            gap: ObstacleShape::Flat,
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            multiplier_space: space,
            model: Model::PlaneStrain,
            formulation: Default::default(),
        };
        let bodies =
            [body("inner", inner_mesh.clone(), inner, "inner"), body("outer", outer_mesh.clone(), outer, "outer")];
        let problem = Problem::two_bodies(bodies, pair, [0.0, 0.0]).expect("two rings");
        for stabilization in [Stabilization::None, Stabilization::default()] {
            let settings = SolverSettings { stabilization, ..SolverSettings::default() };
            for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
                let sol = problem.solve(&friction, &settings, None).expect("solves");
                assert_eq!(sol.report.status, SolveStatus::Converged);
                let off = departure(&problem.mesh, &sol, p, e);
                eprintln!("two bodies, {space:?}, {stabilization:?}, {friction:?}: off the uniform state by {off:.1e}");
                assert!(off < 1e-10, "{space:?} {stabilization:?} {friction:?}: {off:e}");
            }
        }
    }
}

#[test]
fn a_full_ring_held_by_friction_alone_carries_a_uniform_pressure_exactly() {
    let (young, delta) = (1.0, 1e-3);
    let turn = 2.0 * std::f64::consts::PI;
    let sector = RingSector { center: [0.0, 0.0], radii: [0.5, 1.0], angles: [0.0, turn] };
    let grading = ArcGrading { angles: [0.0, turn], h_min: 0.05, h_max: 0.05, growth: 0.1 };
    let mesh = ring_sector(&sector, &grading).expect("a ring");
    let d = facet_distance(&mesh, "outer");
    let (e, p) = (delta / d, bulk(young) * delta / d);
    let spec = ProblemSpec::new(Material { young, poisson: NU }, "outer")
        .traction("inner", Traction::Pressure(p))
        .obstacle(ObstacleShape::Hole { center: [0.0, 0.0], radius: 1.0 })
        .approach(delta);
    let problem = Problem::new(mesh, spec).expect("a ring in a hole");
    let refused = problem.solve(&Friction::Frictionless, &SolverSettings::default(), None).expect_err("refused");
    assert!(matches!(refused, Error::HeldOnlyByContact { .. }), "{refused}");
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).expect("solves");
    assert_eq!(sol.report.status, SolveStatus::Converged);
    let off = departure(&problem.mesh, &sol, p, e);
    eprintln!("a full ring held by friction: off the uniform state by {off:.1e}");
    assert!(off < 1e-10, "{off:e}");
}
