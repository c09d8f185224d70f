//! Projectile motion under uniform gravity, with optional quadratic air drag.
//!
//! ```text
//! H(q, p) = |p|^2 / (2 m) + m g y,            q = (x, y)
//! dq/dt = p / m,   dp/dt = (0, -m g) - c |v| v,   v = p / m
//! ```
//!
//! Without drag (`c = drag_coeff = 0`) the solution is Galileo's parabola
//! `x = v0 cos(theta) t`, `y = h + v0 sin(theta) t - g t^2 / 2`; because the force is constant,
//! `verlet` and `yoshida4` reproduce it to rounding at any step. With `c > 0` the quadratic
//! drag makes the system dissipative (`dE/dt = -c |v|^3 <= 0`): the splitting methods, whose
//! force callback sees only gravity, are refused, and `rk4` (the default) or
//! `implicit_midpoint` integrate the full right-hand side. Reference: J. R. Taylor,
//! *Classical Mechanics* (2005), ch. 2.

use crate::classical::core::error::{
    check_finite_scalar, check_len, check_non_negative, check_positive, check_vector,
};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::lanes::{LanesForce, Real, SplittingLanes};
use crate::classical::integrators::{
    hamiltonian_energy, DynamicalSystem, HamiltonianSystem, MassInv, Method,
};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Hamiltonian};

/// A point projectile `H = |p|^2/(2m) + m g y` with optional drag force `-c |v| v`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::ProjectileMotion;
/// use physicskit::classical::{HamiltonianSystem, Method};
///
/// let mut ball = ProjectileMotion::from_launch(20.0, 45.0, 1.0, 9.81, 0.0, 0.0).unwrap();
/// ball.integrate((0.0, 1.0), 1e-2, Method::Verlet).unwrap();
/// let (x, y) = ProjectileMotion::analytic_trajectory(20.0, 45.0, 9.81, &[1.0], 0.0).unwrap();
/// assert!((ball.q()[0] - x[0]).abs() < 1e-12 && (ball.q()[1] - y[0]).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct ProjectileMotion {
    phase: Phase,
    m: f64,
    /// `1/m`, formed once: every splitting step asks for it (`mass_inv`).
    m_inv: f64,
    g: f64,
    drag_coeff: f64,
}

fn launch_velocity(speed: f64, angle_deg: f64) -> Result<(f64, f64)> {
    let speed = check_non_negative("speed", speed)?;
    let angle = check_finite_scalar("angle_deg", angle_deg)?.to_radians();
    Ok((speed * angle.cos(), speed * angle.sin()))
}

impl ProjectileMotion {
    /// A projectile at `q0 = (x, y)` with momentum `p0 = m v0`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::classical::Error::DimensionMismatch) unless `q0`, `p0` have length 2; [`Error::NonFinite`](crate::classical::Error::NonFinite) for
    /// NaN or infinity; [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for `m <= 0`, `g <= 0` or
    /// `drag_coeff < 0`.
    pub fn new(q0: &[f64], p0: &[f64], m: f64, g: f64, drag_coeff: f64) -> Result<Self> {
        check_vector("q0", q0, 2)?;
        check_vector("p0", p0, 2)?;
        let m = check_positive("m", m)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            m,
            m_inv: 1.0 / m,
            g: check_positive("g", g)?,
            drag_coeff: check_non_negative("drag_coeff", drag_coeff)?,
        })
    }

    /// A projectile launched from `(0, height)` at `speed` and `angle_deg` degrees above the
    /// horizontal.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for `speed < 0`, a non-finite angle or height, and the
    /// errors of [`ProjectileMotion::new`].
    pub fn from_launch(
        speed: f64,
        angle_deg: f64,
        m: f64,
        g: f64,
        drag_coeff: f64,
        height: f64,
    ) -> Result<Self> {
        let (vx, vy) = launch_velocity(speed, angle_deg)?;
        let height = check_finite_scalar("height", height)?;
        let m = check_positive("m", m)?;
        Self::new(&[0.0, height], &[m * vx, m * vy], m, g, drag_coeff)
    }

    /// Mass `m`.
    pub fn m(&self) -> f64 {
        self.m
    }

    /// Gravitational acceleration `g`.
    pub fn g(&self) -> f64 {
        self.g
    }

    /// Quadratic drag coefficient `c`.
    pub fn drag_coeff(&self) -> f64 {
        self.drag_coeff
    }

    /// Galileo's vacuum parabola `x(t) = v0 cos(theta) t`, `y(t) = h + v0 sin(theta) t - g t^2/2`
    /// at the times `t` (launch at `t = 0` from `(0, height)`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for `speed < 0`, `g <= 0`, a non-finite angle or height;
    /// [`Error::NonFinite`](crate::classical::Error::NonFinite) for a non-finite time.
    pub fn analytic_trajectory(
        speed: f64,
        angle_deg: f64,
        g: f64,
        t: &[f64],
        height: f64,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let (vx, vy) = launch_velocity(speed, angle_deg)?;
        let g = check_positive("g", g)?;
        let height = check_finite_scalar("height", height)?;
        check_vector("t", t, t.len())?;
        let x = t.iter().map(|&ti| vx * ti).collect();
        let y = t
            .iter()
            .map(|&ti| height + vy * ti - 0.5 * g * ti * ti)
            .collect();
        Ok((x, y))
    }

    /// Vacuum range and maximum height of a launch from `(0, height)`.
    ///
    /// The range is `x` at the positive root of `y(t) = 0`,
    /// `t = (v0 sin(theta) + sqrt(v0^2 sin^2(theta) + 2 g h)) / g`; the maximum height is
    /// `h + v0^2 sin^2(theta) / (2 g)` for an upward launch and `h` otherwise.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for `speed < 0`, `g <= 0`, a non-finite angle, or
    /// `height < 0` (a launch below the ground never lands on it).
    pub fn range_and_max_height(
        speed: f64,
        angle_deg: f64,
        g: f64,
        height: f64,
    ) -> Result<(f64, f64)> {
        let t_land = Self::flight_time(speed, angle_deg, g, height)?;
        let (vx, vy) = launch_velocity(speed, angle_deg)?;
        let h = height;
        let max_height = if vy > 0.0 { h + vy * vy / (2.0 * g) } else { h };
        Ok((vx * t_land, max_height))
    }

    /// Vacuum time of flight of a launch from `(0, height)` until it lands on `y = 0`: the
    /// positive root `t = (v0 sin(theta) + sqrt(v0^2 sin^2(theta) + 2 g h)) / g` of `y(t) = 0`
    /// (`2 v0 sin(theta) / g` from the ground).
    ///
    /// # Errors
    /// As [`range_and_max_height`](Self::range_and_max_height).
    pub fn flight_time(speed: f64, angle_deg: f64, g: f64, height: f64) -> Result<f64> {
        let (_, vy) = launch_velocity(speed, angle_deg)?;
        let g = check_positive("g", g)?;
        let h = check_non_negative("height", height)?;
        Ok((vy + (vy * vy + 2.0 * g * h).sqrt()) / g)
    }
}

