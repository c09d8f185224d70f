//! [`TaylorProgram`]: an expression-defined vector field compiled into Taylor-coefficient
//! recurrences, the field of the adaptive Taylor method
//! ([`integrators::taylor`](crate::classical::integrators::taylor)).
//!
//! Compilation walks the expression trees bottom-up, as the [`Tape`](super::Tape) does: every
//! distinct operation gets one node (hash-consing, so a subexpression shared between
//! components, such as `cos(q0 - q1)` or `r^-3`, is expanded once), operations on constants
//! are folded and parameters become constants. Constant factors are carried beside the values
//! while building and moved out of products, quotients, negations and sums (`c a + c b =
//! c (a + b)`), and the operands of `+` and `×` are put in one order: values that differ by a
//! constant factor or the order of their operands share their nodes, and a factor is written
//! out (one multiplication per order) only where a sum, a function or an output needs it.
//! A sum's terms that are one monomial up to a constant factor (the same factors' nodes, in
//! any order) are merged, and dropped where they cancel, as the terms of `∂L/∂q` and
//! `d/dt ∂L/∂qdot` of a kinetic energy quadratic in `qdot` do; the factors of a product or
//! quotient that are powers of one base (`√a`, `a^α`, `a²`, `c / a` of one node `a`) with
//! exponents adding up to a non-integer are one power of it (`r^-1 · r^-1 / r` with `r =
//! √(x² + y²)` is `(x² + y²)^-3/2`). A program is built with these merges and without, and
//! the smaller kept: a merge rewrites a sum in place, which can duplicate partial sums that
//! other expressions share. Nodes that no output needs are removed. A Lagrangian quadratic
//! in `qdot` also gives Hamilton's equations on `(q, p)` with the velocities `w = M^-1 p`
//! solved for once and shared ([`TaylorProgram::lagrangian_canonical`]).
//! Each node holds a truncated power series; order `k` of every node follows from orders
//! `< k` of its operands by one recurrence per operation (automatic differentiation of
//! truncated series; Jorba & Zou, *Exp. Math.* 14 (2005) 99, §3; Griewank & Walther,
//! *Evaluating Derivatives*, ch. 13):
//!
//! - `a ± b`, `c a`: term by term; `a b`: the Cauchy product; `a / b`, `√a`: the product
//!   solved for the new term;
//! - `a^α` (`α` real): from `a c' = α a' c`; integer powers are products (exact at `a = 0`);
//!   `a^b = exp(b ln a)`;
//! - `exp a`: from `c' = a' c`; `ln a`, `atan a`, `asin a`, `acos a`: from `d c' = ±a'` with
//!   `d = a`, `1 + a²`, `√(1 - a²)`;
//! - `sin`/`cos` (and `sinh`/`cosh`) as a pair, each from the other's lower orders; `tan`,
//!   `tanh` are their quotients; `|a|` is `±a` by the sign of `a`'s value.
//!
//! The state's coefficients then follow from the field's: `y^[k+1] = f^[k] / (k + 1)`, taken
//! as `f^[k] · (1/(k + 1))`, the reciprocal rounded once: a multiplication where a division
//! would hold up the expansion (a division's throughput is a quarter to an eighth of a
//! multiplication's, and every output takes one per order), for at most an ulp more rounding
//! than the division's half. The `1/k` of the `exp` and `sin`/`cos` recurrences is taken the
//! same way; divisions by a series' value (quotients, powers, `sqrt`, the integrals) stay.
//!
//! A series that is undefined at the point (division by a zero value, a power or logarithm of
//! zero) gives non-finite coefficients, which the stepper refuses with an error.

use super::expr::{Expr, ExprLagrangian, Func};
use super::expr_diff::Var;
use super::expr_hamiltonian::ExprHamiltonian;
use super::expr_ode::ExprOde;
use super::hash_cons::{HashCons, Keyed};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::taylor::{InBlocks, StepCost, TaylorField, LANES, MAX_ORDER};
use crate::classical::integrators::HamiltonianSystem;
use crate::classical::lagrangian::Lagrangian;
use std::collections::HashMap;

use super::tape::Backend;

#[cfg(all(feature = "jit", not(target_arch = "wasm32")))]
#[path = "tape/taylor_jit.rs"]
mod jit;
#[cfg(not(all(feature = "jit", not(target_arch = "wasm32"))))]
#[path = "tape/taylor_interpreted.rs"]
mod jit;
#[path = "tape/taylor_lanes.rs"]
mod lanes;
pub use lanes::{native_lanes, TaylorLanes};

/// An operand: a node's series or a constant.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Val {
    Node(u32),
    Const(f64),
}

/// One operation of the recurrences; operands are node indices.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Node {
    /// A state component (its series comes from the field's outputs).
    State,
    /// The time: `t + τ`.
    Time,
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    AddC(u32, f64),
    /// `c - a`
    CSub(f64, u32),
    MulC(u32, f64),
    /// `c / a`
    CDiv(f64, u32),
    Neg(u32),
    Square(u32),
    Sqrt(u32),
    Powf(u32, f64),
    /// `exp a` of a [`Node::Derivative`] `a`.
    Exp(u32),
    /// `a_0`, then `k a_k` at order `k`: the series `a_0 + τ a'(τ)`, whose orders from 1 on are
    /// the factors the sums of `exp a`, `sin a` and `cos a` take from `a` (`Σ i a_i b_{k-i}`),
    /// each rounded once and shared by every function of `a`; its order 0 is their value's
    /// argument.
    Derivative(u32),
    /// `c` with `d c' = sign a'`: `ln` (`d = a`), `atan` (`1 + a²`), `asin`, `acos`
    /// (`√(1 - a²)`, `acos` with sign −1); `Func` gives the value.
    Integral {
        a: u32,
        d: u32,
        sign: f64,
        func: Func,
    },
    /// `sin a` here, `cos a` in the next node (or `sinh`/`cosh` when `hyperbolic`), of a
    /// [`Node::Derivative`] `a`.
    SinCos(u32, bool),
    /// The second of a [`Node::SinCos`] pair: computed with it.
    Partner,
    /// `|a|`: `a` times the sign of its value.
    Abs(u32),
}

/// Hash key of a node (floats by their bits).
type Key = (u8, u32, u32, u64);

impl Keyed for Node {
    type Key = Key;

    fn key(self) -> Key {
        match self {
            Node::State | Node::Time | Node::Partner => (0, 0, 0, 0),
            Node::Add(a, b) => (1, a, b, 0),
            Node::Sub(a, b) => (2, a, b, 0),
            Node::Mul(a, b) => (3, a, b, 0),
            Node::Div(a, b) => (4, a, b, 0),
            Node::AddC(a, c) => (5, a, 0, c.to_bits()),
            Node::CSub(c, a) => (6, a, 0, c.to_bits()),
            Node::MulC(a, c) => (7, a, 0, c.to_bits()),
            Node::CDiv(c, a) => (8, a, 0, c.to_bits()),
            Node::Neg(a) => (9, a, 0, 0),
            Node::Square(a) => (10, a, 0, 0),
            Node::Sqrt(a) => (11, a, 0, 0),
            Node::Powf(a, x) => (12, a, 0, x.to_bits()),
            Node::Exp(a) => (13, a, 0, 0),
            Node::Integral { a, d, sign, func } => (14 + func as u8, a, d, sign.to_bits()),
            Node::SinCos(a, hyperbolic) => (40, a, u32::from(hyperbolic), 0),
            Node::Abs(a) => (41, a, 0, 0),
            Node::Derivative(a) => (42, a, 0, 0),
        }
    }
}

impl Node {
    /// The terms of this node's sum at order `k`, one for a node without a sum (a sum, a
    /// scaling, a sign), none for the state, the time and a sine's partner (computed with it):
    /// what the recurrences' work ([`step_cost`]) and their unrolled code's size grow with.
    pub(super) fn sum_terms(self, k: usize) -> usize {
        match self {
            Node::State | Node::Time | Node::Partner => 0,
            Node::Mul(..) => k + 1,
            Node::Square(_) => k / 2 + 1,
            Node::Sqrt(_) => (k / 2).max(1),
            Node::Div(..)
            | Node::CDiv(..)
            | Node::Powf(..)
            | Node::Exp(_)
            | Node::Integral { .. } => k.max(1),
            Node::SinCos(..) => 2 * k.max(1),
            Node::Add(..)
            | Node::Sub(..)
            | Node::AddC(..)
            | Node::CSub(..)
            | Node::MulC(..)
            | Node::Neg(_)
            | Node::Abs(_)
            | Node::Derivative(_) => 1,
        }
    }

    /// Multiply-adds per term of [`sum_terms`](Self::sum_terms), and besides the sum at each
    /// order: a power's and an integral's terms take a weight and two products, an
    /// exponential's and a sine–cosine pair's (two sums) one product each (their weights are
    /// a [`Node::Derivative`]'s); a division (of a quotient, a power, a square root, an
    /// integral) counts as four.
    fn work_per_term(self) -> (f64, f64) {
        match self {
            Node::Powf(..) | Node::Integral { .. } => (2.0, 4.0),
            Node::Div(..) | Node::CDiv(..) | Node::Sqrt(_) => (1.0, 4.0),
            Node::Exp(_) => (1.0, 1.0),
            Node::SinCos(..) => (2.0, 0.0),
            _ => (1.0, 0.0),
        }
    }

    /// The node with each operand `a` replaced by `f(a)` (called on every operand).
    fn map_operands(self, mut f: impl FnMut(u32) -> u32) -> Node {
        match self {
            Node::State | Node::Time | Node::Partner => self,
            Node::Add(a, b) => Node::Add(f(a), f(b)),
            Node::Sub(a, b) => Node::Sub(f(a), f(b)),
            Node::Mul(a, b) => Node::Mul(f(a), f(b)),
            Node::Div(a, b) => Node::Div(f(a), f(b)),
            Node::AddC(a, c) => Node::AddC(f(a), c),
            Node::CSub(c, a) => Node::CSub(c, f(a)),
            Node::MulC(a, c) => Node::MulC(f(a), c),
            Node::CDiv(c, a) => Node::CDiv(c, f(a)),
            Node::Neg(a) => Node::Neg(f(a)),
            Node::Square(a) => Node::Square(f(a)),
            Node::Sqrt(a) => Node::Sqrt(f(a)),
            Node::Powf(a, x) => Node::Powf(f(a), x),
            Node::Exp(a) => Node::Exp(f(a)),
            Node::Integral { a, d, sign, func } => Node::Integral {
                a: f(a),
                d: f(d),
                sign,
                func,
            },
            Node::SinCos(a, hyperbolic) => Node::SinCos(f(a), hyperbolic),
            Node::Abs(a) => Node::Abs(f(a)),
            Node::Derivative(a) => Node::Derivative(f(a)),
        }
    }
}

