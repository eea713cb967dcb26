//! Solves for a partition near the factorized one with that factorization, bordered by the multipliers
//! that changed sides.
//!
//! # Why
//! The steps of an active-set solve after its first few, and the first step of a QP whose bounds
//! barely moved, change the sides of tens of multipliers at most. A new `LDLᵀ` costs as much as a dozen
//! or more solves with the existing one (the ratio grows with the mesh). Bordering costs one solve, plus
//! a short forward substitution per changed multiplier.
//!
//! # The mathematics
//! The scaled matrix `K̃` of a partition `F` differs from `K̃₀`, the factorized one of `F₀`, only in the
//! rows and columns of the multipliers `J = F Δ F₀`. Split `J` into the *freed* ones (fixed in `F₀`,
//! free in `F`) and the *fixed* ones (free in `F₀`, fixed in `F`). The bordered system
//!
//! ```text
//! [ K̃₀  V ] [z]   [b₀]
//! [ Vᵀ  C ] [w] = [b₁]
//! ```
//!
//! has one border column `v_j` per changed multiplier:
//!
//! * fixed `j`: `v_j = e_j`, `C_jj = 0` and `b₁_j = 0`. Its row says `z_j = 0`; its unknown `w_j` absorbs
//!   row `j` of `K̃₀`, the equation `F` no longer has;
//! * freed `j`: `v_j` is column `j` of `K̃` on the displacement rows and on the multipliers free in both
//!   partitions, `C` holds `K̃` among the freed multipliers and `b₁_j = b_j`. Row `j` of `K̃₀` is
//!   decoupled (`−z_j = b₀_j = 0`), so `z_j = 0` and `w_j` is the multiplier.
//!
//! with `b₀ = b` off `J` and `0` on it. Outside `J`, `z` solves the rows of `K̃` there, so `x = z` off `J`,
//! `x_j = w_j` on the freed ones and `x_j = 0` on the fixed ones (the caller's `ν_B` replaces it).
//!
//! With `K̃₀ = Pᵀ L D Lᵀ P` and `W = L⁻¹ P V` — a forward substitution per column, whose right-hand side
//! has a few entries, so that only the elimination-tree path above them is visited — the Schur
//! complement is `S = C − Wᵀ D⁻¹ W` (dense, `|J| × |J|`, full-pivoting LU, its entries kept for later
//! calls), and one solve
//!
//! `y = L⁻¹ P b₀`, `w = S⁻¹ (b₁ − Wᵀ D⁻¹ y)`, `z = Pᵀ L⁻ᵀ D⁻¹ (y − W w)`
//!
//! answers: one forward and one backward substitution, as a solve with `K̃₀` alone.
//!
//! The answer is refined against `K̃` of `F` itself, as [`SaddleSystem::solve`] refines against `K̃₀`: the
//! bordered inverse is only the correction, so the accuracy test is the same.

use faer::linalg::solvers::{FullPivLu, Solve};
use faer::Mat;

use super::super::blocks::{Ldlt, Tree};
use super::*;

/// `W = L⁻¹ v` for a sparse `v` (permuted indices) on the blocks its entries reach: those blocks (in
/// order) and the values of their columns. `x` is a zero work vector of the factor's order, left zero.
fn forward_column(
    blocks: &Blocks<'_>,
    tree: &Tree,
    v: &[(usize, f64)],
    x: &mut [f64],
    tmp: &mut Vec<f64>,
    seen: &mut [bool],
) -> (Vec<usize>, Vec<f64>) {
    let reach = tree.reach(v.iter().map(|&(i, _)| i), seen);
    for &(i, val) in v {
        x[i] = val;
    }
    for &k in &reach {
        blocks.forward(k, x, tmp);
    }
    let mut w = Vec::new();
    for &k in &reach {
        for c in blocks.columns(k) {
            w.push(x[c]);
            x[c] = 0.0;
        }
    }
    (reach, w)
}

