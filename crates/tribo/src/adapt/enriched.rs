//! The hierarchical estimate of the traction error: the difference of a solve's multipliers from those of
//! the same problem on an enriched mesh.
//!
//! # The estimate
//! Let λ_H be the answer, λ_f the answer of the same problem on the *enriched* mesh: every triangle bisected on
//! its three edges, then, on that mesh, the triangles within half a contact width of the contact zone bisected
//! again (h halved everywhere and quartered along the zone, each with its conforming closure), T_H halved where
//! the FE edges under it were, both times (`Problem::enriched_twice`); and `d = ‖λ_H − λ_f‖_{L²(Γ_C)}` (normal and
//! tangential together). By the triangle inequality, `(1 − q) e_H ≤ d ≤ (1 + q) e_H` with `e_H = ‖λ − λ_H‖` and
//! `q = e_f / e_H` the reduction of the error by the enrichment. The *saturation assumption* of hierarchical
//! estimators (Bank and Weiser 1985; Bank and Smith 1993; Dörfler and Nochetto 2002 on when it holds; for obstacle
//! problems Zou, Veeser, Kornhuber and Gräser 2011) is that q stays below a constant q₀ < 1; then `d / (1 − q₀)`
//! bounds e_H, with an effectivity in `[1, (1 + q₀) / (1 − q₀)]`: `[1, 2]` for `q₀ = ⅓`
//! ([`SATURATION`]). Hence the estimate
//!
//! `η_hier = 1.5 ‖λ_H − λ_f‖_{L²(Γ_C)}`, relative to `‖λ_f‖`.
//!
//! **Why two bisections, one of them everywhere.** The L² error of λ has two parts. Near the edges of the contact
//! zone λ behaves like a square root, and the best approximation of `√x` on a cell of size h has an L² error of
//! order h over that cell: each halving of h there halves it, two leave a quarter. And under a prescribed
//! approach the pressure scales with the body's compliance, whose error is that of the energy, squared
//! (`P_H − P = ‖u − u_h‖²_a / δ` in a linear problem): of order h² where the energy error is of order h, in the
//! whole body, so that one bisection of the whole mesh leaves a quarter of it and no refinement of a strip touches
//! it. An enrichment of the strip alone leaves that part (the adaptive meshes refine near the contact and leave the
//! far field coarse); one bisection alone leaves half of the first. Measured on the levels of eight adaptive cases
//! with at least 10 multiplier dofs in contact against the references of study 13 (the example `enrichments`, study
//! 12, `docs/hierarchical.md`): this enrichment left `q` = 0.18–0.26 on one-body Hertz, 0.17–0.27 with P0
//! multipliers, 0.18–0.36 off-centre, 0.20–0.58 with Coulomb friction (above ⅓ on its two finest levels only, 30k and
//! 54k unknowns, where the reference's own error is a part of what is measured), 0.22–0.45 and 0.23–0.30 on two
//! bodies (one level above ⅓): 47 of 51 levels within `q₀ = ⅓`; the strip of one contact width bisected once (this
//! estimate's enrichment before 2026-12-01, with `q₀ = ½`) left 0.34–0.98 (above ⅓ on every level), the strip
//! bisected twice 0.23–0.65, the whole mesh once 0.29–0.76, the whole mesh twice about what this enrichment leaves
//! (0.15–0.24 on one-body Hertz, at twice its unknowns). And `1.5 d` was 1.39–1.64 times the true error on every
//! one of the 51 levels. It costs a solve of 8–9 times the level's unknowns (the strip once: 2.6 times).
//!
//! The enriched answer λ_f is the more accurate of the two, and the same assumption bounds its error:
//! `e_f = q e_H ≤ q (d + e_f)`, so `e_f ≤ q d / (1 − q) ≤ d / 2` ([`Hierarchical::enriched_estimate`]); the adaptive
//! loop hands λ_f back where this meets its tolerance with `stop_on = "enriched"` ([`crate::adapt`]). It is
//! pessimistic where the enrichment removes much more than two thirds of the error (`q` = 0.2: `d / 2` is then about
//! 2.5 times `e_f`).
//!
//! It is no guaranteed bound: where the enrichment removes less than two thirds of the error and the two errors
//! point along each other, it falls below the truth; it did on none of the levels above, because the error λ_f keeps
//! and the difference λ_f − λ_H point nearly apart (with `λ − λ_H = (λ − λ_f) + (λ_f − λ_H)`, the cosine of their
//! angle was −0.63 to +0.16 on the 20 levels of `docs/measured_reduction.csv`): `d` is then close to `e_H` (0.93–1.09
//! times it) whatever q is, and the factor 1.5 is what keeps it above.
//!
//! # Ends of Γ_C in contact: the reduction measured
//! The argument for `q₀ = ⅓` holds where λ vanishes like a square root (a free edge of the contact zone)
//! or is smooth. Where the contact zone reaches an end of Γ_C, λ need not vanish there: at a corner of the
//! body where a slipping contact meets a free side it is singular, `λ ~ r^−s`, its L² error on the end
//! cell is of order `h^(1/2 − s)` and a halving of h removes only `1 − 2^−(1/2 − s)` of it. On the block
//! scene (Coulomb, whole bottom in contact) the error of λ lives at the two corners (25 times the rest
//! within 0.05 of them), one bisection removes 14 % of it there (q = 0.86: s ≈ 0.28) and the enrichment above
//! (two there: the strip is the whole bottom) 26–30 % (q = 0.70–0.74 on 19 levels to 49k unknowns), and
//! `1.5 ‖λ_H − λ_f‖` is 0.96–1.02 times the truth (`2 ‖λ_H − λ_f‖` of the strip once was 0.85–0.99). So at each
//! end of Γ_C whose multiplier dof touches, the reduction is measured instead of assumed: R is the two cells of T_H
//! at that end, the enriched problem is enriched again within |R| of the end point, twice (bisected as often as the
//! first enrichment bisected them, `Problem::enriched_at_ends`), solved from λ_f (λ_ff), and that within |R|/4 (λ_fff);
//! with `d_R = ‖λ_H − λ_f‖_R`, `q_R = ‖λ_ff − λ_fff‖_R / ‖λ_f − λ_ff‖_R`, `D_R = ‖λ_H − λ_ff‖_R`,
//!
//! `η_hier² = (1.5 ‖λ_H − λ_f‖_{Γ_C ∖ R})² + Σ_R (D_R / (1 − q²))²`, `q = max(q_R, ⅓)`
//!
//! (infinite where `q_R ≥ 1`, or where the second enriched solve did not converge or could not be made, the memory
//! budget say: the estimate then says nothing, and the error bars stand; where the third did not, q_R is read between
//! the first two, `‖λ_f − λ_ff‖_R / d_R`; an end whose `d_R` is within the accuracy of the solves, `min(fp_tol, 1e-8)
//! ‖λ_f‖`, measures nothing and stays in the rest). Each enrichment at the end repeats the one before (the same
//! bisections of a self-similar corner), so it reduces the error alike: `e_ff = q² e_H`, and the triangle inequality
//! through the answer enriched twice, `e_H ≤ D_R + e_ff`, gives `D_R / (1 − q²)`. The reduction is read between the
//! second and third because those two are alike: the first is global, and on a uniform mesh its difference is a smaller
//! part of the error (0.53 e_H on the block's uniform meshes of 32 and 64 cells) than a local one's (0.60 e_f), so
//! `‖λ_f − λ_ff‖_R / d_R` read 0.88–1.01 there where the true reductions are 0.78 (the first) and 0.74 (a local one),
//! and the estimate 3.6–5.4 times the truth or none; `‖λ_ff − λ_fff‖_R / ‖λ_f − λ_ff‖_R` reads 0.742–0.744 on those
//! meshes and on adaptive levels alike (a local one's true 0.744; study 15b). Through λ_f the bound was `d_R / (1 − q)`
//! (until 2026-12-01), never smaller (`D_R ≤ d_R + q d_R`) and as sharp only where the two differences point the same
//! way; at the block's corners they are nearly orthogonal (cosine 0.01–0.19 on 23 levels from 36 to 104k unknowns), and
//! it was 2.4–2.8 times the truth there. Measured in study 13 (`docs/tol_table.md`), against the block's reference
//! graded toward its corners (`tribo_testkit::graded_at_ends`): the estimate is 1.82–1.88 times the truth on the 6
//! levels the runs estimated (through λ_f, 2.20–2.74 against the reference before its grading); the adaptive stop reads
//! the smaller of it and the bound (on the block, 1.82–1.91 times the truth). The second and third enrichments cost a
//! solve each about as large as the first (each factorization freed before the next is made), only where an end
//! touches.
//!
//! An end is measured only where the difference concentrates there: where `d_R² / |R|` exceeds
//! `(d_P² − d_R²) / (|Z| − |R|)`, d_P the difference on its pair's side and Z its pair's contact zone (out to the T_H
//! points around it; a zone not longer than 2|R| is all end and always measured). A singular λ puts its error at the
//! end (the block: 25 times the rest's density there), a smooth one does not, and there the second enrichment
//! measures nothing: where λ is smooth at the end (a symmetry axis, a frictionless corner: the half block between a
//! punch and a foundation) `d_R` is a few percent of d, the second enrichment moved λ there by up to 5 times `d_R`,
//! `q_R ≥ 1` left no estimate, and the adaptive loop fell back to the bound on every level from 25k unknowns. Such an
//! end stays in the rest, with the rest's factor 1.5.
//!
//! # Several contact pairs
//! Γ_C is then every pair's side, and `‖·‖_{L²(Γ_C)}` adds the squares of each pair's norm on its own side
//! ([`multiplier_difference`]). The strip bisected again is the union of each pair's: the triangles within half the
//! width of that pair's contact zone (`adapt/strip.rs`); the enriched problem halves every pair's T_H where its FE
//! edges were halved (the first pair's where contact is or may be, or a Tresca threshold acts, as for one pair; a
//! further pair's where its FE edges were), and starts from every pair's multipliers. Every end of a pair's side that
//! its contact zone reaches is an end region R, measured as above. Nothing else changes: the argument for `q₀ = ⅓` is
//! the same on each side. The error bars of the forces are those of the totals (the sums over the pairs); those of the
//! widths are the first pair's, as [`Solution::contact_width`] is. Tested: a side cut into two pairs, contact on one,
//! gives the estimate of the side as one pair (measured to 1e-14, asserted to 1e-6:
//! `tests/integration/pair_estimate.rs`).
//!
//! # The level's ratio H/h
//! The enriched T_H keeps the level's ratio H/h where contact is: the largest ratio over the segments of the first
//! pair's T_H that hold a touching dof (or a dof of a positive Tresca threshold, which acts where nothing touches and
//! is refined there as where it touches, [`crate::adapt`]). Over the whole of T_H it would read the segments kept
//! coarse where the body is surely apart ([`crate::adapt`]) above FE edges that refinement halved, and with ratio 2
//! leave T_H unhalved in the strip: λ_f then differs from λ_H by the FE refinement alone (measured: 0.087 against 0.120
//! on a level of the cut side's test, whose zone kept its ratio 1).
//!
//! # Error bars of the forces and the zone widths
//! The same enriched answer gives the error bars ([`ErrorBars`]) of what users read
//! ([`Problem::estimate_error_bars`], [`Problem::solve_with_error_bars`]). For a quantity J of the answer, the
//! argument above with J in place of λ gives `|J − J_H| ≤ |J_H − J_f| / (1 − q_J)`, and the same `1.5 |J_H − J_f|`
//! under the same assumption `q_J ≤ ⅓`:
//! - the forces `P = ∫ λ_n` and `Q = ∫ λ_t` are linear in λ. Under a prescribed approach their error is
//!   that of the body's compliance, which the whole mesh carries: in a linear problem
//!   `P_H − P = ‖u − u_h‖²_a / δ` (Galerkin orthogonality), of order h² where the energy error is of order
//!   h, so the bisection of the whole mesh leaves `q_P ≈ ¼` and the bar overestimates by about `1.5 (1 − ¼) =
//!   1.125`. This is why the enrichment bisects the whole mesh and not the strip along the contact zone alone:
//!   measured on adaptive Hertz (study 14, bars then `2 |J_H − J_f|` of one bisection), the strip gave 0.33–0.76 times
//!   the error of P, the whole mesh 1.47–1.53 times on the coarse levels (up to 2.81 where the reference's own error
//!   of P matters);
//! - the contact and stick widths end at the edges of their zones, which the answer places to within
//!   the multiplier cells there ([`crate::results::Zone`]): their error falls like H, quartered by the
//!   enrichment along the zone, but a difference `w_H − w_f` can vanish where both answers place an edge in cells
//!   that share their midpoint. The bar of a width is therefore `max(1.5 |w_H − w_f|, r_H)`, r_H the resolution
//!   of the zone (half the dof spacing at each end): an edge is never placed better than that.
//!
//! Studies 14 and 15 (`docs/error_bars.md`, generated by the example `error_bars` and
//! `scripts/plot_error_bars.py`) measure their effectivity against a reference on every adaptive case.