/// The work array of the recurrences at one order: every node's coefficients, `order + 1`
/// per node (the state's rows first, then the time's), then the state's coefficients again,
/// side by side in the stepper's blocks of [`LANES`] rows
/// ([`TaylorField::expansion_in_blocks`]), which only the code written for AVX fills (each
/// coefficient stored twice, so that the stepper need not transpose the rows).
#[derive(Debug, Clone, Copy)]
pub(super) struct WorkLayout {
    nodes: usize,
    dim: usize,
    stride: usize,
    /// The terms at each end of a sum outside its groups ([`WorkLayout::lead`]).
    lead: usize,
}

impl WorkLayout {
    /// The layout of the recurrences of `nodes` (the state's `dim` rows first) to `order`.
    fn new(nodes: &[Node], dim: usize, order: usize) -> Self {
        Self {
            nodes: nodes.len(),
            dim,
            stride: order + 1,
            lead: if pass_work(nodes, order) >= LONG_PASS {
                1
            } else {
                2
            },
        }
    }

    /// The layout of `order` kept in `last` (the layout of the last expansion), made and kept
    /// there if it is of another order or none: what an expansion takes, so that a run's
    /// steps, all of one order, read the nodes for the lead once.
    fn of_order(last: &mut Option<Self>, nodes: &[Node], dim: usize, order: usize) -> Self {
        match *last {
            Some(layout) if layout.stride == order + 1 => layout,
            _ => *last.insert(Self::new(nodes, dim, order)),
        }
    }

    /// The index of coefficient `j` of node `n`: every node's coefficients side by side,
    /// node by node (the state's rows are nodes `0..dim`, the time node `dim`).
    #[inline(always)]
    pub(super) fn at(self, n: usize, j: usize) -> usize {
        n * self.stride + j
    }

    /// Where the blocks start: after every node's coefficients.
    pub(super) fn blocks_start(self) -> usize {
        self.at(self.nodes, 0)
    }

    pub(super) fn len(self) -> usize {
        self.blocks_start() + self.dim.div_ceil(LANES) * self.stride * LANES
    }

    /// The index of coefficient `j` of the state's row `i` in the blocks (for the code written
    /// for AVX, the one writer of the blocks).
    #[cfg(all(feature = "jit", target_arch = "x86_64", not(windows)))]
    pub(super) fn in_blocks(self, i: usize, j: usize) -> usize {
        self.blocks_start() + self.at(i / LANES, j) * LANES + i % LANES
    }
}

/// An expression field compiled into Taylor recurrences (see the module documentation).
#[derive(Debug, Clone)]
pub struct TaylorProgram {
    dim: usize,
    nodes: Vec<Node>,
    outputs: Vec<Val>,
    /// Coefficients of every node, `stride` per node, then the state's in blocks
    /// ([`WorkLayout`]); sized at the first expansion of an order and reused (no allocation
    /// per step).
    work: Vec<f64>,
    /// The layout of the last expansion's order, kept for the next expansion of that order
    /// (its lead reads every node: [`pass_work`]).
    layout: Option<WorkLayout>,
    /// Native code of the recurrences per order, once compiled; shared by clones.
    jit: jit::Jit,
}

struct Builder<'a> {
    n_first: usize,
    n_second: usize,
    params: &'a [f64],
    nodes: HashCons<Node>,
    /// What `qdot_i` stands for when it is not a state component: the velocities
    /// `w = M^-1 (p - b)` of [`TaylorProgram::lagrangian_canonical`].
    velocity: Option<Vec<Scaled>>,
    /// The values of the subexpressions of the expression being compiled, by address.
    memo: HashMap<*const Expr, Scaled>,
    /// Whether like terms of sums and powers of one base in products are merged (see
    /// `TaylorProgram::smaller_of`).
    merge: bool,
}

thread_local! {
    /// Off inside [`TaylorProgram::without_merging`].
    static MERGE: std::cell::Cell<bool> = const { std::cell::Cell::new(true) };
}

/// The shape of a sum (its `Add`, `Sub` and `Neg` nodes) over its terms, numbered in the
/// order they are met: the terms are added in this association when none of them merge.
enum SumTree {
    Term(usize),
    Add(Vec<SumTree>),
    Sub(Box<SumTree>, Box<SumTree>),
    Neg(Box<SumTree>),
}

/// A sum's terms and the tree that adds them.
fn sum_tree<'e>(e: &'e Expr, terms: &mut Vec<(&'e Expr, f64)>, sign: f64) -> SumTree {
    match e {
        Expr::Add(v) => SumTree::Add(v.iter().map(|t| sum_tree(t, terms, sign)).collect()),
        Expr::Sub(a, b) => SumTree::Sub(
            Box::new(sum_tree(a, terms, sign)),
            Box::new(sum_tree(b, terms, -sign)),
        ),
        Expr::Neg(a) => SumTree::Neg(Box::new(sum_tree(a, terms, -sign))),
        e => {
            terms.push((e, sign));
            SumTree::Term(terms.len() - 1)
        }
    }
}

/// A value while the program is built: a constant, or a node's series times a constant factor.
/// The factor is kept apart until an operation needs the product itself, so that constant
/// factors fold into one, move out through products, quotients and negations, and values
/// that differ by a factor share their node (`2 x` and `-x` are `x`; the double pendulum's
/// `∂H/∂q0` and `∂H/∂q1` share the products in which they differ only by sign).
#[derive(Debug, Clone, Copy)]
enum Scaled {
    Const(f64),
    Node(u32, f64),
}

impl From<u32> for Scaled {
    fn from(node: u32) -> Self {
        Scaled::Node(node, 1.0)
    }
}

