//! Benchmarks of physicskit: the peer-comparison workloads ([`workloads`]) and the plain-loop
//! references ([`plain`]) that the library's per-step time is held against.

pub mod plain;
pub mod workloads;
