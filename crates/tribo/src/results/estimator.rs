//! A posteriori error estimate of a solve: a residual indicator η_K per triangle for the stabilized
//! method (P1 displacements, P0 or P1 multipliers on their own mesh T_H, any friction law, any load
//! step), split into its parts, and an estimate of the error of the contact tractions on Γ_C, the
//! quantity users read.
//!
//! # The indicator
//! With σ_h = σ(u_h) constant on each triangle (so `div σ_h = 0` there), h_K the diameter of K and
//! h_E = |E| the length of an edge, every term is a residual of one equation of the problem, measured
//! in the units of `stress² × area` (so that `η² / E*` is an energy, E* = E / (1 − ν²) of the in-plane material:
//! E itself in plane stress; each triangle's own where a body has several materials, and the relative energy
//! estimate reads `Σ_K η_K² / E*_K`):
//!
//! * **bulk** (the equilibrium (2.1) and the boundary conditions (2.4)):
//!   `h_K² ‖f‖²_K` (body load; `‖f + div σ_h‖` in axisymmetry, whose norms are all 2π r-weighted:
//!   [`crate::fem::axisymmetric`]), `½ h_E ‖[σ_h n]‖²_E` on each interior edge (half to each side),
//!   `h_E ‖σ_h n − F‖²_E` on each Neumann edge (F the traction, 0 on a free edge) and, on a roller or a
//!   component left free by a prescribed displacement, the traction component along the free direction;
//! * **Γ_C**: `h_E ‖λ_H + σ_h n‖²_E`, normal and tangential: the very residual the Barbosa–Hughes term
//!   penalizes, integrated exactly on the common refinement of the FE edges and T_H (both factors are
//!   polynomials on each piece);
//! * **contact** (the conditions (2.5)): the penetration `E*² h_E⁻¹ ‖(u_n − g)₊‖²_E` with the obstacle's
//!   own gap g(ξ) between the nodes (composite Gauss, [`SUBDIVISIONS`] × 3 points per edge, and pieces
//!   halving toward each of the obstacle's lowest points inside an edge, so an obstacle that dips between
//!   two nodes of a coarse mesh is seen however narrow the dip), and the complementarity
//!   `E* |∫_E λ_Hn (g − u_n)|`;
//! * **friction** (the law (2.6)): the cone violation `h_E ‖(|λ_Ht| − b_H)₊‖²_E` (b_H the threshold μ λ_Hn
//!   or the Tresca one, in W_H) and the dissipation gap `E* |∫_E (b_H |Δu_t| − λ_Ht Δu_t)|` with Δu_t the
//!   slip relative to the obstacle (the slip increment in a history step).
//!
//! The Γ_C, contact and friction terms of an edge of Γ_C go to the triangle that owns it. The terms
//! follow the residual estimators of Coorevits, Hild and Hjiaj (2001, the paper's [17]) for contact with
//! Lagrange multipliers and of Hild and Lleras (2009) for Coulomb friction; Chouly et al. (2018) give the
//! Nitsche analogue, whose `h_E ‖λ + σ n‖²` term is the stabilized one above. The complementarity and
//! dissipation terms enter the energy bound unsquared (they are energies), hence the factor E*; the
//! penetration is a displacement, hence E*² h_E⁻¹ (a trace in H^{1/2} at the scale of the edge).
//!
//! # The traction estimate
//! On Γ_C, `‖λ − λ_H‖ ≤ ‖λ_H + σ_h n‖ + ‖(σ − σ_h) n‖`. The first term is computed; the second is the
//! trace of the stress error, which is not local: a residual anywhere in the body changes the tractions
//! on Γ_C (a coarse layer under a finely cut contact surface makes the body too stiff there and moves the
//! edge of contact). Write the traction error at ξ ∈ Γ_C with the Riesz representer G_ξ of the boundary
//! traction at ξ (`a(v, G_ξ) = σ(v) n (ξ)`): `(σ − σ_h) n (ξ) = R(G_ξ)`, R the residual, and
//! `|R(G_ξ)| ≤ Σ_K η_K ‖∇G_ξ‖_K ≲ Σ_K η_K h_K / (h_K + d_K(ξ))²` (the traction of a point load
//! decays as 1/r in two dimensions, so ∇G_ξ as 1/r², and ‖∇G_ξ‖_K ≈ |K|^{1/2} r⁻²). Squaring and
//! integrating over ξ (Cauchy–Schwarz with the weight (h_K + d_K)⁻¹, whose sum over a mesh graded toward
//! Γ_C grows only as the logarithm of the number of layers) gives
//!
//! `‖(σ − σ_h) n‖²_{L²(Γ_C)} ≲ Σ_K w_K η_K²`, with `w_K = h_K² / (h_K + d_K)³`,
//!
//! d_K the distance from K to Γ_C. A triangle on Γ_C (d_K = 0) weighs `1 / h_K`, the trace inequality at
//! its own scale; the triangles under it count as much as long as they are no larger than their depth;
//! a triangle far from Γ_C counts as `h_K² / d_K³`.
//!
//! The contact and friction conditions enter in units of traction, as the residuals of their
//! projections with `c = E* / h_E` (the stiffness of the edge's scale): the complementarity
//! `min(λ_Hn, c (g − u_n)₊)`, the penetration `c (u_n − g)₊` and the friction law
//! `λ_Ht − P_[−b_H, b_H](λ_Ht + c Δu_t)` (which holds the cone), each zero exactly where its condition
//! holds. Their energy forms in η_K (complementarity and dissipation, unsquared) cannot be moved over by
//! the trace weight: `|∫_E …| / h_E` is a mean over the edge, and a sum of means over 1/h edges does not
//! fall with h.
//!
//! The traction estimate is `ζ² = Σ_K ζ_K²`, `ζ_K² = w_K (η_K,bulk² + η_K,Γ_C²) + ‖conditions‖²_{∂K∩Γ_C}`
//! (η_K,Γ_C² is `h_E ‖λ_H + σ_h n‖²_E`, so the computed term is in it), an estimate of
//! `‖λ − λ_H‖²_{L²(Γ_C)}` (normal and tangential together) up to a constant that does not depend on h.
//! [`ErrorEstimate::traction_relative`] is `ζ / min(‖λ_H‖, ‖σ_h n‖)` in L²(Γ_C): both estimate ‖λ‖, and
//! the smaller keeps a multiplier that oscillates (the classic method with T_H finer than the FE edges,
//! whose checkerboard inflates ‖λ_H‖) from hiding its own error. The weights are [`traction_weights`];
//! ζ_K is [`crate::Solution::traction_estimator`].
//!
//! The bound does not use Galerkin orthogonality (`R(G_ξ) = R(G_ξ − I_h G_ξ)`), which would add a
//! factor `(h_K / (h_K + d_K))²` to w_K: on the layers under the contact zone of a graded or adapted
//! mesh h_K ≈ d_K and the factor is of order one, while G_ξ is too rough near ξ for the interpolation
//! estimate to hold. Measured (study 6, off-centre Hertz): with the factor, the estimate is steadier
//! against the true error but the adaptive loop it drives needs about 30 % more unknowns for 1 % in λ_n,
//! because it lets the layers under the contact stay coarse; without it, as here, the estimate is the
//! more pessimistic of the two (see `docs/adaptive.md` for its effectivity).

