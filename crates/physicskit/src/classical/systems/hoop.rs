//! [`BeadOnRotatingHoop`]: a bead sliding without friction on a hoop of radius `R` that
//! rotates at a fixed rate `omega` about its vertical diameter.
//!
//! Coordinate `q = (theta,)`, the bead's polar angle measured from the bottom of the hoop. In
//! the co-rotating frame the effective Lagrangian of a unit mass is autonomous (Goldstein,
//! *Classical Mechanics*, 3rd ed., §2.6, exercise; Taylor, *Classical Mechanics*, §7.6):
//!
//! ```text
//! L = R^2 (theta'^2 + omega^2 sin^2 theta) / 2 - g R (1 - cos theta)
//! ```
//!
//! The constant `-g R` puts the zero of energy at the bead resting at the bottom (the Numba
//! peer's convention). The energy `p theta' - L` is the Jacobi integral
//! `R^2 theta'^2 / 2 - R^2 omega^2 sin^2(theta) / 2 + g R (1 - cos theta)`, conserved although
//! the lab-frame energy is not. Above the critical speed `omega_c = sqrt(g / R)` the bottom
//! becomes unstable and two stable equilibria appear at `cos theta = g / (R omega^2)`
//! (a supercritical pitchfork bifurcation).
//!
//! # Closed forms
//!
//! The integrators use these instead of differentiating `L` (checked against the
//! [`LagrangianEngine`] in `tests/classical/lagrangian/closed_forms.rs`); the acceleration and
//! the canonical field are written once, generic over the number type, so their Jacobians
//! come from the same code by automatic differentiation (`lagrangian/forward.rs`). With
//! `s = sin theta`,
//! `c = cos theta`, `w = theta'`:
//!
//! ```text
//! mass          M = R^2,   p = R^2 w,   w = p / R^2
//! force         dL/dtheta = (R^2 omega^2 c - g R) s
//! acceleration  theta'' = (dL/dtheta) / R^2 = (omega^2 c - g / R) s      (Taylor eq. 7.69)
//! energy        E = R^2 w^2 / 2 - R^2 omega^2 s^2 / 2 - g R (c - 1)
//! ```

use crate::classical::core::error::check_len;
use crate::classical::core::error::{check_finite_scalar, check_positive};
use crate::classical::core::linalg::negligible_pivot;
use crate::classical::core::trig::sin_cos;
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::lagrangian::{
    singular_mass_matrix, FieldScalar, Lagrangian, LagrangianEngine, Scalar,
};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{Default as D, Family, ParamSpec as P, Range, SystemEntry};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Lagrangian as Erased};

/// Radius, rotation rate and gravity of a [`BeadOnRotatingHoop`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoopParams {
    /// Hoop radius `R`.
    pub r: f64,
    /// Rotation rate `omega` about the vertical diameter.
    pub omega: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for HoopParams {
    /// The defaults of [`HOOP_ENTRY`], where they are written.
    fn default() -> Self {
        HOOP_ENTRY.defaults(Self::from_values)
    }
}

impl HoopParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            r: v.scalar("R")?,
            omega: v.scalar("omega")?,
            g: v.scalar("g")?,
        })
    }
}

