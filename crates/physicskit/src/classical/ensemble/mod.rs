//! Ensembles and parameter sweeps of any catalogue system, or of any system built from named
//! parameters, on all cores, bit-reproducibly.
//!
//! An ensemble is one system and `n` members: values common to all ([`Members::common`]),
//! per-member values of swept parameters ([`Sweep`], e.g. `c_pn` or `theta0[1]`) and
//! optionally per-member initial states. A [`MemberSource`] builds member `i`:
//! [`FromCatalogue`] through a catalogue entry ([`SystemEntry`]; `SystemEntry::build_from`
//! checks every value), [`FromParameters`] by a closure from named real parameters and a state
//! (the SymPy engines' expression systems, which are not in the catalogue). Every member is
//! built and checked **before any integration starts**; the first bad member is reported by
//! index (`member 731: ...`). A run in lanes (below) keeps the members the checks built (up
//! to 65536 of them) and runs those, so each is built once. [`run`] is [`run_source`] on a
//! [`FromCatalogue`].
//!
//! Each member is then integrated by its own `integrate` (the same monomorphized loop as a
//! single run), so a member's results equal those of building it alone and calling
//! `integrate` **bit for bit**. Members run in parallel (rayon) in fixed chunks of
//! [`MEMBER_CHUNK`]; a member's arithmetic does not depend on which thread runs it or on the
//! other members, so the results are **identical for any number of threads** and on any
//! split of the members into runs (which is how the Python front end distributes an ensemble
//! over a Dask cluster).
//!
//! **`taylor` in SIMD lanes.** A plan with the `taylor` method runs its
//! members 16 at a time (AVX-512; 8 with AVX2, else 4) on one Taylor form per distinct system
//! (`taylor.rs`, [`integrate_batch`](crate::classical::integrators::taylor_batch::integrate_batch)),
//! in chunks of 64 to 1024 members: each lane does the scalar recurrences' operations, and
//! then the scalar step's (step size, state update, clock, dense output) in their order, so
//! the bits are still those of its own `integrate`.
//!
//! **Splitting methods in SIMD lanes.** A plan with a splitting method runs
//! the members of a system whose force is written over a lanes type (Kepler, Hénon–Heiles, the pendulum,
//! the harmonic oscillator, the projectile, the Toda lattice:
//! [`SplittingLanes`](crate::classical::integrators::lanes::SplittingLanes)) and that share
//! their parameters 16, 8 or 4 at a time (`lanes.rs`, `integrators/lanes.rs`), in chunks of
//! four batches of lanes: each lane does the scalar step's operations in their order, so the
//! bits are again those of its own `integrate`. Other members run alone.
//!
//! In lanes, the reductions that read a member's steps (the energy error, first events) are
//! computed from the state each lane reports at every step, with the energies and the event
//! location of the member's own run, so again with its bits (`chunk.rs`,
//! `reduction::Stepwise`); the chaos reductions (max Lyapunov exponent, SALI), which follow
//! deviation vectors on a flow of their own, run member by member after the lanes. A member
//! whose lanes run fails (a state or an energy not finite) runs alone, so its error is its
//! own run's; other methods run every member alone.
//!
//! An adaptive method (`dop853`, `taylor`) runs every member at the plan's
//! [`Plan::tolerances`] (`None`: [`Tolerances::default`], as `integrate`'s); a fixed-step
//! method given tolerances is refused before any work, as `integrate` refuses it.
//!
//! Per member the engine keeps ([`Plan`]):
//! * the final state, unless `final_state` is `false`;
//! * optionally the trajectory every `stride` steps (the rows `integrate` with
//!   `Sampling::Stride(stride)` stores); its memory is checked before anything is allocated;
//! * any [`Reduction`]s: the maximum relative energy error, the time of a first event located
//!   inside its step, the largest Lyapunov exponent or SALI by the chaos toolkit's loops (see
//!   [`reduction`]). A member run alone has its steps stored while it runs (one member per
//!   thread at a time; only when a reduction reads them) and reduced as soon as it is done;
//!   in lanes they are reduced step by step as the lanes report them. Memory stays
//!   `O(members x outputs)`.
//!
//! **Early stop.** When every requested output is a first-event time (no final state, no
//! trajectory, no other reduction) and the method has a fixed step, a member is stepped one
//! step at a time by a [`Session`](crate::classical::model::Session) (the same bits as
//! `integrate`), each event is checked as its step completes, and the member stops once all
//! have happened: a flip-time map then costs the time to each member's flip, not the whole
//! span. The times are those of the full run, bit for bit; [`EnsembleResult::steps`] says
//! how many steps each member took.
//!
//! The observer ([`Observer`]) is told `(members done, members, NaN)` from the calling thread
//! every [`PROGRESS_PERIOD`] while members run and once when they have finished, and may stop
//! the run (Ctrl-C): running members stop within 1024 steps. The calling thread waits on the
//! workers (not a sleep), so a short ensemble costs only its work.

