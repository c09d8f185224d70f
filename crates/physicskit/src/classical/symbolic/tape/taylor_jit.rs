//! A [`TaylorProgram`](super::TaylorProgram)'s recurrences compiled to machine code by
//! Cranelift (feature `jit`, native targets only).
//!
//! One function per program and order `p`, `fn(w)`, on the program's work array `w` (every
//! node's coefficients, `p + 1` per node, the state's and time's order 0 already set), in one
//! of two forms ([`Form`], chosen by the program's size at that order):
//! - **unrolled**, as heyoka compiles it (Biscani & Izzo 2021): for `k = 0..=p`, order `k` of
//!   every operation node, then the state's order `k + 1` from the field's, every term of
//!   every sum written out. No loop, no branch, no dispatch: every coefficient is stored to
//!   `w` at an offset known when compiling, and a coefficient of the order being computed is
//!   used as the value just computed (not reloaded), older ones loaded from `w`;
//! - **compact**, for large programs, whose unrolled code grows with the nodes times `p²` and
//!   would take longer to compile than it saves: order 0 as above, then one loop over `k`
//!   whose body is every node's order `k`, each sum a loop over its terms, the coefficients
//!   loaded from and stored to `w` at addresses computed from `k` and the term's index.
//!
//! Each operation is the interpreter's (`TaylorProgram::order_k`), in the same order: the
//! sums start with their first term and run in the same direction, the constant weights
//! (`k`, `j`, `α (k - j) - j`) are computed by the same `f64` operations (while compiling, or
//! in the compact loops at run time from exact integer conversions), `+ - * /`, negation and
//! `sqrt` are the IEEE operations, and order 0 of `exp`, `powf`, `sin`/`cos`, `sinh`/`cosh`,
//! `ln`, `atan`, `asin`, `acos` calls an `extern "C"` shim running the interpreter's own Rust
//! function. Cranelift does not contract a multiplication and an addition into a fused
//! multiply-add (it is never asked to), so the coefficients are the interpreter's bit for bit
//! in both forms (`tests/classical/integrators/taylor_jit.rs` checks every recurrence, both
//! forms and whole runs).
//!
//! On x86-64 hosts with AVX the unrolled form is first written as AVX code by `taylor_asm.rs`
//! ([`Form::Avx`]: the same operations in the same order, loads folded into the arithmetic,
//! compiled in a tenth of Cranelift's time); Cranelift's is the fallback (hosts without AVX,
//! offsets beyond the encoding) and what tests force to keep it checked.
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

#[cfg(doc)]
use super::power0;
use super::{
    func_value, ordered_sum_with, split_terms, Node, Power, TaylorProgram, Val, Weight, WorkLayout,
};
use crate::classical::integrators::taylor::MAX_ORDER;
use crate::classical::symbolic::tape::jit::{
    compile_function, flag_builder, OwnedModule, Param, Shims,
};
use crate::classical::symbolic::Func;

#[cfg(all(target_arch = "x86_64", not(windows)))]
#[path = "taylor_asm.rs"]
pub(super) mod asm;

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

    /// Compiles `order` now (once; later calls return the first outcome), in the form
    /// [`Form::for_size`] picks.
    pub(super) fn compile(&self, nodes: &[Node], outputs: &[Val], order: usize) -> Option<&Native> {
        self.compile_as(nodes, outputs, order, Form::for_size(nodes, order))
    }

    /// Compiles `order` now in [`Form::Compact`] whatever the program's size (once; later
    /// calls return the first outcome, whatever its form).
    pub(super) fn compile_compact(
        &self,
        nodes: &[Node],
        outputs: &[Val],
        order: usize,
    ) -> Option<&Native> {
        self.compile_as(nodes, outputs, order, Form::Compact)
    }

    /// Compiles `order` now in [`Form::Unrolled`] whatever the program's size (once; later
    /// calls return the first outcome, whatever its form).
    pub(super) fn compile_unrolled(
        &self,
        nodes: &[Node],
        outputs: &[Val],
        order: usize,
    ) -> Option<&Native> {
        self.compile_as(nodes, outputs, order, Form::Unrolled)
    }

    fn compile_as(
        &self,
        nodes: &[Node],
        outputs: &[Val],
        order: usize,
        form: Form,
    ) -> Option<&Native> {
        if self.0.never {
            return None;
        }
        self.0
            .code
            .get(order)?
            .get_or_init(|| Native::compile(nodes, outputs, order, form))
            .as_ref()
    }

    /// Whether the native code of `order` is the code written for AVX ([`asm`]).
    pub(super) fn is_avx(&self, order: usize) -> bool {
        matches!(
            self.0.code.get(order).and_then(OnceLock::get),
            Some(Some(Native { avx: true, .. }))
        )
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
    /// Length of the work array ([`WorkLayout`]) the code reads and writes.
    len: usize,
    /// Whether the code is [`asm`]'s, written for AVX (else Cranelift's), which also writes
    /// the state's coefficients into the work array's blocks.
    avx: bool,
    /// Owns the code `entry` points into.
    _module: OwnedModule,
}

