//! The Lagrangian engine: equations of motion from `L(q, qdot, t)` by automatic differentiation,
//! or from closed forms the Lagrangian supplies.

mod buffer;
#[cfg(not(feature = "num-dual-kernels"))]
mod dual;
mod engine;
mod expr;
mod model;
pub use buffer::MAX_STACK_NDOF;
pub use engine::*;
pub use expr::*;
pub use model::*;
pub use num_dual::DualNum;
