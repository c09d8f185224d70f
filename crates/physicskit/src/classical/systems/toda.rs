//! [`TodaLattice`]: the periodic Toda lattice, `n` unit masses on a ring joined by
//! exponential springs, the classic completely integrable many-body system.
//!
//! ```text
//! H = sum_i p_i^2/2 + (a/b) sum_i exp(-b r_i),   r_i = q_{i+1} - q_i,   q_{n+1} = q_1
//! F_i = -dV/dq_i = a (exp(-b r_{i-1}) - exp(-b r_i))
//! ```
//!
//! The textbook potential `(a/b) exp(-b r) + a r` has a linear term that sums to
//! `a sum r_i = 0` on the ring, so it is left out. The bond potential `phi(r) = (a/b) e^{-b r}`
//! has `phi'' = a b e^{-b r}`: `a` and `b` set the stiffness `a b` of small oscillations and
//! `b` the anharmonicity (compression is stiff, stretching soft; `b -> 0` at fixed `a b` is the
//! harmonic ring). Both must be positive: `a, b < 0` is the same lattice mirrored
//! (`q -> -q`), and `a b < 0` would make every bond repulsive-concave with no equilibrium and
//! no real Lax matrix below.
//!
//! At least two particles: with `n = 1` the only bond joins the particle to itself
//! (`r = 0`), the potential is the constant `a/b` and nothing remains of the lattice.
//!
//! # Lax pair (Flaschka's variables for this normalization)
//!
//! With `Q = b q`, `tau = sqrt(a b) t` and `P = dQ/dtau = sqrt(b/a) p` the equations become
//! the standard Toda lattice `d^2 Q_i/dtau^2 = e^{-(Q_i - Q_{i-1})} - e^{-(Q_{i+1} - Q_i)}`.
//! Flaschka's variables `A_i = e^{-(Q_{i+1} - Q_i)/2} / 2`, `B_i = -P_i / 2` satisfy
//! `A_i' = A_i (B_{i+1} - B_i)`, `B_i' = 2 (A_i^2 - A_{i-1}^2)`, which is `L' = [M, L]` for
//! the periodic Jacobi matrix `L` (diagonal `B_i`, off-diagonal and corner `A_i`) and the
//! antisymmetric `M` (`A_i` above the diagonal, `-A_i` below, corners likewise): the flow is
//! isospectral, every eigenvalue of `L` is conserved. Scaling by `-2 sqrt(a/b)` (a constant)
//! and reversing time (`p -> -p`, a symmetry of `H`, which flips the sign of the diagonal)
//! keep the spectrum conserved and give the matrix this module uses, in momentum units:
//!
//! ```text
//! L_ii = p_i,   L_{i,i+1} = L_{i+1,i} = c_i = sqrt(a/b) exp(-b r_i / 2)   (indices mod n)
//! ```
//!
//! Its invariants: `tr L = sum p_i` (the total momentum) and
//! `tr L^2 = sum p_i^2 + 2 sum c_i^2 = sum p_i^2 + 2 (a/b) sum e^{-b r_i} = 2 H`.
//! For `n = 2` the corner and the off-diagonal are the same matrix element, which holds
//! `c_1 + c_2`; then `tr L^2 = 2 H + 4 c_1 c_2 = 2 H + 4 a/b` (as `r_1 + r_2 = 0`), still
//! conserved. [`TodaLattice::conserved_quantities`] returns the `n` eigenvalues in ascending
//! order (from nalgebra's symmetric eigensolver; they are real as `L` is symmetric).
//!
//! # Energy per particle
//!
//! [`TodaLattice::particle_energies`] gives each particle its kinetic energy and half of each
//! of its two bonds, `e_i = p_i^2/2 + (phi(r_{i-1}) + phi(r_i))/2`, so that `sum e_i = H`. At
//! rest in equilibrium every `e_i = a/b`. The eigenvalues stay fixed while the `e_i` slosh
//! around the ring: the energy moves, the `n` integrals do not.
//!
//! References: M. Toda, J. Phys. Soc. Jpn. 22 (1967) 431; H. Flaschka, Phys. Rev. B 9 (1974)
//! 1924 (the Lax pair); M. Hénon, Phys. Rev. B 9 (1974) 1921 (the integrals); M. Toda,
//! *Theory of Nonlinear Lattices*, 2nd ed. (Springer 1989), ch. 2–4.

use nalgebra::{DMatrix, SymmetricEigen};

