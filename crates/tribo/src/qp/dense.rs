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
    ///
    /// Removals go last position first, each a rank-one update of the trailing block with the column
    /// below it; the removed row and column then become the identity's (a unit diagonal, zeros around),
    /// which every later update passes through unchanged (its entry of the update vector stays 0), so the
    /// factor is compacted once at the end, in place, rather than copied at every removal. Each addition
    /// is a new last row, solved in place in the compacted factor, grown once to its final size.
    fn update(
        &self,
        order: Vec<usize>,
        mut l: Mat<f64>,
        keep: &std::collections::HashSet<usize>,
        added: &[usize],
    ) -> Option<(Vec<usize>, Mat<f64>)> {
        let k = order.len();
        let dead: Vec<bool> = order.iter().map(|i| !keep.contains(i)).collect();
        for p in (0..k).rev().filter(|&p| dead[p]) {
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
            for j in 0..k {
                l[(p, j)] = 0.0;
                l[(j, p)] = 0.0;
            }
            l[(p, p)] = 1.0;
        }
        // Compacted in place, column by column: entry (a, b) comes from (live[a], live[b]), never before
        // it in column-major order, so no source is overwritten before it is read; the strictly upper
        // part (which the rank updates may clobber) is zeroed.
        let live: Vec<usize> = (0..k).filter(|&p| !dead[p]).collect();
        let (m0, size) = (live.len(), live.len() + added.len());
        for (b, &j) in live.iter().enumerate() {
            for (a, &i) in live.iter().enumerate() {
                l[(a, b)] = if a >= b { l[(i, j)] } else { 0.0 };
            }
        }
        l.truncate(m0, m0);
        l.resize_with(size, size, |_, _| 0.0);
        let mut out = l;
        let mut order: Vec<usize> = live.iter().map(|&p| order[p]).collect();
        // Addition of unknown a as row m: L y = H[order, a], δ² = H_aa − yᵀy.
        for (m, &a) in (m0..).zip(added) {
            let mut y = Mat::<f64>::from_fn(m, 1, |i, _| self.entry(order[i], a));
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                out.as_ref().submatrix(0, 0, m, m),
                y.as_mut(),
                faer::Par::Seq,
            );
            let yy: f64 = (0..m).map(|i| y[(i, 0)] * y[(i, 0)]).sum();
            let d2 = self.entry(a, a) - yy;
            if d2.is_nan() || d2 <= 64.0 * f64::EPSILON * self.entry(a, a) {
                return None;
            }
            for j in 0..m {
                out[(m, j)] = y[(j, 0)];
            }
            out[(m, m)] = d2.sqrt();
            order.push(a);
        }
        Some((order, out))
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A symmetric positive definite k × k matrix (column-major) from a seed: `BᵀB + k I`.
    fn spd(k: usize, seed: u64) -> Vec<f64> {
        let mut x = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((x >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let b: Vec<f64> = (0..k * k).map(|_| next()).collect();
        let mut h = vec![0.0; k * k];
        for i in 0..k {
            for j in 0..k {
                h[j * k + i] =
                    (0..k).map(|r| b[i * k + r] * b[j * k + r]).sum::<f64>() + if i == j { k as f64 } else { 0.0 };
            }
        }
        h
    }

    proptest! {
        #![proptest_config(ProptestConfig { failure_persistence: None, ..ProptestConfig::default() })]

        /// The factor updated from one free set to another (removals anywhere, several at once, and
        /// additions) is the Cholesky factor of the new free block, to round-off, in the order it reports.
        #[test]
        fn an_updated_factor_is_the_new_blocks_factor(
            k in 2usize..24, seed in any::<u64>(), first in proptest::collection::vec(any::<bool>(), 24),
            second in proptest::collection::vec(any::<bool>(), 24),
        ) {
            let h = spd(k, seed);
            let block = DenseBlock::new(h.clone(), vec![0.0; k]);
            let old: Vec<usize> = (0..k).filter(|&i| first[i]).collect();
            prop_assume!(!old.is_empty());
            // Test code: `spd` is positive definite by construction (BᵀB + kI), so every principal block
            // factorizes and every update keeps it so; a failure here is a defect of the update.
            let hff = Mat::<f64>::from_fn(old.len(), old.len(), |a, b| h[old[b] * k + old[a]]);
            let l = hff.llt(Side::Lower).expect("a principal block of BᵀB + kI is positive definite").L().to_owned();
            let new: Vec<usize> = (0..k).filter(|&i| second[i]).collect();
            let keep: std::collections::HashSet<usize> = new.iter().copied().collect();
            let added: Vec<usize> = new.iter().copied().filter(|i| !old.contains(i)).collect();
            let (order, lu) = block.update(old.clone(), l, &keep, &added).expect("an update of a positive definite block stays so");
            let mut sorted = order.clone();
            sorted.sort_unstable();
            prop_assert_eq!(sorted, new);
            // Round-off: a Cholesky factorization reproduces H to about k ε max|H| (backward stable),
            // and each of at most k removals or additions adds as much again.
            let allowed = 4.0 * (k * k) as f64 * f64::EPSILON * h.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let n = order.len();
            for a in 0..n {
                for b in 0..n {
                    let llt: f64 = (0..n).map(|r| lu[(a, r)] * lu[(b, r)]).sum();
                    let want = h[order[b] * k + order[a]];
                    prop_assert!((llt - want).abs() <= allowed, "{a} {b}: {llt} {want} (allowed {allowed:e})");
                    if b > a {
                        prop_assert_eq!(lu[(a, b)], 0.0);
                    }
                }
            }
        }
    }
}