mod chunk;
mod lanes;
mod members;
mod parameters;
pub mod reduction;
mod taylor;

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use ndarray::{Array1, Array2, Array3};
use rayon::prelude::*;

use members::{check_count, in_member};
pub use members::{FromCatalogue, MemberSource, Members, Sweep};
pub use parameters::FromParameters;
pub use reduction::{Condition, Direction, Event, MemberRun, Reduction};

use crate::classical::core::{memory_check, Error, Result, TimeGrid};
use crate::classical::integrators::ensemble::watched;
#[cfg(doc)]
use crate::classical::integrators::ensemble::PROGRESS_PERIOD;
use crate::classical::integrators::options::check_adaptive;
use crate::classical::integrators::{IntegrateOptions, Method, Observer, Sampling, Tolerances};
use crate::classical::model::{DynSystem, SystemEntry};

/// Members per parallel chunk: enough to make scheduling negligible, few enough that 1e3
/// members balance over many cores.
pub const MEMBER_CHUNK: usize = 16;

/// Steps between checks of the stop flag inside a member's run.
const OBSERVE_EVERY: usize = 1024;

/// What to integrate and what to keep of each member.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Time span `(t0, t1)`.
    pub t_span: (f64, f64),
    /// Step.
    pub dt: f64,
    /// The method; `None`: the first member's default method.
    pub method: Option<Method>,
    /// Keep the trajectory every `stride` steps (`None`: only the final state).
    pub stride: Option<usize>,
    /// Per-member reductions, in output order.
    pub reductions: Vec<Reduction>,
    /// Keep each member's final state (`false`: [`EnsembleResult::final_state`] has no
    /// columns, and a plan of events only stops each member at its last event).
    pub final_state: bool,
    /// Worker threads, at most [`MAX_THREADS`] (`None`: rayon's global pool, one per core).
    pub threads: Option<usize>,
    /// Tolerances of an adaptive method, for every member's run (`None`:
    /// [`Tolerances::default`]); refused with a fixed-step method, as by `integrate`
    /// ([`IntegrateOptions::tolerances`]).
    pub tolerances: Option<Tolerances>,
}

/// The outputs, member-major: member `i`'s values are row `i` (the Python front end reshapes
/// the member axis to the grid's shape).
#[derive(Debug, Clone, PartialEq)]
pub struct EnsembleResult {
    /// The method used.
    pub method: Method,
    /// Degrees of freedom (`None` for ODE systems).
    pub ndof: Option<usize>,
    /// Final states, `members x state length` (`members x 0` when the plan kept none).
    pub final_state: Array2<f64>,
    /// Steps each member took: the span's number of steps, or fewer for a member stopped
    /// early after its last event (see the module docs).
    pub steps: Vec<usize>,
    /// Sample times of the trajectories (the same for every member).
    pub t: Option<Array1<f64>>,
    /// Trajectories, `members x samples x state length`.
    pub trajectory: Option<Array3<f64>>,
    /// One array of `members` values per reduction, named as [`Reduction::name`] says.
    pub reductions: Vec<(&'static str, Array1<f64>)>,
}

/// Members a lanes run keeps from the checks, at most: beyond, its chunks build their members
/// again rather than hold them all at once (a catalogue system is a few hundred bytes, but a
/// system built from expressions holds its trees).
const KEEP_BUILT: usize = 1 << 16;

/// How the members of a plan run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// Each by its own `integrate` (or a session, for a plan of events only).
    Alone,
    /// The `taylor` method in lanes (`taylor.rs`).
    Taylor,
    /// A splitting method in lanes (`lanes.rs`).
    Splitting,
}

