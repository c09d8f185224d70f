//! The catalogue: every built-in system, once, as data that every front end reads.
//!
//! Each entry ([`SystemEntry`]) is written next to its system in `systems/` (or `examples.rs`)
//! and names the system, its typed parameters with defaults, units and ranges, the methods
//! that apply and a builder into the type-erased [`DynSystem`]. The command line (`list`,
//! `simulate`, `--help`, `list --json`), the Python extension (`_core.build`,
//! `_core.catalog`) and the lab iterate over [`SYSTEMS`]; none of them lists systems or
//! defaults of its own. See [`core::catalog`](crate::classical::core::catalog) for the
//! vocabulary and where values are checked.
//!
//! # Example
//! ```
//! use physicskit::classical::catalog;
//! use physicskit::classical::core::catalog::Value;
//!
//! let entry = catalog::find("double-pendulum")?;
//! let mut system = entry.build_from([("m2".to_string(), Value::Scalar(2.0))])?;
//! let result = system.integrate((0.0, 1.0), 1e-3, system.default_method(), Default::default())?;
//! assert_eq!(result.t.len(), 1001);
//! # Ok::<(), physicskit::classical::Error>(())
//! ```

use crate::classical::core::{DynSystem, Error, Result, SystemEntry};
use crate::classical::{examples, systems};

/// Every built-in system, in the order listings show them.
pub static SYSTEMS: &[&SystemEntry] = &[
    &examples::PENDULUM_ENTRY,
    &examples::HARMONIC_OSCILLATOR_ENTRY,
    &systems::KEPLER_ENTRY,
    &systems::KEPLER_STATE_ENTRY,
    &systems::HENON_HEILES_ENTRY,
    &systems::SWARM_ENTRY,
    &systems::SWARM_STATE_ENTRY,
    &systems::PROJECTILE_ENTRY,
    &systems::PROJECTILE_STATE_ENTRY,
    &systems::HARMONIC_CHAIN_ENTRY,
    &systems::FPUT_ENTRY,
    &systems::SINE_GORDON_KINK_ENTRY,
    &systems::SINE_GORDON_STATE_ENTRY,
    &systems::DOUBLE_PENDULUM_ENTRY,
    &systems::HOOP_ENTRY,
    &systems::COUPLED_OSCILLATORS_ENTRY,
    &systems::HEAVY_TOP_ENTRY,
    &systems::EULER_TOP_ENTRY,
];

/// The entry called `name`.
///
/// # Errors
/// [`Error::UnknownSystem`] listing the known names.
pub fn find(name: &str) -> Result<&'static SystemEntry> {
    SYSTEMS
        .iter()
        .copied()
        .find(|e| e.name == name)
        .ok_or_else(|| Error::UnknownSystem {
            name: name.into(),
            valid: SYSTEMS
                .iter()
                .map(|e| e.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// Builds the system `name` from its defaults, overridden by `given`.
///
/// # Errors
/// As [`find`] and [`SystemEntry::build_from`].
pub fn build(
    name: &str,
    given: impl IntoIterator<Item = (String, crate::classical::core::Value)>,
) -> Result<Box<dyn DynSystem>> {
    find(name)?.build_from(given)
}
