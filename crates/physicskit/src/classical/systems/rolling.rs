//! Rigid bodies rolling without slipping on a horizontal plane under gravity:
//! [`RollingRattleback`] (a body bounded below by an ellipsoid whose principal inertia axes are
//! turned about the vertical from its geometric axes) and [`RollingDisk`] (a thin uniform disk
//! rolling on its rim).
//!
//! # Equations
//!
//! Every vector is written in the body frame, whose origin is the centre of mass `G`. `gamma`
//! is the upward vertical seen from the body, `r(gamma)` the vector from `G` to the point of
//! the surface touching the plane (where the outward normal is `-gamma`), `I` the inertia
//! tensor about `G`, `m` the mass and `g` gravity. The contact force `F` and the centre of
//! mass velocity `v` obey Newton and Euler,
//!
//! ```text
//! m (v' + omega x v) = F - m g gamma            I omega' + omega x I omega = r x F
//! ```
//!
//! and the material point at the contact has zero velocity (no slip): `v + omega x r = 0`.
//! Differentiating the constraint, `v' = r x omega' + r' x omega`, and eliminating `F`:
//!
//! ```text
//! J omega' = -omega x I omega + m r x (r' x omega + omega x (r x omega)) + m g r x gamma
//! J        = I + m (|r|^2 1 - r r^T)        (the inertia about the contact point)
//! gamma'   = gamma x omega                  (a fixed space vector seen from the body)
//! r'       = (dr/dgamma) gamma'             (the contact point moving over the surface)
//! q'       = (1/2) q ⊗ (0, omega)           (body-frame angular velocity)
//! P'       = R r'                           (the contact point moving over the plane)
//! ```
//!
//! (Kane & Levinson, Int. J. Non-Linear Mech. 17 (1982) 175, eqs. 58–70, in vector form;
//! Borisov & Mamaev, Phys. Usp. 46 (2003) 393.) The contact force does no work (it acts at a
//! point of zero velocity), so the energy
//! `E = m |r x omega|^2 / 2 + omega . I omega / 2 - m g r . gamma` is conserved; the height of
//! `G` above the plane is `-r . gamma`.
//!
//! # The published body and its reversal
//!
//! The default [`RollingRattlebackParams`] are Kane & Levinson's body (Int. J. Non-Linear Mech.
//! 17 (1982) 175: semi-axes 20, 3 and 2 cm, the ellipsoid's centre 1 cm above the centre of mass,
//! 1 kg, inertia `[[2, -0.2, 0], [-0.2, 16, 0], [0, 0, 17]]` kg cm²), and the default start is
//! theirs: roll and pitch 0.5°, at rest but for the spin about the body's vertical (-5 rad/s in
//! their runs, as the public reproductions of the paper, pydy's `reproduceKane1982` and the
//! `RattleBack` package, state it). Because the spin swings with the pitching near the
//! reversal, the reversal time is taken where the spin averaged over 0.1 s (about two pitching
//! periods) changes sign: from that start at -5 rad/s it is 2.7963 s, at +5 rad/s 11.495 s
//! (without dissipation both senses reverse, one four times later). No printed reversal time
//! for this body could be read, so `tests/classical/systems/rolling.rs` checks these times
//! against Kane & Levinson's own equations in their own variables (roll and pitch angles, their
//! inertia tensor, Cramer's rule), integrated apart from this module, to 1e-5 s.
//!
//! # State
//!
//! `[w1, w2, w3, qw, qx, qy, qz, x, y]`: the angular velocity in the **body** frame, the
//! body-to-world orientation quaternion (as [`EulerTop`](super::EulerTop)), and the position
//! `(x, y)` of the contact point on the plane (world frame, `z` up). The centre of mass is at
//! `(x, y, 0) - R r` ([`center_of_mass`](RollingBody::center_of_mass)).
//!
//! # The quaternion's norm
//!
//! The field never renormalizes the state (the integrators own it, and every method must give
//! the same bits natively and in the browser). Instead every evaluation takes the rotation of
//! `q / |q|` (the rotation matrix with `2 / |q|^2`), so the dynamics do not depend on `|q|`
//! at all, and `q' = q ⊗ (0, omega) / 2` keeps `|q|` constant exactly in exact arithmetic:
//! what an integrator lets it drift (measured in `tests/classical/systems/rolling.rs`: below
//! `1e-10` over the reversal runs with `dop853` at `rtol = 1e-10`, `rk4`'s local error
//! otherwise) changes no physical quantity. Front ends that draw the body use
//! [`rotation_matrix`](RollingBody::rotation_matrix), which normalizes too.

use std::f64::consts::FRAC_PI_2;

use crate::classical::core::error::{
    check_finite, check_finite_scalar, check_len, check_non_negative, check_positive, check_vector,
};
use crate::classical::core::trig::sin_cos;
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{forward_jacobian, Scalar};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Bound, Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation, Shape};
use crate::classical::model::erased::{Capabilities, Ode};

/// Length of the state vector.
const DIM: usize = 9;

type V3 = [f64; 3];

// The field is written once, generic over the number type `X`: `f64` for the field itself,
// num-dual's dual numbers for its Jacobian (forward-mode automatic differentiation, exact to
// rounding), which the implicit methods' Newton iteration needs (`field_jacobian`). At `f64`
// every operation is the one the plain code would do, in the same order.

