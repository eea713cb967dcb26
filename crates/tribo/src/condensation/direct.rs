//! The sparse Cholesky factor of `A = K − G` in its two orderings (fill-reducing, or the dofs `E`
//! touches last for all of H at once), its solves, and the check that a factor fits the memory budget
//! before its values are allocated.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{LdltRef, LltRef, SymbolicCholesky};
use faer::sparse::SparseColMatRef;
use faer::{Conj, Mat, MatMut, MatRef, Par, Side};

use crate::error::{Error, Result};
use crate::linalg::schur;

/// The sparse Cholesky factorization of A, in one of two orderings.
pub(super) enum Direct {
    /// Fill-reducing (AMD) ordering, the symbolic factorization of K's pattern: columns of H are solves.
    Columns(Arc<SymbolicCholesky<usize>>, Vec<f64>),
    /// The dofs E touches ordered last ([`crate::linalg::schur`]): all of `E A⁻¹ Eᵀ` from the trailing block.
    Schur(schur::SchurFactor),
    /// The LDLᵀ factorization of a quasi-definite A (the mixed formulation, [`crate::fem::mixed`]) in the
    /// fill-reducing ordering: columns of H are solves.
    Ldlt(Arc<SymbolicCholesky<usize>>, Vec<f64>),
}

impl Direct {
    /// The fill-reducing order of A's dofs its factor was analysed with (`order[new] = old`), where it has one
    /// of its own (not the partial factorization's, which orders the Γ_C dofs last).
    pub(super) fn order(&self) -> Option<&[usize]> {
        match self {
            Self::Columns(symbolic, _) | Self::Ldlt(symbolic, _) => symbolic.perm().map(|p| p.arrays().0),
            Self::Schur(_) => None,
        }
    }

    /// Bytes of the factor's values: what [`fits_budget`] counted for it before they were allocated.
    pub(super) fn value_bytes(&self) -> f64 {
        let len = match self {
            Self::Columns(_, values) | Self::Ldlt(_, values) => values.len(),
            Self::Schur(f) => f.len_values(),
        };
        8.0 * len as f64
    }

    /// `x_jᵀ A⁻¹ x_j = ‖L⁻¹ P x_j‖²` for each column of `x` (A = Pᵀ L Lᵀ P): one forward substitution, half a
    /// solve, over the elimination-tree paths above `x_j`'s entries ([`super::substitution`]). `None` for a
    /// factor other than the simplicial Cholesky one (a solve gives it there).
    pub(super) fn energies(&self, x: MatRef<'_, f64>) -> Option<Vec<f64>> {
        let simplicial = self.simplicial()?;
        let energy = |j: usize| {
            let column: Vec<f64> = x.col(j).iter().copied().collect();
            let mut y = simplicial.permuted(&column);
            simplicial.forward(&mut y);
            y.iter().map(|v| v * v).sum::<f64>()
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
            Self::Columns(symbolic, values) => {
                let mut mem = workspace(symbolic)?;
                LltRef::new(symbolic, values).solve_in_place_with_conj(Conj::No, x, par, MemStack::new(&mut mem));
            }
            Self::Ldlt(symbolic, values) => {
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

/// The numeric Cholesky factorization of `a` with the symbolic analysis of its pattern, after checking that
/// the factor's values and the factorization's workspace fit `budget` bytes (they are the largest
/// allocation of a solve: about 1.1 kB per unknown on 2D meshes, see docs/scale.md).
///
/// # Errors
/// [`Error::MemoryBudget`] naming the size before anything of it is allocated;
/// [`Error::NotPositiveDefinite`] for a non-positive pivot.
pub(super) fn factorize_plain(
    symbolic: &SymbolicCholesky<usize>,
    a: SparseColMatRef<'_, usize, f64>,
    budget: usize,
) -> Result<Vec<f64>> {
    let par = faer::get_global_parallelism();
    let req = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
    fits_budget("the sparse Cholesky factor of A = K − G", symbolic.len_val(), req, 0.0, a.nrows(), budget)?;
    schur::numeric_llt(symbolic, a, par).map_err(|e| match e {
        schur::SchurError::TooLarge { what, bytes } => Error::MemoryBudget {
            what: format!("the sparse Cholesky factor of A = K − G: {what} (the allocation failed)"),
            needed: bytes as f64,
            budget: budget as f64,
        },
        e => schur_error(e),
    })
}

/// The numeric LDLᵀ factorization of a symmetric quasi-definite `a` (its last `negative` unknowns the
/// pressures of the mixed formulation) with the symbolic analysis of its pattern, after the budget check
/// of [`factorize_plain`]. No pivoting is needed: a quasi-definite matrix has an LDLᵀ factorization in every
/// symmetric ordering, with as many negative pivots as its negative definite block has rows. The inertia
/// is checked, so a γ0 beyond the bound (an unchecked one) or a matrix at the limits of floating point is
/// an error, not a wrong H.
///
/// # Errors
/// [`Error::MemoryBudget`] naming the size; [`Error::NotPositiveDefinite`] for a zero pivot or an inertia
/// other than (n − negative, negative).
pub(super) fn factorize_quasi_definite(
    symbolic: &SymbolicCholesky<usize>,
    a: SparseColMatRef<'_, usize, f64>,
    negative: usize,
    budget: usize,
) -> Result<Vec<f64>> {
    let par = faer::get_global_parallelism();
    let req = symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default());
    let what = "the sparse LDLᵀ factor of the mixed A = K − G";
    fits_budget(what, symbolic.len_val(), req, 0.0, a.nrows(), budget)?;
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
    let pivots = crate::linalg::saddle::ldlt_pivots(symbolic, &values);
    let below = pivots.iter().filter(|d| **d < 0.0).count();
    if below != negative || pivots.iter().any(|d| !d.is_finite() || *d == 0.0) {
        return Err(Error::NotPositiveDefinite {
            what: format!(
                "the mixed A = K − G is not quasi-definite: {below} negative pivots for {negative} pressures"
            ),
        });
    }
    Ok(values)
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
