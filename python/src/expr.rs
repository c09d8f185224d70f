//! The SymPy engines' native half: a Lagrangian, a Hamiltonian or the components of an ODE
//! given as prefix S-expressions (`physicskit::classical::lagrangian::Expr`) become a
//! [`LagrangianModel`], an [`ExprHamiltonian`] or an [`ExprOde`] behind the core's
//! type-erased wrappers, a [`NativeSystem`] like any built-in system.

use numpy::{PyArray2, PyReadonlyArray1};
use physicskit::classical::core::erased::{Hamiltonian, Lagrangian, Ode};
use physicskit::classical::lagrangian::{
    Expr, ExprHamiltonian, ExprLagrangian, ExprOde, LagrangianModel,
};
use physicskit::classical::{Error, HamiltonianSystem};
use pyo3::prelude::*;

use crate::convert::to_vec;
use crate::errors::IntoPyResult;
use crate::native::{check_len, NativeSystem, EXPRESSION_SYSTEM};

type Arr<'a> = PyReadonlyArray1<'a, f64>;

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
    params: Arr<'_>,
    q0: Arr<'_>,
    p0: Arr<'_>,
) -> PyResult<NativeSystem> {
    let expr = Expr::parse(sexpr).py()?;
    let system =
        ExprHamiltonian::new(expr, ndof, to_vec(&params), &to_vec(&q0), &to_vec(&p0)).py()?;
    Ok(NativeSystem::unlisted(
        HAMILTONIAN_EXPRESSION_SYSTEM,
        Box::new(Hamiltonian(system)),
    ))
}

/// A first-order system from prefix S-expressions of the components of `f(t, y)` and
/// optionally of an energy, with parameter values `params`, starting at `y0`.
#[pyfunction]
#[pyo3(signature = (components, params, y0, energy=None))]
pub fn expr_ode(
    components: Vec<String>,
    params: Arr<'_>,
    y0: Arr<'_>,
    energy: Option<&str>,
) -> PyResult<NativeSystem> {
    let f = components
        .iter()
        .map(|c| Expr::parse(c))
        .collect::<Result<Vec<_>, _>>()
        .py()?;
    let energy = energy.map(Expr::parse).transpose().py()?;
    let system = ExprOde::new(f, to_vec(&params), &to_vec(&y0), energy).py()?;
    Ok(NativeSystem::unlisted(
        ODE_EXPRESSION_SYSTEM,
        Box::new(Ode(system)),
    ))
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
    state: Arr<'_>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = to_vec(&state);
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
    q: Arr<'_>,
    t: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let h: &dyn HamiltonianSystem = system.inner().hamiltonian().ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err("force_jacobian: not a Hamiltonian system")
    })?;
    let n = h.ndof();
    let q = to_vec(&q);
    check_len("q", &q, n).py()?;
    let mut out = vec![0.0; n * n];
    let answer = h.force_jacobian(&q, t, &mut out);
    let reason = || "the system is not separable, or supplies no force Jacobian".to_string();
    square_array(py, "force_jacobian", answer, reason, out, n)
}

/// A Lagrangian system from a prefix S-expression (see `physicskit::classical::lagrangian::Expr`)
/// with `ndof` coordinates and parameter values `params`, starting at `(q0, qdot0)`.
#[pyfunction]
pub fn expr_lagrangian(
    sexpr: &str,
    ndof: usize,
    params: Arr<'_>,
    q0: Arr<'_>,
    qdot0: Arr<'_>,
) -> PyResult<NativeSystem> {
    let expr = Expr::parse(sexpr).py()?;
    let lagrangian = ExprLagrangian::new(expr, ndof, to_vec(&params)).py()?;
    let model = LagrangianModel::new(lagrangian, &to_vec(&q0), &to_vec(&qdot0)).py()?;
    Ok(NativeSystem::unlisted(
        EXPRESSION_SYSTEM,
        Box::new(Lagrangian(model)),
    ))
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
