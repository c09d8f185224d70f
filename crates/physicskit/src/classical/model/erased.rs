//! [`DynSystem`]: one type-erased system for every front end, with optional
//! [`Capabilities`].
//!
//! `integrate` is generic over the concrete system so that its force is inlined into the
//! step loop. A front end that picks a system by name at run time holds a
//! `Box<dyn DynSystem>` instead: each family is wrapped once ([`Hamiltonian`],
//! [`Lagrangian`], [`Ode`]), and the wrapper's `integrate` calls the family's generic
//! `integrate_with`, so the only dynamic call is the one into `integrate`, never one per step.
//!
//! What only some systems can tell (bob positions for drawing, normal modes, a rotation
//! matrix, a conserved vector) is a [`Capabilities`] method with a default of `None`, which a
//! system overrides in its own file. Front ends ask for a capability and report its absence;
//! they never downcast to a concrete type.

use std::ops::{Deref, DerefMut};

use super::session::{Refused, Session, StartHamiltonian, StartLagrangian, StartOde};
use crate::classical::core::error::{Error, Result};
use crate::classical::core::result::SimulationResult;
use crate::classical::integrators::options::IntegrateOptions;
use crate::classical::integrators::system::{
    DynamicalSystem, Family, HamiltonianSystem, LagrangianSystem, OdeSystem,
};
use crate::classical::integrators::tangent::{self, Flow};
use crate::classical::integrators::{Method, Tolerances};

/// What only some systems offer. Every method returns `None` unless the system overrides it;
/// `Some(Err(..))` reports bad arguments (wrong lengths).
///
/// Arguments are the caller's states (front ends pass the current state by default), so the
/// same accessor serves a whole trajectory.
pub trait Capabilities {
    /// Cartesian positions of the drawn bodies for the configuration `q`, as
    /// `[x1, y1, x2, y2, ...]` (the double pendulum's two bobs, a spring pendulum's bob).
    /// Allocates the vector: [`positions_into`](Self::positions_into) reuses one.
    fn positions(&self, q: &[f64]) -> Option<Result<Vec<f64>>> {
        let mut out = Vec::new();
        self.positions_into(q, &mut out)
            .map(|done| done.map(|()| out))
    }

    /// [`positions`](Self::positions) written into `out` (cleared first), which allocates
    /// nothing once `out` has the room: for drawing every frame. Systems offering positions
    /// override this one.
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        let _ = (q, out);
        None
    }

    /// The Laplace–Runge–Lenz vector of a central-force orbit.
    fn lrl_vector(&self, q: &[f64], p: &[f64]) -> Option<Result<[f64; 2]>> {
        let _ = (q, p);
        None
    }

    /// The angular momentum about the force centre (planar: the out-of-plane component).
    fn angular_momentum(&self, q: &[f64], p: &[f64]) -> Option<Result<f64>> {
        let _ = (q, p);
        None
    }

    /// The energy of each particle (they sum to the total energy).
    fn per_particle_energy(&self, q: &[f64], p: &[f64]) -> Option<Result<Vec<f64>>> {
        let _ = (q, p);
        None
    }

    /// The area of the phase-space patch that the particles fill.
    fn phase_space_area(&self, q: &[f64], p: &[f64]) -> Option<Result<f64>> {
        let _ = (q, p);
        None
    }

    /// Angular frequencies of the normal modes, lowest first.
    fn normal_mode_frequencies(&self) -> Option<Vec<f64>> {
        None
    }

    /// Normal-mode coordinates `(Q, P)` of the state `(q, p)`.
    fn normal_mode_coordinates(
        &self,
        q: &[f64],
        p: &[f64],
    ) -> Option<Result<(Vec<f64>, Vec<f64>)>> {
        let _ = (q, p);
        None
    }

    /// Energy in each normal mode of the state `(q, p)`.
    fn modal_energies(&self, q: &[f64], p: &[f64]) -> Option<Result<Vec<f64>>> {
        let _ = (q, p);
        None
    }

    /// The rotation matrix (row-major, body to space) of a rigid body's state.
    fn rotation_matrix(&self, state: &[f64]) -> Option<Result<[f64; 9]>> {
        let _ = state;
        None
    }

    /// `|L|^2` of a rigid body's state.
    fn angular_momentum_squared(&self, state: &[f64]) -> Option<Result<f64>> {
        let _ = state;
        None
    }

    /// The instantaneous precession and nutation rates `(phidot, thetadot)` of a top.
    fn precession_nutation_rate(&self, state: &[f64]) -> Option<Result<(f64, f64)>> {
        let _ = state;
        None
    }

    /// Conserved quantities beyond the energy (an integrable system's integrals), sorted.
    fn conserved_quantities(&self, state: &[f64]) -> Option<Result<Vec<f64>>> {
        let _ = state;
        None
    }

    /// The unit vector along a top's symmetry axis, in space, for the configuration `q`.
    fn symmetry_axis(&self, q: &[f64]) -> Option<Result<[f64; 3]>> {
        let _ = q;
        None
    }

    /// A rigid body's angular momentum in the body frame, `(I1 w1, I2 w2, I3 w3)`.
    fn body_angular_momentum(&self, state: &[f64]) -> Option<Result<[f64; 3]>> {
        let _ = state;
        None
    }

    /// Half-extents (m) of the uniform box of mass `mass` (kg) whose principal moments are the
    /// body's: the shape to draw it as.
    fn inertia_box(&self, mass: f64) -> Option<Result<[f64; 3]>> {
        let _ = mass;
        None
    }

    /// Energies of the separatrices of a one-degree-of-freedom system: the energy levels of
    /// its unstable (saddle) equilibria, lowest first.
    fn separatrix_energies(&self) -> Option<Vec<f64>> {
        None
    }
}

