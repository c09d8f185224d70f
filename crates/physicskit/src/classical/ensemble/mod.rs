//! Ensembles and parameter sweeps of any catalogue system, on all cores, bit-reproducibly.
//!
//! An ensemble is one catalogue entry ([`SystemEntry`]) and `n` members: values common to all
//! ([`Members::common`]), per-member values of swept parameters ([`Sweep`], e.g. `c_pn` or
//! `theta0[1]`) and optionally per-member initial states. Every member is built through the
//! catalogue (`SystemEntry::build_from`, which checks every value) and checked **before any
//! integration starts**; the first bad member is reported by index (`member 731: ...`).
//!
//! Each member is then integrated by its own `integrate` (the same monomorphized loop as a
//! single run), so a member's results equal those of building it alone and calling
//! `integrate` **bit for bit**. Members run in parallel (rayon) in fixed chunks of
//! [`MEMBER_CHUNK`]; a member's arithmetic does not depend on which thread runs it or on the
//! other members, so the results are **identical for any number of threads** and on any
//! split of the members into runs (which is how the Python front end distributes an ensemble
//! over a Dask cluster).
//!
//! Per member the engine keeps ([`Plan`]):
//! * the final state, always;
//! * optionally the trajectory every `stride` steps (the rows `integrate` with
//!   `Sampling::Stride(stride)` stores); its memory is checked before anything is allocated;
//! * any [`Reduction`]s: the maximum relative energy error, the time of a first event located
//!   inside its step (see [`reduction`]). A member's steps are stored while it runs (one
//!   member per thread at a time) and reduced as soon as it is done, so memory stays
//!   `O(members x outputs)`.
//!
//! The observer ([`Observer`]) is told `(members done, members, NaN)` about every 20 ms from
//! the calling thread and may stop the run (Ctrl-C): running members stop within 1024 steps.

mod members;
pub mod reduction;

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use ndarray::{Array1, Array2, Array3};
use rayon::prelude::*;

use members::{in_member, Recipe};
pub use members::{Members, Sweep};
pub use reduction::{Condition, Direction, Event, MemberRun, Reduction};

use crate::classical::core::{
    memory_check, DynSystem, Error, IntegrateOptions, Method, Observer, Result, Sampling,
    SystemEntry, TimeGrid,
};

/// Members per parallel chunk: enough to make scheduling negligible, few enough that 1e3
/// members balance over many cores.
pub const MEMBER_CHUNK: usize = 16;

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
    /// Worker threads (`None`: rayon's global pool, one per core).
    pub threads: Option<usize>,
}

/// The outputs, member-major: member `i`'s values are row `i` (the Python front end reshapes
/// the member axis to the grid's shape).
#[derive(Debug, Clone, PartialEq)]
pub struct EnsembleResult {
    /// The method used.
    pub method: Method,
    /// Degrees of freedom (`None` for ODE systems).
    pub ndof: Option<usize>,
    /// Final states, `members x state length`.
    pub final_state: Array2<f64>,
    /// Sample times of the trajectories (the same for every member).
    pub t: Option<Array1<f64>>,
    /// Trajectories, `members x samples x state length`.
    pub trajectory: Option<Array3<f64>>,
    /// One array of `members` values per reduction, named as [`Reduction::name`] says.
    pub reductions: Vec<(&'static str, Array1<f64>)>,
}

/// The checked ensemble, ready to run.
struct Prepared<'a> {
    recipe: Recipe<'a>,
    grid: TimeGrid,
    method: Method,
    ndof: Option<usize>,
    dim: usize,
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
///     threads: None,
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
    let pool = pool(plan)?;
    let prepared = in_pool(&pool, || prepare(entry, members, plan))?;
    run_prepared(prepared, plan, observer, &pool)
}

/// Everything [`run`] checks before integrating (every member built and checked), and nothing
/// else: for front ends that distribute the members and want errors before shipping them.
///
/// # Errors
/// As [`run`] before any integration.
pub fn check(entry: &'static SystemEntry, members: &Members, plan: &Plan) -> Result<()> {
    let pool = pool(plan)?;
    in_pool(&pool, || prepare(entry, members, plan)).map(|_| ())
}

/// The thread pool `plan.threads` asks for (`None`: rayon's global pool).
fn pool(plan: &Plan) -> Result<Option<rayon::ThreadPool>> {
    Ok(match plan.threads {
        None => None,
        Some(0) => return Err(Error::invalid("threads", 0.0, "must be >= 1")),
        Some(k) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| Error::Unsupported {
                    operation: "ensemble thread pool".into(),
                    reason: e.to_string(),
                })?,
        ),
    })
}

/// Runs `f` in `pool`, or in rayon's global pool.
fn in_pool<R: Send>(pool: &Option<rayon::ThreadPool>, f: impl FnOnce() -> R + Send) -> R {
    match pool {
        Some(pool) => pool.install(f),
        None => f(),
    }
}

