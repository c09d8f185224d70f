//! Systems written in Python, integrated by the Rust integrators.
//!
//! A Python subclass of `HamiltonianSystem` (or `ODESystem`, or a `LagrangianSystem` that has
//! no `LagrangianEngine`) is wrapped in `PyHamiltonian` (or `PyOde`), which implements the
//! core traits by calling the Python methods (`force`, `derivatives`, `energy`) with the GIL
//! held. The same integrators run as for the built-in systems; only the right-hand side costs
//! a Python call. The first Python exception raised by a callback stops the run and is
//! re-raised unchanged.
//!
//! What a callback returns is read as float64 directly when it is a float64 array or a
//! `float`; anything else (a list, an integer array, a numpy integer, a complex number) goes
//! through the Python package's converters (`physicskit.classical._native`), whose rules refuse
//! complex values, booleans and strings with a `ValueError` instead of casting them.

use std::cell::RefCell;

use numpy::{PyArray1, PyReadonlyArray1};
use physicskit::classical::integrators::separable_derivatives;
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, MassInv, Method, OdeSystem, Phase,
    Result, SimulationResult, Tolerances,
};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyTuple};

use physicskit::classical::integrators::{hamiltonian_flow, ode_flow, Flow};
use physicskit::classical::TimeGrid;
use pyo3::types::PyDict;

use crate::chaos;
use crate::convert::{result_tuple, Vector};
use crate::errors::IntoPyResult;
use crate::interrupt::{SignalObserver, CHECK_EVERY};
use crate::native::{parse_method, sampling};

/// The Python object and the first exception its methods raised.
struct Callbacks<'py> {
    obj: Bound<'py, PyAny>,
    raised: RefCell<Option<PyErr>>,
}

impl<'py> Callbacks<'py> {
    fn new(obj: Bound<'py, PyAny>) -> Self {
        Self {
            obj,
            raised: RefCell::new(None),
        }
    }

    /// Keeps the first Python exception and turns it into a core error that stops the run.
    fn stash(&self, e: PyErr, what: &str) -> Error {
        let mut slot = self.raised.borrow_mut();
        if slot.is_none() {
            *slot = Some(e);
        }
        Error::Unsupported {
            operation: what.into(),
            reason: "the Python method raised".into(),
        }
    }

    fn call(
        &self,
        name: &Bound<'py, pyo3::types::PyString>,
        args: impl pyo3::call::PyCallArgs<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.obj.call_method1(name, args)
    }

