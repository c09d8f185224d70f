//! [`TaylorLanes`]: a [`TaylorProgram`]'s recurrences run for `L` states at once, one per
//! vector lane, for ensembles of members that share one program
//! ([`integrators::taylor_batch`](crate::classical::integrators::taylor_batch)).
//!
//! Every coefficient is an `[f64; L]`; each lane does exactly the interpreter's operations of
//! [`TaylorProgram`]'s `order_k`, in the same order (sums from their first term, no fused
//! multiply-add: Rust never contracts, and no clone enables `fma`), so each lane's
//! coefficients are the scalar ones bit for bit. Values at order 0 of the transcendental
//! operations (`sin`/`cos`, `exp`, `powf`, `ln`, ...) are computed lane by lane by the same
//! scalar functions. The loops are compiled three times and chosen at run time (std's
//! `is_x86_feature_detected!`, cached): with AVX-512 (`zmm` registers of 8 doubles), with
//! AVX2 (`ymm`, 4), and plain (SSE2 on x86-64, scalar elsewhere, wasm included); IEEE
//! additions, multiplications, divisions and square roots give the same bits in every clone.
//!
//! [`native_lanes`] is two registers' worth (16 with AVX-512, 8 with AVX2): a coefficient's
//! sums run term after term (the scalar order), so one register's lanes wait on the latency
//! of each addition; two independent registers keep the adder busy. On Hénon–Heiles at order
//! 15 (26 nodes) an expansion costs about the same per member at 16 and 32 lanes, and about
//! 1.8x as much at 8 (`benchmarks/README.md`).

use super::{func_value, ordered_sum, power0, Keyed, Node, TaylorProgram, Val, Weight, WorkLayout};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::taylor::{StepCost, TaylorField, MAX_ORDER};
use crate::classical::integrators::taylor_batch::LanesField;
use crate::classical::symbolic::Backend;

#[cfg(all(feature = "jit", not(target_arch = "wasm32")))]
#[path = "taylor_lanes_jit.rs"]
mod jit;

/// The stand-in for `taylor_lanes_jit.rs` where no JIT is built (feature `jit` off, or
/// WebAssembly): the lanes' recurrences are always interpreted.
#[cfg(not(all(feature = "jit", not(target_arch = "wasm32"))))]
mod jit {
    use super::{Node, Val};

    /// No native code, ever.
    #[derive(Debug, Clone)]
    pub(super) struct Jit(());

    /// Native code, which this build cannot have.
    pub(super) enum Native {}

    impl Jit {
        pub(super) fn never() -> Self {
            Self(())
        }

        pub(super) fn cranelift_only() -> Self {
            Self(())
        }

        pub(super) fn shared(_: &[Node], _: &[Val], _: usize) -> Self {
            Self(())
        }

        #[inline(always)]
        pub(super) fn code(&self, _: &[Node], _: &[Val], _: usize, _: usize) -> Option<&Native> {
            None
        }

        pub(super) fn compile(
            &self,
            _: &[Node],
            _: &[Val],
            _: usize,
            _: usize,
            _: usize,
        ) -> Option<&Native> {
            None
        }

        pub(super) fn is_avx(&self, _: usize) -> bool {
            false
        }

        pub(super) fn is_native(&self, _: usize) -> bool {
            false
        }
    }

    impl Native {
        pub(super) fn call<const L: usize>(&self, _: &mut [[f64; L]]) {
            match *self {}
        }
    }
}

/// A [`TaylorProgram`]'s recurrences for `L` states at once (see the module documentation).
#[derive(Debug, Clone)]
pub struct TaylorLanes<const L: usize> {
    dim: usize,
    nodes: Vec<Node>,
    outputs: Vec<Val>,
    /// Coefficients of every node (the nodes of a `WorkLayout`, without its blocks), each an
    /// `[f64; L]`; sized at the first expansion of an order and reused.
    work: Vec<[f64; L]>,
    /// How many of them are the state's rows (none before the first expansion).
    rows: usize,
    /// The layout of the last expansion's order, kept for the next expansion of that order.
    layout: Option<WorkLayout>,
    /// Machine code compiled from the recurrences (feature `jit`), per order.
    jit: jit::Jit,
}

