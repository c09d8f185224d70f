//! [`DoublePendulum`]: two point masses on massless rods in a vertical plane.
//!
//! Coordinates `q = (theta1, theta2)`, angles from the downward vertical. The Lagrangian
//! (Goldstein, *Classical Mechanics*, 3rd ed., §1.6; Taylor, *Classical Mechanics* (2005),
//! §11.4) is
//!
//! ```text
//! L = (m1 + m2) l1^2 theta1'^2 / 2 + m2 l2^2 theta2'^2 / 2
//!     + m2 l1 l2 theta1' theta2' cos(theta1 - theta2)
//!     + (m1 + m2) g l1 cos(theta1) + m2 g l2 cos(theta2)
//! ```
//!
//! The mass matrix depends on `theta1 - theta2`, so the Hamiltonian is not separable:
//! `implicit_midpoint` (default) is the symplectic choice, `rk4` integrates `(q, qdot)`.
//!
//! # Closed forms
//!
//! The [`LagrangianEngine`] can derive everything from `L` by automatic differentiation; the
//! integrators use these hand-derived forms instead (checked against it in
//! `tests/classical/lagrangian/closed_forms.rs`). With `D = theta1 - theta2`, `w = qdot` and the
//! constants `a = (m1 + m2) l1^2`, `b = m2 l1 l2`, `d = m2 l2^2`, `g1 = (m1 + m2) g l1`,
//! `g2 = m2 g l2`, so that `L = a w1^2/2 + d w2^2/2 + b w1 w2 cos D + g1 cos theta1 +
//! g2 cos theta2`:
//!
//! ```text
//! mass matrix   M = [[a, b cos D], [b cos D, d]],   det M = a d - b^2 cos^2 D >= m1 m2 l1^2 l2^2
//! momentum      p = M w
//! velocity      w = M^-1 p = [d p1 - b cos D p2, a p2 - b cos D p1] / det M
//! force         dL/dtheta1 = -b w1 w2 sin D - g1 sin theta1
//!               dL/dtheta2 =  b w1 w2 sin D - g2 sin theta2
//! energy        E = a w1^2/2 + d w2^2/2 + b w1 w2 cos D - g1 cos theta1 - g2 cos theta2
//! ```
//!
//! Euler–Lagrange: `d/dt p1 = a w1' + b cos D w2' - b sin D (w1 - w2) w2` equals `dL/dtheta1`,
//! and likewise for `p2`, so the `w1 w2 sin D` terms cancel and
//!
//! ```text
//! M qddot = f,   f1 = -b w2^2 sin D - g1 sin theta1,   f2 = b w1^2 sin D - g2 sin theta2
//! ```
//!
//! (Taylor §11.4, eqs. 11.41–11.42, multiplied through by `l1` and `l2`), solved by Cramer's
//! rule like the velocity. In the force, acceleration, canonical field and energy, `sin D`
//! and `cos D` come from `sin`/`cos` of the two angles (one two-lane
//! [`sin_cos_array`](crate::classical::core::trig::sin_cos_array)) by the angle-difference
//! identities, at an absolute (not relative) rounding of ~1 ulp in `sin D`, which enters only
//! multiplied by `O(1)` terms. The acceleration and the canonical field are written once,
//! generic over the number type: at `f64` they are the integrators' right-hand sides, on dual
//! numbers they give their exact Jacobians (`lagrangian/forward.rs`).
//!
//! # Which starts can flip an arm
//!
//! An arm flips when its angle passes `±pi` (its bob over the top of its pivot). The kinetic
//! energy is never negative (`M` is positive definite), so a motion of energy `E` stays where
//! `V(theta1, theta2) = -g1 cos theta1 - g2 cos theta2 <= E`. On the line `theta1 = pi`,
//! `V = g1 - g2 cos theta2`, lowest at `g1 - |g2|`; on `theta2 = pi`, `V = g2 - g1 cos
//! theta1`, lowest at `g2 - |g1|`. The flip energy
//!
//! ```text
//! E_flip = min(g1 - |g2|, g2 - |g1|)      (= -|g1 - g2| for g >= 0)
//! ```
//!
//! is the lowest energy of any state with an arm upside down. A motion with `E < E_flip` can
//! never flip; at `E = E_flip` it could reach an inverted arm only at rest at the saddle,
//! an equilibrium, which it approaches without reaching. So `E > E_flip` is necessary for a
//! flip (not sufficient: many such starts stay on regular tori). For `g > 0` the cheaper flip
//! costs `E_flip - (-(g1 + g2)) = 2 min(g1, g2)` above the hanging rest: `2 m2 g l2` lifts the
//! lower bob over the top of the upper one with the upper arm hanging, `2 (m1 + m2) g l1` lifts
//! the upper bob over the pivot with the lower arm hanging from it. Released from rest at
//! `(theta1, theta2)` with equal masses and arms the condition reads `2 cos theta1 + cos theta2
//! < 1` (Heyl's `3 cos theta1 + cos theta2 < 2`, *The double pendulum fractal*, 2008, is for
//! uniform rods, whose moments differ).

