//! # physicskit
//!
//! Classical mechanics on fast structure-preserving integrators: Newtonian and central-force
//! dynamics, Lagrangian mechanics (equations of motion derived from `L(q, qdot, t)` by
//! automatic differentiation), Hamiltonian phase space, lattice chains and rigid bodies.
//!
//! The public API lives in [`classical`], which mirrors the Python module
//! `physicskit.classical`. This crate does numerics only: no plotting, no command line and no
//! Python (those live in `physicskit-viz`, `physicskit-cli` and the `python/` crate).
//!
//! # Example
//!
//! ```
//! use physicskit::classical::{HamiltonianSystem, Method};
//! use physicskit::classical::examples::Pendulum;
//!
//! let mut pendulum = Pendulum::new(1.0, 0.0, 1.0).unwrap();
//! let result = pendulum.integrate((0.0, 10.0), 1e-3, Method::Yoshida4).unwrap();
//! let energy = result.energy.as_ref().unwrap();
//! let drift = (energy[energy.len() - 1] - energy[0]).abs() / energy[0].abs();
//! assert!(drift < 1e-10);
//! ```
#![deny(clippy::float_cmp)]

pub mod classical;

/// The README's Rust example, compiled and run as a doctest so that it stays true.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
