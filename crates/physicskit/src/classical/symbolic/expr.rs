//! [`Expr`]: a small expression tree for Lagrangians supplied at run time (from SymPy via the
//! Python package, or from a string), and [`ExprLagrangian`], which runs one natively through
//! the [`LagrangianEngine`](super::LagrangianEngine).
//!
//! An expression is built from constants, the variables `q_i`, `qdot_i`, `t`, parameters
//! `param_i` (values held by the [`ExprLagrangian`], so a parameter sweep does not rebuild the
//! tree), n-ary sums and products, `-`, `/`, powers and the elementary functions of [`Func`].
//! Evaluation is generic over the number type, so the engine differentiates it exactly like a
//! hand-written Lagrangian; it walks the tree recursively and never allocates.
//!
//! # Serialized form
//!
//! [`Expr::parse`] reads, and `Display` writes, a prefix S-expression:
//!
//! ```text
//! expr  := number | q<i> | qdot<i> | p<i> | y<i> | t | param<i> | pi | ( op expr... )
//! op    := + | * | - | / | ^ | neg | sin | cos | tan | exp | ln | sqrt | sinh | cosh | tanh
//!          | asin | acos | atan | abs
//! ```
//!
//! `p<i>` (a momentum, for [`ExprHamiltonian`](super::ExprHamiltonian)) reads as `qdot<i>`
//! and `y<i>` (a state component, for [`ExprOde`](super::ExprOde)) as `q<i>`: the tree
//! stores the slot (first or second vector), and `Display` writes `q`/`qdot`.
//!
//! `(+ a b ...)` and `(* a b ...)` take any number of operands, `(- a b)` subtracts,
//! `(- a)` and `(neg a)` negate, and `(^ a n)` is an integer power when `n` is an integer
//! literal, a real power for any other literal and `exp(n ln a)` otherwise.
//!
//! ```
//! use physicskit::classical::symbolic::{Expr, ExprLagrangian};
//! use physicskit::classical::lagrangian::LagrangianEngine;
//!
//! // A pendulum: L = qdot0^2 / 2 + g cos q0, with g = param0.
//! let expr = Expr::parse("(+ (* 0.5 (^ qdot0 2)) (* param0 (cos q0)))").unwrap();
//! let engine = LagrangianEngine::new(ExprLagrangian::new(expr, 1, vec![9.81]).unwrap()).unwrap();
//! let mut qddot = [0.0];
//! engine.acceleration(&[0.3], &[0.0], 0.0, &mut qddot).unwrap();
//! assert!((qddot[0] + 9.81 * 0.3_f64.sin()).abs() < 1e-14);
//! ```

use std::fmt;

use crate::classical::core::{Error, Result};
use crate::classical::lagrangian::{Lagrangian, Scalar};

/// Deepest nesting accepted (by [`Expr::parse`] and [`ExprLagrangian::new`]): evaluation
/// recurses once per level, and 256 levels stay far inside any thread's stack while no sensible
/// Lagrangian comes near (n-ary sums and products keep SymPy trees shallow).
pub const MAX_EXPR_DEPTH: usize = 256;

/// An elementary function of one argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Func {
    /// `sin x`
    Sin,
    /// `cos x`
    Cos,
    /// `tan x`
    Tan,
    /// `e^x`
    Exp,
    /// Natural logarithm.
    Ln,
    /// Square root.
    Sqrt,
    /// `sinh x`
    Sinh,
    /// `cosh x`
    Cosh,
    /// `tanh x`
    Tanh,
    /// `arcsin x`
    Asin,
    /// `arccos x`
    Acos,
    /// `arctan x`
    Atan,
    /// `|x|`
    Abs,
}

impl Func {
    /// Every function, in declaration order.
    pub const ALL: [Func; 13] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Exp,
        Func::Ln,
        Func::Sqrt,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Abs,
    ];

    /// The name used in the serialized form (`"sin"`, `"ln"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Sqrt => "sqrt",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Abs => "abs",
        }
    }

    /// The function called `name`, if any.
    pub fn from_name(name: &str) -> Option<Func> {
        Func::ALL.into_iter().find(|f| f.name() == name)
    }

    #[inline]
    pub(crate) fn apply<D: Scalar>(self, x: D) -> D {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Sqrt => x.sqrt(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Abs => x.abs(),
        }
    }
}

