//! Small reference systems with known solutions, used in docs, tests and benchmarks.
//!
//! They are deliberately minimal: the full systems of the spec live in `systems`.

use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::{HamiltonianSystem, MassInv, Phase, Result};

/// The simple pendulum `H = p^2/2 - (g/l) cos q` (unit `m l^2`).
#[derive(Debug, Clone)]
pub struct Pendulum {
    phase: Phase,
    g_over_l: f64,
}

impl Pendulum {
    /// A pendulum at angle `q0` with momentum `p0`.
    ///
    /// # Errors
    /// Non-finite inputs or `g_over_l <= 0`.
    pub fn new(q0: f64, p0: f64, g_over_l: f64) -> Result<Self> {
        Ok(Self {
            phase: Phase::new(
                vec![
                    check_finite_scalar("q0", q0)?,
                    check_finite_scalar("p0", p0)?,
                ],
                0.0,
            )?,
            g_over_l: check_positive("g_over_l", g_over_l)?,
        })
    }
}

impl HamiltonianSystem for Pendulum {
    fn ndof(&self) -> usize {
        1
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        -self.g_over_l * q[0].cos()
    }
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        out[0] = -self.g_over_l * q[0].sin();
        Ok(())
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        out[0] = -self.g_over_l * q[0].cos();
        Some(Ok(()))
    }
}

crate::impl_separable_dynamics!(Pendulum);

/// The harmonic oscillator `H = p^2/(2m) + k q^2/2`, exactly solvable.
#[derive(Debug, Clone)]
pub struct HarmonicOscillator {
    phase: Phase,
    m_inv: f64,
    k: f64,
}

impl HarmonicOscillator {
    /// An oscillator at `q0` with momentum `p0`.
    ///
    /// # Errors
    /// Non-finite inputs, `m <= 0` or `k <= 0`.
    pub fn new(q0: f64, p0: f64, m: f64, k: f64) -> Result<Self> {
        Ok(Self {
            phase: Phase::new(
                vec![
                    check_finite_scalar("q0", q0)?,
                    check_finite_scalar("p0", p0)?,
                ],
                0.0,
            )?,
            m_inv: 1.0 / check_positive("m", m)?,
            k: check_positive("k", k)?,
        })
    }

    /// The exact state `(q, p)` at time `t` from `(q0, p0)` at time 0.
    pub fn exact(&self, q0: f64, p0: f64, t: f64) -> (f64, f64) {
        let m = 1.0 / self.m_inv;
        let w = (self.k * self.m_inv).sqrt();
        let (s, c) = (w * t).sin_cos();
        (q0 * c + p0 / (m * w) * s, p0 * c - m * w * q0 * s)
    }
}

impl HamiltonianSystem for HarmonicOscillator {
    fn ndof(&self) -> usize {
        1
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        0.5 * self.k * q[0] * q[0]
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.m_inv)
    }
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        out[0] = -self.k * q[0];
        Ok(())
    }
    fn force_jacobian(&self, _q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        out[0] = -self.k;
        Some(Ok(()))
    }
}

crate::impl_separable_dynamics!(HarmonicOscillator);
