//! [`TriplePendulum`]: three point masses on massless rigid rods hanging from a fixed pivot, in
//! a vertical plane.
//!
//! Coordinates `q = (theta1, theta2, theta3)`, each rod's angle from the downward vertical.
//! With the pivot at the origin and `y` up, bob `i` is at
//! `(x_i, y_i) = (sum_{k<=i} l_k sin theta_k, -sum_{k<=i} l_k cos theta_k)`. Writing
//! `mu_j = sum_{i>=j} m_i` for the mass hanging at or below rod `j` (`mu = (m1 + m2 + m3,
//! m2 + m3, m3)`), the kinetic and potential energies of the chain are (Goldstein, *Classical
//! Mechanics*, 3rd ed., §1.6, for any number of links)
//!
//! ```text
//! T = (1/2) sum_{i,j} M_ij theta_i' theta_j',   M_ij = mu_max(i,j) l_i l_j cos(theta_i - theta_j)
//! V = -g sum_j mu_j l_j cos(theta_j)
//! L = T - V
//! ```
//!
//! `L` is written once, generic over the number type, and the
//! [`LagrangianEngine`] derives the equations of motion from it by automatic differentiation;
//! they are
//!
//! ```text
//! sum_j M_ij theta_j'' + sum_j mu_max(i,j) l_i l_j sin(theta_i - theta_j) theta_j'^2
//!     + mu_i g l_i sin(theta_i) = 0
//! ```
//!
//! which `tests/classical/systems/triple_pendulum.rs` solves by hand to check them. The mass
//! matrix depends on the angle differences, so the Hamiltonian is not separable:
//! `implicit_midpoint` (default) and the Gauss–Legendre methods are the symplectic choices.
//!
//! # Small oscillations
//!
//! About the hanging rest, `M -> M(0)` with entries `mu_max(i,j) l_i l_j` and the potential's
//! Hessian is `K = diag(mu_j g l_j)`; the normal-mode frequencies solve
//! `det(K - omega^2 M(0)) = 0`. For equal masses `m` and lengths `l`,
//! `M(0) = m l^2 [[3, 2, 1], [2, 2, 1], [1, 1, 1]]` and `K = m g l diag(3, 2, 1)`, and with
//! `lambda = omega^2 l / g` the determinant is `-(lambda^3 - 9 lambda^2 + 18 lambda - 6)`:
//! `lambda = 0.4158, 2.2943, 6.2899`.

use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{Lagrangian, LagrangianEngine, Scalar};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Lagrangian as Erased};
use crate::classical::systems::rod_chain::rod_chain_positions;

/// Masses, rod lengths and gravity of a [`TriplePendulum`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriplePendulumParams {
    /// Mass of the upper bob (kg), `> 0`.
    pub m1: f64,
    /// Mass of the middle bob (kg), `> 0`.
    pub m2: f64,
    /// Mass of the lower bob (kg), `> 0`.
    pub m3: f64,
    /// Length of the upper rod (m), `> 0`.
    pub l1: f64,
    /// Length of the middle rod (m), `> 0`.
    pub l2: f64,
    /// Length of the lower rod (m), `> 0`.
    pub l3: f64,
    /// Gravitational acceleration (m/s²), finite.
    pub g: f64,
}

impl Default for TriplePendulumParams {
    /// The defaults of [`TRIPLE_PENDULUM_ENTRY`], where they are written.
    fn default() -> Self {
        TRIPLE_PENDULUM_ENTRY.defaults(Self::from_values)
    }
}

impl TriplePendulumParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            m1: v.scalar("m1")?,
            m2: v.scalar("m2")?,
            m3: v.scalar("m3")?,
            l1: v.scalar("l1")?,
            l2: v.scalar("l2")?,
            l3: v.scalar("l3")?,
            g: v.scalar("g")?,
        })
    }
}

impl TriplePendulumParams {
    fn validate(self) -> Result<Self> {
        check_positive("m1", self.m1)?;
        check_positive("m2", self.m2)?;
        check_positive("m3", self.m3)?;
        check_positive("l1", self.l1)?;
        check_positive("l2", self.l2)?;
        check_positive("l3", self.l3)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// `mu_j`, the mass at or below rod `j`, and the rod lengths.
    fn links(&self) -> ([f64; 3], [f64; 3]) {
        let Self {
            m1,
            m2,
            m3,
            l1,
            l2,
            l3,
            ..
        } = *self;
        ([m1 + m2 + m3, m2 + m3, m3], [l1, l2, l3])
    }
}

impl Lagrangian for TriplePendulumParams {
    fn ndof(&self) -> usize {
        3
    }

