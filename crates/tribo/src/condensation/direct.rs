//! The sparse factor of `A = K − G` in its two orderings (fill-reducing, or the dofs `E` touches last for all
//! of H at once), its solves, and the check that a factor fits the memory budget before its values are
//! allocated.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, MatRef, Par, Side};

use crate::error::{Error, Result};
use crate::linalg::blocks::Ldlt;
use crate::linalg::schur;

/// The sparse factorization of A, in one of two orderings.
pub(super) enum Direct {
    /// The LDLᵀ factorization in the fill-reducing (AMD) ordering, the symbolic analysis of K's pattern: columns
    /// of H are solves. A is positive definite, or quasi-definite for the mixed formulation
    /// ([`crate::fem::mixed`]). Its symbolic analysis, its values and the inverses of its pivots.
    Ldlt(Arc<SymbolicCholesky<usize>>, Vec<f64>, Vec<f64>),
    /// The Cholesky factorization with the dofs E touches ordered last ([`crate::linalg::schur`]): all of
    /// `E A⁻¹ Eᵀ` from the trailing block.
    Schur(schur::SchurFactor),
}

impl Direct {
    /// The fill-reducing order of A's dofs its factor was analysed with (`order[new] = old`), where it has one
    /// of its own (not the partial factorization's, which orders the Γ_C dofs last).
    pub(super) fn order(&self) -> Option<&[usize]> {
        match self {
            Self::Ldlt(symbolic, ..) => symbolic.perm().map(|p| p.arrays().0),
            Self::Schur(_) => None,
        }
    }

    /// Bytes of the factor's values (and its pivots' inverses): what [`fits_budget`] counted for it before they
    /// were allocated.
    pub(super) fn value_bytes(&self) -> f64 {
        let len = match self {
            Self::Ldlt(_, values, d_inv) => values.len() + d_inv.len(),
            Self::Schur(f) => f.len_values(),
        };
        8.0 * len as f64
    }

    /// The LDLᵀ factor of A read block by block, for solves that read little of it ([`super::substitution`]),
    /// and the inverses of its pivots; `None` for the partial Cholesky factor.
    pub(super) fn blocks(&self) -> Option<(Ldlt<'_>, &[f64])> {
        let Self::Ldlt(symbolic, values, d_inv) = self else { return None };
        Some((Ldlt::new(symbolic, values), d_inv))
    }

    /// `x_jᵀ A⁻¹ x_j = (L⁻¹ P x_j)ᵀ D⁻¹ (L⁻¹ P x_j)` for each column of `x` (A = Pᵀ L D Lᵀ P): one forward
    /// substitution, half a solve, over the blocks `x_j`'s entries reach ([`super::substitution`]). `None` for
    /// the partial factor (a solve gives it there).
    pub(super) fn energies(&self, x: MatRef<'_, f64>) -> Option<Vec<f64>> {
        let (factor, d_inv) = self.blocks()?;
        let energy = |j: usize| {
            let column: Vec<f64> = x.col(j).iter().copied().collect();
            let mut y = factor.permuted(&column);
            factor.forward(&mut y);
            y.iter().zip(d_inv).map(|(v, d)| v * v * d).sum::<f64>()
        };
        Some((0..x.ncols()).map(energy).collect())
    }

    pub(super) fn solve_in_place(&self, x: MatMut<'_, f64>) -> Result<()> {
        let par = faer::get_global_parallelism();
        // The workspace of a solve with a factor in the fill-reducing ordering.
        let workspace = |symbolic: &SymbolicCholesky<usize>| {
            let req = symbolic.solve_in_place_scratch::<f64>(x.ncols(), par);
            MemBuffer::try_new(req).map_err(|_| Error::MemoryBudget {
                what: "the workspace of a solve with the factor of A".to_string(),
                needed: req.size_bytes() as f64,
                budget: f64::NAN,
            })
        };
        match self {
            // One right-hand side: the block substitutions, which read the factor downward (faer's supernodal
            // solve reads each column upward, about twice as slow at 55k).
            Self::Ldlt(symbolic, values, d_inv) if x.ncols() == 1 => {
                let b: Vec<f64> = x.as_ref().col(0).iter().copied().collect();
                let y = Ldlt::new(symbolic, values).solve(&b, d_inv);
                x.col_mut(0).iter_mut().zip(y).for_each(|(xi, yi)| *xi = yi);
            }
            Self::Ldlt(symbolic, values, _) => {
                let mut mem = workspace(symbolic)?;
                LdltRef::new(symbolic, values).solve_in_place_with_conj(Conj::No, x, par, MemStack::new(&mut mem));
            }
            Self::Schur(f) => f.solve_in_place(x, Par::rayon(0)).map_err(schur_error)?,
        }
        Ok(())
    }
}

