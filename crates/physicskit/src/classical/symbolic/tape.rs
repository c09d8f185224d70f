//! [`Tape`]: expressions compiled once into a straight-line program, for the
//! expression-defined systems ([`ExprHamiltonian`](super::ExprHamiltonian),
//! [`ExprOde`](super::ExprOde)) that are evaluated every step.
//!
//! Compilation walks the trees bottom-up and gives every distinct operation one slot
//! (hash-consing, so a subexpression shared between outputs, as `cos(q0 - q1)` is between the
//! components of a double pendulum's field, is computed once); operations on constants only
//! are folded, parameters become constants (a parameter sweep recompiles, which costs
//! microseconds), and constants are operands of the operations, never copied into registers.
//! Evaluation fills the input slots (`first`, `second`, `t`) and runs the operations in order
//! over one register array, on the stack up to [`STACK_SLOTS`] slots.
//! Each operation is the same `f64` (or dual-number) operation, in the same order, as the
//! recursive [`Expr::eval`], so a tape and the tree agree bit for bit.
//!
//! Jacobians come from forward-mode automatic differentiation over the same tape: one pass on
//! num-dual's `Dual64` per input column ([`Tape::jacobian`]).
//!
//! With the feature `jit` on a native target, a tape evaluated more than [`COMPILE_AFTER`] times is
//! compiled to machine code by Cranelift (`tape/jit.rs`), which does the same `f64`
//! operations in the same order, so the results keep their bits; where Cranelift cannot
//! compile, the tape stays interpreted. [`Tape::backend`] tells which runs.

use num_dual::{Dual64, DualNum};

use super::expr::{Expr, Func, MAX_EXPR_DEPTH};
use super::hash_cons::{HashCons, Keyed};
use crate::classical::core::{Error, Result};
use crate::classical::lagrangian::Scalar;

#[cfg(all(feature = "jit", not(target_arch = "wasm32")))]
pub(super) mod jit;
#[cfg(not(all(feature = "jit", not(target_arch = "wasm32"))))]
#[path = "tape/interpreted.rs"]
mod jit;

/// Largest register array kept on the stack; larger tapes use one heap buffer per evaluation
/// (their hundreds of operations then dwarf the allocation).
pub const STACK_SLOTS: usize = 256;

/// Interpreted `f64` evaluations after which a tape is compiled to machine code (feature
/// `jit`). Compiling costs about as much as this many interpreted evaluations of a small
/// tape save once compiled (benchmarks/README.md, "Expression engines", has the measured
/// compile times and savings). Compiling once the interpreter has run about that many (the
/// rent-or-buy rule) costs any run at most about twice what the better choice in hindsight
/// would have.
pub const COMPILE_AFTER: u32 = 10_000;

/// One operation; operands are slot indices (`a`, `b`) or constants (`c`).
///
/// Constants are operands, not slots, so an evaluation never copies them; the variants with
/// a constant on either side keep the operand order of the tree (`c - a` and `a - c` are
/// different variants), so every result has the bits of [`Expr::eval`]'s.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    AddC(u32, f64),
    MulC(u32, f64),
    SubC(u32, f64),
    CSub(f64, u32),
    DivC(u32, f64),
    CDiv(f64, u32),
    Neg(u32),
    /// `a^2`, `a * a`: the same bits as `powi(a, 2)`, without its call.
    Square(u32),
    Powi(u32, i32),
    Powf(u32, f64),
    Pow(u32, u32),
    PowC(u32, f64),
    CPow(f64, u32),
    Func(Func, u32),
}

/// An operand while compiling: a slot or a constant.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Val {
    Slot(u32),
    Const(f64),
}

/// Hash key of an operation (floats by their bits).
type Key = (u8, u64, u64);

impl Keyed for Op {
    type Key = Key;