// Exact comparisons: recognizing the factors 1 and -1 and equal factors.
#[allow(clippy::float_cmp)]
impl Builder<'_> {
    fn node(&mut self, node: Node) -> u32 {
        let (i, new) = self.nodes.intern(node);
        if let (Node::SinCos(..), true) = (node, new) {
            self.nodes.items.push(Node::Partner);
        }
        i
    }

    /// The value as an operand of the recurrences: the node times its factor written out (a
    /// negation for -1, nothing for 1).
    fn val(&mut self, v: Scaled) -> Val {
        match v {
            Scaled::Const(c) => Val::Const(c),
            Scaled::Node(a, c) => Val::Node(self.materialize(a, c)),
        }
    }

    fn materialize(&mut self, a: u32, c: f64) -> u32 {
        if c == 1.0 {
            a
        } else if c == -1.0 {
            self.node(Node::Neg(a))
        } else {
            self.node(Node::MulC(a, c))
        }
    }

    /// `a + b`. Commutative operations take their operands in one order (so `x + y` and
    /// `y + x` are one node), and the factor of the first is moved out of the sum:
    /// `c a + e b = c (a + (e/c) b)`, which is `c (a ± b)` when `e = ±c`.
    fn add(&mut self, a: Scaled, b: Scaled) -> Scaled {
        match (a, b) {
            (Scaled::Const(x), Scaled::Const(y)) => Scaled::Const(x + y),
            (Scaled::Node(a, c), Scaled::Const(k)) | (Scaled::Const(k), Scaled::Node(a, c)) => {
                if k == 0.0 {
                    Scaled::Node(a, c)
                } else if c == -1.0 {
                    self.node(Node::CSub(k, a)).into()
                } else {
                    let a = self.materialize(a, c);
                    self.node(Node::AddC(a, k)).into()
                }
            }
            (Scaled::Node(a, ca), Scaled::Node(b, cb)) if a == b => {
                if ca + cb == 0.0 {
                    Scaled::Const(0.0)
                } else {
                    Scaled::Node(a, ca + cb)
                }
            }
            (Scaled::Node(a, ca), Scaled::Node(b, cb)) => {
                let ((lo, cl), (hi, ch)) = if a < b {
                    ((a, ca), (b, cb))
                } else {
                    ((b, cb), (a, ca))
                };
                if ch == cl {
                    return Scaled::Node(self.node(Node::Add(lo, hi)), cl);
                }
                if ch == -cl {
                    return Scaled::Node(self.node(Node::Sub(lo, hi)), cl);
                }
                let ratio = ch / cl;
                if ratio.is_finite() && ratio != 0.0 {
                    let hi = self.materialize(hi, ratio);
                    Scaled::Node(self.node(Node::Add(lo, hi)), cl)
                } else {
                    let (lo, hi) = (self.materialize(lo, cl), self.materialize(hi, ch));
                    self.node(Node::Add(lo, hi)).into()
                }
            }
        }
    }

    fn neg(v: Scaled) -> Scaled {
        match v {
            Scaled::Const(c) => Scaled::Const(-c),
            Scaled::Node(a, c) => Scaled::Node(a, -c),
        }
    }

    fn sub(&mut self, a: Scaled, b: Scaled) -> Scaled {
        self.add(a, Self::neg(b))
    }

    fn mul(&mut self, a: Scaled, b: Scaled) -> Scaled {
        match (a, b) {
            (Scaled::Const(x), Scaled::Const(y)) => Scaled::Const(x * y),
            // A zero factor: the term drops out (`0 x` is 0 for every finite `x`).
            (Scaled::Node(_, _), Scaled::Const(k)) | (Scaled::Const(k), Scaled::Node(_, _))
                if k == 0.0 =>
            {
                Scaled::Const(0.0)
            }
            (Scaled::Node(a, c), Scaled::Const(k)) | (Scaled::Const(k), Scaled::Node(a, c)) => {
                Scaled::Node(a, c * k)
            }
            (Scaled::Node(a, ca), Scaled::Node(b, cb)) if a == b => {
                Scaled::Node(self.node(Node::Square(a)), ca * cb)
            }
            // The later node first: the Cauchy product's sum starts with `a_0 b_k` and ends
            // with `a_k b_0`, so the coefficient computed last in the same order enters last.
            (Scaled::Node(a, ca), Scaled::Node(b, cb)) => {
                Scaled::Node(self.node(Node::Mul(a.max(b), a.min(b))), ca * cb)
            }
        }
    }

    fn div(&mut self, a: Scaled, b: Scaled) -> Scaled {
        match (a, b) {
            (Scaled::Const(x), Scaled::Const(y)) => Scaled::Const(x / y),
            (Scaled::Node(a, c), Scaled::Const(k)) => Scaled::Node(a, c / k),
            (Scaled::Const(k), Scaled::Node(a, c)) => self.node(Node::CDiv(k / c, a)).into(),
            (Scaled::Node(a, ca), Scaled::Node(b, cb)) => {
                Scaled::Node(self.node(Node::Div(a, b)), ca / cb)
            }
        }
    }

    /// A function of one operand with no rule for its factor: the factor is written out.
    fn unary(
        &mut self,
        a: Scaled,
        value: impl Fn(f64) -> f64,
        node: impl Fn(u32) -> Node,
    ) -> Scaled {
        match self.val(a) {
            Val::Const(x) => Scaled::Const(value(x)),
            Val::Node(a) => self.node(node(a)).into(),
        }
    }

    /// `a^n` by repeated squaring (products: exact where `a` vanishes).
    fn powi(&mut self, a: Scaled, n: i32) -> Scaled {
        if let Scaled::Const(x) = a {
            return Scaled::Const(x.powi(n));
        }
        let mut m = n.unsigned_abs();
        let mut result = Scaled::Const(1.0);
        let mut base = a;
        while m > 0 {
            if m & 1 == 1 {
                result = self.mul(result, base);
            }
            m >>= 1;
            if m > 0 {
                base = self.mul(base, base);
            }
        }
        if n < 0 {
            self.div(Scaled::Const(1.0), result)
        } else {
            result
        }
    }

    /// `a^x`; a positive factor moves out as `c^x`.
    // Exact comparisons: recognizing integer and half-integer exponents.
    fn powf(&mut self, a: Scaled, x: f64) -> Scaled {
        if x == x.trunc() && x.abs() <= 64.0 {
            return self.powi(a, x as i32);
        }
        match a {
            Scaled::Node(n, c) if c > 0.0 && c != 1.0 => {
                let power = self.powf(n.into(), x);
                self.mul(power, Scaled::Const(c.powf(x)))
            }
            _ if x == 0.5 => self.unary(a, f64::sqrt, Node::Sqrt),
            _ => self.unary(a, |v| v.powf(x), |a| Node::Powf(a, x)),
        }
    }

    fn exp(&mut self, a: Scaled) -> Scaled {
        match self.val(a) {
            Val::Const(x) => Scaled::Const(x.exp()),
            Val::Node(a) => {
                let d = self.node(Node::Derivative(a));
                self.node(Node::Exp(d)).into()
            }
        }
    }

    fn integral(&mut self, a: Scaled, d: Scaled, sign: f64, func: Func) -> Scaled {
        match (self.val(a), self.val(d)) {
            (Val::Node(a), Val::Node(d)) => self.node(Node::Integral { a, d, sign, func }).into(),
            (Val::Const(x), _) => Scaled::Const(func_value(func, x)),
            // `d` is a function of `a`: constant only when `a` is.
            (Val::Node(_), Val::Const(_)) => unreachable_const(),
        }
    }

    fn sin_cos(&mut self, a: Scaled, hyperbolic: bool) -> (Scaled, Scaled) {
        match self.val(a) {
            Val::Const(x) if hyperbolic => (Scaled::Const(x.sinh()), Scaled::Const(x.cosh())),
            Val::Const(x) => (Scaled::Const(x.sin()), Scaled::Const(x.cos())),
            Val::Node(a) => {
                let d = self.node(Node::Derivative(a));
                let s = self.node(Node::SinCos(d, hyperbolic));
                (s.into(), (s + 1).into())
            }
        }
    }

    fn func(&mut self, f: Func, a: Scaled) -> Scaled {
        match f {
            Func::Sin => self.sin_cos(a, false).0,
            Func::Cos => self.sin_cos(a, false).1,
            Func::Sinh => self.sin_cos(a, true).0,
            Func::Cosh => self.sin_cos(a, true).1,
            Func::Tan | Func::Tanh => {
                let (s, c) = self.sin_cos(a, f == Func::Tanh);
                self.div(s, c)
            }
            Func::Exp => self.exp(a),
            Func::Sqrt => self.powf(a, 0.5),
            // |c a| = |c| |a|
            Func::Abs => match a {
                Scaled::Node(n, c) => Scaled::Node(self.node(Node::Abs(n)), c.abs()),
                Scaled::Const(x) => Scaled::Const(x.abs()),
            },
            Func::Ln => self.integral(a, a, 1.0, Func::Ln),
            Func::Atan => {
                let a2 = self.mul(a, a);
                let d = self.add(a2, Scaled::Const(1.0));
                self.integral(a, d, 1.0, Func::Atan)
            }
            Func::Asin | Func::Acos => {
                let a2 = self.mul(a, a);
                let one_minus = self.sub(Scaled::Const(1.0), a2);
                let d = self.unary(one_minus, f64::sqrt, Node::Sqrt);
                let sign = if f == Func::Asin { 1.0 } else { -1.0 };
                self.integral(a, d, sign, f)
            }
        }
    }

    /// A product as written (its factors in order, nested products first).
    fn product(&mut self, v: &[Expr]) -> Result<Scaled> {
        let mut acc = Scaled::Const(1.0);
        for (i, factor) in v.iter().enumerate() {
            let b = self.compile(factor)?;
            acc = if i == 0 { b } else { self.mul(acc, b) };
        }
        Ok(acc)
    }

    /// A product or quotient, first compiled as written (as a builder that merges nothing
    /// compiles it: the same nodes in the same order); then, where two or more of its
    /// factors (nested products, quotients and negations flattened) are powers of one base
    /// whose exponents add up to a non-integer `E` (`r^-1 · r^-1/2 / r^1/2`, with `r` itself
    /// `(x² + y²)^1/2`, is `(x² + y²)^-3/2`), with those factors replaced by the one power
    /// `b^E` (the product as written is left to the removal of unused nodes). A
    /// non-integer `E` keeps the domain (`b ≥ 0`, where every factor's non-integer power is
    /// real) and costs one node; an integer one would define the product where a factor was
    /// not (`√b · √b` at `b < 0`), so those factors stay.
    fn product_or_quotient(&mut self, e: &Expr) -> Result<Scaled> {
        let written = match e {
            Expr::Div(a, b) => {
                let (a, b) = (self.compile(a)?, self.compile(b)?);
                self.div(a, b)
            }
            Expr::Mul(v) => self.product(v)?,
            _ => unreachable_const(),
        };
        if !self.merge {
            return Ok(written);
        }
        // The factors' values are the memo's: compiling the product as written compiled them.
        let mut leaves = Vec::new();
        let mut constant = 1.0;
        flatten_product(e, 1, &mut leaves, &mut constant);
        // Each factor as (node, its factor, exponent ±1), and as a power `k b^x` of a base.
        let mut items = Vec::with_capacity(leaves.len());
        for (leaf, sign) in leaves {
            match self.compile(leaf)? {
                Scaled::Const(c) => constant *= if sign > 0 { c } else { 1.0 / c },
                Scaled::Node(n, c) => {
                    let (base, x, k) = self.power_of(n);
                    items.push((n, c, sign, base, x * f64::from(sign), k));
                }
            }
        }
        // The exponent of each base that two or more factors share, where it is not an
        // integer.
        let mut merged: Vec<(u32, f64)> = Vec::new();
        for (i, item) in items.iter().enumerate() {
            let base = item.3;
            if merged.iter().any(|m| m.0 == base) {
                continue;
            }
            let (count, exponent) = items[i..]
                .iter()
                .filter(|o| o.3 == base)
                .fold((0, 0.0), |(n, sum), o| (n + 1, sum + o.4));
            if count > 1 && exponent != exponent.trunc() {
                merged.push((base, exponent));
            }
        }
        if merged.is_empty() {
            return Ok(written);
        }
        let mut numerator = Scaled::Const(constant);
        let mut denominator = Scaled::Const(1.0);
        let mut emitted = Vec::new();
        for &(n, c, sign, base, _, k) in &items {
            match merged.iter().find(|m| m.0 == base) {
                Some(&(_, exponent)) => {
                    let factor = if sign > 0 { c * k } else { 1.0 / (c * k) };
                    numerator = self.mul(numerator, Scaled::Const(factor));
                    if !emitted.contains(&base) {
                        emitted.push(base);
                        let power = self.powf(base.into(), exponent);
                        numerator = self.mul(numerator, power);
                    }
                }
                None if sign > 0 => numerator = self.mul(numerator, Scaled::Node(n, c)),
                None => denominator = self.mul(denominator, Scaled::Node(n, c)),
            }
        }
        Ok(self.div(numerator, denominator))
    }

    /// Node `n` as a power `k b^x` of a base node `b` (through `√`, `a^α`, `a²` and `c / a`),
    /// or `(n, 1, 1)`. A power of a power composes only where the identity holds wherever
    /// the outer one is defined: not through an even integer power (`√(a²)` is `|a|`).
    fn power_of(&self, n: u32) -> (u32, f64, f64) {
        let of_power = |this: &Self, a: u32, alpha: f64| {
            let (b, x, k) = this.power_of(a);
            let even = x == x.trunc() && (x / 2.0) == (x / 2.0).trunc();
            if k == 1.0 && !even {
                (b, x * alpha, 1.0)
            } else {
                (a, alpha, 1.0)
            }
        };
        match self.nodes.items[n as usize] {
            Node::Sqrt(a) => of_power(self, a, 0.5),
            Node::Powf(a, alpha) => of_power(self, a, alpha),
            Node::Square(a) => {
                let (b, x, k) = self.power_of(a);
                (b, 2.0 * x, k * k)
            }
            Node::CDiv(c, a) => {
                let (b, x, k) = self.power_of(a);
                (b, -x, c / k)
            }
            _ => (n, 1.0, 1.0),
        }
    }

    /// A term of a sum as a monomial: the nodes of its factors (nested products flattened),
    /// sorted, and the product of their constant factors; `x v0 v1` and `v1 (2 x) v0` are the
    /// same nodes. The factors are compiled, the products not (the sum decides how).
    fn monomial(&mut self, e: &Expr, nodes: &mut Vec<u32>) -> Result<f64> {
        let mut factor = 1.0;
        if let Expr::Mul(v) = e {
            for f in v {
                factor *= self.monomial(f, nodes)?;
            }
        } else {
            match self.compile(e)? {
                Scaled::Const(c) => factor = c,
                Scaled::Node(n, c) => {
                    nodes.push(n);
                    factor = c;
                }
            }
        }
        Ok(factor)
    }

    /// A sum (its nested sums, differences and negations flattened into terms). Terms that
    /// are the same monomial up to a constant factor are merged into the first of them, and
    /// dropped where their factors cancel, as the terms of `∂L/∂q` and `d/dt ∂L/∂qdot` do in
    /// the Euler–Lagrange equations of a kinetic energy quadratic in `qdot`; the sum is
    /// otherwise added as written.
    fn sum(&mut self, e: &Expr) -> Result<Scaled> {
        let mut terms = Vec::new();
        let tree = sum_tree(e, &mut terms, 1.0);
        if !self.merge {
            return self.add_tree(&tree, &terms, &vec![None; terms.len()]);
        }
        // Each distinct monomial with its summed factor and its terms.
        let mut merged: Vec<(Vec<u32>, f64, Vec<usize>)> = Vec::new();
        let mut factors = Vec::with_capacity(terms.len());
        for (i, &(term, sign)) in terms.iter().enumerate() {
            let mut nodes = Vec::new();
            let c = self.monomial(term, &mut nodes)?;
            factors.push(c);
            nodes.sort_unstable();
            if nodes.is_empty() {
                continue;
            }
            match merged.iter_mut().find(|m| m.0 == nodes) {
                Some(m) => {
                    m.1 += sign * c;
                    m.2.push(i);
                }
                None => merged.push((nodes, sign * c, vec![i])),
            }
        }
        // Each term as written (`None`), or scaled by a factor: the first of a merged group
        // carries the group's sum (`total / (sign factor)`, its written value's factor scaled
        // to it), the others 0.
        let mut scale: Vec<Option<f64>> = vec![None; terms.len()];
        for (_, total, members) in merged {
            if let [first, rest @ ..] = members.as_slice() {
                if rest.is_empty() {
                    continue;
                }
                scale[*first] = Some(total / (terms[*first].1 * factors[*first]));
                for &i in rest {
                    scale[i] = Some(0.0);
                }
            }
        }
        self.add_tree(&tree, &terms, &scale)
    }

    /// The terms, each scaled as `scale` says, added in the association of `tree`.
    fn add_tree(
        &mut self,
        tree: &SumTree,
        terms: &[(&Expr, f64)],
        scale: &[Option<f64>],
    ) -> Result<Scaled> {
        Ok(match tree {
            SumTree::Term(i) => match (scale[*i], self.compile(terms[*i].0)?) {
                (None, value) => value,
                (Some(0.0), _) => Scaled::Const(0.0),
                (Some(m), Scaled::Node(node, c)) => Scaled::Node(node, c * m),
                (Some(m), Scaled::Const(c)) => Scaled::Const(c * m),
            },
            SumTree::Add(v) => {
                let mut acc = Scaled::Const(0.0);
                for (i, t) in v.iter().enumerate() {
                    let b = self.add_tree(t, terms, scale)?;
                    acc = if i == 0 { b } else { self.add(acc, b) };
                }
                acc
            }
            SumTree::Sub(a, b) => {
                let a = self.add_tree(a, terms, scale)?;
                let b = self.add_tree(b, terms, scale)?;
                self.sub(a, b)
            }
            SumTree::Neg(a) => Self::neg(self.add_tree(a, terms, scale)?),
        })
    }

    /// `e` compiled on its own (its subexpressions remembered for it alone: they are known by
    /// their address, which is theirs only while `e` is borrowed).
    fn compile_root(&mut self, e: &Expr) -> Result<Scaled> {
        self.memo.clear();
        let value = self.compile(e);
        self.memo.clear();
        value
    }

    /// `e`'s value; a subexpression met again (by a sum, which looks at its terms before it
    /// adds them) is taken from the memo of the expression being compiled.
    fn compile(&mut self, e: &Expr) -> Result<Scaled> {
        let key: *const Expr = e;
        if let Some(&value) = self.memo.get(&key) {
            return Ok(value);
        }
        let value = self.compile_new(e)?;
        self.memo.insert(key, value);
        Ok(value)
    }

    fn compile_new(&mut self, e: &Expr) -> Result<Scaled> {
        let bad = |kind: &str, i: usize, limit: usize| {
            Err(Error::invalid(
                "expression",
                i as f64,
                format!("refers to {kind}{i}, but there are only {limit}"),
            ))
        };
        let (nf, ns) = (self.n_first, self.n_second);
        Ok(match e {
            Expr::Const(c) => Scaled::Const(*c),
            Expr::Q(i) if *i < nf => (*i as u32).into(),
            Expr::Q(i) => return bad("q", *i, nf),
            Expr::Qdot(i) if self.velocity.is_some() => {
                match self.velocity.as_ref().and_then(|w| w.get(*i)) {
                    Some(&w) => w,
                    None => return bad("qdot", *i, nf),
                }
            }
            Expr::Qdot(i) if *i < ns => ((nf + i) as u32).into(),
            Expr::Qdot(i) => return bad("qdot/p", *i, ns),
            Expr::T => ((nf + ns) as u32).into(),
            Expr::Param(i) => match self.params.get(*i) {
                Some(&p) => Scaled::Const(p),
                None => return bad("param", *i, self.params.len()),
            },
            Expr::Add(_) | Expr::Sub(..) => self.sum(e)?,
            Expr::Mul(_) | Expr::Div(..) => self.product_or_quotient(e)?,
            Expr::Neg(a) => Self::neg(self.compile(a)?),
            Expr::Powi(a, n) => {
                let a = self.compile(a)?;
                self.powi(a, *n)
            }
            Expr::Powf(a, x) => {
                let a = self.compile(a)?;
                self.powf(a, *x)
            }
            Expr::Pow(a, b) => {
                let (a, b) = (self.compile(a)?, self.compile(b)?);
                match (a, b) {
                    (_, Scaled::Const(x)) => self.powf(a, x),
                    (Scaled::Const(c), _) => {
                        let exponent = self.mul(b, Scaled::Const(c.ln()));
                        self.exp(exponent)
                    }
                    _ => {
                        let ln = self.func(Func::Ln, a);
                        let exponent = self.mul(b, ln);
                        self.exp(exponent)
                    }
                }
            }
            Expr::Func(f, a) => {
                let a = self.compile(a)?;
                self.func(*f, a)
            }
        })
    }
}

