//! The roller on a rigid flat (issue 39, `tests/integration/curved.rs` and study 22, the example `roller`): a
//! bent Γ_C, the faceted rim of a ring sector, against plane-strain Hertz and against itself on a finer mesh.
//!
//! The roller has radius R = 1, centre (0, 1): the sector ±1.2 rad around its lowest point between the radii
//! 0.25 and 1, clamped on the inner arc, pressed by `approach` onto the rigid flat y = 0 (a line obstacle:
//! the contact acts along the flat's normal), E = 1, ν = 0.3, plane strain, P1 multipliers on the FE edges.

use std::f64::consts::{FRAC_PI_2, PI};

use tribo::*;

/// Young's modulus and Poisson's ratio of the roller.
pub const ROLLER_MATERIAL: Material = Material { young: 1.0, poisson: 0.3 };

/// `R p + c` for the rotation `r` = (cos θ, sin θ).
pub fn moved([cos, sin]: [f64; 2], c: [f64; 2], p: [f64; 2]) -> [f64; 2] {
    [cos * p[0] - sin * p[1] + c[0], sin * p[0] + cos * p[1] + c[1]]
}

/// The roller graded at `growth` to `h_min` over ±0.1 rad of its lowest point (a uniform mesh where
/// `h_min` = `h_max` = 0.1), moved by the rotation `r` and the translation `c` with its flat, pressed by
/// `approach`, the flat shifted `shift`.
pub fn roller_problem(h_min: f64, growth: f64, r: [f64; 2], c: [f64; 2], approach: f64, shift: f64) -> Problem {
    roller_graded(h_min, growth, 0.1, r, c, approach, shift)
}

/// [`roller_problem`] graded over ±`arc` rad of the lowest point.
pub fn roller_graded(
    h_min: f64,
    growth: f64,
    arc: f64,
    r: [f64; 2],
    c: [f64; 2],
    approach: f64,
    shift: f64,
) -> Problem {
    let sector = RingSector { center: [0.0, 1.0], radii: [0.25, 1.0], angles: [-FRAC_PI_2 - 1.2, -FRAC_PI_2 + 1.2] };
    let grading = ArcGrading { angles: [-FRAC_PI_2 - arc, -FRAC_PI_2 + arc], h_min, h_max: 0.1_f64.max(h_min), growth };
    // Internal invariants of this dev-only kit (no user input reaches it): the callers pass positive sizes
    // with h_min ≤ 0.1 and an arc inside the sector, a rigid motion keeps every triangle valid, and the roller
    // is a valid problem (tests/integration/curved.rs solves it); a broken fixture panics with the message.
    let mesh = ring_sector(&sector, &grading).expect("the calling test's own valid sizes");
    let points = mesh.points().iter().map(|&p| moved(r, c, p)).collect();
    let mesh = Mesh::new(points, mesh.triangles().to_vec(), mesh.edge_sets().clone()).expect("a rigid motion");
    let spec = ProblemSpec::new(ROLLER_MATERIAL, "outer")
        .clamped(["inner"])
        .obstacle(ObstacleShape::Line { point: moved(r, c, [0.0, 0.0]), normal: moved(r, [0.0; 2], [0.0, 1.0]) })
        .approach(approach)
        .shift(shift);
    Problem::new(mesh, spec).expect("a roller on a flat")
}

/// The abscissa on Γ_C of the unmoved roller at horizontal position `x` (x is monotone along the rim).
fn abscissa_at(problem: &Problem, x: f64) -> f64 {
    let c = &problem.contact;
    let (mut lo, mut hi) = (c.start(), c.end());
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if c.point_at(mid)[0] < x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Hertz's pressure of force `p` on the roller and its half-width a (R = 1).
fn hertz(p: f64) -> (impl Fn(f64) -> f64, f64) {
    let e_star = ROLLER_MATERIAL.young / (1.0 - ROLLER_MATERIAL.poisson.powi(2));
    let a = (4.0 * p / (PI * e_star)).sqrt();
    let p0 = 2.0 * p / (PI * a);
    (move |x: f64| if x.abs() < a { p0 * (1.0 - (x / a).powi(2)).sqrt() } else { 0.0 }, a)
}

/// `(relative L2 error of λ_n against Hertz's pressure of the computed force, the second-moment width
/// 2 (∫ λ_n x² / P)^½ over Hertz's, a / R)` of the unmoved roller, x the horizontal distance from its lowest
/// point, integrated by 8-point Gauss on the pieces of T_H and Γ_C's nodes with Hertz's edges ±a among the
/// breaks (the second moment is exact for Hertz's pressure and not tied to where the mesh resolves the edge).
pub fn roller_against_hertz(problem: &Problem, sol: &Solution) -> (f64, f64, f64) {
    let (pressure, a) = hertz(sol.normal_force);
    let c = &problem.contact;
    let mut breaks: Vec<f64> = problem.multipliers.xi.iter().chain(&c.node_xi).copied().collect();
    breaks.extend([abscissa_at(problem, -a), abscissa_at(problem, a)]);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let (gx, gw) = crate::gauss8();
    let (mut num, mut den, mut moment) = (0.0, 0.0, 0.0);
    for w in breaks.windows(2) {
        let (h, m) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for (&g, &wt) in gx.iter().zip(&gw) {
            let xi = m + h * g;
            let (l, x) = (problem.multipliers.evaluate(&sol.lambda_n, xi), c.point_at(xi)[0]);
            num += wt * h * (l - pressure(x)).powi(2);
            den += wt * h * pressure(x).powi(2);
            moment += wt * h * l * x * x;
        }
    }
    ((num / den).sqrt(), 2.0 * (moment / sol.normal_force).sqrt() / a, a)
}

/// The relative L2 difference of λ_n from a reference answer of the same roller (on another mesh), both read
/// at the horizontal position x over [−2a, 2a] (a Hertz's half-width of the reference's force), on 4000
/// pieces of 8-point Gauss.
pub fn roller_against_reference(problem: &Problem, sol: &Solution, reference: (&Problem, &Solution)) -> f64 {
    let (_, a) = hertz(reference.1.normal_force);
    let at = |p: &Problem, s: &Solution, x: f64| p.multipliers.evaluate(&s.lambda_n, abscissa_at(p, x));
    let (gx, gw) = crate::gauss8();
    let (mut num, mut den) = (0.0, 0.0);
    let n = 4000;
    let h = 2.0 * a / n as f64;
    for k in 0..n {
        let m = -2.0 * a + (2 * k + 1) as f64 * h;
        for (&g, &wt) in gx.iter().zip(&gw) {
            let x = m + h * g;
            let r = at(reference.0, reference.1, x);
            num += wt * h * (at(problem, sol, x) - r).powi(2);
            den += wt * h * r * r;
        }
    }
    (num / den).sqrt()
}