impl TaylorProgram {
    /// The program behind a Taylor form, if it is one (every Taylor form the library builds
    /// is).
    pub fn from_field(field: &dyn TaylorField) -> Option<&Self> {
        let any: &dyn std::any::Any = field;
        any.downcast_ref::<Self>()
    }

    /// Whether `other` runs the same recurrences: the same operations on the same operands,
    /// constants equal bit for bit (so the same coefficients, bit for bit, at every state).
    pub fn same_recurrences(&self, other: &Self) -> bool {
        self.dim == other.dim
            && same_recurrences((&self.nodes, &self.outputs), (&other.nodes, &other.outputs))
    }

    /// These recurrences for `L` states at once.
    pub fn lanes<const L: usize>(&self) -> TaylorLanes<L> {
        TaylorLanes {
            dim: self.dim,
            nodes: self.nodes.clone(),
            outputs: self.outputs.clone(),
            work: Vec::new(),
            rows: 0,
            layout: None,
            jit: jit::Jit::shared(&self.nodes, &self.outputs, L),
        }
    }
}

impl<const L: usize> TaylorLanes<L> {
    /// Which code runs expansions to `order` now: native code once that order has been
    /// expanded (compiled at its first expansion, or by
    /// [`compile_native`](Self::compile_native)), else the interpreter.
    pub fn backend(&self, order: usize) -> Backend {
        if self.jit.is_native(order) {
            Backend::Native
        } else {
            Backend::Interpreter
        }
    }

    /// Compiles the recurrences up to `order` for `L` lanes now, rather than at the first
    /// expansion of that order, and returns the backend that then runs them:
    /// [`Backend::Interpreter`] without the feature `jit`, in WebAssembly, for an order above
    /// [`MAX_ORDER`], an odd lane count, a program too large to compile quickly, or if
    /// Cranelift cannot compile for this host. Clones share the code.
    pub fn compile_native(&self, order: usize) -> Backend {
        self.jit.code(&self.nodes, &self.outputs, L, order);
        self.backend(order)
    }

    /// [`compile_native`](Self::compile_native) whatever the program's size: what tests
    /// compare with the interpreter on large programs.
    #[doc(hidden)]
    pub fn compile_native_any_size(&self, order: usize) -> Backend {
        self.jit
            .compile(&self.nodes, &self.outputs, L, order, usize::MAX);
        self.backend(order)
    }

    /// Whether the native code of `order` is the code written for AVX
    /// (`symbolic/tape/taylor_asm.rs`) rather than Cranelift's: what tests check to
    /// know which code they compared.
    #[doc(hidden)]
    pub fn written_for_avx(&self, order: usize) -> bool {
        self.jit.is_avx(order)
    }

    /// These lanes with their recurrences compiled by Cranelift alone, even on hosts where
    /// they are otherwise written as AVX code (no code shared with the original): what tests
    /// compare with the interpreter besides the default.
    #[doc(hidden)]
    #[must_use]
    pub fn cranelift_only(&self) -> Self {
        Self {
            jit: jit::Jit::cranelift_only(),
            ..self.clone()
        }
    }

    /// These lanes with their recurrences interpreted for good (no code shared with the
    /// original, none ever compiled): the reference the compiled code is tested against.
    #[doc(hidden)]
    #[must_use]
    pub fn interpreted_only(&self) -> Self {
        Self {
            jit: jit::Jit::never(),
            ..self.clone()
        }
    }
}

/// Whether two programs' nodes and outputs are the same operations on the same operands,
/// constants equal bit for bit.
fn same_recurrences(
    (a_nodes, a_out): (&[Node], &[Val]),
    (b_nodes, b_out): (&[Node], &[Val]),
) -> bool {
    let val_bits = |v: &Val| match *v {
        Val::Node(n) => (0, u64::from(n)),
        Val::Const(c) => (1, c.to_bits()),
    };
    a_nodes.len() == b_nodes.len()
        && a_out.len() == b_out.len()
        && a_nodes
            .iter()
            .zip(b_nodes)
            .all(|(a, b)| node_tag(*a) == node_tag(*b) && a.key() == b.key())
        && a_out
            .iter()
            .zip(b_out)
            .all(|(a, b)| val_bits(a) == val_bits(b))
}

