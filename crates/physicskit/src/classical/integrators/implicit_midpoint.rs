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

use std::collections::BTreeMap;
use std::ops::{Deref, DerefMut};

use super::field::VectorField;
use super::implicit_solve::{ImplicitRk, Tableau};
use super::stepper::{FieldStepper, Report};
use crate::classical::core::method::{MethodInfo, Scheme};
use crate::classical::core::{ExtraValue, Result};

/// The facts about `implicit_midpoint`.
pub const INFO: MethodInfo = MethodInfo {
    name: "implicit_midpoint",
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

/// The one-stage tableau: `k = f(t + h/2, y0 + (h/2) k)`, `y1 = y0 + h k`.
pub const TABLEAU: Tableau<1> = Tableau {
    a: [[0.5]],
    b: [1.0],
    c: [0.5],
};

/// The implicit midpoint stepper: the shared implicit solve on [`TABLEAU`]. Dereferences to the
/// [`ImplicitRk`] it wraps, for its settings, statistics and `step`.
#[derive(Debug, Clone)]
pub struct ImplicitMidpoint(ImplicitRk<1>);

impl ImplicitMidpoint {
    /// Buffers for a `dim`-dimensional state.
    pub fn new(dim: usize) -> Self {
        Self(ImplicitRk::new(TABLEAU, dim))
    }
}

impl Deref for ImplicitMidpoint {
    type Target = ImplicitRk<1>;

    fn deref(&self) -> &ImplicitRk<1> {
        &self.0
    }
}

impl DerefMut for ImplicitMidpoint {
    fn deref_mut(&mut self) -> &mut ImplicitRk<1> {
        &mut self.0
    }
}

impl FieldStepper for ImplicitMidpoint {
    fn new(dim: usize) -> Self {
        ImplicitMidpoint::new(dim)
    }

    #[inline(always)]
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.0.step(f, t, y, h)
    }
}

impl Report for ImplicitMidpoint {
    /// The solver's statistics ([`SolverStats::report`](super::SolverStats::report)).
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        self.0.report(extra);
    }
}
