//! One kick–drift–kick loop for every splitting method of a separable Hamiltonian
//! `H = T(p) + V(q)`.
//!
//! A method with `s` drifts is `s + 1` kick weights `k_0..k_s` and `s` drift weights
//! `d_0..d_{s-1}` (each set summing to one), executed as
//!
//! ```text
//! kick k_0, drift d_0, kick k_1, drift d_1, ..., drift d_{s-1}, kick k_s
//! ```
//!
//! (a kick is `p += k h F(q)`, a drift `q += d h M^-1 p`). This is the general symmetric
//! partitioned Runge–Kutta method of ABA type (S. Blanes, P. C. Moan, J. Comput. Appl. Math.
//! 142 (2002) 313–330, eq. (2)). A symmetric composition of `s` Störmer–Verlet substeps with
//! weights `w_1..w_s` is the special case `d_i = w_i`, `k_i = (w_{i-1} + w_i) / 2`
//! (the touching half-kicks merged, [`Coefficients::composition`]); `blanes_moan6` declares
//! independent kicks and drifts ([`Coefficients::partitioned`]).
//!
//! The force after the last drift is cached and reused as the first kick of the next step
//! (first same as last), so a step costs `s` force evaluations. As in OrdinaryDiffEq's
//! symplectic tableaus, the methods differ only in their coefficients, declared in each
//! method's file as the [`Scheme::Splitting`](crate::classical::core::method::Scheme::Splitting)
//! of its `INFO` ([`verlet::DRIFTS`](super::verlet::DRIFTS),
//! [`yoshida4::DRIFTS`](super::yoshida4::DRIFTS), ...).
//!
//! The number of drifts is a const parameter of [`SplittingStepper`], so the substep loop
//! unrolls and each kick fuses with the following drift into one pass over the coordinates.
//! Short slices (up to three coordinates) run a fixed-length copy of that pass, long ones
//! (from 64) the SSE2/AVX2/AVX-512 clone the CPU supports.

use std::collections::BTreeMap;

use multiversion::multiversion;

use super::stepper::{Report, Stepper};
use crate::classical::core::{Error, ExtraValue, HamiltonianSystem, MassInv, Method, Result};

/// The weights of a splitting method with `S` drifts: `kicks[i]` before `drifts[i]`, and
/// `last_kick` after the last drift (see the module docs). Built at compile time from a
/// method's [`Scheme::Splitting`](crate::classical::core::method::Scheme::Splitting).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients<const S: usize> {
    /// Kick weight before each drift.
    pub kicks: [f64; S],
    /// Drift weights (summing to one).
    pub drifts: [f64; S],
    /// The closing kick.
    pub last_kick: f64,
}

impl<const S: usize> Coefficients<S> {
    /// The symmetric composition of `S` Störmer–Verlet substeps of lengths `drifts[i] h`:
    /// kicks `(w_{i-1} + w_i) / 2` (with `w_{-1} = 0`) and a closing half-kick `w_{S-1} / 2`.
    pub const fn composition(drifts: [f64; S]) -> Self {
        let mut kicks = [0.0; S];
        let mut i = 0;
        while i < S {
            kicks[i] = composition_kick(&drifts, i);
            i += 1;
        }
        Self {
            kicks,
            drifts,
            last_kick: composition_kick(&drifts, S),
        }
    }

    /// A general method: `kicks` holds the `S + 1` kick weights, `drifts` the `S` drift
    /// weights. Evaluated at compile time, where other lengths fail the build.
    pub const fn partitioned(kicks: &[f64], drifts: &[f64]) -> Self {
        assert!(drifts.len() == S && kicks.len() == S + 1);
        let mut out = Self {
            kicks: [0.0; S],
            drifts: [0.0; S],
            last_kick: kicks[S],
        };
        let mut i = 0;
        while i < S {
            out.kicks[i] = kicks[i];
            out.drifts[i] = drifts[i];
            i += 1;
        }
        out
    }
}

