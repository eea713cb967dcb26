//! The load case of a solve: everything the QP and the fields depend on besides `A` and `H`.
//!
//! For a condensed problem, a load case is the load `f`, the obstacle moments `d` and the QP's linear
//! term `c = d − E A⁻¹ f` (see [`crate::condensation`]), with the gap and the origin of slip at the FE
//! nodes of Γ_C for the reported fields. A static solve has one, built from the problem's own data
//! ([`LoadCase::of_problem`]). A step of a loading history has its own (derived in [`crate::solve::history`]). Neither changes `A`, `H` or `Dγ`, so every load case of a problem shares one
//! factorization.

use crate::condensation::Factor;
use crate::contact::obstacle::{Obstacle, ObstacleRotation};
use crate::error::{Error, Result};
use crate::problem::{slip_origin_on, Problem};
use crate::qp::QpData;

/// One load case of a condensed problem.
#[derive(Debug, Clone)]
pub struct LoadCase {
    /// Load on the free dofs.
    pub f_free: Vec<f64>,
    /// Load on all 2N dofs (for the reactions).
    pub f_full: Vec<f64>,
    /// `d` (2q): the gap moments `∫ψ_j g`, then the tangential data the slip is measured from.
    pub d: Vec<f64>,
    /// `c = d − E A⁻¹ f` (2q), the QP's linear term.
    pub c: Vec<f64>,
    /// The gap `g = g₀ − δ` at the FE nodes of Γ_C (of every pair, the first first).
    pub gap: Vec<f64>,
    /// The (first pair's) obstacle's approach δ and tangential position s.
    pub approach: f64,
    /// See `approach`.
    pub shift: f64,
    /// The obstacle's angle, where it turns ([`crate::ObstacleRotation`]; a step's [`LoadStep::rotation`]).
    pub angle: Option<f64>,
    /// The factor α on the body force and the tractions (1 for a static solve).
    pub load_factor: f64,
    /// At the FE nodes of Γ_C, the tangential displacement from which slip is measured: the shift s of a
    /// static solve (with a turned obstacle's surface motion), `u_t^{k−1} + s_k − s_{k−1}` in step k of a history
    /// (`u_t^{k−1} + m_k − m_{k−1}` where the obstacle turns: [`crate::solve::history`]).
    pub slip_origin: Vec<f64>,
    /// At the FE nodes of Γ_C, the displacement from which slip is measured: 0 for a static solve, `u^{k−1}` in
    /// step k of a history (an edge of a bent Γ_C reads the slip in its own frame from it).
    pub previous_u: Vec<[f64; 2]>,
    /// Where a step of a history moves the prescribed displacements away from the problem's values (and,
    /// once solved, where the rigid motion of a body held only by the contact moves it).
    pub moved_supports: Option<MovedSupports>,
    /// The free rigid motions the contact holds (see `problem/floating.rs`); empty when the supports hold
    /// every piece.
    pub rigid: RigidLoad,
}

/// What the free rigid motions R of the pieces held only by the contact add to a load case: `E R` and
/// the load they take, `Rᵀ f`.
#[derive(Debug, Clone, Default)]
pub struct RigidLoad {
    /// `E R` (2q × r, column-major).
    pub e_r: Vec<f64>,
    /// `Rᵀ f` (r).
    pub load: Vec<f64>,
}

/// Prescribed displacements moved by a step of a history to a lifting ū_k: the change `Δū = ū_k − ū`
/// from the problem's lifting ū enters the load as `− Tᵀ A Δū` and the moments as `− E Δū`.
#[derive(Debug, Clone)]
pub struct MovedSupports {
    /// ū_k (2N).
    pub lifting: Vec<f64>,
    /// `Tᵀ A Δū` (n).
    pub a_change: Vec<f64>,
    /// `E Δū` (2q).
    pub e_change: Vec<f64>,
}

