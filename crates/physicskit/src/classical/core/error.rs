//! The error type of the whole crate.
//!
//! Every fallible operation returns [`Result`]. Variants carry the numbers a user needs to fix
//! the call (the offending value, the expected length, the time and residual of a failed
//! implicit solve). Nothing in the crate panics on user input.

/// Result alias used throughout physicskit.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in physicskit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A physical or numerical parameter is out of its allowed range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name as the user wrote it.
        name: String,
        /// The rejected value.
        value: f64,
        /// What the value must satisfy.
        reason: String,
    },
    /// An argument that is not a number, or not of the kind expected (a vector where a number
    /// belongs, an unknown parameter name, a word outside its set, a missing value).
    #[error("invalid argument `{name}`: {reason}")]
    InvalidArgument {
        /// Argument name as the user wrote it.
        name: String,
        /// What is wrong and what is expected.
        reason: String,
    },
    /// A system name that the catalogue does not know.
    #[error("unknown system `{name}`; known systems are: {valid}")]
    UnknownSystem {
        /// The name given.
        name: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
    /// An array has the wrong length.
    #[error("`{name}` has length {found}, expected {expected}")]
    DimensionMismatch {
        /// Which array.
        name: String,
        /// The length required.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A NaN or infinity appeared in an input or in the trajectory.
    #[error("non-finite value in `{name}` at t = {t}")]
    NonFinite {
        /// Which quantity (an input array, or `state` during integration).
        name: String,
        /// Time at which it was detected.
        t: f64,
    },
    /// The time span or the step is unusable.
    #[error("invalid time span ({t0}, {t1}) with dt = {dt}: {reason}")]
    InvalidTimeSpan {
        /// Start time.
        t0: f64,
        /// End time.
        t1: f64,
        /// Step size.
        dt: f64,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// A method name that physicskit does not know.
    #[error("unknown method `{name}`; valid methods are: {valid}")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
    /// The method exists but cannot honour this system.
    #[error("method `{method}` cannot integrate this system: {reason}")]
    UnsupportedMethod {
        /// Method name.
        method: String,
        /// Why, and which methods to use instead.
        reason: String,
    },
    /// An operation that the system does not define (for example `force` of a non-separable
    /// Hamiltonian).
    #[error("`{operation}` is not available: {reason}")]
    Unsupported {
        /// Operation name.
        operation: String,
        /// Why.
        reason: String,
    },
    /// The implicit solve of a step did not reach the tolerance.
    #[error(
        "implicit solver did not converge at t = {t} after {iterations} iterations \
         (residual {residual:e}); reduce dt"
    )]
    SolverDidNotConverge {
        /// Time at the start of the failing step.
        t: f64,
        /// Iterations spent.
        iterations: usize,
        /// Relative size of the last correction.
        residual: f64,
    },
    /// An adaptive method could not take a step that meets its tolerances (the step size
    /// underflowed, the error estimate was not finite) or exceeded its step budget.
    #[error("adaptive step failed at t = {t} (step size {step:e}): {reason}")]
    StepSizeTooSmall {
        /// Time at the start of the failing step.
        t: f64,
        /// The last step size tried.
        step: f64,
        /// What failed and what to change.
        reason: String,
    },
    /// A matrix that must be inverted is singular (a degenerate Lagrangian, a collapsed
    /// configuration).
    #[error("singular {what} at t = {t}")]
    SingularMatrix {
        /// Which matrix (e.g. `mass matrix`).
        what: String,
        /// Time of the evaluation.
        t: f64,
    },
    /// The requested trajectory would not fit in memory.
    #[error(
        "trajectory of {samples} samples x {values_per_sample} values needs {bytes} bytes, \
         more than the {available} bytes available; use a stride or final-state sampling, \
         a larger dt or a shorter span"
    )]
    TrajectoryTooLarge {
        /// Number of samples that would be stored.
        samples: u128,
        /// f64 values per sample, over all stored arrays.
        values_per_sample: usize,
        /// Bytes needed.
        bytes: u128,
        /// Bytes available.
        available: u128,
    },
    /// A size parameter asks for more memory than is available (checked before allocating,
    /// by [`check_items_fit`](crate::classical::core::check_items_fit)).
    #[error(
        "`{name}` = {value} is too large: {value} items of {item_bytes} bytes need {bytes} \
         bytes, more than the {available} bytes available"
    )]
    TooLarge {
        /// The size parameter, as the user wrote it (`n`, `ndof`, ...).
        name: String,
        /// Its value: the number of items.
        value: u128,
        /// Bytes per item (everything the call allocates per unit of the parameter).
        item_bytes: u128,
        /// Bytes needed.
        bytes: u128,
        /// Bytes available.
        available: u128,
    },
    /// An observer asked the integration to stop (for example on Ctrl-C).
    #[error("integration interrupted at t = {t}")]
    Interrupted {
        /// Time of the last completed step.
        t: f64,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(name: impl Into<String>, value: f64, reason: impl Into<String>) -> Self {
        Error::InvalidParameter {
            name: name.into(),
            value,
            reason: reason.into(),
        }
    }
}

/// Checks that `values` has length `expected` and holds only finite numbers.
///
/// # Errors
/// [`Error::DimensionMismatch`] or [`Error::NonFinite`] (with `t` = 0).
pub fn check_vector(name: &str, values: &[f64], expected: usize) -> Result<()> {
    if values.len() != expected {
        return Err(Error::DimensionMismatch {
            name: name.to_string(),
            expected,
            found: values.len(),
        });
    }
    check_finite(name, values, 0.0)
}

/// Checks that every entry of `values` is finite.
///
/// # Errors
/// [`Error::NonFinite`] naming `name` and `t`.
pub fn check_finite(name: &str, values: &[f64], t: f64) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite {
            name: name.to_string(),
            t,
        })
    }
}

/// Checks that a scalar parameter is finite and strictly positive.
///
/// # Errors
/// [`Error::InvalidParameter`].
pub fn check_positive(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite and > 0"))
    }
}

/// Checks that a scalar parameter is finite.
///
/// # Errors
/// [`Error::InvalidParameter`].
pub fn check_finite_scalar(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite"))
    }
}

/// Checks that a scalar parameter is finite and `>= 0`.
///
/// # Errors
/// [`Error::InvalidParameter`].
pub fn check_non_negative(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite and >= 0"))
    }
}

/// Checks that `values` has length `expected` (any values).
///
/// # Errors
/// [`Error::DimensionMismatch`].
pub fn check_len(name: &str, values: &[f64], expected: usize) -> Result<()> {
    if values.len() == expected {
        Ok(())
    } else {
        Err(Error::DimensionMismatch {
            name: name.to_string(),
            expected,
            found: values.len(),
        })
    }
}
