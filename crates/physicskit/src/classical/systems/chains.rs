//! Lattice chains: the harmonic chain, the Fermi–Pasta–Ulam–Tsingou β-chain and the discrete
//! sine-Gordon (Frenkel–Kontorova) chain, with their shared normal-mode analysis.
//!
//! All chains have `N` equal masses `m`, momenta `p_i = m dq_i/dt` and `T = sum p_i^2/(2m)`.
//!
//! ```text
//! HarmonicChain:   V = sum_{i=0}^{N} (k/2) (q_{i+1} - q_i)^2,                 q_0 = q_{N+1} = 0
//! FPUTChain:       V = sum_{i=0}^{N} [(k/2) r_i^2 + (beta/4) r_i^4], r_i = q_{i+1} - q_i,
//!                                                                              q_0 = q_{N+1} = 0
//! SineGordonChain: V = sum_{i=1}^{N-1} (k/2) (q_{i+1} - q_i)^2 + sum_{i=1}^{N} (1 - cos q_i)
//!                  (free ends)
//! ```
//!
//! # Normal modes
//!
//! The fixed-end harmonic chain has the sine modes
//!
//! ```text
//! Q_j = sqrt(2/(N+1)) sum_i q_i sin(i j pi/(N+1)),   P_j likewise from p,   i, j = 1..N
//! omega_j = 2 sqrt(k/m) sin(j pi / (2(N+1))),   E_j = P_j^2/(2m) + m omega_j^2 Q_j^2/2
//! ```
//!
//! The transform is orthonormal and its own inverse, so `sum_j E_j` is the harmonic part of the
//! energy exactly. For the harmonic chain each `E_j` is conserved; for the FPUT chain their
//! exchange is the famous near-recurrence; for the free-ended sine-Gordon chain the same sine
//! modes are offered as a common spectral diagnostic (they are not its normal modes: its
//! linearised spectrum has the on-site gap `omega >= 1/sqrt(m)`).
//!
//! References: E. Fermi, J. Pasta, S. Ulam, Los Alamos report LA-1940 (1955); G. P. Berman and
//! F. M. Izrailev, Chaos 15 (2005) 015104 (FPU review and normal modes); O. M. Braun and
//! Y. S. Kivshar, *The Frenkel–Kontorova Model* (2004), ch. 2–3 (kinks and their boosts);
//! N. W. Ashcroft and N. D. Mermin, *Solid State Physics* (1976), ch. 22 (chain modes).

use std::f64::consts::PI;

use crate::classical::core::error::{check_finite_scalar, check_positive, check_vector};
use crate::classical::core::sum::lane_sum_map2;
use crate::classical::core::trig::{sin_into, sin_into_sum_cos, sum_cos};
use crate::classical::core::{check_items_fit, Error, Phase, Result};
use crate::classical::integrators::{HamiltonianSystem, MassInv, Method};
use crate::classical::model::entry::catalogue_static;
use crate::classical::model::entry::{
    Default as D, Family, Length, Literal, ParamSpec as P, Range, SystemEntry,
};
use crate::classical::model::entry::{Drawing, Ends, Pace, Presentation};
use crate::classical::model::erased::{Capabilities, Hamiltonian};

/// Angular frequency of normal mode `j` (`1..=n`) of `n` masses `m` joined by springs `k`
/// between fixed walls: `omega_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1)))`.
pub fn chain_mode_frequency(n: usize, m: f64, k: f64, j: usize) -> f64 {
    2.0 * (k / m).sqrt() * (j as f64 * PI / (2.0 * (n as f64 + 1.0))).sin()
}

/// The fixed-end sine modes of an `N`-site chain with mass `m` and spring constant `k`.
#[derive(Debug, Clone)]
pub struct ChainModes {
    n: usize,
    m: f64,
    /// `1/m`, formed once: every splitting step asks for it (`mass_inv`).
    m_inv: f64,
    omega: Vec<f64>,
    /// `sqrt(2/(N+1)) sin(l pi/(N+1))` for `l = 0..2(N+1)`: every entry of the transform,
    /// indexed by `(i j) mod 2(N+1)`, so no matrix is stored.
    sines: Vec<f64>,
}

impl ChainModes {
    /// The modes of a chain of `n >= 1` masses `m > 0` and springs `k > 0`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n < 1`, `m <= 0` or `k <= 0`; [`Error::TooLarge`] if
    /// the tables would not fit in memory.
    pub fn new(n: usize, m: f64, k: f64) -> Result<Self> {
        check_chain_size(n, MODES_BYTES_PER_SITE)?;
        let m = check_positive("m", m)?;
        let k = check_positive("k", k)?;
        let np1 = (n + 1) as f64;
        let omega = (1..=n).map(|j| chain_mode_frequency(n, m, k, j)).collect();
        let norm = (2.0 / np1).sqrt();
        let sines = (0..2 * (n + 1))
            .map(|l| norm * (l as f64 * PI / np1).sin())
            .collect();
        Ok(Self {
            n,
            m,
            m_inv: 1.0 / m,
            omega,
            sines,
        })
    }

    /// Number of sites `N`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// `omega_j = 2 sqrt(k/m) sin(j pi/(2(N+1)))`, `j = 1..N` (index `j - 1`).
    pub fn frequencies(&self) -> &[f64] {
        &self.omega
    }

