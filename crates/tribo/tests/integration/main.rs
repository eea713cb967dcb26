//! tribo's integration tests, one binary with one module per layer:
//!
//! * `adaptive`: the adaptive loop finds an unknown contact zone, stops where it must, refuses bad settings;
//! * `errors`: one rejection test per input rule;
//! * `fuzz`: hostile input (proptest) ends in a typed error or an honest status;
//! * `invariants`: property tests of the Γ_C matrices, the multiplier basis and the common refinement;
//! * `patch`: constant-strain states reproduced exactly, for every multiplier space, γ0 and friction law;
//! * `kkt`: the discrete problem (3.1) checked by its own quadrature, independent of the assembly;
//! * `hertz`: named scenes (Hertz convergence, the checkerboard of the classic method, Coulomb);
//! * `history`: loading histories (the incremental problem against the static one, the path, sliding);
//! * `moved_supports`: histories that move prescribed displacements (moving the body is moving the obstacle);
//! * `methods`: the active-set method against clarabel, QP by QP, on every scene above;
//! * `coulomb_newton`: the semismooth Newton method against the fixed point (Hertz over μ and ν, a body held
//!   only by the contact, a history), `auto` and its fallback;
//! * `paths`: every solver path (QP method, condensation, working set, KKT solver) to the unique answer,
//!   on random problems;
//! * `outputs`: what a reader gets back (global forces, plane-strain stress, current gap, formatted
//!   numbers, the condensation's progress);
//! * `plane_stress`: plane stress as plane strain with the equivalent material, σ_zz = 0, Hertz with E* = E;
//! * `rigid_motion`: a scene turned and moved gives the same tractions and the turned fields;
//! * `supports`: rollers and prescribed displacements: patch tests, the half Hertz model against the full one;
//! * `two_bodies`: two elastic bodies in contact (patch test, action and reaction, the rigid limit, Hertz);
//! * `bent_pair`: two bodies with a bent interface (a shrink fit against Lamé, turned and moved, adaptive, refusals);
//! * `conformal`: conformal contact, a pin pushed across a hole with clearance, against Persson's problem;
//! * `estimator`: the a posteriori estimate (what it sees, and how it tracks the true error of λ_n);
//! * `error_bars`: the error bars of the forces and zone widths against a finer mesh, only when asked for;
//! * `materials`: bodies of several materials (the layered block exact, γ0 from Γ_C's materials, adaptive layers);
//! * `mixed`: the mixed displacement–pressure formulation (the patch state exact to ν = 0.4999, Hertz without
//!   locking, clarabel and the active set to one answer, what it refuses);
//! * `axisymmetric`: solids of revolution (the pressed cylinder exact, a sphere against 3D Hertz, a flat punch
//!   against Boussinesq, a shrink fit against Lamé, histories, two bodies, the refusals);
//! * `axisymmetric_mixed`: the mixed formulation in axisymmetry (rubber against 3D Hertz and Lamé);
//! * `turned_obstacle`: obstacles turned about a point, in one solve and step by step in a history;
//! * `layout`: the house rules of the crate (the layer table of its folders, file sizes).
//!
//! Scenes and measures shared with the benches and examples come from the `tribo-testkit` crate.

mod adaptive;
mod axisymmetric;
mod axisymmetric_mixed;
mod bent_pair;
mod bodies_and_pairs;
mod conformal;
mod coulomb_newton;
mod curved;
mod curved_patch;
mod error_bars;
mod errors;
mod estimator;
mod fuzz;
mod held_by_contact;
mod hertz;
mod history;
mod invariants;
mod kkt;
mod layout;
mod materials;
mod methods;
mod mixed;
mod moved_supports;
mod outputs;
mod pair_adaptive;
mod pair_estimate;
mod pair_friction;
mod pair_history;
mod patch;
mod paths;
mod plane_stress;
mod rigid_motion;
mod several_pairs;
mod supports;
mod turned_obstacle;
mod two_bodies;

/// The property tests' configuration: `cases` cases (or `PROPTEST_CASES`), reproducible like the Python
/// fuzz tests (derandomized there): a fixed seed, or `PROPTEST_RNG_SEED` to explore others; no regression
/// files are written (a failure prints its shrunk case, which the fixed seed reproduces).
fn reproducible(cases: u32) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    let config = Config::default();
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(cases);
    let rng_seed =
        if std::env::var_os("PROPTEST_RNG_SEED").is_some() { config.rng_seed } else { RngSeed::Fixed(0x74_7269_626f) };
    Config { cases, rng_seed, failure_persistence: None, ..config }
}
