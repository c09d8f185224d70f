//! [`NativeSystem`]: the one Python class that wraps every built-in Rust system.
//!
//! It holds the core's type-erased [`DynSystem`] (built by `_core.build` from the catalogue,
//! or by `_core.expr_lagrangian` for the SymPy engine). `integrate` calls the family's generic
//! `integrate_with` behind `DynSystem::integrate`, so the step loop is monomorphized for the
//! concrete system: the only dynamic dispatch is the one call into `integrate`. The family
//! views (`hamiltonian()`, `lagrangian()`) serve `kinetic_energy`, `force`, `acceleration` ...;
//! what only some systems offer (`positions`, `lrl_vector`, normal modes, a rotation matrix
//! ...) is one method per [`Capabilities`] accessor, which raises `NotImplementedError` for a
//! system without it. Nothing here knows a concrete system type.

use numpy::{IntoPyArray, PyArray1, PyArray2};
use physicskit::classical::integrators::taylor::no_taylor_form;
use physicskit::classical::model::entry::{SystemEntry, Values};
use physicskit::classical::model::erased::{missing, offered, Capabilities, DynSystem};
use physicskit::classical::{
    Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method, Result, Sampling,
    Tolerances,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::convert::{array1, result_tuple, Vector};
use crate::errors::IntoPyResult;
use crate::interrupt::{SignalObserver, CHECK_EVERY};
use crate::params::values_to_dict;

/// Checks an input length (and finiteness) before it reaches a system.
///
/// # Errors
/// [`Error::DimensionMismatch`] or [`Error::NonFinite`].
pub fn check_len(name: &str, v: &[f64], n: usize) -> Result<()> {
    physicskit::classical::core::error::check_vector(name, v, n)
}

/// Parses a method name, or takes the system's default for `None`, for a system that accepts
/// the splitting methods when `splitting` (a separable, conservative Hamiltonian) and the
/// methods that need a Taylor form when `taylor` (a system that has one).
///
/// # Errors
/// [`Error::UnknownMethod`] listing the names of the methods the system accepts.
pub fn parse_method(
    name: Option<&str>,
    default: Method,
    splitting: bool,
    taylor: bool,
) -> Result<Method> {
    let Some(name) = name else {
        return Ok(default);
    };
    name.parse().map_err(|_| Error::UnknownMethod {
        name: name.into(),
        valid: Method::ALL
            .into_iter()
            .filter(|m| (splitting || !m.needs_separable()) && (taylor || !m.needs_taylor_form()))
            .map(Method::name)
            .collect::<Vec<_>>()
            .join(", "),
    })
}

/// What `integrate_sampled` stores: the sampling and whether the energy is skipped, from the
/// Python arguments `stride`, `final_only` and `energy`.
///
/// # Errors
/// [`Error::InvalidParameter`] for `stride = 0`, or `stride > 1` together with `final_only`.
pub fn sampling(stride: usize, final_only: bool) -> Result<Sampling> {
    match (stride, final_only) {
        (0, _) => Err(Error::invalid("stride", 0.0, "must be an integer >= 1")),
        (1, true) => Ok(Sampling::FinalOnly),
        (k, true) => Err(Error::invalid(
            "stride",
            k as f64,
            "cannot be combined with final_only=True; pass one or the other",
        )),
        (1, false) => Ok(Sampling::All),
        (k, false) => Ok(Sampling::Stride(k)),
    }
}

/// The name of the systems the SymPy engine builds (not in the catalogue).
pub const EXPRESSION_SYSTEM: &str = "lagrangian-expression";

/// A built-in Rust system, owned by the Python object that wraps it.
#[pyclass(module = "physicskit._core", name = "NativeSystem")]
pub struct NativeSystem {
    inner: Box<dyn DynSystem>,
    name: &'static str,
    values: Option<Values>,
}

impl NativeSystem {
    /// A system built from the catalogue `entry` with the checked `values`.
    pub fn from_entry(
        entry: &'static SystemEntry,
        values: Values,
        inner: Box<dyn DynSystem>,
    ) -> Self {
        Self {
            inner,
            name: entry.name,
            values: Some(values),
        }
    }

    /// A system built outside the catalogue (the SymPy engine's), called `name`.
    pub fn unlisted(name: &'static str, inner: Box<dyn DynSystem>) -> Self {
        Self {
            inner,
            name,
            values: None,
        }
    }

    /// Whether the system has a Taylor form (the expression engines' systems and every
    /// Lagrangian one), read from the system itself.
    pub fn has_taylor_form(&self) -> bool {
        self.inner.dynamical().taylor_field().is_some()
    }

    /// The name the system reports.
    pub fn system_name(&self) -> &'static str {
        self.name
    }

    fn dim(&self) -> usize {
        self.inner.dynamical().state().len()
    }

    /// The wrapped system (the chaos analyses run on it; the expression engines' Jacobians).
    pub fn inner(&self) -> &dyn DynSystem {
        self.inner.as_ref()
    }

    /// The wrapped system, to run and continue.
    pub fn inner_mut(&mut self) -> &mut Box<dyn DynSystem> {
        &mut self.inner
    }

    fn hamiltonian(&self, operation: &str) -> Result<&dyn HamiltonianSystem> {
        self.inner
            .hamiltonian()
            .ok_or_else(|| self.not_in_family(operation))
    }

    fn lagrangian(&self, operation: &str) -> Result<&dyn LagrangianSystem> {
        self.inner
            .lagrangian()
            .ok_or_else(|| self.not_in_family(operation))
    }

    fn not_in_family(&self, operation: &str) -> Error {
        Error::Unsupported {
            operation: operation.into(),
            reason: format!("not defined for a {} system", self.inner.family().name()),
        }
    }

    fn caps(&self) -> &dyn Capabilities {
        self.inner.capabilities()
    }

    /// The capability's result, or `NotImplementedError` naming it and the system.
    fn offer<T>(&self, capability: &str, answer: Option<T>) -> Result<T> {
        answer.ok_or_else(|| missing(capability, self.name))
    }
}

