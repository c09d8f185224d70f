//! The integrators and their drivers: measured convergence orders, bounded vs drifting energy,
//! time reversibility, quadratic invariants, the implicit-midpoint solve, ensembles, the stored
//! energy of splitting methods and their compensated sums, the Lagrangian path, the adaptive
//! dop853 and the adaptive Taylor method.

// Bit-identical reproducibility and exact clock values are claims of their own here, so exact
// float comparisons are intended.
#![allow(clippy::float_cmp)]

mod coefficients;
mod compensated;
mod convergence;
mod dop853;
mod energy_behaviour;
mod ensemble;
mod ensemble_wait;
mod fused_potential;
mod implicit_midpoint;
mod invariants;
mod lagrangian_path;
mod methods;
mod reversibility;
mod session;
mod taylor;
mod taylor_builtin;
mod taylor_jit;
mod taylor_lanes;