// Where they were first: `tribo::adapt::enriched::multiplier_difference` still names them.
use super::difference::pair_difference_on;
pub use super::difference::{multiplier_difference, multiplier_difference_on};
pub use super::strip::near_contact;
use super::strip::{end_regions, near_ends, pair_span, EndRegion};
use crate::error::Result;
use crate::problem::Problem;
use crate::results::{ErrorBars, Solution, SolveStatus, Zone};
use crate::settings::friction::Friction;
use crate::settings::{FixedPointSettings, SolverSettings};
use crate::solve::Observer;

/// The hierarchical estimate of one solve ([`Problem::estimate_hierarchical`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Hierarchical {
    /// `‖λ_H − λ_f‖` in L²(Γ_C), normal and tangential together.
    pub difference: f64,
    /// `‖λ_f‖` in L²(Γ_C).
    pub norm: f64,
    /// The estimate: `1.5 ‖λ_H − λ_f‖` away from the ends of Γ_C in contact, `‖λ_H − λ_ff‖_R / (1 − q²)` at
    /// them, `q = max(q_R, ⅓)` (the module documentation derives both); infinite (no estimate) where an end's
    /// measured reduction is 1 or more, or could not be measured.
    pub estimate: f64,
    /// `estimate / ‖λ_f‖` (NaN when nothing touches in the enriched answer, infinite with `estimate`).
    pub relative: f64,
    /// The estimate of the enriched answer's own error `‖λ − λ_f‖`, under the same assumption: `½ ‖λ_H − λ_f‖`
    /// away from the ends of Γ_C in contact, `q ‖λ_H − λ_ff‖_R / (1 − q²)` at them (the module documentation).
    pub enriched_estimate: f64,
    /// `enriched_estimate / ‖λ_f‖`.
    pub enriched_relative: f64,
    /// The enriched problem's unknowns.
    pub unknowns: usize,
    /// How the enriched solve ended (the estimate means something only when it converged).
    pub status: SolveStatus,
    /// Wall time of building and solving the enriched problem (and the second and third enrichments at the ends
    /// of Γ_C in contact, if any).
    pub seconds: f64,
    /// The reduction `q` measured at each end of Γ_C where the contact zone reaches it (the module
    /// documentation): empty where no end touches.
    pub end_reductions: Vec<f64>,
    /// The error bars of the forces and zone widths (the module documentation derives them); `None` for the steps
    /// of a history ([`Problem::estimate_history_hierarchical`] estimates the tractions only).
    pub error_bars: Option<ErrorBars>,
}

