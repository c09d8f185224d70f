//! Tests of the core engine: integrators, drivers, validation. One binary; modules by topic.

// Bit-identical reproducibility and exact clock values are claims of their own here, so exact
// float comparisons are intended.
#![allow(clippy::float_cmp)]

mod continuation;
mod convergence;
mod energy_behaviour;
mod ensemble;
mod fixtures;
mod fused_potential;
mod invariants;
mod lagrangian_path;
mod methods;
mod reversibility;
mod sampling;
mod solver;
mod validation;