    /// Calls `name(*args)` and copies the returned 1-D array into `out`.
    ///
    /// The method name is only formatted on failure, or for a result that is not a float64
    /// array: this runs once per step (or per stage).
    fn vector(
        &self,
        name: &Bound<'py, pyo3::types::PyString>,
        args: impl pyo3::call::PyCallArgs<'py>,
        out: &mut [f64],
    ) -> Result<()> {
        let r = self
            .call(name, args)
            .map_err(|e| self.stash(e, &name.to_string()))?;
        // The common case, an aligned contiguous float64 array of the right length, is copied
        // straight into `out`; anything else goes through the one reader, after the system's
        // own conversion for what is not a float64 array.
        if let Ok(a) = r.extract::<PyReadonlyArray1<'_, f64>>() {
            if let Ok(s) = a.as_slice() {
                if s.len() == out.len() {
                    out.copy_from_slice(s);
                    return Ok(());
                }
            }
        }
        let a = match r.extract::<Vector>() {
            Ok(a) => a,
            Err(_) => self
                .convert("as_vector", name, &r)
                .and_then(|a| a.extract::<Vector>())
                .map_err(|e| self.stash(e, &name.to_string()))?,
        };
        fill(out, &a.0, name)
    }

    /// Calls `name(*args)` and copies the returned square matrix (any array-like of shape
    /// `(n, n)`, `n * n = out.len()`) into `out`, row-major. Used for the optional Jacobians,
    /// once per step of a tangent run.
    fn matrix(
        &self,
        name: &Bound<'py, pyo3::types::PyString>,
        args: impl pyo3::call::PyCallArgs<'py>,
        out: &mut [f64],
    ) -> Result<()> {
        let fail = |e: PyErr| self.stash(e, &name.to_string());
        let r = self.call(name, args).map_err(fail)?;
        let a = self.convert("as_array", name, &r).map_err(fail)?;
        let a = a
            .call_method0(intern!(self.obj.py(), "ravel"))
            .and_then(|a| a.extract::<Vector>())
            .map_err(fail)?;
        let n = out.len().isqrt();
        let square = r
            .getattr(intern!(self.obj.py(), "shape"))
            .and_then(|s| s.extract::<Vec<usize>>())
            .is_ok_and(|s| s == [n, n]);
        if !square {
            return Err(Error::DimensionMismatch {
                name: format!("value returned by {name} (an ndof x ndof matrix)"),
                expected: out.len(),
                found: a.0.len(),
            });
        }
        fill(out, &a.0, name)
    }

    /// Calls `name(*args)` and converts the result to a float; NaN (and a stashed exception)
    /// on failure, which stops the run at the next sample.
    fn scalar(
        &self,
        name: &Bound<'py, pyo3::types::PyString>,
        args: impl pyo3::call::PyCallArgs<'py>,
    ) -> f64 {
        let value = self.call(name, args).and_then(|r| {
            // `float` and its subclasses (numpy's float64) are read as they are; anything else
            // by the package's rules, which refuse a complex number rather than drop its
            // imaginary part.
            if r.is_instance_of::<PyFloat>() {
                r.extract::<f64>()
            } else {
                self.convert("as_real", name, &r)?.extract::<f64>()
            }
        });
        match value {
            Ok(v) => v,
            Err(e) => {
                self.stash(e, &name.to_string());
                f64::NAN
            }
        }
    }

    /// `physicskit.classical._native.<converter>("value returned by <name>", value)`.
    fn convert(
        &self,
        converter: &str,
        name: &Bound<'py, pyo3::types::PyString>,
        value: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = self.obj.py();
        let module = py.import(intern!(py, "physicskit.classical._native"))?;
        let what = format!("value returned by {name}");
        let kwargs = pyo3::types::PyDict::new(py);
        if converter == "as_vector" {
            kwargs.set_item(intern!(py, "finite"), false)?;
        }
        module
            .getattr(converter)?
            .call((what, value), Some(&kwargs))
    }

    /// The Python `derivatives(t, state)`, the right-hand side of both callback families.
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let py = self.obj.py();
        self.vector(intern!(py, "derivatives"), (t, self.array(state)), out)
    }

    /// The Python `energy(state)`.
    fn energy(&self, state: &[f64]) -> f64 {
        self.scalar_of(intern!(self.obj.py(), "energy"), state)
    }

    /// `name(x)` for one array argument, as a float (see [`scalar`](Self::scalar)).
    fn scalar_of(&self, name: &Bound<'py, pyo3::types::PyString>, x: &[f64]) -> f64 {
        self.scalar(name, (self.array(x),))
    }

    fn array(&self, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(self.obj.py(), v)
    }

    /// The result, or the first exception a callback raised.
    fn finish(
        self,
        outcome: Result<SimulationResult>,
        signal: Option<PyErr>,
    ) -> PyResult<SimulationResult> {
        self.finish_with(outcome, signal)
    }

    /// [`finish`](Self::finish) for any outcome.
    fn finish_with<T>(&self, outcome: Result<T>, signal: Option<PyErr>) -> PyResult<T> {
        if let Some(e) = self.raised.borrow_mut().take() {
            return Err(e);
        }
        match (outcome, signal) {
            (Err(Error::Interrupted { .. }), Some(s)) => Err(s),
            (outcome, _) => outcome.py(),
        }
    }
}

