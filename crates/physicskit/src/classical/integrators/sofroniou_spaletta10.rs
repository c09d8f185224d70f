//! `sofroniou_spaletta10`: Sofroniou and Spaletta's tenth-order composition of
//! Störmer–Verlet, s35odr10.
//!
//! M. Sofroniou, G. Spaletta, "Derivation of symmetric composition constants for symmetric
//! integrators", Optim. Methods Softw. 20 (2005) 597–613, scheme s35odr10 (their optimized
//! 35-substep tenth-order solution; OrdinaryDiffEq.jl's `SofSpa10`): thirty-five Verlet
//! substeps `g1 h, ..., g18 h, ..., g1 h` (symmetric), the weights as published to 26 digits.
//!
//! Order 10, symplectic and time-reversible (the composition is symmetric). Adjacent
//! half-kicks of consecutive substeps merge and the last force is reused by the next step, so a
//! step costs thirty-five force evaluations. Needs a separable `H = T(p) + V(q)` with
//! conservative forces.

use super::splitting::{composition_kicks, mirrored};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The published weights `g1..g18` of s35odr10, the last one the middle substep.
// The published digits, verbatim, so that they can be checked against the source; the
// compiler rounds each once to the nearest double.
#[allow(clippy::excessive_precision)]
pub const HALF: [f64; 18] = [
    0.078_795_722_521_686_419_263_907_68,
    0.313_096_103_415_108_527_764_812_47,
    0.027_918_383_235_078_066_109_520_27,
    -0.229_592_841_593_907_094_151_213_40,
    0.130_962_061_077_164_863_174_656_86,
    -0.269_733_405_654_510_714_344_609_73,
    0.074_973_343_155_891_435_666_137_11,
    0.111_993_423_999_810_204_889_575_08,
    0.366_133_449_546_226_751_193_148_12,
    -0.399_105_630_136_035_897_878_629_81,
    0.103_087_398_527_471_077_315_802_77,
    0.411_430_873_955_890_237_820_704_12,
    -0.004_866_360_583_135_261_762_195_66,
    -0.392_033_353_708_639_906_448_081_94,
    0.051_942_502_962_449_647_037_182_90,
    0.050_665_090_759_924_496_335_874_34,
    0.049_674_370_639_729_879_054_568_80,
    0.049_317_735_759_594_537_917_680_01,
];

/// Drift weights of the thirty-five Störmer–Verlet substeps (the published weights, mirrored).
pub const DRIFTS: [f64; 35] = mirrored(&HALF);

/// Kick weights: the touching half-kicks of consecutive substeps merged.
pub const KICKS: [f64; 36] = composition_kicks(&DRIFTS);

/// The facts about `sofroniou_spaletta10`.
pub const INFO: MethodInfo = MethodInfo {
    name: "sofroniou_spaletta10",
    label: "Sofroniou–Spaletta 10",
    summary: "Sofroniou–Spaletta tenth-order composition of Störmer–Verlet (s35odr10, 35 \
              substeps)",
    order: 10,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 35,
    evaluations: "force evaluations, exact (touching half-kicks merged, the last force reused)",
    reference: "M. Sofroniou, G. Spaletta, Optim. Methods Softw. 20 (2005) 597–613, scheme \
                s35odr10",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
