//! A shrink fit (issue 39: two bodies with a bent interface; `tests/integration/bent_pair.rs` and the example
//! `shrink_fit`): a ring pressed into a ring with a radial interference, a quarter of each by symmetry.
//!
//! The inner ring has radii `a` and `b + δ` (E = 1, ν = 0.3), the outer ring `b` and `c` (E = 2, ν = 0.25), both
//! in plane strain, held by rollers on the x and y axes. The inner ring's outer arc is the secondary side
//! (it carries P1 multipliers on its FE edges), the outer ring's inner arc the primary. The two arcs are
//! meshed independently: their nodes do not match.
//!
//! **Lamé's pressure, as posed.** The contact is written in the reference configuration, with the inner ring
//! of outer radius `r_s = b + δ` and the multiplier on it: under an external pressure λ its rim moves
//! `u_i = −λ C_i`, `C_i = (1 + ν_i) r_s ((1 − 2ν_i) r_s² + a²) / (E_i (r_s² − a²))`; the outer ring is loaded by
//! the same force per radian, the pressure `λ r_s / b` on its radius b, and moves `u_o = (λ r_s / b) C_o`,
//! `C_o = (1 + ν_o) b ((1 − 2ν_o) b² + c²) / (E_o (c² − b²))` (plane strain, e.g. Timoshenko–Goodier §28). The
//! jump closes the gap −δ: `u_i − u_o = −δ`, so `λ = δ / (C_i + C_o r_s / b)`, uniform.

use std::f64::consts::FRAC_PI_2;

use tribo::*;

use crate::moved;

/// The inner ring's material.
pub const INNER_MATERIAL: Material = Material { young: 1.0, poisson: 0.3 };
/// The outer ring's material.
pub const OUTER_MATERIAL: Material = Material { young: 2.0, poisson: 0.25 };

/// A shrink fit of a quarter ring in a quarter ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShrinkFit {
    /// The inner ring's inner radius a, the interface radius b and the outer ring's outer radius c.
    pub radii: [f64; 3],
    /// The radial interference δ (the inner ring's outer radius is b + δ).
    pub interference: f64,
    /// Cell sizes of the inner and the outer ring (along their outer arcs).
    pub h: [f64; 2],
    /// Whether the two arcs carry their circles ([`Curve::Arc`]): the gap is then that of the circles.
    pub curves: bool,
    /// A rigid motion of the whole scene: the rotation (cos θ, sin θ) and the translation.
    pub motion: ([f64; 2], [f64; 2]),
}

impl ShrinkFit {
    /// a = 0.5, b = 1, c = 2, δ = 10⁻³, with curves, at cell sizes `h`.
    pub fn new(h: [f64; 2]) -> Self {
        Self { radii: [0.5, 1.0, 2.0], interference: 1e-3, h, curves: true, motion: ([1.0, 0.0], [0.0, 0.0]) }
    }

    /// Lamé's contact pressure of the fit as posed (module documentation).
    pub fn lame_pressure(&self) -> f64 {
        let ([a, b, c], delta) = (self.radii, self.interference);
        let rs = b + delta;
        let (i, o) = (INNER_MATERIAL, OUTER_MATERIAL);
        let c_i = (1.0 + i.poisson) * rs * ((1.0 - 2.0 * i.poisson) * rs * rs + a * a) / (i.young * (rs * rs - a * a));
        let c_o = (1.0 + o.poisson) * b * ((1.0 - 2.0 * o.poisson) * b * b + c * c) / (o.young * (c * c - b * b));
        delta / (c_i + c_o * rs / b)
    }

    /// The two-body problem, `"inner.outer"` the secondary side, P1 multipliers on its FE edges.
    pub fn problem(&self) -> Problem {
        let ([a, b, c], delta) = (self.radii, self.interference);
        let ring = |radii: [f64; 2], h: f64, name: &str, material: Material| {
            let sector = RingSector { center: [0.0, 0.0], radii, angles: [0.0, FRAC_PI_2] };
            let grading = ArcGrading { angles: [0.0, FRAC_PI_2], h_min: h, h_max: h, growth: 0.1 };
            // Internal invariants of this dev-only kit, not reachable from user input (no user input reaches it):
            // the callers pass positive sizes below the radii, a rigid motion keeps every triangle valid and
            // every arc node on its moved circle, and the fit is a valid pair (`bent_pair.rs` solves it); a broken
            // fixture panics with the message.
            let ring = ring_sector(&sector, &grading).expect("the calling test's own valid sizes");
            let (r, t) = self.motion;
            let points = ring.points().iter().map(|&p| moved(r, t, p)).collect();
            let mut mesh =
                Mesh::new(points, ring.triangles().to_vec(), ring.edge_sets().clone()).expect("a rigid motion");
            if self.curves {
                for (set, radius) in [("inner", radii[0]), ("outer", radii[1])] {
                    let arc = Curve::Arc { center: moved(r, t, [0.0, 0.0]), radius };
                    mesh = mesh.with_curve(set, arc).expect("the arcs of a moved ring");
                }
            }
            Body {
                name: name.into(),
                materials: Materials::uniform(material, mesh.n_triangles()),
                mesh,
                clamped: vec![],
                supports: vec![Support::roller("start"), Support::roller("end")],
                tractions: vec![],
            }
        };
        let inner = ring([a, b + delta], self.h[0], "inner", INNER_MATERIAL);
        let outer = ring([b, c], self.h[1], "outer", OUTER_MATERIAL);
        // A valid pair by the invariants above.
        Problem::two_bodies([inner, outer], ring_pair(), [0.0, 0.0]).expect("a valid shrink fit")
    }
}

/// The pair of a ring `inner` in a ring `outer`: the inner ring's outer arc the secondary side, with P1 multipliers
/// on its FE edges, the outer ring's inner arc the primary, touching (the gap is the arcs'), plane strain.
pub fn ring_pair() -> ContactPair {
    ContactPair {
        secondary: "inner.outer".into(),
        primary: "outer.inner".into(),
        gap: ObstacleShape::Flat,
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        model: Model::PlaneStrain,
        formulation: Default::default(),
    }
}

/// The relative L2 error of λ_n on Γ_C against a uniform pressure `p` (with the multiplier basis, exactly
/// on T_H's cells by 2-point Gauss: λ_n is piecewise linear).
pub fn uniform_pressure_error(problem: &Problem, lambda_n: &[f64], p: f64) -> f64 {
    let mult = &problem.multipliers;
    let (mut err, mut norm) = (0.0, 0.0);
    for cell in 0..mult.xi.len() - 1 {
        let (x0, x1) = (mult.xi[cell], mult.xi[cell + 1]);
        for g in [-1.0 / 3f64.sqrt(), 1.0 / 3f64.sqrt()] {
            let x = 0.5 * (x0 + x1) + 0.5 * (x1 - x0) * g;
            let (b, nb) = mult.basis(cell, x);
            let l: f64 = b[..nb].iter().map(|&(j, v)| v * lambda_n[j]).sum();
            err += 0.5 * (x1 - x0) * (l - p).powi(2);
            norm += 0.5 * (x1 - x0) * p * p;
        }
    }
    (err / norm).sqrt()
}
