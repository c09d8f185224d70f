//! Integration tests of `physicskit::classical`: one test binary (one link of the crate)
//! whose modules mirror `src/classical/`. A test of `src/classical/X/y.rs` goes in `X/y.rs`
//! here (or in the file of its topic), declared in `X/mod.rs`.

mod checks;
mod fixtures;

mod analysis;
mod catalog;
mod core;
mod digests;
mod ensemble;
mod integrators;
mod lagrangian;
mod systems;
