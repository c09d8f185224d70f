//! From a [`Lagrangian`] to a full [`LagrangianSystem`]: the macro
//! [`impl_lagrangian_dynamics!`](crate::impl_lagrangian_dynamics) and the generic
//! [`LagrangianModel`].
//!
//! Every Lagrangian system of physicskit is a struct with a `phase: Phase` and an
//! `engine: LagrangianEngine<L>` field; the macro implements [`DynamicalSystem`] and
//! [`LagrangianSystem`] for it entirely from the engine: the equations of motion are the
//! closed forms the Lagrangian supplies, if any (the built-in systems supply all of them), and
//! automatic differentiation of `L` otherwise. Default method: `implicit_midpoint` on the
//! canonical form, with the engine's exact canonical Jacobian available to its Newton solve.

use super::engine::{Lagrangian, LagrangianEngine};
use crate::classical::core::{Phase, Result};
#[cfg(doc)]
use crate::classical::integrators::{DynamicalSystem, LagrangianSystem};

/// Implements [`DynamicalSystem`](crate::classical::DynamicalSystem) and
/// [`LagrangianSystem`](crate::classical::LagrangianSystem) for a struct with fields
/// `phase: Phase` and `engine: LagrangianEngine<L>`.
///
/// `derivatives` is `[qdot, acceleration]` with the engine's
/// [`first_order_jacobian`](LagrangianEngine::first_order_jacobian) as its `jacobian`,
/// `energy` the engine's `p . qdot - L` at the system's clock, the canonical form and its
/// Jacobian come from the engine, and the default method is `implicit_midpoint`. For a generic struct write
/// `impl_lagrangian_dynamics!(impl [L: Lagrangian] MySystem<L>)`.
#[macro_export]
macro_rules! impl_lagrangian_dynamics {
    (impl [$($gen:tt)*] $ty:ty) => {
        impl<$($gen)*> $crate::classical::DynamicalSystem for $ty {
            fn phase(&self) -> &$crate::classical::Phase {
                &self.phase
            }
            fn phase_mut(&mut self) -> &mut $crate::classical::Phase {
                &mut self.phase
            }
            fn derivatives(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                let n = self.engine.ndof();
                let (q, qdot) = $crate::classical::split(state, n)?;
                if out.len() != 2 * n {
                    return Err($crate::classical::Error::DimensionMismatch {
                        name: "out".into(),
                        expected: 2 * n,
                        found: out.len(),
                    });
                }
                let (dq, dqdot) = out.split_at_mut(n);
                dq.copy_from_slice(qdot);
                self.engine.acceleration(q, qdot, t, dqdot)
            }
            fn energy(&self, state: &[f64]) -> f64 {
                self.engine.energy_of_state(state, self.phase.t())
            }
            fn jacobian(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> Option<$crate::classical::Result<()>> {
                self.engine.first_order_jacobian(t, state, out)
            }
            fn default_method(&self) -> $crate::classical::Method {
                $crate::classical::Method::ImplicitMidpoint
            }
            fn taylor_field(
                &self,
            ) -> Option<
                $crate::classical::Result<
                    Box<dyn $crate::classical::integrators::taylor::TaylorField>,
                >,
            > {
                $crate::classical::lagrangian::Lagrangian::taylor_field(self.engine.lagrangian())
            }
        }

        impl<$($gen)*> $crate::classical::LagrangianSystem for $ty {
            fn ndof(&self) -> usize {
                self.engine.ndof()
            }
            fn acceleration(
                &self,
                q: &[f64],
                qdot: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                self.engine.acceleration(q, qdot, t, out)
            }
            fn momentum(
                &self,
                q: &[f64],
                qdot: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                self.engine.momentum(q, qdot, t, out)
            }
            fn velocity(
                &self,
                q: &[f64],
                p: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                self.engine.velocity(q, p, t, out)
            }
            fn canonical_derivatives(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                self.engine.canonical_derivatives(t, state, out)
            }
            fn canonical_jacobian(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> Option<$crate::classical::Result<()>> {
                Some(self.engine.canonical_jacobian(t, state, out))
            }
        }
    };
    ($ty:ty) => {
        $crate::impl_lagrangian_dynamics!(impl [] $ty);
    };
}

/// A [`LagrangianSystem`] from any [`Lagrangian`], for user-defined systems (including
/// [`ExprLagrangian`](crate::classical::symbolic::ExprLagrangian) expressions from Python).
///
/// # Example
/// ```
/// use physicskit::classical::lagrangian::{Lagrangian, LagrangianModel, Scalar};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// /// A free particle in a uniform field: L = v^2/2 - g q.
/// struct Fall;
/// impl Lagrangian for Fall {
///     fn ndof(&self) -> usize { 1 }
///     fn lagrangian<D: Scalar>(&self, q: &[D], v: &[D], _t: D) -> D {
///         v[0] * v[0] * 0.5 - q[0] * 9.81
///     }
/// }
///
/// let mut system = LagrangianModel::new(Fall, &[0.0], &[0.0]).unwrap();
/// let result = system.integrate((0.0, 1.0), 0.01, Method::ImplicitMidpoint).unwrap();
/// // Implicit midpoint is exact for constant acceleration.
/// assert!((system.q()[0] + 9.81 / 2.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct LagrangianModel<L> {
    phase: Phase,
    engine: LagrangianEngine<L>,
}

impl<L: Lagrangian> LagrangianModel<L> {
    /// The system `lagrangian` starting at `(q0, qdot0)` at `t = 0`.
    ///
    /// # Errors
    /// `ndof = 0`, lengths different from `ndof`, non-finite values, or a singular mass
    /// matrix at the initial state.
    pub fn new(lagrangian: L, q0: &[f64], qdot0: &[f64]) -> Result<Self> {
        let engine = LagrangianEngine::new(lagrangian)?;
        let phase = engine.initial_phase(q0, qdot0)?;
        Ok(Self { phase, engine })
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<L> {
        &self.engine
    }
}

crate::impl_lagrangian_dynamics!(impl [L: Lagrangian] LagrangianModel<L>);

/// A user's Lagrangian offers no capabilities beyond the family's.
impl<L: Lagrangian> crate::classical::model::Capabilities for LagrangianModel<L> {}
