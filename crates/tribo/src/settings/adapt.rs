//! Settings of the adaptive loop ([`crate::Problem::solve_adaptive`]): when to stop and how much to
//! refine at each level.

use crate::choice::named_choice;
use crate::error::{check_setting, Result};

/// How the triangles to refine are chosen from the indicators m_K.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Marking {
    /// Dörfler (bulk) marking: the fewest triangles whose indicators sum to at least θ of the total.
    #[default]
    Dorfler,
    /// Maximum marking: every triangle whose indicator is at least θ times the largest.
    Maximum,
}

named_choice!(Marking, "marking", { Marking::Dorfler => "dorfler", Marking::Maximum => "maximum" });

/// How a marked triangle is bisected ([`crate::mesh::refine::bisect`]; the names of Funken, Praetorius and
/// Wissgott's p1afem are given beside each).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Bisection {
    /// All three edges (p1afem's `bisec3`): a marked triangle becomes four, as by two levels of uniform
    /// bisection. Measured (study 6, Hertz from the 8 × 4 mesh): 0.3 % in λ_n in 14 levels where the one
    /// edge takes 25, at about 0.8 of the time.
    #[default]
    AllEdges,
    /// The refinement edge only (`bisec1`): a marked triangle becomes two (more where the closure reaches
    /// it). The fewest new unknowns per level, and so the most levels.
    RefinementEdge,
}

named_choice!(Bisection, "bisection", { Bisection::AllEdges => "all_edges", Bisection::RefinementEdge => "refinement_edge" });

/// Which estimate of the traction error the adaptive loop's tolerance is read against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StopOn {
    /// The residual bound ζ ([`crate::results::ErrorEstimate::traction_relative`]): above the true error
    /// in every solve measured, but pessimistic, and more so on finer meshes (an effectivity of about 4 on
    /// a few hundred unknowns, 20 at 70k): the loop ends well below `tol`, with many times the unknowns
    /// needed. Free.
    Bound,
    /// The smaller of the bound and the hierarchical estimate ([`crate::Problem::estimate_hierarchical`]):
    /// `1.5 ‖λ_H − λ_f‖`, λ_f the answer of the problem enriched (the whole mesh bisected, the strip along the contact
    /// zone again), the reduction measured where the zone reaches an end of Γ_C. Sharp (study 12: 1.39–1.64 times the
    /// true error on 51 levels of adaptive Hertz, P0 multipliers, Coulomb friction and two bodies, without drift; in
    /// the loop, study 13: 1.38–1.58 on every level of nine cases, the block's 1.82–1.88 at its singular corners)
    /// but not a guaranteed bound, and it costs a solve of 8–9 times the level's unknowns (three times where an end
    /// touches; a whole history solved again for a history), so the loop computes it only where it may stop
    /// the loop, or the next level, before the bound (see [`crate::adapt`]). The level right after an estimated one
    /// reads the calibrated bound, the bound times the ratio of the two estimates measured there
    /// ([`crate::results::ErrorEstimate::traction_calibrated_relative`]), and may stop on it without an enriched
    /// solve of its own. While nothing touches the loop reads the energy estimate, as with the bound. `tol` then
    /// means the accuracy reached, at about the time of the cheapest adequate level (study 13, `docs/tol_table.md`,
    /// measures the runs). The default.
    #[default]
    Hierarchical,
    /// As [`StopOn::Hierarchical`], and where the answer of the problem enriched for a level's estimate has an estimate
    /// of its own error (`½ ‖λ_H − λ_f‖`, a third of the level's away from the ends of Γ_C in contact) at most `tol`
    /// and the level's own is not, that answer is handed back as one more level (P1 multipliers, a mesh without
    /// curves, within `max_unknowns` and `max_levels`; bisected on all edges whatever `bisection`; see
    /// [`crate::adapt`]): the loop stops at the cheapest level whose true error is within `tol` or before it wherever
    /// the level's estimate is within three times its error, and the answer, of 8–9 times the level's unknowns, is the
    /// more accurate one, often more than asked (below a third of `tol` in a third of the runs of study 13). With P0
    /// multipliers nothing is handed back: it stops as [`StopOn::Hierarchical`].
    Enriched,
}

named_choice!(StopOn, "stop_on", {
    StopOn::Bound => "bound",
    StopOn::Hierarchical => "hierarchical",
    StopOn::Enriched => "enriched",
});

/// The adaptive loop's keywords as the Python binding and the scene files give them, each `None` taking its
/// default ([`AdaptSettings::from_keywords`]).
#[derive(Debug, Clone, Default)]
pub struct AdaptKeywords {
    /// [`AdaptSettings::tol`].
    pub tol: Option<f64>,
    /// [`AdaptSettings::max_unknowns`].
    pub max_unknowns: Option<usize>,
    /// [`AdaptSettings::theta`].
    pub theta: Option<f64>,
    /// [`AdaptSettings::marking`], by name.
    pub marking: Option<String>,
    /// [`AdaptSettings::bisection`], by name.
    pub bisection: Option<String>,
    /// [`AdaptSettings::max_levels`].
    pub max_levels: Option<usize>,
    /// [`AdaptSettings::algebraic`].
    pub algebraic: Option<f64>,
    /// [`AdaptSettings::stop_on`], by name.
    pub stop_on: Option<String>,
}

