//! Criterion benches of the solve pipeline on the Hertz scene (`python/tribo/scenes/hertz.toml`, read by
//! `tribo-testkit`): a rigid cylinder (R = 1) pushed 0.01 into the block (−2, 2) × (−2, 0), clamped at the
//! bottom, E = 200, ν = 0.3, P1 multipliers on the FE points of Γ_C, γ0 = half the admissible bound,
//! meshes graded toward the contact zone. Every group takes the finest mesh size `h_min` as its
//! parameter. `cargo bench` at the top of the repository runs them (they belong to the `tribo` crate).
//!
//! Groups (one per phase):
//! - `mesh`: [`graded_rectangle`];
//! - `assembly`: [`Problem::new`] (K, loads, Γ_C geometry, T_H, Γ_C matrices);
//! - `gamma_c_matrices`: [`tribo::mortar::MortarMatrices::new`] alone;
//! - `condensation`: [`Problem::condense`] without its cache (sparse Cholesky of K − G and `c`);
//! - `tresca`: one Tresca solve (threshold 0.5) on a prebuilt [`tribo::Condensed`];
//! - `coulomb`: one whole Coulomb solve (μ = 0.3, shift 0.004) on a prebuilt [`tribo::Condensed`];
//! - `qp_kkt_solver`: frictionless and Tresca solves with clarabel's QDLDL against its faer KKT solver;
//! - `cholesky_reference`: sparse Cholesky factorization + solve of K alone (the plain elastic solve the
//!   Coulomb solve is compared with), also at h_min = 0.04 so that every Coulomb size has its reference;
//! - `admissible_gamma0`: the admissible bound on γ0 (a 3 × 3 eigenproblem per contact triangle);
//! - `uniform_103k`: every phase on a uniform 320 × 160 mesh (103k unknowns): `Problem::new`,
//!   `Problem::condense`, the whole Coulomb solve, and the Cholesky reference;
//! - `qp_method`: the whole Coulomb solve with clarabel for every QP against the default (the warm-started
//!   active-set method), on a prebuilt condensation;
//! - `block`: the block scene (`python/tribo/scenes/block.toml`, contact along the whole bottom edge) at
//!   400 × 100 (80k unknowns) and 800 × 200 (320k): the whole Coulomb solve from a fresh factorization
//!   (H from the partial factorization) and the Cholesky reference.
//! - `graded_55k`: the accurate regime: Hertz graded to h_min = 3.125e-4 (55k unknowns, 2539 multiplier
//!   dofs), the whole Coulomb solve from a fresh factorization as `condensation = auto` chooses (the
//!   sparse saddle-point system) and with H by columns, and the Cholesky reference;
//! - `history`: a loading history on a prebuilt condensation (Hertz, pressed, then dragged to 0.004 in 10
//!   steps, μ = 0.3): the whole history (11 steps) against one static Coulomb solve of its last position
//!   (the target: a step after the first costs no more than the static solve without its factorization).
//!
//! - `two_bodies`: two-body Hertz (`tribo_testkit::two_body_hertz`, E = 200 under E = 70, graded to h_min =
//!   0.005 and 0.00125): the whole Coulomb solve from a fresh factorization and the Cholesky reference of
//!   the two bodies' K (the target: the ratio of one body of as many unknowns).
//!
//! - `mixed`: locking (study 25): Hertz at ν = 0.4999 graded at growth 0.05 to h_min = 0.0025 (43k P1
//!   unknowns), built (`problem_new`) and solved frictionless from a fresh factorization (`solve`) in the
//!   displacement formulation (which locks) and in the mixed one (the target: at most 2.5 times P1's).
//!
//! The set-up prints, once per mesh, the numbers of unknowns (n_free) and of multiplier dofs (q), and the
//! status of the Coulomb solves. `cargo bench --bench solver -- --test` runs every bench once.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::hint::black_box;
use std::rc::Rc;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode};
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;
use faer::Mat;
use tribo::mortar::MortarMatrices;
use tribo::{
    Choice, Condensation, Formulation, Friction, Grading, KktSolver, LoadStep, Material, Mesh, MultiplierPoints,
    MultiplierSpace, Problem, ProblemSpec, QpMethod, QpSettings, Side, SolveStatus, SolverSettings, Stabilization,
    Threshold,
};
use tribo_testkit::{block_problem, hertz_mesh, hertz_scene, hertz_spec, two_body_hertz};