/// Checks everything and builds every member once, before any integration.
fn prepare<'a>(
    entry: &'static SystemEntry,
    members: &'a Members,
    plan: &Plan,
) -> Result<Prepared<'a>> {
    let grid = TimeGrid::new(plan.t_span, plan.dt)?;
    if plan.stride == Some(0) {
        return Err(Error::invalid("stride", 0.0, "must be >= 1"));
    }
    let recipe = Recipe::new(entry, members)?;
    let first = recipe.build(0, grid.t0())?;
    let dim = first.dynamical().state_dim();
    let ndof = first.ndof();
    let method = plan.method.unwrap_or_else(|| first.default_method());
    for r in &plan.reductions {
        r.check(dim)?;
    }
    // Every member is built and checked up front (in parallel; the lowest bad index wins).
    let bad =
        (1..recipe.len())
            .into_par_iter()
            .find_map_first(|i| match recipe.build(i, grid.t0()) {
                Err(e) => Some(e),
                Ok(s) if s.dynamical().state_dim() != dim => Some(in_member(
                    i,
                    Error::DimensionMismatch {
                        name: "state".into(),
                        expected: dim,
                        found: s.dynamical().state_dim(),
                    },
                )),
                Ok(_) => None,
            });
    if let Some(e) = bad {
        return Err(e);
    }
    let n_steps = grid.n_steps();
    let reduce = !plan.reductions.is_empty();
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
    let width = dim + kept_rows * dim + plan.reductions.len();
    // Outputs, counted twice (the member-major buffer and the assembled arrays coexist), and
    // one member's run per thread.
    memory_check(recipe.len(), 2 * width)?;
    memory_check(
        run_rows.saturating_mul(rayon::current_num_threads()),
        1 + dim + usize::from(!skip_energy),
    )?;
    Ok(Prepared {
        recipe,
        grid,
        method,
        ndof,
        dim,
        run_rows,
        kept_rows,
        sampling,
        skip_energy,
    })
}

/// Runs every member of `prepared`, in `in_pool`'s threads.
fn run_prepared(
    prepared: Prepared<'_>,
    plan: &Plan,
    observer: Option<&mut dyn Observer>,
    pool: &Option<rayon::ThreadPool>,
) -> Result<EnsembleResult> {
    let n = prepared.recipe.len();
    let dim = prepared.dim;
    let width = dim + prepared.kept_rows * dim + plan.reductions.len();
    let mut out = vec![0.0; n * width];
    let stop = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    let work = |out: &mut [f64]| -> Result<()> {
        in_pool(pool, || {
            let results: Vec<Result<()>> = out
                .par_chunks_mut(MEMBER_CHUNK * width)
                .enumerate()
                .map(|(chunk, rows)| {
                    for (j, row) in rows.chunks_mut(width).enumerate() {
                        let index = chunk * MEMBER_CHUNK + j;
                        if stop.load(Ordering::Relaxed) {
                            return Err(Error::Interrupted { t: f64::NAN });
                        }
                        run_member(&prepared, plan, index, row, &stop).map_err(|e| match e {
                            Error::Interrupted { .. } => e,
                            e => in_member(index, e),
                        })?;
                        done.fetch_add(1, Ordering::Relaxed);
                    }
                    Ok(())
                })
                .collect();
            // The lowest chunk's error: the same whatever the thread count.
            results.into_iter().collect()
        })
    };
    match observer {
        None => work(&mut out)?,
        Some(observer) => std::thread::scope(|scope| {
            let out = &mut out;
            let work = &work;
            let handle = scope.spawn(move || work(out));
            while !handle.is_finished() {
                std::thread::sleep(Duration::from_millis(20));
                let members_done = done.load(Ordering::Relaxed);
                if observer.observe(members_done, n, f64::NAN).is_break() {
                    stop.store(true, Ordering::Relaxed);
                }
            }
            handle.join().unwrap_or_else(|_| {
                Err(Error::Unsupported {
                    operation: "ensemble integration".into(),
                    reason: "a worker thread panicked".into(),
                })
            })
        })?,
    }
    assemble(prepared, plan, out)
}

/// Member `index`: build, integrate, keep what the plan asks into `row`.
fn run_member(
    p: &Prepared<'_>,
    plan: &Plan,
    index: usize,
    row: &mut [f64],
    stop: &AtomicBool,
) -> Result<()> {
    let mut system: Box<dyn DynSystem> = p.recipe.build(index, p.grid.t0())?;
    let mut flag = StopFlag(stop);
    let result = system.integrate(
        plan.t_span,
        plan.dt,
        p.method,
        IntegrateOptions {
            sampling: p.sampling,
            skip_energy: p.skip_energy,
            observer: Some(&mut flag),
            observe_every: 1024,
            ..IntegrateOptions::default()
        },
    )?;
    debug_assert_eq!(result.y.nrows(), p.run_rows);
    let dim = p.dim;
    let (final_out, rest) = row.split_at_mut(dim);
    final_out.copy_from_slice(result.y.row(result.y.nrows() - 1).as_slice().unwrap_or(&[]));
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
    };
    for (r, out) in plan.reductions.iter().zip(red_out.iter_mut()) {
        *out = r.reduce(&member)?;
    }
    Ok(())
}

/// Splits the member-major buffer into the result's arrays.
fn assemble(p: Prepared<'_>, plan: &Plan, out: Vec<f64>) -> Result<EnsembleResult> {
    let n = p.recipe.len();
    let dim = p.dim;
    let width = dim + p.kept_rows * dim + plan.reductions.len();
    let column = |offset: usize, len: usize| -> Vec<f64> {
        out.chunks(width)
            .flat_map(|row| row[offset..offset + len].iter().copied())
            .collect()
    };
    let shape_error = |e: ndarray::ShapeError| Error::Unsupported {
        operation: "ensemble assembly".into(),
        reason: e.to_string(),
    };
    let final_state = Array2::from_shape_vec((n, dim), column(0, dim)).map_err(shape_error)?;
    let trajectory = match plan.stride {
        None => None,
        Some(_) => Some(
            Array3::from_shape_vec((n, p.kept_rows, dim), column(dim, p.kept_rows * dim))
                .map_err(shape_error)?,
        ),
    };
    let base = dim + p.kept_rows * dim;
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
