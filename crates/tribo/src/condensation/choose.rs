//! How H is formed, chosen from the problem's sizes ([`crate::settings::Condensation::Auto`]): a deterministic cost model
//! of the three paths — columns of H by solves, all of H by the partial factorization
//! ([`crate::linalg::schur`]), or no H at all (the saddle-point system, [`crate::linalg::saddle`]) —
//! calibrated on the measured Hertz families (the numbers are stated with each rule).

use crate::settings::friction::FrictionLaw;

/// `nnz(L) / nnz(K)` of the Cholesky factor of A on these meshes (measured 5.5–7).
pub(super) const CHOLESKY_FILL: usize = 6;

/// Whether doing without H ([`crate::settings::Condensation::Saddle`]) is cheaper than forming its columns, from the
/// number `w` of normal multipliers the load pushes (`c_j < 0`, the working set's start) and nnz(K). In
/// units of one sparse solve with A (`≈ 4 nnz(L)` flops, `nnz(L) ≈ 6 nnz(K)` as for [`prefer_schur`]):
///
/// * columns: `1.4 w` columns (the Coulomb QPs need normal and tangential columns of about 70 % of the
///   pushed dofs, measured on the graded Hertz family), solved in blocks at about twice the rate of
///   single solves (`0.7 w`), plus the dense active-set QPs, about five Cholesky factorizations of the
///   `2w × 2w` free block (refactorizations and updates, measured): `5 (2w)³ / 3` flops at 1.5× the
///   rate of a sparse solve;
/// * saddle: about `0.15 √w` Newton steps with a new sparse LDLᵀ (1.3 × a Cholesky of A ≈ 28 solves, and
///   two solves) and `√w` bordered ones (about 3 solves each: the bordered solve and the gradients) for
///   a whole Coulomb solve (measured: 5–7 LDLᵀ with 37–45 bordered steps from 28k to 109k graded
///   unknowns).
///
/// Measured on graded Hertz meshes (whole solve): the saddle system wins from 8k unknowns on (0.07 s
/// against 0.08 s by columns; 0.19 against 0.24 s at 15k, 0.51 against 0.90 s at 28k), where the
/// partial factorization ([`prefer_schur`], tried first) is not taken; the rule puts the switch at about
/// w = 120 pushed dofs.
///
/// A solve whose QPs start from the multipliers of a nearby problem (`warm`: the coarser level of the
/// adaptive loop) costs the saddle-point system [`WARM_SADDLE`] instead.
pub(super) fn prefer_saddle(nnz_k: usize, w: usize, warm: bool) -> bool {
    let [columns, saddle] = path_costs(nnz_k, w);
    columns > if warm { WARM_SADDLE } else { saddle }
}

/// What the QPs of a solve cost on the saddle-point system when they start from the multipliers of a
/// nearby problem (the coarser level of the adaptive loop, prolongated), in sparse solves with A: the
/// start's partition is factorized once (1.3 × a Cholesky of A ≈ 28 solves, and two solves) and the few
/// multipliers whose state changed are bordered (about 3 solves each; measured on the last levels of study
/// 6's Hertz runs, 12k to 24k unknowns: 1 LDLᵀ and 5 QP iterations). The columns and the partial
/// factorization gain little from the start: their cost is in forming H.
pub(super) const WARM_SADDLE: f64 = 1.3 * 22.0 + 2.0 + 5.0 * 3.0;

/// Whether the warm saddle-point solve ([`WARM_SADDLE`]) is cheaper than the dense block of the partial
/// factorization ([`prefer_schur`]'s flops, in solves of `4 nnz(L) ≈ 24 nnz(K)` flops); both paths
/// factorize A once besides. Measured at 12k adaptive unknowns (q = 295): the partial factorization and H
/// 0.09 s, the plain factorization and the warm QPs 0.05 s.
pub(super) fn warm_saddle_beats_schur(nnz_k: usize, m: usize, n_c: usize) -> bool {
    schur_dense_flops(m, n_c) > WARM_SADDLE * 4.0 * CHOLESKY_FILL as f64 * nnz_k as f64
}

/// The dense flops of the partial factorization's trailing block and of all of `E A⁻¹ Eᵀ` from it.
fn schur_dense_flops(m: usize, n_c: usize) -> f64 {
    let (m, nc) = (m as f64, n_c as f64);
    nc.powi(3) / 3.0 + nc * nc * m / 2.0 + nc * m * m / 2.0
}

/// The costs of a whole solve by columns and by the saddle-point system, in sparse solves with A (the
/// model of [`prefer_saddle`]).
pub(super) fn path_costs(nnz_k: usize, w: usize) -> [f64; 2] {
    let (w, solve_flops) = (w as f64, 4.0 * 6.0 * nnz_k as f64);
    let columns = 0.7 * w + 5.0 * (2.0 * w).powi(3) / 3.0 / (1.5 * solve_flops);
    let saddle = w.sqrt() * (0.15 * (1.3 * 22.0 + 2.0) + 3.0);
    [columns, saddle]
}

