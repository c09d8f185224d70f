//! The bottom layer: errors, a system's state and clock, time grids, results, memory
//! budgets, lane sums, linear algebra, vectorized trigonometry and the facts a method
//! declares. It knows nothing of systems or integrators and uses no module above it.

pub mod error;
pub mod linalg;
mod memory;
pub(crate) use memory::check_fits as memory_check;
pub use memory::{check_items_fit, set_memory_release_hook};
pub mod method;
pub mod phase;
pub mod result;
pub mod sum;
pub mod time_grid;
pub mod trig;

pub use error::{Error, Result};
pub use method::{MethodInfo, Scheme};
pub use phase::Phase;
pub(crate) use result::Recorder;
pub use result::{ExtraValue, SimulationResult};
pub use time_grid::TimeGrid;
