use tribo::tresca::TrescaQp;
use tribo::*;
fn main() -> Result<()> {
    let h_min: f64 = std::env::args().nth(1).map_or(0.005, |s| s.parse().unwrap());
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
        obstacle: Obstacle { shape: ObstacleShape::Circle { center: 0.0, radius: 1.0 }, approach: 0.01, shift: 0.004 },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
    };
    let problem = Problem::new(mesh, spec)?;
    let c = Condensed::new(&problem, Stabilization::Fraction(0.5))?;
    let q = c.q();
    let mut qp0 = TrescaQp::new(&c.h_normal(), &c.c[..q], q, None, &QpSettings::default())?;
    let mut g = qp0.solve().nu;
    let mu = 0.3;
    let mut qp = TrescaQp::new(
        &c.h,
        &c.c,
        q,
        Some(&g.iter().map(|v| mu * v.max(0.0)).collect::<Vec<_>>()),
        &QpSettings::default(),
    )?;
    let x = problem.multipliers.dof_abscissae();
    for it in 0..40 {
        let out = qp.solve();
        let ln = &out.nu[..q];
        let lt = &out.nu[q..];
        if it >= 34 {
            let mut d: Vec<(usize, f64)> = (0..q).map(|j| (j, ln[j] - g[j])).collect();
            d.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
            println!("it {it} status {:?} top diffs:", out.status);
            for &(j, v) in &d[..4] {
                println!(
                    "   j {j} x {:.4} g {:.6e} ln {:.6e} diff {:.3e} lt {:.6e} bound {:.6e}",
                    x[j],
                    g[j],
                    ln[j],
                    v,
                    lt[j],
                    mu * g[j]
                );
            }
        }
        g = ln.iter().map(|v| v.max(0.0)).collect();
        qp.set_bounds(&g.iter().map(|v| mu * v).collect::<Vec<_>>())?;
    }
    Ok(())
}
