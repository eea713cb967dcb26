//! Results of a solve: fields as plain vectors, the contact state per multiplier dof, the discrete KKT
//! residuals of (3.1) and a report of how the solve ended.

use crate::choice::named_choice;
use crate::condensation::Factor;
use crate::elasticity::{element_stresses, stiffness_triplets};
use crate::friction::FrictionLaw;
use crate::loading::Loading;
use crate::problem::Condensed;
use crate::settings::{Condensation, QpMethod};

/// How a solve ended. Not an error: a solve that did not converge still returns its last iterate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SolveStatus {
    /// Every QP solved and (Coulomb) the fixed point converged.
    Converged,
    /// The fixed point reached its iteration cap.
    MaxIterations,
    /// The change of λ_n made no new minimum for [`crate::solve::STAGNATION_WINDOW`] iterations: the
    /// fixed point cycles, or it has reached the accuracy to which the QP determines λ (see the residual
    /// history; a tighter `qp.tol` or a finer mesh may help).
    Stagnated,
    /// The observer asked to stop after the given fixed-point iteration (0 = the initial QP).
    Interrupted {
        /// Fixed-point iteration.
        iteration: usize,
    },
    /// A QP failed at the given fixed-point iteration (0 = the initial QP).
    QpFailed {
        /// Fixed-point iteration.
        iteration: usize,
        /// clarabel's status.
        reason: &'static str,
    },
    /// The solve ran to its end but a reported field or residual is not finite (an overflow).
    NonFinite,
    /// The solve ran to its end but its KKT residuals exceed what the tolerances justify
    /// ([`Solution::accuracy_bound`]).
    Inaccurate,
}

impl SolveStatus {
    /// The names of the statuses, as [`SolveStatus::name`] gives them.
    pub const NAMES: [&'static str; 7] =
        ["converged", "max_iterations", "stagnated", "interrupted", "qp_failed", "non_finite", "inaccurate"];

    /// The status's name (without its data): one of [`SolveStatus::NAMES`].
    pub fn name(&self) -> &'static str {
        match self {
            Self::Converged => "converged",
            Self::MaxIterations => "max_iterations",
            Self::Stagnated => "stagnated",
            Self::Interrupted { .. } => "interrupted",
            Self::QpFailed { .. } => "qp_failed",
            Self::NonFinite => "non_finite",
            Self::Inaccurate => "inaccurate",
        }
    }
}

impl std::fmt::Display for SolveStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Interrupted { iteration } => write!(f, "interrupted after iteration {iteration}"),
            Self::QpFailed { iteration, reason } => write!(f, "qp_failed at iteration {iteration} ({reason})"),
            s => f.write_str(s.name()),
        }
    }
}

/// Contact state of a multiplier dof.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactState {
    /// λ_n = 0.
    Separation,
    /// In contact, |λ_t| below the threshold.
    Stick,
    /// In contact, |λ_t| at the threshold (μ λ_n or the Tresca bound); every contact dof of a
    /// frictionless problem (threshold 0) slips.
    Slip,
}

named_choice!(ContactState, "contact state", {
    ContactState::Separation => "separation",
    ContactState::Stick => "stick",
    ContactState::Slip => "slip",
});

/// Wall times per phase, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Stiffness and load assembly.
    pub assembly: f64,
    /// Γ_C geometry, T_H and the Γ_C matrices.
    pub contact_matrices: f64,
    /// Assembling and factorizing A = K − G.
    pub factorization: f64,
    /// Condensing onto the multipliers (H, c).
    pub condensation: f64,
    /// All QPs (including the fixed point).
    pub qp: f64,
    /// Recovering u.
    pub recovery: f64,
}

