//! The analysis functions: elliptic integrals and the pendulum's action-angle variables, the
//! heavy symmetric top's reduced dynamics.

mod action_angle;
mod chaos_map;
mod lyapunov;
mod sali;
mod section;
mod symmetric_top;
mod watch;
mod work_precision;