/// A border column: the changed multiplier, its column `v` (sparse, scaled) and `W = L⁻¹ P v` on the
/// blocks it reaches (block list, then the values of their columns in that order).
#[derive(Debug)]
struct Column {
    dof: usize,
    v: Vec<(usize, f64)>,
    blocks: Vec<usize>,
    w: Vec<f64>,
}

/// The border columns computed since the last factorization, the products `W_aᵀ D⁻¹ W_b` among them
/// (row a holds b ≤ a), the factorization's `D⁻¹` and the tree of the factor (kept across
/// factorizations: the pattern is fixed).
#[derive(Debug, Default)]
pub(super) struct Border {
    columns: Vec<Column>,
    gram: Vec<Vec<f64>>,
    d_inv: Vec<f64>,
    tree: Option<Tree>,
}

impl Border {
    /// Values the border columns hold (their W; at most the factor's, see [`SaddleSystem::solve`]).
    pub(super) fn held_values(&self) -> usize {
        self.columns.iter().map(|c| c.w.len() + 2 * c.v.len()).sum::<usize>()
            + self.gram.iter().map(Vec::len).sum::<usize>()
    }

    /// The border columns held.
    #[cfg(test)]
    pub(super) fn columns_len(&self) -> usize {
        self.columns.len()
    }

    /// Forgets the columns and takes the pivots `d` of a new factorization (none yet: empty).
    pub(super) fn reset(&mut self, d: &[f64]) {
        self.columns.clear();
        self.gram.clear();
        self.d_inv = d.iter().map(|v| 1.0 / v).collect();
    }
}

/// `Σ a_i b_i / d_i` over the columns two border columns share (their block lists are sorted).
fn product(blocks: &Blocks<'_>, d_inv: &[f64], a: &Column, b: &Column) -> f64 {
    let (mut i, mut j, mut pa, mut pb, mut sum) = (0, 0, 0, 0, 0.0);
    while i < a.blocks.len() && j < b.blocks.len() {
        let (ka, kb) = (a.blocks[i], b.blocks[j]);
        let (wa, wb) = (blocks.columns(ka), blocks.columns(kb));
        if ka == kb {
            let start = wa.start;
            for c in 0..wa.len() {
                sum += a.w[pa + c] * b.w[pb + c] * d_inv[start + c];
            }
        }
        if ka <= kb {
            pa += wa.len();
            i += 1;
        }
        if kb <= ka {
            pb += wb.len();
            j += 1;
        }
    }
    sum
}

