//! [`Phase`]: a system's current state vector and clock.

use super::error::{check_finite, check_vector, Error, Result};

/// The current state vector and time of a system.
///
/// Every system owns one. `integrate` starts from it and leaves it at the final sample, so a
/// second call continues the trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    state: Vec<f64>,
    t: f64,
}

impl Phase {
    /// A phase at time `t` with the given state.
    ///
    /// # Errors
    /// [`Error::NonFinite`] if the state or `t` holds NaN or infinity.
    pub fn new(state: Vec<f64>, t: f64) -> Result<Self> {
        check_finite("state0", &state, t)?;
        if !t.is_finite() {
            return Err(Error::invalid("t0", t, "must be finite"));
        }
        Ok(Self { state, t })
    }

    /// A phase at `t = 0` from stacked halves `[a, b]` (positions then momenta or velocities).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] if the halves differ in length, [`Error::NonFinite`] for
    /// NaN or infinity.
    pub fn from_halves(name_a: &str, a: &[f64], name_b: &str, b: &[f64]) -> Result<Self> {
        check_vector(name_a, a, a.len())?;
        check_vector(name_b, b, a.len())?;
        let mut state = Vec::with_capacity(2 * a.len());
        state.extend_from_slice(a);
        state.extend_from_slice(b);
        Self::new(state, 0.0)
    }

    /// The state vector.
    pub fn state(&self) -> &[f64] {
        &self.state
    }

    /// The clock.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Length of the state vector.
    pub fn len(&self) -> usize {
        self.state.len()
    }

    /// True for an empty state.
    pub fn is_empty(&self) -> bool {
        self.state.is_empty()
    }

    /// Replaces state and clock after validating them.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] if the length changes, [`Error::NonFinite`] for NaN or
    /// infinity, [`Error::InvalidParameter`] for a non-finite `t`.
    pub fn set(&mut self, state: &[f64], t: f64) -> Result<()> {
        check_vector("state0", state, self.state.len())?;
        if !t.is_finite() {
            return Err(Error::invalid("t0", t, "must be finite"));
        }
        self.state.copy_from_slice(state);
        self.t = t;
        Ok(())
    }

    /// Sets only the clock.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite `t`.
    pub fn set_t(&mut self, t: f64) -> Result<()> {
        if !t.is_finite() {
            return Err(Error::invalid("t0", t, "must be finite"));
        }
        self.t = t;
        Ok(())
    }

    /// Overwrites state and clock from an integrator's output, which is already checked.
    pub(crate) fn assign_unchecked(&mut self, state: &[f64], t: f64) {
        self.state.copy_from_slice(state);
        self.t = t;
    }

    /// Checks the state for NaN and infinity.
    ///
    /// # Errors
    /// [`Error::NonFinite`].
    pub fn check_finite(&self) -> Result<()> {
        check_finite("state", &self.state, self.t)
    }
}