/// An expression in `q`, `qdot`, `t` and parameters (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A finite constant.
    Const(f64),
    /// Generalized coordinate `q_i`.
    Q(usize),
    /// Generalized velocity `qdot_i`.
    Qdot(usize),
    /// Time.
    T,
    /// Parameter `i` of the [`ExprLagrangian`].
    Param(usize),
    /// Sum of the terms (an empty sum is 0).
    Add(Vec<Expr>),
    /// Product of the factors (an empty product is 1).
    Mul(Vec<Expr>),
    /// `a - b`
    Sub(Box<Expr>, Box<Expr>),
    /// `a / b`
    Div(Box<Expr>, Box<Expr>),
    /// `-a`
    Neg(Box<Expr>),
    /// `a^n`, integer `n`.
    Powi(Box<Expr>, i32),
    /// `a^x`, constant real `x`.
    Powf(Box<Expr>, f64),
    /// `a^b = exp(b ln a)`.
    Pow(Box<Expr>, Box<Expr>),
    /// `f(a)`
    Func(Func, Box<Expr>),
}

impl Expr {
    /// `q_i`.
    pub fn q(i: usize) -> Expr {
        Expr::Q(i)
    }

    /// `qdot_i`.
    pub fn qdot(i: usize) -> Expr {
        Expr::Qdot(i)
    }

    /// Parameter `i`.
    pub fn param(i: usize) -> Expr {
        Expr::Param(i)
    }

    /// A constant.
    pub fn constant(x: f64) -> Expr {
        Expr::Const(x)
    }

    /// `self^n`.
    pub fn powi(self, n: i32) -> Expr {
        Expr::Powi(Box::new(self), n)
    }

    /// `self^x`.
    pub fn powf(self, x: f64) -> Expr {
        Expr::Powf(Box::new(self), x)
    }

    /// `f(self)`.
    pub fn apply(self, f: Func) -> Expr {
        Expr::Func(f, Box::new(self))
    }

    /// `sin(self)`.
    pub fn sin(self) -> Expr {
        self.apply(Func::Sin)
    }

    /// `cos(self)`.
    pub fn cos(self) -> Expr {
        self.apply(Func::Cos)
    }

    /// Evaluates the expression; `params` holds the parameter values. Indices must have been
    /// checked ([`validate`](Self::validate)); an unchecked out-of-range index evaluates to
    /// `NaN` rather than panicking.
    pub fn eval<D: Scalar>(&self, q: &[D], qdot: &[D], t: D, params: &[f64]) -> D {
        let nan = || D::from(f64::NAN);
        match self {
            Expr::Const(c) => D::from(*c),
            Expr::Q(i) => q.get(*i).copied().unwrap_or_else(nan),
            Expr::Qdot(i) => qdot.get(*i).copied().unwrap_or_else(nan),
            Expr::T => t,
            Expr::Param(i) => params.get(*i).map_or_else(nan, |&p| D::from(p)),
            Expr::Add(terms) => match terms.split_first() {
                None => D::zero(),
                Some((first, rest)) => rest.iter().fold(first.eval(q, qdot, t, params), |s, e| {
                    s + e.eval(q, qdot, t, params)
                }),
            },
            Expr::Mul(factors) => match factors.split_first() {
                None => D::one(),
                Some((first, rest)) => rest.iter().fold(first.eval(q, qdot, t, params), |s, e| {
                    s * e.eval(q, qdot, t, params)
                }),
            },
            Expr::Sub(a, b) => a.eval(q, qdot, t, params) - b.eval(q, qdot, t, params),
            Expr::Div(a, b) => a.eval(q, qdot, t, params) / b.eval(q, qdot, t, params),
            Expr::Neg(a) => -a.eval(q, qdot, t, params),
            Expr::Powi(a, n) => a.eval(q, qdot, t, params).powi(*n),
            Expr::Powf(a, x) => a.eval(q, qdot, t, params).powf(*x),
            Expr::Pow(a, b) => a.eval(q, qdot, t, params).powd(b.eval(q, qdot, t, params)),
            Expr::Func(f, a) => f.apply(a.eval(q, qdot, t, params)),
        }
    }

