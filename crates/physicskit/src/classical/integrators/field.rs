//! [`VectorField`]: the `dy/dt = f(t, y)` view that `rk4` and `implicit_midpoint` integrate,
//! with zero-cost adapters from the system traits.

use crate::classical::core::Result;
use crate::classical::integrators::{DynamicalSystem, LagrangianSystem};

/// A first-order right-hand side `f(t, y)` with an optional Jacobian.
pub trait VectorField {
    /// Dimension of `y`.
    fn dim(&self) -> usize;

    /// Writes `f(t, y)` into `dy`.
    ///
    /// # Errors
    /// Whatever the underlying system reports.
    fn eval(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()>;

    /// Writes `df/dy` (row-major) into `jac`; `None` if the field has no Jacobian.
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut [f64]) -> Option<Result<()>> {
        let _ = (t, y, jac);
        None
    }
}

/// A system's own first-order form, `derivatives(t, state)`.
pub struct FirstOrder<'a, S: ?Sized>(pub &'a S);

impl<S: DynamicalSystem + ?Sized> VectorField for FirstOrder<'_, S> {
    #[inline]
    fn dim(&self) -> usize {
        self.0.state_dim()
    }

    #[inline]
    fn eval(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
        self.0.derivatives(t, y, dy)
    }

    fn jacobian(&self, t: f64, y: &[f64], jac: &mut [f64]) -> Option<Result<()>> {
        self.0.jacobian(t, y, jac)
    }
}

/// A Lagrangian system's canonical form in `(q, p)`.
pub struct Canonical<'a, S: ?Sized>(pub &'a S);

impl<S: LagrangianSystem + ?Sized> VectorField for Canonical<'_, S> {
    #[inline]
    fn dim(&self) -> usize {
        2 * self.0.ndof()
    }

    #[inline]
    fn eval(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
        self.0.canonical_derivatives(t, y, dy)
    }

    fn jacobian(&self, t: f64, y: &[f64], jac: &mut [f64]) -> Option<Result<()>> {
        self.0.canonical_jacobian(t, y, jac)
    }
}