/// Mesh sizes of the set-up, Tresca and KKT-solver groups.
const SIZES: [f64; 3] = [0.02, 0.01, 0.005];
/// Mesh sizes of the Coulomb group.
const COULOMB_SIZES: [f64; 3] = [0.04, 0.02, 0.01];
/// Mesh sizes of the Cholesky reference: the union of the two.
const CHOLESKY_SIZES: [f64; 4] = [0.04, 0.02, 0.01, 0.005];

const STABILIZATION: Stabilization = Stabilization::Fraction(0.5);
const TRESCA_THRESHOLD: f64 = 0.5;
const MU: f64 = 0.3;
const COULOMB_SHIFT: f64 = 0.004;

fn grading(h_min: f64) -> Grading {
    let s = hertz_scene();
    Grading { side: Side::Top, segment: s.segment, h_min, h_max: s.h_max, growth: s.growth }
}

fn spec(shift: f64) -> ProblemSpec {
    hertz_spec(hertz_scene().approach, shift, MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1)
}

/// One Hertz problem, assembled (and condensed once, so its factorization is cached).
struct Scene {
    mesh: Mesh,
    spec: ProblemSpec,
    problem: Problem,
}

impl Scene {
    fn new(h_min: f64, shift: f64) -> Self {
        let mesh = hertz_mesh(h_min);
        let spec = spec(shift);
        let problem = Problem::new(mesh.clone(), spec.clone()).expect("Hertz problem");
        let gamma0 = problem.condense(STABILIZATION).expect("condensation").gamma0();
        eprintln!(
            "[hertz h_min = {h_min}, shift = {shift}] nodes {} triangles {} n_free {} q {} (2q = {}) γ0 {:.3e}",
            mesh.n_nodes(),
            mesh.triangles().len(),
            problem.n_free,
            problem.n_multipliers(),
            2 * problem.n_multipliers(),
            gamma0,
        );
        Self { mesh, spec, problem }
    }
}

thread_local! {
    static SCENES: RefCell<BTreeMap<(u64, u64), Rc<Scene>>> = const { RefCell::new(BTreeMap::new()) };
}

/// The scene of size `h_min` and obstacle shift `shift`, built (and described on stderr) once.
fn scene(h_min: f64, shift: f64) -> Rc<Scene> {
    let key = (h_min.to_bits(), shift.to_bits());
    SCENES.with(|s| s.borrow_mut().entry(key).or_insert_with(|| Rc::new(Scene::new(h_min, shift))).clone())
}

/// Settings of the slow groups: few samples, a flat sampling plan, a short warm-up.
fn configure_slow(group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>, seconds: u64) {
    group.sample_size(10).measurement_time(Duration::from_secs(seconds)).sampling_mode(SamplingMode::Flat);
}

fn bench_mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh");
    group.measurement_time(Duration::from_secs(2));
    for h_min in SIZES {
        let _ = scene(h_min, 0.0);
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &h_min, |b, &h| {
            let sc = hertz_scene();
            b.iter(|| tribo::graded_rectangle(sc.x, sc.y, black_box(&grading(h))).unwrap())
        });
    }
    group.finish();
}

fn bench_assembly(c: &mut Criterion) {
    let mut group = c.benchmark_group("assembly");
    group.measurement_time(Duration::from_secs(2));
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &s, |b, s| {
            b.iter_batched(
                || (s.mesh.clone(), s.spec.clone()),
                |(mesh, spec)| Problem::new(mesh, spec).unwrap(),
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();

    let mut group = c.benchmark_group("gamma_c_matrices");
    group.measurement_time(Duration::from_secs(2));
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &s, |b, s| {
            let p = &s.problem;
            let h_t: Vec<f64> = p.contact.edges.iter().map(|e| p.mesh.diameter(e.triangle)).collect();
            b.iter(|| {
                MortarMatrices::new(black_box(&p.contact), &p.multipliers, &h_t, &p.spec.obstacle, p.spec.model)
                    .unwrap()
            })
        });
    }
    group.finish();
}

