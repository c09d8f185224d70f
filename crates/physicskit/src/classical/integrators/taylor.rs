//! `taylor`: an adaptive Taylor method of high order.
//!
//! Each step expands the solution through the current state as a truncated Taylor series,
//! `y(t + τ) = Σ_k y^[k] τ^k` for `k = 0..=p`, whose normalized coefficients
//! `y^[k] = y^(k)/k!` a [`TaylorField`] computes exactly (to rounding) by automatic
//! differentiation of truncated power series: one recurrence per operation of the field
//! (`taylor_tape.rs` in `lagrangian/` generates them from expression trees).
//!
//! **Order and step** (Jorba & Zou, *Exp. Math.* 14 (2005) 99, with the safety factor of
//! heyoka, Biscani & Izzo, *MNRAS* 504 (2021) 2614): each step takes
//! `h = ρ (ε e^-0.7)^(1/(p - 1))` with `ρ = min((s/‖y^[p-1]‖∞)^(1/(p-1)), (s/‖y^[p]‖∞)^(1/p))`,
//! the series' radius of convergence as its last two orders estimate it, `ε = min(rtol, atol)`
//! the tighter tolerance, and `s = 1` while `rtol ‖y‖∞ ≤ atol` (absolute control), `s = ‖y‖∞`
//! otherwise (relative control). The coefficients fall like `s/ρ^k`, so the first term left
//! out, about `s (h/ρ)^(p+1)`, is below `s ε e^-0.7`: no step is rejected, and the step follows the
//! radius of convergence of the series. The order is fixed for a run: the one that covers a
//! unit of time with the least work, by a count of the field's operations
//! ([`TaylorField::step_cost`], [`order_for`]). A higher order takes longer steps
//! (`h/ρ = (ε e^-0.7)^(1/(p - 1))` nears 1) for more work per step; Jorba and Zou's
//! `p = ⌈-ln(ε)/2 + 1⌉`, steps of `ρ/e²`, is the best where the work is all in the
//! recurrences' products (quadratic in the order), and the work that grows less with the
//! order (sums, the update, the radius) moves the best order up, to steps of
//! `ρ e^-1.2` to `ρ e^-1.7` for the forces of the benchmarks (`benchmarks/README.md` has the
//! times).
//!
//! **Dense output**: a step's polynomial is the solution over the whole step, so outputs on
//! the grid (`dt` is the output spacing, as for `dop853`) are the polynomial evaluated at the
//! output time; the last step is shortened to land on `t1` exactly. Steps do not depend on the
//! output spacing.
//!
//! **Long runs**: the polynomial is evaluated by compensated Horner (Graillat, Langlois &
//! Louvet 2005: error-free products and sums, the rounding errors summed alongside) over its
//! orders 0 to 3; the higher orders, which the step size makes small beside the state, are
//! summed by plain Horner first (`taylor_arith.rs`'s `COMPENSATED_ORDERS` gives the bound),
//! and the state is carried as a double-double: the sum's error, with the state's own low
//! word, is kept in a second word rather than rounded away, so a step adds no rounding of the
//! state (its double, which the field is expanded at and every output reads, is the pair
//! rounded once). Over 100 Kepler orbits (e = 0.5) at tol 1e-16 this cuts the median final
//! error over many starts about eightfold, below 1e-12 (the energy error is a random walk of
//! the per-step errors, and the rounding of the state was the largest of them;
//! `benchmarks/README.md`). The clock is a double-double too, so it does not drift over
//! millions of steps.
//!
//! **Instruction sets**: the error-free product `a b = p + e` is one fused multiply-add,
//! `e = fma(a, b, -p)`, on x86-64 CPUs with FMA (detected at run time by std's
//! `is_x86_feature_detected!`, cached), and Dekker's product (Veltkamp's split, no FMA)
//! elsewhere. Both give the exact `e`, so the same bits, unless an operand exceeds `2^996`
//! (the split overflows) or the product's error underflows: far from any state and step of an
//! integration. The rows of the state are evaluated four at a time, in the four lanes of one
//! vector where the CPU has AVX2 (independent chains the CPU overlaps elsewhere), each with
//! the operations of one row alone: from blocks of four rows, each order's four coefficients
//! side by side, which the recurrences' code written for AVX stores as it computes them
//! ([`TaylorField::expansion_in_blocks`]) and which the stepper otherwise transposes the
//! rows into.
//!
//! **Step size without `powf`**: the two roots of the step-size rule are `2^(log2(·)/k)`,
//! with `log2` and `2^y` written in plain arithmetic (`taylor_arith.rs`: a series of
//! `atanh` and one of `2^f`, the exponents from the doubles' bits), within 1e-13 of `powf`'s
//! roots: the same step to thirteen digits, no libm call, and the ensembles' lanes compute
//! their step sizes in vector registers with this stepper's bits.
//! The Taylor coefficients themselves never use FMA (`symbolic/taylor_tape.rs`).

use std::collections::BTreeMap;

use ndarray::{Array1, Array2};

use crate::classical::core::method::{MethodInfo, Scheme};
use crate::classical::core::{Error, ExtraValue, Result, SimulationResult, TimeGrid};
use crate::classical::integrators::field::VectorField;
use crate::classical::integrators::stepper::{AdaptiveStepper, FieldStepper, Report};
use crate::classical::integrators::system::DynamicalSystem;
use crate::classical::integrators::taylor_arith::{
    log_target, two_product, two_product_fused, two_sum, StepRule, COMPENSATED_ORDERS,
};
use crate::classical::integrators::Tolerances;

/// The method's facts: the [`Taylor`](Scheme::Taylor) kind, so it runs only on systems with a
/// Taylor form ([`DynamicalSystem::taylor_field`]). Its order is chosen per run from the
/// tolerances and the field's work ([`order_for`], from 2 up to [`MAX_ORDER`]); `order`
/// declares the highest.
pub const INFO: MethodInfo = MethodInfo {
    name: "taylor",
    label: "Taylor",
    summary: "adaptive Taylor series method on systems defined by expressions: order 2 to 24 \
              from the tolerance and the work of the system's recurrences (the least work per \
              unit of time), step from the last two Taylor coefficients (Jorba-Zou), dense \
              output from the step polynomial",
    order: MAX_ORDER as u32,
    symplectic: false,
    separable_only: false,
    evaluations_per_step: 1,
    evaluations: "Taylor expansions of the field to order p per step (each costs about p^2/2 \
                  times an evaluation of the field's operations)",
    reference: "A. Jorba and M. Zou, Exp. Math. 14 (2005) 99; F. Biscani and D. Izzo, \
                MNRAS 504 (2021) 2614",
    scheme: Scheme::Taylor,
};

