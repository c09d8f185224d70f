//! An ensemble of independent pendulums: Liouville's theorem made visible.
//!
//! ```text
//! H = sum_i [ p_i^2 / 2 - (g/l) cos q_i ],   i = 1..N
//! ```
//!
//! The pendulums do not interact; integrating them as one `N`-degree-of-freedom separable
//! system evolves a whole cloud of phase points with one call. Each particle keeps its own
//! energy `H_i`, and the phase-space area occupied by the cloud is invariant (Liouville) even as
//! the patch shears into a filament; [`PendulumSwarm::phase_space_area`] measures it by the
//! convex hull (A. M. Andrew, Inf. Process. Lett. 9 (1979) 216–219, monotone chain), which is a
//! faithful proxy while the patch stays convex. Reference: V. I. Arnold, *Mathematical Methods
//! of Classical Mechanics* (2nd ed., 1989), §16.

use crate::classical::core::error::{check_finite_scalar, check_non_negative, check_positive};
use crate::classical::core::trig::{sin_into_scaled, sin_into_sum_cos, sum_cos};
use crate::classical::core::{check_items_fit, Error, Phase, Result, SimulationResult};
use crate::classical::integrators::Ensemble;
use crate::classical::integrators::{HamiltonianSystem, IntegrateOptions, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Hamiltonian};

/// `N` decoupled pendulums `H_i = p_i^2/2 - (g/l) cos q_i`, state `[q_1..q_N, p_1..p_N]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::PendulumSwarm;
/// use physicskit::classical::{HamiltonianSystem, Method};
///
/// let mut swarm = PendulumSwarm::from_box(1.0, 0.0, 0.05, 0.05, 200, 1.0, 7).unwrap();
/// let a0 = swarm.phase_space_area(swarm.q(), swarm.p()).unwrap();
/// swarm.integrate((0.0, 1.0), 1e-2, Method::Yoshida4).unwrap();
/// let a1 = swarm.phase_space_area(swarm.q(), swarm.p()).unwrap();
/// assert!((a1 / a0 - 1.0).abs() < 0.05);
/// ```
#[derive(Debug, Clone)]
pub struct PendulumSwarm {
    phase: Phase,
    n: usize,
    g_over_l: f64,
}

/// Bytes [`PendulumSwarm::from_box`] allocates per pendulum: the drawn `q0`, `p0` and the
/// state `[q, p]` they are copied into.
const SWARM_BYTES_PER_MEMBER: usize = 4 * 8;

/// SplitMix64 (G. L. Steele, D. Lea and C. H. Flood, OOPSLA 2014): a tiny generator with a
/// fixed, documented output stream, so a seed reproduces the same swarm on every platform and
/// every version of physicskit.
struct SplitMix64(u64);