/// What a later step of a loading history costs, as a fraction of the first step's solve, by columns and
/// by the saddle-point system. The columns are formed once for the whole history (a later step adds the
/// few the contact zone grows into and solves small dense QPs), while every step's QPs solve the sparse
/// system again. Measured on study 6b's Cattaneo–Mindlin history (10 drag steps after the press,
/// Coulomb μ = 0.3, graded Hertz meshes): by columns 0.053, 0.052 and 0.065 of the first step at 8.0k,
/// 15k and 28k unknowns; by the saddle-point system 0.45, 0.37 and 0.64.
pub(super) const LATER_STEP: [f64; 2] = [0.06, 0.5];

/// Whether the saddle-point system is still the cheaper path for `load_cases` solves of a loading
/// history (one factorization), from the costs of one solve ([`path_costs`]) and what a later step
/// costs ([`LATER_STEP`]). Measured, the same history: by columns 0.15, 0.41 and 1.63 s, by the
/// saddle-point system 0.42, 0.89 and 3.33 s (8.0k, 15k, 28k unknowns), though one static solve is
/// cheaper by the saddle-point system from 8k unknowns on.
pub(crate) fn saddle_pays_for(costs: [f64; 2], load_cases: usize) -> bool {
    let later = load_cases.saturating_sub(1) as f64;
    let [columns, saddle] = costs;
    columns * (1.0 + LATER_STEP[0] * later) > saddle * (1.0 + LATER_STEP[1] * later)
}

/// Whether the saddle-point systems of the active-set steps can be factorized without pivoting: `Dγ`
/// has a positive diagonal (γ0 > 0: quasi-definite), or `E` has no more rows than the displacement dofs
/// it touches (γ0 = 0: `E_F` of full row rank, as on matching meshes). Without either (γ0 = 0 with T_H
/// finer than the FE edges) `E_F` is rank deficient, every step's LDLᵀ breaks down and the dense path
/// answers after all (measured: 2.1 s against 0.1 s by columns at 8k graded unknowns, H = h/2).
/// `n_c` is [`touched_dofs`] of `e_rows`.
pub(super) fn quasi_definite(e_rows: &[Vec<(usize, f64)>], n_c: usize, d_cols: &[Vec<(usize, f64)>]) -> bool {
    let d_positive = d_cols.iter().enumerate().all(|(j, col)| col.iter().any(|&(i, v)| i == j && v > 0.0));
    d_positive || e_rows.len() <= n_c
}

/// The largest number c of rows of E (multiplier unknowns) that touch one of the `n` displacement dofs, and
/// `c (c + 1) / 2`, the fewest values the saddle-point factor can have: the ordering eliminates every
/// displacement dof before the multipliers its column of E touches, so those form a clique of the factor.
/// Known before the symbolic analysis, whose cost grows with the fill (56 s for 200k multipliers over
/// 8 FE edges).
pub(super) fn saddle_clique(e_rows: &[Vec<(usize, f64)>], n: usize) -> (usize, usize) {
    let mut touching = vec![0usize; n];
    for &(dof, _) in e_rows.iter().flatten() {
        touching[dof] += 1;
    }
    let c = touching.into_iter().max().unwrap_or(0);
    (c, c * (c + 1) / 2)
}

/// The number `n_c` of displacement dofs the rows of E touch (the Γ_C dofs, of both sides for two bodies).
pub(super) fn touched_dofs(e_rows: &[Vec<(usize, f64)>]) -> usize {
    let mut touched: Vec<usize> = e_rows.iter().flatten().map(|&(d, _)| d).collect();
    touched.sort_unstable();
    touched.dedup();
    touched.len()
}

/// The number of normal multipliers the load is expected to push, before anything is factorized: with no
/// load on the free dofs (`f = 0`: the body is pressed only by the obstacle's approach or shape), `c = d`
/// and the count of `d_j < 0` is exact; otherwise every one of the `q` may be.
pub(super) fn pushed_estimate(f: &[f64], d: &[f64], q: usize) -> usize {
    if f.iter().all(|&v| v == 0.0) {
        d[..q].iter().filter(|&&v| v < 0.0).count()
    } else {
        q
    }
}