impl Native {
    /// Runs the recurrences on the work array `w` (left untouched if its length is not the
    /// program's [`WorkLayout`]'s at this order: callers size it first).
    #[inline]
    // SAFETY: the code reads and writes `w[..len]` only, which the check makes in bounds, and
    // calls only the shims below, which are plain functions of their arguments.
    #[allow(unsafe_code)]
    pub(super) fn call(&self, w: &mut [f64]) {
        if w.len() == self.len {
            unsafe { (self.entry)(w.as_mut_ptr()) }
        }
    }

    /// Whether the code writes the state's coefficients into the work array's blocks too
    /// ([`WorkLayout`]).
    pub(super) fn writes_blocks(&self) -> bool {
        self.avx
    }

    fn compile(nodes: &[Node], outputs: &[Val], order: usize, form: Form) -> Option<Native> {
        let layout = WorkLayout::new(nodes, outputs.len(), order);
        #[cfg(all(target_arch = "x86_64", not(windows)))]
        if form == Form::Avx {
            if let Some((code, module)) = asm::compile_scalar(nodes, outputs, layout, order) {
                return Some(Native {
                    entry: entry_point(code),
                    len: layout.len(),
                    avx: true,
                    _module: module,
                });
            }
        }
        let mut flags = flag_builder()?;
        // The IR is generated, not written: verifying it costs compile time (a sixth of
        // Cranelift's samples in a profile of the comparison benchmark) and would find only
        // what the bit-for-bit tests against the interpreter find.
        flags.set("enable_verifier", "false").ok()?;
        // Cranelift's optimizer merges equal constants and loads into values live across the
        // whole function, which the register allocator then spills and reloads at every use
        // (half the instructions of Kepler's code at order 18); unoptimized, each constant is
        // an operand read from the constant pool where it is used, and compiling is faster.
        flags.set("opt_level", "none").ok()?;
        let isa = cranelift_native::builder().ok()?;
        let (code, module) =
            compile_function(isa, flags, &[Param::Pointer], false, |b, params, shims| {
                let mut emit = Emitter {
                    b,
                    shims,
                    w: params[0],
                    fresh: Fresh::new(layout),
                };
                match form {
                    Form::Unrolled | Form::Avx => emit.recurrences(nodes, outputs, order),
                    Form::Compact => emit.compact(nodes, outputs, order),
                }
                Vec::new()
            })?;
        Some(Native {
            entry: entry_point(code),
            len: layout.len(),
            avx: false,
            _module: module,
        })
    }
}

/// The shape of the compiled recurrences. Both run the interpreter's operations in its order,
/// so they give the same bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Form {
    /// Every order and every term of every sum written out, each coefficient at an offset known
    /// when compiling, by Cranelift: the fastest code Cranelift makes, of a size growing with
    /// the nodes times the order squared.
    Unrolled,
    /// Order 0 written out, the orders from 1 on as a loop over `k` whose body is every node's
    /// order `k`, each sum a loop over its terms: code of a size growing with the nodes alone,
    /// compiled in a fraction of the time, run more slowly.
    Compact,
    /// The unrolled form written as AVX code ([`asm`]: x86-64 hosts with AVX), Cranelift's
    /// [`Form::Unrolled`] where it cannot be.
    Avx,
}

impl Form {
    /// The largest number of sum terms (over every node and order) compiled unrolled.
    /// Unrolled code, and Cranelift's time to compile it, grow with the nodes times the order
    /// squared; the compact form compiles in about the same time at any order and runs more
    /// slowly. Up to this size the unrolled code compiles in well under a tenth of the time
    /// heyoka's LLVM takes for the same system (the compile-time goal); larger programs take
    /// the compact form. The measured compile and run times are in `benchmarks/README.md`
    /// ("Adaptive Taylor method against heyoka").
    pub(super) const MAX_UNROLLED_TERMS: usize = 6000;

    /// The unrolled form for programs of at most [`Form::MAX_UNROLLED_TERMS`] sum terms at
    /// `order` ([`Form::Avx`]: written for AVX where it can be, else Cranelift's),
    /// [`Form::Compact`] above.
    fn for_size(nodes: &[Node], order: usize) -> Self {
        if unrolled_terms(nodes, order) <= Self::MAX_UNROLLED_TERMS {
            Self::Avx
        } else {
            Self::Compact
        }
    }
}

