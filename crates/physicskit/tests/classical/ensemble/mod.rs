//! Ensembles of catalogue systems and of systems built from named parameters: bit-identity
//! (threads, members vs single runs), events, validation of members before any work.

// Bit-identical reproducibility is the claim here, so exact float comparisons are intended.
#![allow(clippy::float_cmp)]

mod chaos;
mod engine;
mod events;
mod parameters;
mod reductions_lanes;
mod splitting_lanes;
mod taylor_lanes;
mod tolerances;
