//! Benchmarks of physicskit: the peer-comparison workloads ([`workloads`]) and the plain-loop
//! references ([`plain`]) that the library's per-step time is held against.

pub mod plain;
pub mod workloads;

// A unit test rather than an integration test: an integration test makes `cargo test` build
// the package's six binaries too (about a minute of CI on two cores).
#[cfg(test)]
mod plain_agrees;
