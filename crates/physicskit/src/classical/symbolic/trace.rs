//! Tracing: a Lagrangian written once, generic over the number type ([`Lagrangian`]), turned
//! into an expression ([`ExprLagrangian`]) by evaluating it once on a scalar that records the
//! operations instead of computing them ([`trace_lagrangian`]).
//!
//! Every arithmetic operation and elementary function of the
//! [`Scalar`](crate::classical::lagrangian::Scalar) trait on the tracing scalar appends one
//! node to a per-thread recording: the node is the [`Expr`] of the
//! operation on its operands' expressions (constants folded as `f64` arithmetic folds them,
//! sums and products kept n-ary). The Lagrangian's result is then the expression of `L(q,
//! qdot, t)` in the variables `q_i`, `qdot_i`, `t`, with the system's parameters as
//! constants: the Lagrangian's own code, not a second transcription of it, so the traced form
//! cannot disagree with the `f64` one beyond rounding. Shared subexpressions become repeated
//! subtrees; the Taylor compilation ([`TaylorProgram`](super::TaylorProgram)) hash-conses them
//! back into one node each.
//!
//! What a trace cannot follow is a decision on values: a comparison (`<`, `==`,
//! `PartialOrd`), the real part (`re()`), `signum`, `atan2`'s quadrant, `%`, the
//! small-argument branches of the spherical Bessel functions. The tracing scalar has no value,
//! so such a use is recorded and the trace is refused ([`Error::UnsupportedMethod`] for
//! `taylor`, naming the operation), rather than silently fixing the branch taken at one point.
//! The built-in Lagrangians are straight-line code and trace completely.

use std::cell::RefCell;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};

use super::expr::{Expr, ExprLagrangian, Func};
use super::expr_hamiltonian::ExprHamiltonian;
use crate::classical::core::{Error, Result};
use crate::classical::integrators::taylor::TaylorField;
use crate::classical::lagrangian::{Lagrangian, Scalar};

/// The operations recorded so far on this thread, and the first operation that needed a
/// value (which makes the trace unusable).
struct Recording {
    nodes: Vec<Expr>,
    needs_value: Option<&'static str>,
}

thread_local! {
    static RECORDING: RefCell<Option<Recording>> = const { RefCell::new(None) };
}

/// A value of the traced computation: the index of its node in this thread's recording.
/// Outside a recording (never, through [`trace_lagrangian`]) every operation yields an index
/// past the end, whose expression is `NaN`.
#[derive(Clone, Copy)]
struct Traced(u32);

/// Clears the recording when the trace ends, also when the Lagrangian panics.
struct RecordingGuard;

impl Drop for RecordingGuard {
    fn drop(&mut self) {
        RECORDING.with(|r| r.borrow_mut().take());
    }
}

fn push(expr: Expr) -> Traced {
    RECORDING.with(|r| match r.borrow_mut().as_mut() {
        Some(rec) => {
            rec.nodes.push(expr);
            Traced(u32::try_from(rec.nodes.len() - 1).unwrap_or(u32::MAX))
        }
        None => Traced(u32::MAX),
    })
}

fn expr_of(x: Traced) -> Expr {
    RECORDING.with(|r| {
        r.borrow()
            .as_ref()
            .and_then(|rec| rec.nodes.get(x.0 as usize).cloned())
            .unwrap_or(Expr::Const(f64::NAN))
    })
}

/// Records that `operation` needed a value the trace does not have.
fn needs_value(operation: &'static str) {
    RECORDING.with(|r| {
        if let Some(rec) = r.borrow_mut().as_mut() {
            rec.needs_value.get_or_insert(operation);
        }
    });
}

fn constant(c: f64) -> Traced {
    push(Expr::Const(c))
}

/// `a op b`, folded when both are constants (as the `f64` code would compute it).
fn binary(
    a: Traced,
    b: Traced,
    fold: fn(f64, f64) -> f64,
    build: fn(Expr, Expr) -> Expr,
) -> Traced {
    match (expr_of(a), expr_of(b)) {
        (Expr::Const(x), Expr::Const(y)) => constant(fold(x, y)),
        (x, y) => push(build(x, y)),
    }
}

fn unary(a: Traced, fold: impl Fn(f64) -> f64, build: impl Fn(Expr) -> Expr) -> Traced {
    match expr_of(a) {
        Expr::Const(x) => constant(fold(x)),
        x => push(build(x)),
    }
}

fn func(a: Traced, f: Func) -> Traced {
    unary(a, |x| f.apply(x), |x| Expr::Func(f, Box::new(x)))
}

/// `a + b` with sums kept n-ary (a sum built term by term stays one shallow node).
fn sum_of(a: Expr, b: Expr) -> Expr {
    match a {
        Expr::Add(mut terms) => {
            terms.push(b);
            Expr::Add(terms)
        }
        a => Expr::Add(vec![a, b]),
    }
}

