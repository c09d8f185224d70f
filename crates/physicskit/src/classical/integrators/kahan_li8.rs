//! `kahan_li8`: Kahan and Li's optimized eighth-order composition of Störmer–Verlet,
//! s17odr8a.
//!
//! W. Kahan, R.-C. Li, "Composition constants for raising the orders of unconventional
//! schemes for ordinary differential equations", Math. Comp. 66 (1997) 1089–1099, scheme
//! s17odr8a (the first of their two 17-substep eighth-order schemes; the one OrdinaryDiffEq.jl
//! ships as `KahanLi8`): seventeen Verlet substeps `g1 h, ..., g9 h, ..., g1 h` (symmetric),
//! the weights as published there to 26 digits.
//!
//! Order 8, symplectic and time-reversible (the composition is symmetric). Adjacent half-kicks
//! of consecutive substeps merge and the last force is reused by the next step, so a step
//! costs seventeen force evaluations. Needs a separable `H = T(p) + V(q)` with conservative
//! forces.

use super::splitting::{composition_kicks, mirrored};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The published weights `g1..g9` of s17odr8a, the last one the middle substep.
// The published digits, verbatim, so that they can be checked against the source; the
// compiler rounds each once to the nearest double.
#[allow(clippy::excessive_precision)]
pub const HALF: [f64; 9] = [
    0.130_202_483_088_890_080_878_817_63,
    0.561_162_981_775_108_384_561_964_41,
    -0.389_474_962_644_847_286_408_078_60,
    0.158_841_906_555_155_600_896_210_75,
    -0.395_903_894_133_237_577_336_231_54,
    0.184_539_640_978_315_707_091_832_54,
    0.258_374_387_686_322_047_293_979_11,
    0.295_011_723_609_310_298_870_966_24,
    -0.605_508_533_830_034_511_698_921_08,
];

/// Drift weights of the seventeen Störmer–Verlet substeps (the published weights, mirrored).
pub const DRIFTS: [f64; 17] = mirrored(&HALF);

/// Kick weights: the touching half-kicks of consecutive substeps merged.
pub const KICKS: [f64; 18] = composition_kicks(&DRIFTS);

/// The facts about `kahan_li8`.
pub const INFO: MethodInfo = MethodInfo {
    name: "kahan_li8",
    label: "Kahan–Li 8",
    summary: "Kahan–Li optimized eighth-order composition of Störmer–Verlet (s17odr8a, 17 \
              substeps)",
    order: 8,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 17,
    evaluations: "force evaluations, exact (touching half-kicks merged, the last force reused)",
    reference: "W. Kahan, R.-C. Li, Math. Comp. 66 (1997) 1089–1099, scheme s17odr8a",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
