//! `Mesh`: a validated P1 triangle mesh, from arrays or from the rectangle generators.

use std::collections::BTreeMap;

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyMapping;
use tribo::error::ErrorCategory::Mesh;
use tribo::{ArcGrading, Choice, Curve, Diagonal, DiscSector, Grading, PlateWithHole, RingSector, Side};

use crate::convert::{floats, indices, mat, pair, rows};
use crate::errors::{bad_input, to_pyerr};

/// A validated mesh of P1 triangles with named sets of boundary edges. Its attributes are built once,
/// when it is (the arrays read-only).
///
/// Mesh(points, triangles, edge_sets=None): points (N, 2) float, triangles (T, 3) int listing nodes
/// counter-clockwise, edge_sets a dict name -> (E, 2) int array of boundary edges.
#[pyclass(frozen, name = "Mesh", module = "tribo")]
pub struct PyMesh {
    pub inner: tribo::Mesh,
    /// Node coordinates, (N, 2) float64.
    #[pyo3(get)]
    points: Py<PyAny>,
    /// Triangles, (T, 3) int64, counter-clockwise.
    #[pyo3(get)]
    triangles: Py<PyAny>,
    /// Named edge sets: dict name -> (E, 2) int64 (a new dict on every read).
    #[pyo3(get)]
    edge_sets: BTreeMap<String, Py<PyAny>>,
    /// Number of nodes N.
    #[pyo3(get)]
    n_nodes: usize,
    /// Number of triangles T.
    #[pyo3(get)]
    n_triangles: usize,
    /// Largest triangle diameter h.
    #[pyo3(get)]
    max_diameter: f64,
    /// Bounding box (xmin, ymin, xmax, ymax).
    #[pyo3(get)]
    bounding_box: (f64, f64, f64, f64),
    /// The arcs some edge sets lie on: dict name -> (cx, cy, radius) (`with_curve`).
    #[pyo3(get)]
    curves: BTreeMap<String, (f64, f64, f64)>,
}

/// A count (of cells, rings, nodes): a Python integer, not negative.
fn count(v: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let n: i64 = v.extract().map_err(|_| bad_input(Mesh, format!("{name} must be an integer count, got {v}")))?;
    usize::try_from(n).map_err(|_| bad_input(Mesh, format!("{name} = {n} must be positive")))
}

