//! [`EulerTop`]: the torque-free rigid body, Euler's equations plus quaternion kinematics.
//!
//! State `[w1, w2, w3, qw, qx, qy, qz]`: the body-frame angular velocity `omega` and the
//! body-to-world orientation quaternion `q`. With principal moments `I1, I2, I3` (Landau &
//! Lifshitz, *Mechanics*, 3rd ed. (1976), §36–37; Goldstein §5.5):
//!
//! ```text
//! I1 w1' = (I2 - I3) w2 w3      I2 w2' = (I3 - I1) w3 w1      I3 w3' = (I1 - I2) w1 w2
//! q'     = (1/2) q ⊗ (0, omega)                        (body-frame angular velocity)
//! ```
//!
//! The right-hand side is quadratic, and the kinetic energy `sum I_i w_i^2 / 2`, the squared
//! angular momentum `sum (I_i w_i)^2` and the quaternion norm `|q|^2` are quadratic
//! invariants, which the default `implicit_midpoint` conserves exactly up to the solver
//! tolerance (Cooper 1987). The analytic Jacobian makes its Newton fallback available. A spin
//! near the intermediate axis tumbles periodically (the intermediate-axis theorem) with a
//! period given by a complete elliptic integral (Landau & Lifshitz §37).

use crate::classical::core::error::{check_len, check_positive, check_vector};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Ode};

/// Principal moments of inertia of an [`EulerTop`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerTopParams {
    /// Moment about body axis 1.
    pub i1: f64,
    /// Moment about body axis 2.
    pub i2: f64,
    /// Moment about body axis 3.
    pub i3: f64,
}

impl Default for EulerTopParams {
    /// The defaults of [`EULER_TOP_ENTRY`], where they are written.
    fn default() -> Self {
        EULER_TOP_ENTRY.defaults(Self::from_values)
    }
}

impl EulerTopParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            i1: v.scalar("I1")?,
            i2: v.scalar("I2")?,
            i3: v.scalar("I3")?,
        })
    }
}

/// The torque-free rigid body (the spec's `EulerTop`).
///
/// # Example
/// ```
/// use physicskit::classical::systems::{EulerTop, EulerTopParams};
/// use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
///
/// let mut top = EulerTop::new(&[0.01, 1.0, 0.01], EulerTopParams::default(), None).unwrap();
/// let e0 = top.current_energy();
/// top.integrate((0.0, 10.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((top.current_energy() - e0).abs() < 1e-13);
/// ```
#[derive(Debug, Clone)]
pub struct EulerTop {
    phase: Phase,
    inertia: [f64; 3],
    /// Euler's coefficients `((I2-I3)/I1, (I3-I1)/I2, (I1-I2)/I3)`, computed once rather than
    /// with three divisions per evaluation.
    euler: [f64; 3],
}

