//! `physicskit list`: the catalogue, as text for people or (`--json`) as one JSON object for
//! tools and the browser lab.
//!
//! Both are generated from [`catalog::SYSTEMS`](physicskit::classical::catalog::SYSTEMS) and
//! the method table ([`physicskit::classical::methods`]); nothing here names a system, a
//! default or a method. The methods table is built by [`method_rows`] alone, so a new fact
//! about the methods is a field of [`MethodRow`], a line there and a column in [`text`].

mod json;
mod text;

use std::io::{self, Write};

use physicskit::classical::methods;
use serde::Serialize;

/// Writes the listing to `w`: text, or JSON if `json`.
///
/// # Errors
/// I/O errors of `w` (a closed pipe).
pub fn print(w: &mut impl Write, json: bool) -> io::Result<()> {
    if json {
        json::write(w)
    } else {
        text::write(w)
    }
}

/// What the listings say about one integration method.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRow {
    /// Name, as `--method` takes it.
    pub name: &'static str,
    /// Order of accuracy.
    pub order: u32,
    /// Whether it preserves the symplectic form.
    pub symplectic: bool,
    /// Whether it applies only to separable systems `H = T(p) + V(q)`.
    pub separable_only: bool,
    /// Force or right-hand-side evaluations per step (typical, for implicit methods).
    pub evaluations_per_step: u32,
    /// What `evaluations_per_step` counts.
    pub evaluations: &'static str,
    /// Where the method comes from.
    pub reference: &'static str,
}

/// One row per method, in the method table's order.
pub fn method_rows() -> Vec<MethodRow> {
    methods()
        .iter()
        .map(|m| MethodRow {
            name: m.name,
            order: m.order,
            symplectic: m.symplectic,
            separable_only: m.separable_only,
            evaluations_per_step: m.evaluations_per_step,
            evaluations: m.evaluations,
            reference: m.reference,
        })
        .collect()
}