    #[inline]
    fn lagrangian<X: Scalar>(&self, q: &[X], qdot: &[X], _t: X) -> X {
        let (mu, l) = self.links();
        let mut kinetic = X::zero();
        let mut potential = X::zero();
        for (i, (&qi, &wi)) in q.iter().zip(qdot).enumerate() {
            kinetic += wi * wi * (0.5 * mu[i] * l[i] * l[i]);
            // The pairs (i, j) and (j, i) of the sum: twice the half of M_ij.
            for (j, (&qj, &wj)) in q.iter().zip(qdot).enumerate().skip(i + 1) {
                kinetic += wi * wj * (qi - qj).cos() * (mu[j] * l[i] * l[j]);
            }
            potential -= qi.cos() * (mu[i] * self.g * l[i]);
        }
        kinetic - potential
    }
}

/// The planar triple pendulum. State `[theta1, theta2, theta3, theta1dot, theta2dot,
/// theta3dot]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{TriplePendulum, TriplePendulumParams};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// let mut chain =
///     TriplePendulum::new(&[1.6, 1.8, 2.0], &[0.0; 3], TriplePendulumParams::default())
///         .unwrap();
/// let e0 = chain.current_energy();
/// chain.integrate((0.0, 1.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((chain.current_energy() - e0).abs() < 1e-3 * e0.abs());
/// ```
#[derive(Debug, Clone)]
pub struct TriplePendulum {
    phase: Phase,
    engine: LagrangianEngine<TriplePendulumParams>,
}

impl TriplePendulum {
    /// A triple pendulum at angles `theta0` with angular velocities `thetadot0` (both length
    /// 3).
    ///
    /// # Errors
    /// Lengths other than 3, non-finite values, non-positive masses or lengths, non-finite `g`.
    pub fn new(theta0: &[f64], thetadot0: &[f64], params: TriplePendulumParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(theta0, thetadot0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &TriplePendulumParams {
        self.engine.lagrangian()
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<TriplePendulumParams> {
        &self.engine
    }

    /// Cartesian bob positions `[x1, y1, x2, y2, x3, y3]` (m) for angles `q` (the current
    /// angles if `None`): pivot at the origin, `y` up, so a hanging bob has negative `y`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` has length 3.
    pub fn positions(&self, q: Option<&[f64]>) -> Result<[f64; 6]> {
        let q = q.unwrap_or(&self.phase.state()[..3]);
        if q.len() != 3 {
            return Err(Error::DimensionMismatch {
                name: "q".into(),
                expected: 3,
                found: q.len(),
            });
        }
        let (_, l) = self.params().links();
        let mut out = [0.0; 6];
        rod_chain_positions(q, &l, &mut out);
        Ok(out)
    }
}

crate::impl_lagrangian_dynamics!(TriplePendulum);

impl Capabilities for TriplePendulum {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        Some(TriplePendulum::positions(self, Some(q)).map(|x| fill(out, &x)))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const TRIPLE_PENDULUM_PHYSICS: &str =
    "Three rigid rods hanging one below the other from a fixed pivot, a bob at the end of \
     each. Swinging a little, it moves as the sum of three normal modes, each a fixed shape \
     with its own frequency (for equal bobs and rods, ω² l/g are the roots of \
     λ³ − 9λ² + 18λ − 6 = 0: about 0.42, 2.29 and 6.29), the slowest with all three rods \
     leaning the same way, the fastest with neighbours opposed. Released from high up it is \
     chaotic, more violently than the double pendulum: the lower rods whip over the top, and \
     two starts that differ by a billionth of a radian part within seconds. The mass matrix \
     depends on the differences of the angles, so the Hamiltonian is not separable: the \
     implicit methods (implicit midpoint, Gauss–Legendre) keep the energy error bounded.";

catalogue_static! {
    /// The catalogue entry of [`TriplePendulum`].
    pub static TRIPLE_PENDULUM_ENTRY: SystemEntry = SystemEntry {
        name: "triple-pendulum",
        python: Some("TriplePendulum"),
        summary: "planar triple pendulum, angles from the downward vertical (TriplePendulum)",
        family: Family::Lagrangian,
        params: &[
            P::vector(
                "theta0",
                Length::Fixed(3),
                D::demo_vector(&[1.6, 1.8, 2.0]),
                "rad",
                "initial angles",
            )
            .initial_state(),
            P::vector(
                "thetadot0",
                Length::Fixed(3),
                D::demo_vector(&[0.0, 0.0, 0.0]),
                "rad/s",
                "initial angular velocities",
            )
            .initial_state(),
            P::scalar("m1", D::scalar(1.0), "kg", Range::POSITIVE, "upper mass"),
            P::scalar("m2", D::scalar(1.0), "kg", Range::POSITIVE, "middle mass"),
            P::scalar("m3", D::scalar(1.0), "kg", Range::POSITIVE, "lower mass"),
            P::scalar(
                "l1",
                D::scalar(1.0),
                "m",
                Range::POSITIVE,
                "upper rod length",
            ),
            P::scalar(
                "l2",
                D::scalar(1.0),
                "m",
                Range::POSITIVE,
                "middle rod length",
            ),
            P::scalar(
                "l3",
                D::scalar(1.0),
                "m",
                Range::POSITIVE,
                "lower rod length",
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
        note: Some("p holds thetadot, as in the double pendulum"),
        physics: Some(TRIPLE_PENDULUM_PHYSICS),
        presentation: Presentation {
            title: "Triple pendulum",
            symbols: &["\\theta_1", "\\theta_2", "\\theta_3"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Bobs {
                springs: false,
                scale: None,
            },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = TriplePendulumParams::from_values(v)?;
            Ok(Box::new(Erased(TriplePendulum::new(
                v.vector("theta0")?,
                v.vector("thetadot0")?,
                params,
            )?)))
        },
    };
}
