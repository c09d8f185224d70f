//! [`NativeSystem`]: the one Python class that wraps every built-in Rust system.
//!
//! Each built-in system implements the object-safe [`Native`] trait through one of the macros
//! [`native_hamiltonian!`](crate::native_hamiltonian), [`native_lagrangian!`](crate::native_lagrangian)
//! or [`native_ode!`](crate::native_ode). `Native::integrate` calls the family's generic
//! `integrate_with`, so the step loop is monomorphized for the concrete system: the only
//! dynamic dispatch is the one call into `integrate`.

use std::any::Any;

use numpy::{PyArray1, PyReadonlyArray1};
use physicskit::classical::{Error, IntegrateOptions, Method, Result, Sampling, SimulationResult};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{array1, result_tuple, to_vec};
use crate::errors::IntoPyResult;
use crate::interrupt::{SignalObserver, CHECK_EVERY};

/// Which family of the spec a system belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// `HamiltonianSystem`: state `[q, p]`.
    Hamiltonian,
    /// `LagrangianSystem`: state `[q, qdot]`.
    Lagrangian,
    /// `ODESystem`: the system's own layout.
    Ode,
}

fn unsupported(operation: &str, family: Family) -> Error {
    Error::Unsupported {
        operation: operation.into(),
        reason: format!("not defined for a {family:?} system"),
    }
}

/// Object-safe view of a built-in system, as the Python layer needs it.
#[allow(missing_docs)]
pub trait Native: Send + Sync + Any {
    fn family(&self) -> Family;
    fn ndof(&self) -> Option<usize>;
    fn state(&self) -> &[f64];
    fn t(&self) -> f64;
    fn reset(&mut self, state: &[f64], t0: f64) -> Result<()>;
    fn energy(&self, state: &[f64]) -> f64;
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()>;
    fn default_method(&self) -> Method;
    fn integrate(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        options: IntegrateOptions<'_>,
    ) -> Result<SimulationResult>;
    fn as_any(&self) -> &dyn Any;
    fn kinetic_energy(&self, _p: &[f64]) -> Result<f64> {
        Err(unsupported("kinetic_energy", self.family()))
    }
    fn potential_energy(&self, _q: &[f64]) -> Result<f64> {
        Err(unsupported("potential_energy", self.family()))
    }
    fn force(&self, _q: &[f64], _t: f64, _out: &mut [f64]) -> Result<()> {
        Err(unsupported("force", self.family()))
    }
    fn separable(&self) -> bool {
        false
    }
    fn mass_inv(&self) -> Option<Vec<f64>> {
        None
    }
    fn acceleration(&self, _q: &[f64], _qdot: &[f64], _t: f64, _out: &mut [f64]) -> Result<()> {
        Err(unsupported("acceleration", self.family()))
    }
    fn momentum(&self, _q: &[f64], _qdot: &[f64], _t: f64, _out: &mut [f64]) -> Result<()> {
        Err(unsupported("momentum", self.family()))
    }
}

/// The [`Native`] methods every family shares; `integrate` calls `$system`'s
/// `integrate_with` (the family trait: `HamiltonianSystem`, `LagrangianSystem`, `OdeSystem`).
#[macro_export]
#[doc(hidden)]
macro_rules! native_common {
    ($family:expr, $system:path, $ndof:expr) => {
        fn family(&self) -> $crate::native::Family {
            $family
        }
        fn ndof(&self) -> Option<usize> {
            #[allow(clippy::redundant_closure_call)]
            ($ndof)(self)
        }
        fn state(&self) -> &[f64] {
            physicskit::classical::DynamicalSystem::state(self)
        }
        fn t(&self) -> f64 {
            physicskit::classical::DynamicalSystem::t(self)
        }
        fn reset(&mut self, state: &[f64], t0: f64) -> physicskit::classical::Result<()> {
            physicskit::classical::DynamicalSystem::reset(self, Some(state), t0)
        }
        fn energy(&self, state: &[f64]) -> f64 {
            physicskit::classical::DynamicalSystem::energy(self, state)
        }
        fn derivatives(
            &self,
            t: f64,
            state: &[f64],
            out: &mut [f64],
        ) -> physicskit::classical::Result<()> {
            physicskit::classical::DynamicalSystem::derivatives(self, t, state, out)
        }
        fn default_method(&self) -> physicskit::classical::Method {
            physicskit::classical::DynamicalSystem::default_method(self)
        }
        fn integrate(
            &mut self,
            t_span: (f64, f64),
            dt: f64,
            method: physicskit::classical::Method,
            options: physicskit::classical::IntegrateOptions<'_>,
        ) -> physicskit::classical::Result<physicskit::classical::SimulationResult> {
            <Self as $system>::integrate_with(self, t_span, dt, method, options)
        }
        fn as_any(&self) -> &dyn std::any::Any {
            self
        }
    };
}

