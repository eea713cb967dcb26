//! A primal–dual active-set (semismooth Newton) method for the box-constrained Γ_C QP, warm-started.
//!
//! # The method
//! The QP is `min f(x) = ½ xᵀ H x + cᵀ x` over a box `lo ≤ x ≤ hi` (`ν_n ≥ 0`, `−g ≤ ν_t ≤ g`; a dof with
//! `lo = hi`, a tangential dof where the friction bound vanishes, is fixed). Its optimality conditions
//! are `x = P(x − σ ∇f(x))` for any `σ > 0`, P the projection onto the box. The primal–dual active-set
//! method is Newton's method on that (semismooth) equation: from `x`, with `g = H x + c` and the
//! Jacobi-scaled prediction `y_i = x_i − g_i / H_ii`, the dofs with `y_i ≤ lo_i` (or `≥ hi_i`) are put on
//! their bound and the others, the free set F, solve (see `predict` for the one exception: a dof
//! leaves a bound only for the free set, never straight for the opposite bound)
//!
//! `H_FF x_F = −c_F − H_FB x_B`,
//!
//! one Cholesky factorization of the free block — updated from the previous one when only a few unknowns
//! changed sides (a rank-one update per removed unknown, a new row per added one). When the prediction is
//! right the answer is exact after that one step. From the previous fixed-point iterate (only the bounds
//! `μ g` changed) the first step does not predict at all: it keeps the previous answer's places
//! (`Start::places`), each bound dof on its new bound, and is usually right.
//!
//! # The front
//! From a zone slightly too large, PDAS crawls: the Newton point leaves its box only at the outermost
//! unknown or two of each edge, and each step moves the edge by about that much. When few free unknowns
//! left their box, an operator that can form `[H_FF⁻¹]_JJ` cheaply for a small set J around them
//! (`QpOperator::front`) has the box QP over J, with every other unknown kept on its side, solved
//! exactly (`front_places`); its places replace the prediction on J in the next step. At 55k graded
//! unknowns, Coulomb, the first three QPs took 13, 18 and 11 steps, and take 8, 8 and 4.
//!
//! # The edges
//! From a zone much too large (more than `FRONT_MAX_OUTSIDE` unknowns outside at a Newton point), the
//! excess halves per step. An operator that knows which unknowns neighbour each other along Γ_C
//! (`QpOperator::beyond`) has each edge moved twice as far as the Newton point says (`beyond_edges`): at
//! 55k graded unknowns, Coulomb, the first two QPs take 5 and 6 steps (2 LDLᵀ each) instead of 8 and 8 (3
//! and 2).
//!
//! # The safeguard
//! Plain PDAS may cycle when H is not an M-matrix, as here. A Newton point is accepted only if its
//! projection does not raise f (the first one from the places of a neighbouring answer excepted, which is
//! taken as it comes: see `solve`); otherwise the projected Newton arc `P(x + α (x_N − x))` is searched
//! (Armijo, α halved), and if that fails too, a projected-gradient step `P(x − α D⁻¹ g)` (D = diag H)
//! with Armijo backtracking, which always descends. Since f is convex and every accepted step lowers
//! it, the iterates cannot cycle.
//!
//! # Certification
//! The answer is certified with the optimality test of the scaled QP (see [`crate::qp`]; clarabel's objective is
//! divided further where it would be small, which leaves this test's ratio to `‖q̃‖∞` as it is): with the scaled
//! gradient `g̃_i = w_i g_i / φ` (`w` the variable scaling, `φ` the
//! objective scaling), a free dof needs `|g̃_i| ≤ ε`, a dof on its lower bound `g̃_i ≥ −ε`, one on its
//! upper bound `g̃_i ≤ ε`, with `ε = tol · max(1, ‖q̃‖∞)` (q̃ the scaled linear term) — clarabel's dual
//! residual with the bound multipliers chosen optimally. Feasibility and complementarity hold exactly
//! (every dof is on a bound or free). An answer that is not certified within the step cap is handed to
//! clarabel by the caller, never returned as solved.

use crate::qp::Scaling;

/// What the active-set method needs of the QP's matrix: the gradient and the Newton point. The dense
/// implementation ([`DenseBlock`](crate::qp::dense::DenseBlock)) holds H; a sparse one can apply H with a
/// factorization instead.
pub(crate) trait QpOperator {
    /// `H x + c`.
    fn gradient(&self, x: &[f64]) -> Vec<f64>;
    /// The Newton point for the free set: `x_F` solving `H_FF x_F = −c_F − H_FB x_B` with `x_B` taken from
    /// `x` off F; returns the whole vector, or `None` if `H_FF` is not numerically positive definite.
    fn newton_point(&mut self, free: &[bool], x: &[f64]) -> Option<Vec<f64>>;
    /// The diagonal of H.
    fn diagonal(&self) -> &[f64];
    /// `H x + c` at the Newton point `x` just returned, formed from that point's own solve, or `None`
    /// (then [`Self::gradient`] forms it). It only predicts the next free set: when the projection
    /// moves the point, the certified gradient is the one at the projected point.
    fn newton_gradient(&self, _x: &[f64]) -> Option<Vec<f64>> {
        None
    }
    /// Whether the gradient is formed in other arithmetic than the Newton point (the sparse operator),
    /// so that its round-off must be measured where it should vanish. The dense H shares them.
    fn measures_round_off(&self) -> bool {
        false
    }
    /// The front of a Newton point whose free unknowns `outside` (indices into the QP's unknowns) left
    /// their box: a set J of free unknowns holding them (and those near them, as the operator sees it)
    /// and `[H_FF⁻¹]_JJ` (column-major), F the free set `free` of that Newton point; `None` when the
    /// operator cannot form it cheaply (then the next step predicts every unknown as usual). See
    /// [`front_places`].
    fn front(&mut self, _free: &[bool], _outside: &[usize]) -> Option<(Vec<usize>, Vec<f64>)> {
        None
    }
    /// The free unknowns beyond the edges that left their box at a Newton point with more than
    /// [`FRONT_MAX_OUTSIDE`] unknowns outside, with the place the next step gives them (see
    /// [`beyond_edges`]); empty when the operator does not know which unknowns neighbour each other.
    fn beyond(&self, _free: &[bool], _xn: &[f64], _bounds: &Bounds) -> Vec<(usize, Place)> {
        Vec::new()
    }
    /// `dᵀ H d` for `d` given by its nonzero entries (indices into the QP's unknowns), where the operator has it
    /// for less than a gradient (the sparse operator: half a solve with A); `None` elsewhere.
    fn curvature(&self, _d: &[(usize, f64)]) -> Option<f64> {
        None
    }
}

