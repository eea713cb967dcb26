//! The hierarchical estimate with several contact pairs (issue 41, item 4, and issue 36): the strip along every
//! pair's contact zone, the difference of the multipliers summed over the pairs, the reduction measured at every
//! end of a pair's side that its contact zone reaches.
//!
//! * One contact side cut into two pairs against one obstacle, the contact zone on one of them: the estimate, the
//!   error bars and the adaptive loop of the problem of one pair, to the solves' accuracy.
//! * On every level of that side's adaptive run, the enriched T_H halves the cells that hold the contact zone.
//! * The half block between a punch and a foundation, both touching: the difference summed over the pairs is each
//!   pair's in squares; a history of one step is estimated as the static solve. (The adaptive loop on it:
//!   `pair_adaptive.rs`; its effectivity against a graded reference: the `tol` table, study 13.)

use std::collections::BTreeMap;

use tribo::*;

use crate::several_pairs::MATERIAL;

/// A cylinder of radius ½ centred above x = 0.75 of the unit block's top, approaching by 0.01: its contact zone
/// lies within x ∈ [0.6, 0.9].
fn disc() -> Obstacle {
    Obstacle {
        shape: ObstacleShape::Disc { center: [0.75, 1.5], radius: 0.5 },
        approach: 0.01,
        shift: 0.0,
        rotation: None,
    }
}

/// The unit block (`n` × `n` cells, clamped on its bottom) whose top is the edge set "top" and also "top_left"
/// (x < ½) and "top_right" (x > ½).
fn cut_block(n: usize) -> Mesh {
    let mesh = rectangle([0.0, 1.0], [0.0, 1.0], n, n, Diagonal::Right).unwrap();
    let mut sets: BTreeMap<String, Vec<[usize; 2]>> = mesh.edge_sets().clone();
    let pts = mesh.points();
    let (left, right): (Vec<[usize; 2]>, Vec<[usize; 2]>) =
        sets["top"].iter().partition(|e| pts[e[0]][0] + pts[e[1]][0] < 1.0);
    sets.insert("top_left".into(), left);
    sets.insert("top_right".into(), right);
    Mesh::new(pts.to_vec(), mesh.triangles().to_vec(), sets).unwrap()
}

fn cut_spec(contact: &str) -> ProblemSpec {
    let mut spec = ProblemSpec::new(MATERIAL, contact)
        .clamped(["bottom"])
        .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle = disc();
    spec
}

/// `|a − b| ≤ tol · |b|`.
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs()
}