    fn key(self) -> Key {
        let s = u64::from;
        match self {
            Op::Add(a, b) => (0, s(a), s(b)),
            Op::Sub(a, b) => (1, s(a), s(b)),
            Op::Mul(a, b) => (2, s(a), s(b)),
            Op::Div(a, b) => (3, s(a), s(b)),
            Op::AddC(a, c) => (4, s(a), c.to_bits()),
            Op::MulC(a, c) => (5, s(a), c.to_bits()),
            Op::SubC(a, c) => (6, s(a), c.to_bits()),
            Op::CSub(c, a) => (7, s(a), c.to_bits()),
            Op::DivC(a, c) => (8, s(a), c.to_bits()),
            Op::CDiv(c, a) => (9, s(a), c.to_bits()),
            Op::Neg(a) => (10, s(a), 0),
            Op::Square(a) => (11, s(a), 0),
            Op::Powi(a, n) => (12, s(a), u64::from(n as u32)),
            Op::Powf(a, x) => (13, s(a), x.to_bits()),
            Op::Pow(a, b) => (14, s(a), s(b)),
            Op::PowC(a, c) => (15, s(a), c.to_bits()),
            Op::CPow(c, a) => (16, s(a), c.to_bits()),
            Op::Func(f, a) => (17 + f as u8, s(a), 0),
        }
    }
}

impl Op {
    /// The operation on registers `r`, operands read at `index & mask` (`r.len() - 1`, a
    /// power of two minus one: on a fixed-size array the compiler then drops the bounds
    /// checks).
    #[inline(always)]
    fn apply<D: Scalar>(self, r: &[D], mask: usize) -> D {
        let at = |i: u32| r[i as usize & mask];
        let k = |c: f64| D::from(c);
        match self {
            Op::Add(a, b) => at(a) + at(b),
            Op::Sub(a, b) => at(a) - at(b),
            Op::Mul(a, b) => at(a) * at(b),
            Op::Div(a, b) => at(a) / at(b),
            Op::AddC(a, c) => at(a) + k(c),
            Op::MulC(a, c) => at(a) * k(c),
            Op::SubC(a, c) => at(a) - k(c),
            Op::CSub(c, a) => k(c) - at(a),
            Op::DivC(a, c) => at(a) / k(c),
            Op::CDiv(c, a) => k(c) / at(a),
            Op::Neg(a) => -at(a),
            Op::Square(a) => at(a) * at(a),
            Op::Powi(a, n) => at(a).powi(n),
            Op::Powf(a, x) => at(a).powf(x),
            Op::Pow(a, b) => at(a).powd(at(b)),
            Op::PowC(a, c) => at(a).powd(k(c)),
            Op::CPow(c, a) => k(c).powd(at(a)),
            Op::Func(f, a) => f.apply(at(a)),
        }
    }
}

/// Applies the binary operation `make` (`0` add, `1` subtract, `2` multiply, `3` divide,
/// `4` power) to constants.
fn fold2(kind: u8, x: f64, y: f64) -> f64 {
    match kind {
        0 => x + y,
        1 => x - y,
        2 => x * y,
        3 => x / y,
        _ => DualNum::powd(&x, y),
    }
}

/// Expressions compiled into a straight-line program (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Tape {
    n_first: usize,
    n_second: usize,
    ops: Vec<Op>,
    outputs: Vec<Out>,
    /// Native code for the `f64` evaluations, once compiled; shared by clones.
    jit: jit::Jit,
}

/// Which code runs a tape's `f64` evaluations ([`Tape::eval`], [`Tape::eval_with_last`],
/// [`Tape::eval_scalar`]); both give the same bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// The operations interpreted one by one.
    Interpreter,
    /// Machine code compiled from the operations (feature `jit`).
    Native,
}

/// An output slot or constant, and whether it is negated.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Out(Val, bool);

struct Builder<'a> {
    n_first: usize,
    n_second: usize,
    params: &'a [f64],
    ops: HashCons<Op>,
}

