//! Symbolic derivatives of an [`Expr`], for the expression-defined Hamiltonians
//! ([`ExprHamiltonian`](super::ExprHamiltonian)): `dq/dt = dH/dp` and `dp/dt = -dH/dq` are
//! derived once, at construction, as trees that a [`Tape`](super::Tape) then evaluates in
//! plain `f64` every step (a forward-mode dual pass per step would cost a dual operation per
//! node instead).
//!
//! The rules are the textbook ones (sum, product and chain rules, the quotient rule as
//! `(a/b)' = (a' - (a/b) b') / b`, `d(a^b) = a^b (b' ln a + b a' / a)`). Results are built by
//! simplifying constructors ([`sum`], [`product`], [`negate`]) that flatten nested sums and
//! products, fold their constant operands into one and drop zero terms and unit factors, so
//! that the derivative of `x^2/2 + x^2 y` is `x + 2 x y`, not a tree of zeros and ones.
//! Folding constants re-associates them (`0.5 * (2 * x)` becomes `1 * x = x`), so a derived
//! force can differ from a hand-written one in the last bits; it is never less accurate.

use super::expr::{Expr, Func};

/// A variable to differentiate by: the `i`-th entry of the first vector (`q`, or `y` of an
/// ODE), of the second vector (`qdot` or `p`), or time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Var {
    /// `q_i` ([`Expr::Q`]).
    First(usize),
    /// `qdot_i` or `p_i` ([`Expr::Qdot`]).
    Second(usize),
    /// `t` ([`Expr::T`]).
    Time,
}

// Exact comparisons: recognizing the literal constants 0, 1 and -1 of a tree.
#[allow(clippy::float_cmp)]
fn is_const(e: &Expr, c: f64) -> bool {
    matches!(e, Expr::Const(x) if *x == c)
}

/// `a_1 + a_2 + ...`, flattened, constants summed into one last term, zeros dropped.
pub fn sum(terms: impl IntoIterator<Item = Expr>) -> Expr {
    let mut out = Vec::new();
    let mut constant = 0.0;
    let mut push = |e: Expr, out: &mut Vec<Expr>| match e {
        Expr::Const(c) => constant += c,
        e => out.push(e),
    };
    for term in terms {
        match term {
            Expr::Add(inner) => inner.into_iter().for_each(|e| push(e, &mut out)),
            e => push(e, &mut out),
        }
    }
    if constant != 0.0 {
        out.push(Expr::Const(constant));
    }
    match out.len() {
        0 => Expr::Const(0.0),
        1 => out.pop().unwrap_or(Expr::Const(0.0)),
        _ => Expr::Add(out),
    }
}

/// `a_1 a_2 ...`, flattened, constants multiplied into one leading factor, ones dropped; `0`
/// if a constant factor is zero.
#[allow(clippy::float_cmp)] // exact: a factor of exactly 1 is dropped
pub fn product(factors: impl IntoIterator<Item = Expr>) -> Expr {
    let mut out = Vec::new();
    let mut constant = 1.0;
    let mut push = |e: Expr, out: &mut Vec<Expr>| match e {
        Expr::Const(c) => constant *= c,
        e => out.push(e),
    };
    for factor in factors {
        match factor {
            Expr::Mul(inner) => inner.into_iter().for_each(|e| push(e, &mut out)),
            e => push(e, &mut out),
        }
    }
    if constant == 0.0 {
        return Expr::Const(0.0);
    }
    if constant != 1.0 {
        out.insert(0, Expr::Const(constant));
    }
    match out.len() {
        0 => Expr::Const(1.0),
        1 => out.pop().unwrap_or(Expr::Const(1.0)),
        _ => Expr::Mul(out),
    }
}

/// `-a`: a constant or a product's constant factor changes sign; otherwise `Neg(a)`.
#[allow(clippy::float_cmp)] // exact: a factor of exactly 1 is dropped
pub fn negate(a: Expr) -> Expr {
    match a {
        Expr::Const(c) => Expr::Const(-c),
        Expr::Neg(inner) => *inner,
        Expr::Mul(mut factors) => {
            if let Some(Expr::Const(c)) = factors.first_mut() {
                *c = -*c;
                if *c == 1.0 {
                    factors.remove(0);
                }
                return product(factors);
            }
            factors.insert(0, Expr::Const(-1.0));
            Expr::Mul(factors)
        }
        a => Expr::Neg(Box::new(a)),
    }
}

fn quotient(a: Expr, b: Expr) -> Expr {
    if is_const(&a, 0.0) {
        return Expr::Const(0.0);
    }
    if is_const(&b, 1.0) {
        return a;
    }
    Expr::Div(Box::new(a), Box::new(b))
}

fn power(a: Expr, n: i32) -> Expr {
    match n {
        0 => Expr::Const(1.0),
        1 => a,
        n => Expr::Powi(Box::new(a), n),
    }
}

