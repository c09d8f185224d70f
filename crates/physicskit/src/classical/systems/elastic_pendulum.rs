//! [`ElasticPendulum`]: a point mass `m` on a massless spring (stiffness `k`, rest length
//! `L0`, field `l0`) swinging in a vertical plane: the spring pendulum.
//!
//! Coordinates `q = (r, theta)`: the spring's length and its angle from the downward
//! vertical. With the pivot at the origin and `y` up, the bob is at
//! `(x, y) = (r sin theta, -r cos theta)` and (Taylor, *Classical Mechanics* (2005), problem
//! 7.7; Lynch, Int. J. Bifurcation and Chaos 12 (2002) 1445)
//!
//! ```text
//! L = m (r'^2 + r^2 theta'^2) / 2 + m g r cos(theta) - k (r - l0)^2 / 2
//! ```
//!
//! The mass matrix `diag(m, m r^2)` is singular at `r = 0`, where the bob sits on the pivot and
//! `theta` is undefined; the constructor refuses `r0 <= 0`, and an integration whose length
//! reaches `r <= 0` stops with [`Error::SingularMatrix`] (a negative `r` is outside the
//! chart: the spring energy would be that of length `r`, not `|r|`).
//!
//! # Closed forms
//!
//! The integrators use these hand-derived forms (checked against automatic differentiation
//! of `L` in `tests/classical/lagrangian/closed_forms.rs`); the acceleration and the canonical
//! field are written once, generic over the number type, so their Jacobians come from the
//! same code by automatic differentiation (`lagrangian/forward.rs`). With `s = sin theta`, `c = cos theta` and
//! `w = (r', theta')`:
//!
//! ```text
//! mass matrix   M = diag(m, m r^2)
//! momentum      p_r = m r',   p_theta = m r^2 theta'
//! velocity      r' = p_r / m,   theta' = p_theta / (m r^2)
//! force         dL/dr = m r theta'^2 + m g c - k (r - l0),   dL/dtheta = -m g r s
//! energy        E = m (r'^2 + r^2 theta'^2) / 2 - m g r c + k (r - l0)^2 / 2
//! ```
//!
//! Euler–Lagrange: `d/dt (m r') = dL/dr` and `d/dt (m r^2 theta') = 2 m r r' theta' +
//! m r^2 theta'' = -m g r s`, so
//!
//! ```text
//! r''     = r theta'^2 + g c - (k/m) (r - l0)
//! theta'' = -(g s + 2 r' theta') / r
//! ```
//!
//! (centrifugal and Coriolis terms; the pendulum `theta'' = -(g/l) sin theta` at fixed `r`).
//!
//! # The 2:1 resonance
//!
//! The bob hangs at rest at `r_eq = l0 + m g / k`. Linearized about it the motion separates
//! into the bounce (spring) mode, `omega_s = sqrt(k/m)`, and the swing (pendulum) mode,
//! `omega_p = sqrt(g / r_eq)`: the swing sees the stretched length, not `l0`. When
//! `omega_s = 2 omega_p` the quadratic coupling `r theta'^2` and `r cos theta` resonates and
//! energy passes back and forth between bounce and swing (Vitt & Gorelik 1933; Lynch 2002).
//! The condition is often quoted as `k/m = 4 g / l0`, which neglects the static stretch; the
//! exact condition `k/m = 4 g / r_eq = 4 g / (l0 + m g / k)` solves to
//!
//! ```text
//! k = 3 m g / l0,   r_eq = 4 l0 / 3,   omega_s = 2 omega_p = sqrt(3 g / l0)
//! ```
//!
//! ([`ElasticPendulumParams::resonant_k`]). With `m = l0 = 1`, `g = 9.81` that is
//! `k = 29.43`. The default `k = 39.24` is the often-quoted `4 m g / l0` (the physicskit 0.4.0
//! peer's default, kept for users who move from it): there `r_eq = 5 l0 / 4` and the frequency
//! ratio is `sqrt(k r_eq / (m g)) = sqrt(5)`, near the resonance but not on it, so the
//! exchange is small and fast.
//!
//! # Energy of each mode
//!
//! With `rho = r - r_eq` the cross terms `m g rho` of gravity and spring cancel exactly:
//!
//! ```text
//! E - E_eq = [m r'^2/2 + k rho^2/2] + [m r^2 theta'^2/2 + m g r (1 - cos theta)]
//!          =        E_bounce        +                E_swing
//! E_eq = -m g r_eq + (m g)^2 / (2 k)      (at rest at r_eq)
//! ```
//!
//! Both parts are non-negative for `g >= 0` and sum to the conserved `E - E_eq`; the coupling
//! lives in the factor `r` of the swing energy
//! ([`ElasticPendulum::mode_energies`]).

