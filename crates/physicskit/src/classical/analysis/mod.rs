//! Pure functions on states and trajectories: action-angle variables, symmetric-top analysis.

mod brent;
pub use brent::*;
mod symmetric_top;
pub use symmetric_top::*;
