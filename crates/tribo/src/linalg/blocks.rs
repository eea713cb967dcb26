//! The sparse LDLᵀ factor `A = Pᵀ L D Lᵀ P` of faer (simplicial or supernodal) read block by block, and its
//! substitutions: the forward one visits only the blocks a right-hand side reaches, the backward one runs over
//! the blocks asked for. The saddle-point system's bordered solves ([`super::saddle`]) and the factor of `A`
//! of the condensation share them.
//!
//! # The mathematics
//! The forward substitution `y ← L⁻¹ y` by columns adds column j's multiples only where `y_j ≠ 0`: a column
//! with `y_j = 0` changes nothing, so skipping it is exact. The entries that become nonzero lie on the
//! elimination-tree paths above the right-hand side's entries.
//!
//! The backward substitution `x_j = y_j − Σ_{i>j} L_ij x_i` reads only rows `i` of column j's pattern, all
//! ancestors of j in the elimination tree; a block's pattern lies in the blocks above it in the tree of
//! blocks. So the entries of `x` on a set of blocks closed under "parent of" (the union of the paths from
//! the asked blocks to the root, [`Tree::reach`]) come from the backward substitution over those blocks
//! alone, exactly.

use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};

/// The factor column block by column block: supernodes, or single columns of a simplicial factor. The
/// unit lower triangle holds L, the diagonal D.
pub(crate) enum Blocks<'a> {
    Simplicial {
        col_ptr: &'a [usize],
        row_idx: &'a [usize],
        values: &'a [f64],
    },
    Supernodal {
        begin: &'a [usize],
        end: &'a [usize],
        rows: &'a [usize],
        row_ptr: &'a [usize],
        val_ptr: &'a [usize],
        values: &'a [f64],
    },
}

impl<'a> Blocks<'a> {
    pub(crate) fn new(symbolic: &'a SymbolicCholesky<usize>, values: &'a [f64]) -> Self {
        match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                Self::Simplicial { col_ptr: s.col_ptr(), row_idx: s.row_idx(), values }
            }
            SymbolicCholeskyRaw::Supernodal(s) => Self::Supernodal {
                begin: s.supernode_begin(),
                end: s.supernode_end(),
                rows: s.row_idx(),
                row_ptr: s.col_ptr_for_row_idx(),
                val_ptr: s.col_ptr_for_val(),
                values,
            },
        }
    }

    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Simplicial { col_ptr, .. } => col_ptr.len() - 1,
            Self::Supernodal { begin, .. } => begin.len(),
        }
    }

    /// The columns of block `b`.
    pub(crate) fn columns(&self, b: usize) -> std::ops::Range<usize> {
        match self {
            Self::Simplicial { .. } => b..b + 1,
            Self::Supernodal { begin, end, .. } => begin[b]..end[b],
        }
    }

    /// The rows below block `b`'s diagonal block (its pattern) and its values, column-major with
    /// `width + pattern` rows (a simplicial column: its diagonal, then its pattern).
    pub(crate) fn parts(&self, b: usize) -> (&'a [usize], &'a [f64]) {
        match *self {
            Self::Simplicial { col_ptr, row_idx, values } => {
                (&row_idx[col_ptr[b] + 1..col_ptr[b + 1]], &values[col_ptr[b]..col_ptr[b + 1]])
            }
            Self::Supernodal { rows, row_ptr, val_ptr, values, .. } => {
                (&rows[row_ptr[b]..row_ptr[b + 1]], &values[val_ptr[b]..val_ptr[b + 1]])
            }
        }
    }

    /// `x ← L_b⁻¹ x` on block `b`: the unit lower diagonal block, then the rows below it (accumulated in
    /// `tmp`, contiguous, and scattered once).
    pub(crate) fn forward(&self, b: usize, x: &mut [f64], tmp: &mut Vec<f64>) {
        let cols = self.columns(b);
        let (start, w) = (cols.start, cols.len());
        if x[cols].iter().all(|v| *v == 0.0) {
            return;
        }
        let (pattern, m) = self.parts(b);
        let nr = w + pattern.len();
        tmp.clear();
        tmp.resize(pattern.len(), 0.0);
        let mut any = false;
        for c in 0..w {
            let col = &m[c * nr..(c + 1) * nr];
            let xc = x[start + c];
            if xc == 0.0 {
                continue;
            }
            any = true;
            for r in c + 1..w {
                x[start + r] -= col[r] * xc;
            }
            for (t, l) in tmp.iter_mut().zip(&col[w..]) {
                *t += l * xc;
            }
        }
        if any {
            for (&i, t) in pattern.iter().zip(tmp.iter()) {
                x[i] -= t;
            }
        }
    }

    /// `x ← L_b⁻ᵀ x` on block `b` (the rows below it already final; gathered once into `tmp`).
    pub(crate) fn backward(&self, b: usize, x: &mut [f64], tmp: &mut Vec<f64>) {
        let cols = self.columns(b);
        let (start, w) = (cols.start, cols.len());
        let (pattern, m) = self.parts(b);
        let nr = w + pattern.len();
        tmp.clear();
        tmp.extend(pattern.iter().map(|&i| x[i]));
        // Each column is read from its end: the whole pass then moves down through memory (the order the
        // blocks and columns are taken in), 1.6 times faster at 55k than reading each column upward.
        for c in (0..w).rev() {
            let col = &m[c * nr..(c + 1) * nr];
            let (top, below) = col.split_at(w);
            let sum = dot_from_end(below, tmp) + dot_from_end(&top[c + 1..], &x[start + c + 1..start + w]);
            x[start + c] -= sum;
        }
    }

    /// D (one value per column).
    pub(crate) fn diagonal(&self) -> Vec<f64> {
        let mut d = Vec::new();
        for b in 0..self.len() {
            let w = self.columns(b).len();
            let (pattern, m) = self.parts(b);
            let nr = w + pattern.len();
            d.extend((0..w).map(|c| m[c * nr + c]));
        }
        d
    }
}

