//! Scenes and measures shared by the tests, benches and examples of tribo (a dev-only crate).
//!
//! The Hertz scene is read from `python/tribo/scenes/hertz.toml`, the file the Python tests and the
//! studies read too, so one scene has one definition across the two languages.
//!
//! This is test support: a scene file that does not parse, or a scene the core refuses, is a broken test
//! fixture, so these helpers panic (with a message) instead of returning errors.

use tribo::*;

mod energy;
mod persson;
mod pin_in_hole;
mod roller;
mod shrink_fit;
mod singular_ends;
mod wedge;
pub use energy::*;
pub use persson::*;
pub use pin_in_hole::*;
pub use roller::*;
pub use shrink_fit::*;
pub use singular_ends::*;
pub use wedge::*;

/// The Hertz scene file.
pub const HERTZ_SCENE: &str = include_str!("../../../python/tribo/scenes/hertz.toml");

/// The block scene file (a contact zone along the whole bottom edge).
pub const BLOCK_SCENE: &str = include_str!("../../../python/tribo/scenes/block.toml");

/// The parameters of the Hertz scene that the tests and benches use.
#[derive(Debug, Clone, PartialEq)]
pub struct HertzScene {
    /// x range of the block.
    pub x: [f64; 2],
    /// y range of the block.
    pub y: [f64; 2],
    /// Young's modulus and Poisson's ratio.
    pub material: Material,
    /// Radius of the cylinder.
    pub radius: f64,
    /// Obstacle approach δ of the scene.
    pub approach: f64,
    /// The segment of the top face the mesh is graded toward.
    pub segment: [f64; 2],
    /// Largest cell size.
    pub h_max: f64,
    /// Cell size at the contact zone in the scene file.
    pub h_min: f64,
    /// Growth of the cell size with the distance to the segment.
    pub growth: f64,
}

fn pair(t: &toml::Table, section: &str, key: &str) -> [f64; 2] {
    let v = t[section][key].as_array().unwrap_or_else(|| panic!("{section}.{key} is a pair"));
    [number(&v[0]), number(&v[1])]
}

fn number(v: &toml::Value) -> f64 {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64)).expect("a number")
}

/// The Hertz scene as the scene file gives it.
pub fn hertz_scene() -> HertzScene {
    let t: toml::Table = HERTZ_SCENE.parse().expect("hertz.toml is valid TOML");
    let n = |section: &str, key: &str| number(&t[section][key]);
    assert_eq!(t["obstacle"]["shape"].as_str(), Some("circle"), "the Hertz scene has a circular obstacle");
    HertzScene {
        x: pair(&t, "body", "x"),
        y: pair(&t, "body", "y"),
        material: Material { young: n("material", "young"), poisson: n("material", "poisson") },
        radius: n("obstacle", "radius"),
        approach: n("obstacle", "approach"),
        segment: pair(&t, "discretization", "grading"),
        h_max: n("discretization", "h"),
        h_min: n("discretization", "h_min"),
        growth: n("discretization", "growth"),
    }
}

/// The mesh of the Hertz scene with the given `h_min`, graded toward the scene's segment of the top face.
pub fn hertz_mesh(h_min: f64) -> Mesh {
    let s = hertz_scene();
    let grading = Grading { side: Side::Top, segment: s.segment, h_min, h_max: s.h_max, growth: s.growth };
    graded_rectangle(s.x, s.y, &grading).expect("valid grading")
}

/// An adaptive case of studies 12–14 (issue 36): a coarse start, its friction law and a reference.
pub struct AdaptiveCase {
    /// The friction law.
    pub friction: Friction,
    /// The reference problem and its solution.
    pub reference: (Problem, Solution),
    /// How the reference was made (for the studies' printouts).
    pub reference_source: String,
    /// The coarse start of the adaptive runs.
    pub coarse: Problem,
}

/// The names [`adaptive_case`] knows, with what each is.
pub const ADAPTIVE_CASES: [(&str, &str); 9] = [
    ("hertz", "Hertz, the cylinder centred, frictionless"),
    ("hertz@X", "Hertz, the cylinder at x = X, frictionless"),
    ("hertz-coulomb", "Hertz, centred, Coulomb mu = 0.3, the obstacle shifted 0.004 (partial slip)"),
    (
        "hertz-tresca",
        "Hertz, centred, Tresca threshold 1 on all of the top, the obstacle shifted 0.004 (stick and slip)",
    ),
    ("hertz-p0", "Hertz, centred, frictionless, P0 multipliers"),
    ("block", "the block scene (full contact, Coulomb mu = 0.3, shifted 0.008)"),
    ("two-body", "two-body Hertz, steel under aluminium, frictionless"),
    ("two-body-coulomb", "two-body Hertz, steel under aluminium, Coulomb mu = 0.3 (slip from the mismatch)"),
    ("pairs", "two contact pairs: a half block pressed by a cylindrical punch onto a foundation, frictionless"),
];

