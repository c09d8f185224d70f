//! Splitting-method members in SIMD lanes: `L` members of one separable system (the same
//! parameters, different initial states) stepped at once, each lane doing exactly the scalar
//! step's operations in its order, so each member's states are its own `integrate`'s bit for
//! bit.
//!
//! The force is written once, generic over a [`Real`] scalar ([`LanesForce::force_of`]): the
//! system's own [`HamiltonianSystem::force`] instantiates it with `f64` (so the scalar path's
//! code is what it was), and the lanes with [`Lanes<L>`], `L` doubles under elementwise IEEE
//! operations (additions, multiplications, divisions and square roots, all correctly rounded
//! per lane; `powf`, `sin` and `exp` are the scalar std functions of each lane). The step is the
//! scalar step's kernels ([`compensated`]'s kick–drift update and closing
//! kick, generic over the same scalar): `splitting.rs`'s `step_array` on fixed-length arrays
//! where the type fixes one to three degrees of freedom of uniform mass ([`LanesForce::NDOF`]:
//! Kepler, Hénon–Heiles, the projectile, the pendulum, the oscillator), else the same kernels
//! one coordinate at a time over slices with each coordinate's own inverse mass (the Toda
//! lattice), as the scalar path's loop over a slice does them. The fixed-end chains (harmonic,
//! FPUT) have no lanes force: their scalar step already runs across the sites in vector
//! registers, and their members run faster one by one than in lanes (`benchmarks/README.md`).
//! No FMA is enabled anywhere, so the AVX-512 (16 lanes), AVX2 (8, or 16 for a force that
//! calls std's `sin`, `exp` or `powf` per lane: [`LanesForce::calls_per_lane`]) and plain (4)
//! clones give the same bits; the lane count is the caller's
//! ([`symbolic::native_lanes`](crate::classical::symbolic::native_lanes), as the Taylor
//! members' lanes take it).
//!
//! A system opts in by implementing [`LanesForce`] and returning itself from
//! [`DynamicalSystem::splitting_lanes`](super::DynamicalSystem::splitting_lanes); the ensemble
//! engine finds it there through the type-erased member ([`SplittingLanes`]). Only autonomous
//! forces (`F(q)`, no clock) run in lanes; [`SplittingLanes::accepts`] says which method and
//! system do.

