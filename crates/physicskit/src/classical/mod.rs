//! `physicskit::classical`: the Rust counterpart of the Python module `physicskit.classical`.
//!
//! * [`core`]: the system traits ([`DynamicalSystem`], [`HamiltonianSystem`],
//!   [`LagrangianSystem`], [`OdeSystem`]), the state-and-clock [`Phase`], the validated
//!   [`TimeGrid`], [`SimulationResult`] and the [`Error`] type.
//! * [`integrators`]: `verlet`, `yoshida4`, `rk4` and `implicit_midpoint`, one file each
//!   declaring its facts ([`methods`] lists them), and the drivers that run them over a time
//!   grid.
//! * [`lagrangian`]: the engine deriving equations of motion from `L(q, qdot, t)`.
//! * [`systems`]: the spec's systems; [`analysis`]: functions on states and trajectories.
//! * [`examples`]: small reference systems (pendulum, harmonic oscillator) used in docs, tests
//!   and benchmarks.
//! * [`explanations`]: the physics paragraphs shared by the gallery and the lab.

pub mod analysis;
pub mod catalog;
pub mod core;
pub mod ensemble;
pub mod examples;
pub mod explanations;
pub mod integrators;
pub mod lagrangian;
pub mod systems;

pub use self::core::{
    split, DynSystem, DynamicalSystem, Error, ExtraValue, HamiltonianSystem, IntegrateOptions,
    LagrangianSystem, MassInv, Method, MethodInfo, Observer, OdeSystem, Phase, Result, Sampling,
    SimulationResult, TimeGrid, Tolerances,
};
pub use self::integrators::methods;