impl PyMesh {
    pub(crate) fn from_core(py: Python<'_>, m: tribo::Mesh) -> PyResult<Self> {
        let ints = |r: &[[usize; 2]]| mat(py, &r.iter().map(|e| e.map(|i| i as i64)).collect::<Vec<_>>());
        let triangles: Vec<[i64; 3]> = m.triangles().iter().map(|t| t.map(|i| i as i64)).collect();
        let [x0, y0, x1, y1] = m.bounding_box();
        Ok(Self {
            points: mat(py, m.points())?,
            triangles: mat(py, &triangles)?,
            edge_sets: m.edge_sets().iter().map(|(name, e)| Ok((name.clone(), ints(e)?))).collect::<PyResult<_>>()?,
            n_nodes: m.n_nodes(),
            n_triangles: m.n_triangles(),
            max_diameter: m.max_diameter(),
            bounding_box: (x0, y0, x1, y1),
            curves: m
                .curves()
                .iter()
                .map(|(n, Curve::Arc { center: c, radius })| (n.clone(), (c[0], c[1], *radius)))
                .collect(),
            inner: m,
        })
    }
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
        let p = rows::<f64, 2>(&floats(points, "points", &[None, Some(2)], Mesh)?);
        let t = rows::<usize, 3>(&indices(triangles, "triangles", &[None, Some(3)], Mesh)?);
        let bad = || bad_input(Mesh, "edge_sets must be a dict mapping names to (E, 2) integer arrays");
        let items: Vec<(String, Bound<'_, PyAny>)> = match edge_sets {
            None => Vec::new(),
            Some(obj) => obj.cast::<PyMapping>().ok().and_then(|m| m.items().ok()?.extract().ok()).ok_or_else(bad)?,
        };
        let mut sets = BTreeMap::new();
        for (name, edges) in items {
            let e = indices(&edges, &format!("edge set '{name}'"), &[None, Some(2)], Mesh)?;
            sets.insert(name, rows(&e));
        }
        Self::from_core(py, py.detach(|| tribo::Mesh::new(p, t, sets)).map_err(to_pyerr)?)
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
        let (nx, ny) = (count(nx, "nx")?, count(ny, "ny")?);
        let diagonal = diagonal.map_or(Ok(Diagonal::default()), Diagonal::parse).map_err(to_pyerr)?;
        let (x, y) = (pair(x, "x", Mesh)?, pair(y, "y", Mesh)?);
        Self::from_core(py, py.detach(|| tribo::rectangle(x, y, nx, ny, diagonal)).map_err(to_pyerr)?)
    }

    /// A mesh of the rectangle x × y graded toward `segment` (a coordinate range along `side`): cell size
    /// h(d) = min(h_max, h_min + growth d) at distance d from the segment (defaults: the core's). Edge sets
    /// as `rectangle`.
    #[staticmethod]
    #[pyo3(signature = (x, y, *, side, segment, h_max, h_min=None, growth=None))]
    #[allow(clippy::too_many_arguments)]
    fn graded_rectangle(
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        side: &str,
        segment: &Bound<'_, PyAny>,
        h_max: f64,
        h_min: Option<f64>,
        growth: Option<f64>,
    ) -> PyResult<Self> {
        let (x, y) = (pair(x, "x", Mesh)?, pair(y, "y", Mesh)?);
        let (side, segment) = (Side::parse(side).map_err(to_pyerr)?, pair(segment, "segment", Mesh)?);
        let d = Grading::new(side, segment, h_max);
        let grading = Grading { h_min: h_min.unwrap_or(d.h_min), growth: growth.unwrap_or(d.growth), ..d };
        Self::from_core(py, py.detach(|| tribo::graded_rectangle(x, y, &grading)).map_err(to_pyerr)?)
    }

    /// This mesh with the edge set `edge_set` on the arc of `center` and `radius`: refinement puts the new
    /// nodes of its edges on the arc (MeshError BadCurve when the set's nodes are not on it).
    fn with_curve(&self, py: Python<'_>, edge_set: &str, center: (f64, f64), radius: f64) -> PyResult<Self> {
        let curve = Curve::Arc { center: center.into(), radius };
        Self::from_core(py, self.inner.clone().with_curve(edge_set, curve).map_err(to_pyerr)?)
    }

    /// A mesh of the ring sector radii[0] ≤ ‖x − center‖ ≤ radii[1] between `angles` (radians), graded toward
    /// the `arc` of angles of its outer circle (default: all of it) to h_min (defaults: the core's, as
    /// `graded_rectangle`). Edge sets 'outer', 'inner' (on their arcs), 'start', 'end' (a full turn: a ring, no ends).
    #[staticmethod]
    #[pyo3(signature = (center, radii, angles, *, h_max, h_min=None, arc=None, growth=None))]
    #[allow(clippy::too_many_arguments)]
    fn ring_sector(
        py: Python<'_>,
        center: (f64, f64),
        radii: (f64, f64),
        angles: (f64, f64),
        h_max: f64,
        h_min: Option<f64>,
        arc: Option<(f64, f64)>,
        growth: Option<f64>,
    ) -> PyResult<Self> {
        let sector = RingSector { center: center.into(), radii: radii.into(), angles: angles.into() };
        let d = ArcGrading::new(arc.unwrap_or(angles).into(), h_max);
        let grading = ArcGrading { h_min: h_min.unwrap_or(d.h_min), growth: growth.unwrap_or(d.growth), ..d };
        Self::from_core(py, py.detach(|| tribo::ring_sector(&sector, &grading)).map_err(to_pyerr)?)
    }

    /// A uniform mesh of the disc ‖x − center‖ ≤ radius, or of its sector between `angles` (radians; default a
    /// whole turn; (π, 2π) a half-disc, flat on top), with `rings` circles of nodes around the centre (cells of
    /// about radius / rings). Edge sets 'rim' (on its circle; a loop for a whole disc), 'start', 'end' (a sector's).
    #[staticmethod]
    #[pyo3(signature = (center, radius, *, rings, angles=(0.0, std::f64::consts::TAU)))]
    fn disc(
        py: Python<'_>,
        center: (f64, f64),
        radius: f64,
        rings: &Bound<'_, PyAny>,
        angles: (f64, f64),
    ) -> PyResult<Self> {
        let rings = count(rings, "rings")?;
        let sector = DiscSector { center: center.into(), radius, angles: angles.into() };
        Self::from_core(py, py.detach(|| tribo::disc(&sector, rings)).map_err(to_pyerr)?)
    }

    /// A mesh of the plate [cx − a, cx + a] × [cy − b, cy + b] less the hole ‖x − center‖ < radius: `around` nodes
    /// round the hole (a multiple of 8), `across` cells to the plate's edge, growing from the hole. Edge sets 'hole'
    /// (a loop on its circle), 'right', 'top', 'left', 'bottom'.
    #[staticmethod]
    #[pyo3(signature = (center, radius, half_widths, *, around, across))]
    fn plate_with_hole(
        py: Python<'_>,
        center: (f64, f64),
        radius: f64,
        half_widths: (f64, f64),
        around: &Bound<'_, PyAny>,
        across: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let (around, across) = (count(around, "around")?, count(across, "across")?);
        let plate = PlateWithHole { center: center.into(), radius, half_widths: half_widths.into() };
        Self::from_core(py, py.detach(|| tribo::plate_with_hole(&plate, around, across)).map_err(to_pyerr)?)
    }

    /// Diameter h_T of every triangle, (T,) float64.
    fn diameters<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let d: Vec<f64> = (0..self.inner.n_triangles()).map(|t| self.inner.diameter(t)).collect();
        PyArray1::from_vec(py, d)
    }

    fn __repr__(&self) -> String {
        let names: Vec<String> = self.edge_sets.keys().map(|n| format!("'{n}'")).collect();
        format!("Mesh(n_nodes={}, n_triangles={}, edge_sets=[{}])", self.n_nodes, self.n_triangles, names.join(", "))
    }
}
