//! [`TaylorLanes`](super::TaylorLanes)' recurrences compiled to machine code by Cranelift
//! (feature `jit`, native targets only): one function per program, order `p` and lane count
//! `L`, `fn(w)`, on the lanes' work array `w` (every node's coefficients, `p + 1` per node,
//! each an `[f64; L]`, the state's and time's order 0 already set).
//!
//! The code is the scalar JIT's unrolled form (`taylor_jit.rs`: for `k = 0..=p`, order `k` of
//! every operation node, then the state's order `k + 1`, every term of every sum written out,
//! a coefficient of the order being computed used as the value just computed) on Cranelift's
//! `f64x2` vectors (its x86-64 backend has no wider ones): each value is [`VECTORS`] vectors
//! of two lanes. One pass of that code covers `2 VECTORS` lanes; a loop runs it over the `L`
//! lanes, its base address moving by `2 VECTORS` doubles. The work array is only 8-byte
//! aligned, so the loads and stores claim no more.
//!
//! `f64x2` addition, subtraction, multiplication, division, negation and square root are the
//! IEEE operations lane by lane, and Cranelift does not contract a multiplication and an
//! addition into a fused multiply-add (it is never asked to), so each lane does the
//! interpreter's operations in its order and gets its bits; order 0 of the transcendental
//! operations is computed lane by lane by the scalar JIT's `extern "C"` shims (the
//! interpreter's own functions), and `|x|`'s sign test lane by lane as the scalar JIT does it
//! (`tests/classical/integrators/taylor_lanes.rs` checks every recurrence at orders 1–24).
//!
//! An order is compiled at its first expansion: an ensemble's lanes expand thousands of times
//! (1000 Hénon–Heiles members to t = 100 take 300 000 member steps, 38 000 expansions in 8
//! lanes), and compiling costs about as much as the scalar JIT's unrolled code (1–3 ms for
//! Hénon–Heiles, `benchmarks/README.md`), about a thousand interpreted expansions. Programs whose
//! unrolled code would take long to compile ([`MAX_TERMS`]) stay interpreted. The code lives in
//! a [`JITModule`](cranelift_jit::JITModule) shared behind an `Arc` by the lanes' clones and by
//! later lanes of the same recurrences ([`KEPT`]), and freed with the last of them.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::{types, ConstantData, InstBuilder, MemFlags, Value};
use cranelift_codegen::settings::Configurable;
use cranelift_frontend::FunctionBuilder;

use super::super::jit::{cos, cosh, exp, powf, sin, sinh, unrolled_terms, INTEGRALS};
use super::super::{powf_weight, Node, Val};
use crate::classical::integrators::taylor::MAX_ORDER;
use crate::classical::symbolic::tape::jit::{
    compile_function, flag_builder, OwnedModule, Param, Shims,
};

/// The compiled function: the work array.
type Entry = unsafe extern "C" fn(*mut f64);

/// `f64x2` vectors per value. Two or four, interleaved so that their chains of dependent
/// additions overlap, ran no faster on an AVX2 EPYC (the out-of-order core already overlaps
/// the independent nodes of the unrolled code) and took two and five times as long to compile
/// (`benchmarks/README.md`).
const VECTORS: usize = 1;

/// The largest number of sum terms (over every node and order, as the scalar JIT counts them)
/// compiled; larger programs stay interpreted. The scalar JIT's limit for its unrolled form:
/// this code has its size and compile time.
const MAX_TERMS: usize = 1200;

/// Lanes (of programs with the same recurrences, for the same lane count) whose code is kept
/// for the next lanes of those recurrences: an ensemble builds its members' program and lanes
/// afresh for each chunk of members, and each would otherwise compile the same code again.
const KEPT: usize = 8;

/// The code of the last [`KEPT`] lanes built.
static RECENT: Mutex<Vec<Kept>> = Mutex::new(Vec::new());

/// Lanes' code kept for later lanes, with the recurrences and lane count it was built for.
struct Kept {
    nodes: Vec<Node>,
    outputs: Vec<Val>,
    lanes: usize,
    jit: Jit,
}

/// The lanes' native code per order, or its absence, shared by the lanes' clones and by
/// lanes of the same recurrences ([`Jit::shared`]).
#[derive(Clone, Default)]
pub(super) struct Jit(Arc<State>);

#[derive(Default)]
struct State {
    /// Set for lanes that are never compiled.
    never: bool,
    code: [OnceLock<Option<Native>>; MAX_ORDER + 1],
    /// Orders found above [`MAX_TERMS`] sum terms (not compiled at expansions, but on demand
    /// at any size).
    too_large: [AtomicBool; MAX_ORDER + 1],
}