/// Tells apart the nodes that share a key ([`Node::State`], [`Node::Time`] and
/// [`Node::Partner`] all key as zero).
fn node_tag(node: Node) -> u8 {
    match node {
        Node::State => 1,
        Node::Time => 2,
        Node::Partner => 3,
        _ => 0,
    }
}

#[inline(always)]
fn map<const L: usize>(a: [f64; L], f: impl Fn(f64) -> f64) -> [f64; L] {
    let mut out = [0.0; L];
    for (o, x) in out.iter_mut().zip(a) {
        *o = f(x);
    }
    out
}

#[inline(always)]
fn zip<const L: usize>(a: [f64; L], b: [f64; L], f: impl Fn(f64, f64) -> f64) -> [f64; L] {
    let mut out = [0.0; L];
    for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
        *o = f(x, y);
    }
    out
}

/// The scalar weighted sum (`taylor_tape.rs`'s `weighted_sum`) lane by lane:
/// `Σ_{j < k} (w_j a_{k-j}) b_j` in [`ordered_sum`]'s order, `a` and `b` the indices of
/// coefficient 0 of the two series, `lead` terms at each end; `None` for `k = 0`.
#[inline(always)]
fn weighted_sum<const L: usize>(
    lead: usize,
    w: &[[f64; L]],
    weight: Weight,
    a: usize,
    b: usize,
    k: usize,
) -> Option<[f64; L]> {
    let term = |(): &mut (), j: usize| {
        let wj = weight.at(k, j);
        zip(w[a + k - j], w[b + j], |x, y| wj * x * y)
    };
    ordered_sum(&mut (), lead, k, term, |(), s, t| zip(s, t, |x, y| x + y))
}

/// [`cauchy`] lane by lane: `Σ_j a_j b_{n-1-j}` in [`ordered_sum`]'s order with `lead` terms
/// at each end (zeros for empty slices).
#[inline(always)]
fn cauchy_lanes<const L: usize>(lead: usize, a: &[[f64; L]], b: &[[f64; L]]) -> [f64; L] {
    let n = a.len().min(b.len());
    let term = |(): &mut (), j: usize| zip(a[j], b[n - 1 - j], |x, y| x * y);
    ordered_sum(&mut (), lead, n, term, |(), s, t| zip(s, t, |x, y| x + y)).unwrap_or([0.0; L])
}

/// The scalar `mirrored` (`taylor_tape.rs`) lane by lane: `Σ_{lo ≤ j ≤ k - lo} x_j x_{k-j}`,
/// each term with its mirror.
#[inline(always)]
fn mirrored<const L: usize>(
    lead: usize,
    w: &[[f64; L]],
    x: usize,
    lo: usize,
    k: usize,
) -> [f64; L] {
    let n = k.div_ceil(2) - lo;
    let twice = map(
        cauchy_lanes(
            lead,
            &w[x + lo..x + lo + n],
            &w[x + k + 1 - lo - n..x + k + 1 - lo],
        ),
        |v| v * 2.0,
    );
    if k.is_multiple_of(2) {
        let m = map(w[x + k / 2], |v| v * v);
        if n == 0 {
            m
        } else {
            zip(twice, m, |a, b| a + b)
        }
    } else {
        twice
    }
}

/// Orders `0..=order` of every node for `L` states (the state's and time's order 0 set):
/// the lanes form of `TaylorProgram::interpret`.
#[inline(always)]
fn interpret<const L: usize>(
    nodes: &[Node],
    outputs: &[Val],
    w: &mut [[f64; L]],
    order: usize,
    layout: WorkLayout,
) {
    for k in 0..=order {
        order_k(nodes, w, k, layout);
        if k < order {
            let next = 1.0 / (k + 1) as f64;
            for (i, out) in outputs.iter().enumerate() {
                let fk = match *out {
                    Val::Node(n) => w[layout.at(n as usize, k)],
                    Val::Const(c) if k == 0 => [c; L],
                    Val::Const(_) => [0.0; L],
                };
                w[layout.at(i, k + 1)] = map(fk, |x| x * next);
            }
        }
    }
}

