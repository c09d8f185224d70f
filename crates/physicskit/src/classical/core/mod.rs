//! Traits, state layout, results, options and errors: what every other module builds on.

pub mod catalog;
pub mod erased;
pub mod error;
pub mod linalg;
mod memory;
pub(crate) use memory::check_fits as memory_check;
pub use memory::{check_items_fit, set_memory_release_hook};
pub mod method;
pub mod options;
pub mod phase;
pub mod result;
pub mod sum;
pub mod system;
pub mod time_grid;
pub mod trig;

pub use catalog::{Family, ParamSpec, SystemEntry, Value, Values};
pub use erased::{Capabilities, DynSystem};
pub use error::{Error, Result};
pub use method::{Method, MethodInfo, Scheme};
pub use options::{IntegrateOptions, Observer, Sampling, Tolerances};
pub use phase::Phase;
pub(crate) use result::Recorder;
pub use result::{ExtraValue, SimulationResult};
pub use system::{
    hamiltonian_energy, lagrangian_derivatives, quadratic_kinetic_energy, separable_derivatives,
    separable_jacobian, split, DynamicalSystem, HamiltonianSystem, LagrangianSystem, MassInv,
    OdeSystem,
};
pub use time_grid::TimeGrid;
