//! `Problem`: the contact problem, validated and assembled once, and its solves. The typed surface
//! (`solve`, `solve_history`, their documentation and the broadcast of a history's steps) is the Python
//! subclass in `tribo/problem.py`; here the keywords become core values and the results dicts.

use std::collections::BTreeMap;
use std::ops::ControlFlow;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::conversion::FromPyObjectOwned;
use pyo3::exceptions::{PyIndexError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict, PyTuple};
use pyo3::IntoPyObjectExt;
use tribo::error::ErrorCategory::{ContactGeometry, Settings};
use tribo::{
    AdaptSettings, Bodies, Choice, Friction, FrictionLaw, Level, LevelObserver, LoadStep, MultiplierPoints,
    MultiplierSpace, ObstacleShape, Phase, ProblemKeywords, Progress, SolverSettings, Stabilization, StepProgress,
    Threshold,
};

use crate::convert::{callback, floats, indices, ints, pair, rows, setting_value, vec1};
use crate::errors::to_pyerr;
use crate::mesh::PyMesh;
use crate::obstacle::{chain_gap_error, take_gap_error, PyObstacle};
use crate::results;
use crate::supports::PySupport;

/// A contact problem, validated and assembled once (independent of γ0 and friction). It keeps the
/// factorization of its last solve, reused by the next solve with the same γ0.
#[pyclass(frozen, subclass, name = "Problem", module = "tribo._tribo")]
pub struct PyProblem {
    inner: tribo::Problem,
    /// Its attributes, plain data built once with it (`tribo.Problem` reads them).
    #[pyo3(get, name = "_data")]
    data: Py<PyDict>,
}

/// Tractions as `tribo.Problem` hands them over: (edge set, `[p]` a pressure or `[tx, ty]` a vector).
fn tractions_of(t: Vec<(String, Vec<f64>)>) -> PyResult<Vec<(String, tribo::Traction)>> {
    t.into_iter().map(|(set, v)| Ok((set, tribo::Traction::try_from(v.as_slice()).map_err(to_pyerr)?))).collect()
}

/// A further contact pair (`tribo.Pair`): (edge set, obstacle or None: flat, approach, shift, own μ; None: default).
type PairArgs = (String, Option<Py<PyObstacle>>, Option<f64>, Option<f64>, Option<f64>);
/// A body of `tribo.Body`: (name, mesh, materials, regions or None for one material, clamped, supports, tractions).
type BodyArgs =
    (String, Py<PyMesh>, Vec<(f64, f64)>, Option<Vec<usize>>, Vec<String>, Vec<PySupport>, Vec<(String, Vec<f64>)>);

fn body(b: BodyArgs) -> PyResult<tribo::Body> {
    let (name, mesh, pairs, regions, clamped, supports, tractions) = b;
    let (mesh, supports) = (mesh.get().inner.clone(), supports.into_iter().map(|s| s.inner).collect());
    let materials = tribo::Materials::from_pairs(&pairs, regions, mesh.n_triangles());
    Ok(tribo::Body { name, mesh, materials, clamped, supports, tractions: tractions_of(tractions)? })
}

/// Calls the callback (if any) with `args` and checks for Ctrl-C: `Break` when the callback returned
/// False, raised (kept in `error`, re-raised by the caller) or Ctrl-C was pressed.
fn observe_with<A: for<'py> pyo3::call::PyCallArgs<'py>>(
    callback: Option<&Py<PyAny>>,
    args: A,
    error: &mut Option<PyErr>,
) -> ControlFlow<()> {
    Python::attach(|py| {
        // False or any other false value (numpy.False_, 0) stops; None (no return) goes on.
        let call = |f: &Py<PyAny>| f.call1(py, args).and_then(|r| Ok(!r.is_none(py) && !r.bind(py).is_truthy()?));
        let stop = callback.map(call).transpose().unwrap_or_else(|e| {
            *error = Some(e);
            Some(true)
        });
        if let Err(e) = py.check_signals() {
            error.get_or_insert(e);
        }
        if stop == Some(true) || error.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })
}