use std::any::Any;
use std::array::{from_mut, from_ref};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use super::compensated;
use super::splitting::{check_system, step_array, Coefficients};
use super::stepper::{AdaptiveStepper, Dispatch, FieldStepper};
use super::{HamiltonianSystem, MassInv, Method};
use crate::classical::core::result::EnergyError;
use crate::classical::core::sum::{lane_sum_of, short_lane_sum};
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
    /// `f64::sin` (std's) of each lane.
    fn sin(self) -> Self;
    /// `f64::exp` (std's) of each lane.
    fn exp(self) -> Self;
    /// `f64::cos` (std's) of each lane.
    fn cos(self) -> Self;
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
    #[inline(always)]
    fn sin(self) -> Self {
        f64::sin(self)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        f64::exp(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        f64::cos(self)
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
    fn neg(self) -> Self {
        self.map(|a| -a)
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
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn powf(self, e: f64) -> Self {
        self.map(|a| a.powf(e))
    }
    #[inline(always)]
    fn sin(self) -> Self {
        self.map(f64::sin)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        self.map(f64::exp)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        self.map(f64::cos)
    }
}

impl<const L: usize> Lanes<L> {
    /// `f` of each lane.
    #[inline(always)]
    fn map(mut self, f: impl Fn(f64) -> f64) -> Self {
        for a in &mut self.0 {
            *a = f(*a);
        }
        self
    }
}

/// A separable system whose force is written once over any [`Real`]: `force` is
/// `force_of::<f64>`, and members of equal parameters run in lanes on `force_of::<Lanes<L>>`.
/// The force must not depend on the clock.
pub trait LanesForce: HamiltonianSystem {
    /// The degrees of freedom where the type fixes them (1 to 3: the lanes run on fixed-length
    /// arrays, as the scalar step's fixed-length kernels); 0 where they are the instance's (a
    /// chain's sites), run over slices.
    const NDOF: usize = 0;

    /// `F(q)` into `out` (`ndof` entries each).
    fn force_of<R: Real>(&self, q: &[R], out: &mut [R]);

    /// Whether `other` has the same force and masses, bit for bit (every parameter the force
    /// and the inverse masses read, and the degrees of freedom).
    fn same_force(&self, other: &Self) -> bool;

    /// `V(q)`, where the system's energy is `T(p) + V(q)` with this `V` its
    /// `potential_energy` and `T` the [`quadratic_kinetic_energy`](super::quadratic_kinetic_energy)
    /// of its masses: the lanes then give each recorded state's energy, bit for bit that of
    /// the member's own `energy` ([`Batch::energy`]). `None` (the default): the caller takes
    /// each member's energy alone.
    fn potential_of<R: Real>(&self, _q: &[R]) -> Option<R> {
        None
    }

    /// Whether this force calls a scalar function once per lane ([`Real::sin`],
    /// [`Real::exp`], [`Real::powf`]: std's, so that each lane rounds as its member). Such a
    /// force runs its 16 lanes in the AVX2 clone rather than the AVX-512 one, where (not
    /// profiled) the 512-bit registers are spilled and their upper halves cleared around each
    /// call, which makes it slower there (`benchmarks/README.md`).
    fn calls_per_lane(&self) -> bool {
        false
    }
}

/// `record(member, step, state, energy)`: a member's state at a step of the grid, with its
/// energy where the lanes computed it.
pub type Record<'a> = dyn FnMut(usize, usize, &[f64], Option<f64>) + 'a;

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
    /// Also give each recorded state's energy where the lanes can compute it (a system with a
    /// [`potential_of`](LanesForce::potential_of)).
    pub energy: bool,
    /// `record(member, step, state, energy)` for each recorded step of each member that has
    /// not failed; `energy` is the state's energy where [`energy`](Self::energy) asked for it
    /// and the lanes computed it, else `None`.
    pub record: &'a mut Record<'a>,
    /// Fold each member's largest relative energy error over every step inside the lanes
    /// (against its start's energy, from 0, as `max_relative_energy_error` folds a run's
    /// stored energies) where they compute energies, and give it once at the end for each
    /// member that has not failed: `largest_error(member, error)`, NaN where an energy was not
    /// finite. Where they cannot (no [`potential_of`](LanesForce::potential_of)), every step
    /// is recorded instead, whatever [`every`](Self::every) says, for the caller to fold.
    pub largest_error: Option<&'a mut dyn FnMut(usize, f64)>,
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

    /// Whether `method` runs in lanes on this system: a splitting method the system accepts.
    fn accepts(&self, method: Method) -> bool;

    /// Runs the members of `batch` (at most `lanes` of them; `lanes` is 16, 8 or else 4) by
    /// `method` with this system's force and masses; returns which failed (a state not finite
    /// at a check).
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] where [`accepts`](Self::accepts) is false, more members
    /// than lanes or states not of `2 ndof` values, or [`Error::Interrupted`] when
    /// `batch.stop` says so.
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
        method.needs_separable() && check_system(method, self).is_ok()
    }

    fn run_lanes(&self, lanes: usize, method: Method, batch: Batch<'_>) -> Result<Vec<bool>> {
        let refused = |reason: &str| Error::UnsupportedMethod {
            method: method.name().into(),
            reason: reason.into(),
        };
        if !self.accepts(method) {
            return Err(refused(
                "not a splitting method on a system it runs in lanes",
            ));
        }
        let width = 2 * self.ndof();
        if width == 0
            || batch.starts.len() > lanes * width
            || batch.starts.is_empty()
            || !batch.starts.len().is_multiple_of(width)
        {
            return Err(refused(
                "a batch holds 1 to `lanes` states of 2 ndof values",
            ));
        }
        method.dispatch(Run {
            system: self,
            lanes,
            batch,
        })
    }
}

