//! The SymPy engine's native half: a Lagrangian given as a prefix S-expression
//! (`physicskit::classical::lagrangian::Expr`) becomes a [`LagrangianModel`] behind the
//! core's type-erased `Lagrangian(..)` wrapper, a [`NativeSystem`] like any built-in system.

use numpy::PyReadonlyArray1;
use physicskit::classical::core::erased::Lagrangian;
use physicskit::classical::lagrangian::{Expr, ExprLagrangian, LagrangianModel};
use pyo3::prelude::*;

use crate::convert::to_vec;
use crate::errors::IntoPyResult;
use crate::native::{NativeSystem, EXPRESSION_SYSTEM};

type Arr<'a> = PyReadonlyArray1<'a, f64>;

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

/// Registers `expr_lagrangian` and `expr_validate`.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(expr_lagrangian, m)?)?;
    m.add_function(wrap_pyfunction!(expr_validate, m)?)?;
    Ok(())
}