/// Order `k` of every operation node for `L` states: `TaylorProgram::order_k` with every
/// value an `[f64; L]`, each lane's operations those of the scalar code in its order.
#[inline(always)]
#[allow(clippy::too_many_lines)]
fn order_k<const L: usize>(nodes: &[Node], w: &mut [[f64; L]], k: usize, layout: WorkLayout) {
    let at = |n: u32, j: usize| layout.at(n as usize, j);
    let lead = layout.lead();
    let kf = k as f64;
    for (i, &node) in nodes.iter().enumerate() {
        let me = layout.at(i, 0);
        let value = match node {
            Node::State | Node::Time | Node::Partner => continue,
            Node::Add(a, b) => zip(w[at(a, k)], w[at(b, k)], |x, y| x + y),
            Node::Sub(a, b) => zip(w[at(a, k)], w[at(b, k)], |x, y| x - y),
            Node::AddC(a, c) => {
                if k == 0 {
                    map(w[at(a, 0)], |x| x + c)
                } else {
                    w[at(a, k)]
                }
            }
            Node::CSub(c, a) => {
                if k == 0 {
                    map(w[at(a, 0)], |x| c - x)
                } else {
                    map(w[at(a, k)], |x| -x)
                }
            }
            Node::MulC(a, c) => map(w[at(a, k)], |x| c * x),
            Node::Neg(a) => map(w[at(a, k)], |x| -x),
            Node::Abs(a) => zip(
                w[at(a, 0)],
                w[at(a, k)],
                |v, x| if v < 0.0 { -x } else { x },
            ),
            Node::Mul(a, b) => {
                let (a, b) = (at(a, 0), at(b, 0));
                cauchy_lanes(lead, &w[a..=a + k], &w[b..=b + k])
            }
            Node::Square(a) => mirrored(lead, w, at(a, 0), 0, k),
            Node::Div(a, b) => {
                let b = at(b, 0);
                if k == 0 {
                    zip(w[at(a, 0)], w[b], |x, y| x / y)
                } else {
                    let s = cauchy_lanes(lead, &w[b + 1..=b + k], &w[me..me + k]);
                    let d = zip(w[at(a, k)], s, |x, y| x - y);
                    zip(d, w[b], |x, y| x / y)
                }
            }
            Node::CDiv(c, a) => {
                let a = at(a, 0);
                if k == 0 {
                    map(w[a], |x| c / x)
                } else {
                    let s = cauchy_lanes(lead, &w[a + 1..=a + k], &w[me..me + k]);
                    zip(s, w[a], |x, y| -x / y)
                }
            }
            Node::Sqrt(a) => {
                if k == 0 {
                    map(w[at(a, 0)], f64::sqrt)
                } else {
                    let s = zip(w[at(a, k)], mirrored(lead, w, me, 1, k), |x, y| x - y);
                    zip(s, w[me], |x, y| x / (2.0 * y))
                }
            }
            Node::Powf(a, alpha) => {
                let a = at(a, 0);
                if k == 0 {
                    map(w[a], |x| power0(x, alpha))
                } else {
                    let s = weighted_sum(lead, w, Weight::Power(alpha), a, me, k);
                    zip(s.unwrap_or([0.0; L]), w[a], |x, y| x / (kf * y))
                }
            }
            Node::Derivative(a) => {
                if k == 0 {
                    w[at(a, 0)]
                } else {
                    map(w[at(a, k)], |x| kf * x)
                }
            }
            Node::Exp(d) => {
                let d = at(d, 0);
                if k == 0 {
                    map(w[d], f64::exp)
                } else {
                    let s = cauchy_lanes(lead, &w[me..me + k], &w[d + 1..=d + k]);
                    let rk = 1.0 / kf;
                    map(s, |x| x * rk)
                }
            }
            Node::Integral { a, d, sign, func } => {
                let (a, d) = (at(a, 0), at(d, 0));
                if k == 0 {
                    map(w[a], |x| func_value(func, x))
                } else {
                    let s = map(w[a + k], |x| sign * kf * x);
                    let s = match weighted_sum(lead, w, Weight::Falling, me, d + 1, k - 1) {
                        Some(t) => zip(s, t, |x, y| x - y),
                        None => s,
                    };
                    zip(s, w[d], |x, y| x / (kf * y))
                }
            }
            Node::SinCos(d, hyperbolic) => {
                let d = at(d, 0);
                let partner = layout.at(i + 1, 0);
                if k == 0 {
                    let x = w[d];
                    let (s, c) = if hyperbolic {
                        (map(x, f64::sinh), map(x, f64::cosh))
                    } else {
                        (map(x, f64::sin), map(x, f64::cos))
                    };
                    w[partner] = c;
                    s
                } else {
                    let slopes = &w[d + 1..=d + k];
                    let s = cauchy_lanes(lead, &w[partner..partner + k], slopes);
                    let c = cauchy_lanes(lead, &w[me..me + k], slopes);
                    let rk = 1.0 / kf;
                    w[partner + k] = if hyperbolic {
                        map(c, |x| x * rk)
                    } else {
                        map(c, |x| -x * rk)
                    };
                    map(s, |x| x * rk)
                }
            }
        };
        w[me + k] = value;
    }
}