use crate::classical::core::error::{check_finite_scalar, check_non_negative, check_positive};
use crate::classical::core::linalg::negligible_pivot;
use crate::classical::core::trig::sin_cos;
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{FieldScalar, Lagrangian, LagrangianEngine, Scalar};
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Lagrangian as Erased};

/// Mass, spring constant, rest length and gravity of an [`ElasticPendulum`]; its
/// [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticPendulumParams {
    /// Bob mass `m` (kg), `> 0`.
    pub m: f64,
    /// Spring constant `k` (N/m), `> 0`.
    pub k: f64,
    /// Rest length `l0` of the spring (m), `>= 0` (`0`: a zero-length spring).
    pub l0: f64,
    /// Gravitational acceleration `g` (m/s²), finite.
    pub g: f64,
}

impl Default for ElasticPendulumParams {
    /// The Python class's defaults: `m = 1`, `k = 39.24` (`4 m g / l0`), `l0 = 1`, `g = 9.81`.
    fn default() -> Self {
        Self {
            m: 1.0,
            k: 39.24,
            l0: 1.0,
            g: 9.81,
        }
    }
}

impl ElasticPendulumParams {
    fn validate(self) -> Result<Self> {
        check_positive("m", self.m)?;
        check_positive("k", self.k)?;
        check_non_negative("L0", self.l0)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// The spring constant of the exact 2:1 resonance `sqrt(k/m) = 2 sqrt(g / r_eq)` with
    /// `r_eq = l0 + m g / k`: `k = 3 m g / l0` (module documentation).
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::systems::ElasticPendulumParams;
    ///
    /// let k = ElasticPendulumParams::resonant_k(1.0, 1.0, 9.81).unwrap();
    /// let params = ElasticPendulumParams { k, ..Default::default() };
    /// assert!((params.spring_frequency() - 2.0 * params.swing_frequency()).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `m`, `l0` and `g` are finite and positive (with
    /// `g <= 0` the bob does not hang and has no swing frequency; with `l0 = 0` no finite
    /// `k` is resonant: `omega_s / omega_p = sqrt(k r_eq/(m g)) = 1`).
    pub fn resonant_k(m: f64, l0: f64, g: f64) -> Result<f64> {
        let m = check_positive("m", m)?;
        let l0 = check_positive("L0", l0)?;
        let g = check_positive("g", g)?;
        Ok(3.0 * m * g / l0)
    }

    /// Length `r_eq = l0 + m g / k` at which the bob hangs at rest (m).
    pub fn equilibrium_length(&self) -> f64 {
        self.l0 + self.m * self.g / self.k
    }

    /// Angular frequency `sqrt(k/m)` of small bounces about `r_eq` (rad/s).
    pub fn spring_frequency(&self) -> f64 {
        (self.k / self.m).sqrt()
    }

    /// Angular frequency `sqrt(g / r_eq)` of small swings about the vertical (rad/s; `NaN`
    /// when `g / r_eq < 0`).
    pub fn swing_frequency(&self) -> f64 {
        (self.g / self.equilibrium_length()).sqrt()
    }

    /// Energy `E_eq = -m g r_eq + (m g)^2 / (2 k)` of the bob at rest at `r_eq` (J).
    pub fn equilibrium_energy(&self) -> f64 {
        let mg = self.m * self.g;
        -mg * self.equilibrium_length() + 0.5 * mg * mg / self.k
    }

    /// `(1/m, 1/(m r^2))`, or the singular-mass-matrix error at `r <= 0` (the bob on or past
    /// the pivot) or where LU would find a negligible pivot in `diag(m, m r^2)`.
    #[inline(always)]
    fn inverse_mass<X: FieldScalar>(&self, r: X, t: f64) -> Result<(f64, X)> {
        let m = self.m;
        let mr2 = r * m * r;
        let (r0, mr2_0) = (r.re(), mr2.re());
        let scale = m.max(mr2_0);
        // A NaN r makes m r^2 NaN, which negligible_pivot calls singular.
        if r0 <= 0.0 || negligible_pivot(m, scale) || negligible_pivot(mr2_0, scale) {
            return Err(Error::SingularMatrix {
                what: format!(
                    "mass matrix diag(m, m r^2) at r = {r0} (the bob reached the pivot, r <= 0 \
                     or m r^2 negligible)"
                ),
                t,
            });
        }
        Ok((m.recip(), mr2.recip()))
    }

    /// `dL/dq = (m r theta'^2 + m g cos theta - k (r - l0), -m g r sin theta)`.
    #[inline(always)]
    fn force<X: FieldScalar>(&self, q: &[X], w: &[X]) -> [X; 2] {
        let Self { m, k, l0, g } = *self;
        let (s, c) = q[1].sin_cos_kernel();
        let r = q[0];
        [
            (r * w[1] * w[1] + c * g) * m - (r - l0) * k,
            r * (-m * g) * s,
        ]
    }

    /// The velocity `(p_r / m, p_theta / (m r^2))` at `q = (r, theta)`.
    #[inline(always)]
    fn velocity<X: FieldScalar>(&self, q: &[X], p: &[X], t: f64, out: &mut [X]) -> Result<()> {
        self.inverse_mass(q[0], t).map(|(inv_m, inv_mr2)| {
            out[0] = p[0] * inv_m;
            out[1] = p[1] * inv_mr2;
        })
    }
}

impl Lagrangian for ElasticPendulumParams {
    fn ndof(&self) -> usize {
        2
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let Self { m, k, l0, g } = *self;
        let (r, theta) = (q[0], q[1]);
        let stretch = r - l0;
        (qdot[0] * qdot[0] + r * r * qdot[1] * qdot[1]) * (0.5 * m) + r * theta.cos() * (m * g)
            - stretch * stretch * (0.5 * k)
    }

