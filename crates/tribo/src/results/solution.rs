//! The solution of a contact problem: every field as a plain vector (displacement, stresses, reactions,
//! multipliers and Γ_C traces), the contact state per multiplier dof, the resultants, the discrete KKT
//! residuals and the [`Report`].

use crate::fem::elasticity::{element_stresses, internal_forces, von_mises};
use crate::problem::load_case::LoadCase;
use crate::problem::Condensed;
use crate::results::estimator::{estimate, EstimatorInput, SideInput};
use crate::results::kkt::{kkt_residuals, nan_max};
use crate::results::pairs::{gamma_c_fields, GammaC, PairResult};
use crate::results::{ContactState, KktResiduals, Report};

/// The solution of a contact problem.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Nodal displacements, interleaved (x, y) per node (2N).
    pub displacement: Vec<f64>,
    /// Constant stress (σ_xx, σ_yy, σ_xy) per triangle.
    pub stress: Vec<[f64; 3]>,
    /// The out-of-plane stress per triangle: ν (σ_xx + σ_yy) in plane strain, 0 in plane stress, the hoop
    /// stress σ_θθ in axisymmetry (with [`Solution::stress`], the full symmetric stress tensor; σ_xz = σ_yz = 0).
    /// In axisymmetry x is r and y is z: `stress` is (σ_rr, σ_zz, σ_rz).
    pub stress_zz: Vec<f64>,
    /// Von Mises stress per triangle (with that σ_zz).
    pub von_mises: Vec<f64>,
    /// The recovered stress (σ_xx, σ_yy, σ_xy) per node: the area-weighted mean of the cell stresses
    /// around it ([`crate::fem::elasticity::recovered_stress`]), for plots and files.
    pub nodal_stress: Vec<[f64; 3]>,
    /// The von Mises stress per node, of [`Solution::nodal_stress`] with the recovered σ_zz.
    pub nodal_von_mises: Vec<f64>,
    /// The pressure p per node (N) of the mixed formulation, `σ = 2μ ε(u) − p̄_T I`
    /// ([`crate::fem::mixed`]); empty for the displacement formulation.
    pub pressure: Vec<f64>,
    /// Reaction forces on the supported dofs (2N, zero elsewhere; along a roller's normal): `(K − G) u − f + Eᵀ λ`,
    /// f the load of the load case, the equation of (3.1) at those dofs. At a supported node of a triangle that
    /// touches Γ_C, the contact's share (Eᵀ λ) and the stabilization's (G u) are not the support's: the
    /// reactions and the contact forces balance the loads.
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
    /// Whether Γ_C (the first pair's, [`Solution::pairs`]) is a closed loop ([`crate::ContactBoundary::is_closed`]):
    /// its abscissae wrap with its length, the last of its `node_abscissae` less the first, and a zone may cross the
    /// cut ([`Solution::contact_zone`]).
    pub closed: bool,
    /// u_n at the FE nodes of Γ_C.
    pub u_n: Vec<f64>,
    /// Slip relative to the obstacle at the FE nodes of Γ_C: `u_t − s` for a static solve, the slip
    /// increment `u_t^k − u_t^{k−1} − (s_k − s_{k−1})` in step k of a history ([`crate::solve::history`]).
    pub slip: Vec<f64>,
    /// Gap g = g₀ − δ at the FE nodes of Γ_C (δ of the load case). `u_n` and `slip` at a node read the
    /// node's normal ([`crate::ContactBoundary::node_normal`]; Γ_C's own where it is straight).
    pub gap: Vec<f64>,
    /// Total normal contact force `∫ λ_n`, summed over the pairs (in axisymmetry over the surface of revolution, `∫ λ_n
    /// 2π r ds`: the axial force on a Γ_C across the axis, the total of the pressure on a bore).
    pub normal_force: f64,
    /// Total tangential contact force `∫ λ_t`, summed over the pairs. The friction traction the obstacle exerts on the
    /// body is `−λ_t t`, so a positive `tangential_force` pulls the body toward −t.
    pub tangential_force: f64,
    /// The total force the obstacle exerts on the body, `(F_x, F_y) = −(N n + T t)` in global axes (n, t
    /// the normal and tangent of [`crate::ContactBoundary`]), with
    /// `N` = [`Solution::normal_force`] and `T` = [`Solution::tangential_force`] (the traction on Γ_C is
    /// `σ(u)·n = −λ_n n − λ_t t`). On a bent Γ_C, `−∫ (λ_n n_e + λ_t t_e)` edge by edge. In axisymmetry the
    /// resultant on the whole turn: its radial component is 0 (the radial tractions cancel over the turn). With
    /// several pairs, the sum of theirs ([`crate::PairResult::contact_force`], each in its own frames).
    pub contact_force: [f64; 2],
    /// How the obstacle moved, in global axes: `−δ n + s t` (the approach δ toward the body, against
    /// the outward normal, and the shift s along t; where the frames vary along Γ_C, in the contact frame of
    /// its first edge: against a line obstacle, the line's motion). A turned obstacle's rotation is not in it
    /// ([`crate::ObstacleRotation`]; its surface's motion is in the slip origin). The first pair's obstacle.
    pub obstacle_motion: [f64; 2],
    /// Largest pointwise penetration `max(u_n − g)₊` over the FE nodes of Γ_C.
    pub max_penetration: f64,
    /// The a posteriori error indicator η_K per triangle (its totals and parts are
    /// [`Report::estimate`]; see [`crate::results::ErrorEstimate`]).
    pub estimator: Vec<f64>,
    /// The traction indicator ζ_K per triangle: its part of the estimate of the error of the contact
    /// tractions (`Σ ζ_K² = ζ²`, see [`crate::results::ErrorEstimate`]); it falls with the distance to Γ_C.
    pub traction_estimator: Vec<f64>,
    /// Discrete KKT residuals.
    pub kkt: KktResiduals,
    /// How the solve went.
    pub report: Report,
    /// Each contact pair's part of the fields on Γ_C and its resultants ([`PairResult`]), in the order of
    /// [`crate::Problem::pairs`]; the fields on Γ_C hold the pairs one after the other, the forces above are
    /// their sums.
    pub pairs: Vec<PairResult>,
}

