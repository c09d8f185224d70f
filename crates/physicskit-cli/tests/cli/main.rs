//! Integration tests of the `physicskit` command: one test binary whose modules follow the
//! commands in `src/` (`list`, `simulate`'s output and errors, `lyapunov` and `poincare`), each running the built
//! binary in a scratch directory.

mod chaos;
mod common;

mod ensemble;
mod errors;
mod list;
mod roundtrip;
mod scenario;
