//! [`FoucaultPendulum`]: a long pendulum swinging near the vertical, seen from the rotating
//! Earth.
//!
//! State `[x, y, vx, vy]`: the bob's horizontal displacement from the vertical through the
//! pivot (`x` east, `y` north) and its velocity. In a non-rotating frame a small swing is the
//! isotropic oscillator `q'' = -omega0^2 q` with `omega0 = sqrt(g / length)`; the ground turns
//! about the local vertical at `omega_z = omega_earth sin(latitude)` (the vertical component
//! of Earth's rotation), which adds the Coriolis acceleration (the horizontal part of the
//! centrifugal term is of second order in `omega_earth` and left out, as usual; Landau &
//! Lifshitz, *Mechanics*, §39, problem 1):
//!
//! ```text
//! x'' = -omega0^2 x + 2 omega_z y'
//! y'' = -omega0^2 y - 2 omega_z x'
//! ```
//!
//! The Coriolis force is perpendicular to the velocity and does no work, so the energy per
//! unit mass `E = |v|^2 / 2 + omega0^2 |q|^2 / 2` is conserved; it is a quadratic invariant
//! of a linear equation, which the default `implicit_midpoint` keeps to its solver's rounding.
//!
//! # Closed form
//!
//! With `w = x + i y` the equations read `w'' + 2 i omega_z w' + omega0^2 w = 0`. Writing
//! `w = exp(-i omega_z t) u` removes the first-order term: `u'' = -Omega^2 u` with
//! `Omega = sqrt(omega0^2 + omega_z^2)`, so
//!
//! ```text
//! u(t) = w0 cos(Omega t) + (w0' + i omega_z w0) sin(Omega t) / Omega,   w = exp(-i omega_z t) u
//! ```
//!
//! ([`FoucaultPendulum::analytic_solution`]): a fixed ellipse turned clockwise (seen from
//! above, in the northern hemisphere) at `omega_z`. The swing plane comes back to itself after
//! `2 pi / omega_z`, the sidereal day divided by `sin(latitude)`
//! ([`FoucaultPendulum::precession_period`]).

use crate::classical::core::error::{check_finite_scalar, check_positive, check_vector};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Ode};

/// Earth's sidereal rotation rate `2 pi / 86164.0905 s` (rad/s): the default `omega_earth`.
pub const OMEGA_EARTH: f64 = 2.0 * std::f64::consts::PI / 86164.0905;

/// Length, gravity, latitude and Earth's rotation rate of a [`FoucaultPendulum`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoucaultParams {
    /// Pendulum length (m), `> 0`.
    pub length: f64,
    /// Gravitational acceleration (m/s²), `> 0`.
    pub g: f64,
    /// Geographic latitude in degrees, in `[-90, 90]` (south negative).
    pub latitude_deg: f64,
    /// Earth's rotation rate (rad/s), finite (negative: the other sense).
    pub omega_earth: f64,
}

impl Default for FoucaultParams {
    /// Foucault's 1851 pendulum in the Panthéon, on the Earth's sidereal rate: the
    /// defaults of [`FOUCAULT_ENTRY`], where they are written.
    fn default() -> Self {
        FOUCAULT_ENTRY.defaults(Self::from_values)
    }
}

impl FoucaultParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            length: v.scalar("length")?,
            g: v.scalar("g")?,
            latitude_deg: v.scalar("latitude_deg")?,
            omega_earth: v.scalar("omega_earth")?,
        })
    }
}

impl FoucaultParams {
    fn validate(self) -> Result<Self> {
        check_positive("length", self.length)?;
        check_positive("g", self.g)?;
        let lat = check_finite_scalar("latitude_deg", self.latitude_deg)?;
        if !(-90.0..=90.0).contains(&lat) {
            return Err(Error::invalid(
                "latitude_deg",
                lat,
                "a latitude is between -90 and 90 degrees",
            ));
        }
        check_finite_scalar("omega_earth", self.omega_earth)?;
        Ok(self)
    }

    /// The swing frequency `omega0 = sqrt(g / length)` without rotation (rad/s).
    pub fn omega0(&self) -> f64 {
        (self.g / self.length).sqrt()
    }

    /// The vertical component `omega_z = omega_earth sin(latitude)` of Earth's rotation
    /// (rad/s): the rate at which the swing plane turns.
    pub fn omega_z(&self) -> f64 {
        self.omega_earth * self.latitude_deg.to_radians().sin()
    }
}