    /// The sine transform of `x` into `out` (no allocation); it is its own inverse.
    fn transform(&self, x: &[f64], out: &mut [f64]) {
        let period = 2 * (self.n + 1);
        for (j, o) in (1..=self.n).zip(out.iter_mut()) {
            let mut acc = 0.0;
            let mut l = j % period;
            for &xi in x {
                acc += xi * self.sines[l];
                l += j;
                if l >= period {
                    l -= period;
                }
            }
            *o = acc;
        }
    }

    fn check(&self, q: &[f64], p: &[f64]) -> Result<()> {
        check_vector("q", q, self.n)?;
        check_vector("p", p, self.n)
    }

    /// Modal amplitudes `(Q, P)` of the displacements `q` and momenta `p`, written into
    /// `big_q` and `big_p` (no allocation).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless all four slices have length `N`;
    /// [`Error::NonFinite`] for NaN or infinity in `q` or `p`.
    pub fn coords_into(
        &self,
        q: &[f64],
        p: &[f64],
        big_q: &mut [f64],
        big_p: &mut [f64],
    ) -> Result<()> {
        self.check(q, p)?;
        check_len("Q", big_q.len(), self.n)?;
        check_len("P", big_p.len(), self.n)?;
        self.transform(q, big_q);
        self.transform(p, big_p);
        Ok(())
    }

    /// Modal energies `E_j = P_j^2/(2m) + m omega_j^2 Q_j^2/2` written into `out`, using
    /// `scratch` (length `N`) as work space (no allocation).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless all slices have length `N`; [`Error::NonFinite`].
    pub fn energies_into(
        &self,
        q: &[f64],
        p: &[f64],
        scratch: &mut [f64],
        out: &mut [f64],
    ) -> Result<()> {
        self.coords_into(q, p, scratch, out)?;
        let inv_2m = 0.5 / self.m;
        for ((e, &qj), &w) in out.iter_mut().zip(scratch.iter()).zip(&self.omega) {
            *e = inv_2m * *e * *e + 0.5 * self.m * w * w * qj * qj;
        }
        Ok(())
    }
}

fn check_len(name: &str, found: usize, expected: usize) -> Result<()> {
    if found == expected {
        Ok(())
    } else {
        Err(Error::DimensionMismatch {
            name: name.into(),
            expected,
            found,
        })
    }
}

/// Bytes [`ChainModes`] holds per site: `omega` (one value) and `sines` (two, plus two).
const MODES_BYTES_PER_SITE: usize = 3 * 8 + 16;

/// Bytes [`SineGordonChain::kink_antikink`] holds per site, the most of the kink builders:
/// two profiles `(q, p)`.
const KINK_BYTES_PER_SITE: usize = 4 * 8;

/// Bytes a chain constructor allocates per site, at most: its modes, its state `[q, p]` and
/// the initial `q0`, `p0` it builds or defaults before copying them into the state.
const CHAIN_BYTES_PER_SITE: usize = MODES_BYTES_PER_SITE + 4 * 8;

/// Checks that a chain has at least one site and that `n` sites of `bytes_per_site` fit in
/// memory, before anything of size `n` is allocated.
fn check_chain_size(n: usize, bytes_per_site: usize) -> Result<()> {
    if n < 1 {
        return Err(Error::invalid(
            "n",
            n as f64,
            "a chain needs at least one site",
        ));
    }
    check_items_fit("n", n, bytes_per_site)
}

/// The normal-mode analysis every chain shares (the spec's `_ChainBase`).
pub trait NormalModes {
    /// The chain's fixed-end sine modes.
    fn modes(&self) -> &ChainModes;

    /// `omega_j = 2 sqrt(k/m) sin(j pi/(2(N+1)))`, `j = 1..N`.
    fn normal_mode_frequencies(&self) -> &[f64] {
        self.modes().frequencies()
    }

    /// Modal amplitudes `(Q, P)`, `Q_j = sqrt(2/(N+1)) sum_i q_i sin(i j pi/(N+1))`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` and `p` have length `N`; [`Error::NonFinite`].
    fn normal_mode_coords(&self, q: &[f64], p: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.modes().n();
        let (mut big_q, mut big_p) = (vec![0.0; n], vec![0.0; n]);
        self.modes().coords_into(q, p, &mut big_q, &mut big_p)?;
        Ok((big_q, big_p))
    }

    /// Modal energies `E_j = P_j^2/(2m) + m omega_j^2 Q_j^2/2`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] unless `q` and `p` have length `N`; [`Error::NonFinite`].
    fn modal_energies(&self, q: &[f64], p: &[f64]) -> Result<Vec<f64>> {
        let n = self.modes().n();
        let (mut scratch, mut out) = (vec![0.0; n], vec![0.0; n]);
        self.modes().energies_into(q, p, &mut scratch, &mut out)?;
        Ok(out)
    }
}

