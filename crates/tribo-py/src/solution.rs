//! `Solution` and `Report`: the core's results as numpy arrays, scalars and dicts.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tribo::{Choice, SolveStatus};

use crate::convert::{mat, pairs, vec1};

/// How a solve went: status, iterations, γ0 and timings.
#[pyclass(frozen, name = "Report", module = "tribo")]
pub struct PyReport {
    inner: tribo::Report,
}

#[pymethods]
impl PyReport {
    /// 'converged', 'max_iterations', 'stagnated', 'interrupted' (the progress callback returned False),
    /// 'qp_failed', 'non_finite' (a field overflowed) or 'inaccurate' (KKT residuals above what the
    /// tolerances justify). Only 'converged' promises finite fields and small residuals.
    #[getter]
    fn status(&self) -> &'static str {
        self.inner.status.name()
    }

    /// For 'interrupted': the fixed-point iteration after which the solve stopped, else None.
    #[getter]
    fn interrupted_iteration(&self) -> Option<usize> {
        match self.inner.status {
            SolveStatus::Interrupted { iteration } => Some(iteration),
            _ => None,
        }
    }

    /// True when the status is 'converged'.
    #[getter]
    fn converged(&self) -> bool {
        self.inner.status == SolveStatus::Converged
    }

    /// For 'qp_failed': the fixed-point iteration at which a QP failed (0 = the initial QP), else None.
    #[getter]
    fn failed_iteration(&self) -> Option<usize> {
        match self.inner.status {
            SolveStatus::QpFailed { iteration, .. } => Some(iteration),
            _ => None,
        }
    }

    /// For 'qp_failed': the QP solver's status, else None.
    #[getter]
    fn failure_reason(&self) -> Option<&'static str> {
        match self.inner.status {
            SolveStatus::QpFailed { reason, .. } => Some(reason),
            _ => None,
        }
    }

    /// Fixed-point iterations (0 for frictionless and Tresca).
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }

    /// Relative change of λ_n after each fixed-point iteration.
    #[getter]
    fn residual_history<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.residual_history)
    }

    /// Iterations of each QP: interior-point iterations (clarabel) or steps (active set).
    #[getter]
    fn qp_iterations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_vec(py, self.inner.qp_iterations.iter().map(|&i| i64::from(i)).collect())
    }

    /// Factorizations among each QP's active-set steps (dense Cholesky of the free block, or sparse LDLᵀ
    /// of the saddle-point system): the other steps updated or bordered a factorization. 0 for clarabel.
    #[getter]
    fn qp_factorizations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_vec(py, self.inner.qp_factorizations.iter().map(|&i| i64::from(i)).collect())
    }

    /// The method that answered each QP: 'clarabel' or 'active_set'.
    #[getter]
    fn qp_methods(&self) -> Vec<&'static str> {
        self.inner.qp_methods.iter().map(|m| m.as_str()).collect()
    }

    /// How H was formed: 'columns' (one solve per column the QPs need), 'schur' (all of it from a
    /// partial factorization with the Γ_C dofs last) or 'saddle' (not at all: the QPs' steps solve the
    /// sparse saddle-point system).
    #[getter]
    fn condensation(&self) -> &'static str {
        self.inner.condensation.as_str()
    }

    /// How many QPs the first method tried did not answer, so that the other one did.
    #[getter]
    fn qp_fallbacks(&self) -> usize {
        self.inner.qp_fallbacks
    }

    /// How many QPs met only the fallback tolerance (1e-10), not `qp_tol`.
    #[getter]
    fn qp_inaccurate(&self) -> usize {
        self.inner.qp_inaccurate
    }

    /// γ0 used.
    #[getter]
    fn gamma0(&self) -> f64 {
        self.inner.gamma0
    }

    /// The admissible bound on γ0.
    #[getter]
    fn gamma0_bound(&self) -> f64 {
        self.inner.gamma0_bound
    }

    /// True when this solve reused the factorization of an earlier solve with the same γ0 (the
    /// 'factorization' and 'condensation' timings are then those of that earlier solve).
    #[getter]
    fn reused_factorization(&self) -> bool {
        self.inner.reused_factorization
    }

    /// Wall times per phase in seconds: assembly, contact_matrices, factorization, condensation, qp,
    /// recovery.
    #[getter]
    fn timings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let t = &self.inner.timings;
        let d = PyDict::new(py);
        for (k, v) in [
            ("assembly", t.assembly),
            ("contact_matrices", t.contact_matrices),
            ("factorization", t.factorization),
            ("condensation", t.condensation),
            ("qp", t.qp),
            ("recovery", t.recovery),
        ] {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Report(status='{}', iterations={}, gamma0={}, gamma0_bound={})",
            self.status(),
            self.inner.iterations,
            tribo::Num(self.inner.gamma0),
            tribo::Num(self.inner.gamma0_bound)
        )
    }
}

/// The solution of a contact problem: fields as numpy arrays, totals, KKT residuals and the report.
///
/// Contact fields live at three kinds of places along Γ_C: multiplier dofs (`multiplier_abscissae`:
/// lambda_n, lambda_t, friction_threshold, states), FE edge midpoints (`edge_abscissae`: sigma_n,
/// sigma_t) and FE nodes (`node_abscissae`: u_n, slip, gap).
#[pyclass(frozen, name = "Solution", module = "tribo")]
pub struct PySolution {
    inner: tribo::Solution,
    report: Py<PyReport>,
}

impl PySolution {
    pub fn new(inner: tribo::Solution) -> PyResult<Self> {
        let report = Python::attach(|py| Py::new(py, PyReport { inner: inner.report.clone() }))?;
        Ok(Self { inner, report })
    }
}

