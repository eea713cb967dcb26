//! Several contact pairs in one problem (issue 41, item 4): each against a problem of one pair with the same
//! physics, and against Hertz.
//!
//! * A block pressed by a cylindrical punch onto a rigid foundation (half of it: a roller on its axis, the block
//!   held vertically by the two contacts alone). The foundation stays in contact everywhere, so it acts as a
//!   roller: with γ0 = 0 the problem of one pair, the foundation replaced by a roller, is the same discrete problem.
//! * The same block between two flat platens: the uniform state, σ_yy = −E δ / ((1 − ν²) H), on both pairs.
//! * A disc between two flat platens (half of it, a roller on its axis, held vertically by the contacts alone),
//!   the platens approaching by different amounts: equal forces, and Hertz's pressure of that force at each contact.
//! * A second pair that never touches leaves the first pair's answer as it is alone.
//! * Two pairs on one edge, or a pair on a support, are refused with a typed error.

use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI};

use tribo::*;

pub(crate) const MATERIAL: Material = Material { young: 1.0, poisson: 0.3 };

/// The block [0, ½] × [0, 1], `n` × `2n` cells, a roller on its left side (the axis of the whole block).
pub(crate) fn block_mesh(n: usize) -> Mesh {
    rectangle([0.0, 0.5], [0.0, 1.0], n, 2 * n, Diagonal::Right).expect("a block")
}

/// A rigid cylinder of radius 0.5 above the block's top left corner, approaching by `approach`.
pub(crate) fn punch(approach: f64) -> Obstacle {
    Obstacle { shape: ObstacleShape::Disc { center: [0.0, 1.5], radius: 0.5 }, approach, shift: 0.0, rotation: None }
}

/// The rigid half-plane under the block (its surface y = 0), touching it.
pub(crate) fn foundation() -> Obstacle {
    Obstacle {
        shape: ObstacleShape::Line { point: [0.0, 0.0], normal: [0.0, 1.0] },
        approach: 0.0,
        shift: 0.0,
        rotation: None,
    }
}

pub(crate) fn spec(contact: &str, obstacle: Obstacle) -> ProblemSpec {
    let mut spec = ProblemSpec::new(MATERIAL, contact)
        .support(Support::roller("left"))
        .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle = obstacle;
    spec
}

pub(crate) fn solve(problem: &Problem, friction: &Friction, settings: &SolverSettings) -> Solution {
    let sol = problem.solve(friction, settings, None).expect("solves");
    assert_eq!(sol.report.status, SolveStatus::Converged, "{:?}", sol.report);
    sol
}

