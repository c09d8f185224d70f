//! A [`TaylorProgram`](super::TaylorProgram)'s recurrences compiled to machine code by
//! Cranelift (feature `jit`, native targets only).
//!
//! One function per program and order `p`, `fn(w)`, on the program's work array `w` (every
//! node's coefficients, `p + 1` per node, the state's and time's order 0 already set): the
//! whole recurrence for that order unrolled, as heyoka compiles it (Biscani & Izzo 2021):
//! for `k = 0..=p`, order `k` of every operation node, then the state's order `k + 1` from
//! the field's. No loop, no branch, no dispatch: every coefficient is loaded from and stored
//! to `w` at an offset known when compiling. Each operation is the interpreter's
//! (`TaylorProgram::order_k`), in the same order: the sums start with their first term and
//! run in the same direction, the constant weights (`k`, `j`, `α (k - j) - j`) are computed
//! by the same `f64` operations while compiling, `+ - * /`, negation and `sqrt` are the IEEE
//! operations, and order 0 of `exp`, `powf`, `sin`/`cos`, `sinh`/`cosh`, `ln`, `atan`,
//! `asin`, `acos` calls an `extern "C"` shim running the interpreter's own Rust function.
//! Cranelift does not contract a multiplication and an addition into a fused multiply-add
//! (it is never asked to), so the coefficients are the interpreter's bit for bit
//! (`tests/classical/integrators/taylor.rs` checks every recurrence and whole runs).
//!
//! The code of an order is compiled once, by the expansion that comes after
//! [`TaylorProgram::COMPILE_AFTER`] interpreted ones (or by
//! [`TaylorProgram::compile_native`](super::TaylorProgram::compile_native)); if compilation
//! fails the recurrences stay interpreted. The code lives in a
//! [`JITModule`](cranelift_jit::JITModule) shared by the
//! program's clones behind an `Arc` and freed with the last of them.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, OnceLock};

use cranelift_codegen::ir::{types, InstBuilder, MemFlags, Value};
use cranelift_codegen::settings::Configurable;
use cranelift_frontend::FunctionBuilder;

use super::{func_value, powf_weight, Node, TaylorProgram, Val};
use crate::classical::integrators::taylor::MAX_ORDER;
use crate::classical::symbolic::tape::jit::{
    compile_function, flag_builder, OwnedModule, Param, Shims,
};
use crate::classical::symbolic::Func;

/// The compiled function: the work array.
type Entry = unsafe extern "C" fn(*mut f64);

/// A program's native code per order, or its absence, shared by the program's clones.
#[derive(Clone, Default)]
pub(super) struct Jit(Arc<State>);

#[derive(Default)]
struct State {
    expansions: AtomicU32,
    /// Set for a program that is never compiled.
    never: bool,
    code: [OnceLock<Option<Native>>; MAX_ORDER + 1],
}

impl std::fmt::Debug for Jit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let native: Vec<usize> = (0..=MAX_ORDER).filter(|&p| self.is_native(p)).collect();
        write!(f, "native for orders {native:?}")
    }
}

impl Jit {
    /// A program's code that is never compiled.
    pub(super) fn never() -> Self {
        Self(Arc::new(State {
            never: true,
            ..State::default()
        }))
    }

    /// The native code of `order`, compiling it at the expansion after the
    /// [`TaylorProgram::COMPILE_AFTER`]-th.
    #[inline]
    pub(super) fn code(&self, nodes: &[Node], outputs: &[Val], order: usize) -> Option<&Native> {
        let slot = self.0.code.get(order)?;
        if let Some(code) = slot.get() {
            return code.as_ref();
        }
        if self.0.never
            || self.0.expansions.fetch_add(1, Ordering::Relaxed) < TaylorProgram::COMPILE_AFTER
        {
            return None;
        }
        self.compile(nodes, outputs, order)
    }

    /// Compiles `order` now (once; later calls return the first outcome).
    pub(super) fn compile(&self, nodes: &[Node], outputs: &[Val], order: usize) -> Option<&Native> {
        if self.0.never {
            return None;
        }
        self.0
            .code
            .get(order)?
            .get_or_init(|| Native::compile(nodes, outputs, order))
            .as_ref()
    }

    /// Whether native code runs the expansions to `order`.
    pub(super) fn is_native(&self, order: usize) -> bool {
        matches!(
            self.0.code.get(order).and_then(OnceLock::get),
            Some(Some(_))
        )
    }
}