impl Solution {
    /// Assembles every field from the unknowns `u_free` and the multipliers `lambda` (2q) of a solve,
    /// with the friction threshold the multipliers were computed for and the QP tolerance (which sets
    /// the threshold between "zero" and "non-zero" multipliers in the contact states).
    pub(crate) fn new(
        condensed: &Condensed<'_>,
        loading: &LoadCase,
        u_free: &[f64],
        lambda: Vec<f64>,
        friction_threshold: Vec<f64>,
        qp_tol: f64,
        report: Report,
    ) -> Self {
        let (problem, condensed) = (condensed.problem(), condensed.factor());
        let q = condensed.q();
        let mesh = &problem.mesh;
        // The stresses and the estimates read the in-plane law, σ_zz (the hoop stress in axisymmetry) the model.
        let model = problem.spec.model;
        let materials = &problem.in_plane;
        let displacement = problem.dofs.expand_with(u_free, loading.lifting(problem));
        let pressure = problem.dofs.pressure(u_free).to_vec();
        let stress4 = if problem.spec.formulation.is_mixed() {
            crate::fem::mixed::element_stresses(model, mesh, materials, &displacement, &pressure)
        } else {
            element_stresses(model, mesh, materials, &displacement)
        };
        let stress: Vec<[f64; 3]> = stress4.iter().map(|s| [s[0], s[1], s[2]]).collect();
        let von_mises: Vec<f64> = stress4.iter().map(|s| von_mises(*s)).collect();
        let stress_zz: Vec<f64> = stress4.iter().map(|s| s[3]).collect();
        let hoop: &[f64] = if model.is_axisymmetric() { &stress_zz } else { &[] };
        // The recovered stress is averaged over each node's triangles, σ_zz with the others.
        let nodal_stress4 = crate::fem::elasticity::recovered_stress(mesh, &stress4);
        let nodal_stress = nodal_stress4.iter().map(|s| [s[0], s[1], s[2]]).collect();
        let nodal_von_mises: Vec<f64> = nodal_stress4.iter().map(|s| crate::fem::elasticity::von_mises(*s)).collect();
        // Reactions (K − G) u − f + Eᵀ λ on all dofs (zero up to round-off on free dofs), K u from the stresses.
        let mut reactions = internal_forces(model, mesh, &stress4);
        for (r, f) in reactions.iter_mut().zip(&loading.f_full) {
            *r -= f;
        }
        let n = reactions.len();
        let at = |dof: usize| if dof < n { displacement[dof] } else { pressure[dof - n] };
        problem.add_minus_g_times(condensed.gamma0, at, &mut reactions);
        for (row, l) in problem.coupling_rows(condensed.gamma0).iter().zip(&lambda) {
            row.iter().filter(|(dof, _)| *dof < n).for_each(|&(dof, v)| reactions[dof] += v * l);
        }
        problem.dofs.keep_reactions(&mut reactions);
        let (lambda_n, lambda_t) = (lambda[..q].to_vec(), lambda[q..].to_vec());
        let fields = gamma_c_fields(problem, loading, &stress, &displacement, &lambda_n, &lambda_t);
        let GammaC { u_n, slip, contact_u, pairs, .. } = &fields;
        let gap = loading.gap.clone();
        let max_penetration = u_n.iter().zip(&gap).map(|(u, g)| nan_max(u - g, 0.0)).fold(0.0, nan_max);
        let normal_force: f64 = pairs.iter().map(|p| p.normal_force).sum();
        let tangential_force: f64 = pairs.iter().map(|p| p.tangential_force).sum();
        let contact_force =
            pairs.iter().fold([0.0, 0.0], |f, p| [f[0] + p.contact_force[0], f[1] + p.contact_force[1]]);
        let contact = &problem.contact;
        // In the contact frame of the first edge (Γ_C's own on a straight side against a gap function).
        let (n0, t0) = (contact.edges[0].normal, contact.edges[0].tangent);
        let obstacle_motion = [0, 1].map(|i| -loading.approach * n0[i] + loading.shift * t0[i]);

        let scaled = |v: [f64; 2]| [loading.load_factor * v[0], loading.load_factor * v[1]];
        let spec = &problem.spec;
        let moved = spec.obstacle.approach - loading.approach;
        let geometric = |xi: f64| problem.primary.as_ref().map_or(0.0, |p| p.gap_at(contact, xi));
        // The obstacle as the contact meets it (turned to the load case's angle, where it turns: `Obstacle::placed`).
        let placed = loading.angle.map(|a| problem.obstacle_at(spec.obstacle.shift, a));
        let obstacle = placed.as_ref().unwrap_or(&spec.obstacle);
        let gap_at = |xi: f64| obstacle.initial_gap_on(contact, xi) + geometric(xi) - obstacle.approach + moved;
        // The further pairs' obstacles, placed once (a history moves the first pair's only: `solve::increment`).
        let further: Vec<_> = problem.sides.iter().map(|s| (s, s.obstacle.placed())).collect();
        let further_gaps: Vec<Box<dyn Fn(f64) -> f64 + '_>> = further
            .iter()
            .map(|(s, o)| {
                Box::new(move |xi: f64| o.initial_gap_on(&s.contact, xi) - o.approach) as Box<dyn Fn(f64) -> f64>
            })
            .collect();
        let lowest: Vec<Vec<f64>> = problem.pairs().iter().map(|p| p.obstacle.shape.lowest_points()).collect();
        let sides = problem
            .pairs()
            .into_iter()
            .zip(pairs)
            .zip(&lowest)
            .enumerate()
            .map(|(k, ((p, r), lowest))| SideInput {
                contact: p.contact,
                multipliers: p.multipliers,
                lambda_n: &lambda_n[r.multipliers.clone()],
                lambda_t: &lambda_t[r.multipliers.clone()],
                threshold: &friction_threshold[r.multipliers.clone()],
                u_n: &u_n[r.nodes.clone()],
                slip: &slip[r.nodes.clone()],
                previous_u: &loading.previous_u[r.nodes.clone()],
                contact_u: &contact_u[r.nodes.clone()],
                gap: if k == 0 { &gap_at } else { further_gaps[k - 1].as_ref() },
                lowest,
            })
            .collect();
        let input = EstimatorInput {
            mesh,
            materials,
            primary: problem.primary.as_ref(),
            dofs: &problem.dofs,
            sides,
            body_force: scaled(spec.body_force),
            // The sets were checked when the problem was built.
            tractions: spec
                .tractions
                .iter()
                .filter_map(|(set, g)| Some((mesh.edge_set(set).ok()?, g.scaled(loading.load_factor))))
                .collect(),
            stress: &stress,
            model,
            hoop,
            displacement: &displacement,
            pressure: &pressure,
        };
        let (estimator, traction_estimator, estimate) = estimate(&input);
        let report = Report { estimate, ..report };
        let (k, n_u) = (problem.k_matrix.as_ref(), problem.dofs.n_displacement);
        let kkt = kkt_residuals(condensed, k, loading, u_free, &lambda, &friction_threshold, n_u);
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
        let GammaC { sigma_n, sigma_t, edge_abscissae, node_abscissae, multiplier_abscissae, u_n, slip, pairs, .. } =
            fields;
        let mut solution = Self {
            displacement,
            stress,
            stress_zz,
            von_mises,
            nodal_stress,
            nodal_von_mises,
            pressure,
            reactions,
            multiplier_abscissae,
            lambda_n,
            lambda_t,
            friction_threshold,
            states,
            edge_abscissae,
            sigma_n,
            sigma_t,
            node_abscissae,
            closed: problem.contact.is_closed(),
            u_n,
            slip,
            gap,
            normal_force,
            tangential_force,
            contact_force,
            obstacle_motion,
            max_penetration,
            estimator,
            traction_estimator,
            kkt,
            report,
            pairs,
        };
        for k in 0..solution.pairs.len() {
            let width = |keep: fn(ContactState) -> bool| solution.pair_zone(k, keep).map_or(0.0, |z| z.width());
            let (contact, stick) = (width(|s| s != ContactState::Separation), width(|s| s == ContactState::Stick));
            (solution.pairs[k].contact_width, solution.pairs[k].stick_width) = (contact, stick);
        }
        solution
    }

