//! Phase-space and chaos analyses from Python: Poincaré sections, Lyapunov spectra, SALI and
//! GALI, chaos maps.
//!
//! Each analysis is a [`Job`] run on the core's [`Flow`] of the system and method
//! (`physicskit::classical::analysis`): `chaos_native` for a built-in system (GIL released,
//! monomorphized for the system), `chaos_hamiltonian` / `chaos_ode` for systems written in
//! Python (their methods called back, with their optional `force_jacobian(q, t)` /
//! `jacobian(t, state)` for the tangent dynamics, else central differences), and `chaos_map`
//! / `chaos_map_systems` for a grid of initial conditions on all cores. Each returns a dict
//! of arrays that `physicskit.classical.chaos` turns into its result objects.

use numpy::{IntoPyArray, PyArrayMethods};
use physicskit::classical::analysis::chaos_map::{chaos_map_by, Indicator, MapRun};
use physicskit::classical::analysis::lyapunov::{lyapunov_on_flow, DEFAULT_RENORMALIZE_EVERY};
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::sali::{alignment_on_flow, Alignment, CHAOS_THRESHOLD};
use physicskit::classical::analysis::section::{
    section_on_flow, taylor_section, Continuation, SurfaceOfSection,
};
use physicskit::classical::analysis::watch::AnalysisOptions;
use physicskit::classical::integrators::Flow;
use physicskit::classical::model::erased::DynSystem;
use physicskit::classical::{Error, Method, Result, TimeGrid, Tolerances};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{Matrix, Vector};
use crate::errors::IntoPyResult;
use crate::interrupt::{SignalObserver, CHECK_EVERY};
use crate::native::{parse_method, NativeSystem};

/// One analysis, as the Python functions describe it.
#[derive(Debug, Clone)]
pub enum Job {
    /// A Poincaré section.
    Section(SurfaceOfSection),
    /// `k` Lyapunov exponents (`None`: all).
    Lyapunov {
        /// Number of exponents.
        k: Option<usize>,
        /// Steps between renormalizations.
        every: usize,
        /// Keep every `stride`-th row of the history.
        stride: usize,
    },
    /// SALI or GALI_k.
    Alignment {
        /// Which index.
        which: Alignment,
        /// Steps between evaluations.
        every: usize,
        /// Keep every `stride`-th evaluation.
        stride: usize,
    },
}

/// A job's named outputs and where its run ended.
pub type JobResult = (Vec<(&'static str, Output)>, Continuation);

impl Job {
    /// The deviation vectors the job needs on a state of `dim` components.
    pub fn vectors(&self, dim: usize) -> usize {
        match self {
            Job::Section(_) => 0,
            Job::Lyapunov { k, .. } => k.unwrap_or(dim),
            Job::Alignment { which, .. } => match which {
                Alignment::Sali => 2,
                Alignment::Gali(k) => *k,
            },
        }
    }
}

/// What a job returns: names and arrays (or a string for the verdict).
pub enum Output {
    /// A float64 array (with its shape).
    Array(Vec<f64>, Vec<usize>),
    /// A string.
    Text(&'static str),
}

fn direction(d: i64) -> Result<Direction> {
    match d {
        1 => Ok(Direction::Increasing),
        -1 => Ok(Direction::Decreasing),
        0 => Ok(Direction::Both),
        _ => Err(Error::invalid(
            "direction",
            d as f64,
            "must be 1 (increasing), -1 (decreasing) or 0 (both)",
        )),
    }
}

/// The options of a job, as keyword arguments: `coordinate`, `normal`, `value`, `direction`
/// (sections), `n_exponents` (Lyapunov), `renormalize_every` and `history_stride` (Lyapunov,
/// SALI, GALI), `k` (GALI), each optional.
#[derive(Debug, Clone)]
pub struct JobOptions {
    coordinate: Option<usize>,
    normal: Option<Vec<f64>>,
    value: f64,
    direction: i64,
    n_exponents: Option<usize>,
    renormalize_every: usize,
    history_stride: usize,
    k: usize,
}

impl JobOptions {
    /// Reads the options from keyword arguments, refusing unknown names.
    ///
    /// # Errors
    /// `TypeError` for an unknown name or a value of the wrong type.
    pub fn from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut o = Self {
            coordinate: None,
            normal: None,
            value: 0.0,
            direction: 1,
            n_exponents: None,
            renormalize_every: DEFAULT_RENORMALIZE_EVERY,
            history_stride: 1,
            k: 2,
        };
        let Some(kwargs) = kwargs else {
            return Ok(o);
        };
        for (key, v) in kwargs.iter() {
            let key: String = key.extract()?;
            match key.as_str() {
                "coordinate" => o.coordinate = v.extract()?,
                "normal" => o.normal = v.extract()?,
                "value" => o.value = v.extract()?,
                "direction" => o.direction = v.extract()?,
                "n_exponents" => o.n_exponents = v.extract()?,
                "renormalize_every" => o.renormalize_every = v.extract()?,
                "history_stride" => o.history_stride = v.extract()?,
                "k" => o.k = v.extract()?,
                other => {
                    return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                        "unexpected keyword argument `{other}`"
                    )))
                }
            }
        }
        Ok(o)
    }
}

