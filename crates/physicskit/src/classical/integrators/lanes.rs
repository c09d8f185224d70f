//! Splitting-method members in SIMD lanes: `L` members of one separable system (the same
//! parameters, different initial states) stepped at once, each lane doing exactly the scalar
//! step's operations in its order, so each member's states are its own `integrate`'s bit for
//! bit.
//!
//! The force is written once, generic over a [`Real`] scalar ([`LanesForce::force_of`]): the
//! system's own [`HamiltonianSystem::force`] instantiates it with `f64` (so the scalar path's
//! code is what it was), and the lanes with [`Lanes<L>`], `L` doubles under elementwise IEEE
//! operations (additions, multiplications, divisions and square roots, all correctly rounded
//! per lane; `powf` is the scalar `powf` of each lane). The step is the scalar step's kernels
//! ([`compensated`](super::compensated)'s kick–drift update and closing kick, generic over the
//! same scalar) run by `splitting.rs`'s `step_array`, the splitting loop on fixed-length
//! arrays. No FMA is enabled anywhere, so the AVX-512 (16 lanes), AVX2 (8) and
//! plain (4) clones give the same bits; the lane count is the caller's
//! ([`symbolic::native_lanes`](crate::classical::symbolic::native_lanes), as the Taylor
//! members' lanes take it).
//!
//! A system opts in by implementing [`LanesForce`] and returning itself from
//! [`DynamicalSystem::splitting_lanes`](super::DynamicalSystem::splitting_lanes); the ensemble
//! engine finds it there through the type-erased member ([`SplittingLanes`]). Only autonomous
//! forces (`F(q)`, no clock) on two degrees of freedom with uniform masses run in lanes (Kepler,
//! Hénon–Heiles); [`SplittingLanes::accepts`] says which method and system do.

use std::any::Any;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use super::splitting::{check_system, step_array, Coefficients};
use super::stepper::{AdaptiveStepper, Dispatch, FieldStepper};
use super::{HamiltonianSystem, MassInv, Method};
use crate::classical::core::{Error, Result, TimeGrid};

/// A scalar the splitting step and a [`LanesForce`] are written over: `f64`, or [`Lanes`].
/// Every operation is the IEEE operation of `f64`, per lane.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
    + Add<f64, Output = Self>
    + AddAssign
    + SubAssign
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// The correctly rounded square root.
    fn sqrt(self) -> Self;
    /// `f64::powf` of each lane.
    fn powf(self, e: f64) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        f64::powf(self, e)
    }
}

/// `L` doubles, one member per lane, under elementwise IEEE arithmetic.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const L: usize>(pub [f64; L]);

macro_rules! lanes_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const L: usize> $trait for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(mut self, rhs: Self) -> Self {
                for (a, b) in self.0.iter_mut().zip(rhs.0) {
                    *a $op b;
                }
                self
            }
        }
    };
}
lanes_op!(Add, add, +=);
lanes_op!(Sub, sub, -=);
lanes_op!(Mul, mul, *=);
lanes_op!(Div, div, /=);

impl<const L: usize> Mul<f64> for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, rhs: f64) -> Self {
        self * Self::splat(rhs)
    }
}

impl<const L: usize> Add<f64> for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn add(self, rhs: f64) -> Self {
        self + Self::splat(rhs)
    }
}

impl<const L: usize> Neg for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(mut self) -> Self {
        for a in &mut self.0 {
            *a = -*a;
        }
        self
    }
}

impl<const L: usize> AddAssign for Lanes<L> {
    #[inline(always)]
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}

impl<const L: usize> SubAssign for Lanes<L> {
    #[inline(always)]
    fn sub_assign(&mut self, rhs: Self) {
        *self = *self - rhs;
    }
}

impl<const L: usize> Real for Lanes<L> {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self([x; L])
    }
    #[inline(always)]
    fn sqrt(mut self) -> Self {
        for a in &mut self.0 {
            *a = a.sqrt();
        }
        self
    }
    #[inline(always)]
    fn powf(mut self, e: f64) -> Self {
        for a in &mut self.0 {
            *a = a.powf(e);
        }
        self
    }
}

