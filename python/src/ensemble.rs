//! `_core.ensemble`: a whole ensemble of a catalogue system or of a SymPy engine's expression
//! system in one call, on all cores with the GIL released
//! ([`physicskit::classical::ensemble::run_source`] on a [`FromCatalogue`] or, built from an
//! [`ExprSpec`], a [`FromParameters`]). The Python function `physicskit.classical.ensemble`
//! shapes the arguments and the outputs (grids, Dask).

use std::ops::ControlFlow;

use numpy::IntoPyArray;
use physicskit::classical::catalog as core_catalog;
use physicskit::classical::ensemble::{
    self as core_ensemble, Condition, Direction, EnsembleResult, Event, FromCatalogue,
    FromParameters, MemberSource, Members, Plan, Reduction, Sweep,
};
use physicskit::classical::{Error, Observer, Tolerances};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

use crate::convert::{Matrix, Vector};
use crate::errors::IntoPyResult;
use crate::expr::ExprSpec;
use crate::params::{key, to_value};

/// Calls the Python `progress(done, total)` callback, if any, and checks for Ctrl-C, from the
/// thread that waits for the ensemble (every 20 ms).
struct Progress {
    callback: Option<Py<PyAny>>,
    raised: Option<PyErr>,
}

impl Observer for Progress {
    fn observe(&mut self, done: usize, total: usize, _t: f64) -> ControlFlow<()> {
        let outcome = Python::attach(|py| {
            py.check_signals()?;
            if let Some(cb) = &self.callback {
                cb.call1(py, (done, total))?;
            }
            Ok::<(), PyErr>(())
        });
        match outcome {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.raised = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}

/// One event as `(index, kind, value)`, `kind` one of `crosses`, `rising`, `falling`,
/// `abs_above`.
fn event(index: usize, kind: &str, value: f64) -> PyResult<Reduction> {
    let crosses = |direction| Condition::Crosses { value, direction };
    let condition = match kind {
        "crosses" => crosses(Direction::Either),
        "rising" => crosses(Direction::Rising),
        "falling" => crosses(Direction::Falling),
        "abs_above" => Condition::AbsExceeds(value),
        other => {
            return Err(PyValueError::new_err(format!(
                "event kind must be one of crosses, rising, falling, abs_above, got {other:?}"
            )))
        }
    };
    Ok(Reduction::FirstEvent(Event { index, condition }))
}

/// The system whose members an ensemble builds.
enum System {
    /// A catalogue entry, with the common values.
    Catalogue(&'static physicskit::classical::model::entry::SystemEntry),
    /// A SymPy engine's expression system.
    Expression(ExprSpec),
}

impl System {
    /// `system` as `_core.ensemble` takes it: a catalogue name, or the dict of an expression
    /// system (see [`ExprSpec::from_dict`]), whose parameters are its own (`common` must then be
    /// empty); the common values of a catalogue system converted into `given`.
    fn from_py(
        system: &Bound<'_, PyAny>,
        common: &Bound<'_, PyDict>,
        given: &mut Vec<(String, physicskit::classical::model::Value)>,
    ) -> PyResult<Self> {
        if let Ok(name) = system.cast::<PyString>() {
            let entry = core_catalog::find(&name.to_string()).py()?;
            for (k, v) in common.iter() {
                let k = key(&k)?;
                let spec = entry.lookup(&k).py()?;
                if let Some(value) = to_value(spec, &v)? {
                    given.push((k, value));
                }
            }
            return Ok(Self::Catalogue(entry));
        }
        let Ok(spec) = system.cast::<PyDict>() else {
            return Err(PyTypeError::new_err(
                "system must be a catalogue name or an expression system's dict",
            ));
        };
        if !common.is_empty() {
            return Err(PyValueError::new_err(
                "common values apply to catalogue systems; an expression system's parameter \
                 values are part of it",
            ));
        }
        Ok(Self::Expression(ExprSpec::from_dict(spec)?))
    }
}

/// Integrates `n` members of `system` (a catalogue name, or an expression system's dict: see
/// [`ExprSpec::from_dict`]): `common` values of a catalogue system (as `build` takes them),
/// `sweeps` of `(parameter or "name[i]", values)`, optional initial `states` (`n x state
/// length`). Returns a dict: `method`, `ndof`, `final_state` (`n x dim`), `t` and
/// `trajectory` (`n x samples x dim`) when `stride` is given, `reductions` (the reductions
/// asked, by name: `max_energy_error`, `event_time` (one per event, in order),
/// `max_lyapunov`, `sali`; each a list of arrays of `n`; `max_lyapunov` and `sali` being
/// their `renormalize_every`), `steps` (the steps each member took: fewer than the span's when
/// `final_state` is false and only events are asked, each member then stopping at its last
/// event; `final_state` is then `n x 0`). `rtol`, `atol` and `max_steps` are an adaptive
/// method's tolerances for every member, checked as `integrate` checks them
/// ([`Tolerances::for_method`], against `method` or, without one, member 0's default).
///
/// # Errors
/// `ValueError` for anything the engine refuses (a bad member named by index, before any
/// integration; with `check_only` nothing else is done and an empty dict returned; with
/// `prechecked`, members that a `check_only` call on the same arguments passed, only member
/// 0 and the plan are checked again before the run: the Dask workers' chunks),
/// `KeyboardInterrupt` on Ctrl-C, and what `progress` raises.
#[pyfunction]
#[pyo3(signature = (system, common, sweeps, states, n, t_span, dt, method=None, stride=None,
                    energy_error=false, events=Vec::new(), max_lyapunov=None, sali=None,
                    final_state=true, threads=None, progress=None, check_only=false,
                    prechecked=false, rtol=None, atol=None, max_steps=None))]