impl Builder<'_> {
    fn op(&mut self, op: Op) -> Val {
        let (i, _) = self.ops.intern(op);
        Val::Slot((self.n_first + self.n_second + 1) as u32 + i)
    }

    fn binary(&mut self, kind: u8, a: Val, b: Val) -> Val {
        use Val::{Const as C, Slot as S};
        match (kind, a, b) {
            (_, C(x), C(y)) => C(fold2(kind, x, y)),
            (0, S(a), S(b)) => self.op(Op::Add(a, b)),
            (0, S(a), C(c)) | (0, C(c), S(a)) => self.op(Op::AddC(a, c)),
            (1, S(a), S(b)) => self.op(Op::Sub(a, b)),
            (1, S(a), C(c)) => self.op(Op::SubC(a, c)),
            (1, C(c), S(a)) => self.op(Op::CSub(c, a)),
            (2, S(a), S(b)) => self.op(Op::Mul(a, b)),
            (2, S(a), C(c)) | (2, C(c), S(a)) => self.op(Op::MulC(a, c)),
            (3, S(a), S(b)) => self.op(Op::Div(a, b)),
            (3, S(a), C(c)) => self.op(Op::DivC(a, c)),
            (3, C(c), S(a)) => self.op(Op::CDiv(c, a)),
            (_, S(a), S(b)) => self.op(Op::Pow(a, b)),
            (_, S(a), C(c)) => self.op(Op::PowC(a, c)),
            (_, C(c), S(a)) => self.op(Op::CPow(c, a)),
        }
    }

    fn unary(&mut self, a: Val, op: impl Fn(u32) -> Op) -> Val {
        match a {
            Val::Const(x) => Val::Const(op(0).apply(&[x], 0)),
            Val::Slot(a) => self.op(op(a)),
        }
    }

    // Exact comparison: recognizing the literal factor -1.
    #[allow(clippy::float_cmp)]
    fn chain(&mut self, items: &[Expr], empty: f64, kind: u8) -> Result<Val> {
        let Some((first, rest)) = items.split_first() else {
            return Ok(Val::Const(empty));
        };
        let mut acc = self.compile(first)?;
        for e in rest {
            // `a + (-1) b c ...` is `a - b c ...` exactly (negation is exact, and so is moving
            // it through a product), one operation fewer: the form of every negative term
            // SymPy writes.
            if let (0, Expr::Mul(factors)) = (kind, e) {
                if let [Expr::Const(c), tail @ ..] = factors.as_slice() {
                    if *c == -1.0 && !tail.is_empty() {
                        let b = self.chain(tail, 1.0, 2)?;
                        acc = self.binary(1, acc, b);
                        continue;
                    }
                }
            }
            let b = self.compile(e)?;
            acc = self.binary(kind, acc, b);
        }
        Ok(acc)
    }

    /// An output: a negated expression is computed without its negation, which the output
    /// applies (forces are `-dV/dq`).
    fn output(&mut self, e: &Expr) -> Result<Out> {
        Ok(match e {
            Expr::Neg(inner) => match self.compile(inner)? {
                Val::Const(c) => Out(Val::Const(-c), false),
                v => Out(v, true),
            },
            e => Out(self.compile(e)?, false),
        })
    }

    fn compile(&mut self, e: &Expr) -> Result<Val> {
        let bad = |kind: &str, i: usize, limit: usize| {
            Err(Error::invalid(
                "expression",
                i as f64,
                format!("refers to {kind}{i}, but there are only {limit}"),
            ))
        };
        let (nf, ns) = (self.n_first, self.n_second);
        Ok(match e {
            Expr::Const(c) => Val::Const(*c),
            Expr::Q(i) if *i < nf => Val::Slot(*i as u32),
            Expr::Q(i) => return bad("q", *i, nf),
            Expr::Qdot(i) if *i < ns => Val::Slot((nf + i) as u32),
            Expr::Qdot(i) => return bad("qdot/p", *i, ns),
            Expr::T => Val::Slot((nf + ns) as u32),
            Expr::Param(i) => match self.params.get(*i) {
                Some(&p) => Val::Const(p),
                None => return bad("param", *i, self.params.len()),
            },
            Expr::Add(v) => self.chain(v, 0.0, 0)?,
            Expr::Mul(v) => self.chain(v, 1.0, 2)?,
            Expr::Sub(a, b) | Expr::Div(a, b) | Expr::Pow(a, b) => {
                let kind = match e {
                    Expr::Sub(..) => 1,
                    Expr::Div(..) => 3,
                    _ => 4,
                };
                let (a, b) = (self.compile(a)?, self.compile(b)?);
                self.binary(kind, a, b)
            }
            Expr::Neg(a) => {
                let a = self.compile(a)?;
                self.unary(a, Op::Neg)
            }
            Expr::Powi(a, 2) => {
                let a = self.compile(a)?;
                self.unary(a, Op::Square)
            }
            Expr::Powi(a, n) => {
                let a = self.compile(a)?;
                self.unary(a, |a| Op::Powi(a, *n))
            }
            Expr::Powf(a, x) => {
                let a = self.compile(a)?;
                self.unary(a, |a| Op::Powf(a, *x))
            }
            Expr::Func(f, a) => {
                let a = self.compile(a)?;
                self.unary(a, |a| Op::Func(*f, a))
            }
        })
    }
}

