//! `Obstacle` and `Problem`: the contact problem, its set-up and its solve.

use std::sync::{Arc, Mutex};

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat};
use tribo::stabilization::resolve_gamma0;
use tribo::{
    Condensed, Friction, GapFunction, KktSolver, Material, MultiplierPoints, MultiplierSpace, ObstacleShape,
    ProblemSpec, Progress, SolverSettings, Stabilization, Threshold,
};

use crate::convert::{floats, mat, rows, vec1};
use crate::errors::{geometry_error, settings_error, IntoPy};
use crate::mesh::PyMesh;
use crate::solution::PySolution;

fn geometry_err(msg: String) -> PyErr {
    geometry_error(msg)
}

fn settings_err(msg: String) -> PyErr {
    settings_error(msg)
}

/// The first exception raised by a Python gap function, kept until the core call returns.
type ErrorSlot = Arc<Mutex<Option<PyErr>>>;

/// The shape of a rigid obstacle: the initial gap g0(ξ) ≥ 0 between Γ_C and the obstacle along the
/// outward normal, ξ the abscissa on Γ_C. Build one with `flat`, `circle`, `parabola`, `polyline` or
/// `function`; its motion (approach δ, shift s) is given to `Problem`.
#[pyclass(frozen, name = "Obstacle", module = "tribo")]
pub struct PyObstacle {
    shape: ObstacleShape,
    kind: &'static str,
    repr: String,
    /// Where a Python gap function leaves its exception (None for the built-in shapes).
    slot: Option<ErrorSlot>,
}

impl PyObstacle {
    fn checked(shape: ObstacleShape, kind: &'static str, repr: String, slot: Option<ErrorSlot>) -> PyResult<Self> {
        tribo::Obstacle { shape: shape.clone(), ..Default::default() }.validate().py_err()?;
        Ok(Self { shape, kind, repr, slot })
    }

    fn from_callable(f: Py<PyAny>) -> PyResult<Self> {
        let slot: ErrorSlot = Arc::new(Mutex::new(None));
        let inner_slot = slot.clone();
        let repr = Python::attach(|py| f.bind(py).repr().map(|r| r.to_string()))?;
        // The core calls this during the Γ_C integration (with the GIL released): re-attach for the call.
        // A Python exception or a non-float result becomes NaN, which the core rejects as BadObstacle; the
        // exception itself is kept and chained to that error.
        let call = move |xi: f64| -> f64 {
            Python::attach(|py| match f.call1(py, (xi,)).and_then(|v| v.extract::<f64>(py)) {
                Ok(g) => g,
                Err(e) => {
                    if let Ok(mut s) = inner_slot.lock() {
                        s.get_or_insert(e);
                    }
                    f64::NAN
                }
            })
        };
        let shape = ObstacleShape::Function(GapFunction(Arc::new(call)));
        Self::checked(shape, "function", format!("Obstacle.function({repr})"), Some(slot))
    }
}

/// Takes the exception a Python gap function raised, if any, and chains it to `err`.
fn chain_gap_error(py: Python<'_>, slot: &Option<ErrorSlot>, err: PyErr) -> PyErr {
    if let Some(cause) = slot.as_ref().and_then(|s| s.lock().ok().and_then(|mut s| s.take())) {
        err.set_cause(py, Some(cause));
    }
    err
}

#[pymethods]
impl PyObstacle {
    /// A flat obstacle touching Γ_C: g0 = 0.
    #[staticmethod]
    fn flat() -> PyResult<Self> {
        Self::checked(ObstacleShape::Flat, "flat", "Obstacle.flat()".into(), None)
    }

