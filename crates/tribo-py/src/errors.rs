//! The exception hierarchy and the one conversion `tribo::Error` → Python exception.
//!
//! `TriboError(ValueError)` is the base; every core error maps to one subclass by its category
//! ([`tribo::error::ErrorCategory`]: mesh, contact geometry, settings, solver). The exception carries the
//! core's message (what and where), the variant name as `kind` and the variant's fields as the dict
//! `details`.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tribo::error::{Detail, ErrorCategory};
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
    "A bad contact set-up: Γ_C not one chain of edges (open or closed) or clamped, two sides that do not face, \
     a bad obstacle, bad multiplier points."
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

/// The exception of a category, with the message.
fn new_err(category: ErrorCategory, msg: String) -> PyErr {
    match category {
        ErrorCategory::Mesh => MeshError::new_err(msg),
        ErrorCategory::ContactGeometry => ContactGeometryError::new_err(msg),
        ErrorCategory::Settings => SettingsError::new_err(msg),
        ErrorCategory::Solver => SolverError::new_err(msg),
    }
}

/// The exception of `category` for input the binding rejects before it reaches the core (kind
/// 'BadInput'). Array conversions take the category of the argument they read.
pub fn bad_input(category: ErrorCategory, msg: impl Into<String>) -> PyErr {
    with_details(new_err(category, msg.into()), "BadInput", Vec::new())
}

/// Sets `kind` and `details` on a fresh exception.
fn with_details(err: PyErr, kind: &str, fields: Vec<(&'static str, Detail)>) -> PyErr {
    Python::attach(|py| {
        let details = PyDict::new(py);
        for (key, field) in fields {
            // Setting items and attributes on fresh objects fails only when memory is exhausted.
            let _ = match field {
                Detail::Int(v) => details.set_item(key, v),
                Detail::Float(v) => details.set_item(key, v),
                Detail::Text(v) => details.set_item(key, v),
            };
        }
        let value = err.value(py);
        let _ = value.setattr("kind", kind);
        let _ = value.setattr("details", details);
    });
    err
}

/// A core error as the exception of its category, with `kind` (the variant) and `details` (its fields) set.
pub fn to_pyerr(e: Error) -> PyErr {
    with_details(new_err(e.category(), e.to_string()), e.kind(), e.details())
}
