//! `implicit_midpoint`: the implicit midpoint rule.
//!
//! ```text
//! y1 = y0 + h f(t + h/2, (y0 + y1)/2)
//! ```
//!
//! written as an equation for the midpoint slope `k`, `k = f(t + h/2, y0 + (h/2) k)`,
//! `y1 = y0 + h k`: the one-stage implicit Runge–Kutta method with tableau `a = 1/2`, `b = 1`,
//! `c = 1/2` (the one-stage Gauss–Legendre collocation method). Order 2, symmetric
//! (time-reversible), symplectic for every Hamiltonian (separable or not), and it conserves
//! every quadratic invariant of any ODE exactly, up to the accuracy of the solve (G. J. Cooper,
//! IMA J. Numer. Anal. 7 (1987) 1–13; Hairer, Lubich, Wanner, *Geometric Numerical Integration*
//! (2006), §IV.2).
//!
//! The stage equation is solved by the shared implicit solve
//! ([`implicit_solve`](super::implicit_solve)): fixed-point sweeps from a cubic extrapolation
//! of the last four slopes, iterated to the rounding floor, with Newton's method on
//! `k - f(t + h/2, y0 + h k/2) = 0` where the sweeps contract slowly and the field has a
//! Jacobian. At the small steps symplectic runs use, a step costs two evaluations of `f`.

use super::implicit_solve::{ButcherTableau, ImplicitRk, Tableau};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The facts about `implicit_midpoint`.
pub const INFO: MethodInfo = MethodInfo {
    name: "implicit_midpoint",
    label: "implicit midpoint",
    summary: "implicit midpoint rule; symplectic for any Hamiltonian, keeps quadratic invariants",
    order: 2,
    symplectic: true,
    separable_only: false,
    evaluations_per_step: 2,
    evaluations: "right-hand-side evaluations, typical: the solve iterates to the rounding floor, \
                  which takes two fixed-point sweeps at small steps and more at large ones, plus \
                  Jacobian evaluations where Newton's method is needed",
    reference: "G. J. Cooper, IMA J. Numer. Anal. 7 (1987) 1–13; Hairer, Lubich, Wanner, \
                Geometric Numerical Integration (2006), §IV.2",
    scheme: Scheme::ImplicitRk,
};

/// The implicit midpoint rule's tableau.
#[derive(Debug, Clone, Copy)]
pub struct MidpointRule;

impl ButcherTableau<1> for MidpointRule {
    /// One stage: `k = f(t + h/2, y0 + (h/2) k)`, `y1 = y0 + h k`.
    const TABLEAU: Tableau<1> = Tableau {
        a: [[0.5]],
        b: [1.0],
        c: [0.5],
    };
}

/// The implicit midpoint stepper: the shared implicit solve on [`MidpointRule`].
pub type ImplicitMidpoint = ImplicitRk<1, MidpointRule>;
