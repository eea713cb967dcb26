//! `Support`: a Dirichlet condition on a named edge set (clamp, roller, prescribed displacement, rotation).

use pyo3::prelude::*;

use crate::errors::to_pyerr;

/// A Dirichlet condition on a named edge set: `Support.clamp(set)` (u = 0), `Support.roller(set)`
/// (u·n = 0 on a straight set, any direction: a symmetry line; the tangential component is free) or
/// `Support.displacement(set, x=…, y=…)` (prescribed components; one left out is free) or
/// `Support.rotation(set, center, angle)` (a small rigid rotation, radians). Give a list of
/// them to `Problem(supports=…)`; conditions meeting at a node combine (a clamp and a roller at a corner
/// clamp it), and contradictory ones are a SettingsError.
#[pyclass(frozen, from_py_object, name = "Support", module = "tribo")]
#[derive(Clone)]
pub struct PySupport {
    pub(crate) inner: tribo::Support,
}

#[pymethods]
impl PySupport {
    /// u = 0 on the edge set.
    #[staticmethod]
    fn clamp(edge_set: String) -> Self {
        Self { inner: tribo::Support::clamp(edge_set) }
    }

    /// u·n = 0 on a straight edge set (n its normal); the tangential component is free.
    #[staticmethod]
    fn roller(edge_set: String) -> Self {
        Self { inner: tribo::Support::roller(edge_set) }
    }

    /// u_x = x and/or u_y = y on the edge set; a component left as None is free.
    #[staticmethod]
    #[pyo3(signature = (edge_set, *, x = None, y = None))]
    fn displacement(edge_set: String, x: Option<f64>, y: Option<f64>) -> PyResult<Self> {
        let inner = tribo::Support::displacement(edge_set, x, y);
        inner.validate().map_err(to_pyerr).map(|()| Self { inner })
    }

    /// The small rigid rotation u = angle (−(y − c_y), x − c_x) of the edge set about center (radians).
    #[staticmethod]
    fn rotation(edge_set: String, center: (f64, f64), angle: f64) -> PyResult<Self> {
        let inner = tribo::Support::rotation(edge_set, [center.0, center.1], angle);
        inner.validate().map_err(to_pyerr).map(|()| Self { inner })
    }

    /// 'clamp', 'roller', 'displacement' or 'rotation'.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind()
    }

    /// The edge set it acts on.
    #[getter]
    fn edge_set(&self) -> String {
        self.inner.set().to_string()
    }

    /// The prescribed (x, y) components: None where free or not one value (a roller, a rotation), (0, 0) clamped.
    #[getter]
    fn value(&self) -> (Option<f64>, Option<f64>) {
        let [x, y] = self.inner.components();
        (x, y)
    }

    fn __repr__(&self) -> String {
        format!("Support.{}", self.inner)
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
}