/// The names of the [`Capabilities`] accessors, in declaration order, for listings (`list
/// --json`, the lab): [`offered`] says which of them a system has.
pub const CAPABILITY_NAMES: [&str; 16] = [
    "positions",
    "lrl_vector",
    "angular_momentum",
    "per_particle_energy",
    "phase_space_area",
    "normal_mode_frequencies",
    "normal_mode_coordinates",
    "modal_energies",
    "rotation_matrix",
    "angular_momentum_squared",
    "precession_nutation_rate",
    "conserved_quantities",
    "symmetry_axis",
    "body_angular_momentum",
    "inertia_box",
    "separatrix_energies",
];

/// Which [`CAPABILITY_NAMES`] `system` offers, asked at its current state.
pub fn offered(system: &dyn DynSystem) -> Vec<&'static str> {
    let d = system.dynamical();
    let state = d.state();
    let (q, p) = match system.ndof() {
        Some(n) if state.len() == 2 * n => state.split_at(n),
        _ => (state, state),
    };
    let c = system.capabilities();
    let has = [
        c.positions(q).is_some(),
        c.lrl_vector(q, p).is_some(),
        c.angular_momentum(q, p).is_some(),
        c.per_particle_energy(q, p).is_some(),
        c.phase_space_area(q, p).is_some(),
        c.normal_mode_frequencies().is_some(),
        c.normal_mode_coordinates(q, p).is_some(),
        c.modal_energies(q, p).is_some(),
        c.rotation_matrix(state).is_some(),
        c.angular_momentum_squared(state).is_some(),
        c.precession_nutation_rate(state).is_some(),
        c.conserved_quantities(state).is_some(),
        c.symmetry_axis(q).is_some(),
        c.body_angular_momentum(state).is_some(),
        c.inertia_box(1.0).is_some(),
        c.separatrix_energies().is_some(),
    ];
    CAPABILITY_NAMES
        .into_iter()
        .zip(has)
        .filter_map(|(name, yes)| yes.then_some(name))
        .collect()
}

/// A built-in system behind one object-safe interface, whatever its family.
pub trait DynSystem: Send + Sync {
    /// The family.
    fn family(&self) -> Family;

    /// Degrees of freedom (`None` for ODE systems, whose state has its own layout).
    fn ndof(&self) -> Option<usize>;

    /// State, clock, energy, derivatives and default method.
    fn dynamical(&self) -> &dyn DynamicalSystem;

    /// Resets the clock to `t0` and, if given, the state.
    ///
    /// # Errors
    /// As [`DynamicalSystem::reset`].
    fn reset(&mut self, state0: Option<&[f64]>, t0: f64) -> Result<()>;

    /// Runs the family's `integrate_with`.
    ///
    /// # Errors
    /// Whatever the integrator returns.
    fn integrate(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        options: IntegrateOptions<'_>,
    ) -> Result<SimulationResult>;

    /// The Hamiltonian view (kinetic and potential energy, force, masses), for Hamiltonian
    /// systems.
    fn hamiltonian(&self) -> Option<&dyn HamiltonianSystem> {
        None
    }

    /// The Lagrangian view (acceleration, momentum, Legendre map), for Lagrangian systems.
    fn lagrangian(&self) -> Option<&dyn LagrangianSystem> {
        None
    }

    /// What only some systems offer.
    fn capabilities(&self) -> &dyn Capabilities;

