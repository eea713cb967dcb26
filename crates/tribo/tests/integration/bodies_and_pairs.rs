//! Two bodies with further contact pairs (issue 41, item 4): a body touching a second body and a rigid obstacle at
//! once (`Problem::two_bodies_with_pairs`).
//!
//! * Patch test: two stacked blocks of different materials on non-matching meshes, the lower one resting on a rigid
//!   foundation (a further pair, its only vertical hold), pressed by a prescribed displacement in uniaxial strain:
//!   λ_n is the pressure at every multiplier dof of both pairs, for either side secondary, P0 and P1 multipliers,
//!   γ0 = 0 and ½ bound, frictionless and Coulomb (the foundation with its own μ).
//! * Sheared stack, Coulomb: the fixed point and Newton give one answer, and the supports' reactions balance the
//!   foundation's force (the force between the bodies is internal), a roller's corner node on the foundation too.
//! * A further pair on the primary side, or on an edge set that names no body, is refused.

use tribo::*;

fn body(name: &str, mesh: Mesh, material: Material, supports: Vec<Support>) -> Body {
    let materials = Materials::uniform(material, mesh.n_triangles());
    Body { name: name.into(), mesh, materials, clamped: vec![], supports, tractions: vec![] }
}

fn contact(secondary: &str, primary: &str, space: MultiplierSpace) -> ContactPair {
    ContactPair {
        secondary: secondary.into(),
        primary: primary.into(),
        gap: ObstacleShape::Flat,
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: space,
        model: Model::PlaneStrain,
        formulation: Default::default(),
    }
}

/// The rigid half-plane y < −1 under the lower block, touching it.
fn foundation() -> Obstacle {
    let shape = ObstacleShape::Line { point: [0.0, -1.0], normal: [0.0, 1.0] };
    Obstacle { shape, approach: 0.0, shift: 0.0, rotation: None }
}

const LOWER: Material = Material { young: 100.0, poisson: 0.3 };
const UPPER: Material = Material { young: 300.0, poisson: 0.2 };

/// Plane-strain P-wave modulus E (1 − ν) / ((1 + ν)(1 − 2ν)): σ_yy / ε_yy in uniaxial strain.
fn p_modulus(m: &Material) -> f64 {
    m.young * (1.0 - m.poisson) / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson))
}

/// The lower block [0, 2] × [−1, 0] (rollers on its sides, the foundation under it) and the upper block
/// [0, 2] × [0, ½] (rollers on its sides, its top pressed down by δ), the pair `lower_secondary` or not; the
/// uniaxial-strain pressure p = δ / (h₁/M₁ + h₂/M₂).
pub(crate) fn stacked(lower_secondary: bool, space: MultiplierSpace, foundation_mu: Option<f64>) -> (Problem, f64) {
    let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 5, 3, Diagonal::Alternating).unwrap();
    let upper = rectangle([0.0, 2.0], [0.0, 0.5], 7, 2, Diagonal::Right).unwrap();
    let delta = 0.01;
    let rollers = || vec![Support::roller("left"), Support::roller("right")];
    let mut pressed = rollers();
    pressed.push(Support::displacement("top", None, Some(-delta)));
    let bodies = [body("lower", lower, LOWER, rollers()), body("upper", upper, UPPER, pressed)];
    let p = delta / (1.0 / p_modulus(&LOWER) + 0.5 / p_modulus(&UPPER));
    let (s, q) = if lower_secondary { ("lower.top", "upper.bottom") } else { ("upper.bottom", "lower.top") };
    let mut ground =
        PairSpec { multiplier_points: MultiplierPoints::RatioToFe(1.0), ..PairSpec::new("lower.bottom", foundation()) };
    ground.mu = foundation_mu;
    let problem = Problem::two_bodies_with_pairs(bodies, contact(s, q, space), vec![ground], [0.0, 0.0]).unwrap();
    (problem, p)
}

#[test]
fn stacked_blocks_on_a_foundation_pass_the_patch_test() {
    for lower_secondary in [true, false] {
        for space in [MultiplierSpace::P1, MultiplierSpace::P0] {
            let (problem, p) = stacked(lower_secondary, space, Some(0.5));
            assert_eq!(problem.pairs().iter().map(|p| p.name).collect::<Vec<_>>()[1], "lower.bottom");
            assert!(!problem.dofs.floating.is_empty(), "the lower block is held vertically by the foundation alone");
            for theta in [0.0, 0.5] {
                for friction in [Friction::Frictionless, Friction::Coulomb { mu: 0.3 }] {
                    if friction == Friction::Frictionless {
                        // (a pair's own μ needs Coulomb friction)
                        let (frictionless, _) = stacked(lower_secondary, space, None);
                        check_patch(&frictionless, &friction, theta, p);
                    } else {
                        check_patch(&problem, &friction, theta, p);
                    }
                }
            }
        }
    }
}