fn bench_condensation(c: &mut Criterion) {
    let mut group = c.benchmark_group("condensation");
    configure_slow(&mut group, 3);
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &s, |b, s| {
            b.iter(|| {
                s.problem.forget_factorization();
                s.problem.condense(black_box(STABILIZATION)).unwrap().gamma0()
            })
        });
    }
    group.finish();
}

fn tresca() -> Friction {
    Friction::Tresca(Threshold::Uniform(TRESCA_THRESHOLD))
}

fn bench_tresca(c: &mut Criterion) {
    let mut group = c.benchmark_group("tresca");
    configure_slow(&mut group, 4);
    let settings = SolverSettings::default();
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        let condensed = s.problem.condense(STABILIZATION).unwrap();
        let sol = condensed.solve(&tresca(), &settings, None).unwrap();
        assert_eq!(sol.report.status, SolveStatus::Converged, "Tresca at h_min = {h_min}");
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &condensed, |b, c| {
            b.iter(|| c.solve(black_box(&tresca()), &settings, None).unwrap())
        });
    }
    group.finish();
}

fn bench_coulomb(c: &mut Criterion) {
    let mut group = c.benchmark_group("coulomb");
    configure_slow(&mut group, 5);
    let settings = SolverSettings::default();
    let friction = Friction::Coulomb { mu: MU };
    for h_min in COULOMB_SIZES {
        let s = scene(h_min, COULOMB_SHIFT);
        let condensed = s.problem.condense(STABILIZATION).unwrap();
        let sol = condensed.solve(&friction, &settings, None).unwrap();
        eprintln!(
            "[coulomb h_min = {h_min}] status {:?}, {} fixed-point iterations, QP iterations {:?}",
            sol.report.status, sol.report.iterations, sol.report.qp_iterations
        );
        assert_eq!(sol.report.status, SolveStatus::Converged, "Coulomb at h_min = {h_min}");
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &condensed, |b, c| {
            b.iter(|| c.solve(black_box(&friction), &settings, None).unwrap())
        });
    }
    group.finish();
}