#[allow(clippy::too_many_arguments)]
pub fn ensemble<'py>(
    py: Python<'py>,
    system: &Bound<'py, PyAny>,
    common: &Bound<'py, PyDict>,
    sweeps: Vec<(String, Vector)>,
    states: Option<Matrix>,
    n: usize,
    t_span: (f64, f64),
    dt: f64,
    method: Option<&str>,
    stride: Option<usize>,
    energy_error: bool,
    events: Vec<(usize, String, f64)>,
    max_lyapunov: Option<usize>,
    sali: Option<usize>,
    final_state: bool,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    check_only: bool,
    prechecked: bool,
    rtol: Option<f64>,
    atol: Option<f64>,
    max_steps: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut given = Vec::with_capacity(common.len());
    let system = System::from_py(system, common, &mut given)?;
    let members = Members {
        common: given,
        sweeps: sweeps
            .into_iter()
            .map(|(target, values)| Sweep::new(target, values.0))
            .collect(),
        states: states.map(|s| s.values),
        n,
    };
    let mut reductions = Vec::new();
    if energy_error {
        reductions.push(Reduction::MaxEnergyError);
    }
    for (index, kind, value) in &events {
        reductions.push(event(*index, kind, *value)?);
    }
    if let Some(renormalize_every) = max_lyapunov {
        reductions.push(Reduction::MaxLyapunov { renormalize_every });
    }
    if let Some(renormalize_every) = sali {
        reductions.push(Reduction::Sali { renormalize_every });
    }
    let mut plan = Plan {
        t_span,
        dt,
        method: method.map(str::parse).transpose().py()?,
        stride,
        reductions,
        final_state,
        threads,
        tolerances: None,
    };
    let tolerances = (rtol, atol, max_steps);
    let out = match system {
        System::Catalogue(entry) => {
            let source = FromCatalogue::new(entry, &members).py()?;
            plan.tolerances = checked_tolerances(&source, &plan, tolerances)?;
            execute(py, &source, &plan, progress, check_only, prechecked)?
        }
        System::Expression(spec) => {
            let build = |params: &[f64], state: &[f64]| spec.build(params, state);
            let source =
                FromParameters::new(spec.params.clone(), spec.state.clone(), &members, build)
                    .py()?;
            plan.tolerances = checked_tolerances(&source, &plan, tolerances)?;
            execute(py, &source, &plan, progress, check_only, prechecked)?
        }
    };
    let Some(out) = out else {
        return Ok(PyDict::new(py));
    };
    let d = PyDict::new(py);
    d.set_item("method", out.method.name())?;
    d.set_item("ndof", out.ndof)?;
    d.set_item("final_state", out.final_state.into_pyarray(py))?;
    d.set_item("steps", out.steps.into_pyarray(py))?;
    d.set_item("t", out.t.map(|t| t.into_pyarray(py)))?;
    d.set_item("trajectory", out.trajectory.map(|a| a.into_pyarray(py)))?;
    let reductions = PyDict::new(py);
    for (name, values) in out.reductions {
        let same = match reductions.get_item(name)? {
            Some(list) => list.cast_into::<PyList>()?,
            None => {
                let list = PyList::empty(py);
                reductions.set_item(name, &list)?;
                list
            }
        };
        same.append(values.into_pyarray(py))?;
    }
    d.set_item("reductions", reductions)?;
    Ok(d)
}

/// The tolerances of `(rtol, atol, max_steps)` for the method `plan` runs `source` with
/// (member 0's default when it names none, built only when a tolerance is given).
fn checked_tolerances<S: MemberSource + ?Sized>(
    source: &S,
    plan: &Plan,
    (rtol, atol, max_steps): (Option<f64>, Option<f64>, Option<u64>),
) -> PyResult<Option<Tolerances>> {
    if rtol.is_none() && atol.is_none() && max_steps.is_none() {
        return Ok(None);
    }
    let method = core_ensemble::method(source, plan).py()?;
    Tolerances::for_method(rtol, atol, max_steps, method).py()
}

/// Checks (`check_only`: `None` once every member passed) or runs the members of `source`
/// (`prechecked`: members already checked, see `run_source_prechecked`) with the GIL
/// released, `progress` called and Ctrl-C checked from the waiting thread.
fn execute<S: MemberSource + ?Sized>(
    py: Python<'_>,
    source: &S,
    plan: &Plan,
    progress: Option<Py<PyAny>>,
    check_only: bool,
    prechecked: bool,
) -> PyResult<Option<EnsembleResult>> {
    if check_only {
        py.detach(|| core_ensemble::check_source(source, plan))
            .py()?;
        return Ok(None);
    }
    let (outcome, raised) = py.detach(|| {
        let mut observer = Progress {
            callback: progress,
            raised: None,
        };
        let outcome = if prechecked {
            core_ensemble::run_source_prechecked(source, plan, Some(&mut observer))
        } else {
            core_ensemble::run_source(source, plan, Some(&mut observer))
        };
        (outcome, observer.raised)
    });
    match (outcome, raised) {
        (Ok(r), _) => Ok(Some(r)),
        (Err(Error::Interrupted { .. }), Some(e)) => Err(e),
        (Err(e), _) => Err(crate::errors::to_py(e)),
    }
}

/// Adds `ensemble` and `MAX_THREADS` (the core's limit, so that Python refuses what the core
/// would, before building anything) to the module.
///
/// # Errors
/// Python errors while registering.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MAX_THREADS", core_ensemble::MAX_THREADS)?;
    m.add_function(wrap_pyfunction!(ensemble, m)?)
}
