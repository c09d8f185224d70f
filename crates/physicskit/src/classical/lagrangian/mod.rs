//! The Lagrangian engine: equations of motion from `L(q, qdot, t)` by automatic differentiation.