use crate::contact::mortar::common_refinement;
use crate::contact::pair::PrimarySide;
use crate::fem::axisymmetric::{radial_weight, residual};
use crate::fem::elasticity::{Material, MaterialField, Materials, Model, Traction};
use crate::fem::supports::{Dofs, NodeSupport};
use crate::mesh::Mesh;
pub(crate) use crate::results::gamma_c::SideInput;
use crate::results::gamma_c::{penetration_pieces, side_weights};

/// Sub-intervals per FE edge of Γ_C for the terms whose integrand is not a polynomial there (the
/// positive parts, |Δu_t|, a gap that is not a parabola).
pub const SUBDIVISIONS: usize = 8;

/// 3-point Gauss–Legendre on [−1, 1].
const GAUSS3: [(f64, f64); 3] =
    [(-0.774_596_669_241_483_4, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)];

/// The totals of the estimate (each the square root of a sum of squares over the triangles), and the
/// hierarchical traction estimate when it was computed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ErrorEstimate {
    /// `η = (Σ_K η_K²)^{1/2}`.
    pub total: f64,
    /// The bulk part: body load, interior jumps, Neumann and free-direction residuals.
    pub bulk: f64,
    /// The Γ_C part: `(Σ_E h_E ‖λ_H + σ_h n‖²_E)^{1/2}`.
    pub gamma_c: f64,
    /// The contact part: penetration and complementarity.
    pub contact: f64,
    /// The friction part: cone violation and dissipation gap.
    pub friction: f64,
    /// `(Σ_K η_K² / E*_K)^{1/2} / a(u_h, u_h)^{1/2}` (`η / (E* a(u_h, u_h))^{1/2}` for one material): the
    /// relative energy estimate (dimensionless).
    pub energy_relative: f64,
    /// `ζ`, the estimate of `‖λ − λ_H‖_{L²(Γ_C)}` (see the module documentation).
    pub traction: f64,
    /// `ζ / min(‖λ_H‖, ‖σ_h n‖)` in L²(Γ_C) (NaN when λ_H = 0: nothing touches).
    pub traction_relative: f64,
    /// The hierarchical estimate of the traction error in L²(Γ_C) (λ_f the answer of the problem enriched, the
    /// whole mesh bisected and the strip along the contact zone again, by the adaptive loop with
    /// [`crate::settings::StopOn::Hierarchical`] or by [`crate::Problem::solve_with_error_bars`]): `1.5 ‖λ_H − λ_f‖`,
    /// with the reduction
    /// measured instead of assumed where the contact zone reaches an end of Γ_C ([`crate::adapt::enriched`]
    /// derives it). Sharp where the bound ζ is pessimistic, but not a guaranteed bound; infinite where
    /// a measured reduction is 1 or more (no estimate). On the enriched answer an adaptive loop with
    /// [`crate::settings::StopOn::Enriched`] hands back, the estimate of that answer's own error, `½ ‖λ_H − λ_f‖`
    /// (λ_H the level's answer it enriched; `q D_R / (1 − q²)` at measured ends; [`crate::adapt`]). `None` unless it
    /// was computed (NaN by
    /// [`Self::named`]).
    pub traction_hierarchical: Option<f64>,
    /// `traction_hierarchical / ‖λ_f‖` in L²(Γ_C) (`None` unless computed).
    pub traction_hierarchical_relative: Option<f64>,
    /// The calibrated bound, on a level of an adaptive loop right after a level where the hierarchical estimate was
    /// computed and found below the bound: this level's `traction_relative` times that level's ratio of the two
    /// (`None` elsewhere; [`crate::adapt`], section "The calibrated bound", derives it and says what it assumes).
    /// Sharp where the bound is pessimistic, not a guaranteed bound.
    pub traction_calibrated_relative: Option<f64>,
    /// The error bars of the forces and zone widths, from the same enriched solve (`None` unless it was
    /// computed; NaN by [`Self::named`]).
    pub error_bars: Option<ErrorBars>,
}

