//! A problem condensed onto its multipliers for one γ0 ([`Condensed`]), and the one-entry cache of the
//! factorization that lets a second solve with the same γ0 skip it.
//!
//! The three names around the condensed operator: [`crate::Factor`] is the linear algebra (A's
//! factorization, E, Dγ, c and the columns of H, knowing nothing of meshes); [`Condensed`] pairs a
//! `Factor` with the [`Problem`] it came from; [`crate::Condensation`] is the setting that says how H is
//! formed.

use std::sync::{Arc, Mutex, PoisonError};

use faer::sparse::Triplet;

use crate::condensation::{Expected, Factor};
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::settings::{Condensation, SolverSettings, Stabilization};

/// A one-entry cache of the factorization, keyed by γ0 and the condensation asked for. A clone of the
/// problem shares the entry it had (the factorization depends only on the problem's data and the key).
#[derive(Default)]
pub(super) struct FactorCache(Mutex<Option<(Condensation, Arc<Factor>)>>);

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
    /// The solves this condensation serves (the steps of a loading history; 1 for a static solve): the
    /// QPs' path follows from it ([`Factor::saddle_for`]).
    load_cases: usize,
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

    /// Whether the QPs solve the sparse saddle-point system (else they use columns of H): see
    /// [`Factor::saddle_for`].
    pub fn sparse_qps(&self) -> bool {
        self.factor.saddle_for(self.load_cases)
    }

    /// This condensation, serving `load_cases` solves (the steps of a loading history).
    pub(crate) fn for_load_cases(&self, load_cases: usize) -> Self {
        Self { load_cases, ..self.clone() }
    }

    /// True when the factorization came from the problem's cache (an earlier condensation with the same
    /// γ0) rather than being computed now.
    pub fn reused_factorization(&self) -> bool {
        self.reused
    }
}