    pub(crate) fn children(&self) -> impl Iterator<Item = &Expr> {
        let (slice, pair): (&[Expr], [Option<&Expr>; 2]) = match self {
            Expr::Add(v) | Expr::Mul(v) => (v, [None, None]),
            Expr::Sub(a, b) | Expr::Div(a, b) | Expr::Pow(a, b) => (&[], [Some(a), Some(b)]),
            Expr::Neg(a) | Expr::Powi(a, _) | Expr::Powf(a, _) | Expr::Func(_, a) => {
                (&[], [Some(a), None])
            }
            Expr::Const(_) | Expr::Q(_) | Expr::Qdot(_) | Expr::T | Expr::Param(_) => {
                (&[], [None, None])
            }
        };
        slice.iter().chain(pair.into_iter().flatten())
    }

    /// Nesting depth (a leaf has depth 1). Computed without recursion, so it is safe on any
    /// tree.
    pub fn depth(&self) -> usize {
        let mut stack = vec![(self, 1_usize)];
        let mut deepest = 0;
        while let Some((e, d)) = stack.pop() {
            deepest = deepest.max(d);
            stack.extend(e.children().map(|c| (c, d + 1)));
        }
        deepest
    }

    /// Checks that every `q_i`, `qdot_i` has `i < ndof`, every parameter index is below
    /// `nparams`, every constant is finite and the depth is at most [`MAX_EXPR_DEPTH`].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `expression` and describing the first offence.
    pub fn validate(&self, ndof: usize, nparams: usize) -> Result<()> {
        let depth = self.depth();
        if depth > MAX_EXPR_DEPTH {
            return Err(Error::invalid(
                "expression",
                depth as f64,
                format!("nested {depth} levels deep; at most {MAX_EXPR_DEPTH} are supported"),
            ));
        }
        let mut stack = vec![self];
        while let Some(e) = stack.pop() {
            let bad_index = |kind: &str, i: usize, limit: usize, what: &str| {
                Err(Error::invalid(
                    "expression",
                    i as f64,
                    format!("refers to {kind}{i}, but there are only {limit} {what}"),
                ))
            };
            match e {
                Expr::Q(i) if *i >= ndof => return bad_index("q", *i, ndof, "coordinates"),
                Expr::Qdot(i) if *i >= ndof => return bad_index("qdot", *i, ndof, "coordinates"),
                Expr::Param(i) if *i >= nparams => {
                    return bad_index("param", *i, nparams, "parameters")
                }
                Expr::Const(c) | Expr::Powf(_, c) if !c.is_finite() => {
                    return Err(Error::invalid("expression", *c, "constants must be finite"));
                }
                _ => {}
            }
            stack.extend(e.children());
        }
        Ok(())
    }

    /// Parses the serialized form (see the module documentation).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `expression`, with the offending token and its
    /// position, for malformed input, unknown names or nesting deeper than
    /// [`MAX_EXPR_DEPTH`].
    pub fn parse(text: &str) -> Result<Expr> {
        let tokens = tokenize(text);
        let mut pos = 0;
        let expr = parse_expr(&tokens, &mut pos, 1)?;
        if pos != tokens.len() {
            return Err(syntax(&tokens, pos, "unexpected text after the expression"));
        }
        Ok(expr)
    }
}

fn tokenize(text: &str) -> Vec<(usize, &str)> {
    let mut tokens = Vec::new();
    let mut start = None;
    for (i, ch) in text.char_indices() {
        let delimiter = ch == '(' || ch == ')';
        if delimiter || ch.is_whitespace() {
            if let Some(s) = start.take() {
                tokens.push((s, &text[s..i]));
            }
            if delimiter {
                tokens.push((i, &text[i..i + 1]));
            }
        } else if start.is_none() {
            start = Some(i);
        }
    }
    if let Some(s) = start {
        tokens.push((s, &text[s..]));
    }
    tokens
}