    #[inline]
    fn closed_mass_matrix(&self, q: &[f64], _w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let m = self.m;
        out.copy_from_slice(&[m, 0.0, 0.0, m * q[0] * q[0]]);
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, q: &[f64], w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let (m, r) = (self.m, q[0]);
        out[0] = m * w[0];
        out[1] = m * r * r * w[1];
        Some(())
    }

    #[inline]
    fn closed_generalized_force(
        &self,
        q: &[f64],
        w: &[f64],
        _t: f64,
        out: &mut [f64],
    ) -> Option<()> {
        out.copy_from_slice(&self.force(q, w));
        Some(())
    }

    #[inline]
    fn closed_energy(&self, q: &[f64], w: &[f64], _t: f64) -> Option<f64> {
        let Self { m, k, l0, g } = *self;
        let r = q[0];
        let c = sin_cos(q[1]).1;
        let stretch = r - l0;
        let kinetic = 0.5 * m * (w[0] * w[0] + r * r * w[1] * w[1]);
        Some(kinetic - m * g * r * c + 0.5 * k * stretch * stretch)
    }

    #[inline]
    fn closed_velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        Some(self.velocity(q, p, t, out))
    }

    #[inline(always)]
    fn closed_acceleration_in<X: FieldScalar>(
        &self,
        q: &[X],
        w: &[X],
        t: f64,
        out: &mut [X],
    ) -> Option<Result<()>> {
        let Self { m, k, l0, g } = *self;
        let r = q[0];
        Some(self.inverse_mass(r, t).map(|_| {
            let (s, c) = q[1].sin_cos_kernel();
            out[0] = r * w[1] * w[1] + c * g - (r - l0) * (k / m);
            out[1] = -(s * g + w[0] * 2.0 * w[1]) / r;
        }))
    }

