//! `physicskit::classical`: the Rust counterpart of the Python module `physicskit.classical`.
//!
//! Its modules are layers; each uses only those listed before it (`scripts/check-layers`
//! fails the tests on a path that points up):
//!
//! 1. [`core`]: errors, the state-and-clock [`Phase`], the validated [`TimeGrid`],
//!    [`SimulationResult`], memory budgets, lane sums, linear algebra, vectorized
//!    trigonometry, and the facts a method declares ([`MethodInfo`]).
//! 2. [`integrators`]: the system traits ([`DynamicalSystem`], [`HamiltonianSystem`],
//!    [`LagrangianSystem`], [`OdeSystem`]) with their `integrate`, the methods (one file each,
//!    [`methods`] lists them), the steppers and drivers that run them, the tangent [`integrators::Flow`]
//!    and the parallel ensemble of decoupled members.
//! 3. [`model`]: a system as front ends see it: [`DynSystem`], its capabilities, the frame
//!    by frame [`model::Session`], and the catalogue's vocabulary ([`SystemEntry`]).
//! 4. [`lagrangian`]: the engine deriving equations of motion from `L(q, qdot, t)`, and
//!    [`symbolic`]: expressions, tapes and their JIT, and the engines built on them. One
//!    layer: the expression Lagrangian runs on the engine, and a generic Lagrangian's Taylor
//!    form is its trace compiled from expressions.
//! 5. [`systems`] and [`examples`]: the built-in systems, each with its catalogue entry.
//! 6. [`catalog`]: the list of every system.
//! 7. [`analysis`]: functions on states, trajectories and flows (action–angle, chaos).
//! 8. [`ensemble`]: ensembles and sweeps of any catalogue entry on all cores.

pub mod analysis;
pub mod catalog;
pub mod core;
pub mod ensemble;
pub mod examples;
pub mod integrators;
pub mod lagrangian;
pub mod model;
pub mod symbolic;
pub mod systems;

pub use self::core::{Error, ExtraValue, MethodInfo, Phase, Result, SimulationResult, TimeGrid};
pub use self::integrators::{
    methods, split, DynamicalSystem, HamiltonianSystem, IntegrateOptions, LagrangianSystem,
    MassInv, Method, Observer, OdeSystem, Sampling, Tolerances,
};
pub use self::model::{DynSystem, SystemEntry};