#[inline(always)]
fn cross<X: Scalar>(a: [X; 3], b: [X; 3]) -> [X; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot<X: Scalar>(a: [X; 3], b: [X; 3]) -> X {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn mat_vec<X: Scalar>(m: &[[X; 3]; 3], v: [X; 3]) -> [X; 3] {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// A matrix of constants as numbers of type `X`.
#[inline(always)]
fn lift<X: Scalar>(m: &[[f64; 3]; 3]) -> [[X; 3]; 3] {
    m.map(|row| row.map(X::from))
}

/// Solves `J x = b` for a symmetric positive definite 3x3 `J` by cofactors (no pivoting is
/// needed: `J` is an inertia tensor, its determinant the product of three positive moments).
#[inline(always)]
fn solve3<X: Scalar>(j: &[[X; 3]; 3], b: [X; 3]) -> [X; 3] {
    let c00 = j[1][1] * j[2][2] - j[1][2] * j[2][1];
    let c01 = j[1][2] * j[2][0] - j[1][0] * j[2][2];
    let c02 = j[1][0] * j[2][1] - j[1][1] * j[2][0];
    let c11 = j[0][0] * j[2][2] - j[0][2] * j[2][0];
    let c12 = j[0][1] * j[2][0] - j[0][0] * j[2][1];
    let c22 = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let det = j[0][0] * c00 + j[0][1] * c01 + j[0][2] * c02;
    // The inverse is the transposed cofactor matrix over det; J is symmetric, so c10 = c01,
    // c20 = c02, c21 = c12.
    let inv = det.recip();
    [
        (c00 * b[0] + c01 * b[1] + c02 * b[2]) * inv,
        (c01 * b[0] + c11 * b[1] + c12 * b[2]) * inv,
        (c02 * b[0] + c12 * b[1] + c22 * b[2]) * inv,
    ]
}

fn state_len(state: &[f64]) -> Result<()> {
    check_len("state", state, DIM)
}

/// The body-to-world rotation matrix of the quaternion `state[3..7]`, normalized.
fn rotation<X: Scalar>(state: &[X]) -> Result<[[X; 3]; 3]> {
    let (w, x, y, z) = (state[3], state[4], state[5], state[6]);
    let n2 = w * w + x * x + y * y + z * z;
    let n2_re = n2.re();
    if !(n2_re > 0.0 && n2_re.is_finite()) {
        return Err(Error::invalid(
            "quaternion",
            n2_re.sqrt(),
            "must be non-zero and finite",
        ));
    }
    let (one, k) = (X::from(1.0), X::from(2.0) / n2);
    Ok([
        [
            one - k * (y * y + z * z),
            k * (x * y - w * z),
            k * (x * z + w * y),
        ],
        [
            k * (x * y + w * z),
            one - k * (x * x + z * z),
            k * (y * z - w * x),
        ],
        [
            k * (x * z - w * y),
            k * (y * z + w * x),
            one - k * (x * x + y * y),
        ],
    ])
}

/// A unit quaternion from `quat0` (normalized), or `default` if `None`.
fn initial_quaternion(quat0: Option<&[f64]>, default: [f64; 4]) -> Result<[f64; 4]> {
    match quat0 {
        None => Ok(default),
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
            Ok([q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm])
        }
    }
}

/// The shape under a [`RollingBody`]: where it touches the plane. Implemented by the
/// parameters of each rolling body ([`RollingRattlebackParams`]: an ellipsoid;
/// [`RollingDiskParams`]: a thin disk's rim), which carry its geometry.
pub trait RollingShape: Copy + std::fmt::Debug + PartialEq {
    /// `(r, r')`: the vector from the centre of mass to the contact point, and its rate, both
    /// in the body frame, for the body-frame up vector `gamma` (unit) and its rate
    /// `gamma_dot`; generic over the number type (`f64`, or dual numbers for the Jacobian).
    ///
    /// # Errors
    /// An orientation in which the shape has no single lowest point (a disk lying flat).
    fn contact<X: Scalar>(&self, gamma: [X; 3], gamma_dot: [X; 3]) -> Result<([X; 3], [X; 3])>;
}

/// Mass, gravity and the inertia tensor about the centre of mass, in the body frame.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Body {
    mass: f64,
    g: f64,
    inertia: [[f64; 3]; 3],
}

impl Body {
    /// The rolling equations (module docs) at `state` into `out` (both of length 9).
    #[inline(always)]
    fn derivatives<X: Scalar>(
        &self,
        shape: &impl RollingShape,
        state: &[X],
        out: &mut [X],
    ) -> Result<()> {
        let rot = rotation(state)?;
        let omega = [state[0], state[1], state[2]];
        let gamma = rot[2];
        let gamma_dot = cross(gamma, omega);
        let (r, r_dot) = shape.contact(gamma, gamma_dot)?;
        let m = self.mass;
        let inertia = lift::<X>(&self.inertia);
        let i_omega = mat_vec(&inertia, omega);
        let gyro = cross(omega, i_omega);
        let accel = {
            let a = cross(r_dot, omega);
            let b = cross(omega, cross(r, omega));
            [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
        };
        let contact_torque = cross(r, accel);
        let gravity_torque = cross(r, gamma);
        let rhs =
            [0, 1, 2].map(|i| -gyro[i] + contact_torque[i] * m + gravity_torque[i] * (m * self.g));
        let r2 = dot(r, r);
        let mut j = inertia;
        for (a, row) in j.iter_mut().enumerate() {
            for (b, x) in row.iter_mut().enumerate() {
                let delta = if a == b { r2 } else { X::from(0.0) };
                *x += (delta - r[a] * r[b]) * m;
            }
        }
        let omega_dot = solve3(&j, rhs);
        out[..3].copy_from_slice(&omega_dot);
        let (qw, qx, qy, qz) = (state[3], state[4], state[5], state[6]);
        let [w1, w2, w3] = omega;
        // (1/2) q ⊗ (0, w) = (1/2) (-v.w, qw w + v x w), v = (qx, qy, qz).
        out[3] = (qx * w1 + qy * w2 + qz * w3) * -0.5;
        out[4] = (qw * w1 + qy * w3 - qz * w2) * 0.5;
        out[5] = (qw * w2 + qz * w1 - qx * w3) * 0.5;
        out[6] = (qw * w3 + qx * w2 - qy * w1) * 0.5;
        // The contact point's path on the plane: the world components of r'.
        out[7] = dot(rot[0], r_dot);
        out[8] = dot(rot[1], r_dot);
        Ok(())
    }

    /// Kinetic plus potential energy of a state of length 9 (`NaN` for a bad quaternion or
    /// contact).
    fn energy(&self, shape: &impl RollingShape, state: &[f64]) -> f64 {
        let Ok(rot) = rotation(state) else {
            return f64::NAN;
        };
        let omega = [state[0], state[1], state[2]];
        let gamma = rot[2];
        let Ok((r, _)) = shape.contact(gamma, [0.0; 3]) else {
            return f64::NAN;
        };
        let v = cross(r, omega);
        0.5 * self.mass * dot(v, v) + 0.5 * dot(omega, mat_vec(&self.inertia, omega))
            - self.mass * self.g * dot(r, gamma)
    }

    /// The centre of mass in the world frame: the contact point `(x, y, 0)` minus `R r`.
    fn center_of_mass(&self, shape: &impl RollingShape, state: &[f64]) -> Result<V3> {
        state_len(state)?;
        let rot = rotation(state)?;
        let (r, _) = shape.contact(rot[2], [0.0; 3])?;
        let world = mat_vec(&rot, r);
        Ok([state[7] - world[0], state[8] - world[1], -world[2]])
    }

    /// The vector from the centre of mass to the contact point, in the body frame.
    fn contact_vector(&self, shape: &impl RollingShape, state: &[f64]) -> Result<V3> {
        state_len(state)?;
        let rot = rotation(state)?;
        Ok(shape.contact(rot[2], [0.0; 3])?.0)
    }
}

fn rotation_checked(state: &[f64]) -> Result<[[f64; 3]; 3]> {
    state_len(state)?;
    rotation(state)
}

fn flat(r: [[f64; 3]; 3]) -> [f64; 9] {
    [
        r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
    ]
}

/// The spin about the vertical, `omega . gamma` (rad/s), of `state`.
fn vertical_spin(state: &[f64]) -> Result<f64> {
    let rot = rotation_checked(state)?;
    Ok(dot(rot[2], [state[0], state[1], state[2]]))
}

/// A rigid body rolling without slipping on a horizontal plane (module docs), its contact
/// geometry given by its parameters' [`RollingShape`]: [`RollingRattleback`] and
/// [`RollingDisk`] are its two instances, each with its own constructor.
#[derive(Debug, Clone)]
pub struct RollingBody<S: RollingShape> {
    phase: Phase,
    params: S,
    body: Body,
}

impl<S: RollingShape> RollingBody<S> {
    /// The parameters.
    pub fn params(&self) -> S {
        self.params
    }

    /// The inertia tensor about the centre of mass in the body's geometric axes (kg m²).
    pub fn inertia_tensor(&self) -> [[f64; 3]; 3] {
        self.body.inertia
    }

    /// The body-to-world rotation matrix of `state` (the current state if `None`), from its
    /// normalized quaternion.
    ///
    /// # Errors
    /// A state not of length 9, or a zero or non-finite quaternion.
    pub fn rotation_matrix(&self, state: Option<&[f64]>) -> Result<[[f64; 3]; 3]> {
        rotation_checked(state.unwrap_or(self.phase.state()))
    }

    /// The spin about the vertical, `omega . gamma` (rad/s): what reverses for the
    /// rattleback.
    ///
    /// # Errors
    /// As [`rotation_matrix`](Self::rotation_matrix).
    pub fn vertical_spin(&self, state: Option<&[f64]>) -> Result<f64> {
        vertical_spin(state.unwrap_or(self.phase.state()))
    }

    /// The centre of mass in the world frame (m).
    ///
    /// # Errors
    /// As [`rotation_matrix`](Self::rotation_matrix), or an orientation the shape has no
    /// lowest point in (a disk lying flat).
    pub fn center_of_mass(&self, state: Option<&[f64]>) -> Result<[f64; 3]> {
        self.body
            .center_of_mass(&self.params, state.unwrap_or(self.phase.state()))
    }

    /// The vector from the centre of mass to the contact point, body frame (m).
    ///
    /// # Errors
    /// As [`center_of_mass`](Self::center_of_mass).
    pub fn contact_vector(&self, state: Option<&[f64]>) -> Result<[f64; 3]> {
        self.body
            .contact_vector(&self.params, state.unwrap_or(self.phase.state()))
    }

    /// The rolling equations (module docs), for `impl_ode_dynamics!`.
    #[inline]
    fn field(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        self.body.derivatives(&self.params, state, out)
    }

    /// The Jacobian of [`field`](Self::field) by forward-mode automatic differentiation of the
    /// same code (one pass of dual numbers carrying all nine partial derivatives), for
    /// `impl_ode_dynamics!`: the Newton matrix of the implicit methods, which fixed-point
    /// iteration alone cannot do without here. The pitching of a rattleback rocks at
    /// ~100 rad/s, and the contact point runs over the surface at `a^2/c` (2 m for Kane &
    /// Levinson's body) per radian of tilt, so `d omega'/d q` is ~1e4 s^-2 against `d q'/d
    /// omega` ~ 1/2: the fixed-point corrections of the two blocks trade places from sweep to
    /// sweep instead of shrinking steadily, which the solver takes for a slow contraction.
    fn field_jacobian(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        forward_jacobian::<DIM>(state, out, |x, y| {
            Some(self.body.derivatives(&self.params, x, y))
        })
        .unwrap_or(Ok(()))
    }

    /// Kinetic energy of the rolling body plus `m g` times the height of its centre of mass,
    /// for `impl_ode_dynamics!`.
    fn field_energy(&self, state: &[f64]) -> f64 {
        self.body.energy(&self.params, state)
    }
}

impl_ode_dynamics!(
    impl [S: RollingShape] RollingBody<S>,
    dim = DIM,
    method = Dop853,
    jacobian
);

impl<S: RollingShape> Capabilities for RollingBody<S> {
    fn rotation_matrix(&self, state: &[f64]) -> Option<Result<[f64; 9]>> {
        Some(rotation_checked(state).map(flat))
    }
}

// ---------------------------------------------------------------------------------------
// The rattleback
// ---------------------------------------------------------------------------------------

/// Geometry and mass of a [`RollingRattleback`]. The defaults are Kane & Levinson's body
/// (Int. J. Non-Linear Mech. 17 (1982) 175, the body many later no-slip studies reuse):
/// semi-axes 20, 3 and 2 cm, centre of mass 1 cm below the
/// ellipsoid's centre, 1 kg, and in the geometric axes the inertia tensor
/// `[[A, D, 0], [D, B, 0], [0, 0, C]]` with `A = 2e-4`, `B = 1.6e-3`, `C = 1.7e-3`,
/// `D = -2e-5` kg m², written here as its principal moments and the angle `delta` that turns
/// the principal axes from the geometric ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingRattlebackParams {
    /// Semi-axis along the body's long axis `x` (m).
    pub a: f64,
    /// Semi-axis along `y` (m).
    pub b: f64,
    /// Semi-axis along the vertical `z` (m).
    pub c: f64,
    /// Height of the ellipsoid's centre above the centre of mass (m), `-c < h < c`.
    pub h: f64,
    /// Mass (kg).
    pub m: f64,
    /// Principal moment about the principal axis nearest `x` (kg m²).
    pub i1: f64,
    /// Principal moment about the principal axis nearest `y` (kg m²).
    pub i2: f64,
    /// Principal moment about `z` (kg m²).
    pub i3: f64,
    /// Angle (rad) from the geometric `x` axis to the first principal axis, about `z`.
    pub delta: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

/// Kane & Levinson's principal moments and misalignment: the eigen-decomposition of
/// `[[2e-4, -2e-5], [-2e-5, 1.6e-3]]` (`tests/classical/systems/rolling.rs` rebuilds the
/// tensor from them to 1e-15 relative).
const KL_I1: f64 = 1.997_143_439_995_362_5e-4;
const KL_I2: f64 = 1.600_285_656_000_464e-3;
const KL_DELTA: f64 = 0.014_281_828_919_38;

impl Default for RollingRattlebackParams {
    /// The defaults of [`ROLLING_RATTLEBACK_ENTRY`], where they are written.
    fn default() -> Self {
        ROLLING_RATTLEBACK_ENTRY.defaults(Self::from_values)
    }
}

impl RollingRattlebackParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            a: v.scalar("a")?,
            b: v.scalar("b")?,
            c: v.scalar("c")?,
            h: v.scalar("h")?,
            m: v.scalar("m")?,
            i1: v.scalar("I1")?,
            i2: v.scalar("I2")?,
            i3: v.scalar("I3")?,
            delta: v.scalar("delta")?,
            g: v.scalar("g")?,
        })
    }
}

