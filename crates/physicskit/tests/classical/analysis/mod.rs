//! The analysis functions: elliptic integrals and the pendulum's action-angle variables, the
//! heavy symmetric top's reduced dynamics.

mod action_angle;
mod symmetric_top;