impl Hierarchical {
    /// Writes the estimate and the error bars (if any) into `solution`'s report
    /// ([`crate::results::ErrorEstimate::traction_hierarchical`] and the fields after it).
    pub fn store(&self, solution: &mut Solution) {
        let e = &mut solution.report.estimate;
        e.traction_hierarchical = Some(self.estimate);
        e.traction_hierarchical_relative = Some(self.relative);
        e.error_bars = self.error_bars;
    }

    /// Writes the estimate of the enriched answer's own error into `enriched`'s report (the enriched answer
    /// that this estimate came from).
    pub fn store_enriched(&self, enriched: &mut Solution) {
        let e = &mut enriched.report.estimate;
        e.traction_hierarchical = Some(self.enriched_estimate);
        e.traction_hierarchical_relative = Some(self.enriched_relative);
    }
}

/// The error bar of a zone's width: `max(1.5 |w_H − w_f|, r_H)` (the module documentation), 0 when neither
/// answer has the zone.
fn width_bar(coarse: Option<Zone>, enriched: Option<Zone>) -> f64 {
    let width = |z: Option<Zone>| z.map_or(0.0, |z| z.width());
    let bar = Answer::Coarse.bound((width(coarse) - width(enriched)).abs(), SATURATION);
    bar.max(coarse.map_or(0.0, |z| z.resolution))
}

