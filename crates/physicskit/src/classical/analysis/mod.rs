//! Pure functions on states and trajectories: action-angle variables, symmetric-top analysis;
//! Poincaré sections of any system ([`section`]), Lyapunov spectra ([`lyapunov`]), SALI and
//! GALI ([`sali`]) and chaos maps ([`chaos_map`]) on the tangent dynamics of the integrators
//! ([`Flow`](crate::classical::integrators::Flow)).

mod action_angle;
pub use action_angle::*;
pub mod elliptic;
pub use elliptic::*;
mod brent;
pub use brent::*;
mod symmetric_top;
pub use symmetric_top::*;
pub mod chaos_map;
pub mod convergence;
pub mod lyapunov;
pub mod poincare;
pub mod sali;
pub mod section;
pub mod watch;
pub mod work_precision;
