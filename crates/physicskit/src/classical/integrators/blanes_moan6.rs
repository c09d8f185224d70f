//! `blanes_moan6`: Blanes and Moan's optimized sixth-order symplectic partitioned
//! Runge–Kutta method (S6).
//!
//! S. Blanes, P. C. Moan, "Practical symplectic partitioned Runge–Kutta and
//! Runge–Kutta–Nyström methods", J. Comput. Appl. Math. 142 (2002) 313–330, Table 2, the
//! sixth-order PRK method with `s = 10` (S6):
//!
//! ```text
//! e^{a1 h A} e^{b1 h B} e^{a2 h A} ... e^{b5 h B} e^{a6 h A} e^{b5 h B} ... e^{b1 h B} e^{a1 h A}
//! ```
//!
//! with `a1..a5`, `b1..b4` as printed there (15 significant digits, all the paper gives),
//! `a6 = 1 - 2 (a1 + ... + a5)` and `b5 = 1/2 - (b1 + ... + b4)`. Unlike the compositions of
//! Störmer–Verlet, its kick and drift weights are independent. Its order conditions are those
//! of a general splitting `H = A + B`, so either part may be either flow; here `A` is the
//! potential (eleven kicks) and `B` the kinetic energy (ten drifts), which lets the last kick's
//! force be the next step's first.
//!
//! Order 6, symplectic and time-reversible (both weight sequences are palindromes). Ten force
//! evaluations per step. Needs a separable `H = T(p) + V(q)` with conservative forces.

use super::splitting::mirrored;
use crate::classical::core::method::{MethodInfo, Scheme};

const A1: f64 = 0.050_262_764_400_392_2;
const A2: f64 = 0.413_514_300_428_344;
const A3: f64 = 0.045_079_889_794_397_7;
const A4: f64 = -0.188_054_853_819_569;
const A5: f64 = 0.541_960_678_450_780;
const B1: f64 = 0.148_816_447_901_042;
const B2: f64 = -0.132_385_865_767_784;
const B3: f64 = 0.067_307_604_692_185;
const B4: f64 = 0.432_666_402_578_175;

/// The first half of the kick weights `a1..a6` (Table 2), `a6 = 1 - 2 (a1 + ... + a5)` the
/// middle one.
pub const KICKS_HALF: [f64; 6] = [A1, A2, A3, A4, A5, 1.0 - 2.0 * (A1 + A2 + A3 + A4 + A5)];

/// The first half of the drift weights `b1..b5` (Table 2), `b5 = 1/2 - (b1 + ... + b4)`.
pub const DRIFTS_HALF: [f64; 5] = [B1, B2, B3, B4, 0.5 - (B1 + B2 + B3 + B4)];

/// The eleven kick weights.
pub const KICKS: [f64; 11] = mirrored(&KICKS_HALF);

/// The ten drift weights.
pub const DRIFTS: [f64; 10] = mirrored(&DRIFTS_HALF);

/// The facts about `blanes_moan6`.
pub const INFO: MethodInfo = MethodInfo {
    name: "blanes_moan6",
    label: "Blanes–Moan 6",
    summary: "Blanes–Moan optimized sixth-order symplectic partitioned Runge–Kutta (S6)",
    order: 6,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 10,
    evaluations: "force evaluations, exact (the last force reused as the next step's first)",
    reference: "S. Blanes, P. C. Moan, J. Comput. Appl. Math. 142 (2002) 313–330, Table 2, S6",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
