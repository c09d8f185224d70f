//! [`TaylorLanes`](super::TaylorLanes)' recurrences compiled to machine code by Cranelift
//! (feature `jit`, native targets only): one function per program, order `p` and lane count
//! `L`, `fn(w)`, on the lanes' work array `w` (every node's coefficients, `p + 1` per node,
//! each an `[f64; L]`, the state's and time's order 0 already set).
//!
//! The code is the scalar JIT's unrolled form, emitted by the same code (`taylor_jit.rs`'s
//! `Recurrences`: for `k = 0..=p`, order `k` of every operation node, then the state's order
//! `k + 1`, every term of every sum written out, a coefficient of the order being computed
//! used as the value just computed) on Cranelift's `f64x2` vectors (its x86-64 backend has no
//! wider ones): each value is `N` vectors of two lanes ([`vectors`]: two with 16 lanes or
//! more in multiples of 4, else one). One pass of that code covers `2 N` lanes; a loop runs
//! it over the `L` lanes, its base address moving by `2 N` doubles. The work array is only
//! 8-byte aligned, so the loads and stores claim no more.
//!
//! On x86-64 hosts with AVX the same recurrences are first written as `ymm` or `zmm` code by
//! `taylor_asm.rs` (4 or 8 lanes a register, loads folded, compiled in a twentieth of
//! Cranelift's time); Cranelift's code is the fallback (hosts without AVX, offsets beyond
//! the encoding), and what [`Jit::cranelift_only`] asks for in tests.
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
//! lanes), and compiling costs about as much as the scalar JIT's unrolled code with one vector
//! per value and about twice that with two (a few milliseconds for Hénon–Heiles,
//! `benchmarks/README.md`), a thousand or two interpreted expansions. Programs whose unrolled
//! code would take long to compile ([`MAX_TERMS`]) stay interpreted. The code lives in
//! a [`JITModule`](cranelift_jit::JITModule) shared behind an `Arc` by the lanes' clones and by
//! later lanes of the same recurrences ([`KEPT`]), and freed with the last of them.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::{types, ConstantData, InstBuilder, MemFlags, Value};
use cranelift_codegen::settings::Configurable;
use cranelift_frontend::FunctionBuilder;

#[cfg(all(target_arch = "x86_64", not(windows)))]
use super::super::jit::asm;
use super::super::jit::{powf, unrolled_terms, Form, Fresh, Recurrences};
use super::super::{Node, Val, WorkLayout};
use crate::classical::integrators::taylor::MAX_ORDER;
use crate::classical::symbolic::tape::jit::{
    compile_function, flag_builder, OwnedModule, Param, Shims,
};

/// The compiled function: the work array.
type Entry = unsafe extern "C" fn(*mut f64);

/// `f64x2` vectors per value for `lanes` lanes: two, interleaved so that their chains of
/// dependent additions overlap, for 16 lanes or more in multiples of 4 (what
/// [`native_lanes`](super::native_lanes) gives on AVX-512 hosts, where two vectors measured
/// faster than one for about twice the compile time); one otherwise (AVX2 and older hosts'
/// 8 and 4 lanes, where two measured no faster: the out-of-order core already overlaps the
/// independent nodes of the unrolled code). Four were no faster on either. The figures are in
/// `benchmarks/README.md`.
fn vectors(lanes: usize) -> usize {
    if lanes >= 16 && lanes.is_multiple_of(4) {
        2
    } else {
        1
    }
}

