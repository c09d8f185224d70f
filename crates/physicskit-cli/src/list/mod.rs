//! `physicskit list`: the catalogue, as text for people or (`--json`) as one JSON object for
//! tools and the browser lab.
//!
//! Both are generated from [`catalog::SYSTEMS`](physicskit::classical::catalog::SYSTEMS) and
//! the method table ([`physicskit::classical::methods`]); nothing here names a system, a
//! default or a method. The methods table is built by [`method_rows`] alone, so a new fact
//! about the methods is a field of [`MethodRow`], a line there and a column in [`text`].

mod text;

use std::io::{self, Write};

pub use physicskit_listing::{method_rows, MethodRow};

/// Writes the listing to `w`: text, or JSON if `json`.
///
/// # Errors
/// I/O errors of `w` (a closed pipe).
pub fn print(w: &mut impl Write, json: bool) -> io::Result<()> {
    if json {
        physicskit_listing::write_json(w)
    } else {
        text::write(w)
    }
}