/// The adaptive case named `name` ([`ADAPTIVE_CASES`]). The Hertz cases start from the 8 × 4 mesh and
/// take their 466k-unknown graded reference ([`adaptive_hertz_case`]; P0 multipliers are measured against
/// the P1 reference: both approximate one λ), but for Tresca's, whose λ_t lives on all of the top where that mesh is
/// coarse (against it, the true error of the adaptive levels stalled at 5e-3 from 15k unknowns while the estimate
/// fell). The block starts from 8 × 2 (h = 0.5) and two-body Hertz from its blocks at h = 0.5 (8 × 4 under 8 × 2);
/// their reference, and Tresca Hertz's, is the adaptive loop itself from that start,
/// run to `REFERENCE_UNKNOWNS` with the bound (a few minutes), the block's then graded toward the ends of Γ_C, where
/// its λ is singular ([`graded_at_ends`]).
///
/// # Errors
/// [`Error::UnknownChoice`] for a name not in [`ADAPTIVE_CASES`]; the errors of the solves.
pub fn adaptive_case(name: &str) -> Result<AdaptiveCase> {
    let coulomb = Friction::Coulomb { mu: 0.3 };
    let tresca = Friction::Tresca(Threshold::Uniform(TRESCA_THRESHOLD));
    let steel = Material { young: 200.0, poisson: 0.3 };
    let aluminium = Material { young: 70.0, poisson: 0.33 };
    let (coarse, friction) = match name {
        "hertz" => return adaptive_hertz_case(0.0, Friction::Frictionless, MultiplierSpace::P1),
        "hertz-coulomb" => return adaptive_hertz_case(0.0, coulomb, MultiplierSpace::P1),
        // λ_t lives on all of Γ_C (the threshold acts where nothing touches): the graded reference is coarse there.
        "hertz-tresca" => (hertz_coarse(0.0, &tresca, MultiplierSpace::P1)?, tresca),
        "hertz-p0" => return adaptive_hertz_case(0.0, Friction::Frictionless, MultiplierSpace::P0),
        "block" => (block_problem(8, 2).0, coulomb),
        "two-body" => (two_body_hertz(0.5, steel, aluminium, false, 0.01), Friction::Frictionless),
        "two-body-coulomb" => (two_body_hertz(0.5, steel, aluminium, false, 0.01), coulomb),
        "pairs" => return punch_and_foundation_case(),
        _ => match name.strip_prefix("hertz@").and_then(|x| x.parse::<f64>().ok()) {
            Some(center) => return adaptive_hertz_case(center, Friction::Frictionless, MultiplierSpace::P1),
            None => {
                return Err(Error::UnknownChoice {
                    what: "adaptive case",
                    got: name.to_string(),
                    options: ADAPTIVE_CASES.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", "),
                })
            }
        },
    };
    let adapt = AdaptSettings {
        tol: 1e-9,
        max_unknowns: REFERENCE_UNKNOWNS,
        stop_on: StopOn::Bound,
        ..AdaptSettings::default()
    };
    let run = coarse.solve_adaptive(&friction, &SolverSettings::default(), &adapt, None)?;
    let mut reference_source = format!(
        "the adaptive loop from the coarse start to {} unknowns ({} levels, stopped on {}; its bound {:.2e})",
        run.problem.n_free,
        run.levels.len(),
        run.stop,
        run.solution.report.estimate.traction_relative
    );
    let mut reference = (run.problem, run.solution);
    if name == "block" {
        // λ is singular at both ends of Γ_C: the error of the reference lives there.
        let (problem, solution, rounds, change) = graded_at_ends(reference, &friction);
        reference_source += &format!(
            ", then graded toward the ends of Γ_C ({rounds} rounds of bisection, {} unknowns; the last changed λ by \
             {change:.1e} relative)",
            problem.n_free
        );
        reference = (problem, solution);
    }
    Ok(AdaptiveCase { friction, reference, reference_source, coarse })
}

/// The header of the `tol` tables of studies 13 and 13b (the examples `tol_table` and `history_tol`).
pub const TOL_TABLE_HEADER: &str = "stop_on tol | true error  true/tol  unknowns  seconds | cheapest level reaching \
     tol: unknowns seconds | time / cheapest | stop";