/// The largest number of sum terms (over every node and order, as the scalar JIT counts them)
/// compiled; larger programs stay interpreted. The scalar JIT's limit for its unrolled form:
/// this code has its size and compile time.
const MAX_TERMS: usize = Form::MAX_UNROLLED_TERMS;

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
    /// Set for lanes compiled by Cranelift even where [`asm`] could write their code: what
    /// tests compare with the interpreter on hosts that have AVX.
    cranelift_only: bool,
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

    /// Lanes compiled by Cranelift alone, sharing no code with other lanes.
    pub(super) fn cranelift_only() -> Self {
        Self(Arc::new(State {
            cranelift_only: true,
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
        slot.get_or_init(|| Native::compile(nodes, outputs, lanes, order, self.0.cranelift_only))
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

/// Compiled lanes recurrences: the entry point and the module that owns the code.
pub(super) struct Native {
    entry: Entry,
    /// Length of the work array the code reads and writes, in `[f64; lanes]`.
    len: usize,
    lanes: usize,
    /// Whether the code is [`asm`]'s, written for AVX (else Cranelift's).
    avx: bool,
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

    /// The code written for AVX ([`asm`]) where the host and program allow it (unless
    /// `cranelift_only`), else Cranelift's.
    fn compile(
        nodes: &[Node],
        outputs: &[Val],
        lanes: usize,
        order: usize,
        cranelift_only: bool,
    ) -> Option<Native> {
        #[cfg(all(target_arch = "x86_64", not(windows)))]
        if !cranelift_only {
            if let Some((code, module)) = asm::compile(nodes, outputs, lanes, order) {
                let native = Native::new(code, nodes.len() * (order + 1), lanes, module);
                return Some(Native {
                    avx: true,
                    ..native
                });
            }
        }
        #[cfg(not(all(target_arch = "x86_64", not(windows))))]
        let _ = cranelift_only;
        if vectors(lanes) == 2 {
            Self::compile_with::<2>(nodes, outputs, lanes, order)
        } else {
            Self::compile_with::<1>(nodes, outputs, lanes, order)
        }
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
                    fresh: Fresh::new(WorkLayout::new(nodes, outputs.len(), order)),
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
        Some(Native::new(code, nodes.len() * (order + 1), lanes, module))
    }

    /// The function at `code`, owned by `module`, on a work array of `len` coefficients of
    /// `lanes` lanes.
    fn new(code: *const u8, len: usize, lanes: usize, module: OwnedModule) -> Native {
        Native {
            // SAFETY: `code` is the finalized code of a function of `Entry`'s signature in the
            // platform's default calling convention, `extern "C"`'s: Cranelift's, declared so,
            // or `asm`'s, written so.
            #[allow(unsafe_code)]
            entry: unsafe { std::mem::transmute::<*const u8, Entry>(code) },
            len,
            lanes,
            avx: false,
            _module: module,
        }
    }
}

/// A value of `2 N` lanes: `N` `f64x2` values ([`vectors`]).
type Lanes<const N: usize> = [Value; N];

/// The flags of every load and store: in bounds (`Native::call` checks the length), but only
/// 8-byte aligned.
fn flags() -> MemFlags {
    MemFlags::new().with_notrap()
}

/// Emits the recurrences (the scalar JIT's [`Recurrences`]) for one pass of `2 N` lanes at
/// `base`.
struct Emitter<'a, 'b, const N: usize> {
    b: &'a mut FunctionBuilder<'b>,
    shims: &'a mut Shims,
    /// Address of this pass's first lane of the work array's first coefficient.
    base: Value,
    lanes: usize,
    fresh: Fresh<Lanes<N>>,
}

impl<const N: usize> Emitter<'_, '_, N> {
    /// Byte offset of vector `v` of coefficient `j` of node `n` from `base`.
    fn offset(&self, n: usize, j: usize, v: usize) -> i32 {
        (8 * self.lanes * self.fresh.index(n, j) + 16 * v) as i32
    }

    /// `op` vector by vector.
    fn zip(
        &mut self,
        x: Lanes<N>,
        y: Lanes<N>,
        op: fn(&mut FunctionBuilder<'_>, Value, Value) -> Value,
    ) -> Lanes<N> {
        std::array::from_fn(|v| op(self.b, x[v], y[v]))
    }

    /// `f` lane by lane on the lanes of `args` (scalar `f64` values), the results gathered
    /// back into vectors.
    fn per_lane(
        &mut self,
        args: &[Lanes<N>],
        f: impl Fn(&mut Self, &[Value]) -> Value,
    ) -> Lanes<N> {
        std::array::from_fn(|v| {
            let lane = |e: &mut Self, lane: u8| {
                let scalars: Vec<Value> = args
                    .iter()
                    .map(|x| e.b.ins().extractlane(x[v], lane))
                    .collect();
                f(e, &scalars)
            };
            let x0 = lane(self, 0);
            let x1 = lane(self, 1);
            let x = self.b.ins().scalar_to_vector(types::F64X2, x0);
            self.b.ins().insertlane(x, x1, 1)
        })
    }
}

impl<const N: usize> Recurrences for Emitter<'_, '_, N> {
    type X = Lanes<N>;

    fn set_k(&mut self, k: usize) {
        self.fresh.set_k(k);
    }

    fn lead(&self) -> usize {
        self.fresh.lead()
    }

    fn ld(&mut self, n: usize, j: usize) -> Lanes<N> {
        if let Some(v) = self.fresh.get(n, j) {
            return v;
        }
        std::array::from_fn(|v| {
            let offset = self.offset(n, j, v);
            self.b.ins().load(types::F64X2, flags(), self.base, offset)
        })
    }

    fn st(&mut self, n: usize, j: usize, x: Lanes<N>) {
        self.fresh.set(n, j, x);
        for (v, &x) in x.iter().enumerate() {
            let offset = self.offset(n, j, v);
            self.b.ins().store(flags(), x, self.base, offset);
        }
    }

    /// `c` in every lane (one constant-pool entry).
    fn c(&mut self, c: f64) -> Lanes<N> {
        let bytes: Vec<u8> = [c, c].iter().flat_map(|x| x.to_le_bytes()).collect();
        let handle = self.b.func.dfg.constants.insert(ConstantData::from(bytes));
        let x = self.b.ins().vconst(types::F64X2, handle);
        [x; N]
    }

    fn add(&mut self, x: Lanes<N>, y: Lanes<N>) -> Lanes<N> {
        self.zip(x, y, |b, x, y| b.ins().fadd(x, y))
    }

    fn sub(&mut self, x: Lanes<N>, y: Lanes<N>) -> Lanes<N> {
        self.zip(x, y, |b, x, y| b.ins().fsub(x, y))
    }

    fn mul(&mut self, x: Lanes<N>, y: Lanes<N>) -> Lanes<N> {
        self.zip(x, y, |b, x, y| b.ins().fmul(x, y))
    }

    fn div(&mut self, x: Lanes<N>, y: Lanes<N>) -> Lanes<N> {
        self.zip(x, y, |b, x, y| b.ins().fdiv(x, y))
    }

    fn neg(&mut self, x: Lanes<N>) -> Lanes<N> {
        std::array::from_fn(|v| self.b.ins().fneg(x[v]))
    }

    fn sqrt(&mut self, x: Lanes<N>) -> Lanes<N> {
        std::array::from_fn(|v| self.b.ins().sqrt(x[v]))
    }

    /// Lane by lane, as the scalar JIT tests the sign.
    fn abs(&mut self, x0: Lanes<N>, x: Lanes<N>) -> Lanes<N> {
        self.per_lane(&[x0, x], |e, v| {
            let zero = e.b.ins().f64const(0.0);
            let negative = e.b.ins().fcmp(FloatCC::LessThan, v[0], zero);
            let minus = e.b.ins().fneg(v[1]);
            e.b.ins().select(negative, minus, v[1])
        })
    }

    /// Lane by lane.
    fn call(&mut self, address: usize, x: Lanes<N>) -> Lanes<N> {
        self.per_lane(&[x], |e, x| e.shims.call(e.b, address, x))
    }

    /// Lane by lane.
    fn powf(&mut self, x: Lanes<N>, alpha: f64) -> Lanes<N> {
        self.per_lane(&[x], |e, x| {
            let alpha = e.b.ins().f64const(alpha);
            e.shims
                .call(e.b, powf as *const () as usize, &[x[0], alpha])
        })
    }
}
