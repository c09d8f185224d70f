//! [`ElasticPendulum`]: a point mass `m` on a massless spring (stiffness `k`, rest length
//! `L0`, field `l0`) swinging in a vertical plane: the spring pendulum.
//!
//! Coordinates `q = (s, theta)`: the spring's stretch `s` beyond its rest length (so the
//! bob is `r = L0 + s` from the pivot) and its angle from the downward vertical, the
//! coordinates of the physicskit 0.4.0 peer. With the pivot at the origin and `y` up, the bob
//! is at `(x, y) = (r sin theta, -r cos theta)` and (Taylor, *Classical Mechanics* (2005),
//! problem 7.7; Lynch, Int. J. Bifurcation and Chaos 12 (2002) 1445)
//!
//! ```text
//! L = m (s'^2 + r^2 theta'^2) / 2 + m g r cos(theta) - k s^2 / 2,   r = L0 + s
//! ```
//!
//! The mass matrix `diag(m, m r^2)` is singular at `r = 0` (`s = -L0`), where the bob sits on
//! the pivot and `theta` is undefined; the constructor refuses `L0 + s0 <= 0`, and an
//! integration whose length reaches `r <= 0` stops with [`Error::SingularMatrix`] (a negative
//! `r` is outside the chart: the spring energy `k s^2 / 2` would be that of a bob at
//! distance `|r|` on the far side with the wrong stretch).
//!
//! # Closed forms
//!
//! The integrators use these hand-derived forms (checked against automatic differentiation
//! of `L` in `tests/classical/lagrangian/closed_forms.rs`); the acceleration and the canonical
//! field are written once, generic over the number type, so their Jacobians come from the
//! same code by automatic differentiation (`lagrangian/forward.rs`). With `r = L0 + s`,
//! `sn = sin theta`, `c = cos theta` and `w = (s', theta')`:
//!
//! ```text
//! mass matrix   M = diag(m, m r^2)
//! momentum      p_s = m s',   p_theta = m r^2 theta'
//! velocity      s' = p_s / m,   theta' = p_theta / (m r^2)
//! force         dL/ds = m r theta'^2 + m g c - k s,   dL/dtheta = -m g r sn
//! energy        E = m (s'^2 + r^2 theta'^2) / 2 - m g r c + k s^2 / 2
//! ```
//!
//! Euler–Lagrange: `d/dt (m s') = dL/ds` and `d/dt (m r^2 theta') = 2 m r s' theta' +
//! m r^2 theta'' = -m g r sn` (as `r' = s'`), so
//!
//! ```text
//! s''     = r theta'^2 + g c - (k/m) s
//! theta'' = -(g sn + 2 s' theta') / r
//! ```
//!
//! (centrifugal and Coriolis terms; the pendulum `theta'' = -(g/l) sin theta` at fixed `r`).
//!
//! # The 2:1 resonance
//!
//! The bob hangs at rest at the stretch `s_eq = m g / k`, the length `r_eq = L0 + m g / k`.
//! Linearized about it the motion separates into the bounce (spring) mode,
//! `omega_s = sqrt(k/m)`, and the swing (pendulum) mode, `omega_p = sqrt(g / r_eq)`: the
//! swing sees the stretched length, not `L0`. When `omega_s = 2 omega_p` the quadratic
//! coupling `r theta'^2` and `r cos theta` resonates and energy passes back and forth between
//! bounce and swing (Vitt & Gorelik 1933; Lynch 2002). The condition is often quoted as
//! `k/m = 4 g / L0`, which neglects the static stretch; the exact condition
//! `k/m = 4 g / r_eq = 4 g / (L0 + m g / k)` solves to
//!
//! ```text
//! k = 3 m g / L0,   r_eq = 4 L0 / 3,   omega_s = 2 omega_p = sqrt(3 g / L0)
//! ```
//!
//! ([`ElasticPendulumParams::resonant_k`]). With `m = L0 = 1`, `g = 9.81` that is
//! `k = 29.43`. The default `k = 39.24` is the often-quoted `4 m g / L0` (the physicskit 0.4.0
//! peer's default, kept for users who move from it): there `r_eq = 5 L0 / 4` and the frequency
//! ratio is `sqrt(k r_eq / (m g)) = sqrt(5)`, near the resonance but not on it, so the
//! exchange is small and fast.
//!
//! # Energy of each mode
//!
//! With `rho = s - s_eq = r - r_eq` the cross terms `m g rho` of gravity and spring cancel
//! exactly:
//!
//! ```text
//! E - E_eq = [m s'^2/2 + k rho^2/2] + [m r^2 theta'^2/2 + m g r (1 - cos theta)]
//!          =        E_bounce        +                E_swing
//! E_eq = -m g r_eq + (m g)^2 / (2 k)      (at rest at s_eq)
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
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Lagrangian as Erased};

