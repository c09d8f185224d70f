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
use super::splitting::Coefficients;
use crate::classical::core::{Error, ExtraValue, Result};
use crate::classical::integrators::system::{DynamicalSystem, Family};
use crate::classical::integrators::{Method, Tolerances};

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
    /// [`Error::SolverDidNotConverge`].
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
///
/// `'static` (a stepper owns its buffers) so a stepper can live in a boxed
/// [`Flow`](super::Flow).
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

/// An adaptive method with dense output on any [`VectorField`]: the steppers the registry
/// names for the [`Adaptive`](crate::classical::core::method::Scheme::Adaptive) kind.
///
/// As a [`FieldStepper`], its `step_field` from `t` to `t + h` takes as many internal steps as
/// its error control needs and interpolates at `t + h`, so the drivers' fixed-grid loop runs
/// it unchanged, with `h` the output spacing.
pub trait AdaptiveStepper: FieldStepper {
    /// A stepper for states of `dim` components with these tolerances, which never steps past
    /// `t_bound`: it steps onto `t_bound` exactly, so a run's final state is a step's result,
    /// not an interpolation.
    fn adaptive(dim: usize, tolerances: Tolerances, t_bound: f64) -> Self;

    /// [`adaptive`](Self::adaptive) for stepping `system`'s own first-order form: the driver's
    /// constructor. A stepper that needs more of the system than its vector field (the Taylor
    /// method needs its [`taylor_field`](DynamicalSystem::taylor_field)) overrides it.
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] when `system` lacks what the stepper needs.
    fn for_system<S: DynamicalSystem + ?Sized>(
        system: &S,
        tolerances: Tolerances,
        t_bound: f64,
    ) -> Result<Self> {
        Ok(Self::adaptive(system.state_dim(), tolerances, t_bound))
    }
}

/// What a caller (a driver of one system family, a Poincaré section) does with each kind of
/// method. [`Method::dispatch`] calls exactly one of these, with the stepper or coefficients
/// the registry declares for the method.
pub trait Dispatch {
    /// What the caller returns.
    type Output;

    /// A splitting method (a [`Scheme::Splitting`](crate::classical::core::method::Scheme))
    /// with `N` drifts and the weights `coefficients`, for
    /// [`SplittingStepper`](super::SplittingStepper).
    fn splitting<const N: usize>(
        self,
        method: Method,
        coefficients: Coefficients<N>,
    ) -> Self::Output;

    /// An explicit one-step method on a vector field, stepped by `St`.
    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output;

    /// An implicit Runge–Kutta method on a vector field, stepped by `St` (the shared implicit
    /// solve).
    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output;

    /// An adaptive method with dense output on a vector field, stepped by `St`.
    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output;
}

/// The refusal of a splitting method by a system of `family` that is not a separable
/// Hamiltonian: the one message the integrate driver, sessions and chaos flows give, naming the
/// methods that do apply (read from the method table, so a new general method appears in it).
pub(crate) fn splitting_refused(method: Method, family: Family) -> Error {
    let why = match family {
        Family::Lagrangian => {
            "Lagrangian systems are integrated in canonical form, which is not separable in \
             general"
        }
        Family::Ode => "a general ODE system has no separable Hamiltonian structure",
        Family::Hamiltonian => "this Hamiltonian is not separable as H = T(p) + V(q)",
    };
    let general: Vec<&str> = Method::ALL
        .into_iter()
        .filter(|m| !m.needs_separable())
        .map(Method::name)
        .collect();
    Error::UnsupportedMethod {
        method: method.name().into(),
        reason: format!("{why}; use one of {}", general.join(", ")),
    }
}