/// Discrete KKT residuals of (3.1) at the returned solution, each made dimensionless.
///
/// With `r = E u − d − Dγ λ` (the discrete, stabilized gap and slip: `r_n ≤ 0` is non-penetration),
/// `Λ = max(‖λ‖∞, Factor::lambda_scale, ‖bound‖∞)` (the size of the multipliers, tangential ones and a
/// Tresca threshold included) and `R = max(‖E‖ ‖u‖, ‖d‖, ‖Dγ λ‖)` (∞-norms; the size of the
/// terms of r, so that its round-off is ε R). A residual whose numerator vanishes is 0 whatever its scale:
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct KktResiduals {
    /// `‖A u + Eᵀ λ − f‖_∞ / max(‖f‖_∞, ‖Eᵀ λ‖_∞)`: the equation of (3.1).
    pub equilibrium: f64,
    /// `max(−λ_n)₊ / Λ`.
    pub normal_sign: f64,
    /// `max(r_n)₊ / R`: penetration in the weak sense of the method.
    pub non_penetration: f64,
    /// `max |λ_n r_n| / (Λ R)`.
    pub normal_complementarity: f64,
    /// `max(|λ_t| − bound)₊ / Λ` (bound = μ λ_n, or the Tresca threshold).
    pub friction_bound: f64,
    /// `max (bound − |λ_t|) |r_t| / (Λ R)`: no slip below the threshold.
    pub stick: f64,
    /// `max (−λ_t r_t)₊ / (Λ R)`: slip in the direction of λ_t.
    pub slip_direction: f64,
}

impl KktResiduals {
    /// Largest residual; NaN if any residual is NaN.
    pub fn max(&self) -> f64 {
        [
            self.equilibrium,
            self.normal_sign,
            self.non_penetration,
            self.normal_complementarity,
            self.friction_bound,
            self.stick,
            self.slip_direction,
        ]
        .into_iter()
        .fold(0.0, nan_max)
    }
}

/// The larger of two values, NaN if either is NaN (`f64::max` drops a NaN).
pub(crate) fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Report of a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// How it ended.
    pub status: SolveStatus,
    /// The friction law solved (Coulomb with μ = 0 is solved, and reported, as frictionless).
    pub friction: FrictionLaw,
    /// The Coulomb coefficient μ (`None` unless the law is Coulomb).
    pub mu: Option<f64>,
    /// Fixed-point iterations (0 for frictionless and Tresca).
    pub iterations: usize,
    /// Relative change of λ_n after each fixed-point iteration.
    pub residual_history: Vec<f64>,
    /// Iterations of each QP: interior-point iterations (clarabel) or steps (active set), including a
    /// failed active-set attempt before clarabel.
    pub qp_iterations: Vec<u32>,
    /// Factorizations among the active-set steps of each QP (see [`crate::QpOutcome::factorizations`]):
    /// the other steps updated the dense factor or bordered the sparse one. 0 for a clarabel answer.
    pub qp_factorizations: Vec<u32>,
    /// The method that answered each QP ([`QpMethod::Clarabel`] or [`QpMethod::ActiveSet`]).
    pub qp_methods: Vec<QpMethod>,
    /// How many QPs the first method tried did not answer, so that the other one did (see
    /// [`crate::QpOutcome::fallback`]).
    pub qp_fallbacks: usize,
    /// How many of those QPs met only [`crate::qp::FALLBACK_TOL`] (1e-10), not `qp.tol`: their λ is
    /// determined to about `FALLBACK_TOL · κ(H)` instead of `qp.tol · κ(H)`.
    pub qp_inaccurate: usize,
    /// γ0 used.
    pub gamma0: f64,
    /// Admissible bound on γ0.
    pub gamma0_bound: f64,
    /// True when the factorization of `K − G` was reused from an earlier solve of the same problem with
    /// the same γ0 (the `factorization` timing is then that earlier one).
    pub reused_factorization: bool,
    /// How H was formed: [`Condensation::Columns`] or [`Condensation::Schur`].
    pub condensation: Condensation,
    /// Timings per phase.
    pub timings: Timings,
}