/// Implements [`Native`] for a [`physicskit::classical::HamiltonianSystem`].
#[macro_export]
macro_rules! native_hamiltonian {
    ($ty:ty) => {
        impl $crate::native::Native for $ty {
            $crate::native_common!(
                $crate::native::Family::Hamiltonian,
                physicskit::classical::HamiltonianSystem,
                |s: &Self| Some(physicskit::classical::HamiltonianSystem::ndof(s))
            );
            fn kinetic_energy(&self, p: &[f64]) -> physicskit::classical::Result<f64> {
                $crate::native::check_len(
                    "p",
                    p,
                    physicskit::classical::HamiltonianSystem::ndof(self),
                )?;
                Ok(physicskit::classical::HamiltonianSystem::kinetic_energy(
                    self, p,
                ))
            }
            fn potential_energy(&self, q: &[f64]) -> physicskit::classical::Result<f64> {
                $crate::native::check_len(
                    "q",
                    q,
                    physicskit::classical::HamiltonianSystem::ndof(self),
                )?;
                Ok(physicskit::classical::HamiltonianSystem::potential_energy(
                    self, q,
                ))
            }
            fn force(
                &self,
                q: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> physicskit::classical::Result<()> {
                $crate::native::check_len(
                    "q",
                    q,
                    physicskit::classical::HamiltonianSystem::ndof(self),
                )?;
                physicskit::classical::HamiltonianSystem::force(self, q, t, out)
            }
            fn separable(&self) -> bool {
                physicskit::classical::HamiltonianSystem::separable(self)
            }
            fn mass_inv(&self) -> Option<Vec<f64>> {
                let n = physicskit::classical::HamiltonianSystem::ndof(self);
                let m = physicskit::classical::HamiltonianSystem::mass_inv(self);
                Some((0..n).map(|i| m.get(i)).collect())
            }
        }
    };
}

/// Implements [`Native`] for a [`physicskit::classical::LagrangianSystem`].
#[macro_export]
macro_rules! native_lagrangian {
    ($ty:ty) => {
        impl $crate::native::Native for $ty {
            $crate::native_common!(
                $crate::native::Family::Lagrangian,
                physicskit::classical::LagrangianSystem,
                |s: &Self| Some(physicskit::classical::LagrangianSystem::ndof(s))
            );
            fn acceleration(
                &self,
                q: &[f64],
                qdot: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> physicskit::classical::Result<()> {
                let n = physicskit::classical::LagrangianSystem::ndof(self);
                $crate::native::check_len("q", q, n)?;
                $crate::native::check_len("qdot", qdot, n)?;
                physicskit::classical::LagrangianSystem::acceleration(self, q, qdot, t, out)
            }
            fn momentum(
                &self,
                q: &[f64],
                qdot: &[f64],
                t: f64,
                out: &mut [f64],
            ) -> physicskit::classical::Result<()> {
                let n = physicskit::classical::LagrangianSystem::ndof(self);
                $crate::native::check_len("q", q, n)?;
                $crate::native::check_len("qdot", qdot, n)?;
                physicskit::classical::LagrangianSystem::momentum(self, q, qdot, t, out)
            }
        }
    };
}

/// Implements [`Native`] for a [`physicskit::classical::OdeSystem`].
#[macro_export]
macro_rules! native_ode {
    ($ty:ty) => {
        impl $crate::native::Native for $ty {
            $crate::native_common!(
                $crate::native::Family::Ode,
                physicskit::classical::OdeSystem,
                |_s: &Self| None
            );
        }
    };
}

/// Checks an input length (and finiteness) before it reaches a system.
///
/// # Errors
/// [`Error::DimensionMismatch`] or [`Error::NonFinite`].
pub fn check_len(name: &str, v: &[f64], n: usize) -> Result<()> {
    physicskit::classical::core::error::check_vector(name, v, n)
}

/// Parses a method name, or takes the system's default for `None`.
///
/// # Errors
/// [`Error::UnknownMethod`] listing the valid names.
pub fn parse_method(name: Option<&str>, default: Method) -> Result<Method> {
    name.map_or(Ok(default), str::parse)
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

/// A built-in Rust system, owned by the Python object that wraps it.
#[pyclass(module = "physicskit._core", name = "NativeSystem")]
pub struct NativeSystem {
    /// The system.
    pub inner: Box<dyn Native>,
}

impl NativeSystem {
    /// Wraps a system.
    pub fn new<S: Native>(system: S) -> Self {
        Self {
            inner: Box::new(system),
        }
    }

    /// The wrapped system as its concrete type.
    ///
    /// # Errors
    /// `TypeError` if it is another system.
    pub fn downcast<S: Native>(&self) -> PyResult<&S> {
        self.inner.as_any().downcast_ref::<S>().ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err("native system of the wrong type")
        })
    }

    fn dim(&self) -> usize {
        self.inner.state().len()
    }
}

#[pymethods]
impl NativeSystem {
    /// Current state (a copy).
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.inner.state())
    }

    /// Current time.
    #[getter]
    fn t(&self) -> f64 {
        self.inner.t()
    }

    /// Degrees of freedom, or `None` for a general ODE system.
    #[getter]
    fn ndof(&self) -> Option<usize> {
        self.inner.ndof()
    }

    /// Whether `H = T(p) + V(q)`.
    #[getter]
    fn separable(&self) -> bool {
        self.inner.separable()
    }

    /// Inverse masses per coordinate, or `None`.
    #[getter]
    fn mass_inv<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner.mass_inv().map(|m| array1(py, &m))
    }

    /// Name of the default integrator.
    #[getter]
    fn default_method(&self) -> &'static str {
        self.inner.default_method().name()
    }

    /// Sets state and clock after validating them.
    fn reset(&mut self, state: PyReadonlyArray1<'_, f64>, t0: f64) -> PyResult<()> {
        self.inner.reset(&to_vec(&state), t0).py()
    }

    /// Total energy of `state`.
    fn energy(&self, state: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
        let s = to_vec(&state);
        check_len("state", &s, self.dim()).py()?;
        Ok(self.inner.energy(&s))
    }

    /// `dstate/dt` at `(t, state)`.
    fn derivatives<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        state: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let s = to_vec(&state);
        check_len("state", &s, self.dim()).py()?;
        let mut out = vec![0.0; s.len()];
        self.inner.derivatives(t, &s, &mut out).py()?;
        Ok(array1(py, &out))
    }

    /// `T(p)`.
    fn kinetic_energy(&self, p: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
        self.inner.kinetic_energy(&to_vec(&p)).py()
    }

    /// `V(q)`.
    fn potential_energy(&self, q: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
        self.inner.potential_energy(&to_vec(&q)).py()
    }

    /// `-dV/dq` at `(q, t)`.
    fn force<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray1<'_, f64>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        let mut out = vec![0.0; q.len()];
        self.inner.force(&q, t, &mut out).py()?;
        Ok(array1(py, &out))
    }

    /// `qddot` at `(q, qdot, t)`.
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray1<'_, f64>,
        qdot: PyReadonlyArray1<'_, f64>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        let mut out = vec![0.0; q.len()];
        self.inner
            .acceleration(&q, &to_vec(&qdot), t, &mut out)
            .py()?;
        Ok(array1(py, &out))
    }

    /// `p = dL/dqdot` at `(q, qdot, t)`.
    fn momentum<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray1<'_, f64>,
        qdot: PyReadonlyArray1<'_, f64>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let q = to_vec(&q);
        let mut out = vec![0.0; q.len()];
        self.inner.momentum(&q, &to_vec(&qdot), t, &mut out).py()?;
        Ok(array1(py, &out))
    }

    /// Starts from `(state, t0)`, integrates over `t_span` with step `dt`, and returns the result
    /// tuple `(t, y, energy, method, extra)`. `stride` keeps every `stride`-th step (and
    /// the last), `final_only` only the first and last, `energy=False` skips the energy
    /// diagnostic (`None` in the tuple). The GIL is released during the run; Ctrl-C stops it
    /// with `KeyboardInterrupt`.
    #[pyo3(signature = (state, t0, t_span, dt, method=None, stride=1, final_only=false, energy=true))]
    #[allow(clippy::too_many_arguments)]
    fn integrate<'py>(
        &mut self,
        py: Python<'py>,
        state: PyReadonlyArray1<'_, f64>,
        t0: f64,
        t_span: (f64, f64),
        dt: f64,
        method: Option<&str>,
        stride: usize,
        final_only: bool,
        energy: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let state = to_vec(&state);
        let method = parse_method(method, self.inner.default_method()).py()?;
        let sampling = sampling(stride, final_only).py()?;
        let inner = &mut self.inner;
        let (outcome, raised) = py.detach(move || {
            let mut observer = SignalObserver::default();
            let outcome = inner.reset(&state, t0).and_then(|()| {
                inner.integrate(
                    t_span,
                    dt,
                    method,
                    IntegrateOptions {
                        sampling,
                        skip_energy: !energy,
                        observer: Some(&mut observer),
                        observe_every: CHECK_EVERY,
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
}