use crate::classical::core::error::{check_positive, check_vector};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::lanes::{LanesForce, Real, SplittingLanes};
use crate::classical::integrators::{HamiltonianSystem, MassInv, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{
    Default as D, Family, Length, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Ends, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Hamiltonian};

/// The periodic Toda lattice `H = sum p_i^2/2 + (a/b) sum exp(-b (q_{i+1} - q_i))` (see the
/// module documentation). Unit masses; state `[q, p]`; default method `yoshida4`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::TodaLattice;
/// use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};
///
/// let mut toda = TodaLattice::new(&[0.0, 0.5, 0.0, -0.5], &[1.0, 0.0, -0.5, 0.0], 1.0, 1.0)
///     .unwrap();
/// let before = toda.conserved_quantities(None).unwrap();
/// // tr L^2 = 2 H.
/// let trace2: f64 = before.iter().map(|l| l * l).sum();
/// assert!((trace2 - 2.0 * toda.current_energy()).abs() < 1e-12);
/// toda.integrate((0.0, 10.0), 1e-3, Method::Yoshida4).unwrap();
/// let after = toda.conserved_quantities(None).unwrap();
/// for (x, y) in before.iter().zip(&after) {
///     assert!((x - y).abs() < 1e-10);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct TodaLattice {
    phase: Phase,
    a: f64,
    b: f64,
    /// `a / b`, the bond energy at zero stretch, formed once.
    a_over_b: f64,
}