impl LoadCase {
    /// The data a Γ_C QP needs of this load case.
    pub fn qp_data(&self) -> QpData<'_> {
        let rigid = (!self.rigid.load.is_empty()).then_some((self.rigid.e_r.as_slice(), self.rigid.load.as_slice()));
        QpData { f: &self.f_free, d: &self.d, c: &self.c, rigid }
    }

    /// The problem's own load case (the static solve).
    pub fn of_problem(problem: &Problem, factor: &Factor) -> Self {
        let shift = problem.spec.obstacle.shift;
        Self {
            f_free: factor.f.clone(),
            f_full: problem.f_full.clone(),
            d: factor.d.clone(),
            c: factor.c.clone(),
            gap: problem.pairs().iter().flat_map(|p| p.gap.iter().copied()).collect(),
            approach: problem.spec.obstacle.approach,
            shift,
            angle: problem.spec.obstacle.rotation.map(|r| r.angle),
            load_factor: 1.0,
            slip_origin: problem.pairs().iter().flat_map(|p| slip_origin_on(p.contact, &p.obstacle.placed())).collect(),
            previous_u: vec![[0.0, 0.0]; problem.pair_node_offsets().last().copied().unwrap_or(0)],
            moved_supports: None,
            rigid: problem.rigid_load(&problem.f_full),
        }
    }

    /// This load case with the bodies held only by the contact moved by their rigid motion `alpha` (one
    /// amplitude per free motion): the displacement of a solve is `T x + ū + R α`, and the moments
    /// `d − E R α` (as for a moved support), so that `E x − d` is the gap of the whole motion.
    pub(crate) fn with_rigid_motion(&self, problem: &Problem, alpha: &[f64]) -> Self {
        let mut lifting = self.lifting(problem).to_vec();
        for (field, a) in problem.dofs.rigid_fields(&problem.mesh).iter().zip(alpha) {
            lifting.iter_mut().zip(field).for_each(|(l, r)| *l += a * r);
        }
        // The moments see the motion as a moved support does: d − E R α (A R = 0 leaves the load).
        let two_q = self.d.len();
        let mut d = self.d.clone();
        for (column, a) in self.rigid.e_r.chunks_exact(two_q).zip(alpha) {
            d.iter_mut().zip(column).for_each(|(d, e)| *d -= a * e);
        }
        let (a_change, e_change) =
            self.moved_supports.as_ref().map_or((Vec::new(), Vec::new()), |m| (m.a_change.clone(), m.e_change.clone()));
        Self { d, moved_supports: Some(MovedSupports { lifting, a_change, e_change }), ..self.clone() }
    }

    /// The lifting ū of this load case: the moved one, or the problem's.
    pub fn lifting<'a>(&'a self, problem: &'a Problem) -> &'a [f64] {
        self.moved_supports.as_ref().map_or(&problem.dofs.lifting, |m| &m.lifting)
    }
}

/// The former name of [`LoadCase`].
#[deprecated(note = "renamed LoadCase: one load case of a condensed problem")]
pub type Loading = LoadCase;

impl Problem {
    /// Checks that the supports do not prescribe a node of Γ_C into the obstacle: at every FE node of Γ_C
    /// whose normal displacement a support fixes (a fixed node, or a sliding one whose condition is along
    /// n), that displacement `u · n` from the lifting `lifting` (2N) is at most the gap `gap` (at the nodes
    /// of the first pair's Γ_C; every further pair with its own gap), to `√ε` of the larger of the two. The pair
    /// of two bodies is not checked (the jump needs both sides); their further pairs are.
    ///
    /// # Errors
    /// [`crate::Error::PrescribedPenetration`] naming the node (and `step`, of a history).
    pub fn check_prescribed_contact(&self, gap: &[f64], lifting: &[f64], step: Option<usize>) -> crate::Result<()> {
        use crate::fem::supports::NodeSupport;
        let tol = crate::mesh::line::geometric_tol_rel();
        // The first pair's side with `gap` (not that of two bodies), the others with their own.
        let first = self.primary.is_none().then_some((&self.contact, gap));
        let sides = first.into_iter().chain(self.sides.iter().map(|s| (&s.contact, &s.gap[..])));
        for (contact, gap) in sides {
            for (k, (&node, &g)) in contact.nodes.iter().zip(gap).enumerate() {
                let n = contact.node_normal(k);
                let prescribed = match self.dofs.nodes[node] {
                    NodeSupport::Fixed { .. } => true,
                    // Along n: the condition's unit vector is ±n (to the straightness tolerance).
                    NodeSupport::Slide { normal, .. } => (normal[0] * n[1] - normal[1] * n[0]).abs() <= 4.0 * tol,
                    NodeSupport::Free => false,
                };
                if !prescribed {
                    continue;
                }
                let u_n = lifting[2 * node] * n[0] + lifting[2 * node + 1] * n[1];
                if u_n - g > tol * u_n.abs().max(g.abs()) {
                    return Err(crate::Error::PrescribedPenetration { node, u_n, gap: g, step });
                }
            }
        }
        Ok(())
    }
}

/// The obstacle of a history that turns it, at one step's shift and angle (at the problem's approach, which a
/// step moves by a constant): what the step's data read of it (derived in [`crate::solve::history`]).
#[derive(Debug, Clone)]
pub struct Placement {
    /// `∫ψ_j (g₀ − δ)` (q) of the obstacle turned to the step's angle.
    pub gap_moments: Vec<f64>,
    /// `∫ψ_j s(ξ)` (q): how far its surface has moved along Γ_C, the shift and the rotation's `w · t`.
    pub motion: Vec<f64>,
    /// The gap `g₀ − δ` at the FE nodes of Γ_C.
    pub node_gap: Vec<f64>,
    /// The surface's motion along each FE node's tangent.
    pub node_motion: Vec<f64>,
}

