//! [`ExprHamiltonian`]: a Hamiltonian `H(q, p, t)` given as an [`Expr`] (from SymPy through
//! the Python `HamiltonianEngine`, or parsed from text), run natively as a
//! [`HamiltonianSystem`].
//!
//! Hamilton's equations `dq/dt = dH/dp`, `dp/dt = -dH/dq` are derived symbolically once, at
//! construction ([`Expr::diff`]), and compiled into [`Tape`]s evaluated in `f64` every step.
//!
//! # Separability
//!
//! `H` is split into its terms (the operands of a top-level sum). When no term mixes momenta
//! with coordinates or time, `H = T(p) + V(q, t)`; if moreover `T` has a constant diagonal
//! Hessian in `p` and no linear term (`T = T(0) + sum_i p_i^2 / (2 m_i)`, which the splitting
//! drift `q += h mass_inv p` requires), the system is separable: `verlet` and `yoshida4`
//! apply, with `mass_inv_i = d2T/dp_i^2`, force `-dV/dq` and `T(0)` counted in the potential.
//! The test is structural and conservative: an `H` that is separable only after rewriting
//! (`(p + q)^2 - 2 p q`), or a kinetic energy that is not quadratic (relativistic
//! `sqrt(p^2 + m^2)`), is integrated as a general Hamiltonian by `implicit_midpoint` (the
//! default then) or `rk4`.
//!
//! # Jacobians
//!
//! By forward-mode automatic differentiation (num-dual's `Dual64`) over the compiled tapes
//! ([`Tape::jacobian`]): the force Jacobian `-d2V/dq2` of a separable `H`, or the Jacobian of
//! the whole field `[dH/dp, -dH/dq]` of a general one. They serve the implicit-midpoint Newton
//! solve and the tangent dynamics of chaos indicators.
//!
//! ```
//! use physicskit::classical::symbolic::{Expr, ExprHamiltonian};
//! use physicskit::classical::{HamiltonianSystem, Method};
//!
//! // Hénon–Heiles: H = (p0^2 + p1^2)/2 + (q0^2 + q1^2)/2 + q0^2 q1 - q1^3/3.
//! let h = Expr::parse(
//!     "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* 0.5 (^ q0 2)) (* 0.5 (^ q1 2)) \
//!      (* (^ q0 2) q1) (* -0.3333333333333333 (^ q1 3)))",
//! )
//! .unwrap();
//! let mut system = ExprHamiltonian::new(h, 2, vec![], &[0.0, 0.1], &[0.5, 0.0]).unwrap();
//! assert!(system.separable());
//! let result = system.integrate((0.0, 10.0), 0.01, Method::Yoshida4).unwrap();
//! // Yoshida-4 at h = 0.01 keeps H to ~1e-9 on this regular orbit.
//! let e = result.energy.unwrap();
//! assert!(e.iter().all(|v| (v - e[0]).abs() < 1e-7));
//! ```

use super::expr::Expr;
use super::expr_diff::{negate, sum, Var};
use super::tape::{Backend, Tape};
use super::taylor_tape::TaylorProgram;
use crate::classical::core::error::{check_len, check_vector};
use crate::classical::core::{Error, Phase, Result};
use crate::classical::integrators::taylor::TaylorField;
use crate::classical::integrators::{
    hamiltonian_energy, separable_derivatives, separable_jacobian, DynamicalSystem,
    HamiltonianSystem, MassInv, Method,
};
use crate::classical::model::Capabilities;

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    /// `H = T(0) + sum_i mass_inv_i p_i^2 / 2 + V(q, t)`.
    Separable {
        mass_inv: Vec<f64>,
        /// `-dV/dq`, inputs `(q, t)`.
        force: Tape,
        /// `V + T(0)`, inputs `(q, t)`.
        potential: Tape,
        /// `[-dV/dq, V + T(0)]`: the splitting methods' last force of a stored step, whose
        /// potential then costs only the operations the force does not share.
        force_potential: Tape,
    },
    /// Anything else: the field `[dH/dp, -dH/dq]`, inputs `(q, p, t)`.
    General { field: Tape },
}

