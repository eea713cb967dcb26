//! The data of one step of a loading history (derived in [`crate::solve::history`]): where a converged step leaves
//! the contact for the next (`PreviousStep`), the load case of the next step from it (`step_load_case`), and the
//! checks of the steps before a history runs (`check_steps`).
//!
//! # Several contact pairs
//! A step moves the first pair's obstacle (its approach δ_k, shift s_k and angle θ_k) and the prescribed
//! displacements; a further pair's obstacle stays where the problem puts it (its own approach and shift). Each
//! pair's multipliers read only its own side, so the step's data are the one-pair data pair by pair: the first
//! pair's as derived in [`crate::solve::history`], a further pair's with its gap `g₀ − δ` and, in Coulomb's slip
//! increment, its surface's motion since the previous step, `m_k − m_{k−1}`: its own shift at the first step from
//! rest (`m_0 = 0`), 0 after. Its tangential data is then `∫ψ_j s − (E_t ū)_j` at the first step (u^0 = 0, λ^0 = 0),
//! the static data (the problem's own `d`), and `(E_t (u^{k−1} − ū) − Dγ λ_t^{k−1})_j` after it.

use crate::condensation::Factor;
use crate::error::{Error, Result};
use crate::problem::load_case::{LoadCase, LoadStep, MovedSupports, Placement};
use crate::problem::{slip_origin_on, Condensed, Problem};
use crate::results::Solution;

/// The state a converged step leaves for the next: `E_t (u^k − ū) − Dγ λ_t^k` (ū the problem's own
/// lifting), `u_t^k` at the FE nodes of Γ_C (of every pair) and s_k.
pub(crate) fn after(
    condensed: &Condensed<'_>,
    solution: &Solution,
    loading: &LoadCase,
    placed: Option<Placement>,
) -> PreviousStep {
    let (problem, factor) = (condensed.problem(), condensed.factor());
    let q = condensed.q();
    // The unknowns x = Tᵀ (u − ū_k) (T has orthonormal columns: a node's unknowns are its free
    // directions) and the pressures; `E (u − ū) = E T x + E (ū_k − ū)` (+ E R α for a body held by the contact).
    let relative: Vec<f64> = solution.displacement.iter().zip(loading.lifting(problem)).map(|(u, l)| u - l).collect();
    let lambda = solution.multipliers();
    // A body held only by the contact also moves by R α, which the unknowns do not carry at the pins.
    let eu = if problem.dofs.floating.is_empty() {
        factor.apply_e(&problem.unknowns_of(&relative, &solution.pressure))
    } else {
        problem.e_action(factor.gamma0, &[relative.as_slice(), &solution.pressure].concat())
    };
    let dl = factor.apply_d(&lambda);
    let moved = |j: usize| loading.moved_supports.as_ref().map_or(0.0, |m| m.e_change[j]);
    let tangential = (q..2 * q).map(|j| eu[j] + moved(j) - dl[j]).collect();
    let u_nodes = problem.contact_displacements(&solution.displacement);
    let u_t = u_nodes.iter().zip(problem.contact_node_tangents()).map(|(u, t)| u[0] * t[0] + u[1] * t[1]);
    PreviousStep { tangential, u_t_nodes: u_t.collect(), u_nodes, shift: loading.shift, placed, at_rest: false }
}