/// Compiled recurrences: the entry point and the module that owns the code.
pub(super) struct Native {
    entry: Entry,
    /// Length of the work array the code reads and writes.
    len: usize,
    /// Owns the code `entry` points into.
    _module: OwnedModule,
}

impl Native {
    /// Runs the recurrences on the work array `w` (left untouched if its length is not the
    /// program's nodes times `order + 1`: callers size it first).
    #[inline]
    // SAFETY: the code reads and writes `w[..len]` only, which the check makes in bounds, and
    // calls only the shims below, which are plain functions of their arguments.
    #[allow(unsafe_code)]
    pub(super) fn call(&self, w: &mut [f64]) {
        if w.len() == self.len {
            unsafe { (self.entry)(w.as_mut_ptr()) }
        }
    }

    fn compile(nodes: &[Node], outputs: &[Val], order: usize) -> Option<Native> {
        let mut flags = flag_builder()?;
        // The IR is generated, not written: verifying it costs compile time (a sixth of
        // Cranelift's samples in a profile of the comparison benchmark) and would find only
        // what the bit-for-bit tests against the interpreter find.
        flags.set("enable_verifier", "false").ok()?;
        let isa = cranelift_native::builder().ok()?;
        let (code, module) =
            compile_function(isa, flags, &[Param::Pointer], false, |b, params, shims| {
                let mut emit = Emitter {
                    b,
                    shims,
                    w: params[0],
                    stride: order + 1,
                };
                emit.recurrences(nodes, outputs, order);
                Vec::new()
            })?;
        Some(Native {
            entry: entry_point(code),
            len: nodes.len() * (order + 1),
            _module: module,
        })
    }
}

/// The compiled function's pointer as its type.
// SAFETY: `code` is the finalized code of a function declared with `Entry`'s signature in the
// platform's default calling convention, which is `extern "C"`'s.
#[allow(unsafe_code)]
fn entry_point(code: *const u8) -> Entry {
    unsafe { std::mem::transmute::<*const u8, Entry>(code) }
}

extern "C" fn exp(x: f64) -> f64 {
    x.exp()
}

extern "C" fn sin(x: f64) -> f64 {
    x.sin()
}

extern "C" fn cos(x: f64) -> f64 {
    x.cos()
}

extern "C" fn sinh(x: f64) -> f64 {
    x.sinh()
}

extern "C" fn cosh(x: f64) -> f64 {
    x.cosh()
}

extern "C" fn powf(x: f64, y: f64) -> f64 {
    x.powf(y)
}

/// `func_value(F, x)` for `Func::ALL[F]` (the functions of [`Node::Integral`]).
extern "C" fn integral<const F: usize>(x: f64) -> f64 {
    func_value(Func::ALL[F], x)
}

/// Emits a program's recurrences into one block.
struct Emitter<'a, 'b> {
    b: &'a mut FunctionBuilder<'b>,
    shims: &'a mut Shims,
    /// The work array.
    w: Value,
    stride: usize,
}

impl Emitter<'_, '_> {
    /// Coefficient `j` of node `n`.
    fn ld(&mut self, n: usize, j: usize) -> Value {
        let offset = (8 * (n * self.stride + j)) as i32;
        // In bounds and aligned: `Native::call` checks the work array's length.
        self.b
            .ins()
            .load(types::F64, MemFlags::trusted(), self.w, offset)
    }

    fn st(&mut self, n: usize, j: usize, v: Value) {
        let offset = (8 * (n * self.stride + j)) as i32;
        self.b.ins().store(MemFlags::trusted(), v, self.w, offset);
    }

    fn c(&mut self, c: f64) -> Value {
        self.b.ins().f64const(c)
    }

    fn add(&mut self, x: Value, y: Value) -> Value {
        self.b.ins().fadd(x, y)
    }

    fn sub(&mut self, x: Value, y: Value) -> Value {
        self.b.ins().fsub(x, y)
    }

    fn mul(&mut self, x: Value, y: Value) -> Value {
        self.b.ins().fmul(x, y)
    }

    fn div(&mut self, x: Value, y: Value) -> Value {
        self.b.ins().fdiv(x, y)
    }

    /// `x · c` with the constant on the side the interpreter has it: `c * x`.
    fn cmul(&mut self, c: f64, x: Value) -> Value {
        let c = self.c(c);
        self.b.ins().fmul(c, x)
    }

