//! numpy <-> Rust conversions: inputs are copied into `Vec<f64>` (they are small: states and
//! parameters); trajectories are *moved* into numpy without copying (`into_pyarray` takes
//! ownership of the contiguous row-major buffers the core produced).

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use physicskit::classical::{ExtraValue, SimulationResult};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// Copies a 1-D float64 array (any strides) into a `Vec`.
pub fn to_vec(a: &PyReadonlyArray1<'_, f64>) -> Vec<f64> {
    match a.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => a.as_array().iter().copied().collect(),
    }
}

/// A new 1-D float64 numpy array holding a copy of `v`.
pub fn array1<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// Converts a result into the tuple `(t, y, ndof, energy, method, extra)` from which the Python
/// `SimulationResult` is built. Arrays are moved, not copied; `q` and `p` are not sent (they
/// are views of `y`'s halves, which the Python side splits off on first access,
/// `_SplitOnAccess`, where `ndof` is not `None`).
///
/// # Errors
/// Python allocation failures.
pub fn result_tuple<'py>(py: Python<'py>, r: SimulationResult) -> PyResult<Bound<'py, PyTuple>> {
    let extra = PyDict::new(py);
    for (k, v) in r.extra {
        match v {
            ExtraValue::Scalar(x) => extra.set_item(k, x)?,
            ExtraValue::Array(a) => extra.set_item(k, a.into_pyarray(py))?,
        }
    }
    let items: [Bound<'py, PyAny>; 6] = [
        r.t.into_pyarray(py).into_any(),
        r.y.into_pyarray(py).into_any(),
        r.ndof.into_pyobject(py)?.into_any(),
        opt(py, r.energy.map(|a| a.into_pyarray(py).into_any())),
        r.method.into_pyobject(py)?.into_any(),
        extra.into_any(),
    ];
    PyTuple::new(py, items)
}

fn opt<'py>(py: Python<'py>, v: Option<Bound<'py, PyAny>>) -> Bound<'py, PyAny> {
    v.unwrap_or_else(|| py.None().into_bound(py))
}