/// The job `kind` (`"section"`, `"lyapunov"`, `"sali"`, `"gali"`) with its options.
///
/// # Errors
/// [`Error::InvalidParameter`] or [`Error::InvalidArgument`] for an unknown kind, a bad
/// direction, or a section with neither or both of `coordinate` and `normal`.
pub fn job(kind: &str, o: JobOptions) -> Result<Job> {
    let every = o.renormalize_every;
    let stride = o.history_stride;
    if stride == 0 {
        return Err(Error::invalid("history_stride", 0.0, "must be >= 1"));
    }
    Ok(match kind {
        "section" => {
            let d = direction(o.direction)?;
            match (o.coordinate, o.normal) {
                (Some(i), None) => Job::Section(SurfaceOfSection::coordinate(i, o.value, d)?),
                (None, Some(a)) => Job::Section(SurfaceOfSection::linear(a, o.value, d)?),
                _ => {
                    return Err(Error::InvalidArgument {
                        name: "coordinate".into(),
                        reason: "give exactly one of `coordinate` (an index into the state) \
                                 and `normal` (the coefficients a of a·y = value)"
                            .into(),
                    })
                }
            }
        }
        "lyapunov" => Job::Lyapunov {
            k: o.n_exponents,
            every,
            stride,
        },
        "sali" => Job::Alignment {
            which: Alignment::Sali,
            every,
            stride,
        },
        "gali" => Job::Alignment {
            which: Alignment::Gali(o.k),
            every,
            stride,
        },
        other => {
            return Err(Error::InvalidArgument {
                name: "kind".into(),
                reason: format!("unknown analysis `{other}`"),
            })
        }
    })
}

