//! The SymPy engines' native half: a Lagrangian, a Hamiltonian or the components of an ODE
//! given as prefix S-expressions (`physicskit::classical::symbolic::Expr`) become a
//! [`LagrangianModel`], an [`ExprHamiltonian`] or an [`ExprOde`] behind the core's
//! type-erased wrappers, a [`NativeSystem`] like any built-in system. [`ExprSpec`] holds what
//! builds one (the expressions, named parameters, a state), for ensembles, which build one
//! system per member.

use numpy::PyArray2;
use physicskit::classical::lagrangian::LagrangianModel;
use physicskit::classical::model::erased::{DynSystem, Hamiltonian, Lagrangian, Ode};
use physicskit::classical::symbolic::{Expr, ExprHamiltonian, ExprLagrangian, ExprOde};
use physicskit::classical::{Error, HamiltonianSystem};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::Vector;
use crate::errors::IntoPyResult;
use crate::native::{check_len, NativeSystem, EXPRESSION_SYSTEM};

/// The name a `HamiltonianEngine` system reports (it is not in the catalogue).
pub const HAMILTONIAN_EXPRESSION_SYSTEM: &str = "hamiltonian-expression";

/// The name an `ODEEngine` system reports (it is not in the catalogue).
pub const ODE_EXPRESSION_SYSTEM: &str = "ode-expression";

/// A Hamiltonian system from a prefix S-expression of `H(q, p, t)` with `ndof` degrees of
/// freedom and parameter values `params`, starting at `(q0, p0)`.
#[pyfunction]
pub fn expr_hamiltonian(
    sexpr: &str,
    ndof: usize,
    params: Vector,
    q0: Vector,
    p0: Vector,
) -> PyResult<NativeSystem> {
    let expr = Expr::parse(sexpr).py()?;
    let system = hamiltonian(expr, ndof, params.0, &q0.0, &p0.0).py()?;
    Ok(NativeSystem::unlisted(
        HAMILTONIAN_EXPRESSION_SYSTEM,
        system,
    ))
}

/// The system `expr_hamiltonian` wraps.
fn hamiltonian(
    expr: Expr,
    ndof: usize,
    params: Vec<f64>,
    q0: &[f64],
    p0: &[f64],
) -> physicskit::classical::Result<Box<dyn DynSystem>> {
    Ok(Box::new(Hamiltonian(ExprHamiltonian::new(
        expr, ndof, params, q0, p0,
    )?)))
}

/// The system `expr_ode` wraps.
fn ode(
    f: Vec<Expr>,
    params: Vec<f64>,
    y0: &[f64],
    energy: Option<Expr>,
) -> physicskit::classical::Result<Box<dyn DynSystem>> {
    Ok(Box::new(Ode(ExprOde::new(f, params, y0, energy)?)))
}

/// The system `expr_lagrangian` wraps.
fn lagrangian(
    expr: Expr,
    ndof: usize,
    params: Vec<f64>,
    q0: &[f64],
    qdot0: &[f64],
) -> physicskit::classical::Result<Box<dyn DynSystem>> {
    let lagrangian = ExprLagrangian::new(expr, ndof, params)?;
    Ok(Box::new(Lagrangian(LagrangianModel::new(
        lagrangian, q0, qdot0,
    )?)))
}

/// Which engine an [`ExprSpec`] is of.
#[derive(Debug, Clone)]
enum ExprFamily {
    /// `HamiltonianEngine`: `H` in `ndof` coordinates and momenta.
    Hamiltonian { ndof: usize },
    /// `LagrangianEngine`: `L` in `ndof` coordinates and velocities.
    Lagrangian { ndof: usize },
    /// `ODEEngine`: one expression per component, and optionally an energy.
    Ode { energy: Option<Expr> },
}

/// What builds an expression system: the engine's expressions, its parameters by name (in
/// the order the expressions index them) and an initial state. An ensemble builds each member
/// from it with the member's parameters and state ([`ExprSpec::build`]).
#[derive(Debug, Clone)]
pub struct ExprSpec {
    family: ExprFamily,
    exprs: Vec<Expr>,
    /// The parameters' names and values.
    pub params: Vec<(String, f64)>,
    /// The initial state.
    pub state: Vec<f64>,
}

