//! Ensembles of decoupled members (a swarm of independent pendulums) on all cores.
//!
//! A system whose degrees of freedom split into independent members implements [`Ensemble`]:
//! it can hand out the sub-system of a contiguous range of members. [`integrate_ensemble`]
//! integrates fixed-size chunks of members in parallel with rayon and assembles the result.
//!
//! # Reproducibility
//!
//! Chunk boundaries depend only on [`ENSEMBLE_CHUNK`], never on the number of threads, and each
//! member's arithmetic is the same in any chunk (forces are element-wise), so `q` and `p` are
//! bit-identical to the serial `integrate` on any number of threads. The energy of each stored
//! sample is computed afterwards from the assembled row with the system's own `energy`, in the
//! same order as the serial run, so it is bit-identical too.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use rayon::prelude::*;

use crate::classical::core::{Error, ExtraValue, Result, SimulationResult, TimeGrid};
use crate::classical::integrators::{HamiltonianSystem, IntegrateOptions, Method, Observer};
use ndarray::{s, Array1, Array2};

/// Members per parallel chunk: large enough that the per-chunk set-up (one small allocation
/// per chunk) is negligible, small enough to balance 2–64 cores for 10^5–10^7 members.
pub const ENSEMBLE_CHUNK: usize = 8192;

/// A Hamiltonian system made of independent members, one degree of freedom each.
pub trait Ensemble: HamiltonianSystem + Sized + Send + Sync {
    /// The sub-system of members `start..start + len`, at the current state and clock.
    ///
    /// # Errors
    /// If the range is out of bounds.
    fn members(&self, start: usize, len: usize) -> Result<Self>;
}

/// Integrates an [`Ensemble`] in parallel chunks.
///
/// For the explicit methods (`verlet`, `yoshida4`, `rk4`) the result equals
/// [`HamiltonianSystem::integrate_with`] bit for bit. For `implicit_midpoint` each chunk
/// iterates its own solve to the rounding floor, so the result may differ from the serial run
/// in the last bits, but it is the same on any number of threads.
///
/// The observer in `options`, if any, is called from the calling thread every
/// [`PROGRESS_PERIOD`] while the chunks run and once when they have finished, with the mean
/// progress of the chunks; a `Break` stops every chunk.
///
/// # Errors
/// As [`HamiltonianSystem::integrate`], and [`Error::TrajectoryTooLarge`] when the assembled
/// result (counted twice: chunk results and the assembled arrays coexist briefly) would not fit.
pub fn integrate_ensemble<S: Ensemble>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Method,
    options: IntegrateOptions<'_>,
) -> Result<SimulationResult> {
    let n = system.ndof();
    let sampling = options.sampling;
    let skip_energy = options.skip_energy;
    let grid = TimeGrid::new(t_span, dt)?;
    sampling.validate()?;
    let samples = sampling.count(grid.n_steps());
    crate::classical::core::memory_check(samples, 2 * (1 + 2 * n + usize::from(!skip_energy)))?;
    let starts: Vec<usize> = (0..n).step_by(ENSEMBLE_CHUNK).collect();
    let chunks: Vec<S> = starts
        .iter()
        .map(|&s| system.members(s, ENSEMBLE_CHUNK.min(n - s)))
        .collect::<Result<_>>()?;
    let stop = AtomicBool::new(false);
    let progress = AtomicU64::new(0);
    let n_chunks = chunks.len() as u64;
    let work = || {
        chunks
            .into_par_iter()
            .map(|mut chunk| {
                let mut flag = StopFlag {
                    stop: &stop,
                    progress: &progress,
                    reported: 0,
                };
                chunk.integrate_with(
                    t_span,
                    dt,
                    method,
                    IntegrateOptions {
                        sampling,
                        skip_energy: true,
                        observer: Some(&mut flag),
                        observe_every: 1024,
                        tolerances: options.tolerances,
                    },
                )
            })
            .collect::<Result<Vec<SimulationResult>>>()
    };
    let results = match options.observer {
        None => work()?,
        Some(observer) => watched(work, || {
            let done = (progress.load(Ordering::Relaxed) / n_chunks) as usize;
            let t = grid.time(done.min(grid.n_steps()));
            if observer.observe(done, grid.n_steps(), t).is_break() {
                stop.store(true, Ordering::Relaxed);
            }
        })?,
    };
    let first = results
        .first()
        .ok_or_else(|| Error::invalid("n", 0.0, "empty ensemble"))?;
    let rows = first.n_samples();
    // Each chunk's rows are [q_chunk, p_chunk]; the assembled rows are [q, p].
    let mut y = Array2::<f64>::zeros((rows, 2 * n));
    let mut force_evaluations = 0.0;
    for (&start, r) in starts.iter().zip(&results) {
        let width = r.y.ncols() / 2;
        y.slice_mut(s![.., start..start + width])
            .assign(&r.y.slice(s![.., ..width]));
        y.slice_mut(s![.., n + start..n + start + width])
            .assign(&r.y.slice(s![.., width..]));
        force_evaluations += r.extra_scalar("force_evaluations").unwrap_or(0.0);
    }
    let energy = if skip_energy {
        None
    } else {
        let e: Vec<f64> = y
            .rows()
            .into_iter()
            .map(|row| match row.as_slice() {
                Some(state) => system.energy(state),
                None => f64::NAN,
            })
            .collect();
        Some(Array1::from(e))
    };
    let mut extra = first.extra.clone();
    extra.insert(
        "force_evaluations".into(),
        ExtraValue::Scalar(force_evaluations),
    );
    extra.insert("chunks".into(), ExtraValue::Scalar(starts.len() as f64));
    let t = first.t.clone();
    let t_end = t[rows - 1];
    let final_state: Vec<f64> = y.row(rows - 1).to_vec();
    system.reset(Some(&final_state), t_end)?;
    Ok(SimulationResult {
        t,
        y,
        ndof: Some(n),
        energy,
        method: method.name().to_string(),
        extra,
    })
}