impl std::fmt::Debug for Jit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let native: Vec<usize> = (0..=MAX_ORDER).filter(|&p| self.is_native(p)).collect();
        write!(f, "native for orders {native:?}")
    }
}

impl Jit {
    /// Lanes whose recurrences are never compiled.
    pub(super) fn never() -> Self {
        Self(Arc::new(State {
            never: true,
            ..State::default()
        }))
    }

    /// The code of lanes of these recurrences for `lanes` lanes: one of the last [`KEPT`]
    /// built if it runs the same recurrences (so the same coefficients, bit for bit), else
    /// code of its own, kept in their place.
    pub(super) fn shared(nodes: &[Node], outputs: &[Val], lanes: usize) -> Self {
        let Ok(mut recent) = RECENT.lock() else {
            return Self::default();
        };
        let same = |k: &&Kept| {
            k.lanes == lanes && super::same_recurrences((&k.nodes, &k.outputs), (nodes, outputs))
        };
        if let Some(kept) = recent.iter().find(same) {
            return kept.jit.clone();
        }
        let jit = Self::default();
        if recent.len() == KEPT {
            recent.remove(0);
        }
        recent.push(Kept {
            nodes: nodes.to_vec(),
            outputs: outputs.to_vec(),
            lanes,
            jit: jit.clone(),
        });
        jit
    }

    /// The native code of `order` for `lanes` lanes, compiled at the first expansion of that
    /// order if the program has at most [`MAX_TERMS`] sum terms (once; later calls return the
    /// first outcome).
    #[inline]
    pub(super) fn code(
        &self,
        nodes: &[Node],
        outputs: &[Val],
        lanes: usize,
        order: usize,
    ) -> Option<&Native> {
        self.compile(nodes, outputs, lanes, order, MAX_TERMS)
    }