/// A row of the `tol` tables: the stop and the asked `tol`, the true error reached, the run's unknowns and
/// seconds, the cheapest level of the run whose true error is at most `tol` (unknowns, seconds to reach it)
/// if any, and why the run stopped.
pub fn tol_table_row(
    (stop_on, tol): (StopOn, f64),
    achieved: f64,
    (unknowns, total): (usize, f64),
    cheapest: Option<(usize, f64)>,
    stop: AdaptStop,
) -> String {
    let (cn, ct) = cheapest.unwrap_or((0, f64::NAN));
    format!(
        "{:>12} {tol:<5} | {achieved:.3e} {:>8.3} {unknowns:>9} {total:>8.3} | {cn:>9} {ct:>8.3} | {:>6.2} | {stop}",
        stop_on.as_str(),
        achieved / tol,
        total / ct,
    )
}

/// Where the examples `tol_table` and `history_tol` write their CSV files by default: `docs/tol_table` of the
/// repository.
pub fn tol_table_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/tol_table")
}

/// The header of a `tol` table's runs file (`CASE-STOP.csv`, one row per run: [`tol_table_csv`]).
pub const TOL_RUNS_HEADER: &str =
    "case,stop_on,tol,true_error,unknowns,seconds,levels,cheapest_unknowns,cheapest_seconds,stop";

/// The header of a `tol` table's levels file (`CASE-STOP_levels.csv`, one row per level, or per step of a level of a
/// history: [`LevelRow`]).
pub const TOL_LEVELS_HEADER: &str =
    "case,stop_on,tol,level,unknowns,seconds,step,in_contact,true_error,hierarchical,bound,calibrated";

/// Creates `dir` and the runs and levels files of the `tol` table of `case` stopping on `stop_on` in it
/// (`CASE-STOP.csv`, `CASE-STOP_levels.csv`: the runs of one stop do not overwrite the other's), their headers
/// written.
///
/// # Errors
/// When `dir` or a file cannot be made.
pub fn tol_table_files(
    dir: &std::path::Path,
    case: &str,
    stop_on: StopOn,
) -> std::io::Result<(std::fs::File, std::fs::File)> {
    use std::io::Write;
    std::fs::create_dir_all(dir)?;
    let create = |name: String, header: &str| -> std::io::Result<std::fs::File> {
        let mut file = std::fs::File::create(dir.join(name))?;
        writeln!(file, "{header}")?;
        Ok(file)
    };
    let stem = format!("{case}-{}", stop_on.as_str());
    Ok((create(format!("{stem}.csv"), TOL_RUNS_HEADER)?, create(format!("{stem}_levels.csv"), TOL_LEVELS_HEADER)?))
}

/// A run's row of the runs file ([`TOL_RUNS_HEADER`]): as [`tol_table_row`], with the run's levels; the
/// cheapest columns empty where no level reached `tol`.
pub fn tol_table_csv(
    case: &str,
    (stop_on, tol): (StopOn, f64),
    achieved: f64,
    (unknowns, total, levels): (usize, f64, usize),
    cheapest: Option<(usize, f64)>,
    stop: AdaptStop,
) -> String {
    let (cn, ct) = cheapest.map_or((String::new(), String::new()), |(n, t)| (n.to_string(), format!("{t:.6}")));
    format!("{case},{},{tol},{achieved:.6e},{unknowns},{total:.6},{levels},{cn},{ct},{stop}", stop_on.as_str())
}

/// A level's row of the levels file ([`TOL_LEVELS_HEADER`]).
#[derive(Debug, Clone, Copy)]
pub struct LevelRow {
    /// The level's index in its run.
    pub level: usize,
    /// Its unknowns.
    pub unknowns: usize,
    /// Its seconds (the hierarchical solves included).
    pub seconds: f64,
    /// The step of a history (`None`: a static solve, or the level's worst step of a history).
    pub step: Option<usize>,
    /// Multiplier dofs not in separation.
    pub in_contact: usize,
    /// The relative L²(Γ_C) error of λ against the case's reference.
    pub true_error: f64,
    /// The relative hierarchical estimate where it was computed.
    pub hierarchical: Option<f64>,
    /// The relative bound.
    pub bound: f64,
    /// The calibrated bound where the loop formed it (the level after an estimated one).
    pub calibrated: Option<f64>,
}