    /// `method`'s step on this system, able to carry up to `max_vectors` deviation vectors
    /// (the chaos indicators and Poincaré sections run on it; monomorphized for the system).
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] for a method the system cannot run.
    fn flow(&self, method: Method, max_vectors: usize) -> Result<Box<dyn Flow + '_>>;

    /// The method `integrate` uses when none is given.
    fn default_method(&self) -> Method {
        self.dynamical().default_method()
    }

    /// Hands the system to a [`Session`] stepping it with `method` and step `dt` from its
    /// current state and clock, a frame at a time, with the same bits as `integrate` over the
    /// same steps and no allocation per frame. An adaptive method runs with the default
    /// [`Tolerances`] (see [`start_with`](Self::start_with)).
    ///
    /// # Errors
    /// A [`Refused`] holding the reason (the method is not one this system can use, `dt` is
    /// not finite and positive, the state is not finite) and the system, unchanged.
    fn start(
        self: Box<Self>,
        method: Method,
        dt: f64,
    ) -> std::result::Result<Box<dyn Session>, Refused> {
        self.start_with(method, dt, None)
    }

    /// [`start`](Self::start) with the `tolerances` of an adaptive method (`None`: the
    /// defaults), `dt` then being the output spacing. An adaptive session has the bits of
    /// `integrate` with the same tolerances up to `integrate`'s last internal step (the
    /// session's [module documentation](super::session) says exactly which samples).
    ///
    /// # Errors
    /// As [`start`](Self::start), and as `integrate` refuses tolerances:
    /// [`Error::InvalidArgument`] naming `tolerances` for a fixed-step method,
    /// [`Error::InvalidParameter`] naming `rtol` or `atol` when it is not finite and positive (or, for `taylor`, outside
    /// the range its order rule takes).
    fn start_with(
        self: Box<Self>,
        method: Method,
        dt: f64,
        tolerances: Option<Tolerances>,
    ) -> std::result::Result<Box<dyn Session>, Refused>;
}

/// A [`HamiltonianSystem`] behind [`DynSystem`].
#[derive(Debug, Clone)]
pub struct Hamiltonian<S>(pub S);

/// A [`LagrangianSystem`] behind [`DynSystem`].
#[derive(Debug, Clone)]
pub struct Lagrangian<S>(pub S);

/// An [`OdeSystem`] behind [`DynSystem`].
#[derive(Debug, Clone)]
pub struct Ode<S>(pub S);

macro_rules! impl_dyn_system {
    ($wrapper:ident, $family:ident, $tag:expr, $ndof:expr, $view:ident, $flow:ident, $start:ident) => {
        impl<S> Deref for $wrapper<S> {
            type Target = S;
            fn deref(&self) -> &S {
                &self.0
            }
        }

        impl<S> DerefMut for $wrapper<S> {
            fn deref_mut(&mut self) -> &mut S {
                &mut self.0
            }
        }

        impl<S: $family + Capabilities + Send + Sync + 'static> DynSystem for $wrapper<S> {
            fn family(&self) -> Family {
                $tag
            }
            fn ndof(&self) -> Option<usize> {
                #[allow(clippy::redundant_closure_call)]
                ($ndof)(&self.0)
            }
            fn dynamical(&self) -> &dyn DynamicalSystem {
                &self.0
            }
            fn reset(&mut self, state0: Option<&[f64]>, t0: f64) -> Result<()> {
                self.0.reset(state0, t0)
            }
            fn integrate(
                &mut self,
                t_span: (f64, f64),
                dt: f64,
                method: Method,
                options: IntegrateOptions<'_>,
            ) -> Result<SimulationResult> {
                $family::integrate_with(&mut self.0, t_span, dt, method, options)
            }
            fn start_with(
                self: Box<Self>,
                method: Method,
                dt: f64,
                tolerances: Option<Tolerances>,
            ) -> std::result::Result<Box<dyn Session>, Refused> {
                method.dispatch($start {
                    system: self,
                    dt,
                    tolerances,
                })
            }
            impl_dyn_system!(@view $view);
            fn capabilities(&self) -> &dyn Capabilities {
                &self.0
            }
            fn flow(&self, method: Method, max_vectors: usize) -> Result<Box<dyn Flow + '_>> {
                tangent::$flow(&self.0, method, max_vectors)
            }
        }
    };
    (@view hamiltonian) => {
        fn hamiltonian(&self) -> Option<&dyn HamiltonianSystem> {
            Some(&self.0)
        }
    };
    (@view lagrangian) => {
        fn lagrangian(&self) -> Option<&dyn LagrangianSystem> {
            Some(&self.0)
        }
    };
    (@view none) => {};
}

impl_dyn_system!(
    Hamiltonian,
    HamiltonianSystem,
    Family::Hamiltonian,
    |s: &S| Some(HamiltonianSystem::ndof(s)),
    hamiltonian,
    hamiltonian_flow,
    StartHamiltonian
);
impl_dyn_system!(
    Lagrangian,
    LagrangianSystem,
    Family::Lagrangian,
    |s: &S| Some(LagrangianSystem::ndof(s)),
    lagrangian,
    lagrangian_flow,
    StartLagrangian
);
impl_dyn_system!(
    Ode,
    OdeSystem,
    Family::Ode,
    |_: &S| None,
    none,
    ode_flow,
    StartOde
);

/// Replaces the contents of `out` by `values`: what a `positions_into` writes (no allocation
/// once `out` has the room).
pub fn fill(out: &mut Vec<f64>, values: &[f64]) {
    out.clear();
    out.extend_from_slice(values);
}

/// An [`Error::Unsupported`] for a capability `system` lacks, for front ends.
pub fn missing(capability: &str, system: &str) -> Error {
    Error::Unsupported {
        operation: capability.into(),
        reason: format!("`{system}` does not offer it"),
    }
}
