//! The spec's systems, one file per family.
//!
//! Hamiltonian (issue 3): `kepler`, `henon_heiles`, `swarm`, `projectile`, `chains`; and
//! the integrable `toda` lattice.
//! Lagrangian and rigid bodies (issue 4): `double_pendulum`, `hoop`, `coupled_oscillators`,
//! `symmetric_top`, `rigid_body`; and the `elastic_pendulum`.

mod kepler;
pub use kepler::*;
mod henon_heiles;
pub use henon_heiles::*;
mod swarm;
pub use swarm::*;
mod projectile;
pub use projectile::*;
mod chains;
pub use chains::*;
mod toda;
pub use toda::*;
mod double_pendulum;
pub use double_pendulum::*;
mod hoop;
pub use hoop::*;
mod coupled_oscillators;
pub use coupled_oscillators::*;
mod symmetric_top;
pub use symmetric_top::*;
mod rigid_body;
pub use rigid_body::*;
mod elastic_pendulum;
pub use elastic_pendulum::*;
