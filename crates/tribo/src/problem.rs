//! A contact problem: mesh, material, supports, loads, contact boundary, obstacle and multiplier mesh,
//! assembled once into everything that does not depend on γ0 or on friction; and its condensed form for
//! one γ0 ([`Condensed`]), which borrows the problem it was built from.
//!
//! The problem keeps the factorization of its last [`Problem::condense`] (one entry, keyed by γ0), so
//! solving it again with the same γ0 (another friction law, other solver settings) costs no
//! factorization: [`crate::Report::reused_factorization`] says when that happened.

use std::sync::OnceLock;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use faer::sparse::linalg::solvers::SymbolicLlt;
use faer::sparse::{SparseColMat, Triplet};

use crate::condensation::Factor;
use crate::contact::ContactBoundary;
use crate::elasticity::{add_body_force, add_traction, stiffness_triplets, Material};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::mortar::MortarMatrices;
use crate::multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
use crate::obstacle::Obstacle;
use crate::settings::{Condensation, SolverSettings};
use crate::stabilization::{admissible_gamma0, ContactStress, Gamma0Bound, Stabilization};
use crate::supports::{Dofs, NodeSupport, Support};

/// Everything that defines a contact problem besides the mesh.
#[derive(Debug, Clone)]
pub struct ProblemSpec {
    /// Material.
    pub material: Material,
    /// Names of the clamped edge sets (u = 0): shorthand for [`Support::Clamp`] entries of `supports`.
    pub clamped: Vec<String>,
    /// Further Dirichlet conditions: rollers (symmetry lines) and prescribed displacements (see
    /// [`crate::supports`]). Γ_D is the union of these and `clamped`.
    pub supports: Vec<Support>,
    /// Constant body force f (per unit area).
    pub body_force: [f64; 2],
    /// Constant tractions (per unit length) on named edge sets (Γ_N).
    pub tractions: Vec<(String, [f64; 2])>,
    /// Name of the contact edge set Γ_C.
    pub contact: String,
    /// The rigid obstacle.
    pub obstacle: Obstacle,
    /// Points of the multiplier mesh T_H.
    pub multiplier_points: MultiplierPoints,
    /// Multiplier space.
    pub multiplier_space: MultiplierSpace,
}

/// Timings of the set-up phases, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SetupTimings {
    /// Stiffness and load assembly (the symbolic Cholesky factorization of K's pattern is formed by the
    /// first condensation that needs it, and timed with it).
    pub assembly: f64,
    /// Contact geometry, multiplier mesh and Γ_C matrices.
    pub contact_matrices: f64,
}

/// An assembled contact problem (independent of γ0 and friction).
#[derive(Debug, Clone)]
pub struct Problem {
    /// The mesh.
    pub mesh: Mesh,
    /// The specification it was built from.
    pub spec: ProblemSpec,
    /// Γ_C.
    pub contact: ContactBoundary,
    /// T_H.
    pub multipliers: MultiplierMesh,
    /// The Γ_C matrices.
    pub mortar: MortarMatrices,
    /// The supports resolved on the nodes: the unknown each dof follows and the lifting ū
    /// (`u = T x + ū`, see [`crate::supports`]).
    pub dofs: Dofs,
    /// Number of unknowns n.
    pub n_free: usize,
    /// Stiffness on the unknowns, `Tᵀ K T` (CSC, both triangles). Its pattern is also the pattern of
    /// the stabilized `A = K − G` (G couples the dofs of one triangle only).
    pub k_matrix: SparseColMat<usize, f64>,
    /// Symbolic Cholesky factorization of that pattern (fill-reducing ordering, elimination tree),
    /// computed by the first condensation that factorizes A by it (H by columns, or the saddle-point
    /// system's gradients; the partial factorization has its own ordering) and reused for every γ0.
    pub symbolic: OnceLock<SymbolicLlt<usize>>,
    /// Load on the unknowns with the lifting through K, `Tᵀ (f − K ū)`; the part through G, which
    /// depends on γ0, is added when A is factorized ([`Factor::f`]).
    pub f_free: Vec<f64>,
    /// Full load vector (all 2N dofs), for reactions.
    pub f_full: Vec<f64>,
    /// The gap `g = g₀ − δ` at the FE nodes of Γ_C (in the order of `contact.nodes`).
    pub contact_gap: Vec<f64>,
    /// σ_n(v), σ_t(v) on each contact edge as linear forms of the unknowns.
    pub contact_stress: ContactStress,
    /// Admissible bound on γ0 and the triangle that sets it.
    pub gamma0_bound: Gamma0Bound,
    /// Set-up timings.
    pub timings: SetupTimings,
    /// The factorization of the last [`Problem::condense`].
    factor_cache: FactorCache,
}