/// `(‖λ − λ_patch‖_H, ‖λ‖_H)` for an answer `sol` of the stacked blocks: its multipliers' distance from the patch
/// answer (λ_n = p at every dof of both pairs, λ_t = 0) in the energy norm, and their size in it.
///
/// At γ0 = 0 this is where a Coulomb answer is determined: the rollers hold the lower block's bottom corners in x,
/// which leaves 4 tangential trace dofs under the foundation's 5 (P0) or 6 (P1) multipliers, so H = E A⁻¹ Eᵀ has a
/// kernel there and nothing but the QP method decides the answer's part in it. Measured: with clarabel regularized by
/// 1e-12 the foundation's λ_t is up to 2.8e-6 p (P1) and 2.7e-5 p (P0, alternating) from 0, with 1e-10 3.4e-7 p;
/// the two answers are 2e-16 apart in the energy norm, and each is 4e-13 of its size or less from the patch answer.
pub(crate) fn patch_distance(problem: &Problem, sol: &Solution, stabilization: Stabilization, p: f64) -> (f64, f64) {
    let answer = [sol.lambda_n.as_slice(), &sol.lambda_t].concat();
    let patch: Vec<f64> = sol.lambda_n.iter().map(|_| p).chain(sol.lambda_t.iter().map(|_| 0.0)).collect();
    let size = tribo_testkit::energy_distance(problem, stabilization, &answer, &vec![0.0; answer.len()]);
    (tribo_testkit::energy_distance(problem, stabilization, &answer, &patch), size)
}

fn check_patch(problem: &Problem, friction: &Friction, theta: f64, p: f64) {
    let settings = SolverSettings { stabilization: Stabilization::Fraction(theta), ..Default::default() };
    let sol = problem.solve(friction, &settings, None).unwrap();
    let what =
        format!("{} secondary, {:?}, θ = {theta}, {friction:?}", problem.spec.contact, problem.spec.multiplier_space);
    assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
    // Round-off of these small solves (as `two_bodies.rs`'s patch test: 64 ulps times κ(K)). Under Coulomb the
    // sticking λ_t lies inside its bound, where the QPs of the fixed point determine it to the accuracy that
    // `converged` grants the KKT residuals, √qp_tol (1e-10 p on the pair of the bodies), at γ0 > 0; at γ0 = 0 only in
    // the energy norm (above).
    let tol = 1e-10 * p;
    let tol_t = if matches!(friction, Friction::Coulomb { .. }) { settings.qp.tol.sqrt() * p } else { tol };
    // At γ0 = 0 a sticking λ_t is determined only in the energy norm ([`patch_distance`]): checked there, to the same
    // √qp_tol, relative.
    let kernel = theta == 0.0 && matches!(friction, Friction::Coulomb { .. });
    if kernel {
        let (apart, size) = patch_distance(problem, &sol, settings.stabilization, p);
        assert!(apart <= settings.qp.tol.sqrt() * size, "{what}: {apart:e} from the patch answer (of {size:e})");
    }
    for r in &sol.pairs {
        let dofs = r.multipliers.clone();
        let worst = sol.lambda_n[dofs.clone()].iter().fold(0.0_f64, |m, l| m.max((l - p).abs()));
        let slip = sol.lambda_t[dofs].iter().fold(0.0_f64, |m, l| m.max(l.abs()));
        assert!(
            worst <= tol && (kernel || slip <= tol_t),
            "{what}: pair '{}': |λ_n − p| {worst:e}, |λ_t| {slip:e}",
            r.name
        );
        assert!((r.normal_force - 2.0 * p).abs() <= 2.0 * tol, "{what}: pair '{}' carries {}", r.name, r.normal_force);
    }
    let sigma_yy = sol.stress.iter().fold(0.0_f64, |m, s| m.max((s[1] + p).abs()));
    assert!(sigma_yy <= tol, "{what}: σ_yy + p up to {sigma_yy:e}");
}

