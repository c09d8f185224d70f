//! The fixed-step integrators, one file per method, and the drivers that run them.
//!
//! | method | file | order | evaluations per step | structure kept |
//! |---|---|---|---|---|
//! | `verlet` | [`verlet`] | 2 | 1 force (first same as last) | symplectic, time-reversible |
//! | `yoshida4` | [`yoshida4`] | 4 | 3 forces (first same as last) | symplectic, time-reversible |
//! | `rk4` | [`rk4`] | 4 | 4 right-hand sides | none (energy drifts) |
//! | `implicit_midpoint` | [`implicit_midpoint`] | 2 | 2 right-hand sides at small steps (iterated to the rounding floor) | symplectic for any `H`, reversible, every quadratic invariant |
//!
//! `verlet` and `yoshida4` share one kick–drift–kick loop ([`splitting`]) and differ only in
//! their coefficients. The steppers are public for users who drive steps themselves (with
//! either sign of `dt`); `integrate` goes through [`driver`], which validates inputs, allocates
//! once and records samples.

pub mod driver;
pub mod ensemble;
pub mod field;
pub mod implicit_midpoint;
pub mod rk4;
pub mod splitting;
pub mod verlet;
pub mod yoshida4;

pub use ensemble::{integrate_ensemble, Ensemble, ENSEMBLE_CHUNK};
pub use field::{Canonical, FirstOrder, VectorField};
pub use implicit_midpoint::{ImplicitMidpoint, SolverSettings, SolverStats};
pub use rk4::Rk4;
pub use splitting::{SplittingStepper, VerletStepper, Yoshida4Stepper};
