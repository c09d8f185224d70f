//! [`Stepper`]: one step of a method on its problem; [`Dispatch`]: what a caller does with each
//! kind of method.
//!
//! A stepper owns its work buffers (allocated once, by its constructor) and advances a state by
//! one step. The problem it steps depends on the kind of method:
//!
//! - a splitting method ([`SplittingStepper`](super::SplittingStepper)) steps a separable
//!   [`HamiltonianSystem`](crate::classical::HamiltonianSystem), on the state `[q, p]`;
//! - a one-step method on a vector field ([`FieldStepper`]: [`Rk4`](super::Rk4), the implicit
//!   Runge–Kutta methods of [`implicit_solve`](super::implicit_solve)) steps any
//!   [`VectorField`].
//!
//! An adaptive method with dense output fits the same trait: its `step` from `t` to `t + h`
//! takes as many internal steps as its error control needs and interpolates at `t + h`.
//!
//! The drivers' loop is generic over the stepper, so each step is a static call, inlined where
//! the stepper allows it. [`Method::dispatch`](crate::classical::Method::dispatch) chooses the
//! stepper from the registry: it calls exactly one method of a [`Dispatch`], the one of the
//! method's [`Scheme`](crate::classical::core::method::Scheme). `Dispatch` has no provided
//! methods, so a new kind of method does not compile until every caller says what it does
//! with it.

use std::collections::BTreeMap;

use super::field::VectorField;
use crate::classical::core::{ExtraValue, Method, Result};

/// A stepper's statistics over the steps so far (evaluations, solver iterations), reported
/// into `result.extra`.
pub trait Report {
    /// Adds the statistics to `extra`, under the names `SimulationResult::extra` documents.
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>);
}

/// One step of a method on its problem `P`.
pub trait Stepper<P: ?Sized>: Report {
    /// Advances `y` from `t` to `t + h` (`h` may be negative).
    ///
    /// # Errors
    /// Whatever the problem's evaluation reports; for implicit methods,
    /// [`Error::SolverDidNotConverge`](crate::classical::Error::SolverDidNotConverge).
    fn step(&mut self, problem: &P, t: f64, y: &mut [f64], h: f64) -> Result<()>;

    /// [`step`](Self::step), told whether the new state will be stored with its energy
    /// (`stored`). A stepper that obtains the potential energy of the new state as a
    /// by-product (the splitting methods, from their last force evaluation) returns it then,
    /// so that the stored energy costs no second evaluation; the default returns `None`.
    ///
    /// # Errors
    /// As [`step`](Self::step).
    #[inline(always)]
    fn step_sampled(
        &mut self,
        problem: &P,
        t: f64,
        y: &mut [f64],
        h: f64,
        stored: bool,
    ) -> Result<Option<f64>> {
        let _ = stored;
        self.step(problem, t, y, h).map(|()| None)
    }
}

/// A one-step method on any [`VectorField`]: the steppers the registry names for the
/// [`ExplicitRk`](crate::classical::core::method::Scheme::ExplicitRk) and
/// [`ImplicitRk`](crate::classical::core::method::Scheme::ImplicitRk) kinds. Every
/// `FieldStepper` is a [`Stepper`] of every vector field.
pub trait FieldStepper: Report + Sized + 'static {
    /// A stepper with its work buffers for states of `dim` components.
    fn new(dim: usize) -> Self;

    /// Advances `y` from `t` to `t + h` on the field `f`.
    ///
    /// # Errors
    /// As [`Stepper::step`].
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()>;
}

impl<F: VectorField + ?Sized, St: FieldStepper> Stepper<F> for St {
    #[inline(always)]
    fn step(&mut self, problem: &F, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.step_field(problem, t, y, h)
    }
}

/// What a caller (a driver of one system family, a Poincaré section) does with each kind of
/// method. [`Method::dispatch`] calls exactly one of these, with the stepper or coefficients
/// the registry declares for the method.
pub trait Dispatch {
    /// What the caller returns.
    type Output;

    /// A splitting method (a [`Scheme::Splitting`](crate::classical::core::method::Scheme)):
    /// a symmetric composition of `N` Störmer–Verlet substeps with drift weights `drifts`,
    /// for [`SplittingStepper`](super::SplittingStepper).
    fn splitting<const N: usize>(self, method: Method, drifts: [f64; N]) -> Self::Output;

    /// An explicit one-step method on a vector field, stepped by `St`.
    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output;

    /// An implicit Runge–Kutta method on a vector field, stepped by `St` (the shared implicit
    /// solve).
    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output;
}