    /// A call of the shim at `address`.
    fn call(&mut self, address: usize, args: &[Value]) -> Value {
        self.shims.call(self.b, address, args)
    }

    /// `Σ_{j < n} a_j b_{n-1-j}` from `j = 0` (the interpreter's `cauchy` of the slices
    /// starting at coefficient `a0` of node `a` and `b0` of node `b`); `None` for `n = 0`.
    fn cauchy(
        &mut self,
        (a, a0): (usize, usize),
        (b, b0): (usize, usize),
        n: usize,
    ) -> Option<Value> {
        let mut s = None;
        for j in 0..n {
            let (x, y) = (self.ld(a, a0 + j), self.ld(b, b0 + n - 1 - j));
            let t = self.mul(x, y);
            s = Some(match s {
                Some(s) => self.add(s, t),
                None => t,
            });
        }
        s
    }

    /// Orders `0..=order` of every node and of the state, as `TaylorProgram::interpret`.
    fn recurrences(&mut self, nodes: &[Node], outputs: &[Val], order: usize) {
        for k in 0..=order {
            for (i, &node) in nodes.iter().enumerate() {
                self.node(i, node, k);
            }
            if k < order {
                let next = self.c((k + 1) as f64);
                for (i, out) in outputs.iter().enumerate() {
                    let fk = match *out {
                        Val::Node(n) => self.ld(n as usize, k),
                        Val::Const(c) if k == 0 => self.c(c),
                        Val::Const(_) => self.c(0.0),
                    };
                    let v = self.div(fk, next);
                    self.st(i, k + 1, v);
                }
            }
        }
    }