/// `composition_kicks(w)`: the `M = S + 1` kick weights of the symmetric composition of
/// Störmer–Verlet with drift weights `w` ([`Coefficients::composition`]), for a method file's
/// [`Scheme::Splitting`](crate::classical::core::method::Scheme::Splitting).
pub const fn composition_kicks<const M: usize>(drifts: &[f64]) -> [f64; M] {
    assert!(drifts.len() + 1 == M);
    let mut kicks = [0.0; M];
    let mut i = 0;
    while i < M {
        kicks[i] = composition_kick(drifts, i);
        i += 1;
    }
    kicks
}

/// The `N` weights of a palindromic sequence from its first half `half`: for odd `N`, the last
/// entry of `half` is the middle weight (`N = 2 half.len() - 1`); for even `N`, `N = 2
/// half.len()`. The published coefficients of the symmetric methods are given this way.
pub const fn mirrored<const N: usize>(half: &[f64]) -> [f64; N] {
    assert!(N == 2 * half.len() || N + 1 == 2 * half.len());
    let mut out = [0.0; N];
    let mut i = 0;
    while i < half.len() {
        out[i] = half[i];
        out[N - 1 - i] = half[i];
        i += 1;
    }
    out
}

/// Kick `i` of the composition of Störmer–Verlet substeps `drifts`: the half-kicks of the
/// substeps either side merged, `(w_{i-1} + w_i) / 2` with `w_{-1} = w_s = 0`.
const fn composition_kick(drifts: &[f64], i: usize) -> f64 {
    if i == 0 {
        0.5 * drifts[0]
    } else if i == drifts.len() {
        0.5 * drifts[i - 1]
    } else {
        0.5 * (drifts[i - 1] + drifts[i])
    }
}

/// Kick–drift–kick stepper for a separable Hamiltonian system, for a splitting method with
/// `S` drifts (`S = 1`: verlet, `S = 3`: yoshida4). `S` is a compile-time constant so the
/// substep loop unrolls and each kick fuses with the following drift into one pass. As a
/// [`Stepper`] it advances the state `y = [q, p]`.
///
/// `B` holds the cached force: a `Vec` (any size), or for small systems a fixed-length array
/// ([`with_buffer`](Self::with_buffer)), which the compiler can keep in registers.
#[derive(Debug, Clone)]
pub struct SplittingStepper<const S: usize, B = Vec<f64>> {
    drifts: [f64; S],
    /// Kick weight before each drift.
    kicks: [f64; S],
    /// The closing kick.
    last_kick: f64,
    /// Substep end times as fractions of the step; the last is exactly 1.
    ends: [f64; S],
    force: B,
    /// The cached force belongs to the current `q` (first same as last).
    force_valid: bool,
    force_evaluations: u64,
}

/// The Störmer–Verlet stepper.
pub type VerletStepper = SplittingStepper<1>;
/// The Yoshida-4 stepper.
pub type Yoshida4Stepper = SplittingStepper<3>;

impl SplittingStepper<1> {
    /// A Verlet stepper on `ndof` degrees of freedom.
    pub fn verlet(ndof: usize) -> Self {
        Self::from_drifts(super::verlet::DRIFTS, ndof)
    }
}

impl SplittingStepper<3> {
    /// A Yoshida-4 stepper on `ndof` degrees of freedom.
    pub fn yoshida4(ndof: usize) -> Self {
        Self::from_drifts(super::yoshida4::DRIFTS, ndof)
    }
}

/// Checks that `system` can be integrated by a splitting method.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for non-separable or non-conservative systems, or a method
/// that is not a splitting method.
pub fn check_system<S: HamiltonianSystem + ?Sized>(method: Method, system: &S) -> Result<()> {
    let reason = if !method.needs_separable() {
        "not a splitting method"
    } else if !system.separable() {
        "the system is not separable (H != T(p) + V(q)); use implicit_midpoint or rk4"
    } else if !system.conservative() {
        "the system has non-conservative forces (e.g. drag) that a splitting method would \
         silently drop; use rk4 or implicit_midpoint"
    } else {
        return Ok(());
    };
    Err(Error::UnsupportedMethod {
        method: method.name().into(),
        reason: reason.into(),
    })
}

impl<const S: usize> SplittingStepper<S> {
    /// A stepper for the symmetric composition of Störmer–Verlet with drift weights `drifts`
    /// (summing to 1).
    pub fn from_drifts(drifts: [f64; S], ndof: usize) -> Self {
        Self::new(Coefficients::composition(drifts), ndof)
    }