    /// The largest KKT residual a converged solve may report: `max(√tol, fp_tol)`, `tol` the QP tolerance
    /// the QPs met (`FALLBACK_TOL` if any met only that). An interior-point answer's complementarity is
    /// about `tol`, and at most `√tol` where the QP is degenerate; Coulomb's law holds at the fixed point
    /// to its stopping tolerance.
    pub fn accuracy_bound(qp_tol: f64, qp_inaccurate: usize, fp_tol: f64) -> f64 {
        Self::reached_qp_tol(qp_tol, qp_inaccurate).sqrt().max(fp_tol)
    }

    /// The QP tolerance the QPs of a solve met: `qp_tol`, or [`crate::qp::FALLBACK_TOL`] if any met only that.
    pub fn reached_qp_tol(qp_tol: f64, qp_inaccurate: usize) -> f64 {
        if qp_inaccurate > 0 {
            qp_tol.max(crate::qp::FALLBACK_TOL)
        } else {
            qp_tol
        }
    }

    /// True when every field, total, residual and error indicator is finite (the relative estimates
    /// may be NaN: without contact the traction estimate has nothing to be relative to).
    pub fn all_finite(&self) -> bool {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        [
            &self.displacement,
            &self.von_mises,
            &self.nodal_von_mises,
            &self.pressure,
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
            &self.estimator,
            &self.traction_estimator,
        ]
        .into_iter()
        .all(|v| finite(v))
            && self.stress.iter().all(|s| finite(s))
            && [
                self.normal_force,
                self.tangential_force,
                self.max_penetration,
                self.kkt.max(),
                self.report.estimate.total,
                self.report.estimate.traction,
            ]
            .iter()
            .all(|x| x.is_finite())
    }