/// The ellipsoid `x^2/a^2 + y^2/b^2 + (z - h)^2/c^2 = 1` around a centre of mass at the origin
/// (its centre a height `h` above the centre of mass).
impl RollingShape for RollingRattlebackParams {
    #[inline(always)]
    fn contact<X: Scalar>(&self, gamma: [X; 3], gamma_dot: [X; 3]) -> Result<([X; 3], [X; 3])> {
        // The outward normal at p (from the centre) is A^-1 p, A = diag(a^2, b^2, c^2); it is
        // -gamma at p = -A gamma / s, s = sqrt(gamma . A gamma).
        let a = [self.a * self.a, self.b * self.b, self.c * self.c];
        let ag = [gamma[0] * a[0], gamma[1] * a[1], gamma[2] * a[2]];
        let s2 = dot(gamma, ag);
        let s = s2.sqrt();
        let agd = [
            gamma_dot[0] * a[0],
            gamma_dot[1] * a[1],
            gamma_dot[2] * a[2],
        ];
        let k = dot(gamma, agd) / s2;
        let r = [-ag[0] / s, -ag[1] / s, -ag[2] / s + self.h];
        let r_dot = [0, 1, 2].map(|i| -(agd[i] - ag[i] * k) / s);
        Ok((r, r_dot))
    }
}