/// Estimates of the errors of what users read, each from the answer λ_H and the answer λ_f of the problem
/// enriched for the hierarchical estimate ([`crate::Problem::estimate_error_bars`]; [`crate::adapt::enriched`] derives
/// them): the absolute errors of [`crate::Solution::normal_force`], [`crate::Solution::tangential_force`],
/// [`crate::Solution::contact_width`] and [`crate::Solution::stick_width`]. Like the hierarchical traction
/// estimate, sharp but not guaranteed bounds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ErrorBars {
    /// `1.5 |P_H − P_f|`, P = ∫ λ_n.
    pub normal_force: f64,
    /// `1.5 |Q_H − Q_f|`, Q = ∫ λ_t.
    pub tangential_force: f64,
    /// `max(1.5 |w_H − w_f|, r_H)`, w the width of the contact zone and r_H its resolution
    /// ([`crate::results::Zone::resolution`]).
    pub contact_width: f64,
    /// The same for the stick zone.
    pub stick_width: f64,
}

impl ErrorEstimate {
    /// Every total by name, in the order of the fields (an estimate not computed is NaN).
    pub fn named(&self) -> [(&'static str, f64); 15] {
        let bars = self.error_bars.unwrap_or(ErrorBars {
            normal_force: f64::NAN,
            tangential_force: f64::NAN,
            contact_width: f64::NAN,
            stick_width: f64::NAN,
        });
        [
            ("total", self.total),
            ("bulk", self.bulk),
            ("gamma_c", self.gamma_c),
            ("contact", self.contact),
            ("friction", self.friction),
            ("energy_relative", self.energy_relative),
            ("traction", self.traction),
            ("traction_relative", self.traction_relative),
            ("traction_hierarchical", self.traction_hierarchical.unwrap_or(f64::NAN)),
            ("traction_hierarchical_relative", self.traction_hierarchical_relative.unwrap_or(f64::NAN)),
            ("traction_calibrated_relative", self.traction_calibrated_relative.unwrap_or(f64::NAN)),
            ("normal_force_error", bars.normal_force),
            ("tangential_force_error", bars.tangential_force),
            ("contact_width_error", bars.contact_width),
            ("stick_width_error", bars.stick_width),
        ]
    }
}

/// What the estimator reads of a problem and its solution.
pub(crate) struct EstimatorInput<'a> {
    pub mesh: &'a Mesh,
    /// Every triangle's material (E* of a contact edge's terms is its triangle's).
    pub materials: &'a Materials,
    /// The primary side of a two-body pair: its contact edges carry the traction `+λ` (action and
    /// reaction), not a Neumann datum.
    pub primary: Option<&'a PrimarySide>,
    pub dofs: &'a Dofs,
    /// Every contact pair's side and fields, the first pair first.
    pub sides: Vec<SideInput<'a>>,
    /// The body force and the tractions by edge set, as they act in this load case.
    pub body_force: [f64; 2],
    pub tractions: Vec<(&'a [[usize; 2]], Traction)>,
    pub stress: &'a [[f64; 3]],
    /// Plane or axisymmetric, and in axisymmetry the hoop stress σ_θθ per triangle (empty otherwise).
    pub model: Model,
    pub hoop: &'a [f64],
    pub displacement: &'a [f64],
    /// The nodal pressure of the mixed formulation (empty for the displacement formulation): the energy
    /// norm is then `∫ 2μ ε:ε + ∫ p²/λ` ([`crate::fem::mixed::energy_norm`]).
    pub pressure: &'a [f64],
}

/// The four parts of η_K².
#[derive(Debug, Clone, Copy, Default)]
struct Parts {
    bulk: f64,
    gamma_c: f64,
    contact: f64,
    friction: f64,
}

impl Parts {
    fn sum(&self) -> f64 {
        self.bulk + self.gamma_c + self.contact + self.friction
    }
}

/// `σ n` for σ = (σ_xx, σ_yy, σ_xy).
fn traction(s: &[f64; 3], n: [f64; 2]) -> [f64; 2] {
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// The per-triangle indicators η_K and ζ_K (not squared) and the totals.
///
/// Each term of η² and ζ² has the units of a stress squared (times a length of the mesh): the
/// displacement-like fields (u, u_n, the slip, the gap) enter with E*, the stress-like ones (σ_h, λ_H,
/// the threshold, the loads) without. Multiplying the first by k_u, the second by k_σ and E by
/// k_σ / k_u therefore multiplies η and ζ by k_σ and leaves the relative estimates unchanged. The
/// estimate is computed so, with powers of two that bring both kinds to order one (exact: nothing
/// changes for data of ordinary size), and divided by k_σ after: for data of 1e-200 (or 1e200), or E of
/// 1e-300, the squares no longer underflow (or overflow).
pub(crate) fn estimate(input: &EstimatorInput<'_>) -> (Vec<f64>, Vec<f64>, ErrorEstimate) {
    let sup = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let stresses = input.stress.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    let sides = &input.sides;
    let over_sides = |f: &dyn Fn(&SideInput<'_>) -> f64| sides.iter().map(f).fold(0.0_f64, f64::max);
    let length = sup(input.displacement).max(over_sides(&|s| sup(s.u_n).max(sup(s.slip))));
    let stress = stresses.max(over_sides(&|s| sup(s.lambda_n).max(sup(s.lambda_t)).max(sup(s.threshold))));
    let power = |size: f64| if size > 0.0 && size.is_finite() { -(size.log2().round() as i32) } else { 0 };
    let (pu, ps) = (power(length), power(stress));
    if pu == 0 && ps == 0 {
        return estimate_scaled(input);
    }
    let (ku, ks, ke) = (2f64.powi(pu), 2f64.powi(ps), 2f64.powi(ps - pu));
    let times = |v: &[f64], k: f64| v.iter().map(|x| x * k).collect::<Vec<f64>>();
    let stress: Vec<[f64; 3]> = input.stress.iter().map(|s| s.map(|x| x * ks)).collect();
    let hoop = times(input.hoop, ks);
    let u = times(input.displacement, ku);
    let pressure = times(input.pressure, ks);
    let points = |v: &[[f64; 2]]| v.iter().map(|p| p.map(|x| x * ku)).collect::<Vec<[f64; 2]>>();
    // Each side's fields scaled, and its gap.
    let fields: Vec<[Vec<f64>; 5]> = sides
        .iter()
        .map(|s| {
            [times(s.lambda_n, ks), times(s.lambda_t, ks), times(s.threshold, ks), times(s.u_n, ku), times(s.slip, ku)]
        })
        .collect();
    let motions: Vec<[Vec<[f64; 2]>; 2]> = sides.iter().map(|s| [points(s.previous_u), points(s.contact_u)]).collect();
    let gaps: Vec<Box<dyn Fn(f64) -> f64 + '_>> =
        sides.iter().map(|s| Box::new(move |xi: f64| (s.gap)(xi) * ku) as Box<dyn Fn(f64) -> f64>).collect();
    let young = |m: &Material| Material { young: m.young * ke, ..*m };
    let materials = Materials {
        materials: input.materials.materials.iter().map(young).collect(),
        region: input.materials.region.clone(),
    };
    let scaled = EstimatorInput {
        mesh: input.mesh,
        materials: &materials,
        primary: input.primary,
        dofs: input.dofs,
        sides: sides
            .iter()
            .zip(&fields)
            .zip(&motions)
            .zip(&gaps)
            .map(|(((s, [ln, lt, b, un, slip]), [previous_u, contact_u]), gap)| SideInput {
                contact: s.contact,
                multipliers: s.multipliers,
                lambda_n: ln,
                lambda_t: lt,
                threshold: b,
                u_n: un,
                slip,
                previous_u,
                contact_u,
                gap: gap.as_ref(),
                lowest: s.lowest,
            })
            .collect(),
        body_force: input.body_force.map(|x| x * ks),
        tractions: input.tractions.iter().map(|(e, t)| (*e, t.scaled(ks))).collect(),
        stress: &stress,
        model: input.model,
        hoop: &hoop,
        displacement: &u,
        pressure: &pressure,
    };
    let (eta, zeta, e) = estimate_scaled(&scaled);
    let back = |v: Vec<f64>| v.into_iter().map(|x| x / ks).collect::<Vec<f64>>();
    let estimate = ErrorEstimate {
        total: e.total / ks,
        bulk: e.bulk / ks,
        gamma_c: e.gamma_c / ks,
        contact: e.contact / ks,
        friction: e.friction / ks,
        traction: e.traction / ks,
        ..e
    };
    (back(eta), back(zeta), estimate)
}

/// [`estimate`] on fields of ordinary size.
fn estimate_scaled(input: &EstimatorInput<'_>) -> (Vec<f64>, Vec<f64>, ErrorEstimate) {
    let mesh = input.mesh;
    let pts = mesh.points();
    // E* = E / (1 − ν²) of triangle t's (in-plane) material.
    let e_star = |t: usize| {
        let m = input.materials.at(t);
        m.young / (1.0 - m.poisson.powi(2))
    };
    let mut parts = vec![Parts::default(); mesh.n_triangles()];
    // The measure of a point: 1, or 2π r in axisymmetry (integrals over the solid or a surface of revolution).
    let radial = input.model.is_axisymmetric();
    let measure = |r: f64| if radial { radial_weight(r) } else { 1.0 };
    // Body load, and in axisymmetry the part of div σ_h that a constant stress leaves.
    let f = input.body_force;
    if f[0] != 0.0 || f[1] != 0.0 || radial {
        for (t, p) in parts.iter_mut().enumerate() {
            let (r, w) = if radial { residual(mesh, t, &input.stress[t], input.hoop[t], f) } else { (f, mesh.area(t)) };
            p.bulk += mesh.diameter(t).powi(2) * w * (r[0] * r[0] + r[1] * r[1]);
        }
    }

    // The triangles around each node, to find the neighbour across each edge without a map of the edges.
    let tris = mesh.triangles();
    let (start, around) =
        crate::mesh::grouped(mesh.n_nodes(), tris.iter().enumerate().flat_map(|(t, tri)| tri.map(|v| (v, t))));
    // Per Neumann edge, the vectors and the pressures given on it, summed (a pressure reads the edge's normal).
    let mut neumann: std::collections::HashMap<[usize; 2], ([f64; 2], f64)> = std::collections::HashMap::new();
    for (set, g) in &input.tractions {
        for &[a, b] in *set {
            let e = neumann.entry([a.min(b), a.max(b)]).or_insert(([0.0, 0.0], 0.0));
            match *g {
                Traction::Vector(v) => (e.0[0], e.0[1]) = (e.0[0] + v[0], e.0[1] + v[1]),
                Traction::Pressure(p) => e.1 += p,
            }
        }
    }
    // The primary's contact edges, with the abscissae they span on the secondary side.
    let first = &input.sides[0];
    let primary_edges = input.primary.map_or_else(Default::default, |p| p.edge_spans(first.contact));
    let on_contact: std::collections::HashSet<[usize; 2]> =
        input.sides.iter().flat_map(|s| &s.contact.edges).map(|e| [e.left.min(e.right), e.left.max(e.right)]).collect();
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (pa, pb) = (pts[a], pts[b]);
            // h_E = |E|, and |E| in the measure at its midpoint; CCW: the outward normal of a → b is (dy, −dx) / |E|.
            let len_m = mesh.edge_length(a, b);
            let len = len_m * measure(0.5 * (pa[0] + pb[0]));
            let n = [(pb[1] - pa[1]) / len_m, -(pb[0] - pa[0]) / len_m];
            let other = around[start[a]..start[a + 1]].iter().copied().find(|&t2| t2 != t && tris[t2].contains(&b));
            match other {
                // Interior edge, seen from both sides: half of h_E |E| |[σ n]|² to this side.
                Some(t2) => {
                    let (s1, s2) = (traction(&input.stress[t], n), traction(&input.stress[t2], n));
                    parts[t].bulk += 0.5 * len_m * len * ((s1[0] - s2[0]).powi(2) + (s1[1] - s2[1]).powi(2));
                }
                None => {
                    let key = [a.min(b), a.max(b)];
                    if on_contact.contains(&key) {
                        continue;
                    }
                    let s = traction(&input.stress[t], n);
                    let r2 = if let Some(spans) = primary_edges.get(&key) {
                        // The mean over the edge (of its two spans where it straddles a loop's cut).
                        let lambda = [first.lambda_n, first.lambda_t];
                        let residual = |x: &[f64; 2]| {
                            let mean = crate::contact::pair::traction_residual(
                                first.contact,
                                first.multipliers,
                                lambda,
                                s,
                                *x,
                            );
                            mean * (x[1] - x[0])
                        };
                        spans.iter().map(residual).sum::<f64>() / spans.iter().map(|x| x[1] - x[0]).sum::<f64>()
                    } else if input.dofs.edges.contains(&key) {
                        // Γ_D: the traction along a direction the supports leave free must vanish.
                        let free = [a, b].into_iter().find_map(|node| match input.dofs.nodes[node] {
                            NodeSupport::Slide { tangent, .. } => Some(tangent),
                            _ => None,
                        });
                        free.map_or(0.0, |d| (s[0] * d[0] + s[1] * d[1]).powi(2))
                    } else {
                        let (v, p) = neumann.get(&key).copied().unwrap_or(([0.0, 0.0], 0.0));
                        let g = [v[0] - p * n[0], v[1] - p * n[1]];
                        (s[0] - g[0]).powi(2) + (s[1] - g[1]).powi(2)
                    };
                    parts[t].bulk += len_m * len * r2;
                }
            }
        }
    }

    // Γ_C: the stabilized residual, contact and friction, edge by edge on the common refinement.
    let mut lambda_l2 = 0.0;
    let mut sigma_l2 = 0.0;
    let mut zeta2 = 0.0;
    // The contact and friction conditions in units of traction, squared and integrated, per triangle.
    let mut conditions = vec![0.0; mesh.n_triangles()];
    for side in &input.sides {
        let contact = side.contact;
        let mult = side.multipliers;
        // u_n and the slip at the two ends of each edge, in the edge's own frame (a node's values read the node's
        // normal, the mean of its edges' on a bent Γ_C).
        let in_frame = |nodal: &[f64], k: usize, tangential: bool| -> [f64; 2] {
            [k, k + 1].map(|j| {
                if contact.one_frame {
                    return nodal[j];
                }
                // The slip is an increment: from the previous displacement (0 but in a history).
                let from = if tangential { side.previous_u.get(j).copied().unwrap_or([0.0, 0.0]) } else { [0.0, 0.0] };
                let (now, e) = (side.contact_u[j], &contact.edges[k]);
                let u = [now[0] - from[0], now[1] - from[1]];
                let (a, b) =
                    if tangential { (e.tangent, contact.node_tangent(j)) } else { (e.normal, contact.node_normal(j)) };
                nodal[j] + u[0] * (a[0] - b[0]) + u[1] * (a[1] - b[1])
            })
        };
        let pieces = common_refinement(&contact.node_xi, &mult.xi);
        let value = |values: &[f64], cell: usize, xi: f64| -> f64 {
            let (b, nb) = mult.basis(cell, xi);
            b[..nb].iter().map(|&(j, v)| v * values[j]).sum()
        };
        for piece in &pieces {
            let e = &contact.edges[piece.edge];
            let (nrm, tng) = (e.normal, e.tangent);
            let s = &input.stress[e.triangle];
            let sn = traction(s, e.outward);
            let (sigma_n, sigma_t) = (sn[0] * nrm[0] + sn[1] * nrm[1], sn[0] * tng[0] + sn[1] * tng[1]);
            let (x0, x1) = (contact.node_xi[piece.edge], contact.node_xi[piece.edge + 1]);
            let (u_n, slip) = (in_frame(side.u_n, piece.edge, false), in_frame(side.slip, piece.edge, true));
            let along = |ends: [f64; 2], xi: f64| {
                let w = (xi - x0) / (x1 - x0);
                (1.0 - w) * ends[0] + w * ends[1]
            };
            let ends_r = [contact.node_points[piece.edge][0], contact.node_points[piece.edge + 1][0]];
            let (mut gc, mut comp, mut cone, mut diss, mut lam, mut ncp) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
            // c = E* / h_E turns a displacement into a traction at the scale of the edge.
            let e_star = e_star(e.triangle);
            let c = e_star / e.length;
            let half = 0.5 * (piece.b - piece.a);
            for (x, w) in GAUSS3 {
                let xi = piece.a + half * (x + 1.0);
                let wq = w * half * measure(along(ends_r, xi));
                let (ln, lt, b) = (
                    value(side.lambda_n, piece.cell, xi),
                    value(side.lambda_t, piece.cell, xi),
                    value(side.threshold, piece.cell, xi),
                );
                gc += wq * ((ln + sigma_n).powi(2) + (lt + sigma_t).powi(2));
                lam += wq * (ln * ln + lt * lt);
                sigma_l2 += wq * (sigma_n * sigma_n + sigma_t * sigma_t);
                comp += wq * ln * ((side.gap)(xi) - along(u_n, xi));
                cone += wq * (lt.abs() - b).max(0.0).powi(2);
                let du = along(slip, xi);
                diss += wq * (b * du.abs() - lt * du);
                // The conditions as residuals of their projections (zero exactly when they hold): the
                // complementarity min(λ_n, c (g − u_n)₊) (penetration is the term below) and the friction
                // law λ_t − P_[−b, b](λ_t + c Δu_t).
                let rn = ln.min(c * ((side.gap)(xi) - along(u_n, xi)).max(0.0));
                let rt = lt - (lt + c * du).clamp(-b.max(0.0), b.max(0.0));
                ncp += wq * (rn * rn + rt * rt);
            }
            conditions[e.triangle] += ncp;
            let p = &mut parts[e.triangle];
            p.gamma_c += e.length * gc;
            p.contact += e_star * comp.abs();
            p.friction += e.length * cone + e_star * diss.abs();
            lambda_l2 += lam;
        }
        // Penetration, with the obstacle's own gap between the nodes.
        for (k, e) in contact.edges.iter().enumerate() {
            let (x0, x1) = (contact.node_xi[k], contact.node_xi[k + 1]);
            let u_n = in_frame(side.u_n, k, false);
            let mut pen = 0.0;
            for w in penetration_pieces(x0, x1, side.lowest).windows(2) {
                let half = 0.5 * (w[1] - w[0]);
                for (x, wg) in GAUSS3 {
                    let xi = w[0] + half * (x + 1.0);
                    let s = (xi - x0) / (x1 - x0);
                    let un = (1.0 - s) * u_n[0] + s * u_n[1];
                    let r = (1.0 - s) * contact.node_points[k][0] + s * contact.node_points[k + 1][0];
                    pen += half * wg * measure(r) * (un - (side.gap)(xi)).max(0.0).powi(2);
                }
            }
            // As squares of products: E*² alone overflows for E* beyond 1e154, and ∞ · 0 where nothing
            // penetrates would be NaN (defect D29).
            let (root, e_star) = (pen.sqrt(), e_star(e.triangle));
            parts[e.triangle].contact += (e_star * root).powi(2) / e.length;
            conditions[e.triangle] += (e_star / e.length * root).powi(2);
        }
    }
    let weights = side_weights(mesh, &input.sides);
    let zeta: Vec<f64> = parts
        .iter()
        .zip(&weights)
        .zip(&conditions)
        .map(|((p, w), c)| {
            let z2 = w * (p.bulk + p.gamma_c) + c;
            zeta2 += z2;
            z2.sqrt()
        })
        .collect();

    let eta: Vec<f64> = parts.iter().map(|p| p.sum().sqrt()).collect();
    let total = |f: fn(&Parts) -> f64| parts.iter().map(f).sum::<f64>().sqrt();
    let energy = if input.pressure.is_empty() {
        crate::fem::elasticity::energy_norm(input.model, mesh, input.materials, input.displacement)
    } else {
        crate::fem::mixed::energy_norm(input.model, mesh, input.materials, input.displacement, input.pressure)
    };
    let eta_total = total(Parts::sum);
    // η² / E* is an energy: each triangle's part over its own E* (one E* for a body of one material).
    let eta_energy = parts.iter().enumerate().map(|(t, p)| p.sum() / e_star(t)).sum::<f64>().sqrt();
    let estimate = ErrorEstimate {
        total: eta_total,
        bulk: total(|p| p.bulk),
        gamma_c: total(|p| p.gamma_c),
        contact: total(|p| p.contact),
        friction: total(|p| p.friction),
        energy_relative: if eta_total == 0.0 { 0.0 } else { eta_energy / energy },
        traction: zeta2.sqrt(),
        // ‖λ‖ estimated by the smaller of ‖λ_H‖ and ‖σ_h n‖: a checkerboard inflates ‖λ_H‖ and would
        // hide its own error behind it.
        traction_relative: if lambda_l2 > 0.0 { (zeta2 / lambda_l2.min(sigma_l2)).sqrt() } else { f64::NAN },
        ..ErrorEstimate::default()
    };
    (eta, zeta, estimate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactBoundary;
    use crate::mesh::generate::{rectangle, Diagonal};
    use crate::results::gamma_c::traction_weights;

    /// The penetration pieces of an edge: the equal ones, and around a lowest point inside the edge pieces
    /// halving toward it, so that a dip of any width about it holds Gauss points; points outside the edge
    /// add nothing.
    #[test]
    fn the_penetration_pieces_close_in_on_the_lowest_points() {
        let equal = penetration_pieces(0.0, 1.0, &[-1.0, 1.0, 2.0]);
        assert_eq!(equal, (0..=SUBDIVISIONS).map(|m| m as f64 / SUBDIVISIONS as f64).collect::<Vec<_>>());
        let c = 0.3;
        let pieces = penetration_pieces(0.0, 1.0, &[-1.0, c, 2.0]);
        assert!(pieces.windows(2).all(|w| w[0] < w[1]) && pieces[0] == 0.0 && pieces[pieces.len() - 1] == 1.0);
        assert!(pieces.contains(&c));
        // On each side of c, a piece no longer than 2⁻⁴⁰ of the edge ends at c.
        let at = pieces.iter().position(|&x| x == c).expect("c is a break");
        assert!(c - pieces[at - 1] <= 2f64.powi(-40) && pieces[at + 1] - c <= 2f64.powi(-40));
    }

    /// A triangle on Γ_C weighs 1/h_K (the trace inequality at its own scale); one at depth d weighs
    /// h_K²/(h_K + d)³, so a layer of triangles no larger than its depth counts alike and a far one
    /// fades as d⁻³.
    #[test]
    fn the_traction_weight_falls_with_the_distance_to_gamma_c() {
        // A test of fixed, valid data: a 4 × 4 square and its straight top side.
        let mesh = rectangle([0.0, 4.0], [0.0, 4.0], 4, 4, Diagonal::Right).expect("valid");
        let contact = ContactBoundary::new(&mesh, "top").expect("straight");
        let w = traction_weights(&mesh, &contact);
        let h = mesh.diameter(0);
        for (t, &wt) in w.iter().enumerate() {
            let depth = mesh.vertices(t).iter().map(|p| 4.0 - p[1]).fold(f64::INFINITY, f64::min);
            let expected = h * h / (h + depth).powi(3);
            assert!((wt - expected).abs() <= 1e-12 * expected, "triangle {t}: {wt} against {expected}");
        }
        let on = (0..mesh.n_triangles()).filter(|&t| mesh.vertices(t).iter().any(|p| p[1] == 4.0));
        assert!(on.into_iter().all(|t| (w[t] - 1.0 / h).abs() <= 1e-12 / h));
    }
}
