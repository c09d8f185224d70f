//! The Hénon–Heiles system.
//!
//! ```text
//! H = (p_x^2 + p_y^2)/2 + (x^2 + y^2)/2 + x^2 y - y^3/3
//! ```
//!
//! A non-integrable two-degree-of-freedom oscillator, introduced as a model of a star moving in
//! an axisymmetric galactic potential. Below `E ~ 1/6` (the saddle energy) the Poincaré section
//! `(x, p_x)` at `y = 0` is dominated by KAM tori; near and above it they break into a chaotic
//! sea. Reference: M. Hénon and C. Heiles, Astron. J. 69 (1964) 73–79.

use crate::classical::core::error::{check_len, check_vector};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::lanes::{LanesForce, Real, SplittingLanes};
use crate::classical::integrators::{HamiltonianSystem, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{Default as D, Family, Length, ParamSpec as P, SystemEntry};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Hamiltonian};

/// The Hénon–Heiles Hamiltonian `H = |p|^2/2 + (x^2 + y^2)/2 + x^2 y - y^3/3` (unit masses).
#[derive(Debug, Clone)]
pub struct HenonHeilesSystem {
    phase: Phase,
}

impl HenonHeilesSystem {
    /// The system at position `q0 = (x, y)` with momentum `p0 = (p_x, p_y)`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::classical::Error::DimensionMismatch) unless both
    /// have length 2, [`Error::NonFinite`](crate::classical::Error::NonFinite) for NaN or
    /// infinity.
    pub fn new(q0: &[f64], p0: &[f64]) -> Result<Self> {
        check_vector("q0", q0, 2)?;
        check_vector("p0", p0, 2)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
        })
    }
}

impl HamiltonianSystem for HenonHeilesSystem {
    fn ndof(&self) -> usize {
        2
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        potential(q)
    }
    /// `F = -(x + 2 x y, y + x^2 - y^2)` ([`LanesForce::force_of`] at `f64`).
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        self.force_of(q, out);
        Ok(())
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let (x, y) = (q[0], q[1]);
        out[0] = -1.0 - 2.0 * y;
        out[1] = -2.0 * x;
        out[2] = -2.0 * x;
        out[3] = -1.0 + 2.0 * y;
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes.
impl LanesForce for HenonHeilesSystem {
    const NDOF: usize = 2;

    /// `F = -(x + 2 x y, y + x^2 - y^2)`.
    #[inline(always)]
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        let (x, y) = (q[0], q[1]);
        out[0] = -x - x * 2.0 * y;
        out[1] = -y - x * x + y * y;
    }

    /// No parameters: every Hénon–Heiles system has the same force.
    fn same_force(&self, _: &Self) -> bool {
        true
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(potential(q))
    }
}

/// `V = (x^2 + y^2)/2 + x^2 y - y^3/3`, over `f64` and over members in SIMD lanes.
#[inline(always)]
fn potential<R: Real>(q: &[R]) -> R {
    let (x, y) = (q[0], q[1]);
    (x * x + y * y) * 0.5 + x * x * y - y * y * y / R::splat(3.0)
}

crate::impl_separable_dynamics!(HenonHeilesSystem, taylor: crate::classical::symbolic::traced_hamiltonian_taylor_field, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

/// `H` written once over any number type, for the system's Taylor form
/// ([`traced_hamiltonian_taylor_field`](crate::classical::symbolic::traced_hamiltonian_taylor_field)).
impl crate::classical::symbolic::TracedHamiltonian for HenonHeilesSystem {
    fn ndof(&self) -> usize {
        2
    }
    fn hamiltonian<D: crate::classical::lagrangian::Scalar>(&self, q: &[D], p: &[D], _t: D) -> D {
        let (x, y) = (q[0], q[1]);
        (p[0] * p[0] + p[1] * p[1] + x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

impl Capabilities for HenonHeilesSystem {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        Some(check_len("q", q, 2).map(|()| fill(out, q)))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const HENON_HEILES_PHYSICS: &str =
    "A star in an axisymmetric galaxy (Hénon & Heiles 1964), H = (px² + py²)/2 + (x² + \
         y²)/2 + x²y − y³/3. A Poincaré section records each crossing of the plane y = 0 with \
         py > 0 (located exactly with Hénon's trick, not taken from the nearest time step). \
         At low energy almost every orbit's crossings lie on a smooth closed curve, the \
         section of an invariant (KAM) torus: the motion is regular. As the energy rises, the \
         tori between the islands dissolve into a chaotic sea of scattered dots, and at E = \
         1/6, the energy of the saddle points of the potential, almost all tori are gone.";

catalogue_static! {
    /// The catalogue entry of [`HenonHeilesSystem`].
    pub static HENON_HEILES_ENTRY: SystemEntry = SystemEntry {
        name: "henon-heiles",
        python: Some("HenonHeilesSystem"),
        summary: "Henon-Heiles H = |p|^2/2 + (x^2 + y^2)/2 + x^2 y - y^3/3 (HenonHeilesSystem)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Fixed(2),
                D::demo_vector(&[0.0, 0.3]),
                "",
                "initial position (x, y)",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::Fixed(2),
                D::demo_vector(&[0.3, 0.0]),
                "",
                "initial momentum (p_x, p_y)",
            )
            .initial_state(),
        ],
        separable: true,
        taylor_form: true,
        default_method: Method::Yoshida4,
        note: Some("orbits are bounded for E < 1/6"),
        physics: Some(HENON_HEILES_PHYSICS),
        presentation: Presentation {
            title: "Hénon–Heiles",
            symbols: &["x", "y"],
            time_unit: "",
            state_units: None,
            drawing: Drawing::Orbit {
                central_body: false,
                ground: false,
            },
            pace: Pace::Own,
            section_first: true,
            energy_conserved: true,
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(HenonHeilesSystem::new(
                v.vector("q0")?,
                v.vector("p0")?,
            )?)))
        },
    };
}
