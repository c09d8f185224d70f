//! The planar two-body (Kepler) problem with optional non-Newtonian perturbations.
//!
//! ```text
//! H(q, p) = |p|^2 / (2 mu) + V(r_s),   r_s = sqrt(|q|^2 + softening^2)
//! V(r)    = -k / r + c_eps / r^(1 + eps) + c_pn / r^3
//! ```
//!
//! `q` is the relative position, `p` the reduced-mass momentum, `k = G M mu` the coupling.
//! Plummer softening replaces `r` by `r_s` in every term (H. C. Plummer, MNRAS 71 (1911) 460),
//! so `softening > 0` removes the singular force at the origin; `softening = 0` is the exact
//! point-mass problem. The `c_eps` term with `eps = 0` is an extra inverse-square potential;
//! the `c_pn / r^3` term is the effective post-Newtonian correction whose orbit average makes
//! the perihelion precess (`c_pn < 0`, attractive, gives prograde precession as in general
//! relativity).
//!
//! Without perturbations (`c_eps = c_pn = softening = 0`) the energy, the angular momentum
//! `L = x p_y - y p_x` and the Laplace–Runge–Lenz vector `A = p x L - mu k r_hat` (pointing to
//! perihelion, `|A| = mu k e`) are conserved, and the orbit of semi-major axis `a` has period
//! `T = 2 pi sqrt(mu a^3 / k)`. Reference: H. Goldstein, C. Poole and J. Safko, *Classical
//! Mechanics* (3rd ed., 2002), §3.7–3.9.

use crate::classical::core::error::check_len;
use crate::classical::core::error::{check_finite_scalar, check_non_negative, check_positive};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::lanes::{LanesForce, Real, SplittingLanes};
use crate::classical::integrators::{HamiltonianSystem, MassInv, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry, Values,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{fill, Capabilities, Hamiltonian};

/// The optional perturbations of [`KeplerSystem`]; `Default` is the pure two-body problem.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KeplerPerturbations {
    /// Exponent of the `c_eps / r^(1 + eps)` term.
    pub eps: f64,
    /// Coefficient of the `c_eps / r^(1 + eps)` term.
    pub c_eps: f64,
    /// Coefficient of the post-Newtonian `c_pn / r^3` term.
    pub c_pn: f64,
    /// Plummer softening length (`>= 0`).
    pub softening: f64,
}

impl KeplerPerturbations {
    /// No perturbation: the exact point-mass Kepler problem.
    pub fn none() -> Self {
        Self::default()
    }

    /// With the `c_eps / r^(1 + eps)` term.
    pub fn with_power_law(self, eps: f64, c_eps: f64) -> Self {
        Self { eps, c_eps, ..self }
    }

    /// With the `c_pn / r^3` term.
    pub fn with_post_newtonian(self, c_pn: f64) -> Self {
        Self { c_pn, ..self }
    }

    /// With Plummer softening.
    pub fn with_softening(self, softening: f64) -> Self {
        Self { softening, ..self }
    }

    fn validate(self) -> Result<Self> {
        check_finite_scalar("eps", self.eps)?;
        check_finite_scalar("c_eps", self.c_eps)?;
        check_finite_scalar("c_pn", self.c_pn)?;
        check_non_negative("softening", self.softening)?;
        Ok(self)
    }
}

/// Planar Kepler problem `H = |p|^2/(2 mu) - k/r_s + c_eps/r_s^(1+eps) + c_pn/r_s^3`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{KeplerPerturbations, KeplerSystem};
/// use physicskit::classical::{HamiltonianSystem, Method};
///
/// let mut orbit =
///     KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())
///         .unwrap();
/// let a0 = orbit.lrl_vector(orbit.q(), orbit.p());
/// orbit.integrate((0.0, 6.283), 1e-3, Method::Yoshida4).unwrap(); // about one orbit
/// let a1 = orbit.lrl_vector(orbit.q(), orbit.p());
/// assert!((a1[0] - a0[0]).abs() < 1e-9 && (a1[1] - a0[1]).abs() < 1e-9);
/// ```
#[derive(Debug, Clone)]
pub struct KeplerSystem {
    phase: Phase,
    k: f64,
    mu: f64,
    mu_inv: f64,
    pert: KeplerPerturbations,
}

