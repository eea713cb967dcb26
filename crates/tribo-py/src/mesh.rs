//! `Mesh`: a validated P1 triangle mesh, from arrays or from the rectangle generators.

use std::collections::BTreeMap;

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyMapping};
use tribo::{Choice, Diagonal, Grading, Side};

use crate::convert::{floats, indices, mat, rows};
use crate::errors::{mesh_error, ToPyResult};

fn mesh_err(msg: String) -> PyErr {
    mesh_error(msg)
}

/// A validated mesh of P1 triangles with named sets of boundary edges.
///
/// Mesh(points, triangles, edge_sets=None): points (N, 2) float, triangles (T, 3) int listing nodes
/// counter-clockwise, edge_sets a dict name -> (E, 2) int array of boundary edges.
#[pyclass(frozen, name = "Mesh", module = "tribo")]
pub struct PyMesh {
    pub inner: tribo::Mesh,
}

fn range(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<[f64; 2]> {
    let v = floats(obj, what, &[Some(2)], mesh_err)?;
    Ok([v[0], v[1]])
}

#[pymethods]
impl PyMesh {
    #[new]
    #[pyo3(signature = (points, triangles, edge_sets = None))]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        triangles: &Bound<'_, PyAny>,
        edge_sets: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let p = rows::<f64, 2>(&floats(points, "points", &[None, Some(2)], mesh_err)?);
        let t = rows::<usize, 3>(&indices(triangles, "triangles", &[None, Some(3)], mesh_err)?);
        let mut sets = BTreeMap::new();
        if let Some(obj) = edge_sets {
            let map = obj
                .cast::<PyMapping>()
                .map_err(|_| mesh_error("edge_sets must be a dict mapping names to (E, 2) integer arrays"))?;
            for item in map.items()?.iter() {
                let (name, edges): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item.extract()?;
                let name: String =
                    name.extract().map_err(|_| mesh_error(format!("edge set names must be strings, got {name}")))?;
                let e = indices(&edges, &format!("edge set '{name}'"), &[None, Some(2)], mesh_err)?;
                sets.insert(name, rows::<usize, 2>(&e));
            }
        }
        let inner = py.detach(|| tribo::Mesh::new(p, t, sets)).py_err()?;
        Ok(Self { inner })
    }

    /// A uniform mesh of the rectangle x × y with nx × ny cells split along `diagonal` ('right',
    /// 'left' or 'alternating'; default: the core's). Edge sets 'bottom', 'right', 'top', 'left'.
    #[staticmethod]
    #[pyo3(signature = (x, y, nx, ny, *, diagonal = None))]
    fn rectangle(
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        nx: &Bound<'_, PyAny>,
        ny: &Bound<'_, PyAny>,
        diagonal: Option<&str>,
    ) -> PyResult<Self> {
        let count = |v: &Bound<'_, PyAny>, name: &str| -> PyResult<usize> {
            let n: i64 =
                v.extract().map_err(|_| mesh_error(format!("{name} must be an integer cell count, got {v}")))?;
            usize::try_from(n).map_err(|_| mesh_error(format!("{name} = {n} must be a positive cell count")))
        };
        let (nx, ny) = (count(nx, "nx")?, count(ny, "ny")?);
        let diagonal = diagonal.map_or(Ok(Diagonal::default()), Diagonal::parse).py_err()?;
        let (x, y) = (range(x, "x")?, range(y, "y")?);
        let inner = py.detach(|| tribo::rectangle(x, y, nx, ny, diagonal)).py_err()?;
        Ok(Self { inner })
    }

    /// A mesh of the rectangle x × y graded toward `segment` (a coordinate range along `side`): cell size
    /// h(d) = min(h_max, h_min + growth d) at distance d from the segment. Edge sets as `rectangle`.
    #[staticmethod]
    #[pyo3(signature = (x, y, *, side, segment, h_min, h_max, growth))]
    #[allow(clippy::too_many_arguments)]
    fn graded_rectangle(
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        side: &str,
        segment: &Bound<'_, PyAny>,
        h_min: f64,
        h_max: f64,
        growth: f64,
    ) -> PyResult<Self> {
        let (x, y) = (range(x, "x")?, range(y, "y")?);
        let grading =
            Grading { side: Side::parse(side).py_err()?, segment: range(segment, "segment")?, h_min, h_max, growth };
        let inner = py.detach(|| tribo::graded_rectangle(x, y, &grading)).py_err()?;
        Ok(Self { inner })
    }

    /// Node coordinates, (N, 2) float64.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, self.inner.points())
    }

    /// Triangles, (T, 3) int64, counter-clockwise.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let t: Vec<[i64; 3]> = self.inner.triangles().iter().map(|t| t.map(|i| i as i64)).collect();
        mat(py, &t)
    }

    /// Named edge sets: dict name -> (E, 2) int64.
    #[getter]
    fn edge_sets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, edges) in self.inner.edge_sets() {
            let e: Vec<[i64; 2]> = edges.iter().map(|e| e.map(|i| i as i64)).collect();
            d.set_item(name, mat(py, &e))?;
        }
        Ok(d)
    }

    /// Number of nodes N.
    #[getter]
    fn n_nodes(&self) -> usize {
        self.inner.n_nodes()
    }

    /// Number of triangles T.
    #[getter]
    fn n_triangles(&self) -> usize {
        self.inner.n_triangles()
    }

    /// Largest triangle diameter h.
    #[getter]
    fn max_diameter(&self) -> f64 {
        self.inner.max_diameter()
    }

    /// Bounding box (xmin, ymin, xmax, ymax).
    #[getter]
    fn bounding_box(&self) -> (f64, f64, f64, f64) {
        let b = self.inner.bounding_box();
        (b[0], b[1], b[2], b[3])
    }

    /// Diameter h_T of every triangle, (T,) float64.
    fn diameters<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let d: Vec<f64> = (0..self.inner.n_triangles()).map(|t| self.inner.diameter(t)).collect();
        PyArray1::from_vec(py, d)
    }

    fn __repr__(&self) -> String {
        let names: Vec<&str> = self.inner.edge_set_names().collect();
        format!(
            "Mesh(n_nodes={}, n_triangles={}, edge_sets=[{}])",
            self.inner.n_nodes(),
            self.inner.n_triangles(),
            names.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
        )
    }
}
