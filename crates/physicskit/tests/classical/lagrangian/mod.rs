//! The Lagrangian engine: automatic differentiation against equations of motion derived by
//! hand, and the built-in systems' closed forms against automatic differentiation; the
//! expression-defined Hamiltonians and ODEs against built-in and hand-written systems; their
//! tapes compiled to machine code against the interpreter.

mod closed_forms;
mod engine;
mod expr_systems;
mod jacobians;
mod jit;