/// Mass, spring constant, rest length and gravity of an [`ElasticPendulum`]; its
/// [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticPendulumParams {
    /// Bob mass `m` (kg), `> 0`.
    pub m: f64,
    /// Spring constant `k` (N/m), `> 0`.
    pub k: f64,
    /// Rest length `L0` of the spring (m), `>= 0` (`0`: a zero-length spring).
    pub l0: f64,
    /// Gravitational acceleration `g` (m/s²), finite.
    pub g: f64,
}

impl Default for ElasticPendulumParams {
    /// The defaults of [`ELASTIC_PENDULUM_ENTRY`], where they are written.
    fn default() -> Self {
        ELASTIC_PENDULUM_ENTRY.defaults(Self::from_values)
    }
}

impl ElasticPendulumParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            m: v.scalar("m")?,
            k: v.scalar("k")?,
            l0: v.scalar("L0")?,
            g: v.scalar("g")?,
        })
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
    /// `r_eq = L0 + m g / k`: `k = 3 m g / L0` (module documentation).
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
    /// [`Error::InvalidParameter`] unless `m`, `L0` and `g` are finite and positive (with
    /// `g <= 0` the bob does not hang and has no swing frequency; with `L0 = 0` no finite
    /// `k` is resonant: `omega_s / omega_p = sqrt(k r_eq/(m g)) = 1`).
    pub fn resonant_k(m: f64, l0: f64, g: f64) -> Result<f64> {
        let m = check_positive("m", m)?;
        let l0 = check_positive("L0", l0)?;
        let g = check_positive("g", g)?;
        Ok(3.0 * m * g / l0)
    }

    /// Stretch `s_eq = m g / k` at which the bob hangs at rest (m): the first coordinate of
    /// the hanging equilibrium `q = (s_eq, 0)`.
    pub fn equilibrium_stretch(&self) -> f64 {
        self.m * self.g / self.k
    }

    /// Length `r_eq = L0 + m g / k` of the spring when the bob hangs at rest (m).
    pub fn equilibrium_length(&self) -> f64 {
        self.l0 + self.equilibrium_stretch()
    }

    /// Angular frequency `sqrt(k/m)` of small bounces about `s_eq` (rad/s).
    pub fn spring_frequency(&self) -> f64 {
        (self.k / self.m).sqrt()
    }

    /// Angular frequency `sqrt(g / r_eq)` of small swings about the vertical (rad/s; `NaN`
    /// when `g / r_eq < 0`).
    pub fn swing_frequency(&self) -> f64 {
        (self.g / self.equilibrium_length()).sqrt()
    }

    /// Energy `E_eq = -m g r_eq + (m g)^2 / (2 k)` of the bob at rest at `s_eq` (J).
    pub fn equilibrium_energy(&self) -> f64 {
        let mg = self.m * self.g;
        -mg * self.equilibrium_length() + 0.5 * mg * mg / self.k
    }

    /// `(1/m, 1/(m r^2))` at the length `r = L0 + s`, or the singular-mass-matrix error at
    /// `r <= 0` (the bob on or past the pivot) or where LU would find a negligible pivot in
    /// `diag(m, m r^2)`.
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
                    "mass matrix diag(m, m r^2) at the length r = L0 + s = {r0} (the bob \
                     reached the pivot, r <= 0 or m r^2 negligible)"
                ),
                t,
            });
        }
        Ok((m.recip(), mr2.recip()))
    }

    /// `dL/dq = (m r theta'^2 + m g cos theta - k s, -m g r sin theta)`, `r = L0 + s`.
    #[inline(always)]
    fn force<X: FieldScalar>(&self, q: &[X], w: &[X]) -> [X; 2] {
        let Self { m, k, l0, g } = *self;
        let (sn, c) = q[1].sin_cos_kernel();
        let s = q[0];
        let r = s + l0;
        [(r * w[1] * w[1] + c * g) * m - s * k, r * (-m * g) * sn]
    }

    /// The velocity `(p_s / m, p_theta / (m r^2))` at `q = (s, theta)`.
    #[inline(always)]
    fn velocity<X: FieldScalar>(&self, q: &[X], p: &[X], t: f64, out: &mut [X]) -> Result<()> {
        self.inverse_mass(q[0] + self.l0, t)
            .map(|(inv_m, inv_mr2)| {
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
        let (s, theta) = (q[0], q[1]);
        let r = s + l0;
        (qdot[0] * qdot[0] + r * r * qdot[1] * qdot[1]) * (0.5 * m) + r * theta.cos() * (m * g)
            - s * s * (0.5 * k)
    }

    #[inline]
    fn closed_mass_matrix(&self, q: &[f64], _w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let (m, r) = (self.m, q[0] + self.l0);
        out.copy_from_slice(&[m, 0.0, 0.0, m * r * r]);
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, q: &[f64], w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let (m, r) = (self.m, q[0] + self.l0);
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
        let s = q[0];
        let r = s + l0;
        let c = sin_cos(q[1]).1;
        let kinetic = 0.5 * m * (w[0] * w[0] + r * r * w[1] * w[1]);
        Some(kinetic - m * g * r * c + 0.5 * k * s * s)
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
        let s = q[0];
        let r = s + l0;
        Some(self.inverse_mass(r, t).map(|_| {
            let (sn, c) = q[1].sin_cos_kernel();
            out[0] = r * w[1] * w[1] + c * g - s * (k / m);
            out[1] = -(sn * g + w[0] * 2.0 * w[1]) / r;
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

/// The elastic (spring) pendulum. State `[s, theta, sdot, thetadot]` (`s` the spring's
/// stretch beyond `L0`); default method `implicit_midpoint`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{ElasticPendulum, ElasticPendulumParams};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// let params = ElasticPendulumParams::default();
/// // Stretched 0.1 m beyond where it hangs at rest, swung out by 0.3 rad.
/// let s0 = params.equilibrium_stretch() + 0.1;
/// let mut bob = ElasticPendulum::new(&[s0, 0.3], &[0.0, 0.0], params).unwrap();
/// let e0 = bob.current_energy();
/// bob.integrate((0.0, 5.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((bob.current_energy() - e0).abs() < 1e-4 * e0.abs());
/// let [x, y] = bob.positions(None).unwrap();
/// let r_eq = params.equilibrium_length();
/// assert!(y < 0.0 && x.abs() < r_eq + 0.5);
/// ```
#[derive(Debug, Clone)]
pub struct ElasticPendulum {
    phase: Phase,
    engine: LagrangianEngine<ElasticPendulumParams>,
}

impl ElasticPendulum {
    /// A spring pendulum at `q0 = (s0, theta0)` (stretch beyond `L0`, angle) with velocities
    /// `qdot0 = (sdot0, thetadot0)`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for lengths other than 2; [`Error::NonFinite`];
    /// [`Error::InvalidParameter`] (named `q0`) for a length `L0 + s0 <= 0`, and for `m <= 0`,
    /// `k <= 0`, `L0 < 0` or a non-finite parameter.
    pub fn new(q0: &[f64], qdot0: &[f64], params: ElasticPendulumParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        if let Some(&s0) = q0.first() {
            let r0 = params.l0 + s0;
            if r0.is_finite() && r0 <= 0.0 {
                return Err(Error::invalid(
                    "q0",
                    s0,
                    format!(
                        "the stretch s0 = q0[0] must be > -L0 = {}: the spring's length L0 + s0 \
                         = {r0} must be > 0 (at length 0 the bob is on the pivot, theta is \
                         undefined and the mass matrix diag(m, m r^2) singular)",
                        -params.l0
                    ),
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

    /// Cartesian bob position `[x, y] = [r sin theta, -r cos theta]` (m), `r = L0 + s`, for
    /// `q = (s, theta)` (the current `q` if `None`): pivot at the origin, `y` up.
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
        let r = self.params().l0 + q[0];
        let (sn, c) = q[1].sin_cos();
        Ok([r * sn, -r * c])
    }

    /// `[E_bounce, E_swing]` of `state = [s, theta, sdot, thetadot]` (the current state if
    /// `None`), in J: `E_bounce = m s'^2/2 + k (s - s_eq)^2/2`,
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
        let [s, theta, sdot, thetadot] = [state[0], state[1], state[2], state[3]];
        let r = p.l0 + s;
        let rho = s - p.equilibrium_stretch();
        let bounce = 0.5 * p.m * sdot * sdot + 0.5 * p.k * rho * rho;
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
    "A bob on a spring swings and bounces. Its coordinates are the spring's stretch s beyond \
         its rest length L0 (the bob is r = L0 + s from the pivot) and the angle θ from the \
         vertical. Small bounces have the frequency ω_s = √(k/m), small swings ω_p = \
         √(g/r_eq), where r_eq = L0 + mg/k is the stretched length it hangs at. When ω_s = 2ω_p the bob bounces twice per swing, rising at each end of the \
         swing and dropping at the bottom (as a child pumps a swing by standing and \
         crouching), and the energy passes almost completely from bounce to swing and back: \
         the Fermi resonance of the CO₂ molecule in a classroom toy. The condition is often \
         quoted as k/m = 4g/L0, but the swing sees the stretched length; solving k/m = \
         4g/r_eq gives k = 3mg/L0. The energies are split exactly: E − E_eq = [m ṡ²/2 + k(r − \
         r_eq)²/2] + [m r² θ̇²/2 + m g r (1 − cos θ)].";

catalogue_static! {
    /// The catalogue entry of [`ElasticPendulum`].
    pub static ELASTIC_PENDULUM_ENTRY: SystemEntry = SystemEntry {
        name: "elastic-pendulum",
        python: Some("ElasticPendulum"),
        summary: "spring pendulum, q = (s, theta): s the spring's stretch beyond L0, theta from \
                  the downward vertical (ElasticPendulum)",
        family: Family::Lagrangian,
        params: &[
            P::vector(
                "q0",
                Length::Fixed(2),
                D::demo_vector(&[0.3, 0.3]),
                "m, rad",
                "initial (s, theta): stretch beyond L0 (> -L0), angle",
            )
            .initial_state(),
            P::vector(
                "qdot0",
                Length::Fixed(2),
                D::demo_vector(&[0.0, 0.0]),
                "m/s, rad/s",
                "initial (sdot, thetadot)",
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
        taylor_form: true,
        default_method: Method::ImplicitMidpoint,
        note: Some(
            "exact 2:1 resonance (bounce twice the swing frequency) at k = 3 m g / L0; p holds qdot",
        ),
        physics: Some(ELASTIC_PENDULUM_PHYSICS),
        presentation: Presentation {
            title: "Elastic pendulum",
            symbols: &["s", "\\theta"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Bobs {
                springs: true,
                scale: None,
            },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = ElasticPendulumParams::from_values(v)?;
            Ok(Box::new(Erased(ElasticPendulum::new(
                v.vector("q0")?,
                v.vector("qdot0")?,
                params,
            )?)))
        },
    };
}
