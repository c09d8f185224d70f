//! Small reference systems with known solutions, used in docs, tests and benchmarks.
//!
//! They are deliberately minimal: the full systems of the spec live in `systems`.

use crate::classical::core::error::check_len;
use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::lanes::{LanesForce, Real, SplittingLanes};
use crate::classical::integrators::{HamiltonianSystem, MassInv, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{Default as D, Family, ParamSpec as P, Range, SystemEntry};
use crate::classical::model::entry::{Drawing, Ends, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Hamiltonian};

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
        self.potential(q)
    }
    #[inline]
    /// `F = -(g/l) sin q` ([`LanesForce::force_of`] at `f64`).
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        self.force_of(q, out);
        Ok(())
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        out[0] = -self.g_over_l * q[0].cos();
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes (std's `sin` per lane).
impl LanesForce for Pendulum {
    const NDOF: usize = 1;

    #[inline(always)]
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        out[0] = q[0].sin() * -self.g_over_l;
    }

    /// Equal `g/l`, bit for bit.
    fn same_force(&self, other: &Self) -> bool {
        self.g_over_l.to_bits() == other.g_over_l.to_bits()
    }

    /// `sin` (and for the energy `cos`) per lane.
    fn calls_per_lane(&self) -> bool {
        true
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(self.potential(q))
    }
}

impl Pendulum {
    /// `V = -(g/l) cos q`, over `f64` and over members in SIMD lanes.
    #[inline(always)]
    fn potential<R: Real>(&self, q: &[R]) -> R {
        q[0].cos() * -self.g_over_l
    }
}

crate::impl_separable_dynamics!(Pendulum, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

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
        self.potential(q)
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.m_inv)
    }
    #[inline]
    /// `F = -k q` ([`LanesForce::force_of`] at `f64`).
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        self.force_of(q, out);
        Ok(())
    }
    fn force_jacobian(&self, _q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        out[0] = -self.k;
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes.
impl LanesForce for HarmonicOscillator {
    const NDOF: usize = 1;

    #[inline(always)]
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        out[0] = q[0] * -self.k;
    }

    /// Equal `k` and mass, bit for bit.
    fn same_force(&self, other: &Self) -> bool {
        let bits = |s: &Self| [s.k, s.m_inv].map(f64::to_bits);
        bits(self) == bits(other)
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(self.potential(q))
    }
}

impl HarmonicOscillator {
    /// `V = k q^2 / 2`, over `f64` and over members in SIMD lanes.
    #[inline(always)]
    fn potential<R: Real>(&self, q: &[R]) -> R {
        R::splat(0.5 * self.k) * q[0] * q[0]
    }
}

crate::impl_separable_dynamics!(HarmonicOscillator, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

impl Capabilities for Pendulum {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        // The bob of a unit-length pendulum, angle from the downward vertical.
        Some(check_len("q", q, 1).map(|()| fill(out, &[q[0].sin(), -q[0].cos()])))
    }
}

impl Capabilities for HarmonicOscillator {}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const PENDULUM_PHYSICS: &str =
    "The symplectic methods (verlet, yoshida4 and the higher-order compositions) and the \
         implicit midpoint rule conserve a modified energy exactly, so their energy error \
         oscillates but never grows, however long the run; rk4 is more accurate per step than \
         verlet but not symplectic, and its energy error grows steadily. The order p of a \
         method shows in the slope of its error at a fixed time against the step size (error \
         ∝ dt^p): 2 for verlet and implicit_midpoint, 4 for yoshida4 and rk4.";

catalogue_static! {
    /// The catalogue entry of [`Pendulum`].
    pub static PENDULUM_ENTRY: SystemEntry = SystemEntry {
        name: "pendulum",
        python: None,
        summary: "simple pendulum H = p^2/2 - (g/l) cos q (examples::Pendulum)",
        family: Family::Hamiltonian,
        params: &[
            P::scalar(
                "q0",
                D::demo_scalar(1.0),
                "rad",
                Range::ANY,
                "initial angle",
            )
            .initial_state(),
            P::scalar(
                "p0",
                D::demo_scalar(0.0),
                "rad/s",
                Range::ANY,
                "initial momentum (unit m l^2)",
            )
            .initial_state(),
            P::scalar(
                "g_over_l",
                D::scalar(1.0),
                "1/s^2",
                Range::POSITIVE,
                "g / l",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(PENDULUM_PHYSICS),
        presentation: Presentation {
            title: "Simple pendulum",
            symbols: &["\\theta"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Bobs {
                springs: false,
                scale: Some("l"),
            },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(Pendulum::new(
                v.scalar("q0")?,
                v.scalar("p0")?,
                v.scalar("g_over_l")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`HarmonicOscillator`].
    pub static HARMONIC_OSCILLATOR_ENTRY: SystemEntry = SystemEntry {
        name: "harmonic-oscillator",
        python: None,
        summary: "harmonic oscillator H = p^2/(2m) + k q^2/2 (examples::HarmonicOscillator)",
        family: Family::Hamiltonian,
        params: &[
            P::scalar(
                "q0",
                D::demo_scalar(1.0),
                "m",
                Range::ANY,
                "initial position",
            )
            .initial_state(),
            P::scalar(
                "p0",
                D::demo_scalar(0.0),
                "kg m/s",
                Range::ANY,
                "initial momentum",
            )
            .initial_state(),
            P::scalar("m", D::scalar(1.0), "kg", Range::POSITIVE, "mass"),
            P::scalar(
                "k",
                D::scalar(1.0),
                "N/m",
                Range::POSITIVE,
                "spring constant",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: None,
        presentation: Presentation {
            title: "Harmonic oscillator",
            symbols: &["x"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Chain { ends: Ends::Fixed },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(HarmonicOscillator::new(
                v.scalar("q0")?,
                v.scalar("p0")?,
                v.scalar("m")?,
                v.scalar("k")?,
            )?)))
        },
    };
}