/// The solution of a contact problem.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Nodal displacements, interleaved (x, y) per node (2N).
    pub displacement: Vec<f64>,
    /// Constant stress (σ_xx, σ_yy, σ_xy) per triangle.
    pub stress: Vec<[f64; 3]>,
    /// The out-of-plane stress σ_zz = ν (σ_xx + σ_yy) of plane strain per triangle (with
    /// [`Solution::stress`], the full symmetric stress tensor; σ_xz = σ_yz = 0).
    pub stress_zz: Vec<f64>,
    /// Von Mises stress per triangle (plane strain).
    pub von_mises: Vec<f64>,
    /// Reaction forces on clamped dofs (2N, zero elsewhere): `K u − f` (f the load of the load case).
    pub reactions: Vec<f64>,
    /// Abscissae of the multiplier dofs.
    pub multiplier_abscissae: Vec<f64>,
    /// λ_n at multiplier dofs.
    pub lambda_n: Vec<f64>,
    /// λ_t at multiplier dofs (zeros if frictionless).
    pub lambda_t: Vec<f64>,
    /// Tangential threshold per multiplier dof (μ g at the fixed point, the Tresca threshold, or 0).
    pub friction_threshold: Vec<f64>,
    /// Contact state per multiplier dof: separation where `λ_n ≤ √tol Λ`, slip where
    /// `|λ_t| ≥ threshold − √tol Λ`, stick otherwise (`tol` the QP tolerance, Λ the scale of λ_n: an
    /// interior-point solution puts inactive bounds at about `tol / (active value)`, so `√tol` is the
    /// geometric middle between "zero" and "non-zero").
    pub states: Vec<ContactState>,
    /// Abscissae of the midpoints of the FE edges of Γ_C.
    pub edge_abscissae: Vec<f64>,
    /// σ_n(u_h) on each FE edge of Γ_C.
    pub sigma_n: Vec<f64>,
    /// σ_t(u_h) on each FE edge of Γ_C.
    pub sigma_t: Vec<f64>,
    /// Abscissae of the FE nodes of Γ_C.
    pub node_abscissae: Vec<f64>,
    /// u_n at the FE nodes of Γ_C.
    pub u_n: Vec<f64>,
    /// Slip relative to the obstacle at the FE nodes of Γ_C: `u_t − s` for a static solve, the slip
    /// increment `u_t^k − u_t^{k−1} − (s_k − s_{k−1})` in step k of a history ([`crate::history`]).
    pub slip: Vec<f64>,
    /// Gap g = g₀ − δ at the FE nodes of Γ_C (δ of the load case).
    pub gap: Vec<f64>,
    /// Total normal contact force `∫ λ_n`.
    pub normal_force: f64,
    /// Total tangential contact force `∫ λ_t`. The friction traction the obstacle exerts on the body is
    /// `−λ_t t`, so a positive `tangential_force` pulls the body toward −t.
    pub tangential_force: f64,
    /// The total force the obstacle exerts on the body, `(F_x, F_y) = −(N n + T t)` in global axes (n, t
    /// the normal and tangent of [`crate::ContactBoundary`]), with
    /// `N` = [`Solution::normal_force`] and `T` = [`Solution::tangential_force`] (the traction on Γ_C is
    /// `σ(u)·n = −λ_n n − λ_t t`).
    pub contact_force: [f64; 2],
    /// How the obstacle moved, in global axes: `−δ n + s t` (the approach δ toward the body, against
    /// the outward normal, and the shift s along t).
    pub obstacle_motion: [f64; 2],
    /// Largest pointwise penetration `max(u_n − g)₊` over the FE nodes of Γ_C.
    pub max_penetration: f64,
    /// Discrete KKT residuals.
    pub kkt: KktResiduals,
    /// How the solve went.
    pub report: Report,
}

