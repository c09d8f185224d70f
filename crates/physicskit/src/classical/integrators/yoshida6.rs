//! `yoshida6`: Yoshida's sixth-order composition of Störmer–Verlet, solution A.
//!
//! H. Yoshida, "Construction of higher order symplectic integrators", Phys. Lett. A 150
//! (1990) 262–268, Table 1, solution A: seven Verlet substeps of lengths
//! `w3 h, w2 h, w1 h, w0 h, w1 h, w2 h, w3 h`, with `w1, w2, w3` as printed there (15
//! significant digits, all the paper gives; they are roots of Yoshida's order-6 equations, so
//! those hold to ~1e-15) and `w0 = 1 - 2 (w1 + w2 + w3)` (consistency).
//!
//! Order 6, symplectic and time-reversible (the composition is symmetric). Adjacent half-kicks
//! of consecutive substeps merge and the last force is reused by the next step, so a step
//! costs seven force evaluations. Needs a separable `H = T(p) + V(q)` with conservative forces.

use super::splitting::{composition_kicks, mirrored};
use crate::classical::core::method::{MethodInfo, Scheme};

/// `w1` of solution A (Yoshida 1990, Table 1).
pub const W1: f64 = -1.177_679_984_178_87;
/// `w2` of solution A.
pub const W2: f64 = 0.235_573_213_359_357;
/// `w3` of solution A (the outermost substeps).
pub const W3: f64 = 0.784_513_610_477_560;
/// `w0 = 1 - 2 (w1 + w2 + w3)`, the middle substep.
pub const W0: f64 = 1.0 - 2.0 * (W1 + W2 + W3);

/// The first half of the substep weights, up to the middle one.
pub const HALF: [f64; 4] = [W3, W2, W1, W0];

/// Drift weights of the seven Störmer–Verlet substeps (the published weights, mirrored).
pub const DRIFTS: [f64; 7] = mirrored(&HALF);

/// Kick weights: the touching half-kicks of consecutive substeps merged.
pub const KICKS: [f64; 8] = composition_kicks(&DRIFTS);

/// The facts about `yoshida6`.
pub const INFO: MethodInfo = MethodInfo {
    name: "yoshida6",
    label: "Yoshida 6",
    summary: "Yoshida's sixth-order composition of Störmer–Verlet (solution A, 7 substeps)",
    order: 6,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 7,
    evaluations: "force evaluations, exact (touching half-kicks merged, the last force reused)",
    reference: "H. Yoshida, Phys. Lett. A 150 (1990) 262–268, Table 1, solution A",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
