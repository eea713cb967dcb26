//! Hertz contact, frictionless or with Coulomb friction: a rigid cylinder (R = 1) pushed δ = 0.01 into
//! the block (−2, 2) × (−2, 0), clamped at the bottom, E = 200, ν = 0.3, on meshes graded toward the
//! contact zone. Prints, per mesh, the contact force, the Hertz half-width, the relative L2 error of λ_n
//! against the plane-strain Hertz pressure (frictionless), the fixed-point iterations and the time.
//!
//! `cargo run --release -p tribo --example hertz [MU]` (MU > 0: Coulomb with an obstacle shift 0.004).
use tribo::*;

fn main() -> Result<()> {
    let mu: f64 = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let (young, nu, radius) = (200.0, 0.3, 1.0);
    for h_min in [0.04, 0.02, 0.01, 0.005] {
        let grading = Grading { side: Side::Top, segment: [-0.3, 0.3], h_min, h_max: 0.5, growth: 0.3 };
        let mesh = graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading)?;
        let spec = ProblemSpec {
            material: Material { young, poisson: nu },
            clamped: vec!["bottom".into()],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle {
                shape: ObstacleShape::Circle { center: 0.0, radius },
                approach: 0.01,
                shift: if mu > 0.0 { 0.004 } else { 0.0 },
            },
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            multiplier_space: MultiplierSpace::P1,
        };
        let problem = Problem::new(mesh, spec)?;
        let friction = if mu > 0.0 { Friction::Coulomb { mu } } else { Friction::Frictionless };
        let clock = std::time::Instant::now();
        let sol = problem.solve(&friction, &SolverSettings::default(), None)?;
        let seconds = clock.elapsed().as_secs_f64();
        let p = sol.normal_force;
        let a = (4.0 * p * radius * (1.0 - nu * nu) / (std::f64::consts::PI * young)).sqrt();
        let hertz =
            |x: f64| if x.abs() < a { 2.0 * p / (std::f64::consts::PI * a * a) * (a * a - x * x).sqrt() } else { 0.0 };
        // Relative L2 error by fine sampling of λ_n.
        let (mut num, mut den) = (0.0, 0.0);
        for k in 0..20000 {
            let x = -2.0 + 4.0 * (k as f64 + 0.5) / 20000.0;
            num += (problem.multipliers.evaluate(&sol.lambda_n, x) - hertz(x)).powi(2);
            den += hertz(x).powi(2);
        }
        let count = |s: ContactState| sol.states.iter().filter(|x| **x == s).count();
        println!(
            "h_min {h_min:<6} unknowns {:>5}  q {:>4}  force {p:.5}  a {a:.4}  L2 error vs Hertz {:.3e}  {:?} after {} iterations  stick {} slip {}  {seconds:.3} s",
            problem.n_free,
            problem.n_multipliers(),
            (num / den).sqrt(),
            sol.report.status,
            sol.report.iterations,
            count(ContactState::Stick),
            count(ContactState::Slip),
        );
        let t = &sol.report.timings;
        println!(
            "    timings [s]: assembly {:.4}  Γ_C matrices {:.4}  factorization {:.4}  condensation {:.4}  QPs {:.4} ({} QPs, {} only to the fallback tolerance, IPM iterations {:?})  recovery {:.4}",
            t.assembly, t.contact_matrices, t.factorization, t.condensation, t.qp,
            sol.report.qp_iterations.len(), sol.report.qp_inaccurate, sol.report.qp_iterations, t.recovery
        );
    }
    Ok(())
}