/// When the adaptive loop stops and how it marks and refines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptSettings {
    /// The relative estimated error at which to stop: of the contact tractions when something touches (the
    /// estimate [`AdaptSettings::stop_on`] names: by default the smaller of
    /// [`crate::results::ErrorEstimate::traction_hierarchical_relative`] where the loop computed it, or of
    /// [`crate::results::ErrorEstimate::traction_calibrated_relative`] on the level after, and
    /// [`crate::results::ErrorEstimate::traction_relative`]), of the energy
    /// ([`crate::results::ErrorEstimate::energy_relative`]) when nothing does. Default 0.01.
    pub tol: f64,
    /// The most unknowns a level may have: a refinement that would exceed it is not made, and the loop
    /// stops with the last level. Default 200 000.
    pub max_unknowns: usize,
    /// The marking parameter θ ∈ (0, 1]. Default 0.5.
    pub theta: f64,
    /// The marking strategy. Default Dörfler.
    pub marking: Marking,
    /// How a marked triangle is bisected. Default all three edges.
    pub bisection: Bisection,
    /// The most levels (solves), the first included. Default 40.
    pub max_levels: usize,
    /// The fraction of the previous level's relative estimate to which a level's Coulomb fixed point is
    /// converged (its stopping change, never below `fp_tol`): the algebraic error of a coarse level need
    /// not be far below its discretization error. The last level is then solved again to `fp_tol`, so
    /// the answer handed back is converged as asked. Default 0.1; 0 converges every level to `fp_tol`.
    pub algebraic: f64,
    /// Which traction estimate `tol` is read against, and whether the enriched answer may be handed back.
    /// Default [`StopOn::Hierarchical`]: the smaller of the bound and the hierarchical estimate where it was computed,
    /// the calibrated bound on the level after.
    pub stop_on: StopOn,
}

impl Default for AdaptSettings {
    fn default() -> Self {
        Self {
            tol: 0.01,
            max_unknowns: 200_000,
            theta: 0.5,
            marking: Marking::Dorfler,
            bisection: Bisection::AllEdges,
            max_levels: 40,
            algebraic: 0.1,
            stop_on: StopOn::Hierarchical,
        }
    }
}

impl AdaptSettings {
    /// The settings from keywords as the Python binding and the scene files give them, each `None` taking
    /// its default, validated.
    ///
    /// # Errors
    /// [`crate::Error::UnknownChoice`] for a marking that is not `dorfler` or `maximum`, a bisection
    /// that is not `all_edges` or `refinement_edge`, or a `stop_on` that is not `bound`, `hierarchical` or `enriched`;
    /// as [`AdaptSettings::validate`].
    pub fn from_keywords(keywords: AdaptKeywords) -> Result<Self> {
        let AdaptKeywords { tol, max_unknowns, theta, marking, bisection, max_levels, algebraic, stop_on } = keywords;
        let d = Self::default();
        let settings = Self {
            tol: tol.unwrap_or(d.tol),
            max_unknowns: max_unknowns.unwrap_or(d.max_unknowns),
            theta: theta.unwrap_or(d.theta),
            marking: marking.as_deref().map_or(Ok(d.marking), crate::choice::Choice::parse)?,
            bisection: bisection.as_deref().map_or(Ok(d.bisection), crate::choice::Choice::parse)?,
            max_levels: max_levels.unwrap_or(d.max_levels),
            algebraic: algebraic.unwrap_or(d.algebraic),
            stop_on: stop_on.as_deref().map_or(Ok(d.stop_on), crate::choice::Choice::parse)?,
        };
        settings.validate()?;
        Ok(settings)
    }

    /// Checks every setting (`max_unknowns` is checked against the first level when the loop starts).
    ///
    /// # Errors
    /// [`crate::Error::BadSetting`] naming the setting: `adapt_tol` not positive or not finite,
    /// `adapt_theta` outside (0, 1], `adapt_max_levels` zero, `adapt_algebraic` outside [0, 1).
    pub fn validate(&self) -> Result<()> {
        check_setting("adapt_tol", self.tol, self.tol > 0.0, "must be positive")?;
        check_setting("adapt_theta", self.theta, self.theta > 0.0 && self.theta <= 1.0, "must lie in (0, 1]")?;
        check_setting("adapt_max_levels", self.max_levels as f64, self.max_levels >= 1, "must be at least 1")?;
        let a = self.algebraic;
        check_setting("adapt_algebraic", a, (0.0..1.0).contains(&a), "must lie in [0, 1)")
    }
}
