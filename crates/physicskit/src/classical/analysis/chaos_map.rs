//! Chaos maps: one indicator per initial condition of a grid, on all cores.
//!
//! Each point's orbit is independent: it gets its own [`Flow`](crate::classical::integrators::Flow)
//! and buffers, and its indicator depends on nothing but its initial state. Points are cut
//! into fixed chunks of [`MAP_CHUNK`] handed to rayon's pool, so the result is bit-identical
//! for any number of threads (the chunking decides only who computes a point, never how).
//!
//! Indicators ([`Indicator`]): the largest Lyapunov exponent at the end of the run
//! ([`lyapunov`](super::lyapunov)), SALI at the end of the run ([`sali`](super::sali); the run
//! of a point stops early below [`SALI_FLOOR`] = 1e-14, where SALI has classified the orbit long before and only
//! rounding remains), or the number of crossings of a surface of section
//! ([`section`](super::section)).

use rayon::prelude::*;

use super::lyapunov::max_exponent_on_flow;
use super::sali::sali_on_flow;
use super::section::{section_on_flow, SurfaceOfSection};
use super::watch::AnalysisOptions;
use crate::classical::core::error::check_vector;
use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::Method;
use crate::classical::model::erased::DynSystem;

/// Points per parallel task.
pub const MAP_CHUNK: usize = 4;

/// SALI below which a point's run stops (see the module docs): a map's SALI values are at
/// least this, or exactly zero where the deviation vectors aligned to rounding before a check.
pub const SALI_FLOOR: f64 = 1e-14;

/// What a chaos map computes for each point.
#[derive(Debug, Clone, PartialEq)]
pub enum Indicator {
    /// The largest Lyapunov exponent at the end of the run, renormalizing every
    /// `renormalize_every` steps.
    MaxLyapunov {
        /// Steps between renormalizations.
        renormalize_every: usize,
    },
    /// SALI at the end of the run (or when it fell below [`SALI_FLOOR`]).
    Sali {
        /// Steps between evaluations.
        renormalize_every: usize,
    },
    /// The number of crossings of the surface.
    Crossings(SurfaceOfSection),
}

/// The run shared by every point of a map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRun {
    /// Time span of each orbit.
    pub t_span: (f64, f64),
    /// Step.
    pub dt: f64,
    /// Method (`None`: each system's default).
    pub method: Option<Method>,
    /// The indicator.
    pub indicator: Indicator,
}

/// The indicator of one orbit of `system` from `state0`.
fn one_point(system: &dyn DynSystem, state0: &[f64], grid: &TimeGrid, run: &MapRun) -> Result<f64> {
    let method = run.method.unwrap_or_else(|| system.default_method());
    check_vector("state", state0, system.dynamical().state().len())?;
    match &run.indicator {
        Indicator::MaxLyapunov { renormalize_every } => max_exponent_on_flow(
            system.flow(method, 1)?.as_mut(),
            state0,
            grid,
            *renormalize_every,
            AnalysisOptions::default(),
        ),
        Indicator::Sali { renormalize_every } => sali_on_flow(
            system.flow(method, 2)?.as_mut(),
            state0,
            grid,
            *renormalize_every,
            SALI_FLOOR,
            AnalysisOptions::default(),
        ),
        Indicator::Crossings(surface) => {
            let mut flow = system.flow(method, 0)?;
            let (cut, _) = section_on_flow(
                flow.as_mut(),
                state0,
                grid,
                surface,
                usize::MAX,
                AnalysisOptions::default(),
            )?;
            Ok(cut.len() as f64)
        }
    }
}

/// The indicator for each of `n_points` points, point `i` being the orbit of `point(i)`'s
/// system from its state, in parallel (fixed chunks, bit-identical for any thread count).
/// The systems are not changed.
///
/// # Errors
/// [`Error::InvalidTimeSpan`]; the first error of a point, in point order.
pub fn chaos_map_by<'s, G>(n_points: usize, point: G, run: &MapRun) -> Result<Vec<f64>>
where
    G: Fn(usize) -> (&'s dyn DynSystem, &'s [f64]) + Sync,
{
    let grid = TimeGrid::new(run.t_span, run.dt)?;
    let mut out = vec![0.0; n_points];
    let errors: Vec<Option<Error>> = out
        .par_chunks_mut(MAP_CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            for (j, value) in chunk.iter_mut().enumerate() {
                let (system, state) = point(c * MAP_CHUNK + j);
                match one_point(system, state, &grid, run) {
                    Ok(v) => *value = v,
                    Err(e) => return Some(e),
                }
            }
            None
        })
        .collect();
    match errors.into_iter().flatten().next() {
        Some(e) => Err(e),
        None => Ok(out),
    }
}

/// The indicator for each initial state of `states` (row-major, one row of the system's state
/// length per point) of the one `system`, in parallel. The system is not changed.
///
/// # Errors
/// [`Error::DimensionMismatch`] for rows of the wrong length; as [`chaos_map_by`].
///
/// # Example
/// Two Hénon–Heiles orbits at E = 1/8, one in a regular island, one in the chaotic sea
/// (SALI after t = 500):
///
/// ```
/// use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun};
/// use physicskit::classical::model::erased::Hamiltonian;
/// use physicskit::classical::systems::HenonHeilesSystem;
///
/// let hh = Hamiltonian(HenonHeilesSystem::new(&[0.0, 0.0], &[0.5, 0.0]).unwrap());
/// let energy = 1.0 / 8.0;
/// let py = |x: f64, px: f64| (2.0 * energy - px * px - x * x).sqrt();
/// let states = [0.0, 0.0, 0.0, py(0.0, 0.0), 0.0, -0.2, 0.2, py(0.0, 0.2)];
/// let run = MapRun {
///     t_span: (0.0, 500.0),
///     dt: 0.02,
///     method: None,
///     indicator: Indicator::Sali { renormalize_every: 10 },
/// };
/// let sali = chaos_map(&hh, &states, &run).unwrap();
/// assert_eq!(sali.len(), 2);
/// ```
pub fn chaos_map<S: DynSystem>(system: &S, states: &[f64], run: &MapRun) -> Result<Vec<f64>> {
    let dim = system.dynamical().state().len();
    if dim == 0 || !states.len().is_multiple_of(dim) {
        return Err(Error::DimensionMismatch {
            name: "states (rows of the state length)".into(),
            expected: dim,
            found: states.len(),
        });
    }
    let sys: &dyn DynSystem = system;
    chaos_map_by(
        states.len() / dim,
        |i| (sys, &states[i * dim..(i + 1) * dim]),
        run,
    )
}
