//! [`HeavySymmetricTop`]: a symmetric top with one point fixed, spinning under gravity.
//!
//! Coordinates `q = (phi, theta, psi)`, the z-x-z Euler angles (precession, nutation, spin).
//! With `I1` the transverse moment of inertia about the fixed point, `I3` the axial moment,
//! `M` the mass and `l` the pivot-to-centre-of-mass distance (Goldstein, *Classical
//! Mechanics*, 3rd ed., §5.7, eq. 5.58):
//!
//! ```text
//! L = (I1/2)(theta'^2 + phi'^2 sin^2 theta) + (I3/2)(psi' + phi' cos theta)^2 - M g l cos theta
//! ```
//!
//! `phi` and `psi` are cyclic, so `p_phi` and `p_psi` are conserved; the canonical field has
//! `dp_phi/dt = dp_psi/dt = 0` exactly, so the canonical integration keeps them to rounding.
//! The mass matrix depends on `theta` and is singular at `sin theta = 0` (gimbal lock of the
//! Euler angles). Energy `T + M g l cos theta`. The slow dynamics is analysed in
//! [`analysis::symmetric_top`](crate::classical::analysis).
//!
//! # Closed forms
//!
//! The integrators use these instead of differentiating `L` (checked against the
//! [`LagrangianEngine`] in `tests/classical/lagrangian/closed_forms.rs`); the acceleration and
//! the canonical field are written once, generic over the number type, so their Jacobians
//! come from the same code by automatic differentiation (`lagrangian/forward.rs`). With
//! `s = sin theta`, `c = cos theta` and the spin `w3 = psi' + phi' c` (Goldstein §5.7, eqs. 5.59–5.62):
//!
//! ```text
//! mass matrix   M = [[I1 s^2 + I3 c^2, 0, I3 c], [0, I1, 0], [I3 c, 0, I3]],  det = I1^2 I3 s^2
//! momentum      p_phi = I1 s^2 phi' + I3 w3 c,   p_theta = I1 theta',   p_psi = I3 w3
//! velocity      w3 = p_psi / I3,   phi' = (p_phi - p_psi c) / (I1 s^2),
//!               theta' = p_theta / I1,   psi' = w3 - phi' c
//! force         dL/dtheta = (phi' (I1 phi' c - I3 w3) + M g l) s,   dL/dphi = dL/dpsi = 0
//! energy        E = I1 (theta'^2 + phi'^2 s^2) / 2 + I3 w3^2 / 2 + M g l c
//! ```
//!
//! The accelerations follow from the Euler–Lagrange equations: `theta'' = (dL/dtheta) / I1`;
//! `d p_psi / dt = 0` gives `w3' = 0`; `d p_phi / dt = 0` then gives
//! `I1 (s^2 phi'' + 2 s c theta' phi') - I3 w3 s theta' = 0`, so
//!
//! ```text
//! phi'' = theta' (I3 w3 - 2 I1 phi' c) / (I1 s),   psi'' = phi' theta' s - phi'' c
//! ```
//!
//! The mass matrix counts as singular where the pivot `I1 s^2` (the Schur complement of the
//! `psi` row) is negligible against its largest entry, the criterion of partial-pivoting LU.

use crate::classical::core::error::check_len;
use crate::classical::core::error::{check_finite_scalar, check_positive};
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

/// Inertia, mass, lever arm and gravity of a [`HeavySymmetricTop`]; its [`Lagrangian`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetricTopParams {
    /// Transverse moment of inertia about the fixed point.
    pub i1: f64,
    /// Axial moment of inertia.
    pub i3: f64,
    /// Mass.
    pub m: f64,
    /// Distance from the pivot to the centre of mass.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for SymmetricTopParams {
    /// The defaults of [`HEAVY_TOP_ENTRY`], where they are written.
    fn default() -> Self {
        HEAVY_TOP_ENTRY.defaults(Self::from_values)
    }
}

impl SymmetricTopParams {
    /// The parameters as its catalogue entry's values hold them.
    fn from_values(v: &Values) -> Result<Self> {
        Ok(Self {
            i1: v.scalar("I1")?,
            i3: v.scalar("I3")?,
            m: v.scalar("M")?,
            l: v.scalar("l")?,
            g: v.scalar("g")?,
        })
    }
}