/// Foucault's pendulum in the small-swing approximation.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{FoucaultParams, FoucaultPendulum};
/// use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
///
/// let params = FoucaultParams::default();
/// let mut p = FoucaultPendulum::new(&[1.0, 0.0], &[0.0, 0.0], params).unwrap();
/// let e0 = p.current_energy();
/// p.integrate((0.0, 100.0), 0.05, Method::ImplicitMidpoint).unwrap();
/// assert!((p.current_energy() - e0).abs() < 1e-12 * e0);
/// ```
#[derive(Debug, Clone)]
pub struct FoucaultPendulum {
    phase: Phase,
    params: FoucaultParams,
    /// `omega0^2` and `2 omega_z`, formed once.
    omega0_sq: f64,
    two_omega_z: f64,
}

impl FoucaultPendulum {
    /// A pendulum at horizontal displacement `q0 = (x, y)` (m; `x` east, `y` north) with
    /// velocity `v0 = (vx, vy)` (m/s).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q0`, `v0` have length 2; [`Error::NonFinite`];
    /// [`Error::InvalidParameter`] for `length <= 0`, `g <= 0`, a latitude outside
    /// `[-90, 90]` or a non-finite parameter.
    pub fn new(q0: &[f64], v0: &[f64], params: FoucaultParams) -> Result<Self> {
        let params = params.validate()?;
        check_vector("q0", q0, 2)?;
        check_vector("v0", v0, 2)?;
        let omega0 = params.omega0();
        Ok(Self {
            phase: Phase::new(vec![q0[0], q0[1], v0[0], v0[1]], 0.0)?,
            omega0_sq: omega0 * omega0,
            two_omega_z: 2.0 * params.omega_z(),
            params,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &FoucaultParams {
        &self.params
    }

    /// Time for the swing plane to turn once, `2 pi / |omega_z|` (s): the sidereal day over
    /// `|sin(latitude)|` (infinite on the equator).
    pub fn precession_period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.params.omega_z().abs()
    }

    /// The exact solution `(x(t), y(t))` of the equations of motion from `q0`, `v0` at
    /// `t = 0`, for swing frequency `omega0` and vertical rotation rate `omega_z` (module
    /// documentation).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q0`, `v0` have length 2; [`Error::NonFinite`] for
    /// a non-finite input; [`Error::InvalidParameter`] for `omega0 < 0` or
    /// `omega0 = omega_z = 0` (no oscillation).
    pub fn analytic_solution(
        q0: &[f64],
        v0: &[f64],
        omega0: f64,
        omega_z: f64,
        t: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        check_vector("q0", q0, 2)?;
        check_vector("v0", v0, 2)?;
        let omega0 = check_finite_scalar("omega0", omega0)?;
        if omega0 < 0.0 {
            return Err(Error::invalid("omega0", omega0, "must be >= 0"));
        }
        let omega_z = check_finite_scalar("omega_z", omega_z)?;
        let big = omega0.hypot(omega_z);
        if big == 0.0 {
            return Err(Error::invalid(
                "omega0",
                omega0,
                "omega0 and omega_z are both zero: the bob moves in a straight line",
            ));
        }
        check_vector("t", t, t.len())?;
        // u(0) = w0, u'(0) = w0' + i omega_z w0.
        let (a_re, a_im) = (q0[0], q0[1]);
        let (b_re, b_im) = (
            (v0[0] - omega_z * q0[1]) / big,
            (v0[1] + omega_z * q0[0]) / big,
        );
        let (mut x, mut y) = (Vec::with_capacity(t.len()), Vec::with_capacity(t.len()));
        for &ti in t {
            let (s, c) = (big * ti).sin_cos();
            let (u_re, u_im) = (a_re * c + b_re * s, a_im * c + b_im * s);
            // exp(-i omega_z t) u
            let (sz, cz) = (omega_z * ti).sin_cos();
            x.push(cz * u_re + sz * u_im);
            y.push(cz * u_im - sz * u_re);
        }
        Ok((x, y))
    }
}

impl FoucaultPendulum {
    /// The right-hand side, for `impl_ode_dynamics!`.
    #[inline]
    fn field(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let (w2, c) = (self.omega0_sq, self.two_omega_z);
        out[0] = state[2];
        out[1] = state[3];
        out[2] = -w2 * state[0] + c * state[3];
        out[3] = -w2 * state[1] - c * state[2];
        Ok(())
    }

    /// Energy per unit mass `|v|^2 / 2 + omega0^2 |q|^2 / 2` (J/kg; `NaN` for a state of the
    /// wrong length).
    fn field_energy(&self, state: &[f64]) -> f64 {
        let [x, y, vx, vy] = [state[0], state[1], state[2], state[3]];
        0.5 * (vx * vx + vy * vy) + 0.5 * self.omega0_sq * (x * x + y * y)
    }

    /// The Jacobian of [`field`](Self::field), for `impl_ode_dynamics!`.
    fn field_jacobian(&self, _t: f64, _state: &[f64], out: &mut [f64]) -> Result<()> {
        let (w2, c) = (self.omega0_sq, self.two_omega_z);
        out.copy_from_slice(&[
            0.0, 0.0, 1.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, //
            -w2, 0.0, 0.0, c, //
            0.0, -w2, -c, 0.0,
        ]);
        Ok(())
    }
}

impl_ode_dynamics!(
    FoucaultPendulum,
    dim = 4,
    method = ImplicitMidpoint,
    jacobian
);

impl Capabilities for FoucaultPendulum {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        // The bob seen from above: its horizontal displacement (the state's first half).
        if q.len() < 2 {
            return Some(Err(Error::DimensionMismatch {
                name: "q".into(),
                expected: 2,
                found: q.len(),
            }));
        }
        fill(out, &q[..2]);
        Some(Ok(()))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const FOUCAULT_PHYSICS: &str =
    "A long pendulum swinging on the rotating Earth, seen from the ground. For small swings \
    the bob moves in the horizontal plane under the restoring force −ω₀²(x, y), with ω₀² = \
    g/ℓ, and the Coriolis force of the vertical part of the Earth's rotation, Ω_z = Ω sin \
    φ at latitude φ: ẍ = −ω₀²x + 2Ω_z ẏ, ÿ = −ω₀²y − 2Ω_z ẋ. The plane of the swing turns \
    clockwise in the northern hemisphere at the rate Ω sin φ, once every sidereal day \
    divided by sin φ, while the energy of the swing stays constant: the Coriolis force \
    does no work. The closed form, a plain swing in a frame turning at −Ω_z, solves these \
    equations exactly.";

catalogue_static! {
    /// The catalogue entry of [`FoucaultPendulum`].
    pub static FOUCAULT_ENTRY: SystemEntry = SystemEntry {
        name: "foucault-pendulum",
        python: Some("FoucaultPendulum"),
        summary: "small swings seen from the rotating Earth: the swing plane turns at \
                  omega_earth sin(latitude) (FoucaultPendulum)",
        family: Family::Ode,
        params: &[
            P::vector(
                "q0",
                Length::Fixed(2),
                D::demo_vector(&[1.0, 0.0]),
                "m",
                "initial horizontal displacement (x east, y north)",
            )
            .initial_state(),
            P::vector(
                "v0",
                Length::Fixed(2),
                D::demo_vector(&[0.0, 0.0]),
                "m/s",
                "initial horizontal velocity",
            )
            .initial_state(),
            P::scalar(
                "length",
                D::scalar(67.0),
                "m",
                Range::POSITIVE,
                "pendulum length",
            ),
            P::scalar(
                "g",
                D::scalar(9.81),
                "m/s^2",
                Range::POSITIVE,
                "gravitational acceleration",
            ),
            P::scalar(
                "latitude_deg",
                D::scalar(48.85),
                "deg",
                Range::closed(-90.0, 90.0),
                "geographic latitude (south negative)",
            ),
            P::scalar(
                "omega_earth",
                D::scalar(OMEGA_EARTH),
                "rad/s",
                Range::ANY,
                "Earth's rotation rate (sidereal)",
            ),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::ImplicitMidpoint,
        note: Some(
            "y columns: x, y, vx, vy; the swing plane turns once in 2 pi / (omega_earth \
             sin(latitude)); energy is per unit mass",
        ),
        physics: Some(FOUCAULT_PHYSICS),
        presentation: Presentation {
            title: "Foucault pendulum",
            symbols: &["x", "y"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Swing,
            pace: Pace::TimeLapse {
                dt: 0.02,
                steps_per_frame: 400,
            },
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = FoucaultParams::from_values(v)?;
            Ok(Box::new(Ode(FoucaultPendulum::new(
                v.vector("q0")?,
                v.vector("v0")?,
                params,
            )?)))
        },
    };
}