impl Problem {
    /// The problem's obstacle moved to `shift` and turned to `angle` about the centre of its rotation (at its
    /// own approach), placed ([`Obstacle::placed`]); the problem's own where it does not turn.
    pub fn obstacle_at(&self, shift: f64, angle: f64) -> Obstacle {
        let o = &self.spec.obstacle;
        let rotation = o.rotation.map(|r| ObstacleRotation { angle, ..r });
        Obstacle { shift, rotation, ..o.clone() }.placed()
    }

    /// The obstacle at `shift` and `angle` ([`Problem::obstacle_at`]) as a history step reads it.
    ///
    /// # Errors
    /// [`Error::BadObstacle`] if a gap function returns a non-finite value.
    pub fn placement(&self, shift: f64, angle: f64) -> Result<Placement> {
        let obstacle = self.obstacle_at(shift, angle);
        let (gap_moments, motion) =
            crate::contact::mortar::obstacle_moments(&self.contact, &self.multipliers, &obstacle, self.spec.model)?;
        let node_gap = self.contact.node_xi.iter().map(|&xi| obstacle.gap(&self.contact, xi)).collect::<Result<_>>()?;
        let motion =
            if motion.is_empty() { self.mortar.psi_integrals.iter().map(|w| w * shift).collect() } else { motion };
        Ok(Placement { gap_moments, motion, node_gap, node_motion: self.slip_origin_of(&obstacle) })
    }
}

/// One step of a loading history: where the obstacle is, how much of the load acts and where the
/// prescribed displacements are.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStep {
    /// Normal approach δ_k of the obstacle toward the body (the total, not an increment).
    pub approach: f64,
    /// Tangential position s_k of the obstacle along t (the total, not an increment).
    pub shift: f64,
    /// Factor α_k on the body force and the tractions.
    pub load_factor: f64,
    /// The values of the prescribed displacement components at this step, in the order of
    /// [`crate::ProblemSpec::prescribed_components`] (`"set.x"`, `"set.y"` of each
    /// [`crate::Support::Displacement`]); empty for the problem's own values.
    pub displacements: Vec<f64>,
    /// The obstacle's angle θ_k at this step (radians, counterclockwise, the total about the centre of the
    /// problem's [`crate::ObstacleRotation`], which it needs); `None` for the problem's own angle.
    pub rotation: Option<f64>,
}

impl LoadStep {
    /// A step to approach δ and shift s under the full load, the prescribed displacements as the problem
    /// has them.
    pub fn new(approach: f64, shift: f64) -> Self {
        Self { approach, shift, load_factor: 1.0, displacements: Vec::new(), rotation: None }
    }

    /// This step with the obstacle turned to `angle` (see [`LoadStep::rotation`]).
    #[must_use]
    pub fn with_rotation(self, angle: f64) -> Self {
        Self { rotation: Some(angle), ..self }
    }

    /// This step with the prescribed displacement components at `values` (see [`LoadStep::displacements`]).
    #[must_use]
    pub fn with_displacements(self, values: Vec<f64>) -> Self {
        Self { displacements: values, ..self }
    }

    /// A step from one row of numbers: approach, shift, load factor, the obstacle's angle (NaN: the problem's
    /// own), then the prescribed displacement components (the rows of a history as the Python binding and tables
    /// give them).
    ///
    /// # Errors
    /// [`Error::BadLoadStep`] for a row of fewer than four values.
    pub fn from_row(index: usize, row: &[f64]) -> Result<Self> {
        match row {
            [approach, shift, load_factor, angle, displacements @ ..] => Ok(Self {
                approach: *approach,
                shift: *shift,
                load_factor: *load_factor,
                displacements: displacements.to_vec(),
                rotation: (!angle.is_nan()).then_some(*angle),
            }),
            _ => Err(Error::BadLoadStep {
                step: index,
                what: format!("a step needs approach, shift, load_factor and angle, got {} values", row.len()),
            }),
        }
    }

    /// Checks that every value is finite and not subnormal.
    ///
    /// # Errors
    /// [`Error::BadLoadStep`] naming the step (`index`) and the value.
    pub fn validate(&self, index: usize) -> Result<()> {
        let named = [("approach", self.approach), ("shift", self.shift), ("load_factor", self.load_factor)];
        let angle = self.rotation.map(|v| ("the obstacle's angle", v));
        let displacements = self.displacements.iter().map(|&v| ("a prescribed displacement", v));
        let values = named.into_iter().chain(angle).chain(displacements);
        for (name, v) in values {
            if !v.is_finite() {
                return Err(Error::BadLoadStep { step: index, what: format!("{name} must be finite, got {v}") });
            }
            if v.is_subnormal() {
                return Err(Error::BadLoadStep { step: index, what: crate::error::subnormal(name, v) });
            }
        }
        Ok(())
    }
}