impl Problem {
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
        self.condense_for(stabilization, condensation, memory_budget, Expected::default())
    }

    /// As [`Problem::condense_with`]; `expected` says whether the QPs will start from the multipliers of a
    /// nearby problem (the adaptive loop's coarser level) and whether a Coulomb fixed point follows, which
    /// [`Condensation::Auto`] weighs. A factorization kept from an earlier call is reused whatever that
    /// call expected: a second factorization costs more than the better path saves.
    pub(crate) fn condense_for(
        &self,
        stabilization: Stabilization,
        condensation: Condensation,
        memory_budget: usize,
        expected: Expected,
    ) -> Result<Condensed<'_>> {
        let gamma0 = self.gamma0_bound.resolve(stabilization)?;
        // A body held only by the contact needs all of H for clarabel's QP with its equilibrium
        // (`problem/floating.rs`): the saddle-point path does without H, so `auto` forms it by columns.
        let condensation = match condensation {
            Condensation::Saddle if !self.dofs.floating.is_empty() => {
                return Err(Error::BadSetting {
                    name: "condensation",
                    value: f64::NAN,
                    what: "'saddle' does without H, which a body held only by the contact needs: use 'auto' or \
                           'columns' (or 'schur' with P1 displacements)"
                        .to_string(),
                });
            }
            Condensation::Auto if !self.dofs.floating.is_empty() => Condensation::Columns,
            c => c,
        };
        if let Some(factor) = self.factor_cache.get(gamma0, condensation) {
            return Ok(Condensed { problem: self, factor, reused: true, load_cases: 1 });
        }
        // −G and E over all dofs, restricted to the unknowns; their action on the lifting ū gives the
        // γ0-dependent part of the lifted load and obstacle moments (see [`crate::fem::supports`]).
        let minus_g_full = self.minus_g_triplets(gamma0);
        let e_full = self.coupling_rows(gamma0);
        let mut f = self.f_free.clone();
        let mut d = self.obstacle_moments();
        if !self.dofs.homogeneous() {
            let (g_lift, e_lift) = self.lifting_action(&minus_g_full, &e_full, &self.dofs.lifting, false);
            for (fi, gi) in f.iter_mut().zip(g_lift) {
                *fi -= gi;
            }
            for (di, ei) in d.iter_mut().zip(e_lift) {
                *di -= ei;
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
            self.d_h_entries().into_iter().map(|(i, j, v)| (i, j, gamma0 * v)).collect()
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
            expected,
            self.n_free - self.dofs.n_displacement,
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
        Ok(Condensed { problem: self, factor, reused: false, load_cases: 1 })
    }

    /// What a lifting ū (2N) adds to the equations, for the γ0 of a factorization: `(Tᵀ A ū, E ū)`
    /// (n and 2q values) with `A = K − G`, the lifted load being `Tᵀ f − Tᵀ A ū` and the lifted obstacle
    /// moments `d − E ū` (see [`crate::fem::supports`]). A loading history that moves the prescribed
    /// displacements applies it to the change of ū ([`crate::solve::history`]).
    pub(crate) fn lifting_terms(&self, gamma0: f64, ubar: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let minus_g_full = self.minus_g_triplets(gamma0);
        let e_full = self.coupling_rows(gamma0);
        self.lifting_action(&minus_g_full, &e_full, ubar, true)
    }

    /// `E v` (2q) for a displacement v of all 2N dofs, E of the γ0 of a factorization (a body held only
    /// by the contact moves by R α, which no unknown carries where the pins are).
    pub(crate) fn e_action(&self, gamma0: f64, v: &[f64]) -> Vec<f64> {
        let e_full = self.coupling_rows(gamma0);
        let at = |k: usize| v.get(k).copied().unwrap_or(0.0);
        e_full.iter().map(|row| row.iter().map(|&(k, x)| x * at(k)).sum()).collect()
    }

    /// `(Tᵀ(K − G) ū, E ū)` from the triplets of −G and the rows of E over all dofs, without K's part unless
    /// `with_stiffness` (the problem's own lifting has it in `f_free` already).
    fn lifting_action(
        &self,
        minus_g_full: &[Triplet<usize, usize, f64>],
        e_full: &[Vec<(usize, f64)>],
        ubar: &[f64],
        with_stiffness: bool,
    ) -> (Vec<f64>, Vec<f64>) {
        use crate::fem::elasticity::{element_stresses, internal_forces};
        use crate::fem::mixed;
        // In the mixed formulation the pressures' dofs follow the 2N displacements, with no lifting.
        let pressures = if self.spec.formulation.is_mixed() { self.mesh.n_nodes() } else { 0 };
        let mut a_lift = if with_stiffness && pressures > 0 {
            // [K_μ ū; −B ū]: the shear stresses of ū, and its divergence in the pressure rows.
            let stresses =
                mixed::element_stresses(self.spec.model, &self.mesh, &self.in_plane, ubar, &vec![0.0; pressures]);
            let mut a = internal_forces(self.spec.model, &self.mesh, &stresses);
            a.extend(mixed::divergence(self.spec.model, &self.mesh, ubar).iter().map(|v| -v));
            a
        } else if with_stiffness {
            let stresses = element_stresses(self.spec.model, &self.mesh, &self.in_plane, ubar);
            internal_forces(self.spec.model, &self.mesh, &stresses)
        } else {
            vec![0.0; ubar.len() + pressures]
        };
        let at = |k: usize| ubar.get(k).copied().unwrap_or(0.0);
        for t in minus_g_full {
            a_lift[t.row] += t.val * at(t.col);
        }
        let e_lift = e_full.iter().map(|row| row.iter().map(|&(k, v)| v * at(k)).sum()).collect();
        (self.dofs.restrict(&a_lift), e_lift)
    }

    /// Drops the cached factorization, so that the next [`Problem::condense`] factorizes again (for
    /// benchmarks, and to free its memory).
    pub fn forget_factorization(&self) {
        *self.factor_cache.0.lock().unwrap_or_else(PoisonError::into_inner) = None;
    }

    /// Bytes the cached factorization holds ([`Factor::held_bytes`]: its factor's values and the columns of H
    /// formed so far); 0 when none is cached. A solve of another problem made while this one is held (an
    /// enriched problem, the adaptive loop's estimate) has that much less of the memory budget.
    pub fn held_bytes(&self) -> f64 {
        self.factor_cache.0.lock().unwrap_or_else(PoisonError::into_inner).as_ref().map_or(0.0, |(_, f)| f.held_bytes())
    }
}