/// The top cut into "top_right" (the first pair, where the disc touches) and "top_left" (a further pair against the
/// same disc, apart from it) is the top as one pair: the strip, the enriched problem and its answer are the same
/// where anything touches, so the hierarchical estimate, the error bars and the adaptive loop's levels are too, to
/// the accuracy of the solves.
#[test]
fn one_side_cut_into_two_pairs_is_estimated_as_one() {
    let settings = SolverSettings::default();
    let one = Problem::new(cut_block(16), cut_spec("top")).unwrap();
    let mut two = cut_spec("top_right");
    two.pairs
        .push(PairSpec { multiplier_points: MultiplierPoints::RatioToFe(1.0), ..PairSpec::new("top_left", disc()) });
    let two = Problem::new(cut_block(16), two).unwrap();
    for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
        let (s1, s2) = (one.solve(&friction, &settings, None).unwrap(), two.solve(&friction, &settings, None).unwrap());
        assert!(close(s2.normal_force, s1.normal_force, 1e-8), "{} {}", s2.normal_force, s1.normal_force);
        assert_eq!(s2.pairs[1].normal_force, 0.0, "the left half stays apart");
        let (h1, h2) = (
            one.estimate_hierarchical(&s1, &friction, &settings).unwrap(),
            two.estimate_hierarchical(&s2, &friction, &settings).unwrap(),
        );
        eprintln!("{friction:?}: one pair {h1:?}\ntwo pairs {h2:?}");
        assert_eq!((h1.status, h2.status), (SolveStatus::Converged, SolveStatus::Converged));
        assert!(h1.end_reductions.is_empty() && h2.end_reductions.is_empty(), "no end touches");
        for (a, b) in [(h2.difference, h1.difference), (h2.norm, h1.norm), (h2.estimate, h1.estimate)] {
            assert!(close(a, b, 1e-6), "{friction:?}: {a:e} against {b:e}");
        }
        assert!(h2.relative > 0.01, "a coarse mesh: an estimate well above the solves' accuracy");
        // The error bars (the whole mesh enriched): the forces' bars of the one pair, the widths of the first pair.
        let (b1, b2) = (
            one.estimate_error_bars(&s1, &friction, &settings).unwrap().error_bars.unwrap(),
            two.estimate_error_bars(&s2, &friction, &settings).unwrap().error_bars.unwrap(),
        );
        assert!(close(b2.normal_force, b1.normal_force, 1e-5), "{b2:?} {b1:?}");
        assert!(close(b2.contact_width, b1.contact_width, 1e-9), "{b2:?} {b1:?}");
        // The difference of two problems whose pairs differ is not defined.
        assert!(adapt::multiplier_difference(&one, &s1, &two, &s2).0.is_nan());
    }
    // The adaptive loop reads the same estimates and so makes the same levels.
    let adapt = AdaptSettings { tol: 0.05, ..AdaptSettings::default() };
    let (a1, a2) = (
        one.solve_adaptive(&Friction::Frictionless, &settings, &adapt, None).unwrap(),
        two.solve_adaptive(&Friction::Frictionless, &settings, &adapt, None).unwrap(),
    );
    assert_eq!((a1.stop, a2.stop), (AdaptStop::Tolerance, AdaptStop::Tolerance));
    let sizes = |a: &Adaptive| a.levels.iter().map(|l| l.mesh.n_triangles()).collect::<Vec<_>>();
    assert_eq!(sizes(&a1), sizes(&a2));
    for (l1, l2) in a1.levels.iter().zip(&a2.levels) {
        assert!(close(l2.relative, l1.relative, 1e-6), "{} {}", l2.relative, l1.relative);
        let sharp = [l1, l2].map(|l| l.estimate.traction_hierarchical_relative);
        assert_eq!(sharp[0].is_some(), sharp[1].is_some());
    }
    let estimated = a2.levels.iter().filter(|l| l.estimate.traction_hierarchical_relative.is_some()).count();
    println!("{} levels, {estimated} estimated", a2.levels.len());
    // Three of six levels at tol 5 % (four before the estimate's factor went from 2 to 1.5: the loop stops sooner).
    assert!(estimated >= 2, "the loops compare hierarchical estimates on several levels");
}