    /// The current gap `g − u_n` at the FE nodes of Γ_C (along n, from the deformed body to the
    /// obstacle in its final position): 0 where the body touches it, negative where it penetrates.
    pub fn current_gap(&self) -> Vec<f64> {
        self.gap.iter().zip(&self.u_n).map(|(g, u)| g - u).collect()
    }

    /// The multipliers as the QPs take them: λ_n then λ_t (2q values), e.g. to start a solve from them.
    pub fn multipliers(&self) -> Vec<f64> {
        [self.lambda_n.as_slice(), self.lambda_t.as_slice()].concat()
    }

    /// About how many bytes a solution of `problem` holds: its fields per node, triangle, multiplier dof
    /// and Γ_C edge and node, and a report (a history keeps one per step; see
    /// [`crate::Condensed::solve_history`]).
    pub fn estimated_bytes(problem: &crate::Problem) -> usize {
        let (n, t) = (problem.mesh.n_nodes(), problem.mesh.n_triangles());
        let (q, e, c) = (problem.n_multipliers(), problem.pair_edge_offsets(), problem.pair_node_offsets());
        let (e, c) = (e.last().copied().unwrap_or(0), c.last().copied().unwrap_or(0));
        // 2N displacements and reactions, 3T + 3N stresses, T σ_zz, von Mises and the two indicators,
        // N recovered von Mises, N pressures (mixed); 4q on T_H (and q states); 3 per Γ_C edge, 4 per Γ_C node.
        let p = if problem.spec.formulation.is_mixed() { n } else { 0 };
        let floats = (8 * n + p + 7 * t + 4 * q + 3 * e + 4 * c) as f64;
        (8.0 * floats) as usize + q + 512
    }

