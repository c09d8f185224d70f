//! The Lagrangian engine: equations of motion from `L(q, qdot, t)` by automatic differentiation,
//! or from closed forms the Lagrangian supplies.

mod buffer;
#[cfg(not(feature = "num-dual-kernels"))]
mod dual;
mod engine;
mod expr;
mod expr_diff;
mod expr_hamiltonian;
mod expr_ode;
mod forward;
mod model;
mod tape;
mod taylor_tape;
pub use buffer::MAX_STACK_NDOF;
pub use engine::*;
pub use expr::*;
pub use expr_diff::*;
pub use expr_hamiltonian::*;
pub use expr_ode::*;
pub use forward::{forward_jacobian, CentralDifferences, FieldScalar};
pub use model::*;
pub use num_dual::DualNum;
pub use tape::*;
pub use taylor_tape::TaylorProgram;
