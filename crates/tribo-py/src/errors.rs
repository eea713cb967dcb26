//! The exception hierarchy and the one conversion `tribo::Error` → Python exception.
//!
//! `TriboError(ValueError)` is the base; every core error variant maps to one subclass by what it is
//! about (mesh, contact geometry, settings, solver). The exception carries the core's message (what and
//! where), the variant name as `kind` and the variant's fields as the dict `details`.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tribo::Error;

create_exception!(
    tribo,
    TriboError,
    PyValueError,
    "Base class of tribo's errors: bad input, never a numerical outcome (see Report.status).\n\n\
     Attributes: `kind` (the name of the core's error variant, e.g. 'DegenerateTriangle') and `details` \
     (a dict of its fields, e.g. {'element': 3, 'area': 0.0, ...})."
);
create_exception!(
    tribo,
    MeshError,
    TriboError,
    "A bad mesh: arrays of the wrong shape or dtype, non-finite coordinates, degenerate or inverted \
     triangles, unknown or bad edge sets, bad generator parameters."
);
create_exception!(
    tribo,
    ContactGeometryError,
    TriboError,
    "A bad contact set-up: Γ_C not straight or not connected or clamped, a bad obstacle, bad multiplier \
     points."
);
create_exception!(
    tribo,
    SettingsError,
    TriboError,
    "A bad material, load, support, friction law or solver setting (γ0 above its admissible bound among \
     them)."
);
create_exception!(
    tribo,
    SolverError,
    TriboError,
    "The linear algebra refused the problem (factorization or QP set-up failed)."
);

/// Which exception class a core error becomes.
#[derive(Clone, Copy)]
enum Class {
    Base,
    Mesh,
    Geometry,
    Settings,
    Solver,
}

fn new_err(class: Class, msg: String) -> PyErr {
    match class {
        Class::Base => TriboError::new_err(msg),
        Class::Mesh => MeshError::new_err(msg),
        Class::Geometry => ContactGeometryError::new_err(msg),
        Class::Settings => SettingsError::new_err(msg),
        Class::Solver => SolverError::new_err(msg),
    }
}

/// A `MeshError` for input the binding rejects before it reaches the core.
pub fn mesh_error(msg: impl Into<String>) -> PyErr {
    with_kind(Class::Mesh, msg.into(), "BadInput")
}

/// A `ContactGeometryError` for input the binding rejects before it reaches the core.
pub fn geometry_error(msg: impl Into<String>) -> PyErr {
    with_kind(Class::Geometry, msg.into(), "BadInput")
}

/// A `SettingsError` for input the binding rejects before it reaches the core.
pub fn settings_error(msg: impl Into<String>) -> PyErr {
    with_kind(Class::Settings, msg.into(), "BadInput")
}

fn with_kind(class: Class, msg: String, kind: &str) -> PyErr {
    let err = new_err(class, msg);
    Python::attach(|py| {
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail but for memory exhaustion.
        let _ = value.setattr("kind", kind);
        let _ = value.setattr("details", PyDict::new(py));
    });
    err
}

/// A value of a `details` dict.
enum Field {
    Int(usize),
    Float(f64),
    Str(String),
}