impl LevelRow {
    /// The row, for the run of `case` stopping on `stop_on` at `tol`.
    pub fn csv(&self, case: &str, stop_on: StopOn, tol: f64) -> String {
        let step = self.step.map_or(String::new(), |s| s.to_string());
        let sharp = self.hierarchical.map_or(String::new(), |h| format!("{h:.6e}"));
        let calibrated = self.calibrated.map_or(String::new(), |c| format!("{c:.6e}"));
        format!(
            "{case},{},{tol},{},{},{:.6},{step},{},{:.6e},{sharp},{:.6e},{calibrated}",
            stop_on.as_str(),
            self.level,
            self.unknowns,
            self.seconds,
            self.in_contact,
            self.true_error,
            self.bound
        )
    }
}

/// The Tresca threshold of the case `hertz-tresca` ([`ADAPTIVE_CASES`]), uniform on all of Γ_C: about an eighth of the
/// peak Hertz pressure (7.9), so that with the shift of 0.004 the contact zone slips backward over its first half and
/// forward over its last third, with a stick zone between, and the free top sticks in part (a Tresca threshold acts
/// where nothing touches: λ_t takes every value of [−1, 1] along Γ_C).
pub const TRESCA_THRESHOLD: f64 = 1.0;

/// The largest reference [`adaptive_case`] builds by the adaptive loop.
pub const REFERENCE_UNKNOWNS: usize = 500_000;

/// The adaptive Hertz cases of studies 12 and 13 (issue 36): the cylinder at `center`, with `friction` (the obstacle
/// shifted 0.004 unless frictionless), with multipliers in `space`; their 466k-unknown
/// reference (P1 multipliers) on a mesh graded toward [center − 0.1, center + 0.1] (h_min 1.5625e-4,
/// growth 0.02), solved with the default settings (about a minute); and their coarse 8 × 4 start.
///
/// # Errors
/// Those of the solves.
pub fn adaptive_hertz_case(center: f64, friction: Friction, space: MultiplierSpace) -> Result<AdaptiveCase> {
    let mut spec = hertz_coarse(center, &friction, MultiplierSpace::P1)?.spec;
    let grading =
        Grading { side: Side::Top, segment: [center - 0.1, center + 0.1], h_min: 1.5625e-4, h_max: 0.05, growth: 0.02 };
    let reference = Problem::new(graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading)?, spec.clone())?;
    let solution = reference.solve(&friction, &SolverSettings::default(), None)?;
    spec.multiplier_space = space;
    let coarse = hertz_coarse(center, &friction, space)?;
    let reference_source = format!("a graded mesh of {} unknowns (h_min 1.5625e-4, growth 0.02)", reference.n_free);
    Ok(AdaptiveCase { friction, reference: (reference, solution), reference_source, coarse })
}

/// The coarse 8 × 4 start of the adaptive Hertz cases: the cylinder at `center` pushed 0.01, shifted 0.004 unless
/// `friction` is frictionless, multipliers in `space`.
///
/// # Errors
/// Those of the mesh and the problem.
pub fn hertz_coarse(center: f64, friction: &Friction, space: MultiplierSpace) -> Result<Problem> {
    let mut spec = hertz_spec(0.01, 0.0, MultiplierPoints::RatioToFe(1.0), space);
    spec.obstacle.shape = ObstacleShape::Circle { center, radius: 1.0 };
    if *friction != Friction::Frictionless {
        spec.obstacle.shift = 0.004;
    }
    Problem::new(rectangle([-2.0, 2.0], [-2.0, 0.0], 8, 4, Diagonal::Right)?, spec)
}

