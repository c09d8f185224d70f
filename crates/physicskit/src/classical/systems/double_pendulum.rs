//! [`DoublePendulum`]: two point masses on massless rods in a vertical plane.
//!
//! Coordinates `q = (theta1, theta2)`, angles from the downward vertical. The Lagrangian
//! (Goldstein, *Classical Mechanics*, 3rd ed., §1.6; Taylor, *Classical Mechanics* (2005),
//! §11.4) is
//!
//! ```text
//! L = (m1 + m2) l1^2 theta1'^2 / 2 + m2 l2^2 theta2'^2 / 2
//!     + m2 l1 l2 theta1' theta2' cos(theta1 - theta2)
//!     + (m1 + m2) g l1 cos(theta1) + m2 g l2 cos(theta2)
//! ```
//!
//! It is written once below; the equations of motion, momenta, energy `T + V` and the
//! canonical form come from the [`LagrangianEngine`]. The mass matrix depends on
//! `theta1 - theta2`, so the Hamiltonian is not separable: `implicit_midpoint` (default) is the
//! symplectic choice, `rk4` integrates `(q, qdot)`.

use crate::classical::core::error::check_finite_scalar;
use crate::classical::core::error::check_positive;
use crate::classical::core::{Error, Phase, Result};
use crate::classical::lagrangian::{Lagrangian, LagrangianEngine, Scalar};

/// Masses, rod lengths and gravity of a [`DoublePendulum`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulumParams {
    /// Mass of the upper bob.
    pub m1: f64,
    /// Mass of the lower bob.
    pub m2: f64,
    /// Length of the upper rod.
    pub l1: f64,
    /// Length of the lower rod.
    pub l2: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for DoublePendulumParams {
    /// The spec's defaults: `m1 = m2 = 1`, `l1 = l2 = 1`, `g = 9.81`.
    fn default() -> Self {
        Self {
            m1: 1.0,
            m2: 1.0,
            l1: 1.0,
            l2: 1.0,
            g: 9.81,
        }
    }
}

impl DoublePendulumParams {
    fn validate(self) -> Result<Self> {
        check_positive("m1", self.m1)?;
        check_positive("m2", self.m2)?;
        check_positive("l1", self.l1)?;
        check_positive("l2", self.l2)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }
}

impl Lagrangian for DoublePendulumParams {
    fn ndof(&self) -> usize {
        2
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let Self { m1, m2, l1, l2, g } = *self;
        let (w1, w2) = (qdot[0], qdot[1]);
        let kinetic = w1 * w1 * (0.5 * (m1 + m2) * l1 * l1)
            + w2 * w2 * (0.5 * m2 * l2 * l2)
            + w1 * w2 * (q[0] - q[1]).cos() * (m2 * l1 * l2);
        let potential = q[0].cos() * (-(m1 + m2) * g * l1) - q[1].cos() * (m2 * g * l2);
        kinetic - potential
    }
}

/// The planar double pendulum (the spec's `DoublePendulum`). State `[theta1, theta2,
/// theta1dot, theta2dot]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// let mut dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], DoublePendulumParams::default())
///     .unwrap();
/// let e0 = dp.current_energy();
/// dp.integrate((0.0, 1.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((dp.current_energy() - e0).abs() < 1e-5 * e0.abs());
/// ```
#[derive(Debug, Clone)]
pub struct DoublePendulum {
    phase: Phase,
    engine: LagrangianEngine<DoublePendulumParams>,
}

impl DoublePendulum {
    /// A double pendulum at angles `theta0` with angular velocities `thetadot0` (both length
    /// 2).
    ///
    /// # Errors
    /// Lengths other than 2, non-finite values, non-positive masses or lengths, non-finite `g`.
    pub fn new(theta0: &[f64], thetadot0: &[f64], params: DoublePendulumParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(theta0, thetadot0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &DoublePendulumParams {
        self.engine.lagrangian()
    }

    /// Cartesian bob positions `[x1, y1, x2, y2]` for angles `q` (the current angles if
    /// `None`): pivot at the origin, `y` up, so a hanging bob has negative `y`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` has
    /// length 2.
    pub fn positions(&self, q: Option<&[f64]>) -> Result<[f64; 4]> {
        let q = q.unwrap_or(&self.phase.state()[..2]);
        if q.len() != 2 {
            return Err(Error::DimensionMismatch {
                name: "q".into(),
                expected: 2,
                found: q.len(),
            });
        }
        let DoublePendulumParams { l1, l2, .. } = *self.params();
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (x1, y1) = (l1 * s1, -l1 * c1);
        Ok([x1, y1, x1 + l2 * s2, y1 - l2 * c2])
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<DoublePendulumParams> {
        &self.engine
    }
}

crate::impl_lagrangian_dynamics!(DoublePendulum);
