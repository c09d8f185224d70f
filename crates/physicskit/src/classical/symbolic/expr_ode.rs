//! [`ExprOde`]: a first-order system `dy/dt = f(t, y)` given as one [`Expr`] per component
//! (from SymPy through the Python `ODEEngine`, or parsed from text), run natively as an
//! [`OdeSystem`].
//!
//! The components are compiled into one [`Tape`] (subexpressions shared between components
//! are computed once) and evaluated in `f64`; the Jacobian `df/dy` comes from forward-mode
//! automatic differentiation over the same tape (one `Dual64` pass per column), for the
//! implicit-midpoint Newton solve and the tangent dynamics of chaos indicators. `y_i` is
//! written `y<i>` (an alias of `q<i>`: the tree stores [`Expr::Q`]).
//!
//! An ODE has no energy in general: an optional expression gives one (a conserved quantity
//! to monitor); without it [`energy`](DynamicalSystem::energy) is `NaN` and `integrate`
//! stores no energies (`result.energy` is `None`).
//!
//! ```
//! use physicskit::classical::symbolic::{Expr, ExprOde};
//! use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
//!
//! // The Lorenz system, sigma = 10, rho = 28, beta = 8/3 as parameters 0, 1, 2.
//! let f = ["(* param0 (- y1 y0))", "(- (* y0 (- param1 y2)) y1)", "(- (* y0 y1) (* param2 y2))"]
//!     .map(|s| Expr::parse(s).unwrap());
//! let mut lorenz = ExprOde::new(f.to_vec(), vec![10.0, 28.0, 8.0 / 3.0], &[1.0, 1.0, 1.0], None)
//!     .unwrap();
//! let result = lorenz.integrate((0.0, 1.0), 0.001, Method::Rk4).unwrap();
//! assert!(result.energy.is_none());
//! assert_eq!(lorenz.state().len(), 3);
//! ```

use super::expr::Expr;
use super::tape::{Backend, Tape};
use super::taylor_tape::TaylorProgram;
use crate::classical::core::error::check_len;
use crate::classical::core::{Error, Phase, Result, SimulationResult};
use crate::classical::integrators::driver;
use crate::classical::integrators::taylor::TaylorField;
use crate::classical::integrators::{DynamicalSystem, IntegrateOptions, Method, OdeSystem};
use crate::classical::model::Capabilities;

/// A first-order system given by expressions (see the module documentation).
#[derive(Debug, Clone)]
pub struct ExprOde {
    phase: Phase,
    field: Tape,
    energy: Option<Tape>,
    components: Vec<Expr>,
    params: Vec<f64>,
}

impl ExprOde {
    /// `dy_i/dt = f[i]` in `y_j`, `t` and parameters with values `params`, starting at `y0`
    /// at `t = 0`; `energy`, if given, is an expression in the same variables.
    ///
    /// # Errors
    /// No components; non-finite parameters; an expression referring to `y_j` with
    /// `j >= f.len()`, an unknown parameter, a non-finite constant, or nested too deeply
    /// ([`Expr::validate`]); `y0` not of length `f.len()` or not finite.
    pub fn new(f: Vec<Expr>, params: Vec<f64>, y0: &[f64], energy: Option<Expr>) -> Result<Self> {
        let dim = f.len();
        if dim == 0 {
            return Err(Error::invalid("f", 0.0, "needs at least one component"));
        }
        if let Some(bad) = params.iter().find(|p| !p.is_finite()) {
            return Err(Error::invalid("params", *bad, "must be finite"));
        }
        for e in f.iter().chain(energy.as_ref()) {
            e.validate(dim, params.len())?;
            if e.uses().1 {
                return Err(Error::invalid(
                    "expression",
                    f64::NAN,
                    "an ODE's expressions take y<i> and t only (found a qdot<i> or p<i>)",
                ));
            }
        }
        check_len("y0", y0, dim)?;
        let field = Tape::new(&f, dim, 0, &params)?;
        let energy = energy
            .map(|e| Tape::new(std::slice::from_ref(&e), dim, 0, &params))
            .transpose()?;
        Ok(Self {
            phase: Phase::new(y0.to_vec(), 0.0).map_err(|e| rename(e, "y0"))?,
            field,
            energy,
            components: f,
            params,
        })
    }