/// The specification of the Hertz scene: clamped at the bottom, contact on the top, the cylinder pushed
/// `approach` and shifted `shift`.
pub fn hertz_spec(approach: f64, shift: f64, points: MultiplierPoints, space: MultiplierSpace) -> ProblemSpec {
    let s = hertz_scene();
    ProblemSpec {
        material: s.material,
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec!["bottom".into()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: "top".into(),
        obstacle: Obstacle {
            shape: ObstacleShape::Circle { center: 0.0, radius: s.radius },
            approach,
            shift,
            rotation: None,
        },
        multiplier_points: points,
        multiplier_space: space,
        pairs: Vec::new(),
    }
}

/// The Hertz problem on the graded mesh of size `h_min`.
pub fn hertz_problem(
    h_min: f64,
    approach: f64,
    shift: f64,
    points: MultiplierPoints,
    space: MultiplierSpace,
) -> Problem {
    Problem::new(hertz_mesh(h_min), hertz_spec(approach, shift, points, space)).expect("valid Hertz problem")
}

/// The block scene on a uniform `nx × ny` mesh (right diagonals): the block pressed onto a flat foundation
/// and dragged, with the friction coefficient of the scene file.
pub fn block_problem(nx: usize, ny: usize) -> (Problem, f64) {
    let t: toml::Table = BLOCK_SCENE.parse().expect("block.toml is valid TOML");
    let n = |section: &str, key: &str| number(&t[section][key]);
    assert_eq!(t["obstacle"]["shape"].as_str(), Some("flat"), "the block scene has a flat foundation");
    let mesh = rectangle(pair(&t, "body", "x"), pair(&t, "body", "y"), nx, ny, Diagonal::Right).expect("valid");
    let spec = ProblemSpec {
        material: Material { young: n("material", "young"), poisson: n("material", "poisson") },
        model: Model::PlaneStrain,
        formulation: Default::default(),
        clamped: vec![t["supports"]["clamped"].as_str().expect("one set").to_string()],
        supports: vec![],
        body_force: [0.0, 0.0],
        tractions: vec![],
        contact: t["contact"]["edge_set"].as_str().expect("a set").to_string(),
        obstacle: Obstacle {
            shape: ObstacleShape::Flat,
            approach: n("obstacle", "approach"),
            shift: n("obstacle", "shift"),
            rotation: None,
        },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        pairs: Vec::new(),
    };
    (Problem::new(mesh, spec).expect("valid block problem"), n("friction", "mu"))
}

/// Two contact pairs: the half block [0, ½] × [0, 1] (E = 1, ν = 0.3, `n` × `2n` cells, a roller on its left side,
/// the axis of the whole block) pressed by a rigid cylinder of radius ½ centred above its top left corner
/// (approach 0.01; the pair "top", P1 multipliers on the FE edges) onto a rigid foundation touching its bottom (the
/// pair "bottom"): the block is held vertically by the contacts alone.
///
/// # Panics
/// When `n` is 0 (no cells): a test fixture, given its sizes by the tests and studies, never by a user.
pub fn punch_and_foundation(n: usize) -> Problem {
    punch_and_foundation_on(rectangle([0.0, 0.5], [0.0, 1.0], n, 2 * n, Diagonal::Right).expect("n ≥ 1 cells"))
}

/// [`punch_and_foundation`] on `mesh` (of the block [0, ½] × [0, 1], its edge sets those of [`rectangle`]).
///
/// # Panics
/// When `mesh` lacks the edge sets "top", "bottom" and "left" of [`rectangle`] or is degenerate: a test fixture,
/// given its meshes by the tests and studies (this crate's generators), never by a user.
pub fn punch_and_foundation_on(mesh: Mesh) -> Problem {
    let line = |y: f64| ObstacleShape::Line { point: [0.0, y], normal: [0.0, 1.0] };
    let mut spec = ProblemSpec::new(Material { young: 1.0, poisson: 0.3 }, "top")
        .support(Support::roller("left"))
        .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
    spec.obstacle = Obstacle {
        shape: ObstacleShape::Disc { center: [0.0, 1.5], radius: 0.5 },
        approach: 0.01,
        shift: 0.0,
        rotation: None,
    };
    let foundation = Obstacle { shape: line(0.0), approach: 0.0, shift: 0.0, rotation: None };
    spec.pairs.push(PairSpec::new("bottom", foundation));
    Problem::new(mesh, spec).expect("the block between a punch and a foundation")
}

/// The adaptive case `pairs` (frictionless): its coarse start [`punch_and_foundation`] on 4 × 8 cells, and its
/// reference on a mesh graded toward the punch's contact zone (half-width 0.048: the segment [0, 0.06] of the top,
/// h_min 1.5625e-4, growth 0.02, so h = 0.02 along the foundation, whose pressure is smooth: the block's corner on a
/// frictionless flat is its mirror image's straight side).
///
/// # Errors
/// Those of the mesh and of the solve.
pub fn punch_and_foundation_case() -> Result<AdaptiveCase> {
    let grading = Grading { side: Side::Top, segment: [0.0, 0.06], h_min: 1.5625e-4, h_max: 0.05, growth: 0.02 };
    let reference = punch_and_foundation_on(graded_rectangle([0.0, 0.5], [0.0, 1.0], &grading)?);
    let friction = Friction::Frictionless;
    let solution = reference.solve(&friction, &SolverSettings::default(), None)?;
    let reference_source = format!("a graded mesh of {} unknowns (h_min 1.5625e-4, growth 0.02)", reference.n_free);
    Ok(AdaptiveCase { friction, reference: (reference, solution), reference_source, coarse: punch_and_foundation(4) })
}

/// The Hertz cylinder (R = 1) pushed `approach` into the uniform 80 × 40 mesh of the Hertz block (h = 0.05),
/// shifted `shift`, with P1 multipliers of size `ratio` × h: with `ratio` < 1 and γ0 = 0, the classic
/// method's checkerboard.
pub fn checkerboard_problem(ratio: f64, approach: f64, shift: f64) -> Problem {
    let s = hertz_scene();
    let mesh = rectangle(s.x, s.y, 80, 40, Diagonal::Right).expect("valid");
    Problem::new(mesh, hertz_spec(approach, shift, MultiplierPoints::RatioToFe(ratio), MultiplierSpace::P1))
        .expect("valid checkerboard problem")
}

/// Plane-strain Hertz pressure for total force `p` (R, E, ν of the Hertz scene) and its half-width.
pub fn hertz_pressure(p: f64) -> (impl Fn(f64) -> f64, f64) {
    let s = hertz_scene();
    hertz_pressure_with(p, s.material.young / (1.0 - s.material.poisson.powi(2)))
}

/// The plane-strain Hertz pressure of force `p` (per unit depth) and half-width a, for the scene's radius
/// and the contact modulus `e_star` (E/(1 − ν²) against a rigid cylinder, `combined_modulus` for two bodies).
pub fn hertz_pressure_with(p: f64, e_star: f64) -> (impl Fn(f64) -> f64, f64) {
    let r = hertz_scene().radius;
    let a = (4.0 * p * r / (std::f64::consts::PI * e_star)).sqrt();
    let pmax = 2.0 * p / (std::f64::consts::PI * a);
    (move |x: f64| if x.abs() < a { pmax * (1.0 - (x / a).powi(2)).sqrt() } else { 0.0 }, a)
}

/// The contact modulus of two bodies, `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂`.
pub fn combined_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / ((1.0 - a.poisson.powi(2)) / a.young + (1.0 - b.poisson.powi(2)) / b.young)
}