/// Whether the partial factorization is the cheaper way to H, and fits the memory budget. It forms all
/// of `E A⁻¹ Eᵀ` (m = 2q rows) with a dense trailing block of the `n_c` dofs E touches: about
/// `n_c³/3 + n_c² m/2 + n_c m²/2` dense flops (the cost model of [`crate::linalg::schur`]) on top of the
/// sparse factorization, against about `w` sparse solves of `4 nnz(L) ≈ 24 nnz(K)` flops for the columns
/// the QPs need (the `w` pushed multipliers) or the saddle-point system's few factorizations (`√w`). Two
/// rules, both measured:
///
/// * `m² ≤ 16 nnz(K)`: forming all m columns by solves costs `≈ 4 nnz(L) m` flops, with `nnz(L) ≈ 6 nnz(K)`
///   (measured 5.5–7), against one factorization with its dense trailing block;
/// * dense flops `≤ margin × 24 nnz(K) w`, with `margin` [`BEFORE_FACTORIZING`] or [`AFTER_FACTORIZING`]: measured on the Hertz families (`scripts/study_paths.py`,
///   docs/paths.md, frictionless and Coulomb), the partial factorization is the fastest path up to a ratio
///   of about 2.4 (uniform meshes 1.8–2.0, the full-contact block 0.27, adaptive meshes 1.8–2.4) and 1.5 to
///   12 times slower than the best from 2.5 on (graded meshes 2.5–35, adaptive ones 4–7). The dense block
///   grows like n_c³: two bodies, whose contact dofs lie on both sides, reach it sooner.
///
/// `w` is [`pushed_estimate`] (exact without a load) or, with a load, the count the factorized c gives;
/// with `w = q` the rule is as favourable to the partial factorization as it can be.
pub(super) const BEFORE_FACTORIZING: f64 = 2.5;

/// [`BEFORE_FACTORIZING`] when a Coulomb fixed point will follow ([`Expected::fixed_point`]) and the
/// alternative is the saddle-point system ([`prefer_saddle`]). The fixed point's QPs have tangential
/// unknowns and there are several of them: on the saddle-point system a Coulomb solve costs 1.6–2.3
/// times a frictionless one, while from the partial factorization, whose cost is in forming H, it costs
/// about the same (study 7, docs/paths.md). Measured on the last meshes of adaptive Hertz runs: at dense
/// ratios 2.6 and 3.6 (22k and 39k unknowns) the partial factorization answers Coulomb in 0.23 and
/// 0.65 s, the saddle-point system in 0.30 and 0.81 s, while frictionless the saddle-point system is 1.2
/// times faster; on graded meshes, from ratio 10 (15k unknowns) the partial factorization is 1.6 times
/// slower or more for Coulomb too. Against the columns (small contact zones, whose dense QPs are cheap)
/// the margin stays: at ratio 3.6 (graded, 4.5k unknowns) the columns answer Coulomb in 20 ms, the
/// partial factorization in 28 ms.
pub(super) const FIXED_POINT_BEFORE_FACTORIZING: f64 = 5.0;

/// The margin of [`prefer_schur`] before anything is factorized: [`FIXED_POINT_BEFORE_FACTORIZING`] for a
/// Coulomb fixed point whose alternative is the saddle-point system (`definite`: it can be factorized
/// without pivoting, [`quasi_definite`]; `w` the pushed multipliers), else [`BEFORE_FACTORIZING`].
pub(super) fn margin_before_factorizing(expected: Expected, definite: bool, nnz_k: usize, w: usize) -> f64 {
    if expected.fixed_point && definite && prefer_saddle(nnz_k, w, false) {
        FIXED_POINT_BEFORE_FACTORIZING
    } else {
        BEFORE_FACTORIZING
    }
}

/// What the solves that follow a factorization will do, as far as the choice of the path weighs it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Expected {
    /// The QPs start from the multipliers of a nearby problem (the adaptive loop's coarser level):
    /// [`WARM_SADDLE`].
    pub warm: bool,
    /// A Coulomb fixed point follows, not a single QP: [`FIXED_POINT_BEFORE_FACTORIZING`].
    pub fixed_point: bool,
}

impl Expected {
    /// The solves of the friction law `law` as solved (`Problem::friction_law_as_solved`: Coulomb where the μ of
    /// some contact pair is positive), warm or not: a fixed point for Coulomb.
    pub(crate) fn solving(law: FrictionLaw, warm: bool) -> Self {
        Self { warm, fixed_point: law == FrictionLaw::Coulomb }
    }
}

/// The margin once A is factorized the plain way (a loaded problem, whose pushed multipliers the
/// factorization told): the partial factorization then costs a second factorization besides its dense
/// block, the columns only their solves, so it must be cheaper outright. Measured on two-body Hertz
/// (`examples/two_bodies.rs`, pressed by a prescribed displacement): at 10k and 16.5k unknowns (dense
/// ratios 2.1 and 2.4) the partial factorization took 0.15 and 0.40 s, the columns 0.03 and 0.08 s;
/// on the block pressed by a traction (every multiplier pushed, ratio 0.27) it stays the fastest.
pub(super) const AFTER_FACTORIZING: f64 = 1.0;
///
/// `m` is the number of rows of E and `n_c` the dofs they touch ([`touched_dofs`]).
pub(super) fn prefer_schur(nnz_k: usize, m: usize, n_c: usize, w: usize, margin: f64, budget: usize) -> (bool, f64) {
    let dense = schur_dense_flops(m, n_c);
    let (m, nc) = (m as f64, n_c as f64);
    let bytes = 8.0 * (nc * nc + nc * m + 2.0 * m * m);
    let nnz = nnz_k as f64;
    let dense_pays = dense <= margin * 4.0 * CHOLESKY_FILL as f64 * nnz * w as f64;
    (m * m <= 16.0 * nnz && dense_pays && bytes <= budget as f64, bytes)
}
