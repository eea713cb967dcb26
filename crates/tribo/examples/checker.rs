use tribo::*;
fn main() -> Result<()> {
    let n: usize = std::env::args().nth(1).map_or(40, |s| s.parse().unwrap());
    let ratio: f64 = std::env::args().nth(2).map_or(0.5, |s| s.parse().unwrap());
    let mesh = rectangle([-2.0, 2.0], [-2.0, 0.0], 2 * n, n, Diagonal::Right)?;
    for (name, stab) in [
        ("γ0=0", Stabilization::None),
        ("θ=0.05", Stabilization::Fraction(0.05)),
        ("θ=0.2", Stabilization::Fraction(0.2)),
        ("θ=0.5", Stabilization::Fraction(0.5)),
        ("θ=0.9", Stabilization::Fraction(0.9)),
    ] {
        let spec = ProblemSpec {
            material: Material { young: 200.0, poisson: 0.3 },
            clamped: vec!["bottom".into()],
            body_force: [0.0, 0.0],
            tractions: vec![],
            contact: "top".into(),
            obstacle: Obstacle {
                shape: ObstacleShape::Circle { center: 0.0, radius: 1.0 },
                approach: 0.05,
                shift: 0.0,
            },
            multiplier_points: MultiplierPoints::RatioToFe(ratio),
            multiplier_space: MultiplierSpace::P1,
        };
        let problem = Problem::new(mesh.clone(), spec)?;
        let mut settings = SolverSettings::default();
        settings.stabilization = stab;
        let sol = problem.solve(&Friction::Frictionless, &settings, None)?;
        let p = sol.normal_force;
        let a = (4.0 * p * (1.0 - 0.09) / (std::f64::consts::PI * 200.0)).sqrt();
        let tv: f64 = sol.lambda_n.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
        let pmax = 2.0 * p / (std::f64::consts::PI * a);
        println!(
            "{name}: q {} P {p:.4} a {a:.3} TV/TVhertz {:.3} status {:?} kkt {:.1e} minλ {:.2e}",
            problem.n_multipliers(),
            tv / (2.0 * pmax),
            sol.report.status,
            sol.kkt.max(),
            sol.lambda_n.iter().cloned().fold(f64::INFINITY, f64::min)
        );
        if std::env::var("SHOW").is_ok() {
            let mid = sol.lambda_n.len() / 2;
            println!(
                "   {:?}",
                &sol.lambda_n[mid - 6..mid + 6].iter().map(|v| (v * 100.0).round() / 100.0).collect::<Vec<_>>()
            );
        }
    }
    Ok(())
}