/// The checked ensemble, ready to run.
struct Prepared<'s, S: ?Sized> {
    source: &'s S,
    grid: TimeGrid,
    method: Method,
    ndof: Option<usize>,
    dim: usize,
    /// Columns of the final state in a member's output row (`dim` or 0).
    final_width: usize,
    /// The events of a plan of events only, run by `events_only`; `None` otherwise.
    early: Option<Vec<Event>>,
    /// How the members run.
    path: Path,
    /// The members the checks built, kept for a lanes run to take (empty: none kept).
    built: Vec<Mutex<Option<Box<dyn DynSystem>>>>,
    /// Stored rows of the run of one member, and of its kept trajectory.
    run_rows: usize,
    kept_rows: usize,
    sampling: Sampling,
    skip_energy: bool,
}

/// Integrates the ensemble of `entry` described by `members` as `plan` says.
///
/// # Errors
/// Before any integration: a bad plan (time span, step, stride, reductions), a member the
/// catalogue or its constructor refuses (named by index; the lowest such index), members
/// whose states differ in length, or outputs that would not fit in memory
/// ([`Error::TrajectoryTooLarge`]). During: the error of the lowest-indexed failing member
/// (named by index), or [`Error::Interrupted`] if the observer stopped the run.
///
/// # Example
/// ```
/// use physicskit::classical::catalog;
/// use physicskit::classical::ensemble::{self, Members, Plan, Sweep};
///
/// let members = Members {
///     sweeps: vec![Sweep::new("q0", vec![0.1, 0.2, 0.3])],
///     n: 3,
///     ..Members::default()
/// };
/// let plan = Plan {
///     t_span: (0.0, 1.0),
///     dt: 0.01,
///     method: None,
///     stride: None,
///     reductions: vec![],
///     final_state: true,
///     threads: None,
///     tolerances: None,
/// };
/// let out = ensemble::run(catalog::find("harmonic-oscillator")?, &members, &plan, None)?;
/// assert_eq!(out.final_state.dim(), (3, 2));
/// # Ok::<(), physicskit::classical::Error>(())
/// ```
pub fn run(
    entry: &'static SystemEntry,
    members: &Members,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
) -> Result<EnsembleResult> {
    run_source(&FromCatalogue::new(entry, members)?, plan, observer)
}

/// Integrates the members of `source` as `plan` says: [`run`] for members from anywhere (see
/// [`FromParameters`] for an example).
///
/// # Errors
/// As [`run`]; a member `source` refuses is named by index.
pub fn run_source<S: MemberSource + ?Sized>(
    source: &S,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
) -> Result<EnsembleResult> {
    run_checking(source, plan, observer, true)
}

/// [`run_source`] for members that [`check_source`] has already passed with the same plan
/// (elsewhere: the Dask front end checks every member before shipping chunks of them to
/// workers): the plan and member 0 are checked again, but the other members are built only to
/// run them, not once more before. The bits are those of [`run_source`].
///
/// # Errors
/// As [`run_source`]; a member `check_source` would have refused (which it did not, for the
/// same members) is reported by index when its run builds it.
pub fn run_source_prechecked<S: MemberSource + ?Sized>(
    source: &S,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
) -> Result<EnsembleResult> {
    run_checking(source, plan, observer, false)
}

/// [`run_source`] (`every_member`) or [`run_source_prechecked`].
fn run_checking<S: MemberSource + ?Sized>(
    source: &S,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
    every_member: bool,
) -> Result<EnsembleResult> {
    let pool = pool(plan)?;
    let prepared = in_pool(&pool, || prepare(source, plan, every_member))?;
    run_prepared(prepared, plan, observer, &pool)
}

/// Everything [`run`] checks before integrating (every member built and checked), and nothing
/// else: for front ends that distribute the members and want errors before shipping them.
///
/// # Errors
/// As [`run`] before any integration.
pub fn check(entry: &'static SystemEntry, members: &Members, plan: &Plan) -> Result<()> {
    check_source(&FromCatalogue::new(entry, members)?, plan)
}

/// [`check`] for members from anywhere.
///
/// # Errors
/// As [`run_source`] before any integration.
pub fn check_source<S: MemberSource + ?Sized>(source: &S, plan: &Plan) -> Result<()> {
    let pool = pool(plan)?;
    in_pool(&pool, || prepare(source, plan, true)).map(|_| ())
}

