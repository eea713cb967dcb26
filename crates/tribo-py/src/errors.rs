//! The one conversion `tribo::Error` → Python exception.
//!
//! The hierarchy is `tribo.errors` (Python): `TriboError(ValueError)` the base, and every core error maps to one
//! subclass by its category ([`tribo::error::ErrorCategory`]: mesh, contact geometry, settings, solver). The exception
//! carries the core's message (what and where), the variant name as `kind` and the variant's fields as the dict
//! `details`.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyType};
use tribo::error::{Detail, ErrorCategory};
use tribo::Error;

/// The exception of a category, with the message: the class of `tribo.errors` (the hierarchy is Python's).
fn new_err(category: ErrorCategory, msg: String) -> PyErr {
    let name = match category {
        ErrorCategory::Mesh => "MeshError",
        ErrorCategory::ContactGeometry => "ContactGeometryError",
        ErrorCategory::Settings => "SettingsError",
        ErrorCategory::Solver => "SolverError",
    };
    Python::attach(|py| {
        let class = py.import("tribo.errors").and_then(|m| m.getattr(name)).and_then(|c| Ok(c.cast_into::<PyType>()?));
        class.map_or_else(|e| e, |class| PyErr::from_type(class, msg))
    })
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
