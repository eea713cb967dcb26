//! `tribo._tribo`: the compiled half of the `tribo` Python package.
//!
//! This crate only converts: numpy arrays ↔ Rust vectors, keyword options ↔ the core's settings (names, kinds and
//! defaults come from the core's tables), core results → dicts of read-only arrays, core errors → the Python exceptions
//! of `tribo.errors`. It releases the GIL around every heavy call and re-attaches only to call back into Python (a gap
//! function, a progress callback). The user-facing API is the pure-Python package `tribo` (`tribo.problem.Problem` and
//! the result classes of `tribo.results` among it).

mod convert;
mod errors;
mod mesh;
mod obstacle;
mod problem;
mod results;
mod supports;

/// mimalloc: about a fifth less time than the system allocator for an adaptive solve in a fresh process.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};
use pyo3::IntoPyObjectExt;
use tribo::{Choice, ContactState, ProblemSpec, SettingKind, SettingValue, SolverSettings};

/// A setting's value as a Python bool, int, float or str.
fn value<'py>(py: Python<'py>, v: &SettingValue) -> PyResult<Bound<'py, PyAny>> {
    match v {
        SettingValue::Bool(b) => b.into_bound_py_any(py),
        SettingValue::Int(i) => i.into_bound_py_any(py),
        SettingValue::Float(f) => f.into_bound_py_any(py),
        SettingValue::Name(s) => s.into_bound_py_any(py),
    }
}

/// The core's defaults, as a dict of the keyword names `Problem` and `Problem.solve` take: how γ0 is
/// chosen (gamma0_fraction), every solver setting (see `solver_settings()`), multiplier_ratio, space, model.
#[pyfunction]
fn solver_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let defaults = SolverSettings::keyword_defaults().into_iter().chain(ProblemSpec::keyword_defaults());
    defaults.map(|(name, d)| Ok((name, value(py, &d)?))).collect::<PyResult<Vec<_>>>()?.into_py_dict(py)
}

/// The solver settings `Problem.solve` takes as keywords (and scene files in `[solver]`): a dict name →
/// {'kind': 'float' | 'count' | 'bool' | 'choice', 'default': value, 'max': int (counts),
/// 'options': list of names (choices)}.
#[pyfunction]
fn solver_settings(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for info in SolverSettings::table() {
        let d = PyDict::new(py);
        d.set_item("default", value(py, &info.default)?).and(d.set_item("kind", info.kind.name()))?;
        match info.kind {
            SettingKind::Count { max } => d.set_item("max", max)?,
            SettingKind::Choice(options) => d.set_item("options", options)?,
            SettingKind::Float | SettingKind::Bool => {}
        }
        out.set_item(info.name, d)?;
    }
    Ok(out)
}

/// The names of every choice, as the core parses and prints them: side, diagonal, space, friction,
/// state (in the order of the int8 codes of `Solution.states`), status, marking, qp_kkt_solver,
/// qp_method and condensation.
#[pyfunction]
fn choices(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    tribo::choice_registry().into_py_dict(py)
}

/// A number formatted for people, as the core's messages print it (`tribo::Num`): `digits` significant
/// digits, trailing zeros dropped, plain decimals for 0.01 ≤ |x| < 10⁴ and `2.63e-3` outside.
#[pyfunction]
#[pyo3(signature = (x, digits = 3))]
fn format_number(x: f64, digits: usize) -> String {
    format!("{:.*}", digits.min(17), tribo::Num(x)) // Num prints ≤ 17 digits; > u16::MAX would panic
}

/// Checks `solve_adaptive`'s keywords before any mesh is made (`tribo.scene` reads `[adapt]` with it).
#[pyfunction]
fn check_adapt(a: problem::AdaptArgs) -> PyResult<()> {
    problem::adapt_settings(a).map(drop)
}

#[pymodule]
fn _tribo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("STATE_NAMES", ContactState::names())?;
    m.add("MAX_CELLS", tribo::generate::MAX_CELLS)?;
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<obstacle::PyObstacle>()?;
    m.add_class::<problem::PyProblem>()?;
    m.add_class::<supports::PySupport>()?;
    m.add_function(wrap_pyfunction!(solver_defaults, m)?).and(m.add_function(wrap_pyfunction!(solver_settings, m)?))?;
    m.add_function(wrap_pyfunction!(choices, m)?).and(m.add_function(wrap_pyfunction!(format_number, m)?))?;
    m.add_function(wrap_pyfunction!(check_adapt, m)?)?;
    Ok(())
}
