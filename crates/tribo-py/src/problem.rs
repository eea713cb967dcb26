//! `Obstacle` and `Problem`: the contact problem, its set-up and its solve.

use std::cell::RefCell;
use std::ops::ControlFlow;
use std::sync::Arc;

use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyException, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat};
use tribo::{
    Choice, Friction, FrictionLaw, GapFunction, LoadStep, Material, MultiplierPoints, MultiplierSpace, ObstacleShape,
    Phase, ProblemSpec, Progress, SolverSettings, Stabilization, StepProgress, Threshold,
};

use crate::convert::{floats, mat, rows, setting_value, vec1};
use crate::errors::{geometry_error, settings_error, to_pyerr, ToPyResult};
use crate::history::PyHistory;
use crate::mesh::PyMesh;
use crate::solution::PySolution;
use crate::supports::PySupport;

fn geometry_err(msg: String) -> PyErr {
    geometry_error(msg)
}

fn settings_err(msg: String) -> PyErr {
    settings_error(msg)
}

thread_local! {
    /// The first exception a Python gap function raised during the current core call on this thread,
    /// kept until the call returns. Per thread, so that problems sharing one `Obstacle.function` in two
    /// threads never see each other's exceptions (the core calls the gap function on the caller's thread).
    static GAP_ERROR: RefCell<Option<PyErr>> = const { RefCell::new(None) };
}

/// Takes the exception a gap function raised on this thread, if any.
fn take_gap_error() -> Option<PyErr> {
    GAP_ERROR.with(|slot| slot.borrow_mut().take())
}

/// The shape of a rigid obstacle: the initial gap g0(ξ) ≥ 0 between Γ_C and the obstacle along the
/// outward normal, ξ the abscissa on Γ_C. Build one with `flat`, `circle`, `parabola`, `polyline` or
/// `function`; its motion (approach δ, shift s) is given to `Problem`.
#[pyclass(frozen, name = "Obstacle", module = "tribo")]
pub struct PyObstacle {
    shape: ObstacleShape,
    kind: &'static str,
    repr: String,
}

impl PyObstacle {
    fn checked(shape: ObstacleShape, kind: &'static str, repr: String) -> PyResult<Self> {
        tribo::Obstacle { shape: shape.clone(), ..Default::default() }.validate().py_err()?;
        Ok(Self { shape, kind, repr })
    }

    fn from_callable(f: Py<PyAny>) -> PyResult<Self> {
        let repr = Python::attach(|py| f.bind(py).repr().map(|r| r.to_string()))?;
        // The core calls this during the Γ_C integration (with the GIL released): re-attach for the call.
        // A Python exception or a non-float result becomes NaN, which the core rejects as BadObstacle; the
        // exception itself is kept (per thread) and chained to that error, or re-raised as it is for
        // KeyboardInterrupt and SystemExit.
        let call = move |xi: f64| -> f64 {
            Python::attach(|py| match f.call1(py, (xi,)).and_then(|v| v.extract::<f64>(py)) {
                Ok(g) => g,
                Err(e) => {
                    GAP_ERROR.with(|slot| {
                        slot.borrow_mut().get_or_insert(e);
                    });
                    f64::NAN
                }
            })
        };
        let shape = ObstacleShape::Function(GapFunction(Arc::new(call)));
        Self::checked(shape, "function", format!("Obstacle.function({repr})"))
    }
}

/// The exception to raise for a core error: the gap function's own exception if it was a
/// KeyboardInterrupt or SystemExit (they must propagate unchanged), else `err` with that exception
/// chained as its cause.
fn chain_gap_error(py: Python<'_>, err: PyErr) -> PyErr {
    match take_gap_error() {
        Some(cause) if !cause.is_instance_of::<PyException>(py) => cause,
        Some(cause) => {
            err.set_cause(py, Some(cause));
            err
        }
        None => err,
    }
}

#[pymethods]
impl PyObstacle {
    /// A flat obstacle touching Γ_C: g0 = 0.
    #[staticmethod]
    fn flat() -> PyResult<Self> {
        Self::checked(ObstacleShape::Flat, "flat", "Obstacle.flat()".into())
    }