    /// [`code`](Self::code) for programs of at most `max_terms` sum terms.
    pub(super) fn compile(
        &self,
        nodes: &[Node],
        outputs: &[Val],
        lanes: usize,
        order: usize,
        max_terms: usize,
    ) -> Option<&Native> {
        if self.0.never {
            return None;
        }
        let slot = self.0.code.get(order)?;
        if let Some(code) = slot.get() {
            return code.as_ref();
        }
        let too_large = &self.0.too_large[order];
        if max_terms <= MAX_TERMS && too_large.load(Ordering::Relaxed) {
            return None;
        }
        // Recorded apart from the code: a call allowing more terms may still compile it.
        if unrolled_terms(nodes, order) > max_terms {
            too_large.store(true, Ordering::Relaxed);
            return None;
        }
        slot.get_or_init(|| Native::compile(nodes, outputs, lanes, order))
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

/// Compiled lanes recurrences: the entry point and the module that owns the code.
pub(super) struct Native {
    entry: Entry,
    /// Length of the work array the code reads and writes, in `[f64; lanes]`.
    len: usize,
    lanes: usize,
    /// Owns the code `entry` points into.
    _module: OwnedModule,
}

impl Native {
    /// Runs the recurrences on the work array `w` (left untouched if its length is not the
    /// program's nodes times `order + 1`, or `L` not the lanes compiled for: callers size it
    /// first).
    #[inline]
    // SAFETY: the code reads and writes `w[..len]` only (`lanes` doubles each), which the
    // check makes in bounds, with loads and stores claiming 8-byte alignment, which an
    // `[f64; L]` has; it calls only the scalar JIT's shims, plain functions of their arguments.
    #[allow(unsafe_code)]
    pub(super) fn call<const L: usize>(&self, w: &mut [[f64; L]]) {
        if w.len() == self.len && L == self.lanes {
            unsafe { (self.entry)(w.as_mut_ptr().cast::<f64>()) }
        }
    }

    fn compile(nodes: &[Node], outputs: &[Val], lanes: usize, order: usize) -> Option<Native> {
        Self::compile_with::<VECTORS>(nodes, outputs, lanes, order)
    }

    /// The recurrences with values of `V` vectors.
    fn compile_with<const V: usize>(
        nodes: &[Node],
        outputs: &[Val],
        lanes: usize,
        order: usize,
    ) -> Option<Native> {
        if lanes == 0 || !lanes.is_multiple_of(2 * V) {
            return None;
        }
        let mut flags = flag_builder()?;
        // As for the scalar JIT (`taylor_jit.rs`): the generated IR is checked by the
        // bit-for-bit tests, and Cranelift's optimizer would merge constants into values
        // spilled across the whole function.
        flags.set("enable_verifier", "false").ok()?;
        flags.set("opt_level", "none").ok()?;
        let isa = cranelift_native::builder().ok()?;
        let (code, module) =
            compile_function(isa, flags, &[Param::Pointer], false, |b, params, shims| {
                let w = params[0];
                let pass = (16 * V) as i64;
                let end = b.ins().iadd_imm(w, 8 * lanes as i64);
                let body = b.create_block();
                let base = b.append_block_param(body, types::I64);
                b.ins().jump(body, &[w.into()]);
                b.switch_to_block(body);
                Emitter::<V> {
                    b: &mut *b,
                    shims,
                    base,
                    lanes,
                    stride: order + 1,
                    k: 0,
                    fresh: vec![None; nodes.len() * (order + 1)],
                }
                .recurrences(nodes, outputs, order);
                let next = b.ins().iadd_imm(base, pass);
                let more = b.ins().icmp(IntCC::UnsignedLessThan, next, end);
                let exit = b.create_block();
                b.ins().brif(more, body, &[next.into()], exit, &[]);
                b.seal_block(body);
                b.switch_to_block(exit);
                b.seal_block(exit);
                Vec::new()
            })?;
        Some(Native {
            // SAFETY: `code` is the finalized code of a function declared with `Entry`'s
            // signature in the platform's default calling convention, `extern "C"`'s.
            #[allow(unsafe_code)]
            entry: unsafe { std::mem::transmute::<*const u8, Entry>(code) },
            len: nodes.len() * (order + 1),
            lanes,
            _module: module,
        })
    }
}

/// A value of `2 VECTORS` lanes: [`VECTORS`] `f64x2` values.
type Lanes<const V: usize> = [Value; V];

/// The flags of every load and store: in bounds (`Native::call` checks the length), but only
/// 8-byte aligned.
fn flags() -> MemFlags {
    MemFlags::new().with_notrap()
}

/// Emits the recurrences for one pass of `2 VECTORS` lanes at `base`.
struct Emitter<'a, 'b, const V: usize> {
    b: &'a mut FunctionBuilder<'b>,
    shims: &'a mut Shims,
    /// Address of this pass's first lane of the work array's first coefficient.
    base: Value,
    lanes: usize,
    stride: usize,
    /// The order being emitted.
    k: usize,
    /// The value of each coefficient stored by this function, used instead of a load while
    /// its order is at least the one being emitted.
    fresh: Vec<Option<Lanes<V>>>,
}

impl<const V: usize> Emitter<'_, '_, V> {
    /// Byte offset of vector `v` of coefficient `j` of node `n` from `base`.
    fn offset(&self, n: usize, j: usize, v: usize) -> i32 {
        (8 * self.lanes * (n * self.stride + j) + 16 * v) as i32
    }

    /// Coefficient `j` of node `n`.
    fn ld(&mut self, n: usize, j: usize) -> Lanes<V> {
        if j >= self.k {
            if let Some(v) = self.fresh[n * self.stride + j] {
                return v;
            }
        }
        std::array::from_fn(|v| {
            let offset = self.offset(n, j, v);
            self.b.ins().load(types::F64X2, flags(), self.base, offset)
        })
    }

    fn st(&mut self, n: usize, j: usize, x: Lanes<V>) {
        self.fresh[n * self.stride + j] = Some(x);
        for (v, &x) in x.iter().enumerate() {
            let offset = self.offset(n, j, v);
            self.b.ins().store(flags(), x, self.base, offset);
        }
    }

    /// `c` in every lane (one constant-pool entry).
    fn c(&mut self, c: f64) -> Lanes<V> {
        let bytes: Vec<u8> = [c, c].iter().flat_map(|x| x.to_le_bytes()).collect();
        let handle = self.b.func.dfg.constants.insert(ConstantData::from(bytes));
        let x = self.b.ins().vconst(types::F64X2, handle);
        [x; V]
    }

    /// `op` vector by vector.
    fn zip(
        &mut self,
        x: Lanes<V>,
        y: Lanes<V>,
        op: fn(&mut FunctionBuilder<'_>, Value, Value) -> Value,
    ) -> Lanes<V> {
        std::array::from_fn(|v| op(self.b, x[v], y[v]))
    }

    fn add(&mut self, x: Lanes<V>, y: Lanes<V>) -> Lanes<V> {
        self.zip(x, y, |b, x, y| b.ins().fadd(x, y))
    }

    fn sub(&mut self, x: Lanes<V>, y: Lanes<V>) -> Lanes<V> {
        self.zip(x, y, |b, x, y| b.ins().fsub(x, y))
    }

    fn mul(&mut self, x: Lanes<V>, y: Lanes<V>) -> Lanes<V> {
        self.zip(x, y, |b, x, y| b.ins().fmul(x, y))
    }

    fn div(&mut self, x: Lanes<V>, y: Lanes<V>) -> Lanes<V> {
        self.zip(x, y, |b, x, y| b.ins().fdiv(x, y))
    }

    fn neg(&mut self, x: Lanes<V>) -> Lanes<V> {
        std::array::from_fn(|v| self.b.ins().fneg(x[v]))
    }

    /// `x · c` (the interpreter's `c * x`: IEEE multiplication commutes exactly).
    fn cmul(&mut self, c: f64, x: Lanes<V>) -> Lanes<V> {
        let c = self.c(c);
        self.mul(x, c)
    }

    /// `f` lane by lane on the lanes of `args` (scalar `f64` values), the results gathered
    /// back into vectors.
    fn per_lane(
        &mut self,
        args: &[Lanes<V>],
        f: impl Fn(&mut Self, &[Value]) -> Value,
    ) -> Lanes<V> {
        std::array::from_fn(|v| {
            let mut lanes = [None; 2];
            for (lane, out) in lanes.iter_mut().enumerate() {
                let scalars: Vec<Value> = args
                    .iter()
                    .map(|x| self.b.ins().extractlane(x[v], lane as u8))
                    .collect();
                *out = Some(f(self, &scalars));
            }
            let [Some(x0), Some(x1)] = lanes else {
                unreachable!("both lanes are set above")
            };
            let x = self.b.ins().scalar_to_vector(types::F64X2, x0);
            self.b.ins().insertlane(x, x1, 1)
        })
    }

    /// The shim at `address` lane by lane on `x`.
    fn call(&mut self, address: usize, x: Lanes<V>) -> Lanes<V> {
        self.per_lane(&[x], |e, x| e.shims.call(e.b, address, x))
    }

    /// Order `k` of `|a|` from `a`'s orders 0 and `k`: `-x` where `a_0 < 0`, else `x`, lane
    /// by lane.
    fn abs(&mut self, x0: Lanes<V>, x: Lanes<V>) -> Lanes<V> {
        self.per_lane(&[x0, x], |e, v| {
            let zero = e.b.ins().f64const(0.0);
            let negative = e.b.ins().fcmp(FloatCC::LessThan, v[0], zero);
            let minus = e.b.ins().fneg(v[1]);
            e.b.ins().select(negative, minus, v[1])
        })
    }

    /// `Σ_{j < n} a_j b_{n-1-j}` from `j = 0` (the interpreter's `cauchy` of the slices
    /// starting at coefficient `a0` of node `a` and `b0` of node `b`); `None` for `n = 0`.
    fn cauchy(
        &mut self,
        (a, a0): (usize, usize),
        (b, b0): (usize, usize),
        n: usize,
    ) -> Option<Lanes<V>> {
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

    /// `Σ term(j)` for `j` in `range`, from its first term, `None` for an empty range.
    fn sum(
        &mut self,
        range: impl Iterator<Item = usize>,
        mut term: impl FnMut(&mut Self, usize) -> Lanes<V>,
    ) -> Option<Lanes<V>> {
        let mut s = None;
        for j in range {
            let t = term(self, j);
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
            self.k = k;
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

    /// Order `k` of node `me`, as `TaylorProgram::order_k` (and the scalar JIT's `node`).
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
                    std::array::from_fn(|v| self.b.ins().sqrt(x[v]))
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
                    self.per_lane(&[a0], |e, x| {
                        let alpha = e.b.ins().f64const(alpha);
                        e.shims
                            .call(e.b, powf as *const () as usize, &[x[0], alpha])
                    })
                } else {
                    let s = self.sum(0..k, |e, j| {
                        let x = e.ld(u(a), k - j);
                        let wx = e.cmul(powf_weight(alpha, k, j), x);
                        let y = e.ld(me, j);
                        e.mul(wx, y)
                    });
                    let d = self.cmul(kf, a0);
                    let s = s.unwrap_or(d);
                    self.div(s, d)
                }
            }
            Node::Exp(a) => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.call(exp as *const () as usize, x)
                } else {
                    let s = self.sum(1..=k, |e, j| {
                        let x = e.ld(u(a), j);
                        let jx = e.cmul(j as f64, x);
                        let y = e.ld(me, k - j);
                        e.mul(jx, y)
                    });
                    let kf = self.c(kf);
                    let s = s.unwrap_or(kf);
                    self.div(s, kf)
                }
            }
            Node::Integral { a, d, sign, func } => {
                if k == 0 {
                    let x = self.ld(u(a), 0);
                    self.call(INTEGRALS[func as usize] as usize, x)
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
                    let s = self.call(fs as usize, x);
                    let c = self.call(fc as usize, x);
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
                    let c = if hyperbolic { c } else { self.neg(c) };
                    let pc = self.div(c, kf);
                    self.st(partner, k, pc);
                    self.div(s, kf)
                }
            }
        };
        self.st(me, k, value);
    }
}