impl Solution {
    /// Assembles every field from the unknowns `u_free` and the multipliers `lambda` (2q) of a solve,
    /// with the friction threshold the multipliers were computed for and the QP tolerance (which sets
    /// the threshold between "zero" and "non-zero" multipliers in the contact states).
    pub(crate) fn new(
        condensed: &Condensed<'_>,
        loading: &Loading,
        u_free: &[f64],
        lambda: Vec<f64>,
        friction_threshold: Vec<f64>,
        qp_tol: f64,
        report: Report,
    ) -> Self {
        let (problem, condensed) = (condensed.problem(), condensed.factor());
        let q = condensed.q();
        let mesh = &problem.mesh;
        let material = &problem.spec.material;
        let displacement = problem.expand(u_free);
        let stress = element_stresses(mesh, material, &displacement);
        let von_mises = stress.iter().map(|s| material.von_mises(*s)).collect();
        let stress_zz = stress.iter().map(|s| material.sigma_zz(*s)).collect();
        // Reactions K u − f on all dofs (zero up to round-off on free dofs).
        let mut reactions: Vec<f64> = loading.f_full.iter().map(|f| -f).collect();
        for t in stiffness_triplets(mesh, material) {
            reactions[t.row] += t.val * displacement[t.col];
        }
        problem.dofs.keep_reactions(&mut reactions);
        let contact = &problem.contact;
        let (n, t) = (contact.normal, contact.tangent);
        let (lambda_n, lambda_t) = (lambda[..q].to_vec(), lambda[q..].to_vec());
        let sig = |s: &[f64; 3], a: [f64; 2], b: [f64; 2]| {
            a[0] * (s[0] * b[0] + s[2] * b[1]) + a[1] * (s[2] * b[0] + s[1] * b[1])
        };
        let sigma_n = contact.edges.iter().map(|e| sig(&stress[e.triangle], n, n)).collect();
        let sigma_t = contact.edges.iter().map(|e| sig(&stress[e.triangle], t, n)).collect();
        let edge_abscissae = contact.node_xi.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let mut u_n = Vec::with_capacity(contact.nodes.len());
        let mut slip = Vec::with_capacity(contact.nodes.len());
        for (&node, origin) in contact.nodes.iter().zip(&loading.slip_origin) {
            let (ux, uy) = (displacement[2 * node], displacement[2 * node + 1]);
            u_n.push(ux * n[0] + uy * n[1]);
            slip.push(ux * t[0] + uy * t[1] - origin);
        }
        let gap = loading.gap.clone();
        let max_penetration = u_n.iter().zip(&gap).map(|(u, g)| nan_max(u - g, 0.0)).fold(0.0, nan_max);
        let w = &problem.mortar.psi_integrals;
        let normal_force: f64 = lambda_n.iter().zip(w).map(|(l, w)| l * w).sum();
        let tangential_force: f64 = lambda_t.iter().zip(w).map(|(l, w)| l * w).sum();
        let contact_force = [0, 1].map(|i| -(normal_force * n[i] + tangential_force * t[i]));
        let obstacle_motion = [0, 1].map(|i| -loading.approach * n[i] + loading.shift * t[i]);

        let kkt = kkt_residuals(condensed, loading, u_free, &lambda, &friction_threshold);
        let lam_scale = lambda_n.iter().fold(condensed.lambda_scale(&loading.c), |m, v| m.max(v.abs()));
        let theta = qp_tol.sqrt() * lam_scale;
        let states = (0..q)
            .map(|j| {
                if lambda_n[j] <= theta {
                    ContactState::Separation
                } else if lambda_t[j].abs() >= friction_threshold[j] - theta {
                    ContactState::Slip
                } else {
                    ContactState::Stick
                }
            })
            .collect();
        Self {
            displacement,
            stress,
            stress_zz,
            von_mises,
            reactions,
            multiplier_abscissae: problem.multipliers.dof_abscissae(),
            lambda_n,
            lambda_t,
            friction_threshold,
            states,
            edge_abscissae,
            sigma_n,
            sigma_t,
            node_abscissae: contact.node_xi.clone(),
            u_n,
            slip,
            gap,
            normal_force,
            tangential_force,
            contact_force,
            obstacle_motion,
            max_penetration,
            kkt,
            report,
        }
    }

    /// The largest KKT residual a converged solve may report: `max(√tol, fp_tol)`, `tol` the QP tolerance
    /// the QPs met (`FALLBACK_TOL` if any met only that). An interior-point answer's complementarity is
    /// about `tol`, and at most `√tol` where the QP is degenerate; Coulomb's law holds at the fixed point
    /// to its stopping tolerance.
    pub fn accuracy_bound(qp_tol: f64, qp_inaccurate: usize, fp_tol: f64) -> f64 {
        let reached = if qp_inaccurate > 0 { qp_tol.max(crate::qp::FALLBACK_TOL) } else { qp_tol };
        reached.sqrt().max(fp_tol)
    }