    /// The components of `f`.
    pub fn components(&self) -> &[Expr] {
        &self.components
    }

    /// The parameter values.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Whether an energy expression was given.
    pub fn has_energy(&self) -> bool {
        self.energy.is_some()
    }

    /// Which code evaluates `f`: native code once compiled (with the feature `jit`: after
    /// [`COMPILE_AFTER`](super::COMPILE_AFTER) evaluations, or by [`compile_native`](Self::compile_native)), else the
    /// interpreter; both give the same bits ([`Tape`]).
    pub fn backend(&self) -> Backend {
        self.field.backend()
    }

    /// Compiles `f` (and the energy expression) to machine code now
    /// ([`Tape::compile_native`]) and returns `f`'s backend.
    pub fn compile_native(&self) -> Backend {
        self.energy.iter().for_each(|e| {
            e.compile_native();
        });
        self.field.compile_native()
    }

    /// [`Tape::compile_native_for_unsupported_host`] on every tape: the system stays
    /// interpreted (for tests of the fallback).
    #[doc(hidden)]
    pub fn compile_native_for_unsupported_host(&self) -> Backend {
        self.energy.iter().for_each(|e| {
            e.compile_native_for_unsupported_host();
        });
        self.field.compile_native_for_unsupported_host()
    }

    /// Operations per evaluation of `f`, after shared subexpressions and constants are folded.
    pub fn operations_per_evaluation(&self) -> usize {
        self.field.n_operations()
    }

    fn options<'a>(&self, mut options: IntegrateOptions<'a>) -> IntegrateOptions<'a> {
        options.skip_energy |= self.energy.is_none();
        options
    }
}

fn rename(e: Error, name: &str) -> Error {
    match e {
        Error::NonFinite { t, .. } => Error::NonFinite {
            name: name.into(),
            t,
        },
        Error::DimensionMismatch {
            expected, found, ..
        } => Error::DimensionMismatch {
            name: name.into(),
            expected,
            found,
        },
        e => e,
    }
}

impl DynamicalSystem for ExprOde {
    fn phase(&self) -> &Phase {
        &self.phase
    }

    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }

    #[inline]
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.field.n_outputs();
        check_len("state", state, dim)?;
        check_len("out", out, dim)?;
        self.field.eval(state, &[], t, out);
        Ok(())
    }

    /// The energy expression at the system's clock; `NaN` without one.
    fn energy(&self, state: &[f64]) -> f64 {
        match &self.energy {
            Some(e) if state.len() == self.field.n_outputs() => {
                e.eval_scalar(state, &[], self.phase.t())
            }
            _ => f64::NAN,
        }
    }

    fn jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let dim = self.field.n_outputs();
        if let Err(e) = check_len("state", state, dim).and(check_len("jacobian", out, dim * dim)) {
            return Some(Err(e));
        }
        self.field.jacobian(state, &[], t, 0..dim, out);
        Some(Ok(()))
    }

    /// The components as Taylor recurrences ([`TaylorProgram::ode`]).
    fn taylor_field(&self) -> Option<Result<Box<dyn TaylorField>>> {
        Some(TaylorProgram::ode(self).map(|p| Box::new(p) as Box<dyn TaylorField>))
    }

    fn default_method(&self) -> Method {
        Method::ImplicitMidpoint
    }
}

impl OdeSystem for ExprOde {
    /// As the provided method, storing no energies when the system has none.
    fn integrate_with(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        options: IntegrateOptions<'_>,
    ) -> Result<SimulationResult> {
        let options = self.options(options);
        driver::integrate_ode(self, t_span, dt, method, options)
    }
}

/// A user's ODE offers no capabilities beyond the family's.
impl Capabilities for ExprOde {}