/// `out[i] = site(bond(q[i+1] - q[i]) - bond(q[i] - q[i-1]), out[i])` for the interior sites
/// `0 < i < n-1` (`n = q.len() >= 3`; the caller writes the two ends).
///
/// Each bond is evaluated twice, for the site on either side, so that no value is carried from
/// one site to the next and the loop vectorizes; the values are the same bits as a single
/// evaluation.
#[inline(always)]
fn interior_bond_differences(
    q: &[f64],
    out: &mut [f64],
    bond: impl Fn(f64) -> f64,
    site: impl Fn(f64, f64) -> f64,
) {
    let n = q.len();
    for (((o, &prev), &here), &next) in out[1..n - 1]
        .iter_mut()
        .zip(&q[..n - 2])
        .zip(&q[1..n - 1])
        .zip(&q[2..])
    {
        *o = site(bond(next - here) - bond(here - prev), *o);
    }
}

/// Fixed-end nearest-neighbour force `F_i = phi'(q_{i+1} - q_i) - phi'(q_i - q_{i-1})` with
/// walls `q_0 = q_{N+1} = 0`.
#[inline]
pub(super) fn fixed_end_force(q: &[f64], out: &mut [f64], dphi: impl Fn(f64) -> f64) {
    let n = q.len();
    // The wall bonds are `q_1 - 0` and `0 - q_N`, written as such (`0.0 - x` and `-x` differ
    // for x = 0).
    if n == 1 {
        out[0] = dphi(0.0 - q[0]) - dphi(q[0]);
        return;
    }
    out[0] = dphi(q[1] - q[0]) - dphi(q[0]);
    if n > 2 {
        interior_bond_differences(q, out, &dphi, |difference, _| difference);
    }
    out[n - 1] = dphi(0.0 - q[n - 1]) - dphi(q[n - 1] - q[n - 2]);
}

/// Tridiagonal force Jacobian of [`fixed_end_force`] written densely (`N x N`).
fn fixed_end_jacobian(q: &[f64], out: &mut [f64], d2phi: impl Fn(f64) -> f64) {
    let n = q.len();
    out.iter_mut().for_each(|v| *v = 0.0);
    let mut left = d2phi(q[0]);
    for i in 0..n {
        let next = if i + 1 < n { q[i + 1] } else { 0.0 };
        let right = d2phi(next - q[i]);
        out[i * n + i] = -left - right;
        if i + 1 < n {
            out[i * n + i + 1] = right;
            out[(i + 1) * n + i] = right;
        }
        left = right;
    }
}

/// Sum of `phi` over the `N + 1` bonds of a fixed-end chain (the interior bonds in the fixed
/// order of [`lane_sum`](crate::classical::core::sum::lane_sum)).
pub(super) fn fixed_end_potential(q: &[f64], phi: impl Fn(f64) -> f64) -> f64 {
    let n = q.len();
    let interior = lane_sum_map2(&q[..n - 1], &q[1..], |a, b| phi(b - a));
    interior + phi(q[0]) + phi(-q[n - 1])
}

// ---------------------------------------------------------------------------------------------

/// Harmonic chain with fixed ends,
/// `H = sum p_i^2/(2m) + sum_{i=0}^{N} (k/2)(q_{i+1} - q_i)^2`. Each modal energy is conserved.
#[derive(Debug, Clone)]
pub struct HarmonicChain {
    phase: Phase,
    /// The normal modes, and the mass `m` (one copy, read through them).
    modes: ChainModes,
    k: f64,
}

impl HarmonicChain {
    /// A chain of `N = q0.len()` masses with displacements `q0` and momenta `p0`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an empty chain, `m <= 0` or `k <= 0`;
    /// [`Error::DimensionMismatch`] if `p0` differs in length; [`Error::NonFinite`];
    /// [`Error::TooLarge`] if the chain would not fit in memory.
    pub fn new(q0: &[f64], p0: &[f64], m: f64, k: f64) -> Result<Self> {
        check_chain_size(q0.len(), CHAIN_BYTES_PER_SITE)?;
        let modes = ChainModes::new(q0.len(), m, k)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            modes,
            k,
        })
    }

    /// Mass `m`.
    pub fn m(&self) -> f64 {
        self.modes.m
    }

    /// Spring constant `k`.
    pub fn k(&self) -> f64 {
        self.k
    }
}

impl NormalModes for HarmonicChain {
    fn modes(&self) -> &ChainModes {
        &self.modes
    }
}

impl HamiltonianSystem for HarmonicChain {
    fn ndof(&self) -> usize {
        self.modes.n
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        let k = self.k;
        fixed_end_potential(q, |r| 0.5 * k * r * r)
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.modes.m_inv)
    }
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        let k = self.k;
        fixed_end_force(q, out, |r| k * r);
        Ok(())
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let k = self.k;
        fixed_end_jacobian(q, out, |_| k);
        Some(Ok(()))
    }
}

crate::impl_separable_dynamics!(HarmonicChain);

// ---------------------------------------------------------------------------------------------

/// The displacements of `n` fixed-end sites in the shape of sine mode `mode`:
/// `q_i = amplitude sin(pi mode i/(n+1))`, `i = 1..n` (the start of [`FPUTChain::new`], and of
/// the benchmarks' chain workloads, which call this so that both start from the same bits).
/// Any `mode` gives its sine; the modes of the chain are `1..=n`.
pub fn sine_mode(n: usize, mode: usize, amplitude: f64) -> Vec<f64> {
    let wave = PI * mode as f64 / (n + 1) as f64;
    (1..=n)
        .map(|i| amplitude * (wave * i as f64).sin())
        .collect()
}