/// At most this many free unknowns outside their box for a Newton point to have its front resolved: a
/// front is where the free set crawls (a few unknowns a step), not the first steps of a cold start.
pub(crate) const FRONT_MAX_OUTSIDE: usize = 32;

/// The places of the front J (see [`QpOperator::front`]) in the exact minimizer of the QP over the
/// Newton point's face with J released to its box.
///
/// # Why
/// From a contact zone slightly too large, the pressure of a Newton point is negative only at its
/// outermost unknown or two: the projection moves each edge by about one unknown a step, and so does
/// the front between stick and slip (42 steps in the first three QPs of a graded Coulomb solve at 55k,
/// most of them moving a front by one unknown).
///
/// # The mathematics
/// With the unknowns off J kept on their side (those of F free, the others on their bounds), the QP
/// over `y = x_J` is, up to a constant, `½ (y − x_N,J)ᵀ R (y − x_N,J)` with `R = ([H_FF⁻¹]_JJ)⁻¹` (the
/// Schur complement of `H_{F∖J,F∖J}` in `H_FF`) and `x_N` the Newton point of F: its gradient
/// `R (y − x_N,J)` is the gradient of the whole QP on J once the free unknowns off J have followed
/// (they keep a zero gradient). The box QP over J is small and dense; its answer is solved here by the
/// same method, and the places it finds replace the prediction of the next step on J. The answer of the
/// whole QP is exact after that next step whenever its places differ from the Newton point's only on J.
/// Nothing is certified here: the next step is a Newton step like any other, accepted only if it
/// lowers the objective.
pub(crate) fn front_places(
    dofs: &[usize],
    inverse: &[f64],
    xn: &[f64],
    bounds: &Bounds,
    scaling: &Scaling,
    tol: f64,
) -> Option<Vec<(usize, Place)>> {
    let r = dofs.len();
    if r == 0 || inverse.len() != r * r {
        return None;
    }
    let m = faer::Mat::from_fn(r, r, |a, b| inverse[b * r + a]);
    let llt = m.llt(faer::Side::Lower).ok()?;
    let reduced = faer::linalg::solvers::DenseSolveCore::inverse(&llt);
    let h: Vec<f64> = (0..r * r).map(|p| reduced[(p % r, p / r)]).collect();
    let centre: Vec<f64> = dofs.iter().map(|&i| xn[i]).collect();
    let c: Vec<f64> = (0..r).map(|a| -(0..r).map(|b| h[b * r + a] * centre[b]).sum::<f64>()).collect();
    let box_j =
        Bounds { lo: dofs.iter().map(|&i| bounds.lo[i]).collect(), hi: dofs.iter().map(|&i| bounds.hi[i]).collect() };
    let scaling_j = Scaling {
        w: dofs.iter().map(|&i| scaling.w[i]).collect(),
        r: dofs.iter().map(|&i| scaling.r[i]).collect(),
        root_phi: scaling.root_phi,
        c_max: scaling.c_max,
    };
    let mut op = crate::qp::dense::DenseBlock::new(h, c.clone());
    let out = solve(&mut op, &c, &box_j, Start { x: &centre, places: None }, &scaling_j, tol, 4 * r as u32 + 20);
    out.certified
        .then(|| places(&out.x, &box_j).into_iter().zip(dofs).filter_map(|(p, &i)| p.map(|p| (i, p))).collect())
}

/// The free unknowns beyond the edges of a Newton point's free zones, put on the bound their edge left for
/// in the next step.
///
/// # Why
/// From a zone too large, the multipliers of a Newton point leave their box only over about half of the
/// excess, next to its edge, and the next zone is too large by the other half: the excess halves per step.
/// At 55k graded unknowns the frictionless QP's free set went 1155 → 887 → 739 → 659 → 617 → 589 → 575 → 573
/// (three LDLᵀ), the first Coulomb QP's stick zone 399 → 284 → 252 → 223 → 193 → 181 → 175 (two). A zone too
/// small is mended in one step (the missing part shows over its whole width). With the rule: 1155 → 619 →
/// 589 → 575 → 573 (two LDLᵀ) and 399 → 161 → 180 → 171 → 175 (two).
///
/// # The rule
/// `lines` lists the unknowns in order along Γ_C, one line per kind (neighbours are consecutive). On each
/// line, a zone is a maximal stretch of free unknowns. Its edge band at an end is the stretch from that end
/// that holds unknowns outside their box with no two neighbours inside it between them (a band that ends at
/// the zone's end, not a dip inside it; a single unknown inside the box between two outside ones is the
/// usual ripple of the multipliers there). The band's unknowns inside their box go to the bound of its
/// innermost unknown outside, and so do as many more beyond it as the band is long, at most half of the
/// zone's unknowns left between the two bands (a zone never vanishes this way). Nothing is certified or
/// assumed: the next step is an ordinary Newton step, accepted only if it lowers the objective. Where the
/// excess does halve, the next zone is about right (a deficit of a few unknowns, which the step after
/// mends); where less than half leaves, the excess still shrinks faster than without the rule.
pub(crate) fn beyond_edges(lines: &[&[usize]], free: &[bool], xn: &[f64], bounds: &Bounds) -> Vec<(usize, Place)> {
    let mut out = Vec::new();
    for line in lines {
        let outside = |p: usize| {
            let a = line[p];
            xn[a] < bounds.lo[a] || xn[a] > bounds.hi[a]
        };
        let place = |p: usize| if xn[line[p]] < bounds.lo[line[p]] { Place::Lower } else { Place::Upper };
        let n = line.len();
        let mut z0 = 0;
        while z0 < n {
            if !free[line[z0]] {
                z0 += 1;
                continue;
            }
            let mut z1 = z0;
            while z1 < n && free[line[z1]] {
                z1 += 1;
            }
            // The band from one end: the positions it covers (from the end inward) and its innermost outside
            // one.
            let band = |order: &mut dyn Iterator<Item = usize>| -> Vec<usize> {
                let (mut covered, mut last, mut gap) = (Vec::new(), None, 0);
                for p in order {
                    if outside(p) {
                        (last, gap) = (Some(covered.len()), 0);
                    } else if last.is_none() || gap == 1 {
                        break;
                    } else {
                        gap += 1;
                    }
                    covered.push(p);
                }
                covered.truncate(last.map_or(0, |l| l + 1));
                covered
            };
            let left = band(&mut (z0..z1));
            let right = band(&mut (z0..z1).rev());
            if left.len() + right.len() < z1 - z0 {
                let between = z1 - z0 - left.len() - right.len();
                let (lo, hi) = (z0 + left.len(), z1 - right.len());
                for (edge, inner) in [(&left, (lo..hi).collect::<Vec<_>>()), (&right, (lo..hi).rev().collect())] {
                    let Some(&innermost) = edge.last() else { continue };
                    let place = place(innermost);
                    let reach = edge.len().min(between / 2);
                    let inside = edge.iter().filter(|&&p| !outside(p));
                    out.extend(inside.chain(&inner[..reach]).map(|&p| (line[p], place)));
                }
            }
            z0 = z1;
        }
    }
    out
}