/// Roll and pitch of the default start, 0.5° each (Kane & Levinson's start).
const START_TILT: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// The orientation turned by `roll` about the world `x` axis after `pitch` about `y`.
fn tilted(roll: f64, pitch: f64) -> [f64; 4] {
    let (sr, cr) = sin_cos(0.5 * roll);
    let (sp, cp) = sin_cos(0.5 * pitch);
    // (cr, sr, 0, 0) ⊗ (cp, 0, sp, 0)
    [cr * cp, sr * cp, cr * sp, sr * sp]
}

/// Checks the principal moments: positive, and no one above the sum of the other two.
fn check_moments(moments: [f64; 3]) -> Result<()> {
    for (name, &x) in ["I1", "I2", "I3"].iter().zip(&moments) {
        check_positive(name, x)?;
    }
    let sum: f64 = moments.iter().sum();
    // `sum - 2 I_i` rounds with an error of a few ulps of `sum`: within that it is a plate.
    let slack = 4.0 * f64::EPSILON * sum;
    for (i, &x) in moments.iter().enumerate() {
        if sum - 2.0 * x < -slack {
            return Err(Error::invalid(
                ["I1", "I2", "I3"][i],
                x,
                "exceeds the sum of the other two principal moments (the triangle \
                 inequality): no rigid body has these moments",
            ));
        }
    }
    Ok(())
}

