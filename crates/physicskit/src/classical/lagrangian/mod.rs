//! The Lagrangian engine: equations of motion from `L(q, qdot, t)` by automatic differentiation,
//! or from closed forms the Lagrangian supplies.

mod buffer;
#[cfg(not(feature = "num-dual-kernels"))]
mod dual;
mod engine;
mod forward;
mod model;
pub use buffer::MAX_STACK_NDOF;
pub use engine::*;
pub use forward::{forward_jacobian, CentralDifferences, FieldScalar};
pub use model::*;
pub use num_dual::DualNum;