    /// A stepper for the method with weights `coefficients`, on `ndof` degrees of freedom.
    pub fn new(coefficients: Coefficients<S>, ndof: usize) -> Self {
        SplittingStepper::with_buffer(coefficients, vec![0.0; ndof])
    }
}

impl<const S: usize, B: AsRef<[f64]> + AsMut<[f64]>> SplittingStepper<S, B> {
    /// A stepper for the method with weights `coefficients`, caching the force in `force` (of
    /// length `ndof`).
    pub fn with_buffer(coefficients: Coefficients<S>, force: B) -> Self {
        let Coefficients {
            kicks,
            drifts,
            last_kick,
        } = coefficients;
        let mut ends = [0.0; S];
        let mut elapsed = 0.0;
        for i in 0..S {
            elapsed += drifts[i];
            ends[i] = if i + 1 == S { 1.0 } else { elapsed };
        }
        Self {
            drifts,
            kicks,
            last_kick,
            ends,
            force,
            force_valid: false,
            force_evaluations: 0,
        }
    }

    /// Force evaluations so far.
    pub fn force_evaluations(&self) -> u64 {
        self.force_evaluations
    }

    /// Forgets the cached force (call after changing `q` outside the stepper).
    pub fn invalidate(&mut self) {
        self.force_valid = false;
    }

    /// Advances `(q, p)` from `t` to `t + h` (`h` may be negative).
    ///
    /// The force left by the previous step is reused as this step's first kick, so `q` must be
    /// the one the previous step returned; call [`invalidate`](Self::invalidate) after
    /// changing it in between.
    ///
    /// # Errors
    /// Whatever [`HamiltonianSystem::force`] returns.
    #[inline]
    pub fn step<H: HamiltonianSystem + ?Sized>(
        &mut self,
        system: &H,
        t: f64,
        q: &mut [f64],
        p: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.step_with_potential(system, t, q, p, h, false)
            .map(|_| ())
    }

    /// [`step`](Self::step), evaluating the last force with
    /// [`HamiltonianSystem::force_and_potential`] when `potential` is true: returns the
    /// potential of the new `q` where the system supplies it that way.
    ///
    /// # Errors
    /// Whatever [`HamiltonianSystem::force`] returns.
    #[inline(always)]
    pub fn step_with_potential<H: HamiltonianSystem + ?Sized>(
        &mut self,
        system: &H,
        t: f64,
        q: &mut [f64],
        p: &mut [f64],
        h: f64,
        potential: bool,
    ) -> Result<Option<f64>> {
        if !self.force_valid {
            system.force(q, t, self.force.as_mut())?;
            self.force_evaluations += 1;
        }
        // Until the step completes, the cache does not match q (an error mid-step leaves it
        // invalid).
        self.force_valid = false;
        let mass_inv = system.mass_inv();
        let mut v = None;
        for i in 0..S {
            kick_drift(
                mass_inv,
                q,
                p,
                self.force.as_ref(),
                self.kicks[i] * h,
                self.drifts[i] * h,
            );
            let t_force = t + self.ends[i] * h;
            if potential && i + 1 == S {
                v = system.force_and_potential(q, t_force, self.force.as_mut())?;
            } else {
                system.force(q, t_force, self.force.as_mut())?;
            }
        }
        self.force_evaluations += S as u64;
        kick(p, self.force.as_ref(), self.last_kick * h);
        self.force_valid = true;
        Ok(v)
    }
}

impl<const S: usize, B, H> Stepper<H> for SplittingStepper<S, B>
where
    B: AsRef<[f64]> + AsMut<[f64]>,
    H: HamiltonianSystem + ?Sized,
{
    /// Advances `y = [q, p]` (see [`SplittingStepper::step`]).
    #[inline(always)]
    fn step(&mut self, system: &H, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.step_sampled(system, t, y, h, false).map(|_| ())
    }

    /// Returns the potential of the new `q` when `stored` and the system supplies it with the
    /// force ([`step_with_potential`](SplittingStepper::step_with_potential)).
    #[inline(always)]
    fn step_sampled(
        &mut self,
        system: &H,
        t: f64,
        y: &mut [f64],
        h: f64,
        stored: bool,
    ) -> Result<Option<f64>> {
        let (q, p) = y.split_at_mut(y.len() / 2);
        self.step_with_potential(system, t, q, p, h, stored)
    }
}