/// A rattleback (celt, wobblestone) rolling without slipping: the full nonholonomic rigid-body
/// equations (module docs), no reduced model. Its spin about the vertical reverses when it is
/// spun one way, because the misalignment `delta` couples the spin to the pitching and rolling
/// oscillations; spun the other way it keeps its sense (over the times in which the first
/// reverses; without dissipation both senses eventually reverse, as Kondo & Nakanishi, Phys.
/// Rev. E 95 (2017) 062207, recall of the no-slip model).
///
/// # Example
/// ```
/// use physicskit::classical::systems::{RollingRattleback, RollingRattlebackParams};
/// use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
///
/// let params = RollingRattlebackParams::default();
/// let mut body = RollingRattleback::new(&[0.0, 0.0, -3.0], params, None).unwrap();
/// let e0 = body.current_energy();
/// // The rolling constraint does no work: rk4 at this step keeps the energy to ~1e-9.
/// body.integrate((0.0, 0.5), 1e-4, Method::Rk4).unwrap();
/// assert!((body.current_energy() - e0).abs() < 1e-8 * e0.abs());
/// ```
pub type RollingRattleback = RollingBody<RollingRattlebackParams>;

impl RollingRattleback {
    /// A rattleback with body-frame angular velocity `omega0` (rad/s) in orientation `quat0`
    /// (`(w, x, y, z)`, normalized; if `None`, tilted by 0.5° in roll and in pitch), its
    /// contact point at the origin.
    ///
    /// # Errors
    /// Wrong lengths, non-finite values, non-positive semi-axes, mass or moments, moments that
    /// break the triangle inequality, `h` outside `(-c, c)` (the centre of mass outside the
    /// body), negative `g`, or a zero quaternion.
    pub fn new(
        omega0: &[f64],
        params: RollingRattlebackParams,
        quat0: Option<&[f64]>,
    ) -> Result<Self> {
        check_vector("omega0", omega0, 3)?;
        let p = params;
        check_positive("a", p.a)?;
        check_positive("b", p.b)?;
        check_positive("c", p.c)?;
        check_finite_scalar("h", p.h)?;
        if p.h.abs() >= p.c {
            return Err(Error::invalid(
                "h",
                p.h,
                format!(
                    "must lie in (-c, c) = ({}, {}): the centre of mass must be inside the body",
                    -p.c, p.c
                ),
            ));
        }
        check_positive("m", p.m)?;
        check_moments([p.i1, p.i2, p.i3])?;
        check_finite_scalar("delta", p.delta)?;
        check_non_negative("g", p.g)?;
        let (s, c) = sin_cos(p.delta);
        // R_z(delta) diag(I1, I2, I3) R_z(delta)^T in the geometric axes.
        let off = (p.i1 - p.i2) * s * c;
        let inertia = [
            [p.i1 * c * c + p.i2 * s * s, off, 0.0],
            [off, p.i1 * s * s + p.i2 * c * c, 0.0],
            [0.0, 0.0, p.i3],
        ];
        let quat = initial_quaternion(quat0, tilted(START_TILT, START_TILT))?;
        let mut state = omega0.to_vec();
        state.extend_from_slice(&quat);
        state.extend_from_slice(&[0.0, 0.0]);
        Ok(Self {
            phase: Phase::new(state, 0.0)?,
            params,
            body: Body {
                mass: p.m,
                g: p.g,
                inertia,
            },
        })
    }
}

/// The averaging window of [`averaged_spin`] and [`spin_reversal_time`] for the default
/// [`RollingRattlebackParams`] (s): about two periods of that body's pitching (about 109 rad/s
/// at small amplitude, a period of 0.058 s), so the mean takes out the swing the pitching gives
/// the spin.
pub const SPIN_REVERSAL_WINDOW: f64 = 0.1;

/// A spin history `spin` sampled at the uniformly spaced times `t` (such as
/// [`vertical_spin`](RollingBody::vertical_spin) along a run) averaged over a sliding window
/// of `window` seconds, rounded to a whole number `m` of samples: the mean over `[t_k, t_(k +
/// m)]`, the heading turned (the trapezoidal integral of the spin) over the window's width,
/// placed at the window's centre. Returns the centres and the means.
///
/// # Errors
/// [`Error::DimensionMismatch`] if `t` and `spin` differ in length; [`Error::NonFinite`] for a
/// non-finite time or spin; [`Error::InvalidParameter`] for fewer than two samples, times not
/// increasing by one spacing (to 1e-6 of it), or a window that is not finite, is shorter than
/// the spacing or longer than the record.
pub fn averaged_spin(t: &[f64], spin: &[f64], window: f64) -> Result<(Vec<f64>, Vec<f64>)> {
    check_len("spin", spin, t.len())?;
    check_finite("t", t, 0.0)?;
    check_finite("spin", spin, 0.0)?;
    let n = t.len();
    if n < 2 {
        return Err(Error::invalid(
            "t",
            n as f64,
            "needs at least two samples to average the spin",
        ));
    }
    let dt = (t[n - 1] - t[0]) / (n - 1) as f64;
    // Sampled times are `t0 + k dt` rounded: far within 1e-6 of the spacing.
    let uneven = |k: usize| t[k] <= t[k - 1] || (t[k] - t[k - 1] - dt).abs() > 1e-6 * dt;
    if let Some(k) = (1..n).find(|&k| uneven(k)) {
        return Err(Error::invalid(
            "t",
            t[k],
            format!("times must increase by one spacing ({dt}), as a run's samples do"),
        ));
    }
    check_positive("window", window)?;
    let m = (window / dt).round();
    if m < 1.0 || m >= n as f64 {
        return Err(Error::invalid(
            "window",
            window,
            format!(
                "must span at least one sample spacing ({dt} s) and less than the record ({} s)",
                t[n - 1] - t[0]
            ),
        ));
    }
    let m = m as usize;
    let mut heading = Vec::with_capacity(n);
    heading.push(0.0);
    for pair in spin.windows(2) {
        let last = heading[heading.len() - 1];
        heading.push(last + 0.5 * (pair[0] + pair[1]) * dt);
    }
    let width = m as f64 * dt;
    let centres = t[..n - m].iter().map(|tk| tk + 0.5 * width).collect();
    let means = (0..n - m)
        .map(|k| (heading[k + m] - heading[k]) / width)
        .collect();
    Ok((centres, means))
}