/// Swarms of at least this many pendulums run in parallel (two chunks' worth: below that one
/// core does the work as fast).
pub const PARALLEL_MEMBERS: usize = 2 * crate::classical::integrators::ENSEMBLE_CHUNK;

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` from the top 53 bits.
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

impl PendulumSwarm {
    /// A swarm with angles `q0` and momenta `p0` (one entry per pendulum).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an empty swarm or `g_over_l <= 0`;
    /// [`Error::DimensionMismatch`] if `p0` and `q0` differ in length; [`Error::NonFinite`]
    /// for NaN or infinity; [`Error::TooLarge`] if the state would not fit in memory.
    pub fn new(q0: &[f64], p0: &[f64], g_over_l: f64) -> Result<Self> {
        if q0.is_empty() {
            return Err(Error::invalid(
                "n",
                0.0,
                "the swarm needs at least one pendulum",
            ));
        }
        // The state [q, p] is a copy of the two slices.
        check_items_fit("n", q0.len(), 2 * 8)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            n: q0.len(),
            g_over_l: check_positive("g_over_l", g_over_l)?,
        })
    }

    /// `n` phase points drawn uniformly from the box `[q_center -/+ dq/2] x [p_center -/+ dp/2]`.
    ///
    /// The same `seed` always gives the same swarm (the generator is SplitMix64 with a fixed
    /// stream: the first `n` draws give the angles, the next `n` the momenta).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for non-finite centres, `dq < 0` or `dp < 0`, `n < 1` or
    /// `g_over_l <= 0`; [`Error::TooLarge`] if `n` pendulums would not fit in memory (checked
    /// before allocating).
    pub fn from_box(
        q_center: f64,
        p_center: f64,
        dq: f64,
        dp: f64,
        n: usize,
        g_over_l: f64,
        seed: u64,
    ) -> Result<Self> {
        let q_center = check_finite_scalar("q_center", q_center)?;
        let p_center = check_finite_scalar("p_center", p_center)?;
        let dq = check_non_negative("dq", dq)?;
        let dp = check_non_negative("dp", dp)?;
        if n < 1 {
            return Err(Error::invalid(
                "n",
                0.0,
                "the swarm needs at least one pendulum",
            ));
        }
        check_items_fit("n", n, SWARM_BYTES_PER_MEMBER)?;
        let mut rng = SplitMix64(seed);
        let q0: Vec<f64> = (0..n)
            .map(|_| q_center + (rng.next_f64() - 0.5) * dq)
            .collect();
        let p0: Vec<f64> = (0..n)
            .map(|_| p_center + (rng.next_f64() - 0.5) * dp)
            .collect();
        Self::new(&q0, &p0, g_over_l)
    }

    /// Number of pendulums.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The shared ratio `g/l`.
    pub fn g_over_l(&self) -> f64 {
        self.g_over_l
    }

    fn check_pair(&self, q: &[f64], p: &[f64]) -> Result<()> {
        crate::classical::core::error::check_vector("q", q, self.n)?;
        crate::classical::core::error::check_vector("p", p, self.n)
    }

    /// Energy `H_i = p_i^2/2 - (g/l) cos q_i` of each pendulum (conserved one by one).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` and `p` have one entry per pendulum;
    /// [`Error::NonFinite`] for NaN or infinity.
    pub fn per_particle_energy(&self, q: &[f64], p: &[f64]) -> Result<Vec<f64>> {
        self.check_pair(q, p)?;
        Ok(q.iter()
            .zip(p)
            .map(|(&qi, &pi)| 0.5 * pi * pi - self.g_over_l * qi.cos())
            .collect())
    }

    /// Upper branch `p = 2 sqrt(g/l) cos(q/2)` of the separatrix, the orbit of energy `g/l`
    /// (the unstable equilibrium's) between libration and rotation, at `|q| <= pi`; the lower
    /// branch is its negative. From `p^2/2 - (g/l) cos q = g/l` and `1 + cos q = 2 cos^2(q/2)`.
    pub fn separatrix_momentum(&self, q: f64) -> f64 {
        2.0 * self.g_over_l.sqrt() * (0.5 * q).cos()
    }

    /// Area of the convex hull of the `(q_i, p_i)` cloud (Andrew's monotone chain,
    /// `O(N log N)`); zero for collinear points.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] or [`Error::NonFinite`] for bad `q`, `p`;
    /// [`Error::InvalidParameter`] for fewer than three points, which enclose no area.
    pub fn phase_space_area(&self, q: &[f64], p: &[f64]) -> Result<f64> {
        self.check_pair(q, p)?;
        convex_hull_area(q, p)
    }
}

/// Area enclosed by the closed polygon through `(x_i, y_i)` in order (shoelace formula).
///
/// For a swarm seeded on the boundary of a phase-space patch this is the area Liouville's
/// theorem conserves exactly, while the convex hull ([`convex_hull_area`]) grows once the
/// patch curls into a filament.
///
/// # Errors
/// [`Error::DimensionMismatch`] if the slices differ in length; [`Error::NonFinite`] for NaN or
/// infinity.
pub fn polygon_area(x: &[f64], y: &[f64]) -> Result<f64> {
    crate::classical::core::error::check_vector("y", y, x.len())?;
    crate::classical::core::error::check_finite("x", x, 0.0)?;
    let n = x.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let j = (i + 1) % n;
            x[i] * y[j] - x[j] * y[i]
        })
        .sum();
    Ok(0.5 * twice.abs())
}

/// Area of the convex hull of the points `(x_i, y_i)` by Andrew's monotone chain.
///
/// # Errors
/// [`Error::InvalidParameter`] for fewer than three points; [`Error::DimensionMismatch`] if
/// the coordinate slices differ in length; [`Error::NonFinite`] for NaN or infinity.
pub fn convex_hull_area(x: &[f64], y: &[f64]) -> Result<f64> {
    crate::classical::core::error::check_finite("x", x, 0.0)?;
    crate::classical::core::error::check_vector("y", y, x.len())?;
    if x.len() < 3 {
        return Err(Error::invalid(
            "n",
            x.len() as f64,
            "a convex hull needs at least three points",
        ));
    }
    let mut pts: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    // All values are finite (checked above), so total_cmp is the usual order.
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut hull = half_hull(pts.iter().copied());
    hull.extend(half_hull(pts.iter().rev().copied()));
    // Shoelace formula as a fan of triangles from the first vertex, which keeps the
    // cancellation small for a small cloud far from the origin.
    let o = hull[0];
    let twice_area: f64 = hull
        .windows(2)
        .map(|w| (w[0].0 - o.0) * (w[1].1 - o.1) - (w[0].1 - o.1) * (w[1].0 - o.0))
        .sum();
    Ok(0.5 * twice_area.abs())
}