/// A one-entry cache of the factorization, keyed by γ0 and the condensation asked for. A clone of the
/// problem shares the entry it had (the factorization depends only on the problem's data and the key).
#[derive(Default)]
struct FactorCache(Mutex<Option<(Condensation, Arc<Factor>)>>);

impl FactorCache {
    fn get(&self, gamma0: f64, asked: Condensation) -> Option<Arc<Factor>> {
        let guard = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        guard.as_ref().filter(|(c, f)| *c == asked && f.gamma0.to_bits() == gamma0.to_bits()).map(|(_, f)| f.clone())
    }

    fn set(&self, asked: Condensation, factor: Arc<Factor>) {
        *self.0.lock().unwrap_or_else(PoisonError::into_inner) = Some((asked, factor));
    }
}

impl Clone for FactorCache {
    fn clone(&self) -> Self {
        Self(Mutex::new(self.0.lock().unwrap_or_else(PoisonError::into_inner).clone()))
    }
}

impl std::fmt::Debug for FactorCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let gamma0 = self.0.lock().unwrap_or_else(PoisonError::into_inner).as_ref().map(|(_, f)| f.gamma0);
        f.debug_tuple("FactorCache").field(&gamma0).finish()
    }
}

/// A problem condensed onto its multipliers for one γ0: the problem (borrowed, so a factorization can
/// never be paired with another problem) and the factorization of `A = K − G` with the multiplier
/// operator it defines ([`Factor`]). Build it with [`Problem::condense`]; solve with
/// [`Condensed::solve`].
#[derive(Debug, Clone)]
pub struct Condensed<'p> {
    problem: &'p Problem,
    factor: Arc<Factor>,
    reused: bool,
}

impl<'p> Condensed<'p> {
    /// The problem this was condensed from.
    pub fn problem(&self) -> &'p Problem {
        self.problem
    }

    /// The factorization and the condensed operators.
    pub fn factor(&self) -> &Factor {
        &self.factor
    }

    /// The γ0 in use.
    pub fn gamma0(&self) -> f64 {
        self.factor.gamma0
    }

    /// Number of multiplier dofs q (per component).
    pub fn q(&self) -> usize {
        self.factor.q()
    }

    /// True when the factorization came from the problem's cache (an earlier condensation with the same
    /// γ0) rather than being computed now.
    pub fn reused_factorization(&self) -> bool {
        self.reused
    }
}