impl EulerTop {
    /// A body spinning at `omega0` (body frame) in orientation `quat0 = (w, x, y, z)`
    /// (normalized; the identity if `None`).
    ///
    /// # Errors
    /// `omega0` not of length 3 or `quat0` not of length 4, non-finite values, non-positive
    /// moments, or a zero quaternion.
    pub fn new(omega0: &[f64], params: EulerTopParams, quat0: Option<&[f64]>) -> Result<Self> {
        check_vector("omega0", omega0, 3)?;
        let inertia = [
            check_positive("I1", params.i1)?,
            check_positive("I2", params.i2)?,
            check_positive("I3", params.i3)?,
        ];
        let quat = match quat0 {
            None => [1.0, 0.0, 0.0, 0.0],
            Some(q) => {
                check_vector("quat0", q, 4)?;
                let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
                if !(norm > 0.0 && norm.is_finite()) {
                    return Err(Error::invalid(
                        "quat0",
                        norm,
                        "quaternion norm must be positive (a zero quaternion is no rotation)",
                    ));
                }
                [q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm]
            }
        };
        let mut state = omega0.to_vec();
        state.extend_from_slice(&quat);
        let [i1, i2, i3] = inertia;
        Ok(Self {
            phase: Phase::new(state, 0.0)?,
            inertia,
            euler: [(i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3],
        })
    }

    /// The principal moments `(I1, I2, I3)`.
    pub fn inertia(&self) -> [f64; 3] {
        self.inertia
    }

    /// Current body-frame angular velocity.
    pub fn omega(&self) -> [f64; 3] {
        let s = self.phase.state();
        [s[0], s[1], s[2]]
    }

    /// Current orientation quaternion `(w, x, y, z)`.
    pub fn quaternion(&self) -> [f64; 4] {
        let s = self.phase.state();
        [s[3], s[4], s[5], s[6]]
    }

    /// `|L|^2 = sum (I_i w_i)^2` of `state` (the current state if `None`).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 7.
    pub fn angular_momentum_squared(&self, state: Option<&[f64]>) -> Result<f64> {
        let s = state.unwrap_or(self.phase.state());
        check_len("state", s, 7)?;
        Ok((0..3).map(|i| (self.inertia[i] * s[i]).powi(2)).sum())
    }

    /// The angular momentum in the body frame, `L = (I1 w1, I2 w2, I3 w3)` (kg m^2/s), of
    /// `state` (the current state if `None`). Its tip traces the polhodes on the sphere
    /// `|L|^2 = const`; `R L` (with [`EulerTop::rotation_matrix`]) is the conserved space-frame
    /// angular momentum.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 7.
    pub fn body_angular_momentum(&self, state: Option<&[f64]>) -> Result<[f64; 3]> {
        let s = state.unwrap_or(self.phase.state());
        check_len("state", s, 7)?;
        Ok([0, 1, 2].map(|i| self.inertia[i] * s[i]))
    }

    /// Half-extents `(a1, a2, a3)` (m) of the uniform box of mass `mass` (kg) whose principal
    /// moments are this body's, the shape to draw it as. A box of half-extents `a_i` has
    /// `I1 = M (a2^2 + a3^2) / 3` and cyclically, so `a1^2 = 3 (I2 + I3 - I1) / (2 M)`. The
    /// default moments `(1, 2, 3)` are those of a flat plate (`a3 = 0`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a mass that is not finite and positive, or moments that
    /// break the triangle inequality `I_i <= I_j + I_k` (no rigid body has them).
    pub fn inertia_box(&self, mass: f64) -> Result<[f64; 3]> {
        check_positive("mass", mass)?;
        let sum: f64 = self.inertia.iter().sum();
        // `sum - 2 I_i` rounds with an error of a few ulps of `sum`: within that it is a plate.
        let slack = 4.0 * f64::EPSILON * sum;
        let mut half = [0.0; 3];
        for (i, (a, &moment)) in half.iter_mut().zip(&self.inertia).enumerate() {
            let excess = sum - 2.0 * moment;
            if excess < -slack {
                return Err(Error::invalid(
                    ["I1", "I2", "I3"][i],
                    moment,
                    "exceeds the sum of the other two moments: no rigid body (so no box) has \
                     these moments",
                ));
            }
            *a = (1.5 * excess.max(0.0) / mass).sqrt();
        }
        Ok(half)
    }

    /// The body-to-world rotation matrix (row-major) of the quaternion in `state` (the current
    /// state if `None`): `v_world = R v_body`. The quaternion is normalized first, so the
    /// result is a rotation even after a non-norm-preserving integrator (`rk4`).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 7; [`Error::InvalidParameter`]
    /// for a zero or non-finite quaternion.
    pub fn rotation_matrix(&self, state: Option<&[f64]>) -> Result<[[f64; 3]; 3]> {
        let s = state.unwrap_or(self.phase.state());
        check_len("state", s, 7)?;
        let (w, x, y, z) = (s[3], s[4], s[5], s[6]);
        let n2 = w * w + x * x + y * y + z * z;
        if !(n2 > 0.0 && n2.is_finite()) {
            return Err(Error::invalid(
                "quaternion",
                n2.sqrt(),
                "must be non-zero and finite",
            ));
        }
        let k = 2.0 / n2;
        Ok([
            [
                1.0 - k * (y * y + z * z),
                k * (x * y - w * z),
                k * (x * z + w * y),
            ],
            [
                k * (x * y + w * z),
                1.0 - k * (x * x + z * z),
                k * (y * z - w * x),
            ],
            [
                k * (x * z - w * y),
                k * (y * z + w * x),
                1.0 - k * (x * x + y * y),
            ],
        ])
    }
}

impl EulerTop {
    /// The right-hand side, for `impl_ode_dynamics!`.
    #[inline]
    fn field(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let [a1, a2, a3] = self.euler;
        let (w1, w2, w3) = (state[0], state[1], state[2]);
        let (qw, qx, qy, qz) = (state[3], state[4], state[5], state[6]);
        out[0] = a1 * w2 * w3;
        out[1] = a2 * w3 * w1;
        out[2] = a3 * w1 * w2;
        // (1/2) q ⊗ (0, w) = (1/2) (-v.w, qw w + v x w), v = (qx, qy, qz).
        out[3] = -0.5 * (qx * w1 + qy * w2 + qz * w3);
        out[4] = 0.5 * (qw * w1 + qy * w3 - qz * w2);
        out[5] = 0.5 * (qw * w2 + qz * w1 - qx * w3);
        out[6] = 0.5 * (qw * w3 + qx * w2 - qy * w1);
        Ok(())
    }