/// One monotone chain of the hull (lower for points sorted ascending, upper for descending),
/// without its last point, which starts the other chain.
fn half_hull(points: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut c: Vec<(f64, f64)> = Vec::new();
    for pt in points {
        // Keep only left turns: a point making a non-left turn is popped.
        while c.len() >= 2 && cross(c[c.len() - 2], c[c.len() - 1], pt) <= 0.0 {
            c.pop();
        }
        c.push(pt);
    }
    c.pop();
    c
}

impl HamiltonianSystem for PendulumSwarm {
    fn ndof(&self) -> usize {
        self.n
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        let g = -self.g_over_l;
        g * sum_cos(q)
    }
    /// `F_i = -(g/l) sin q_i`, with the vectorized slice sine (1-ulp class, see
    /// [`trig`](crate::classical::core::trig)).
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        sin_into_scaled(q, out, -self.g_over_l);
        Ok(())
    }
    /// The force and `-(g/l) sum cos q_i` from one pass of reductions.
    #[inline]
    fn force_and_potential(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        let g = -self.g_over_l;
        let cos_sum = sin_into_sum_cos(q, out, g);
        Ok(Some(g * cos_sum))
    }
    /// Swarms of at least [`PARALLEL_MEMBERS`] pendulums are integrated on all cores with
    /// [`integrate_ensemble`](crate::classical::integrators::integrate_ensemble): fixed chunks, the same
    /// result on any number of threads (bit-identical to this serial path for the explicit
    /// methods).
    fn integrate_with(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        options: IntegrateOptions<'_>,
    ) -> Result<SimulationResult> {
        if self.n >= PARALLEL_MEMBERS {
            crate::classical::integrators::integrate_ensemble(self, t_span, dt, method, options)
        } else {
            crate::classical::integrators::driver::integrate_hamiltonian(
                self, t_span, dt, method, options,
            )
        }
    }

    /// Diagonal `-(g/l) cos q_i`, written as a dense `N x N` matrix (used only when the
    /// implicit-midpoint fixed point fails to contract, and only for swarms small enough for a
    /// dense Newton solve).
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let n = self.n;
        out.iter_mut().for_each(|v| *v = 0.0);
        for (i, qi) in q.iter().enumerate() {
            out[i * n + i] = -self.g_over_l * qi.cos();
        }
        Some(Ok(()))
    }
}

crate::impl_separable_dynamics!(PendulumSwarm);

impl Ensemble for PendulumSwarm {
    /// The pendulums `start..start + len`, at the swarm's clock.
    fn members(&self, start: usize, len: usize) -> Result<Self> {
        let end = start
            .checked_add(len)
            .filter(|&e| e <= self.n && len > 0)
            .ok_or_else(|| Error::invalid("len", len as f64, "member range out of bounds"))?;
        let (q, p) = self.phase.state().split_at(self.n);
        let mut sub = Self::new(&q[start..end], &p[start..end], self.g_over_l)?;
        sub.phase.set_t(self.phase.t())?;
        Ok(sub)
    }
}

impl Capabilities for PendulumSwarm {
    fn per_particle_energy(&self, q: &[f64], p: &[f64]) -> Option<Result<Vec<f64>>> {
        Some(PendulumSwarm::per_particle_energy(self, q, p))
    }
    fn phase_space_area(&self, q: &[f64], p: &[f64]) -> Option<Result<f64>> {
        Some(PendulumSwarm::phase_space_area(self, q, p))
    }
    fn separatrix_energies(&self) -> Option<Vec<f64>> {
        // Each pendulum's one saddle, inverted at rest: H_i(pi, 0) = g/l.
        Some(vec![self.g_over_l])
    }
}

const G_OVER_L: P = P::scalar(
    "g_over_l",
    D::scalar(1.0),
    "1/s^2",
    Range::POSITIVE,
    "g / l",
);

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const SWARM_PHYSICS: &str =
    "A cloud of identical, independent pendulums starts as a small rectangle in phase \
         space (angle q, momentum p). Near the separatrix, the boundary between swinging and \
         whirling motion, the swing period depends strongly on the energy, so the patch is \
         sheared and wound into a long thin filament; yet by Liouville's theorem the \
         Hamiltonian flow preserves phase-space area, so the area enclosed by the patch's \
         boundary stays at its initial value.";