/// The rows (approach, shift, load_factor, angle, prescribed displacements…) of a history as load steps.
fn load_steps(steps: &Bound<'_, PyAny>) -> PyResult<Vec<LoadStep>> {
    let width: usize = steps.getattr("shape")?.get_item(1)?.extract()?;
    let flat = floats(steps, "steps", &[None, Some(width)], Settings)?;
    flat.chunks(width.max(1)).enumerate().map(|(k, row)| LoadStep::from_row(k, row).map_err(to_pyerr)).collect()
}

/// `solve_adaptive`'s tol, max_unknowns, theta, (marking, bisection, stop_on), max_levels, algebraic (None: default).
pub type AdaptArgs = (Option<f64>, Option<usize>, Option<f64>, [Option<String>; 3], Option<usize>, Option<f64>);

/// The core's adaptive settings from `solve_adaptive`'s keywords, checked (`SettingsError` naming the setting).
pub fn adapt_settings(a: AdaptArgs) -> PyResult<AdaptSettings> {
    let (tol, max_unknowns, theta, [marking, bisection, stop_on], max_levels, algebraic) = a;
    let k = tribo::AdaptKeywords { tol, max_unknowns, theta, marking, bisection, max_levels, algebraic, stop_on };
    AdaptSettings::from_keywords(k).map_err(to_pyerr)
}

/// The keywords of a solve as core values: the friction law, the settings (γ0 among them) and the
/// callbacks. `tribo.Problem.solve` and `solve_history` (Python) spell them out and pass them as one dict.
struct SolveOptions {
    friction: Friction,
    settings: SolverSettings,
    progress: Option<Py<PyAny>>,
    on_phase: Option<Py<PyAny>>,
}

/// The value of `key` (None when left out or None), removed from `options`.
fn take<'py, T: FromPyObjectOwned<'py>>(options: &Bound<'py, PyDict>, key: &str) -> PyResult<Option<T>> {
    let v = options.call_method1("pop", (key, options.py().None()))?;
    let bad = |e: T::Error| PyTypeError::new_err(format!("{key}: {}", Into::<PyErr>::into(e)));
    (!v.is_none()).then(|| v.extract().map_err(bad)).transpose()
}

impl SolveOptions {
    /// Reads the keywords; `call` is the progress callback's arguments, for its error message.
    fn new(options: &Bound<'_, PyDict>, call: &str) -> PyResult<Self> {
        take_gap_error(); // every solve starts from here: no exception of an earlier call is left over
        let options = options.copy()?;
        let threshold = match take::<Bound<'_, PyAny>>(&options, "threshold")? {
            None => None,
            Some(t) => Some(match t.extract::<f64>() {
                Ok(s) => Threshold::Uniform(s),
                Err(_) => Threshold::PerDof(floats(&t, "threshold", &[None], Settings)?),
            }),
        };
        let law =
            take::<String>(&options, "friction")?.map(|f| FrictionLaw::parse(&f)).transpose().map_err(to_pyerr)?;
        let friction = Friction::from_keywords(law, take(&options, "mu")?, threshold).map_err(to_pyerr)?;
        let (gamma0, fraction) = (take(&options, "gamma0")?, take(&options, "gamma0_fraction")?);
        let checked = take(&options, "check_gamma0")?.unwrap_or(true);
        let stabilization = Stabilization::from_keywords(gamma0, fraction, checked).map_err(to_pyerr)?;
        let progress = take::<Bound<'_, PyAny>>(&options, "progress")?;
        let on_phase = take::<Bound<'_, PyAny>>(&options, "on_phase")?;
        let mut settings = SolverSettings { stabilization, ..Default::default() };
        for (key, value) in options.iter() {
            let name: String = key.extract()?;
            match settings.set(&name, setting_value(&value, &name)?) {
                Err(tribo::Error::UnknownSetting { known, .. }) => {
                    return Err(PyTypeError::new_err(format!(
                        "Problem.solve() got an unexpected keyword argument '{name}' (solver settings: {known})"
                    )));
                }
                other => other.map_err(to_pyerr)?,
            }
        }
        Ok(Self {
            friction,
            settings,
            progress: progress.map(|p| callback(&p, "progress", call, Settings)).transpose()?,
            on_phase: on_phase.map(|p| callback(&p, "on_phase", "(phase, seconds)", Settings)).transpose()?,
        })
    }
}