impl HoopParams {
    fn validate(self) -> Result<Self> {
        check_positive("R", self.r)?;
        check_finite_scalar("omega", self.omega)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// The critical rotation rate `sqrt(g / R)` above which the bottom is unstable (`NaN` for
    /// `g < 0`).
    pub fn critical_omega(&self) -> f64 {
        (self.g / self.r).sqrt()
    }

    /// The equilibria at rest in `(-pi, pi]`, in increasing `theta`, each with its branch
    /// ([`HoopBranch`]) and stiffness.
    ///
    /// With `a = R^2 omega^2` and `b = g R` the effective potential is
    /// `V = -a sin^2(theta) / 2 + b (1 - cos theta)`, so `V' = sin theta (b - a cos theta)`
    /// vanishes at `theta = 0`, `theta = pi` and, when `|b / a| < 1`, at
    /// `theta* = ±arccos(g / (R omega^2))` (the pitchfork's branches above `omega_c`). The
    /// stiffness is `V''(theta) / R^2 = -d theta'' / d theta` (units 1/s^2):
    /// `g / R - omega^2` at the bottom, `-omega^2 - g / R` at the top and
    /// `omega^2 sin^2 theta*` on the branches (always stable). At a degenerate point
    /// (`V'' = 0`, e.g. the bottom at `omega = omega_c`) `V` grows like `a x^4 / 8`, so the
    /// equilibrium is stable: stability is `stiffness >= 0` (which side of the bifurcation a
    /// rate within rounding of `omega_c` falls on is decided by that rounding).
    pub fn equilibria(&self) -> Vec<HoopEquilibrium> {
        let Self { r, omega, g } = *self;
        let (a, b) = (r * r * omega * omega, g * r);
        let mut out = vec![
            HoopEquilibrium {
                kind: HoopBranch::Bottom,
                theta: 0.0,
                stiffness: (b - a) / (r * r),
            },
            HoopEquilibrium {
                kind: HoopBranch::Top,
                theta: std::f64::consts::PI,
                stiffness: -(a + b) / (r * r),
            },
        ];
        let c = b / a;
        if c.abs() < 1.0 {
            let theta = c.acos();
            // V'' = a sin^2(theta*) there (from b = a cos theta*): positive, stable.
            let stiffness = omega * omega * (1.0 - c * c);
            for (kind, theta) in [(HoopBranch::Left, -theta), (HoopBranch::Right, theta)] {
                out.push(HoopEquilibrium {
                    kind,
                    theta,
                    stiffness,
                });
            }
        }
        out.sort_by(|x, y| x.theta.total_cmp(&y.theta));
        out
    }

    /// The stable equilibria of [`equilibria`](Self::equilibria): the bottom below the
    /// critical rate, the pair `±arccos(g / (R omega^2))` above it (for `g > 0`).
    pub fn stable_equilibria(&self) -> Vec<f64> {
        self.equilibria()
            .into_iter()
            .filter(HoopEquilibrium::is_stable)
            .map(|e| e.theta)
            .collect()
    }

    /// `dL/dtheta = (R^2 omega^2 cos theta - g R) sin theta`.
    #[inline(always)]
    fn force<X: FieldScalar>(&self, theta: X) -> X {
        let Self { r, omega, g } = *self;
        let (s, c) = theta.sin_cos_kernel();
        (c * (r * r * omega * omega) - g * r) * s
    }

    /// `1 / M = 1 / R^2`, or the singular-matrix error for `R^2 = 0` (unvalidated parameters).
    #[inline(always)]
    fn inverse_mass(&self, t: f64) -> Result<f64> {
        let m = self.r * self.r;
        if negligible_pivot(m, m) {
            return Err(singular_mass_matrix(t));
        }
        Ok(m.recip())
    }
}

/// Which branch of the pitchfork an equilibrium lies on ([`HoopParams::equilibria`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HoopBranch {
    /// The bottom, `theta = 0`: stable below the critical rate, a saddle above it.
    Bottom,
    /// The top, `theta = pi`: always unstable for `g > 0`.
    Top,
    /// The off-axis branch `theta* = -arccos(g / (R omega^2))`, when it exists.
    Left,
    /// The off-axis branch `theta* = +arccos(g / (R omega^2))`, when it exists.
    Right,
}

/// An equilibrium of the bead at rest on the rotating hoop ([`HoopParams::equilibria`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoopEquilibrium {
    /// The branch it lies on (identity, independent of the angle's rounding).
    pub kind: HoopBranch,
    /// The angle from the bottom, in `(-pi, pi]` (rad).
    pub theta: f64,
    /// `V''(theta) / R^2 = -d theta'' / d theta` (1/s^2): the linearization about the
    /// equilibrium is `x'' = -stiffness x`.
    pub stiffness: f64,
}

impl HoopEquilibrium {
    /// Stable: a minimum of the effective potential (`stiffness >= 0`, see
    /// [`HoopParams::equilibria`]).
    pub fn is_stable(&self) -> bool {
        self.stiffness >= 0.0
    }

    /// The largest Lyapunov exponent of the linearized flow about the equilibrium (1/s):
    /// `sqrt(-stiffness)` at a saddle (the deviations grow as `exp(t sqrt(-stiffness))`), zero
    /// at a centre (they rotate on an ellipse). At the bottom above the critical rate this is
    /// `sqrt(omega^2 - g / R)`.
    pub fn linear_exponent(&self) -> f64 {
        (-self.stiffness).max(0.0).sqrt()
    }
}

impl Lagrangian for HoopParams {
    fn ndof(&self) -> usize {
        1
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let Self { r, omega, g } = *self;
        let s = q[0].sin();
        (qdot[0] * qdot[0] + s * s * (omega * omega)) * (0.5 * r * r) + (q[0].cos() - 1.0) * (g * r)
    }

    #[inline]
    fn closed_mass_matrix(&self, _q: &[f64], _w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        out[0] = self.r * self.r;
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, _q: &[f64], w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        out[0] = self.r * self.r * w[0];
        Some(())
    }

    #[inline]
    fn closed_generalized_force(
        &self,
        q: &[f64],
        _w: &[f64],
        _t: f64,
        out: &mut [f64],
    ) -> Option<()> {
        out[0] = self.force(q[0]);
        Some(())
    }

    #[inline]
    fn closed_energy(&self, q: &[f64], w: &[f64], _t: f64) -> Option<f64> {
        let Self { r, omega, g } = *self;
        let (s, c) = sin_cos(q[0]);
        let (ws, r2) = (omega * s, r * r);
        Some(0.5 * r2 * (w[0] * w[0] - ws * ws) - g * r * (c - 1.0))
    }

