//! Integration tests of the `physicskit` command: one test binary whose modules follow the
//! commands in `src/` (`list`, and `simulate`'s output and errors), each running the built
//! binary in a scratch directory.

mod common;

mod ensemble;
mod errors;
mod list;
mod roundtrip;
