//! The catalogue as data for front ends: the methods table ([`method_rows`]) and the whole
//! catalogue as one JSON object ([`catalogue_json`]).
//!
//! Both are generated from [`catalog::SYSTEMS`](physicskit::classical::catalog::SYSTEMS) and
//! the method table ([`physicskit::classical::methods`]); nothing here names a system, a
//! default or a method. The command line prints this JSON as `physicskit list --json`, and the
//! browser lab (`physicskit-wasm`) hands the same string to its page, so the two cannot
//! disagree. A new fact about the methods is a field of [`MethodRow`] and a line in
//! [`method_rows`].

mod json;
pub mod people;

use physicskit::classical::methods;
use serde::Serialize;

pub use json::{catalogue_json, write_json};

/// What the listings say about one integration method.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRow {
    /// Name, as `--method` takes it.
    pub name: &'static str,
    /// The name in words, for titles and legends.
    pub label: &'static str,
    /// Order of accuracy.
    pub order: u32,
    /// Whether it preserves the symplectic form.
    pub symplectic: bool,
    /// Whether it applies only to separable systems `H = T(p) + V(q)`.
    pub separable_only: bool,
    /// Whether its step adapts to tolerances (`dt` is then the output spacing); the browser
    /// lab then offers a tolerance in place of the step.
    pub adaptive: bool,
    /// Whether it runs only on systems with a Taylor form (defined by expressions: the
    /// symbolic engines), which no catalogue system has.
    pub needs_taylor_form: bool,
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
            label: m.label,
            order: m.order,
            symplectic: m.symplectic,
            separable_only: m.separable_only,
            adaptive: m.is_adaptive(),
            needs_taylor_form: m.needs_taylor_form(),
            evaluations_per_step: m.evaluations_per_step,
            evaluations: m.evaluations,
            reference: m.reference,
        })
        .collect()
}
