//! The fields on Γ_C of every contact pair, and each pair's part of a solution ([`PairResult`]).
//!
//! A solution's fields on Γ_C hold the pairs one after the other, in the order of [`crate::Problem::pairs`]:
//! the multiplier dofs of the first pair, then the second's (each pair's abscissae its own side's), and so
//! for the FE nodes and the edges of Γ_C. [`PairResult`] says where each pair's values lie and gives its
//! resultants; the solution's totals are the sums over the pairs.

use std::ops::Range;

use crate::problem::load_case::LoadCase;
use crate::problem::sides::PairParts;
use crate::problem::Problem;

/// One contact pair's part of a solution.
#[derive(Debug, Clone, PartialEq)]
pub struct PairResult {
    /// The pair's name (its contact edge set).
    pub name: String,
    /// Its multiplier dofs among `lambda_n`, `lambda_t`, `friction_threshold`, `states` and
    /// `multiplier_abscissae`.
    pub multipliers: Range<usize>,
    /// Its FE nodes of Γ_C among `node_abscissae`, `u_n`, `slip` and `gap`.
    pub nodes: Range<usize>,
    /// Its FE edges of Γ_C among `edge_abscissae`, `sigma_n` and `sigma_t`.
    pub edges: Range<usize>,
    /// Its normal contact force `∫ λ_n` (in axisymmetry over the surface of revolution).
    pub normal_force: f64,
    /// Its tangential contact force `∫ λ_t`.
    pub tangential_force: f64,
    /// The force its obstacle (or the other body) exerts on the body, in global (x, y) components (in
    /// axisymmetry the axial one alone).
    pub contact_force: [f64; 2],
    /// Whether its side is a closed loop.
    pub closed: bool,
    /// The width of its contact zone and of its stick zone ([`crate::Solution::pair_zone`]; 0 where none).
    pub contact_width: f64,
    /// See `contact_width`.
    pub stick_width: f64,
    /// Its Coulomb coefficient as solved (None for the other laws).
    pub mu: Option<f64>,
}

/// The fields on Γ_C of every pair, one pair after the other.
pub(crate) struct GammaC {
    pub sigma_n: Vec<f64>,
    pub sigma_t: Vec<f64>,
    pub edge_abscissae: Vec<f64>,
    pub node_abscissae: Vec<f64>,
    pub multiplier_abscissae: Vec<f64>,
    pub u_n: Vec<f64>,
    pub slip: Vec<f64>,
    /// The displacement the contact law reads at each FE node (the jump for two bodies).
    pub contact_u: Vec<[f64; 2]>,
    pub pairs: Vec<PairResult>,
}

/// σ_n or σ_t: `a · σ b`.
fn component(s: &[f64; 3], a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * (s[0] * b[0] + s[2] * b[1]) + a[1] * (s[2] * b[0] + s[1] * b[1])
}

/// The fields on Γ_C from the element stresses, the displacement (all 2N dofs) and the multipliers.
pub(crate) fn gamma_c_fields(
    problem: &Problem,
    loading: &LoadCase,
    stress: &[[f64; 3]],
    displacement: &[f64],
    lambda_n: &[f64],
    lambda_t: &[f64],
) -> GammaC {
    let axisymmetric = problem.spec.model.is_axisymmetric();
    let (offsets, node_offsets) = (problem.pair_offsets(), problem.pair_node_offsets());
    let edge_offsets = problem.pair_edge_offsets();
    let mut out = GammaC {
        sigma_n: Vec::new(),
        sigma_t: Vec::new(),
        edge_abscissae: Vec::new(),
        node_abscissae: Vec::new(),
        multiplier_abscissae: Vec::new(),
        u_n: Vec::new(),
        slip: Vec::new(),
        contact_u: Vec::new(),
        pairs: Vec::new(),
    };
    let contact_u = problem.contact_displacements(displacement);
    for (k, p) in problem.pairs().into_iter().enumerate() {
        let PairParts { contact, multipliers, mortar, .. } = p;
        let dofs = offsets[k]..offsets[k + 1];
        let (ln, lt) = (&lambda_n[dofs.clone()], &lambda_t[dofs.clone()]);
        out.sigma_n.extend(contact.edges.iter().map(|e| component(&stress[e.triangle], e.normal, e.outward)));
        out.sigma_t.extend(contact.edges.iter().map(|e| component(&stress[e.triangle], e.tangent, e.outward)));
        out.edge_abscissae.extend(contact.node_xi.windows(2).map(|w| 0.5 * (w[0] + w[1])));
        out.node_abscissae.extend_from_slice(&contact.node_xi);
        out.multiplier_abscissae.extend(multipliers.dof_abscissae());
        for i in 0..contact.nodes.len() {
            let u = contact_u[node_offsets[k] + i];
            let (n, t) = (contact.node_normal(i), contact.node_tangent(i));
            out.u_n.push(u[0] * n[0] + u[1] * n[1]);
            out.slip.push(u[0] * t[0] + u[1] * t[1] - loading.slip_origin[node_offsets[k] + i]);
            out.contact_u.push(u);
        }
        let w = &mortar.psi_integrals;
        let normal_force: f64 = ln.iter().zip(w).map(|(l, w)| l * w).sum();
        let tangential_force: f64 = lt.iter().zip(w).map(|(l, w)| l * w).sum();
        let contact_force = if contact.one_frame {
            let (n, t) = (contact.normal, contact.tangent);
            [0, 1].map(|i| -(normal_force * n[i] + tangential_force * t[i]))
        } else {
            // Edge by edge in its own frame: Σ_i M2_e[i, j] = ∫_{E_e} ψ_j.
            let mut force = [0.0, 0.0];
            for &(_, j, e, m) in &mortar.m2_edges {
                let e = &contact.edges[e];
                for (c, f) in force.iter_mut().enumerate() {
                    *f -= m * (ln[j] * e.normal[c] + lt[j] * e.tangent[c]);
                }
            }
            force
        };
        // A solid of revolution: the radial tractions cancel over the turn, the resultant is axial.
        let contact_force = if axisymmetric { [0.0, contact_force[1]] } else { contact_force };
        out.pairs.push(PairResult {
            name: p.name.to_string(),
            multipliers: dofs,
            nodes: node_offsets[k]..node_offsets[k + 1],
            edges: edge_offsets[k]..edge_offsets[k + 1],
            normal_force,
            tangential_force,
            contact_force,
            closed: contact.is_closed(),
            contact_width: 0.0,
            stick_width: 0.0,
            mu: None,
        });
    }
    out
}