impl TodaLattice {
    /// A ring of `n = q0.len() >= 2` particles at positions `q0` with momenta `p0`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n < 2` or `a`, `b` not finite and positive;
    /// [`Error::DimensionMismatch`] if `p0` differs in length from `q0`;
    /// [`Error::NonFinite`] for NaN or infinity in `q0` or `p0`.
    pub fn new(q0: &[f64], p0: &[f64], a: f64, b: f64) -> Result<Self> {
        let n = q0.len();
        if n < 2 {
            return Err(Error::invalid(
                "n",
                n as f64,
                "a periodic Toda lattice needs at least 2 particles (with 1 the only bond \
                 joins the particle to itself)",
            ));
        }
        check_vector("q0", q0, n)?;
        check_vector("p0", p0, n)?;
        let a = check_positive("a", a)?;
        let b = check_positive("b", b)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            a,
            b,
            a_over_b: a / b,
        })
    }

    /// Number of particles `n`.
    pub fn n(&self) -> usize {
        self.phase.len() / 2
    }

    /// Force scale `a` (the product `a b` is the small-oscillation stiffness).
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Decay rate `b` of the exponential bond.
    pub fn b(&self) -> f64 {
        self.b
    }

    /// `(q, p)` of `state`, or of the current state if `None`.
    fn halves<'s>(&'s self, state: Option<&'s [f64]>) -> Result<(&'s [f64], &'s [f64])> {
        let n = self.n();
        let state = state.unwrap_or(self.phase.state());
        check_vector("state", state, 2 * n)?;
        Ok(state.split_at(n))
    }

    /// Calls `site(i, e_left, e_right)` for every particle `i` with the exponentials
    /// `e^{-b r_{i-1}}` and `e^{-b r_i}` of its two bonds, and returns `sum_i e^{-b r_i}`
    /// (bonds `0..n-1` in order, the wrap-around bond `q_1 - q_n` last). One `exp` per bond;
    /// the force, its potential and the energies all use it, so they agree bit for bit. For
    /// any [`Real`] (`f64`, or members in SIMD lanes: std's `exp` per lane).
    #[inline(always)]
    fn sweep<R: Real>(&self, q: &[R], mut site: impl FnMut(usize, R, R)) -> R {
        let n = q.len();
        let b = -self.b;
        let wrap = ((q[0] - q[n - 1]) * b).exp();
        let mut left = wrap;
        let mut sum = R::splat(0.0);
        for i in 0..n - 1 {
            let right = ((q[i + 1] - q[i]) * b).exp();
            site(i, left, right);
            sum += right;
            left = right;
        }
        site(n - 1, left, wrap);
        sum + wrap
    }

    /// `V = (a/b) sum_i e^{-b r_i}` over the ring's bonds (no linear term: see the module
    /// docs), written once over any [`Real`]: the scalar `potential_energy` and the members'
    /// energies in lanes.
    #[inline(always)]
    fn potential<R: Real>(&self, q: &[R]) -> R {
        R::splat(self.a_over_b) * self.sweep(q, |_, _, _| {})
    }

    /// The Lax matrix `L` of `state = [q, p]` (the current state if `None`), row-major
    /// `n x n`: `L_ii = p_i`, `L_{i,i+1} = L_{i+1,i} = sqrt(a/b) exp(-b (q_{i+1} - q_i)/2)`
    /// with the corner `L_{1n} = L_{n1}` for the bond `q_1 - q_n`; for `n = 2` the two bonds
    /// share the one off-diagonal element, which holds their sum.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length `2 n`; [`Error::NonFinite`].
    pub fn lax_matrix(&self, state: Option<&[f64]>) -> Result<Vec<f64>> {
        let (q, p) = self.halves(state)?;
        let n = q.len();
        let (root, half_b) = (self.a_over_b.sqrt(), 0.5 * self.b);
        let mut l = vec![0.0; n * n];
        for (i, &pi) in p.iter().enumerate() {
            l[i * n + i] = pi;
        }
        for i in 0..n {
            let j = (i + 1) % n;
            let c = root * (-half_b * (q[j] - q[i])).exp();
            l[i * n + j] += c;
            l[j * n + i] += c;
        }
        Ok(l)
    }

    /// The `n` eigenvalues of the Lax matrix ([`lax_matrix`](Self::lax_matrix)) of `state`
    /// (the current state if `None`), ascending: the lattice's `n` independent integrals of
    /// motion, in momentum units. `sum = total momentum`, `sum of squares = 2 H` (`2 H + 4 a/b`
    /// for `n = 2`).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `state` has length `2 n`; [`Error::NonFinite`]
    /// for a non-finite state or a Lax matrix that overflows.
    pub fn conserved_quantities(&self, state: Option<&[f64]>) -> Result<Vec<f64>> {
        let n = self.n();
        let l = self.lax_matrix(state)?;
        // exp(-b r/2) overflows for stretches of the order of 1400/b: refuse rather than hand
        // the eigensolver infinities.
        if !l.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite {
                name: "Lax matrix".into(),
                t: self.phase.t(),
            });
        }
        let eigen = SymmetricEigen::new(DMatrix::from_row_slice(n, n, &l));
        let mut values: Vec<f64> = eigen.eigenvalues.iter().copied().collect();
        values.sort_by(f64::total_cmp);
        Ok(values)
    }

    /// Energy of each particle, `e_i = p_i^2/2 + (phi(r_{i-1}) + phi(r_i))/2` with
    /// `phi(r) = (a/b) e^{-b r}`, written into `out` (no allocation); `sum e_i = H`, and
    /// `e_i = a/b` at rest in equilibrium.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q`, `p` and `out` have length `n`;
    /// [`Error::NonFinite`] for NaN or infinity in `q` or `p`.
    pub fn particle_energies_into(&self, q: &[f64], p: &[f64], out: &mut [f64]) -> Result<()> {
        let n = self.n();
        check_vector("q", q, n)?;
        check_vector("p", p, n)?;
        if out.len() != n {
            return Err(Error::DimensionMismatch {
                name: "out".into(),
                expected: n,
                found: out.len(),
            });
        }
        let half = 0.5 * self.a_over_b;
        self.sweep(q, |i, left, right| {
            out[i] = 0.5 * p[i] * p[i] + half * (left + right);
        });
        Ok(())
    }

    /// [`particle_energies_into`](Self::particle_energies_into) of `state = [q, p]` (the
    /// current state if `None`), allocating the result.
    ///
    /// # Errors
    /// As [`particle_energies_into`](Self::particle_energies_into), for `state` of length
    /// `2 n`.
    pub fn particle_energies(&self, state: Option<&[f64]>) -> Result<Vec<f64>> {
        let (q, p) = self.halves(state)?;
        let mut out = vec![0.0; q.len()];
        self.particle_energies_into(q, p, &mut out)?;
        Ok(out)
    }
}

