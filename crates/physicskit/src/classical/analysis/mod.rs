//! Pure functions on states and trajectories: action-angle variables, symmetric-top analysis.

pub mod convergence;
pub mod poincare;