/// The elimination tree of the factor's blocks, for forward substitutions with few right-hand-side
/// entries: the block of every (permuted) column and the parent of every block.
#[derive(Debug)]
pub(crate) struct Tree {
    block_of: Vec<usize>,
    parent: Vec<Option<usize>>,
}

impl Tree {
    pub(crate) fn new(blocks: &Blocks<'_>) -> Self {
        let mut block_of = Vec::new();
        for b in 0..blocks.len() {
            block_of.extend(blocks.columns(b).map(|_| b));
        }
        let parent = (0..blocks.len()).map(|b| blocks.parts(b).0.iter().min().map(|&i| block_of[i])).collect();
        Self { block_of, parent }
    }

    /// The blocks a forward substitution from the (permuted) columns `cols` visits, in order.
    pub(crate) fn reach(&self, cols: impl Iterator<Item = usize>, seen: &mut [bool]) -> Vec<usize> {
        let mut out = Vec::new();
        for c in cols {
            let mut b = Some(self.block_of[c]);
            while let Some(k) = b.filter(|&k| !seen[k]) {
                seen[k] = true;
                out.push(k);
                b = self.parent[k];
            }
        }
        for &k in &out {
            seen[k] = false;
        }
        out.sort_unstable();
        out
    }
}

/// The LDLᵀ factor `A = Pᵀ L D Lᵀ P` with its order, for solves that read little of it.
pub(crate) struct Ldlt<'a> {
    blocks: Blocks<'a>,
    /// `order[new] = old` and its inverse `at[old] = new`, where the factor has an order.
    perm: Option<(&'a [usize], &'a [usize])>,
}

impl<'a> Ldlt<'a> {
    /// The factor of faer's numeric LDLᵀ `values` with the symbolic analysis `symbolic`.
    pub(crate) fn new(symbolic: &'a SymbolicCholesky<usize>, values: &'a [f64]) -> Self {
        Self { blocks: Blocks::new(symbolic, values), perm: symbolic.perm().map(|p| p.arrays()) }
    }

    /// The position in the factor of A's unknown `i`.
    pub(crate) fn position(&self, i: usize) -> usize {
        self.perm.map_or(i, |(_, at)| at[i])
    }

    /// `P b`: `b` (A's numbering) in the factor's order.
    pub(crate) fn permuted(&self, b: &[f64]) -> Vec<f64> {
        (0..b.len()).map(|p| b[self.perm.map_or(p, |(order, _)| order[p])]).collect()
    }

    /// `Pᵀ y`: `y` (the factor's order) in A's numbering.
    pub(crate) fn unpermuted(&self, y: &[f64]) -> Vec<f64> {
        (0..y.len()).map(|i| y[self.position(i)]).collect()
    }

    /// D (one pivot per position).
    pub(crate) fn diagonal(&self) -> Vec<f64> {
        self.blocks.diagonal()
    }

    /// `y ← L⁻¹ y` (`y` in the factor's order), visiting only the columns where `y` is nonzero.
    pub(crate) fn forward(&self, y: &mut [f64]) {
        let mut tmp = Vec::new();
        for k in 0..self.blocks.len() {
            self.blocks.forward(k, y, &mut tmp);
        }
    }

    /// `y ← L⁻ᵀ y` on the blocks `closed` only (increasing, closed under the tree's parent,
    /// [`Self::closure`]): exact there, the other entries of `y` left as they were.
    pub(crate) fn backward_on(&self, y: &mut [f64], closed: &[usize]) {
        let mut tmp = Vec::new();
        for &k in closed.iter().rev() {
            self.blocks.backward(k, y, &mut tmp);
        }
    }

    /// `y ← L⁻ᵀ y` on every block.
    pub(crate) fn backward(&self, y: &mut [f64]) {
        let mut tmp = Vec::new();
        for k in (0..self.blocks.len()).rev() {
            self.blocks.backward(k, y, &mut tmp);
        }
    }

    /// `A⁻¹ b = Pᵀ L⁻ᵀ D⁻¹ L⁻¹ P b`, with `d_inv` the inverses of the pivots (the factor's order).
    pub(crate) fn solve(&self, b: &[f64], d_inv: &[f64]) -> Vec<f64> {
        let mut y = self.permuted(b);
        self.forward(&mut y);
        y.iter_mut().zip(d_inv).for_each(|(yi, di)| *yi *= di);
        self.backward(&mut y);
        self.unpermuted(&y)
    }

    /// The blocks holding A's unknowns `dofs` and every block above them in the tree, increasing.
    pub(crate) fn closure(&self, dofs: impl Iterator<Item = usize>) -> Vec<usize> {
        let tree = Tree::new(&self.blocks);
        let mut seen = vec![false; self.blocks.len()];
        tree.reach(dofs.map(|i| self.position(i)), &mut seen)
    }
}

/// `Σ a_i b_i` from the last term to the first, in four independent sums.
pub(crate) fn dot_from_end(a: &[f64], b: &[f64]) -> f64 {
    let (ca, cb) = (a.rchunks_exact(4), b.rchunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    let mut acc = [0.0; 4];
    for (x, y) in ca.zip(cb) {
        for k in (0..4).rev() {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}
