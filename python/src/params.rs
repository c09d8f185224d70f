//! Python values <-> the catalogue's parameter [`Value`]s: the one place where a Python
//! object becomes a system parameter.
//!
//! `_core.build(name, params)` converts each argument by the kind its catalogue parameter
//! declares ([`ParamKind`]), with one function per kind below, and hands the values to the
//! catalogue, which checks everything else (unknown or repeated names, missing values,
//! finiteness, ranges, vector lengths). These functions decide only *what kind of Python
//! object* a parameter accepts; they never check a number's value.
//!
//! The rules (the non-constructor paths of the Python package, `_native.as_vector` and
//! `as_scalar`, follow the same ones):
//!
//! | kind | accepted | refused (ValueError naming the parameter) |
//! |---|---|---|
//! | scalar | `numbers.Real` (int, float, numpy real scalars, `Fraction`); a real numpy array or sequence holding exactly one number in at most one dimension (`theta0=[0.3]`) | bools, complex numbers and complex arrays, strings, ints too large for a float (`10**400`), anything else |
//! | integer | objects with `__index__` (int, numpy integers) that fit in 64 bits | bools, floats even when integral (`5.4e16`, `1.5`), ints outside 64 bits |
//! | vector | array-likes of reals in at most one dimension (lists, tuples, numpy arrays of integer or float dtype; object arrays whose items are real numbers); a single real number is a vector of length 1 | complex dtypes or items, bool dtypes or items, strings, ragged or 2-D input, ints too large for a float |
//! | choice | `str` | everything else |
//! | any | `None` where the spec's default is `None` (`quat0`, `q0` of `SineGordonChain`): the parameter is left out and the constructor decides | `None` elsewhere |
//!
//! Bools are refused where a number belongs: `True` is an `int` in Python, but a flag passed
//! as a mass or a count is a mistake, not a 1. NaN and infinities are numbers here; the
//! catalogue refuses them with its own message.

use numpy::PyArray1;
use physicskit::classical::model::entry::{Default, ParamKind, ParamSpec, Value, Values};
use physicskit::classical::Error;
use pyo3::exceptions::{PyOverflowError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString};

use crate::convert::floats;
use crate::errors::to_py;

/// The Python classes and functions the rules refer to, imported once per call.
struct Rules<'py> {
    real: Bound<'py, PyAny>,
    complex: Bound<'py, PyAny>,
    numpy_bool: Bound<'py, PyAny>,
    asarray: Bound<'py, PyAny>,
    index: Bound<'py, PyAny>,
}

impl<'py> Rules<'py> {
    fn new(py: Python<'py>) -> PyResult<Self> {
        let numbers = py.import("numbers")?;
        let numpy = py.import("numpy")?;
        Ok(Self {
            real: numbers.getattr("Real")?,
            complex: numbers.getattr("Complex")?,
            numpy_bool: numpy.getattr("bool_")?,
            asarray: numpy.getattr("asarray")?,
            index: py.import("operator")?.getattr("index")?,
        })
    }

    fn is_bool(&self, obj: &Bound<'py, PyAny>) -> PyResult<bool> {
        Ok(obj.is_instance_of::<PyBool>() || obj.is_instance(&self.numpy_bool)?)
    }
}

fn refuse(name: &str, reason: impl Into<String>) -> PyErr {
    to_py(Error::InvalidArgument {
        name: name.into(),
        reason: reason.into(),
    })
}

/// `repr(obj)`, shortened for messages.
fn show(obj: &Bound<'_, PyAny>) -> String {
    let text = obj
        .repr()
        .map_or_else(|_| "<unprintable>".to_string(), |r| r.to_string());
    if text.chars().count() > 60 {
        let head: String = text.chars().take(57).collect();
        format!("{head}...")
    } else {
        text
    }
}