/// Where a history stands before a step: the tangential displacement at rest is 0 and the obstacle at
/// shift 0.
#[derive(Debug, Clone)]
pub(crate) struct PreviousStep {
    /// `(E_t (u^{k−1} − ū) − Dγ λ_t^{k−1})_j` (q values), ū the problem's own lifting: the previous step's
    /// stabilized tangential displacement, `∫ ψ_j u_t^{k−1} − ∫ γ ψ_j (λ_t^{k−1} + σ_t(u^{k−1}))`, without
    /// the part of the problem's prescribed displacements (the lifted moments `d` hold it).
    pub tangential: Vec<f64>,
    /// `u_t^{k−1}` at the FE nodes of Γ_C (of every pair, the first first).
    pub u_t_nodes: Vec<f64>,
    /// `u^{k−1}` at the FE nodes of Γ_C (of every pair).
    pub u_nodes: Vec<[f64; 2]>,
    /// `s_{k−1}` (the first pair's obstacle).
    pub shift: f64,
    /// Where the obstacle turns, its step's placement (its surface's motion from rest, at rest 0); `None` else.
    pub placed: Option<Placement>,
    /// Whether this is the state at rest (the further pairs' obstacles then move to their own shifts).
    pub at_rest: bool,
}

impl PreviousStep {
    /// The state at rest: the body undeformed (u = 0, also where a support prescribes ū: the first step
    /// moves it there), the obstacle at shift 0 and, where it turns, at angle 0. Its tangential data is then
    /// `−(E ū)_t`, the tangential part of the lifting in the problem's own `d` (exactly 0 without prescribed
    /// displacements).
    pub(crate) fn rest(problem: &Problem, factor: &Factor) -> Self {
        let q = problem.n_multipliers();
        let own = problem.obstacle_moments();
        let tangential = own[q..].iter().zip(&factor.d[q..]).map(|(o, d)| d - o).collect();
        let n = problem.pair_node_offsets().last().copied().unwrap_or(0);
        let placed = problem.spec.obstacle.rotation.map(|_| Placement {
            gap_moments: Vec::new(),
            motion: vec![0.0; problem.multipliers.n_dofs()],
            node_gap: Vec::new(),
            node_motion: vec![0.0; problem.contact.nodes.len()],
        });
        Self { tangential, u_t_nodes: vec![0.0; n], u_nodes: vec![[0.0, 0.0]; n], shift: 0.0, placed, at_rest: true }
    }
}

