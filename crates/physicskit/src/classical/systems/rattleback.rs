//! [`Rattleback`]: a reduced, phenomenological model of the rattleback's spin reversal.
//!
//! A real rattleback reverses because its principal axes of inertia are turned from its
//! geometric axes and it rolls without slipping (Garcia & Hubbard, Proc. R. Soc. Lond. A 418
//! (1988) 165). This model does not simulate that contact: it is the physicskit 0.4.0 peer's
//! reduced model, kept with the same equations for users who move from it. Three rates
//! `n = (n1, n2, n3)` (two rocking modes and the spin `n3`) follow Euler's equations of a free
//! body, with a term even in `n3` added to the first rocking mode only (which breaks the
//! `n3 -> -n3` symmetry, as the misaligned axes do), linear damping `mu` on all three and a
//! cubic saturation `eta` on the rocking modes:
//!
//! ```text
//! n1' = (I2 - I3)/I1 n2 n3 + gamma n3^2 - mu n1 - eta n1^3
//! n2' = (I3 - I1)/I2 n3 n1             - mu n2 - eta n2^3
//! n3' = (I1 - I2)/I3 n1 n2             - mu n3
//! ```
//!
//! A spin `n3` drives the first rocking mode through `gamma n3^2`, the second follows through
//! `(I3 - I1)/I2 n3 n1`, and `(I1 - I2)/I3 n1 n2` then brakes the spin: it stops and turns
//! round. **It does so for both senses of spin.** The equations are invariant under
//! `(n1, n2, n3) -> (n1, -n2, -n3)` (each term of `n1'` is even in `(n2, n3)`, each term of
//! `n2'` and `n3'` odd), so the run from `(n1, -n2, -n3)` is the mirror image of the run from
//! `(n1, n2, n3)`, bit for bit: the term even in `n3` does not select a sense of spin, contrary
//! to what the peer's documentation says of it. A rattleback that reverses one way only needs
//! the rolling contact. With `gamma = 0` it is a damped Euler top and never reverses.
//!
//! [`DynamicalSystem::energy`] is the kinetic energy `(I1 n1^2 + I2 n2^2 + I3 n3^2) / 2`, not
//! conserved (the model is dissipative, and its pumping term does work).

use crate::classical::core::error::{
    check_finite_scalar, check_non_negative, check_positive, check_vector,
};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::Method;
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::Values;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Ode};

/// Moments, coupling and damping of a [`Rattleback`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RattlebackParams {
    /// Moment about body axis 1, `> 0`.
    pub i1: f64,
    /// Moment about body axis 2, `> 0`.
    pub i2: f64,
    /// Moment about body axis 3 (the spin), `> 0`.
    pub i3: f64,
    /// `gamma`: the coupling of the spin into the first rocking mode, finite.
    pub gamma: f64,
    /// `mu`: linear damping rate of all three rates, `>= 0`.
    pub mu: f64,
    /// `eta`: cubic saturation of the rocking modes, `>= 0`.
    pub eta: f64,
}

impl Default for RattlebackParams {
    /// The defaults of [`RATTLEBACK_ENTRY`], where they are written.
    fn default() -> Self {
        RATTLEBACK_ENTRY.defaults(Self::from_values)
    }
}

impl RattlebackParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            i1: v.scalar("I1")?,
            i2: v.scalar("I2")?,
            i3: v.scalar("I3")?,
            gamma: v.scalar("gamma")?,
            mu: v.scalar("mu")?,
            eta: v.scalar("eta")?,
        })
    }
}

/// The reduced rattleback; state `[n1, n2, n3]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{Rattleback, RattlebackParams};
/// use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
///
/// let mut r = Rattleback::new(&[0.01, 0.01, 3.0], RattlebackParams::default()).unwrap();
/// r.integrate((0.0, 20.0), 1e-3, Method::Rk4).unwrap();
/// assert!(r.state()[2] < 0.0); // the spin has turned round
/// ```
#[derive(Debug, Clone)]
pub struct Rattleback {
    phase: Phase,
    params: RattlebackParams,
    /// Euler's coefficients `((I2-I3)/I1, (I3-I1)/I2, (I1-I2)/I3)`, formed once.
    euler: [f64; 3],
}

