//! `Obstacle`: the shape of a rigid obstacle, and the channel that carries a Python gap function's
//! exception through the core.

use std::cell::RefCell;
use std::sync::Arc;

use numpy::PyArray1;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyTuple};
use tribo::error::ErrorCategory::ContactGeometry;
use tribo::{DistanceFunction, GapFunction, ObstacleShape};

use crate::convert::{callback, floats};
use crate::errors::to_pyerr;

thread_local! {
    /// The first exception a gap function raised in the current core call on this thread (the core calls it on
    /// the caller's thread), kept until the call returns: per thread, so that threads never see each other's.
    static GAP_ERROR: RefCell<Option<PyErr>> = const { RefCell::new(None) };
}

/// Takes the exception a gap function raised on this thread, if any.
pub fn take_gap_error() -> Option<PyErr> {
    GAP_ERROR.with(|slot| slot.borrow_mut().take())
}

/// The exception to raise for a core error: the gap function's own exception if it was a KeyboardInterrupt
/// or SystemExit (they must propagate unchanged), else `err` with that exception chained as its cause.
pub fn chain_gap_error(py: Python<'_>, err: PyErr) -> PyErr {
    match take_gap_error() {
        Some(cause) if !cause.is_instance_of::<PyException>(py) => cause,
        Some(cause) => {
            err.set_cause(py, Some(cause));
            err
        }
        None => err,
    }
}

/// The shape of a rigid obstacle: the initial gap g0(ξ) ≥ 0 along the outward normal, ξ the abscissa on Γ_C
/// (`flat`, `circle`, `parabola`, `polyline`, `function`), or the obstacle's geometry (`line`, `disc`, `hole`,
/// `profile`, `distance`: for a contact side of any shape). Its motion (approach δ, shift s) is given to `Problem`.
#[pyclass(frozen, name = "Obstacle", module = "tribo")]
pub struct PyObstacle {
    pub(crate) shape: ObstacleShape,
    /// The call that built it (a gap function shows its Python repr).
    repr: String,
    /// 'flat', 'circle', 'parabola', 'polyline', 'function', 'line', 'disc', 'hole', 'profile' or 'distance'.
    #[pyo3(get)]
    kind: &'static str,
    /// The radius R of a circle or a parabola (its curvature radius), else None.
    #[pyo3(get)]
    radius: Option<f64>,
    /// The abscissa of the lowest point of a circle or a parabola, else None.
    #[pyo3(get)]
    center: Option<f64>,
}

impl PyObstacle {
    pub fn checked(shape: ObstacleShape) -> PyResult<Self> {
        tribo::Obstacle { shape: shape.clone(), ..Default::default() }.validate().map_err(to_pyerr)?;
        let (radius, center) = (shape.radius_center().map(|r| r.0), shape.radius_center().map(|r| r.1));
        Ok(Self { repr: format!("Obstacle.{shape}"), kind: shape.kind(), radius, center, shape })
    }

    /// A gap function, called by the core (GIL released: it re-attaches). An exception or a non-float is NaN, which
    /// the core rejects as BadObstacle; the exception is kept (per thread) and chained to that error, or re-raised
    /// as it is for KeyboardInterrupt and SystemExit.
    pub fn from_callable(f: Py<PyAny>) -> PyResult<Self> {
        let repr = Python::attach(|py| f.bind(py).repr().map(|r| format!("Obstacle.function({r})")))?;
        let call = move |xi: f64| -> f64 { call_or_nan(&f, &[xi]) };
        Ok(Self { repr, ..Self::checked(ObstacleShape::Function(GapFunction(Arc::new(call))))? })
    }
}

/// `f(*args)` as a float, attached to Python for the call; a Python exception or a non-float result is NaN,
/// the exception kept (per thread) for [`chain_gap_error`].
fn call_or_nan(f: &Py<PyAny>, args: &[f64]) -> f64 {
    Python::attach(|py| match PyTuple::new(py, args).and_then(|a| f.call1(py, a)).and_then(|v| v.extract::<f64>(py)) {
        Ok(g) => g,
        Err(e) => {
            GAP_ERROR.with(|slot| {
                slot.borrow_mut().get_or_insert(e);
            });
            f64::NAN
        }
    })
}

#[pymethods]
impl PyObstacle {
    /// A flat obstacle touching Γ_C: g0 = 0.
    #[staticmethod]
    fn flat() -> PyResult<Self> {
        Self::checked(ObstacleShape::Flat)
    }