/// The systems that have a Taylor form, for messages.
pub const TAYLOR_SYSTEMS: &str = "systems defined by expressions: Python's HamiltonianEngine, \
     LagrangianEngine and ODEEngine (Rust's ExprHamiltonian, ExprLagrangian and ExprOde), \
     every Lagrangian system (the catalogue's Lagrangian family, whose generic L is traced into \
     an expression), and the Kepler and Hénon–Heiles systems (their H is traced likewise)";

/// The refusal of the `taylor` method by `system` (a name, or a description such as "this \
/// Hamiltonian system"), which has no Taylor form: the one message every front end gives.
pub fn no_taylor_form(system: &str) -> Error {
    Error::UnsupportedMethod {
        method: INFO.name.into(),
        reason: format!(
            "{system} has a hand-written field and no Taylor form (its field as expressions, \
             from which the Taylor recurrences are generated); `taylor` runs on {TAYLOR_SYSTEMS}; \
             use dop853 for the same tolerances here"
        ),
    }
}

/// The system's type for messages (`KeplerSystem`, from its path), or "this system" behind a
/// trait object, whose type names only the trait.
fn system_name<S: ?Sized>() -> String {
    let full = std::any::type_name::<S>();
    let short = full.split('<').next().unwrap_or(full);
    match short.rsplit("::").next() {
        Some(name) if !full.starts_with("dyn ") && !name.is_empty() => format!("`{name}`"),
        _ => "this system".into(),
    }
}

/// Highest order the method uses: `ε = 1e-18` needs 22; tighter tolerances than double
/// precision can deliver gain nothing from more terms.
pub const MAX_ORDER: usize = 24;

/// An expansion's rows, and the same coefficients in the stepper's blocks if the field wrote
/// them so ([`TaylorField::expansion_in_blocks`]).
pub type InBlocks<'a> = (&'a [f64], Option<&'a [[f64; LANES]]>);

/// A vector field that can expand the solution through a point as a Taylor series (`Any`: an
/// ensemble recognizes the program behind a system's Taylor form, to share it).
pub trait TaylorField: std::any::Any {
    /// Dimension of the state.
    fn dim(&self) -> usize;

    /// The work of a step on this field, by which [`order_for`] chooses the order. The
    /// default takes the recurrences as one product per row ([`StepCost::generic`]).
    fn step_cost(&self) -> StepCost {
        StepCost::generic(self.dim())
    }

    /// The normalized Taylor coefficients of the solution through `(t, y)` to `order`,
    /// `y_i^[0] = y_i`, `y_i^[k+1] = f_i^[k] / (k + 1)`: `dim` rows of `order + 1`, row `i`
    /// holding `y_i^[0..=order]`, borrowed from the field's own storage (valid until its next
    /// expansion), so the stepper reads them where the recurrences wrote them.
    ///
    /// # Errors
    /// If the expansion is not defined at `(t, y)` (a division by a series with zero
    /// constant term, a logarithm of zero ...), `y` is not of the field's dimension, or
    /// `order` exceeds what the field was built for.
    fn expansion(&mut self, t: f64, y: &[f64], order: usize) -> Result<&[f64]>;

    /// [`expansion`](Self::expansion) copied into `coefficients` (`dim` rows of `order + 1`).
    ///
    /// # Errors
    /// As [`expansion`](Self::expansion), and for `coefficients` of another length.
    fn coefficients(
        &mut self,
        t: f64,
        y: &[f64],
        order: usize,
        coefficients: &mut [f64],
    ) -> Result<()> {
        let rows = self.expansion(t, y, order)?;
        if rows.len() != coefficients.len() {
            return Err(Error::invalid(
                "coefficients",
                coefficients.len() as f64,
                format!("needs room for {} coefficients", rows.len()),
            ));
        }
        coefficients.copy_from_slice(rows);
        Ok(())
    }

    /// [`expansion`](Self::expansion), and the same coefficients side by side in blocks of
    /// [`LANES`] rows where the field writes them so as well (the layout the stepper
    /// evaluates, which it otherwise transposes the rows into): `dim.div_ceil(LANES)` blocks
    /// of `order + 1` groups, group `k` of a block holding coefficient `k` of its rows, the
    /// lanes past the last row zeros. The default writes no blocks (`None`).
    ///
    /// # Errors
    /// As [`expansion`](Self::expansion).
    fn expansion_in_blocks(
        &mut self,
        t: f64,
        y: &[f64],
        order: usize,
    ) -> Result<InBlocks<'_>> {
        Ok((self.expansion(t, y, order)?, None))
    }
}

/// The tightest relative tolerance the method accepts: `2^-54`, half the unit roundoff. A
/// double's rounding error relative to its value is at least this (just below a power of
/// two) and at most `2^-53`, so no double result can be held to a tighter `rtol`.
pub const MIN_RTOL: f64 = f64::EPSILON / 4.0;

/// Checks tolerances for the Taylor method, beyond [`Tolerances::validate`] (finite and
/// positive): `rtol` from [`MIN_RTOL`] (tighter than any double can hold) up to below 1 (a
/// relative tolerance of 1 or more asks for no correct digit, and would run at order 2 with
/// steps as long as the series' radius of convergence allows). `atol` has no scale of its
/// own (it is in the state's units): any positive value is accepted, and an `atol` so small
/// that the order rule asks for more than [`MAX_ORDER`] terms runs at [`MAX_ORDER`] (the run
/// reports its `order`).
///
/// # Errors
/// [`Error::InvalidParameter`] naming the offending field.
pub fn check_tolerances(tolerances: &Tolerances) -> Result<()> {
    tolerances.validate()?;
    let rtol = tolerances.rtol;
    if rtol < MIN_RTOL {
        return Err(Error::invalid(
            "rtol",
            rtol,
            format!(
                "is below what double precision can reach: a double's rounding is at least \
                 {MIN_RTOL:.3e} of its value (2^-54), so the taylor method accepts rtol >= that"
            ),
        ));
    }
    if rtol >= 1.0 {
        return Err(Error::invalid(
            "rtol",
            rtol,
            "must be below 1 for the taylor method: a relative tolerance of 1 or more asks \
             for no correct digit",
        ));
    }
    Ok(())
}

/// The work of one step of the method at order `p`, in multiply-adds, as a field's
/// recurrences and the stepper's update need it: the convolutions (a product's or a
/// function's order `k` sums `k + 1` terms), the work at each order that does not grow with
/// it (sums, scalings, the update's Horner step of each row) and the work once per step (the
/// update's compensated low orders, the norms and the radius):
/// `convolution · p(p + 1)/2 + per_order · (p + 1) + per_step`. [`order_for`] weighs it
/// against the step's length to choose the order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepCost {
    /// Multiply-adds per term of the convolutions at each order.
    pub convolution: f64,
    /// Multiply-adds at each order besides the convolutions.
    pub per_order: f64,
    /// Multiply-adds once per step.
    pub per_step: f64,
}