/// `Σ_j a_j b_{n-1-j}` for slices of length `n`: the Cauchy product's term of order `n - 1`,
/// in [`ordered_sum`]'s order with `lead` terms at each end (zero for empty slices).
#[inline(always)]
fn cauchy(lead: usize, a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    ordered_sum(
        &mut (),
        lead,
        n,
        |(), j| a[j] * b[n - 1 - j],
        |(), s, t| s + t,
    )
    .unwrap_or(0.0)
}

/// `Σ_{lo ≤ j ≤ k - lo} x_j x_{k-j}` of the series at offset `x` of the work array `w`, each
/// term with its mirror: `2 Σ x_j x_{k-j}` over `lo ≤ j < k/2` (a [`cauchy`] sum), plus
/// `x_{k/2}²` for even `k`. A square's sum (`lo = 0`), a square root's (`lo = 1`, `k >= 1`).
#[inline(always)]
fn mirrored(lead: usize, w: &[f64], x: usize, lo: usize, k: usize) -> f64 {
    let n = k.div_ceil(2) - lo;
    let twice = cauchy(
        lead,
        &w[x + lo..x + lo + n],
        &w[x + k + 1 - lo - n..x + k + 1 - lo],
    ) * 2.0;
    if k.is_multiple_of(2) {
        let m = w[x + k / 2] * w[x + k / 2];
        if n == 0 {
            m
        } else {
            twice + m
        }
    } else {
        twice
    }
}

/// The work of one order's pass ([`pass_work`], in multiply-adds) at or above which a
/// program leaves one term at each end of a sum out of its groups, below which two
/// ([`WorkLayout::lead`]).
const LONG_PASS: f64 = 72.0;

/// The multiply-adds of the pass over `nodes` at order `k`: each node's sum's terms by the
/// work of a term, plus its work besides the sum ([`Node::work_per_term`]).
fn pass_work(nodes: &[Node], k: usize) -> f64 {
    nodes
        .iter()
        .map(|node| {
            let (per_term, besides) = node.work_per_term();
            node.sum_terms(k) as f64 * per_term + besides
        })
        .sum()
}

impl WorkLayout {
    /// The terms at each end of a sum that [`ordered_sum`] leaves out of its groups of four, in
    /// this program at this order. The AVX code (`taylor_asm.rs`) reads the groups by vector
    /// loads, and a vector load spanning a scalar store still pending waits for it (failed
    /// store forwarding). The end terms read a factor's newest coefficients: order `k`, stored
    /// just before the sum, always stays out; order `k − 1` was stored about one order's pass
    /// earlier. Where the pass at the program's order does at least [`LONG_PASS`]
    /// multiply-adds ([`pass_work`]: the double pendulum's Hamiltonian from order 2 up,
    /// Kepler's from order 13 up), that store is done by then and order `k − 1` joins the
    /// groups (lead 1); after a shorter pass (Hénon–Heiles' at every order: 56 at order 24)
    /// it is not (lead 2). The pass's work tells the two apart better than its count of
    /// nodes, whose cost ranges from one addition to a sum of `k + 1` products. The other
    /// forms take the same order for the same bits; it makes no clear difference to their
    /// speed. `benchmarks/README.md` has the measurements.
    pub(super) fn lead(self) -> usize {
        self.lead
    }
}