/// The upper block's top moved down and sideways (its sides free), the lower block held along x by a roller on its
/// left side (whose corner node is on the foundation's side too), or without a support (held along x by the
/// foundation's friction alone); Coulomb μ = 0.3 between the bodies, the foundation's own μ = 0.5. The fixed point
/// and Newton give one answer (the check agrees), and the supports' reactions balance the foundation's force on the
/// stack (the bodies' forces on each other cancel): at the corner node the reaction is the roller's alone, the
/// contact's and the stabilization's shares left out (with `K u − f` there, as reported before, 1.7e-3 of the force
/// was missing).
#[test]
fn a_sheared_stack_on_a_foundation_balances() {
    for supports in [vec![Support::roller("left")], vec![]] {
        let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 10, 5, Diagonal::Alternating).unwrap();
        let upper = rectangle([0.5, 1.5], [0.0, 0.5], 9, 4, Diagonal::Right).unwrap();
        let held = !supports.is_empty();
        let bodies = [
            body("lower", lower, LOWER, supports),
            body("upper", upper, UPPER, vec![Support::displacement("top", Some(0.001), Some(-0.005))]),
        ];
        let ground = PairSpec::new("lower.bottom", foundation()).with_mu(0.5);
        let pair = contact("upper.bottom", "lower.top", MultiplierSpace::P1);
        let problem = Problem::two_bodies_with_pairs(bodies, pair, vec![ground], [0.0, 0.0]).unwrap();
        let mut answers = Vec::new();
        for method in [CoulombMethod::FixedPoint, CoulombMethod::Newton] {
            let what = format!("{method}, roller {held}");
            let settings = SolverSettings { coulomb: method, coulomb_check: true, ..Default::default() };
            let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &settings, None).unwrap();
            assert_eq!(sol.report.status, SolveStatus::Converged, "{what}");
            let check = sol.report.coulomb_check.as_ref().expect("checked");
            assert_eq!(check.agreement, Agreement::Agree, "{what}: {check:?}");
            let [between, ground] = [&sol.pairs[0], &sol.pairs[1]];
            assert_eq!((between.mu, ground.mu), (Some(0.3), Some(0.5)));
            assert!(between.tangential_force.abs() > 0.01 * between.normal_force, "{what}: the top drags");
            assert!(ground.tangential_force.abs() > 0.05 * ground.normal_force, "{what}: the foundation's friction");
            // Σ reactions + the foundation's force = 0 (no body force; the bodies' forces on each other cancel).
            let scale = between.normal_force;
            for c in 0..2 {
                let reactions: f64 = sol.reactions.iter().skip(c).step_by(2).sum();
                let sum = reactions + ground.contact_force[c];
                assert!(sum.abs() <= 1e-8 * scale, "{what}: component {c}: {sum:e} of {scale:e}");
            }
            answers.push(sol.displacement);
        }
        let d = answers[0].iter().zip(&answers[1]).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(d <= 1e-6 * 0.005, "roller {held}: the two methods differ by {d:e}");
    }
}

#[test]
fn a_further_pair_of_two_bodies_is_checked() {
    let make = |set: &str| {
        let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 4, 2, Diagonal::Right).unwrap();
        let upper = rectangle([0.0, 2.0], [0.0, 0.5], 4, 2, Diagonal::Right).unwrap();
        let bodies = [
            body("lower", lower, LOWER, vec![Support::clamp("bottom")]),
            body("upper", upper, UPPER, vec![Support::displacement("top", None, Some(-0.01))]),
        ];
        let pair = contact("upper.bottom", "lower.top", MultiplierSpace::P1);
        Problem::two_bodies_with_pairs(bodies, pair, vec![PairSpec::new(set, foundation())], [0.0, 0.0])
    };
    let e = make("lower.top").unwrap_err();
    assert!(
        matches!(e, Error::SeveralPairs { ref pair, ref what } if pair == "lower.top" && what.contains("primary")),
        "{e}"
    );
    assert!(matches!(make("bottom").unwrap_err(), Error::UnknownEdgeSet { .. }));
    assert!(matches!(make("lower.bottom").unwrap_err(), Error::ContactOverlapsDirichlet { .. }));
    assert!(make("lower.right").is_ok());
}

/// The upper block free along x (its top pressed down only), frictionless against the lower block (the law's
/// μ = 0) while the foundation has its own μ = 0.5: nothing holds the upper block along x, and the solve says so
/// before it starts (the foundation's friction holds the lower block only). With μ = 0.3 between the blocks it is
/// held.
#[test]
fn a_pairs_own_mu_does_not_hold_another_pairs_body() {
    let make = || {
        let lower = rectangle([0.0, 2.0], [-1.0, 0.0], 6, 3, Diagonal::Right).unwrap();
        let upper = rectangle([0.5, 1.5], [0.0, 0.5], 5, 3, Diagonal::Right).unwrap();
        let bodies = [
            body("lower", lower, LOWER, vec![Support::roller("left")]),
            body("upper", upper, UPPER, vec![Support::displacement("top", None, Some(-0.005))]),
        ];
        let ground = PairSpec::new("lower.bottom", foundation()).with_mu(0.5);
        let pair = contact("upper.bottom", "lower.top", MultiplierSpace::P1);
        Problem::two_bodies_with_pairs(bodies, pair, vec![ground], [0.0, 0.0]).unwrap()
    };
    let problem = make();
    let e = problem.solve(&Friction::Coulomb { mu: 0.0 }, &SolverSettings::default(), None).unwrap_err();
    // (Counting the tangential rows of the frictionless pair too, the check passed and the solve ended "nothing
    // presses it against the contact along that motion".)
    let said = |body: &str, what: &str| body == "upper" && what.contains("cannot hold");
    assert!(matches!(e, Error::HeldOnlyByContact { ref body, ref what, .. } if said(body, what)), "{e}");
    let sol = problem.solve(&Friction::Coulomb { mu: 0.3 }, &SolverSettings::default(), None).unwrap();
    assert_eq!(sol.report.status, SolveStatus::Converged);
}