/// How both pendulum-swarm entries are shown (the second with its own title).
const SWARM_PRESENTATION: Presentation = Presentation {
    title: "Pendulum swarm",
    symbols: &["\\theta"],
    time_unit: "s",
    state_units: None,
    drawing: Drawing::Swarm,
    pace: Pace::Own,
    section_first: false,
    energy_conserved: true,
};

catalogue_static! {
    /// The catalogue entry of [`PendulumSwarm::new`].
    pub static SWARM_STATE_ENTRY: SystemEntry = SystemEntry {
        name: "pendulum-swarm-state",
        python: Some("PendulumSwarm"),
        summary: "independent pendulums from explicit angles and momenta (PendulumSwarm::new)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Any,
                D::demo_vector(&[1.0, 1.05, 1.0, 1.05]),
                "rad",
                "initial angles",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::SameAs("q0"),
                D::demo_vector(&[0.0, 0.0, 0.05, 0.05]),
                "rad/s",
                "initial momenta, one per angle",
            )
            .initial_state(),
            G_OVER_L,
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(SWARM_PHYSICS),
        presentation: Presentation {
            title: "Pendulum swarm (from a state)",
            ..SWARM_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(PendulumSwarm::new(
                v.vector("q0")?,
                v.vector("p0")?,
                v.scalar("g_over_l")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`PendulumSwarm::from_box`].
    pub static SWARM_ENTRY: SystemEntry = SystemEntry {
        name: "pendulum-swarm",
        python: Some("PendulumSwarm.from_box"),
        summary: "n independent pendulums filling a box in phase space (PendulumSwarm::from_box)",
        family: Family::Hamiltonian,
        params: &[
            P::scalar(
                "q_center",
                D::demo_scalar(1.0),
                "rad",
                Range::ANY,
                "centre angle of the box",
            ),
            P::scalar(
                "p_center",
                D::demo_scalar(0.0),
                "rad/s",
                Range::ANY,
                "centre momentum of the box",
            ),
            P::scalar(
                "dq",
                D::demo_scalar(0.05),
                "rad",
                Range::NON_NEGATIVE,
                "box width in q",
            ),
            P::scalar(
                "dp",
                D::demo_scalar(0.05),
                "rad/s",
                Range::NON_NEGATIVE,
                "box height in p",
            ),
            P::integer(
                "n",
                D::integer(1000),
                Range::at_least(1.0),
                "number of pendulums",
            ),
            G_OVER_L,
            P::integer(
                "seed",
                D::integer(0),
                Range::NON_NEGATIVE,
                "seed of the reproducible uniform fill",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: Some("q and p have one column per pendulum; use --stride for long runs"),
        physics: Some(SWARM_PHYSICS),
        // Filled from a box, not from a state: the state's units said here.
        presentation: Presentation {
            state_units: Some(("rad", "rad/s")),
            ..SWARM_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(PendulumSwarm::from_box(
                v.scalar("q_center")?,
                v.scalar("p_center")?,
                v.scalar("dq")?,
                v.scalar("dp")?,
                v.count("n")?,
                v.scalar("g_over_l")?,
                v.count("seed")? as u64,
            )?)))
        },
    };
}

#[cfg(test)]
mod polygon_tests {
    use super::polygon_area;

    #[test]
    fn regular_polygon_area_matches_its_closed_form() {
        // A regular n-gon inscribed in a circle of radius r has area (n/2) r^2 sin(2 pi / n).
        let (n, r) = (97, 1.7);
        let angle = |i: usize| std::f64::consts::TAU * i as f64 / n as f64;
        let x: Vec<f64> = (0..n).map(|i| r * angle(i).cos()).collect();
        let y: Vec<f64> = (0..n).map(|i| r * angle(i).sin()).collect();
        let exact = 0.5 * n as f64 * r * r * (std::f64::consts::TAU / n as f64).sin();
        // Sum of 97 products of size ~r^2 sin(2pi/n): rounding ~1e-15 relative.
        assert!((polygon_area(&x, &y).unwrap() - exact).abs() < 1e-13 * exact);
        // Orientation does not matter; a length mismatch is an error.
        let (xr, yr): (Vec<f64>, Vec<f64>) = (
            x.iter().rev().copied().collect(),
            y.iter().rev().copied().collect(),
        );
        assert!((polygon_area(&xr, &yr).unwrap() - exact).abs() < 1e-13 * exact);
        assert!(polygon_area(&x, &y[1..]).is_err());
    }
}