/// The Fermi–Pasta–Ulam–Tsingou β-chain with fixed ends,
/// `H = sum p_i^2/(2m) + sum_{i=0}^{N} [(k/2) r_i^2 + (beta/4) r_i^4]`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::{FPUTChain, NormalModes};
/// use physicskit::classical::HamiltonianSystem;
///
/// let chain = FPUTChain::new(32, 1.0, 1.0, 0.7, 1, 0.5).unwrap();
/// let e = chain.modal_energies(chain.q(), chain.p()).unwrap();
/// assert!(e[1..].iter().all(|&ej| ej < 1e-25 * e[0].max(1.0))); // only mode 1 is excited
/// ```
#[derive(Debug, Clone)]
pub struct FPUTChain {
    phase: Phase,
    /// The normal modes, and the mass `m` (one copy, read through them).
    modes: ChainModes,
    k: f64,
    beta: f64,
}

impl FPUTChain {
    /// A chain of `n` masses at rest in the shape of mode `mode`:
    /// `q_i = amplitude sin(mode i pi/(n+1))`, `i = 1..n`, `p = 0` (the modal amplitude is then
    /// `Q_mode = amplitude sqrt((n+1)/2)`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n < 1`, `m <= 0`, `k <= 0`, a non-finite `beta` or
    /// `amplitude`, or `mode` outside `1..=n`; [`Error::TooLarge`] if `n` sites would not fit in
    /// memory (checked before allocating).
    pub fn new(n: usize, m: f64, k: f64, beta: f64, mode: usize, amplitude: f64) -> Result<Self> {
        check_chain_size(n, CHAIN_BYTES_PER_SITE)?;
        let modes = ChainModes::new(n, m, k)?;
        let beta = check_finite_scalar("beta", beta)?;
        let amplitude = check_finite_scalar("amplitude", amplitude)?;
        if !(1..=n).contains(&mode) {
            return Err(Error::invalid(
                "mode",
                mode as f64,
                format!("must be in 1..={n} (one of the chain's normal modes)"),
            ));
        }
        let q0 = sine_mode(n, mode, amplitude);
        let p0 = vec![0.0; n];
        Ok(Self {
            phase: Phase::from_halves("q0", &q0, "p0", &p0)?,
            modes,
            k,
            beta,
        })
    }

    /// Mass `m`.
    pub fn m(&self) -> f64 {
        self.modes.m
    }

    /// Linear spring constant `k`.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// Quartic coefficient `beta`.
    pub fn beta(&self) -> f64 {
        self.beta
    }
}

impl NormalModes for FPUTChain {
    fn modes(&self) -> &ChainModes {
        &self.modes
    }
}

impl HamiltonianSystem for FPUTChain {
    fn ndof(&self) -> usize {
        self.modes.n
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        let (k, b) = (self.k, self.beta);
        fixed_end_potential(q, |r| {
            let r2 = r * r;
            0.5 * k * r2 + 0.25 * b * r2 * r2
        })
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.modes.m_inv)
    }
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        let (k, b) = (self.k, self.beta);
        fixed_end_force(q, out, |r| r * (k + b * r * r));
        Ok(())
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let (k, b) = (self.k, self.beta);
        fixed_end_jacobian(q, out, |r| k + 3.0 * b * r * r);
        Some(Ok(()))
    }
}

crate::impl_separable_dynamics!(FPUTChain);

// ---------------------------------------------------------------------------------------------

/// The discrete sine-Gordon (Frenkel–Kontorova) chain with free ends,
/// `H = sum p_i^2/(2m) + sum_{i=1}^{N-1} (k/2)(q_{i+1} - q_i)^2 + sum_i (1 - cos q_i)`.
///
/// # Example
/// ```
/// use physicskit::classical::systems::SineGordonChain;
/// use physicskit::classical::DynamicalSystem;
///
/// // m = k = 9: wave speed 1 site per unit time, soliton width sqrt(k) = 3 sites.
/// let (q0, p0) = SineGordonChain::kink(200, 100.0, 3.0, 0.5, 1).unwrap();
/// let p0: Vec<f64> = p0.iter().map(|p| 9.0 * p).collect(); // momentum = m dq/dt
/// let chain = SineGordonChain::new(200, 9.0, 9.0, Some(&q0), Some(&p0)).unwrap();
/// let gamma = 1.0 / (1.0 - 0.25_f64).sqrt();
/// assert!((chain.current_energy() / (8.0 * gamma * 3.0) - 1.0).abs() < 0.01);
/// ```
#[derive(Debug, Clone)]
pub struct SineGordonChain {
    phase: Phase,
    /// The normal modes, and the mass `m` (one copy, read through them).
    modes: ChainModes,
    k: f64,
}