impl<const S: usize, B> Report for SplittingStepper<S, B> {
    /// `force_evaluations`.
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        extra.insert(
            "force_evaluations".into(),
            ExtraValue::Scalar(self.force_evaluations as f64),
        );
    }
}

/// `p += kick * F; q += drift * mass_inv * p`, fused into one pass.
///
/// Systems with up to three degrees of freedom (Kepler, Hénon–Heiles, the projectile, a
/// pendulum) take a fixed-length copy of the loop: a runtime-length loop over two elements
/// spends more instructions on its own control than on the arithmetic. The length test is one
/// well-predicted branch. From [`DISPATCH_MIN`] coordinates on, the loop runs in the
/// AVX2/AVX-512 clone this CPU supports.
#[inline(always)]
fn kick_drift(
    mass_inv: MassInv<'_>,
    q: &mut [f64],
    p: &mut [f64],
    force: &[f64],
    kick: f64,
    drift: f64,
) {
    match (q.len(), mass_inv) {
        (1, MassInv::Uniform(m)) => kick_drift_fixed::<1>(m, q, p, force, kick, drift),
        (2, MassInv::Uniform(m)) => kick_drift_fixed::<2>(m, q, p, force, kick, drift),
        (3, MassInv::Uniform(m)) => kick_drift_fixed::<3>(m, q, p, force, kick, drift),
        (n, MassInv::Uniform(m)) if n >= DISPATCH_MIN => {
            kick_drift_uniform(q, p, force, kick, drift * m);
        }
        (_, MassInv::Uniform(m)) => kick_drift_uniform_body(q, p, force, kick, drift * m),
        (n, MassInv::PerCoordinate(m)) if n >= DISPATCH_MIN => {
            kick_drift_per_coordinate(q, p, force, m, kick, drift);
        }
        (_, MassInv::PerCoordinate(m)) => {
            kick_drift_per_coordinate_body(q, p, force, m, kick, drift);
        }
    }
}

/// Shortest slices worth the indirect call into the SIMD clones below (the generic integrator
/// itself is compiled for the baseline, SSE2). Chosen by measurement: the 100-site sine-Gordon
/// chain and the 200-pendulum swarm gain from the clones, while the 32-site FPUT chain lost
/// more to the call than it gained (figures in `benchmarks/README.md`), so it stays inline.
const DISPATCH_MIN: usize = 64;

// The kick-drift loops of long slices, compiled for SSE2, AVX2 and AVX-512 and chosen at run
// time like the slice trig (core/trig.rs). `fma` is not enabled: each clone performs the same
// IEEE multiplications and additions, so the results are the same bits on every machine.

#[inline(always)]
fn kick_drift_uniform_body(q: &mut [f64], p: &mut [f64], force: &[f64], kick: f64, dm: f64) {
    for ((qi, pi), fi) in q.iter_mut().zip(p.iter_mut()).zip(force) {
        *pi += kick * fi;
        *qi += dm * *pi;
    }
}

#[inline(always)]
fn kick_drift_per_coordinate_body(
    q: &mut [f64],
    p: &mut [f64],
    force: &[f64],
    m: &[f64],
    kick: f64,
    drift: f64,
) {
    for (((qi, pi), fi), mi) in q.iter_mut().zip(p.iter_mut()).zip(force).zip(m) {
        *pi += kick * fi;
        *qi += drift * mi * *pi;
    }
}

#[inline(always)]
fn kick_body(p: &mut [f64], force: &[f64], k: f64) {
    p.iter_mut().zip(force).for_each(|(pi, fi)| *pi += k * fi);
}

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
fn kick_drift_uniform(q: &mut [f64], p: &mut [f64], force: &[f64], kick: f64, dm: f64) {
    kick_drift_uniform_body(q, p, force, kick, dm);
}

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
fn kick_drift_per_coordinate(
    q: &mut [f64],
    p: &mut [f64],
    force: &[f64],
    m: &[f64],
    kick: f64,
    drift: f64,
) {
    kick_drift_per_coordinate_body(q, p, force, m, kick, drift);
}

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
fn kick_long(p: &mut [f64], force: &[f64], k: f64) {
    kick_body(p, force, k);
}