/// The reversal time of a spin history: the first zero of the spin averaged over `window`
/// ([`averaged_spin`]; [`SPIN_REVERSAL_WINDOW`] for the default body), by linear interpolation
/// between the windows' centres; `None` if the averaged spin never changes sign.
///
/// The raw spin swings with the pitching near the reversal and can touch zero briefly before
/// it turns for good (for Kane & Levinson's body spun at -5 rad/s, a root-finder on the raw
/// spin stops at 2.685 s and a 1 ms grid first sees a sign change at 2.761 s, while the
/// averaged spin turns at 2.796 s), so only the averaged spin, the spin of the averaged
/// theories, has one well-conditioned zero.
///
/// # Example
/// ```
/// use std::f64::consts::PI;
/// use physicskit::classical::systems::spin_reversal_time;
///
/// let t: Vec<f64> = (0..=1000).map(|k| k as f64 * 1e-3).collect();
/// // Turning at 0.5 s, with a swing of period 0.05 s that takes it through zero from 0.2 s on.
/// let spin: Vec<f64> = t.iter().map(|&s| 0.5 - s + 0.3 * (40.0 * PI * s).sin()).collect();
/// assert!(spin.iter().position(|&w| w < 0.0).unwrap() < 300);
/// let t_rev = spin_reversal_time(&t, &spin, 0.1).unwrap().unwrap();
/// // Two whole periods a window: the swing averages out, the zero is the trend's.
/// assert!((t_rev - 0.5).abs() < 1e-9);
/// ```
///
/// # Errors
/// As [`averaged_spin`].
pub fn spin_reversal_time(t: &[f64], spin: &[f64], window: f64) -> Result<Option<f64>> {
    let (centres, means) = averaged_spin(t, spin, window)?;
    Ok((1..means.len())
        .find(|&k| {
            let (before, after) = (means[k - 1], means[k]);
            before != 0.0 && (after == 0.0 || (before < 0.0) != (after < 0.0))
        })
        .map(|k| {
            let (before, after) = (means[k - 1], means[k]);
            centres[k - 1] + (centres[k] - centres[k - 1]) * before / (before - after)
        }))
}

// ---------------------------------------------------------------------------------------
// The disk
// ---------------------------------------------------------------------------------------

/// A thin disk's rim, radius `a`, around its centre (the centre of mass), normal `z`.
impl RollingShape for RollingDiskParams {
    #[inline(always)]
    fn contact<X: Scalar>(&self, gamma: [X; 3], gamma_dot: [X; 3]) -> Result<([X; 3], [X; 3])> {
        // The lowest rim point: -a times the unit projection u of gamma onto the disk's plane.
        let n2 = gamma[0] * gamma[0] + gamma[1] * gamma[1];
        if n2.re().is_nan() || n2.re() <= 0.0 {
            return Err(Error::Unsupported {
                operation: "rolling".into(),
                reason: "the disk lies flat on the plane: its rim has no lowest point".into(),
            });
        }
        let n = n2.sqrt();
        let u = [gamma[0] / n, gamma[1] / n];
        let along = u[0] * gamma_dot[0] + u[1] * gamma_dot[1];
        let r = [u[0] * -self.a, u[1] * -self.a, X::from(0.0)];
        let r_dot = [
            (gamma_dot[0] - u[0] * along) * -self.a / n,
            (gamma_dot[1] - u[1] * along) * -self.a / n,
            X::from(0.0),
        ];
        Ok((r, r_dot))
    }
}

/// Radius and mass of a [`RollingDisk`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingDiskParams {
    /// Radius (m).
    pub a: f64,
    /// Mass (kg).
    pub m: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

impl Default for RollingDiskParams {
    /// A coin-sized disk (the motion does not depend on the mass): the defaults of
    /// [`ROLLING_DISK_ENTRY`], where they are written.
    fn default() -> Self {
        ROLLING_DISK_ENTRY.defaults(disk_params)
    }
}

/// A thin uniform disk rolling without slipping on its rim (Euler's disk with no dissipation):
/// moments `m a^2 / 4` about a diameter and `m a^2 / 2` about the normal (body `z`).
///
/// Its steady motions (Routh, *Advanced Rigid Dynamics* (1905) §244; O'Reilly, Nonlinear
/// Dynamics 10 (1996) 287): tilted at `theta` from the table and precessing at `Omega` about
/// the vertical, it rolls steadily when its spin about the normal is
/// `w3 = cos(theta) (I1 Omega^2 sin(theta) - m g a) / ((I3 + m a^2) Omega sin(theta))`
/// ([`RollingDisk::steady`], derived in `tests/classical/systems/rolling.rs`), its centre on a
/// circle of radius `a w3 / Omega`.
pub type RollingDisk = RollingBody<RollingDiskParams>;

/// Tilt of the default start: 1 rad between the disk and the table.
const DISK_TILT: f64 = 1.0;

fn check_disk(params: RollingDiskParams) -> Result<Body> {
    let a = check_positive("a", params.a)?;
    let m = check_positive("m", params.m)?;
    let g = check_non_negative("g", params.g)?;
    let i1 = 0.25 * m * a * a;
    Ok(Body {
        mass: m,
        g,
        inertia: [[i1, 0.0, 0.0], [0.0, i1, 0.0], [0.0, 0.0, 2.0 * i1]],
    })
}