impl SineGordonChain {
    /// A chain of `n` pendulums with displacements `q0` and momenta `p0` (each defaults to
    /// zeros; use [`SineGordonChain::kink`] for soliton initial data).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n < 1`, `m <= 0` or `k <= 0`;
    /// [`Error::DimensionMismatch`] if `q0` or `p0` does not have length `n`;
    /// [`Error::NonFinite`]; [`Error::TooLarge`] if `n` sites would not fit in memory (checked
    /// before allocating).
    pub fn new(n: usize, m: f64, k: f64, q0: Option<&[f64]>, p0: Option<&[f64]>) -> Result<Self> {
        check_chain_size(n, CHAIN_BYTES_PER_SITE)?;
        let modes = ChainModes::new(n, m, k)?;
        let zeros = if q0.is_none() || p0.is_none() {
            vec![0.0; n]
        } else {
            Vec::new()
        };
        let q0 = q0.unwrap_or(&zeros);
        let p0 = p0.unwrap_or(&zeros);
        check_vector("q0", q0, n)?;
        check_vector("p0", p0, n)?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            modes,
            k,
        })
    }

    /// Continuum single-kink (`polarity = 1`) or antikink (`polarity = -1`) initial data,
    /// Lorentz-boosted to `velocity` (sites per unit time; the wave speed is 1 for
    /// `m = k = 1`):
    ///
    /// ```text
    /// u_i = gamma (i - center) / width,  gamma = 1/sqrt(1 - v^2),   i = 0..n-1
    /// q_i = polarity 4 atan(exp(u_i))
    /// p_i = dq_i/dt = -polarity 2 gamma v / (width cosh(u_i))
    /// ```
    ///
    /// the exact travelling solution `q = 4 atan(exp(gamma (x - center - v t) / width))` of
    /// `q_tt = q_xx - sin q` and its time derivative at `t = 0`. `p` is the momentum for
    /// `m = 1`; multiply by `m` otherwise. `width` must equal `sqrt(k)` for a genuine soliton
    /// (otherwise the profile relaxes and radiates).
    ///
    /// The profile is exact for the continuum equation. On the lattice it is accurate when the
    /// kink spans several sites: with `m = k = 9` (width 3, wave speed 1) a kink keeps its
    /// speed within 1% and its energy is within 0.2% of `8 gamma width`; on the unit lattice
    /// (`m = k = 1`, width 1) the energy is ~1.4% low and Peierls–Nabarro pinning slows a
    /// moving kink markedly.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `n < 1`, a non-finite `center`, `width <= 0`,
    /// `|velocity| >= 1` (no Lorentz boost reaches the wave speed) or a polarity other than
    /// `1` or `-1`; [`Error::TooLarge`] if the two profiles would not fit in memory (checked
    /// before allocating).
    pub fn kink(
        n: usize,
        center: f64,
        width: f64,
        velocity: f64,
        polarity: i32,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        check_chain_size(n, KINK_BYTES_PER_SITE)?;
        let center = check_finite_scalar("center", center)?;
        let width = check_positive("width", width)?;
        if !(velocity.is_finite() && velocity.abs() < 1.0) {
            return Err(Error::invalid(
                "velocity",
                velocity,
                "|velocity| must be < 1, the wave speed sqrt(k/m) of the default chain",
            ));
        }
        if polarity != 1 && polarity != -1 {
            return Err(Error::invalid(
                "polarity",
                f64::from(polarity),
                "must be +1 (kink) or -1 (antikink)",
            ));
        }
        let sign = f64::from(polarity);
        let gamma = 1.0 / (1.0 - velocity * velocity).sqrt();
        let (mut q, mut p) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for i in 0..n {
            let u = gamma * (i as f64 - center) / width;
            q.push(sign * 4.0 * u.exp().atan());
            p.push(-sign * 2.0 * gamma * velocity / (width * u.cosh()));
        }
        Ok((q, p))
    }

    /// A kink (`polarity = 1`) or antikink (`-1`) of a chain with any `m` and `k`, moving at
    /// `velocity` sites per unit time, as canonical `(q, p)`.
    ///
    /// The chain's wave speed is `c = sqrt(k/m)` and its static kink has width `sqrt(k)`; the
    /// profile is [`kink`](Self::kink)'s with the Lorentz factor of `velocity / c`, and the
    /// momentum is `p = m dq/dt`. With `m = k = 1` this is exactly `kink`'s output.
    ///
    /// # Errors
    /// As [`kink`](Self::kink), with `|velocity| < c` and `m, k > 0` required.
    pub fn boosted_kink(
        n: usize,
        m: f64,
        k: f64,
        center: f64,
        width: f64,
        velocity: f64,
        polarity: i32,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let c = (check_positive("k", k)? / check_positive("m", m)?).sqrt();
        if !(velocity.is_finite() && velocity.abs() < c) {
            return Err(Error::invalid(
                "velocity",
                velocity,
                format!("|velocity| must be < the wave speed sqrt(k/m) = {c}"),
            ));
        }
        let (q, mut p) = Self::kink(n, center, width, velocity / c, polarity)?;
        // `kink` returns dq/dt for a wave speed of 1: scale to speed c and to momentum m dq/dt.
        p.iter_mut().for_each(|v| *v *= m * c);
        Ok((q, p))
    }

    /// A kink at `left` moving right and an antikink at `right` moving left, both at `speed`
    /// sites per unit time (see [`boosted_kink`](Self::boosted_kink)): far apart, the sum of the
    /// two profiles is the standard initial condition of a kink–antikink collision.
    ///
    /// # Errors
    /// As [`boosted_kink`](Self::boosted_kink).
    #[allow(clippy::too_many_arguments)]
    pub fn kink_antikink(
        n: usize,
        m: f64,
        k: f64,
        left: f64,
        right: f64,
        width: f64,
        speed: f64,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let (mut q, mut p) = Self::boosted_kink(n, m, k, left, width, speed, 1)?;
        let (qa, pa) = Self::boosted_kink(n, m, k, right, width, -speed, -1)?;
        q.iter_mut().zip(&qa).for_each(|(a, b)| *a += b);
        p.iter_mut().zip(&pa).for_each(|(a, b)| *a += b);
        Ok((q, p))
    }

    /// Mass `m`.
    pub fn m(&self) -> f64 {
        self.modes.m
    }

    /// Coupling constant `k`.
    pub fn k(&self) -> f64 {
        self.k
    }
}