/// The part of the estimate at one end of Γ_C in contact (the module documentation).
pub(super) struct EndReduction {
    /// `‖λ_H − λ_f‖` on the end's region R.
    pub(super) difference: f64,
    /// The measured reduction `q = ‖λ_ff − λ_fff‖_R / ‖λ_f − λ_ff‖_R` (`‖λ_f − λ_ff‖_R / ‖λ_H − λ_f‖_R` without λ_fff).
    pub(super) reduction: f64,
    /// `‖λ_H − λ_ff‖` on R: the difference from the answer enriched twice there.
    pub(super) to_twice: f64,
}

impl EndReduction {
    /// An end whose second enrichment failed: no estimate there.
    pub(super) fn unmeasured() -> Self {
        EndReduction { difference: f64::NAN, reduction: f64::INFINITY, to_twice: f64::NAN }
    }

    /// The bound of the error of `answer` at this end: `D_R / (1 − q²)` for the coarse answer, `q D_R / (1 − q²)`
    /// for the enriched one, `D_R = ‖λ_H − λ_ff‖_R` (the module documentation), `q = max(q_R, ⅓)`: never a smaller
    /// factor than the rest of Γ_C takes; infinite when the enrichment does not reduce the difference (q ≥ 1) or q
    /// or `‖λ_H − λ_ff‖_R` is unknown (NaN).
    fn estimate(&self, answer: Answer) -> f64 {
        // Not `max`, which would turn a NaN reduction into ⅓.
        let q = if self.reduction < SATURATION { SATURATION } else { self.reduction };
        if q < 1.0 && !self.to_twice.is_nan() {
            let coarse = self.to_twice / (1.0 - q * q);
            match answer {
                Answer::Coarse => coarse,
                Answer::Enriched => q * coarse,
            }
        } else {
            f64::INFINITY
        }
    }
}

/// Whose error an estimate bounds: the answer `λ_H` estimated, or the enriched answer `λ_f` that estimated it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Answer {
    /// `λ_H`: `e_H ≤ d / (1 − q)` (the rest of Γ_C; at an end, [`EndReduction::estimate`]).
    Coarse,
    /// `λ_f`: `e_f = q e_H ≤ d q / (1 − q)`.
    Enriched,
}

impl Answer {
    /// The bound of the error from a difference `d` and a reduction `q < 1`: `d / (1 − q)` or `d q / (1 − q)`.
    fn bound(self, d: f64, q: f64) -> f64 {
        match self {
            Answer::Coarse => d / (1.0 - q),
            Answer::Enriched => d * q / (1.0 - q),
        }
    }
}