use crate::classical::core::error::check_finite_scalar;
use crate::classical::core::error::check_positive;
use crate::classical::core::linalg::negligible_pivot;
use crate::classical::core::trig::sin_cos;
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{
    singular_mass_matrix, FieldScalar, Lagrangian, LagrangianEngine, Scalar,
};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Lagrangian as Erased};
use crate::classical::systems::rod_chain::rod_chain_positions;

/// Masses, rod lengths and gravity of a [`DoublePendulum`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulumParams {
    /// Mass of the upper bob.
    pub m1: f64,
    /// Mass of the lower bob.
    pub m2: f64,
    /// Length of the upper rod.
    pub l1: f64,
    /// Length of the lower rod.
    pub l2: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for DoublePendulumParams {
    /// The defaults of [`DOUBLE_PENDULUM_ENTRY`], where they are written.
    fn default() -> Self {
        DOUBLE_PENDULUM_ENTRY.defaults(Self::from_values)
    }
}

impl DoublePendulumParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            m1: v.scalar("m1")?,
            m2: v.scalar("m2")?,
            l1: v.scalar("l1")?,
            l2: v.scalar("l2")?,
            g: v.scalar("g")?,
        })
    }
}

impl DoublePendulumParams {
    fn validate(self) -> Result<Self> {
        check_positive("m1", self.m1)?;
        check_positive("m2", self.m2)?;
        check_positive("l1", self.l1)?;
        check_positive("l2", self.l2)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// The off-diagonal mass-matrix entry `e = b cos(theta1 - theta2)`, from one reduction of
    /// the difference (the mass matrix, the momenta and the velocity; the canonical field and
    /// the acceleration take `cos D` from [`angles`], which they need anyway).
    #[inline(always)]
    fn coupling(&self, q: &[f64]) -> f64 {
        self.coefficients()[1] * sin_cos(q[0] - q[1]).1
    }

    /// The flip energy `E_flip = min(g1 - |g2|, g2 - |g1|)` (J): the lowest energy of a state
    /// with an arm upside down (`theta1 = pi` or `theta2 = pi`), in the energy of
    /// [`DoublePendulum`] (zero with both bobs at the pivot's height). A motion with energy at
    /// or below it never flips an arm (derivation in the module documentation).
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::systems::DoublePendulumParams;
    ///
    /// // Unit masses and arms (g1 = 2g, g2 = g): lifting the lower bob over the upper one
    /// // costs 2 m2 g l2 = 2g above the hanging rest at -3g.
    /// let p = DoublePendulumParams::default();
    /// assert_eq!(p.flip_energy(), -p.g);
    /// ```
    pub fn flip_energy(&self) -> f64 {
        let [.., g1, g2] = self.coefficients();
        (g1 - g2.abs()).min(g2 - g1.abs())
    }

    /// Whether the pendulum released from rest at `(theta1, theta2)` has more than the
    /// [`flip_energy`](Self::flip_energy), the energy an arm needs to swing over the top.
    /// `false` means no arm can ever flip; `true` only that energy does not forbid it. The
    /// energy at rest is the system's own (`-g1 cos theta1 - g2 cos theta2`, the same bits as
    /// [`DoublePendulum`]'s energy at zero velocity).
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::systems::DoublePendulumParams;
    ///
    /// let p = DoublePendulumParams::default();
    /// // Equal masses and arms: a flip needs 2 cos(theta1) + cos(theta2) < 1.
    /// assert!(!p.can_flip_from_rest(1.0, 1.0)); // 2 cos 1 + cos 1 = 1.62
    /// assert!(p.can_flip_from_rest(1.5, 2.0)); // 0.14 - 0.42 < 1
    /// ```
    pub fn can_flip_from_rest(&self, theta1: f64, theta2: f64) -> bool {
        let [.., g1, g2] = self.coefficients();
        let [_, c1, _, c2, ..] = angles(&[theta1, theta2]);
        -g1 * c1 - g2 * c2 > self.flip_energy()
    }

    /// `[a, b, d, g1, g2]` of the closed forms (module documentation).
    #[inline(always)]
    fn coefficients(&self) -> [f64; 5] {
        let Self { m1, m2, l1, l2, g } = *self;
        [
            (m1 + m2) * l1 * l1,
            m2 * l1 * l2,
            m2 * l2 * l2,
            (m1 + m2) * g * l1,
            m2 * g * l2,
        ]
    }
}

/// `sin`, `cos` of both angles and of their difference `D`: `[s1, c1, s2, c2, sin D, cos D]`.
#[inline(always)]
fn angles<X: FieldScalar>(q: &[X]) -> [X; 6] {
    let ([s1, s2], [c1, c2]) = X::sin_cos_kernel_array([q[0], q[1]]);
    [s1, c1, s2, c2, s1 * c2 - c1 * s2, c1 * c2 + s1 * s2]
}

/// `dL/dq` at angular velocities `w`, from [`DoublePendulumParams::coefficients`] and
/// [`angles`].
#[inline(always)]
fn force<X: FieldScalar>(coefficients: &[f64; 5], angles: &[X; 6], w: &[X]) -> [X; 2] {
    let [_, b, _, g1, g2] = *coefficients;
    let [s1, _, s2, _, sd, _] = *angles;
    let k = w[0] * b * w[1] * sd;
    [-k - s1 * g1, k - s2 * g2]
}

/// Solves `[[a, e], [e, d]] x = r` by Cramer's rule, or the singular-matrix error where
/// partial-pivoting LU would find a negligible pivot (first pivot `max(|a|, |e|)`, second
/// `det / max(|a|, |e|)`).
#[inline(always)]
fn solve_2x2<X: FieldScalar>(a: f64, e: X, d: f64, r: [X; 2], t: f64) -> Result<[X; 2]> {
    let det = X::from(a * d) - e * e;
    let first = a.abs().max(e.re().abs());
    let scale = first.max(d.abs());
    if negligible_pivot(first, scale) || negligible_pivot(det.re(), scale * first) {
        return Err(singular_mass_matrix(t));
    }
    let inv = det.recip();
    Ok([(r[0] * d - e * r[1]) * inv, (r[1] * a - e * r[0]) * inv])
}

impl Lagrangian for DoublePendulumParams {
    fn ndof(&self) -> usize {
        2
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let Self { m1, m2, l1, l2, g } = *self;
        let (w1, w2) = (qdot[0], qdot[1]);
        let kinetic = w1 * w1 * (0.5 * (m1 + m2) * l1 * l1)
            + w2 * w2 * (0.5 * m2 * l2 * l2)
            + w1 * w2 * (q[0] - q[1]).cos() * (m2 * l1 * l2);
        let potential = q[0].cos() * (-(m1 + m2) * g * l1) - q[1].cos() * (m2 * g * l2);
        kinetic - potential
    }