impl KeplerSystem {
    /// A Kepler system at relative position `q0 = (x, y)` with momentum `p0`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q0` and `p0` have length 2; [`Error::NonFinite`]
    /// for NaN or infinity; [`Error::InvalidParameter`] for `k <= 0`, `mu <= 0`, a non-finite
    /// `eps`, `c_eps` or `c_pn`, `softening < 0`, or `q0` at the origin without softening
    /// (where the potential is singular).
    pub fn new(
        q0: &[f64],
        p0: &[f64],
        k: f64,
        mu: f64,
        perturbations: KeplerPerturbations,
    ) -> Result<Self> {
        crate::classical::core::error::check_vector("q0", q0, 2)?;
        crate::classical::core::error::check_vector("p0", p0, 2)?;
        let k = check_positive("k", k)?;
        let mu = check_positive("mu", mu)?;
        let pert = perturbations.validate()?;
        let r2 = q0[0] * q0[0] + q0[1] * q0[1];
        if r2 + pert.softening * pert.softening <= 0.0 {
            return Err(Error::invalid(
                "q0",
                r2.sqrt(),
                "the potential is singular at r = 0 without softening",
            ));
        }
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            k,
            mu,
            mu_inv: 1.0 / mu,
            pert,
        })
    }

    /// A system starting at perihelion of the two-body orbit with semi-major axis `a` and
    /// eccentricity `e`: `q0 = (a (1 - e), 0)`, `p0 = (0, sqrt(mu k (1 + e) / (a (1 - e))))`
    /// (vis-viva). The perturbations are added on top, so with them the orbit is only
    /// approximately the one described by `(a, e)`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `a > 0` and `0 <= e < 1` (bound orbits only), and
    /// the errors of [`KeplerSystem::new`].
    pub fn from_orbital_elements(
        a: f64,
        e: f64,
        k: f64,
        mu: f64,
        perturbations: KeplerPerturbations,
    ) -> Result<Self> {
        let a = check_positive("a", a)?;
        if !(e.is_finite() && (0.0..1.0).contains(&e)) {
            return Err(Error::invalid(
                "e",
                e,
                "eccentricity must satisfy 0 <= e < 1 (bound orbit)",
            ));
        }
        let k = check_positive("k", k)?;
        let mu = check_positive("mu", mu)?;
        let r_peri = a * (1.0 - e);
        let p_peri = (mu * k * (1.0 + e) / r_peri).sqrt();
        Self::new(&[r_peri, 0.0], &[0.0, p_peri], k, mu, perturbations)
    }

    /// Coupling `k = G M mu`.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// Reduced mass `mu`.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The perturbation parameters.
    pub fn perturbations(&self) -> KeplerPerturbations {
        self.pert
    }

    /// Out-of-plane angular momentum `L = x p_y - y p_x`. `q` and `p` must have length 2
    /// (use `sys.q()`, `sys.p()` for the current state); extra entries are ignored.
    pub fn angular_momentum(&self, q: &[f64], p: &[f64]) -> f64 {
        q[0] * p[1] - q[1] * p[0]
    }

    /// Laplace–Runge–Lenz vector `A = p x L - mu k r_hat` (planar form,
    /// `A = (p_y L - mu k x/r, -p_x L - mu k y/r)`, with the unsoftened `r = |q|`). Conserved
    /// and pointing at perihelion for the unperturbed problem; it rotates at the precession
    /// rate when `c_eps` or `c_pn` is nonzero. At `q = 0` the radial unit vector is undefined
    /// and `r_hat` is taken as zero.
    pub fn lrl_vector(&self, q: &[f64], p: &[f64]) -> [f64; 2] {
        let l = self.angular_momentum(q, p);
        let r = q[0].hypot(q[1]);
        let (rx, ry) = if r > 0.0 {
            (q[0] / r, q[1] / r)
        } else {
            (0.0, 0.0)
        };
        let mk = self.mu * self.k;
        [p[1] * l - mk * rx, -p[0] * l - mk * ry]
    }

    /// `V(r_s)` and its first two derivatives with respect to `r_s`, for any [`Real`] (`f64`,
    /// or members in SIMD lanes).
    #[inline(always)]
    fn radial<R: Real>(&self, s: R) -> (R, R, R) {
        let KeplerPerturbations {
            eps, c_eps, c_pn, ..
        } = self.pert;
        let inv = R::splat(1.0) / s;
        let inv2 = inv * inv;
        let mut v = inv * -self.k;
        let mut dv = inv2 * self.k;
        let mut d2v = inv2 * (-2.0 * self.k) * inv;
        if c_eps != 0.0 {
            let t = s.powf(-(1.0 + eps)) * c_eps;
            v += t;
            dv -= t * (1.0 + eps) * inv;
            d2v += t * ((1.0 + eps) * (2.0 + eps)) * inv2;
        }
        if c_pn != 0.0 {
            let t = inv2 * c_pn * inv;
            v += t;
            dv -= t * 3.0 * inv;
            d2v += t * 12.0 * inv2;
        }
        (v, dv, d2v)
    }

    #[inline(always)]
    fn softened_radius<R: Real>(&self, q: &[R]) -> R {
        let s = self.pert.softening;
        (q[0] * q[0] + q[1] * q[1] + s * s).sqrt()
    }

    /// `V(r_s)` for any [`Real`].
    #[inline(always)]
    fn potential<R: Real>(&self, q: &[R]) -> R {
        self.radial(self.softened_radius(q)).0
    }

    /// The force into `out` and `V(r_s)`, from the same radial evaluation (no second square
    /// root), for any [`Real`].
    #[inline(always)]
    fn force_and_potential_of<R: Real>(&self, q: &[R], out: &mut [R]) -> R {
        let s = self.softened_radius(q);
        let (v, dv, _) = self.radial(s);
        // Times the reciprocal `radial` already formed (the compiler merges the two), not a
        // second division: a division's latency was a sixth of a Kepler step.
        let f = -dv * (R::splat(1.0) / s);
        out[0] = f * q[0];
        out[1] = f * q[1];
        v
    }
}