/// [`SplittingLanes::run_lanes`] as a [`Dispatch`]: the splitting method's weights and number
/// of drifts from the registry.
struct Run<'s, 'b, T: ?Sized> {
    system: &'s T,
    lanes: usize,
    batch: Batch<'b>,
}

impl<T: LanesForce + ?Sized> Dispatch for Run<'_, '_, T> {
    type Output = Result<Vec<bool>>;

    fn splitting<const S: usize>(self, _: Method, c: Coefficients<S>) -> Self::Output {
        let Run {
            system,
            lanes,
            mut batch,
        } = self;
        let b = &mut batch;
        // SAFETY (each call): the clone's features are the ones just detected.
        #[cfg(target_arch = "x86_64")]
        #[allow(unsafe_code)]
        {
            if lanes == 16
                && !system.calls_per_lane()
                && std::arch::is_x86_feature_detected!("avx512f")
            {
                return unsafe { run_avx512::<S, T>(system, &c, b) };
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                match lanes {
                    16 => return unsafe { run_avx2::<S, 16, T>(system, &c, b) },
                    8 => return unsafe { run_avx2::<S, 8, T>(system, &c, b) },
                    _ => {}
                }
            }
        }
        match lanes {
            16 => run::<S, 16, T>(system, &c, b),
            8 => run::<S, 8, T>(system, &c, b),
            _ => run::<S, 4, T>(system, &c, b),
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
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    run::<S, 16, T>(system, c, b)
}

/// [`run`] on 8 lanes, or on 16 for a force that [calls per lane](LanesForce::calls_per_lane),
/// compiled for AVX2 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn run_avx2<const S: usize, const L: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    run::<S, L, T>(system, c, b)
}

/// The members of `b` in `L` lanes: on fixed-length arrays where the type fixes one to three
/// degrees of freedom of uniform mass (the scalar step's fixed-length kernels), else over
/// slices.
#[inline(always)]
fn run<const S: usize, const L: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    let mass = system.mass_inv();
    match (T::NDOF, mass) {
        (1, MassInv::Uniform(m)) => run_array::<S, 1, L, T>(system, c, m, b),
        (2, MassInv::Uniform(m)) => run_array::<S, 2, L, T>(system, c, m, b),
        (3, MassInv::Uniform(m)) => run_array::<S, 3, L, T>(system, c, m, b),
        _ => {
            let n = system.ndof();
            let mut state = State {
                q: vec![Lanes([0.0; L]); n],
                p: vec![Lanes([0.0; L]); n],
            };
            let count = state.load(b);
            let (mut force, mut eq, mut ep) = (state.q.clone(), state.q.clone(), state.q.clone());
            system.force_of(&state.q, &mut force);
            let h = b.grid.dt();
            // Every closure of the step inlined (as below): see `run_array`.
            state.drive(
                count,
                b,
                #[inline(always)]
                |q, p| {
                    step_slices(
                        c,
                        mass,
                        q,
                        p,
                        &mut force,
                        &mut eq,
                        &mut ep,
                        h,
                        #[inline(always)]
                        |q, f| system.force_of(q, f),
                    );
                },
                // `hamiltonian_energy`'s `T(p) + V(q)`, `T` as `quadratic_kinetic_energy`
                // sums it.
                #[inline(always)]
                |q, p| {
                    let v = system.potential_of(q)?;
                    let zero = Lanes([-0.0; L]);
                    let t = match mass {
                        MassInv::Uniform(m) => {
                            Lanes::splat(0.5 * m) * lane_sum_of(n, zero, |k| p[k] * p[k])
                        }
                        MassInv::PerCoordinate(m) => {
                            Lanes::splat(0.5) * lane_sum_of(n, zero, |k| p[k] * m[k] * p[k])
                        }
                    };
                    Some(t + v)
                },
            )
        }
    }
}