/// A Hamiltonian system given by an expression (see the module documentation).
#[derive(Debug, Clone)]
pub struct ExprHamiltonian {
    phase: Phase,
    ndof: usize,
    expr: Expr,
    params: Vec<f64>,
    /// `H`, inputs `(q, p, t)`.
    hamiltonian: Tape,
    kind: Kind,
}

/// `(mass_inv, T(0))` if `kinetic` (terms in `p` only) is `T(0) + sum_i mass_inv_i p_i^2/2`.
fn quadratic_kinetic(kinetic: &Expr, ndof: usize, params: &[f64]) -> Result<Option<Vec<f64>>> {
    let zeros = vec![0.0; ndof];
    let value_at_rest = |e: &Expr| -> Result<f64> {
        Ok(Tape::new(std::slice::from_ref(e), 0, ndof, params)?.eval_scalar(&[], &zeros, 0.0))
    };
    let mut mass_inv = Vec::with_capacity(ndof);
    for i in 0..ndof {
        let gradient = kinetic.diff(Var::Second(i));
        if (0..ndof).any(|j| j != i && gradient.depends_on(Var::Second(j))) {
            return Ok(None);
        }
        let curvature = gradient.diff(Var::Second(i));
        if curvature.uses() != (false, false, false) || value_at_rest(&gradient)? != 0.0 {
            return Ok(None);
        }
        let m = value_at_rest(&curvature)?;
        if !m.is_finite() {
            return Ok(None);
        }
        mass_inv.push(m);
    }
    Ok(Some(mass_inv))
}

impl ExprHamiltonian {
    /// `H = expr` in `q_i` (`q<i>`), `p_i` (`p<i>`, stored as [`Expr::Qdot`]), `t` and
    /// parameters with values `params`, starting at `(q0, p0)` at `t = 0`.
    ///
    /// # Errors
    /// `ndof = 0`; non-finite parameters; any failure of [`Expr::validate`]; `q0`, `p0` not
    /// of length `ndof` or not finite.
    pub fn new(expr: Expr, ndof: usize, params: Vec<f64>, q0: &[f64], p0: &[f64]) -> Result<Self> {
        if ndof == 0 {
            return Err(Error::invalid("ndof", 0.0, "must be at least 1"));
        }
        if let Some(bad) = params.iter().find(|p| !p.is_finite()) {
            return Err(Error::invalid("params", *bad, "must be finite"));
        }
        expr.validate(ndof, params.len())?;
        check_vector("q0", q0, ndof)?;
        check_vector("p0", p0, ndof)?;
        let hamiltonian = Tape::new(std::slice::from_ref(&expr), ndof, ndof, &params)?;
        let kind = Self::separate(&expr, ndof, &params)?.map_or_else(
            || {
                let field: Vec<Expr> = (0..ndof)
                    .map(|i| expr.diff(Var::Second(i)))
                    .chain((0..ndof).map(|i| negate(expr.diff(Var::First(i)))))
                    .collect();
                Ok::<_, Error>(Kind::General {
                    field: Tape::new(&field, ndof, ndof, &params)?,
                })
            },
            Ok,
        )?;
        Ok(Self {
            phase: Phase::from_halves("q0", q0, "p0", p0)?,
            ndof,
            expr,
            params,
            hamiltonian,
            kind,
        })
    }