/// The load case of one step of a history (see [`crate::solve::history`] for the derivation): loads
/// `α f` (the lifting of prescribed displacements is not scaled), gap moments `∫ψ_j (g₀ − δ_k)`,
/// tangential data `∫ψ_j (s_k − s_{k−1}) + (E_t u^{k−1} − Dγ λ_t^{k−1})_j` (`∫ψ_j (m_k − m_{k−1})` for the first
/// term where the obstacle turns: the module documentation), and where the step moves the
/// prescribed displacements to ū_k, the change `Δū = ū_k − ū` lifted: `− Tᵀ A Δū` in the load, `− E Δū`
/// in the moments. From rest with α = 1, the problem's own approach and its own prescribed values, this
/// is bit for bit the static load case. A further pair's data are its own (the module documentation).
///
/// # Errors
/// [`crate::Error::MemoryBudget`] if the solve for a changed load cannot allocate its workspace;
/// [`Error::BadLoadStep`] if the step's prescribed values conflict (checked before the history too).
pub(crate) fn step_load_case(
    problem: &Problem,
    factor: &Factor,
    step: &LoadStep,
    previous: &PreviousStep,
) -> Result<(LoadCase, Option<Placement>)> {
    let alpha = step.load_factor;
    let (q, q0, n0) = (problem.n_multipliers(), problem.multipliers.n_dofs(), problem.contact.nodes.len());
    let w = &problem.mortar.psi_integrals;
    // g_k = g₀ − δ_k = (g₀ − δ) + (δ − δ_k): the problem's gap moved by the change of approach.
    let moved = problem.spec.obstacle.approach - step.approach;
    let ds = step.shift - previous.shift;
    let angle = problem.spec.obstacle.rotation.map(|r| step.rotation.unwrap_or(r.angle));
    let placed = angle.map(|a| problem.placement(step.shift, a)).transpose()?;
    // A further pair's tangential data: the static one from rest, the previous step's after.
    let further = |j: usize| if previous.at_rest { factor.d[q + j] } else { previous.tangential[j] };
    let mut d: Vec<f64> = factor.d[..q0]
        .iter()
        .zip(w)
        .map(|(m, w)| m + moved * w)
        .chain(factor.d[q0..q].iter().copied())
        .chain(w.iter().zip(&previous.tangential).map(|(w, t)| w * ds + t))
        .chain((q0..q).map(further))
        .collect();
    let (mut gap, mut slip_origin): (Vec<f64>, Vec<f64>) = (
        problem.contact_gap.iter().map(|g| g + moved).collect(),
        previous.u_t_nodes[..n0].iter().map(|u| u + ds).collect(),
    );
    // A turned obstacle: the gap of its new angle, the motion of its surface since the previous step.
    if let (Some(p), Some(before)) = (&placed, &previous.placed) {
        let own = &problem.mortar.gap_moments;
        d[..q0].iter_mut().zip(own.iter().zip(&p.gap_moments)).for_each(|(d, (o, g))| *d += g - o);
        let change = p.motion.iter().zip(&before.motion).map(|(a, b)| a - b);
        d[q..q + q0].iter_mut().zip(previous.tangential[..q0].iter().zip(change)).for_each(|(d, (t, c))| *d = c + t);
        gap = p.node_gap.iter().map(|g| g + moved).collect();
        let node_change = p.node_motion.iter().zip(&before.node_motion).map(|(a, b)| a - b);
        slip_origin = previous.u_t_nodes[..n0].iter().zip(node_change).map(|(u, c)| u + c).collect();
    }
    // The further pairs: their own gap; slip measured from their obstacle's shift at the first step, from u_t^{k−1}
    // after.
    for side in &problem.sides {
        gap.extend_from_slice(&side.gap);
    }
    if previous.at_rest {
        slip_origin.extend(problem.sides.iter().flat_map(|s| slip_origin_on(&s.contact, &s.obstacle.placed())));
    } else {
        slip_origin.extend_from_slice(&previous.u_t_nodes[n0..]);
    }
    debug_assert_eq!((d.len(), gap.len(), slip_origin.len()), (2 * q, previous.u_nodes.len(), previous.u_nodes.len()));
    let moved_supports = moved_supports(problem, factor, step)?;
    let (f_free, c) = if alpha == 1.0 && moved_supports.is_none() {
        let c = d.iter().zip(&factor.e_ainv_f).map(|(d, e)| d - e).collect();
        (factor.f.clone(), c)
    } else {
        // f̃ + (α − 1) Tᵀ f − Tᵀ A Δū: the load scaled, its lifting moved; one more solve for E A⁻¹ f.
        let load = problem.load_on_unknowns();
        let mut f: Vec<f64> = factor.f.iter().zip(&load).map(|(f, l)| f + (alpha - 1.0) * l).collect();
        if let Some(m) = &moved_supports {
            f.iter_mut().zip(&m.a_change).for_each(|(f, a)| *f -= a);
            d.iter_mut().zip(&m.e_change).for_each(|(d, e)| *d -= e);
        }
        let u = factor.displacement(&f, &vec![0.0; d.len()])?;
        let c = d.iter().zip(factor.apply_e(&u)).map(|(d, e)| d - e).collect();
        (f, c)
    };
    let loading = LoadCase {
        f_free,
        f_full: problem.f_full.iter().map(|f| alpha * f).collect(),
        d,
        c,
        gap,
        approach: step.approach,
        shift: step.shift,
        angle,
        load_factor: alpha,
        slip_origin,
        previous_u: previous.u_nodes.clone(),
        moved_supports,
        rigid: problem.rigid_load(&problem.f_full.iter().map(|f| alpha * f).collect::<Vec<_>>()),
    };
    Ok((loading, placed))
}