fn bench_history(c: &mut Criterion) {
    let mut group = c.benchmark_group("history");
    configure_slow(&mut group, 5);
    let settings = SolverSettings::default();
    let friction = Friction::Coulomb { mu: MU };
    let approach = hertz_scene().approach;
    let steps: Vec<LoadStep> = (0..=10).map(|k| LoadStep::new(approach, COULOMB_SHIFT * k as f64 / 10.0)).collect();
    for h_min in COULOMB_SIZES {
        let s = scene(h_min, COULOMB_SHIFT);
        let condensed = s.problem.condense(STABILIZATION).unwrap();
        let h = condensed.solve_history(&friction, &steps, &settings, None).unwrap();
        assert_eq!(h.status, SolveStatus::Converged, "history at h_min = {h_min}");
        eprintln!(
            "[history h_min = {h_min}] 11 steps, fixed-point iterations {:?}",
            h.solutions.iter().map(|s| s.report.iterations).collect::<Vec<_>>()
        );
        group.bench_with_input(BenchmarkId::new("11_steps", h_min), &condensed, |b, c| {
            b.iter(|| c.solve_history(black_box(&friction), &steps, &settings, None).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("static", h_min), &condensed, |b, c| {
            b.iter(|| c.solve(black_box(&friction), &settings, None).unwrap())
        });
    }
    group.finish();
}

fn bench_qp_kkt_solver(c: &mut Criterion) {
    let mut group = c.benchmark_group("qp_kkt_solver");
    configure_slow(&mut group, 3);
    let cases = [("frictionless", Friction::Frictionless), ("tresca", tresca())];
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        let condensed = s.problem.condense(STABILIZATION).unwrap();
        for (law, friction) in &cases {
            for (name, kkt) in [("qdldl", KktSolver::Qdldl), ("faer", KktSolver::Faer)] {
                let mut settings = SolverSettings::default();
                settings.qp.kkt_solver = kkt;
                let sol = condensed.solve(friction, &settings, None).unwrap();
                assert_eq!(sol.report.status, SolveStatus::Converged, "{law} with {name} at h_min = {h_min}");
                group.bench_with_input(BenchmarkId::new(format!("{law}/{name}"), h_min), &condensed, |b, c| {
                    b.iter(|| c.solve(black_box(friction), &settings, None).unwrap())
                });
            }
        }
    }
    group.finish();
}

/// Sparse Cholesky factorization (symbolic + numeric) of `k` and one solve with `f`.
fn cholesky_solve(k: &SparseColMat<usize, f64>, f: &[f64]) -> Mat<f64> {
    let llt = k.sp_cholesky(faer::Side::Lower).expect("K is positive definite");
    let mut x = Mat::<f64>::from_fn(f.len(), 1, |i, _| f[i]);
    llt.solve_in_place(x.as_mut());
    x
}

fn bench_cholesky_reference(c: &mut Criterion) {
    let mut group = c.benchmark_group("cholesky_reference");
    group.sample_size(10).measurement_time(Duration::from_secs(2));
    for h_min in CHOLESKY_SIZES {
        let s = scene(h_min, 0.0);
        let p = &s.problem;
        let n = p.n_free;
        let k = p.k_matrix.clone();
        // Sanity check of K u = f. The Hertz load comes from the obstacle only (f_free = 0, which costs the
        // same to solve), so check the residual against a non-trivial right-hand side.
        let f: Vec<f64> = (0..n).map(|i| ((i % 7) as f64) - 3.0).collect();
        let u = cholesky_solve(&k, &f);
        let ku = &k * &u;
        let res = (0..n).map(|i| (ku[(i, 0)] - f[i]).abs()).fold(0.0, f64::max);
        assert!(res < 1e-8 * f.iter().map(|v| v.abs()).fold(0.0, f64::max), "K u = f residual {res:e}");
        group.bench_with_input(BenchmarkId::new("factor_solve", h_min), &k, |b, k| {
            b.iter(|| cholesky_solve(black_box(k), &p.f_free))
        });
    }
    group.finish();
}

fn bench_admissible_gamma0(c: &mut Criterion) {
    let mut group = c.benchmark_group("admissible_gamma0");
    group.sample_size(10).measurement_time(Duration::from_secs(2));
    for h_min in SIZES {
        let s = scene(h_min, 0.0);
        group.bench_with_input(BenchmarkId::from_parameter(h_min), &s, |b, s| {
            b.iter(|| {
                tribo::stabilization::admissible_gamma0(
                    black_box(&s.mesh),
                    s.spec.model,
                    &s.spec.material,
                    &s.problem.contact,
                )
            })
        });
    }
    group.finish();
}

/// Every phase at more than 100k unknowns: a uniform 320 × 160 mesh of the Hertz block (h = 0.0125).
fn bench_uniform_103k(c: &mut Criterion) {
    let mut group = c.benchmark_group("uniform_103k");
    configure_slow(&mut group, 20);
    let mesh = tribo::rectangle([-2.0, 2.0], [-2.0, 0.0], 320, 160, tribo::Diagonal::Alternating).expect("mesh");
    let spec = spec(COULOMB_SHIFT);
    let problem = Problem::new(mesh.clone(), spec.clone()).expect("problem");
    let settings = SolverSettings::default();
    let coulomb = Friction::Coulomb { mu: MU };
    let check = problem.solve(&coulomb, &settings, None).expect("solve");
    eprintln!(
        "[uniform 320 x 160] n_free {} q {} Coulomb {:?} after {} iterations",
        problem.n_free,
        problem.n_multipliers(),
        check.report.status,
        check.report.iterations
    );
    assert_eq!(check.report.status, SolveStatus::Converged);
    group.bench_function("problem_new", |b| {
        b.iter_batched(|| (mesh.clone(), spec.clone()), |(m, s)| Problem::new(m, s).unwrap(), BatchSize::LargeInput)
    });
    group.bench_function("condense", |b| {
        b.iter(|| {
            problem.forget_factorization();
            problem.condense(black_box(STABILIZATION)).unwrap().gamma0()
        })
    });
    group.bench_function("coulomb_solve", |b| {
        b.iter(|| {
            // A fresh factorization each time: the columns of H are computed on demand and kept with it.
            problem.forget_factorization();
            problem.solve(black_box(&coulomb), &settings, None).unwrap()
        })
    });
    let k = problem.k_matrix.clone();
    group.bench_function("cholesky_reference", |b| b.iter(|| cholesky_solve(black_box(&k), &problem.f_free)));
    group.finish();
}

fn bench_qp_method(c: &mut Criterion) {
    let mut group = c.benchmark_group("qp_method");
    configure_slow(&mut group, 5);
    let friction = Friction::Coulomb { mu: MU };
    for h_min in COULOMB_SIZES {
        let s = scene(h_min, COULOMB_SHIFT);
        let condensed = s.problem.condense(STABILIZATION).unwrap();
        for method in [QpMethod::Clarabel, QpMethod::Auto] {
            let settings = SolverSettings { qp: QpSettings { method, ..Default::default() }, ..Default::default() };
            let sol = condensed.solve(&friction, &settings, None).unwrap();
            assert_eq!(sol.report.status, SolveStatus::Converged, "{method} at h_min = {h_min}");
            group.bench_with_input(BenchmarkId::new(method.to_string(), h_min), &condensed, |b, c| {
                b.iter(|| c.solve(black_box(&friction), &settings, None).unwrap())
            });
        }
    }
    group.finish();
}

fn bench_block(c: &mut Criterion) {
    let mut group = c.benchmark_group("block");
    configure_slow(&mut group, 20);
    for nx in [400usize, 800] {
        let (problem, mu) = block_problem(nx, nx / 4);
        let friction = Friction::Coulomb { mu };
        let settings = SolverSettings::default();
        let label = format!("block {nx} x {}", nx / 4);
        bench_coulomb_and_cholesky(&mut group, &label, nx as f64, &problem, &friction, &settings);
    }
    group.finish();
}

/// One checked Coulomb solve (its sizes, status and path printed), then the benches of the whole solve from
/// a fresh factorization and of the Cholesky reference, both with parameter `id`.
fn bench_coulomb_and_cholesky(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    label: &str,
    id: f64,
    problem: &Problem,
    friction: &Friction,
    settings: &SolverSettings,
) {
    let check = problem.solve(friction, settings, None).expect("solve");
    eprintln!(
        "[{label}] n_free {} q {} Coulomb {} after {} iterations, H by {}",
        problem.n_free,
        problem.n_multipliers(),
        check.report.status,
        check.report.iterations,
        check.report.condensation
    );
    assert_eq!(check.report.status, SolveStatus::Converged);
    bench_fresh_solve(group, BenchmarkId::new("coulomb_solve", id), problem, friction, settings);
    bench_cholesky(group, BenchmarkId::new("cholesky_reference", id), problem);
}

/// The whole solve of `problem` from a fresh factorization (its cache forgotten at every iteration).
fn bench_fresh_solve(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: BenchmarkId,
    problem: &Problem,
    friction: &Friction,
    settings: &SolverSettings,
) {
    group.bench_with_input(id, problem, |b, p| {
        b.iter(|| {
            p.forget_factorization();
            p.solve(black_box(friction), settings, None).unwrap()
        })
    });
}

/// The Cholesky reference of `problem`: factorization and solve of K alone.
fn bench_cholesky(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: BenchmarkId,
    problem: &Problem,
) {
    let k = problem.k_matrix.clone();
    group.bench_with_input(id, &k, |b, k| b.iter(|| cholesky_solve(black_box(k), &problem.f_free)));
}

fn bench_graded_55k(c: &mut Criterion) {
    let mut group = c.benchmark_group("graded_55k");
    configure_slow(&mut group, 30);
    let h_min = 3.125e-4;
    let problem = Problem::new(hertz_mesh(h_min), spec(COULOMB_SHIFT)).expect("valid problem");
    let friction = Friction::Coulomb { mu: MU };
    for condensation in [Condensation::Auto, Condensation::Columns] {
        let settings = SolverSettings { stabilization: STABILIZATION, condensation, ..Default::default() };
        let check = problem.solve(&friction, &settings, None).expect("solve");
        eprintln!(
            "[graded h_min = {h_min}] n_free {} q {} Coulomb {} after {} iterations, H by {}, {} LDLᵀ or dense factorizations over {} active-set steps",
            problem.n_free,
            problem.n_multipliers(),
            check.report.status,
            check.report.iterations,
            check.report.condensation,
            check.report.qp_factorizations.iter().sum::<u32>(),
            check.report.qp_iterations.iter().sum::<u32>()
        );
        assert_eq!(check.report.status, SolveStatus::Converged);
        let id = BenchmarkId::new("coulomb_solve", condensation.as_str());
        bench_fresh_solve(&mut group, id, &problem, &friction, &settings);
    }
    bench_cholesky(&mut group, BenchmarkId::new("cholesky_reference", h_min), &problem);
    group.finish();
}

fn bench_two_bodies(c: &mut Criterion) {
    let mut group = c.benchmark_group("two_bodies");
    configure_slow(&mut group, 20);
    let steel = Material { young: 200.0, poisson: 0.3 };
    let aluminium = Material { young: 70.0, poisson: 0.33 };
    let friction = Friction::Coulomb { mu: MU };
    let settings = SolverSettings::default();
    for h_min in [0.005, 0.00125] {
        let problem = two_body_hertz(h_min, steel, aluminium, false, 0.01);
        let label = format!("two bodies h_min = {h_min}");
        bench_coulomb_and_cholesky(&mut group, &label, h_min, &problem, &friction, &settings);
    }
    group.finish();
}

fn bench_mixed(c: &mut Criterion) {
    let mut group = c.benchmark_group("mixed");
    configure_slow(&mut group, 10);
    let s = hertz_scene();
    let grading = Grading { side: Side::Top, segment: s.segment, h_min: 0.0025, h_max: 0.1, growth: 0.05 };
    let mesh = tribo::graded_rectangle(s.x, s.y, &grading).expect("valid grading");
    let settings = SolverSettings::default();
    for formulation in [Formulation::Displacement, Formulation::Mixed] {
        let material = Material { young: s.material.young, poisson: 0.4999 };
        let spec = ProblemSpec { material, ..spec(0.0) }.formulation(formulation);
        let problem = Problem::new(mesh.clone(), spec.clone()).expect("valid problem");
        eprintln!("[mixed, {formulation}] n_free {} q {}", problem.n_free, problem.n_multipliers());
        group.bench_function(BenchmarkId::new("problem_new", formulation.as_str()), |b| {
            b.iter(|| Problem::new(black_box(mesh.clone()), spec.clone()).unwrap())
        });
        bench_fresh_solve(
            &mut group,
            BenchmarkId::new("solve", formulation.as_str()),
            &problem,
            &Friction::Frictionless,
            &settings,
        );
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default().sample_size(10).warm_up_time(Duration::from_millis(500)).nresamples(20_000)
}

criterion_group! {
    name = benches;
    config = config();
    targets = bench_mesh, bench_assembly, bench_condensation, bench_tresca, bench_coulomb, bench_qp_kkt_solver,
        bench_cholesky_reference, bench_admissible_gamma0, bench_uniform_103k, bench_qp_method, bench_block,
        bench_history, bench_graded_55k, bench_two_bodies, bench_mixed
}
criterion_main!(benches);