/// The method `plan` runs `source`'s members with: `plan.method`, else member 0's default
/// (built to ask it, clock at `plan.t_span.0`). For front ends that check an adaptive method's
/// tolerances against the method, as [`Tolerances::for_method`] does, before the run.
///
/// # Errors
/// Member 0 refused by `source` (named as member 0), when the plan names no method.
pub fn method<S: MemberSource + ?Sized>(source: &S, plan: &Plan) -> Result<Method> {
    match plan.method {
        Some(method) => Ok(method),
        None => Ok(build(source, 0, plan.t_span.0)?.default_method()),
    }
}

impl<S: MemberSource + ?Sized> Prepared<'_, S> {
    /// Member `index` at its initial state: the one the checks built and kept, else built
    /// now (its errors not yet named by the index).
    fn member(&self, index: usize) -> Result<Box<dyn DynSystem>> {
        let kept = self.built.get(index).and_then(|m| m.lock().ok()?.take());
        match kept {
            Some(system) => Ok(system),
            None => self.source.build(index, self.grid.t0()),
        }
    }
}

/// Member `index` of `source`, its errors named by the index.
fn build<S: MemberSource + ?Sized>(
    source: &S,
    index: usize,
    t0: f64,
) -> Result<Box<dyn DynSystem>> {
    source.build(index, t0).map_err(|e| in_member(index, e))
}

/// The most worker threads a run may ask for. Each thread holds a stack of its own (2 MiB by
/// default), and far more threads than cores only add switching, so a larger count is refused
/// rather than started (rayon would start up to 65 535). Python and the CLI read this value.
pub const MAX_THREADS: usize = 4096;

/// Thread pools kept for later runs, at most this many (the thread counts asked for last).
const KEPT_POOLS: usize = 4;

/// Pools of more threads than this are built for each run and not kept: their idle threads
/// would hold their stacks for the life of the process.
const KEPT_POOL_THREADS: usize = 64;

/// The pools of the last [`KEPT_POOLS`] thread counts asked for, the latest last, and the
/// process that started their threads. A pool built for each run would cost each run the start
/// of its threads, and its threads after the first would join the work late
/// (`benchmarks/README.md` has the figures). The split of the members does not depend on the
/// pool, so neither do the results.
static POOLS: Mutex<KeptPools> = Mutex::new(KeptPools {
    process: 0,
    pools: Vec::new(),
});

/// See [`POOLS`].
struct KeptPools {
    process: u32,
    pools: Vec<(usize, Arc<rayon::ThreadPool>)>,
}

impl KeptPools {
    /// The kept pools, forgotten first if this process is not the one that built them: a
    /// process forked from it (Python's `multiprocessing` on Linux) has none of their threads,
    /// and a run on them would wait forever. Forgotten, not dropped: dropping one wakes its
    /// threads, which this process does not have.
    fn of_this_process(&mut self) -> &mut Vec<(usize, Arc<rayon::ThreadPool>)> {
        let process = std::process::id();
        if self.process != process {
            std::mem::forget(std::mem::take(&mut self.pools));
            self.process = process;
        }
        &mut self.pools
    }
}