/// The tolerance on the scaled gradient: `tol · max(1, ‖q̃‖∞)`.
fn threshold(scaling: &Scaling, tol: f64) -> f64 {
    tol * scaling.c_max.max(1.0)
}

/// How an active-set solve ended.
#[derive(Debug, Clone)]
pub(crate) struct ActiveSetOutcome {
    /// The last iterate (feasible).
    pub x: Vec<f64>,
    /// True when the optimality test holds at `x`.
    pub certified: bool,
    /// Newton steps (each one factorization of a free block).
    pub newton_steps: u32,
    /// Projected-gradient steps (the safeguard).
    pub gradient_steps: u32,
}

/// The box constraints of the QP.
#[derive(Debug, Clone)]
pub(crate) struct Bounds {
    /// Lower bounds (may be −∞).
    pub lo: Vec<f64>,
    /// Upper bounds (may be +∞).
    pub hi: Vec<f64>,
}

impl Bounds {
    /// The box of the Γ_C QP on `q_n` normal unknowns (`ν_n ≥ 0`) followed by tangential ones with the
    /// bounds `b` (`|ν_t| ≤ b`).
    pub(crate) fn contact(q_n: usize, b: &[f64]) -> Self {
        let lo = std::iter::repeat_n(0.0, q_n).chain(b.iter().map(|v| -v)).collect();
        let hi = std::iter::repeat_n(f64::INFINITY, q_n).chain(b.iter().copied()).collect();
        Self { lo, hi }
    }

    fn project(&self, x: &mut [f64]) {
        for ((xi, lo), hi) in x.iter_mut().zip(&self.lo).zip(&self.hi) {
            *xi = xi.max(*lo).min(*hi);
        }
    }

    fn fixed(&self, i: usize) -> bool {
        self.lo[i] >= self.hi[i]
    }
}

/// `f(x) = ½ xᵀ (g + c)` from `g = H x + c`, and the size of its terms (for round-off slack).
fn objective(x: &[f64], g: &[f64], c: &[f64]) -> (f64, f64) {
    let mut f = 0.0;
    let mut size = 0.0;
    for ((xi, gi), ci) in x.iter().zip(g).zip(c) {
        f += 0.5 * xi * (gi + ci);
        size += xi.abs() * (ci.abs() + 0.5 * (gi - ci).abs());
    }
    (f, size)
}

/// The gradient and the objective at `x`.
fn gradient_and_objective(op: &impl QpOperator, x: &[f64], c: &[f64]) -> (Vec<f64>, f64) {
    let g = op.gradient(x);
    let (f, _) = objective(x, &g, c);
    (g, f)
}

/// The largest violation of the scaled optimality conditions at `x` (see the module documentation).
fn residual(x: &[f64], g: &[f64], bounds: &Bounds, scaling: &Scaling) -> f64 {
    let mut r = 0.0_f64;
    for i in 0..x.len() {
        if bounds.fixed(i) {
            continue;
        }
        let gs = scaling.scaled_gradient(i, g[i]);
        let v = if x[i] <= bounds.lo[i] {
            (-gs).max(0.0)
        } else if x[i] >= bounds.hi[i] {
            gs.max(0.0)
        } else {
            gs.abs()
        };
        r = if v.is_nan() { f64::NAN } else { r.max(v) };
    }
    r
}

/// Armijo backtracking along the projected arc `P(x + α d)`: the first α in 1, ½, ¼, … (at most 40 halvings)
/// with `f(P(x + α d)) ≤ f(x) + 1e-4 gᵀ(P(x + α d) − x)` and a strict decrease beyond round-off.
fn arc_search(
    op: &impl QpOperator,
    c: &[f64],
    bounds: &Bounds,
    x: &[f64],
    g: &[f64],
    fx: f64,
    d: &[f64],
) -> Option<(Vec<f64>, Vec<f64>, f64)> {
    let mut alpha = 1.0;
    for _ in 0..40 {
        let mut t: Vec<f64> = x.iter().zip(d).map(|(xi, di)| xi + alpha * di).collect();
        bounds.project(&mut t);
        let slope: f64 = t.iter().zip(x).zip(g).map(|((ti, xi), gi)| gi * (ti - xi)).sum();
        if slope < 0.0 {
            let gt = op.gradient(&t);
            let (ft, _) = objective(&t, &gt, c);
            if ft <= fx + 1e-4 * slope && ft < fx {
                return Some((t, gt, ft));
            }
        }
        alpha *= 0.5;
    }
    None
}