impl Expr {
    /// Whether the expression involves `var`.
    pub fn depends_on(&self, var: Var) -> bool {
        self.any_leaf(&|e| match (e, var) {
            (Expr::Q(i), Var::First(j)) | (Expr::Qdot(i), Var::Second(j)) => *i == j,
            (Expr::T, Var::Time) => true,
            _ => false,
        })
    }

    /// Whether the expression involves any `q_i` (`first`), any `qdot_i`/`p_i` (`second`)
    /// or `t`.
    pub fn uses(&self) -> (bool, bool, bool) {
        (
            self.any_leaf(&|e| matches!(e, Expr::Q(_))),
            self.any_leaf(&|e| matches!(e, Expr::Qdot(_))),
            self.any_leaf(&|e| matches!(e, Expr::T)),
        )
    }

    fn any_leaf(&self, pred: &dyn Fn(&Expr) -> bool) -> bool {
        let mut stack = vec![self];
        while let Some(e) = stack.pop() {
            if pred(e) {
                return true;
            }
            stack.extend(e.children());
        }
        false
    }

    /// The symbolic derivative `d self / d var`, simplified (see the module documentation).
    /// Parameters are constants. Recursion is as deep as the tree, which
    /// [`Expr::validate`] bounds.
    pub fn diff(&self, var: Var) -> Expr {
        let d = |e: &Expr| e.diff(var);
        match self {
            Expr::Const(_) | Expr::Param(_) => Expr::Const(0.0),
            Expr::Q(_) | Expr::Qdot(_) | Expr::T => {
                Expr::Const(if self.depends_on(var) { 1.0 } else { 0.0 })
            }
            Expr::Add(terms) => sum(terms.iter().map(d)),
            Expr::Mul(factors) => sum((0..factors.len()).map(|k| {
                let dk = d(&factors[k]);
                if is_const(&dk, 0.0) {
                    return dk;
                }
                product(
                    factors
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != k)
                        .map(|(_, f)| f.clone())
                        .chain(std::iter::once(dk)),
                )
            })),
            Expr::Sub(a, b) => sum([d(a), negate(d(b))]),
            Expr::Div(a, b) => {
                // (a/b)' = (a' - (a/b) b') / b: the quotient itself is reused (a program built
                // from the derivatives computes it once for every variable) and `b` is not
                // squared, so each derivative costs a product and a division more than `a/b`.
                let db = d(b);
                if is_const(&db, 0.0) {
                    return quotient(d(a), (**b).clone());
                }
                let numerator = sum([d(a), negate(product([self.clone(), db]))]);
                quotient(numerator, (**b).clone())
            }
            Expr::Neg(a) => negate(d(a)),
            Expr::Powi(a, n) => {
                let da = d(a);
                if is_const(&da, 0.0) {
                    return da;
                }
                product([Expr::Const(f64::from(*n)), power((**a).clone(), n - 1), da])
            }
            Expr::Powf(a, x) => {
                let da = d(a);
                if is_const(&da, 0.0) {
                    return da;
                }
                product([Expr::Const(*x), (**a).clone().powf(x - 1.0), da])
            }
            Expr::Pow(a, b) => {
                // (a^b)' = a^b (b' ln a + b a' / a)
                let (da, db) = (d(a), d(b));
                let log_part = product([db, (**a).clone().apply(Func::Ln)]);
                let base_part = quotient(product([(**b).clone(), da]), (**a).clone());
                let inner = sum([log_part, base_part]);
                if is_const(&inner, 0.0) {
                    return inner;
                }
                product([self.clone(), inner])
            }
            Expr::Func(f, a) => {
                let da = d(a);
                if is_const(&da, 0.0) {
                    return da;
                }
                let a = (**a).clone();
                let outer = match f {
                    Func::Sin => a.cos(),
                    Func::Cos => negate(a.sin()),
                    // 1 / cos^2 a
                    Func::Tan => quotient(Expr::Const(1.0), power(a.cos(), 2)),
                    Func::Exp => a.apply(Func::Exp),
                    Func::Ln => quotient(Expr::Const(1.0), a),
                    Func::Sqrt => quotient(Expr::Const(0.5), a.apply(Func::Sqrt)),
                    Func::Sinh => a.apply(Func::Cosh),
                    Func::Cosh => a.apply(Func::Sinh),
                    Func::Tanh => quotient(Expr::Const(1.0), power(a.apply(Func::Cosh), 2)),
                    Func::Asin | Func::Acos => {
                        let root = sum([Expr::Const(1.0), negate(power(a, 2))]).apply(Func::Sqrt);
                        let sign = if *f == Func::Asin { 1.0 } else { -1.0 };
                        quotient(Expr::Const(sign), root)
                    }
                    Func::Atan => quotient(Expr::Const(1.0), sum([Expr::Const(1.0), power(a, 2)])),
                    // sign(a), undefined (NaN) at a = 0 like the derivative itself.
                    Func::Abs => quotient(a.clone(), a.apply(Func::Abs)),
                };
                product([outer, da])
            }
        }
    }
}