#[pymethods]
impl PySolution {
    /// Friction law solved: 'frictionless', 'tresca' or 'coulomb'.
    #[getter]
    fn friction(&self) -> &'static str {
        self.inner.report.friction.as_str()
    }

    /// Coulomb coefficient μ, or None.
    #[getter]
    fn mu(&self) -> Option<f64> {
        self.inner.report.mu
    }

    /// Nodal displacements, (N, 2).
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        pairs(py, &self.inner.displacement)
    }

    /// Constant stress (σ_xx, σ_yy, σ_xy) per triangle, (T, 3).
    #[getter]
    fn stress<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.inner.stress)
    }

    /// Out-of-plane stress σ_zz = ν (σ_xx + σ_yy) of plane strain per triangle, (T,).
    #[getter]
    fn stress_zz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.stress_zz)
    }

    /// Von Mises stress per triangle (plane strain), (T,).
    #[getter]
    fn von_mises<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.von_mises)
    }

    /// Reaction forces K u − f per node, (N, 2) (zero off the clamped nodes).
    #[getter]
    fn reactions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        pairs(py, &self.inner.reactions)
    }

    /// Abscissae of the multiplier dofs, (q,).
    #[getter]
    fn multiplier_abscissae<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.multiplier_abscissae)
    }

    /// λ_n at the multiplier dofs (a contact pressure: ≥ 0), (q,).
    #[getter]
    fn lambda_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.lambda_n)
    }

    /// λ_t at the multiplier dofs (along t), (q,).
    #[getter]
    fn lambda_t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.lambda_t)
    }

    /// Bound on |λ_t| per multiplier dof: μ λ_n (Coulomb), the Tresca threshold, or 0, (q,).
    #[getter]
    fn friction_threshold<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.friction_threshold)
    }

    /// Contact state per multiplier dof as int8: 0 separation, 1 stick, 2 slip (see STATE_NAMES).
    #[getter]
    fn states<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i8>> {
        PyArray1::from_vec(py, self.inner.states.iter().map(|&s| s.code() as i8).collect())
    }

    /// Contact state per multiplier dof as strings.
    #[getter]
    fn state_names(&self) -> Vec<&'static str> {
        self.inner.states.iter().map(|&s| s.as_str()).collect()
    }

    /// Abscissae of the midpoints of the FE edges of Γ_C.
    #[getter]
    fn edge_abscissae<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.edge_abscissae)
    }

    /// σ_n(u_h) on each FE edge of Γ_C.
    #[getter]
    fn sigma_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.sigma_n)
    }

    /// σ_t(u_h) on each FE edge of Γ_C.
    #[getter]
    fn sigma_t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.sigma_t)
    }

    /// Abscissae of the FE nodes of Γ_C.
    #[getter]
    fn node_abscissae<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.node_abscissae)
    }

    /// u_n at the FE nodes of Γ_C.
    #[getter]
    fn u_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.u_n)
    }

    /// u_t − s (slip relative to the obstacle) at the FE nodes of Γ_C.
    #[getter]
    fn slip<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.slip)
    }

    /// Gap g = g0 − δ at the FE nodes of Γ_C.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.gap)
    }

    /// Current gap g − u_n at the FE nodes of Γ_C: 0 where the body touches the obstacle, < 0 where
    /// it penetrates.
    #[getter]
    fn current_gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, &self.inner.current_gap())
    }

    /// Total force (Fx, Fy) the obstacle exerts on the body in global axes: −(normal_force n +
    /// tangential_force t).
    #[getter]
    fn contact_force(&self) -> (f64, f64) {
        let [x, y] = self.inner.contact_force;
        (x, y)
    }

    /// How the obstacle moved, in global axes: −approach n + shift t.
    #[getter]
    fn obstacle_motion(&self) -> (f64, f64) {
        let [x, y] = self.inner.obstacle_motion;
        (x, y)
    }

    /// Total normal contact force ∫ λ_n.
    #[getter]
    fn normal_force(&self) -> f64 {
        self.inner.normal_force
    }

    /// Total tangential contact force ∫ λ_t (the obstacle pulls the body by −tangential_force along t).
    #[getter]
    fn tangential_force(&self) -> f64 {
        self.inner.tangential_force
    }

    /// Largest pointwise penetration max(u_n − g)₊ over the FE nodes of Γ_C.
    #[getter]
    fn max_penetration(&self) -> f64 {
        self.inner.max_penetration
    }

    /// Dimensionless discrete KKT residuals of (3.1): equilibrium, normal_sign, non_penetration,
    /// normal_complementarity, friction_bound, stick, slip_direction.
    #[getter]
    fn kkt<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let k = &self.inner.kkt;
        let d = PyDict::new(py);
        for (name, v) in [
            ("equilibrium", k.equilibrium),
            ("normal_sign", k.normal_sign),
            ("non_penetration", k.non_penetration),
            ("normal_complementarity", k.normal_complementarity),
            ("friction_bound", k.friction_bound),
            ("stick", k.stick),
            ("slip_direction", k.slip_direction),
        ] {
            d.set_item(name, v)?;
        }
        Ok(d)
    }

    /// The largest KKT residual.
    #[getter]
    fn kkt_max(&self) -> f64 {
        self.inner.kkt.max()
    }

    /// The report of the solve.
    #[getter]
    fn report(&self, py: Python<'_>) -> Py<PyReport> {
        self.report.clone_ref(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "Solution(friction='{}', status='{}', normal_force={:.6}, tangential_force={:.6})",
            self.inner.report.friction,
            self.inner.report.status.name(),
            tribo::Num(self.inner.normal_force),
            tribo::Num(self.inner.tangential_force)
        )
    }
}