impl Tape {
    /// Compiles `outputs`, expressions in `q_0..q_{n_first}` (`first`), `qdot_0..`/`p_0..`
    /// (`second`, `n_second` of them), `t` and parameters with values `params`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `expression` for a variable or parameter index out
    /// of range or a tree deeper than 4 [`MAX_EXPR_DEPTH`]; naming `params` for a non-finite
    /// parameter; naming `expression` if a constant, or an operation on constants only, is
    /// not finite.
    pub fn new(outputs: &[Expr], n_first: usize, n_second: usize, params: &[f64]) -> Result<Self> {
        if let Some(bad) = params.iter().find(|p| !p.is_finite()) {
            return Err(Error::invalid("params", *bad, "must be finite"));
        }
        for e in outputs {
            // Compiling recurses once per level. Derived expressions (Hamilton's equations)
            // may nest a few levels deeper than the validated expression they come from, so
            // the bound is a multiple of the one users' expressions get; constants are checked
            // once folded, below, and indices (per vector) while compiling.
            let depth = e.depth();
            if depth > 4 * MAX_EXPR_DEPTH {
                return Err(Error::invalid(
                    "expression",
                    depth as f64,
                    format!(
                        "nested {depth} levels deep; at most {} are supported",
                        4 * MAX_EXPR_DEPTH
                    ),
                ));
            }
        }
        let mut b = Builder {
            n_first,
            n_second,
            params,
            ops: HashCons::new(Vec::new()),
        };
        let outputs = outputs
            .iter()
            .map(|e| b.output(e))
            .collect::<Result<Vec<_>>>()?;
        let constants = b.ops.items.iter().filter_map(|op| match *op {
            Op::AddC(_, c)
            | Op::MulC(_, c)
            | Op::SubC(_, c)
            | Op::CSub(c, _)
            | Op::DivC(_, c)
            | Op::CDiv(c, _)
            | Op::PowC(_, c)
            | Op::CPow(c, _) => Some(c),
            _ => None,
        });
        let folded = outputs.iter().filter_map(|v| match v.0 {
            Val::Const(c) => Some(c),
            Val::Slot(_) => None,
        });
        if let Some(c) = constants.chain(folded).find(|c| !c.is_finite()) {
            return Err(Error::invalid(
                "expression",
                c,
                "evaluates to a non-finite constant (a division by zero, or the log of a \
                 non-positive number, among constants and parameters)",
            ));
        }
        Ok(Self {
            n_first,
            n_second,
            ops: b.ops.items,
            outputs,
            jit: jit::Jit::default(),
        })
    }

    /// Number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of operations run per evaluation (after sharing and folding).
    pub fn n_operations(&self) -> usize {
        self.ops.len()
    }