impl StepCost {
    /// The stepper's own work for `dim` rows, beside the field's recurrences: at each order
    /// the scaling of each row's new coefficient and its Horner step in the update; once per
    /// step the update's compensated part (an error-free product and sum, about eight
    /// operations, for each of its five coefficients of each row: the compensated orders and
    /// the plain sum of the others), the three norms and the radius's two logarithms and power
    /// (about 30 operations each).
    pub fn stepper(dim: usize) -> Self {
        let dim = dim as f64;
        Self {
            convolution: 0.0,
            per_order: 2.0 * dim,
            per_step: (8.0 * (COMPENSATED_ORDERS as f64 + 1.0) + 3.0) * dim + 90.0,
        }
    }

    /// A field of `dim` rows that reports nothing of its recurrences, taken as one product
    /// per row, and the stepper's work ([`stepper`](Self::stepper)).
    pub fn generic(dim: usize) -> Self {
        Self {
            convolution: dim as f64,
            ..Self::stepper(dim)
        }
    }

    /// The multiply-adds of one step at order `p`.
    pub fn work(&self, p: usize) -> f64 {
        let p = p as f64;
        self.convolution * p * (p + 1.0) / 2.0 + self.per_order * (p + 1.0) + self.per_step
    }
}

/// The order the method uses for tolerances `rtol`, `atol` on a field whose steps cost
/// `cost`: the order `p` from 2 to [`MAX_ORDER`] with the least work per unit of time,
/// `cost.work(p) / h(p)`. With the tightest tolerance `ε = min(rtol, atol)` (at least about
/// `1e-20`), the step `h(p) = ρ (ε e^-0.7)^(1/(p - 1))` (ρ the series' radius of
/// convergence, the same for every order) keeps the truncation error at `ε` (the module
/// documentation). Jorba and Zou's `p = -ln(ε)/2 + 1` is the least work of a step made only
/// of convolutions; the work that grows more slowly with the order (sums, the stepper's
/// update, the radius) favours higher orders and longer steps. Ties go to the lower order.
pub fn order_for(tolerances: &Tolerances, cost: &StepCost) -> usize {
    let target = log_target(tolerances);
    // The logarithm of the work per unit of time (ρ left out).
    let per_time = |p: usize| cost.work(p).ln() - target / (p - 1) as f64;
    let mut best = (2, per_time(2));
    for p in 3..=MAX_ORDER {
        let work = per_time(p);
        // A NaN (no cost or tolerance that validates gives one) keeps the lower order.
        if work < best.1 {
            best = (p, work);
        }
    }
    best.0
}

/// Rows evaluated side by side (by the compensated Horner, and as the stepper's blocks of
/// coefficients: [`TaylorField::expansion_in_blocks`]): independent chains the CPU overlaps,
/// the four lanes of a vector of doubles.
pub const LANES: usize = 4;

/// Compensated Horner of each row of `c` (rows of `n1` coefficients) at `x` into `out`, `LANES`
/// rows at a time (each row's operations are those of [`compensated_horner`], in its order);
/// error-free products by FMA if `FUSED`.
#[inline(always)]
fn horner_rows<const FUSED: bool>(c: &[f64], n1: usize, x: f64, out: &mut [f64]) {
    let product = if FUSED {
        two_product_fused
    } else {
        two_product
    };
    for (rows, out) in c.chunks(n1 * LANES).zip(out.chunks_mut(LANES)) {
        let m = out.len();
        let (mut s, mut err) = ([0.0; LANES], [0.0; LANES]);
        for (r, sr) in s[..m].iter_mut().enumerate() {
            *sr = rows[r * n1 + n1 - 1];
        }
        for k in (0..n1 - 1).rev() {
            for (r, (sr, er)) in s[..m].iter_mut().zip(&mut err[..m]).enumerate() {
                let (p, pi) = product(*sr, x);
                let (sum, sigma) = two_sum(p, rows[r * n1 + k]);
                *sr = sum;
                *er = *er * x + (pi + sigma);
            }
        }
        for ((o, sr), er) in out.iter_mut().zip(&s).zip(&err) {
            *o = sr + er;
        }
    }
}

/// [`horner_rows`] with FMA (compiled for it; called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
fn horner_rows_fma(c: &[f64], n1: usize, x: f64, out: &mut [f64]) {
    horner_rows::<true>(c, n1, x, out);
}

/// Compensated Horner of each row of `c` (rows of `n1` coefficients, `n1 >= 1`, `out.len()`
/// rows) at `x` into `out`, on the FMA path where the CPU has FMA.
#[inline]
fn eval_rows(c: &[f64], n1: usize, x: f64, out: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has FMA (checked just above), the one feature the function enables.
        #[allow(unsafe_code)]
        unsafe {
            horner_rows_fma(c, n1, x, out);
        }
        return;
    }
    horner_rows::<false>(c, n1, x, out);
}

/// Horner of the rows held side by side in `blocks` (each block `n1` groups of `LANES`
/// lanes, group `k` holding coefficient `k` of `LANES` rows; lanes past the last row hold
/// zeros) at `x`, plus each row's low word `lo`, into `out`: plain from the highest order down
/// to [`COMPENSATED_ORDERS`], then compensated (the operations of [`compensated_horner`]),
/// each group's lanes as one vector operation where the target has vectors of four doubles;
/// the low word joins the summed errors before the one rounding. With `out_lo`, the
/// rounding's error goes there (`out + out_lo` is the sum as a double-double). Error-free
/// products by FMA if `FUSED`.
#[inline(always)]
fn horner_blocks<const FUSED: bool>(
    blocks: &[[f64; LANES]],
    n1: usize,
    x: f64,
    lo: &[f64],
    out: &mut [f64],
    mut out_lo: Option<&mut [f64]>,
) {
    let product = if FUSED {
        two_product_fused
    } else {
        two_product
    };
    for (b, (block, out)) in blocks
        .chunks_exact(n1)
        .zip(out.chunks_mut(LANES))
        .enumerate()
    {
        let mut s = block[n1 - 1];
        let mut err = [0.0; LANES];
        let plain = COMPENSATED_ORDERS.min(n1 - 1);
        for c in block[plain..n1 - 1].iter().rev() {
            for r in 0..LANES {
                s[r] = s[r] * x + c[r];
            }
        }
        for c in block[..plain].iter().rev() {
            for r in 0..LANES {
                let (p, pi) = product(s[r], x);
                let (sum, sigma) = two_sum(p, c[r]);
                s[r] = sum;
                err[r] = err[r] * x + (pi + sigma);
            }
        }
        let rows = b * LANES..b * LANES + out.len();
        if let (Ok(out), Some(lo)) = (
            <&mut [f64; LANES]>::try_from(&mut *out),
            lo.get(rows.clone()).and_then(|lo| <&[f64; LANES]>::try_from(lo).ok()),
        ) {
            // A whole block: its rows' sums as vector operations.
            let mut low = [0.0; LANES];
            for r in 0..LANES {
                (out[r], low[r]) = two_sum(s[r], err[r] + lo[r]);
            }
            if let Some(out_lo) = out_lo.as_deref_mut() {
                out_lo[rows].copy_from_slice(&low);
            }
            continue;
        }
        for (r, o) in out.iter_mut().enumerate() {
            let row = b * LANES + r;
            let (hi, low) = two_sum(s[r], err[r] + lo[row]);
            *o = hi;
            if let Some(out_lo) = out_lo.as_deref_mut() {
                out_lo[row] = low;
            }
        }
    }
}

