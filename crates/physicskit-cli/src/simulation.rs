//! [`Simulation`]: the one dynamically dispatched edge between the registry and the library.
//!
//! The library's `integrate` is generic over the concrete system so that its force is inlined
//! into the step loop. The command line picks a system by name at run time, so each family is
//! wrapped once here ([`Hamiltonian`], [`Lagrangian`], [`Ode`]); the `dyn` call happens once
//! per run, never per step.

use physicskit::classical::{
    DynamicalSystem, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method, OdeSystem,
    Result, SimulationResult,
};

/// A system ready to integrate, whatever its family.
pub trait Simulation {
    /// The system as a [`DynamicalSystem`] (state, energy, default method).
    fn as_dynamical(&self) -> &dyn DynamicalSystem;

    /// The library's default method for this system.
    fn default_method(&self) -> Method {
        self.as_dynamical().default_method()
    }

    /// Runs the family's `integrate_with`.
    ///
    /// # Errors
    /// Whatever the library's integrator returns.
    fn run(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        options: IntegrateOptions<'_>,
    ) -> Result<SimulationResult>;
}

/// A [`HamiltonianSystem`] behind [`Simulation`].
#[derive(Debug)]
pub struct Hamiltonian<S>(pub S);

/// A [`LagrangianSystem`] behind [`Simulation`].
#[derive(Debug)]
pub struct Lagrangian<S>(pub S);

/// An [`OdeSystem`] behind [`Simulation`].
#[derive(Debug)]
pub struct Ode<S>(pub S);

macro_rules! impl_simulation {
    ($wrapper:ident, $family:ident) => {
        impl<S: $family> Simulation for $wrapper<S> {
            fn as_dynamical(&self) -> &dyn DynamicalSystem {
                &self.0
            }

            fn run(
                &mut self,
                t_span: (f64, f64),
                dt: f64,
                method: Method,
                options: IntegrateOptions<'_>,
            ) -> Result<SimulationResult> {
                $family::integrate_with(&mut self.0, t_span, dt, method, options)
            }
        }
    };
}

impl_simulation!(Hamiltonian, HamiltonianSystem);
impl_simulation!(Lagrangian, LagrangianSystem);
impl_simulation!(Ode, OdeSystem);