/// The fewest terms [`ordered_sum`] splits with `lead` terms at each end: one group and the
/// terms at both ends.
pub(super) const fn split_terms(lead: usize) -> usize {
    2 * lead + 4
}

/// The sum of the terms `term(j)`, `j < n`, of a Cauchy product or a weighted sum
/// ([`Weight`]), in the order every form of the recurrences sums it (`None` for `n = 0`), with
/// `L = lead` terms at each end ([`WorkLayout::lead`]):
/// - fewer than [`split_terms`]`(L)` terms: from `j = 0` up;
/// - else the `4 G` terms from `j = L` (`G = ⌊(n − 2 L)/4⌋` groups of four) into four partial
///   sums `p_l = t_{L+l} + t_{L+4+l} + …`, then `(p_0 + p_2) + (p_1 + p_3)`, plus the terms
///   below `L` from `j = 0` up, plus the terms after the groups from the lowest up.
///
/// So the four partial sums are the lanes of one AVX vector, and one state's AVX code
/// (`taylor_asm.rs`) sums a group by one vector multiplication and addition instead of
/// four of each; the end terms are the ones its vector loads must not read.
///
/// Every form calls `term` and `add` in the order the sum is taken, so a recorder of the
/// calls (`s`) records them in that order.
#[inline(always)]
fn ordered_sum<S: ?Sized, T: Copy>(
    s: &mut S,
    lead: usize,
    n: usize,
    term: impl FnMut(&mut S, usize) -> T,
    add: impl FnMut(&mut S, T, T) -> T,
) -> Option<T> {
    ordered_sum_with(s, lead, n, term, add, |_, _| None)
}

/// [`ordered_sum`], the groups' `(p_0 + p_2) + (p_1 + p_3)` taken by `groups_sum(s, G)` where
/// it gives one (the vector code's sum of the groups, on the same bits).
#[inline(always)]
fn ordered_sum_with<S: ?Sized, T: Copy>(
    s: &mut S,
    lead: usize,
    n: usize,
    mut term: impl FnMut(&mut S, usize) -> T,
    mut add: impl FnMut(&mut S, T, T) -> T,
    groups_sum: impl FnOnce(&mut S, usize) -> Option<T>,
) -> Option<T> {
    if n < split_terms(lead) {
        let mut acc = None;
        for j in 0..n {
            let t = term(s, j);
            acc = Some(match acc {
                Some(a) => add(s, a, t),
                None => t,
            });
        }
        return acc;
    }
    let groups = (n - 2 * lead) / 4;
    let mut acc = match groups_sum(s, groups) {
        Some(sum) => sum,
        None => {
            let mut p = [
                term(s, lead),
                term(s, lead + 1),
                term(s, lead + 2),
                term(s, lead + 3),
            ];
            for g in 1..groups {
                for (l, p) in p.iter_mut().enumerate() {
                    let t = term(s, lead + 4 * g + l);
                    *p = add(s, *p, t);
                }
            }
            let even = add(s, p[0], p[2]);
            let odd = add(s, p[1], p[3]);
            add(s, even, odd)
        }
    };
    for j in 0..lead {
        let first = term(s, j);
        acc = add(s, acc, first);
    }
    for j in lead + 4 * groups..n {
        let t = term(s, j);
        acc = add(s, acc, t);
    }
    Some(acc)
}

/// The factors of a product or quotient (nested products, quotients and negations
/// flattened), each with the exponent `±1` it enters with; negations multiply `constant` by
/// -1.
fn flatten_product<'e>(e: &'e Expr, sign: i32, out: &mut Vec<(&'e Expr, i32)>, constant: &mut f64) {
    match e {
        Expr::Mul(v) => v
            .iter()
            .for_each(|f| flatten_product(f, sign, out, constant)),
        Expr::Div(a, b) => {
            flatten_product(a, sign, out, constant);
            flatten_product(b, -sign, out, constant);
        }
        Expr::Neg(a) => {
            *constant = -*constant;
            flatten_product(a, sign, out, constant);
        }
        e => out.push((e, sign)),
    }
}

/// Whether `e` refers to a velocity `qdot_i`.
fn mentions_velocity(e: &Expr) -> bool {
    match e {
        Expr::Qdot(_) => true,
        Expr::Const(_) | Expr::Q(_) | Expr::T | Expr::Param(_) => false,
        Expr::Add(v) | Expr::Mul(v) => v.iter().any(mentions_velocity),
        Expr::Sub(a, b) | Expr::Div(a, b) | Expr::Pow(a, b) => {
            mentions_velocity(a) || mentions_velocity(b)
        }
        Expr::Neg(a) | Expr::Powi(a, _) | Expr::Powf(a, _) | Expr::Func(_, a) => {
            mentions_velocity(a)
        }
    }
}

/// The value of an [`Node::Integral`]'s function.
fn func_value(func: Func, x: f64) -> f64 {
    match func {
        Func::Atan => x.atan(),
        Func::Asin => x.asin(),
        Func::Acos => x.acos(),
        _ => x.ln(),
    }
}

/// A function of a non-constant operand folded to a constant cannot happen (the builder
/// folds only operations whose operands are all constants); a NaN then makes the stepper
/// refuse the run rather than panic.
fn unreachable_const() -> Scaled {
    Scaled::Const(f64::NAN)
}

impl TaylorProgram {
    /// Interpreted expansions (of any order) after which a program's recurrences of the order
    /// being expanded are compiled to machine code (feature `jit`). Compiling the unrolled
    /// recurrences costs 3 to 150 ms (growing with the nodes and the square of the order),
    /// and each compiled expansion saves 1 to 5 µs: compiling pays after 5 000 to 30 000
    /// expansions (benchmarks/README.md, "Adaptive Taylor method against heyoka", has the
    /// measured figures). Compiling once the interpreter has run about that many (the
    /// rent-or-buy rule) costs any run at most about twice what the better choice in
    /// hindsight would have; [`compile_native`](Self::compile_native) compiles at once.
    pub const COMPILE_AFTER: u32 = 20_000;

    /// Compiles `outputs`, the components of `dy/dt` for the state
    /// `y = (q_0..q_{n_first}, qdot_0/p_0..)` (`n_first + n_second` components, one output
    /// each), in `t` and parameters with values `params`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `expression` for a variable or parameter index out
    /// of range, or naming `outputs` when there is not one output per state component.
    pub fn new(outputs: &[Expr], n_first: usize, n_second: usize, params: &[f64]) -> Result<Self> {
        let dim = n_first + n_second;
        if outputs.len() != dim || dim == 0 {
            return Err(Error::invalid(
                "outputs",
                outputs.len() as f64,
                format!("needs one output per state component ({dim}), at least one"),
            ));
        }
        Self::smaller_of(|merge| {
            let mut nodes = vec![Node::State; dim];
            nodes.push(Node::Time);
            let mut builder = Builder {
                n_first,
                n_second,
                params,
                nodes: HashCons::new(nodes),
                velocity: None,
                memo: HashMap::new(),
                merge,
            };
            let mut compiled = Vec::with_capacity(dim);
            for e in outputs {
                let value = builder.compile_root(e)?;
                compiled.push(builder.val(value));
            }
            Ok(Self::from_built(dim, builder.nodes.items, compiled))
        })
    }

    /// The program `build` makes with merging (its argument: like terms of sums, powers of
    /// one base in products) unless the one it makes without has fewer nodes; without
    /// merging alone inside [`without_merging`](Self::without_merging). Both are the same
    /// field. A merge rewrites a sum or product in place, and where other expressions share
    /// the partial sums it changed (the elimination's rows of the triple pendulum's
    /// Euler–Lagrange equations reuse each other's sums), the rewritten ones are new nodes
    /// beside the shared ones: merging alone would grow such a program (the triple pendulum:
    /// 112 nodes merged, 104 as written). Building twice costs microseconds to a
    /// millisecond, against the milliseconds of compiling the recurrences.
    fn smaller_of(build: impl Fn(bool) -> Result<Self>) -> Result<Self> {
        let written = build(false)?;
        if !MERGE.get() {
            return Ok(written);
        }
        let merged = build(true)?;
        Ok(if merged.nodes() <= written.nodes() {
            merged
        } else {
            written
        })
    }

    /// The program of `nodes` and `outputs` without the nodes no output needs (forms the
    /// builder tried and did not take); the state and time keep their places.
    fn from_built(dim: usize, nodes: Vec<Node>, outputs: Vec<Val>) -> Self {
        let mut live = vec![false; nodes.len()];
        live[..=dim].fill(true);
        for out in &outputs {
            if let Val::Node(n) = *out {
                live[n as usize] = true;
            }
        }
        for i in (0..nodes.len()).rev() {
            // A sin/cos pair lives or dies together.
            if matches!(nodes[i], Node::Partner) && live[i] {
                live[i - 1] = true;
            }
            if let Node::SinCos(..) = nodes[i] {
                live[i] |= live[i + 1];
                live[i + 1] = live[i];
            }
            if live[i] {
                nodes[i].map_operands(|a| {
                    live[a as usize] = true;
                    a
                });
            }
        }
        let mut index = vec![0_u32; nodes.len()];
        let mut kept = Vec::with_capacity(nodes.len());
        for (i, node) in nodes.into_iter().enumerate() {
            if live[i] {
                index[i] = kept.len() as u32;
                kept.push(node);
            }
        }
        for node in &mut kept {
            *node = node.map_operands(|a| index[a as usize]);
        }
        let outputs = outputs
            .into_iter()
            .map(|out| match out {
                Val::Node(n) => Val::Node(index[n as usize]),
                c => c,
            })
            .collect();
        Self {
            dim,
            nodes: kept,
            outputs,
            work: Vec::new(),
            layout: None,
            jit: jit::Jit::default(),
        }
    }

    /// The recurrences of an [`ExprOde`]'s field `dy/dt = f(t, y)`.
    ///
    /// # Errors
    /// As [`TaylorProgram::new`] (never, for a valid `ExprOde`).
    pub fn ode(system: &ExprOde) -> Result<Self> {
        Self::new(
            system.components(),
            system.components().len(),
            0,
            system.params(),
        )
    }