/// A separable system whose force is written once over any [`Real`]: `force` is
/// `force_of::<f64>`, and members of equal parameters run in lanes on `force_of::<Lanes<L>>`.
/// The force must not depend on the clock.
pub trait LanesForce: HamiltonianSystem {
    /// `F(q)` into `out` (`ndof` entries each).
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]);

    /// Whether `other` has the same force, bit for bit (equal parameters).
    fn same_force(&self, other: &Self) -> bool;
}

/// One batch of at most `lanes` members for [`SplittingLanes::run_lanes`].
pub struct Batch<'a> {
    /// The members' initial states `[q, p]`, one after another.
    pub starts: &'a [f64],
    /// The time grid (the force is autonomous: only its step and number of steps matter).
    pub grid: &'a TimeGrid,
    /// Also record every `k`-th step (the final step is always recorded).
    pub every: Option<usize>,
    /// Steps between checks of the states' finiteness and of `stop`, as `integrate`'s
    /// `observe_every`: a member fails when its state is not finite at such a step or at the
    /// end, where its own run would.
    pub check_every: usize,
    /// `record(member, step, state)` for each recorded step of each member that has not failed.
    pub record: &'a mut dyn FnMut(usize, usize, &[f64]),
    /// Polled at each check: stops the run with [`Error::Interrupted`].
    pub stop: &'a dyn Fn() -> bool,
}

/// The type-erased side of [`LanesForce`], which the ensemble engine reaches through
/// [`DynamicalSystem::splitting_lanes`](super::DynamicalSystem::splitting_lanes).
pub trait SplittingLanes: Sync {
    /// The system, for [`same_force_as`](Self::same_force_as).
    fn as_any(&self) -> &dyn Any;

    /// Whether `other` is the same type of system with the same force.
    fn same_force_as(&self, other: &dyn SplittingLanes) -> bool;

    /// Whether `method` runs in lanes on this system: a splitting method the system accepts,
    /// two degrees of freedom, uniform masses.
    fn accepts(&self, method: Method) -> bool;

    /// Runs the members of `batch` (at most `lanes` of them; `lanes` is 16, 8 or else 4) by
    /// `method` with this system's force; returns which failed (a state not finite at a
    /// check).
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] where [`accepts`](Self::accepts) is false, more members
    /// than lanes, or [`Error::Interrupted`] when `batch.stop` says so.
    fn run_lanes(&self, lanes: usize, method: Method, batch: Batch<'_>) -> Result<Vec<bool>>;
}

impl<T: LanesForce + Any + Sync> SplittingLanes for T {
    fn as_any(&self) -> &dyn Any {
        self
    }

    fn same_force_as(&self, other: &dyn SplittingLanes) -> bool {
        other
            .as_any()
            .downcast_ref::<T>()
            .is_some_and(|o| self.same_force(o))
    }

    fn accepts(&self, method: Method) -> bool {
        method.needs_separable()
            && self.ndof() == 2
            && matches!(self.mass_inv(), MassInv::Uniform(_))
            && check_system(method, self).is_ok()
    }

    fn run_lanes(&self, lanes: usize, method: Method, batch: Batch<'_>) -> Result<Vec<bool>> {
        let refused = |reason: &str| Error::UnsupportedMethod {
            method: method.name().into(),
            reason: reason.into(),
        };
        let (MassInv::Uniform(m), true) = (self.mass_inv(), self.accepts(method)) else {
            return Err(refused(
                "not a splitting method on a system it runs in lanes",
            ));
        };
        if batch.starts.len() > lanes * 4
            || batch.starts.is_empty()
            || !batch.starts.len().is_multiple_of(4)
        {
            return Err(refused("a batch holds 1 to `lanes` states of 4 values"));
        }
        method.dispatch(Run {
            system: self,
            m,
            lanes,
            batch,
        })
    }
}