/// A single number: not a bool, a `numbers.Real`, convertible to a float without overflow.
/// `None` if `obj` is not a number at all (an array-like, say), so the caller may look inside.
fn real_number(rules: &Rules<'_>, name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
    if rules.is_bool(obj)? {
        return Err(refuse(
            name,
            format!("expected a real number, got the bool {}", show(obj)),
        ));
    }
    if obj.is_instance(&rules.real)? {
        return match obj.extract::<f64>() {
            Ok(x) => Ok(Some(x)),
            Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => Err(refuse(
                name,
                format!("{} is too large for a 64-bit float", show(obj)),
            )),
            Err(e) => Err(refuse(name, format!("not a real number: {e}"))),
        };
    }
    if obj.is_instance(&rules.complex)? {
        return Err(refuse(
            name,
            format!(
                "expected a real number, got the complex number {}",
                show(obj)
            ),
        ));
    }
    if obj.is_instance_of::<PyString>() {
        return Err(refuse(
            name,
            format!("expected a real number, got the string {}", show(obj)),
        ));
    }
    Ok(None)
}

/// `obj` as a numpy array of reals in at most one dimension, flattened to a `Vec`.
fn real_array(rules: &Rules<'_>, name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if obj.is_instance_of::<PyString>() {
        return Err(refuse(
            name,
            format!("expected real numbers, got the string {}", show(obj)),
        ));
    }
    let arr = rules.asarray.call1((obj,)).map_err(|e| {
        refuse(
            name,
            format!("expected real numbers, got {} ({e})", show(obj)),
        )
    })?;
    let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
    if shape.len() > 1 {
        return Err(refuse(
            name,
            format!("must be one-dimensional, got an array of shape {shape:?}"),
        ));
    }
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    match kind.as_str() {
        "f" | "i" | "u" => {
            let flat = arr
                .call_method1("astype", ("float64",))?
                .call_method1("reshape", (-1,))?;
            Ok(floats(&flat, 1)?.0)
        }
        "O" => {
            let items = arr.call_method1("reshape", (-1,))?.call_method0("tolist")?;
            let items = items.cast_into::<PyList>()?;
            items
                .iter()
                .map(|item| {
                    real_number(rules, name, &item)?.ok_or_else(|| {
                        refuse(
                            name,
                            format!("expected real numbers, found the item {}", show(&item)),
                        )
                    })
                })
                .collect()
        }
        "c" => Err(refuse(
            name,
            "expected real numbers, got complex numbers; pass the real part",
        )),
        "b" => Err(refuse(name, "expected real numbers, got bools")),
        _ => Err(refuse(
            name,
            format!("expected real numbers, got {}", show(obj)),
        )),
    }
}

/// A scalar parameter: a real number (a Python or numpy number, or a 0-d numpy array); a
/// scalar part of the initial state (`initial_state`: a one-dimensional system's `theta0`)
/// also as a sequence of one number, the state vector it is, as the peer takes it.
///
/// # Errors
/// ValueError naming the parameter: bools, complex numbers, strings, ints too large for a
/// float, sequences of more than one number, and, for a constant of the system, a sequence of
/// one (`R=[1.0]` is refused, not read as `1.0`: a list where a number is wanted is a mistake
/// worth naming).
pub fn scalar(name: &str, obj: &Bound<'_, PyAny>, initial_state: bool) -> PyResult<Value> {
    let rules = Rules::new(obj.py())?;
    if let Some(x) = real_number(&rules, name, obj)? {
        return Ok(Value::Scalar(x));
    }
    let values = real_array(&rules, name, obj)?;
    let ndim: usize = rules.asarray.call1((obj,))?.getattr("ndim")?.extract()?;
    match (ndim, values.as_slice()) {
        (0, [x]) => Ok(Value::Scalar(*x)),
        (_, [x]) if initial_state => Ok(Value::Scalar(*x)),
        (_, [x]) => Err(refuse(
            name,
            format!(
                "expected one real number, got a sequence of length 1 ({}); pass {x}",
                show(obj)
            ),
        )),
        (_, other) => Err(refuse(
            name,
            format!(
                "expected one real number, got a sequence of {} numbers",
                other.len()
            ),
        )),
    }
}