fn fill(out: &mut [f64], v: &[f64], what: &Bound<'_, pyo3::types::PyString>) -> Result<()> {
    if v.len() != out.len() {
        return Err(Error::DimensionMismatch {
            name: format!("value returned by {what}"),
            expected: out.len(),
            found: v.len(),
        });
    }
    out.copy_from_slice(v);
    Ok(())
}

/// A Python `HamiltonianSystem` subclass seen as a Rust [`HamiltonianSystem`].
struct PyHamiltonian<'py> {
    cb: Callbacks<'py>,
    phase: Phase,
    ndof: usize,
    separable: bool,
    mass_inv: Vec<f64>,
    /// The object defines `force_jacobian(q, t)`.
    has_jacobian: bool,
}

impl DynamicalSystem for PyHamiltonian<'_> {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        if self.separable {
            separable_derivatives(self, t, state, out)
        } else {
            self.cb.derivatives(t, state, out)
        }
    }
    fn energy(&self, state: &[f64]) -> f64 {
        self.cb.energy(state)
    }
    fn default_method(&self) -> Method {
        Method::Yoshida4
    }
}

impl HamiltonianSystem for PyHamiltonian<'_> {
    fn ndof(&self) -> usize {
        self.ndof
    }
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        self.cb
            .scalar_of(intern!(self.cb.obj.py(), "kinetic_energy"), p)
    }
    fn potential_energy(&self, q: &[f64]) -> f64 {
        self.cb
            .scalar_of(intern!(self.cb.obj.py(), "potential_energy"), q)
    }
    fn separable(&self) -> bool {
        self.separable
    }
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::PerCoordinate(&self.mass_inv)
    }
    fn force(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let py = self.cb.obj.py();
        self.cb
            .vector(intern!(py, "force"), (self.cb.array(q), t), out)
    }
    fn force_jacobian(&self, q: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let py = self.cb.obj.py();
        self.has_jacobian.then(|| {
            self.cb
                .matrix(intern!(py, "force_jacobian"), (self.cb.array(q), t), out)
        })
    }
}

/// A Python `ODESystem` (or engine-less `LagrangianSystem`) seen as a Rust [`OdeSystem`].
struct PyOde<'py> {
    cb: Callbacks<'py>,
    phase: Phase,
    /// The object defines `jacobian(t, state)`.
    has_jacobian: bool,
}

impl DynamicalSystem for PyOde<'_> {
    fn phase(&self) -> &Phase {
        &self.phase
    }
    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        self.cb.derivatives(t, state, out)
    }
    fn energy(&self, state: &[f64]) -> f64 {
        self.cb.energy(state)
    }
    fn default_method(&self) -> Method {
        Method::ImplicitMidpoint
    }
    fn jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let py = self.cb.obj.py();
        self.has_jacobian.then(|| {
            self.cb
                .matrix(intern!(py, "jacobian"), (t, self.cb.array(state)), out)
        })
    }
}

impl OdeSystem for PyOde<'_> {}

impl<'py> PyHamiltonian<'py> {
    fn new(
        obj: Bound<'py, PyAny>,
        state: Vec<f64>,
        t0: f64,
        ndof: usize,
        separable: bool,
        mass_inv: Vec<f64>,
    ) -> Result<Self> {
        crate::native::check_len("state", &state, 2 * ndof)?;
        crate::native::check_len("mass_inv", &mass_inv, ndof)?;
        let has_jacobian = obj.hasattr("force_jacobian").unwrap_or(false);
        Ok(Self {
            cb: Callbacks::new(obj),
            phase: Phase::new(state, t0)?,
            ndof,
            separable,
            mass_inv,
            has_jacobian,
        })
    }
}

impl<'py> PyOde<'py> {
    fn new(obj: Bound<'py, PyAny>, state: Vec<f64>, t0: f64) -> Result<Self> {
        let has_jacobian = obj.hasattr("jacobian").unwrap_or(false);
        Ok(Self {
            cb: Callbacks::new(obj),
            phase: Phase::new(state, t0)?,
            has_jacobian,
        })
    }
}

