//! [`CoupledOscillators`]: `n` equal masses joined by `n + 1` equal springs between two fixed
//! walls.
//!
//! Coordinates `q_i`, the displacement of mass `i` from equilibrium. With `q_0 = q_{n+1} = 0`
//! for the walls,
//!
//! ```text
//! L = (m/2) sum_i q_i'^2 - (k/2) sum_{i=0}^{n} (q_{i+1} - q_i)^2
//! ```
//!
//! The normal modes are `q_i = sin(i j pi / (n + 1))` with angular frequencies
//! `omega_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1)))`, `j = 1..n` (Goldstein, *Classical
//! Mechanics*, 3rd ed., §6.4; French, *Vibrations and Waves* (1971), ch. 5).

use crate::classical::core::error::check_positive;
use crate::classical::core::{Error, Phase, Result};
use crate::classical::lagrangian::{Lagrangian, LagrangianEngine, Scalar};

/// Size, mass and spring constant of a [`CoupledOscillators`] chain; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledOscillatorsParams {
    /// Number of masses.
    pub n: usize,
    /// Mass of each particle.
    pub m: f64,
    /// Spring constant of each spring.
    pub k: f64,
}

impl Default for CoupledOscillatorsParams {
    /// The spec's defaults: `n = 3`, `m = 1`, `k = 1`.
    fn default() -> Self {
        Self {
            n: 3,
            m: 1.0,
            k: 1.0,
        }
    }
}

impl CoupledOscillatorsParams {
    fn validate(self) -> Result<Self> {
        if self.n == 0 {
            return Err(Error::invalid("n", 0.0, "must be at least 1"));
        }
        check_positive("m", self.m)?;
        check_positive("k", self.k)?;
        Ok(self)
    }

    /// Angular frequency of normal mode `j` (`1..=n`): `2 sqrt(k/m) sin(j pi / (2(n+1)))`.
    pub fn mode_frequency(&self, j: usize) -> f64 {
        super::chain_mode_frequency(self.n, self.m, self.k, j)
    }
}

impl Lagrangian for CoupledOscillatorsParams {
    fn ndof(&self) -> usize {
        self.n
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let kinetic = qdot.iter().fold(D::zero(), |s, &v| s + v * v);
        let mut stretch = q[0] * q[0] + q[self.n - 1] * q[self.n - 1];
        for w in q.windows(2) {
            let d = w[1] - w[0];
            stretch += d * d;
        }
        kinetic * (0.5 * self.m) - stretch * (0.5 * self.k)
    }
}

/// The chain of coupled oscillators between fixed walls (the spec's `CoupledOscillators`).
/// State `[q_1..q_n, qdot_1..qdot_n]`.
#[derive(Debug, Clone)]
pub struct CoupledOscillators {
    phase: Phase,
    engine: LagrangianEngine<CoupledOscillatorsParams>,
}

impl CoupledOscillators {
    /// A chain of `params.n` masses with displacements `q0` and velocities `qdot0`.
    ///
    /// # Errors
    /// `n = 0`, `q0` or `qdot0` of length other than `n`, non-finite values, `m <= 0` or
    /// `k <= 0`.
    pub fn new(q0: &[f64], qdot0: &[f64], params: CoupledOscillatorsParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(q0, qdot0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &CoupledOscillatorsParams {
        self.engine.lagrangian()
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<CoupledOscillatorsParams> {
        &self.engine
    }
}

crate::impl_lagrangian_dynamics!(CoupledOscillators);