/// [`run`] on `N` coordinates of uniform inverse mass `m` in arrays: `step_array`, the scalar
/// step's fixed-length kernels.
#[inline(always)]
fn run_array<const S: usize, const N: usize, const L: usize, T: LanesForce + ?Sized>(
    system: &T,
    c: &Coefficients<S>,
    m: f64,
    b: &mut Batch<'_>,
) -> Result<Vec<bool>> {
    let mut state = State {
        q: [Lanes([0.0; L]); N],
        p: [Lanes([0.0; L]); N],
    };
    let count = state.load(b);
    let mut force = [Lanes([0.0; L]); N];
    system.force_of(&state.q, &mut force);
    let h = b.grid.dt();
    // The step's closures are inlined by force: a closure left a function of its own is
    // compiled without the AVX-512 or AVX2 of the `run_*` clone that calls it (it is not
    // lexically inside it), and the kernels then run on SSE2 at half the speed.
    state.drive(
        count,
        b,
        #[inline(always)]
        |q, p| {
            step_array::<S, N, Lanes<L>>(
                c,
                m,
                q,
                p,
                &mut force,
                h,
                #[inline(always)]
                |q, f| system.force_of(q, f),
            );
        },
        // `hamiltonian_energy`'s `T(p) + V(q)`, `T = 0.5 m sum p_k^2` as
        // `quadratic_kinetic_energy` sums it.
        #[inline(always)]
        |q, p| {
            let v = system.potential_of(q)?;
            let sum = short_lane_sum(N, Lanes([-0.0; L]), |k| p[k] * p[k])?;
            Some(Lanes::splat(0.5 * m) * sum + v)
        },
    )
}

/// One step of the method `c` on coordinates held in slices, with inverse masses `mass`:
/// `step_array`'s operations in its order, each coordinate through the one-coordinate
/// kernels with its own `drift m_i` (the scalar path's per-coordinate loop forms the same
/// product; with uniform masses, its `drift m`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn step_slices<const S: usize, R: Real>(
    c: &Coefficients<S>,
    mass: MassInv<'_>,
    q: &mut [R],
    p: &mut [R],
    force: &mut [R],
    eq: &mut [R],
    ep: &mut [R],
    h: f64,
    mut evaluate: impl FnMut(&[R], &mut [R]),
) {
    let n = q.len();
    // The corrections start at -0.0 as `compensated::begin_step` sets them.
    eq.fill(R::splat(-0.0));
    ep.fill(R::splat(-0.0));
    for i in 0..S {
        let (kick, drift) = (c.kicks[i] * h, c.drifts[i] * h);
        for k in 0..n {
            let dm = match mass {
                MassInv::Uniform(m) => drift * m,
                MassInv::PerCoordinate(m) => drift * m[k],
            };
            compensated::substep_array::<S, 1, R>(
                i,
                from_mut(&mut q[k]),
                from_mut(&mut p[k]),
                from_mut(&mut eq[k]),
                from_mut(&mut ep[k]),
                from_ref(&force[k]),
                kick,
                dm,
            );
        }
        evaluate(q, force);
    }
    for (k, f) in force.iter().enumerate() {
        compensated::end_step_array::<S, 1, R>(
            from_mut(&mut p[k]),
            from_ref(&ep[k]),
            from_ref(f),
            c.last_kick * h,
        );
    }
}

/// The members' coordinates and momenta, `q[k].0[l]` coordinate `k` of lane `l`'s member:
/// arrays of fixed length or vectors.
struct State<Q> {
    q: Q,
    p: Q,
}