    /// The per-entity vectors of floats by name (per triangle, node, multiplier dof, edge or node of Γ_C),
    /// as the Python binding and the files name them.
    pub fn vectors(&self) -> [(&'static str, &[f64]); 17] {
        [
            ("pressure", &self.pressure),
            ("stress_zz", &self.stress_zz),
            ("von_mises", &self.von_mises),
            ("nodal_von_mises", &self.nodal_von_mises),
            ("multiplier_abscissae", &self.multiplier_abscissae),
            ("lambda_n", &self.lambda_n),
            ("lambda_t", &self.lambda_t),
            ("friction_threshold", &self.friction_threshold),
            ("edge_abscissae", &self.edge_abscissae),
            ("sigma_n", &self.sigma_n),
            ("sigma_t", &self.sigma_t),
            ("node_abscissae", &self.node_abscissae),
            ("u_n", &self.u_n),
            ("slip", &self.slip),
            ("gap", &self.gap),
            ("estimator", &self.estimator),
            ("traction_estimator", &self.traction_estimator),
        ]
    }

    /// The totals by name, as the Python binding and the files name them: the forces, the largest
    /// penetration and the widths of the contact and stick zones ([`Solution::contact_width`]).
    pub fn scalars(&self) -> [(&'static str, f64); 5] {
        [
            ("normal_force", self.normal_force),
            ("tangential_force", self.tangential_force),
            ("max_penetration", self.max_penetration),
            ("contact_width", self.contact_width()),
            ("stick_width", self.stick_width()),
        ]
    }

    /// Displacement of node `i`.
    pub fn node_displacement(&self, i: usize) -> [f64; 2] {
        [self.displacement[2 * i], self.displacement[2 * i + 1]]
    }
}