fn syntax(tokens: &[(usize, &str)], pos: usize, reason: &str) -> Error {
    match tokens.get(pos) {
        Some((offset, tok)) => Error::invalid(
            "expression",
            *offset as f64,
            format!("{reason} at byte {offset} (`{tok}`)"),
        ),
        None => Error::invalid("expression", f64::NAN, format!("{reason} at the end")),
    }
}

fn index_after(tok: &str, prefix: &str) -> Option<usize> {
    tok.strip_prefix(prefix)
        .filter(|rest| !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|rest| rest.parse().ok())
}

fn parse_atom(tok: &str) -> Option<Expr> {
    if let Ok(x) = tok.parse::<f64>() {
        return x.is_finite().then_some(Expr::Const(x));
    }
    match tok {
        "t" => return Some(Expr::T),
        "pi" => return Some(Expr::Const(std::f64::consts::PI)),
        _ => {}
    }
    index_after(tok, "qdot")
        .map(Expr::Qdot)
        .or_else(|| index_after(tok, "q").map(Expr::Q))
        .or_else(|| index_after(tok, "p").map(Expr::Qdot))
        .or_else(|| index_after(tok, "y").map(Expr::Q))
        .or_else(|| index_after(tok, "param").map(Expr::Param))
}

fn parse_expr(tokens: &[(usize, &str)], pos: &mut usize, depth: usize) -> Result<Expr> {
    if depth > MAX_EXPR_DEPTH {
        return Err(syntax(tokens, *pos, "expression nested too deeply"));
    }
    let Some(&(_, tok)) = tokens.get(*pos) else {
        return Err(syntax(tokens, *pos, "expected an expression"));
    };
    if tok == ")" {
        return Err(syntax(tokens, *pos, "expected an expression"));
    }
    if tok != "(" {
        let atom = parse_atom(tok).ok_or_else(|| {
            syntax(
                tokens,
                *pos,
                "unknown name or non-finite number (expected a number, q<i>, qdot<i>, p<i>, \
                 y<i>, t, param<i> or pi)",
            )
        })?;
        *pos += 1;
        return Ok(atom);
    }
    let op_pos = *pos + 1;
    let Some(&(_, op)) = tokens.get(op_pos) else {
        return Err(syntax(tokens, op_pos, "expected an operator"));
    };
    *pos = op_pos + 1;
    let mut args = Vec::new();
    let mut arg_tokens = Vec::new();
    loop {
        match tokens.get(*pos) {
            None => return Err(syntax(tokens, *pos, "missing `)`")),
            Some(&(_, ")")) => {
                *pos += 1;
                break;
            }
            Some(&(_, t)) => {
                arg_tokens.push(t);
                args.push(parse_expr(tokens, pos, depth + 1)?);
            }
        }
    }
    let arity = |n: usize| -> Result<()> {
        if args.len() == n {
            Ok(())
        } else {
            Err(syntax(
                tokens,
                op_pos,
                &format!("`{op}` takes {n} operand(s), got {}", args.len()),
            ))
        }
    };
    let mut it = args.clone().into_iter();
    let mut next = || Box::new(it.next().unwrap_or(Expr::Const(f64::NAN)));
    Ok(match op {
        "+" => Expr::Add(args),
        "*" => Expr::Mul(args),
        "-" if args.len() == 1 => Expr::Neg(next()),
        "-" => {
            arity(2)?;
            Expr::Sub(next(), next())
        }
        "neg" => {
            arity(1)?;
            Expr::Neg(next())
        }
        "/" => {
            arity(2)?;
            Expr::Div(next(), next())
        }
        "^" | "pow" => {
            arity(2)?;
            let base = next();
            let exponent = arg_tokens[1];
            if let Ok(n) = exponent.parse::<i32>() {
                Expr::Powi(base, n)
            } else if let Some(Expr::Const(x)) = parse_atom(exponent) {
                Expr::Powf(base, x)
            } else {
                Expr::Pow(base, next())
            }
        }
        name => match Func::from_name(name) {
            Some(f) => {
                arity(1)?;
                Expr::Func(f, next())
            }
            None => return Err(syntax(tokens, op_pos, "unknown operator")),
        },
    })
}