impl HamiltonianSystem for ProjectileMotion {
    fn ndof(&self) -> usize {
        2
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.potential(q)
    }
    fn conservative(&self) -> bool {
        self.drag_coeff <= 0.0
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.m_inv)
    }
    /// The conservative force only, gravity `(0, -m g)` ([`LanesForce::force_of`] at `f64`);
    /// drag enters through [`DynamicalSystem::derivatives`].
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        self.force_of(q, out);
        Ok(())
    }
    fn force_jacobian(&self, _q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        out.iter_mut().for_each(|v| *v = 0.0);
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes. With drag the
/// splitting methods are refused (`conservative` is false), in lanes as alone.
impl LanesForce for ProjectileMotion {
    const NDOF: usize = 2;

    #[inline(always)]
    fn force_of<R: Real>(&self, _q: &[R], out: &mut [R]) {
        out[0] = R::splat(0.0);
        out[1] = R::splat(-self.m * self.g);
    }

    /// Equal mass, gravity and drag coefficient, bit for bit.
    fn same_force(&self, other: &Self) -> bool {
        let bits = |s: &Self| [s.m, s.g, s.drag_coeff].map(f64::to_bits);
        bits(self) == bits(other)
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(self.potential(q))
    }
}

impl ProjectileMotion {
    /// `V = m g y`, written once over any [`Real`]: the scalar `potential_energy` and the
    /// members' energies in lanes.
    #[inline(always)]
    fn potential<R: Real>(&self, q: &[R]) -> R {
        R::splat(self.m * self.g) * q[1]
    }
}

impl DynamicalSystem for ProjectileMotion {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    /// `[p/m, (0, -m g) - c |v| v]` with `v = p/m`.
    fn derivatives(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let inv_m = self.m_inv;
        let (vx, vy) = (state[2] * inv_m, state[3] * inv_m);
        let drag = self.drag_coeff * vx.hypot(vy);
        out[0] = vx;
        out[1] = vy;
        out[2] = -drag * vx;
        out[3] = -self.m * self.g - drag * vy;
        Ok(())
    }
    #[inline]
    fn energy(&self, state: &[f64]) -> f64 {
        hamiltonian_energy(self, state)
    }
    /// Rows `dq/dt`: `I/m` in the `p` block; rows `dp/dt`: the drag Jacobian
    /// `-(c/m)(|v| I + v v^T / |v|)` (zero at rest).
    fn jacobian(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let inv_m = self.m_inv;
        let v = [state[2] * inv_m, state[3] * inv_m];
        let speed = v[0].hypot(v[1]);
        out.iter_mut().for_each(|x| *x = 0.0);
        out[2] = inv_m;
        out[4 + 3] = inv_m;
        for i in 0..2 {
            for j in 0..2 {
                let mut d = if i == j { speed } else { 0.0 };
                if speed > 0.0 {
                    d += v[i] * v[j] / speed;
                }
                out[(2 + i) * 4 + 2 + j] = -self.drag_coeff * inv_m * d;
            }
        }
        Some(Ok(()))
    }
    /// `yoshida4` in vacuum, `rk4` with drag (the splitting methods are refused then).
    fn default_method(&self) -> Method {
        if self.conservative() {
            Method::Yoshida4
        } else {
            Method::Rk4
        }
    }
}

impl Capabilities for ProjectileMotion {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        Some(check_len("q", q, 2).map(|()| fill(out, q)))
    }
}

