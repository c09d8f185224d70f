//! numpy <-> Rust conversions: inputs are copied into `Vec<f64>` (they are small: states and
//! parameters) by one reader that takes any float64 array ([`floats`]); trajectories are *moved* into numpy without copying (`into_pyarray` takes
//! ownership of the contiguous row-major buffers the core produced).

use numpy::{
    IntoPyArray, PyArray1, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use physicskit::classical::{ExtraValue, SimulationResult};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use pyo3::{intern, Borrowed};

/// A one-dimensional float64 argument, copied out of its numpy array.
pub struct Vector(pub Vec<f64>);

/// A two-dimensional float64 argument: its values in C order and its `[rows, columns]`.
pub struct Matrix {
    /// The values, row after row.
    pub values: Vec<f64>,
    /// `[rows, columns]`.
    pub shape: [usize; 2],
}

impl<'a, 'py> FromPyObject<'a, 'py> for Vector {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        Ok(Self(floats(&obj, 1)?.0))
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Matrix {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let (values, shape) = floats(&obj, 2)?;
        Ok(Self {
            values,
            shape: [shape[0], shape[1]],
        })
    }
}

/// The values (C order) and shape of a float64 numpy array of `ndim` dimensions, in either
/// byte order, with any strides, at any address: every read of a numpy array at the boundary
/// goes through here.
///
/// numpy may hand over float64s at an address that is not a multiple of eight (a buffer
/// sliced at an odd offset, an array deserialized inside a message), where reading them in
/// place is undefined behaviour, and in another byte order: such an array is first copied by
/// `numpy.require` into an aligned native one. An aligned native array is read in place.
///
/// # Errors
/// TypeError for anything but a numpy array of float64 with `ndim` dimensions.
pub fn floats(obj: &Bound<'_, PyAny>, ndim: usize) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let untyped = obj.cast::<PyUntypedArray>().map_err(|_| {
        let kind = obj
            .get_type()
            .name()
            .map_or_else(|_| "?".to_string(), |n| n.to_string());
        PyTypeError::new_err(format!(
            "expected a {ndim}-dimensional numpy array of float64, got {kind}"
        ))
    })?;
    let dtype = untyped.dtype();
    if untyped.ndim() != ndim || dtype.kind() != b'f' || dtype.itemsize() != 8 {
        return Err(PyTypeError::new_err(format!(
            "expected a {ndim}-dimensional numpy array of float64, got a {}-dimensional array of {}",
            untyped.ndim(),
            dtype
        )));
    }
    let shape = untyped.shape().to_vec();
    let array = match obj.cast::<PyArrayDyn<f64>>() {
        Ok(a) if a.is_aligned() => a.clone(),
        _ => {
            let py = obj.py();
            let numpy = py.import(intern!(py, "numpy"))?;
            numpy
                .call_method1(
                    intern!(py, "require"),
                    (obj, intern!(py, "float64"), intern!(py, "A")),
                )?
                .cast_into::<PyArrayDyn<f64>>()?
        }
    };
    // `as_slice` is memory order, which is C order only for a C-contiguous array (a
    // Fortran-order matrix is contiguous too); the view's iterator is C order for any strides.
    let c_order = array.is_c_contiguous();
    let array = array.try_readonly()?;
    let values = match array.as_slice() {
        Ok(s) if c_order => s.to_vec(),
        _ => array.as_array().iter().copied().collect(),
    };
    Ok((values, shape))
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