impl Problem {
    /// Validates the specification against the mesh and assembles the problem.
    ///
    /// # Errors
    /// Any input error: material, unknown edge sets, no support, bad or conflicting supports, a piece the
    /// supports do not hold, non-finite loads, Γ_C not straight or not connected or overlapping Γ_D, bad
    /// obstacle, bad multiplier points.
    pub fn new(mesh: Mesh, spec: ProblemSpec) -> Result<Self> {
        let clock = Instant::now();
        spec.material.validate()?;
        spec.obstacle.validate()?;
        let supports: Vec<Support> =
            spec.clamped.iter().map(|set| Support::clamp(set.as_str())).chain(spec.supports.iter().cloned()).collect();
        let dofs = Dofs::new(&mesh, &supports)?;
        let n_free = dofs.n_free;
        let n_dofs = 2 * mesh.n_nodes();
        for (name, f) in [("body".to_string(), spec.body_force)].iter().chain(&spec.tractions) {
            if !(f[0].is_finite() && f[1].is_finite()) {
                return Err(Error::NonFiniteLoad { target: name.clone(), x: f[0], y: f[1] });
            }
        }
        let mut f_full = vec![0.0; n_dofs];
        add_body_force(&mesh, spec.body_force, &mut f_full);
        for (set, g) in &spec.tractions {
            add_traction(&mesh, mesh.edge_set(set)?, *g, &mut f_full);
        }
        if let Some(d) = f_full.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFiniteLoad {
                target: format!("the assembled load at dof {d}"),
                x: f_full[d],
                y: f64::NAN,
            });
        }
        // K over all dofs, then `Tᵀ K T` (faer sums the duplicates a rotated node's two dofs give) and
        // the lifting `K ū` of the prescribed displacements.
        let k_full = stiffness_triplets(&mesh, &spec.material);
        let mut k_lift = vec![0.0; n_dofs];
        let mut k_free = Vec::with_capacity(k_full.len());
        for t in &k_full {
            if !t.val.is_finite() {
                return Err(Error::Assembly {
                    matrix: "K",
                    what: format!("entry ({}, {}) is {}", t.row, t.col, t.val),
                });
            }
            k_lift[t.row] += t.val * dofs.lifting[t.col];
            if let (Some((i, a)), Some((j, b))) = (dofs.unknown(t.row), dofs.unknown(t.col)) {
                k_free.push(Triplet::new(i, j, a * b * t.val));
            }
        }
        drop(k_full);
        let f_lifted: Vec<f64> = f_full.iter().zip(&k_lift).map(|(f, k)| f - k).collect();
        if let Some(d) = f_lifted.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFiniteLoad {
                target: format!("the load with the prescribed displacements lifted, at dof {d}"),
                x: f_lifted[d],
                y: f64::NAN,
            });
        }
        let f_free = dofs.restrict(&f_lifted);
        let k_matrix = SparseColMat::try_new_from_triplets(n_free, n_free, &k_free)
            .map_err(|e| Error::Assembly { matrix: "K", what: format!("{e:?}") })?;
        drop(k_free);
        let assembly = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        let contact = ContactBoundary::new(&mesh, &spec.contact)?;
        // The gap at the nodes of Γ_C: every value the solver and its results use is checked.
        let contact_gap = contact.node_xi.iter().map(|&xi| spec.obstacle.gap(xi)).collect::<Result<Vec<f64>>>()?;
        let contact_edges: std::collections::HashSet<[usize; 2]> =
            contact.edges.iter().map(|e| [e.left.min(e.right), e.left.max(e.right)]).collect();
        for e in &contact.edges {
            if dofs.edges.contains(&[e.left.min(e.right), e.left.max(e.right)]) {
                return Err(Error::ContactOverlapsDirichlet { set: spec.contact.clone(), a: e.left, b: e.right });
            }
        }
        for (traction_set, _) in &spec.tractions {
            for &[a, b] in mesh.edge_set(traction_set)? {
                if contact_edges.contains(&[a.min(b), a.max(b)]) {
                    return Err(Error::TractionOnContact {
                        set: spec.contact.clone(),
                        traction_set: traction_set.clone(),
                        a,
                        b,
                    });
                }
            }
        }
        if contact.nodes.iter().all(|&node| matches!(dofs.nodes[node], NodeSupport::Fixed { .. })) {
            return Err(Error::ContactFullyClamped { set: spec.contact.clone() });
        }
        let multipliers = MultiplierMesh::new(&contact, &spec.multiplier_points, spec.multiplier_space)?;
        let h_t: Vec<f64> = contact.edges.iter().map(|e| mesh.diameter(e.triangle)).collect();
        let mortar = MortarMatrices::new(&contact, &multipliers, &h_t, &spec.obstacle)?;
        let contact_stress = ContactStress::new(&mesh, &spec.material, &contact);
        let gamma0_bound = admissible_gamma0(&mesh, &spec.material, &contact);
        let contact_matrices = clock.elapsed().as_secs_f64();
        Ok(Self {
            mesh,
            spec,
            contact,
            multipliers,
            mortar,
            dofs,
            n_free,
            k_matrix,
            symbolic: OnceLock::new(),
            f_free,
            f_full,
            contact_gap,
            contact_stress,
            gamma0_bound,
            timings: SetupTimings { assembly, contact_matrices },
            factor_cache: FactorCache::default(),
        })
    }

    /// Factorizes `A = K − G` for the γ0 that `stabilization` asks for and condenses onto the
    /// multipliers, or takes the factorization of the previous call if it had the same γ0; H is formed
    /// as the default settings choose ([`Problem::condense_with`] chooses).
    ///
    /// # Errors
    /// [`Error::BadSetting`] / [`Error::Gamma0TooLarge`] for a bad γ0; [`Error::NotPositiveDefinite`] if
    /// `K − G` is not positive definite (only possible for [`Stabilization::Unchecked`] beyond the bound).
    pub fn condense(&self, stabilization: Stabilization) -> Result<Condensed<'_>> {
        let d = SolverSettings::default();
        self.condense_with(stabilization, d.condensation, d.memory_budget)
    }

    /// As [`Problem::condense`], with H formed as `condensation` asks within `memory_budget` bytes.
    ///
    /// # Errors
    /// As [`Problem::condense`]; [`Error::MemoryBudget`] when the partial factorization is asked for and
    /// does not fit.
    pub fn condense_with(
        &self,
        stabilization: Stabilization,
        condensation: Condensation,
        memory_budget: usize,
    ) -> Result<Condensed<'_>> {
        let gamma0 = self.gamma0_bound.resolve(stabilization)?;
        if let Some(factor) = self.factor_cache.get(gamma0, condensation) {
            return Ok(Condensed { problem: self, factor, reused: true });
        }
        // −G and E over all dofs, restricted to the unknowns; their action on the lifting ū gives the
        // γ0-dependent part of the lifted load and obstacle moments (see [`crate::supports`]).
        let minus_g_full = self.contact_stress.stiffness_triplets(&self.mortar, gamma0);
        let e_full = self.contact_stress.coupling_rows(&self.contact, &self.mortar, gamma0);
        let ubar = &self.dofs.lifting;
        let mut f = self.f_free.clone();
        let mut d = self.obstacle_moments();
        if !self.dofs.homogeneous() {
            let mut g_lift = vec![0.0; ubar.len()];
            for t in &minus_g_full {
                g_lift[t.row] += t.val * ubar[t.col];
            }
            for (fi, gi) in f.iter_mut().zip(self.dofs.restrict(&g_lift)) {
                *fi -= gi;
            }
            for (di, row) in d.iter_mut().zip(&e_full) {
                *di -= row.iter().map(|&(k, v)| v * ubar[k]).sum::<f64>();
            }
        }
        let minus_g: Vec<_> = minus_g_full
            .iter()
            .filter_map(|t| {
                let ((i, a), (j, b)) = (self.dofs.unknown(t.row)?, self.dofs.unknown(t.col)?);
                Some(Triplet::new(i, j, a * b * t.val))
            })
            .collect();
        let e_rows = self.dofs.restrict_rows(&e_full);
        let d_gamma: Vec<(usize, usize, f64)> = if gamma0 > 0.0 {
            self.mortar.d_h.entries.iter().map(|&(i, j, v)| (i, j, gamma0 * v)).collect()
        } else {
            Vec::new()
        };
        let factor = Factor::new(
            &self.k_matrix,
            &self.symbolic,
            &minus_g,
            e_rows,
            d_gamma,
            &f,
            d,
            gamma0,
            condensation,
            memory_budget,
        )
        .map_err(|e| match e {
            // At γ0 = 0 the matrix is K itself: the supports hold every piece (checked at the door), so only
            // a material or a mesh at the limits of floating point is left; do not blame the stabilization.
            Error::NotPositiveDefinite { what } if gamma0 == 0.0 => Error::NotPositiveDefinite {
                what: format!(
                    "{what}; γ0 = 0, so this is K itself (a material or mesh at the limits of floating point)"
                ),
            },
            Error::NotPositiveDefinite { what } => Error::NotPositiveDefinite {
                what: format!(
                    "{what} (γ0 = {}, admissible bound {})",
                    crate::error::Num(gamma0),
                    crate::error::Num(self.gamma0_bound.value)
                ),
            },
            e => e,
        })?;
        let factor = Arc::new(factor);
        self.factor_cache.set(condensation, factor.clone());
        Ok(Condensed { problem: self, factor, reused: false })
    }

    /// Drops the cached factorization, so that the next [`Problem::condense`] factorizes again (for
    /// benchmarks, and to free its memory).
    pub fn forget_factorization(&self) {
        *self.factor_cache.0.lock().unwrap_or_else(PoisonError::into_inner) = None;
    }

    /// `d = (∫ψ_j g, ∫ψ_j s)` (2q): the obstacle's gap and tangential shift tested with the multiplier
    /// basis, the part of the QP's linear term that the obstacle contributes (see [`crate::obstacle`]).
    pub fn obstacle_moments(&self) -> Vec<f64> {
        let shift = self.spec.obstacle.shift;
        self.mortar.gap_moments.iter().copied().chain(self.mortar.psi_integrals.iter().map(|w| w * shift)).collect()
    }

    /// Number of multiplier dofs q (per component).
    pub fn n_multipliers(&self) -> usize {
        self.multipliers.n_dofs()
    }

    /// The displacement on all 2N dofs from the unknowns: `u = T x + ū` (prescribed values included).
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        self.dofs.expand(x)
    }
}

impl ProblemSpec {
    /// The defaults of the keywords a problem is built from, besides the required ones, as the Python
    /// binding and the scene files name them: the multiplier points (`multiplier_ratio`, or
    /// `multiplier_size`; see [`MultiplierPoints::from_keywords`]) and the multiplier `space`.
    pub fn keyword_defaults() -> Vec<(&'static str, crate::settings::SettingValue)> {
        use crate::choice::Choice;
        use crate::settings::SettingValue;
        let points = match MultiplierPoints::default() {
            MultiplierPoints::RatioToFe(r) => Some(("multiplier_ratio", SettingValue::Float(r))),
            MultiplierPoints::Size(h) => Some(("multiplier_size", SettingValue::Float(h))),
            MultiplierPoints::Abscissae(_) | MultiplierPoints::Points(_) => None,
        };
        let space = ("space", SettingValue::Name(MultiplierSpace::default().as_str().to_string()));
        points.into_iter().chain([space]).collect()
    }
}