/// The thread pool `plan.threads` asks for (`None`: rayon's global pool): one kept from an
/// earlier run of that many threads, else a new one, then kept (up to [`KEPT_POOL_THREADS`]
/// threads). The lock on the kept pools is not held while a pool starts its threads, so a
/// process forked meanwhile does not find it locked.
fn pool(plan: &Plan) -> Result<Option<Arc<rayon::ThreadPool>>> {
    let k = match plan.threads {
        None => return Ok(None),
        Some(0) => return Err(Error::invalid("threads", 0.0, "must be >= 1")),
        Some(k) if k > MAX_THREADS => {
            return Err(Error::invalid(
                "threads",
                k as f64,
                format!("must be <= {MAX_THREADS}"),
            ))
        }
        Some(k) => k,
    };
    let lock = || {
        POOLS
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    };
    {
        let mut kept = lock();
        let pools = kept.of_this_process();
        if let Some(i) = pools.iter().position(|(threads, _)| *threads == k) {
            let found = pools.remove(i);
            let pool = Arc::clone(&found.1);
            pools.push(found);
            return Ok(Some(pool));
        }
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(k)
        .build()
        .map_err(|e| Error::Unsupported {
            operation: "ensemble thread pool".into(),
            reason: e.to_string(),
        })?;
    let pool = Arc::new(pool);
    if k <= KEPT_POOL_THREADS {
        let mut kept = lock();
        let pools = kept.of_this_process();
        // Another run may have kept a pool of `k` threads meanwhile: this one replaces it.
        pools.retain(|(threads, _)| *threads != k);
        if pools.len() == KEPT_POOLS {
            pools.remove(0);
        }
        pools.push((k, Arc::clone(&pool)));
    }
    Ok(Some(pool))
}

/// Runs `f` in `pool`, or in rayon's global pool.
fn in_pool<R: Send>(pool: &Option<Arc<rayon::ThreadPool>>, f: impl FnOnce() -> R + Send) -> R {
    match pool {
        Some(pool) => pool.install(f),
        None => f(),
    }
}

/// Checks everything and, with `every_member`, builds every member once, before any
/// integration (without: member 0 only, the others having been checked before).
fn prepare<'s, S: MemberSource + ?Sized>(
    source: &'s S,
    plan: &Plan,
    every_member: bool,
) -> Result<Prepared<'s, S>> {
    let grid = TimeGrid::new(plan.t_span, plan.dt)?;
    if plan.stride == Some(0) {
        return Err(Error::invalid("stride", 0.0, "must be >= 1"));
    }
    if !plan.final_state && plan.stride.is_none() && plan.reductions.is_empty() {
        return Err(Error::InvalidArgument {
            name: "plan".into(),
            reason: "nothing to keep: ask for the final state, a trajectory or a reduction".into(),
        });
    }
    let n = source.count();
    check_count(n)?;
    let first = build(source, 0, grid.t0())?;
    let dim = first.dynamical().state_dim();
    let ndof = first.ndof();
    let method = plan.method.unwrap_or_else(|| first.default_method());
    if let Some(tolerances) = plan.tolerances {
        check_adaptive("tolerances", method)?;
        tolerances.validate()?;
    }
    for r in &plan.reductions {
        r.check(dim)?;
    }
    // A chaos reduction's flow refuses what the member cannot run (a splitting method on a
    // non-separable system), here rather than in member 0's run.
    let vectors = plan.reductions.iter().map(Reduction::vectors).max();
    if let Some(k) = vectors.filter(|&k| k > 0) {
        first.flow(method, k)?;
    }
    let n_steps = grid.n_steps();
    let fixed_step = !method.is_adaptive();
    let early = (!plan.final_state && plan.stride.is_none() && fixed_step)
        .then(|| {
            plan.reductions
                .iter()
                .map(|r| match r {
                    Reduction::FirstEvent(e) => Some(*e),
                    _ => None,
                })
                .collect::<Option<Vec<Event>>>()
        })
        .flatten()
        .filter(|events| !events.is_empty());
    let path = if early.is_some() || n_steps == 0 {
        Path::Alone
    } else if taylor::in_lanes(method) {
        Path::Taylor
    } else if lanes::in_lanes(method) {
        Path::Splitting
    } else {
        Path::Alone
    };
    // Every member is built and checked up front (in parallel; the lowest bad index wins).
    // A lanes run keeps them for its chunks, which would otherwise build each again.
    let checked = |i: usize| -> Result<Box<dyn DynSystem>> {
        let s = build(source, i, grid.t0())?;
        let found = s.dynamical().state_dim();
        if found != dim {
            return Err(in_member(
                i,
                Error::DimensionMismatch {
                    name: "state".into(),
                    expected: dim,
                    found,
                },
            ));
        }
        Ok(s)
    };
    let others = if every_member { 1..n } else { n..n };
    let mut built = Vec::new();
    if every_member && path != Path::Alone && n <= KEEP_BUILT {
        let mut others: Vec<Result<Box<dyn DynSystem>>> =
            others.into_par_iter().map(checked).collect();
        if let Some(bad) = others.iter().position(Result::is_err) {
            others.swap_remove(bad)?;
        }
        built.push(Mutex::new(Some(first)));
        built.extend(others.into_iter().map(|s| Mutex::new(s.ok())));
    } else if let Some(e) = others.into_par_iter().find_map_first(|i| checked(i).err()) {
        return Err(e);
    }
    let reduce = plan.reductions.iter().any(Reduction::needs_steps);
    let sampling = match (reduce, plan.stride) {
        (true, _) => Sampling::All,
        (false, Some(k)) => Sampling::Stride(k),
        (false, None) => Sampling::FinalOnly,
    };
    let kept_rows = plan
        .stride
        .map_or(0, |k| Sampling::Stride(k).count(n_steps));
    let run_rows = sampling.count(n_steps);
    let skip_energy = !plan.reductions.iter().any(Reduction::needs_energy);
    let final_width = if plan.final_state { dim } else { 0 };
    let width = final_width + kept_rows * dim + plan.reductions.len();
    // Outputs, counted twice (the member-major buffer and the assembled arrays coexist), and
    // one member's run per thread.
    memory_check(n, 2 * width)?;
    memory_check(
        run_rows.saturating_mul(rayon::current_num_threads()),
        1 + dim + usize::from(!skip_energy),
    )?;
    Ok(Prepared {
        source,
        grid,
        method,
        ndof,
        dim,
        final_width,
        early,
        path,
        built,
        run_rows,
        kept_rows,
        sampling,
        skip_energy,
    })
}