impl fmt::Display for Expr {
    /// The serialized form read by [`Expr::parse`]; constants are written so that they read
    /// back bit for bit.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let list = |f: &mut fmt::Formatter<'_>, op: &str, items: &[&Expr]| {
            write!(f, "({op}")?;
            for item in items {
                write!(f, " {item}")?;
            }
            write!(f, ")")
        };
        match self {
            Expr::Const(c) => write!(f, "{c:?}"),
            Expr::Q(i) => write!(f, "q{i}"),
            Expr::Qdot(i) => write!(f, "qdot{i}"),
            Expr::T => write!(f, "t"),
            Expr::Param(i) => write!(f, "param{i}"),
            Expr::Add(v) => list(f, "+", &v.iter().collect::<Vec<_>>()),
            Expr::Mul(v) => list(f, "*", &v.iter().collect::<Vec<_>>()),
            Expr::Sub(a, b) => list(f, "-", &[a, b]),
            Expr::Div(a, b) => list(f, "/", &[a, b]),
            Expr::Neg(a) => list(f, "neg", &[a]),
            Expr::Powi(a, n) => write!(f, "(^ {a} {n})"),
            Expr::Powf(a, x) => write!(f, "(^ {a} {x:?})"),
            Expr::Pow(a, b) => list(f, "^", &[a, b]),
            Expr::Func(func, a) => list(f, func.name(), &[a]),
        }
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident, $build:expr) => {
        impl std::ops::$trait for Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                $build(self, rhs)
            }
        }
    };
}

binary_op!(Add, add, |a, b| Expr::Add(vec![a, b]));
binary_op!(Mul, mul, |a, b| Expr::Mul(vec![a, b]));
binary_op!(Sub, sub, |a, b| Expr::Sub(Box::new(a), Box::new(b)));
binary_op!(Div, div, |a, b| Expr::Div(Box::new(a), Box::new(b)));

impl std::ops::Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::Neg(Box::new(self))
    }
}

/// A [`Lagrangian`] given by an [`Expr`] and parameter values.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprLagrangian {
    expr: Expr,
    ndof: usize,
    params: Vec<f64>,
}

impl ExprLagrangian {
    /// `L = expr` with `ndof` coordinates and parameter values `params`.
    ///
    /// # Errors
    /// `ndof = 0`; non-finite parameter values; any failure of [`Expr::validate`] (a variable
    /// or parameter index out of range, a non-finite constant, too deep a tree).
    pub fn new(expr: Expr, ndof: usize, params: Vec<f64>) -> Result<Self> {
        if ndof == 0 {
            return Err(Error::invalid("ndof", 0.0, "must be at least 1"));
        }
        if let Some(bad) = params.iter().find(|p| !p.is_finite()) {
            return Err(Error::invalid("params", *bad, "must be finite"));
        }
        expr.validate(ndof, params.len())?;
        Ok(Self { expr, ndof, params })
    }

    /// The expression.
    pub fn expr(&self) -> &Expr {
        &self.expr
    }

    /// The parameter values.
    pub fn params(&self) -> &[f64] {
        &self.params
    }
}

impl Lagrangian for ExprLagrangian {
    fn ndof(&self) -> usize {
        self.ndof
    }

    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], t: D) -> D {
        self.expr.eval(q, qdot, t, &self.params)
    }

    /// The Euler–Lagrange equations solved for `qdot'` symbolically
    /// ([`TaylorProgram::lagrangian`](super::TaylorProgram::lagrangian)).
    fn taylor_field(
        &self,
    ) -> Option<Result<Box<dyn crate::classical::integrators::taylor::TaylorField>>> {
        Some(super::TaylorProgram::lagrangian(self).map(|p| Box::new(p) as Box<_>))
    }
}