/// An integer parameter: an object with `__index__` (not a bool) that fits in an `i64`.
///
/// # Errors
/// ValueError naming the parameter: floats (even integral ones), bools, ints outside 64 bits,
/// anything without `__index__`.
pub fn integer(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    let rules = Rules::new(obj.py())?;
    if rules.is_bool(obj)? {
        return Err(refuse(
            name,
            format!("must be an integer, got the bool {}", show(obj)),
        ));
    }
    let index = rules.index.call1((obj,)).map_err(|e| {
        if e.is_instance_of::<PyTypeError>(obj.py()) {
            refuse(name, format!("must be an integer, got {}", show(obj)))
        } else {
            e
        }
    })?;
    match index.extract::<i64>() {
        Ok(n) => Ok(Value::Integer(n)),
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => Err(refuse(
            name,
            format!("{} does not fit in a 64-bit integer", show(obj)),
        )),
        Err(e) => Err(e),
    }
}

/// A vector parameter: an array-like of real numbers in at most one dimension (a single
/// number is a vector of length 1). Lengths are the catalogue's to check.
///
/// # Errors
/// ValueError naming the parameter: complex or bool dtypes or items, strings, ragged or
/// multi-dimensional input, ints too large for a float.
pub fn vector(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    let rules = Rules::new(obj.py())?;
    Ok(Value::Vector(real_array(&rules, name, obj)?))
}

/// A choice parameter: a `str` (whether it is one of the words is the catalogue's to check).
///
/// # Errors
/// ValueError naming the parameter for anything but a `str`.
pub fn choice(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    obj.cast::<PyString>()
        .map(|s| Value::Choice(s.to_string()))
        .map_err(|_| refuse(name, format!("must be a string, got {}", show(obj))))
}

/// Converts `obj` by the kind of `spec`; `None` leaves the parameter out where the spec's
/// default is `None` (and is refused elsewhere: `m=None` is a mistake, not "the default").
///
/// # Errors
/// As the function of the parameter's kind; `None` for a parameter whose spec default is not
/// `None`.
pub fn to_value(spec: &ParamSpec, obj: &Bound<'_, PyAny>) -> PyResult<Option<Value>> {
    if obj.is_none() {
        return if spec.default == Default::Absent {
            Ok(None)
        } else {
            Err(refuse(
                spec.name,
                format!("must be {}, got None", spec.expectation()),
            ))
        };
    }
    let value = match spec.kind {
        ParamKind::Scalar => scalar(spec.name, obj, spec.initial_state)?,
        ParamKind::Integer => integer(spec.name, obj)?,
        ParamKind::Vector(_) => vector(spec.name, obj)?,
        ParamKind::Choice(_) => choice(spec.name, obj)?,
    };
    Ok(Some(value))
}

/// A [`Value`] as a Python object: float, int, a new float64 array, or str.
///
/// # Errors
/// Python allocation failures.
pub fn value_to_py<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Scalar(x) => x.into_pyobject(py)?.into_any(),
        Value::Integer(n) => n.into_pyobject(py)?.into_any(),
        Value::Vector(v) => PyArray1::from_slice(py, v).into_any(),
        Value::Choice(w) => PyString::new(py, w).into_any(),
    })
}

/// Checked values as a dict `name -> value` (`None` for a parameter left out), in the
/// catalogue's order.
///
/// # Errors
/// Python allocation failures.
pub fn values_to_dict<'py>(py: Python<'py>, values: &Values) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for (name, value) in values.iter() {
        match value {
            Some(v) => dict.set_item(name, value_to_py(py, v)?)?,
            None => dict.set_item(name, py.None())?,
        }
    }
    Ok(dict)
}

/// Refuses a non-string key of the `params` dict.
///
/// # Errors
/// TypeError, as Python does for a non-string keyword.
pub fn key(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    obj.extract::<String>().map_err(|_| {
        PyTypeError::new_err(format!(
            "parameter names must be strings, got {}",
            show(obj)
        ))
    })
}
