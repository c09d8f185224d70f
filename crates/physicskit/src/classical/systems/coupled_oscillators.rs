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
//!
//! # Closed forms
//!
//! `L` is quadratic with a constant mass matrix, so every equation of motion is linear
//! (Goldstein §6.2); the integrators use these instead of differentiating `L` (checked against
//! the [`LagrangianEngine`] in `tests/classical/lagrangian/closed_forms.rs`):
//!
//! ```text
//! mass          M = m I,   p = m qdot,   qdot = p / m
//! force         dL/dq_i = k (q_{i-1} - 2 q_i + q_{i+1})        (q_0 = q_{n+1} = 0)
//! acceleration  q_i'' = (dL/dq_i) / m
//! energy        E = (m/2) sum_i q_i'^2 + (k/2) sum_{i=0}^{n} (q_{i+1} - q_i)^2
//! ```
//!
//! They work on the slices in place for any `n`, without buffers.

use super::chains::{fixed_end_force, fixed_end_potential};
use crate::classical::core::error::check_positive;
use crate::classical::core::linalg::negligible_pivot;
use crate::classical::core::sum::lane_sum_map;
use crate::classical::core::{check_items_fit, Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{singular_mass_matrix, Lagrangian, LagrangianEngine, Scalar};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Ends, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Lagrangian as Erased};

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
    /// The defaults of [`COUPLED_OSCILLATORS_ENTRY`], where they are written.
    fn default() -> Self {
        COUPLED_OSCILLATORS_ENTRY.defaults(Self::from_values)
    }
}

impl CoupledOscillatorsParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            n: v.count("n")?,
            m: v.scalar("m")?,
            k: v.scalar("k")?,
        })
    }
}

impl CoupledOscillatorsParams {
    fn validate(self) -> Result<Self> {
        if self.n == 0 {
            return Err(Error::invalid("n", 0.0, "must be at least 1"));
        }
        // The engine's work matrices are `n x n` (see `LagrangianEngine::new`, which checks
        // the same under the name `ndof`): named here as the user wrote it.
        check_items_fit("n", self.n, self.n.saturating_mul(3 * 8))?;
        check_positive("m", self.m)?;
        check_positive("k", self.k)?;
        Ok(self)
    }

    /// Angular frequency of normal mode `j` (`1..=n`): `2 sqrt(k/m) sin(j pi / (2(n+1)))`.
    pub fn mode_frequency(&self, j: usize) -> f64 {
        super::chain_mode_frequency(self.n, self.m, self.k, j)
    }

    /// `out_i = scale * k ((q_{i+1} - q_i) - (q_i - q_{i-1}))` between the walls: `dL/dq` for
    /// `scale = 1` (the harmonic chain's force, [`fixed_end_force`]).
    #[inline(always)]
    fn force(&self, q: &[f64], scale: f64, out: &mut [f64]) {
        let k = self.k * scale;
        fixed_end_force(q, out, |r| k * r);
    }

    /// `1 / m`, or the singular-matrix error for `m = 0` (unvalidated parameters).
    #[inline(always)]
    fn inverse_mass(&self, t: f64) -> Result<f64> {
        if negligible_pivot(self.m, self.m) {
            return Err(singular_mass_matrix(t));
        }
        Ok(self.m.recip())
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

    #[inline]
    fn closed_mass_matrix(&self, _q: &[f64], _v: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        out.fill(0.0);
        out.iter_mut().step_by(self.n + 1).for_each(|d| *d = self.m);
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, _q: &[f64], v: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        out.iter_mut().zip(v).for_each(|(p, &vi)| *p = self.m * vi);
        Some(())
    }

    #[inline]
    fn closed_generalized_force(
        &self,
        q: &[f64],
        _v: &[f64],
        _t: f64,
        out: &mut [f64],
    ) -> Option<()> {
        self.force(q, 1.0, out);
        Some(())
    }

    #[inline]
    fn closed_energy(&self, q: &[f64], v: &[f64], _t: f64) -> Option<f64> {
        let kinetic = lane_sum_map(v, |vi| vi * vi);
        let springs = fixed_end_potential(q, |r| r * r);
        Some(0.5 * (self.m * kinetic + self.k * springs))
    }

    #[inline]
    fn closed_acceleration(
        &self,
        q: &[f64],
        _v: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Option<Result<()>> {
        Some(self.inverse_mass(t).map(|inv| self.force(q, inv, out)))
    }

    #[inline]
    fn closed_velocity(
        &self,
        _q: &[f64],
        p: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Option<Result<()>> {
        Some(self.inverse_mass(t).map(|inv| {
            out.iter_mut().zip(p).for_each(|(v, &pi)| *v = pi * inv);
        }))
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
    /// `k <= 0`; [`Error::TooLarge`] if the `n x n` work matrices would not fit in memory.
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

impl Capabilities for CoupledOscillators {}

catalogue_static! {
    /// The catalogue entry of [`CoupledOscillators`].
    pub static COUPLED_OSCILLATORS_ENTRY: SystemEntry = SystemEntry {
        name: "coupled-oscillators",
        python: Some("CoupledOscillators"),
        summary: "n masses and springs between fixed walls, Lagrangian form (CoupledOscillators)",
        family: Family::Lagrangian,
        params: &[
            P::vector(
                "q0",
                Length::Count("n"),
                D::demo_vector(&[0.1, -0.2, 0.15]),
                "m",
                "initial displacements, length n",
            )
            .initial_state(),
            P::vector(
                "qdot0",
                Length::Count("n"),
                D::DemoAbsent,
                "m/s",
                "initial velocities, length n (left out: zeros)",
            )
            .initial_state(),
            P::integer("n", D::integer(3), Range::at_least(1.0), "number of masses"),
            P::scalar(
                "m",
                D::scalar(1.0),
                "kg",
                Range::POSITIVE,
                "mass of each particle",
            ),
            P::scalar(
                "k",
                D::scalar(1.0),
                "N/m",
                Range::POSITIVE,
                "spring constant",
            ),
        ],
        separable: false,
        taylor_form: true,
        default_method: Method::ImplicitMidpoint,
        note: Some("p holds qdot, as in the spec"),
        physics: Some(super::chains::CHAINS_PHYSICS),
        presentation: Presentation {
            title: "Coupled oscillators",
            symbols: &["x"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Chain { ends: Ends::Fixed },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let q0 = v.vector("q0")?;
            let zeros = vec![0.0; q0.len()];
            let qdot0 = v.opt_vector("qdot0")?.unwrap_or(&zeros);
            let params = CoupledOscillatorsParams::from_values(v)?;
            Ok(Box::new(Erased(CoupledOscillators::new(
                q0, qdot0, params,
            )?)))
        },
    };
}