impl NormalModes for SineGordonChain {
    fn modes(&self) -> &ChainModes {
        &self.modes
    }
}

impl HamiltonianSystem for SineGordonChain {
    fn ndof(&self) -> usize {
        self.modes.n
    }
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.potential_with_cos_sum(q, sum_cos(q))
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(self.modes.m_inv)
    }
    /// `F_i = k (q_{i+1} - q_i) - k (q_i - q_{i-1}) - sin q_i`, the missing bond at each free
    /// end contributing nothing.
    #[inline]
    fn force(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<()> {
        // The on-site term first, with the vectorized slice sine (1-ulp class).
        sin_into(q, out);
        self.add_bonds(q, out);
        Ok(())
    }
    /// The force, and the potential with the cosines of the same reductions.
    #[inline]
    fn force_and_potential(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        let cos_sum = sin_into_sum_cos(q, out, 1.0);
        self.add_bonds(q, out);
        Ok(Some(self.potential_with_cos_sum(q, cos_sum)))
    }
    fn force_jacobian(&self, q: &[f64], _t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let n = q.len();
        let k = self.k;
        out.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n {
            let bonds = usize::from(i > 0) + usize::from(i + 1 < n);
            out[i * n + i] = -k * bonds as f64 - q[i].cos();
            if i + 1 < n {
                out[i * n + i + 1] = k;
                out[(i + 1) * n + i] = k;
            }
        }
        Some(Ok(()))
    }
}

impl SineGordonChain {
    /// `0.5 k sum (q_{i+1} - q_i)^2 + sum (1 - cos q_i)`, given `sum cos q_i`.
    #[inline(always)]
    fn potential_with_cos_sum(&self, q: &[f64], cos_sum: f64) -> f64 {
        // Pairs (q_i, q_{i+1}): the sum runs over the common length, N - 1.
        let springs = lane_sum_map2(q, q.get(1..).unwrap_or(&[]), |a, b| (b - a) * (b - a));
        let onsite = q.len() as f64 - cos_sum;
        0.5 * self.k * springs + onsite
    }

    /// Turns `out = sin q` into the force: each site's bond difference minus its sine.
    #[inline(always)]
    fn add_bonds(&self, q: &[f64], out: &mut [f64]) {
        let n = q.len();
        let k = self.k;
        // out holds sin q here; each site subtracts it from its bond difference. A missing bond
        // counts as +0.0: the right end's difference is `0.0 - left`, written as such (not
        // `-left`) so that signed zeros come out as from the uniform formula; the left end's
        // `right - 0.0` is `right`, bit for bit.
        if n == 1 {
            out[0] = 0.0 - out[0];
            return;
        }
        let bond = |r: f64| k * r;
        let first = bond(q[1] - q[0]);
        let last = 0.0 - bond(q[n - 1] - q[n - 2]);
        out[0] = first - out[0];
        out[n - 1] = last - out[n - 1];
        if n > 2 {
            interior_bond_differences(q, out, bond, |difference, sin_q| difference - sin_q);
        }
    }
}

crate::impl_separable_dynamics!(SineGordonChain);

// ---------------------------------------------------------------------------------------------
// The catalogue.

macro_rules! chain_capabilities {
    ($($ty:ty),*) => {$(
        impl Capabilities for $ty {
            fn normal_mode_frequencies(&self) -> Option<Vec<f64>> {
                Some(NormalModes::normal_mode_frequencies(self).to_vec())
            }
            fn normal_mode_coordinates(
                &self,
                q: &[f64],
                p: &[f64],
            ) -> Option<Result<(Vec<f64>, Vec<f64>)>> {
                Some(self.normal_mode_coords(q, p))
            }
            fn modal_energies(&self, q: &[f64], p: &[f64]) -> Option<Result<Vec<f64>>> {
                Some(NormalModes::modal_energies(self, q, p))
            }
        }
    )*};
}

chain_capabilities!(HarmonicChain, FPUTChain, SineGordonChain);