/// Relative L2 error of λ_n against the Hertz pressure of the computed force, integrated with 8-point
/// Gauss on every segment of the union of T_H, the FE nodes and the Hertz edge points ±a (so the square
/// root singularity sits at a breakpoint).
pub fn hertz_l2_error(problem: &Problem, sol: &Solution) -> f64 {
    let s = hertz_scene();
    hertz_l2_error_with(problem, sol, s.material.young / (1.0 - s.material.poisson.powi(2)))
}

/// [`hertz_l2_error`] for the contact modulus `e_star`.
pub fn hertz_l2_error_with(problem: &Problem, sol: &Solution, e_star: f64) -> f64 {
    let (p, a) = hertz_pressure_with(sol.normal_force, e_star);
    pressure_l2_error(problem, sol, &p, &[-a, a], None, |_| 1.0)
}

/// The relative L² error of λ_n against the pressure `exact`, with the measure `weight(ξ)` (1 in the plane,
/// ξ for an axisymmetric Γ_C from the axis), by 8-point Gauss on every segment of the union of T_H, the FE
/// nodes and `extra` breakpoints (where `exact` is singular), over all of Γ_C or up to `up_to`.
pub fn pressure_l2_error(
    problem: &Problem,
    sol: &Solution,
    exact: &dyn Fn(f64) -> f64,
    extra: &[f64],
    up_to: Option<f64>,
    weight: impl Fn(f64) -> f64,
) -> f64 {
    let end = up_to.unwrap_or(f64::INFINITY);
    let mut breaks: Vec<f64> = problem.multipliers.xi.iter().chain(&problem.contact.node_xi).copied().collect();
    breaks.extend(extra);
    breaks.extend(up_to);
    breaks.retain(|&x| x <= end);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let (gx, gw) = gauss8();
    let (mut num, mut den) = (0.0, 0.0);
    for w in breaks.windows(2) {
        let (h, m) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for (x, wt) in gx.iter().zip(&gw) {
            let xi = m + h * x;
            let (l, e) = (problem.multipliers.evaluate(&sol.lambda_n, xi), exact(xi));
            num += wt * h * weight(xi) * (l - e).powi(2);
            den += wt * h * weight(xi) * e * e;
        }
    }
    (num / den).sqrt()
}