const PROJECTILE_PARAMS: [P; 3] = [
    P::scalar("m", D::scalar(1.0), "kg", Range::POSITIVE, "mass"),
    P::scalar(
        "g",
        D::scalar(9.81),
        "m/s^2",
        Range::POSITIVE,
        "gravitational acceleration",
    ),
    P::scalar(
        "drag_coeff",
        D::scalar(0.0),
        "kg/m",
        Range::NON_NEGATIVE,
        "quadratic drag coefficient c",
    ),
];

const DRAG_NOTE: &str =
    "with drag_coeff > 0 only rk4 (then the default), implicit_midpoint and dop853 apply";

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const PROJECTILE_PHYSICS: &str =
    "Without air resistance every trajectory is Galileo's parabola and the range v² \
         sin(2θ)/g is largest at 45°, with complementary angles (30° and 60°) landing at the \
         same spot. Quadratic air drag (force −c|v|v) takes energy out of the flight: the \
         paths become lopsided, steeper on the way down, the range shrinks a lot, and the \
         best launch angle drops below 45°.";

/// How both projectile entries are shown (the second with its own title).
const PROJECTILE_PRESENTATION: Presentation = Presentation {
    title: "Projectile",
    symbols: &["x", "y"],
    time_unit: "s",
    state_units: None,
    drawing: Drawing::Orbit {
        central_body: false,
        ground: true,
    },
    pace: Pace::Own,
    section_first: false,
    energy_conserved: true,
};

catalogue_static! {
    /// The catalogue entry of [`ProjectileMotion::new`].
    pub static PROJECTILE_STATE_ENTRY: SystemEntry = SystemEntry {
        name: "projectile-state",
        python: Some("ProjectileMotion"),
        summary: "projectile from a position and momentum (ProjectileMotion::new)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Fixed(2),
                D::demo_vector(&[0.0, 0.0]),
                "m",
                "initial position (x, y)",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::Fixed(2),
                D::demo_vector(&[10.0, 10.0]),
                "kg m/s",
                "initial momentum m v",
            )
            .initial_state(),
            PROJECTILE_PARAMS[0],
            PROJECTILE_PARAMS[1],
            PROJECTILE_PARAMS[2],
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: Some(DRAG_NOTE),
        physics: Some(PROJECTILE_PHYSICS),
        presentation: Presentation {
            title: "Projectile (from a state)",
            ..PROJECTILE_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(ProjectileMotion::new(
                v.vector("q0")?,
                v.vector("p0")?,
                v.scalar("m")?,
                v.scalar("g")?,
                v.scalar("drag_coeff")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`ProjectileMotion::from_launch`].
    pub static PROJECTILE_ENTRY: SystemEntry = SystemEntry {
        name: "projectile",
        python: Some("ProjectileMotion.from_launch"),
        summary: "projectile launched from (0, height), optional quadratic drag \
                  (ProjectileMotion::from_launch)",
        family: Family::Hamiltonian,
        params: &[
            P::scalar(
                "speed",
                D::demo_scalar(20.0),
                "m/s",
                Range::NON_NEGATIVE,
                "launch speed",
            ),
            P::scalar(
                "angle_deg",
                D::demo_scalar(45.0),
                "deg",
                Range::ANY,
                "launch angle above the horizontal",
            ),
            PROJECTILE_PARAMS[0],
            PROJECTILE_PARAMS[1],
            PROJECTILE_PARAMS[2],
            P::scalar("height", D::scalar(0.0), "m", Range::ANY, "launch height"),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: Some(DRAG_NOTE),
        physics: Some(PROJECTILE_PHYSICS),
        // Started from a speed and an angle, not from a state: the state's units said here.
        presentation: Presentation {
            state_units: Some(("m", "kg m/s")),
            ..PROJECTILE_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(ProjectileMotion::from_launch(
                v.scalar("speed")?,
                v.scalar("angle_deg")?,
                v.scalar("m")?,
                v.scalar("g")?,
                v.scalar("drag_coeff")?,
                v.scalar("height")?,
            )?)))
        },
    };
}
