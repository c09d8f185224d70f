//! The Lagrangian engine: automatic differentiation against equations of motion derived by
//! hand, and the built-in systems' closed forms against automatic differentiation.

mod closed_forms;
mod engine;