    #[inline]
    fn closed_mass_matrix(&self, q: &[f64], _qdot: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let [a, _, d, ..] = self.coefficients();
        let e = self.coupling(q);
        out.copy_from_slice(&[a, e, e, d]);
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, q: &[f64], w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let [a, _, d, ..] = self.coefficients();
        let e = self.coupling(q);
        out[0] = a * w[0] + e * w[1];
        out[1] = e * w[0] + d * w[1];
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
        out.copy_from_slice(&force(&self.coefficients(), &angles(q), w));
        Some(())
    }

    #[inline]
    fn closed_energy(&self, q: &[f64], w: &[f64], _t: f64) -> Option<f64> {
        let [a, b, d, g1, g2] = self.coefficients();
        let [_, c1, _, c2, _, cd] = angles(q);
        let kinetic = 0.5 * (a * w[0] * w[0] + d * w[1] * w[1]) + b * cd * w[0] * w[1];
        Some(kinetic - g1 * c1 - g2 * c2)
    }

    #[inline]
    fn closed_velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let [a, _, d, ..] = self.coefficients();
        let e = self.coupling(q);
        Some(solve_2x2(a, e, d, [p[0], p[1]], t).map(|w| out.copy_from_slice(&w)))
    }

    #[inline(always)]
    fn closed_acceleration_in<X: FieldScalar>(
        &self,
        q: &[X],
        w: &[X],
        t: f64,
        out: &mut [X],
    ) -> Option<Result<()>> {
        let [a, b, d, g1, g2] = self.coefficients();
        let [s1, _, s2, _, sd, cd] = angles(q);
        let f = [
            w[1] * -b * w[1] * sd - s1 * g1,
            w[0] * b * w[0] * sd - s2 * g2,
        ];
        Some(solve_2x2(a, cd * b, d, f, t).map(|x| out.copy_from_slice(&x)))
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
        let coefficients = self.coefficients();
        let [a, b, d, ..] = coefficients;
        let angles = angles(q);
        Some(solve_2x2(a, angles[5] * b, d, [p[0], p[1]], t).map(|w| {
            qdot.copy_from_slice(&w);
            pdot.copy_from_slice(&force(&coefficients, &angles, &w));
        }))
    }
}