    /// A rigid cylinder of radius R touching Γ_C at abscissa `center`: g0 = R − √(R² − (ξ − c)²).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn circle(radius: f64, center: f64) -> PyResult<Self> {
        let repr = format!("Obstacle.circle(radius={radius}, center={center})");
        Self::checked(ObstacleShape::Circle { center, radius }, "circle", repr, None)
    }

    /// The parabolic (Hertz) approximation of a cylinder: g0 = (ξ − c)² / (2R).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn parabola(radius: f64, center: f64) -> PyResult<Self> {
        let repr = format!("Obstacle.parabola(radius={radius}, center={center})");
        Self::checked(ObstacleShape::Parabola { center, radius }, "parabola", repr, None)
    }

    /// A polyline through (xi[k], gap[k]) (xi strictly increasing), constant beyond its ends.
    #[staticmethod]
    fn polyline(xi: &Bound<'_, PyAny>, gap: &Bound<'_, PyAny>) -> PyResult<Self> {
        let xi = floats(xi, "polyline abscissae", &[None], geometry_err)?;
        let gap = floats(gap, "polyline gaps", &[None], geometry_err)?;
        let repr = format!("Obstacle.polyline(<{} points>)", xi.len());
        Self::checked(ObstacleShape::Polyline { xi, gap }, "polyline", repr, None)
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

    /// The initial gap g0 at abscissae `xi` (a float or an array of floats).
    fn gap0<'py>(&self, py: Python<'py>, xi: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let o = tribo::Obstacle { shape: self.shape.clone(), ..Default::default() };
        let take = || self.slot.as_ref().and_then(|s| s.lock().ok().and_then(|mut s| s.take()));
        let ndim: usize = py.import("numpy")?.call_method1("ndim", (xi,))?.extract()?;
        let out = if ndim == 0 {
            let x = floats(xi, "xi", &[], geometry_err)?;
            PyFloat::new(py, o.initial_gap(x[0])).into_any()
        } else {
            let x = floats(xi, "xi", &[None], geometry_err)?;
            PyArray1::from_vec(py, x.iter().map(|&x| o.initial_gap(x)).collect()).into_any()
        };
        match take() {
            Some(e) => Err(e),
            None => Ok(out),
        }
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }
}

/// A contact problem, validated and assembled once (independent of γ0 and friction).
#[pyclass(frozen, name = "Problem", module = "tribo")]
pub struct PyProblem {
    inner: tribo::Problem,
    mesh: Py<PyMesh>,
    obstacle: Py<PyObstacle>,
    slot: Option<ErrorSlot>,
    /// The last condensed system: reused by a later solve with the same γ0.
    condensed: Mutex<Option<Arc<Condensed>>>,
}

fn parse_space(space: Option<&str>) -> PyResult<MultiplierSpace> {
    match space {
        None => Ok(MultiplierSpace::default()),
        Some("P0" | "p0") => Ok(MultiplierSpace::P0),
        Some("P1" | "p1") => Ok(MultiplierSpace::P1),
        Some(s) => Err(geometry_error(format!("space must be 'P0' or 'P1', got '{s}'"))),
    }
}

pub fn space_name(s: MultiplierSpace) -> &'static str {
    match s {
        MultiplierSpace::P0 => "P0",
        MultiplierSpace::P1 => "P1",
    }
}

pub fn kkt_solver_name(s: KktSolver) -> &'static str {
    match s {
        KktSolver::Qdldl => "qdldl",
        KktSolver::Faer => "faer",
    }
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