/// The job from a Python call's `kind` and keyword arguments.
///
/// # Errors
/// As [`JobOptions::from_kwargs`] and [`job`], as Python exceptions.
pub fn job_from_py(kind: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Job> {
    job(kind, JobOptions::from_kwargs(kwargs)?).py()
}

/// Runs `job` on `flow` from `state0` over `grid`, `observer` checking for Ctrl-C every
/// `check_every` steps.
///
/// # Errors
/// Whatever the analysis reports; [`Error::Interrupted`] when a signal handler raised (the
/// exception is in `observer`).
pub fn run(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    job: &Job,
    observer: &mut SignalObserver,
    check_every: usize,
) -> Result<JobResult> {
    let dim = state0.len();
    let options = AnalysisOptions::observed(observer, check_every);
    Ok(match job {
        Job::Section(surface) => {
            let (cut, end) = section_on_flow(flow, state0, grid, surface, usize::MAX, options)?;
            let n = cut.len();
            (
                vec![
                    ("t", Output::Array(cut.t, vec![n])),
                    ("y", Output::Array(cut.states, vec![n, dim])),
                ],
                end,
            )
        }
        Job::Lyapunov { k, every, stride } => {
            let k = k.unwrap_or(flow.dim());
            let options = options.with_history_stride(*stride);
            let (s, end) = lyapunov_on_flow(flow, state0, grid, k, *every, options)?;
            let rows = s.t.len();
            (
                vec![
                    ("exponents", Output::Array(s.exponents, vec![k])),
                    ("t", Output::Array(s.t, vec![rows])),
                    ("history", Output::Array(s.history, vec![rows, k])),
                ],
                end,
            )
        }
        Job::Alignment {
            which,
            every,
            stride,
        } => {
            let options = options.with_history_stride(*stride);
            let (s, end) = alignment_on_flow(flow, state0, grid, *which, *every, 0.0, options)?;
            let verdict = s.verdict().name();
            let rows = s.t.len();
            (
                vec![
                    ("t", Output::Array(s.t, vec![rows])),
                    ("index", Output::Array(s.index, vec![rows])),
                    ("verdict", Output::Text(verdict)),
                ],
                end,
            )
        }
    })
}

/// The job's output as a dict, plus `state` and `t` where the run ended.
///
/// # Errors
/// Python allocation failures.
pub fn to_dict<'py>(py: Python<'py>, (items, end): JobResult) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, value) in items {
        match value {
            Output::Array(v, shape) => {
                let a = v.into_pyarray(py);
                if shape.len() == 2 {
                    d.set_item(name, a.reshape([shape[0], shape[1]])?)?;
                } else {
                    d.set_item(name, a)?;
                }
            }
            Output::Text(s) => d.set_item(name, s)?,
        }
    }
    d.set_item("state", end.state.into_pyarray(py))?;
    d.set_item("t_end", end.t)?;
    Ok(d)
}

/// Runs an analysis on a built-in system from `(state, t0)` over `t_span` with `dt` and
/// `method` (the system's default for `None`), with the GIL released; the system is left at
/// the end of the run. Returns a dict of the results plus `state` and `t_end`.
#[pyfunction]
#[pyo3(signature = (native, state, t0, t_span, dt, method, kind, **options))]
#[allow(clippy::too_many_arguments)]
pub fn chaos_native<'py>(
    py: Python<'py>,
    mut native: PyRefMut<'_, NativeSystem>,
    state: Vector,
    t0: f64,
    t_span: (f64, f64),
    dt: f64,
    method: Option<&str>,
    kind: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let job = job_from_py(kind, options)?;
    let state = state.0;
    // Only a section runs on the Taylor form (crossings on the step polynomial); the tangent
    // flows of the other analyses have none.
    let taylor = matches!(job, Job::Section(_)) && native.has_taylor_form();
    let inner = native.inner_mut();
    let method = parse_method(method, inner.default_method(), true, taylor).py()?;
    let mut observer = SignalObserver::default();
    let outcome = py.detach(|| -> Result<_> {
        inner.reset(Some(&state), t0)?;
        let grid = TimeGrid::new(t_span, dt)?;
        if let (Job::Section(surface), true) = (&job, method.needs_taylor_form()) {
            // The Taylor method chooses its own steps (`dt` is not used) and leaves the
            // system where the run ended.
            let cut = taylor_section(
                &mut **inner,
                t_span,
                Tolerances::default(),
                surface,
                usize::MAX,
            )?;
            let n = cut.len();
            let dim = state.len();
            let end = Continuation {
                state: inner.dynamical().state().to_vec(),
                t: inner.dynamical().t(),
            };
            return Ok((
                vec![
                    ("t", Output::Array(cut.t, vec![n])),
                    ("y", Output::Array(cut.states, vec![n, dim])),
                ],
                end,
            ));
        }
        let out = {
            let sys: &dyn DynSystem = &**inner;
            let mut flow = sys.flow(method, job.vectors(state.len()))?;
            run(
                flow.as_mut(),
                &state,
                &grid,
                &job,
                &mut observer,
                CHECK_EVERY,
            )?
        };
        inner.reset(Some(&out.1.state), out.1.t)?;
        Ok(out)
    });
    match (outcome, observer.raised) {
        (Ok(out), _) => to_dict(py, out),
        (Err(Error::Interrupted { .. }), Some(signal)) => Err(signal),
        (Err(e), _) => Err(crate::errors::to_py(e)),
    }
}

