//! The scaling of the Γ_C QP.
//!
//! clarabel's tolerances are absolute as well as relative, so the QP is non-dimensionalised before it is
//! handed over. The unknowns are `x = (ν_n / s, ν_t / w_t)` with `s = c_s / h_s` (`h_s = max diag H_nn`,
//! `c_s = max |c_n|`, the size of λ_n for which the quadratic and linear terms balance) and
//! `w_t,j = min(g_j, s_t)`, `s_t = max(s, c_st / h_st)` the natural size of λ_t (`c_st`, `h_st` as `c_s`,
//! `h_s` on the tangential unknowns); the box is then `|x_t,j| ≤ g_j / w_t,j ≥ 1`. The objective is divided
//! by the largest diagonal entry of the resulting P. The scaled data are O(1) whatever the units of E and
//! of lengths, and a friction bound far above the multiplier it limits (a Tresca threshold of 1e6 where
//! |λ_t| ≈ 2) only loosens the box instead of shrinking every tangential entry of P by g². For clarabel the
//! objective is divided further where a feasible point's is below 1 in these units
//! ([`Scaling::with_objective_at_least_one`]): the scales are set by the largest data, often a coarse dof far from
//! the contact, and on a graded mesh the answer's objective was 1e-4 of them.

/// The smallest objective (in the units of [`Scaling::new`]) that [`Scaling::with_objective_at_least_one`] brings
/// to 1: √ε. Where the contact is pushed only by round-off (a body unloaded off a curved obstacle), a feasible
/// point's objective is ε² of the data's units or less, and dividing by that would hand clarabel data of 1e30.
pub(crate) const OBJECTIVE_FLOOR: f64 = 1.4901161193847656e-8;

/// The scaling of the QP clarabel is handed (see the module documentation): `x̃_i = x_i / w_i` (`w_i = s`
/// on a normal unknown, `min(g_j, s_t)` on a tangential one, 0 where the bound vanishes) and the objective
/// divided by `φ = max_i w_i² H_ii`. The active-set method certifies its answers in the same scaled units
/// ([`crate::qp::active_set`]).
///
/// φ itself is never formed: for data of 1e-200 (an approach in those units) w is about 1e-200 and
/// φ ≈ w² H would underflow to 0. The scaled data are formed from `r_i = w_i / √φ` (about 1/√H_ii) and
/// `√φ = max_i w_i √H_ii` instead: `w_i H_ij w_j / φ = r_i H_ij r_j`, `w_i c_i / φ = r_i c_i / √φ`. The
/// QP is homogeneous in (c, g), so its answer then scales with the data down to the subnormal range.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Scaling {
    /// `w_i` per unknown.
    pub w: Vec<f64>,
    /// `r_i = w_i / √φ` per unknown.
    pub r: Vec<f64>,
    /// `√φ`.
    pub root_phi: f64,
    /// `max_i |w_i c_i| / φ`, the size of the scaled linear term the optimality tolerance is relative to.
    pub c_max: f64,
}

impl Scaling {
    /// The scaled gradient `w_i g_i / φ` of unknown i, g the gradient `(Hν + c)_i`.
    pub(crate) fn scaled_gradient(&self, i: usize, g: f64) -> f64 {
        self.r[i] * g / self.root_phi
    }

    /// The normal scale `s = c_s / h_s` (`h_s = max diag H_nn`, `c_s = max |c_n|`) of a QP with `q` normal
    /// unknowns; where nothing pushes normally (`c_n = 0`) but the tangential term does (a Tresca
    /// threshold with a shift), the same ratio over all unknowns. `None` only when `c = 0` (or H has no
    /// positive diagonal): λ = 0 solves such a QP.
    pub(crate) fn normal_scale(diag: &[f64], c: &[f64], q: usize) -> Option<f64> {
        let k = c.len();
        let ratio = |range: std::ops::Range<usize>| {
            let h_s = range.clone().map(|i| diag[i]).fold(0.0, f64::max);
            let c_s = c[range].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            (c_s > 0.0 && h_s > 0.0).then(|| c_s / h_s)
        };
        ratio(0..q).or_else(|| ratio(0..k))
    }

    /// The scaling for the diagonal of H, the normal scale `s`, the linear term `c` and the tangential
    /// bounds (empty for a frictionless QP).
    pub(crate) fn new(diag: &[f64], c: &[f64], q: usize, s: f64, bounds: &[f64]) -> Self {
        let k = q + bounds.len();
        let h_st = (q..k).map(|i| diag[i]).fold(0.0, f64::max);
        let c_st = c[q..].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let s_t = if h_st > 0.0 { s.max(c_st / h_st) } else { s };
        let w: Vec<f64> = (0..k).map(|i| if i < q { s } else { bounds[i - q].min(s_t) }).collect();
        // w √H_ii rather than w² H_ii: w is about 1/H, so w² alone can overflow (and underflow) where the
        // product cannot.
        let root_phi = (0..k).map(|i| w[i] * diag[i].max(0.0).sqrt()).fold(0.0, f64::max);
        let r: Vec<f64> = w.iter().map(|wi| wi / root_phi).collect();
        let c_max = c.iter().zip(&r).fold(0.0_f64, |m, (ci, ri)| m.max((ri * ci / root_phi).abs()));
        Self { w, r, root_phi, c_max }
    }

    /// This scaling with the objective divided further by `|f̃|` where `f̃`, the objective at a feasible point in
    /// these units, is smaller than 1 in magnitude (unchanged otherwise, or where `f̃` is 0 or not finite), by at
    /// most [`OBJECTIVE_FLOOR`]. clarabel's relative gap is the gap over `max(1, |objective|)`: an answer whose
    /// objective is 1e-5 of the data's units is held to an absolute gap, 1e5 times looser than asked. The optimum
    /// lies below any feasible point, so afterwards `|objective| ≥ 1` at the answer and the gap is relative.
    pub(crate) fn with_objective_at_least_one(mut self, f: f64) -> Self {
        let size = f.abs().max(OBJECTIVE_FLOOR);
        if size < 1.0 && f != 0.0 && f.is_finite() {
            let root = size.sqrt();
            self.root_phi *= root;
            self.r.iter_mut().for_each(|r| *r /= root);
            self.c_max /= size;
        }
        self
    }

    /// The scaled box of the tangential unknowns: `g_j / w_t,j` (1 where the bound vanishes, so that the
    /// box keeps an interior).
    pub(crate) fn tangential_box(&self, q: usize, bounds: &[f64]) -> Vec<f64> {
        bounds.iter().zip(&self.w[q..]).map(|(b, w)| if *w > 0.0 { b / w } else { 1.0 }).collect()
    }
}

/// The diagonal of the column-major `k × k` matrix `h`.
pub(crate) fn diagonal(h: &[f64], k: usize) -> Vec<f64> {
    (0..k).map(|i| h[i * k + i]).collect()
}