impl SymmetricTopParams {
    fn validate(self) -> Result<Self> {
        check_positive("I1", self.i1)?;
        check_positive("I3", self.i3)?;
        check_positive("M", self.m)?;
        check_finite_scalar("l", self.l)?;
        check_finite_scalar("g", self.g)?;
        Ok(self)
    }

    /// `M g l`, the gravitational torque scale.
    pub fn mgl(&self) -> f64 {
        self.m * self.g * self.l
    }

    /// The conserved momenta `(p_phi, p_psi)` of a state `[phi, theta, psi, phi', theta',
    /// psi']`: `p_psi = I3 (psi' + phi' cos theta)`,
    /// `p_phi = I1 phi' sin^2 theta + p_psi cos theta`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 6.
    pub fn conserved_momenta(&self, state: &[f64]) -> Result<(f64, f64)> {
        if state.len() != 6 {
            return Err(Error::DimensionMismatch {
                name: "state".into(),
                expected: 6,
                found: state.len(),
            });
        }
        let (s, c) = state[1].sin_cos();
        let [p_phi, _, p_psi] = self.momenta(s, c, &state[3..]);
        Ok((p_phi, p_psi))
    }

    /// `p = dL/dqdot` at `(sin theta, cos theta) = (s, c)` and rates `w`:
    /// `[I1 phi' s^2 + p_psi c, I1 theta', p_psi]`, `p_psi = I3 w3`.
    #[inline(always)]
    fn momenta(&self, s: f64, c: f64, w: &[f64]) -> [f64; 3] {
        let p_psi = self.i3 * spin(w, c);
        [self.i1 * w[0] * s * s + p_psi * c, self.i1 * w[1], p_psi]
    }

    /// `I1 s^2`, the pivot that vanishes with `sin theta`, or the singular-matrix error where
    /// it is negligible against the largest entry of the mass matrix.
    #[inline(always)]
    fn pivot<X: FieldScalar>(&self, s: X, c: X, t: f64) -> Result<X> {
        let pivot = s * self.i1 * s;
        let (pivot0, c0) = (pivot.re(), c.re());
        let scale = (pivot0 + self.i3 * c0 * c0).max(self.i1).max(self.i3);
        if negligible_pivot(pivot0, scale)
            || negligible_pivot(self.i1, scale)
            || negligible_pivot(self.i3, scale)
        {
            return Err(singular_mass_matrix(t));
        }
        Ok(pivot)
    }

    /// The velocity `qdot(q, p)` and the spin `w3` at `(s, c)` (module documentation).
    #[inline(always)]
    fn velocity_and_spin<X: FieldScalar>(
        &self,
        p: &[X],
        s: X,
        c: X,
        t: f64,
    ) -> Result<([X; 3], X)> {
        let pivot = self.pivot(s, c, t)?;
        let (phid, w3) = ((p[0] - p[2] * c) / pivot, p[2] / self.i3);
        Ok(([phid, p[1] / self.i1, w3 - phid * c], w3))
    }

    /// `dL/dtheta` at `(s, c)`, precession rate `phid` and spin `w3`.
    #[inline(always)]
    fn nutation_force<X: FieldScalar>(&self, s: X, c: X, phid: X, w3: X) -> X {
        (phid * (phid * self.i1 * c - w3 * self.i3) + self.mgl()) * s
    }
}

/// The spin `w3 = psi' + phi' cos theta` from the rates `w = (phi', theta', psi')` and
/// `c = cos theta`.
#[inline(always)]
fn spin<X: FieldScalar>(w: &[X], c: X) -> X {
    w[2] + w[0] * c
}

impl Lagrangian for SymmetricTopParams {
    fn ndof(&self) -> usize {
        3
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let (s, c) = q[1].sin_cos();
        let (phid, thetad, psid) = (qdot[0], qdot[1], qdot[2]);
        let spin = psid + phid * c;
        (thetad * thetad + phid * phid * s * s) * (0.5 * self.i1) + spin * spin * (0.5 * self.i3)
            - c * self.mgl()
    }