fn indicator(kind: &str, job: Job) -> Result<Indicator> {
    Ok(match (kind, job) {
        ("lyapunov", Job::Lyapunov { every, .. }) => Indicator::MaxLyapunov {
            renormalize_every: every,
        },
        ("sali", Job::Alignment { every, .. }) => Indicator::Sali {
            renormalize_every: every,
        },
        ("crossings", Job::Section(surface)) => Indicator::Crossings(surface),
        _ => {
            return Err(Error::InvalidArgument {
                name: "indicator".into(),
                reason: format!(
                    "unknown indicator `{kind}`: use \"lyapunov\", \"sali\" or \"crossings\""
                ),
            })
        }
    })
}

/// The job kind an indicator name reads its options as.
fn job_kind(indicator: &str) -> &str {
    match indicator {
        "crossings" => "section",
        other => other,
    }
}

/// One indicator per point: point `i` is the orbit of `systems[i]` (or of `systems[0]` for
/// every point when one system is given) from row `i` of `states`, over `t_span` with `dt`;
/// on all cores with the GIL released, bit-identical for any number of threads. The systems
/// are not changed.
#[pyfunction]
#[pyo3(signature = (systems, states, t_span, dt, method, indicator_name, **options))]
#[allow(clippy::too_many_arguments)]
pub fn chaos_map<'py>(
    py: Python<'py>,
    systems: Vec<PyRef<'py, NativeSystem>>,
    states: Matrix,
    t_span: (f64, f64),
    dt: f64,
    method: Option<&str>,
    indicator_name: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let job = job_from_py(job_kind(indicator_name), options)?;
    let indicator = indicator(indicator_name, job).py()?;
    let method = method.map(str::parse::<Method>).transpose().py()?;
    let [n_points, dim] = states.shape;
    let states = states.values;
    if systems.is_empty() || (systems.len() != 1 && systems.len() != n_points) {
        return Err(Error::DimensionMismatch {
            name: "systems (one, or one per point)".into(),
            expected: n_points,
            found: systems.len(),
        })
        .py();
    }
    let inners: Vec<&dyn DynSystem> = systems.iter().map(|s| s.inner()).collect();
    let run = MapRun {
        t_span,
        dt,
        method,
        indicator,
    };
    let out = py.detach(|| {
        chaos_map_by(
            n_points,
            |i| {
                let sys = if inners.len() == 1 {
                    inners[0]
                } else {
                    inners[i]
                };
                (sys, &states[i * dim..(i + 1) * dim])
            },
            &run,
        )
    });
    Ok(out.py()?.into_pyarray(py))
}

/// Registers the analyses and `CHAOS_THRESHOLD` (the core's constant, so Python's verdicts and
/// plots use the same value as Rust's).
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("CHAOS_THRESHOLD", CHAOS_THRESHOLD)?;
    m.add("DEFAULT_RENORMALIZE_EVERY", DEFAULT_RENORMALIZE_EVERY)?;
    m.add_function(wrap_pyfunction!(chaos_native, m)?)?;
    m.add_function(wrap_pyfunction!(chaos_map, m)?)?;
    Ok(())
}
