//! `gauss_legendre4`: the two-stage Gauss–Legendre collocation method.
//!
//! The implicit Runge–Kutta method whose nodes are the zeros of the shifted Legendre
//! polynomial of degree 2, `c = 1/2 ∓ sqrt(3)/6` (J. C. Butcher, Math. Comp. 18 (1964) 50–64;
//! Hairer, Lubich, Wanner, *Geometric Numerical Integration* (2006), §II.1.3, Table 1.1):
//!
//! ```text
//!  1/2 - sqrt(3)/6 | 1/4              1/4 - sqrt(3)/6
//!  1/2 + sqrt(3)/6 | 1/4 + sqrt(3)/6  1/4
//! -----------------+----------------------------------
//!                  | 1/2              1/2
//! ```
//!
//! Order 4 (the collocation order `2s`), symmetric (time-reversible), symplectic for every
//! Hamiltonian, separable or not, and for Lagrangian systems in their canonical form; it keeps
//! every quadratic invariant of any ODE (Cooper 1987; GNI §IV.2.1), up to the accuracy of the
//! solve. Entries are the exact values rounded once to the nearest double.
//!
//! The stage equations are solved by the shared implicit solve
//! ([`implicit_solve`](super::implicit_solve)): fixed-point sweeps from the extrapolation of
//! the previous steps' stages, iterated to the rounding floor, and simplified Newton with one
//! LU of `I - h (A ⊗ J)` where the sweeps contract slowly. At the small steps symplectic runs
//! use, two sweeps suffice: four evaluations of `f` per step.

use super::implicit_solve::{ButcherTableau, ImplicitRk, Tableau};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The facts about `gauss_legendre4`.
pub const INFO: MethodInfo = MethodInfo {
    name: "gauss_legendre4",
    label: "Gauss–Legendre 4",
    summary: "two-stage Gauss–Legendre collocation; symplectic for any Hamiltonian, keeps \
              quadratic invariants",
    order: 4,
    symplectic: true,
    separable_only: false,
    evaluations_per_step: 4,
    evaluations: "right-hand-side evaluations, typical: two per fixed-point sweep, and the solve \
                  iterates to the rounding floor, which takes two sweeps at small steps and more \
                  at large ones, plus Jacobian evaluations where Newton's method is needed",
    reference: "J. C. Butcher, Math. Comp. 18 (1964) 50–64; Hairer, Lubich, Wanner, Geometric \
                Numerical Integration (2006), §II.1.3",
    scheme: Scheme::ImplicitRk,
};

/// The two-stage Gauss–Legendre tableau.
#[derive(Debug, Clone, Copy)]
pub struct GaussLegendre4Tableau;

impl ButcherTableau<2> for GaussLegendre4Tableau {
    /// The tableau of the module docs, each entry rounded once.
    const TABLEAU: Tableau<2> = Tableau {
        a: [
            [0.25, -0.038_675_134_594_812_88],
            [0.538_675_134_594_812_9, 0.25],
        ],
        b: [0.5, 0.5],
        c: [0.211_324_865_405_187_1, 0.788_675_134_594_812_9],
    };
}

/// The `gauss_legendre4` stepper: the shared implicit solve on [`GaussLegendre4Tableau`].
pub type GaussLegendre4 = ImplicitRk<2, GaussLegendre4Tableau>;