impl RollingDisk {
    /// A disk with body-frame angular velocity `omega0` (rad/s) in orientation `quat0`
    /// (normalized; if `None`, its normal turned by 1 rad from the vertical about the world
    /// `y` axis), its contact point at the origin.
    ///
    /// # Errors
    /// Wrong lengths, non-finite values, non-positive radius or mass, negative `g`, a zero
    /// quaternion, or an orientation in which the disk lies flat.
    pub fn new(omega0: &[f64], params: RollingDiskParams, quat0: Option<&[f64]>) -> Result<Self> {
        check_vector("omega0", omega0, 3)?;
        let body = check_disk(params)?;
        let (s, c) = sin_cos(0.5 * DISK_TILT);
        let quat = initial_quaternion(quat0, [c, 0.0, s, 0.0])?;
        let mut state = omega0.to_vec();
        state.extend_from_slice(&quat);
        state.extend_from_slice(&[0.0, 0.0]);
        let rot = rotation(&state)?;
        if rot[2][2].abs() >= 1.0 - 1e-12 {
            return Err(Error::invalid(
                "quat0",
                rot[2][2],
                "lays the disk flat (its normal vertical): it would not roll on its rim",
            ));
        }
        Ok(Self {
            phase: Phase::new(state, 0.0)?,
            params,
            body,
        })
    }

    /// The disk rolling steadily: tilted at `theta` (rad, in `(0, pi/2]`) from the table, its
    /// normal precessing about the vertical at `precession` (rad/s, non-zero), with the spin
    /// of the closed form (type docs). The normal starts in the world `x`–`z` plane, the
    /// contact point at the origin.
    ///
    /// # Errors
    /// As [`new`](Self::new), `theta` outside `(0, pi/2]` or a zero or non-finite
    /// `precession`.
    pub fn steady(params: RollingDiskParams, theta: f64, precession: f64) -> Result<Self> {
        let body = check_disk(params)?;
        if !(theta > 0.0 && theta <= FRAC_PI_2) {
            return Err(Error::invalid(
                "theta",
                theta,
                "must be > 0 and <= pi/2 (the angle between the disk and the table)",
            ));
        }
        check_finite_scalar("precession", precession)?;
        if precession == 0.0 {
            return Err(Error::invalid(
                "precession",
                precession,
                "must be non-zero (a disk rolling straight does not precess)",
            ));
        }
        let (st, ct) = sin_cos(theta);
        let (m, a, g) = (params.m, params.a, body.g);
        let (i1, i3) = (body.inertia[0][0], body.inertia[2][2]);
        let w3 = ct * (i1 * precession * precession * st - m * g * a)
            / ((i3 + m * a * a) * precession * st);
        // Normal e3 = R_y(theta) z; omega = precession z + s e3 has body components
        // (-precession sin(theta), 0, w3).
        let omega0 = [-precession * st, 0.0, w3];
        let (sh, ch) = sin_cos(0.5 * theta);
        Self::new(&omega0, params, Some(&[ch, 0.0, sh, 0.0]))
    }
}

// ---------------------------------------------------------------------------------------
// Catalogue
// ---------------------------------------------------------------------------------------

/// `> 0` and `<= pi/2`.
const TILT_RANGE: Range = Range {
    min: Bound::Exclusive(0.0),
    max: Bound::Inclusive(FRAC_PI_2),
};

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const ROLLING_RATTLEBACK_PHYSICS: &str =
    "A rigid body bounded by an ellipsoid, rolling without slipping on a horizontal plane \
    under gravity, its principal axes of inertia turned about the vertical from the \
    ellipsoid's axes: the celt or rattleback. The no-slip constraint eliminates the \
    contact force from the Newton–Euler equations; that force does no work, so the energy \
    is conserved and nothing is dissipated. The turned axes couple spin to rocking: spun \
    one way the body starts to rock, stops spinning and spins back the other way, while \
    spun the other way it keeps its spin far longer. The state is the angular velocity in \
    the body frame, the orientation as a unit quaternion and the contact point on the \
    plane.";

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const ROLLING_DISK_PHYSICS: &str =
    "A thin uniform disk rolling without slipping on its rim on a horizontal plane under \
    gravity, from the Newton–Euler equations with the contact force eliminated by the \
    no-slip constraint, so the energy is conserved. Tilted and rolling steadily, it runs \
    round a circle whose radius and precession rate satisfy the steady-motion condition of \
    the rolling disk; spinning about a vertical axis through its centre, at the precession \
    rate Ω² = 4g/(a sin θ), its centre stays still (Moffatt's spinning coin). The \
    ever-faster spin-down of Euler's disk needs dissipation, which this model leaves out.";