    /// Order `k` of node `me`, as `TaylorProgram::order_k`.
    #[allow(clippy::too_many_lines)]
    fn node(&mut self, me: usize, node: Node, k: usize) {
        let kf = k as f64;
        let u = |n: u32| n as usize;
        let value = match node {
            Node::State | Node::Time | Node::Partner => return,
            Node::Add(a, b) => {
                let (x, y) = (self.ld(u(a), k), self.ld(u(b), k));
                self.add(x, y)
            }
            Node::Sub(a, b) => {
                let (x, y) = (self.ld(u(a), k), self.ld(u(b), k));
                self.sub(x, y)
            }
            Node::AddC(a, c) => {
                let x = self.ld(u(a), k);
                if k == 0 {
                    let c = self.c(c);
                    self.add(x, c)
                } else {
                    x
                }
            }
            Node::CSub(c, a) => {
                let x = self.ld(u(a), k);
                if k == 0 {
                    let c = self.c(c);
                    self.sub(c, x)
                } else {
                    self.b.ins().fneg(x)
                }
            }
            Node::MulC(a, c) => {
                let x = self.ld(u(a), k);
                self.cmul(c, x)
            }
            Node::Neg(a) => {
                let x = self.ld(u(a), k);
                self.b.ins().fneg(x)
            }
            Node::Abs(a) => {
                let (x0, x) = (self.ld(u(a), 0), self.ld(u(a), k));
                let zero = self.c(0.0);
                let negative = self.b.ins().fcmp(
                    cranelift_codegen::ir::condcodes::FloatCC::LessThan,
                    x0,
                    zero,
                );
                let minus = self.b.ins().fneg(x);
                self.b.ins().select(negative, minus, x)
            }
            Node::Mul(a, b) => self
                .cauchy((u(a), 0), (u(b), 0), k + 1)
                .unwrap_or_else(|| self.c(0.0)),
            Node::Square(a) => {
                let half = k.div_ceil(2);
                let twice = self.cauchy((u(a), 0), (u(a), k + 1 - half), half).map(|s| {
                    let two = self.c(2.0);
                    self.mul(s, two)
                });
                if k.is_multiple_of(2) {
                    let m = self.ld(u(a), k / 2);
                    let m = self.mul(m, m);
                    match twice {
                        Some(t) => self.add(t, m),
                        None => m,
                    }
                } else {
                    twice.unwrap_or_else(|| self.c(0.0))
                }
            }
            Node::Div(a, b) => {
                let (x, b0) = (self.ld(u(a), k), self.ld(u(b), 0));
                match self.cauchy((u(b), 1), (me, 0), k) {
                    Some(s) => {
                        let num = self.sub(x, s);
                        self.div(num, b0)
                    }
                    None => self.div(x, b0),
                }
            }
            Node::CDiv(c, a) => {
                let a0 = self.ld(u(a), 0);
                match self.cauchy((u(a), 1), (me, 0), k) {
                    Some(s) => {
                        let minus = self.b.ins().fneg(s);
                        self.div(minus, a0)
                    }
                    None => {
                        let c = self.c(c);
                        self.div(c, a0)
                    }
                }
            }
            Node::Sqrt(a) => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.b.ins().sqrt(x)
                } else {
                    let mut s = self.ld(u(a), k);
                    for j in 1..k {
                        let (x, y) = (self.ld(me, j), self.ld(me, k - j));
                        let t = self.mul(x, y);
                        s = self.sub(s, t);
                    }
                    let me0 = self.ld(me, 0);
                    let d = self.cmul(2.0, me0);
                    self.div(s, d)
                }
            }
            Node::Powf(a, alpha) => {
                let a0 = self.ld(u(a), 0);
                if k == 0 {
                    let alpha = self.c(alpha);
                    self.call(powf as *const () as usize, &[a0, alpha])
                } else {
                    let mut s = None;
                    for j in 0..k {
                        let x = self.ld(u(a), k - j);
                        let wx = self.cmul(powf_weight(alpha, k, j), x);
                        let y = self.ld(me, j);
                        let t = self.mul(wx, y);
                        s = Some(match s {
                            Some(s) => self.add(s, t),
                            None => t,
                        });
                    }
                    let d = self.cmul(kf, a0);
                    let s = s.unwrap_or(d);
                    self.div(s, d)
                }
            }
            Node::Exp(a) => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.call(exp as *const () as usize, &[x])
                } else {
                    let mut s = None;
                    for j in 1..=k {
                        let x = self.ld(u(a), j);
                        let jx = self.cmul(j as f64, x);
                        let y = self.ld(me, k - j);
                        let t = self.mul(jx, y);
                        s = Some(match s {
                            Some(s) => self.add(s, t),
                            None => t,
                        });
                    }
                    let kf = self.c(kf);
                    let s = s.unwrap_or(kf);
                    self.div(s, kf)
                }
            }
            Node::Integral { a, d, sign, func } => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.call(INTEGRALS[func as usize] as usize, &[x])
                } else {
                    let x = self.ld(u(a), k);
                    let mut s = self.cmul(sign * kf, x);
                    for j in 1..k {
                        let m = self.ld(me, j);
                        let jm = self.cmul(j as f64, m);
                        let y = self.ld(u(d), k - j);
                        let t = self.mul(jm, y);
                        s = self.sub(s, t);
                    }
                    let d0 = self.ld(u(d), 0);
                    let den = self.cmul(kf, d0);
                    self.div(s, den)
                }
            }
            Node::SinCos(a, hyperbolic) => {
                let partner = me + 1;
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    let (fs, fc): (extern "C" fn(f64) -> f64, extern "C" fn(f64) -> f64) =
                        if hyperbolic { (sinh, cosh) } else { (sin, cos) };
                    let s = self.call(fs as usize, &[x]);
                    let c = self.call(fc as usize, &[x]);
                    self.st(partner, 0, c);
                    s
                } else {
                    let ja = self.ld(u(a), 1);
                    let (p, m) = (self.ld(partner, k - 1), self.ld(me, k - 1));
                    let mut s = self.mul(ja, p);
                    let mut c = self.mul(ja, m);
                    for j in 2..=k {
                        let x = self.ld(u(a), j);
                        let ja = self.cmul(j as f64, x);
                        let (p, m) = (self.ld(partner, k - j), self.ld(me, k - j));
                        let ts = self.mul(ja, p);
                        s = self.add(s, ts);
                        let tc = self.mul(ja, m);
                        c = self.add(c, tc);
                    }
                    let kf = self.c(kf);
                    let c = if hyperbolic { c } else { self.b.ins().fneg(c) };
                    let pc = self.div(c, kf);
                    self.st(partner, k, pc);
                    self.div(s, kf)
                }
            }
        };
        self.st(me, k, value);
    }
}

/// The shims of [`Node::Integral`]'s functions, indexed by [`Func`] (`ln`, `atan`, `asin`,
/// `acos`; the others are never called).
const INTEGRALS: [extern "C" fn(f64) -> f64; 13] = [
    integral::<0>,
    integral::<1>,
    integral::<2>,
    integral::<3>,
    integral::<4>,
    integral::<5>,
    integral::<6>,
    integral::<7>,
    integral::<8>,
    integral::<9>,
    integral::<10>,
    integral::<11>,
    integral::<12>,
];