#[pymethods]
impl PyProblem {
    #[new]
    #[pyo3(signature = (
        mesh, *, young, poisson, clamped, contact, obstacle = None, approach = None, shift = None,
        tractions = None, body_force = None, multiplier_ratio = None, multiplier_size = None,
        multiplier_points = None, space = None,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        mesh: Py<PyMesh>,
        young: f64,
        poisson: f64,
        clamped: &Bound<'_, PyAny>,
        contact: String,
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
            clamped: names(clamped, "clamped")?,
            body_force,
            tractions: trac,
            contact,
            obstacle: spec_obstacle,
            multiplier_points: points,
            multiplier_space: parse_space(space)?,
        };
        let mesh_inner = mesh.get().inner.clone();
        let slot = obs.slot.clone();
        let inner = py
            .detach(|| tribo::Problem::new(mesh_inner, spec))
            .map_err(|e| chain_gap_error(py, &slot, crate::errors::to_pyerr(e)))?;
        Ok(Self { inner, mesh, obstacle, slot, condensed: Mutex::new(None) })
    }

    /// Solves the problem; returns a Solution whose `report.status` says how the solve ended.
    ///
    /// The friction law is `friction` ('frictionless', 'tresca' or 'coulomb'), or, when None, inferred:
    /// `mu` given → Coulomb (mu = 0 is frictionless), `threshold` given → Tresca, neither → frictionless.
    /// γ0 is `gamma0`, or `gamma0_fraction` × the admissible bound, or the core's default. Every other
    /// setting left at None takes the core's default (see `solver_defaults()`); `working_set=False`
    /// solves every QP over all of Γ_C instead of over the dofs that can be in contact. `progress`, if given,
    /// is called as progress(iteration, change, qp_iterations, qp_seconds) after every QP.
    /// `check_gamma0=False` takes an explicit `gamma0` even at or above the admissible bound (for
    /// studies of what happens there; the factorization then may fail with SolverError).
    #[pyo3(signature = (
        *, friction = None, mu = None, threshold = None, gamma0 = None, gamma0_fraction = None,
        qp_tol = None, qp_max_iter = None, kkt_solver = None, working_set = None, fp_tol = None,
        fp_max_iter = None, relaxation = None, progress = None, check_gamma0 = true,
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
        qp_tol: Option<f64>,
        qp_max_iter: Option<u32>,
        kkt_solver: Option<&str>,
        working_set: Option<bool>,
        fp_tol: Option<f64>,
        fp_max_iter: Option<usize>,
        relaxation: Option<f64>,
        progress: Option<Py<PyAny>>,
        check_gamma0: bool,
    ) -> PyResult<PySolution> {
        let threshold = match threshold {
            None => None,
            Some(t) => Some(match t.extract::<f64>() {
                Ok(s) => Threshold::Uniform(s),
                Err(_) => Threshold::PerDof(floats(t, "threshold", &[None], settings_err)?),
            }),
        };
        let law = match (friction, mu, threshold) {
            (_, Some(_), Some(_)) => {
                return Err(settings_error("give mu (Coulomb) or threshold (Tresca), not both"));
            }
            (None | Some("coulomb"), Some(mu), None) => Friction::Coulomb { mu },
            (None | Some("tresca"), None, Some(t)) => Friction::Tresca(t),
            (None | Some("frictionless"), None, None) => Friction::Frictionless,
            (Some("coulomb"), None, _) => return Err(settings_error("friction='coulomb' needs mu")),
            (Some("tresca"), _, None) => return Err(settings_error("friction='tresca' needs threshold")),
            (Some("frictionless"), _, _) => {
                return Err(settings_error("friction='frictionless' takes neither mu nor threshold"))
            }
            (Some(f), _, _) => {
                return Err(settings_error(format!(
                    "friction must be 'frictionless', 'tresca' or 'coulomb', got '{f}'"
                )))
            }
        };
        let mut settings = SolverSettings::default();
        settings.stabilization = match (gamma0, gamma0_fraction) {
            (Some(_), Some(_)) => return Err(settings_error("give gamma0 or gamma0_fraction, not both")),
            (Some(g), None) => Stabilization::Gamma0(g),
            (None, Some(f)) => Stabilization::Fraction(f),
            (None, None) => settings.stabilization,
        };
        if let Some(t) = qp_tol {
            settings.qp.tol = t;
        }
        if let Some(m) = qp_max_iter {
            settings.qp.max_iter = m;
        }
        settings.qp.kkt_solver = match kkt_solver {
            None => settings.qp.kkt_solver,
            Some("faer") => KktSolver::Faer,
            Some("qdldl") => KktSolver::Qdldl,
            Some(k) => return Err(settings_error(format!("kkt_solver must be 'faer' or 'qdldl', got '{k}'"))),
        };
        if let Some(w) = working_set {
            settings.qp.working_set = w;
        }
        if let Some(t) = fp_tol {
            settings.fixed_point.tol_change_rel = t;
        }
        if let Some(m) = fp_max_iter {
            settings.fixed_point.max_iter = m;
        }
        if let Some(w) = relaxation {
            settings.fixed_point.relaxation = w;
        }
        if let Some(p) = &progress {
            if !p.bind(py).is_callable() {
                return Err(settings_error(
                    "progress must be a callable (iteration, change, qp_iterations, qp_seconds)",
                ));
            }
        }
        settings.validate().py_err()?;
        law.validate().py_err()?;
        let (bound, element) = self.inner.gamma0_bound;
        let g0 = match (check_gamma0, settings.stabilization) {
            // Studies beyond the admissible bound: γ0 is taken as given, the factorization may fail.
            (false, Stabilization::Gamma0(g)) if g.is_finite() && g >= 0.0 => g,
            _ => resolve_gamma0(settings.stabilization, bound, element).py_err()?,
        };

        let cached = self.condensed.lock().ok().and_then(|c| c.clone()).filter(|c| c.gamma0 == g0);
        let reused = cached.is_some();
        let mut callback_error: Option<PyErr> = None;
        let problem = &self.inner;
        let result = py.detach(|| -> tribo::Result<(Arc<Condensed>, tribo::Solution)> {
            let condensed = match cached {
                Some(c) => c,
                None => Arc::new(Condensed::with_gamma0(problem, g0)?),
            };
            // A callback that raises (or Ctrl-C) stops the solve; the exception is re-raised below.
            let mut report = |p: &Progress| {
                if let Some(f) = &progress {
                    Python::attach(|py| {
                        let r = f.call1(py, (p.iteration, p.change, p.qp_iterations, p.qp_seconds));
                        if let Err(e) = r.and_then(|_| py.check_signals()) {
                            callback_error = Some(e);
                        }
                    });
                }
                if callback_error.is_some() {
                    std::ops::ControlFlow::Break(())
                } else {
                    std::ops::ControlFlow::Continue(())
                }
            };
            let observer: Option<tribo::Observer<'_>> = if progress.is_some() { Some(&mut report) } else { None };
            let solution = condensed.solve(problem, &law, &settings, observer)?;
            Ok((condensed, solution))
        });
        let (condensed, solution) = result.map_err(|e| chain_gap_error(py, &self.slot, crate::errors::to_pyerr(e)))?;
        if let Ok(mut c) = self.condensed.lock() {
            *c = Some(condensed);
        }
        if let Some(e) = callback_error {
            return Err(e);
        }
        if let Some(e) = self.slot.as_ref().and_then(|s| s.lock().ok().and_then(|mut s| s.take())) {
            let err = geometry_error("the gap function raised while the gap was evaluated at the nodes of Γ_C");
            err.set_cause(py, Some(e));
            return Err(err);
        }
        let (friction_name, mu) = match &law {
            Friction::Frictionless | Friction::Coulomb { mu: 0.0 } => ("frictionless", None),
            Friction::Tresca(_) => ("tresca", None),
            Friction::Coulomb { mu } => ("coulomb", Some(*mu)),
        };
        PySolution::new(solution, friction_name, mu, reused)
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

    /// Multiplier space, 'P0' or 'P1'.
    #[getter]
    fn space(&self) -> &'static str {
        space_name(self.inner.multipliers.space)
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
        self.inner.gamma0_bound.0
    }

    /// The triangle that sets the admissible bound on γ0.
    #[getter]
    fn gamma0_bound_element(&self) -> usize {
        self.inner.gamma0_bound.1
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
            "Problem(n_free={}, n_multipliers={}, space='{}', contact='{}', gamma0_bound={:e})",
            self.inner.n_free,
            self.inner.n_multipliers(),
            space_name(self.inner.multipliers.space),
            self.inner.spec.contact,
            self.inner.gamma0_bound.0
        )
    }
}
