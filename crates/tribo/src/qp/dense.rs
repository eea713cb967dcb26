//! The dense block of H on a working set, for the active-set method ([`QpOperator`]): H and c on the
//! set's unknowns and the Cholesky factor of the last free block, updated (a rank-one downdate per
//! unknown that left the free set, a new row per unknown that joined it) rather than refactorized when
//! few unknowns change sides.

use faer::{Mat, Side};

use crate::qp::active_set::QpOperator;

/// The dense QP data on a set of unknowns: H (column-major `k × k`) and c, with the Cholesky factor of
/// the last free block, updated rather than refactored when few unknowns change sides.
#[derive(Debug)]
pub(crate) struct DenseBlock {
    k: usize,
    h: Vec<f64>,
    c: Vec<f64>,
    diag: Vec<f64>,
    /// The free unknowns in the order of the factor, and the factor L (lower) of `H_FF` in that order.
    factor: Option<(Vec<usize>, Mat<f64>)>,
    /// Full Cholesky factorizations of a free block.
    pub factorizations: u32,
    /// Free blocks obtained by updating the previous factor (unknowns removed or appended).
    pub updates: u32,
}

impl DenseBlock {
    /// The block from H (column-major `k × k`, symmetric) and c (k).
    pub(crate) fn new(h: Vec<f64>, c: Vec<f64>) -> Self {
        let k = c.len();
        let diag = (0..k).map(|i| h[i * k + i]).collect();
        Self { k, h, c, diag, factor: None, factorizations: 0, updates: 0 }
    }

    /// H (column-major).
    pub(crate) fn matrix(&self) -> &[f64] {
        &self.h
    }

    /// c.
    pub(crate) fn linear_term(&self) -> &[f64] {
        &self.c
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        self.h[j * self.k + i]
    }

    /// The Cholesky factor of `H_FF` for the free unknowns `free` (ascending), by updating the previous
    /// factor when at most an eighth of the block changes (each removal a rank-one update of the trailing
    /// block, each addition a new last row: O(k²) each), else by a new factorization (O(k³/3)).
    fn free_factor(&mut self, free: &[usize]) -> Option<(Vec<usize>, Mat<f64>)> {
        if let Some((order, l)) = self.factor.take() {
            let in_new: std::collections::HashSet<usize> = free.iter().copied().collect();
            let in_old: std::collections::HashSet<usize> = order.iter().copied().collect();
            let removed = order.iter().filter(|i| !in_new.contains(i)).count();
            let added: Vec<usize> = free.iter().copied().filter(|i| !in_old.contains(i)).collect();
            if removed + added.len() <= (free.len() / 8).max(8) {
                if let Some(updated) = self.update(order, l, &in_new, &added) {
                    self.updates += 1;
                    return Some(updated);
                }
            }
        }
        self.factorizations += 1;
        let nf = free.len();
        let hff = Mat::<f64>::from_fn(nf, nf, |a, b| self.entry(free[a], free[b]));
        let llt = hff.llt(Side::Lower).ok()?;
        Some((free.to_vec(), llt.L().to_owned()))
    }

    /// Removes the unknowns not in `keep` from the factor and appends `added`; `None` if an update loses
    /// positive definiteness (the caller factorizes anew).
    fn update(
        &self,
        mut order: Vec<usize>,
        mut l: Mat<f64>,
        keep: &std::collections::HashSet<usize>,
        added: &[usize],
    ) -> Option<(Vec<usize>, Mat<f64>)> {
        // Removal of position p: the trailing block takes the rank-one update with its column below p.
        while let Some(p) = order.iter().rposition(|i| !keep.contains(i)) {
            let k = order.len();
            if p + 1 < k {
                let mut w = Mat::<f64>::from_fn(k - p - 1, 1, |a, _| l[(p + 1 + a, p)]);
                let mut alpha = Mat::<f64>::from_fn(1, 1, |_, _| 1.0);
                let (_, _, _, trailing) = l.as_mut().split_at_mut(p + 1, p + 1);
                faer::linalg::cholesky::llt::update::rank_r_update_clobber(
                    trailing,
                    w.as_mut(),
                    alpha.as_mut().col_mut(0).as_diagonal_mut(),
                )
                .ok()?;
            }
            let kept = Mat::<f64>::from_fn(k - 1, k - 1, |a, b| {
                let (i, j) = (a + usize::from(a >= p), b + usize::from(b >= p));
                if i >= j {
                    l[(i, j)]
                } else {
                    0.0
                }
            });
            l = kept;
            order.remove(p);
        }
        // Addition of unknown a as the last row: L y = H[order, a], δ² = H_aa − yᵀy.
        for &a in added {
            let k = order.len();
            let mut y = Mat::<f64>::from_fn(k, 1, |i, _| self.entry(order[i], a));
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), faer::Par::Seq);
            let yy: f64 = (0..k).map(|i| y[(i, 0)] * y[(i, 0)]).sum();
            let d2 = self.entry(a, a) - yy;
            if d2.is_nan() || d2 <= 64.0 * f64::EPSILON * self.entry(a, a) {
                return None;
            }
            let grown = Mat::<f64>::from_fn(k + 1, k + 1, |i, j| match (i < k, j < k) {
                (true, true) => l[(i, j)],
                (false, true) => y[(j, 0)],
                (false, false) => d2.sqrt(),
                (true, false) => 0.0,
            });
            l = grown;
            order.push(a);
        }
        Some((order, l))
    }
}

impl QpOperator for DenseBlock {
    fn gradient(&self, x: &[f64]) -> Vec<f64> {
        let mut g = self.c.clone();
        for (j, &xj) in x.iter().enumerate() {
            if xj != 0.0 {
                for (gi, hij) in g.iter_mut().zip(&self.h[j * self.k..(j + 1) * self.k]) {
                    *gi += hij * xj;
                }
            }
        }
        g
    }

    fn newton_point(&mut self, free: &[bool], x: &[f64]) -> Option<Vec<f64>> {
        let idx: Vec<usize> = (0..self.k).filter(|&i| free[i]).collect();
        let mut out = x.to_vec();
        if idx.is_empty() {
            return Some(out);
        }
        let (order, l) = self.free_factor(&idx)?;
        let mut rhs = Mat::<f64>::from_fn(order.len(), 1, |a, _| -self.c[order[a]]);
        for (j, &xj) in x.iter().enumerate() {
            if !free[j] && xj != 0.0 {
                let col = &self.h[j * self.k..(j + 1) * self.k];
                for (a, &i) in order.iter().enumerate() {
                    rhs[(a, 0)] -= col[i] * xj;
                }
            }
        }
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), rhs.as_mut(), faer::Par::Seq);
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            l.as_ref().transpose(),
            rhs.as_mut(),
            faer::Par::Seq,
        );
        for (a, &i) in order.iter().enumerate() {
            out[i] = rhs[(a, 0)];
        }
        self.factor = Some((order, l));
        out.iter().all(|v| v.is_finite()).then_some(out)
    }

    fn diagonal(&self) -> &[f64] {
        &self.diag
    }
}