    fn separate(expr: &Expr, ndof: usize, params: &[f64]) -> Result<Option<Kind>> {
        let terms = match expr {
            Expr::Add(terms) => terms.clone(),
            e => vec![e.clone()],
        };
        let (mut kinetic, mut potential) = (Vec::new(), Vec::new());
        for term in terms {
            match term.uses() {
                (_, true, _) if term.uses() != (false, true, false) => return Ok(None),
                (_, true, _) => kinetic.push(term),
                _ => potential.push(term),
            }
        }
        let kinetic = sum(kinetic);
        let Some(mass_inv) = quadratic_kinetic(&kinetic, ndof, params)? else {
            return Ok(None);
        };
        let at_rest = Tape::new(std::slice::from_ref(&kinetic), 0, ndof, params)?.eval_scalar(
            &[],
            &vec![0.0; ndof],
            0.0,
        );
        if at_rest != 0.0 {
            potential.push(Expr::Const(at_rest));
        }
        let potential = sum(potential);
        let mut force: Vec<Expr> = (0..ndof)
            .map(|i| negate(potential.diff(Var::First(i))))
            .collect();
        let force_tape = Tape::new(&force, ndof, 0, params)?;
        force.push(potential.clone());
        Ok(Some(Kind::Separable {
            mass_inv,
            force: force_tape,
            force_potential: Tape::new(&force, ndof, 0, params)?,
            potential: Tape::new(std::slice::from_ref(&potential), ndof, 0, params)?,
        }))
    }

    /// Whether `H` was recognized as `T(p) + V(q, t)` with a quadratic `T` (see the module
    /// documentation): the splitting methods apply.
    pub fn separable(&self) -> bool {
        matches!(self.kind, Kind::Separable { .. })
    }

    /// The expression of `H`.
    pub fn expr(&self) -> &Expr {
        &self.expr
    }

    /// The parameter values.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// `H(q, p, t)`.
    pub fn hamiltonian(&self, q: &[f64], p: &[f64], t: f64) -> f64 {
        self.hamiltonian.eval_scalar(q, p, t)
    }

    /// The tapes: the step's first (the force, or the field), then the others.
    fn tapes(&self) -> [&Tape; 4] {
        match &self.kind {
            Kind::Separable {
                force,
                potential,
                force_potential,
                ..
            } => [force, force_potential, potential, &self.hamiltonian],
            Kind::General { field } => [field, field, field, &self.hamiltonian],
        }
    }

    /// Which code evaluates the right-hand side: native code once compiled (with the feature
    /// `jit`: after [`COMPILE_AFTER`](super::COMPILE_AFTER) evaluations, or by [`compile_native`](Self::compile_native)),
    /// else the interpreter; both give the same bits ([`Tape`]).
    pub fn backend(&self) -> Backend {
        self.tapes()[0].backend()
    }

    /// Compiles every tape to machine code now ([`Tape::compile_native`]) and returns the
    /// right-hand side's backend.
    pub fn compile_native(&self) -> Backend {
        self.tapes().iter().for_each(|t| {
            t.compile_native();
        });
        self.backend()
    }

    /// [`Tape::compile_native_for_unsupported_host`] on every tape: the system stays
    /// interpreted (for tests of the fallback).
    #[doc(hidden)]
    pub fn compile_native_for_unsupported_host(&self) -> Backend {
        self.tapes().iter().for_each(|t| {
            t.compile_native_for_unsupported_host();
        });
        self.backend()
    }

    /// Operations per evaluation of the right-hand side (the force of a separable `H`, else
    /// the whole field), after shared subexpressions and constants are folded.
    pub fn operations_per_evaluation(&self) -> usize {
        match &self.kind {
            Kind::Separable { force, .. } => force.n_operations(),
            Kind::General { field } => field.n_operations(),
        }
    }
}