/// Runs every member of `prepared`, in `in_pool`'s threads.
fn run_prepared<S: MemberSource + ?Sized>(
    prepared: Prepared<'_, S>,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
    pool: &Option<Arc<rayon::ThreadPool>>,
) -> Result<EnsembleResult> {
    let n = prepared.source.count();
    let dim = prepared.dim;
    let width = prepared.final_width + prepared.kept_rows * dim + plan.reductions.len();
    let mut out = vec![0.0; n * width];
    let mut steps = vec![0; n];
    let stop = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    let members_per_chunk = match prepared.path {
        Path::Taylor => taylor::chunk(n, in_pool(pool, rayon::current_num_threads)),
        Path::Splitting => lanes::chunk(),
        Path::Alone => MEMBER_CHUNK,
    };
    let work = |(out, steps): (&mut [f64], &mut [usize])| -> Result<()> {
        in_pool(pool, || {
            let results: Vec<Result<()>> = out
                .par_chunks_mut(members_per_chunk * width.max(1))
                .zip(steps.par_chunks_mut(members_per_chunk))
                .enumerate()
                .map(|(k, (rows, steps))| {
                    let mut c = chunk::Chunk {
                        first: k * members_per_chunk,
                        rows,
                        steps,
                        width,
                        stop: &stop,
                        done: &done,
                    };
                    match prepared.path {
                        Path::Taylor => chunk::run_chunk(&taylor::Taylor, &prepared, plan, c),
                        Path::Splitting => {
                            let kind = lanes::Splitting(prepared.method);
                            chunk::run_chunk(&kind, &prepared, plan, c)
                        }
                        Path::Alone => {
                            let members = 0..c.steps.len();
                            chunk::run_alone(&prepared, plan, &mut c, members)
                        }
                    }
                })
                .collect();
            // The lowest chunk's error: the same whatever the thread count.
            results.into_iter().collect()
        })
    };
    match observer {
        None => work((&mut out, &mut steps))?,
        Some(observer) => {
            let buffers = (&mut out[..], &mut steps[..]);
            let work = &work;
            watched(
                move || work(buffers),
                || {
                    let members_done = done.load(Ordering::Relaxed);
                    if observer.observe(members_done, n, f64::NAN).is_break() {
                        stop.store(true, Ordering::Relaxed);
                    }
                },
            )?
        }
    }
    assemble(prepared, plan, out, steps)
}