/// The displacement for multipliers λ: `u = A⁻¹ (f − Eᵀ λ)`. On the partial factor `A⁻¹ Eᵀ λ` costs
/// about half a solve (`Eᵀ λ` lives on the dofs ordered last), and so does u with no load, or with the
/// load whose solve `u_f = A⁻¹ f` is known.
pub(super) fn displacement(
    direct: &Direct,
    e_rows: &[Vec<(usize, f64)>],
    f: &[f64],
    lambda: &[f64],
    u_f: Option<&Vec<f64>>,
) -> Result<Vec<f64>> {
    let half = matches!(direct, Direct::Schur(_)) && (u_f.is_some() || f.iter().all(|v| *v == 0.0));
    let mut rhs = if half { vec![0.0; f.len()] } else { f.to_vec() };
    for (row, l) in e_rows.iter().zip(lambda) {
        for &(d, v) in row {
            rhs[d] -= v * l;
        }
    }
    match direct {
        Direct::Schur(factor) if half => {
            let mut u = factor.solve_from_contact(&rhs, Par::rayon(0)).map_err(schur_error)?;
            u.iter_mut().zip(u_f.into_iter().flatten()).for_each(|(ui, fi)| *ui += fi);
            Ok(u)
        }
        _ => solve(direct, &rhs),
    }
}

/// The partial factorization's errors as the crate's.
pub(super) fn schur_error(e: schur::SchurError) -> Error {
    match e {
        schur::SchurError::NotPositiveDefinite { dof } => {
            Error::NotPositiveDefinite { what: format!("non-positive pivot at unknown {dof}") }
        }
        schur::SchurError::TooLarge { what, bytes } => Error::MemoryBudget {
            what: format!("the partial factorization's {what}"),
            needed: bytes as f64,
            budget: f64::NAN,
        },
        schur::SchurError::InvalidInput(what) => Error::Assembly { matrix: "the Schur complement of A", what },
    }
}

/// The symbolic analysis of A's pattern (K's) in the fill-reducing (AMD) ordering, supernodal: faer's own
/// choice (by the ratio of flops to non-zeros) takes the simplicial factorization on tribo's meshes, whose
/// numeric factorization is 1.5–2 times slower (graded Hertz meshes of 15k–109k unknowns, measured).
///
/// # Errors
/// [`Error::Assembly`] if faer refuses the pattern.
pub(super) fn analyse(pattern: SymbolicSparseColMatRef<'_, usize>) -> Result<SymbolicCholesky<usize>> {
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    factorize_symbolic_cholesky(pattern, Side::Lower, SymmetricOrdering::Amd, params)
        .map_err(|e| Error::Assembly { matrix: "the symbolic Cholesky factor of K", what: format!("{e:?}") })
}

