//! The spec's systems, one file per family.
//!
//! Hamiltonian (issue 3): `kepler`, `henon_heiles`, `swarm`, `projectile`, `chains`.
//! Lagrangian and rigid bodies (issue 4): `double_pendulum`, `hoop`, `coupled_oscillators`,
//! `symmetric_top`, `rigid_body`.