/// The options of a callback run: the requested sampling, and Ctrl-C checks.
fn options(
    observer: &mut SignalObserver,
    stride: usize,
    final_only: bool,
    energy: bool,
    (rtol, atol, max_steps, method): (Option<f64>, Option<f64>, Option<u64>, Method),
) -> Result<IntegrateOptions<'_>> {
    Ok(IntegrateOptions {
        sampling: sampling(stride, final_only)?,
        skip_energy: !energy,
        observer: Some(observer),
        // A Python right-hand side is ~100x slower than a native one: check more often.
        observe_every: CHECK_EVERY / 16,
        tolerances: Tolerances::for_method(rtol, atol, max_steps, method)?,
    })
}

/// Integrates a Python `HamiltonianSystem` subclass `obj` from `(state, t0)` with the Rust
/// integrators; returns the result tuple `(t, y, energy, method, extra)`. `stride`,
/// `final_only`, `energy`, `progress`, `rtol`, `atol` and `max_steps` as for
/// `NativeSystem.integrate`.
#[pyfunction]
#[pyo3(signature = (obj, state, t0, t_span, dt, method, ndof, separable, mass_inv, stride=1, final_only=false, energy=true, progress=None, rtol=None, atol=None, max_steps=None))]
#[allow(clippy::too_many_arguments)]
pub fn integrate_hamiltonian<'py>(
    py: Python<'py>,
    obj: Bound<'py, PyAny>,
    state: Vector,
    t0: f64,
    t_span: (f64, f64),
    dt: f64,
    method: &str,
    ndof: usize,
    separable: bool,
    mass_inv: Vector,
    stride: usize,
    final_only: bool,
    energy: bool,
    progress: Option<Py<PyAny>>,
    rtol: Option<f64>,
    atol: Option<f64>,
    max_steps: Option<u64>,
) -> PyResult<Bound<'py, PyTuple>> {
    let method = parse_method(Some(method), Method::Yoshida4, separable, false).py()?;
    let mut sys = PyHamiltonian::new(obj, state.0, t0, ndof, separable, mass_inv.0).py()?;
    let mut observer = SignalObserver::new(progress);
    let options = options(
        &mut observer,
        stride,
        final_only,
        energy,
        (rtol, atol, max_steps, method),
    )
    .py()?;
    let outcome = sys.integrate_with(t_span, dt, method, options);
    let r = sys.cb.finish(outcome, observer.raised)?;
    result_tuple(py, r)
}

/// Integrates a Python `ODESystem` (or engine-less `LagrangianSystem`) `obj` from
/// `(state, t0)`; returns the result tuple `(t, y, energy, method, extra)`.
/// `stride`, `final_only`, `energy`, `progress`, `rtol`, `atol` and `max_steps` as for
/// `NativeSystem.integrate`.
#[pyfunction]
#[pyo3(signature = (obj, state, t0, t_span, dt, method, stride=1, final_only=false, energy=true, progress=None, rtol=None, atol=None, max_steps=None))]
#[allow(clippy::too_many_arguments)]
pub fn integrate_ode<'py>(
    py: Python<'py>,
    obj: Bound<'py, PyAny>,
    state: Vector,
    t0: f64,
    t_span: (f64, f64),
    dt: f64,
    method: &str,
    stride: usize,
    final_only: bool,
    energy: bool,
    progress: Option<Py<PyAny>>,
    rtol: Option<f64>,
    atol: Option<f64>,
    max_steps: Option<u64>,
) -> PyResult<Bound<'py, PyTuple>> {
    let method = parse_method(Some(method), Method::ImplicitMidpoint, false, false).py()?;
    let mut sys = PyOde::new(obj, state.0, t0).py()?;
    let mut observer = SignalObserver::new(progress);
    let options = options(
        &mut observer,
        stride,
        final_only,
        energy,
        (rtol, atol, max_steps, method),
    )
    .py()?;
    let outcome = sys.integrate_with(t_span, dt, method, options);
    let r = sys.cb.finish(outcome, observer.raised)?;
    result_tuple(py, r)
}