    /// True when every field, total and residual is finite.
    pub fn all_finite(&self) -> bool {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        [
            &self.displacement,
            &self.von_mises,
            &self.reactions,
            &self.lambda_n,
            &self.lambda_t,
            &self.friction_threshold,
            &self.sigma_n,
            &self.sigma_t,
            &self.u_n,
            &self.slip,
            &self.gap,
            &self.report.residual_history,
        ]
        .into_iter()
        .all(|v| finite(v))
            && self.stress.iter().all(|s| finite(s))
            && [self.normal_force, self.tangential_force, self.max_penetration, self.kkt.max()]
                .iter()
                .all(|x| x.is_finite())
    }

    /// The current gap `g − u_n` at the FE nodes of Γ_C (along n, from the deformed body to the
    /// obstacle in its final position): 0 where the body touches it, negative where it penetrates.
    pub fn current_gap(&self) -> Vec<f64> {
        self.gap.iter().zip(&self.u_n).map(|(g, u)| g - u).collect()
    }

    /// Displacement of node `i`.
    pub fn node_displacement(&self, i: usize) -> [f64; 2] {
        [self.displacement[2 * i], self.displacement[2 * i + 1]]
    }
}

/// `num / den`, 0 when `num` is 0 (a residual that vanishes is 0 whatever its scale, even a vanishing
/// one), NaN propagated.
fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else {
        num / den
    }
}

fn kkt_residuals(c: &Factor, loading: &Loading, u: &[f64], lambda: &[f64], bound: &[f64]) -> KktResiduals {
    let q = c.q();
    let au = c.apply_a(u);
    let etl = c.apply_et(lambda);
    let inf = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| nan_max(m, x.abs()));
    let res: Vec<f64> = au.iter().zip(&etl).zip(&loading.f_free).map(|((a, e), f)| a + e - f).collect();
    let eq_scale = inf(&loading.f_free).max(inf(&etl));
    let eu = c.apply_e(u);
    // r = E u − d − Dγ λ.
    let dl = c.apply_d(lambda);
    let r: Vec<f64> = eu.iter().zip(&loading.d).zip(&dl).map(|((a, b), dl)| a - b - dl).collect();
    // The scales: Λ the size of λ_n (never 0 when something pushes), R the size of the terms of r (its
    // round-off is ε R): ‖E‖ ‖u‖ bounds ‖E u‖ and stays positive when the terms cancel.
    let lam = inf(lambda).max(c.lambda_scale(&loading.c)).max(inf(bound));
    let e_norm = c.e_rows.iter().map(|row| row.iter().map(|(_, v)| v.abs()).sum::<f64>()).fold(0.0, f64::max);
    let gap_scale = (e_norm * inf(u)).max(inf(&loading.d)).max(inf(&dl));
    let mut k = KktResiduals { equilibrium: ratio(inf(&res), eq_scale), ..Default::default() };
    // Positive parts and maxima propagate NaN (`f64::max` would drop it); products of two ratios never
    // underflow to 0/0.
    let pos = |x: f64| nan_max(x, 0.0);
    for j in 0..q {
        let (ln, lt) = (ratio(lambda[j], lam), ratio(lambda[q + j], lam));
        let (rn, rt) = (ratio(r[j], gap_scale), ratio(r[q + j], gap_scale));
        let b = ratio(bound[j], lam);
        k.normal_sign = nan_max(k.normal_sign, pos(-ln));
        k.non_penetration = nan_max(k.non_penetration, pos(rn));
        k.normal_complementarity = nan_max(k.normal_complementarity, (ln * rn).abs());
        k.friction_bound = nan_max(k.friction_bound, pos(lt.abs() - b));
        k.stick = nan_max(k.stick, pos(b - lt.abs()) * rt.abs());
        k.slip_direction = nan_max(k.slip_direction, pos(-lt * rt));
    }
    k
}
