//! `gauss_legendre6`: the three-stage Gauss–Legendre collocation method.
//!
//! The implicit Runge–Kutta method whose nodes are the zeros of the shifted Legendre
//! polynomial of degree 3, `c = 1/2 - sqrt(15)/10, 1/2, 1/2 + sqrt(15)/10` (J. C. Butcher,
//! Math. Comp. 18 (1964) 50–64; Hairer, Lubich, Wanner, *Geometric Numerical Integration*
//! (2006), §II.1.3, Table 1.2):
//!
//! ```text
//!  1/2 - sqrt(15)/10 | 5/36              2/9 - sqrt(15)/15  5/36 - sqrt(15)/30
//!  1/2               | 5/36 + sqrt(15)/24  2/9              5/36 - sqrt(15)/24
//!  1/2 + sqrt(15)/10 | 5/36 + sqrt(15)/30  2/9 + sqrt(15)/15  5/36
//! -------------------+-------------------------------------------------------
//!                    | 5/18              4/9                5/18
//! ```
//!
//! Order 6 (the collocation order `2s`), symmetric (time-reversible), symplectic for every
//! Hamiltonian, separable or not, and for Lagrangian systems in their canonical form; it keeps
//! every quadratic invariant of any ODE (Cooper 1987; GNI §IV.2.1), up to the accuracy of the
//! solve. Entries are the exact values rounded once to the nearest double.
//!
//! Solved by the shared implicit solve ([`implicit_solve`](super::implicit_solve)) like
//! [`gauss_legendre4`](super::gauss_legendre4); at small steps, two sweeps of three
//! evaluations each.

use super::implicit_solve::{ButcherTableau, ImplicitRk, Tableau};
use crate::classical::core::method::{MethodInfo, Scheme};

/// The facts about `gauss_legendre6`.
pub const INFO: MethodInfo = MethodInfo {
    name: "gauss_legendre6",
    label: "Gauss–Legendre 6",
    summary: "three-stage Gauss–Legendre collocation; symplectic for any Hamiltonian, keeps \
              quadratic invariants",
    order: 6,
    symplectic: true,
    separable_only: false,
    evaluations_per_step: 6,
    evaluations: "right-hand-side evaluations, typical: three per fixed-point sweep, and the \
                  solve iterates to the rounding floor, which takes two sweeps at small steps and \
                  more at large ones, plus Jacobian evaluations where Newton's method is needed",
    reference: "J. C. Butcher, Math. Comp. 18 (1964) 50–64; Hairer, Lubich, Wanner, Geometric \
                Numerical Integration (2006), §II.1.3",
    scheme: Scheme::ImplicitRk,
};

/// The three-stage Gauss–Legendre tableau.
#[derive(Debug, Clone, Copy)]
pub struct GaussLegendre6Tableau;

impl ButcherTableau<3> for GaussLegendre6Tableau {
    /// The tableau of the module docs, each entry rounded once.
    const TABLEAU: Tableau<3> = Tableau {
        a: [
            [
                0.138_888_888_888_888_9,
                -0.035_976_667_524_938_9,
                0.009_789_444_015_308_325,
            ],
            [
                0.300_263_194_980_864_57,
                0.222_222_222_222_222_2,
                -0.022_485_417_203_086_815,
            ],
            [
                0.267_988_333_762_469_44,
                0.480_421_111_969_383_36,
                0.138_888_888_888_888_9,
            ],
        ],
        b: [
            0.277_777_777_777_777_8,
            0.444_444_444_444_444_4,
            0.277_777_777_777_777_8,
        ],
        c: [0.112_701_665_379_258_31, 0.5, 0.887_298_334_620_741_7],
    };
}

/// The `gauss_legendre6` stepper: the shared implicit solve on [`GaussLegendre6Tableau`].
pub type GaussLegendre6 = ImplicitRk<3, GaussLegendre6Tableau>;