/// The planar double pendulum (the spec's `DoublePendulum`). State `[theta1, theta2,
/// theta1dot, theta2dot]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
/// use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
///
/// let mut dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], DoublePendulumParams::default())
///     .unwrap();
/// let e0 = dp.current_energy();
/// dp.integrate((0.0, 1.0), 1e-3, Method::ImplicitMidpoint).unwrap();
/// assert!((dp.current_energy() - e0).abs() < 1e-5 * e0.abs());
/// ```
#[derive(Debug, Clone)]
pub struct DoublePendulum {
    phase: Phase,
    engine: LagrangianEngine<DoublePendulumParams>,
}

impl DoublePendulum {
    /// A double pendulum at angles `theta0` with angular velocities `thetadot0` (both length
    /// 2).
    ///
    /// # Errors
    /// Lengths other than 2, non-finite values, non-positive masses or lengths, non-finite `g`.
    pub fn new(theta0: &[f64], thetadot0: &[f64], params: DoublePendulumParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(theta0, thetadot0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &DoublePendulumParams {
        self.engine.lagrangian()
    }

    /// Cartesian bob positions `[x1, y1, x2, y2]` for angles `q` (the current angles if
    /// `None`): pivot at the origin, `y` up, so a hanging bob has negative `y`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` has
    /// length 2.
    pub fn positions(&self, q: Option<&[f64]>) -> Result<[f64; 4]> {
        let q = q.unwrap_or(&self.phase.state()[..2]);
        if q.len() != 2 {
            return Err(Error::DimensionMismatch {
                name: "q".into(),
                expected: 2,
                found: q.len(),
            });
        }
        let DoublePendulumParams { l1, l2, .. } = *self.params();
        let mut out = [0.0; 4];
        rod_chain_positions(q, &[l1, l2], &mut out);
        Ok(out)
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<DoublePendulumParams> {
        &self.engine
    }
}

crate::impl_lagrangian_dynamics!(DoublePendulum);

impl Capabilities for DoublePendulum {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        Some(DoublePendulum::positions(self, Some(q)).map(|x| fill(out, &x)))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const DOUBLE_PENDULUM_PHYSICS: &str =
    "Two rigid rods, each with a bob at its end, hanging from a fixed pivot. Given enough \
         energy the motion is deterministic yet chaotic: two runs whose starting angles \
         differ by a billionth of a radian separate exponentially (a straight rise of the log \
         of their separation, whose slope is the largest Lyapunov exponent) until the \
         difference is as large as the motion itself, and the lower bob's angle θ₂ against \
         its canonical momentum p₂ fills a region instead of tracing a closed curve. Its \
         Hamiltonian is not separable (the mass matrix depends on θ₁ − θ₂), so the symplectic \
         choices are the implicit methods (implicit midpoint, Gauss–Legendre): their energy \
         error stays bounded, while rk4's drifts.";

catalogue_static! {
    /// The catalogue entry of [`DoublePendulum`].
    pub static DOUBLE_PENDULUM_ENTRY: SystemEntry = SystemEntry {
        name: "double-pendulum",
        python: Some("DoublePendulum"),
        summary: "planar double pendulum, angles from the downward vertical (DoublePendulum)",
        family: Family::Lagrangian,
        params: &[
            P::vector(
                "theta0",
                Length::Fixed(2),
                D::demo_vector(&[2.0, 1.0]),
                "rad",
                "initial angles",
            )
            .initial_state(),
            P::vector(
                "thetadot0",
                Length::Fixed(2),
                D::demo_vector(&[0.5, -0.3]),
                "rad/s",
                "initial angular velocities",
            )
            .initial_state(),
            P::scalar("m1", D::scalar(1.0), "kg", Range::POSITIVE, "upper mass"),
            P::scalar("m2", D::scalar(1.0), "kg", Range::POSITIVE, "lower mass"),
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
        note: Some("p holds thetadot, as in the spec"),
        physics: Some(DOUBLE_PENDULUM_PHYSICS),
        presentation: Presentation {
            title: "Double pendulum",
            symbols: &["\\theta_1", "\\theta_2"],
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
            let params = DoublePendulumParams::from_values(v)?;
            Ok(Box::new(Erased(DoublePendulum::new(
                v.vector("theta0")?,
                v.vector("thetadot0")?,
                params,
            )?)))
        },
    };
}