impl DynamicalSystem for ExprHamiltonian {
    fn phase(&self) -> &Phase {
        &self.phase
    }

    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }

    #[inline]
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("state", state, 2 * self.ndof)?;
        check_len("out", out, 2 * self.ndof)?;
        match &self.kind {
            Kind::Separable { .. } => separable_derivatives(self, t, state, out),
            Kind::General { field } => {
                let (q, p) = state.split_at(self.ndof);
                field.eval(q, p, t, out);
                Ok(())
            }
        }
    }

    /// `H` of `state` at the system's clock: `T(p) + V(q, t)` for a separable `H` (the
    /// splitting methods' masses), else the tape of `H`.
    fn energy(&self, state: &[f64]) -> f64 {
        if state.len() != 2 * self.ndof {
            return f64::NAN;
        }
        match &self.kind {
            Kind::Separable { .. } => hamiltonian_energy(self, state),
            Kind::General { .. } => {
                let (q, p) = state.split_at(self.ndof);
                self.hamiltonian(q, p, self.phase.t())
            }
        }
    }

    fn jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let dim = 2 * self.ndof;
        if let Err(e) = check_len("state", state, dim).and(check_len("jacobian", out, dim * dim)) {
            return Some(Err(e));
        }
        match &self.kind {
            Kind::Separable { .. } => separable_jacobian(self, t, state, out),
            Kind::General { field } => {
                let (q, p) = state.split_at(self.ndof);
                field.jacobian(q, p, t, 0..dim, out);
                Some(Ok(()))
            }
        }
    }

    /// `H`'s canonical equations as Taylor recurrences ([`TaylorProgram::hamiltonian`]).
    fn taylor_field(&self) -> Option<Result<Box<dyn TaylorField>>> {
        Some(TaylorProgram::hamiltonian(self).map(|p| Box::new(p) as Box<dyn TaylorField>))
    }

    fn default_method(&self) -> Method {
        if self.separable() {
            Method::Yoshida4
        } else {
            Method::ImplicitMidpoint
        }
    }
}

impl HamiltonianSystem for ExprHamiltonian {
    fn ndof(&self) -> usize {
        self.ndof
    }

    /// `sum_i mass_inv_i p_i^2 / 2` of a separable `H`; `NaN` for a general one, whose
    /// energy does not split.
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        match &self.kind {
            Kind::Separable { mass_inv, .. } => {
                crate::classical::integrators::quadratic_kinetic_energy(
                    MassInv::PerCoordinate(mass_inv),
                    p,
                )
            }
            Kind::General { .. } => f64::NAN,
        }
    }

    /// `V(q, t) + T(0)` at the system's clock for a separable `H`; `NaN` for a general one.
    #[inline]
    fn potential_energy(&self, q: &[f64]) -> f64 {
        match &self.kind {
            Kind::Separable { potential, .. } if q.len() == self.ndof => {
                potential.eval_scalar(q, &[], self.phase.t())
            }
            Kind::Separable { .. } => f64::NAN,
            Kind::General { .. } => f64::NAN,
        }
    }

    fn separable(&self) -> bool {
        ExprHamiltonian::separable(self)
    }

    fn mass_inv(&self) -> MassInv<'_> {
        match &self.kind {
            Kind::Separable { mass_inv, .. } => MassInv::PerCoordinate(mass_inv),
            Kind::General { .. } => MassInv::Uniform(1.0),
        }
    }

    #[inline]
    fn force(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        match &self.kind {
            Kind::Separable { force, .. } => {
                check_len("q", q, self.ndof)?;
                check_len("out", out, self.ndof)?;
                force.eval(q, &[], t, out);
                Ok(())
            }
            Kind::General { .. } => Err(Error::Unsupported {
                operation: "force".into(),
                reason: "H is not separable as T(p) + V(q) with a quadratic T".into(),
            }),
        }
    }

    /// The force and, from the same tape, `V + T(0)`: the bits of
    /// [`potential_energy`](HamiltonianSystem::potential_energy), since each operation is
    /// the same whichever tape runs it.
    #[inline]
    fn force_and_potential(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        match &self.kind {
            Kind::Separable {
                force_potential, ..
            } => {
                check_len("q", q, self.ndof)?;
                check_len("out", out, self.ndof)?;
                Ok(Some(force_potential.eval_with_last(q, &[], t, out)))
            }
            Kind::General { .. } => self.force(q, t, out).map(|()| None),
        }
    }

    fn force_jacobian(&self, q: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        match &self.kind {
            Kind::Separable { force, .. } => {
                let n = self.ndof;
                if let Err(e) = check_len("q", q, n).and(check_len("jacobian", out, n * n)) {
                    return Some(Err(e));
                }
                force.jacobian(q, &[], t, 0..n, out);
                Some(Ok(()))
            }
            Kind::General { .. } => None,
        }
    }
}

/// A user's Hamiltonian offers no capabilities beyond the family's.
impl Capabilities for ExprHamiltonian {}
