//! `verlet`: the Störmer–Verlet (leapfrog) method in kick–drift–kick form.
//!
//! ```text
//! p_{1/2} = p_0 + (h/2) F(q_0)
//! q_1     = q_0 + h M^-1 p_{1/2}
//! p_1     = p_{1/2} + (h/2) F(q_1)
//! ```
//!
//! L. Verlet, Phys. Rev. 159 (1967) 98; E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical
//! Integration*, 2nd ed. (2006), §I.3. Order 2, symplectic, time-reversible. `F(q_1)` is reused
//! as the next step's first kick, so a step costs one force evaluation. Needs a separable
//! `H = T(p) + V(q)` with conservative forces.

use super::splitting::composition_kicks;
use crate::classical::core::method::{MethodInfo, Scheme};

/// Drift weights: a single full drift.
pub const DRIFTS: [f64; 1] = [1.0];

/// Kick weights: the two half-kicks.
pub const KICKS: [f64; 2] = composition_kicks(&DRIFTS);

/// The facts about `verlet`.
pub const INFO: MethodInfo = MethodInfo {
    name: "verlet",
    label: "Störmer–Verlet",
    summary: "Störmer–Verlet leapfrog, kick–drift–kick",
    order: 2,
    symplectic: true,
    separable_only: true,
    evaluations_per_step: 1,
    evaluations: "force evaluations, exact (the last force is reused as the next step's first)",
    reference: "L. Verlet, Phys. Rev. 159 (1967) 98; Hairer, Lubich, Wanner, Geometric \
                Numerical Integration (2006), §I.3",
    scheme: Scheme::Splitting {
        kicks: &KICKS,
        drifts: &DRIFTS,
    },
};