/// Two-body Hertz: the scene's block (−2, 2) × (−2, 0) of material `lower`, clamped at the bottom, under a
/// block (−2, 2) × (0, 1) of material `upper` whose top is pushed down by `delta` (u_x held there too when
/// `hold_top`, else only on its left side), both graded toward [−0.15, 0.15] at growth 0.15 down to
/// `h_min`; the gap between them is the parabola of the scene's radius (the sum of the two curvatures),
/// the lower top is the secondary side, P1 multipliers on its edges.
///
/// # Panics
/// If `h_min` or a material is not valid (a test's own parameters: this dev-only scene has no user input;
/// the fixed geometry — two blocks on one line, each held by its supports — is always a valid pair).
pub fn two_body_hertz(h_min: f64, lower: Material, upper: Material, hold_top: bool, delta: f64) -> Problem {
    two_body_hertz_sides(h_min, lower, upper, hold_top, delta, true)
}

/// [`two_body_hertz`] with the secondary side (T_H and the stabilization) on the lower block's top
/// (`lower_secondary`) or on the upper block's bottom.
///
/// # Panics
/// As [`two_body_hertz`].
pub fn two_body_hertz_sides(
    h_min: f64,
    lower: Material,
    upper: Material,
    hold_top: bool,
    delta: f64,
    lower_secondary: bool,
) -> Problem {
    let top = Support::displacement("top", hold_top.then_some(0.0), Some(-delta));
    two_blocks(h_min, lower, upper, vec![top, Support::displacement("left", Some(0.0), None)], lower_secondary)
}

/// Two-body Hertz set up for shearing (Cattaneo–Mindlin between two bodies): the blocks of
/// [`two_body_hertz`], the lower top secondary, but the upper block held only by its top, through a
/// prescribed displacement `(0, 0)` that a history moves (components `"upper.top.x"`, `"upper.top.y"`).
///
/// # Panics
/// As [`two_body_hertz`].
pub fn two_body_shear(h_min: f64, lower: Material, upper: Material) -> Problem {
    two_blocks(h_min, lower, upper, vec![Support::displacement("top", Some(0.0), Some(0.0))], true)
}

/// The two blocks of [`two_body_hertz`] as values (the bodies, their pair), for a test to change before it builds
/// the problem: the lower one clamped at its bottom, the upper one pushed down `delta` at its top (held in x at its
/// left side), the lower top secondary, in plane strain.
pub fn two_body_hertz_parts(h_min: f64, lower: Material, upper: Material, delta: f64) -> ([Body; 2], ContactPair) {
    let top = Support::displacement("top", None, Some(-delta));
    two_block_parts(h_min, lower, upper, vec![top, Support::displacement("left", Some(0.0), None)], true)
}

/// The bodies and the pair of [`two_blocks`].
fn two_block_parts(
    h_min: f64,
    lower: Material,
    upper: Material,
    upper_supports: Vec<Support>,
    lower_secondary: bool,
) -> ([Body; 2], ContactPair) {
    let body = |name: &str, upper_block: bool, material, supports| {
        let mesh = graded_half(h_min, upper_block);
        let materials = Materials::uniform(material, mesh.n_triangles());
        Body { name: String::from(name), mesh, materials, clamped: vec![], supports, tractions: vec![] }
    };
    let bodies =
        [body("lower", false, lower, vec![Support::clamp("bottom")]), body("upper", true, upper, upper_supports)];
    let (secondary, primary) =
        if lower_secondary { ("lower.top", "upper.bottom") } else { ("upper.bottom", "lower.top") };
    let pair = ContactPair {
        secondary: secondary.into(),
        primary: primary.into(),
        gap: ObstacleShape::Parabola { center: 0.0, radius: hertz_scene().radius },
        multiplier_points: MultiplierPoints::RatioToFe(1.0),
        multiplier_space: MultiplierSpace::P1,
        model: Model::PlaneStrain,
        formulation: Default::default(),
    };
    (bodies, pair)
}

/// The two blocks of [`two_body_hertz`]: the lower one clamped at its bottom, the upper one held by
/// `upper_supports`, the parabolic gap of the scene's radius, P1 multipliers on the secondary side's edges.
///
/// # Panics
/// As [`two_body_hertz`]: only `h_min` and the materials come from the caller, a test's own parameters.
fn two_blocks(
    h_min: f64,
    lower: Material,
    upper: Material,
    upper_supports: Vec<Support>,
    lower_secondary: bool,
) -> Problem {
    let (bodies, pair) = two_block_parts(h_min, lower, upper, upper_supports, lower_secondary);
    // Dev-only scene, no user input: two blocks on one line with opposite normals, each held by its own
    // supports, are a valid pair by construction; a bad material is the calling test's own parameter.
    Problem::two_bodies(bodies, pair, [0.0, 0.0]).expect("a valid two-body scene")
}