    /// Rotational kinetic energy `sum I_i w_i^2 / 2` (`NaN` for a state of the wrong length).
    fn field_energy(&self, state: &[f64]) -> f64 {
        0.5 * (0..3)
            .map(|i| self.inertia[i] * state[i] * state[i])
            .sum::<f64>()
    }

    /// The Jacobian of [`field`](Self::field), for `impl_ode_dynamics!`.
    fn field_jacobian(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let [a1, a2, a3] = self.euler;
        let (w1, w2, w3) = (state[0], state[1], state[2]);
        let (qw, qx, qy, qz) = (
            0.5 * state[3],
            0.5 * state[4],
            0.5 * state[5],
            0.5 * state[6],
        );
        let (h1, h2, h3) = (0.5 * w1, 0.5 * w2, 0.5 * w3);
        let rows: [[f64; 7]; 7] = [
            [0.0, a1 * w3, a1 * w2, 0.0, 0.0, 0.0, 0.0],
            [a2 * w3, 0.0, a2 * w1, 0.0, 0.0, 0.0, 0.0],
            [a3 * w2, a3 * w1, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-qx, -qy, -qz, 0.0, -h1, -h2, -h3],
            [qw, -qz, qy, h1, 0.0, h3, -h2],
            [qz, qw, -qx, h2, -h3, 0.0, h1],
            [-qy, qx, qw, h3, h2, -h1, 0.0],
        ];
        for (dst, src) in out.chunks_exact_mut(7).zip(rows.iter()) {
            dst.copy_from_slice(src);
        }
        Ok(())
    }
}

impl_ode_dynamics!(EulerTop, dim = 7, method = ImplicitMidpoint, jacobian);

impl Capabilities for EulerTop {
    fn rotation_matrix(&self, state: &[f64]) -> Option<Result<[f64; 9]>> {
        Some(EulerTop::rotation_matrix(self, Some(state)).map(|r| {
            [
                r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
            ]
        }))
    }
    fn angular_momentum_squared(&self, state: &[f64]) -> Option<Result<f64>> {
        Some(EulerTop::angular_momentum_squared(self, Some(state)))
    }
    fn body_angular_momentum(&self, state: &[f64]) -> Option<Result<[f64; 3]>> {
        Some(EulerTop::body_angular_momentum(self, Some(state)))
    }
    fn inertia_box(&self, mass: f64) -> Option<Result<[f64; 3]>> {
        Some(EulerTop::inertia_box(self, mass))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const EULER_TOP_PHYSICS: &str =
    "A free rigid body with three different principal moments I₁ < I₂ < I₃ rotates stably \
         about its smallest and its largest axis, but not about the intermediate one: spun \
         almost exactly about it, the spin ω₂ periodically reverses, the body flipping over \
         while angular momentum stays fixed in space (the effect the cosmonaut Dzhanibekov \
         saw with a wing nut). In the body frame the angular momentum L moves on a sphere |L| \
         = const along its intersections with the energy ellipsoid, the polhodes: closed \
         loops around the stable axes 1 and 3, and separatrices through the unstable axis 2. \
         The implicit midpoint rule keeps energy and |L| exactly, so the computed curves \
         close.";

catalogue_static! {
    /// The catalogue entry of [`EulerTop`].
    pub static EULER_TOP_ENTRY: SystemEntry = SystemEntry {
        name: "euler-top",
        python: Some("EulerTop"),
        summary: "torque-free rigid body: Euler's equations and the orientation quaternion \
                  (EulerTop)",
        family: Family::Ode,
        params: &[
            P::vector(
                "omega0",
                Length::Fixed(3),
                D::demo_vector(&[0.01, 1.0, 0.01]),
                "rad/s",
                "initial body angular velocity",
            )
            .initial_state(),
            P::scalar(
                "I1",
                D::scalar(1.0),
                "kg m^2",
                Range::POSITIVE,
                "principal moment 1",
            ),
            P::scalar(
                "I2",
                D::scalar(2.0),
                "kg m^2",
                Range::POSITIVE,
                "principal moment 2",
            ),
            P::scalar(
                "I3",
                D::scalar(3.0),
                "kg m^2",
                Range::POSITIVE,
                "principal moment 3",
            ),
            P::vector(
                "quat0",
                Length::Fixed(4),
                D::Absent,
                "",
                "initial orientation (w, x, y, z) (left out: identity)",
            )
            .initial_state(),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::ImplicitMidpoint,
        note: Some("y columns: w1, w2, w3, qw, qx, qy, qz; spin near axis 2 to see the flips"),
        physics: Some(EULER_TOP_PHYSICS),
        presentation: Presentation {
            title: "Euler top",
            symbols: &[],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::InertiaBox,
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = EulerTopParams::from_values(v)?;
            Ok(Box::new(Ode(EulerTop::new(
                v.vector("omega0")?,
                params,
                v.opt_vector("quat0")?,
            )?)))
        },
    };
}
