//! What the adaptive loop hands back: its levels, why it stopped, and the last level's problem and answer
//! ([`crate::adapt`] describes the loop).

use std::ops::ControlFlow;

use crate::problem::Problem;
use crate::results::{ErrorEstimate, Solution, SolveStatus};

/// One level of an adaptive solve.
#[derive(Debug, Clone)]
pub struct Level {
    /// Unknowns (displacement dofs after the supports, and the pressures of a mixed formulation).
    pub unknowns: usize,
    /// Multiplier dofs q (per component).
    pub multipliers: usize,
    /// Triangles.
    pub triangles: usize,
    /// The estimate of this level's solution.
    pub estimate: ErrorEstimate,
    /// The relative estimate the stopping test reads: of the tractions (the smaller of the hierarchical
    /// estimate and the bound where the loop computed the former, of the calibrated bound and the bound on the level
    /// after, the bound elsewhere), or of the energy when nothing touches.
    pub relative: f64,
    /// Wall time of the level (building the problem, solving, estimating, marking and refining); 0 for the
    /// enriched answer handed back as the last level (module documentation), solved as the estimate of the
    /// level before it and counted there.
    pub seconds: f64,
    /// How the level's solve ended.
    pub status: SolveStatus,
    /// Whether the level is the answer enriched for the estimate of the level before it, handed back as the
    /// last level (`stop_on = "enriched"`: module documentation); its estimate is then half its change from that
    /// level.
    pub enriched: bool,
    /// The level's mesh (the edge sets and the newest-vertex labels with it), so that a level can be
    /// looked at or solved again. The levels grow geometrically, so all their meshes together take a few
    /// times the memory of the last one.
    pub mesh: crate::mesh::Mesh,
    /// The points of the level's multiplier mesh T_H (abscissae on Γ_C).
    pub multiplier_mesh: Vec<f64>,
    /// Where each body lies in `mesh` (as [`Problem::bodies`]).
    pub bodies: Vec<crate::problem::bodies::BodyPart>,
    /// The material of every triangle of `mesh`: an index into the materials of the problem the run
    /// started from (as [`crate::fem::elasticity::Materials::region`]).
    pub regions: Vec<usize>,
}

/// Why the adaptive loop stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdaptStop {
    /// The relative estimate reached `tol` (the last level's, or the enriched answer's, handed back as one more
    /// level: module documentation).
    Tolerance,
    /// The next refinement would have exceeded `max_unknowns`.
    MaxUnknowns,
    /// `max_levels` levels were solved.
    MaxLevels,
    /// The next level's solve would have exceeded the memory budget ([`crate::SolverSettings::memory_budget`],
    /// [`crate::Error::MemoryBudget`]): the level before is handed back, as at `max_unknowns`.
    MemoryBudget,
    /// A level's solve did not converge (its status is the last level's).
    NotConverged,
    /// The estimate is exactly zero: nothing to refine. Either the discrete answer is exact, or nothing
    /// touches and nothing penetrates where the estimator looks (its Gauss points on every edge of Γ_C,
    /// and finely around the obstacle's lowest points, [`crate::ObstacleShape::lowest_points`]: a gap
    /// *function* that dips below Γ_C only between those points is not seen). It is checked before the
    /// tolerance, so a relative estimate of 0 / 0 never reads as an accuracy reached.
    Exact,
    /// The observer asked to stop.
    Interrupted,
}

crate::choice::named_choice!(AdaptStop, "adaptive stop", {
    AdaptStop::Tolerance => "tolerance",
    AdaptStop::MaxUnknowns => "max_unknowns",
    AdaptStop::MaxLevels => "max_levels",
    AdaptStop::MemoryBudget => "memory_budget",
    AdaptStop::NotConverged => "not_converged",
    AdaptStop::Exact => "exact",
    AdaptStop::Interrupted => "interrupted",
});

/// The result of an adaptive solve: the problem on the last mesh, its solution, and every level.
#[derive(Debug, Clone)]
pub struct Adaptive {
    /// The problem on the last mesh.
    pub problem: Problem,
    /// The last level's solution.
    pub solution: Solution,
    /// Every level, the first (the given mesh) included.
    pub levels: Vec<Level>,
    /// Why the loop stopped.
    pub stop: AdaptStop,
}

/// An observer of the levels: called after each one; `ControlFlow::Break(())` stops the loop there.
pub type LevelObserver<'a> = &'a mut dyn FnMut(&Level) -> ControlFlow<()>;