/// The number of terms of every sum of the recurrences to `order` ([`Node::sum_terms`]):
/// what the unrolled code's size grows with.
pub(super) fn unrolled_terms(nodes: &[Node], order: usize) -> usize {
    (0..=order)
        .map(|k| nodes.iter().map(|node| node.sum_terms(k)).sum::<usize>())
        .sum()
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

pub(super) extern "C" fn powf(x: f64, y: f64) -> f64 {
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
    fresh: Fresh<Value>,
}

impl Recurrences for Emitter<'_, '_> {
    type X = Value;

    fn set_k(&mut self, k: usize) {
        self.fresh.set_k(k);
    }

    fn lead(&self) -> usize {
        self.fresh.lead()
    }

    fn ld(&mut self, n: usize, j: usize) -> Value {
        if let Some(v) = self.fresh.get(n, j) {
            return v;
        }
        let offset = (8 * self.fresh.index(n, j)) as i32;
        // In bounds and aligned: `Native::call` checks the work array's length.
        self.b
            .ins()
            .load(types::F64, MemFlags::trusted(), self.w, offset)
    }

    fn st(&mut self, n: usize, j: usize, v: Value) {
        self.fresh.set(n, j, v);
        let offset = (8 * self.fresh.index(n, j)) as i32;
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

    fn neg(&mut self, x: Value) -> Value {
        self.b.ins().fneg(x)
    }

    fn sqrt(&mut self, x: Value) -> Value {
        self.b.ins().sqrt(x)
    }

    fn abs(&mut self, x0: Value, x: Value) -> Value {
        let zero = self.c(0.0);
        let negative = self.b.ins().fcmp(
            cranelift_codegen::ir::condcodes::FloatCC::LessThan,
            x0,
            zero,
        );
        let minus = self.b.ins().fneg(x);
        self.b.ins().select(negative, minus, x)
    }

    fn call(&mut self, address: usize, x: Value) -> Value {
        self.shims.call(self.b, address, &[x])
    }

    fn powf(&mut self, x: Value, alpha: f64) -> Value {
        let alpha = self.b.ins().f64const(alpha);
        self.shims
            .call(self.b, powf as *const () as usize, &[x, alpha])
    }
}

/// The coefficients an emitter of [`Recurrences`] has stored, kept as its values: coefficient
/// `j` of a node stored while emitting order `k <= j` was computed by this order's code, and is
/// reused as that value rather than loaded back; older coefficients are loaded.
pub(super) struct Fresh<X> {
    layout: WorkLayout,
    /// The order being emitted.
    k: usize,
    values: Vec<Option<X>>,
}

impl<X: Copy> Fresh<X> {
    /// None stored yet, for the nodes of `layout`.
    pub(super) fn new(layout: WorkLayout) -> Self {
        Fresh {
            layout,
            k: 0,
            values: vec![None; layout.blocks_start()],
        }
    }

    /// The program's end terms of a sum ([`WorkLayout::lead`]).
    pub(super) fn lead(&self) -> usize {
        self.layout.lead()
    }

    /// Sets the order being emitted.
    pub(super) fn set_k(&mut self, k: usize) {
        self.k = k;
    }

    /// The work array's index of coefficient `j` of node `n`.
    pub(super) fn index(&self, n: usize, j: usize) -> usize {
        self.layout.at(n, j)
    }

    /// The value stored as coefficient `j` of node `n`, if it is to be used instead of a load.
    pub(super) fn get(&self, n: usize, j: usize) -> Option<X> {
        if j >= self.k {
            self.values[self.index(n, j)]
        } else {
            None
        }
    }

    /// Records `x` as stored for coefficient `j` of node `n`.
    pub(super) fn set(&mut self, n: usize, j: usize, x: X) {
        let i = self.index(n, j);
        self.values[i] = Some(x);
    }
}

/// The operations the recurrences are emitted from, on values of one `f64` (this file's
/// [`Emitter`]) or of several lanes (`taylor_lanes_jit.rs`): the provided methods emit the
/// interpreter's operations in its order from them, once for both.
pub(super) trait Recurrences {
    /// A value: one `f64`, or lanes of them.
    type X: Copy;

    /// Sets the order being emitted.
    fn set_k(&mut self, k: usize);

    /// The terms at each end of a sum outside its groups of four, in this program
    /// ([`WorkLayout::lead`]).
    fn lead(&self) -> usize;

    /// Coefficient `j` of node `n`.
    fn ld(&mut self, n: usize, j: usize) -> Self::X;

    /// Stores coefficient `j` of node `n`.
    fn st(&mut self, n: usize, j: usize, x: Self::X);

    /// The constant `c`.
    fn c(&mut self, c: f64) -> Self::X;

    fn add(&mut self, x: Self::X, y: Self::X) -> Self::X;

    fn sub(&mut self, x: Self::X, y: Self::X) -> Self::X;

    fn mul(&mut self, x: Self::X, y: Self::X) -> Self::X;

    fn div(&mut self, x: Self::X, y: Self::X) -> Self::X;

    fn neg(&mut self, x: Self::X) -> Self::X;

    fn sqrt(&mut self, x: Self::X) -> Self::X;

    /// Order `k` of `|a|` from `a`'s orders 0 and `k`: `-x` where `a_0 < 0`, else `x`.
    fn abs(&mut self, x0: Self::X, x: Self::X) -> Self::X;

    /// The unary shim at `address` on `x`.
    fn call(&mut self, address: usize, x: Self::X) -> Self::X;

    /// `x^alpha` by the [`powf`] shim.
    fn powf(&mut self, x: Self::X, alpha: f64) -> Self::X;

    /// Order 0 of `x^alpha`: [`power0`]'s operations in its order, the [`powf`] shim for
    /// the exponents [`Power::of`] leaves to it.
    fn power(&mut self, x: Self::X, alpha: f64) -> Self::X {
        match Power::of(alpha) {
            Power::Half { n, reciprocal } => {
                let mut r = self.sqrt(x);
                for _ in 0..n {
                    r = self.mul(r, x);
                }
                if reciprocal {
                    let one = self.c(1.0);
                    self.div(one, r)
                } else {
                    r
                }
            }
            Power::General => self.powf(x, alpha),
        }
    }

    /// `x · c` (the interpreter's `c * x`: IEEE multiplication commutes exactly), the
    /// constant second, where x86 reads it from the constant pool as an operand.
    fn cmul(&mut self, c: f64, x: Self::X) -> Self::X {
        let c = self.c(c);
        self.mul(x, c)
    }

    /// `Σ_{j < n} a_j b_{n-1-j}` in [`ordered_sum`](super::ordered_sum)'s order (the
    /// interpreter's `cauchy` of the slices starting at coefficient `a0` of node `a` and `b0`
    /// of node `b`); `None` for `n = 0`.
    fn cauchy(
        &mut self,
        (a, a0): (usize, usize),
        (b, b0): (usize, usize),
        n: usize,
    ) -> Option<Self::X> {
        let lead = self.lead();
        let groups = |r: &mut Self, g| r.cauchy_groups((a, a0 + lead), (b, b0 + n - 1 - lead), g);
        let term = |r: &mut Self, j: usize| {
            let (x, y) = (r.ld(a, a0 + j), r.ld(b, b0 + n - 1 - j));
            r.mul(x, y)
        };
        ordered_sum_with(self, lead, n, term, |r, s, t| r.add(s, t), groups)
    }

    /// The sum of a [`cauchy`](Self::cauchy)'s `groups` groups of four terms,
    /// `Σ_{i < 4 groups} a_{a1 + i} b_{b1 - i}`, as [`ordered_sum`](super::ordered_sum) takes
    /// it, if this form sums them at once (`None`: term by term).
    fn cauchy_groups(
        &mut self,
        _a1: (usize, usize),
        _b1: (usize, usize),
        _groups: usize,
    ) -> Option<Self::X> {
        None
    }

    /// `Σ_{lo ≤ j ≤ k - lo} x_j x_{k-j}` of node `x` at order `k` as
    /// [`mirrored`](super::mirrored) sums it: each term with its mirror, `2 Σ x_j x_{k-j}` over
    /// `lo ≤ j < k/2` (a Cauchy sum), plus `x_{k/2}²` for even `k` (a square's sum for `lo = 0`,
    /// a square root's for `lo = 1`).
    fn mirrored(&mut self, x: usize, lo: usize, k: usize) -> Self::X {
        let n = k.div_ceil(2) - lo;
        let twice = self.cauchy((x, lo), (x, k + 1 - lo - n), n).map(|s| {
            let two = self.c(2.0);
            self.mul(s, two)
        });
        if k.is_multiple_of(2) {
            let m = self.ld(x, k / 2);
            let m = self.mul(m, m);
            match twice {
                Some(t) => self.add(t, m),
                None => m,
            }
        } else {
            twice.unwrap_or_else(|| self.c(0.0))
        }
    }

    /// The sum of a [`weighted_sum`](Self::weighted_sum)'s groups, `Σ (w_j a_{k-j}) b_{b0+j}`
    /// over `L ≤ j < L + 4 groups` (`L` the [`lead`](Self::lead)), as
    /// [`ordered_sum`](super::ordered_sum) takes it, if this form sums them at once (`None`:
    /// term by term).
    fn weighted_groups(
        &mut self,
        _a: usize,
        _b: (usize, usize),
        _k: usize,
        _weight: Weight,
        _groups: usize,
    ) -> Option<Self::X> {
        None
    }

    /// `Σ_{j < k} (w_j a_{k-j}) b_{b0+j}` of nodes `a` and `b` in
    /// [`ordered_sum`](super::ordered_sum)'s order (`None` for `k = 0`), `w_j` the constant
    /// [`Weight`] (the sum of a power's recurrence or an integral's; an exponential's and a
    /// sine–cosine pair's are Cauchy sums over a `Node::Derivative`).
    fn weighted_sum(
        &mut self,
        a: usize,
        (b, b0): (usize, usize),
        k: usize,
        weight: Weight,
    ) -> Option<Self::X> {
        let term = |r: &mut Self, j: usize| {
            let x = r.ld(a, k - j);
            let wx = r.cmul(weight.at(k, j), x);
            let y = r.ld(b, b0 + j);
            r.mul(wx, y)
        };
        let groups = |r: &mut Self, g| r.weighted_groups(a, (b, b0), k, weight, g);
        ordered_sum_with(self, self.lead(), k, term, |r, s, t| r.add(s, t), groups)
    }

    /// Orders `0..=order` of every node and of the state, as `TaylorProgram::interpret`.
    fn recurrences(&mut self, nodes: &[Node], outputs: &[Val], order: usize) {
        for k in 0..=order {
            self.set_k(k);
            for (i, &node) in nodes.iter().enumerate() {
                self.node(i, node, k);
            }
            if k < order {
                let next = self.c(1.0 / (k + 1) as f64);
                for (i, out) in outputs.iter().enumerate() {
                    let fk = match *out {
                        Val::Node(n) => self.ld(n as usize, k),
                        Val::Const(c) if k == 0 => self.c(c),
                        Val::Const(_) => self.c(0.0),
                    };
                    let v = self.mul(fk, next);
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
                    self.neg(x)
                }
            }
            Node::MulC(a, c) => {
                let x = self.ld(u(a), k);
                self.cmul(c, x)
            }
            Node::Neg(a) => {
                let x = self.ld(u(a), k);
                self.neg(x)
            }
            Node::Abs(a) => {
                let (x0, x) = (self.ld(u(a), 0), self.ld(u(a), k));
                self.abs(x0, x)
            }
            Node::Mul(a, b) => self
                .cauchy((u(a), 0), (u(b), 0), k + 1)
                .unwrap_or_else(|| self.c(0.0)),
            Node::Square(a) => self.mirrored(u(a), 0, k),
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
                        let minus = self.neg(s);
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
                    self.sqrt(x)
                } else {
                    let inner = self.mirrored(me, 1, k);
                    let x = self.ld(u(a), k);
                    let s = self.sub(x, inner);
                    let me0 = self.ld(me, 0);
                    let d = self.cmul(2.0, me0);
                    self.div(s, d)
                }
            }
            Node::Powf(a, alpha) => {
                let a0 = self.ld(u(a), 0);
                if k == 0 {
                    self.power(a0, alpha)
                } else {
                    let s = self.weighted_sum(u(a), (me, 0), k, Weight::Power(alpha));
                    let d = self.cmul(kf, a0);
                    let s = s.unwrap_or(d);
                    self.div(s, d)
                }
            }
            Node::Derivative(a) => {
                let x = self.ld(u(a), k);
                if k == 0 {
                    x
                } else {
                    self.cmul(kf, x)
                }
            }
            Node::Exp(d) => {
                if k == 0 {
                    let x = self.ld(u(d), 0);
                    self.call(exp as *const () as usize, x)
                } else {
                    let s = self.cauchy((me, 0), (u(d), 1), k);
                    let s = s.unwrap_or_else(|| self.c(0.0));
                    let rk = self.c(1.0 / kf);
                    self.mul(s, rk)
                }
            }
            Node::Integral { a, d, sign, func } => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.call(INTEGRALS[func as usize] as usize, x)
                } else {
                    let x = self.ld(u(a), k);
                    let s = self.cmul(sign * kf, x);
                    let s = match self.weighted_sum(me, (u(d), 1), k - 1, Weight::Falling) {
                        Some(t) => self.sub(s, t),
                        None => s,
                    };
                    let d0 = self.ld(u(d), 0);
                    let den = self.cmul(kf, d0);
                    self.div(s, den)
                }
            }
            Node::SinCos(d, hyperbolic) => {
                let partner = me + 1;
                if k == 0 {
                    let x = self.ld(u(d), 0);
                    let (fs, fc): (extern "C" fn(f64) -> f64, extern "C" fn(f64) -> f64) =
                        if hyperbolic { (sinh, cosh) } else { (sin, cos) };
                    let s = self.call(fs as usize, x);
                    let c = self.call(fc as usize, x);
                    self.st(partner, 0, c);
                    s
                } else {
                    let s = self.cauchy((partner, 0), (u(d), 1), k);
                    let s = s.unwrap_or_else(|| self.c(0.0));
                    let c = self.cauchy((me, 0), (u(d), 1), k);
                    let c = c.unwrap_or_else(|| self.c(0.0));
                    let rk = self.c(1.0 / kf);
                    let c = if hyperbolic { c } else { self.neg(c) };
                    let pc = self.mul(c, rk);
                    self.st(partner, k, pc);
                    self.mul(s, rk)
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

/// The order `k` a [`Form::Compact`] loop body runs: `k` (`i64`), `k` as `f64`, and the
/// address of coefficient `k` of node 0, `w + 8 k`.
#[derive(Clone, Copy)]
struct Order {
    k: Value,
    kf: Value,
    /// `1/k`, rounded once (the interpreter's `1.0 / kf`).
    rk: Value,
    wk: Value,
}

/// A term of a sum in a [`Form::Compact`] loop, from the term's index `j` (`i64`), `w + 8 j`
/// and `w + 8 (k - j)`.
type Term<'t, 'a, 'b> = &'t dyn Fn(&mut Emitter<'a, 'b>, Value, Value, Value) -> Value;

impl<'a, 'b> Emitter<'a, 'b> {
    /// Byte offset of coefficient `j` of node `n` from the work array (`j` may be negative:
    /// added to a run-time address).
    fn offset(&self, n: usize, j: isize) -> i32 {
        (8 * (self.fresh.index(n, 0) as isize + j)) as i32
    }

    /// The `f64` at `address + offset`.
    fn ld_at(&mut self, address: Value, offset: i32) -> Value {
        // In bounds and aligned: every address is of a coefficient in `0..=order` of a node.
        self.b
            .ins()
            .load(types::F64, MemFlags::trusted(), address, offset)
    }

    /// Coefficient `k - d` of node `n`.
    fn ldk(&mut self, o: Order, n: usize, d: usize) -> Value {
        let offset = self.offset(n, -(d as isize));
        self.ld_at(o.wk, offset)
    }

    /// Stores coefficient `k` of node `n`.
    fn stk(&mut self, o: Order, n: usize, v: Value) {
        let offset = self.offset(n, 0);
        self.b.ins().store(MemFlags::trusted(), v, o.wk, offset);
    }

    /// An integer as `f64` (exact for the orders and indices here).
    fn float(&mut self, i: Value) -> Value {
        self.b.ins().fcvt_from_sint(types::F64, i)
    }

    /// `s + Σ_{j = lo}^{hi - 1} term(j)` summed in order of `j` as a loop, none if `hi <= lo`.
    fn sum_loop(
        &mut self,
        o: Order,
        s: Value,
        (lo, hi): (Value, Value),
        term: Term<'_, 'a, 'b>,
    ) -> Value {
        let header = self.b.create_block();
        let j = self.b.append_block_param(header, types::I64);
        let acc = self.b.append_block_param(header, types::F64);
        let body = self.b.create_block();
        let exit = self.b.create_block();
        let done = self.b.append_block_param(exit, types::F64);
        self.b.ins().jump(header, &[lo.into(), s.into()]);

        self.b.switch_to_block(header);
        let more = self.b.ins().icmp(
            cranelift_codegen::ir::condcodes::IntCC::SignedLessThan,
            j,
            hi,
        );
        self.b.ins().brif(more, body, &[], exit, &[acc.into()]);

        self.b.switch_to_block(body);
        self.b.seal_block(body);
        let j8 = self.b.ins().ishl_imm(j, 3);
        let wj = self.b.ins().iadd(self.w, j8);
        let wkj = self.b.ins().isub(o.wk, j8);
        let t = term(self, j, wj, wkj);
        let next = self.add(acc, t);
        let j1 = self.b.ins().iadd_imm(j, 1);
        self.b.ins().jump(header, &[j1.into(), next.into()]);
        self.b.seal_block(header);

        self.b.switch_to_block(exit);
        self.b.seal_block(exit);
        done
    }

    /// `Σ_{j < n} term(j)` for a run-time `n` (at least 1) in
    /// [`ordered_sum`](super::ordered_sum)'s order with the program's end terms
    /// ([`WorkLayout::lead`]): below [`split_terms`] terms the first term and a loop over the
    /// others; else the four partial sums over the groups (a loop), the end terms before them,
    /// and a loop over the terms after them.
    fn ordered_loop(&mut self, o: Order, n: Value, term: Term<'_, 'a, 'b>) -> Value {
        use cranelift_codegen::ir::condcodes::IntCC;
        let lead = self.fresh.lead();
        // Term `j` at a run-time `j`.
        let at = |e: &mut Self, j: Value| {
            let j8 = e.b.ins().ishl_imm(j, 3);
            let wj = e.b.ins().iadd(e.w, j8);
            let wkj = e.b.ins().isub(o.wk, j8);
            term(e, j, wj, wkj)
        };
        let plain = self.b.create_block();
        let split = self.b.create_block();
        let exit = self.b.create_block();
        let done = self.b.append_block_param(exit, types::F64);
        let few = self
            .b
            .ins()
            .icmp_imm(IntCC::SignedLessThan, n, split_terms(lead) as i64);
        self.b.ins().brif(few, plain, &[], split, &[]);

        self.b.switch_to_block(plain);
        self.b.seal_block(plain);
        let zero = self.b.ins().iconst(types::I64, 0);
        let first = at(self, zero);
        let one = self.b.ins().iconst(types::I64, 1);
        let s = self.sum_loop(o, first, (one, n), term);
        self.b.ins().jump(exit, &[s.into()]);

        self.b.switch_to_block(split);
        self.b.seal_block(split);
        let p: [Value; 4] = std::array::from_fn(|l| {
            let j = self.b.ins().iconst(types::I64, (lead + l) as i64);
            at(self, j)
        });
        let groups = self.b.ins().iadd_imm(n, -2 * lead as i64);
        let groups = self.b.ins().ushr_imm(groups, 2);
        let header = self.b.create_block();
        let g = self.b.append_block_param(header, types::I64);
        let acc = [(); 4].map(|()| self.b.append_block_param(header, types::F64));
        let body = self.b.create_block();
        let after = self.b.create_block();
        let sums = [(); 4].map(|()| self.b.append_block_param(after, types::F64));
        let one = self.b.ins().iconst(types::I64, 1);
        let args = |g: Value, p: [Value; 4]| {
            [g.into(), p[0].into(), p[1].into(), p[2].into(), p[3].into()]
        };
        self.b.ins().jump(header, &args(one, p));

        self.b.switch_to_block(header);
        let more = self.b.ins().icmp(IntCC::SignedLessThan, g, groups);
        let acc_args = acc.map(Into::into);
        self.b.ins().brif(more, body, &[], after, &acc_args);

        self.b.switch_to_block(body);
        self.b.seal_block(body);
        let base = self.b.ins().ishl_imm(g, 2);
        let next: [Value; 4] = std::array::from_fn(|l| {
            let j = self.b.ins().iadd_imm(base, (lead + l) as i64);
            let t = at(self, j);
            self.add(acc[l], t)
        });
        let g1 = self.b.ins().iadd_imm(g, 1);
        self.b.ins().jump(header, &args(g1, next));
        self.b.seal_block(header);

        self.b.switch_to_block(after);
        self.b.seal_block(after);
        let even = self.add(sums[0], sums[2]);
        let odd = self.add(sums[1], sums[3]);
        let mut s = self.add(even, odd);
        for j in 0..lead {
            let j = self.b.ins().iconst(types::I64, j as i64);
            let t = at(self, j);
            s = self.add(s, t);
        }
        let lo = self.b.ins().ishl_imm(groups, 2);
        let lo = self.b.ins().iadd_imm(lo, lead as i64);
        let s = self.sum_loop(o, s, (lo, n), term);
        self.b.ins().jump(exit, &[s.into()]);

        self.b.switch_to_block(exit);
        self.b.seal_block(exit);
        done
    }

    /// `Σ_j a_{a0 + j} b_{k - b0 - j}` for `j` from 0 below `n` (at least 1), as
    /// [`cauchy`](Self::cauchy) sums it ([`ordered_loop`](Self::ordered_loop)).
    fn cauchy_loop(
        &mut self,
        o: Order,
        (a, a0): (usize, usize),
        (b, b0): (usize, usize),
        n: Value,
    ) -> Value {
        let (oa, ob) = (self.offset(a, a0 as isize), self.offset(b, -(b0 as isize)));
        self.ordered_loop(o, n, &move |e, _, wj, wkj| {
            let x = e.ld_at(wj, oa);
            let y = e.ld_at(wkj, ob);
            e.mul(x, y)
        })
    }

    /// [`Recurrences::mirrored`] for the run-time `k >= 1` of `o`: `n = ⌈k/2⌉ - lo` pairs,
    /// none where `lo = 1` and `k ≤ 2`, whose loop (at least one term, read in bounds) is then
    /// discarded for the interpreter's zero.
    fn mirrored_loop(&mut self, o: Order, x: usize, lo: usize) -> Value {
        use cranelift_codegen::ir::condcodes::IntCC;
        let k1 = self.b.ins().iadd_imm(o.k, 1);
        let half = self.b.ins().sshr_imm(k1, 1);
        let n = self.b.ins().iadd_imm(half, -(lo as i64));
        let s = self.cauchy_loop(o, (x, lo), (x, lo), n);
        let two = self.c(2.0);
        let twice = self.mul(s, two);
        let mid = self.b.ins().sshr_imm(o.k, 1);
        let mid8 = self.b.ins().ishl_imm(mid, 3);
        let at = self.b.ins().iadd(self.w, mid8);
        let offset = self.offset(x, 0);
        let m = self.ld_at(at, offset);
        let m = self.mul(m, m);
        let plus_m = self.add(twice, m);
        let (twice, with_m) = if lo == 0 {
            (twice, plus_m)
        } else {
            let none = self.b.ins().icmp_imm(IntCC::Equal, n, 0);
            let zero = self.c(0.0);
            let twice = self.b.ins().select(none, zero, twice);
            (twice, self.b.ins().select(none, m, plus_m))
        };
        let odd = self.b.ins().band_imm(o.k, 1);
        self.b.ins().select(odd, twice, with_m)
    }

    /// The recurrences to `order` in [`Form::Compact`]: order 0 as the unrolled code has it,
    /// then one loop over `k = 1..=order` whose body sets the state's order `k` from the field's
    /// order `k - 1` and then every node's order `k` (the interpreter's sequence of operations).
    fn compact(&mut self, nodes: &[Node], outputs: &[Val], order: usize) {
        self.fresh.set_k(0);
        for (i, &node) in nodes.iter().enumerate() {
            self.node(i, node, 0);
        }
        if order == 0 {
            return;
        }
        // Only order 0's values stored above are reused as values; nothing from the loop.
        self.fresh.set_k(1);
        let body = self.b.create_block();
        let k = self.b.append_block_param(body, types::I64);
        let exit = self.b.create_block();
        let one = self.b.ins().iconst(types::I64, 1);
        self.b.ins().jump(body, &[one.into()]);

        self.b.switch_to_block(body);
        let kf = self.float(k);
        let one = self.c(1.0);
        let rk = self.div(one, kf);
        let k8 = self.b.ins().ishl_imm(k, 3);
        let wk = self.b.ins().iadd(self.w, k8);
        let o = Order { k, kf, rk, wk };
        for (i, out) in outputs.iter().enumerate() {
            let fk = match *out {
                Val::Node(n) => self.ldk(o, n as usize, 1),
                Val::Const(c) => {
                    let first =
                        self.b
                            .ins()
                            .icmp_imm(cranelift_codegen::ir::condcodes::IntCC::Equal, k, 1);
                    let (c, zero) = (self.c(c), self.c(0.0));
                    self.b.ins().select(first, c, zero)
                }
            };
            let v = self.mul(fk, rk);
            self.stk(o, i, v);
        }
        for (i, &node) in nodes.iter().enumerate() {
            self.node_k(o, i, node);
        }
        let next = self.b.ins().iadd_imm(k, 1);
        let more = self.b.ins().icmp_imm(
            cranelift_codegen::ir::condcodes::IntCC::SignedLessThanOrEqual,
            next,
            order as i64,
        );
        self.b.ins().brif(more, body, &[next.into()], exit, &[]);
        self.b.seal_block(body);
        self.b.switch_to_block(exit);
        self.b.seal_block(exit);
    }

    /// An integral `c`'s sum `Σ_{j < n} ((n - j) c_{n-j}) d_{1+j}`, `n = k - 1`, for the
    /// run-time `k` of `o` (`Weight::Falling` from `d`'s order 1, in `ordered_sum`'s order).
    /// Its loop takes one term at least (read in bounds); `n = 0` (`k = 1`) is for the caller
    /// to discard.
    fn integral_loop(&mut self, o: Order, c: usize, d: usize) -> Value {
        let (oa, ob) = (self.offset(c, -1), self.offset(d, 1));
        let n = self.b.ins().iadd_imm(o.k, -1);
        self.ordered_loop(o, n, &move |e, j, wj, wkj| {
            let nj = e.b.ins().isub(n, j);
            let wt = e.float(nj);
            let x = e.ld_at(wkj, oa);
            let wx = e.mul(wt, x);
            let y = e.ld_at(wj, ob);
            e.mul(wx, y)
        })
    }

    /// Order `k >= 1` of node `me` for the run-time `k` of `o`, as `TaylorProgram::order_k`.
    #[allow(clippy::too_many_lines)]
    fn node_k(&mut self, o: Order, me: usize, node: Node) {
        let u = |n: u32| n as usize;
        let value = match node {
            Node::State | Node::Time | Node::Partner => return,
            Node::Add(a, b) => {
                let (x, y) = (self.ldk(o, u(a), 0), self.ldk(o, u(b), 0));
                self.add(x, y)
            }
            Node::Sub(a, b) => {
                let (x, y) = (self.ldk(o, u(a), 0), self.ldk(o, u(b), 0));
                self.sub(x, y)
            }
            Node::AddC(a, _) => self.ldk(o, u(a), 0),
            Node::CSub(_, a) | Node::Neg(a) => {
                let x = self.ldk(o, u(a), 0);
                self.b.ins().fneg(x)
            }
            Node::MulC(a, c) => {
                let x = self.ldk(o, u(a), 0);
                self.cmul(c, x)
            }
            Node::Abs(a) => {
                let (x0, x) = (self.ld(u(a), 0), self.ldk(o, u(a), 0));
                self.abs(x0, x)
            }
            Node::Mul(a, b) => {
                let n = self.b.ins().iadd_imm(o.k, 1);
                self.cauchy_loop(o, (u(a), 0), (u(b), 0), n)
            }
            Node::Square(a) => self.mirrored_loop(o, u(a), 0),
            Node::Div(a, b) => {
                let (x, b0) = (self.ldk(o, u(a), 0), self.ld(u(b), 0));
                let s = self.cauchy_loop(o, (u(b), 1), (me, 1), o.k);
                let num = self.sub(x, s);
                self.div(num, b0)
            }
            Node::CDiv(_, a) => {
                let a0 = self.ld(u(a), 0);
                let s = self.cauchy_loop(o, (u(a), 1), (me, 1), o.k);
                let minus = self.b.ins().fneg(s);
                self.div(minus, a0)
            }
            Node::Sqrt(a) => {
                let inner = self.mirrored_loop(o, me, 1);
                let x = self.ldk(o, u(a), 0);
                let s = self.sub(x, inner);
                let me0 = self.ld(me, 0);
                let d = self.cmul(2.0, me0);
                self.div(s, d)
            }
            Node::Powf(a, alpha) => {
                let a0 = self.ld(u(a), 0);
                let (oa, om) = (self.offset(u(a), 0), self.offset(me, 0));
                // The weight `α (k - j) - j` by the `f64` operations of `powf_weight`.
                let term = move |e: &mut Self, j: Value, wj: Value, wkj: Value| {
                    let kj = e.b.ins().isub(o.k, j);
                    let kj = e.float(kj);
                    let jf = e.float(j);
                    let alpha = e.c(alpha);
                    let wt = e.mul(alpha, kj);
                    let wt = e.sub(wt, jf);
                    let x = e.ld_at(wkj, oa);
                    let wx = e.mul(wt, x);
                    let y = e.ld_at(wj, om);
                    e.mul(wx, y)
                };
                let s = self.ordered_loop(o, o.k, &term);
                let d = self.mul(o.kf, a0);
                self.div(s, d)
            }
            Node::Derivative(a) => {
                let x = self.ldk(o, u(a), 0);
                self.mul(o.kf, x)
            }
            Node::Exp(d) => {
                let s = self.cauchy_loop(o, (me, 0), (u(d), 0), o.k);
                self.mul(s, o.rk)
            }
            Node::Integral {
                a,
                d,
                sign,
                func: _,
            } => {
                let x = self.ldk(o, u(a), 0);
                let sign = self.c(sign);
                let sk = self.mul(sign, o.kf);
                let s = self.mul(sk, x);
                // No terms at `k = 1`: the interpreter's `s` then, not `s - 0`.
                let t = self.integral_loop(o, me, u(d));
                let minus_t = self.sub(s, t);
                let none =
                    self.b
                        .ins()
                        .icmp_imm(cranelift_codegen::ir::condcodes::IntCC::Equal, o.k, 1);
                let s = self.b.ins().select(none, s, minus_t);
                let d0 = self.ld(u(d), 0);
                let den = self.mul(o.kf, d0);
                self.div(s, den)
            }
            Node::SinCos(d, hyperbolic) => {
                let partner = me + 1;
                // The sine's sum runs over the cosine, the cosine's over the sine.
                let s = self.cauchy_loop(o, (partner, 0), (u(d), 0), o.k);
                let c = self.cauchy_loop(o, (me, 0), (u(d), 0), o.k);
                let c = if hyperbolic { c } else { self.b.ins().fneg(c) };
                let pc = self.mul(c, o.rk);
                self.stk(o, partner, pc);
                self.mul(s, o.rk)
            }
        };
        self.stk(o, me, value);
    }
}