impl HamiltonianSystem for KeplerSystem {
    fn ndof(&self) -> usize {
        2
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.potential(q)
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.mu_inv)
    }
    /// `F = -V'(r_s) q / r_s` (the potential [`force_and_potential`](Self::force_and_potential)
    /// also returns is dead code here, removed once inlined).
    #[inline]
    fn force(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        self.force_and_potential(q, t, out).map(|_| ())
    }
    /// The force and `V(r_s)` from the same radial evaluation (no second square root).
    #[inline]
    fn force_and_potential(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        Ok(Some(self.force_and_potential_of(q, out)))
    }
    /// `dF_i/dq_j = f delta_ij + f'(r_s) q_i q_j / r_s` with `f = -V'/r_s`.
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let s = self.softened_radius(q);
        let (_, dv, d2v) = self.radial(s);
        let f = -dv / s;
        let df = (-d2v + dv / s) / s;
        for i in 0..2 {
            for j in 0..2 {
                let diag = if i == j { f } else { 0.0 };
                out[2 * i + j] = diag + df * q[i] * q[j] / s;
            }
        }
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes.
impl LanesForce for KeplerSystem {
    const NDOF: usize = 2;

    #[inline(always)]
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        self.force_and_potential_of(q, out);
    }

    /// Equal coupling, mass and perturbations, bit for bit.
    fn same_force(&self, other: &Self) -> bool {
        let bits = |s: &Self| {
            let p = s.pert;
            [s.k, s.mu, p.eps, p.c_eps, p.c_pn, p.softening].map(f64::to_bits)
        };
        bits(self) == bits(other)
    }

    /// `powf` per lane where the power-law perturbation is on.
    fn calls_per_lane(&self) -> bool {
        self.pert.c_eps != 0.0
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(self.potential(q))
    }
}