    /// Which code runs the `f64` evaluations now: native code once the tape has been
    /// compiled (by [`compile_native`](Self::compile_native), or after [`COMPILE_AFTER`]
    /// evaluations), else the interpreter.
    pub fn backend(&self) -> Backend {
        if self.jit.is_native() {
            Backend::Native
        } else {
            Backend::Interpreter
        }
    }

    /// Compiles the tape to machine code now rather than after [`COMPILE_AFTER`] evaluations, and
    /// returns the backend that then runs it: [`Backend::Interpreter`] without the feature
    /// `jit`, in WebAssembly, or if Cranelift cannot compile for this host. Compilation
    /// happens once; clones share the code.
    pub fn compile_native(&self) -> Backend {
        self.jit.compile(self);
        self.backend()
    }

    /// Compiles the tape as for a host Cranelift cannot generate code for, to test the
    /// fallback: the tape stays interpreted for good (unless it was compiled before).
    #[doc(hidden)]
    pub fn compile_native_for_unsupported_host(&self) -> Backend {
        self.jit.compile_for_foreign_target(self);
        self.backend()
    }

    fn n_inputs(&self) -> usize {
        self.n_first + self.n_second + 1
    }

    fn n_slots(&self) -> usize {
        self.n_inputs() + self.ops.len()
    }

    /// Runs the program on a register array whose input slots `fill` sets, and hands each
    /// output to `output(i, value)`. Registers live in a stack array of the smallest of 16,
    /// 32, 64 and [`STACK_SLOTS`] slots that holds them (each is zeroed per evaluation), else
    /// in one heap buffer.
    #[inline]
    fn run<D: Scalar>(&self, fill: impl Fn(&mut [D]), output: impl FnMut(usize, D)) {
        match self.n_slots() {
            0..=16 => self.run_in(&mut [D::zero(); 16], fill, output),
            17..=32 => self.run_in(&mut [D::zero(); 32], fill, output),
            33..=64 => self.run_in(&mut [D::zero(); 64], fill, output),
            65..=STACK_SLOTS => self.run_in(&mut [D::zero(); STACK_SLOTS], fill, output),
            n => self.run_in(&mut vec![D::zero(); n.next_power_of_two()], fill, output),
        }
    }

    /// [`run`](Self::run) on `r`, whose length is a power of two of at least `n_slots`.
    #[inline(always)]
    fn run_in<D: Scalar, R: AsMut<[D]> + AsRef<[D]> + ?Sized>(
        &self,
        r: &mut R,
        fill: impl Fn(&mut [D]),
        mut output: impl FnMut(usize, D),
    ) {
        let n_in = self.n_inputs();
        let mask = r.as_ref().len() - 1;
        fill(&mut r.as_mut()[..n_in]);
        for (dst, op) in (n_in..).zip(&self.ops) {
            let v = op.apply(r.as_ref(), mask);
            r.as_mut()[dst & mask] = v;
        }
        for (i, &Out(v, negate)) in self.outputs.iter().enumerate() {
            let v = match v {
                Val::Slot(s) => r.as_ref()[s as usize & mask],
                Val::Const(c) => D::from(c),
            };
            output(i, if negate { -v } else { v });
        }
    }

    #[inline]
    fn input_value(&self, first: &[f64], second: &[f64], t: f64, k: usize) -> f64 {
        if k < self.n_first {
            first[k]
        } else if k < self.n_first + self.n_second {
            second[k - self.n_first]
        } else {
            t
        }
    }

    /// Whether `first`, `second` and `out` are long enough.
    #[inline]
    fn fits(&self, first: usize, second: usize, out: usize) -> bool {
        first >= self.n_first && second >= self.n_second && out >= self.outputs.len()
    }

