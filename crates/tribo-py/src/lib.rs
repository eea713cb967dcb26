//! `tribo._tribo`: the compiled half of the `tribo` Python package.
//!
//! This crate only converts: numpy arrays ↔ Rust vectors, keyword options ↔ the core's settings
//! (names, kinds and defaults come from the core's table), core errors ↔ Python exceptions. It releases the GIL
//! around every heavy call and re-attaches only to call back into Python (a gap function, a progress
//! callback). The user-facing API is the pure-Python package `tribo`.

mod convert;
mod errors;
mod history;
mod mesh;
mod problem;
mod solution;
mod supports;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use tribo::{
    Choice, Condensation, ContactState, Diagonal, FrictionLaw, KktSolver, MultiplierPoints, MultiplierSpace, QpMethod,
    SettingKind, SettingValue, Side, SolveStatus, SolverSettings, Stabilization,
};

fn value<'py>(py: Python<'py>, v: &SettingValue) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        SettingValue::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        SettingValue::Int(i) => i.into_pyobject(py)?.into_any(),
        SettingValue::Float(f) => f.into_pyobject(py)?.into_any(),
        SettingValue::Name(s) => s.into_pyobject(py)?.into_any(),
    })
}

/// The core's defaults, as a dict of the keyword names `Problem` and `Problem.solve` take: every solver
/// setting (see `solver_settings()`), gamma0_fraction, multiplier_ratio and space.
#[pyfunction]
fn solver_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    match SolverSettings::default().stabilization {
        Stabilization::Fraction(f) => d.set_item("gamma0_fraction", f)?,
        Stabilization::Gamma0(g) | Stabilization::Unchecked(g) => d.set_item("gamma0", g)?,
        Stabilization::None => d.set_item("gamma0", 0.0)?,
    }
    for info in SolverSettings::table() {
        d.set_item(info.name, value(py, &info.default)?)?;
    }
    match MultiplierPoints::default() {
        MultiplierPoints::RatioToFe(r) => d.set_item("multiplier_ratio", r)?,
        MultiplierPoints::Size(h) => d.set_item("multiplier_size", h)?,
        _ => {}
    }
    d.set_item("space", MultiplierSpace::default().as_str())?;
    Ok(d)
}

/// The solver settings `Problem.solve` takes as keywords (and scene files in `[solver]`): a dict name →
/// {'kind': 'float' | 'count' | 'bool' | 'choice', 'default': value, 'max': int (counts),
/// 'options': list of names (choices)}.
#[pyfunction]
fn solver_settings(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for info in SolverSettings::table() {
        let d = PyDict::new(py);
        d.set_item("default", value(py, &info.default)?)?;
        match info.kind {
            SettingKind::Float => d.set_item("kind", "float")?,
            SettingKind::Bool => d.set_item("kind", "bool")?,
            SettingKind::Count { max } => {
                d.set_item("kind", "count")?;
                d.set_item("max", max)?;
            }
            SettingKind::Choice(options) => {
                d.set_item("kind", "choice")?;
                d.set_item("options", PyList::new(py, options)?)?;
            }
        }
        out.set_item(info.name, d)?;
    }
    Ok(out)
}

/// The names of every choice, as the core parses and prints them: side, diagonal, space, friction,
/// state (in the order of the int8 codes of `Solution.states`), status, qp_kkt_solver and qp_method.
#[pyfunction]
fn choices(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("side", Side::names())?;
    d.set_item("diagonal", Diagonal::names())?;
    d.set_item("space", MultiplierSpace::names())?;
    d.set_item("friction", FrictionLaw::names())?;
    d.set_item("state", ContactState::names())?;
    d.set_item("status", SolveStatus::NAMES.to_vec())?;
    d.set_item("qp_kkt_solver", KktSolver::names())?;
    d.set_item("qp_method", QpMethod::names())?;
    d.set_item("condensation", Condensation::names())?;
    Ok(d)
}

#[pymodule]
fn _tribo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("STATE_NAMES", ContactState::names())?;
    m.add("MAX_CELLS", tribo::generate::MAX_CELLS)?;
    m.add("TriboError", py.get_type::<errors::TriboError>())?;
    m.add("MeshError", py.get_type::<errors::MeshError>())?;
    m.add("ContactGeometryError", py.get_type::<errors::ContactGeometryError>())?;
    m.add("SettingsError", py.get_type::<errors::SettingsError>())?;
    m.add("SolverError", py.get_type::<errors::SolverError>())?;
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<problem::PyObstacle>()?;
    m.add_class::<problem::PyProblem>()?;
    m.add_class::<supports::PySupport>()?;
    m.add_class::<solution::PySolution>()?;
    m.add_class::<solution::PyReport>()?;
    m.add_class::<history::PyHistory>()?;
    m.add_function(wrap_pyfunction!(solver_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(solver_settings, m)?)?;
    m.add_function(wrap_pyfunction!(choices, m)?)?;
    Ok(())
}