/// [`horner_blocks`] with FMA and vectors of four doubles (compiled for them; called only
/// where the CPU has both).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn horner_blocks_avx2(
    blocks: &[[f64; LANES]],
    n1: usize,
    x: f64,
    lo: &[f64],
    out: &mut [f64],
    out_lo: Option<&mut [f64]>,
) {
    horner_blocks::<true>(blocks, n1, x, lo, out, out_lo);
}

/// [`horner_blocks`] with FMA, without vectors (called only where the CPU has FMA).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
fn horner_blocks_fma(
    blocks: &[[f64; LANES]],
    n1: usize,
    x: f64,
    lo: &[f64],
    out: &mut [f64],
    out_lo: Option<&mut [f64]>,
) {
    horner_blocks::<true>(blocks, n1, x, lo, out, out_lo);
}

/// [`horner_blocks`] (plain over the high orders, compensated over the low ones) of the rows
/// side by side in `blocks` (`n1 >= 1`,
/// `out.len()` rows, `lo` at least as many low words) at `x` into `out` (and the low words of
/// the results into `out_lo`), in vector lanes where the CPU has AVX2 and FMA.
#[inline]
fn eval_blocks(
    blocks: &[[f64; LANES]],
    n1: usize,
    x: f64,
    lo: &[f64],
    out: &mut [f64],
    out_lo: Option<&mut [f64]>,
) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("fma") {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 and FMA (checked just above), the features the
            // function enables.
            #[allow(unsafe_code)]
            unsafe {
                horner_blocks_avx2(blocks, n1, x, lo, out, out_lo);
            }
        } else {
            // SAFETY: the CPU has FMA (checked just above), the one feature the function
            // enables.
            #[allow(unsafe_code)]
            unsafe {
                horner_blocks_fma(blocks, n1, x, lo, out, out_lo);
            }
        }
        return;
    }
    horner_blocks::<false>(blocks, n1, x, lo, out, out_lo);
}

/// The `dim` rows of `c` (`n1 >= 1` coefficients each) side by side in `blocks` (`n1` groups
/// of `LANES` per `LANES` rows; the lanes past the last row are left as they are: zeros in the
/// stepper's buffers, which never write them), and whether every coefficient is finite, in
/// one pass over the groups. In vector registers of four doubles where the CPU has AVX2 (a
/// transposition, bit for bit the plain one's).
fn to_blocks_checked(c: &[f64], dim: usize, n1: usize, blocks: &mut [[f64; LANES]]) -> bool {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (checked just above), the one feature the function
        // enables.
        #[allow(unsafe_code)]
        return unsafe { to_blocks_checked_avx2(c, dim, n1, blocks) };
    }
    to_blocks_checked_plain(c, dim, n1, blocks)
}

/// [`blocks_checked`] compiled for AVX2 (called only where the CPU has it), each whole block
/// transposed four orders at a time by [`transpose_avx2`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn to_blocks_checked_avx2(c: &[f64], dim: usize, n1: usize, blocks: &mut [[f64; LANES]]) -> bool {
    blocks_checked(c, dim, n1, blocks, |rows, block, zero| {
        transpose_avx2(rows, block, zero);
    })
}

/// Four rows (`block.len()` coefficients each) into the groups of `block`, `zero` summing
/// every coefficient's `x · 0` ([`blocks_checked`]): four orders at a time as a 4×4
/// transposition in vector registers, the orders left over one group at a time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn transpose_avx2(rows: [&[f64]; LANES], block: &mut [[f64; LANES]], zero: &mut [f64; LANES]) {
    use std::arch::x86_64::{
        _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_permute2f128_pd,
        _mm256_setzero_pd, _mm256_storeu_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
    };
    let [r0, r1, r2, r3] = rows;
    let whole = block.len() / 4 * 4;
    // SAFETY: every load reads four doubles of a row at `k..k + 4` and every store writes
    // the four groups `k..k + 4` of `block` (16 doubles, contiguous in `[[f64; 4]]`), with
    // `k + 4 <= whole <= block.len()`, the length of each row and of `block`; unaligned
    // loads and stores; the CPU has AVX2 (this function's feature).
    #[allow(unsafe_code)]
    unsafe {
        let nought = _mm256_setzero_pd();
        let mut z = _mm256_loadu_pd(zero.as_ptr());
        for k in (0..whole).step_by(4) {
            let a = _mm256_loadu_pd(r0.as_ptr().add(k));
            let b = _mm256_loadu_pd(r1.as_ptr().add(k));
            let c = _mm256_loadu_pd(r2.as_ptr().add(k));
            let d = _mm256_loadu_pd(r3.as_ptr().add(k));
            z = _mm256_add_pd(z, _mm256_mul_pd(a, nought));
            z = _mm256_add_pd(z, _mm256_mul_pd(b, nought));
            z = _mm256_add_pd(z, _mm256_mul_pd(c, nought));
            z = _mm256_add_pd(z, _mm256_mul_pd(d, nought));
            // (a0 b0 a2 b2), (a1 b1 a3 b3), (c0 d0 c2 d2), (c1 d1 c3 d3)
            let ab_even = _mm256_unpacklo_pd(a, b);
            let ab_odd = _mm256_unpackhi_pd(a, b);
            let cd_even = _mm256_unpacklo_pd(c, d);
            let cd_odd = _mm256_unpackhi_pd(c, d);
            let out = block.as_mut_ptr().add(k).cast::<f64>();
            _mm256_storeu_pd(out, _mm256_permute2f128_pd(ab_even, cd_even, 0x20));
            _mm256_storeu_pd(out.add(4), _mm256_permute2f128_pd(ab_odd, cd_odd, 0x20));
            _mm256_storeu_pd(out.add(8), _mm256_permute2f128_pd(ab_even, cd_even, 0x31));
            _mm256_storeu_pd(out.add(12), _mm256_permute2f128_pd(ab_odd, cd_odd, 0x31));
        }
        _mm256_storeu_pd(zero.as_mut_ptr(), z);
    }
    transpose_orders(rows, &mut block[whole..], whole, zero);
}