/// [`kick_drift`] with uniform masses on exactly `N` coordinates (`q`, `p`, `force` all of
/// length `N`, which the caller has checked).
#[inline(always)]
fn kick_drift_fixed<const N: usize>(
    m: f64,
    q: &mut [f64],
    p: &mut [f64],
    force: &[f64],
    kick: f64,
    drift: f64,
) {
    let (Ok(q), Ok(p), Ok(force)) = (
        <&mut [f64; N]>::try_from(q),
        <&mut [f64; N]>::try_from(p),
        <&[f64; N]>::try_from(force),
    ) else {
        return;
    };
    let dm = drift * m;
    for i in 0..N {
        p[i] += kick * force[i];
        q[i] += dm * p[i];
    }
}

/// `p += kick * F`, fixed-length for up to three coordinates and dispatched to a SIMD clone
/// from [`DISPATCH_MIN`] on, as in [`kick_drift`].
#[inline(always)]
fn kick(p: &mut [f64], force: &[f64], k: f64) {
    #[inline(always)]
    fn fixed<const N: usize>(p: &mut [f64], force: &[f64], k: f64) {
        if let (Ok(p), Ok(force)) = (<&mut [f64; N]>::try_from(p), <&[f64; N]>::try_from(force)) {
            for i in 0..N {
                p[i] += k * force[i];
            }
        }
    }
    match p.len() {
        1 => fixed::<1>(p, force, k),
        2 => fixed::<2>(p, force, k),
        3 => fixed::<3>(p, force, k),
        n if n >= DISPATCH_MIN => kick_long(p, force, k),
        _ => kick_body(p, force, k),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The run-time-dispatched clones (AVX-512 or AVX2 where the CPU has them) against the same
    /// bodies compiled here at the baseline, bit for bit, at lengths around the vector widths
    /// and the dispatch threshold, with values spanning many binades.
    #[test]
    fn dispatched_and_baseline_loops_are_bit_identical() {
        let value = |i: usize, k: f64| ((i as f64) * k).sin() * 10f64.powi((i % 9) as i32 - 4);
        for n in [DISPATCH_MIN, DISPATCH_MIN + 1, 100, 200, 257] {
            let q: Vec<f64> = (0..n).map(|i| value(i, 0.37)).collect();
            let p: Vec<f64> = (0..n).map(|i| value(i, 1.13)).collect();
            let f: Vec<f64> = (0..n).map(|i| value(i, 2.71)).collect();
            let m: Vec<f64> = (0..n).map(|i| 1.0 + value(i, 0.05).abs()).collect();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let (mut q1, mut p1, mut q2, mut p2) = (q.clone(), p.clone(), q.clone(), p.clone());
            kick_drift_uniform(&mut q1, &mut p1, &f, 0.3, -0.7);
            kick_drift_uniform_body(&mut q2, &mut p2, &f, 0.3, -0.7);
            assert_eq!(
                (bits(&q1), bits(&p1)),
                (bits(&q2), bits(&p2)),
                "uniform, n = {n}"
            );
            let (mut q1, mut p1, mut q2, mut p2) = (q.clone(), p.clone(), q.clone(), p.clone());
            kick_drift_per_coordinate(&mut q1, &mut p1, &f, &m, 0.3, -0.7);
            kick_drift_per_coordinate_body(&mut q2, &mut p2, &f, &m, 0.3, -0.7);
            assert_eq!(
                (bits(&q1), bits(&p1)),
                (bits(&q2), bits(&p2)),
                "masses, n = {n}"
            );
            let (mut p1, mut p2) = (p.clone(), p.clone());
            kick_long(&mut p1, &f, 0.3);
            kick_body(&mut p2, &f, 0.3);
            assert_eq!(bits(&p1), bits(&p2), "kick, n = {n}");
            // And the loops do what they say (against the formula written out).
            let mut p3 = p.clone();
            kick_body(&mut p3, &f, 0.3);
            assert!((0..n).all(|i| p3[i].to_bits() == (p[i] + 0.3 * f[i]).to_bits()));
        }
    }
}