    #[inline(always)]
    fn closed_canonical_in<X: FieldScalar>(
        &self,
        q: &[X],
        p: &[X],
        t: f64,
        qdot: &mut [X],
        pdot: &mut [X],
    ) -> Option<Result<()>> {
        Some(self.velocity(q, p, t, qdot).map(|()| {
            pdot.copy_from_slice(&self.force(q, qdot));
        }))
    }
}

/// The elastic (spring) pendulum. State `[r, theta, rdot, thetadot]`; default method
/// `implicit_midpoint`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{ElasticPendulum, ElasticPendulumParams};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// let params = ElasticPendulumParams::default();
/// let r_eq = params.equilibrium_length();
/// let mut bob = ElasticPendulum::new(&[r_eq + 0.1, 0.3], &[0.0, 0.0], params).unwrap();
/// let e0 = bob.current_energy();
/// bob.integrate((0.0, 5.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((bob.current_energy() - e0).abs() < 1e-4 * e0.abs());
/// let [x, y] = bob.positions(None).unwrap();
/// assert!(y < 0.0 && x.abs() < r_eq + 0.5);
/// ```
#[derive(Debug, Clone)]
pub struct ElasticPendulum {
    phase: Phase,
    engine: LagrangianEngine<ElasticPendulumParams>,
}