    /// The recurrences of an [`ExprHamiltonian`]'s canonical equations
    /// `dq/dt = ∂H/∂p`, `dp/dt = -∂H/∂q`, state `(q, p)`, from `H`'s symbolic derivatives.
    ///
    /// # Errors
    /// As [`TaylorProgram::new`] (never, for a valid `ExprHamiltonian`).
    pub fn hamiltonian(system: &ExprHamiltonian) -> Result<Self> {
        let n = system.ndof();
        let h = system.expr();
        let outputs: Vec<Expr> = (0..n)
            .map(|i| h.diff(Var::Second(i)))
            .chain((0..n).map(|i| Expr::Neg(Box::new(h.diff(Var::First(i))))))
            .collect();
        Self::new(&outputs, n, n, system.params())
    }

    /// The recurrences of an [`ExprLagrangian`]'s Euler–Lagrange equations on the state
    /// `(q, qdot)`: `dq/dt = qdot` and `M qdot' = r` with the mass matrix
    /// `M_ij = ∂²L/∂qdot_i∂qdot_j` and `r_i = ∂L/∂q_i - Σ_j ∂²L/∂qdot_i∂q_j qdot_j -
    /// ∂²L/∂qdot_i∂t`, all from `L`'s symbolic derivatives; the linear system is solved
    /// symbolically by Gaussian elimination without pivoting, which needs no pivot for a
    /// positive definite `M` (a kinetic energy: its leading minors are positive). Where a
    /// leading minor of `M` vanishes the coefficients come out non-finite and the stepper
    /// refuses the step. The elimination's expressions share their subexpressions, which the
    /// compilation expands once each.
    ///
    /// # Errors
    /// As [`TaylorProgram::new`] (never, for a valid `ExprLagrangian`).
    pub fn lagrangian(system: &ExprLagrangian) -> Result<Self> {
        let n = system.ndof();
        let l = system.expr();
        let dl_dqdot: Vec<Expr> = (0..n).map(|i| l.diff(Var::Second(i))).collect();
        let mut m: Vec<Vec<Expr>> = dl_dqdot
            .iter()
            .map(|d| (0..n).map(|j| d.diff(Var::Second(j))).collect())
            .collect();
        let mut r: Vec<Expr> = (0..n)
            .map(|i| {
                let mut terms = vec![l.diff(Var::First(i))];
                for j in 0..n {
                    terms.push(Expr::Neg(Box::new(Expr::Mul(vec![
                        dl_dqdot[i].diff(Var::First(j)),
                        Expr::Qdot(j),
                    ]))));
                }
                terms.push(Expr::Neg(Box::new(dl_dqdot[i].diff(Var::Time))));
                Expr::Add(terms)
            })
            .collect();
        // Forward elimination: row i -= (m_ik / m_kk) row k below each pivot k.
        for k in 0..n {
            for i in k + 1..n {
                let factor = Expr::Div(Box::new(m[i][k].clone()), Box::new(m[k][k].clone()));
                // Row k is above row i: borrow it beside row i.
                let (above, from_i) = m.split_at_mut(i);
                for (mij, mkj) in from_i[0][k + 1..n].iter_mut().zip(&above[k][k + 1..n]) {
                    *mij = Expr::Sub(
                        Box::new(mij.clone()),
                        Box::new(Expr::Mul(vec![factor.clone(), mkj.clone()])),
                    );
                }
                r[i] = Expr::Sub(
                    Box::new(r[i].clone()),
                    Box::new(Expr::Mul(vec![factor, r[k].clone()])),
                );
            }
        }
        // Back substitution.
        let mut acceleration = vec![Expr::Const(0.0); n];
        for i in (0..n).rev() {
            let mut rhs = vec![r[i].clone()];
            for j in i + 1..n {
                rhs.push(Expr::Neg(Box::new(Expr::Mul(vec![
                    m[i][j].clone(),
                    acceleration[j].clone(),
                ]))));
            }
            acceleration[i] = Expr::Div(Box::new(Expr::Add(rhs)), Box::new(m[i][i].clone()));
        }
        let outputs: Vec<Expr> = (0..n).map(Expr::Qdot).chain(acceleration).collect();
        Self::new(&outputs, n, n, system.params())
    }

    /// The recurrences of Hamilton's equations of an [`ExprLagrangian`] whose kinetic energy
    /// is quadratic in `qdot` (`L = ½ qdotᵀ M(q, t) qdot + b(q, t)·qdot - V(q, t)`), on the
    /// state `(q, p)` with the momenta `p = ∂L/∂qdot = M qdot + b`: the velocities
    /// `w = M^-1 (p - b)` are solved for once (Gaussian elimination without pivoting, as in
    /// [`lagrangian`](Self::lagrangian), on `M = ∂²L/∂qdot²` and `b = ∂L/∂qdot` at
    /// `qdot = 0`), and then `dq/dt = w` and `dp/dt = ∂L/∂q` at `qdot = w`. That is `-∂H/∂q`
    /// (the Legendre transform's envelope: `∂H/∂q = -∂L/∂q` at the velocity that gives `p`),
    /// which for `b = 0` and `V` is `½ wᵀ (∂M/∂q) w - ∂V/∂q`: the equations written with
    /// `w` shared, not `H = ½ pᵀ M^-1 p + V` differentiated entry by entry of `M^-1`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `lagrangian` when `∂²L/∂qdot²` depends on `qdot`
    /// (the kinetic energy is not quadratic); otherwise as [`TaylorProgram::new`].
    pub fn lagrangian_canonical(system: &ExprLagrangian) -> Result<Self> {
        let n = system.ndof();
        let l = system.expr();
        let dl_dqdot: Vec<Expr> = (0..n).map(|i| l.diff(Var::Second(i))).collect();
        let m: Vec<Vec<Expr>> = dl_dqdot
            .iter()
            .map(|d| (0..n).map(|j| d.diff(Var::Second(j))).collect())
            .collect();
        if m.iter().flatten().any(mentions_velocity) {
            return Err(Error::invalid(
                "lagrangian",
                n as f64,
                "has a mass matrix d2L/dqdot2 that depends on qdot: its kinetic energy is not \
                 quadratic in qdot, so the momenta are not linear in it",
            ));
        }
        let dim = 2 * n;
        Self::smaller_of(|merge| {
            let mut nodes = vec![Node::State; dim];
            nodes.push(Node::Time);
            let mut builder = Builder {
                n_first: n,
                n_second: n,
                params: system.params(),
                nodes: HashCons::new(nodes),
                velocity: Some(vec![Scaled::Const(0.0); n]),
                memo: HashMap::new(),
                merge,
            };
            // `p - b`, `b` the momenta at `qdot = 0`.
            let mut rhs = Vec::with_capacity(n);
            for (i, d) in dl_dqdot.iter().enumerate() {
                let b = builder.compile_root(d)?;
                rhs.push(builder.sub(((n + i) as u32).into(), b));
            }
            let mut mass = Vec::with_capacity(n);
            for row in &m {
                let mut compiled = Vec::with_capacity(n);
                for e in row {
                    compiled.push(builder.compile_root(e)?);
                }
                mass.push(compiled);
            }
            // Forward elimination, row i -= (m_ik / m_kk) row k, then back substitution.
            for k in 0..n {
                for i in k + 1..n {
                    let factor = builder.div(mass[i][k], mass[k][k]);
                    let row_k = mass[k].clone();
                    for (mij, &mkj) in mass[i][k + 1..].iter_mut().zip(&row_k[k + 1..]) {
                        let product = builder.mul(factor, mkj);
                        *mij = builder.sub(*mij, product);
                    }
                    let product = builder.mul(factor, rhs[k]);
                    rhs[i] = builder.sub(rhs[i], product);
                }
            }
            let mut w = vec![Scaled::Const(0.0); n];
            for i in (0..n).rev() {
                let mut acc = rhs[i];
                for j in i + 1..n {
                    let product = builder.mul(mass[i][j], w[j]);
                    acc = builder.sub(acc, product);
                }
                w[i] = builder.div(acc, mass[i][i]);
            }
            builder.velocity = Some(w.clone());
            let mut outputs = Vec::with_capacity(dim);
            for &wi in &w {
                outputs.push(builder.val(wi));
            }
            for i in 0..n {
                let force = builder.compile_root(&l.diff(Var::First(i)))?;
                outputs.push(builder.val(force));
            }
            Ok(Self::from_built(dim, builder.nodes.items, outputs))
        })
    }

    /// `f()` with the programs it builds on this thread compiled without merging (each sum
    /// and product as written): the reference a test compares the programs' sizes with.
    #[doc(hidden)]
    pub fn without_merging<T>(f: impl FnOnce() -> T) -> T {
        struct Restore(bool);
        impl Drop for Restore {
            fn drop(&mut self) {
                MERGE.set(self.0);
            }
        }
        let _restore = Restore(MERGE.replace(false));
        f()
    }

    /// Number of recurrence nodes (state, time and operations).
    pub fn nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Which code runs expansions to `order` now: native code once the recurrences of that
    /// order have been compiled (by [`compile_native`](Self::compile_native), or after
    /// [`COMPILE_AFTER`](Self::COMPILE_AFTER) expansions), else the interpreter.
    pub fn backend(&self, order: usize) -> Backend {
        if self.jit.is_native(order) {
            Backend::Native
        } else {
            Backend::Interpreter
        }
    }

    /// Compiles the recurrences up to `order` (at most [`MAX_ORDER`]) to machine code now,
    /// rather than after [`COMPILE_AFTER`](Self::COMPILE_AFTER) expansions, and returns the backend
    /// that then runs them: [`Backend::Interpreter`] without the feature `jit`, in
    /// WebAssembly, for an order above [`MAX_ORDER`], or if Cranelift cannot compile for this
    /// host. Each order compiles once; clones share the code.
    pub fn compile_native(&self, order: usize) -> Backend {
        self.jit.compile(&self.nodes, &self.outputs, order);
        self.backend(order)
    }