/// The saturation constant q₀ of the enrichment (`Problem::enriched_twice`): the fraction of the error of λ it is
/// assumed to leave at most (the module documentation).
pub const SATURATION: f64 = 1.0 / 3.0;

/// The largest relative difference at an end of Γ_C that counts as the solves' noise (the default `fp_tol`).
const NOISE: f64 = FixedPointSettings::DEFAULT_TOL;

/// `η_hier` from the difference `d` on all of Γ_C and the parts measured at its ends (the module
/// documentation): for the error of the coarse answer `(2.25 (d² − Σ d_R²) + Σ (D_R / (1 − q²))²)^½`; of the
/// enriched answer `(¼ (d² − Σ d_R²) + Σ (q D_R / (1 − q²))²)^½`, `D_R = ‖λ_H − λ_ff‖_R`, `q = max(q_R, ⅓)` (the factor
/// ⅓ / (1 − ⅓) = ½ on the rest). An end whose difference is at most `noise` (the accuracy to which the solves
/// determine λ) measures nothing: its q is a ratio of rounding, and it is left in the rest of Γ_C, where the
/// factor 1.5 (½ for the enriched answer) keeps it within 1.5 times the noise.
pub(super) fn combine_for(answer: Answer, difference: f64, ends: &[EndReduction], noise: f64) -> f64 {
    // Squared in units of the difference, so that no unit of stress under- or overflows (defect D27).
    let unit = if difference > 0.0 && difference.is_finite() { difference } else { 1.0 };
    // A NaN difference (an end that could not be measured) stays among the ends.
    let measured = || ends.iter().filter(|e| e.difference > noise || e.difference.is_nan());
    let at_ends: f64 = measured().map(|e| (e.difference / unit).powi(2)).filter(|d| d.is_finite()).sum();
    // Clamped without `max`, which would turn a NaN difference into 0.
    let rest = (difference / unit).powi(2) - at_ends;
    let rest = if rest < 0.0 { 0.0 } else { rest };
    let ends: f64 = measured().map(|e| (e.estimate(answer) / unit).powi(2)).sum();
    // The rest takes q = ⅓: (1.5 d)² for the coarse answer, (d / 2)² for the enriched one.
    unit * (answer.bound(1.0, SATURATION).powi(2) * rest + ends).sqrt()
}

/// `η_hier` and `η_hier / ‖λ_f‖` (NaN when `norm` is 0) from the difference and the norm on Γ_C and the
/// parts measured at the ends ([`combine_for`]), the noise being the solves' accuracy: `fp_tol`, never looser
/// than the default (a loose `fp_tol` must not leave a singular end to the factor 1.5, below the truth there);
/// then the same for the enriched answer.
pub(super) fn estimate_of(difference: f64, norm: f64, ends: &[EndReduction], fp_tol: f64) -> [(f64, f64); 2] {
    [Answer::Coarse, Answer::Enriched].map(|answer| {
        let estimate = combine_for(answer, difference, ends, fp_tol.min(NOISE) * norm);
        (estimate, if norm > 0.0 { estimate / norm } else { f64::NAN })
    })
}