impl ElasticPendulum {
    /// A spring pendulum at `q0 = (r0, theta0)` with velocities `qdot0 = (rdot0, thetadot0)`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for lengths other than 2; [`Error::NonFinite`];
    /// [`Error::InvalidParameter`] for `r0 <= 0`, `m <= 0`, `k <= 0`, `L0 < 0` or a
    /// non-finite parameter.
    pub fn new(q0: &[f64], qdot0: &[f64], params: ElasticPendulumParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        if let Some(&r0) = q0.first() {
            if r0.is_finite() && r0 <= 0.0 {
                return Err(Error::invalid(
                    "r0",
                    r0,
                    "the spring length must be > 0 (at r = 0 the bob is on the pivot: theta is \
                     undefined and the mass matrix diag(m, m r^2) singular)",
                ));
            }
        }
        let phase = engine.initial_phase(q0, qdot0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &ElasticPendulumParams {
        self.engine.lagrangian()
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<ElasticPendulumParams> {
        &self.engine
    }

    /// Cartesian bob position `[x, y] = [r sin theta, -r cos theta]` (m) for `q = (r, theta)`
    /// (the current `q` if `None`): pivot at the origin, `y` up.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` has length 2.
    pub fn positions(&self, q: Option<&[f64]>) -> Result<[f64; 2]> {
        let q = q.unwrap_or(&self.phase.state()[..2]);
        if q.len() != 2 {
            return Err(Error::DimensionMismatch {
                name: "q".into(),
                expected: 2,
                found: q.len(),
            });
        }
        let (s, c) = q[1].sin_cos();
        Ok([q[0] * s, -q[0] * c])
    }

    /// `[E_bounce, E_swing]` of `state = [r, theta, rdot, thetadot]` (the current state if
    /// `None`), in J: `E_bounce = m r'^2/2 + k (r - r_eq)^2/2`,
    /// `E_swing = m r^2 theta'^2/2 + m g r (1 - cos theta)`; they sum to `E - E_eq` exactly
    /// (module documentation).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 4.
    pub fn mode_energies(&self, state: Option<&[f64]>) -> Result<[f64; 2]> {
        let state = state.unwrap_or(self.phase.state());
        if state.len() != 4 {
            return Err(Error::DimensionMismatch {
                name: "state".into(),
                expected: 4,
                found: state.len(),
            });
        }
        let p = self.params();
        let [r, theta, rdot, thetadot] = [state[0], state[1], state[2], state[3]];
        let rho = r - p.equilibrium_length();
        let bounce = 0.5 * p.m * rdot * rdot + 0.5 * p.k * rho * rho;
        // 1 - cos theta = 2 sin^2(theta/2), without the cancellation at small angles.
        let half = (0.5 * theta).sin();
        let swing = 0.5 * p.m * r * r * thetadot * thetadot + 2.0 * p.m * p.g * r * half * half;
        Ok([bounce, swing])
    }
}

crate::impl_lagrangian_dynamics!(ElasticPendulum);

impl Capabilities for ElasticPendulum {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        Some(ElasticPendulum::positions(self, Some(q)).map(|x| fill(out, &x)))
    }
    fn modal_energies(&self, q: &[f64], qdot: &[f64]) -> Option<Result<Vec<f64>>> {
        // The bounce and the swing: the two modes the 2:1 resonance couples.
        let state = [q, qdot].concat();
        Some(self.mode_energies(Some(&state)).map(|e| e.to_vec()))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const ELASTIC_PENDULUM_PHYSICS: &str =
    "A bob on a spring swings and bounces. Small bounces have the frequency ω_s = √(k/m), \
         small swings ω_p = √(g/r_eq), where r_eq = l0 + mg/k is the stretched length it \
         hangs at. When ω_s = 2ω_p the bob bounces twice per swing, rising at each end of the \
         swing and dropping at the bottom (as a child pumps a swing by standing and \
         crouching), and the energy passes almost completely from bounce to swing and back: \
         the Fermi resonance of the CO₂ molecule in a classroom toy. The condition is often \
         quoted as k/m = 4g/l0, but the swing sees the stretched length; solving k/m = \
         4g/r_eq gives k = 3mg/l0. The energies are split exactly: E − E_eq = [m ṙ²/2 + k(r − \
         r_eq)²/2] + [m r² θ̇²/2 + m g r (1 − cos θ)].";

/// The catalogue entry of [`ElasticPendulum`].
pub static ELASTIC_PENDULUM_ENTRY: SystemEntry = SystemEntry {
    name: "elastic-pendulum",
    python: Some("ElasticPendulum"),
    summary: "spring pendulum, q = (r, theta) with theta from the downward vertical \
              (ElasticPendulum)",
    family: Family::Lagrangian,
    params: &[
        P::vector(
            "q0",
            Length::Fixed(2),
            D::demo_vector(&[1.3, 0.3]),
            "m, rad",
            "initial (r, theta)",
        )
        .initial_state(),
        P::vector(
            "qdot0",
            Length::Fixed(2),
            D::demo_vector(&[0.0, 0.0]),
            "m/s, rad/s",
            "initial (rdot, thetadot)",
        )
        .initial_state(),
        P::scalar("m", D::scalar(1.0), "kg", Range::POSITIVE, "bob mass"),
        P::scalar(
            "k",
            D::scalar(39.24),
            "N/m",
            Range::POSITIVE,
            "spring constant (default 4 m g / L0)",
        ),
        P::scalar(
            "L0",
            D::scalar(1.0),
            "m",
            Range::NON_NEGATIVE,
            "rest length of the spring",
        ),
        P::scalar(
            "g",
            D::scalar(9.81),
            "m/s^2",
            Range::ANY,
            "gravitational acceleration",
        ),
    ],
    separable: false,
    default_method: Method::ImplicitMidpoint,
    note: Some(
        "exact 2:1 resonance (bounce twice the swing frequency) at k = 3 m g / L0; p holds qdot",
    ),
    physics: Some(ELASTIC_PENDULUM_PHYSICS),
    presentation: Presentation {
        symbols: &["r", "\\theta"],
        time_unit: "s",
        state_units: None,
        drawing: Drawing::Bobs,
    },
    build: |v| {
        let params = ElasticPendulumParams {
            m: v.scalar("m")?,
            k: v.scalar("k")?,
            l0: v.scalar("L0")?,
            g: v.scalar("g")?,
        };
        Ok(Box::new(Erased(ElasticPendulum::new(
            v.vector("q0")?,
            v.vector("qdot0")?,
            params,
        )?)))
    },
};
