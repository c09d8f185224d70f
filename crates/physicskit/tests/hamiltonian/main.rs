//! Physics tests of the Hamiltonian systems, lattice chains and action-angle functions
//! (issue 3). One test binary; its modules mirror `src/classical/systems` and `analysis`.

mod action_angle;
mod chains;
mod common;
mod henon_heiles;
mod kepler;
mod projectile;
mod sizes;
mod swarm;
mod validation;