impl Problem {
    /// The hierarchical estimate of the traction error of `solution`, a solve of this problem with
    /// `friction` (see the module documentation), with the error bars of its forces and zone widths: the whole
    /// mesh bisected, then the triangles within half a contact width of the contact zone again (within the two T_H
    /// cells around a single dof touching; nothing more when none touches), solved with `settings` from
    /// `solution`'s multipliers (8–9 times the unknowns of this problem; where an end of Γ_C touches, a second and a
    /// third solve of about that size follow, each factorization freed before the next). A Tresca threshold given per
    /// dof is carried to the enriched T_H as the W_H function it defines.
    ///
    /// # Errors
    /// Those of [`Problem::solve_enriched`].
    pub fn estimate_hierarchical(
        &self,
        solution: &Solution,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Hierarchical> {
        Ok(self.hierarchical_and_enriched(solution, friction, settings)?.0)
    }

    /// [`Problem::estimate_hierarchical`], with the enriched problem and its answer.
    pub(super) fn hierarchical_and_enriched(
        &self,
        solution: &Solution,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<(Hierarchical, Problem, Solution)> {
        let all: Vec<usize> = (0..self.mesh.n_triangles()).collect();
        self.hierarchical_on(solution, &all, friction, settings)
    }

    /// The hierarchical estimate of the traction error of `solution` and the error bars of its forces and
    /// zone widths: the same as [`Problem::estimate_hierarchical`] (whose enrichment bisects the whole mesh since
    /// 2026-12-01; before, only a strip along the contact zone, which misses the error of the forces).
    ///
    /// # Errors
    /// Those of [`Problem::solve_enriched`].
    pub fn estimate_error_bars(
        &self,
        solution: &Solution,
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Hierarchical> {
        self.estimate_hierarchical(solution, friction, settings)
    }

    /// [`Problem::estimate_hierarchical`] with the triangles `marked` bisected first (in place of the whole mesh),
    /// then the strip of half a contact width again; the error bars included (they mean what the module
    /// documentation says only when every triangle is marked).
    ///
    /// # Errors
    /// Those of [`Problem::solve_enriched`].
    pub fn estimate_hierarchical_on(
        &self,
        solution: &Solution,
        marked: &[usize],
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Hierarchical> {
        Ok(self.hierarchical_on(solution, marked, friction, settings)?.0)
    }

    /// [`Problem::estimate_hierarchical_on`], with the enriched problem and its answer.
    fn hierarchical_on(
        &self,
        solution: &Solution,
        marked: &[usize],
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<(Hierarchical, Problem, Solution)> {
        let clock = std::time::Instant::now();
        let (enriched, answer) = self.solve_enriched_twice(solution, marked, friction, settings)?;
        let (difference, norm) = multiplier_difference(self, solution, &enriched, &answer);
        // Measured only where the first enrichment converged (its estimate means nothing otherwise); a
        // second enrichment that cannot be built or solved leaves those ends unmeasured (no estimate there),
        // not the whole estimate and the error bars failed.
        let ends = if answer.report.status == SolveStatus::Converged {
            self.end_reductions(solution, (&enriched, &answer), friction, settings)
        } else {
            Ok(Vec::new())
        };
        let ends = ends.unwrap_or_else(|e| {
            log::warn!("the second enrichment at the ends of Γ_C failed ({e}): no estimate there");
            vec![EndReduction::unmeasured()]
        });
        let [(estimate, relative), (enriched_estimate, enriched_relative)] =
            estimate_of(difference, norm, &ends, settings.fp.tol);
        let error_bars = Some(ErrorBars {
            normal_force: Answer::Coarse.bound((solution.normal_force - answer.normal_force).abs(), SATURATION),
            tangential_force: Answer::Coarse
                .bound((solution.tangential_force - answer.tangential_force).abs(), SATURATION),
            contact_width: width_bar(solution.contact_zone(), answer.contact_zone()),
            stick_width: width_bar(solution.stick_zone(), answer.stick_zone()),
        });
        let h = Hierarchical {
            difference,
            norm,
            estimate,
            relative,
            enriched_estimate,
            enriched_relative,
            unknowns: enriched.n_free,
            status: answer.report.status,
            seconds: clock.elapsed().as_secs_f64(),
            end_reductions: ends.iter().map(|e| e.reduction).collect(),
            error_bars,
        };
        Ok((h, enriched, answer))
    }

    /// The difference and the measured reduction at each end of Γ_C (T_H's first and last points) whose
    /// multiplier dof touches (not in separation): the two cells of T_H at that end are the region R;
    /// the enriched problem is enriched again within |R| of each such end point (one solve for both ends,
    /// from its answer), and that once more, and `q = ‖λ_ff − λ_fff‖_R / ‖λ_f − λ_ff‖_R` (the module
    /// documentation). Not measured on a T_H of fewer than 4 cells.
    fn end_reductions(
        &self,
        solution: &Solution,
        (enriched, answer): (&Problem, &Solution),
        friction: &Friction,
        settings: &SolverSettings,
    ) -> Result<Vec<EndReduction>> {
        let regions = self.concentrated(&end_regions(self, solution), solution, (enriched, answer));
        if regions.is_empty() {
            return Ok(Vec::new());
        }
        let near = near_ends(self, enriched, &regions);
        let (law, friction) = (friction, self.carried_friction(friction, enriched));
        // The first enrichment's factorization is not needed again: the second solve does not hold both. This
        // problem's may be held (the adaptive loop's level): the second solve has what it leaves of the budget.
        enriched.forget_factorization();
        let rest = (settings.memory_budget as f64 - self.held_bytes()).max(0.0) as usize;
        let settings = SolverSettings { memory_budget: rest, ..*settings };
        let build = |p: &Problem| p.enriched_at_ends(&[answer], &near, self, &regions);
        let (twice, again) = enriched.solve_built(answer, &friction, &settings, build)?;
        let converged = again.report.status == SolveStatus::Converged;
        // The third, at the ends again: the reduction is read between the two alike (the module documentation).
        let thrice = converged.then(|| {
            twice.forget_factorization();
            let inner: Vec<EndRegion> = regions.iter().map(|r| r.toward_end(0.25)).collect();
            let (near, friction) = (near_ends(self, &twice, &inner), self.carried_friction(law, &twice));
            let build = |p: &Problem| p.enriched_at_ends(&[&again], &near, self, &inner);
            let third = twice.solve_built(&again, &friction, &settings, build);
            let third = third.inspect_err(|e| log::warn!("the third enrichment at the ends of Γ_C failed ({e})")).ok();
            third.filter(|(_, s)| s.report.status == SolveStatus::Converged)
        });
        let thrice = thrice.flatten();
        let (twice, thrice) = (converged.then_some((&twice, &again)), thrice.as_ref().map(|(p, s)| (p, s)));
        Ok(self.reductions(&regions, (solution, (enriched, answer)), twice, thrice))
    }

    /// The regions of `regions` whose difference `‖λ_H − λ_f‖²_R` per length is above that of the rest of their
    /// pair's contact zone (the module documentation, "Ends of Γ_C in contact"): an end whose λ is singular
    /// concentrates the difference there; one that carries no more than the rest is left to it.
    pub(super) fn concentrated(
        &self,
        regions: &[EndRegion],
        solution: &Solution,
        (enriched, answer): (&Problem, &Solution),
    ) -> Vec<EndRegion> {
        let concentrated = |r: &&EndRegion| {
            let Some((lo, hi)) = pair_span(self, solution, r.pair) else { return true };
            let length = r.span[1] - r.span[0];
            // The zone reaches the neighbouring T_H points: a zone within R (or hardly beyond) is all end.
            let rest = (hi - lo) - length;
            if rest <= length {
                return true;
            }
            let d = |[a, b]: [f64; 2]| pair_difference_on(self, solution, enriched, answer, r.pair, a, b).0;
            let (at_end, all) = (d(r.span), d([f64::NEG_INFINITY, f64::INFINITY]));
            let rest_squared = all.powi(2) - at_end.powi(2);
            // Not where the difference is NaN (a solve of another problem): kept, it then leaves no estimate.
            let (density, rest_density) = (at_end.powi(2) / length, rest_squared / rest);
            density > rest_density || density.is_nan() || rest_density.is_nan()
        };
        regions.iter().filter(concentrated).copied().collect()
    }

    /// At each region R of `regions`: `d_R = ‖λ_H − λ_f‖_R`, `q_R = ‖λ_ff − λ_fff‖_R / ‖λ_f − λ_ff‖_R` (from the
    /// third enrichment `thrice`; without it `‖λ_f − λ_ff‖_R / d_R`; infinite when the second, `twice`, did not
    /// converge: it measures nothing) and `‖λ_H − λ_ff‖_R`. Regions with `d_R = 0` are left out.
    pub(super) fn reductions(
        &self,
        regions: &[EndRegion],
        (solution, (enriched, answer)): (&Solution, (&Problem, &Solution)),
        twice: Option<(&Problem, &Solution)>,
        thrice: Option<(&Problem, &Solution)>,
    ) -> Vec<EndReduction> {
        let mut out = Vec::new();
        for &EndRegion { pair, span: [lo, hi], .. } in regions {
            let (d1, _) = pair_difference_on(self, solution, enriched, answer, pair, lo, hi);
            let on = |a: (&Problem, &Solution), (p, s): (&Problem, &Solution)| {
                pair_difference_on(a.0, a.1, p, s, pair, lo, hi).0
            };
            let (d2, d3) =
                twice.map_or((f64::INFINITY, f64::NAN), |t| (on((enriched, answer), t), on((self, solution), t)));
            // Between the second and third enrichments, alike; between the first two where there is no third.
            let d4 = thrice.zip(twice).map(|(t3, t2)| on(t2, t3)).filter(|_| d2 > 0.0 && d2.is_finite());
            if d1 > 0.0 {
                let reduction = d4.map_or(d2 / d1, |d4| d4 / d2);
                out.push(EndReduction { difference: d1, reduction, to_twice: d3 });
            }
        }
        out
    }

    /// Solves (as [`Problem::solve`]) and, when the solve converged, adds the hierarchical estimate and
    /// the error bars of [`Problem::estimate_error_bars`] to the answer's report
    /// ([`crate::results::ErrorEstimate::error_bars`]). When the enriched problem cannot be built or solved
    /// (the memory budget, say) or does not converge, the answer keeps `None` there and a warning is logged:
    /// the answer itself is returned either way. The enriched solve has 8–9 times the unknowns (and
    /// is made three times where an end of Γ_C touches). An infinite hierarchical estimate (a measured reduction of
    /// 1 or more at an end) is stored as it is: no estimate of the traction error, the error bars standing.
    ///
    /// # Errors
    /// Those of [`Problem::solve`] and of [`Problem::solve_enriched`].
    pub fn solve_with_error_bars(
        &self,
        friction: &Friction,
        settings: &SolverSettings,
        observer: Option<Observer<'_>>,
    ) -> Result<Solution> {
        let mut solution = self.solve(friction, settings, observer)?;
        if solution.report.status == SolveStatus::Converged {
            // The answer stands whatever becomes of the enriched problem (8–9 times the unknowns: it may not fit
            // the memory budget, or not converge).
            match self.estimate_error_bars(&solution, friction, settings) {
                Ok(h) if h.status == SolveStatus::Converged => h.store(&mut solution),
                Ok(h) => log::warn!("the enriched solve ended {}: no error bars", h.status),
                Err(e) => log::warn!("the enriched problem failed ({e}): no error bars"),
            }
        }
        Ok(solution)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An end with `d_R`, `q_R` and `‖λ_H − λ_ff‖_R`.
    fn end(difference: f64, reduction: f64, to_twice: f64) -> EndReduction {
        EndReduction { difference, reduction, to_twice }
    }

    /// |a − b| within 1e-12 relative.
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs()
    }

    #[test]
    fn the_ends_take_their_measured_reduction_and_the_rest_one_and_a_half_times_the_difference() {
        // d² = 25: 16 at one end (q = 0.75, ‖λ_H − λ_ff‖ = 3.5: 3.5 / (1 − 0.5625) = 8), 9 elsewhere (1.5 · 3 = 4.5).
        assert!(close(combine_for(Answer::Coarse, 5.0, &[end(4.0, 0.75, 3.5)], 0.0), (64.0_f64 + 20.25).sqrt()));
        // Where λ_f − λ_H and λ_ff − λ_f point along each other (‖λ_H − λ_ff‖ = d_R (1 + q)), the bound
        // through λ_f: d_R / (1 − q) = 16.
        assert!(close(combine_for(Answer::Coarse, 5.0, &[end(4.0, 0.75, 7.0)], 0.0), (256.0_f64 + 20.25).sqrt()));
        // A reduction below ⅓ takes ⅓, as the rest does: 1.125 ‖λ_H − λ_ff‖ (1.5 d_R where ‖λ_H − λ_ff‖ is
        // (1 + ⅓) d_R).
        assert!(close(combine_for(Answer::Coarse, 5.0, &[end(4.0, 0.1, 16.0 / 3.0)], 0.0), 7.5));
        assert!(close(combine_for(Answer::Coarse, 5.0, &[end(4.0, 0.1, 4.0)], 0.0), (20.25_f64 + 20.25).sqrt()));
        assert!(close(combine_for(Answer::Coarse, 5.0, &[], 0.0), 7.5));
    }

    #[test]
    fn the_enriched_answer_takes_q_times_the_coarse_bound_at_an_end_and_half_the_difference_elsewhere() {
        // The rest: ⅓ / (1 − ⅓) = ½ times d; an end with q = 0.75 and ‖λ_H − λ_ff‖ = 3.5: 0.75 · 8 = 6, the rest
        // (9 / 4).
        assert!(close(combine_for(Answer::Enriched, 5.0, &[], 0.0), 2.5));
        assert!(close(combine_for(Answer::Enriched, 5.0, &[end(4.0, 0.75, 3.5)], 0.0), 38.25_f64.sqrt()));
        assert_eq!(combine_for(Answer::Enriched, 5.0, &[end(1.0, 1.2, 2.0)], 0.0), f64::INFINITY);
        let [(coarse, rc), (fine, rf)] = estimate_of(5.0, 50.0, &[], 1e-8);
        assert!(close(coarse, 7.5) && close(rc, 0.15) && close(fine, 2.5) && close(rf, 0.05));
    }

    #[test]
    fn an_end_not_reduced_or_not_measured_leaves_no_estimate_unless_it_is_noise() {
        assert_eq!(combine_for(Answer::Coarse, 5.0, &[end(1.0, 1.2, 2.0)], 0.0), f64::INFINITY);
        assert_eq!(combine_for(Answer::Coarse, 5.0, &[end(1.0, f64::NAN, f64::NAN)], 0.0), f64::INFINITY);
        assert_eq!(combine_for(Answer::Coarse, 5.0, &[end(1.0, 0.75, f64::NAN)], 0.0), f64::INFINITY);
        assert_eq!(combine_for(Answer::Enriched, 5.0, &[end(1.0, 0.75, f64::NAN)], 0.0), f64::INFINITY);
        assert_eq!(combine_for(Answer::Coarse, 5.0, &[EndReduction::unmeasured()], 1e-8), f64::INFINITY);
        // An end within the solves' accuracy measures nothing: it stays in the rest (1.5 d).
        assert!(close(combine_for(Answer::Coarse, 5.0, &[end(1e-9, 3.0, 3e-9)], 1e-8), 7.5));
        assert!(combine_for(Answer::Coarse, f64::NAN, &[], 0.0).is_nan());
    }

    #[test]
    fn the_estimate_scales_with_the_multipliers_at_any_magnitude() {
        // Defect D27: its squares underflowed to 0 for multipliers of about 1e-300 (E and the motion × 1e-150).
        let at = |by: f64| combine_for(Answer::Coarse, 5.0 * by, &[end(4.0 * by, 0.75, 3.5 * by)], 0.0) / by;
        let one = at(1.0);
        for by in [1e-300, 1e-160, 1e160, 1e300] {
            assert!((at(by) / one - 1.0).abs() < 1e-12, "× {by:e}: {}", at(by));
        }
    }
}
