//! `yoshida4`: Yoshida's fourth-order triple-jump composition of Störmer–Verlet.
//!
//! H. Yoshida, "Construction of higher order symplectic integrators", Phys. Lett. A 150
//! (1990) 262–268, eq. (4.4)–(4.5): three Verlet substeps of lengths `w1 h`, `w0 h`, `w1 h`
//! with
//!
//! ```text
//! w1 = 1 / (2 - 2^(1/3)),    w0 = -2^(1/3) / (2 - 2^(1/3)) = 1 - 2 w1
//! ```
//!
//! Order 4, symplectic and time-reversible (the composition is symmetric). Adjacent kicks of
//! consecutive substeps merge, so a step costs three force evaluations, and the last force is
//! reused by the next step. Needs a separable `H = T(p) + V(q)` with conservative forces.

use super::splitting::composition_kicks;
use crate::classical::core::method::{MethodInfo, Scheme};

/// `w1 = 1 / (2 - 2^(1/3))`, the outer substep weight.
pub const W1: f64 = 1.351_207_191_959_657_6;

/// `w0 = -2^(1/3) / (2 - 2^(1/3))`, the (negative) middle substep weight.
pub const W0: f64 = -1.702_414_383_919_315_3;

/// Drift weights of the three substeps.
pub const DRIFTS: [f64; 3] = [W1, W0, W1];

/// Kick weights: the touching half-kicks of consecutive substeps merged.
pub const KICKS: [f64; 4] = composition_kicks(&DRIFTS);

/// The facts about `yoshida4`.
pub const INFO: MethodInfo = MethodInfo {
    name: "yoshida4",
    label: "Yoshida 4",
    summary: "Yoshida's fourth-order triple-jump composition of Störmer–Verlet",
    order: 4,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 3,
    evaluations: "force evaluations, exact (touching half-kicks merged, the last force reused)",
    reference: "H. Yoshida, Phys. Lett. A 150 (1990) 262–268",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_match_their_closed_form() {
        let c = 2.0_f64.cbrt();
        // Both sides are one or two roundings away from the exact real number: 2 ulps.
        assert!((W1 - 1.0 / (2.0 - c)).abs() <= 2.0 * f64::EPSILON * W1);
        assert!((W0 + c / (2.0 - c)).abs() <= 2.0 * f64::EPSILON * W0.abs());
        // Consistency (weights sum to one step) and the order-3 condition 2 w1^3 + w0^3 = 0.
        assert!((2.0 * W1 + W0 - 1.0).abs() <= 4.0 * f64::EPSILON);
        assert!((2.0 * W1.powi(3) + W0.powi(3)).abs() <= 32.0 * f64::EPSILON);
    }
}