/// `a b` with products kept n-ary.
fn product_of(a: Expr, b: Expr) -> Expr {
    match a {
        Expr::Mul(mut factors) => {
            factors.push(b);
            Expr::Mul(factors)
        }
        a => Expr::Mul(vec![a, b]),
    }
}

fn add(a: Traced, b: Traced) -> Traced {
    binary(a, b, |x, y| x + y, sum_of)
}

fn sub(a: Traced, b: Traced) -> Traced {
    binary(
        a,
        b,
        |x, y| x - y,
        |x, y| Expr::Sub(Box::new(x), Box::new(y)),
    )
}

fn mul(a: Traced, b: Traced) -> Traced {
    binary(a, b, |x, y| x * y, product_of)
}

fn div(a: Traced, b: Traced) -> Traced {
    binary(
        a,
        b,
        |x, y| x / y,
        |x, y| Expr::Div(Box::new(x), Box::new(y)),
    )
}

fn rem(_: Traced, _: Traced) -> Traced {
    needs_value("the remainder %");
    constant(f64::NAN)
}

/// `L(q, qdot, t)` of `lagrangian` as an expression in `q_i`, `qdot_i` and `t`, its parameters
/// folded in as constants (see the module documentation).
///
/// # Errors
/// [`Error::UnsupportedMethod`] (for `taylor`) when `L` decides on a value of its arguments
/// (a comparison, `re()`, `signum`, `atan2`, ...), naming the operation; whatever
/// [`ExprLagrangian::new`] refuses (a non-finite constant in `L`).
pub fn trace_lagrangian<L: Lagrangian>(lagrangian: &L) -> Result<ExprLagrangian> {
    let n = lagrangian.ndof();
    let expr = record(n, |q, qdot, t| lagrangian.lagrangian(q, qdot, t))?;
    ExprLagrangian::new(expr, n, Vec::new())
}

/// A Hamiltonian `H(q, p, t)` written once, generic over the number type, as a system with a
/// hand-written `f64` force writes its potential so that [`trace_hamiltonian`] can give it a
/// Taylor form. Straight-line code only, as for [`Lagrangian`] (a branch on a parameter is
/// fine: parameters are numbers, not traced values).
pub trait TracedHamiltonian {
    /// Degrees of freedom (the length of `q` and of `p`).
    fn ndof(&self) -> usize;

    /// `H(q, p, t)`.
    fn hamiltonian<D: Scalar>(&self, q: &[D], p: &[D], t: D) -> D;
}

/// `H(q, p, t)` of `hamiltonian` as an expression (momenta as `p<i>`, stored as
/// [`Expr::Qdot`]), with the system at `(q0, p0)`: see the module documentation.
///
/// # Errors
/// As [`trace_lagrangian`]; whatever [`ExprHamiltonian::new`] refuses.
pub fn trace_hamiltonian<H: TracedHamiltonian>(
    hamiltonian: &H,
    q0: &[f64],
    p0: &[f64],
) -> Result<ExprHamiltonian> {
    let n = hamiltonian.ndof();
    let expr = record(n, |q, p, t| hamiltonian.hamiltonian(q, p, t))?;
    ExprHamiltonian::new(expr, n, Vec::new(), q0, p0)
}

/// The Taylor form of a [`TracedHamiltonian`]: its trace compiled into the recurrences of
/// Hamilton's equations on `(q, p)`
/// ([`TaylorProgram::hamiltonian`](super::TaylorProgram::hamiltonian)).
///
/// # Errors
/// As [`trace_hamiltonian`].
pub fn traced_hamiltonian_taylor_field<H: TracedHamiltonian>(
    hamiltonian: &H,
) -> Result<Box<dyn TaylorField>> {
    let n = hamiltonian.ndof();
    // The start only seeds the engine's own state; the Taylor form does not keep it.
    let zero = vec![0.0; n];
    let traced = trace_hamiltonian(hamiltonian, &zero, &zero)?;
    Ok(Box::new(super::TaylorProgram::hamiltonian(&traced)?))
}

/// The expression of `f(q, v, t)` (`v` the velocities or momenta, recorded as
/// [`Expr::Qdot`]) for `n` degrees of freedom, traced on this thread.
fn record(n: usize, f: impl FnOnce(&[Traced], &[Traced], Traced) -> Traced) -> Result<Expr> {
    let started = RECORDING.with(|r| {
        let mut r = r.borrow_mut();
        if r.is_some() {
            return false;
        }
        *r = Some(Recording {
            nodes: Vec::new(),
            needs_value: None,
        });
        true
    });
    if !started {
        // A Lagrangian that traces another one inside its own `lagrangian`.
        return Err(refusal("traces a Lagrangian inside its own"));
    }
    let _guard = RecordingGuard;
    let q: Vec<Traced> = (0..n).map(|i| push(Expr::Q(i))).collect();
    let v: Vec<Traced> = (0..n).map(|i| push(Expr::Qdot(i))).collect();
    let t = push(Expr::T);
    let value = f(&q, &v, t);
    let expr = expr_of(value);
    if let Some(operation) = RECORDING.with(|r| r.borrow().as_ref().and_then(|rec| rec.needs_value))
    {
        return Err(refusal(operation));
    }
    Ok(expr)
}

