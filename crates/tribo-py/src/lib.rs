//! `tribo._tribo`: the compiled half of the `tribo` Python package.
//!
//! This crate only converts: numpy arrays ↔ Rust vectors, keyword options ↔ the core's settings
//! structs (whose `Default`s are the defaults), core errors ↔ Python exceptions. It releases the GIL
//! around every heavy call and re-attaches only to call back into Python (a gap function, a progress
//! callback). The user-facing API is the pure-Python package `tribo`.

mod convert;
mod errors;
mod mesh;
mod problem;
mod solution;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use tribo::{MultiplierPoints, MultiplierSpace, SolverSettings, Stabilization};

/// The core's default settings, as a dict of the keyword names `Problem` and `Problem.solve` take:
/// gamma0_fraction, qp_tol, qp_max_iter, kkt_solver, working_set, fp_tol, fp_max_iter, relaxation,
/// multiplier_ratio, space.
#[pyfunction]
fn solver_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let s = SolverSettings::default();
    let d = PyDict::new(py);
    match s.stabilization {
        Stabilization::Fraction(f) => d.set_item("gamma0_fraction", f)?,
        Stabilization::Gamma0(g) => d.set_item("gamma0", g)?,
        Stabilization::None => d.set_item("gamma0", 0.0)?,
    }
    d.set_item("qp_tol", s.qp.tol)?;
    d.set_item("qp_max_iter", s.qp.max_iter)?;
    d.set_item("kkt_solver", problem::kkt_solver_name(s.qp.kkt_solver))?;
    d.set_item("working_set", s.qp.working_set)?;
    d.set_item("fp_tol", s.fixed_point.tol_change_rel)?;
    d.set_item("fp_max_iter", s.fixed_point.max_iter)?;
    d.set_item("relaxation", s.fixed_point.relaxation)?;
    match MultiplierPoints::default() {
        MultiplierPoints::RatioToFe(r) => d.set_item("multiplier_ratio", r)?,
        MultiplierPoints::Size(h) => d.set_item("multiplier_size", h)?,
        _ => {}
    }
    d.set_item("space", problem::space_name(MultiplierSpace::default()))?;
    Ok(d)
}

#[pymodule]
fn _tribo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("STATE_NAMES", solution::STATE_NAMES.to_vec())?;
    m.add("TriboError", py.get_type::<errors::TriboError>())?;
    m.add("MeshError", py.get_type::<errors::MeshError>())?;
    m.add("ContactGeometryError", py.get_type::<errors::ContactGeometryError>())?;
    m.add("SettingsError", py.get_type::<errors::SettingsError>())?;
    m.add("SolverError", py.get_type::<errors::SolverError>())?;
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<problem::PyObstacle>()?;
    m.add_class::<problem::PyProblem>()?;
    m.add_class::<solution::PySolution>()?;
    m.add_class::<solution::PyReport>()?;
    m.add_function(wrap_pyfunction!(solver_defaults, m)?)?;
    Ok(())
}