/// [`blocks_checked`] for any CPU, each whole block transposed group by group. Not inlined,
/// as the AVX2 clone is not: as a function of its own its slices are known not to overlap.
#[inline(never)]
fn to_blocks_checked_plain(c: &[f64], dim: usize, n1: usize, blocks: &mut [[f64; LANES]]) -> bool {
    blocks_checked(c, dim, n1, blocks, |rows, block, zero| {
        transpose_orders(rows, block, 0, zero);
    })
}

/// The orders `from..` of four rows into `groups` (the groups of those orders), one group at
/// a time, `zero` summing each coefficient's `x · 0`.
#[inline(always)]
fn transpose_orders(
    rows: [&[f64]; LANES],
    groups: &mut [[f64; LANES]],
    from: usize,
    zero: &mut [f64; LANES],
) {
    for (j, slot) in groups.iter_mut().enumerate() {
        let k = from + j;
        let group = rows.map(|row| row[k]);
        *slot = group;
        add_zeros(zero, &group);
    }
}

/// `zero += group · 0`, lane by lane: each lane's sum of `x · 0` is a zero for finite `x` and
/// NaN otherwise, so a lane's sum is a zero exactly when all its coefficients are finite, in
/// any order (no branch, in vector lanes). [`all_zeros`] reads the verdict.
#[inline(always)]
fn add_zeros(zero: &mut [f64; LANES], group: &[f64; LANES]) {
    for r in 0..LANES {
        zero[r] += group[r] * 0.0;
    }
}

/// Whether every lane's sum of [`add_zeros`] is a zero: every coefficient finite.
#[inline(always)]
fn all_zeros(zero: &[f64; LANES]) -> bool {
    zero.iter().all(|&z| z == 0.0)
}

/// [`to_blocks_checked`]'s pass, block by block: a whole block's four rows transposed into
/// its groups by `whole(rows, block, zero)`, which also sums each coefficient's `x · 0` into
/// `zero`, or the rows of the last, partial block one by one.
#[inline(always)]
fn blocks_checked(
    c: &[f64],
    dim: usize,
    n1: usize,
    blocks: &mut [[f64; LANES]],
    whole: impl Fn([&[f64]; LANES], &mut [[f64; LANES]], &mut [f64; LANES]),
) -> bool {
    let mut zero = [0.0_f64; LANES];
    let full = dim / LANES;
    for b in 0..dim.div_ceil(LANES) {
        let block = &mut blocks[b * n1..(b + 1) * n1];
        let rows = &c[b * LANES * n1..(b * LANES + LANES).min(dim) * n1];
        if b < full {
            let four = std::array::from_fn(|r| &rows[r * n1..(r + 1) * n1]);
            whole(four, block, &mut zero);
        } else {
            for (r, row) in rows.chunks_exact(n1).enumerate() {
                for (group, &x) in block.iter_mut().zip(row) {
                    group[r] = x;
                }
            }
            for group in block.iter() {
                add_zeros(&mut zero, group);
            }
        }
    }
    all_zeros(&zero)
}

/// Whether `blocks` hold `rows` (`dim` rows of `n1`) as [`to_blocks_checked`] places them, bit
/// for bit, with zeros in the lanes past the last row: what a field's
/// [`TaylorField::expansion_in_blocks`] promises (checked in debug builds).
fn blocks_hold_rows(blocks: &[[f64; LANES]], rows: &[f64], dim: usize, n1: usize) -> bool {
    blocks.iter().enumerate().all(|(at, group)| {
        let (b, j) = (at / n1, at % n1);
        (0..LANES).all(|r| {
            let row = b * LANES + r;
            let want = if row < dim { rows[row * n1 + j] } else { 0.0 };
            group[r].to_bits() == want.to_bits()
        })
    })
}

/// `from` copied into `to` (of the same length), and whether every coefficient is finite: the
/// same sum of `x · 0` as [`blocks_checked`] (in any order: a zero exactly when all are
/// finite), in vector registers of four doubles where the CPU has AVX2.
fn copy_checked(from: &[[f64; LANES]], to: &mut [[f64; LANES]]) -> bool {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (checked just above), the one feature the function
        // enables.
        #[allow(unsafe_code)]
        return unsafe { copy_checked_avx2(from, to) };
    }
    copy_checked_plain(from, to)
}

/// [`copy_checked`] compiled for AVX2 (called only where the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn copy_checked_avx2(from: &[[f64; LANES]], to: &mut [[f64; LANES]]) -> bool {
    copy_checked_plain(from, to)
}

/// [`copy_checked`] for any CPU.
#[inline(always)]
fn copy_checked_plain(from: &[[f64; LANES]], to: &mut [[f64; LANES]]) -> bool {
    let mut zero = [0.0_f64; LANES];
    for (to, from) in to.iter_mut().zip(from) {
        *to = *from;
        add_zeros(&mut zero, from);
    }
    all_zeros(&zero)
}

/// `Σ_k c_k x^k` by compensated Horner: as accurate as Horner in twice the working precision,
/// then rounded once.
#[inline]
pub fn compensated_horner(c: &[f64], x: f64) -> f64 {
    if c.is_empty() {
        return 0.0;
    }
    let mut out = [0.0];
    eval_rows(c, c.len(), x, &mut out);
    out[0]
}

/// The adaptive Taylor stepper: its own steps, the last step's polynomial kept for output.
#[derive(Debug, Clone)]
pub struct Taylor {
    dim: usize,
    order: usize,
    tolerances: Tolerances,
    /// The current step's Taylor coefficients side by side in vector lanes, for the state
    /// update and the outputs.
    blocks: Vec<[f64; LANES]>,
    /// The next step's, filled by its expansion and swapped in when it is taken.
    next_blocks: Vec<[f64; LANES]>,
    /// Start of the current polynomial's step, as a double-double `(hi, lo)`.
    start: (f64, f64),
    /// The clock after the last step (the end of the current polynomial's step).
    t: (f64, f64),
    /// The state at `t`, rounded: `y + lo` is the state carried.
    y: Vec<f64>,
    /// The state's low words (see the module documentation: the state as a double-double).
    lo: Vec<f64>,
    /// The low words of the current polynomial's start, whose high words are its order 0.
    start_lo: Vec<f64>,
    /// Length of the current polynomial's step (signed); 0 before the first step.
    h: f64,
    /// The end of the integration: the last step lands on it exactly.
    t_bound: f64,
    accepted: u64,
    smallest: f64,
    largest: f64,
    /// The step-size rule at the run's order.
    rule: StepRule,
}