catalogue_static! {
    /// The catalogue entry of [`RollingRattleback`].
    pub static ROLLING_RATTLEBACK_ENTRY: SystemEntry = SystemEntry {
        name: "rolling-rattleback",
        python: Some("RollingRattleback"),
        summary: "rattleback rolling without slipping: the nonholonomic rigid-body equations of an \
                  ellipsoid whose inertia axes are turned from its geometric axes",
        family: Family::Ode,
        params: &[
            P::vector(
                "omega0",
                Length::Fixed(3),
                D::demo_vector(&[0.0, 0.0, -3.0]),
                "rad/s",
                "initial angular velocity, body frame (z: the spin about the body's vertical)",
            )
            .initial_state(),
            P::scalar(
                "a",
                D::scalar(0.2),
                "m",
                Range::POSITIVE,
                "semi-axis along the body's long axis x",
            ),
            P::scalar(
                "b",
                D::scalar(0.03),
                "m",
                Range::POSITIVE,
                "semi-axis along y",
            ),
            P::scalar(
                "c",
                D::scalar(0.02),
                "m",
                Range::POSITIVE,
                "semi-axis along the vertical z",
            ),
            P::scalar(
                "h",
                D::scalar(0.01),
                "m",
                Range::ANY,
                "height of the ellipsoid's centre above the centre of mass (between -c and c)",
            ),
            P::scalar("m", D::scalar(1.0), "kg", Range::POSITIVE, "mass"),
            P::scalar(
                "I1",
                D::scalar(KL_I1),
                "kg m^2",
                Range::POSITIVE,
                "principal moment about the axis turned by delta from x",
            ),
            P::scalar(
                "I2",
                D::scalar(KL_I2),
                "kg m^2",
                Range::POSITIVE,
                "principal moment about the axis turned by delta from y",
            ),
            P::scalar(
                "I3",
                D::scalar(1.7e-3),
                "kg m^2",
                Range::POSITIVE,
                "principal moment about z",
            ),
            P::scalar(
                "delta",
                D::scalar(KL_DELTA),
                "rad",
                Range::ANY,
                "angle about z from the geometric axes to the principal inertia axes",
            ),
            P::scalar(
                "g",
                D::scalar(9.81),
                "m/s^2",
                Range::NON_NEGATIVE,
                "gravitational acceleration",
            ),
            P::vector(
                "quat0",
                Length::Fixed(4),
                D::Absent,
                "",
                "initial orientation (w, x, y, z) (left out: tilted 0.5 degrees in roll and pitch)",
            )
            .initial_state(),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::Dop853,
        note: Some(
            "y columns: w1, w2, w3 (body), qw, qx, qy, qz, contact x, y; defaults: Kane & \
             Levinson's body; spin -3 reverses, +3 does not",
        ),
        physics: Some(ROLLING_RATTLEBACK_PHYSICS),
        presentation: Presentation {
            title: "Rolling rattleback",
            symbols: &[],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Rolling {
                shape: Shape::Ellipsoid,
            },
            pace: Pace::Fixed {
                method: Method::Rk4,
                dt: 1e-4,
                steps_per_frame: 167,
                energy_error: 1e-8,
            },
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = RollingRattlebackParams::from_values(v)?;
            Ok(Box::new(Ode(RollingRattleback::new(
                v.vector("omega0")?,
                params,
                v.opt_vector("quat0")?,
            )?)))
        },
    };
}

const DISK_PARAMS: [P; 3] = [
    P::scalar("a", D::scalar(0.05), "m", Range::POSITIVE, "radius"),
    P::scalar(
        "m",
        D::scalar(1.0),
        "kg",
        Range::POSITIVE,
        "mass (the motion does not depend on it)",
    ),
    P::scalar(
        "g",
        D::scalar(9.81),
        "m/s^2",
        Range::NON_NEGATIVE,
        "gravitational acceleration",
    ),
];

/// The disk's parameters as either rolling-disk entry's values hold them.
fn disk_params(v: &Values) -> Result<RollingDiskParams> {
    Ok(RollingDiskParams {
        a: v.scalar("a")?,
        m: v.scalar("m")?,
        g: v.scalar("g")?,
    })
}

/// How both rolling-disk entries are shown (the second with its own title).
const DISK_PRESENTATION: Presentation = Presentation {
    title: "Rolling disk",
    symbols: &[],
    time_unit: "s",
    state_units: None,
    drawing: Drawing::Rolling { shape: Shape::Disk },
    // rk4 at 1 ms, 17 steps a frame (real time at 60 frames a second): dop853, the disks'
    // default, takes adaptive steps, which do not pace a frame.
    pace: Pace::Fixed {
        method: Method::Rk4,
        dt: 1e-3,
        steps_per_frame: 17,
        energy_error: 1e-8,
    },
    section_first: false,
    energy_conserved: true,
};

catalogue_static! {
    /// The catalogue entry of [`RollingDisk`].
    pub static ROLLING_DISK_ENTRY: SystemEntry = SystemEntry {
        name: "rolling-disk",
        python: Some("RollingDisk"),
        summary: "thin uniform disk rolling without slipping on its rim (Euler's disk without \
                  dissipation)",
        family: Family::Ode,
        params: &[
            P::vector(
                "omega0",
                Length::Fixed(3),
                D::demo_vector(&[-4.0, 0.0, -15.0]),
                "rad/s",
                "initial angular velocity, body frame (z: about the disk's normal)",
            )
            .initial_state(),
            DISK_PARAMS[0],
            DISK_PARAMS[1],
            DISK_PARAMS[2],
            P::vector(
                "quat0",
                Length::Fixed(4),
                D::Absent,
                "",
                "initial orientation (w, x, y, z) (left out: the disk 1 rad from the table)",
            )
            .initial_state(),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::Dop853,
        note: Some("y columns: w1, w2, w3 (body), qw, qx, qy, qz, contact x, y"),
        physics: Some(ROLLING_DISK_PHYSICS),
        presentation: DISK_PRESENTATION,
        build: |v| {
            Ok(Box::new(Ode(RollingDisk::new(
                v.vector("omega0")?,
                disk_params(v)?,
                v.opt_vector("quat0")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`RollingDisk::steady`].
    pub static ROLLING_DISK_STEADY_ENTRY: SystemEntry = SystemEntry {
        name: "rolling-disk-steady",
        python: Some("RollingDisk.steady"),
        summary: "thin disk started on a steady rolling circle (tilt and precession rate; the spin \
                  from the closed form)",
        family: Family::Ode,
        params: &[
            P::scalar(
                "theta",
                D::demo_scalar(1.0),
                "rad",
                TILT_RANGE,
                "angle between the disk and the table (pi/2: upright)",
            ),
            P::scalar(
                "precession",
                D::demo_scalar(5.0),
                "rad/s",
                Range::ANY,
                "rate at which the disk's normal turns about the vertical (non-zero)",
            ),
            DISK_PARAMS[0],
            DISK_PARAMS[1],
            DISK_PARAMS[2],
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::Dop853,
        note: Some("y columns: w1, w2, w3 (body), qw, qx, qy, qz, contact x, y"),
        physics: Some(ROLLING_DISK_PHYSICS),
        presentation: Presentation {
            title: "Rolling disk (steady circle)",
            ..DISK_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Ode(RollingDisk::steady(
                disk_params(v)?,
                v.scalar("theta")?,
                v.scalar("precession")?,
            )?)))
        },
    };
}
