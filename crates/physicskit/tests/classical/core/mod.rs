//! The core types: a run continuing from the stored phase, sampling and the result's layout,
//! one test per validation rule.

// Bit-identical reproducibility and exact clock values are claims of their own here, so exact
// float comparisons are intended.
#![allow(clippy::float_cmp)]

mod continuation;
mod presentation;
mod sampling;
mod validation;