type Array<'py> = Bound<'py, PyArray1<f64>>;

#[pymethods]
impl NativeSystem {
    /// The catalogue name of the system (`"double-pendulum"`, ...).
    #[getter]
    fn name(&self) -> &'static str {
        self.name
    }

    /// `"hamiltonian"`, `"lagrangian"` or `"ode"`.
    #[getter]
    fn family(&self) -> &'static str {
        self.inner.family().name()
    }

    /// The parameters as the catalogue checked them (`name -> value`, `None` for one left
    /// out), or `None` for a system built outside the catalogue.
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.values
            .as_ref()
            .map(|v| values_to_dict(py, v))
            .transpose()
    }

    /// The names of the capability methods this system offers (`positions`, ...).
    #[getter]
    fn capabilities(&self) -> Vec<&'static str> {
        offered(self.inner.as_ref())
    }

    /// Current state (a copy).
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Array<'py> {
        array1(py, self.inner.dynamical().state())
    }

    /// Current time.
    #[getter]
    fn t(&self) -> f64 {
        self.inner.dynamical().t()
    }

    /// Degrees of freedom, or `None` for a general ODE system.
    #[getter]
    fn ndof(&self) -> Option<usize> {
        self.inner.ndof()
    }

    /// Whether `H = T(p) + V(q)`.
    #[getter]
    fn separable(&self) -> bool {
        self.inner.hamiltonian().is_some_and(|h| h.separable())
    }

    /// Inverse masses per coordinate (Hamiltonian systems), or `None`.
    #[getter]
    fn mass_inv<'py>(&self, py: Python<'py>) -> Option<Array<'py>> {
        self.inner.hamiltonian().map(|h| {
            let m = h.mass_inv();
            let v: Vec<f64> = (0..h.ndof()).map(|i| m.get(i)).collect();
            PyArray1::from_vec(py, v)
        })
    }

    /// Name of the default integrator.
    #[getter]
    fn default_method(&self) -> &'static str {
        self.inner.default_method().name()
    }

    /// Sets state and clock after validating them.
    fn reset(&mut self, state: Vector, t0: f64) -> PyResult<()> {
        self.inner.reset(Some(&state.0), t0).py()
    }

    /// Total energy of `state`.
    fn energy(&self, state: Vector) -> PyResult<f64> {
        let s = state.0;
        check_len("state", &s, self.dim()).py()?;
        Ok(self.inner.dynamical().energy(&s))
    }

    /// `dstate/dt` at `(t, state)`.
    fn derivatives<'py>(&self, py: Python<'py>, t: f64, state: Vector) -> PyResult<Array<'py>> {
        let s = state.0;
        check_len("state", &s, self.dim()).py()?;
        let mut out = vec![0.0; s.len()];
        self.inner.dynamical().derivatives(t, &s, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// `T(p)` (Hamiltonian systems).
    fn kinetic_energy(&self, p: Vector) -> PyResult<f64> {
        let h = self.hamiltonian("kinetic_energy").py()?;
        let p = p.0;
        check_len("p", &p, h.ndof()).py()?;
        Ok(h.kinetic_energy(&p))
    }

    /// `V(q)` (Hamiltonian systems).
    fn potential_energy(&self, q: Vector) -> PyResult<f64> {
        let h = self.hamiltonian("potential_energy").py()?;
        let q = q.0;
        check_len("q", &q, h.ndof()).py()?;
        Ok(h.potential_energy(&q))
    }

    /// `-dV/dq` at `(q, t)` (separable Hamiltonian systems).
    fn force<'py>(&self, py: Python<'py>, q: Vector, t: f64) -> PyResult<Array<'py>> {
        let h = self.hamiltonian("force").py()?;
        let q = q.0;
        check_len("q", &q, h.ndof()).py()?;
        let mut out = vec![0.0; q.len()];
        h.force(&q, t, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// `qddot` at `(q, qdot, t)` (Lagrangian systems).
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        q: Vector,
        qdot: Vector,
        t: f64,
    ) -> PyResult<Array<'py>> {
        let l = self.lagrangian("acceleration").py()?;
        let (q, qdot) = (q.0, qdot.0);
        check_len("q", &q, l.ndof()).py()?;
        check_len("qdot", &qdot, l.ndof()).py()?;
        let mut out = vec![0.0; q.len()];
        l.acceleration(&q, &qdot, t, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// `p = dL/dqdot` at `(q, qdot, t)` (Lagrangian systems).
    fn momentum<'py>(
        &self,
        py: Python<'py>,
        q: Vector,
        qdot: Vector,
        t: f64,
    ) -> PyResult<Array<'py>> {
        let l = self.lagrangian("momentum").py()?;
        let (q, qdot) = (q.0, qdot.0);
        check_len("q", &q, l.ndof()).py()?;
        check_len("qdot", &qdot, l.ndof()).py()?;
        let mut out = vec![0.0; q.len()];
        l.momentum(&q, &qdot, t, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// The velocity `qdot(q, p, t)` inverting `p = dL/dqdot` (Lagrangian systems).
    fn velocity<'py>(&self, py: Python<'py>, q: Vector, p: Vector, t: f64) -> PyResult<Array<'py>> {
        let l = self.lagrangian("velocity").py()?;
        let (q, p) = (q.0, p.0);
        check_len("q", &q, l.ndof()).py()?;
        check_len("p", &p, l.ndof()).py()?;
        let mut out = vec![0.0; q.len()];
        l.velocity(&q, &p, t, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// `d[q, p]/dt` of the canonical form at `(t, [q, p])` (Lagrangian systems).
    fn canonical_derivatives<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        state: Vector,
    ) -> PyResult<Array<'py>> {
        let l = self.lagrangian("canonical_derivatives").py()?;
        let s = state.0;
        check_len("state", &s, 2 * l.ndof()).py()?;
        let mut out = vec![0.0; s.len()];
        l.canonical_derivatives(t, &s, &mut out).py()?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// Starts from `(state, t0)`, integrates over `t_span` with step `dt`, and returns the result
    /// tuple `(t, y, ndof, energy, method, extra)`. `stride` keeps every `stride`-th step (and
    /// the last), `final_only` only the first and last, `energy=False` skips the energy
    /// diagnostic (`None` in the tuple), and `progress(step, n_steps)`, if given, is called every
    /// few thousand steps; `rtol`, `atol` and `max_steps` are an adaptive method's tolerances and
    /// step budget (refused for a fixed-step method). The GIL is released during the run; Ctrl-C stops it with
    /// `KeyboardInterrupt`.
    #[pyo3(signature = (state, t0, t_span, dt, method=None, stride=1, final_only=false, energy=true, progress=None, rtol=None, atol=None, max_steps=None))]
    #[allow(clippy::too_many_arguments)]
    fn integrate<'py>(
        &mut self,
        py: Python<'py>,
        state: Vector,
        t0: f64,
        t_span: (f64, f64),
        dt: f64,
        method: Option<&str>,
        stride: usize,
        final_only: bool,
        energy: bool,
        progress: Option<Py<PyAny>>,
        rtol: Option<f64>,
        atol: Option<f64>,
        max_steps: Option<u64>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let state = state.0;
        let splitting = self
            .inner
            .hamiltonian()
            .is_some_and(|h| h.separable() && h.conservative());
        let taylor = self.has_taylor_form();
        let method = parse_method(method, self.inner.default_method(), splitting, taylor).py()?;
        if method.needs_taylor_form() && !taylor {
            // A catalogue system whose field is hand-written.
            return Err(no_taylor_form(&format!("`{}`", self.name))).py();
        }
        let sampling = sampling(stride, final_only).py()?;
        let tolerances = Tolerances::for_method(rtol, atol, max_steps, method).py()?;
        let inner = &mut self.inner;
        let (outcome, raised) = py.detach(move || {
            let mut observer = SignalObserver::new(progress);
            let outcome = inner.reset(Some(&state), t0).and_then(|()| {
                inner.integrate(
                    t_span,
                    dt,
                    method,
                    IntegrateOptions {
                        sampling,
                        skip_energy: !energy,
                        observer: Some(&mut observer),
                        observe_every: CHECK_EVERY,
                        tolerances,
                    },
                )
            });
            (outcome, observer.raised)
        });
        match (outcome, raised) {
            (Ok(r), _) => result_tuple(py, r),
            (Err(Error::Interrupted { .. }), Some(signal)) => Err(signal),
            (Err(e), _) => Err(crate::errors::to_py(e)),
        }
    }

    // -- capabilities: one method per `Capabilities` accessor ------------------------------

    /// Cartesian positions of the drawn bodies for the configuration `q`, `[x1, y1, ...]`.
    fn positions<'py>(&self, py: Python<'py>, q: Vector) -> PyResult<Array<'py>> {
        let x = self.offer("positions", self.caps().positions(&q.0));
        Ok(PyArray1::from_vec(py, x.and_then(|r| r).py()?))
    }

    /// Laplace-Runge-Lenz vector of `(q, p)`.
    fn lrl_vector<'py>(&self, py: Python<'py>, q: Vector, p: Vector) -> PyResult<Array<'py>> {
        let a = self.offer("lrl_vector", self.caps().lrl_vector(&q.0, &p.0));
        Ok(array1(py, &a.and_then(|r| r).py()?))
    }

    /// Angular momentum about the force centre of `(q, p)`.
    fn angular_momentum(&self, q: Vector, p: Vector) -> PyResult<f64> {
        let l = self.caps().angular_momentum(&q.0, &p.0);
        self.offer("angular_momentum", l).and_then(|r| r).py()
    }

    /// Energy of each particle of `(q, p)`.
    fn per_particle_energy<'py>(
        &self,
        py: Python<'py>,
        q: Vector,
        p: Vector,
    ) -> PyResult<Array<'py>> {
        let e = self.caps().per_particle_energy(&q.0, &p.0);
        let e = self.offer("per_particle_energy", e).and_then(|r| r).py()?;
        Ok(PyArray1::from_vec(py, e))
    }

    /// Area of the phase-space patch the particles of `(q, p)` fill.
    fn phase_space_area(&self, q: Vector, p: Vector) -> PyResult<f64> {
        let a = self.caps().phase_space_area(&q.0, &p.0);
        self.offer("phase_space_area", a).and_then(|r| r).py()
    }

    /// Normal-mode angular frequencies, lowest first.
    fn normal_mode_frequencies<'py>(&self, py: Python<'py>) -> PyResult<Array<'py>> {
        let w = self.caps().normal_mode_frequencies();
        Ok(PyArray1::from_vec(
            py,
            self.offer("normal_mode_frequencies", w).py()?,
        ))
    }

    /// Normal-mode coordinates `(Q, P)` of `(q, p)`.
    fn normal_mode_coordinates<'py>(
        &self,
        py: Python<'py>,
        q: Vector,
        p: Vector,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let c = self.caps().normal_mode_coordinates(&q.0, &p.0);
        let (bq, bp) = self
            .offer("normal_mode_coordinates", c)
            .and_then(|r| r)
            .py()?;
        Ok((PyArray1::from_vec(py, bq), PyArray1::from_vec(py, bp)))
    }

    /// Energy in each normal mode of `(q, p)`.
    fn modal_energies<'py>(&self, py: Python<'py>, q: Vector, p: Vector) -> PyResult<Array<'py>> {
        let e = self.caps().modal_energies(&q.0, &p.0);
        let e = self.offer("modal_energies", e).and_then(|r| r).py()?;
        Ok(PyArray1::from_vec(py, e))
    }

    /// Body-to-space rotation matrix, shape (3, 3), of `state`.
    fn rotation_matrix<'py>(
        &self,
        py: Python<'py>,
        state: Vector,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.caps().rotation_matrix(&state.0);
        let r = self.offer("rotation_matrix", r).and_then(|r| r).py()?;
        let a = ndarray::Array2::from_shape_fn((3, 3), |(i, j)| r[3 * i + j]);
        Ok(a.into_pyarray(py))
    }

    /// `|L|^2` of `state`.
    fn angular_momentum_squared(&self, state: Vector) -> PyResult<f64> {
        let l2 = self.caps().angular_momentum_squared(&state.0);
        self.offer("angular_momentum_squared", l2)
            .and_then(|r| r)
            .py()
    }

    /// Instantaneous precession and nutation rates `(phidot, thetadot)` of `state`.
    fn precession_nutation_rate(&self, state: Vector) -> PyResult<(f64, f64)> {
        let r = self.caps().precession_nutation_rate(&state.0);
        self.offer("precession_nutation_rate", r)
            .and_then(|r| r)
            .py()
    }

    /// Unit vector along a top's symmetry axis in space for the configuration `q`.
    fn symmetry_axis<'py>(&self, py: Python<'py>, q: Vector) -> PyResult<Array<'py>> {
        let a = self.caps().symmetry_axis(&q.0);
        Ok(array1(
            py,
            &self.offer("symmetry_axis", a).and_then(|r| r).py()?,
        ))
    }

    /// A rigid body's body-frame angular momentum `(I1 w1, I2 w2, I3 w3)` of `state`.
    fn body_angular_momentum<'py>(&self, py: Python<'py>, state: Vector) -> PyResult<Array<'py>> {
        let l = self.caps().body_angular_momentum(&state.0);
        let l = self
            .offer("body_angular_momentum", l)
            .and_then(|r| r)
            .py()?;
        Ok(array1(py, &l))
    }

    /// Half-extents of the uniform box of mass `mass` with the body's principal moments.
    fn inertia_box<'py>(&self, py: Python<'py>, mass: f64) -> PyResult<Array<'py>> {
        let b = self.caps().inertia_box(mass);
        Ok(array1(
            py,
            &self.offer("inertia_box", b).and_then(|r| r).py()?,
        ))
    }

    /// Energies of the separatrices (saddle equilibria), lowest first.
    fn separatrix_energies<'py>(&self, py: Python<'py>) -> PyResult<Array<'py>> {
        let e = self.caps().separatrix_energies();
        Ok(PyArray1::from_vec(
            py,
            self.offer("separatrix_energies", e).py()?,
        ))
    }

    /// Conserved quantities beyond the energy of `state`, sorted.
    fn conserved_quantities<'py>(&self, py: Python<'py>, state: Vector) -> PyResult<Array<'py>> {
        let c = self.caps().conserved_quantities(&state.0);
        let c = self.offer("conserved_quantities", c).and_then(|r| r).py()?;
        Ok(PyArray1::from_vec(py, c))
    }
}