type Points<'py> = PyResult<Bound<'py, PyArray2<f64>>>;
/// `f` of Γ_C at abscissae `xi` (M, 2) on the side of pair `pair` (an index into `pairs`; IndexError beyond them).
fn on_side<'py>(p: &tribo::Problem, py: Python<'py>, xi: &Bound<'_, PyAny>, pair: usize, f: Along) -> Points<'py> {
    let x = floats(xi, "xi", &[None], ContactGeometry)?;
    let bad = || PyIndexError::new_err(format!("pair {pair}: the problem has {} contact pairs", p.sides.len() + 1));
    let c = p.pairs().get(pair).map(|p| p.contact).ok_or_else(bad)?;
    Ok(Array2::from(x.iter().map(|&x| f(c, x)).collect::<Vec<_>>()).into_pyarray(py))
}
type Along = fn(&tribo::ContactBoundary, f64) -> [f64; 2];

/// A core call with callbacks: its error (a gap's exception chained), else theirs, else a gap's, else the value.
fn finish<T>(py: Python<'_>, result: tribo::Result<T>, error: Option<PyErr>) -> PyResult<T> {
    let value = result.map_err(|e| chain_gap_error(py, to_pyerr(e)))?;
    error.or_else(take_gap_error).map_or(Ok(value), Err)
}

