//! Each contact pair with its own Coulomb coefficient (issue 41, item 4): `PairSpec::mu`, μ per multiplier dof
//! through the fixed point, Newton and the check of one by the other.
//!
//! * A pair of its own μ = 0 is frictionless while the other pair slides: the block pressed and dragged by a
//!   shifted punch onto a foundation of μ = 0 is the block on a roller (one pair, the same Coulomb law on the punch).
//! * The pairs in either order are one problem: the punch first (the law's μ) and the foundation second (its own),
//!   or the foundation first and the punch second, give one answer; so do a law of μ = 0 with the other pair's own
//!   μ > 0 (still Coulomb, not frictionless) and the two methods.
//! * A pair's own μ needs Coulomb friction, and is ≥ 0.

use tribo::*;

use super::several_pairs::{block_mesh, foundation, solve, spec, sup};

/// The punch of `several_pairs` approaching by 0.01 and shifted by `shift`.
fn punch(shift: f64) -> Obstacle {
    Obstacle { shift, ..super::several_pairs::punch(0.01) }
}

/// A further pair with T_H its FE edges and its own μ.
fn pair(contact: &str, obstacle: Obstacle, mu: f64) -> PairSpec {
    PairSpec { multiplier_points: MultiplierPoints::RatioToFe(1.0), ..PairSpec::new(contact, obstacle) }.with_mu(mu)
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// The punch shifted by 0.0005 drags the block's top (Coulomb μ = 0.5); the foundation has its own
/// μ = 0. Touching everywhere, it then acts as a roller does (γ0 = 0): the problem of the punch alone on a block
/// whose bottom is a roller, with the same Coulomb law, has the same displacement and multipliers on the top, to the
/// fixed point's tolerance, and the foundation carries no tangential traction. Without the foundation's own μ
/// (μ = 0.3 there too) the answer is another: the bottom holds the block by friction.
#[test]
fn a_pair_of_its_own_mu_zero_is_frictionless_beside_a_sliding_one() {
    let settings = SolverSettings { stabilization: Stabilization::None, ..SolverSettings::default() };
    let friction = Friction::Coulomb { mu: 0.5 };
    let mut two = spec("top", punch(0.0005));
    two.pairs.push(pair("bottom", foundation(), 0.0));
    let two = Problem::new(block_mesh(16), two).expect("two pairs");
    let one = Problem::new(block_mesh(16), spec("top", punch(0.0005)).support(Support::roller("bottom"))).unwrap();
    let (s2, s1) = (solve(&two, &friction, &settings), solve(&one, &friction, &settings));
    let [top, bottom] = [&s2.pairs[0], &s2.pairs[1]];
    assert_eq!((top.mu, bottom.mu, s2.report.mu), (Some(0.5), Some(0.0), Some(0.5)));
    assert_eq!(s2.report.friction, FrictionLaw::Coulomb);
    let (scale, top_dofs) = (sup(&s1.lambda_n), top.multipliers.clone());
    assert!(s1.tangential_force.abs() > 0.1 * s1.normal_force, "the punch drags: {:?}", s1.states);
    let du = distance(&s2.displacement, &s1.displacement) / sup(&s1.displacement);
    let (dn, dt) =
        (distance(&s2.lambda_n[top_dofs.clone()], &s1.lambda_n), distance(&s2.lambda_t[top_dofs], &s1.lambda_t));
    eprintln!("|Δu| {du:.1e}, |Δλ_n| {:.1e}, |Δλ_t| {:.1e} (relative)", dn / scale, dt / scale);
    assert!(du <= 1e-6 && dn <= 1e-6 * scale && dt <= 1e-6 * scale, "{du:e} {dn:e} {dt:e}");
    let foot = &s2.lambda_t[bottom.multipliers.clone()];
    assert!(sup(foot) <= 1e-8 * scale, "the frictionless foundation carries λ_t {:e}", sup(foot));
    assert!(s2.friction_threshold[bottom.multipliers.clone()].iter().all(|&g| g == 0.0));
    // The same problem with the law's μ on the foundation too: it holds the block's bottom by friction.
    let mut held = spec("top", punch(0.0005));
    held.pairs.push(PairSpec { mu: None, ..pair("bottom", foundation(), 0.0) });
    let held = solve(&Problem::new(block_mesh(16), held).unwrap(), &friction, &settings);
    assert!(sup(&held.lambda_t[bottom.multipliers.clone()]) > 1e-3 * scale, "friction on the foundation");
    assert_eq!(held.pairs[1].mu, Some(0.5));
}

/// The punch (μ_p) and the foundation (μ_f) as pairs in either order, each μ given as the law's (the first pair's)
/// or as the pair's own: one answer, by the fixed point and by Newton (the check agrees), the forces of each pair
/// equal. With μ_p = 0 the law's μ is 0 and the foundation's own 0.4 keeps the problem Coulomb.
#[test]
fn the_pairs_in_either_order_are_one_problem() {
    for (mu_p, mu_f) in [(0.3, 0.4), (0.0, 0.4), (0.3, 0.0)] {
        let mut punch_first = spec("top", punch(0.004));
        punch_first.pairs.push(pair("bottom", foundation(), mu_f));
        let mut foundation_first = spec("bottom", foundation());
        foundation_first.pairs.push(pair("top", punch(0.004), mu_p));
        let a = Problem::new(block_mesh(12), punch_first).unwrap();
        let b = Problem::new(block_mesh(12), foundation_first).unwrap();
        for method in [CoulombMethod::FixedPoint, CoulombMethod::Newton] {
            let settings = SolverSettings { coulomb: method, coulomb_check: true, ..SolverSettings::default() };
            let sa = solve(&a, &Friction::Coulomb { mu: mu_p }, &settings);
            let sb = solve(&b, &Friction::Coulomb { mu: mu_f }, &settings);
            assert_eq!((sa.report.friction, sb.report.friction), (FrictionLaw::Coulomb, FrictionLaw::Coulomb));
            for s in [&sa, &sb] {
                let check = s.report.coulomb_check.as_ref().expect("checked");
                assert_eq!(check.agreement, Agreement::Agree, "μ {mu_p}/{mu_f} by {method}: {check:?}");
            }
            let du = distance(&sa.displacement, &sb.displacement) / sup(&sa.displacement);
            eprintln!("μ {mu_p}/{mu_f} by {method}: |Δu| {du:.1e}; {:?}", sa.pairs);
            assert!(du <= 1e-6, "μ {mu_p}/{mu_f} by {method}: {du:e}");
            let [(ta, fa), (fb, tb)] = [(&sa.pairs[0], &sa.pairs[1]), (&sb.pairs[0], &sb.pairs[1])];
            assert_eq!((ta.mu, fa.mu, tb.mu, fb.mu), (Some(mu_p), Some(mu_f), Some(mu_p), Some(mu_f)));
            for (x, y) in [(ta, tb), (fa, fb)] {
                let (p, q) = (x.normal_force, x.tangential_force);
                assert!((p - y.normal_force).abs() <= 1e-6 * p && (q - y.tangential_force).abs() <= 1e-6 * p);
            }
            // Each pair's tangential multipliers within its own bound μ λ_n.
            for r in [ta, fa] {
                for j in r.multipliers.clone() {
                    let bound = r.mu.unwrap() * sa.lambda_n[j].max(0.0);
                    assert!(sa.lambda_t[j].abs() <= bound + 1e-7 * sup(&sa.lambda_n), "{}: dof {j}", r.name);
                }
            }
            if mu_p > 0.0 {
                assert!(ta.tangential_force.abs() > 0.01 * ta.normal_force, "the punch drags the top");
            } else {
                assert!(ta.tangential_force.abs() <= 1e-7 * ta.normal_force, "a frictionless punch");
            }
        }
    }
}

/// A pair's own μ needs Coulomb friction (said at the solve, naming the pair), is ≥ 0 and finite (said when the
/// problem is built); Coulomb of μ = 0 on every pair is solved and reported as frictionless.
#[test]
fn a_pairs_own_mu_is_checked() {
    let mut given = spec("top", punch(0.0));
    given.pairs.push(pair("bottom", foundation(), 0.3));
    let problem = Problem::new(block_mesh(6), given.clone()).unwrap();
    let settings = SolverSettings::default();
    for friction in [Friction::Frictionless, Friction::Tresca(Threshold::Uniform(0.01))] {
        let e = problem.solve(&friction, &settings, None).unwrap_err();
        assert!(
            matches!(e, Error::SeveralPairs { ref pair, ref what } if pair == "bottom" && what.contains("Coulomb"))
        );
    }
    for mu in [-0.1, f64::NAN, f64::INFINITY] {
        let mut bad = given.clone();
        bad.pairs[0].mu = Some(mu);
        let e = Problem::new(block_mesh(6), bad).unwrap_err();
        assert!(matches!(e, Error::BadSetting { name: "mu", .. }), "{e}");
    }
    let mut zero = given.clone();
    zero.pairs[0].mu = Some(0.0);
    let sol = solve(&Problem::new(block_mesh(6), zero).unwrap(), &Friction::Coulomb { mu: 0.0 }, &settings);
    assert_eq!((sol.report.friction, sol.report.mu), (FrictionLaw::Frictionless, None));
    assert!(sol.pairs.iter().all(|r| r.mu.is_none()));
}
