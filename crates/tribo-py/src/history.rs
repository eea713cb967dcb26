//! `History`: the core's loading history as a list of solutions and stacked numpy arrays.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use tribo::{ContactState, SolveStatus};

use crate::convert::{mat, vec1};
use crate::solution::PySolution;

/// A quasi-static loading history: the solution of every step that converged, and per-step arrays.
///
/// The arrays have one entry per converged step (`len(history)`); `approach`, `shift` and `load_factor`
/// give the steps asked for (all of them).
#[pyclass(frozen, name = "History", module = "tribo")]
pub struct PyHistory {
    /// The core's history without its solutions (they moved into `solutions`).
    inner: tribo::History,
    solutions: Vec<Py<PySolution>>,
    failed: Option<Py<PySolution>>,
    normal_force: Vec<f64>,
    tangential_force: Vec<f64>,
    /// Stick, slip and separation counts per step.
    counts: [Vec<i64>; 3],
    contact_zone: Vec<[f64; 2]>,
    stick_zone: Vec<[f64; 2]>,
    boundaries: Vec<Vec<f64>>,
    sliding: Vec<bool>,
}

impl PyHistory {
    pub fn new(py: Python<'_>, mut inner: tribo::History) -> PyResult<Self> {
        let count = |state| inner.count(state).into_iter().map(|c| c as i64).collect();
        let counts = [count(ContactState::Stick), count(ContactState::Slip), count(ContactState::Separation)];
        let (normal_force, tangential_force) = (inner.normal_force(), inner.tangential_force());
        let contact_zone = inner.extent(|s| s != ContactState::Separation);
        let stick_zone = inner.extent(|s| s == ContactState::Stick);
        let boundaries = inner.stick_slip_boundaries();
        let sliding = inner.gross_sliding();
        let solutions = std::mem::take(&mut inner.solutions)
            .into_iter()
            .map(|s| Py::new(py, PySolution::new(s)?))
            .collect::<PyResult<Vec<_>>>()?;
        let failed = inner.failed.take().map(|s| Py::new(py, PySolution::new(*s)?)).transpose()?;
        Ok(Self {
            inner,
            solutions,
            failed,
            normal_force,
            tangential_force,
            counts,
            contact_zone,
            stick_zone,
            boundaries,
            sliding,
        })
    }
}

#[pymethods]
impl PyHistory {
    /// 'converged' when every step converged; otherwise the status of the step that ended the history
    /// ('interrupted' when the progress callback returned False).
    #[getter]
    fn status(&self) -> &'static str {
        self.inner.status.name()
    }

    /// True when every step converged.
    #[getter]
    fn converged(&self) -> bool {
        self.inner.status == SolveStatus::Converged
    }

    /// The step (0-based) that ended the history early, or None.
    #[getter]
    fn ended_at(&self) -> Option<usize> {
        self.inner.ended_at
    }

    /// The solutions of the steps that converged, in order.
    #[getter]
    fn solutions(&self, py: Python<'_>) -> Vec<Py<PySolution>> {
        self.solutions.iter().map(|s| s.clone_ref(py)).collect()
    }

    /// The last iterate of a step that did not converge (not in `solutions`), or None.
    #[getter]
    fn failed(&self, py: Python<'_>) -> Option<Py<PySolution>> {
        self.failed.as_ref().map(|s| s.clone_ref(py))
    }

    /// Approach δ_k of every step asked for.
    #[getter]
    fn approach<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.steps.iter().map(|s| s.approach).collect::<Vec<_>>())
    }

    /// Tangential position s_k of every step asked for.
    #[getter]
    fn shift<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.steps.iter().map(|s| s.shift).collect::<Vec<_>>())
    }

    /// Load factor α_k of every step asked for.
    #[getter]
    fn load_factor<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.steps.iter().map(|s| s.load_factor).collect::<Vec<_>>())
    }

    /// Total normal force ∫λ_n per converged step.
    #[getter]
    fn normal_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.normal_force)
    }

    /// Total tangential force ∫λ_t per converged step.
    #[getter]
    fn tangential_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.tangential_force)
    }

    /// Multiplier dofs that stick, per converged step.
    #[getter]
    fn stick_count<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_slice(py, &self.counts[0])
    }

    /// Multiplier dofs that slip, per converged step.
    #[getter]
    fn slip_count<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_slice(py, &self.counts[1])
    }

    /// Multiplier dofs separated from the obstacle, per converged step.
    #[getter]
    fn separation_count<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_slice(py, &self.counts[2])
    }

    /// (first, last) abscissa of the multiplier dofs in contact, per converged step, (K, 2); NaN when
    /// nothing touches.
    #[getter]
    fn contact_zone<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.contact_zone)
    }

    /// (first, last) abscissa of the multiplier dofs that stick, per converged step, (K, 2); NaN when
    /// none sticks.
    #[getter]
    fn stick_zone<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.stick_zone)
    }

    /// Per converged step, the abscissae of the stick–slip boundaries (midpoints between a dof that
    /// sticks and a neighbour that slips).
    #[getter]
    fn stick_slip_boundaries<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray1<f64>>> {
        self.boundaries.iter().map(|b| vec1(py, b)).collect()
    }

    /// Per converged step, True when the contact slides as a whole (something touches and every dof in
    /// contact slips: |Q| = μP for Coulomb friction).
    #[getter]
    fn gross_sliding<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        PyArray1::from_slice(py, &self.sliding)
    }

    /// Wall time of each step solved, in seconds.
    #[getter]
    fn step_seconds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.step_seconds)
    }

    /// Factorizations of K − G done for the history: 1, or 0 when an earlier solve's was reused.
    #[getter]
    fn factorizations(&self) -> usize {
        self.inner.factorizations
    }

    /// Wall time of the factorization set-up, in seconds (0 when reused).
    #[getter]
    fn setup_seconds(&self) -> f64 {
        self.inner.setup_seconds
    }

    fn __len__(&self) -> usize {
        self.solutions.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "History(status='{}', steps={}/{}, factorizations={})",
            self.inner.status.name(),
            self.solutions.len(),
            self.inner.steps.len(),
            self.inner.factorizations
        )
    }
}
