//! numpy arrays ↔ Rust vectors, with shape and dtype checks that name the argument, and setting values.
//! A bad argument raises the exception of the category given (`ErrorCategory::Mesh` for mesh arrays…).

use std::borrow::Cow;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt};
use tribo::error::ErrorCategory;
use tribo::SettingValue;

use crate::errors::bad_input;

/// `(a, b)`, or `(a,)` for one part: a shape as Python prints it.
fn tuple(parts: Vec<String>) -> String {
    match parts.as_slice() {
        [one] => format!("({one},)"),
        _ => format!("({})", parts.join(", ")),
    }
}

/// `numpy.asarray(obj)` with its dtype kind: a kind among `kinds` (`holds` says what they are; an empty
/// array may have any dtype) and the shape `expected` (`None` = any length on that axis).
fn checked<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    expected: &[Option<usize>],
    cat: ErrorCategory,
    (kinds, holds): (&str, &str),
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let arr = (obj.py().import("numpy")?.call_method1("asarray", (obj,)))
        .map_err(|e| bad_input(cat, format!("{what} cannot be read as a numeric array: {e}")))?;
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
    if !kinds.contains(kind.as_str()) && !shape.contains(&0) {
        let dtype = arr.getattr("dtype")?.str()?;
        return Err(bad_input(cat, format!("{what} must hold {holds}, got dtype {dtype}")));
    }
    if shape.len() != expected.len() || shape.iter().zip(expected).any(|(s, e)| e.is_some_and(|e| *s != e)) {
        let axis =
            |(i, e): (usize, &Option<usize>)| e.map_or_else(|| ["N", "M"][i.min(1)].to_string(), |e| e.to_string());
        let want = tuple(expected.iter().enumerate().map(axis).collect());
        let got = tuple(shape.iter().map(usize::to_string).collect());
        return Err(bad_input(cat, format!("{what} must have shape {want}, got shape {got}")));
    }
    Ok((arr, kind))
}

/// The values of a checked array as `dtype` (C order).
fn values<T: numpy::Element + Copy>(
    arr: &Bound<'_, PyAny>,
    dtype: &str,
    what: &str,
    cat: ErrorCategory,
) -> PyResult<Vec<T>> {
    let arr = arr.call_method1("astype", (dtype,))?;
    let arr = arr.cast::<PyArrayDyn<T>>().map_err(|e| bad_input(cat, format!("{what}: {e}")))?;
    Ok(arr.readonly().as_array().iter().copied().collect())
}

/// A real array of the given shape as float64 values in C order.
pub fn floats(
    obj: &Bound<'_, PyAny>,
    what: &str,
    expected: &[Option<usize>],
    cat: ErrorCategory,
) -> PyResult<Vec<f64>> {
    let (arr, _) = checked(obj, what, expected, cat, ("fiu", "real numbers"))?;
    values(&arr, "float64", what, cat)
}

/// An integer array of the given shape as non-negative indices in C order.
pub fn indices(
    obj: &Bound<'_, PyAny>,
    what: &str,
    expected: &[Option<usize>],
    cat: ErrorCategory,
) -> PyResult<Vec<usize>> {
    let (arr, kind) = checked(obj, what, expected, cat, ("iu", "integers (node indices)"))?;
    // Unsigned arrays are read as such, so that a huge index is reported as it is (not wrapped around).
    let v: Vec<i128> = match kind.as_str() {
        "u" => values::<u64>(&arr, "uint64", what, cat)?.into_iter().map(i128::from).collect(),
        _ => values::<i64>(&arr, "int64", what, cat)?.into_iter().map(i128::from).collect(),
    };
    let index = |(k, v): (usize, i128)| {
        let why = if v < 0 { "indices must be non-negative" } else { "too large an index" };
        usize::try_from(v).map_err(|_| bad_input(cat, format!("{what}: entry {k} is {v}, {why}")))
    };
    v.into_iter().enumerate().map(index).collect()
}

/// Rows of `K` columns from a flat vector (`chunks_exact(K)` yields K values each: the `expect` cannot fail).
pub fn rows<T: Copy, const K: usize>(flat: &[T]) -> Vec<[T; K]> {
    flat.chunks_exact(K).map(|c| c.try_into().expect("chunks of K values")).collect()
}

/// A pair of reals, e.g. a coordinate range (x0, x1) or a force (fx, fy).
pub fn pair(obj: &Bound<'_, PyAny>, what: &str, cat: ErrorCategory) -> PyResult<[f64; 2]> {
    Ok(rows(&floats(obj, what, &[Some(2)], cat)?)[0])
}

/// The array made read-only: results and the fields of a mesh or a problem are built once and shared by
/// every read, so that no reader can change them for the others.
pub fn frozen<T>(a: Bound<'_, T>) -> PyResult<Py<PyAny>> {
    a.as_any().getattr("flags")?.setattr("writeable", false)?;
    Ok(a.into_any().unbind())
}

/// A read-only 1D array: a `Vec` handed over without a copy (a long history's series), a slice copied.
pub fn vec1<'a, T: numpy::Element + Copy + 'a>(py: Python<'_>, v: impl Into<Cow<'a, [T]>>) -> PyResult<Py<PyAny>> {
    frozen(v.into().into_owned().into_pyarray(py))
}

/// A read-only 1D int64 array of indices (node numbers, steps, regions, counts).
pub fn ints(py: Python<'_>, v: impl IntoIterator<Item = usize>) -> PyResult<Py<PyAny>> {
    vec1(py, v.into_iter().map(|i| i as i64).collect::<Vec<_>>())
}

/// A read-only (n, K) array from rows.
pub fn mat<T: numpy::Element + Copy, const K: usize>(py: Python<'_>, r: &[[T; K]]) -> PyResult<Py<PyAny>> {
    frozen(Array2::from(r.to_vec()).into_pyarray(py))
}

/// A read-only (n, 2) array from an interleaved (x, y) vector: the core's 2N-dof vectors, of even length.
pub fn pairs(py: Python<'_>, v: &[f64]) -> PyResult<Py<PyAny>> {
    frozen(Array2::from_shape_vec((v.len() / 2, 2), v.to_vec()).expect("interleaved pairs").into_pyarray(py))
}

/// A Python value as a solver setting: a bool, an integer, a real number or an option's name.
pub fn setting_value(v: &Bound<'_, PyAny>, name: &str) -> PyResult<SettingValue> {
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(SettingValue::Bool(b.is_true()));
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(SettingValue::Int(i));
    }
    if v.is_instance_of::<PyInt>() {
        return Err(bad_input(ErrorCategory::Settings, format!("setting '{name}' = {v} is out of range")));
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(SettingValue::Float(f));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(SettingValue::Name(s));
    }
    Err(bad_input(ErrorCategory::Settings, format!("setting '{name}' must be a number, a bool or a name, got {v}")))
}

/// A Python callable, e.g. `callback(f, "on_phase", "(phase, seconds)", Settings)`; anything else raises
/// "on_phase must be a callable (phase, seconds), got …" in the exception of `cat`.
pub fn callback(obj: &Bound<'_, PyAny>, what: &str, call: &str, cat: ErrorCategory) -> PyResult<Py<PyAny>> {
    let bad = || bad_input(cat, format!("{what} must be a callable {call}, got {obj}"));
    obj.is_callable().then(|| obj.clone().unbind()).ok_or_else(bad)
}