    #[inline]
    fn closed_velocity(
        &self,
        _q: &[f64],
        p: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Option<Result<()>> {
        Some(self.inverse_mass(t).map(|inv| out[0] = p[0] * inv))
    }

    #[inline(always)]
    fn closed_acceleration_in<X: FieldScalar>(
        &self,
        q: &[X],
        _w: &[X],
        t: f64,
        out: &mut [X],
    ) -> Option<Result<()>> {
        Some(
            self.inverse_mass(t)
                .map(|inv| out[0] = self.force(q[0]) * inv),
        )
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
        Some(self.inverse_mass(t).map(|inv| {
            qdot[0] = p[0] * inv;
            pdot[0] = self.force(q[0]);
        }))
    }
}

/// The bead on a rotating hoop (the spec's `BeadOnRotatingHoop`). State `[theta, thetadot]`.
#[derive(Debug, Clone)]
pub struct BeadOnRotatingHoop {
    phase: Phase,
    engine: LagrangianEngine<HoopParams>,
}

impl BeadOnRotatingHoop {
    /// A bead at angle `theta0` (from the bottom) with angular velocity `thetadot0`.
    ///
    /// # Errors
    /// Non-finite initial values, `R <= 0`, non-finite `omega` or `g`.
    pub fn new(theta0: f64, thetadot0: f64, params: HoopParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(&[theta0], &[thetadot0])?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &HoopParams {
        self.engine.lagrangian()
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<HoopParams> {
        &self.engine
    }

    /// Energies of the separatrices, lowest first: the levels of the saddle equilibria.
    ///
    /// The equilibria at rest are `sin theta = 0` and `cos theta = g / (R omega^2)`. With the
    /// effective potential `V = -R^2 omega^2 sin^2(theta) / 2 + g R (1 - cos theta)`,
    /// `V'' = -R^2 omega^2 cos 2theta + g R cos theta`: the top (`V = 2 g R`) is a saddle when
    /// `R omega^2 + g > 0`, the bottom (`V = 0`) when `R omega^2 > g` (above the critical
    /// rate), and the off-axis pair never (`V'' = R^2 omega^2 sin^2 theta > 0` there). A
    /// degenerate equilibrium (`V'' = 0`, at the bifurcation) is not counted.
    pub fn separatrix_energies(&self) -> Vec<f64> {
        let HoopParams { r, omega, g } = *self.params();
        let spin = r * omega * omega;
        let mut levels = Vec::with_capacity(2);
        if spin > g {
            levels.push(0.0);
        }
        if spin + g > 0.0 {
            levels.push(2.0 * g * r);
        }
        levels.sort_by(f64::total_cmp);
        levels.dedup();
        levels
    }
}

crate::impl_lagrangian_dynamics!(BeadOnRotatingHoop);

impl Capabilities for BeadOnRotatingHoop {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        // The bead in the hoop's rotating plane: (R sin theta, -R cos theta).
        let r = self.params().r;
        Some(check_len("q", q, 1).map(|()| fill(out, &[r * q[0].sin(), -r * q[0].cos()])))
    }
    fn separatrix_energies(&self) -> Option<Vec<f64>> {
        Some(BeadOnRotatingHoop::separatrix_energies(self))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const HOOP_PHYSICS: &str =
    "A bead slides without friction on a vertical hoop of radius R spun at a fixed rate ω \
         about its vertical diameter. In the rotating frame gravity pulls the bead down and \
         the centrifugal force pushes it out. Below the critical rate ω_c = √(g/R) the bottom \
         θ = 0 is the only stable rest point; above it the bottom becomes unstable and two \
         new stable equilibria appear at cos θ = g/(Rω²), climbing the hoop as ω grows: a \
         pitchfork bifurcation, the textbook example of spontaneous symmetry breaking. In \
         phase space the single centre turns into a saddle between two centres.";

catalogue_static! {
    /// The catalogue entry of [`BeadOnRotatingHoop`].
    pub static HOOP_ENTRY: SystemEntry = SystemEntry {
        name: "hoop",
        python: Some("BeadOnRotatingHoop"),
        summary: "bead on a hoop rotating about its vertical diameter (BeadOnRotatingHoop)",
        family: Family::Lagrangian,
        params: &[
            P::scalar(
                "theta0",
                D::demo_scalar(0.3),
                "rad",
                Range::ANY,
                "initial polar angle on the hoop",
            )
            .initial_state(),
            P::scalar(
                "thetadot0",
                D::demo_scalar(0.0),
                "rad/s",
                Range::ANY,
                "initial angular velocity",
            )
            .initial_state(),
            P::scalar("R", D::scalar(1.0), "m", Range::POSITIVE, "hoop radius"),
            P::scalar(
                "omega",
                D::scalar(2.0),
                "rad/s",
                Range::ANY,
                "rotation rate",
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
        note: Some("critical speed omega_c = sqrt(g/R); p holds thetadot"),
        physics: Some(HOOP_PHYSICS),
        presentation: Presentation {
            title: "Bead on a rotating hoop",
            symbols: &["\\theta"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Hoop,
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = HoopParams::from_values(v)?;
            Ok(Box::new(Erased(BeadOnRotatingHoop::new(
                v.scalar("theta0")?,
                v.scalar("thetadot0")?,
                params,
            )?)))
        },
    };
}
