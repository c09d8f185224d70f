//! [`EulersDisk`]: a reduced, phenomenological model of Euler's disk running down.
//!
//! A spun disk rolling on a table is described here only by its inclination `theta` (between
//! the disk and the table) and the azimuth `phi` of the contact point. Both the dissipation
//! and the precession rate grow without bound as the disk flattens, which makes `theta` reach
//! zero in finite time (the finite-time singularity of Moffatt, Nature 404 (2000) 833; which
//! dissipation mechanism sets it is still argued). The model keeps only that behaviour:
//!
//! ```text
//! theta' = -decay_rate / max(theta, theta_floor)
//! phi'   = precession_const / max(theta, theta_floor)
//! ```
//!
//! It is not derived from the rolling disk's equations of motion: it is the reduced model of
//! the physicskit 0.4.0 peer, kept with the same equations for users who move from it. The
//! floor regularizes both right-hand sides near `theta = 0`.
//!
//! # Closed form
//!
//! Above the floor `theta theta' = -decay_rate`, so
//! `theta(t) = sqrt(theta0^2 - 2 decay_rate t)`, which vanishes at the collapse time
//! `t_f = theta0^2 / (2 decay_rate)` ([`eulers_disk_theta_analytic`]).
//!
//! There is no conserved energy: [`DynamicalSystem::energy`] returns `theta`, a quantity that
//! decreases to zero at the collapse, so that the energy column of a run shows the decay.

use crate::classical::core::error::{check_finite_scalar, check_non_negative, check_positive};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{Default as D, Family, ParamSpec as P, Range, SystemEntry};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Ode};

/// Rate constants and floor of an [`EulersDisk`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulersDiskParams {
    /// `decay_rate` (rad²/s), `>= 0`: the collapse time is `theta0^2 / (2 decay_rate)`.
    pub decay_rate: f64,
    /// `precession_const` (rad²/s), finite: the precession rate at `theta` is
    /// `precession_const / theta`.
    pub precession_const: f64,
    /// `theta_floor` (rad), `> 0`: the smallest `theta` the right-hand sides divide by.
    pub theta_floor: f64,
}

impl Default for EulersDiskParams {
    /// The defaults of [`EULERS_DISK_ENTRY`], where they are written.
    fn default() -> Self {
        EULERS_DISK_ENTRY.defaults(Self::from_values)
    }
}

impl EulersDiskParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            decay_rate: v.scalar("decay_rate")?,
            precession_const: v.scalar("precession_const")?,
            theta_floor: v.scalar("theta_floor")?,
        })
    }
}

/// `theta(t) = sqrt(theta0^2 - 2 decay_rate t)` at each `t`, zero from the collapse time
/// `theta0^2 / (2 decay_rate)` on (the floor ignored).
///
/// # Errors
/// [`Error::NonFinite`](crate::classical::Error::NonFinite) for a non-finite input;
/// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for `decay_rate < 0`.
pub fn eulers_disk_theta_analytic(t: &[f64], theta0: f64, decay_rate: f64) -> Result<Vec<f64>> {
    let theta0 = check_finite_scalar("theta0", theta0)?;
    let decay_rate = check_non_negative("decay_rate", decay_rate)?;
    crate::classical::core::error::check_vector("t", t, t.len())?;
    Ok(t.iter()
        .map(|&ti| (theta0 * theta0 - 2.0 * decay_rate * ti).max(0.0).sqrt())
        .collect())
}

/// The reduced Euler's-disk model; state `[theta, phi]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{eulers_disk_theta_analytic, EulersDisk, EulersDiskParams};
/// use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
///
/// let mut disk = EulersDisk::new(0.5, 0.0, EulersDiskParams::default()).unwrap();
/// disk.integrate((0.0, 2.0), 1e-3, Method::Rk4).unwrap();
/// let exact = eulers_disk_theta_analytic(&[2.0], 0.5, 0.05).unwrap()[0];
/// assert!((disk.state()[0] - exact).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct EulersDisk {
    phase: Phase,
    params: EulersDiskParams,
}