impl Rattleback {
    /// A rattleback with initial rates `n0 = (n1, n2, n3)` (rad/s).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::classical::Error::DimensionMismatch) unless `n0`
    /// has length 3; [`Error::NonFinite`](crate::classical::Error::NonFinite);
    /// [`Error::InvalidParameter`](crate::classical::Error::InvalidParameter) for a moment
    /// `<= 0`, `mu < 0` or `eta < 0`.
    pub fn new(n0: &[f64], params: RattlebackParams) -> Result<Self> {
        check_vector("n0", n0, 3)?;
        let i1 = check_positive("I1", params.i1)?;
        let i2 = check_positive("I2", params.i2)?;
        let i3 = check_positive("I3", params.i3)?;
        check_finite_scalar("gamma", params.gamma)?;
        check_non_negative("mu", params.mu)?;
        check_non_negative("eta", params.eta)?;
        Ok(Self {
            phase: Phase::new(n0.to_vec(), 0.0)?,
            params,
            euler: [(i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3],
        })
    }

    /// The parameters.
    pub fn params(&self) -> &RattlebackParams {
        &self.params
    }
}

impl Rattleback {
    /// The right-hand side, for `impl_ode_dynamics!`.
    #[inline]
    fn field(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let [a1, a2, a3] = self.euler;
        let RattlebackParams { gamma, mu, eta, .. } = self.params;
        let (n1, n2, n3) = (state[0], state[1], state[2]);
        out[0] = a1 * n2 * n3 + gamma * n3 * n3 - mu * n1 - eta * n1 * n1 * n1;
        out[1] = a2 * n3 * n1 - mu * n2 - eta * n2 * n2 * n2;
        out[2] = a3 * n1 * n2 - mu * n3;
        Ok(())
    }

    /// Kinetic energy `(I1 n1^2 + I2 n2^2 + I3 n3^2) / 2` (`NaN` for a state of the wrong
    /// length); not conserved.
    fn field_energy(&self, state: &[f64]) -> f64 {
        let p = &self.params;
        0.5 * (p.i1 * state[0] * state[0] + p.i2 * state[1] * state[1] + p.i3 * state[2] * state[2])
    }

    /// The Jacobian of [`field`](Self::field), for `impl_ode_dynamics!`.
    fn field_jacobian(&self, _t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let [a1, a2, a3] = self.euler;
        let RattlebackParams { gamma, mu, eta, .. } = self.params;
        let (n1, n2, n3) = (state[0], state[1], state[2]);
        out.copy_from_slice(&[
            -mu - 3.0 * eta * n1 * n1,
            a1 * n3,
            a1 * n2 + 2.0 * gamma * n3,
            a2 * n3,
            -mu - 3.0 * eta * n2 * n2,
            a2 * n1,
            a3 * n2,
            a3 * n1,
            -mu,
        ]);
        Ok(())
    }
}

impl_ode_dynamics!(Rattleback, dim = 3, method = ImplicitMidpoint, jacobian);

impl Capabilities for Rattleback {}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const RATTLEBACK_PHYSICS: &str =
    "The peer's reduced model of a rattleback (a celt): the rates n₁ and n₂ of rocking \
    about the two horizontal axes and the spin n₃ about the vertical, coupled as in \
    Euler's equations of a free body, with a term γn₃² that feeds spin into rocking and \
    linear and cubic damping. Its equations are unchanged by (n₁, n₂, n₃) → (n₁, −n₂, \
    −n₃), so a spin of either sense reverses alike. The one-way reversal of a real \
    rattleback comes from its rolling contact with inertia axes turned from its geometric \
    axes, which RollingRattleback simulates.";

catalogue_static! {
    /// The catalogue entry of [`Rattleback`].
    pub static RATTLEBACK_ENTRY: SystemEntry = SystemEntry {
        name: "rattleback",
        python: Some("Rattleback"),
        summary: "reduced rattleback: the spin rocks, stops and reverses (Rattleback)",
        family: Family::Ode,
        params: &[
            P::vector(
                "n0",
                Length::Fixed(3),
                D::demo_vector(&[0.01, 0.01, 3.0]),
                "rad/s",
                "initial rates (rocking n1, rocking n2, spin n3)",
            )
            .initial_state(),
            P::scalar("I1", D::scalar(1.0), "kg m^2", Range::POSITIVE, "moment 1"),
            P::scalar("I2", D::scalar(1.5), "kg m^2", Range::POSITIVE, "moment 2"),
            P::scalar(
                "I3",
                D::scalar(2.0),
                "kg m^2",
                Range::POSITIVE,
                "moment 3 (spin axis)",
            ),
            P::scalar(
                "gamma",
                D::scalar(1.0),
                "1/rad",
                Range::ANY,
                "coupling of the spin into rocking mode 1",
            ),
            P::scalar(
                "mu",
                D::scalar(0.01),
                "1/s",
                Range::NON_NEGATIVE,
                "linear damping",
            ),
            P::scalar(
                "eta",
                D::scalar(0.01),
                "s/rad^2",
                Range::NON_NEGATIVE,
                "cubic saturation of the rocking",
            ),
        ],
        separable: false,
        taylor_form: false,
        default_method: Method::ImplicitMidpoint,
        note: Some(
            "y columns: n1, n2, n3; a phenomenological reduced model, not rolling mechanics; it \
             is symmetric under (n1, n2, n3) -> (n1, -n2, -n3), so it reverses either sense of spin",
        ),
        physics: Some(RATTLEBACK_PHYSICS),
        presentation: Presentation {
            title: "Rattleback (reduced model)",
            symbols: &[],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::Spin,
            pace: Pace::Own,
            section_first: false,
            energy_conserved: false,
        },
        build: |v| {
            let params = RattlebackParams::from_values(v)?;
            Ok(Box::new(Ode(Rattleback::new(v.vector("n0")?, params)?)))
        },
    };
}
