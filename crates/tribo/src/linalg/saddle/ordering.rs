//! The fill-reducing order of the saddle-point unknowns: the displacement dofs in a fill-reducing order of A
//! (AMD on the pattern of `A + EᵀE`, or the order of A's own factor), each multiplier right after the last
//! displacement dof of its row, so that every multiplier's pivot comes after the dofs it constrains and the
//! factorization exists without regularization where `E_F` has full row rank and `D_FF ⪰ 0`.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMat;

use super::{too_large, try_zeroed, SaddleError};

/// AMD on the pattern of `A + EᵀE`; each multiplier is placed right after the
/// last displacement dof of its row (rows without entries go last).
/// Returns `(fwd, inv)` over `n + m` with `fwd[new] = old`.
pub(super) fn constrained_amd(
    a: faer::sparse::SparseColMatRef<'_, usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
) -> Result<(Vec<usize>, Vec<usize>), SaddleError> {
    let n = a.nrows();
    // E^T pattern
    let mut et: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (r, row) in e_rows.iter().enumerate() {
        for &(c, _) in row {
            et[c].push(r);
        }
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx: Vec<usize> = Vec::new();
    row_idx.try_reserve(a.compute_nnz()).map_err(too_large)?;
    col_ptr.push(0usize);
    let mut col: Vec<usize> = Vec::new();
    for j in 0..n {
        col.clear();
        col.extend(a.symbolic().row_idx_of_col_raw(j).iter().copied().filter(|&i| i != j));
        for &r in &et[j] {
            col.extend(e_rows[r].iter().map(|&(c, _)| c).filter(|&c| c != j));
        }
        col.sort_unstable();
        col.dedup();
        row_idx.extend_from_slice(&col);
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let g = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    let mut p = try_zeroed::<usize>(n)?;
    let mut pinv = try_zeroed::<usize>(n)?;
    {
        let mut mem = MemBuffer::try_new(amd::order_maybe_unsorted_scratch::<usize>(n, nnz)).map_err(too_large)?;
        amd::order_maybe_unsorted(&mut p, &mut pinv, g.as_ref(), amd::Control::default(), MemStack::new(&mut mem))
            .map_err(too_large)?;
    }
    drop(g);
    Ok(interleaved(&p, &pinv, e_rows))
}

/// The inverse of the permutation `order` of `0..n` (`order[new] = old`); refused when it is not one.
pub(super) fn inverse_of(order: &[usize], n: usize) -> Result<Vec<usize>, SaddleError> {
    let mut inv = vec![usize::MAX; n];
    if order.len() != n {
        return Err(SaddleError::InvalidInput(format!("an order of {} dofs for A of {n}", order.len())));
    }
    for (new, &old) in order.iter().enumerate() {
        if old >= n || inv[old] != usize::MAX {
            return Err(SaddleError::InvalidInput("the order of A's dofs is not a permutation".into()));
        }
        inv[old] = new;
    }
    Ok(inv)
}

/// The order of the saddle-point unknowns from the order `p` of the displacement dofs (`pinv` its inverse):
/// each multiplier right after the last displacement dof of its row (rows without entries last). Returns
/// `(fwd, inv)` over `n + m` with `fwd[new] = old`.
pub(super) fn interleaved(p: &[usize], pinv: &[usize], e_rows: &[Vec<(usize, f64)>]) -> (Vec<usize>, Vec<usize>) {
    let (n, m) = (p.len(), e_rows.len());
    // bucket multipliers by the position of their last displacement dof
    let mut start = vec![0usize; n + 2];
    let last: Vec<usize> = e_rows.iter().map(|row| row.iter().map(|&(c, _)| pinv[c]).max().unwrap_or(n)).collect();
    for &l in &last {
        start[l + 1] += 1;
    }
    for k in 0..=n {
        start[k + 1] += start[k];
    }
    let mut bucket = vec![0usize; m];
    {
        let mut pos = start.clone();
        for (r, &l) in last.iter().enumerate() {
            bucket[pos[l]] = r;
            pos[l] += 1;
        }
    }
    let mut fwd = Vec::with_capacity(n + m);
    for k in 0..=n {
        if k < n {
            fwd.push(p[k]);
        }
        for &r in &bucket[start[k]..start[k + 1]] {
            fwd.push(n + r);
        }
    }
    let mut inv = vec![0usize; n + m];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    (fwd, inv)
}

/// Whether every row of `E` couples only dofs within two steps of each other in the graph of `a` (each of
/// them next to the row's first dof, or next to one of its neighbours).
pub(super) fn rows_within_two_steps(
    a: faer::sparse::SparseColMatRef<'_, usize, f64>,
    e_rows: &[Vec<(usize, f64)>],
) -> bool {
    let n = a.nrows();
    let neighbours = |c: usize| a.symbolic().row_idx_of_col_raw(c);
    let mut stamp = vec![usize::MAX; n];
    e_rows.iter().enumerate().all(|(r, row)| {
        let Some(&(first, _)) = row.first() else { return true };
        stamp[first] = r;
        for &k in neighbours(first) {
            stamp[k] = r;
        }
        row.iter().all(|&(c, _)| stamp[c] == r || neighbours(c).iter().any(|&k| stamp[k] == r))
    })
}