pub(crate) fn sup(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The punch and the foundation as two pairs, against the punch alone on a block whose bottom is a roller: with
/// γ0 = 0 the same displacement and the same punch pressure, to the QP's tolerance; the foundation's force equals
/// the punch's (the block is held vertically by the contacts alone) and the roller's reaction.
#[test]
fn a_block_between_a_punch_and_a_foundation_is_the_block_on_a_roller() {
    let settings = SolverSettings { stabilization: Stabilization::None, ..SolverSettings::default() };
    for n in [16, 32] {
        let mut two = spec("top", punch(0.01));
        two.pairs.push(PairSpec {
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            ..PairSpec::new("bottom", foundation())
        });
        let two = Problem::new(block_mesh(n), two).expect("two pairs");
        assert_eq!(two.pairs().iter().map(|p| p.name).collect::<Vec<_>>(), ["top", "bottom"]);
        assert!(!two.dofs.floating.is_empty(), "held vertically by the contacts alone");
        let one = Problem::new(block_mesh(n), spec("top", punch(0.01)).support(Support::roller("bottom"))).unwrap();
        let (s2, s1) =
            (solve(&two, &Friction::Frictionless, &settings), solve(&one, &Friction::Frictionless, &settings));
        let [top, bottom] = [&s2.pairs[0], &s2.pairs[1]];
        // The foundation touches everywhere (so it acts as the roller does).
        let foot = &s2.lambda_n[bottom.multipliers.clone()];
        assert!(foot.iter().all(|&l| l > 0.0), "the foundation touches everywhere: {foot:?}");
        let tol = 1e-6;
        let du = s2.displacement.iter().zip(&s1.displacement).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        let dl = s2.lambda_n[top.multipliers.clone()].iter().zip(&s1.lambda_n).map(|(a, b)| (a - b).abs());
        let dl = dl.fold(0.0, f64::max);
        eprintln!(
            "{n}²: P = {:.6e} (punch) {:.6e} (foundation) {:.6e} (one pair); |Δu| {du:.1e}, |Δλ_n| {dl:.1e}",
            top.normal_force, bottom.normal_force, s1.normal_force
        );
        assert!(du <= tol * sup(&s1.displacement) && dl <= tol * sup(&s1.lambda_n), "{du:e} {dl:e}");
        // The punch's frames follow its circle (the force it takes is tilted by the first edge's angle to it).
        assert!((-top.contact_force[1] - bottom.normal_force).abs() <= tol * top.normal_force);
        assert!((top.normal_force - s1.normal_force).abs() <= tol * s1.normal_force);
        // The roller's reaction on the bottom is the foundation's force.
        let bottom_nodes: Vec<usize> = one.mesh.edge_set("bottom").unwrap().iter().flatten().copied().collect();
        let mut seen = std::collections::HashSet::new();
        let reaction: f64 = bottom_nodes.iter().filter(|&&k| seen.insert(k)).map(|&k| s1.reactions[2 * k + 1]).sum();
        assert!(
            (reaction - bottom.normal_force).abs() <= tol * bottom.normal_force,
            "{reaction} {}",
            bottom.normal_force
        );
        // The totals are the sums of the pairs': the two forces on the block cancel.
        assert!((s2.normal_force - top.normal_force - bottom.normal_force).abs() <= 1e-12 * s2.normal_force);
        assert!(s2.contact_force[1].abs() <= tol * top.normal_force, "{:?}", s2.contact_force);
        assert_eq!(
            (s2.lambda_n.len(), s2.u_n.len(), s2.sigma_n.len()),
            (bottom.multipliers.end, bottom.nodes.end, bottom.edges.end)
        );
    }
}

/// Two flat platens pressing the block by δ₁ + δ₂ give the uniform state on both pairs, with and without the
/// stabilization: λ_n = E δ / ((1 − ν²) H) with δ = δ₁ + δ₂, to round-off.
#[test]
fn a_block_between_two_flat_platens_is_uniformly_pressed() {
    let top_flat = Obstacle {
        shape: ObstacleShape::Line { point: [0.0, 1.0], normal: [0.0, -1.0] },
        approach: 0.004,
        shift: 0.0,
        rotation: None,
    };
    for stabilization in [Stabilization::None, Stabilization::Fraction(0.5)] {
        let mut two = spec("top", top_flat.clone());
        two.pairs.push(PairSpec::new("bottom", Obstacle { approach: 0.002, ..foundation() }));
        let problem = Problem::new(block_mesh(6), two).expect("two pairs");
        let sol = solve(&problem, &Friction::Frictionless, &SolverSettings { stabilization, ..Default::default() });
        let exact = MATERIAL.young * 0.006 / (1.0 - MATERIAL.poisson.powi(2));
        let worst = sol.lambda_n.iter().map(|l| (l / exact - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst <= 1e-8, "{stabilization:?}: λ_n departs from E δ / (1 − ν²) by {worst:e}");
        for p in &sol.pairs {
            assert!((p.normal_force / (0.5 * exact) - 1.0).abs() <= 1e-8, "{}: {}", p.name, p.normal_force);
        }
        // Each platen moves its side by its own approach: the bottom up by 0.002, the top down by 0.004.
        for (set, u_y) in [("bottom", 0.002), ("top", -0.004)] {
            for &[a, _] in problem.mesh.edge_set(set).unwrap() {
                let off = (sol.displacement[2 * a + 1] - u_y).abs();
                assert!(off <= 1e-9, "{stabilization:?}: node {a} of '{set}' moves by {}", sol.displacement[2 * a + 1]);
            }
        }
    }
}

/// The half disc (x ≥ 0) of radii 0.25 and 1 — a ring, whose generator grades toward an arc of its rim — made of
/// a quarter graded toward its lowest point (over 0.1 rad, at growth 0.075, as the roller of `curved.rs`) and that
/// quarter mirrored in y = 0 (its nodes on y = 0 merged). Edge sets: `"lower"` and `"upper"`, the rim's quarters
/// (each with its arc, as the generator gives a ring's rim), `"axis"`, both radii on x = 0.
fn half_disc(h_min: f64) -> Mesh {
    let sector = RingSector { center: [0.0, 0.0], radii: [0.25, 1.0], angles: [-FRAC_PI_2, 0.0] };
    let grading = ArcGrading { angles: [-FRAC_PI_2, -FRAC_PI_2 + 0.1], h_min, h_max: 0.1, growth: 0.075 };
    let quarter = ring_sector(&sector, &grading).expect("a quarter ring");
    let pts = quarter.points();
    let n = pts.len();
    // Node k of the mirror is n + k, or k itself on y = 0 (the quarter's "end" side).
    let on_cut = |k: usize| pts[k][1] == 0.0;
    let mirror = |k: usize| if on_cut(k) { k } else { n + k };
    let mut points = pts.to_vec();
    points.extend(pts.iter().map(|p| [p[0], -p[1]]));
    // Mirrored triangles turn clockwise: two nodes swapped.
    let mut triangles = quarter.triangles().to_vec();
    triangles.extend(quarter.triangles().iter().map(|t| [mirror(t[0]), mirror(t[2]), mirror(t[1])]));
    let sets = quarter.edge_sets();
    let mirrored = |set: &str| sets[set].iter().map(|e| [mirror(e[1]), mirror(e[0])]).collect::<Vec<_>>();
    let mut edge_sets = BTreeMap::new();
    edge_sets.insert("lower".to_string(), sets["outer"].clone());
    edge_sets.insert("upper".to_string(), mirrored("outer"));
    edge_sets.insert("axis".to_string(), [sets["start"].clone(), mirrored("start")].concat());
    // The unused nodes of the mirror (its copy of the cut) are dropped by renumbering.
    let mut used = vec![false; points.len()];
    triangles.iter().flatten().for_each(|&k| used[k] = true);
    let mut index = vec![usize::MAX; points.len()];
    let mut kept = Vec::new();
    for (k, p) in points.iter().enumerate().filter(|(k, _)| used[*k]) {
        index[k] = kept.len();
        kept.push(*p);
    }
    let renumber = |k: usize| index[k];
    let triangles = triangles.iter().map(|t| t.map(renumber)).collect();
    let edge_sets =
        edge_sets.into_iter().map(|(name, e)| (name, e.iter().map(|e| e.map(renumber)).collect())).collect();
    // Both quarters of the rim on the circle (the gap is measured from it: the chords sag by h²/8R).
    let rim = Curve::Arc { center: [0.0, 0.0], radius: 1.0 };
    let mesh = Mesh::new(kept, triangles, edge_sets).expect("a half disc");
    mesh.with_curve("lower", rim).and_then(|m| m.with_curve("upper", rim)).expect("on the circle")
}

/// The relative L2 error of a pair's λ_n against Hertz's pressure `p₀ (1 − x²/a²)^½` at the horizontal distance x
/// from the axis, over x < 1.5 a.
fn against_hertz(pair: &PairParts<'_>, lambda: &[f64], a: f64, p0: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    let (lo, hi) = (pair.contact.start(), pair.contact.end());
    let n = 40_000;
    for i in 0..n {
        let xi = lo + (hi - lo) * (i as f64 + 0.5) / n as f64;
        let x = pair.contact.point_at(xi)[0].abs();
        if x > 1.5 * a {
            continue;
        }
        let exact = if x < a { p0 * (1.0 - (x / a).powi(2)).sqrt() } else { 0.0 };
        num += (pair.multipliers.evaluate(lambda, xi) - exact).powi(2);
        den += exact * exact;
    }
    (num / den).sqrt()
}

/// The half disc, a roller on its axis, between a platen above approaching by 0.004 and one below by 0.002: the
/// disc moves down and both contacts carry one force; each pressure against Hertz's of that force, `a² = 4 P R /
/// (π E*)` with P the whole disc's force (twice the half's). On meshes graded to a/18 and a/35: within 1 % and
/// falling (measured 0.95 % and 0.60 % at each contact; the roller of `curved.rs` on one flat: 2.07 % at a/20 and
/// 0.83 % at a/40, its grading from the contact point, graded here over ±0.1 rad alike).
#[test]
fn a_disc_between_two_platens_matches_hertz_at_both() {
    let platen = |y: f64, normal: f64, approach: f64| Obstacle {
        shape: ObstacleShape::Line { point: [0.0, y], normal: [0.0, normal] },
        approach,
        shift: 0.0,
        rotation: None,
    };
    let mut errors = Vec::new();
    for h_min in [0.002, 0.001] {
        let mut spec = ProblemSpec::new(MATERIAL, "upper").support(Support::roller("axis"));
        spec.obstacle = platen(1.0, -1.0, 0.004);
        spec.pairs.push(PairSpec::new("lower", platen(-1.0, 1.0, 0.002)));
        let problem = Problem::new(half_disc(h_min), spec).expect("a disc between two platens");
        assert!(!problem.dofs.floating.is_empty(), "held vertically by the contacts alone");
        let sol = solve(&problem, &Friction::Frictionless, &SolverSettings::default());
        let [upper, lower] = [&sol.pairs[0], &sol.pairs[1]];
        let forces = (upper.normal_force, lower.normal_force);
        assert!((forces.0 - forces.1).abs() <= 1e-6 * forces.0, "equal forces: {forces:?}");
        assert!((upper.contact_force[1] + lower.contact_force[1]).abs() <= 1e-6 * forces.0);
        let e_star = MATERIAL.young / (1.0 - MATERIAL.poisson.powi(2));
        let p = 2.0 * forces.0;
        let a = (4.0 * p / (PI * e_star)).sqrt();
        let p0 = 2.0 * p / (PI * a);
        let pairs = problem.pairs();
        let l2: Vec<f64> = sol
            .pairs
            .iter()
            .zip(&pairs)
            .map(|(r, pair)| against_hertz(pair, &sol.lambda_n[r.multipliers.clone()], a, p0))
            .collect();
        eprintln!(
            "h_min {h_min} (a/{:.0}): {} triangles, q = {}, P = {p:.6e}, a = {a:.4}; λ_n against Hertz {:.3e} (upper), {:.3e} (lower)",
            a / h_min,
            problem.mesh.n_triangles(),
            problem.n_multipliers(),
            l2[0],
            l2[1]
        );
        errors.push(l2);
        // The same physics with one pair: the lower quarter alone, a roller on its cut y = 0 (the symmetry line of
        // the disc once its rigid motion, down by half the difference of the approaches, is taken off) pressed by
        // the half sum of the approaches. Its mesh is the lower half's: λ_n dof by dof.
        let quarter = ring_sector(
            &RingSector { center: [0.0, 0.0], radii: [0.25, 1.0], angles: [-FRAC_PI_2, 0.0] },
            &ArcGrading { angles: [-FRAC_PI_2, -FRAC_PI_2 + 0.1], h_min, h_max: 0.1, growth: 0.075 },
        )
        .unwrap();
        let mut one =
            ProblemSpec::new(MATERIAL, "outer").support(Support::roller("start")).support(Support::roller("end"));
        one.obstacle = platen(-1.0, 1.0, 0.003);
        let one = Problem::new(quarter, one).unwrap();
        let s1 = solve(&one, &Friction::Frictionless, &SolverSettings::default());
        let mine = &sol.lambda_n[lower.multipliers.clone()];
        assert_eq!(mine.len(), s1.lambda_n.len());
        let apart = mine.iter().zip(&s1.lambda_n).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / sup(&s1.lambda_n);
        eprintln!(
            "  the lower pair against the quarter of one pair: λ_n {apart:.1e} apart, P {:.6e} and {:.6e}",
            lower.normal_force, s1.normal_force
        );
        let n1 = one.mesh.n_nodes();
        // Node by node, the disc's rigid motion (down by 0.001) taken off.
        let du = (0..n1).map(|k| {
            (sol.displacement[2 * k] - s1.displacement[2 * k])
                .abs()
                .max((sol.displacement[2 * k + 1] + 0.001 - s1.displacement[2 * k + 1]).abs())
        });
        let du = du.fold(0.0, f64::max) / sup(&s1.displacement);
        let l2 = mine.iter().zip(&s1.lambda_n).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
            / s1.lambda_n.iter().map(|b| b * b).sum::<f64>().sqrt();
        eprintln!(
            "  and u {du:.1e} apart; λ_n in l2 {l2:.1e}, forces {:.1e}",
            (lower.normal_force / s1.normal_force - 1.0).abs()
        );
        // Both are QP answers, each of λ to about qp_tol · κ(H) (κ grows with the grading): measured λ_n 4.2e-6 and
        // 3.7e-5 apart at the contact zone's last dof (1.5e-6 and 9.5e-6 in l2), u 4e-8 and 2e-7, the forces 1e-8
        // and 4e-8 (the disc held by the contacts alone is clarabel's, the quarter the active set's).
        assert!(
            l2 <= 1e-4 && du <= 1e-6 && (lower.normal_force / s1.normal_force - 1.0).abs() <= 1e-7,
            "{l2:e} {du:e}"
        );
    }
    assert!(errors.iter().flatten().all(|&e| e < 0.01), "{errors:?}");
    assert!(errors[1].iter().zip(&errors[0]).all(|(f, c)| *f < 0.7 * c), "falls under refinement: {errors:?}");
}

/// The whole block [−½, ½] × [0, 1] between the punch, shifted along its top, and the foundation, both with Coulomb
/// friction μ = 0.5 (one law for every pair), and no support: the two contacts alone hold it, along x, y and in
/// rotation. The fixed point and Newton give one answer (the check agrees); the forces of the two pairs cancel; each
/// pair's multipliers meet Coulomb's law on their own dofs.
#[test]
fn coulomb_friction_on_both_pairs_two_methods_one_answer() {
    let mesh = rectangle([-0.5, 0.5], [0.0, 1.0], 24, 24, Diagonal::Right).expect("a block");
    let mut spec = ProblemSpec::new(MATERIAL, "top").multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle = Obstacle { shift: 0.004, ..punch(0.02) };
    spec.pairs.push(PairSpec::new("bottom", foundation()));
    let problem = Problem::new(mesh, spec).expect("two pairs");
    assert_eq!(problem.dofs.floating[0].motions.len(), 3, "free along x, y and in rotation");
    let friction = Friction::Coulomb { mu: 0.5 };
    let settings = SolverSettings { coulomb_check: true, ..SolverSettings::default() };
    let sol = solve(&problem, &friction, &settings);
    let check = sol.report.coulomb_check.as_ref().expect("checked by Newton");
    eprintln!("{check:?}; pairs {:?}", sol.pairs);
    assert_eq!(check.agreement, Agreement::Agree, "{check:?}");
    let [top, bottom] = [&sol.pairs[0], &sol.pairs[1]];
    assert!(top.tangential_force.abs() > 0.05 * top.normal_force, "the shifted punch pulls along the top");
    for c in 0..2 {
        let sum = top.contact_force[c] + bottom.contact_force[c];
        assert!(sum.abs() <= 1e-6 * top.normal_force, "component {c}: {sum:e}");
    }
    // Coulomb's law dof by dof, each pair on its own thresholds μ λ_n (to the fixed point's last change).
    let reached = sol.report.residual_history.last().copied().unwrap_or(0.0).max(1e-6);
    for r in [top, bottom] {
        for j in r.multipliers.clone() {
            let bound = 0.5 * sol.lambda_n[j].max(0.0);
            assert!(sol.lambda_t[j].abs() <= bound + reached * sup(&sol.lambda_n), "{}: dof {j}", r.name);
        }
    }
    assert!(sol.states[bottom.multipliers.clone()].contains(&ContactState::Stick), "the foundation holds the block");
}

/// A second pair whose obstacle never reaches its side (a wall 0.1 beyond the block's right side) leaves the first
/// pair's answer as the problem of that pair alone gives it, to the QP's tolerance (γ0 = 0), and carries nothing.
#[test]
fn a_pair_that_never_touches_changes_nothing() {
    // γ0 = 0: with γ0 > 0 the Barbosa–Hughes term acts on the far side's triangles too, where it stands for the
    // free boundary only weakly (measured: 2e-5 of λ_n at γ0 = ½ bound), so the discrete problems differ.
    let settings = SolverSettings { stabilization: Stabilization::None, ..SolverSettings::default() };
    let held = |s: ProblemSpec| s.support(Support::roller("bottom"));
    let one = Problem::new(block_mesh(12), held(spec("top", punch(0.02)))).unwrap();
    let mut two = held(spec("top", punch(0.02)));
    two.pairs.push(PairSpec::new(
        "right",
        Obstacle {
            shape: ObstacleShape::Line { point: [0.6, 0.0], normal: [-1.0, 0.0] },
            approach: 0.0,
            shift: 0.0,
            rotation: None,
        },
    ));
    let two = Problem::new(block_mesh(12), two).unwrap();
    let friction = Friction::Frictionless;
    let (s1, s2) = (solve(&one, &friction, &settings), solve(&two, &friction, &settings));
    let q1 = s1.lambda_n.len();
    assert_eq!(s2.pairs[0].multipliers, 0..q1);
    let scale = sup(&s1.lambda_n);
    let m1 = s1.multipliers();
    let dl = m1.iter().zip(s2.lambda_n[..q1].iter().chain(&s2.lambda_t[..q1])).map(|(a, b)| (a - b).abs());
    let dl = dl.fold(0.0, f64::max) / scale;
    let du = s1.displacement.iter().zip(&s2.displacement).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    eprintln!("the far pair changes λ by {dl:.1e} and u by {du:.1e}");
    assert!(dl <= 1e-6 && du <= 1e-6 * sup(&s1.displacement), "{dl:e} {du:e}");
    assert!(sup(&s2.lambda_n[q1..]) <= 1e-6 * scale && s2.pairs[1].normal_force.abs() <= 1e-6 * scale);
    assert_eq!(s2.states[q1..].iter().filter(|s| **s != ContactState::Separation).count(), 0);
}

/// Two pairs on one edge are refused with [`Error::SeveralPairs`]. A further pair's side is checked as the first's:
/// its edge set, Γ_D and Γ_N on it.
#[test]
fn pairs_on_one_edge_or_on_a_support_are_refused() {
    let mut spec = spec("top", punch(0.02));
    spec.pairs.push(PairSpec::new("bottom", foundation()));
    // An edge set with an edge of another pair's.
    let mut mesh = block_mesh(8);
    let mut sets = mesh.edge_sets().clone();
    sets.insert("corner".into(), vec![sets["bottom"][0]]);
    mesh = Mesh::new(mesh.points().to_vec(), mesh.triangles().to_vec(), sets).unwrap();
    let mut shared = spec.clone();
    shared.pairs.push(PairSpec::new("corner", foundation()));
    let e = Problem::new(mesh, shared).unwrap_err();
    assert!(matches!(e, Error::SeveralPairs { ref pair, .. } if pair == "corner"), "{e}");
    // A pair on an unknown edge set, or on an edge of Γ_D.
    let mut bad = spec.clone();
    bad.pairs[0].contact = "nowhere".into();
    assert!(matches!(Problem::new(block_mesh(8), bad).unwrap_err(), Error::UnknownEdgeSet { .. }));
    let e = Problem::new(block_mesh(8), spec.clone().support(Support::roller("bottom"))).unwrap_err();
    assert!(matches!(e, Error::ContactOverlapsDirichlet { ref set, .. } if set == "bottom"), "{e}");
    let e = Problem::new(block_mesh(8), spec.clone().traction("bottom", [0.0, 1.0])).unwrap_err();
    assert!(matches!(e, Error::TractionOnContact { ref set, .. } if set == "bottom"), "{e}");
    // One side, one pair: the first pair's edge set again, or a further pair's twice.
    for twice in ["top", "bottom"] {
        let mut again = spec.clone();
        again.pairs.push(PairSpec::new(twice, foundation()));
        let e = Problem::new(block_mesh(8), again).unwrap_err();
        assert!(matches!(e, Error::SeveralPairs { ref pair, .. } if pair == twice), "{e}");
    }
    // In axisymmetry a further pair's obstacle does not shift, and its side is not on the axis.
    let axisymmetric = spec.clone().model(Model::Axisymmetric);
    let mut shifted = axisymmetric.clone();
    shifted.pairs[0].obstacle.shift = 0.001;
    assert!(matches!(Problem::new(block_mesh(8), shifted).unwrap_err(), Error::BadAxisymmetry { .. }));
    let mut on_axis = axisymmetric.clone();
    on_axis.supports.clear();
    on_axis.pairs[0] = PairSpec::new("left", foundation());
    let e = Problem::new(block_mesh(8), on_axis).unwrap_err();
    assert!(matches!(e, Error::BadAxisymmetry { ref what } if what.contains("axis")), "{e}");
}

/// A triangle with an edge on each of two pairs' sides (the corner of a block clamped on its top, pressed by a
/// foundation from below and spreading against a wall touching its right side) carries both pairs' terms of G: its bound on γ0 is the harmonic sum of the two sides' bounds there, below each
/// side's own; A = K − G stays positive definite just below it (factorized unchecked at 0.99 of it) and is not at
/// 0.99 of the sides' own bound (measured: 0.263 each, 0.131 together) — what taking them one by one would allow.
#[test]
fn a_corner_triangle_of_two_pairs_bounds_gamma0_by_both() {
    let wall = Obstacle {
        shape: ObstacleShape::Line { point: [0.5, 0.0], normal: [-1.0, 0.0] },
        approach: 0.0,
        shift: 0.0,
        rotation: None,
    };
    let mut spec = spec("bottom", Obstacle { approach: 0.002, ..foundation() }).clamped(["top"]);
    spec.supports.clear();
    spec.pairs.push(PairSpec::new("right", wall));
    let mesh = rectangle([0.0, 0.5], [0.0, 1.0], 4, 8, Diagonal::Right).unwrap();
    let problem = Problem::new(mesh, spec).expect("two pairs meeting at a corner");
    let own = [problem.pairs()[0], problem.pairs()[1]].map(|p| {
        tribo::contact::gamma0::admissible_gamma0(&problem.mesh, problem.spec.model, &problem.in_plane, p.contact).value
    });
    let bound = problem.gamma0_bound.value;
    eprintln!("γ0 bounds: the bottom alone {:.4e}, the right alone {:.4e}, both {bound:.4e}", own[0], own[1]);
    assert!(bound < own[0].min(own[1]), "the corner triangle's bound is below each side's");
    let settings = |g: f64| SolverSettings { stabilization: Stabilization::Unchecked(g), ..SolverSettings::default() };
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &settings(0.99 * bound), None).expect("positive definite");
    assert_eq!(sol.report.status, SolveStatus::Converged);
    assert_eq!(sol.pairs.iter().filter(|p| p.normal_force > 0.0).count(), 2, "both pairs press");
    let beyond = problem.solve(&Friction::Frictionless, &settings(0.99 * own[0].min(own[1])), None);
    assert!(matches!(beyond, Err(Error::NotPositiveDefinite { .. })), "{beyond:?}");
}