/// Runs a chaos analysis (`kind` and options as `chaos.chaos_native`) on a Python
/// `HamiltonianSystem` subclass from `(state, t0)`; returns the dict of results with `state`
/// and `t_end`.
#[pyfunction]
#[pyo3(signature = (obj, state, t0, t_span, dt, method, ndof, separable, mass_inv, kind, **options))]
#[allow(clippy::too_many_arguments)]
pub fn chaos_hamiltonian<'py>(
    py: Python<'py>,
    obj: Bound<'py, PyAny>,
    state: Vector,
    t0: f64,
    t_span: (f64, f64),
    dt: f64,
    method: &str,
    ndof: usize,
    separable: bool,
    mass_inv: Vector,
    kind: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let job = chaos::job_from_py(kind, options)?;
    let method = parse_method(Some(method), Method::Yoshida4, separable, false).py()?;
    let sys = PyHamiltonian::new(obj, state.0, t0, ndof, separable, mass_inv.0).py()?;
    let mut observer = SignalObserver::default();
    let outcome = chaos_run(&sys, t_span, dt, &job, &mut observer, |s, k| {
        hamiltonian_flow(s, method, k)
    });
    let out = sys.cb.finish_with(outcome, observer.raised)?;
    chaos::to_dict(py, out)
}

/// Runs a chaos analysis on a Python `ODESystem` (or engine-less `LagrangianSystem`) `obj`
/// from `(state, t0)`; as [`chaos_hamiltonian`].
#[pyfunction]
#[pyo3(signature = (obj, state, t0, t_span, dt, method, kind, **options))]
#[allow(clippy::too_many_arguments)]
pub fn chaos_ode<'py>(
    py: Python<'py>,
    obj: Bound<'py, PyAny>,
    state: Vector,
    t0: f64,
    t_span: (f64, f64),
    dt: f64,
    method: &str,
    kind: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let job = chaos::job_from_py(kind, options)?;
    let method = parse_method(Some(method), Method::ImplicitMidpoint, false, false).py()?;
    let sys = PyOde::new(obj, state.0, t0).py()?;
    let mut observer = SignalObserver::default();
    let outcome = chaos_run(&sys, t_span, dt, &job, &mut observer, |s, k| {
        ode_flow(s, method, k)
    });
    let out = sys.cb.finish_with(outcome, observer.raised)?;
    chaos::to_dict(py, out)
}

/// The job on the flow `make(system, vectors)` from the system's state and clock.
fn chaos_run<'s, S: DynamicalSystem>(
    sys: &'s S,
    t_span: (f64, f64),
    dt: f64,
    job: &chaos::Job,
    observer: &mut SignalObserver,
    make: impl FnOnce(&'s S, usize) -> Result<Box<dyn Flow + 's>>,
) -> Result<chaos::JobResult> {
    let grid = TimeGrid::new(t_span, dt)?;
    let state = sys.state().to_vec();
    let mut flow = make(sys, job.vectors(state.len()))?;
    // Python callbacks are ~100x slower than native code: check more often, as `integrate`.
    chaos::run(
        flow.as_mut(),
        &state,
        &grid,
        job,
        observer,
        CHECK_EVERY / 16,
    )
}

/// Registers the callback integrators.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(integrate_hamiltonian, m)?)?;
    m.add_function(wrap_pyfunction!(integrate_ode, m)?)?;
    m.add_function(wrap_pyfunction!(chaos_hamiltonian, m)?)?;
    m.add_function(wrap_pyfunction!(chaos_ode, m)?)?;
    Ok(())
}