impl SaddleSystem {
    /// A factorization's flops in units of a solve's: `Σ_j c_j²` against `4 nnz(L)`, `c_j` the column
    /// counts of L. Deterministic (from the symbolic analysis), unlike a timing.
    pub fn factorization_in_solves(&self) -> f64 {
        let sq = |c: usize| (c * c) as f64;
        let (flops, len) = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let cp = s.col_ptr();
                ((0..self.n + self.m).map(|j| sq(cp[j + 1] - cp[j])).sum::<f64>(), s.len_val())
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let (begin, end, rows) = (s.supernode_begin(), s.supernode_end(), s.col_ptr_for_row_idx());
                let flops = (0..s.n_supernodes())
                    .map(|k| {
                        let (w, p) = (end[k] - begin[k], rows[k + 1] - rows[k]);
                        (1..=w).map(|i| sq(i + p)).sum::<f64>()
                    })
                    .sum::<f64>();
                (flops, s.len_val())
            }
        };
        flops / (4.0 * len.max(1) as f64)
    }

    /// The most changed multipliers [`Self::solve_near`] should take: 10 × [`Self::factorization_in_solves`],
    /// at most 400. A bordered solve costs about one solve, plus a forward substitution along one path
    /// of the elimination tree and the products with the others per multiplier not seen before
    /// (measured at 109k graded unknowns: 11–17 ms for 4 to 65 changed multipliers, against 100 ms for
    /// a factorization and its solve). The factor 10 was measured best on the graded Hertz family (7
    /// factorizations per Coulomb solve at 109k instead of 11 at 4 ×, no gain at 25 ×); the cap bounds
    /// the dense LU of S.
    pub fn border_limit(&self) -> usize {
        (10.0 * self.factorization_in_solves()).min(400.0) as usize
    }

    /// Whether a factorization is held (of the partition last given to [`Self::factorize`]).
    pub fn is_factorized(&self) -> bool {
        self.factorized
    }

    /// The multipliers whose side (free or fixed) differs between `free` and the factorized partition.
    pub fn changed(&self, free: &[bool]) -> Vec<usize> {
        (0..self.m.min(free.len())).filter(|&j| free[j] != self.free[j]).collect()
    }

    /// The border column of the changed multiplier `j` for the partition `free` (module documentation).
    fn border_vector(&self, free: &[bool], j: usize) -> Vec<(usize, f64)> {
        let n = self.n;
        if self.free[j] {
            return vec![(n + j, 1.0)];
        }
        let s = self.scale[n + j];
        let mut v: Vec<(usize, f64)> = self.e_rows[j].iter().map(|&(c, e)| (c, e * self.scale[c] * s)).collect();
        v.extend(
            self.d_rows[j]
                .iter()
                .filter(|&&(i, _)| i != j && self.free[i] && free[i])
                .map(|&(i, d)| (n + i, -d * self.scale[n + i] * s)),
        );
        v
    }

    /// `K̃_ij` of the partition `free` between the freed multipliers `i` and `j` (0 when one is fixed).
    fn freed_entry(&self, free: &[bool], i: usize, j: usize) -> f64 {
        if self.free[i] || self.free[j] || !free[i] || !free[j] {
            return 0.0;
        }
        let d = self.d_rows[i].binary_search_by_key(&j, |&(k, _)| k).map_or(0.0, |p| self.d_rows[i][p].1);
        -d * self.scale[self.n + i] * self.scale[self.n + j]
    }

    /// Solves the saddle-point system of the partition `free` (arguments as in [`Self::solve`]) with the
    /// factorization of the current partition, bordered by the multipliers that changed sides (module
    /// documentation). The border columns are kept for later calls until the next factorization.
    ///
    /// # Errors
    /// As [`Self::solve`]; [`SaddleError::RefinementNotConverged`] when the border is singular (the
    /// partition `free` has no solution) or too ill-conditioned to refine.
    pub fn solve_near(
        &mut self,
        free: &[bool],
        f: &[f64],
        d_rhs: &[f64],
        nu_fixed: &[f64],
    ) -> Result<SaddleSolution, SaddleError> {
        if !self.factorized {
            return Err(SaddleError::NotFactorized);
        }
        let b = self.rhs(free, f, d_rhs, nu_fixed)?;
        let changed = self.changed(free);
        if changed.is_empty() {
            return self.solve(f, d_rhs, nu_fixed);
        }
        // The residual of the refinement is that of K̃ of `free`: its values stand in `self.k` meanwhile.
        self.set_values(free);
        let out = self.solve_bordered(free, &changed, &b, nu_fixed);
        let reference = std::mem::take(&mut self.free);
        self.set_values(&reference);
        self.free = reference;
        out
    }

    /// The border columns of `changed` for `free`: their positions in `self.border.columns`, the new ones
    /// computed (forward substitutions and products).
    ///
    /// # Errors
    /// [`SaddleError::TooLarge`] when the columns would hold more values than the factor.
    fn border_columns(&mut self, free: &[bool], changed: &[usize]) -> Result<Vec<usize>, SaddleError> {
        let nk = self.n + self.m;
        let vectors: Vec<Vec<(usize, f64)>> = changed.iter().map(|&j| self.border_vector(free, j)).collect();
        let blocks = Blocks::new(&self.symbolic, &self.l_values);
        let Border { columns, gram, d_inv, tree } = &mut self.border;
        let tree = tree.get_or_insert_with(|| Tree::new(&blocks));
        let inv = self.symbolic.perm().map(|p| p.arrays().1);
        let at = |i: usize| inv.map_or(i, |inv| inv[i]);
        let mut x = try_zeroed::<f64>(nk)?;
        let mut tmp = Vec::new();
        let mut seen = vec![false; blocks.len()];
        let mut positions = Vec::with_capacity(changed.len());
        for (&j, v) in changed.iter().zip(vectors) {
            if let Some(p) = columns.iter().position(|c| c.dof == j && c.v == v) {
                positions.push(p);
                continue;
            }
            let permuted: Vec<(usize, f64)> = v.iter().map(|&(i, val)| (at(i), val)).collect();
            let (reach, w) = forward_column(&blocks, tree, &permuted, &mut x, &mut tmp, &mut seen);
            // The columns together may hold no more values than the factor itself: beyond, a new
            // factorization is the cheaper start (and the memory stays that of the factor).
            let held: usize = columns.iter().map(|c| c.w.len()).sum::<usize>() + w.len();
            if held > self.symbolic.len_val() {
                return Err(SaddleError::TooLarge(format!("border columns holding {held} values")));
            }
            let column = Column { dof: j, v, blocks: reach, w };
            let row: Vec<f64> = columns
                .iter()
                .chain(std::iter::once(&column))
                .map(|other| product(&blocks, d_inv, &column, other))
                .collect();
            positions.push(columns.len());
            columns.push(column);
            gram.push(row);
        }
        Ok(positions)
    }

    /// `S = C − Wᵀ D⁻¹ W` of the border columns at the positions `at` of the multipliers `changed`.
    fn border_schur(&self, free: &[bool], changed: &[usize], at: &[usize]) -> Mat<f64> {
        let gram = |a: usize, c: usize| {
            let (p, q) = (at[a].max(at[c]), at[a].min(at[c]));
            self.border.gram[p][q]
        };
        Mat::from_fn(changed.len(), changed.len(), |a, c| self.freed_entry(free, changed[a], changed[c]) - gram(a, c))
    }

    /// `[H_FF⁻¹]_JJ` (column-major, `J` = `dofs`, every one free in `free`) for the partition `free`, from
    /// the factorization held and the border of `free` (the one [`Self::solve_near`] last solved with),
    /// without a solve: the multipliers' block of the inverse of the saddle-point matrix is `−H_FF⁻¹`,
    /// and that of the bordered matrix is, in the scaled variables,
    ///
    /// `[K̃⁻¹]_ij = W_iᵀ D⁻¹ W_j + h_iᵀ S⁻¹ h_j`,
    ///
    /// with `W_j = L⁻¹ P e_j` (a forward substitution along one path of the elimination tree) and
    /// `h_j = Wᵀ_C D⁻¹ W_j` for a multiplier outside the changed ones `C`; for a changed (freed) one at
    /// position `a` of `C`, `W_j = 0` and `h_j = −e_a` (its value is the border unknown `w_a`).
    ///
    /// # Errors
    /// [`SaddleError::NotFactorized`]; [`SaddleError::InvalidInput`] for a multiplier that is not free in
    /// `free` or out of range; [`SaddleError::TooLarge`] as [`Self::solve_near`].
    pub fn inverse_block(&mut self, free: &[bool], dofs: &[usize]) -> Result<Vec<f64>, SaddleError> {
        if !self.factorized {
            return Err(SaddleError::NotFactorized);
        }
        let (n, m) = (self.n, self.m);
        if free.len() != m || dofs.iter().any(|&j| j >= m || !free[j]) {
            return Err(SaddleError::InvalidInput("inverse block: a multiplier not free or out of range".into()));
        }
        let changed = self.changed(free);
        let at = self.border_columns(free, &changed)?;
        let lu = (!changed.is_empty()).then(|| FullPivLu::new(self.border_schur(free, &changed, &at).as_ref()));
        let blocks = Blocks::new(&self.symbolic, &self.l_values);
        let Border { columns, d_inv, tree, .. } = &mut self.border;
        let tree = tree.get_or_insert_with(|| Tree::new(&blocks));
        let inv = self.symbolic.perm().map(|p| p.arrays().1);
        let at_perm = |i: usize| inv.map_or(i, |inv| inv[i]);
        let (r, c) = (dofs.len(), changed.len());
        let mut x = try_zeroed::<f64>(n + m)?;
        let (mut tmp, mut seen) = (Vec::new(), vec![false; blocks.len()]);
        // W_j and h_j per multiplier of J (W_j empty for a changed one).
        let mut own: Vec<Option<Column>> = Vec::with_capacity(r);
        let mut h = Mat::<f64>::zeros(c, r);
        for (b, &j) in dofs.iter().enumerate() {
            if let Some(a) = changed.iter().position(|&k| k == j) {
                h[(a, b)] = -1.0;
                own.push(None);
                continue;
            }
            let (reach, w) = forward_column(&blocks, tree, &[(at_perm(n + j), 1.0)], &mut x, &mut tmp, &mut seen);
            let column = Column { dof: j, v: vec![(n + j, 1.0)], blocks: reach, w };
            for (a, &pos) in at.iter().enumerate() {
                h[(a, b)] = product(&blocks, d_inv, &columns[pos], &column);
            }
            own.push(Some(column));
        }
        let s_h = lu.map_or_else(|| Mat::zeros(0, r), |lu| lu.solve(h.as_ref()));
        let mut out = vec![0.0; r * r];
        for b in 0..r {
            for a in 0..=b {
                let direct = match (&own[a], &own[b]) {
                    (Some(x), Some(y)) => product(&blocks, d_inv, x, y),
                    _ => 0.0,
                };
                let coupled: f64 = (0..c).map(|k| h[(k, a)] * s_h[(k, b)]).sum();
                let v = -(direct + coupled) * self.scale[n + dofs[a]] * self.scale[n + dofs[b]];
                out[b * r + a] = v;
                out[a * r + b] = v;
            }
        }
        if out.iter().all(|v| v.is_finite()) {
            Ok(out)
        } else {
            Err(SaddleError::RefinementNotConverged { steps: 0, backward_error: f64::INFINITY })
        }
    }

    /// `x ← K̃₀⁻¹ x` with the factorization held, `K̃₀ = Pᵀ L D Lᵀ P`: the forward substitution over the blocks
    /// `x`'s entries reach, the backward one over all (faer's solve with a supernodal factor reads each
    /// column upward and took about twice as long at 55k).
    pub(super) fn substitute(&self, x: &mut [f64]) {
        let y = Ldlt::new(&self.symbolic, &self.l_values).solve(x, &self.border.d_inv);
        x.copy_from_slice(&y);
    }

    /// [`Self::solve_near`] once `self.k` holds the values of `free`.
    fn solve_bordered(
        &mut self,
        free: &[bool],
        changed: &[usize],
        b: &[f64],
        nu_fixed: &[f64],
    ) -> Result<SaddleSolution, SaddleError> {
        let n = self.n;
        let at = self.border_columns(free, changed)?;
        let border = &self.border;
        let blocks = Blocks::new(&self.symbolic, &self.l_values);
        let cols: Vec<&Column> = at.iter().map(|&p| &border.columns[p]).collect();
        let r = changed.len();
        let lu = FullPivLu::new(self.border_schur(free, changed, &at).as_ref());
        let freed: Vec<bool> = changed.iter().map(|&j| !self.free[j]).collect();
        let (fwd, inv) = match self.symbolic.perm() {
            Some(p) => {
                let (fwd, inv) = p.arrays();
                (Some(fwd), Some(inv))
            }
            None => (None, None),
        };
        let d_inv = &border.d_inv;
        let mut y = vec![0.0; n + self.m];
        let mut tmp = Vec::new();
        let correct = |x: &mut [f64]| {
            let b1: Vec<f64> = changed.iter().zip(&freed).map(|(&j, &fr)| if fr { x[n + j] } else { 0.0 }).collect();
            for &j in changed {
                x[n + j] = 0.0;
            }
            // y = L⁻¹ P b₀
            for (i, yi) in y.iter_mut().enumerate() {
                *yi = x[fwd.map_or(i, |f| f[i])];
            }
            for k in 0..blocks.len() {
                blocks.forward(k, &mut y, &mut tmp);
            }
            // w = S⁻¹ (b₁ − Wᵀ D⁻¹ y)
            let mut t = Mat::from_fn(r, 1, |a, _| b1[a] - column_dot(&blocks, d_inv, cols[a], &y));
            lu.solve_in_place(t.as_mut());
            // z = Pᵀ L⁻ᵀ D⁻¹ (y − W w)
            for (a, col) in cols.iter().enumerate() {
                let wa = t[(a, 0)];
                let mut p = 0;
                for &k in &col.blocks {
                    for c in blocks.columns(k) {
                        y[c] -= wa * col.w[p];
                        p += 1;
                    }
                }
            }
            for (yi, di) in y.iter_mut().zip(d_inv) {
                *yi *= di;
            }
            for k in (0..blocks.len()).rev() {
                blocks.backward(k, &mut y, &mut tmp);
            }
            for (i, xi) in x.iter_mut().enumerate() {
                *xi = y[inv.map_or(i, |v| v[i])];
            }
            for (a, &j) in changed.iter().enumerate() {
                x[n + j] = if freed[a] { t[(a, 0)] } else { 0.0 };
            }
            if t.col(0).iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(SaddleError::RefinementNotConverged { steps: 0, backward_error: f64::INFINITY })
            }
        };
        self.refine(free, b, nu_fixed, correct)
    }
}

