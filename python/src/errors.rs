//! Mapping of [`physicskit::classical::Error`] onto Python exceptions.
//!
//! | Rust error | Python exception |
//! |---|---|
//! | `InvalidParameter`, `InvalidArgument` (a value of the wrong kind, an unknown or missing parameter), `UnknownSystem`, `DimensionMismatch`, `NonFinite`, `InvalidTimeSpan`, `UnknownMethod`, `UnsupportedMethod`, `SingularMatrix`, `TrajectoryTooLarge`, `TooLarge` | `ValueError` |
//! | `Unsupported` (e.g. `force` of a non-separable system) | `NotImplementedError` (as the spec says) |
//! | `SolverDidNotConverge`, `StepSizeTooSmall` | [`ConvergenceError`], a `RuntimeError` subclass: the input was valid, the step too large (or, for an adaptive method, no step small enough met the tolerances) |
//! | `Interrupted` | `KeyboardInterrupt` (the pending signal's own exception when there is one) |
//!
//! Every message is the Rust error's `Display`, which names the offending value and says what
//! to change.

use physicskit::classical::Error;
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyNotImplementedError, PyRuntimeError, PyValueError};
use pyo3::PyErr;

create_exception!(
    _core,
    ConvergenceError,
    PyRuntimeError,
    "The implicit solver of a step did not converge (reduce dt), or an adaptive method found no \
     step meeting its tolerances."
);

/// Converts a core error into the Python exception the spec names.
pub fn to_py(err: Error) -> PyErr {
    let msg = err.to_string();
    match err {
        Error::Unsupported { .. } => PyNotImplementedError::new_err(msg),
        Error::SolverDidNotConverge { .. } | Error::StepSizeTooSmall { .. } => {
            ConvergenceError::new_err(msg)
        }
        Error::Interrupted { .. } => PyKeyboardInterrupt::new_err(msg),
        _ => PyValueError::new_err(msg),
    }
}

/// Shorthand for `Result<T, PyErr>` conversions of core results.
pub trait IntoPyResult<T> {
    /// Maps the error with [`to_py`].
    ///
    /// # Errors
    /// The converted error.
    fn py(self) -> pyo3::PyResult<T>;
}

impl<T> IntoPyResult<T> for Result<T, Error> {
    fn py(self) -> pyo3::PyResult<T> {
        self.map_err(to_py)
    }
}