/// [`interpret`] compiled with AVX-512 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn interpret_avx512<const L: usize>(
    nodes: &[Node],
    outputs: &[Val],
    w: &mut [[f64; L]],
    order: usize,
    layout: WorkLayout,
) {
    interpret(nodes, outputs, w, order, layout);
}

/// [`interpret`] compiled with AVX2 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn interpret_avx2<const L: usize>(
    nodes: &[Node],
    outputs: &[Val],
    w: &mut [[f64; L]],
    order: usize,
    layout: WorkLayout,
) {
    interpret(nodes, outputs, w, order, layout);
}

/// The lanes an ensemble runs on this CPU: two vector registers' worth (see the module
/// documentation), 16 with AVX-512, 8 with AVX2, 4 otherwise.
pub fn native_lanes() -> usize {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            return 16;
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            return 8;
        }
    }
    4
}

impl<const L: usize> LanesField<L> for TaylorLanes<L> {
    fn dim(&self) -> usize {
        self.dim
    }

    fn step_cost(&self) -> StepCost {
        super::step_cost(self.dim, &self.nodes)
    }

    fn expand(&mut self, t: &[f64; L], y: &[[f64; L]], order: usize) -> Result<()> {
        if order > MAX_ORDER || y.len() != self.dim {
            return Err(Error::invalid(
                "order",
                order as f64,
                format!(
                    "a Taylor expansion takes an order <= {MAX_ORDER} and a state of {}",
                    self.dim
                ),
            ));
        }
        let layout = WorkLayout::of_order(&mut self.layout, &self.nodes, self.dim, order);
        let size = layout.blocks_start();
        if self.work.len() != size {
            self.work = vec![[0.0; L]; size];
        }
        for (i, yi) in y.iter().enumerate() {
            self.work[layout.at(i, 0)] = *yi;
        }
        // The time's series is `t + τ`; its orders from 2 on are the allocation's zeros.
        let time = layout.at(self.dim, 0);
        self.rows = time;
        self.work[time] = *t;
        if order >= 1 {
            self.work[time + 1] = [1.0; L];
        }
        if let Some(code) = self.jit.code(&self.nodes, &self.outputs, L, order) {
            code.call(&mut self.work);
            return Ok(());
        }
        let (nodes, outputs, w) = (&self.nodes[..], &self.outputs[..], &mut self.work[..]);
        #[cfg(target_arch = "x86_64")]
        {
            if L >= 8 && std::arch::is_x86_feature_detected!("avx512f") {
                // SAFETY: the CPU has AVX-512F (checked just above), the one feature the
                // function enables.
                #[allow(unsafe_code)]
                unsafe {
                    interpret_avx512(nodes, outputs, w, order, layout);
                }
                return Ok(());
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the one feature the function
                // enables.
                #[allow(unsafe_code)]
                unsafe {
                    interpret_avx2(nodes, outputs, w, order, layout);
                }
                return Ok(());
            }
        }
        interpret(nodes, outputs, w, order, layout);
        Ok(())
    }

    /// The state's rows, which come first in the work array (empty before the first
    /// expansion).
    fn coefficients(&self) -> &[[f64; L]] {
        &self.work[..self.rows]
    }
}