    /// Whether the native code of `order` is the code written for AVX
    /// (`symbolic/tape/taylor_asm.rs`) rather than Cranelift's: what tests check to know
    /// which code they compared.
    #[doc(hidden)]
    pub fn written_for_avx(&self, order: usize) -> bool {
        self.jit.is_avx(order)
    }

    /// [`compile_native`](Self::compile_native) in the compact form (the orders and the sums
    /// as loops, the form large programs are compiled in) whatever the program's size: what
    /// tests compare with the unrolled form and the interpreter.
    #[doc(hidden)]
    pub fn compile_native_compact(&self, order: usize) -> Backend {
        self.jit.compile_compact(&self.nodes, &self.outputs, order);
        self.backend(order)
    }

    /// [`compile_native`](Self::compile_native) in Cranelift's unrolled form (every order and
    /// term written out, the form small programs are compiled in where the recurrences are not
    /// written as AVX code) whatever the program's size.
    #[doc(hidden)]
    pub fn compile_native_unrolled(&self, order: usize) -> Backend {
        self.jit.compile_unrolled(&self.nodes, &self.outputs, order);
        self.backend(order)
    }

    /// This program with its recurrences interpreted for good (no code shared with the
    /// original, none ever compiled): the reference the compiled code is tested against.
    #[doc(hidden)]
    #[must_use]
    pub fn interpreted_only(&self) -> Self {
        Self {
            jit: jit::Jit::never(),
            ..self.clone()
        }
    }

    /// Orders `0..=order` of every node, by the recurrences interpreted (the state's and
    /// time's order 0 already set): each order of the operations, then the state's next order
    /// from the field's, `y^[k+1] = f^[k] · (1/(k + 1))`.
    fn interpret(&mut self, order: usize, layout: WorkLayout) {
        for k in 0..=order {
            self.order_k(k, layout);
            if k < order {
                let next = 1.0 / (k + 1) as f64;
                for (i, out) in self.outputs.iter().enumerate() {
                    let fk = match *out {
                        Val::Node(n) => self.work[layout.at(n as usize, k)],
                        Val::Const(c) if k == 0 => c,
                        Val::Const(_) => 0.0,
                    };
                    self.work[layout.at(i, k + 1)] = fk * next;
                }
            }
        }
    }

    /// Order `k` of every operation node, from orders `< k` of all nodes (the state's and
    /// time's order `k` already set). Every sum runs in the order written here, starting with
    /// its first term; the compiled recurrences (`tape/taylor_jit.rs`) do the same operations
    /// in the same order, so both give the same bits.
    #[allow(clippy::too_many_lines)]
    fn order_k(&mut self, k: usize, layout: WorkLayout) {
        let w = &mut self.work[..];
        let at = |n: u32, j: usize| layout.at(n as usize, j);
        let lead = layout.lead();
        let kf = k as f64;
        for (i, &node) in self.nodes.iter().enumerate() {
            let me = layout.at(i, 0);
            let value = match node {
                Node::State | Node::Time | Node::Partner => continue,
                Node::Add(a, b) => w[at(a, k)] + w[at(b, k)],
                Node::Sub(a, b) => w[at(a, k)] - w[at(b, k)],
                Node::AddC(a, c) => {
                    if k == 0 {
                        w[at(a, 0)] + c
                    } else {
                        w[at(a, k)]
                    }
                }
                Node::CSub(c, a) => {
                    if k == 0 {
                        c - w[at(a, 0)]
                    } else {
                        -w[at(a, k)]
                    }
                }
                Node::MulC(a, c) => c * w[at(a, k)],
                Node::Neg(a) => -w[at(a, k)],
                Node::Abs(a) => {
                    if w[at(a, 0)] < 0.0 {
                        -w[at(a, k)]
                    } else {
                        w[at(a, k)]
                    }
                }
                Node::Mul(a, b) => {
                    let (a, b) = (at(a, 0), at(b, 0));
                    cauchy(lead, &w[a..=a + k], &w[b..=b + k])
                }
                Node::Square(a) => mirrored(lead, w, at(a, 0), 0, k),
                Node::Div(a, b) => {
                    let b = at(b, 0);
                    if k == 0 {
                        w[at(a, 0)] / w[b]
                    } else {
                        (w[at(a, k)] - cauchy(lead, &w[b + 1..=b + k], &w[me..me + k])) / w[b]
                    }
                }
                Node::CDiv(c, a) => {
                    let a = at(a, 0);
                    if k == 0 {
                        c / w[a]
                    } else {
                        -cauchy(lead, &w[a + 1..=a + k], &w[me..me + k]) / w[a]
                    }
                }
                Node::Sqrt(a) => {
                    if k == 0 {
                        w[at(a, 0)].sqrt()
                    } else {
                        (w[at(a, k)] - mirrored(lead, w, me, 1, k)) / (2.0 * w[me])
                    }
                }
                Node::Powf(a, alpha) => {
                    let a = at(a, 0);
                    if k == 0 {
                        power0(w[a], alpha)
                    } else {
                        let s = weighted_sum(lead, w, Weight::Power(alpha), a, me, k);
                        s.unwrap_or(0.0) / (kf * w[a])
                    }
                }
                Node::Derivative(a) => {
                    if k == 0 {
                        w[at(a, 0)]
                    } else {
                        kf * w[at(a, k)]
                    }
                }
                Node::Exp(d) => {
                    let d = at(d, 0);
                    if k == 0 {
                        w[d].exp()
                    } else {
                        cauchy(lead, &w[me..me + k], &w[d + 1..=d + k]) * (1.0 / kf)
                    }
                }
                Node::Integral { a, d, sign, func } => {
                    let (a, d) = (at(a, 0), at(d, 0));
                    if k == 0 {
                        func_value(func, w[a])
                    } else {
                        // `Σ_{1 ≤ j < k} j c_j d_{k-j}` as a weighted sum of `k - 1` terms.
                        let s = sign * kf * w[a + k];
                        let s = match weighted_sum(lead, w, Weight::Falling, me, d + 1, k - 1) {
                            Some(t) => s - t,
                            None => s,
                        };
                        s / (kf * w[d])
                    }
                }
                Node::SinCos(d, hyperbolic) => {
                    let d = at(d, 0);
                    let partner = layout.at(i + 1, 0);
                    if k == 0 {
                        let x = w[d];
                        let (s, c) = if hyperbolic {
                            (x.sinh(), x.cosh())
                        } else {
                            (x.sin(), x.cos())
                        };
                        w[partner] = c;
                        s
                    } else {
                        let slopes = &w[d + 1..=d + k];
                        let s = cauchy(lead, &w[partner..partner + k], slopes);
                        let c = cauchy(lead, &w[me..me + k], slopes);
                        let rk = 1.0 / kf;
                        w[partner + k] = if hyperbolic { c * rk } else { -c * rk };
                        s * rk
                    }
                }
            };
            w[me + k] = value;
        }
    }
}

/// How order 0 of `a^α` is computed: by a square root and multiplications for the
/// half-integer exponents of inverse-square forces and their kin, by `powf` otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Power {
    /// `α = ±(n + ½)`, `n <= 2`: `r = √a · a · … · a` (`n` products, left to right), then
    /// `1/r` for a negative `α`. At most four roundings (a relative error of at most 2 ε),
    /// and no libm call on the critical path of every expansion. It differs from `pow` only
    /// off any state a step can have: the sign of the result at `a = -0`, NaN (not `pow`'s
    /// `+0` or `+inf`) at `a = -inf`, and zero where `r` overflows while `a^α` is subnormal
    /// (`a > 1e123` at `α = -2.5`).
    Half { n: u32, reciprocal: bool },
    /// `a.powf(α)`.
    General,
}

impl Power {
    /// The form for exponent `alpha`.
    // Exact comparison: recognizing half-integers.
    #[allow(clippy::float_cmp)]
    pub(super) fn of(alpha: f64) -> Self {
        let twice = 2.0 * alpha.abs();
        if twice == twice.trunc() && twice % 2.0 == 1.0 && twice <= 5.0 {
            Self::Half {
                n: (twice as u32 - 1) / 2,
                reciprocal: alpha < 0.0,
            }
        } else {
            Self::General
        }
    }
}

/// Order 0 of `a^α` at `a = x`, as [`Power::of`] says (the JIT emits the same operations in
/// the same order: `Recurrences::power`).
#[inline]
pub(super) fn power0(x: f64, alpha: f64) -> f64 {
    match Power::of(alpha) {
        Power::Half { n, reciprocal } => {
            let mut r = x.sqrt();
            for _ in 0..n {
                r *= x;
            }
            if reciprocal {
                1.0 / r
            } else {
                r
            }
        }
        Power::General => x.powf(alpha),
    }
}

/// The weight `α (k - j) - j` of the term `j` of order `k` of `a^α`'s recurrence.
#[inline(always)]
fn powf_weight(alpha: f64, k: usize, j: usize) -> f64 {
    alpha * (k - j) as f64 - j as f64
}

/// The constant weights `w_j` of a weighted sum of order `k`, `Σ_{j < k} (w_j a_{k-j}) b_j`,
/// taken in [`ordered_sum`]'s order by every form, with its groups as vectors in one state's
/// AVX code.
#[derive(Clone, Copy, Debug)]
enum Weight {
    /// `a^α`'s recurrence, `b` the power itself: [`powf_weight`].
    Power(f64),
    /// An [`Node::Integral`]'s (`a` the integral itself, `b` its `d` from order 1, `k - 1`
    /// terms): `k - j`, so that the sum is `Σ_{1 ≤ i < k} i a_i b_{k-i}`. The weights are
    /// whole numbers, exact in any form.
    Falling,
}

impl Weight {
    /// The weight of term `j` of order `k`.
    #[inline(always)]
    fn at(self, k: usize, j: usize) -> f64 {
        match self {
            Weight::Power(alpha) => powf_weight(alpha, k, j),
            Weight::Falling => (k - j) as f64,
        }
    }
}

/// `Σ_{j < k} (w_j a_{k-j}) b_j` in [`ordered_sum`]'s order with `lead` terms at each end, on
/// the work array `w` with `a` and `b` the offsets of coefficient 0 of the two series; `None`
/// for `k = 0`.
#[inline(always)]
fn weighted_sum(
    lead: usize,
    w: &[f64],
    weight: Weight,
    a: usize,
    b: usize,
    k: usize,
) -> Option<f64> {
    let term = |(): &mut (), j: usize| weight.at(k, j) * w[a + k - j] * w[b + j];
    ordered_sum(&mut (), lead, k, term, |(), s, t| s + t)
}