impl ExprSpec {
    /// The spec from the dict the Python engines make (`family`: `"hamiltonian"`,
    /// `"lagrangian"` or `"ode"`; `expressions`: prefix S-expressions, one for `H` or `L`, one
    /// per component for an ODE; `ndof`, except for an ODE; `params`: `(name, value)` pairs;
    /// `energy`: an ODE's optional energy expression; `state`: the initial state).
    ///
    /// # Errors
    /// `ValueError` for a missing or malformed entry, an expression that does not parse, or a
    /// state of the wrong length.
    pub fn from_dict(spec: &Bound<'_, PyDict>) -> PyResult<Self> {
        fn item<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
            let value = d.get_item(key)?.ok_or_else(|| {
                PyValueError::new_err(format!("the expression system lacks {key:?}"))
            })?;
            value.extract::<T>().map_err(|e| {
                let e: PyErr = e.into();
                PyValueError::new_err(format!("the expression system's {key:?}: {e}"))
            })
        }
        let exprs = item::<Vec<String>>(spec, "expressions")?
            .iter()
            .map(|e| Expr::parse(e))
            .collect::<Result<Vec<_>, _>>()
            .py()?;
        let family: String = item(spec, "family")?;
        let state: Vec<f64> = item(spec, "state")?;
        let params: Vec<(String, f64)> = item(spec, "params")?;
        let (family, dim) = match family.as_str() {
            "hamiltonian" | "lagrangian" if exprs.len() == 1 => {
                let ndof: usize = item(spec, "ndof")?;
                let family = if family == "hamiltonian" {
                    ExprFamily::Hamiltonian { ndof }
                } else {
                    ExprFamily::Lagrangian { ndof }
                };
                (family, 2 * ndof)
            }
            "ode" => {
                let energy: Option<String> = item(spec, "energy")?;
                let energy = energy.as_deref().map(Expr::parse).transpose().py()?;
                (ExprFamily::Ode { energy }, exprs.len())
            }
            other => {
                return Err(PyValueError::new_err(format!(
                    "the expression system's family must be hamiltonian or lagrangian (one \
                     expression) or ode, got {other:?} with {} expressions",
                    exprs.len()
                )))
            }
        };
        check_len("state", &state, dim).py()?;
        Ok(Self {
            family,
            exprs,
            params,
            state,
        })
    }

    /// The system with parameter values `params` (in the order of [`ExprSpec::params`]) at
    /// `state`.
    ///
    /// # Errors
    /// Whatever the system's constructor refuses (parameters not finite, a state of the
    /// wrong length or not finite, a singular mass matrix ...).
    pub fn build(
        &self,
        params: &[f64],
        state: &[f64],
    ) -> physicskit::classical::Result<Box<dyn DynSystem>> {
        let params = params.to_vec();
        let halves = |ndof: usize| state.split_at(ndof.min(state.len()));
        match &self.family {
            ExprFamily::Hamiltonian { ndof } => {
                let (q0, p0) = halves(*ndof);
                hamiltonian(self.exprs[0].clone(), *ndof, params, q0, p0)
            }
            ExprFamily::Lagrangian { ndof } => {
                let (q0, qdot0) = halves(*ndof);
                lagrangian(self.exprs[0].clone(), *ndof, params, q0, qdot0)
            }
            ExprFamily::Ode { energy } => ode(self.exprs.clone(), params, state, energy.clone()),
        }
    }
}

/// A first-order system from prefix S-expressions of the components of `f(t, y)` and
/// optionally of an energy, with parameter values `params`, starting at `y0`.
#[pyfunction]
#[pyo3(signature = (components, params, y0, energy=None))]
pub fn expr_ode(
    components: Vec<String>,
    params: Vector,
    y0: Vector,
    energy: Option<&str>,
) -> PyResult<NativeSystem> {
    let f = components
        .iter()
        .map(|c| Expr::parse(c))
        .collect::<Result<Vec<_>, _>>()
        .py()?;
    let energy = energy.map(Expr::parse).transpose().py()?;
    let system = ode(f, params.0, &y0.0, energy).py()?;
    Ok(NativeSystem::unlisted(ODE_EXPRESSION_SYSTEM, system))
}

