//! # physicskit-wasm
//!
//! The physicskit core compiled for `wasm32-unknown-unknown`, for the browser lab (`web/`).
//!
//! - [`Lab`] is one running system: built by name from the catalogue
//!   (`classical::catalog::SYSTEMS`) with parameters given as JSON, stepped `n` steps at a
//!   time with any method of the method table through the type-erased
//!   [`DynSystem`](physicskit::classical::model::erased::DynSystem), and read: state, time,
//!   energy and its relative error `|E - E0| / |E0|`, drawing positions (the `positions`
//!   capability) and the crossings of a Poincaré section (located by Hénon's trick,
//!   `analysis::poincare::henon_step`), each with the number of its orbit: orbits launched
//!   on the section at the run's energy accumulate; the energy of any state (the page traces
//!   the section's edge with it). It is plain safe Rust and runs natively too: the
//!   native run of the same setup is what the wasm build is compared with
//!   (`src/bin/lab_reference.rs`, `web/test/node_compare.mjs`).
//! - [`exports`] are the `extern "C"` functions the page calls: handles into a slab of
//!   [`Lab`]s, buffers the handle owns, read by the page as typed-array views of the linear
//!   memory, and errors returned as status codes with a message the page reads (every path
//!   is a `Result`: a panic would abort the module).
//! - Parameters come as JSON from the page or a share link, untrusted: a count `n` above
//!   [`MAX_LAB_COUNT`] is refused before anything is allocated.
//! - The catalogue JSON the page builds its pickers from is
//!   [`physicskit_listing::catalogue_json`], the string `physicskit list --json` prints.
//!
//! Why plain exports and not wasm-bindgen: the build needs only `rustup target add
//! wasm32-unknown-unknown` (no `wasm-bindgen-cli` whose version must match the crate's, no
//! generated glue to keep in step), and the surface is a dozen numeric functions that
//! typed-array views serve without copies.

pub mod exports;
mod lab;
mod params;

pub use lab::{method_order, Lab};
pub use params::{values_from_json, MAX_LAB_COUNT};
