//! The core's results as dicts of read-only numpy arrays, numbers and names, handed over once; the typed
//! classes `Report`, `Solution` and `History` that read them are pure Python (`tribo/results.py`).

use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};
use tribo::results::Scalar;
use tribo::{Choice, ContactState};

use crate::convert::{ints, mat, pairs, vec1};

/// `Report` as a dict.
fn report<'py>(py: Python<'py>, r: &tribo::Report) -> PyResult<Bound<'py, PyDict>> {
    let ints = |v: &[u32]| vec1(py, v.iter().map(|&i| i64::from(i)).collect::<Vec<_>>());
    let d = PyDict::new(py);
    for (name, v) in r.scalars() {
        match v {
            Scalar::Missing => d.set_item(name, py.None()),
            Scalar::Bool(b) => d.set_item(name, b),
            Scalar::Count(c) => d.set_item(name, c),
            Scalar::Float(x) => d.set_item(name, x),
            Scalar::Name(s) => d.set_item(name, s),
        }?;
    }
    d.set_item("residual_history", vec1(py, &r.residual_history)?)?;
    d.set_item("qp_iterations", ints(&r.qp_iterations)?)?;
    d.set_item("qp_factorizations", ints(&r.qp_factorizations)?)?;
    d.set_item("qp_methods", r.qp_methods.iter().map(|m| m.as_str()).collect::<Vec<_>>())?;
    d.set_item("timings", r.timings.named().into_py_dict(py)?)?;
    d.set_item("estimate", r.estimate.named().into_py_dict(py)?)?;
    Ok(d)
}

/// `Solution` as a dict (its report as a dict too).
pub fn solution<'py>(py: Python<'py>, s: &tribo::Solution) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("friction", s.report.friction.as_str()).and(d.set_item("mu", s.report.mu))?;
    d.set_item("displacement", pairs(py, &s.displacement)?)?;
    d.set_item("stress", mat(py, &s.stress)?)?;
    d.set_item("nodal_stress", mat(py, &s.nodal_stress)?)?;
    d.set_item("reactions", pairs(py, &s.reactions)?)?;
    d.set_item("states", vec1(py, s.states.iter().map(|&s| s.code() as i8).collect::<Vec<_>>())?)?;
    s.vectors().into_iter().try_for_each(|(name, v)| d.set_item(name, vec1(py, v)?))?;
    let pair = |v: [f64; 2]| (v[0], v[1]);
    d.set_item("contact_force", pair(s.contact_force)).and(d.set_item("obstacle_motion", pair(s.obstacle_motion)))?;
    s.scalars().into_iter().try_for_each(|(name, v)| d.set_item(name, v))?;
    d.set_item("closed", s.closed)?;
    let spans =
        |r: &tribo::PairResult| [r.multipliers.clone(), r.nodes.clone(), r.edges.clone()].map(|s| (s.start, s.end));
    let forces = |r: &tribo::PairResult| {
        [r.normal_force, r.tangential_force, r.contact_force[0], r.contact_force[1], r.contact_width, r.stick_width]
    };
    let each = |r: &tribo::PairResult| (r.name.clone(), spans(r), forces(r), r.closed, r.mu);
    d.set_item("pairs", s.pairs.iter().map(each).collect::<Vec<_>>())?;
    d.set_item("kkt", s.kkt.named().into_py_dict(py)?)?;
    d.set_item("report", report(py, &s.report)?)?;
    Ok(d)
}

/// `History` as a dict: its solutions as dicts, and the per-step series the core derives from them.
pub fn history<'py>(py: Python<'py>, h: &tribo::History) -> PyResult<Bound<'py, PyDict>> {
    let count = |state| ints(py, h.count(state));
    let (steps, at) = h.stick_slip_table();
    let d = PyDict::new(py);
    d.set_item("status", h.status.name()).and(d.set_item("ended_at", h.ended_at))?;
    d.set_item("solutions", h.solutions.iter().map(|s| solution(py, s)).collect::<PyResult<Vec<_>>>()?)?;
    d.set_item("kept", ints(py, h.kept.iter().copied())?)?;
    d.set_item("failed", h.failed.as_deref().map(|s| solution(py, s)).transpose()?)?;
    h.series().into_iter().try_for_each(|(name, v)| d.set_item(name, vec1(py, v)?))?;
    d.set_item("stick_count", count(ContactState::Stick)?).and(d.set_item("slip_count", count(ContactState::Slip)?))?;
    d.set_item("separation_count", count(ContactState::Separation)?)?;
    d.set_item("stick_slip_steps", ints(py, steps)?).and(d.set_item("stick_slip_boundaries", vec1(py, at)?))?;
    // Each pair's series by its name (the first pair's zones and gross sliding are the history's own).
    let pair = |k: usize| -> PyResult<_> {
        let s = PyDict::new(py);
        h.pair_series(k).into_iter().try_for_each(|(name, v)| s.set_item(name, vec1(py, v)?))?;
        s.set_item("contact_zone", mat(py, &h.pair_extent(k, |s| s != ContactState::Separation))?)?;
        s.set_item("stick_zone", mat(py, &h.pair_extent(k, |s| s == ContactState::Stick))?)?;
        s.set_item("gross_sliding", vec1(py, h.pair_gross_sliding(k))?).map(|()| (h.pairs[k].name.as_str(), s))
    };
    d.set_item("pairs", (0..h.pairs.len()).map(pair).collect::<PyResult<Vec<_>>>()?)?;
    d.set_item("factorizations", h.factorizations).and(d.set_item("setup_seconds", h.setup_seconds))?;
    Ok(d)
}