/// The step's prescribed displacements, where they differ from the problem's: the lifting ū_k and the
/// change `Δū = ū_k − ū` lifted (`Tᵀ A Δū`, `E Δū`).
fn moved_supports(problem: &Problem, factor: &Factor, step: &LoadStep) -> Result<Option<MovedSupports>> {
    let own: Vec<f64> = problem.spec.prescribed_components().into_iter().map(|(_, v)| v).collect();
    if step.displacements.is_empty() || step.displacements == own {
        return Ok(None);
    }
    let supports = problem.spec.all_supports(Some(&step.displacements));
    let lifting = problem.dofs.lifting_of(&problem.mesh, &supports)?;
    let change: Vec<f64> = lifting.iter().zip(&problem.dofs.lifting).map(|(a, b)| a - b).collect();
    let (a_change, e_change) = problem.lifting_terms(factor.gamma0, &change);
    Ok(Some(MovedSupports { lifting, a_change, e_change }))
}

/// Checks the steps against the problem before a history runs: two bodies move through their prescribed
/// displacements only (no obstacle motion); as many prescribed values as the problem has components (or
/// none: the problem's own), values that agree where supports meet, and no node of Γ_C prescribed into
/// the obstacle.
///
/// # Errors
/// [`Error::BadLoadStep`] naming the step; [`Error::PrescribedPenetration`] naming the node and the step.
pub(crate) fn check_steps(problem: &Problem, steps: &[LoadStep]) -> Result<()> {
    let components = problem.spec.prescribed_components();
    let mut last: Option<&[f64]> = None;
    let mut lifting: Option<Vec<f64>> = None;
    for (k, step) in steps.iter().enumerate() {
        if let (Some(angle), None) = (step.rotation, problem.spec.obstacle.rotation) {
            return Err(Error::BadLoadStep {
                step: k,
                what: format!(
                    "the step turns the obstacle to {angle} rad, but the problem's obstacle has no rotation: give it \
                     one (its centre, the angle 0: ProblemSpec::obstacle_rotation)"
                ),
            });
        }
        if problem.is_two_bodies() && (step.approach != 0.0 || step.shift != 0.0) {
            return Err(Error::BadLoadStep {
                step: k,
                what: format!(
                    "two bodies move through their prescribed displacements, not by an approach ({}) or a shift ({})",
                    step.approach, step.shift
                ),
            });
        }
        if step.shift != 0.0 {
            problem.check_axisymmetric_shift().map_err(|e| Error::BadLoadStep { step: k, what: e.to_string() })?;
        }
        let values = step.displacements.as_slice();
        let moved = problem.spec.obstacle.approach - step.approach;
        let turned = step.rotation.map(|a| problem.placement(step.shift, a)).transpose();
        let turned = turned.map_err(|e| Error::BadLoadStep { step: k, what: e.to_string() })?;
        let gap0 = turned.as_ref().map_or(&problem.contact_gap, |p| &p.node_gap);
        let gap: Vec<f64> = gap0.iter().map(|g| g + moved).collect();
        if values.is_empty() || last == Some(values) {
            let own = if values.is_empty() { None } else { lifting.as_deref() };
            problem.check_prescribed_contact(&gap, own.unwrap_or(&problem.dofs.lifting), Some(k))?;
            continue;
        }
        let bad = |what: String| Error::BadLoadStep { step: k, what };
        if values.len() != components.len() {
            let names: Vec<&str> = components.iter().map(|(n, _)| n.as_str()).collect();
            return Err(bad(format!(
                "{} prescribed displacement values for {} components ({})",
                values.len(),
                names.len(),
                if names.is_empty() { "the problem prescribes none".to_string() } else { names.join(", ") }
            )));
        }
        let moved_lifting = problem
            .dofs
            .lifting_of(&problem.mesh, &problem.spec.all_supports(Some(values)))
            .map_err(|e| bad(e.to_string()))?;
        problem.check_prescribed_contact(&gap, &moved_lifting, Some(k))?;
        lifting = Some(moved_lifting);
        last = Some(values);
    }
    Ok(())
}