impl EulersDisk {
    /// A disk at inclination `theta0` (rad) and contact azimuth `phi0` (rad).
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::classical::Error::NonFinite);
    /// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter)
    /// for `decay_rate < 0` or `theta_floor <= 0`.
    pub fn new(theta0: f64, phi0: f64, params: EulersDiskParams) -> Result<Self> {
        check_non_negative("decay_rate", params.decay_rate)?;
        check_finite_scalar("precession_const", params.precession_const)?;
        check_positive("theta_floor", params.theta_floor)?;
        Ok(Self {
            phase: Phase::new(vec![theta0, phi0], 0.0)?,
            params,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &EulersDiskParams {
        &self.params
    }

    /// The collapse time `theta0^2 / (2 decay_rate)` from inclination `theta0` (s; infinite
    /// without decay).
    pub fn collapse_time(&self, theta0: f64) -> f64 {
        theta0 * theta0 / (2.0 * self.params.decay_rate)
    }
}

impl EulersDisk {
    /// The right-hand side, for `impl_ode_dynamics!`.
    #[inline]
    fn field(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let inv = self.params.theta_floor.max(state[0]).recip();
        out[0] = -self.params.decay_rate * inv;
        out[1] = self.params.precession_const * inv;
        Ok(())
    }

    /// `theta`: not a conserved energy (the model is dissipative by design) but the
    /// inclination itself, which decreases to zero at the collapse.
    fn field_energy(&self, state: &[f64]) -> f64 {
        state[0]
    }

    /// The Jacobian of [`field`](Self::field), for `impl_ode_dynamics!`.
    fn field_jacobian(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        // d(1/theta)/dtheta = -1/theta^2 above the floor; the floor's branch is constant.
        let theta = state[0];
        let d_inv = if theta > self.params.theta_floor {
            -1.0 / (theta * theta)
        } else {
            0.0
        };
        out.copy_from_slice(&[
            -self.params.decay_rate * d_inv,
            0.0,
            self.params.precession_const * d_inv,
            0.0,
        ]);
        Ok(())
    }
}

impl_ode_dynamics!(EulersDisk, dim = 2, method = ImplicitMidpoint, jacobian);

impl Capabilities for EulersDisk {}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const EULERS_DISK_PHYSICS: &str =
    "The peer's reduced, phenomenological model of Euler's disk, a coin spinning down on a \
    table: not rolling mechanics but two equations for its tilt θ and the azimuth φ of its \
    contact point, θ̇ = −k / max(θ, θ_min) and φ̇ = c / max(θ, θ_min). The tilt falls ever \
    faster, θ² = θ₀² − 2kt reaching zero at the finite time θ₀²/2k, and the precession \
    rate grows without bound: the finite-time singularity of a real disk's last moments, \
    which the floor θ_min stops. Its energy() returns θ, as the peer's does: the model has \
    no energy.";

catalogue_static! {
    /// The catalogue entry of [`EulersDisk`].
    pub static EULERS_DISK_ENTRY: SystemEntry = SystemEntry {
        name: "eulers-disk",
        python: Some("EulersDisk"),
        summary: "reduced Euler's disk: inclination collapsing in finite time, precession \
                  speeding up (EulersDisk)",
        family: Family::Ode,
        params: &[
            P::scalar(
                "theta0",
                D::demo_scalar(0.5),
                "rad",
                Range::ANY,
                "initial inclination of the disk to the table",
            )
            .initial_state(),
            P::scalar(
                "phi0",
                D::scalar(0.0),
                "rad",
                Range::ANY,
                "initial azimuth of the contact point",
            )
            .initial_state(),
            P::scalar(
                "decay_rate",
                D::scalar(0.05),
                "rad^2/s",
                Range::NON_NEGATIVE,
                "collapse rate: theta' = -decay_rate / theta",
            ),
            P::scalar(
                "precession_const",
                D::scalar(1.0),
                "rad^2/s",
                Range::ANY,
                "precession: phi' = precession_const / theta",
            ),
            P::scalar(
                "theta_floor",
                D::scalar(1e-3),
                "rad",
                Range::POSITIVE,
                "smallest theta the rates divide by",
            ),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::ImplicitMidpoint,
        note: Some(
            "y columns: theta, phi; a phenomenological reduced model, not rolling mechanics; the \
             energy column is theta; collapse at theta0^2 / (2 decay_rate)",
        ),
        physics: Some(EULERS_DISK_PHYSICS),
        presentation: Presentation {
            title: "Euler's disk (reduced model)",
            symbols: &["\\theta", "\\phi"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::ContactSpiral,
            pace: Pace::Own,
            section_first: false,
            energy_conserved: false,
        },
        build: |v| {
            let params = EulersDiskParams::from_values(v)?;
            Ok(Box::new(Ode(EulersDisk::new(
                v.scalar("theta0")?,
                v.scalar("phi0")?,
                params,
            )?)))
        },
    };
}
