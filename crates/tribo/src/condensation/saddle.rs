//! The saddle-point system `[[A, Eᵀ], [E, −Dγ]]` of the condensation's saddle path, built within the memory
//! budget: refused as [`Error::MemoryBudget`] before its factorization when one displacement dof already couples
//! more multiplier unknowns than the budget's factor can hold.

use faer::sparse::SparseColMatRef;

use crate::error::{Error, Result};
use crate::linalg::saddle::{SaddleError, SaddleOptions, SaddleSystem};

use super::choose::{saddle_clique, CHOLESKY_FILL};

/// Which saddle-point system a condensation builds beside the factor of A.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Wish {
    /// None: H is formed (by columns or all of it).
    No,
    /// Asked for (`condensation = "saddle"`): a factor beyond the budget is an error.
    Asked,
    /// Preferred by `auto`: one that fills in much beyond a Cholesky of A (T_H far finer than the FE edges: the
    /// multipliers' block fills) or beyond the budget leaves H to the columns.
    Preferred,
}

/// The bytes the saddle-point system may hold beside the factor of A of `factor_bytes`: half of what the budget
/// leaves, for its own factor's values, and as many again for the border columns of nearby partitions.
pub(super) fn beside(budget: usize, factor_bytes: f64) -> usize {
    (budget as f64 - factor_bytes).max(0.0) as usize / 2
}

/// The saddle-point system `wish` names, within `beside` bytes ([`beside`]); A's last `pressures` unknowns are a
/// mixed formulation's, `order` the fill-reducing order of A's factor and `nnz_k` the non-zeros of K (the cost
/// model's unit). Its symbolic analysis says how large its factor is before anything of that size is allocated.
#[allow(clippy::too_many_arguments)]
pub(super) fn wished(
    wish: Wish,
    a: SparseColMatRef<'_, usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
    d_cols: &[Vec<(usize, f64)>],
    beside: usize,
    pressures: usize,
    nnz_k: usize,
    order: Option<&[usize]>,
) -> Result<Option<SaddleSystem>> {
    match wish {
        Wish::No => Ok(None),
        Wish::Asked => Ok(Some(saddle_system(a, e_rows, d_cols, [beside / 8, beside, pressures], order)?)),
        Wish::Preferred => {
            let limits = [2 * CHOLESKY_FILL * nnz_k, beside, pressures];
            Ok(saddle_system(a, e_rows, d_cols, limits, order).ok())
        }
    }
}

/// The saddle-point kernel's errors as the crate's (its inputs come from the core, so only size and
/// breakdowns can occur; a breakdown is reported by the caller as an uncertified QP).
fn saddle_error(e: SaddleError) -> Error {
    match e {
        SaddleError::TooLarge(what) => Error::MemoryBudget {
            what: format!("the saddle-point factorization: {what}"),
            needed: f64::NAN,
            budget: f64::NAN,
        },
        e => Error::Assembly { matrix: "the saddle-point system [[A, Eᵀ], [E, −Dγ]]", what: e.to_string() },
    }
}

/// The saddle-point system of `A`, `E` and `Dγ` (by columns), refused beyond `max_len` factor values
/// (and beyond `budget` bytes, as [`Error::MemoryBudget`]); A's last `pressures` unknowns are a mixed
/// formulation's (A quasi-definite). Its displacement dofs take `order`, the fill-reducing order of A's own
/// factor, where there is one ([`SaddleSystem::with_order`]).
fn saddle_system(
    a: SparseColMatRef<'_, usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
    d_cols: &[Vec<(usize, f64)>],
    [max_len, budget, pressures]: [usize; 3],
    order: Option<&[usize]>,
) -> Result<SaddleSystem> {
    let d: Vec<(usize, usize, f64)> =
        d_cols.iter().enumerate().flat_map(|(j, col)| col.iter().map(move |&(i, v)| (i, j, v))).collect();
    let opts = SaddleOptions { max_factor_len: max_len.min(budget / 8), negative: pressures, ..Default::default() };
    let (c, clique) = saddle_clique(e_rows, a.nrows());
    if clique > opts.max_factor_len {
        let what = format!(
            "the sparse factor of the saddle-point system [[A, Eᵀ], [E, −Dγ]] (at least: {c} multiplier \
                            unknowns couple to one displacement dof), in half the budget left beside the factor of A"
        );
        return Err(Error::MemoryBudget { what, needed: 8.0 * clique as f64, budget: budget as f64 });
    }
    SaddleSystem::with_order(a, e_rows, &d, opts, order).map_err(|e| match e {
        SaddleError::FactorTooLarge { values } => Error::MemoryBudget {
            what: "the sparse factor of the saddle-point system [[A, Eᵀ], [E, −Dγ]], in half the budget left beside \
                   the factor of A"
                .to_string(),
            needed: 8.0 * values as f64,
            budget: budget as f64,
        },
        e => saddle_error(e),
    })
}