    /// Evaluates every output at `(first, second, t)` into `out` (`first` and `second` of the
    /// compiled lengths, `out` of [`n_outputs`](Self::n_outputs)). Shorter slices give `NaN`
    /// outputs, never a panic (callers check lengths and report them).
    #[inline]
    pub fn eval(&self, first: &[f64], second: &[f64], t: f64, out: &mut [f64]) {
        let (nf, ns) = (self.n_first, self.n_second);
        if !self.fits(first.len(), second.len(), out.len()) {
            out.iter_mut().for_each(|o| *o = f64::NAN);
            return;
        }
        if let Some(code) = self.jit.code(self) {
            if let Some((last, rest)) = out[..self.outputs.len()].split_last_mut() {
                *last = code.call(first, second, t, rest);
            }
            return;
        }
        self.run(
            |r: &mut [f64]| {
                for (slot, &x) in r.iter_mut().zip(&first[..nf]) {
                    *slot = x;
                }
                for (slot, &x) in r[nf..].iter_mut().zip(&second[..ns]) {
                    *slot = x;
                }
                r[nf + ns] = t;
            },
            |i, v| out[i] = v,
        );
    }

    /// Evaluates at `(first, second, t)`, writing all outputs but the last into `out` and
    /// returning the last (a force and its potential from one tape); `NaN` everywhere for
    /// slices that are too short.
    #[inline]
    pub fn eval_with_last(&self, first: &[f64], second: &[f64], t: f64, out: &mut [f64]) -> f64 {
        let (nf, ns) = (self.n_first, self.n_second);
        if !self.fits(first.len(), second.len(), out.len() + 1) {
            out.iter_mut().for_each(|o| *o = f64::NAN);
            return f64::NAN;
        }
        if let Some(code) = self.jit.code(self) {
            return code.call(first, second, t, out);
        }
        let last = self.outputs.len().wrapping_sub(1);
        let mut value = f64::NAN;
        self.run(
            |r: &mut [f64]| {
                for (slot, &x) in r.iter_mut().zip(&first[..nf]) {
                    *slot = x;
                }
                for (slot, &x) in r[nf..].iter_mut().zip(&second[..ns]) {
                    *slot = x;
                }
                r[nf + ns] = t;
            },
            |i, v| {
                if i == last {
                    value = v;
                } else {
                    out[i] = v;
                }
            },
        );
        value
    }

    /// The first output at `(first, second, t)`; `NaN` for slices that are too short.
    #[inline]
    pub fn eval_scalar(&self, first: &[f64], second: &[f64], t: f64) -> f64 {
        let mut out = f64::NAN;
        if !self.fits(first.len(), second.len(), self.outputs.len()) {
            return out;
        }
        if self.outputs.len() == 1 {
            if let Some(code) = self.jit.code(self) {
                return code.call(first, second, t, &mut []);
            }
        }
        self.run(
            |r: &mut [f64]| {
                for (k, slot) in r.iter_mut().enumerate() {
                    *slot = self.input_value(first, second, t, k);
                }
            },
            |i, v| {
                if i == 0 {
                    out = v;
                }
            },
        );
        out
    }

    /// Writes `d output_i / d input_j` for the inputs `columns` (`0..n_first` are `first`,
    /// then `second`; row-major, `n_outputs x columns.len()`) by one forward-mode pass on
    /// `Dual64` per column. Slices that are too short give `NaN` entries.
    pub fn jacobian(
        &self,
        first: &[f64],
        second: &[f64],
        t: f64,
        columns: std::ops::Range<usize>,
        out: &mut [f64],
    ) {
        let width = columns.len();
        let rows = self.outputs.len();
        if !self.fits(first.len(), second.len(), rows) || out.len() < rows * width {
            out.iter_mut().for_each(|o| *o = f64::NAN);
            return;
        }
        for (j, col) in columns.enumerate() {
            self.run(
                |r: &mut [Dual64]| {
                    for (k, slot) in r.iter_mut().enumerate() {
                        let x = self.input_value(first, second, t, k);
                        *slot = Dual64::new(x, if k == col { 1.0 } else { 0.0 });
                    }
                },
                |i, v| out[i * width + j] = v.eps,
            );
        }
    }
}