    /// A rigid cylinder of radius R touching Γ_C at abscissa `center`: g0 = R − √(R² − (ξ − c)²).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn circle(radius: f64, center: f64) -> PyResult<Self> {
        let repr = format!("Obstacle.circle(radius={radius}, center={center})");
        Self::checked(ObstacleShape::Circle { center, radius }, "circle", repr)
    }

    /// The parabolic (Hertz) approximation of a cylinder: g0 = (ξ − c)² / (2R).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn parabola(radius: f64, center: f64) -> PyResult<Self> {
        let repr = format!("Obstacle.parabola(radius={radius}, center={center})");
        Self::checked(ObstacleShape::Parabola { center, radius }, "parabola", repr)
    }

    /// A polyline through (xi[k], gap[k]) (xi strictly increasing), constant beyond its ends.
    #[staticmethod]
    fn polyline(xi: &Bound<'_, PyAny>, gap: &Bound<'_, PyAny>) -> PyResult<Self> {
        let xi = floats(xi, "polyline abscissae", &[None], geometry_err)?;
        let gap = floats(gap, "polyline gaps", &[None], geometry_err)?;
        let repr = format!("Obstacle.polyline(<{} points>)", xi.len());
        Self::checked(ObstacleShape::Polyline { xi, gap }, "polyline", repr)
    }

    /// Any Python callable gap(xi: float) -> float giving g0 at an abscissa of Γ_C. It is called
    /// during the set-up (Γ_C integration) and at the FE nodes of Γ_C after a solve.
    #[staticmethod]
    fn function(gap: &Bound<'_, PyAny>) -> PyResult<Self> {
        if !gap.is_callable() {
            return Err(geometry_error(format!("Obstacle.function needs a callable gap(xi) -> float, got {gap}")));
        }
        Self::from_callable(gap.clone().unbind())
    }

    /// 'flat', 'circle', 'parabola', 'polyline' or 'function'.
    #[getter]
    fn kind(&self) -> &'static str {
        self.kind
    }

    /// The radius R of a circle or a parabola (its curvature radius), else None.
    #[getter]
    fn radius(&self) -> Option<f64> {
        match &self.shape {
            ObstacleShape::Circle { radius, .. } | ObstacleShape::Parabola { radius, .. } => Some(*radius),
            _ => None,
        }
    }

    /// The abscissa of the lowest point of a circle or a parabola, else None.
    #[getter]
    fn center(&self) -> Option<f64> {
        match &self.shape {
            ObstacleShape::Circle { center, .. } | ObstacleShape::Parabola { center, .. } => Some(*center),
            _ => None,
        }
    }

    /// The initial gap g0 at abscissae `xi` (a float or an array of floats).
    fn gap0<'py>(&self, py: Python<'py>, xi: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let o = tribo::Obstacle { shape: self.shape.clone(), ..Default::default() };
        take_gap_error();
        let ndim: usize = py.import("numpy")?.call_method1("ndim", (xi,))?.extract()?;
        let out = if ndim == 0 {
            let x = floats(xi, "xi", &[], geometry_err)?;
            PyFloat::new(py, o.initial_gap(x[0])).into_any()
        } else {
            let x = floats(xi, "xi", &[None], geometry_err)?;
            PyArray1::from_vec(py, x.iter().map(|&x| o.initial_gap(x)).collect()).into_any()
        };
        match take_gap_error() {
            Some(e) => Err(e),
            None => Ok(out),
        }
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }
}

/// A contact problem, validated and assembled once (independent of γ0 and friction). It keeps the
/// factorization of its last solve, reused by the next solve with the same γ0.
#[pyclass(frozen, name = "Problem", module = "tribo")]
pub struct PyProblem {
    inner: tribo::Problem,
    mesh: Py<PyMesh>,
    obstacle: Py<PyObstacle>,
}