/// The Jacobian `d(derivatives)/d(state)` of `system` at `(t, state)`, row-major as a square
/// array, from the system's own Jacobian (automatic differentiation for the expression
/// systems).
///
/// # Errors
/// `ValueError` for a wrong length; `NotImplementedError` if the system supplies no Jacobian.
#[pyfunction]
pub fn system_jacobian<'py>(
    py: Python<'py>,
    system: PyRef<'_, NativeSystem>,
    t: f64,
    state: Vector,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = state.0;
    let dynamical = system.inner().dynamical();
    let dim = dynamical.state_dim();
    check_len("state", &s, dim).py()?;
    let mut out = vec![0.0; dim * dim];
    let answer = dynamical.jacobian(t, &s, &mut out);
    let reason = || format!("`{}` supplies no Jacobian", system.system_name());
    square_array(py, "jacobian", answer, reason, out, dim)
}

/// `out` (row-major, `n x n`) as a numpy array once the hook's `answer` is `Some(Ok(()))`;
/// `NotImplementedError` (`Unsupported`) with `reason` when it is `None`.
fn square_array<'py>(
    py: Python<'py>,
    operation: &str,
    answer: Option<physicskit::classical::Result<()>>,
    reason: impl FnOnce() -> String,
    out: Vec<f64>,
    n: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    answer
        .ok_or_else(|| Error::Unsupported {
            operation: operation.into(),
            reason: reason(),
        })
        .and_then(|r| r)
        .py()?;
    let rows: Vec<Vec<f64>> = out.chunks(n.max(1)).map(<[f64]>::to_vec).collect();
    PyArray2::from_vec2(py, &rows)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// The force Jacobian `dF/dq` of a separable Hamiltonian `system` at `(q, t)`.
#[pyfunction]
pub fn force_jacobian<'py>(
    py: Python<'py>,
    system: PyRef<'_, NativeSystem>,
    q: Vector,
    t: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let h: &dyn HamiltonianSystem = system.inner().hamiltonian().ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err("force_jacobian: not a Hamiltonian system")
    })?;
    let n = h.ndof();
    let q = q.0;
    check_len("q", &q, n).py()?;
    let mut out = vec![0.0; n * n];
    let answer = h.force_jacobian(&q, t, &mut out);
    let reason = || "the system is not separable, or supplies no force Jacobian".to_string();
    square_array(py, "force_jacobian", answer, reason, out, n)
}

/// A Lagrangian system from a prefix S-expression (see `physicskit::classical::symbolic::Expr`)
/// with `ndof` coordinates and parameter values `params`, starting at `(q0, qdot0)`.
#[pyfunction]
pub fn expr_lagrangian(
    sexpr: &str,
    ndof: usize,
    params: Vector,
    q0: Vector,
    qdot0: Vector,
) -> PyResult<NativeSystem> {
    let expr = Expr::parse(sexpr).py()?;
    let system = lagrangian(expr, ndof, params.0, &q0.0, &qdot0.0).py()?;
    Ok(NativeSystem::unlisted(EXPRESSION_SYSTEM, system))
}

/// Parses `sexpr` and checks its variable and parameter indices against `ndof` and `nparams`.
#[pyfunction]
pub fn expr_validate(sexpr: &str, ndof: usize, nparams: usize) -> PyResult<()> {
    Expr::parse(sexpr).py()?.validate(ndof, nparams).py()
}

/// Registers `expr_lagrangian`, `expr_validate`, `expr_hamiltonian`, `expr_ode`,
/// `system_jacobian` and `force_jacobian`.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(expr_lagrangian, m)?)?;
    m.add_function(wrap_pyfunction!(expr_validate, m)?)?;
    m.add_function(wrap_pyfunction!(expr_hamiltonian, m)?)?;
    m.add_function(wrap_pyfunction!(expr_ode, m)?)?;
    m.add_function(wrap_pyfunction!(system_jacobian, m)?)?;
    m.add_function(wrap_pyfunction!(force_jacobian, m)?)?;
    Ok(())
}