/// `Σ w_i y_i / d_i` of a border column and a dense (permuted) vector.
fn column_dot(blocks: &Blocks<'_>, d_inv: &[f64], col: &Column, y: &[f64]) -> f64 {
    let mut p = 0;
    let mut sum = 0.0;
    for &k in &col.blocks {
        for c in blocks.columns(k) {
            sum += col.w[p] * y[c] * d_inv[c];
            p += 1;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::cholesky::supernodal::SupernodalLdltRef;

    /// The block view reads faer's supernodal factor as faer itself does: the same pattern, the same
    /// number of rows and the same values for every supernode.
    #[test]
    fn blocks_read_the_supernodes_as_faer_does() {
        let p = super::super::testgen::contact_problem(30, 10, true);
        let opts = SaddleOptions {
            supernodal_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            par: Par::Seq,
            ..Default::default()
        };
        let mut sys = SaddleSystem::with_options(p.a.as_ref(), &p.e_rows, &p.d, opts).expect("analysed");
        sys.factorize(&vec![true; p.m]).expect("factorized");
        let SymbolicCholeskyRaw::Supernodal(s) = sys.symbolic.raw() else { panic!("supernodal") };
        let faer = SupernodalLdltRef::new(s, &sys.l_values);
        let blocks = Blocks::new(&sys.symbolic, &sys.l_values);
        assert_eq!(blocks.len(), s.n_supernodes());
        for b in 0..blocks.len() {
            let node = faer.supernode(b);
            let (pattern, values) = blocks.parts(b);
            assert_eq!(pattern, node.pattern(), "supernode {b}");
            assert_eq!(blocks.columns(b).start, node.start());
            let m = node.val();
            assert_eq!((m.nrows(), m.ncols()), (blocks.columns(b).len() + pattern.len(), blocks.columns(b).len()));
            for c in 0..m.ncols() {
                for r in 0..m.nrows() {
                    assert_eq!(values[c * m.nrows() + r], m[(r, c)]);
                }
            }
        }
    }
}