impl Taylor {
    /// A stepper for `field` at `(t0, y0)` towards `t_bound`, at the order [`order_for`]
    /// chooses for the tolerances and the field's [`step_cost`](TaylorField::step_cost).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a state of the wrong length or not finite, or
    /// tolerances that [`check_tolerances`] refuses.
    pub fn new<F: TaylorField + ?Sized>(
        field: &F,
        tolerances: Tolerances,
        t0: f64,
        y0: &[f64],
        t_bound: f64,
    ) -> Result<Self> {
        check_tolerances(&tolerances)?;
        let dim = field.dim();
        if y0.len() != dim {
            return Err(Error::invalid(
                "y0",
                y0.len() as f64,
                format!("needs {dim} components"),
            ));
        }
        if let Some(bad) = y0.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid("y0", *bad, "must be finite"));
        }
        let order = order_for(&tolerances, &field.step_cost());
        Ok(Self {
            dim,
            order,
            tolerances,
            blocks: vec![[0.0; LANES]; dim.div_ceil(LANES) * (order + 1)],
            next_blocks: vec![[0.0; LANES]; dim.div_ceil(LANES) * (order + 1)],
            start: (t0, 0.0),
            t: (t0, 0.0),
            y: y0.to_vec(),
            lo: vec![0.0; dim],
            start_lo: vec![0.0; dim],
            h: 0.0,
            t_bound,
            accepted: 0,
            smallest: f64::INFINITY,
            largest: 0.0,
            rule: StepRule::new(&tolerances, order),
        })
    }

    /// The order of the series (fixed by the tolerances).
    pub fn order(&self) -> usize {
        self.order
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.accepted
    }

    /// Signed time from the current step's start to `t`, in double-double.
    #[inline]
    fn offset(&self, t: f64) -> f64 {
        (t - self.t.0) - self.t.1
    }

    /// Expands at the current state and chooses the step toward `t_bound` (not yet taken).
    fn expand<F: TaylorField + ?Sized>(&mut self, field: &mut F) -> Result<f64> {
        let (p, n1) = (self.order, self.order + 1);
        let t = self.t.0;
        let fail = |step: f64, reason: String| Error::StepSizeTooSmall { t, step, reason };
        if self.accepted >= self.tolerances.max_steps {
            return Err(fail(
                self.h,
                format!(
                    "the step budget max_steps = {} is spent; raise max_steps or loosen the \
                     tolerances",
                    self.tolerances.max_steps
                ),
            ));
        }
        let (rows, blocks) = field.expansion_in_blocks(t, &self.y, p)?;
        if rows.len() != self.dim * n1 {
            return Err(Error::invalid(
                "Taylor field",
                rows.len() as f64,
                format!("gave coefficients for other than {} rows of {n1}", self.dim),
            ));
        }
        // The step size first, from the rows as the recurrences wrote them (the largest
        // magnitudes of the rule's orders: `f64::max`'s values, which pass over a NaN, in any
        // order give the same), so that its chain of operations overlaps the blocks' copy.
        // `x > norm` is false for a NaN, so the select is `f64::max` with a norm that is never
        // NaN, and one `maxsd`; the rows by index, as their length was checked just above.
        let mut norms = [0.0_f64; 3];
        let orders = self.rule.norm_orders();
        for i in 0..self.dim {
            let row = &rows[i * n1..(i + 1) * n1];
            for (norm, k) in norms.iter_mut().zip(orders) {
                let x = row[k].abs();
                if x > *norm {
                    *norm = x;
                }
            }
        }
        let rho = self.rule.radius(norms);
        // Into the spare blocks: the current ones hold the polynomial outputs read until the
        // step is taken. Copied where the field wrote the blocks itself, else transposed.
        let finite = match blocks {
            Some(blocks) if blocks.len() == self.next_blocks.len() => {
                debug_assert!(
                    blocks_hold_rows(blocks, rows, self.dim, n1),
                    "a Taylor field's blocks disagree with its rows"
                );
                copy_checked(blocks, &mut self.next_blocks)
            }
            _ => to_blocks_checked(rows, self.dim, n1, &mut self.next_blocks),
        };
        self.rule.step(rho, finite, t, self.offset(self.t_bound))
    }

    /// Takes one step on the current expansion of length `h`, moving the clock.
    fn take(&mut self, h: f64, lands: bool) {
        let n1 = self.order + 1;
        std::mem::swap(&mut self.blocks, &mut self.next_blocks);
        // The old state's low words become the polynomial's start's; the new ones are written.
        std::mem::swap(&mut self.lo, &mut self.start_lo);
        eval_blocks(
            &self.blocks,
            n1,
            h,
            &self.start_lo,
            &mut self.y,
            Some(&mut self.lo),
        );
        self.start = self.t;
        if lands {
            self.t = (self.t_bound, 0.0);
        } else {
            let (hi, lo) = two_sum(self.t.0, h);
            let (hi, lo2) = two_sum(hi, lo + self.t.1);
            self.t = (hi, lo2);
        }
        self.h = h;
        self.accepted += 1;
        self.smallest = self.smallest.min(h.abs());
        self.largest = self.largest.max(h.abs());
    }

    /// Steps until the current polynomial covers `t_out` (between the step's start and
    /// `t_bound`) and writes the solution there into `y_out`.
    ///
    /// # Errors
    /// As [`TaylorField::coefficients`]; [`Error::StepSizeTooSmall`] for a step size that
    /// underflows, non-finite coefficients, or the `max_steps` budget spent.
    // Exact comparisons: the clock lands on `t_bound` exactly, and the first output may be the
    // start itself.
    #[allow(clippy::float_cmp)]
    pub fn advance<F: TaylorField + ?Sized>(
        &mut self,
        field: &mut F,
        t_out: f64,
        y_out: &mut [f64],
    ) -> Result<()> {
        if y_out.len() != self.dim || field.dim() != self.dim {
            return Err(Error::invalid(
                "y",
                y_out.len() as f64,
                format!(
                    "the stepper, the field and the output must have {} components",
                    self.dim
                ),
            ));
        }
        let direction = (self.t_bound - self.t.0).signum();
        let n1 = self.order + 1;
        loop {
            // The current polynomial (from the last step's start) covers t_out?
            if self.h != 0.0 {
                let from_start = (t_out - self.start.0) - self.start.1;
                if from_start * direction <= self.h.abs() {
                    eval_blocks(&self.blocks, n1, from_start, &self.start_lo, y_out, None);
                    return Ok(());
                }
            } else if t_out == self.t.0 {
                y_out.copy_from_slice(&self.y);
                return Ok(());
            }
            if self.t.0 == self.t_bound {
                return Err(Error::invalid(
                    "t",
                    t_out,
                    "lies beyond the end of the integration",
                ));
            }
            let h = self.expand(field)?;
            let lands = h == self.offset(self.t_bound);
            self.take(h, lands);
        }
    }
}

