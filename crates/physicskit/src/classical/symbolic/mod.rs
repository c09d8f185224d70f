//! Systems written as expressions (the SymPy bridge): expression trees and their symbolic
//! derivatives, tapes (straight-line programs compiled once from them, with Cranelift with
//! the feature `jit`), and the engines on them: expression Lagrangians (through the
//! Lagrangian engine), Hamiltonians and first-order ODEs.

mod expr;
mod expr_diff;
mod expr_hamiltonian;
mod expr_ode;
mod hash_cons;
mod tape;
mod taylor_tape;
mod trace;
pub use expr::*;
pub use expr_diff::*;
pub use expr_hamiltonian::*;
pub use expr_ode::*;
pub use tape::*;
pub use taylor_tape::{native_lanes, TaylorLanes, TaylorProgram};
pub use trace::{
    trace_hamiltonian, trace_lagrangian, traced_hamiltonian_taylor_field, traced_taylor_field,
    TracedHamiltonian,
};
