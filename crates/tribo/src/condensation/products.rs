//! The products with the condensation's matrices, without forming H: `A x` (`K x − G x`), `E u`, `Eᵀ λ`, `Dγ λ`, and
//! the diagonals of A and Dγ.

use faer::sparse::SparseColMatRef;

use super::Factor;

impl Factor {
    /// The diagonal of A.
    pub(crate) fn a_diagonal(&self) -> Vec<f64> {
        self.a_diag.clone()
    }

    /// The diagonal of Dγ (2q).
    pub(crate) fn d_diagonal(&self) -> Vec<f64> {
        self.d_cols
            .iter()
            .enumerate()
            .map(|(j, col)| col.iter().filter(|(i, _)| *i == j).map(|(_, v)| v).sum())
            .collect()
    }

    /// `A x` (free dofs) for the stiffness `k` this factor was built from: `K x − G x`.
    pub fn apply_a(&self, k: SparseColMatRef<'_, usize, f64>, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        for (j, xj) in x.iter().enumerate() {
            for (i, v) in k.row_idx_of_col(j).zip(k.val_of_col(j)) {
                y[i] += v * xj;
            }
        }
        for t in &self.minus_g {
            y[t.row] += t.val * x[t.col];
        }
        y
    }

    /// `Dγ λ` (2q).
    pub fn apply_d(&self, lambda: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; lambda.len()];
        for (col, l) in self.d_cols.iter().zip(lambda) {
            for &(r, v) in col {
                y[r] += v * l;
            }
        }
        y
    }

    /// `E u` (2q).
    pub fn apply_e(&self, u: &[f64]) -> Vec<f64> {
        self.e_rows.iter().map(|row| dot(row, u)).collect()
    }

    /// `Eᵀ λ` (free dofs).
    pub fn apply_et(&self, lambda: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for (row, l) in self.e_rows.iter().zip(lambda) {
            for &(d, v) in row {
                y[d] += v * l;
            }
        }
        y
    }
}

/// The diagonal of a sparse matrix (0 where it stores none).
pub(super) fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    (0..a.ncols())
        .map(|j| a.row_idx_of_col(j).zip(a.val_of_col(j)).find(|(i, _)| *i == j).map_or(0.0, |(_, v)| *v))
        .collect()
}

pub(super) fn dot(row: &[(usize, f64)], x: &[f64]) -> f64 {
    row.iter().map(|&(d, v)| v * x[d]).sum()
}