    /// A rigid cylinder of radius R touching Γ_C at abscissa `center`: g0 = R − √(R² − (ξ − c)²).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn circle(radius: f64, center: f64) -> PyResult<Self> {
        Self::checked(ObstacleShape::Circle { center, radius })
    }

    /// The parabolic (Hertz) approximation of a cylinder: g0 = (ξ − c)² / (2R).
    #[staticmethod]
    #[pyo3(signature = (radius, center = 0.0))]
    fn parabola(radius: f64, center: f64) -> PyResult<Self> {
        Self::checked(ObstacleShape::Parabola { center, radius })
    }

    /// A polyline through (xi[k], gap[k]) (xi strictly increasing), constant beyond its ends.
    #[staticmethod]
    fn polyline(xi: &Bound<'_, PyAny>, gap: &Bound<'_, PyAny>) -> PyResult<Self> {
        let xi = floats(xi, "polyline abscissae", &[None], ContactGeometry)?;
        let gap = floats(gap, "polyline gaps", &[None], ContactGeometry)?;
        Self::checked(ObstacleShape::Polyline { xi, gap })
    }

    /// Any Python callable gap(xi: float) -> float giving g0 at an abscissa of Γ_C. It is called
    /// during the set-up (Γ_C integration) and at the FE nodes of Γ_C after a solve.
    #[staticmethod]
    fn function(gap: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::from_callable(callback(gap, "Obstacle.function", "gap(xi) -> float", ContactGeometry)?)
    }

    /// A rigid half-plane whose surface is the line through `point` with normal `normal` (out of the obstacle,
    /// toward the body): g0 is the signed distance of a point of Γ_C from it, and the contact acts along the
    /// line's normal. For a contact side of any shape.
    #[staticmethod]
    fn line(point: (f64, f64), normal: (f64, f64)) -> PyResult<Self> {
        Self::checked(ObstacleShape::Line { point: point.into(), normal: normal.into() })
    }

    /// A rigid disc of centre `center` and radius R outside the body: g0 = ‖x − c‖ − R.
    #[staticmethod]
    fn disc(center: (f64, f64), radius: f64) -> PyResult<Self> {
        Self::checked(ObstacleShape::Disc { center: center.into(), radius })
    }

    /// A rigid hole of centre `center` and radius R around the body: g0 = R − ‖x − c‖ (δ: a shrink fit's).
    #[staticmethod]
    fn hole(center: (f64, f64), radius: f64) -> PyResult<Self> {
        Self::checked(ObstacleShape::Hole { center: center.into(), radius })
    }

    /// A rigid body bounded by the polyline through `points` (m × 2, m ≥ 2), on its right from the first point to
    /// the last, its end segments extended: g0 is the signed distance from it (a V-groove, a step).
    #[staticmethod]
    fn profile(points: &Bound<'_, PyAny>) -> PyResult<Self> {
        let p = floats(points, "profile points", &[None, Some(2)], ContactGeometry)?;
        Self::checked(ObstacleShape::Profile { points: p.chunks_exact(2).map(|c| [c[0], c[1]]).collect() })
    }

    /// Any Python callable distance(x: float, y: float) -> float: the signed distance from the obstacle,
    /// positive outside it (its normal by central differences).
    #[staticmethod]
    fn distance(distance: &Bound<'_, PyAny>) -> PyResult<Self> {
        let f = callback(distance, "Obstacle.distance", "distance(x, y) -> float", ContactGeometry)?;
        let repr = format!("Obstacle.distance({})", distance.repr()?);
        let call = move |x: [f64; 2]| -> f64 { call_or_nan(&f, &x) };
        Ok(Self { repr, ..Self::checked(ObstacleShape::Distance(DistanceFunction(Arc::new(call))))? })
    }

    /// The initial gap g0 at abscissae `xi` (a float or an array; NaN for a shape given by its geometry).
    fn gap0<'py>(&self, py: Python<'py>, xi: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let o = tribo::Obstacle { shape: self.shape.clone(), ..Default::default() };
        take_gap_error();
        let ndim: usize = py.import("numpy")?.call_method1("ndim", (xi,))?.extract()?;
        let out = if ndim == 0 {
            let x = floats(xi, "xi", &[], ContactGeometry)?;
            PyFloat::new(py, o.initial_gap(x[0])).into_any()
        } else {
            let x = floats(xi, "xi", &[None], ContactGeometry)?;
            PyArray1::from_vec(py, x.iter().map(|&x| o.initial_gap(x)).collect()).into_any()
        };
        take_gap_error().map_or(Ok(out), Err)
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }
}
