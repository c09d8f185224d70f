//! The catalogue: every built-in system, once, as data that every front end reads.
//!
//! Each entry ([`SystemEntry`]) is written next to its system in `systems/` (or `examples.rs`)
//! and names the system, its typed parameters with defaults, units and ranges, the methods
//! that apply and a builder into the type-erased [`DynSystem`]. The command line (`list`,
//! `simulate`, `--help`, `list --json`), the Python extension (`_core.build`,
//! `_core.catalog`) and the lab iterate over [`SYSTEMS`] (kept in `systems/mod.rs`, next to the
//! `mod` line of each system's file); none of them lists systems or defaults of its own. See
//! [`model::entry`](crate::classical::model::entry) for the vocabulary and where values are
//! checked. The catalogue's tests (every entry built, run with every method it lists and
//! refused by every other, its ranges the constructors' own) are in `tests/classical/catalog.rs`.
//!
//! # Example
//! ```
//! use physicskit::classical::catalog;
//! use physicskit::classical::model::entry::Value;
//!
//! let entry = catalog::find("double-pendulum")?;
//! let mut system = entry.build_from([("m2".to_string(), Value::Scalar(2.0))])?;
//! let result = system.integrate((0.0, 1.0), 1e-3, system.default_method(), Default::default())?;
//! assert_eq!(result.t.len(), 1001);
//! # Ok::<(), physicskit::classical::Error>(())
//! ```

use crate::classical::core::{Error, Result};
use crate::classical::model::{DynSystem, SystemEntry};

pub use crate::classical::systems::SYSTEMS;

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
    given: impl IntoIterator<Item = (String, crate::classical::model::Value)>,
) -> Result<Box<dyn DynSystem>> {
    find(name)?.build_from(given)
}