const MASS: P = P::scalar(
    "m",
    D::scalar(1.0),
    "mass",
    Range::POSITIVE,
    "mass of each particle",
);
const SPRING: P = P::scalar(
    "k",
    D::scalar(1.0),
    "force/length",
    Range::POSITIVE,
    "spring constant",
);
const SITES: Range = Range::at_least(1.0);

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const FPUT_PHYSICS: &str =
    "A chain of unit masses joined by springs with a weak quartic non-linearity (V(r) = \
         r²/2 + β r⁴/4, fixed ends) starts in its lowest normal mode. Fermi, Pasta, Ulam and \
         Tsingou expected the non-linearity to share the energy out evenly among all modes \
         (equipartition). Instead the energy flows into a few neighbouring modes and then \
         comes back almost entirely to mode 1: the FPUT recurrence, an early hint of solitons \
         and of KAM stability. (The quartic force keeps the chain's left–right symmetry, so \
         the even modes are never excited.)";

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
const SINE_GORDON_PHYSICS: &str =
    "A chain of pendulums on a torsion spring (the Frenkel–Kontorova model) is the \
         lattice form of the sine-Gordon equation q_tt = c² q_xx − sin q. A kink is a \
         travelling twist by 2π in which the pendulums turn over one after another; an \
         antikink twists back. They behave like particles: sent towards each other, they \
         collide, pass through each other and re-emerge with their shapes intact, the \
         signature of a soliton (the lattice sheds only a little radiation).";

/// The physics of the system, true for any parameters: its catalogue entry's
/// [`physics`](crate::classical::model::SystemEntry::physics).
pub(super) const CHAINS_PHYSICS: &str =
    "Masses joined by identical springs between two walls move, for small oscillations, \
         as a superposition of normal modes: standing waves in which every mass oscillates at \
         the same frequency ωⱼ = 2√(k/m) sin(jπ/2(N+1)). Started in a mode shape, the chain \
         stays in it. Started in a superposition of two modes of close frequencies, each mode \
         keeps its own energy, yet a single mass swells and falls silent at the difference \
         frequency, cos(ω₁t) + cos(ω₂t) = 2 cos(Δω t/2) cos(ω̄ t): beats are interference.";