crate::impl_separable_dynamics!(KeplerSystem, taylor: crate::classical::symbolic::traced_hamiltonian_taylor_field, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

/// `H` written once over any number type, for the system's Taylor form
/// ([`traced_hamiltonian_taylor_field`](crate::classical::symbolic::traced_hamiltonian_taylor_field)):
/// the terms of the force's `radial` at the softened radius; a perturbation whose
/// coefficient is zero is left out, as there (a branch on a parameter, which a trace follows).
impl crate::classical::symbolic::TracedHamiltonian for KeplerSystem {
    fn ndof(&self) -> usize {
        2
    }
    fn hamiltonian<D: crate::classical::lagrangian::Scalar>(&self, q: &[D], p: &[D], _t: D) -> D {
        let KeplerPerturbations {
            eps,
            c_eps,
            c_pn,
            softening,
        } = self.pert;
        let mut r2 = q[0] * q[0] + q[1] * q[1];
        if softening != 0.0 {
            r2 += softening * softening;
        }
        let s = r2.sqrt();
        let inv = s.recip();
        let mut v = inv * (-self.k);
        if c_eps != 0.0 {
            v += s.powf(-(1.0 + eps)) * c_eps;
        }
        if c_pn != 0.0 {
            v += inv.powi(3) * c_pn;
        }
        (p[0] * p[0] + p[1] * p[1]) * (0.5 * self.mu_inv) + v
    }
}

impl Capabilities for KeplerSystem {
    fn positions_into(&self, q: &[f64], out: &mut Vec<f64>) -> Option<Result<()>> {
        // The body relative to the force centre.
        Some(check_len("q", q, 2).map(|()| fill(out, q)))
    }
    fn lrl_vector(&self, q: &[f64], p: &[f64]) -> Option<Result<[f64; 2]>> {
        Some(check_qp(q, p).map(|()| KeplerSystem::lrl_vector(self, q, p)))
    }
    fn angular_momentum(&self, q: &[f64], p: &[f64]) -> Option<Result<f64>> {
        Some(check_qp(q, p).map(|()| KeplerSystem::angular_momentum(self, q, p)))
    }
}

fn check_qp(q: &[f64], p: &[f64]) -> Result<()> {
    check_len("q", q, 2)?;
    check_len("p", p, 2)
}

/// The perturbation parameters, shared by both Kepler entries (`**kwargs` of
/// `from_orbital_elements` in the spec).
const PERTURBATION_PARAMS: [P; 4] = [
    P::scalar(
        "eps",
        D::scalar(0.0),
        "",
        Range::ANY,
        "exponent of the c_eps / r^(1+eps) term",
    ),
    P::scalar(
        "c_eps",
        D::scalar(0.0),
        "",
        Range::ANY,
        "coefficient of the c_eps / r^(1+eps) term",
    ),
    P::scalar(
        "c_pn",
        D::scalar(0.0),
        "",
        Range::ANY,
        "coefficient of the post-Newtonian c_pn / r^3 term",
    ),
    P::scalar(
        "softening",
        D::scalar(0.0),
        "length",
        Range::NON_NEGATIVE,
        "Plummer softening length",
    ),
];

fn perturbations(v: &Values) -> Result<KeplerPerturbations> {
    Ok(KeplerPerturbations::none()
        .with_power_law(v.scalar("eps")?, v.scalar("c_eps")?)
        .with_post_newtonian(v.scalar("c_pn")?)
        .with_softening(v.scalar("softening")?))
}

const COUPLING: P = P::scalar(
    "k",
    D::scalar(1.0),
    "",
    Range::POSITIVE,
    "coupling k = G M mu",
);
const REDUCED_MASS: P = P::scalar(
    "mu",
    D::scalar(1.0),
    "mass",
    Range::POSITIVE,
    "reduced mass",
);

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const KEPLER_PHYSICS: &str =
    "A planet in an inverse-square force traces the same closed ellipse for ever: besides \
         energy and angular momentum, the Laplace–Runge–Lenz vector, which points at the \
         perihelion, is conserved, a symmetry special to 1/r². Adding a small attractive 1/r³ \
         term, the effective post-Newtonian correction of general relativity, breaks that \
         symmetry: the ellipse turns a little every orbit into a rosette, and the LRL \
         vector's angle grows at a steady rate, the perihelion precession (43 arc-seconds per \
         century for Mercury).";

/// How both Kepler entries are shown (the second with its own title).
const KEPLER_PRESENTATION: Presentation = Presentation {
    title: "Kepler problem",
    symbols: &["x", "y"],
    time_unit: "time",
    state_units: None,
    drawing: Drawing::Orbit {
        central_body: true,
        ground: false,
    },
    pace: Pace::Own,
    section_first: false,
    energy_conserved: true,
};

catalogue_static! {
    /// The catalogue entry of [`KeplerSystem::new`].
    pub static KEPLER_STATE_ENTRY: SystemEntry = SystemEntry {
        name: "kepler-state",
        python: Some("KeplerSystem"),
        summary: "planar Kepler problem from a position and momentum (KeplerSystem::new)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Fixed(2),
                D::demo_vector(&[1.0, 0.0]),
                "length",
                "initial relative position (x, y)",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::Fixed(2),
                D::demo_vector(&[0.0, 1.0]),
                "mass length/time",
                "initial momentum (p_x, p_y)",
            )
            .initial_state(),
            COUPLING,
            REDUCED_MASS,
            PERTURBATION_PARAMS[0],
            PERTURBATION_PARAMS[1],
            PERTURBATION_PARAMS[2],
            PERTURBATION_PARAMS[3],
        ],
        separable: true,
        taylor_form: true,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(KEPLER_PHYSICS),
        presentation: Presentation {
            title: "Kepler problem (from a state)",
            ..KEPLER_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(KeplerSystem::new(
                v.vector("q0")?,
                v.vector("p0")?,
                v.scalar("k")?,
                v.scalar("mu")?,
                perturbations(v)?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`KeplerSystem::from_orbital_elements`].
    pub static KEPLER_ENTRY: SystemEntry = SystemEntry {
        name: "kepler",
        python: Some("KeplerSystem.from_orbital_elements"),
        summary: "planar Kepler orbit from its elements, starting at perihelion \
                  (KeplerSystem::from_orbital_elements)",
        family: Family::Hamiltonian,
        params: &[
            P::scalar(
                "a",
                D::demo_scalar(1.0),
                "length",
                Range::POSITIVE,
                "semi-major axis",
            ),
            P::scalar(
                "e",
                D::demo_scalar(0.5),
                "",
                Range::half_open(0.0, 1.0),
                "eccentricity (bound orbits)",
            ),
            COUPLING,
            REDUCED_MASS,
            PERTURBATION_PARAMS[0],
            PERTURBATION_PARAMS[1],
            PERTURBATION_PARAMS[2],
            PERTURBATION_PARAMS[3],
        ],
        separable: true,
        taylor_form: true,
        default_method: Method::Yoshida4,
        note: Some("period 2 pi sqrt(mu a^3 / k); c_pn != 0 makes the orbit precess"),
        physics: Some(KEPLER_PHYSICS),
        // Started from orbital elements, not from a state: the state's units said here, as the
        // entry started from a state has them.
        presentation: Presentation {
            state_units: Some(("length", "mass length/time")),
            ..KEPLER_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(KeplerSystem::from_orbital_elements(
                v.scalar("a")?,
                v.scalar("e")?,
                v.scalar("k")?,
                v.scalar("mu")?,
                perturbations(v)?,
            )?)))
        },
    };
}