impl<Q> State<Q> {
    /// Loads the initial states of `b` into the lanes (lanes past the last member repeat its
    /// state; their results are dropped); returns the number of members.
    #[inline(always)]
    fn load<const L: usize>(&mut self, b: &Batch<'_>) -> usize
    where
        Q: AsMut<[Lanes<L>]>,
    {
        let (q, p) = (self.q.as_mut(), self.p.as_mut());
        let n = q.len();
        let count = b.starts.len() / (2 * n);
        for l in 0..L {
            let start = &b.starts[l.min(count - 1) * 2 * n..][..2 * n];
            for k in 0..n {
                q[k].0[l] = start[k];
                p[k].0[l] = start[n + k];
            }
        }
        count
    }

    /// The scalar driver's loop over the `count` members loaded from `b`: `n` steps of `dt`
    /// by `step(q, p)` (the force at the start evaluated once by the caller and then reused,
    /// first same as last), the finiteness and `stop` checks where `integrate` makes them,
    /// the recorded rows, with their energies by `energy(q, p)` where `b` asks for them, and
    /// each member's largest energy error where `b` asks for it and `energy` gives them.
    #[inline(always)]
    fn drive<const L: usize>(
        &mut self,
        count: usize,
        b: &mut Batch<'_>,
        mut step: impl FnMut(&mut Q, &mut Q),
        energy: impl Fn(&Q, &Q) -> Option<Lanes<L>>,
    ) -> Result<Vec<bool>>
    where
        Q: AsRef<[Lanes<L>]>,
    {
        let dof = self.q.as_ref().len();
        let (n, mut failed, mut row) = (b.grid.n_steps(), vec![false; count], vec![0.0; 2 * dof]);
        // Each lane's error against its start, where the largest is folded here.
        let start = match b.largest_error {
            Some(_) => energy(&self.q, &self.p),
            None => None,
        };
        let against = start.map(|e0| e0.0.map(EnergyError::new));
        let (mut largest, mut finite) = (
            [0.0_f64; L],
            start.map_or([true; L], |e0| e0.0.map(f64::is_finite)),
        );
        let every = match (&b.largest_error, against) {
            (Some(_), None) => Some(1),
            _ => b.every,
        };
        for done in 1..=n {
            step(&mut self.q, &mut self.p);
            if let Some(against) = &against {
                match energy(&self.q, &self.p) {
                    Some(e) => {
                        let lanes = largest
                            .iter_mut()
                            .zip(&mut finite)
                            .zip(against.iter().zip(e.0));
                        for ((largest, finite), (against, e)) in lanes {
                            *largest = largest.max(against.of(e));
                            *finite &= e.is_finite();
                        }
                    }
                    // Not given after all: each member's own run says.
                    None => finite = [false; L],
                }
            }
            let (q, p) = (self.q.as_ref(), self.p.as_ref());
            let last = done == n;
            if last || done.is_multiple_of(b.check_every) {
                for (l, failed) in failed.iter_mut().enumerate() {
                    *failed |= !q.iter().chain(p).all(|v| v.0[l].is_finite());
                }
                if !last && (b.stop)() {
                    return Err(Error::Interrupted {
                        t: b.grid.time(done),
                    });
                }
            }
            if last || every.is_some_and(|k| done.is_multiple_of(k)) {
                let e = if b.energy {
                    energy(&self.q, &self.p)
                } else {
                    None
                };
                for (l, _) in failed.iter().enumerate().filter(|(_, f)| !**f) {
                    for k in 0..dof {
                        row[k] = q[k].0[l];
                        row[dof + k] = p[k].0[l];
                    }
                    (b.record)(l, done, &row, e.map(|e| e.0[l]));
                }
            }
        }
        if let (Some(report), Some(_)) = (b.largest_error.as_deref_mut(), against) {
            for (l, _) in failed.iter().enumerate().filter(|(_, f)| !**f) {
                report(l, if finite[l] { largest[l] } else { f64::NAN });
            }
        }
        Ok(failed)
    }
}