/// The Taylor form of any [`Lagrangian`]: its trace ([`trace_lagrangian`]) compiled into the
/// recurrences of its Euler–Lagrange equations on `(q, qdot)`
/// ([`TaylorProgram::lagrangian`](super::TaylorProgram::lagrangian)).
///
/// # Errors
/// As [`trace_lagrangian`].
pub fn traced_taylor_field<L: Lagrangian>(lagrangian: &L) -> Result<Box<dyn TaylorField>> {
    let traced = trace_lagrangian(lagrangian)?;
    Ok(Box::new(super::TaylorProgram::lagrangian(&traced)?))
}

fn refusal(operation: &str) -> Error {
    Error::UnsupportedMethod {
        method: "taylor".into(),
        reason: format!(
            "this Lagrangian has no Taylor form: its code takes a decision on a value of its \
             arguments ({operation}), which a trace of its operations cannot follow; write L \
             without it (an expression, or straight-line arithmetic and elementary functions), \
             or use dop853"
        ),
    }
}

macro_rules! binary_ops {
    ($($trait:ident $method:ident $assign_trait:ident $assign:ident $f:ident;)*) => {$(
        impl $trait for Traced {
            type Output = Traced;
            fn $method(self, rhs: Traced) -> Traced {
                $f(self, rhs)
            }
        }
        impl $trait<&Traced> for Traced {
            type Output = Traced;
            fn $method(self, rhs: &Traced) -> Traced {
                $f(self, *rhs)
            }
        }
        impl $trait<f64> for Traced {
            type Output = Traced;
            fn $method(self, rhs: f64) -> Traced {
                $f(self, constant(rhs))
            }
        }
        impl $assign_trait for Traced {
            fn $assign(&mut self, rhs: Traced) {
                *self = $f(*self, rhs);
            }
        }
        impl $assign_trait<f64> for Traced {
            fn $assign(&mut self, rhs: f64) {
                *self = $f(*self, constant(rhs));
            }
        }
    )*};
}

binary_ops! {
    Add add AddAssign add_assign add;
    Sub sub SubAssign sub_assign sub;
    Mul mul MulAssign mul_assign mul;
    Div div DivAssign div_assign div;
    Rem rem RemAssign rem_assign rem;
}

impl Neg for Traced {
    type Output = Traced;
    fn neg(self) -> Traced {
        unary(self, |x| -x, |x| Expr::Neg(Box::new(x)))
    }
}

impl PartialEq for Traced {
    fn eq(&self, _: &Traced) -> bool {
        needs_value("a comparison ==");
        false
    }
}

impl PartialOrd for Traced {
    fn partial_cmp(&self, _: &Traced) -> Option<std::cmp::Ordering> {
        needs_value("a comparison");
        None
    }
}

impl PartialEq<f64> for Traced {
    fn eq(&self, _: &f64) -> bool {
        needs_value("a comparison ==");
        false
    }
}

impl PartialOrd<f64> for Traced {
    fn partial_cmp(&self, _: &f64) -> Option<std::cmp::Ordering> {
        needs_value("a comparison");
        None
    }
}

impl fmt::Debug for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Traced({})", expr_of(*self))
    }
}

impl fmt::Display for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", expr_of(*self))
    }
}

impl From<f64> for Traced {
    fn from(c: f64) -> Traced {
        constant(c)
    }
}

impl Zero for Traced {
    fn zero() -> Traced {
        constant(0.0)
    }
    fn is_zero(&self) -> bool {
        needs_value("is_zero");
        false
    }
}

impl One for Traced {
    fn one() -> Traced {
        constant(1.0)
    }
}

impl Num for Traced {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> std::result::Result<Traced, Self::FromStrRadixErr> {
        f64::from_str_radix(s, radix).map(constant)
    }
}

impl Signed for Traced {
    fn abs(&self) -> Traced {
        func(*self, Func::Abs)
    }
    fn abs_sub(&self, _: &Traced) -> Traced {
        needs_value("abs_sub");
        constant(f64::NAN)
    }
    fn signum(&self) -> Traced {
        needs_value("signum");
        constant(f64::NAN)
    }
    fn is_positive(&self) -> bool {
        needs_value("is_positive");
        false
    }
    fn is_negative(&self) -> bool {
        needs_value("is_negative");
        false
    }
}

