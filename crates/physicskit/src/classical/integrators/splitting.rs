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
//!
//! **Rounding.** In the compositions of more than three drifts, the kicks and drifts of a
//! step are summed with compensated summation ([`compensated`] module; Hairer, Lubich &
//! Wanner, *Geometric Numerical Integration*, 2nd ed., §VIII.5); `verlet` and `yoshida4` sum
//! plainly (`compensated::PLAIN_MAX_DRIFTS`). The `2 s + 1` additions of a step round the
//! state once, where plain sums round it `2 s + 1` times (35 for `kahan_li8`), so the rounding
//! random walk of a long run is about `sqrt(2 s + 1)` times smaller. The corrections enter `q` in the last
//! drift (so the last force, reused by the next step, is the force of the `q` returned) and
//! `p` in the last kick: between steps the state is just `[q, p]`, and a run continued by a
//! second call, a session or a section repeats one long run's bits.

use std::collections::BTreeMap;

use super::compensated;
use super::lanes::Real;
use super::stepper::{Report, Stepper};
use crate::classical::core::{Error, ExtraValue, Result};
use crate::classical::integrators::{HamiltonianSystem, Method};

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
    /// The compensated sums' corrections of `q` and `p`: work space of one step (reset at its
    /// start, nothing in them outlives it; unused by the plain steps of `verlet` and
    /// `yoshida4`).
    carry_q: B,
    carry_p: B,
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
    /// length `ndof`; two copies of it hold the compensated sums' corrections).
    pub fn with_buffer(coefficients: Coefficients<S>, mut force: B) -> Self
    where
        B: Clone,
    {
        force.as_mut().fill(0.0);
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
            carry_q: force.clone(),
            carry_p: force.clone(),
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
        let (carry_q, carry_p) = (self.carry_q.as_mut(), self.carry_p.as_mut());
        compensated::begin_step::<S>(carry_q, carry_p);
        let mut v = None;
        for i in 0..S {
            let (force, kick, drift) = (self.force.as_ref(), self.kicks[i] * h, self.drifts[i] * h);
            compensated::substep::<S>(i, mass_inv, q, p, carry_q, carry_p, force, kick, drift);
            let t_force = t + self.ends[i] * h;
            if potential && i + 1 == S {
                v = system.force_and_potential(q, t_force, self.force.as_mut())?;
            } else {
                system.force(q, t_force, self.force.as_mut())?;
            }
        }
        self.force_evaluations += S as u64;
        compensated::end_step::<S>(p, carry_p, self.force.as_ref(), self.last_kick * h);
        self.force_valid = true;
        Ok(v)
    }
}

/// One step of the method `c` from `q`, `p`, with `force` the force at `q` (replaced by the
/// force at the new `q`), on `N` coordinates in arrays of any [`Real`] with the uniform
/// inverse mass `m`; `evaluate(q, out)` is the (autonomous) force. Per element the
/// operations of [`SplittingStepper::step`] on `N` coordinates of uniform mass, in their
/// order (its fixed-length kernels are these, at `f64`), so a lane of
/// [`Lanes`](super::lanes::Lanes) repeats a scalar run's bits.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_array<const S: usize, const N: usize, R: Real>(
    c: &Coefficients<S>,
    m: f64,
    q: &mut [R; N],
    p: &mut [R; N],
    force: &mut [R; N],
    h: f64,
    mut evaluate: impl FnMut(&[R; N], &mut [R; N]),
) {
    // The corrections start at -0.0 as `compensated::begin_step` sets them (unused by the
    // plain steps).
    let (mut eq, mut ep) = ([R::splat(-0.0); N], [R::splat(-0.0); N]);
    for i in 0..S {
        let (kick, drift) = (c.kicks[i] * h, c.drifts[i] * h);
        compensated::substep_array::<S, N, R>(i, q, p, &mut eq, &mut ep, force, kick, drift * m);
        evaluate(q, force);
    }
    compensated::end_step_array::<S, N, R>(p, &ep, force, c.last_kick * h);
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