impl HamiltonianSystem for TodaLattice {
    fn ndof(&self) -> usize {
        self.n()
    }

    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.potential(q)
    }

    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(1.0)
    }

    /// `F_i = a (e^{-b r_{i-1}} - e^{-b r_i})`.
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        self.force_of(q, out);
        Ok(())
    }

    /// The force, and the potential from the same exponentials.
    #[inline]
    fn force_and_potential(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        let a = self.a;
        let sum = self.sweep(q, |i, left, right| out[i] = (left - right) * a);
        Ok(Some(self.a_over_b * sum))
    }

    /// `dF_i/dq_i = -a b (e^{-b r_{i-1}} + e^{-b r_i})`, `dF_i/dq_{i+1} = a b e^{-b r_i}`
    /// (symmetric, periodic; for `n = 2` both bonds land on the one off-diagonal pair).
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let n = q.len();
        let ab = self.a * self.b;
        out.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n {
            let j = (i + 1) % n;
            let k = ab * (-self.b * (q[j] - q[i])).exp();
            out[i * n + i] -= k;
            out[j * n + j] -= k;
            out[i * n + j] += k;
            out[j * n + i] += k;
        }
        Some(Ok(()))
    }
}

/// The force written once, over `f64` and over members in SIMD lanes.
impl LanesForce for TodaLattice {
    /// `F_i = a (e^{-b r_{i-1}} - e^{-b r_i})`.
    #[inline(always)]
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]) {
        let a = self.a;
        self.sweep(q, |i, left, right| out[i] = (left - right) * a);
    }

    /// Equal particles, `a` and `b`, bit for bit (unit masses).
    fn same_force(&self, other: &Self) -> bool {
        self.n() == other.n()
            && [self.a, self.b].map(f64::to_bits) == [other.a, other.b].map(f64::to_bits)
    }

    /// `exp` per spring.
    fn calls_per_lane(&self) -> bool {
        true
    }

    #[inline(always)]
    fn potential_of<R: Real>(&self, q: &[R]) -> Option<R> {
        Some(self.potential(q))
    }
}

crate::impl_separable_dynamics!(TodaLattice, {
    fn splitting_lanes(&self) -> Option<&dyn SplittingLanes> {
        Some(self)
    }
});

impl Capabilities for TodaLattice {
    fn per_particle_energy(&self, q: &[f64], p: &[f64]) -> Option<Result<Vec<f64>>> {
        let mut out = vec![0.0; q.len()];
        Some(self.particle_energies_into(q, p, &mut out).map(|()| out))
    }
    fn conserved_quantities(&self, state: &[f64]) -> Option<Result<Vec<f64>>> {
        Some(TodaLattice::conserved_quantities(self, Some(state)))
    }
}

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const TODA_PHYSICS: &str =
    "Unit masses on a ring joined by exponential springs, V(r) = (a/b) e^(−b r) (stiff \
         under compression, soft under stretching), the lattice Morikazu Toda found in 1967. \
         A kick launches a compression pulse (a lattice soliton) that runs around the ring, \
         and the energy sloshes from particle to particle. Yet the motion is completely \
         integrable: Flaschka's Lax matrix L (diagonal pᵢ, off-diagonal √(a/b) e^(−b rᵢ/2), \
         corners closing the ring) only rotates as time goes on, so its eigenvalues are \
         conserved (the sum of their squares is twice the energy). The FPUT chain is the same \
         kind of lattice with a polynomial spring: it is only close to integrable, which is \
         why its energy nearly, but not exactly, returns.";

catalogue_static! {
    /// The catalogue entry of [`TodaLattice`].
    pub static TODA_ENTRY: SystemEntry = SystemEntry {
        name: "toda",
        python: Some("TodaLattice"),
        summary: "periodic Toda lattice H = sum p^2/2 + (a/b) sum exp(-b (q_{i+1} - q_i)), \
                  completely integrable (TodaLattice)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Any,
                D::demo_vector(&[0.0; 8]),
                "length",
                "initial positions; the ring has one particle per entry (>= 2)",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::SameAs("q0"),
                D::demo_vector(&[1.5, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, -1.0]),
                "momentum",
                "initial momenta, one per particle",
            )
            .initial_state(),
            P::scalar(
                "a",
                D::scalar(1.0),
                "force",
                Range::POSITIVE,
                "bond strength: stiffness a b",
            ),
            P::scalar(
                "b",
                D::scalar(1.0),
                "1/length",
                Range::POSITIVE,
                "bond anharmonicity",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: Some("conserved_quantities: the n eigenvalues of Flaschka's Lax matrix"),
        physics: Some(TODA_PHYSICS),
        presentation: Presentation {
            title: "Toda lattice",
            symbols: &["q"],
            time_unit: "time",
            state_units: None,
            drawing: Drawing::Chain {
                ends: Ends::Periodic,
            },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(TodaLattice::new(
                v.vector("q0")?,
                v.vector("p0")?,
                v.scalar("a")?,
                v.scalar("b")?,
            )?)))
        },
    };
}
