//! Benchmarks of physicskit: the peer-comparison workloads ([`workloads`]), the plain-loop
//! references ([`plain`]) that the library's per-step time is held against, and what the
//! ensemble binaries share ([`ensembles`]).

pub mod ensembles;
pub mod plain;
pub mod workloads;

// A unit test rather than an integration test: an integration test makes `cargo test` build
// the package's six binaries too (about a minute of CI on two cores).
#[cfg(test)]
mod plain_agrees;