impl Taylor {
    /// Takes one step toward `t_bound` (the last one lands on it exactly); `false` once the
    /// clock is at `t_bound` (no step taken). The step's polynomial is then the current one:
    /// [`step_start`](Self::step_start), [`step_length`](Self::step_length),
    /// [`eval_component`](Self::eval_component).
    ///
    /// # Errors
    /// As [`advance`](Self::advance).
    // Exact comparison: the clock lands on `t_bound` exactly.
    #[allow(clippy::float_cmp)]
    pub fn step<F: TaylorField + ?Sized>(&mut self, field: &mut F) -> Result<bool> {
        if field.dim() != self.dim {
            return Err(Error::DimensionMismatch {
                name: "Taylor field".into(),
                expected: self.dim,
                found: field.dim(),
            });
        }
        if self.t.0 == self.t_bound {
            return Ok(false);
        }
        let h = self.expand(field)?;
        let lands = h == self.offset(self.t_bound);
        self.take(h, lands);
        Ok(true)
    }

    /// Start of the current polynomial's step, as a double-double `(hi, lo)`.
    pub fn step_start(&self) -> (f64, f64) {
        self.start
    }

    /// Signed length of the current polynomial's step (0 before the first step).
    pub fn step_length(&self) -> f64 {
        self.h
    }

    /// The state at the end of the last step.
    pub fn state(&self) -> &[f64] {
        &self.y
    }

    /// The clock at the end of the last step, as a double-double `(hi, lo)`.
    pub fn time(&self) -> (f64, f64) {
        self.t
    }

    /// Component `i` of the current step's polynomial and its derivative in `τ`, at `τ` from
    /// the step's start: the value by compensated Horner over every order (with the start's
    /// low word; the state update and the outputs compensate the low orders only, so the two
    /// may differ in the last bit), the derivative by Horner.
    ///
    /// # Panics
    /// Never for `i < dim`; `i >= dim` is a caller's bug (an index into the state).
    pub fn eval_component(&self, i: usize, tau: f64) -> (f64, f64) {
        let n1 = self.order + 1;
        let mut coefficients = [0.0; MAX_ORDER + 1];
        let row = &mut coefficients[..n1];
        let block = &self.blocks[i / LANES * n1..][..n1];
        for (c, group) in row.iter_mut().zip(block) {
            *c = group[i % LANES];
        }
        let row = &*row;
        let mut d = 0.0;
        for (k, &c) in row.iter().enumerate().skip(1).rev() {
            d = d * tau + k as f64 * c;
        }
        (compensated_horner(row, tau) + self.start_lo[i], d)
    }

    /// The whole state on the current step's polynomial at `τ` from its start.
    pub fn eval_state(&self, tau: f64, out: &mut [f64]) {
        let n = out.len().min(self.dim);
        eval_blocks(
            &self.blocks,
            self.order + 1,
            tau,
            &self.start_lo,
            &mut out[..n],
            None,
        );
    }
}

impl Report for Taylor {
    /// `steps`, `order`, `rhs_evaluations`, `smallest_step`, `largest_step`.
    /// `rhs_evaluations` is the cost in the yardstick every other method reports, field
    /// evaluations, modelled rather than counted: a step is one expansion to order `p`, whose
    /// Cauchy products compute `k + 1` terms for coefficient `k` of each nonlinear operation,
    /// `(p + 1)(p + 2)/2` in all where one evaluation of the field computes one; so a step
    /// counts as `(p + 1)(p + 2)/2` evaluations (an upper bound for a field with linear
    /// operations, which cost `p + 1`).
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        let p = self.order as f64;
        extra.insert("steps".into(), ExtraValue::Scalar(self.accepted as f64));
        extra.insert("order".into(), ExtraValue::Scalar(p));
        extra.insert(
            "rhs_evaluations".into(),
            ExtraValue::Scalar(self.accepted as f64 * (p + 1.0) * (p + 2.0) / 2.0),
        );
        extra.insert(
            "smallest_step".into(),
            ExtraValue::Scalar(if self.accepted > 0 {
                self.smallest
            } else {
                0.0
            }),
        );
        extra.insert("largest_step".into(), ExtraValue::Scalar(self.largest));
    }
}

/// Integrates `field` from `y0` over `t_span`, with outputs every `dt` (the grid of
/// [`TimeGrid`]: `round((t1 - t0)/dt)` intervals, the last landing on `t1`), by the adaptive
/// Taylor method at `tolerances`: for a field that is not a system's
/// ([`Method::Taylor`](crate::classical::Method::Taylor) runs a system's own Taylor form).
///
/// # Errors
/// As [`TimeGrid::new`] and [`Taylor::advance`]; [`Error::InvalidParameter`] for `y0` of
/// the wrong length or not finite, or invalid tolerances.
pub fn integrate_taylor<F: TaylorField + ?Sized>(
    field: &mut F,
    y0: &[f64],
    t_span: (f64, f64),
    dt: f64,
    tolerances: Tolerances,
) -> Result<SimulationResult> {
    let grid = TimeGrid::new(t_span, dt)?;
    let dim = field.dim();
    let mut stepper = Taylor::new(field, tolerances, grid.t0(), y0, grid.t_end())?;
    let n = grid.n_steps() + 1;
    crate::classical::core::memory_check(n, 1 + dim)?;
    let mut y = Array2::<f64>::zeros((n, dim));
    let mut t = Array1::<f64>::zeros(n);
    for (i, mut row) in y.rows_mut().into_iter().enumerate() {
        let ti = grid.time(i);
        t[i] = ti;
        let out = row
            .as_slice_mut()
            .ok_or_else(|| Error::invalid("dim", dim as f64, "rows must be contiguous"))?;
        if i == 0 {
            out.copy_from_slice(y0);
        } else {
            stepper.advance(field, ti, out)?;
        }
    }
    let mut extra = BTreeMap::new();
    stepper.report(&mut extra);
    Ok(SimulationResult {
        t,
        y,
        ndof: None,
        energy: None,
        method: INFO.name.to_string(),
        extra,
    })
}

/// Relative distance under which two times are the same output time (the grid's `t + dt` and
/// its `time(i + 1)` differ by a few roundings).
const SAME_TIME_ULPS: f64 = 64.0;

#[inline]
pub(crate) fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_TIME_ULPS * f64::EPSILON * a.abs().max(b.abs())
}

/// The `taylor` method as the registry runs it: a [`Taylor`] stepper on a system's Taylor form
/// ([`DynamicalSystem::taylor_field`], taken by [`AdaptiveStepper::for_system`]), advancing
/// from output to output. The vector field the drivers pass is not evaluated: the Taylor form
/// is the same field, as recurrences.
pub struct TaylorStepper {
    field: Option<Box<dyn TaylorField>>,
    tolerances: Tolerances,
    t_bound: f64,
    stepper: Option<Taylor>,
    /// The last output and its time: a call from them continues the run, any other restarts.
    out: Vec<f64>,
    out_t: f64,
}

impl std::fmt::Debug for TaylorStepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TaylorStepper")
            .field("has_field", &self.field.is_some())
            .field("tolerances", &self.tolerances)
            .field("t_bound", &self.t_bound)
            .field("stepper", &self.stepper)
            .finish_non_exhaustive()
    }
}