/// Where a dof sits in an answer: on its lower bound, free, or on its upper bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Place {
    Lower,
    Free,
    Upper,
}

/// The places of the dofs of `x` in the box (`None` for a fixed dof).
pub(crate) fn places(x: &[f64], bounds: &Bounds) -> Vec<Option<Place>> {
    (0..x.len())
        .map(|i| {
            if bounds.fixed(i) {
                None
            } else if x[i] <= bounds.lo[i] {
                Some(Place::Lower)
            } else if x[i] >= bounds.hi[i] {
                Some(Place::Upper)
            } else {
                Some(Place::Free)
            }
        })
        .collect()
}

/// The place the Newton step gives a dof at `x` with the prediction `y` (see the module documentation).
///
/// A dof on a bound whose multiplier has the wrong sign is freed, even when `y` lies beyond the
/// opposite bound: H is far from diagonal (E A⁻¹ Eᵀ smooths), so `y` overshoots on smooth modes, and
/// sending a whole stick zone from one slip direction to the other made the method zig-zag between
/// the two (43 steps instead of 18 for a first Coulomb QP on 55k graded unknowns). A free dof needs no
/// such care: at a Newton point its gradient vanishes and `y = x`.
fn predict(x: f64, y: f64, lo: f64, hi: f64) -> Place {
    if (x <= lo && y > lo) || (x >= hi && y < hi) {
        Place::Free
    } else if y <= lo {
        Place::Lower
    } else if y >= hi {
        Place::Upper
    } else {
        Place::Free
    }
}

/// Where the method starts: a point (projected onto the box) and, if known, the places of the dofs in
/// the answer of a neighbouring QP — the same one with other bounds. The first step then puts those
/// dofs on their (new) bounds or frees them as that answer did, instead of predicting from `x`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Start<'a> {
    pub x: &'a [f64],
    pub places: Option<&'a [Option<Place>]>,
}

