//! Pure functions on states and trajectories: action-angle variables, symmetric-top analysis.

mod action_angle;
pub use action_angle::*;
pub mod elliptic;
pub use elliptic::*;
mod brent;
pub use brent::*;
mod symmetric_top;
pub use symmetric_top::*;
pub mod convergence;
pub mod poincare;
pub mod work_precision;