    #[inline]
    fn closed_mass_matrix(&self, q: &[f64], _w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let (s, c) = sin_cos(q[1]);
        let (i1, i3) = (self.i1, self.i3);
        let ic = i3 * c;
        out.copy_from_slice(&[i1 * s * s + ic * c, 0.0, ic, 0.0, i1, 0.0, ic, 0.0, i3]);
        Some(())
    }

    #[inline]
    fn closed_momentum(&self, q: &[f64], w: &[f64], _t: f64, out: &mut [f64]) -> Option<()> {
        let (s, c) = sin_cos(q[1]);
        out.copy_from_slice(&self.momenta(s, c, w));
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
        let (s, c) = sin_cos(q[1]);
        let w3 = spin(w, c);
        out.copy_from_slice(&[0.0, self.nutation_force(s, c, w[0], w3), 0.0]);
        Some(())
    }

    #[inline]
    fn closed_energy(&self, q: &[f64], w: &[f64], _t: f64) -> Option<f64> {
        let (s, c) = sin_cos(q[1]);
        let (phis, w3) = (w[0] * s, spin(w, c));
        Some(0.5 * (self.i1 * (w[1] * w[1] + phis * phis) + self.i3 * w3 * w3) + self.mgl() * c)
    }

    #[inline]
    fn closed_velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let (s, c) = sin_cos(q[1]);
        Some(
            self.velocity_and_spin(p, s, c, t)
                .map(|(w, _)| out.copy_from_slice(&w)),
        )
    }

    #[inline(always)]
    fn closed_acceleration_in<X: FieldScalar>(
        &self,
        q: &[X],
        w: &[X],
        t: f64,
        out: &mut [X],
    ) -> Option<Result<()>> {
        let (s, c) = q[1].sin_cos_kernel();
        let (phid, thetad) = (w[0], w[1]);
        let w3 = spin(w, c);
        Some(self.pivot(s, c, t).map(|_| {
            let phidd = thetad * (w3 * self.i3 - phid * (2.0 * self.i1) * c) / (s * self.i1);
            out.copy_from_slice(&[
                phidd,
                self.nutation_force(s, c, phid, w3) / self.i1,
                phid * thetad * s - phidd * c,
            ]);
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
        let (s, c) = q[1].sin_cos_kernel();
        Some(self.velocity_and_spin(p, s, c, t).map(|(w, w3)| {
            qdot.copy_from_slice(&w);
            let zero = X::from(0.0);
            pdot.copy_from_slice(&[zero, self.nutation_force(s, c, w[0], w3), zero]);
        }))
    }
}

/// The heavy symmetric top (the spec's `HeavySymmetricTop`). State `[phi, theta, psi, phi',
/// theta', psi']`.
#[derive(Debug, Clone)]
pub struct HeavySymmetricTop {
    phase: Phase,
    engine: LagrangianEngine<SymmetricTopParams>,
}

impl HeavySymmetricTop {
    /// A top at Euler angles `angles0 = (phi, theta, psi)` with rates `angledots0`.
    ///
    /// # Errors
    /// Lengths other than 3, non-finite values, non-positive `I1`, `I3` or `M`, non-finite
    /// `l` or `g`, or `sin theta = 0` (singular mass matrix: the Euler angles degenerate).
    pub fn new(angles0: &[f64], angledots0: &[f64], params: SymmetricTopParams) -> Result<Self> {
        let engine = LagrangianEngine::new(params.validate()?)?;
        let phase = engine.initial_phase(angles0, angledots0)?;
        Ok(Self { phase, engine })
    }

    /// The parameters.
    pub fn params(&self) -> &SymmetricTopParams {
        self.engine.lagrangian()
    }

    /// The instantaneous `(phidot, thetadot)`, precession and nutation rates, of `state` (the
    /// current state if `None`).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length 6.
    pub fn precession_nutation_rate(&self, state: Option<&[f64]>) -> Result<(f64, f64)> {
        let state = state.unwrap_or(self.phase.state());
        if state.len() != 6 {
            return Err(Error::DimensionMismatch {
                name: "state".into(),
                expected: 6,
                found: state.len(),
            });
        }
        Ok((state[3], state[4]))
    }

    /// The engine deriving the equations of motion.
    pub fn engine(&self) -> &LagrangianEngine<SymmetricTopParams> {
        &self.engine
    }

    /// The unit vector along the symmetry axis, in the space frame (z up), for the Euler
    /// angles `q = (phi, theta, psi)` (the current ones if `None`): the third column of the
    /// z-x-z rotation matrix (Goldstein, 3rd ed., eq. 4.47),
    /// `(sin theta sin phi, -sin theta cos phi, cos theta)`. `psi` (the spin) does not move it.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` has length 3.
    pub fn symmetry_axis(&self, q: Option<&[f64]>) -> Result<[f64; 3]> {
        let q = q.unwrap_or(&self.phase.state()[..3]);
        check_len("q", q, 3)?;
        let (sp, cp) = q[0].sin_cos();
        let (st, ct) = q[1].sin_cos();
        Ok([st * sp, -st * cp, ct])
    }
}

crate::impl_lagrangian_dynamics!(HeavySymmetricTop);

impl Capabilities for HeavySymmetricTop {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        // The centre of mass, on the symmetry axis at distance l from the pivot (the origin).
        let l = self.params().l;
        Some(HeavySymmetricTop::symmetry_axis(self, Some(q)).map(|a| fill(out, &a.map(|x| l * x))))
    }
    fn symmetry_axis(&self, q: &[f64]) -> Option<Result<[f64; 3]>> {
        Some(HeavySymmetricTop::symmetry_axis(self, Some(q)))
    }
    fn precession_nutation_rate(&self, state: &[f64]) -> Option<Result<(f64, f64)>> {
        Some(HeavySymmetricTop::precession_nutation_rate(
            self,
            Some(state),
        ))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const HEAVY_TOP_PHYSICS: &str =
    "A spinning top with its tip fixed precesses slowly about the vertical while its axis \
         nods up and down (nutation). Because the angles φ and ψ do not appear in the \
         Lagrangian, their momenta are conserved and the tilt θ moves like a particle in the \
         effective potential V_eff(θ): it oscillates between the two turning points where \
         V_eff equals the energy, so θ against its rate is the revealing phase portrait. \
         Depending on the start, the tip of the axis draws waves, loops or, started from rest \
         in φ, cusps on the unit sphere.";

catalogue_static! {
    /// The catalogue entry of [`HeavySymmetricTop`].
    pub static HEAVY_TOP_ENTRY: SystemEntry = SystemEntry {
        name: "heavy-top",
        python: Some("HeavySymmetricTop"),
        summary: "heavy symmetric top on a fixed point, Euler angles (phi, theta, psi) \
                  (HeavySymmetricTop)",
        family: Family::Lagrangian,
        params: &[
            P::vector(
                "angles0",
                Length::Fixed(3),
                D::demo_vector(&[0.0, 0.5, 0.0]),
                "rad",
                "initial (phi, theta, psi)",
            )
            .initial_state(),
            P::vector(
                "angledots0",
                Length::Fixed(3),
                D::demo_vector(&[0.0, 0.0, 20.0]),
                "rad/s",
                "initial rates (phidot, thetadot, psidot)",
            )
            .initial_state(),
            P::scalar(
                "I1",
                D::scalar(1.0),
                "kg m^2",
                Range::POSITIVE,
                "transverse moment of inertia about the pivot",
            ),
            P::scalar(
                "I3",
                D::scalar(0.5),
                "kg m^2",
                Range::POSITIVE,
                "axial moment of inertia",
            ),
            P::scalar("M", D::scalar(1.0), "kg", Range::POSITIVE, "mass"),
            P::scalar(
                "l",
                D::scalar(1.0),
                "m",
                Range::ANY,
                "pivot to centre of mass",
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
        note: Some("p holds the angle rates, as in the spec"),
        physics: Some(HEAVY_TOP_PHYSICS),
        presentation: Presentation {
            title: "Heavy symmetric top",
            symbols: &["\\phi", "\\theta", "\\psi"],
            time_unit: "s",
            state_units: None,
            drawing: Drawing::TopAxis,
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let params = SymmetricTopParams::from_values(v)?;
            Ok(Box::new(Erased(HeavySymmetricTop::new(
                v.vector("angles0")?,
                v.vector("angledots0")?,
                params,
            )?)))
        },
    };
}