/// Solves the QP from `start` with at most `max_steps` steps.
pub(crate) fn solve(
    op: &mut impl QpOperator,
    c: &[f64],
    bounds: &Bounds,
    start: Start<'_>,
    scaling: &Scaling,
    tol: f64,
    max_steps: u32,
) -> ActiveSetOutcome {
    let k = c.len();
    let mut x = start.x.to_vec();
    bounds.project(&mut x);
    // Started from the places of a neighbouring answer that name every dof's place, the first step needs
    // neither the gradient at the start (its prediction is those places) nor its objective: that step is
    // taken as it comes (one step cannot make a cycle; every later one must lower f), and the solve with A
    // the gradient costs is saved (one per fixed-point QP after the first). Elsewhere they are formed now.
    let named = start.places.is_some_and(|p| (0..k).all(|i| bounds.fixed(i) || p.get(i).is_some_and(Option::is_some)));
    let (mut g, mut fx) = if named { (Vec::new(), f64::INFINITY) } else { gradient_and_objective(op, &x, c) };
    // Whether g and fx are those of x (not so only before the first step from named places).
    let mut known = !named;
    // A scaling that is not a positive finite number certifies nothing (every scaled residual would be 0).
    let base = if scaling.root_phi.is_finite() && scaling.root_phi > 0.0 { threshold(scaling, tol) } else { -1.0 };
    let mut threshold = base;
    let mut out = ActiveSetOutcome { x: Vec::new(), certified: false, newton_steps: 0, gradient_steps: 0 };
    // The PDAS iterate (a Newton point, possibly outside the box) the next prediction starts from, and
    // its gradient; x is the best feasible point so far.
    let (mut xk, mut gk) = (x.clone(), g.clone());
    // The free set of the last Newton step.
    let mut last_free: Option<Vec<bool>> = None;
    // The places the last Newton point's front resolved ([`front_places`]), if any.
    let mut front: Vec<Option<Place>> = vec![None; k];
    loop {
        let r = if known { residual(&x, &g, bounds, scaling) } else { f64::INFINITY };
        if r <= threshold {
            out.certified = true;
            break;
        }
        if (known && !r.is_finite()) || out.newton_steps + out.gradient_steps >= max_steps {
            break;
        }
        // The active-set prediction from the PDAS iterate: a free dof outside its box becomes active, an
        // active dof whose multiplier has the wrong sign becomes free.
        let diag = op.diagonal();
        let mut free = vec![false; k];
        let mut xb = xk.clone();
        let first = out.newton_steps + out.gradient_steps == 0;
        for i in 0..k {
            if bounds.fixed(i) {
                xb[i] = bounds.lo[i];
                continue;
            }
            let known = if first { start.places.and_then(|p| p[i]) } else { front[i] };
            let place = known.unwrap_or_else(|| {
                let y = if diag[i] > 0.0 { xk[i] - gk[i] / diag[i] } else { xk[i] };
                predict(xk[i], y, bounds.lo[i], bounds.hi[i])
            });
            match place {
                Place::Lower => xb[i] = bounds.lo[i],
                Place::Upper => xb[i] = bounds.hi[i],
                Place::Free => free[i] = true,
            }
        }
        let mut accepted = false;
        front.fill(None);
        if let Some(xn) = op.newton_point(&free, &xb) {
            out.newton_steps += 1;
            let outside: Vec<usize> =
                (0..k).filter(|&i| free[i] && (xn[i] < bounds.lo[i] || xn[i] > bounds.hi[i])).collect();
            if outside.len() > FRONT_MAX_OUTSIDE {
                for (i, place) in op.beyond(&free, &xn, bounds) {
                    front[i] = Some(place);
                }
            } else if !outside.is_empty() {
                let resolved = op
                    .front(&free, &outside)
                    .and_then(|(dofs, inverse)| front_places(&dofs, &inverse, &xn, bounds, scaling, tol));
                for (i, place) in resolved.into_iter().flatten() {
                    front[i] = Some(place);
                }
            }
            let mut t = xn.clone();
            bounds.project(&mut t);
            // The gradient at the projected point, in the certifying arithmetic. Where the gradient is
            // formed in other arithmetic than the Newton point (the sparse operator), the test cannot ask
            // for less than twice the gradient's round-off, measured where it should vanish: on the free
            // unknowns of the Newton point, in that arithmetic. That costs a second solve when the
            // projection moved the point, so it is measured only where the answer may be near: the
            // free set of the step before again (PDAS at its fixed point), or a point inside the box.
            // Elsewhere the Newton point's gradient only predicts the next free set, and an operator
            // that has it from its solve hands it over.
            let measure = op.measures_round_off() && (t == xn || last_free.as_ref() == Some(&free));
            // Where the projection moved the point and the answer cannot be near (no round-off to measure), its
            // objective comes from the Newton point's own gradient and the curvature along the move,
            // `f(t) = f(x_N) + g_Nᵀ d + ½ dᵀ H d` with `d = t − x_N` on the unknowns that left their box: half a
            // solve with A instead of the gradient at t, which only a certification would need.
            let moved: Vec<(usize, f64)> = (0..k).filter(|&i| t[i] != xn[i]).map(|i| (i, t[i] - xn[i])).collect();
            let cheap = if moved.is_empty() || measure { None } else { op.newton_gradient(&xn) }
                .and_then(|gn| op.curvature(&moved).map(|curvature| (gn, curvature)));
            if let Some((gn, curvature)) = cheap {
                let (fxn, size) = objective(&xn, &gn, c);
                let ft = fxn + moved.iter().map(|&(i, di)| gn[i] * di).sum::<f64>() + 0.5 * curvature;
                if ft <= fx + 64.0 * f64::EPSILON * size.max(curvature.abs()) {
                    (gk, xk) = (gn, xn);
                    (x, fx) = (t, ft);
                    last_free = Some(free);
                    known = false;
                    continue;
                }
            }
            let gt = op.gradient(&t);
            let gn = match op.newton_gradient(&xn) {
                _ if t == xn => gt.clone(),
                Some(g) if !measure => g,
                _ => op.gradient(&xn),
            };
            if measure {
                let noise =
                    (0..k).filter(|&i| free[i]).fold(0.0_f64, |m, i| m.max(scaling.scaled_gradient(i, gn[i]).abs()));
                threshold = base.max(2.0 * noise);
            }
            let (ft, size) = objective(&t, &gt, c);
            if ft <= fx + 64.0 * f64::EPSILON * size {
                gk = gn;
                xk = xn;
                (x, g, fx, accepted) = (t, gt, ft, true);
            } else {
                if !known {
                    (g, fx) = gradient_and_objective(op, &x, c);
                    known = true;
                }
                let d: Vec<f64> = xn.iter().zip(&x).map(|(a, b)| a - b).collect();
                if let Some((t, gt, ft)) = arc_search(op, c, bounds, &x, &g, fx, &d) {
                    (x, g, fx, accepted) = (t, gt, ft, true);
                    (xk, gk) = (x.clone(), g.clone());
                }
            }
        }
        last_free = Some(free);
        if !accepted {
            if !known {
                (g, fx) = gradient_and_objective(op, &x, c);
            }
            out.gradient_steps += 1;
            let d: Vec<f64> =
                g.iter().zip(op.diagonal()).map(|(gi, di)| if *di > 0.0 { -gi / di } else { -gi }).collect();
            match arc_search(op, c, bounds, &x, &g, fx, &d) {
                Some((t, gt, ft)) => (x, g, fx) = (t, gt, ft),
                // No descent along the gradient either: x is optimal to round-off, or the QP is
                // degenerate beyond what this method resolves; the residual decides.
                None => break,
            }
            (xk, gk) = (x.clone(), g.clone());
        }
        // Every branch above leaves g and fx those of x.
        known = true;
    }
    out.x = x;
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::qp::dense::DenseBlock;

    /// A random symmetric positive definite matrix (column-major) with a spread of eigenvalues.
    fn spd(k: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let b: Vec<f64> = (0..k * k).map(|_| rnd()).collect();
        let mut h = vec![0.0; k * k];
        for i in 0..k {
            for j in 0..k {
                h[j * k + i] = (0..k).map(|l| b[l * k + i] * b[l * k + j]).sum::<f64>();
            }
            h[i * k + i] += 1e-3 * (i + 1) as f64;
        }
        h
    }

    fn unit_scaling(k: usize) -> Scaling {
        Scaling { w: vec![1.0; k], r: vec![1.0; k], root_phi: 1.0, c_max: 1.0 }
    }

    /// A QP of 12 unknowns: H, c, and the box of half normal-like (`≥ 0`), half tangential-like
    /// (`|x| ≤ b`) unknowns.
    fn test_qp(seed: u64, b: f64) -> (Vec<f64>, Vec<f64>, Bounds) {
        let k = 12;
        let c = (0..k).map(|i| ((i as f64) * 0.7 + seed as f64).sin()).collect();
        let bounds = Bounds {
            lo: (0..k).map(|i| if i < k / 2 { 0.0 } else { -b }).collect(),
            hi: (0..k).map(|i| if i < k / 2 { f64::INFINITY } else { b }).collect(),
        };
        (spd(k, seed), c, bounds)
    }

    /// The certified answer satisfies the optimality conditions exactly checked here, from a cold and
    /// from a warm start, with normal-like and box-like bounds and a fixed unknown.
    #[test]
    fn certified_answers_are_optimal() {
        for seed in 1..20u64 {
            let (h, c, mut bounds) = test_qp(seed, 0.05);
            let k = c.len();
            bounds.hi[k - 1] = -0.05; // lo = hi: fixed
            let mut op = DenseBlock::new(h.clone(), c.clone());
            let out = solve(&mut op, &c, &bounds, cold(&vec![0.0; k]), &unit_scaling(k), 1e-12, 100);
            assert!(out.certified, "seed {seed}: {out:?}");
            let g = op.gradient(&out.x);
            for (i, gi) in g.iter().enumerate().take(k - 1) {
                let (x, l, u) = (out.x[i], bounds.lo[i], bounds.hi[i]);
                assert!(x >= l && x <= u);
                if x > l && x < u {
                    assert!(gi.abs() <= 1e-10, "seed {seed} dof {i}: free with gradient {gi}");
                } else if x == l {
                    assert!(*gi >= -1e-10);
                } else {
                    assert!(*gi <= 1e-10);
                }
            }
            assert_eq!(out.x[k - 1], -0.05);
            // Warm start from the answer: certified at once, no factorization.
            let before = op.factorizations;
            let again = solve(&mut op, &c, &bounds, cold(&out.x), &unit_scaling(k), 1e-12, 100);
            assert!(again.certified && again.newton_steps == 0 && op.factorizations == before);
        }
    }

    fn cold(x: &[f64]) -> Start<'_> {
        Start { x, places: None }
    }

    /// A QP whose bounds moved a little, started from the places of the previous answer, is solved by
    /// one Newton step when those places are still right, and certified in any case. Such a start takes its
    /// first step without the gradient at the start point: one gradient per step (at its projected point),
    /// where a start without places forms one more. A QP without unknowns started so is certified after its
    /// one (empty) step.
    #[test]
    fn the_places_of_a_neighbouring_answer_start_the_next_qp() {
        let mut one_step = 0;
        for seed in 1..20u64 {
            let ((h, c, first), (_, _, second)) = (test_qp(seed, 0.05), test_qp(seed, 0.051));
            let k = c.len();
            let gradients = Default::default();
            let mut op =
                Fronted { inner: DenseBlock::new(h.clone(), c.clone()), reach: 4, fronts: 0, edges: false, gradients };
            let a = solve(&mut op, &c, &first, cold(&vec![0.0; k]), &unit_scaling(k), 1e-12, 100);
            let b = solve(&mut op, &c, &second, cold(&vec![0.0; k]), &unit_scaling(k), 1e-12, 100);
            let (pa, pb) = (places(&a.x, &first), places(&b.x, &second));
            let before = op.gradients.get();
            let unnamed = solve(&mut op, &c, &second, cold(&a.x), &unit_scaling(k), 1e-12, 100);
            let cold_gradients = op.gradients.get() - before;
            assert!(cold_gradients > unnamed.newton_steps + unnamed.gradient_steps, "seed {seed}");
            let warm = Start { x: &a.x, places: Some(&pa) };
            let before = op.gradients.get();
            let w = solve(&mut op, &c, &second, warm, &unit_scaling(k), 1e-12, 100);
            assert!(w.certified, "seed {seed}");
            assert!(w.x.iter().zip(&b.x).all(|(x, y)| (x - y).abs() <= 1e-10), "seed {seed}");
            if pa == pb {
                assert_eq!(w.newton_steps + w.gradient_steps, 1, "seed {seed}: the places were right");
                assert_eq!(op.gradients.get() - before, 1, "seed {seed}: the certifying gradient only");
                one_step += 1;
            }
        }
        assert!(one_step > 10, "the bounds moved too much to test the start ({one_step} of 19)");
        let none = Bounds { lo: Vec::new(), hi: Vec::new() };
        let named: [Option<Place>; 0] = [];
        let start = Start { x: &[], places: Some(&named) };
        let out = solve(&mut DenseBlock::new(Vec::new(), Vec::new()), &[], &none, start, &unit_scaling(0), 1e-12, 10);
        assert!(out.certified && out.newton_steps + out.gradient_steps <= 1, "{out:?}");
    }

    /// The rule for the edges on one line: bands at the ends of a zone (a single unknown inside the box
    /// between outside ones belongs to its band), as many more beyond them as they are long, at most half of
    /// what lies between; a dip inside a zone and an outside run two unknowns away from the edge are left alone.
    #[test]
    fn the_edges_of_a_zone_too_large_move_twice_as_far() {
        let n = 60;
        let line: Vec<usize> = (0..n).collect();
        let bounds = Bounds { lo: vec![0.0; n], hi: vec![f64::INFINITY; n] };
        let mut free = vec![false; n];
        let mut xn = vec![0.0; n];
        // A zone 10..40: outside at 10, 11, 13 (12 a ripple), a dip at 20–21, outside at 38, 39. A zone 50..58:
        // outside at 50..=55, at 58, not at 56–57.
        for p in (10..40).chain(50..58) {
            free[p] = true;
            xn[p] = 1.0;
        }
        for p in [10, 11, 13, 20, 21, 38, 39, 50, 51, 52, 53, 54, 55] {
            xn[p] = -1.0;
        }
        let got = beyond_edges(&[&line], &free, &xn, &bounds);
        let mut moved: Vec<usize> = got
            .iter()
            .map(|&(a, p)| {
                assert_eq!(p, Place::Lower);
                a
            })
            .collect();
        moved.sort_unstable();
        // Left band 10..=13 (4 long): 12, then 14..=17; right band 38..=39: 36, 37. Zone 50..58: the band 50..=55
        // with 56, 57 between the bands (58 alone is the right band): one more, 56.
        assert_eq!(moved, [12, 14, 15, 16, 17, 36, 37, 56]);
        // The tangential side: a stick zone leaving for the upper bound moves to it.
        let bounds = Bounds { lo: vec![-1.0; n], hi: vec![1.0; n] };
        let mut xn = vec![0.0; n];
        let free: Vec<bool> = (0..n).map(|p| (10..40).contains(&p)).collect();
        xn[10] = 1.5;
        xn[11] = 1.2;
        let got = beyond_edges(&[&line], &free, &xn, &bounds);
        assert_eq!(got, [(12, Place::Upper), (13, Place::Upper)]);
        // An outside run two unknowns inside the zone is a dip: no band.
        let mut xn = vec![0.0; n];
        xn[10] = 1.5;
        xn[13] = 1.5;
        let got = beyond_edges(&[&line], &free, &xn, &bounds);
        assert_eq!(got, [(11, Place::Upper)]);
    }

    /// The compliance of an elastic half-plane on (−1, 1) by cells of width h (H_ij = −h ln|x_i − x_j|, the
    /// cell's own integral on the diagonal), pressed by a parabola: the box QP of 2D Hertz contact.
    fn half_plane_hertz(n: usize, depth: f64) -> (Vec<f64>, Vec<f64>) {
        let h = 2.0 / n as f64;
        let x: Vec<f64> = (0..n).map(|i| -1.0 + h * (i as f64 + 0.5)).collect();
        let mut m = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                m[j * n + i] = if i == j { h * (1.0 - (h / 2.0).ln()) } else { -h * (x[i] - x[j]).abs().ln() };
            }
        }
        let c = x.iter().map(|xi| xi * xi - depth).collect();
        (m, c)
    }

    /// Hertz on the half-plane from a cold start, fronts resolved as on the saddle-point system: the pushed zone
    /// is about 1.5 times the contact zone, and without the rule its excess halves per step, so that the steps
    /// grow with n (n = 200 … 1600: 3, 4, 5, 6). With it the same answer (the QP's, to round-off) takes 3, 4, 4,
    /// 4: no more at 1600 unknowns than at 400. (At n ≤ 400 the first Newton point has at most
    /// `FRONT_MAX_OUTSIDE` unknowns outside and the rule does not apply.)
    #[test]
    fn moving_the_edges_twice_as_far_finds_a_hertz_zone_in_steps_that_do_not_grow() {
        let mut counts = Vec::new();
        for n in [400, 800, 1600] {
            let (h, c) = half_plane_hertz(n, 0.25);
            let bounds = Bounds { lo: vec![0.0; n], hi: vec![f64::INFINITY; n] };
            let steps = |edges: bool| {
                let mut op = Fronted {
                    inner: DenseBlock::new(h.clone(), c.clone()),
                    reach: 4,
                    fronts: 0,
                    edges,
                    gradients: Default::default(),
                };
                let out = solve(&mut op, &c, &bounds, cold(&vec![0.0; n]), &unit_scaling(n), 1e-12, 200);
                assert!(out.certified, "n {n}, edges {edges}: {out:?}");
                (out.x, out.newton_steps + out.gradient_steps)
            };
            let ((plain, before), (ruled, after)) = (steps(false), steps(true));
            let size = plain.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert!(plain.iter().zip(&ruled).all(|(a, b)| (a - b).abs() <= 1e-9 * size), "n {n}");
            let zone = plain.iter().filter(|v| **v > 0.0).count();
            let pushed = c.iter().filter(|v| **v < 0.0).count();
            assert!(pushed > zone + zone / 4, "n {n}: pushed {pushed}, zone {zone}: not a zone too large");
            assert!(after <= before, "n {n}: {after} steps with the rule, {before} without");
            counts.push((before, after));
        }
        let (first, last) = (counts[0], counts[2]);
        assert!(last.0 > first.0, "without the rule the steps should grow with n: {counts:?}");
        assert!(last.1 <= first.1, "with the rule they should not: {counts:?}");
    }

    /// H with a gradient formed in other arithmetic than the Newton point: each entry off by up to
    /// `eps` relative (a fixed pattern of signs, as a solve's round-off), while the Newton point's own
    /// gradient (`newton_gradient`) is exact, as the saddle-point solve's is.
    struct Noisy {
        inner: DenseBlock,
        eps: f64,
        calls: std::cell::Cell<u32>,
    }

    impl QpOperator for Noisy {
        fn gradient(&self, x: &[f64]) -> Vec<f64> {
            self.calls.set(self.calls.get() + 1);
            let g = self.inner.gradient(x);
            let size = g.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            g.iter().enumerate().map(|(i, v)| v + self.eps * size * ((i * 7 % 5) as f64 - 2.0) / 2.0).collect()
        }
        fn newton_point(&mut self, free: &[bool], x: &[f64]) -> Option<Vec<f64>> {
            self.inner.newton_point(free, x)
        }
        fn diagonal(&self) -> &[f64] {
            self.inner.diagonal()
        }
        fn newton_gradient(&self, x: &[f64]) -> Option<Vec<f64>> {
            Some(self.inner.gradient(x))
        }
        fn measures_round_off(&self) -> bool {
            true
        }
    }

    /// An operator whose gradient carries round-off far above the tolerance is certified at the
    /// threshold its measured round-off sets (the size of the gradient on the free unknowns of a Newton
    /// point, whatever its sign), with the answer of the exact operator to that round-off; it takes one
    /// gradient per step where the projection moves the Newton point, and never more than two.
    #[test]
    fn a_gradient_with_round_off_is_certified_at_its_measured_noise() {
        for seed in 1..20u64 {
            let (h, c, bounds) = test_qp(seed, 0.05);
            let k = c.len();
            let mut exact = DenseBlock::new(h.clone(), c.clone());
            let reference = solve(&mut exact, &c, &bounds, cold(&vec![0.0; k]), &unit_scaling(k), 1e-12, 100);
            let mut op = Noisy { inner: DenseBlock::new(h, c.clone()), eps: 1e-9, calls: Default::default() };
            let out = solve(&mut op, &c, &bounds, cold(&vec![0.0; k]), &unit_scaling(k), 1e-12, 100);
            assert!(reference.certified && out.certified, "seed {seed}: {out:?}");
            assert_eq!(places(&out.x, &bounds), places(&reference.x, &bounds), "seed {seed}");
            assert!(out.x.iter().zip(&reference.x).all(|(a, b)| (a - b).abs() <= 1e-6), "seed {seed}");
            assert!(op.calls.get() <= 1 + 2 * (out.newton_steps + out.gradient_steps), "seed {seed}");
        }
    }

    /// The dense block with its front: `[H_FF⁻¹]_JJ` from the inverse of the free block, J the unknowns
    /// outside their box and the free ones within `reach` of them.
    struct Fronted {
        inner: DenseBlock,
        reach: usize,
        fronts: u32,
        /// Whether the edges of a zone much too large move twice as far (the unknowns on one line).
        edges: bool,
        /// Gradients asked for.
        gradients: std::cell::Cell<u32>,
    }

    impl QpOperator for Fronted {
        fn gradient(&self, x: &[f64]) -> Vec<f64> {
            self.gradients.set(self.gradients.get() + 1);
            self.inner.gradient(x)
        }
        fn newton_point(&mut self, free: &[bool], x: &[f64]) -> Option<Vec<f64>> {
            self.inner.newton_point(free, x)
        }
        fn diagonal(&self) -> &[f64] {
            self.inner.diagonal()
        }
        fn front(&mut self, free: &[bool], outside: &[usize]) -> Option<(Vec<usize>, Vec<f64>)> {
            let k = free.len();
            let f: Vec<usize> = (0..k).filter(|&i| free[i]).collect();
            let dofs: Vec<usize> =
                (0..k).filter(|&i| free[i] && outside.iter().any(|&o| o.abs_diff(i) <= self.reach)).collect();
            let h = self.inner.matrix();
            let hff = faer::Mat::from_fn(f.len(), f.len(), |a, b| h[f[b] * k + f[a]]);
            let inverse = faer::linalg::solvers::DenseSolveCore::inverse(&hff.llt(faer::Side::Lower).ok()?);
            let at = |i: usize| f.iter().position(|&j| j == i);
            let r = dofs.len();
            let block =
                (0..r * r).map(|p| Some(inverse[(at(dofs[p % r])?, at(dofs[p / r])?)])).collect::<Option<_>>()?;
            self.fronts += 1;
            Some((dofs, block))
        }
        fn beyond(&self, free: &[bool], xn: &[f64], bounds: &Bounds) -> Vec<(usize, Place)> {
            let line: Vec<usize> = (0..free.len()).collect();
            if self.edges {
                beyond_edges(&[&line], free, xn, bounds)
            } else {
                Vec::new()
            }
        }
    }

    /// A Hertz-like QP along a line: H a smoothing kernel (`exp(−|i − j| / ℓ)`, positive definite, not an
    /// M-matrix) and a gap `c_i = (x_i² − δ)` that pushes a zone wider than the one in contact. From the
    /// pushed zone the plain method crawls, an edge unknown or two a step; with the front resolved it
    /// takes far fewer steps to the same certified answer, the places of every unknown included.
    #[test]
    fn a_resolved_front_ends_the_crawl_with_the_same_answer() {
        for (k, ell) in [(120_usize, 10.0), (200, 20.0), (300, 15.0)] {
            let h: Vec<f64> = (0..k * k).map(|p| (-((p % k).abs_diff(p / k) as f64) / ell).exp()).collect();
            let c: Vec<f64> = (0..k).map(|i| ((i as f64 - k as f64 / 2.0) / k as f64).powi(2) - 0.04).collect();
            let bounds = Bounds { lo: vec![0.0; k], hi: vec![f64::INFINITY; k] };
            let pushed: Vec<f64> = c.iter().map(|v| if *v < 0.0 { 1.0 } else { 0.0 }).collect();
            let mut plain = DenseBlock::new(h.clone(), c.clone());
            let a = solve(&mut plain, &c, &bounds, cold(&pushed), &unit_scaling(k), 1e-12, 200);
            let mut fronted = Fronted {
                inner: DenseBlock::new(h, c.clone()),
                reach: 4,
                fronts: 0,
                edges: false,
                gradients: Default::default(),
            };
            let b = solve(&mut fronted, &c, &bounds, cold(&pushed), &unit_scaling(k), 1e-12, 200);
            assert!(a.certified && b.certified, "k = {k}");
            assert_eq!(places(&a.x, &bounds), places(&b.x, &bounds), "k = {k}");
            let scale = a.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert!(a.x.iter().zip(&b.x).all(|(x, y)| (x - y).abs() <= 1e-10 * scale), "k = {k}");
            eprintln!("k = {k}: {} steps plain, {} with {} fronts", a.newton_steps, b.newton_steps, fronted.fronts);
            assert!(a.newton_steps >= 8, "k = {k}: the plain method did not crawl ({} steps)", a.newton_steps);
            assert!(
                fronted.fronts > 0 && 2 * b.newton_steps < a.newton_steps,
                "k = {k}: {} against {}",
                b.newton_steps,
                a.newton_steps
            );
        }
    }

    /// A dof leaves its bound for the free set, never straight for the opposite bound.
    #[test]
    fn a_dof_leaves_a_bound_for_the_free_set() {
        assert_eq!(predict(-1.0, 5.0, -1.0, 1.0), Place::Free);
        assert_eq!(predict(1.0, -5.0, -1.0, 1.0), Place::Free);
        assert_eq!(predict(-1.0, -1.5, -1.0, 1.0), Place::Lower);
        assert_eq!(predict(0.0, 5.0, -1.0, 1.0), Place::Upper);
        assert_eq!(predict(0.0, -5.0, -1.0, 1.0), Place::Lower);
        assert_eq!(predict(0.5, 0.2, -1.0, 1.0), Place::Free);
    }

    /// On a matrix that is only semidefinite on the free set, the method never reports an uncertified
    /// answer as certified (it may still certify when the optimum is reached).
    #[test]
    fn a_singular_block_is_not_certified_by_accident() {
        let k = 4;
        // H = v vᵀ (rank one), c pushes every dof away from its lower bound.
        let v = [1.0, 1.0, 1.0, 1.0];
        let h: Vec<f64> = (0..k * k).map(|p| v[p % k] * v[p / k]).collect();
        let c = vec![-1.0, -2.0, -3.0, -4.0];
        let bounds = Bounds { lo: vec![0.0; k], hi: vec![1.0; k] };
        let mut op = DenseBlock::new(h, c.clone());
        let out = solve(&mut op, &c, &bounds, cold(&[0.0; 4]), &unit_scaling(k), 1e-12, 50);
        let g = op.gradient(&out.x);
        let r = residual(&out.x, &g, &bounds, &unit_scaling(k));
        assert_eq!(out.certified, r <= 1e-12, "certified {} with residual {r:e}", out.certified);
    }
}