/// `supports=`: a Support or a sequence of them.
fn support_list(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<tribo::Support>> {
    let Some(obj) = obj else { return Ok(Vec::new()) };
    if let Ok(s) = obj.cast::<PySupport>() {
        return Ok(vec![s.get().inner.clone()]);
    }
    let bad = || settings_error(format!("supports must be a tribo.Support or a list of them, got {obj}"));
    if obj.extract::<String>().is_ok() {
        return Err(bad());
    }
    let mut out = Vec::new();
    for item in obj.try_iter().map_err(|_| bad())? {
        let item = item?;
        out.push(item.cast::<PySupport>().map_err(|_| bad())?.get().inner.clone());
    }
    Ok(out)
}

fn names(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<String>> {
    if let Ok(s) = obj.extract::<String>() {
        return Ok(vec![s]);
    }
    obj.extract::<Vec<String>>()
        .map_err(|_| settings_error(format!("{what} must be an edge set name or a list of names, got {obj}")))
}

fn vec2(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<[f64; 2]> {
    let v = floats(obj, what, &[Some(2)], settings_err)?;
    Ok([v[0], v[1]])
}

/// Calls the progress callback (if any) with `args` and checks for Ctrl-C: `Break` when the callback
/// returned False, raised (kept in `error`, re-raised by the caller) or Ctrl-C was pressed.
fn observe_with<A: for<'py> pyo3::call::PyCallArgs<'py>>(
    progress: Option<&Py<PyAny>>,
    args: A,
    error: &mut Option<PyErr>,
) -> ControlFlow<()> {
    Python::attach(|py| {
        let stop = match progress {
            Some(f) => match f.call1(py, args) {
                Ok(r) => r.bind(py).is(pyo3::types::PyBool::new(py, false)),
                Err(e) => {
                    *error = Some(e);
                    true
                }
            },
            None => false,
        };
        if let Err(e) = py.check_signals() {
            error.get_or_insert(e);
        }
        if stop || error.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })
}

/// The solve's keywords as core values: the friction law, γ0 and the settings table.
fn solve_arguments(
    friction: Option<&str>,
    mu: Option<f64>,
    threshold: Option<&Bound<'_, PyAny>>,
    stabilization: (Option<f64>, Option<f64>, bool),
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<(Friction, SolverSettings)> {
    let threshold = match threshold {
        None => None,
        Some(t) => Some(match t.extract::<f64>() {
            Ok(s) => Threshold::Uniform(s),
            Err(_) => Threshold::PerDof(floats(t, "threshold", &[None], settings_err)?),
        }),
    };
    let law = friction.map(FrictionLaw::parse).transpose().py_err()?;
    let friction = Friction::from_keywords(law, mu, threshold).py_err()?;
    let (gamma0, fraction, checked) = stabilization;
    let mut s = SolverSettings {
        stabilization: Stabilization::from_keywords(gamma0, fraction, checked).py_err()?,
        ..Default::default()
    };
    for (key, value) in settings.into_iter().flat_map(|d| d.iter()) {
        let name: String = key.extract()?;
        match s.set(&name, setting_value(&value, &name)?) {
            Err(tribo::Error::UnknownSetting { known, .. }) => {
                return Err(PyTypeError::new_err(format!(
                    "Problem.solve() got an unexpected keyword argument '{name}' (solver settings: {known})"
                )));
            }
            other => other.py_err()?,
        }
    }
    Ok((friction, s))
}

#[pymethods]
impl PyProblem {
    #[new]
    #[pyo3(signature = (
        mesh, *, young, poisson, contact, clamped = None, supports = None, obstacle = None, approach = None, shift = None,
        tractions = None, body_force = None, multiplier_ratio = None, multiplier_size = None,
        multiplier_points = None, space = None,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        mesh: Py<PyMesh>,
        young: f64,
        poisson: f64,
        contact: String,
        clamped: Option<&Bound<'_, PyAny>>,
        supports: Option<&Bound<'_, PyAny>>,
        obstacle: Option<&Bound<'_, PyAny>>,
        approach: Option<f64>,
        shift: Option<f64>,
        tractions: Option<&Bound<'_, PyAny>>,
        body_force: Option<&Bound<'_, PyAny>>,
        multiplier_ratio: Option<f64>,
        multiplier_size: Option<f64>,
        multiplier_points: Option<&Bound<'_, PyAny>>,
        space: Option<&str>,
    ) -> PyResult<Self> {
        let obstacle: Py<PyObstacle> = match obstacle {
            None => Py::new(py, PyObstacle::flat()?)?,
            Some(o) => match o.cast::<PyObstacle>() {
                Ok(o) => o.clone().unbind(),
                Err(_) if o.is_callable() => Py::new(py, PyObstacle::from_callable(o.clone().unbind())?)?,
                Err(_) => {
                    return Err(geometry_error(format!(
                        "obstacle must be a tribo.Obstacle or a callable gap(xi) -> float, got {o}"
                    )))
                }
            },
        };
        let defaults = tribo::Obstacle::default();
        let obs = obstacle.get();
        let spec_obstacle = tribo::Obstacle {
            shape: obs.shape.clone(),
            approach: approach.unwrap_or(defaults.approach),
            shift: shift.unwrap_or(defaults.shift),
        };
        let mut trac = Vec::new();
        if let Some(t) = tractions {
            let d = t
                .cast::<PyDict>()
                .map_err(|_| settings_error(format!("tractions must be a dict edge set -> (tx, ty), got {t}")))?;
            for (k, v) in d.iter() {
                let name: String = k
                    .extract()
                    .map_err(|_| settings_error(format!("traction keys must be edge set names, got {k}")))?;
                let g = vec2(&v, &format!("traction on '{name}'"))?;
                trac.push((name, g));
            }
        }
        let body_force = match body_force {
            Some(b) => vec2(b, "body_force")?,
            None => [0.0, 0.0],
        };
        let given = [multiplier_ratio.is_some(), multiplier_size.is_some(), multiplier_points.is_some()];
        if given.iter().filter(|g| **g).count() > 1 {
            return Err(geometry_error(
                "give at most one of multiplier_ratio (H/h), multiplier_size (H) and multiplier_points",
            ));
        }
        let points = if let Some(r) = multiplier_ratio {
            MultiplierPoints::RatioToFe(r)
        } else if let Some(h) = multiplier_size {
            MultiplierPoints::Size(h)
        } else if let Some(p) = multiplier_points {
            let ndim: usize = py.import("numpy")?.call_method1("ndim", (p,))?.extract()?;
            if ndim == 2 {
                MultiplierPoints::Points(rows::<f64, 2>(&floats(
                    p,
                    "multiplier_points",
                    &[None, Some(2)],
                    geometry_err,
                )?))
            } else {
                MultiplierPoints::Abscissae(floats(p, "multiplier_points", &[None], geometry_err)?)
            }
        } else {
            MultiplierPoints::default()
        };
        let spec = ProblemSpec {
            material: Material { young, poisson },
            clamped: clamped.map_or(Ok(Vec::new()), |c| names(c, "clamped"))?,
            supports: support_list(supports)?,
            body_force,
            tractions: trac,
            contact,
            obstacle: spec_obstacle,
            multiplier_points: points,
            multiplier_space: space.map_or(Ok(MultiplierSpace::default()), MultiplierSpace::parse).py_err()?,
        };
        let mesh_inner = mesh.get().inner.clone();
        take_gap_error();
        let inner =
            py.detach(|| tribo::Problem::new(mesh_inner, spec)).map_err(|e| chain_gap_error(py, to_pyerr(e)))?;
        Ok(Self { inner, mesh, obstacle })
    }

    /// Solves the problem; returns a Solution whose `report.status` says how the solve ended.
    ///
    /// The friction law is `friction` ('frictionless', 'tresca' or 'coulomb'), or, when None, inferred:
    /// `mu` given → Coulomb (mu = 0 is frictionless), `threshold` given → Tresca, neither → frictionless.
    /// γ0 is `gamma0`, or `gamma0_fraction` × the admissible bound, or the core's default;
    /// `check_gamma0=False` takes an explicit `gamma0` even at or above the admissible bound (for studies
    /// of what happens there; the factorization may then fail with SolverError). Every other keyword is
    /// a solver setting by its name in `solver_defaults()` (qp_tol, qp_max_iter, qp_kkt_solver,
    /// qp_working_set, fp_tol, fp_max_iter, fp_relaxation); unset ones take the core's defaults.
    /// `progress`, if given, is called as progress(iteration, change, qp_iterations, qp_seconds) after
    /// every QP; returning False stops the solve (status 'interrupted', with the last iterate), raising
    /// stops it and propagates. `on_phase`, if given, is called as on_phase(phase, seconds) when a phase
    /// before the QPs ends: 'condensation' (A = K − G factorized or reused, c and possibly all of H
    /// formed; `seconds` is its wall time so far); False or an exception stops the solve the same way,
    /// before any QP. Ctrl-C is honoured after the condensation and between QPs.
    #[pyo3(signature = (
        *, friction = None, mu = None, threshold = None, gamma0 = None, gamma0_fraction = None,
        check_gamma0 = true, progress = None, on_phase = None, **settings,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        friction: Option<&str>,
        mu: Option<f64>,
        threshold: Option<&Bound<'_, PyAny>>,
        gamma0: Option<f64>,
        gamma0_fraction: Option<f64>,
        check_gamma0: bool,
        progress: Option<Py<PyAny>>,
        on_phase: Option<Py<PyAny>>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PySolution> {
        let (law, settings) =
            solve_arguments(friction, mu, threshold, (gamma0, gamma0_fraction, check_gamma0), settings)?;
        if let Some(p) = &progress {
            if !p.bind(py).is_callable() {
                return Err(settings_error(
                    "progress must be a callable (iteration, change, qp_iterations, qp_seconds)",
                ));
            }
        }
        if let Some(p) = &on_phase {
            if !p.bind(py).is_callable() {
                return Err(settings_error("on_phase must be a callable (phase, seconds)"));
            }
        }
        let mut callback_error: Option<PyErr> = None;
        let problem = &self.inner;
        let result = py.detach(|| {
            // After every QP: the progress callback (False stops the solve, an exception stops it and is
            // re-raised below) and Ctrl-C.
            let mut observe = |p: &Progress| {
                let call = match p.phase {
                    Phase::Condensation => (on_phase.as_ref(), None),
                    _ => (progress.as_ref(), Some((p.iteration, p.change, p.qp_iterations, p.qp_seconds))),
                };
                match call {
                    (f, None) => observe_with(f, ("condensation", p.condensation_seconds), &mut callback_error),
                    (f, Some(args)) => observe_with(f, args, &mut callback_error),
                }
            };
            problem.solve(&law, &settings, Some(&mut observe))
        });
        let solution = result.map_err(to_pyerr)?;
        if let Some(e) = callback_error {
            return Err(e);
        }
        PySolution::new(solution)
    }

    /// Solves a quasi-static loading history from rest on one factorization; returns a History.
    ///
    /// Step k moves the obstacle to approach `approach[k]` and tangential position `shift[k]` (totals,
    /// not increments; a scalar is the same at every step) under `load_factor[k]` × the body force and
    /// tractions (default 1). Coulomb's law acts on the slip increment relative to the obstacle, so the
    /// answer depends on the path; a history of one step is the static `solve`. The friction, γ0 and
    /// settings keywords are those of `solve`. `progress`, if given, is called as
    /// progress(step, steps, status, seconds) after every step; returning False ends the history there
    /// (status 'interrupted', the steps done kept), raising ends it and propagates. Ctrl-C is honoured
    /// between steps. A step that does not converge ends the history with its status; `History.failed`
    /// holds its last iterate.
    #[pyo3(signature = (
        approach, shift, load_factor = None, *, friction = None, mu = None, threshold = None, gamma0 = None,
        gamma0_fraction = None, check_gamma0 = true, progress = None, **settings,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn solve_history(
        &self,
        py: Python<'_>,
        approach: &Bound<'_, PyAny>,
        shift: &Bound<'_, PyAny>,
        load_factor: Option<&Bound<'_, PyAny>>,
        friction: Option<&str>,
        mu: Option<f64>,
        threshold: Option<&Bound<'_, PyAny>>,
        gamma0: Option<f64>,
        gamma0_fraction: Option<f64>,
        check_gamma0: bool,
        progress: Option<Py<PyAny>>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyHistory> {
        let (law, settings) =
            solve_arguments(friction, mu, threshold, (gamma0, gamma0_fraction, check_gamma0), settings)?;
        let one = |obj: &Bound<'_, PyAny>, what: &str| -> PyResult<Vec<f64>> {
            match obj.extract::<f64>() {
                Ok(v) => Ok(vec![v]),
                Err(_) => floats(obj, what, &[None], settings_err),
            }
        };
        let columns = [
            one(approach, "approach")?,
            one(shift, "shift")?,
            load_factor.map_or(Ok(vec![1.0]), |l| one(l, "load_factor"))?,
        ];
        let n = columns.iter().map(Vec::len).max().unwrap_or(0);
        if let Some(what) = columns.iter().zip(["approach", "shift", "load_factor"]).find(|(c, _)| c.is_empty()) {
            return Err(settings_error(format!("a history needs at least one step ({} has no value)", what.1)));
        }
        for (c, what) in columns.iter().zip(["approach", "shift", "load_factor"]) {
            if c.len() != 1 && c.len() != n {
                return Err(settings_error(format!(
                    "{what} has {} values, but the history has {n} steps (give one value, or one per step)",
                    c.len()
                )));
            }
        }
        let at = |c: &Vec<f64>, k: usize| if c.len() == 1 { c[0] } else { c[k] };
        let steps: Vec<LoadStep> = (0..n)
            .map(|k| LoadStep {
                approach: at(&columns[0], k),
                shift: at(&columns[1], k),
                load_factor: at(&columns[2], k),
            })
            .collect();
        if let Some(p) = &progress {
            if !p.bind(py).is_callable() {
                return Err(settings_error("progress must be a callable (step, steps, status, seconds)"));
            }
        }
        let mut callback_error: Option<PyErr> = None;
        let problem = &self.inner;
        let result = py.detach(|| {
            let mut observe = |p: &StepProgress| {
                let args = (p.step, p.steps, p.status.name(), p.seconds);
                observe_with(progress.as_ref(), args, &mut callback_error)
            };
            problem.solve_history(&law, &steps, &settings, Some(&mut observe))
        });
        let history = result.map_err(to_pyerr)?;
        if let Some(e) = callback_error {
            return Err(e);
        }
        PyHistory::new(py, history)
    }

    /// The mesh.
    #[getter]
    fn mesh(&self, py: Python<'_>) -> Py<PyMesh> {
        self.mesh.clone_ref(py)
    }

    /// The obstacle shape.
    #[getter]
    fn obstacle(&self, py: Python<'_>) -> Py<PyObstacle> {
        self.obstacle.clone_ref(py)
    }

    /// Normal approach δ of the obstacle.
    #[getter]
    fn approach(&self) -> f64 {
        self.inner.spec.obstacle.approach
    }

    /// Tangential shift s of the obstacle.
    #[getter]
    fn shift(&self) -> f64 {
        self.inner.spec.obstacle.shift
    }

    /// Young's modulus E.
    #[getter]
    fn young(&self) -> f64 {
        self.inner.spec.material.young
    }

    /// Poisson's ratio ν.
    #[getter]
    fn poisson(&self) -> f64 {
        self.inner.spec.material.poisson
    }

    /// Name of the contact edge set.
    #[getter]
    fn contact(&self) -> String {
        self.inner.spec.contact.clone()
    }

    /// Names of the clamped edge sets.
    #[getter]
    fn clamped(&self) -> Vec<String> {
        self.inner.spec.clamped.clone()
    }

    /// The supports given besides `clamped` (rollers, prescribed displacements, clamps).
    #[getter]
    fn supports(&self) -> Vec<PySupport> {
        self.inner.spec.supports.iter().map(|s| PySupport { inner: s.clone() }).collect()
    }

    /// Multiplier space, 'P0' or 'P1'.
    #[getter]
    fn space(&self) -> &'static str {
        self.inner.multipliers.space.as_str()
    }

    /// Number of free displacement dofs.
    #[getter]
    fn n_free(&self) -> usize {
        self.inner.n_free
    }

    /// Number of multiplier dofs q (per component).
    #[getter]
    fn n_multipliers(&self) -> usize {
        self.inner.n_multipliers()
    }

    /// The admissible bound on γ0 (K − G stays positive definite below it).
    #[getter]
    fn gamma0_bound(&self) -> f64 {
        self.inner.gamma0_bound.value
    }

    /// The triangle that sets the admissible bound on γ0.
    #[getter]
    fn gamma0_bound_element(&self) -> usize {
        self.inner.gamma0_bound.triangle
    }

    /// Outward unit normal n on Γ_C.
    #[getter]
    fn contact_normal(&self) -> (f64, f64) {
        let n = self.inner.contact.normal;
        (n[0], n[1])
    }

    /// Tangent t = (−n₂, n₁) on Γ_C (tangential quantities are components along t).
    #[getter]
    fn contact_tangent(&self) -> (f64, f64) {
        let t = self.inner.contact.tangent;
        (t[0], t[1])
    }

    /// d · t = ±1: +1 when the abscissa ξ increases along t.
    #[getter]
    fn tangent_sign(&self) -> f64 {
        self.inner.contact.tangent_sign()
    }

    /// FE nodes of Γ_C by increasing abscissa, (n_c,) int64.
    #[getter]
    fn contact_nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_vec(py, self.inner.contact.nodes.iter().map(|&n| n as i64).collect())
    }

    /// Abscissae of the FE nodes of Γ_C (in the order of `contact_nodes`).
    #[getter]
    fn node_abscissae<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.contact.node_xi)
    }

    /// FE edges of Γ_C by increasing abscissa, (n_c − 1, 2) int64 (left, right node).
    #[getter]
    fn contact_edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let e: Vec<[i64; 2]> = self.inner.contact.edges.iter().map(|e| [e.left as i64, e.right as i64]).collect();
        mat(py, &e)
    }

    /// Points x_0 < … < x_N of the multiplier mesh T_H (abscissae).
    #[getter]
    fn multiplier_mesh<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.multipliers.xi)
    }

    /// Abscissae of the multiplier dofs (segment midpoints for P0, points for P1).
    #[getter]
    fn multiplier_abscissae<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.multipliers.dof_abscissae())
    }

    /// Points of Γ_C's line at abscissae `xi`, (M, 2).
    fn contact_points<'py>(&self, py: Python<'py>, xi: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = floats(xi, "xi", &[None], geometry_err)?;
        let p: Vec<[f64; 2]> = x.iter().map(|&x| self.inner.contact.point_at(x)).collect();
        Ok(mat(py, &p))
    }

    /// Values at abscissae `xi` of the multiplier with dof values `values` (P0 or P1 on T_H).
    fn evaluate_multiplier<'py>(
        &self,
        py: Python<'py>,
        values: &Bound<'py, PyAny>,
        xi: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = self.inner.n_multipliers();
        let v = floats(values, "values", &[Some(q)], settings_err)?;
        let x = floats(xi, "xi", &[None], geometry_err)?;
        Ok(PyArray1::from_vec(py, x.iter().map(|&x| self.inner.multipliers.evaluate(&v, x)).collect()))
    }

    /// The elastic energy norm sqrt(uᵀ K u) of a nodal displacement `u` (N, 2) on this problem's mesh and
    /// material (K without supports), element by element.
    fn energy_norm(&self, u: &Bound<'_, PyAny>) -> PyResult<f64> {
        let n = self.inner.mesh.n_nodes();
        let u = floats(u, "u", &[Some(n), Some(2)], settings_err)?;
        Ok(tribo::elasticity::energy_norm(&self.inner.mesh, &self.inner.spec.material, &u))
    }

    /// Set-up wall times in seconds: {'assembly', 'contact_matrices'}.
    #[getter]
    fn setup_timings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("assembly", self.inner.timings.assembly)?;
        d.set_item("contact_matrices", self.inner.timings.contact_matrices)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Problem(n_free={}, n_multipliers={}, space='{}', contact='{}', gamma0_bound={})",
            self.inner.n_free,
            self.inner.n_multipliers(),
            self.inner.multipliers.space,
            self.inner.spec.contact,
            tribo::Num(self.inner.gamma0_bound.value)
        )
    }
}
