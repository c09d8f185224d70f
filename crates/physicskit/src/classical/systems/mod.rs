//! The built-in systems, one file per family, each with its catalogue entry.
//!
//! Hamiltonian: `kepler`, `henon_heiles`, `swarm`, `projectile`, `chains`, and the integrable
//! `toda` lattice. Lagrangian and rigid bodies: `double_pendulum`, `hoop`,
//! `coupled_oscillators`, `symmetric_top`, `rigid_body`, `elastic_pendulum`.

use crate::classical::model::SystemEntry;

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
mod foucault;
pub use foucault::*;
mod eulers_disk;
pub use eulers_disk::*;
mod rattleback;
pub use rattleback::*;
mod rolling;
pub use rolling::*;

/// Every built-in system of the catalogue, in the order listings show them: one line per
/// entry, each written next to its system.
pub static SYSTEMS: &[&SystemEntry] = &[
    &crate::classical::examples::PENDULUM_ENTRY,
    &crate::classical::examples::HARMONIC_OSCILLATOR_ENTRY,
    &KEPLER_ENTRY,
    &KEPLER_STATE_ENTRY,
    &HENON_HEILES_ENTRY,
    &SWARM_ENTRY,
    &SWARM_STATE_ENTRY,
    &PROJECTILE_ENTRY,
    &PROJECTILE_STATE_ENTRY,
    &HARMONIC_CHAIN_ENTRY,
    &FPUT_ENTRY,
    &SINE_GORDON_KINK_ENTRY,
    &SINE_GORDON_STATE_ENTRY,
    &DOUBLE_PENDULUM_ENTRY,
    &HOOP_ENTRY,
    &COUPLED_OSCILLATORS_ENTRY,
    &HEAVY_TOP_ENTRY,
    &EULER_TOP_ENTRY,
    &TODA_ENTRY,
    &ELASTIC_PENDULUM_ENTRY,
    &ROLLING_RATTLEBACK_ENTRY,
    &ROLLING_DISK_ENTRY,
    &ROLLING_DISK_STEADY_ENTRY,
    &FOUCAULT_ENTRY,
    &EULERS_DISK_ENTRY,
    &RATTLEBACK_ENTRY,
];