/// The lower (−2, 2) × (−2, 0) or upper (−2, 2) × (0, 1) block of [`two_body_hertz`], graded toward
/// [−0.15, 0.15] of its contact side.
///
/// # Panics
/// If `h_min` is not a valid grading size: the calling test's own parameter (ranges, h_max and growth are
/// fixed and valid; this dev-only kit sees no user input).
fn graded_half(h_min: f64, upper: bool) -> Mesh {
    let (side, y) = if upper { (Side::Bottom, [0.0, 1.0]) } else { (Side::Top, [-2.0, 0.0]) };
    let grading = Grading { side, segment: [-0.15, 0.15], h_min, h_max: 0.5, growth: 0.15 };
    // Internal invariant of this dev-only kit (no user input reaches it): every caller passes a positive
    // h_min below h_max = 0.5, so the generator cannot refuse it.
    graded_rectangle([-2.0, 2.0], y, &grading).expect("h_min is the calling test's own valid parameter")
}

/// 8-point Gauss–Legendre rule on [−1, 1].
pub fn gauss8() -> ([f64; 8], [f64; 8]) {
    let x = [0.183_434_642_495_649_8, 0.525_532_409_916_329, 0.796_666_477_413_626_7, 0.960_289_856_497_536_3];
    let w = [0.362_683_783_378_362, 0.313_706_645_877_887_3, 0.222_381_034_453_374_5, 0.101_228_536_290_376_3];
    ([-x[3], -x[2], -x[1], -x[0], x[0], x[1], x[2], x[3]], [w[3], w[2], w[1], w[0], w[0], w[1], w[2], w[3]])
}

/// Least-squares slope of log(y) against log(x).
pub fn fitted_rate(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// A unit square meshed with alternating diagonals and interior nodes moved by up to 25 % of h in a
/// deterministic pseudo-random way, so patch tests run on a genuinely irregular mesh.
pub fn distorted_square(n: usize) -> Mesh {
    let m = rectangle([0.0, 1.0], [0.0, 1.0], n, n, Diagonal::Alternating).expect("valid");
    let h = 1.0 / n as f64;
    let mut seed: u64 = 0x2545_F491_4F6C_DD1D;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let pts: Vec<[f64; 2]> = m
        .points()
        .iter()
        .map(|p| {
            let interior = p[0] > 1e-12 && p[0] < 1.0 - 1e-12 && p[1] > 1e-12 && p[1] < 1.0 - 1e-12;
            if interior {
                [p[0] + 0.5 * h * rnd(), p[1] + 0.5 * h * rnd()]
            } else {
                *p
            }
        })
        .collect();
    Mesh::new(pts, m.triangles().to_vec(), m.edge_sets().clone()).expect("distortion keeps triangles valid")
}

/// Spectral condition number of the condensed multiplier operator H on its range (eigenvalues below
/// `k ε λ_max` count as its kernel: the non-unique part of λ when γ0 = 0 and T_H is too fine). A QP
/// solved to relative accuracy `tol` determines λ to about `tol · κ`.
pub fn condition_number(c: &Condensed<'_>) -> f64 {
    let k = 2 * c.q();
    let ev = nalgebra::DMatrix::from_column_slice(k, k, &c.factor().dense_h()).symmetric_eigenvalues();
    let max = ev.iter().fold(0.0_f64, |a, v| a.max(*v));
    max / ev.iter().filter(|v| **v > k as f64 * f64::EPSILON * max).fold(f64::INFINITY, |a, v| a.min(*v))
}

/// The tolerance the QPs of a solve actually met: `qp.tol`, or [`tribo::qp::FALLBACK_TOL`] if any of
/// them only reached that (the report counts them).
pub fn reached_qp_tol(settings: &SolverSettings, sol: &Solution) -> f64 {
    Solution::reached_qp_tol(settings.qp.tol, sol.report.qp_inaccurate)
}

/// The peak resident memory of this process so far, in MB (Linux's VmHWM; NaN where there is none): the
/// cost and scale examples read it after each phase.
pub fn peak_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kb = status.lines().find_map(|l| l.strip_prefix("VmHWM:")?.split_whitespace().next()?.parse::<f64>().ok());
    kb.map_or(f64::NAN, |kb| kb / 1024.0)
}