/// The numeric LDLᵀ factorization of a symmetric `a`, positive definite or quasi-definite (its last `negative`
/// unknowns the pressures of the mixed formulation), with the symbolic analysis of its pattern, after checking
/// that the factor's values and the factorization's workspace fit `budget` bytes (they are the largest
/// allocation of a solve: about 1.1 kB per unknown on 2D meshes, see docs/scale.md). No pivoting is needed: a
/// quasi-definite matrix has an LDLᵀ factorization in every symmetric ordering, with as many negative pivots
/// as its negative definite block has rows. The inertia is checked, so a γ0 beyond the bound (an unchecked
/// one) or a matrix at the limits of floating point is an error, not a wrong H.
///
/// # Errors
/// [`Error::MemoryBudget`] naming the size before anything of it is allocated; [`Error::NotPositiveDefinite`]
/// for a zero pivot or an inertia other than (n − negative, negative).
pub(super) fn factorize(
    symbolic: &SymbolicCholesky<usize>,
    a: SparseColMatRef<'_, usize, f64>,
    negative: usize,
    budget: usize,
) -> Result<(Vec<f64>, Vec<f64>)> {
    // Sequential, as the saddle-point system's (`SaddleOptions::par`): the fronts of a 2D mesh are narrow, and with
    // faer's rayon kernels the factorization phase of the graded Coulomb solve took longer on two cores (best of
    // four fresh runs: 0.073 and 0.136 s at 28k and 55k unknowns, against 0.061 and 0.115 s sequential).
    let par = Par::Seq;
    let req = symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default());
    let what = if negative == 0 {
        "the sparse LDLᵀ factor of A = K − G"
    } else {
        "the sparse LDLᵀ factor of the mixed A = K − G"
    };
    // The inverse pivots, n values, sit beside the factor's.
    fits_budget(what, symbolic.len_val(), req, 8.0 * a.nrows() as f64, a.nrows(), budget)?;
    let too_large = |bytes: f64| Error::MemoryBudget {
        what: format!("{what} (the allocation failed)"),
        needed: bytes,
        budget: budget as f64,
    };
    let mut values = Vec::new();
    let len = symbolic.len_val();
    values.try_reserve_exact(len).map_err(|_| too_large(8.0 * len as f64))?;
    values.resize(len, 0.0);
    let mut mem = MemBuffer::try_new(req).map_err(|_| too_large(req.size_bytes() as f64))?;
    let reg = LdltRegularization::default();
    let stack = MemStack::new(&mut mem);
    if let Err(LdltError::ZeroPivot { index }) =
        symbolic.factorize_numeric_ldlt(&mut values, a, Side::Lower, reg, par, stack, Default::default())
    {
        return Err(Error::NotPositiveDefinite {
            what: format!("zero pivot at position {index} of the LDLᵀ factor")
        });
    }
    let pivots = Ldlt::new(symbolic, &values).diagonal();
    let below = pivots.iter().filter(|d| **d < 0.0).count();
    let bad = pivots.iter().position(|d| !d.is_finite() || *d == 0.0);
    if negative == 0 {
        if let Some(p) = bad.or_else(|| pivots.iter().position(|d| *d < 0.0)) {
            let dof = symbolic.perm().map_or(p, |perm| perm.arrays().0[p]);
            return Err(Error::NotPositiveDefinite { what: format!("non-positive pivot at unknown {dof}") });
        }
    } else if below != negative || bad.is_some() {
        return Err(Error::NotPositiveDefinite {
            what: format!(
                "the mixed A = K − G is not quasi-definite: {below} negative pivots for {negative} pressures"
            ),
        });
    }
    let d_inv = pivots.iter().map(|d| 1.0 / d).collect();
    Ok((values, d_inv))
}

/// A sparse factor of `len_val` values with a workspace `req`, and `extra` bytes beside them, must fit
/// `budget` bytes.
pub(super) fn fits_budget(
    what: &str,
    len_val: usize,
    req: StackReq,
    extra: f64,
    n: usize,
    budget: usize,
) -> Result<()> {
    let needed = 8.0 * len_val as f64 + req.size_bytes() as f64 + extra;
    if needed > budget as f64 {
        return Err(Error::MemoryBudget {
            what: format!("{what} ({n} unknowns: {len_val} values and the factorization's workspace)"),
            needed,
            budget: budget as f64,
        });
    }
    Ok(())
}

pub(super) fn solve(direct: &Direct, b: &[f64]) -> Result<Vec<f64>> {
    let mut x = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
    direct.solve_in_place(x.as_mut())?;
    Ok((0..b.len()).map(|i| x[(i, 0)]).collect())
}