/// Member `index`: build, integrate, keep what the plan asks into `row`; returns the steps
/// taken.
fn run_member<S: MemberSource + ?Sized>(
    p: &Prepared<'_, S>,
    plan: &Plan,
    index: usize,
    row: &mut [f64],
    stop: &AtomicBool,
) -> Result<usize> {
    // Not `build`: the caller names the member in every error of its run.
    let mut system: Box<dyn DynSystem> = p.source.build(index, p.grid.t0())?;
    // Checked up front too, except by `run_source_prechecked`, which relies on this check:
    // a member of another length would not fit its output row.
    let found = system.dynamical().state_dim();
    if found != p.dim {
        return Err(Error::DimensionMismatch {
            name: "state".into(),
            expected: p.dim,
            found,
        });
    }
    if let Some(events) = &p.early {
        return events_only(system, p, events, row, stop);
    }
    let state0 = system.dynamical().state().to_vec();
    let mut flag = StopFlag(stop);
    let result = system.integrate(
        plan.t_span,
        plan.dt,
        p.method,
        IntegrateOptions {
            sampling: p.sampling,
            skip_energy: p.skip_energy,
            observer: Some(&mut flag),
            observe_every: OBSERVE_EVERY,
            tolerances: plan.tolerances,
        },
    )?;
    debug_assert_eq!(result.y.nrows(), p.run_rows);
    let dim = p.dim;
    let (final_out, rest) = row.split_at_mut(p.final_width);
    if p.final_width > 0 {
        final_out.copy_from_slice(result.y.row(result.y.nrows() - 1).as_slice().unwrap_or(&[]));
    }
    let (traj_out, red_out) = rest.split_at_mut(p.kept_rows * dim);
    if let Some(k) = plan.stride {
        let n_steps = p.grid.n_steps();
        let stride = Sampling::Stride(k);
        // The rows `integrate` stores with `Sampling::Stride(k)`, picked from the run's.
        let all = p.sampling == Sampling::All;
        let mut step = 0;
        for (r, out) in traj_out.chunks_mut(dim).enumerate() {
            let source = if all { step } else { r };
            out.copy_from_slice(result.y.row(source).as_slice().unwrap_or(&[]));
            step = stride.next_stored(step, n_steps);
        }
    }
    let member = MemberRun {
        system: &*system,
        method: p.method,
        result: &result,
        state0: &state0,
        grid: &p.grid,
    };
    for (r, out) in plan.reductions.iter().zip(red_out.iter_mut()) {
        *out = r.reduce(&member, Some(&mut flag), OBSERVE_EVERY)?;
    }
    Ok(p.grid.n_steps())
}

/// A member of a plan of events only: stepped one step at a time by a session (the same bits
/// as `integrate`), each event checked as its step completes, located inside its step as
/// [`Reduction::FirstEvent`] does, and stopped once every event has happened. Writes the event
/// times (`NaN`: never) into `out` and returns the steps taken.
fn events_only<S: MemberSource + ?Sized>(
    system: Box<dyn DynSystem>,
    p: &Prepared<'_, S>,
    events: &[Event],
    out: &mut [f64],
    stop: &AtomicBool,
) -> Result<usize> {
    let mut session = system.start(p.method, p.grid.dt()).map_err(|r| r.error)?;
    let mut previous = session.state().to_vec();
    let mut pending = events.len();
    for (e, out) in events.iter().zip(out.iter_mut()) {
        *out = if e.condition.at_start(previous[e.index]) {
            pending -= 1;
            p.grid.t0()
        } else {
            f64::NAN
        };
    }
    let n_steps = p.grid.n_steps();
    let mut done = 0;
    while pending > 0 && done < n_steps {
        if done % OBSERVE_EVERY == 0 && stop.load(Ordering::Relaxed) {
            return Err(Error::Interrupted {
                t: p.grid.time(done),
            });
        }
        session.advance(1)?;
        done += 1;
        let current = session.state();
        let span = (p.grid.time(done - 1), p.grid.time(done));
        for (e, out) in events.iter().zip(out.iter_mut()) {
            if !out.is_nan() {
                continue;
            }
            let c = e.index;
            if let Some(target) = e.condition.target(previous[c], current[c]) {
                *out = reduction::locate(session.system(), span, &previous, current, c, target)?;
                pending -= 1;
            }
        }
        previous.copy_from_slice(current);
    }
    Ok(done)
}

/// Splits the member-major buffer into the result's arrays.
fn assemble<S: MemberSource + ?Sized>(
    p: Prepared<'_, S>,
    plan: &Plan,
    out: Vec<f64>,
    steps: Vec<usize>,
) -> Result<EnsembleResult> {
    let n = p.source.count();
    let dim = p.dim;
    let fw = p.final_width;
    let width = fw + p.kept_rows * dim + plan.reductions.len();
    let column = |offset: usize, len: usize| -> Vec<f64> {
        out.chunks(width)
            .flat_map(|row| row[offset..offset + len].iter().copied())
            .collect()
    };
    let shape_error = |e: ndarray::ShapeError| Error::Unsupported {
        operation: "ensemble assembly".into(),
        reason: e.to_string(),
    };
    let final_state = Array2::from_shape_vec((n, fw), column(0, fw)).map_err(shape_error)?;
    let trajectory = match plan.stride {
        None => None,
        Some(_) => Some(
            Array3::from_shape_vec((n, p.kept_rows, dim), column(fw, p.kept_rows * dim))
                .map_err(shape_error)?,
        ),
    };
    let base = fw + p.kept_rows * dim;
    let reductions = plan
        .reductions
        .iter()
        .enumerate()
        .map(|(k, r)| (r.name(), Array1::from(column(base + k, 1))))
        .collect();
    Ok(EnsembleResult {
        method: p.method,
        ndof: p.ndof,
        final_state,
        steps,
        t: plan.stride.map(|k| {
            let n_steps = p.grid.n_steps();
            let stride = Sampling::Stride(k);
            let mut step = 0;
            (0..p.kept_rows)
                .map(|_| {
                    let t = p.grid.time(step);
                    step = stride.next_stored(step, n_steps);
                    t
                })
                .collect()
        }),
        trajectory,
        reductions,
    })
}