/// The work of a step on the recurrences `nodes` of a field of `dim` rows, with the stepper's
/// own ([`StepCost::stepper`]), in multiply-adds: each node's [`sum_terms`](Node::sum_terms)
/// at order `k`, as a first term and a slope in `k` (over the orders up to [`MAX_ORDER`]),
/// times its [`work_per_term`](Node::work_per_term), and the work besides its sum: the
/// [`pass_work`] at order 0 and its mean growth an order.
fn step_cost(dim: usize, nodes: &[Node]) -> StepCost {
    let first = pass_work(nodes, 0);
    let stepper = StepCost::stepper(dim);
    StepCost {
        convolution: stepper.convolution + (pass_work(nodes, MAX_ORDER) - first) / MAX_ORDER as f64,
        per_order: stepper.per_order + first,
        ..stepper
    }
}

impl TaylorField for TaylorProgram {
    fn dim(&self) -> usize {
        self.dim
    }

    fn step_cost(&self) -> StepCost {
        step_cost(self.dim, &self.nodes)
    }

    fn expansion(&mut self, t: f64, y: &[f64], order: usize) -> Result<&[f64]> {
        Ok(self.expansion_in_blocks(t, y, order)?.0)
    }

    fn expansion_in_blocks(&mut self, t: f64, y: &[f64], order: usize) -> Result<InBlocks<'_>> {
        if order > MAX_ORDER {
            return Err(Error::invalid(
                "order",
                order as f64,
                format!("a Taylor expansion takes an order <= {MAX_ORDER}"),
            ));
        }
        if y.len() != self.dim {
            return Err(Error::DimensionMismatch {
                name: "y".into(),
                expected: self.dim,
                found: y.len(),
            });
        }
        let dim = self.dim;
        let layout = WorkLayout::of_order(&mut self.layout, &self.nodes, dim, order);
        if self.work.len() != layout.len() {
            // The blocks' lanes past the last row stay the zeros of the allocation.
            self.work = vec![0.0; layout.len()];
        }
        for (i, &yi) in y.iter().enumerate() {
            self.work[layout.at(i, 0)] = yi;
        }
        let time = layout.at(dim, 0);
        // The time's series is `t + τ`: its orders from 2 on are the zeros of the allocation,
        // which no recurrence writes.
        self.work[time] = t;
        if order >= 1 {
            self.work[time + 1] = 1.0;
        }
        let blocks = match self.jit.code(&self.nodes, &self.outputs, order) {
            Some(code) => {
                code.call(&mut self.work);
                code.writes_blocks()
            }
            None => {
                self.interpret(order, layout);
                false
            }
        };
        // The state's rows come first in the work array, its blocks last.
        let (rows, rest) = self.work.split_at(layout.blocks_start());
        let blocks = blocks.then_some(rest.as_chunks::<LANES>().0);
        Ok((&rows[..time], blocks))
    }
}

#[cfg(test)]
mod tests {
    use super::{ordered_sum, pass_work, power0, Power, TaylorProgram, WorkLayout, MAX_ORDER};
    use crate::classical::symbolic::{Expr, ExprHamiltonian};

    /// The program of Hamilton's equations of `h` (two degrees of freedom, parameters
    /// `params`).
    fn hamiltonian(h: &str, params: Vec<f64>) -> TaylorProgram {
        let h = Expr::parse(h).expect("parses");
        let system = ExprHamiltonian::new(h, 2, params, &[0.5, 0.1], &[0.2, 0.3]).expect("valid");
        TaylorProgram::hamiltonian(&system).expect("has a Taylor form")
    }

    /// The sums' end terms follow the work of a pass as `WorkLayout::lead` documents it for
    /// the programs it names (the heyoka comparison's, where it was measured): Hénon–Heiles
    /// keeps two at every order (its pass at order 24: 56 multiply-adds), Kepler takes one
    /// from order 13 up (75), the double pendulum's Hamiltonian from order 2 up (94); and a
    /// pass grows with the order.
    #[test]
    fn the_end_terms_follow_the_work_of_a_pass() {
        let kepler = hamiltonian(
            "(- (* 0.5 (+ (^ p0 2) (^ p1 2))) (^ (+ (^ q0 2) (^ q1 2)) -0.5))",
            vec![],
        );
        let henon_heiles = hamiltonian(
            "(+ (* 0.5 (+ (^ p0 2) (^ p1 2) (^ q0 2) (^ q1 2))) (* (^ q0 2) q1) \
             (* (/ -1 3) (^ q1 3)))",
            vec![],
        );
        let pendulum = hamiltonian(
            "(- (- (/ (+ (* param2 (^ p0 2)) (* param0 (^ p1 2)) \
             (* -2 param1 (cos (- q0 q1)) p0 p1)) \
             (* 2 (- (* param0 param2) (^ (* param1 (cos (- q0 q1))) 2)))) \
             (* param3 (cos q0))) (* param4 (cos q1)))",
            vec![2.0, 1.0, 1.0, 19.62, 9.81],
        );
        let lead = |p: &TaylorProgram, order| WorkLayout::new(&p.nodes, 4, order).lead();
        for order in 1..=MAX_ORDER {
            for p in [&kepler, &henon_heiles, &pendulum] {
                assert!(pass_work(&p.nodes, order) > pass_work(&p.nodes, order - 1));
            }
            assert_eq!(lead(&henon_heiles, order), 2, "order {order}");
            assert_eq!(
                lead(&kepler, order),
                if order >= 13 { 1 } else { 2 },
                "order {order}"
            );
            assert_eq!(
                lead(&pendulum, order),
                if order >= 2 { 1 } else { 2 },
                "order {order}"
            );
        }
    }

    /// Every term enters a sum once, in the order `ordered_sum`'s documentation gives, with
    /// one and with two end terms: terms as the bits of a mask, each addition recorded as its
    /// two operands.
    #[test]
    fn ordered_sums_take_every_term_once_in_the_documented_order() {
        let sum = |lead: usize, n: usize| {
            let mut adds: Vec<(u128, u128)> = Vec::new();
            let total = ordered_sum(
                &mut adds,
                lead,
                n,
                |_, j| 1u128 << j,
                |adds, a, b| {
                    assert_eq!(a & b, 0, "a term added twice, n = {n}, lead {lead}");
                    adds.push((a, b));
                    a | b
                },
            );
            (total, adds)
        };
        for lead in [1, 2] {
            for n in 0..=127 {
                let (total, adds) = sum(lead, n);
                let want = (n > 0).then(|| (1u128 << n) - 1);
                assert_eq!(total, want, "n = {n}, lead {lead}");
                assert_eq!(adds.len(), n.saturating_sub(1), "n = {n}, lead {lead}");
            }
        }
        let t = |j: u32| 1u128 << j;
        // One by one from the first: below eight terms with two end terms, below six with one.
        for (lead, n) in [(2, 7), (1, 5)] {
            let (_, adds) = sum(lead, n);
            let plain: Vec<(u128, u128)> = (1..n as u32).map(|j| (t(j) - 1, t(j))).collect();
            assert_eq!(adds, plain, "lead {lead}");
        }
        // Thirteen terms with two end terms: groups `2..=5` and `6..=9` in four partial sums,
        // then the terms 0 and 1, then 10, 11 and 12. With one: groups `1..=4` and `5..=8`,
        // then the term 0, then 9 to 12.
        for (lead, first, last) in [(2u32, 2u32, 9u32), (1, 1, 8)] {
            let (_, adds) = sum(lead as usize, 13);
            let f = first;
            let p = [
                t(f) | t(f + 4),
                t(f + 1) | t(f + 5),
                t(f + 2) | t(f + 6),
                t(f + 3) | t(f + 7),
            ];
            let groups = p[0] | p[1] | p[2] | p[3];
            let mut want = vec![
                (t(f), t(f + 4)),
                (t(f + 1), t(f + 5)),
                (t(f + 2), t(f + 6)),
                (t(f + 3), t(f + 7)),
                (p[0], p[2]),
                (p[1], p[3]),
                (p[0] | p[2], p[1] | p[3]),
            ];
            let mut acc = groups;
            for j in (0..lead).chain(last + 1..13) {
                want.push((acc, t(j)));
                acc |= t(j);
            }
            assert_eq!(adds, want, "lead {lead}");
        }
    }

    /// The half-integer powers are within 2.5 ε (relative) of libm's `pow` over 24 binades
    /// around 1: their at most four roundings of half an ulp (2 ε), plus `pow`'s own error,
    /// below half an ulp. They agree with it at `+0`, `+inf`, negative and NaN arguments
    /// (the differences at `-0` and `-inf` are documented on `Power::Half`); other exponents
    /// are `pow` itself.
    #[test]
    // Exact comparisons: the special values and `pow`'s own bits.
    #[allow(clippy::float_cmp)]
    fn half_integer_powers_agree_with_powf() {
        for alpha in [-2.5, -1.5, -0.5, 0.5, 1.5, 2.5] {
            assert!(matches!(Power::of(alpha), Power::Half { .. }), "{alpha}");
            let mut x = 2f64.powi(-12);
            while x < 4096.0 {
                let want = x.powf(alpha);
                let got = power0(x, alpha);
                assert!(
                    (got - want).abs() <= 2.5 * f64::EPSILON * want,
                    "{x}^{alpha}: {got:e} against {want:e}"
                );
                x *= 1.001_3;
            }
            assert_eq!(power0(f64::INFINITY, alpha), f64::INFINITY.powf(alpha));
            assert_eq!(power0(0.0, alpha), 0f64.powf(alpha));
            assert!(power0(-1.0, alpha).is_nan());
            assert!(power0(f64::NAN, alpha).is_nan());
        }
        for alpha in [3.5, -3.5, 0.25, 1.0 / 3.0, -0.75] {
            assert_eq!(Power::of(alpha), Power::General, "{alpha}");
            assert_eq!(power0(0.7, alpha), 0.7f64.powf(alpha));
        }
    }
}