impl TaylorStepper {
    /// A stepper on `field` at `tolerances` that never steps past `t_bound`.
    pub fn on(field: Box<dyn TaylorField>, tolerances: Tolerances, t_bound: f64) -> Self {
        let dim = field.dim();
        Self {
            field: Some(field),
            tolerances,
            t_bound,
            stepper: None,
            out: vec![0.0; dim],
            out_t: f64::NAN,
        }
    }

    /// Advances `y` from `t` to `t + h` on the Taylor form (`h` the output spacing).
    ///
    /// # Errors
    /// [`Error::UnsupportedMethod`] for a stepper built without a Taylor form;
    /// [`Error::InvalidArgument`] for `t + h` beyond `t_bound` or against the direction of
    /// the run; as [`Taylor::advance`].
    pub fn advance(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        let Some(field) = self.field.as_deref_mut() else {
            return Err(no_taylor_form("this system"));
        };
        if h == 0.0 {
            return Ok(());
        }
        let mut target = t + h;
        if self.t_bound.is_finite() && same_time(target, self.t_bound) {
            target = self.t_bound;
        } else if (target - self.t_bound) * (self.t_bound - t).signum() > 0.0
            || (self.t_bound - t) * h < 0.0
        {
            return Err(Error::InvalidArgument {
                name: "h".into(),
                reason: format!(
                    "t + h = {target} lies beyond the end {} this stepper was built for",
                    self.t_bound
                ),
            });
        }
        let continuing = self.stepper.is_some()
            && same_time(t, self.out_t)
            && y.iter()
                .zip(&self.out)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !continuing {
            self.stepper = Some(Taylor::new(
                &*field,
                self.tolerances,
                t,
                y,
                self.t_bound,
            )?);
        }
        if let Some(stepper) = self.stepper.as_mut() {
            stepper.advance(field, target, y)?;
        }
        if self.out.len() == y.len() {
            self.out.copy_from_slice(y);
        }
        self.out_t = target;
        Ok(())
    }

    /// The Taylor form this stepper runs on, and its tolerances: for callers that drive
    /// [`Taylor`] step by step (events located on the step polynomial).
    pub fn into_parts(self) -> (Option<Box<dyn TaylorField>>, Tolerances) {
        (self.field, self.tolerances)
    }
}

impl FieldStepper for TaylorStepper {
    /// A stepper without a Taylor form, which refuses to step: the registry builds its steppers
    /// by [`AdaptiveStepper::for_system`].
    fn new(dim: usize) -> Self {
        Self {
            field: None,
            tolerances: Tolerances::default(),
            t_bound: f64::INFINITY,
            stepper: None,
            out: vec![0.0; dim],
            out_t: f64::NAN,
        }
    }

    #[inline]
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        _f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.advance(t, y, h)
    }
}

impl AdaptiveStepper for TaylorStepper {
    fn adaptive(dim: usize, tolerances: Tolerances, t_bound: f64) -> Self {
        Self {
            tolerances,
            t_bound,
            ..<Self as FieldStepper>::new(dim)
        }
    }

    /// The stepper on `system`'s Taylor form.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for tolerances [`check_tolerances`] refuses;
    /// [`Error::UnsupportedMethod`] for a system without a Taylor form ([`no_taylor_form`]);
    /// whatever building its recurrences reports.
    fn for_system<S: DynamicalSystem + ?Sized>(
        system: &S,
        tolerances: Tolerances,
        t_bound: f64,
    ) -> Result<Self> {
        check_tolerances(&tolerances)?;
        let field = system
            .taylor_field()
            .ok_or_else(|| no_taylor_form(&system_name::<S>()))??;
        if field.dim() != system.state_dim() {
            return Err(Error::DimensionMismatch {
                name: "Taylor form".into(),
                expected: system.state_dim(),
                found: field.dim(),
            });
        }
        Ok(Self::on(field, tolerances, t_bound))
    }
}

impl Report for TaylorStepper {
    /// As [`Taylor`]'s report, of the current run.
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        if let Some(stepper) = &self.stepper {
            stepper.report(extra);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{
        copy_checked, copy_checked_plain, to_blocks_checked, to_blocks_checked_plain, LANES,
        MAX_ORDER,
    };

    /// The transposition into blocks (the AVX2 clone where the CPU has it) puts coefficient
    /// `k` of row `i` in group `k`, lane `i % 4`, of block `i / 4`, for every dimension (whole
    /// blocks and a partial last one) and every order, and leaves the lanes past the last row
    /// as they were; the plain clone gives the same bits; and both report the coefficients
    /// finite unless one of them (first, middle or last) is an infinity or a NaN. Blocks that
    /// a field wrote itself are copied bit for bit, checked the same way.
    #[test]
    fn the_transposition_places_every_coefficient_and_checks_finiteness() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut draw = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        // A value no row holds, in the lanes past the last row.
        let untouched = 7.0_f64;
        let bits = |blocks: &[[f64; LANES]]| -> Vec<u64> {
            blocks.iter().flatten().map(|x| x.to_bits()).collect()
        };
        for dim in 1..=9 {
            for n1 in 1..=MAX_ORDER + 1 {
                let rows: Vec<f64> = (0..dim * n1).map(|_| draw()).collect();
                let size = dim.div_ceil(LANES) * n1;
                let mut fast = vec![[untouched; LANES]; size];
                let mut plain = vec![[untouched; LANES]; size];
                assert!(to_blocks_checked(&rows, dim, n1, &mut fast));
                assert!(to_blocks_checked_plain(&rows, dim, n1, &mut plain));
                for i in 0..dim.div_ceil(LANES) * LANES {
                    for k in 0..n1 {
                        let want = if i < dim { rows[i * n1 + k] } else { untouched };
                        let got = fast[i / LANES * n1 + k][i % LANES];
                        assert_eq!(got.to_bits(), want.to_bits(), "dim {dim}, n1 {n1}, {i}, {k}");
                    }
                }
                assert_eq!(bits(&fast), bits(&plain), "dim {dim}, n1 {n1}");
                // Blocks a field wrote itself are copied whole, lanes past the last row too.
                let mut copied = vec![[untouched; LANES]; size];
                assert!(copy_checked(&fast, &mut copied));
                assert_eq!(bits(&copied), bits(&fast), "dim {dim}, n1 {n1}");
                for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
                    for at in [0, dim * n1 / 2, dim * n1 - 1] {
                        let mut poisoned = rows.clone();
                        poisoned[at] = bad;
                        assert!(!to_blocks_checked(&poisoned, dim, n1, &mut fast));
                        assert!(!to_blocks_checked_plain(&poisoned, dim, n1, &mut plain));
                        assert!(!copy_checked(&fast, &mut copied));
                        assert!(!copy_checked_plain(&fast, &mut copied));
                    }
                }
            }
        }
    }
}