#[pymethods]
impl PyProblem {
    #[new]
    #[pyo3(signature = (
        mesh, *, materials = None, regions = None, contact, clamped = None, supports = None, obstacle = None, approach = None,
        shift = None, tractions = None, body_force = None, multiplier_ratio = None, multiplier_size = None,
        multiplier_points = None, space = None, primary = None, model = None, rotation = None, formulation = None,
        pairs = None,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        mesh: &Bound<'_, PyAny>,
        materials: Option<Vec<(f64, f64)>>,
        regions: Option<&Bound<'_, PyAny>>,
        contact: String,
        clamped: Option<Vec<String>>,
        supports: Option<Vec<PySupport>>,
        obstacle: Option<Py<PyObstacle>>,
        approach: Option<f64>,
        shift: Option<f64>,
        tractions: Option<Vec<(String, Vec<f64>)>>,
        body_force: Option<&Bound<'_, PyAny>>,
        multiplier_ratio: Option<f64>,
        multiplier_size: Option<f64>,
        multiplier_points: Option<&Bound<'_, PyAny>>,
        space: Option<&str>,
        primary: Option<String>,
        model: Option<&str>,
        rotation: Option<([f64; 2], f64)>,
        formulation: Option<&str>,
        pairs: Option<Vec<PairArgs>>,
    ) -> PyResult<Self> {
        let obstacle = obstacle.map_or_else(|| Py::new(py, PyObstacle::checked(ObstacleShape::Flat)?), Ok)?;
        let shape = obstacle.get().shape.clone();
        let points = match multiplier_points {
            None => None,
            Some(p) if py.import("numpy")?.call_method1("ndim", (p,))?.extract::<usize>()? == 2 => Some(
                MultiplierPoints::Points(rows(&floats(p, "multiplier_points", &[None, Some(2)], ContactGeometry)?)),
            ),
            Some(p) => Some(MultiplierPoints::Abscissae(floats(p, "multiplier_points", &[None], ContactGeometry)?)),
        };
        let points = MultiplierPoints::from_keywords(multiplier_ratio, multiplier_size, points).map_err(to_pyerr)?;
        take_gap_error();
        let shape_of = |o: Option<Py<PyObstacle>>| o.map(|o| o.get().shape.clone());
        // Two bodies (`tribo.Problem.two_bodies`): `mesh` is their list, each with its own materials, supports and
        // tractions; one body: `tribo.Problem` gives `young`, `poisson` as one material.
        let bodies = match &primary {
            Some(primary) => {
                let [first, second]: [BodyArgs; 2] = mesh.extract()?;
                Bodies::Two { bodies: Box::new([body(first)?, body(second)?]), primary: primary.clone() }
            }
            None => Bodies::One(mesh.cast::<PyMesh>()?.get().inner.clone()),
        };
        let keywords = ProblemKeywords {
            pairs: (pairs.unwrap_or_default().into_iter())
                .map(|(c, o, a, s, mu)| tribo::PairSpec::from_keywords(c, shape_of(o), (a, s), mu, &points))
                .collect(),
            contact,
            materials,
            regions: regions.map(|r| indices(r, "regions", &[None], Settings)).transpose()?,
            clamped,
            supports: supports.map(|s| s.into_iter().map(|s| s.inner).collect()),
            tractions: tractions.map(tractions_of).transpose()?,
            obstacle: shape,
            approach,
            shift,
            rotation,
            body_force: body_force.map_or(Ok([0.0, 0.0]), |b| pair(b, "body_force", Settings))?,
            model: model.map(tribo::Model::parse).transpose().map_err(to_pyerr)?,
            formulation: formulation.map_or(Ok(Default::default()), tribo::Formulation::parse).map_err(to_pyerr)?,
            multiplier_points: points,
            multiplier_space: space.map_or(Ok(MultiplierSpace::default()), MultiplierSpace::parse).map_err(to_pyerr)?,
        };
        let p = py
            .detach(|| tribo::Problem::from_keywords(bodies, keywords))
            .map_err(|e| chain_gap_error(py, to_pyerr(e)))?;
        let (c, spec) = (&p.contact, &p.spec);
        let mesh = match mesh.cast::<PyMesh>() {
            Ok(m) => m.clone().into_any().unbind(),
            Err(_) => Py::new(py, PyMesh::from_core(py, p.mesh.clone())?)?.into_any(),
        };
        let supports: Vec<_> = spec.supports.iter().map(|s| PySupport { inner: s.clone() }).collect();
        // Each body's name, (first node, end, first triangle, end) and unknowns.
        let part = |b: &tribo::BodyPart| (b.name.clone(), <(usize, usize, usize, usize)>::from(b.spans()), b.unknowns);
        let data = [
            ("mesh", mesh),
            ("obstacle", obstacle.into_any()),
            ("approach", spec.obstacle.approach.into_py_any(py)?),
            ("shift", spec.obstacle.shift.into_py_any(py)?),
            ("young", spec.material.young.into_py_any(py)?),
            ("poisson", spec.material.poisson.into_py_any(py)?),
            (
                "materials",
                p.materials.materials.iter().map(|m| (m.young, m.poisson)).collect::<Vec<_>>().into_py_any(py)?,
            ),
            ("regions", ints(py, p.materials.region.iter().copied())?),
            ("contact", spec.contact.clone().into_py_any(py)?),
            ("clamped", spec.clamped.clone().into_py_any(py)?),
            ("supports", supports.into_py_any(py)?),
            ("space", p.multipliers.space.as_str().into_py_any(py)?),
            ("n_free", p.n_free.into_py_any(py)?),
            ("n_multipliers", p.n_multipliers().into_py_any(py)?),
            ("gamma0_bound", p.gamma0_bound.value.into_py_any(py)?),
            ("gamma0_bound_element", p.gamma0_bound.triangle.into_py_any(py)?),
            ("contact_normal", (c.normal[0], c.normal[1]).into_py_any(py)?),
            ("contact_tangent", (c.tangent[0], c.tangent[1]).into_py_any(py)?),
            ("tangent_sign", c.tangent_sign().into_py_any(py)?),
            ("contact_nodes", ints(py, c.nodes.iter().copied())?),
            ("node_abscissae", vec1(py, &c.node_xi)?),
            ("multiplier_mesh", vec1(py, &p.multipliers.xi)?),
            ("multiplier_abscissae", vec1(py, p.multipliers.dof_abscissae())?),
            ("setup_timings", BTreeMap::from(p.timings.named()).into_py_any(py)?),
            ("primary", primary.into_py_any(py)?),
            ("bodies", p.bodies.iter().map(part).collect::<Vec<_>>().into_py_any(py)?),
            ("prescribed", spec.prescribed_components().into_py_any(py)?),
            ("pairs", p.pairs().iter().map(|p| p.name.to_string()).collect::<Vec<_>>().into_py_any(py)?),
        ];
        Ok(Self { inner: p, data: data.into_py_dict(py)?.unbind() })
    }

    /// Solves with the keywords of `tribo.Problem.solve` in `options`; returns a Solution's fields (dict).
    #[pyo3(name = "_solve")]
    fn solve<'py>(&self, py: Python<'py>, options: &Bound<'_, PyDict>) -> PyResult<Bound<'py, PyDict>> {
        let bars = take::<bool>(options, "error_bars")?.unwrap_or(false);
        let o = SolveOptions::new(options, "(iteration, change, qp_iterations, qp_seconds)")?;
        let mut error: Option<PyErr> = None;
        let (on_phase, progress) = (o.on_phase.as_ref(), o.progress.as_ref());
        let result = py.detach(|| {
            let mut observe = |p: &Progress| match p.phase {
                Phase::Condensation => observe_with(on_phase, ("condensation", p.condensation_seconds), &mut error),
                _ => observe_with(progress, (p.iteration, p.change, p.qp_iterations, p.qp_seconds), &mut error),
            };
            let solve = if bars { tribo::Problem::solve_with_error_bars } else { tribo::Problem::solve };
            solve(&self.inner, &o.friction, &o.settings, Some(&mut observe))
        });
        results::solution(py, &finish(py, result, error)?)
    }

    /// `tribo.Problem.solve_history` on `steps` (rows: approach, shift, load_factor, angle, displacements…).
    #[pyo3(name = "_solve_history")]
    fn solve_history<'py>(
        &self,
        py: Python<'py>,
        steps: &Bound<'_, PyAny>,
        options: &Bound<'_, PyDict>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let o = SolveOptions::new(options, "(step, steps, status, seconds)")?;
        let steps = load_steps(steps)?;
        let mut error: Option<PyErr> = None;
        let result = py.detach(|| {
            let mut observe = |p: &StepProgress| {
                observe_with(o.progress.as_ref(), (p.step, p.steps, p.status.name(), p.seconds), &mut error)
            };
            self.inner.solve_history(&o.friction, &steps, &o.settings, Some(&mut observe))
        });
        // An exception from the callback (or Ctrl-C, or a gap function) ends the history: it carries the steps done.
        let history = results::history(py, &result.map_err(|e| chain_gap_error(py, to_pyerr(e)))?)?;
        match error.or_else(take_gap_error) {
            Some(e) => {
                e.value(py).setattr("_partial_history", history)?;
                Err(e)
            }
            None => Ok(history),
        }
    }

    /// Solves adaptively (`solve_adaptive`), or the history `steps` on the steps `on` (`solve_history_adaptive`);
    /// returns the solution's or history's fields, the levels (each with its bodies' spans, mesh and T_H), the stop.
    #[pyo3(name = "_solve_adaptive", signature = (options, a, steps = None, on = Vec::new()))]
    fn solve_adaptive<'py>(
        &self,
        py: Python<'py>,
        options: &Bound<'_, PyDict>,
        a: AdaptArgs,
        steps: Option<&Bound<'_, PyAny>>,
        on: Vec<usize>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let o = SolveOptions::new(options, "(unknowns, relative, seconds)")?;
        let adapt = adapt_settings(a)?;
        let steps = steps.map(load_steps).transpose()?;
        let mut error = None;
        let result = py.detach(|| {
            let mut observe =
                |l: &Level| observe_with(o.progress.as_ref(), (l.unknowns, l.relative, l.seconds), &mut error);
            let (p, f, s, ob) = (&self.inner, &o.friction, &o.settings, Some(&mut observe as LevelObserver<'_>));
            match &steps {
                None => p.solve_adaptive(f, s, &adapt, ob).map(|a| (Err(a.solution), a.levels, a.stop)),
                Some(t) => {
                    p.solve_history_adaptive(f, t, s, &adapt, &on, ob).map(|a| (Ok(a.history), a.levels, a.stop))
                }
            }
        });
        let (answer, levels, stop) = finish(py, result, error)?;
        let answer = answer.map_or_else(|s| results::solution(py, &s), |h| results::history(py, &h))?;
        let level = |l: &Level| (l.unknowns, l.multipliers, l.triangles, l.estimate.named(), l.relative, l.seconds);
        let spans = |l: &Level| l.bodies.iter().map(|b| b.spans()).collect::<Vec<_>>();
        let mesh = |l: Level| {
            let at = (spans(&l), ints(py, l.regions.iter().copied())?, vec1(py, &l.multiplier_mesh)?);
            Ok((level(&l), l.status.name(), (at.0, PyMesh::from_core(py, l.mesh)?, at.2, at.1), l.enriched))
        };
        let levels = levels.into_iter().map(mesh).collect::<PyResult<Vec<_>>>()?;
        (answer, levels, stop.as_str()).into_pyobject(py)
    }

    /// Points of Γ_C's line at abscissae `xi`, (M, 2), on the side of pair `pair` (`pairs`; the first by default).
    #[pyo3(signature = (xi, pair = 0))]
    fn contact_points<'py>(&self, py: Python<'py>, xi: &Bound<'_, PyAny>, pair: usize) -> Points<'py> {
        on_side(&self.inner, py, xi, pair, tribo::ContactBoundary::point_at)
    }

    /// The contact normal n at abscissae `xi` of Γ_C, (M, 2): one for a straight side against a gap function;
    /// on a bent side or against an obstacle given by its geometry, each edge's (a node's: its edges' mean). `pair`
    /// as for `contact_points`.
    #[pyo3(signature = (xi, pair = 0))]
    fn contact_normals<'py>(&self, py: Python<'py>, xi: &Bound<'_, PyAny>, pair: usize) -> Points<'py> {
        on_side(&self.inner, py, xi, pair, tribo::ContactBoundary::normal_at)
    }

    /// Values at abscissae `xi` of the multiplier with dof values `values` (P0 or P1 on T_H; the first pair's).
    fn evaluate_multiplier<'py>(
        &self,
        py: Python<'py>,
        values: &Bound<'_, PyAny>,
        xi: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = floats(values, "values", &[Some(self.inner.multipliers.n_dofs())], Settings)?;
        let x = floats(xi, "xi", &[None], ContactGeometry)?;
        Ok(PyArray1::from_vec(py, x.iter().map(|&x| self.inner.multipliers.evaluate(&v, x)).collect()))
    }

    /// The energy norm sqrt(uᵀ K u) of a nodal displacement `u` (N, 2), K of this mesh, material and model.
    fn energy_norm(&self, u: &Bound<'_, PyAny>) -> PyResult<f64> {
        let u = floats(u, "u", &[Some(self.inner.mesh.n_nodes()), Some(2)], Settings)?;
        Ok(tribo::elasticity::energy_norm(self.inner.spec.model, &self.inner.mesh, &self.inner.in_plane, &u))
    }
}
