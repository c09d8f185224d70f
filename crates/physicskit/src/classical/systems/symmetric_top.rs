//! [`HeavySymmetricTop`]: a symmetric top with one point fixed, spinning under gravity.
//!
//! Coordinates `q = (phi, theta, psi)`, the z-x-z Euler angles (precession, nutation, spin).
//! With `I1` the transverse moment of inertia about the fixed point, `I3` the axial moment,
//! `M` the mass and `l` the pivot-to-centre-of-mass distance (Goldstein, *Classical
//! Mechanics*, 3rd ed., §5.7, eq. 5.58):
//!
//! ```text
//! L = (I1/2)(theta'^2 + phi'^2 sin^2 theta) + (I3/2)(psi' + phi' cos theta)^2 - M g l cos theta
//! ```
//!
//! `phi` and `psi` are cyclic, so `p_phi` and `p_psi` are conserved; the engine computes
//! `dL/dphi = dL/dpsi = 0` exactly, so the canonical integration keeps them to rounding. The
//! mass matrix depends on `theta` and is singular at `sin theta = 0` (gimbal lock of the Euler
//! angles). Energy `T + M g l cos theta`. The slow dynamics is analysed in
//! [`analysis::symmetric_top`](crate::classical::analysis).

use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::lagrangian::{Lagrangian, LagrangianEngine, Scalar};

/// Inertia, mass, lever arm and gravity of a [`HeavySymmetricTop`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetricTopParams {
    /// Transverse moment of inertia about the fixed point.
    pub i1: f64,
    /// Axial moment of inertia.
    pub i3: f64,
    /// Mass.
    pub m: f64,
    /// Distance from the pivot to the centre of mass.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for SymmetricTopParams {
    /// The spec's defaults: `I1 = 1`, `I3 = 0.5`, `M = 1`, `l = 1`, `g = 9.81`.
    fn default() -> Self {
        Self {
            i1: 1.0,
            i3: 0.5,
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }
}

impl SymmetricTopParams {
    fn validate(self) -> Result<Self> {
        check_positive("I1", self.i1)?;
        check_positive("I3", self.i3)?;
        check_positive("M", self.m)?;
        check_finite_scalar("l", self.l)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// `M g l`, the gravitational torque scale.
    pub fn mgl(&self) -> f64 {
        self.m * self.g * self.l
    }

    /// The conserved momenta `(p_phi, p_psi)` of a state `[phi, theta, psi, phi', theta',
    /// psi']`: `p_psi = I3 (psi' + phi' cos theta)`,
    /// `p_phi = I1 phi' sin^2 theta + p_psi cos theta`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 6.
    pub fn conserved_momenta(&self, state: &[f64]) -> Result<(f64, f64)> {
        if state.len() != 6 {
            return Err(Error::DimensionMismatch {
                name: "state".into(),
                expected: 6,
                found: state.len(),
            });
        }
        let (s, c) = state[1].sin_cos();
        let p_psi = self.i3 * (state[5] + state[3] * c);
        Ok((self.i1 * state[3] * s * s + p_psi * c, p_psi))
    }
}

impl Lagrangian for SymmetricTopParams {
    fn ndof(&self) -> usize {
        3
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let (s, c) = q[1].sin_cos();
        let (phid, thetad, psid) = (qdot[0], qdot[1], qdot[2]);
        let spin = psid + phid * c;
        (thetad * thetad + phid * phid * s * s) * (0.5 * self.i1) + spin * spin * (0.5 * self.i3)
            - c * self.mgl()
    }
}

/// The heavy symmetric top (the spec's `HeavySymmetricTop`). State `[phi, theta, psi, phi',
/// theta', psi']`.
#[derive(Debug, Clone)]
pub struct HeavySymmetricTop {
    phase: Phase,
    engine: LagrangianEngine<SymmetricTopParams>,
}

impl HeavySymmetricTop {
    /// A top at Euler angles `angles0 = (phi, theta, psi)` with rates `angledots0`.
    ///
    /// # Errors
    /// Lengths other than 3, non-finite values, non-positive `I1`, `I3` or `M`, non-finite
    /// `l` or `g`, or `sin theta = 0` (singular mass matrix: the Euler angles degenerate).
    pub fn new(angles0: &[f64], angledots0: &[f64], params: SymmetricTopParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(angles0, angledots0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &SymmetricTopParams {
        self.engine.lagrangian()
    }

    /// The instantaneous `(phidot, thetadot)`, precession and nutation rates, of `state` (the
    /// current state if `None`).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 6.
    pub fn precession_nutation_rate(&self, state: Option<&[f64]>) -> Result<(f64, f64)> {
        let state = state.unwrap_or(self.phase.state());
        if state.len() != 6 {
            return Err(Error::DimensionMismatch {
                name: "state".into(),
                expected: 6,
                found: state.len(),
            });
        }
        Ok((state[3], state[4]))
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<SymmetricTopParams> {
        &self.engine
    }
}

crate::impl_lagrangian_dynamics!(HeavySymmetricTop);