impl Inv for Traced {
    type Output = Traced;
    fn inv(self) -> Traced {
        div(constant(1.0), self)
    }
}

impl Sum for Traced {
    fn sum<I: Iterator<Item = Traced>>(iter: I) -> Traced {
        iter.fold(constant(0.0), add)
    }
}

impl Product for Traced {
    fn product<I: Iterator<Item = Traced>>(iter: I) -> Traced {
        iter.fold(constant(1.0), mul)
    }
}

impl FromPrimitive for Traced {
    fn from_i64(n: i64) -> Option<Traced> {
        Some(constant(n as f64))
    }
    fn from_u64(n: u64) -> Option<Traced> {
        Some(constant(n as f64))
    }
    fn from_f64(x: f64) -> Option<Traced> {
        Some(constant(x))
    }
}

impl DualStruct for Traced {
    type Real = f64;
    type Inner = f64;
    fn re(&self) -> f64 {
        needs_value("the real part re()");
        f64::NAN
    }
    fn from_inner(inner: &f64) -> Traced {
        constant(*inner)
    }
}

impl Mappable<Traced> for Traced {
    type Output<O> = O;
    fn map_dual<M: Fn(Traced) -> O, O>(self, f: M) -> O {
        f(self)
    }
}

impl DualNum for Traced {
    type Primitive = f64;
    const NDERIV: usize = 0;
    type InnerDual = f64;

    fn from_re(re: f64) -> Traced {
        constant(re)
    }
    fn scale(self, factor: &f64) -> Traced {
        self * *factor
    }
    fn recip(&self) -> Traced {
        self.inv()
    }
    fn powi(&self, n: i32) -> Traced {
        unary(*self, |x| x.powi(n), |x| Expr::Powi(Box::new(x), n))
    }
    fn powf(&self, n: f64) -> Traced {
        unary(*self, |x| x.powf(n), |x| Expr::Powf(Box::new(x), n))
    }
    fn powd(&self, n: Traced) -> Traced {
        binary(*self, n, f64::powf, |x, y| {
            Expr::Pow(Box::new(x), Box::new(y))
        })
    }
    fn sqrt(&self) -> Traced {
        func(*self, Func::Sqrt)
    }
    fn cbrt(&self) -> Traced {
        self.powf(1.0 / 3.0)
    }
    fn exp(&self) -> Traced {
        func(*self, Func::Exp)
    }
    fn exp2(&self) -> Traced {
        (*self * std::f64::consts::LN_2).exp()
    }
    fn exp_m1(&self) -> Traced {
        self.exp() - 1.0
    }
    fn ln(&self) -> Traced {
        func(*self, Func::Ln)
    }
    fn log(&self, base: f64) -> Traced {
        self.ln() / base.ln()
    }
    fn log2(&self) -> Traced {
        self.ln() / std::f64::consts::LN_2
    }
    fn log10(&self) -> Traced {
        self.ln() / std::f64::consts::LN_10
    }
    fn ln_1p(&self) -> Traced {
        (*self + 1.0).ln()
    }
    fn sin(&self) -> Traced {
        func(*self, Func::Sin)
    }
    fn cos(&self) -> Traced {
        func(*self, Func::Cos)
    }
    fn tan(&self) -> Traced {
        func(*self, Func::Tan)
    }
    fn sin_cos(&self) -> (Traced, Traced) {
        (self.sin(), self.cos())
    }
    fn asin(&self) -> Traced {
        func(*self, Func::Asin)
    }
    fn acos(&self) -> Traced {
        func(*self, Func::Acos)
    }
    fn atan(&self) -> Traced {
        func(*self, Func::Atan)
    }
    fn atan2(&self, _: Traced) -> Traced {
        needs_value("atan2, whose quadrant depends on the signs");
        constant(f64::NAN)
    }
    fn sinh(&self) -> Traced {
        func(*self, Func::Sinh)
    }
    fn cosh(&self) -> Traced {
        func(*self, Func::Cosh)
    }
    fn tanh(&self) -> Traced {
        func(*self, Func::Tanh)
    }
    fn asinh(&self) -> Traced {
        (*self + (*self * *self + 1.0).sqrt()).ln()
    }
    fn acosh(&self) -> Traced {
        (*self + (*self * *self - 1.0).sqrt()).ln()
    }
    fn atanh(&self) -> Traced {
        ((constant(1.0) + *self) / (constant(1.0) - *self)).ln() * 0.5
    }
    fn sph_j0(&self) -> Traced {
        needs_value("sph_j0, which branches near 0");
        constant(f64::NAN)
    }
    fn sph_j1(&self) -> Traced {
        needs_value("sph_j1, which branches near 0");
        constant(f64::NAN)
    }
    fn sph_j2(&self) -> Traced {
        needs_value("sph_j2, which branches near 0");
        constant(f64::NAN)
    }
}
