//! Hertz contact: a rigid cylinder (R = 1) pushed δ = 0.01 into the block (−2, 2) × (−2, 0), clamped at
//! the bottom, E = 200, ν = 0.3. Prints the contact force, the contact half-width and the L2 error of
//! λ_n against the plane-strain Hertz pressure for a few meshes graded toward the contact zone.
use tribo::*;

fn main() -> Result<()> {
    let mu: f64 = std::env::args().nth(1).map_or(0.0, |s| s.parse().unwrap());
    for h_min in [0.04, 0.02, 0.01, 0.005] {
        let mesh = graded_rectangle(
            [-2.0, 2.0],
            [-2.0, 0.0],
            &Grading { side: Side::Top, segment: [-0.3, 0.3], h_min, h_max: 0.5, growth: 0.3 },
        )?;
        let spec = ProblemSpec {
            material: Material { young: 200.0, poisson: 0.3 },
            clamped: vec!["bottom".into()],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle {
                shape: ObstacleShape::Circle { center: 0.0, radius: 1.0 },
                approach: 0.01,
                shift: if mu > 0.0 { 0.004 } else { 0.0 },
            },
            multiplier_points: MultiplierPoints::RatioToFe(1.0),
            multiplier_space: MultiplierSpace::P1,
        };
        let problem = Problem::new(mesh, spec)?;
        let mut settings = SolverSettings::default();
        if std::env::var("TRIBO_FAER").is_ok() {
            settings.qp.kkt_solver = KktSolver::Faer;
        }
        if let Ok(w) = std::env::var("TRIBO_THETA") {
            settings.stabilization = Stabilization::Fraction(w.parse().unwrap());
        }
        if let Ok(w) = std::env::var("TRIBO_TOL") {
            settings.qp.tol = w.parse().unwrap();
        }
        if let Ok(w) = std::env::var("TRIBO_RELAX") {
            settings.fixed_point.relaxation = w.parse().unwrap();
        }
        let friction = if mu > 0.0 { Friction::Coulomb { mu } } else { Friction::Frictionless };
        let t = std::time::Instant::now();
        let sol = problem.solve(&friction, &settings, None)?;
        let el = t.elapsed().as_secs_f64();
        let p = sol.normal_force;
        let nu = 0.3;
        let a = (4.0 * p * 1.0 * (1.0 - nu * nu) / (std::f64::consts::PI * 200.0)).sqrt();
        let hertz =
            |x: f64| if x.abs() < a { 2.0 * p / (std::f64::consts::PI * a * a) * (a * a - x * x).sqrt() } else { 0.0 };
        let (mut num, mut den) = (0.0, 0.0);
        // L2 error by fine sampling of the P1 multiplier.
        let m = &problem.multipliers;
        let nsamp = 20000;
        for k in 0..nsamp {
            let x = -2.0 + 4.0 * (k as f64 + 0.5) / nsamp as f64;
            let l = m.evaluate(&sol.lambda_n, x);
            num += (l - hertz(x)).powi(2);
            den += hertz(x).powi(2);
        }
        let n_contact = sol.states.iter().filter(|s| **s != ContactState::Separation).count();
        let n_slip = sol.states.iter().filter(|s| **s == ContactState::Slip).count();
        println!(
            "h_min {h_min}: n_free {} q {} P {p:.6} a {a:.4} relL2 {:.4e} kkt {:.2e} status {:?} its {} contact {n_contact} slip {n_slip} pen {:.2e} time {el:.3}s {:?}",
            problem.n_free,
            problem.n_multipliers(),
            (num / den).sqrt(),
            sol.kkt.max(),
            sol.report.status,
            sol.report.iterations,
            sol.max_penetration,
            sol.report.timings
        );
        if std::env::var("TRIBO_DEBUG").is_ok() {
            println!(
                "history {:?}\nqp its {:?}\nkkt {:?}",
                sol.report.residual_history, sol.report.qp_iterations, sol.kkt
            );
        }
    }
    Ok(())
}