/// How often a watched run's observer is called while the work runs.
pub const PROGRESS_PERIOD: Duration = Duration::from_millis(20);

/// Runs `work` on a scoped thread and calls `tick` from the calling thread every
/// [`PROGRESS_PERIOD`] while it runs and once after it ends. The calling thread waits on a
/// channel the worker signals when done, so a run shorter than the period costs only its
/// work (a sleep-and-poll loop would round it up to a whole period). A worker that panics
/// drops its sender, which ends the wait too; its panic becomes an error.
pub(crate) fn watched<R: Send>(
    work: impl FnOnce() -> Result<R> + Send,
    mut tick: impl FnMut(),
) -> Result<R> {
    std::thread::scope(|scope| {
        let (finished, wait) = mpsc::channel::<()>();
        let handle = scope.spawn(move || {
            let out = work();
            // The receiver lives until this scope ends; a failed send cannot happen.
            let _ = finished.send(());
            out
        });
        while let Err(mpsc::RecvTimeoutError::Timeout) = wait.recv_timeout(PROGRESS_PERIOD) {
            tick();
        }
        tick();
        handle.join().unwrap_or_else(|_| {
            Err(Error::Unsupported {
                operation: "ensemble integration".into(),
                reason: "a worker thread panicked".into(),
            })
        })
    })
}

/// The per-chunk observer: counts progress and stops when asked.
struct StopFlag<'a> {
    stop: &'a AtomicBool,
    progress: &'a AtomicU64,
    reported: usize,
}

impl Observer for StopFlag<'_> {
    fn observe(&mut self, step: usize, _n_steps: usize, _t: f64) -> ControlFlow<()> {
        self.progress
            .fetch_add((step - self.reported) as u64, Ordering::Relaxed);
        self.reported = step;
        if self.stop.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