/// [`SplittingLanes::run_lanes`] as a [`Dispatch`]: the splitting method's weights and number
/// of drifts from the registry.
struct Run<'s, 'b, T: ?Sized> {
    system: &'s T,
    m: f64,
    lanes: usize,
    batch: Batch<'b>,
}

impl<T: LanesForce + ?Sized> Dispatch for Run<'_, '_, T> {
    type Output = Result<Vec<bool>>;

    fn splitting<const S: usize>(self, _: Method, c: Coefficients<S>) -> Self::Output {
        let Run {
            system,
            m,
            lanes,
            mut batch,
        } = self;
        let b = &mut batch;
        // SAFETY (each call): the clone's features are the ones just detected.
        #[cfg(target_arch = "x86_64")]
        #[allow(unsafe_code)]
        {
            if lanes == 16 && std::arch::is_x86_feature_detected!("avx512f") {
                return unsafe { run_avx512::<S, T>(system, &c, m, b) };
            }
            if lanes == 8 && std::arch::is_x86_feature_detected!("avx2") {
                return unsafe { run_avx2::<S, T>(system, &c, m, b) };
            }
        }
        match lanes {
            16 => run::<S, 16, T>(system, &c, m, b),
            8 => run::<S, 8, T>(system, &c, m, b),
            _ => run::<S, 4, T>(system, &c, m, b),
        }
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        Err(not_splitting(method))
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        Err(not_splitting(method))
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        Err(not_splitting(method))
    }
}

fn not_splitting(method: Method) -> Error {
    Error::UnsupportedMethod {
        method: method.name().into(),
        reason: "only splitting methods run in lanes".into(),
    }
}

/// [`run`] on 16 lanes, compiled for AVX-512 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn run_avx512<const S: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    m: f64,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    run::<S, 16, T>(system, c, m, b)
}

/// [`run`] on 8 lanes, compiled for AVX2 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn run_avx2<const S: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    m: f64,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    run::<S, 8, T>(system, c, m, b)
}

/// The members of `b` in `L` lanes (lanes past the last member repeat its state; their
/// results are dropped): the scalar driver's loop, `n` steps of `dt`, the force at the
/// start evaluated once and then reused (first same as last).
#[inline(always)]
fn run<const S: usize, const L: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    m: f64,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    const N: usize = 2;
    let count = b.starts.len() / (2 * N);
    let mut q = [Lanes([0.0; L]); N];
    let mut p = [Lanes([0.0; L]); N];
    for l in 0..L {
        let start = &b.starts[l.min(count - 1) * 2 * N..][..2 * N];
        for k in 0..N {
            q[k].0[l] = start[k];
            p[k].0[l] = start[N + k];
        }
    }
    let mut force = [Lanes([0.0; L]); N];
    system.force_of(&q, &mut force);
    let (n, h) = (b.grid.n_steps(), b.grid.dt());
    let mut failed = vec![false; count];
    let mut row = [0.0; 2 * N];
    for done in 1..=n {
        step_array::<S, N, Lanes<L>>(c, m, &mut q, &mut p, &mut force, h, |q, f| {
            system.force_of(q, f)
        });
        let last = done == n;
        if last || done.is_multiple_of(b.check_every) {
            for (l, failed) in failed.iter_mut().enumerate() {
                *failed |= !q.iter().chain(&p).all(|v| v.0[l].is_finite());
            }
            if !last && (b.stop)() {
                return Err(Error::Interrupted {
                    t: b.grid.time(done),
                });
            }
        }
        if last || b.every.is_some_and(|k| done.is_multiple_of(k)) {
            for (l, _) in failed.iter().enumerate().filter(|(_, f)| !**f) {
                for k in 0..N {
                    row[k] = q[k].0[l];
                    row[N + k] = p[k].0[l];
                }
                (b.record)(l, done, &row);
            }
        }
    }
    Ok(failed)
}