/// The per-member observer: stops the member when the run is stopped.
struct StopFlag<'a>(&'a AtomicBool);

impl Observer for StopFlag<'_> {
    fn observe(&mut self, _step: usize, _n_steps: usize, _t: f64) -> ControlFlow<()> {
        if self.0.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{pool, Plan, KEPT_POOLS, KEPT_POOL_THREADS, MAX_THREADS, POOLS};
    use std::sync::Arc;

    fn plan(threads: Option<usize>) -> Plan {
        Plan {
            t_span: (0.0, 1.0),
            dt: 0.1,
            method: None,
            stride: None,
            reductions: vec![],
            final_state: true,
            threads,
            tolerances: None,
        }
    }

    /// A run on `k` threads takes the pool an earlier run of `k` threads left, of `k` threads;
    /// the oldest of more than `KEPT_POOLS` counts is dropped; a pool of more than
    /// `KEPT_POOL_THREADS` threads is not kept; pools kept by another process are not used; no
    /// count gives no pool of ours.
    #[test]
    fn pools_are_kept_per_thread_count_and_the_oldest_dropped() {
        // Thread counts no other test asks for, so tests running alongside do not evict them
        // between two calls here.
        let counts: Vec<usize> = (0..=KEPT_POOLS).map(|i| 11 + i).collect();
        let first = pool(&plan(Some(counts[0]))).unwrap().unwrap();
        assert_eq!(first.current_num_threads(), counts[0]);
        let again = pool(&plan(Some(counts[0]))).unwrap().unwrap();
        assert!(
            Arc::ptr_eq(&first, &again),
            "a second pool of the same size was built"
        );
        for &k in &counts[1..] {
            assert_eq!(
                pool(&plan(Some(k))).unwrap().unwrap().current_num_threads(),
                k
            );
        }
        let kept: Vec<usize> = POOLS
            .lock()
            .unwrap()
            .pools
            .iter()
            .map(|(k, _)| *k)
            .collect();
        assert!(kept.len() <= KEPT_POOLS, "kept {kept:?}");
        assert!(
            !kept.contains(&counts[0]),
            "the oldest count is still kept: {kept:?}"
        );
        let rebuilt = pool(&plan(Some(counts[0]))).unwrap().unwrap();
        assert!(!Arc::ptr_eq(&first, &rebuilt), "the dropped pool came back");
        let large = KEPT_POOL_THREADS + 1;
        let once = pool(&plan(Some(large))).unwrap().unwrap();
        assert_eq!(once.current_num_threads(), large);
        let twice = pool(&plan(Some(large))).unwrap().unwrap();
        assert!(
            !Arc::ptr_eq(&once, &twice),
            "a pool of {large} threads was kept"
        );
        // Pools another process kept (as a child forked from it finds them) are not used.
        let mine = pool(&plan(Some(counts[1]))).unwrap().unwrap();
        POOLS.lock().unwrap().process ^= 1;
        let own = pool(&plan(Some(counts[1]))).unwrap().unwrap();
        assert!(
            !Arc::ptr_eq(&mine, &own),
            "a pool of another process was used"
        );
        assert!(pool(&plan(Some(0))).is_err());
        assert!(pool(&plan(None)).unwrap().is_none());
    }

    /// More than `MAX_THREADS` threads are refused with the name and the limit, however many
    /// (rayon would otherwise start up to 65 535 of them, and clamp anything beyond).
    #[test]
    fn more_threads_than_the_limit_are_refused() {
        for k in [MAX_THREADS + 1, 65_536, usize::MAX] {
            let message = pool(&plan(Some(k))).unwrap_err().to_string();
            assert!(
                message.contains("threads") && message.contains(&MAX_THREADS.to_string()),
                "{k} threads: {message}"
            );
        }
    }
}