catalogue_static! {
    /// The catalogue entry of [`HarmonicChain`].
    pub static HARMONIC_CHAIN_ENTRY: SystemEntry = SystemEntry {
        name: "harmonic-chain",
        python: Some("HarmonicChain"),
        summary: "masses and linear springs between fixed walls (HarmonicChain)",
        family: Family::Hamiltonian,
        params: &[
            P::vector(
                "q0",
                Length::Any,
                D::demo_vector(&[0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
                "length",
                "initial displacements; the chain has one mass per entry",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::SameAs("q0"),
                D::DemoAbsent,
                "mass length/time",
                "initial momenta, one per mass (left out: zeros)",
            )
            .initial_state(),
            MASS,
            SPRING,
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(CHAINS_PHYSICS),
        presentation: Presentation {
            title: "Harmonic chain",
            symbols: &["q"],
            time_unit: "time",
            state_units: None,
            drawing: Drawing::Chain { ends: Ends::Fixed },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            let q0 = v.vector("q0")?;
            let zeros = vec![0.0; q0.len()];
            let p0 = v.opt_vector("p0")?.unwrap_or(&zeros);
            Ok(Box::new(Hamiltonian(HarmonicChain::new(
                q0,
                p0,
                v.scalar("m")?,
                v.scalar("k")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of [`FPUTChain`].
    pub static FPUT_ENTRY: SystemEntry = SystemEntry {
        name: "fput",
        python: Some("FPUTChain"),
        summary: "Fermi-Pasta-Ulam-Tsingou beta chain started in one normal mode (FPUTChain)",
        family: Family::Hamiltonian,
        params: &[
            P::integer("n", D::integer(32), SITES, "number of masses"),
            MASS,
            SPRING,
            P::scalar(
                "beta",
                D::scalar(0.0),
                "force/length^3",
                Range::ANY,
                "quartic coupling, V(r) = k r^2/2 + beta r^4/4",
            ),
            P::integer(
                "mode",
                D::integer(1),
                Range::at_least(1.0),
                "initially excited mode, 1..n",
            ),
            P::scalar(
                "amplitude",
                D::scalar(1.0),
                "length",
                Range::ANY,
                "amplitude of the initial mode shape",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: Some("the recurrence shows with e.g. --beta 0.7 --amplitude 0.5"),
        physics: Some(FPUT_PHYSICS),
        presentation: Presentation {
            title: "Fermi–Pasta–Ulam–Tsingou chain",
            symbols: &["q"],
            time_unit: "time",
            state_units: Some(("length", "mass length/time")),
            drawing: Drawing::Chain { ends: Ends::Fixed },
            pace: Pace::Own,
            section_first: false,
            energy_conserved: true,
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(FPUTChain::new(
                v.count("n")?,
                v.scalar("m")?,
                v.scalar("k")?,
                v.scalar("beta")?,
                v.count("mode")?,
                v.scalar("amplitude")?,
            )?)))
        },
    };
}

const SINE_GORDON_SITES: P = P::integer("n", D::integer(200), SITES, "number of sites");
const SINE_GORDON_MASS: P = P::scalar(
    "m",
    D::scalar(1.0),
    "mass",
    Range::POSITIVE,
    "mass of each site",
);
const SINE_GORDON_COUPLING: P = P::scalar(
    "k",
    D::scalar(1.0),
    "",
    Range::POSITIVE,
    "coupling constant",
);

/// How both sine–Gordon entries are shown (the second with its own title). The angles are in
/// radians; time is in the units in which the on-site energy `1 - cos q` has amplitude 1 and
/// the mass is `m` (the kink's speed is in sites per that time), the momenta `m q̇` in mass
/// radians per that time.
const SINE_GORDON_PRESENTATION: Presentation = Presentation {
    title: "Sine–Gordon chain",
    symbols: &["\\phi"],
    time_unit: "time",
    state_units: None,
    drawing: Drawing::Field,
    pace: Pace::Own,
    section_first: false,
    energy_conserved: true,
};

catalogue_static! {
    /// The catalogue entry of [`SineGordonChain::new`].
    pub static SINE_GORDON_STATE_ENTRY: SystemEntry = SystemEntry {
        name: "sine-gordon-state",
        python: Some("SineGordonChain"),
        summary: "discrete sine-Gordon chain from explicit displacements (SineGordonChain::new)",
        family: Family::Hamiltonian,
        params: &[
            SINE_GORDON_SITES,
            SINE_GORDON_MASS,
            SINE_GORDON_COUPLING,
            P::vector(
                "q0",
                Length::Count("n"),
                D::Absent,
                "rad",
                "initial displacements, length n (left out: zeros)",
            )
            .initial_state(),
            P::vector(
                "p0",
                Length::Count("n"),
                D::Absent,
                "mass rad/time",
                "initial momenta, length n (left out: zeros)",
            )
            .initial_state(),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(SINE_GORDON_PHYSICS),
        presentation: Presentation {
            title: "Sine–Gordon chain (from a state)",
            ..SINE_GORDON_PRESENTATION
        },
        build: |v| {
            Ok(Box::new(Hamiltonian(SineGordonChain::new(
                v.count("n")?,
                v.scalar("m")?,
                v.scalar("k")?,
                v.opt_vector("q0")?,
                v.opt_vector("p0")?,
            )?)))
        },
    };
}

catalogue_static! {
    /// The catalogue entry of the sine-Gordon kink demonstrations: a chain built from
    /// [`SineGordonChain::boosted_kink`] or [`SineGordonChain::kink_antikink`] initial data.
    pub static SINE_GORDON_KINK_ENTRY: SystemEntry = SystemEntry {
        name: "sine-gordon",
        python: None,
        summary: "discrete sine-Gordon chain with kink initial data \
                  (SineGordonChain::kink, free ends)",
        family: Family::Hamiltonian,
        params: &[
            SINE_GORDON_SITES,
            SINE_GORDON_MASS,
            SINE_GORDON_COUPLING,
            P::choice(
                "initial",
                &["kink-antikink", "kink", "antikink", "rest"],
                D::Demo(Literal::Choice("kink-antikink")),
                "initial data: a colliding kink-antikink pair, one (anti)kink, or rest",
            ),
            P::scalar(
                "center",
                D::DemoAbsent,
                "sites",
                Range::ANY,
                "centre site (left out: the middle, (n-1)/2)",
            ),
            P::scalar(
                "separation",
                D::demo_scalar(60.0),
                "sites",
                Range::ANY,
                "kink-antikink distance",
            ),
            P::scalar(
                "width",
                D::demo_scalar(1.0),
                "sites",
                Range::POSITIVE,
                "kink width; sqrt(k) for a true soliton",
            ),
            P::scalar(
                "velocity",
                D::demo_scalar(0.2),
                "sites/time",
                Range::ANY,
                "kink speed, |v| < sqrt(k/m) (the pair approaches)",
            ),
        ],
        separable: true,
        taylor_form: false,
        default_method: Method::Yoshida4,
        note: None,
        physics: Some(SINE_GORDON_PHYSICS),
        // Started from kink data, not from a state: the state's units said here.
        presentation: Presentation {
            state_units: Some(("rad", "mass rad/time")),
            ..SINE_GORDON_PRESENTATION
        },
        build: |v| {
            let n = v.count("n")?;
            let (m, k) = (v.scalar("m")?, v.scalar("k")?);
            let (width, velocity) = (v.scalar("width")?, v.scalar("velocity")?);
            let center = v.opt_scalar("center")?.unwrap_or((n as f64 - 1.0) / 2.0);
            let half = v.scalar("separation")? / 2.0;
            // `velocity` is in sites per unit time, below the wave speed sqrt(k/m); the library
            // returns canonical momenta (m dq/dt).
            let (q0, p0) = match v.choice("initial")? {
                "kink" => SineGordonChain::boosted_kink(n, m, k, center, width, velocity, 1)?,
                "antikink" => SineGordonChain::boosted_kink(n, m, k, center, width, velocity, -1)?,
                "kink-antikink" => SineGordonChain::kink_antikink(
                    n,
                    m,
                    k,
                    center - half,
                    center + half,
                    width,
                    velocity,
                )?,
                // At rest: the constructor's zeros, allocated after its size check.
                _ => {
                    return Ok(Box::new(Hamiltonian(SineGordonChain::new(
                        n, m, k, None, None,
                    )?)))
                }
            };
            Ok(Box::new(Hamiltonian(SineGordonChain::new(
                n,
                m,
                k,
                Some(&q0),
                Some(&p0),
            )?)))
        },
    };
}
