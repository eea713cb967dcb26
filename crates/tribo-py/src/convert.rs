//! numpy arrays ↔ Rust vectors, with shape and dtype checks that name the argument.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt};
use tribo::SettingValue;

use crate::errors::settings_error;

/// An error constructor (which exception class a bad array raises).
pub type ErrFn = fn(String) -> PyErr;

/// `numpy.asarray(obj)` with its dtype kind ('f', 'i', 'u', …) and shape.
fn as_array<'py>(obj: &Bound<'py, PyAny>, what: &str, err: ErrFn) -> PyResult<(Bound<'py, PyAny>, String, Vec<usize>)> {
    let py = obj.py();
    let arr = py
        .import("numpy")?
        .call_method1("asarray", (obj,))
        .map_err(|e| err(format!("{what} cannot be read as a numeric array: {e}")))?;
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
    Ok((arr, kind, shape))
}

fn shape_str(shape: &[usize]) -> String {
    let parts: Vec<String> = shape.iter().map(|s| s.to_string()).collect();
    if parts.len() == 1 {
        format!("({},)", parts[0])
    } else {
        format!("({})", parts.join(", "))
    }
}

/// Checks the shape against `expected` (`None` = any length on that axis) and returns it.
fn check_shape(shape: &[usize], expected: &[Option<usize>], what: &str, err: ErrFn) -> PyResult<()> {
    let ok = shape.len() == expected.len() && shape.iter().zip(expected).all(|(s, e)| e.is_none_or(|e| *s == e));
    if ok {
        return Ok(());
    }
    let want: Vec<String> = expected
        .iter()
        .enumerate()
        .map(|(i, e)| e.map_or_else(|| ["N", "M"][i.min(1)].to_string(), |e| e.to_string()))
        .collect();
    let want = if want.len() == 1 { format!("({},)", want[0]) } else { format!("({})", want.join(", ")) };
    Err(err(format!("{what} must have shape {want}, got shape {}", shape_str(shape))))
}

/// A real array of the given shape as float64 values in C order.
pub fn floats(obj: &Bound<'_, PyAny>, what: &str, expected: &[Option<usize>], err: ErrFn) -> PyResult<Vec<f64>> {
    let (arr, kind, shape) = as_array(obj, what, err)?;
    if !matches!(kind.as_str(), "f" | "i" | "u") && !shape.contains(&0) {
        let dtype: String = arr.getattr("dtype")?.str()?.extract()?;
        return Err(err(format!("{what} must hold real numbers, got dtype {dtype}")));
    }
    check_shape(&shape, expected, what, err)?;
    let arr = arr.call_method1("astype", ("float64",))?;
    let arr = arr.cast::<PyArrayDyn<f64>>().map_err(|e| err(format!("{what}: {e}")))?;
    Ok(arr.readonly().as_array().iter().copied().collect())
}

/// An integer array of the given shape as non-negative indices in C order.
pub fn indices(obj: &Bound<'_, PyAny>, what: &str, expected: &[Option<usize>], err: ErrFn) -> PyResult<Vec<usize>> {
    let (arr, kind, shape) = as_array(obj, what, err)?;
    if !matches!(kind.as_str(), "i" | "u") && !shape.contains(&0) {
        let dtype: String = arr.getattr("dtype")?.str()?.extract()?;
        return Err(err(format!("{what} must hold integers (node indices), got dtype {dtype}")));
    }
    check_shape(&shape, expected, what, err)?;
    if kind == "u" {
        // Unsigned: read as u64 so that a huge index is reported as it is (not wrapped to a negative one).
        let arr = arr.call_method1("astype", ("uint64",))?;
        let arr = arr.cast::<PyArrayDyn<u64>>().map_err(|e| err(format!("{what}: {e}")))?;
        let view = arr.readonly();
        return view
            .as_array()
            .iter()
            .enumerate()
            .map(|(k, &v)| usize::try_from(v).map_err(|_| err(format!("{what}: entry {k} is {v}, too large an index"))))
            .collect();
    }
    let arr = arr.call_method1("astype", ("int64",))?;
    let arr = arr.cast::<PyArrayDyn<i64>>().map_err(|e| err(format!("{what}: {e}")))?;
    let view = arr.readonly();
    let mut out = Vec::with_capacity(view.len());
    for (k, &v) in view.as_array().iter().enumerate() {
        match usize::try_from(v) {
            Ok(v) => out.push(v),
            Err(_) => return Err(err(format!("{what}: entry {k} is {v}, indices must be non-negative"))),
        }
    }
    Ok(out)
}

/// Rows of `K` columns from a flat vector.
pub fn rows<T: Copy + Default, const K: usize>(flat: &[T]) -> Vec<[T; K]> {
    flat.chunks_exact(K)
        .map(|c| {
            let mut r = [T::default(); K];
            r.copy_from_slice(c);
            r
        })
        .collect()
}

/// A 1D float64 array.
pub fn vec1<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// An (n, K) array from rows.
pub fn mat<'py, T: numpy::Element + Copy, const K: usize>(py: Python<'py>, r: &[[T; K]]) -> Bound<'py, PyArray2<T>> {
    let flat: Vec<T> = r.iter().flatten().copied().collect();
    Array2::from_shape_vec((r.len(), K), flat).expect("rows of K values").into_pyarray(py)
}

/// An (n, 2) array from an interleaved (x, y) vector.
pub fn pairs<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_vec((v.len() / 2, 2), v.to_vec()).expect("interleaved pairs").into_pyarray(py)
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
        return Err(settings_error(format!("setting '{name}' = {v} is out of range")));
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(SettingValue::Float(f));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(SettingValue::Name(s));
    }
    Err(settings_error(format!("setting '{name}' must be a number, a bool or a name, got {v}")))
}
