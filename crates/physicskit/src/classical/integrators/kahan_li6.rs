//! `kahan_li6`: Kahan and Li's optimized sixth-order composition of Störmer–Verlet, s9odr6a.
//!
//! W. Kahan, R.-C. Li, "Composition constants for raising the orders of unconventional
//! schemes for ordinary differential equations", Math. Comp. 66 (1997) 1089–1099, scheme
//! s9odr6a: nine Verlet substeps `g1 h, ..., g5 h, ..., g1 h` (symmetric), the weights as
//! published there to 26 digits (also in OrdinaryDiffEq.jl's `KahanLi6`).
//!
//! Order 6, symplectic and time-reversible (the composition is symmetric). Adjacent half-kicks
//! of consecutive substeps merge and the last force is reused by the next step, so a step
//! costs nine force evaluations. Needs a separable `H = T(p) + V(q)` with conservative forces.

use super::splitting::{composition_kicks, mirrored};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The published weights `g1..g5` of s9odr6a, the last one the middle substep.
// The published digits, verbatim, so that they can be checked against the source; the
// compiler rounds each once to the nearest double.
#[allow(clippy::excessive_precision)]
pub const HALF: [f64; 5] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
    0.798_543_990_934_829_963_398_950_35,
];

/// Drift weights of the nine Störmer–Verlet substeps (the published weights, mirrored).
pub const DRIFTS: [f64; 9] = mirrored(&HALF);

/// Kick weights: the touching half-kicks of consecutive substeps merged.
pub const KICKS: [f64; 10] = composition_kicks(&DRIFTS);

/// The facts about `kahan_li6`.
pub const INFO: MethodInfo = MethodInfo {
    name: "kahan_li6",
    label: "Kahan–Li 6",
    summary: "Kahan–Li optimized sixth-order composition of Störmer–Verlet (s9odr6a, 9 substeps)",
    order: 6,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 9,
    evaluations: "force evaluations, exact (touching half-kicks merged, the last force reused)",
    reference: "W. Kahan, R.-C. Li, Math. Comp. 66 (1997) 1089–1099, scheme s9odr6a",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