/// Class, variant name and fields of a core error.
fn describe(e: &Error) -> (Class, &'static str, Vec<(&'static str, Field)>) {
    use Field::{Float as F, Int as I, Str as S};
    match e {
        Error::NonFiniteCoordinate { node, x, y } => {
            (Class::Mesh, "NonFiniteCoordinate", vec![("node", I(*node)), ("x", F(*x)), ("y", F(*y))])
        }
        Error::NodeIndexOutOfRange { element, node, n_nodes } => (
            Class::Mesh,
            "NodeIndexOutOfRange",
            vec![("element", I(*element)), ("node", I(*node)), ("n_nodes", I(*n_nodes))],
        ),
        Error::DegenerateTriangle { element, area, diameter_sq } => (
            Class::Mesh,
            "DegenerateTriangle",
            vec![("element", I(*element)), ("area", F(*area)), ("diameter_sq", F(*diameter_sq))],
        ),
        Error::InvertedTriangle { element, area } => {
            (Class::Mesh, "InvertedTriangle", vec![("element", I(*element)), ("area", F(*area))])
        }
        Error::UnusedNode { node } => (Class::Mesh, "UnusedNode", vec![("node", I(*node))]),
        Error::DuplicateTriangle { first, second } => {
            (Class::Mesh, "DuplicateTriangle", vec![("first", I(*first)), ("second", I(*second))])
        }
        Error::NotABoundaryEdge { set, index, a, b } => (
            Class::Mesh,
            "NotABoundaryEdge",
            vec![("set", S(set.clone())), ("index", I(*index)), ("a", I(*a)), ("b", I(*b))],
        ),
        Error::UnknownEdgeSet { name, available } => {
            (Class::Mesh, "UnknownEdgeSet", vec![("name", S(name.clone())), ("available", S(available.clone()))])
        }
        Error::EmptyEdgeSet { name } => (Class::Mesh, "EmptyEdgeSet", vec![("name", S(name.clone()))]),
        Error::EmptyMesh => (Class::Mesh, "EmptyMesh", vec![]),
        Error::BadGenerator { what } => (Class::Mesh, "BadGenerator", vec![("what", S(what.clone()))]),
        Error::BadMaterial { what } => (Class::Settings, "BadMaterial", vec![("what", S(what.clone()))]),
        Error::NonFiniteLoad { target, x, y } => {
            (Class::Settings, "NonFiniteLoad", vec![("target", S(target.clone())), ("x", F(*x)), ("y", F(*y))])
        }
        Error::NoDirichlet => (Class::Settings, "NoDirichlet", vec![]),
        Error::TractionOnContact { set, traction_set, a, b } => (
            Class::Settings,
            "TractionOnContact",
            vec![("set", S(set.clone())), ("traction_set", S(traction_set.clone())), ("a", I(*a)), ("b", I(*b))],
        ),
        Error::ContactNotStraight { set, node, distance, length } => (
            Class::Geometry,
            "ContactNotStraight",
            vec![("set", S(set.clone())), ("node", I(*node)), ("distance", F(*distance)), ("length", F(*length))],
        ),
        Error::ContactNotConnected { set, what } => {
            (Class::Geometry, "ContactNotConnected", vec![("set", S(set.clone())), ("what", S(what.clone()))])
        }
        Error::ContactOverlapsDirichlet { set, a, b } => {
            (Class::Geometry, "ContactOverlapsDirichlet", vec![("set", S(set.clone())), ("a", I(*a)), ("b", I(*b))])
        }
        Error::BadObstacle { what } => (Class::Geometry, "BadObstacle", vec![("what", S(what.clone()))]),
        Error::MultiplierPointsNotIncreasing { index, value, previous } => (
            Class::Geometry,
            "MultiplierPointsNotIncreasing",
            vec![("index", I(*index)), ("value", F(*value)), ("previous", F(*previous))],
        ),
        Error::MultiplierPointOffContact { index, distance, start, end } => (
            Class::Geometry,
            "MultiplierPointOffContact",
            vec![("index", I(*index)), ("distance", F(*distance)), ("start", F(*start)), ("end", F(*end))],
        ),
        Error::MultiplierMeshDoesNotCover { which, value, expected } => (
            Class::Geometry,
            "MultiplierMeshDoesNotCover",
            vec![("which", S(which.to_string())), ("value", F(*value)), ("expected", F(*expected))],
        ),
        Error::BadMultiplierMesh { what } => (Class::Geometry, "BadMultiplierMesh", vec![("what", S(what.clone()))]),
        Error::BadSetting { name, value, what } => (
            Class::Settings,
            "BadSetting",
            vec![("name", S(name.to_string())), ("value", F(*value)), ("what", S(what.clone()))],
        ),
        Error::Gamma0TooLarge { gamma0, bound, element } => (
            Class::Settings,
            "Gamma0TooLarge",
            vec![("gamma0", F(*gamma0)), ("bound", F(*bound)), ("element", I(*element))],
        ),
        Error::BadThreshold { what } => (Class::Settings, "BadThreshold", vec![("what", S(what.clone()))]),
        Error::NotPositiveDefinite { what } => (Class::Solver, "NotPositiveDefinite", vec![("what", S(what.clone()))]),
        Error::QpSetup { what } => (Class::Solver, "QpSetup", vec![("what", S(what.clone()))]),
        // `Error` is non-exhaustive: a variant added later still becomes a TriboError with its message.
        _ => (Class::Base, "Other", vec![]),
    }
}

/// Converts a core error into the matching Python exception, with `kind` and `details` set.
pub fn to_pyerr(e: Error) -> PyErr {
    let (class, kind, fields) = describe(&e);
    let err = new_err(class, e.to_string());
    Python::attach(|py| {
        let details = PyDict::new(py);
        for (key, field) in fields {
            let _ = match field {
                Field::Int(v) => details.set_item(key, v),
                Field::Float(v) => details.set_item(key, v),
                Field::Str(v) => details.set_item(key, v),
            };
        }
        let value = err.value(py);
        let _ = value.setattr("kind", kind);
        let _ = value.setattr("details", details);
    });
    err
}

/// `Result<T, tribo::Error>` → `PyResult<T>`.
pub trait IntoPy<T> {
    /// Maps the error with [`to_pyerr`].
    fn py_err(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for tribo::Result<T> {
    fn py_err(self) -> PyResult<T> {
        self.map_err(to_pyerr)
    }
}