/// On every level of the one-pair run, the enriched problem halves T_H across the contact zone, also where T_H was
/// kept coarse beyond it over FE edges that refinement halved (fails without taking the level's ratio H/h from the
/// contact zone: the apart segment's ratio 2 left T_H unhalved in the strip, the estimate 0.087 against 0.120).
#[test]
fn the_enrichment_halves_the_multiplier_mesh_across_the_contact_zone() {
    let settings = SolverSettings::default();
    let one = Problem::new(cut_block(16), cut_spec("top")).unwrap();
    let adapt = AdaptSettings { tol: 0.05, ..AdaptSettings::default() };
    let run = one.solve_adaptive(&Friction::Frictionless, &settings, &adapt, None).unwrap();
    let mut coarser = 0;
    for level in &run.levels {
        let p = one.on_level(level).unwrap();
        let s = p.solve(&Friction::Frictionless, &settings, None).unwrap();
        let zone = s.contact_zone().unwrap();
        // The T_H cells that hold the zone, from the T_H point before it to the one after it.
        let (a, b) = p.multipliers.points_around((zone.lo, zone.hi), false);
        let inside = |x: &[f64]| x.iter().filter(|&&x| x > a && x < b).count();
        let marked = adapt::near_contact(&p, &s, zone.width());
        let (enriched, _) = p.solve_enriched(&s, &marked, &Friction::Frictionless, &settings).unwrap();
        let (n, m) = (inside(&p.multipliers.xi), inside(&enriched.multipliers.xi));
        assert!(m > 2 * n, "{} unknowns: {n} T_H points in the zone, enriched {m}", p.n_free);
        // A level whose T_H beyond the zone is coarser than the FE edges under it (what the test is about).
        let apart = p.multipliers.xi.windows(2).filter(|w| w[1] <= zone.lo || w[0] >= zone.hi);
        let under = |w: &[f64]| p.contact.node_xi.iter().filter(|&&x| x > w[0] && x < w[1]).count();
        coarser += usize::from(apart.into_iter().any(|w| under(w) > 0));
    }
    assert!(coarser > 0, "no level had a T_H coarser than its FE edges beyond the zone");
}

/// Both pairs touch: the difference of two answers (a level and its enriched problem) is the pairs' differences
/// added in squares, each pair's on its own side, and both are there.
#[test]
fn the_difference_adds_the_pairs_in_squares() {
    let settings = SolverSettings::default();
    let problem = tribo_testkit::punch_and_foundation(8);
    let s = problem.solve(&Friction::Frictionless, &settings, None).unwrap();
    let all: Vec<usize> = (0..problem.mesh.n_triangles()).collect();
    let (fine, f) = problem.solve_enriched(&s, &all, &Friction::Frictionless, &settings).unwrap();
    let (d, norm) = adapt::multiplier_difference(&problem, &s, &fine, &f);
    let each = [0, 1].map(|k| adapt::pair_difference_on(&problem, &s, &fine, &f, k, f64::NEG_INFINITY, f64::INFINITY));
    eprintln!("{d:e} {norm:e} {each:?}");
    assert!(each.iter().all(|(dk, nk)| *dk > 1e-3 * d && *nk > 0.1 * norm), "both pairs count: {each:?}");
    assert!(close(d, each[0].0.hypot(each[1].0), 1e-12) && close(norm, each[0].1.hypot(each[1].1), 1e-12));
    // The first pair's part on the whole side is `multiplier_difference_on`'s.
    let first = adapt::multiplier_difference_on(&problem, &s, &fine, &f, f64::NEG_INFINITY, f64::INFINITY);
    assert_eq!(first, each[0]);
}

/// A history of one step from rest is estimated as the static solve is: the same strips, ends and enriched answer.
#[test]
fn a_history_of_one_step_is_estimated_as_the_static_solve() {
    let settings = SolverSettings { coulomb: CoulombMethod::Newton, ..SolverSettings::default() };
    let problem = tribo_testkit::punch_and_foundation(8);
    for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
        let s = problem.solve(&friction, &settings, None).unwrap();
        let h = problem.estimate_hierarchical(&s, &friction, &settings).unwrap();
        let history = problem.solve_history(&friction, &[LoadStep::new(0.01, 0.0)], &settings, None).unwrap();
        let steps = problem.estimate_history_hierarchical(&history, &friction, &settings).unwrap();
        eprintln!("{friction:?}: {h:?}");
        let same = |a: f64, b: f64| a == b || close(a, b, 1e-6);
        let (step, ends) = (&steps[0], steps[0].end_reductions.iter().zip(&h.end_reductions));
        assert!(same(step.estimate, h.estimate) && same(step.difference, h.difference), "{step:?} {h:?}");
        let ends_agree = ends.into_iter().all(|(a, b)| same(*a, *b));
        assert!(step.end_reductions.len() == h.end_reductions.len() && ends_agree, "{step:?} {h:?}");
    }
}
