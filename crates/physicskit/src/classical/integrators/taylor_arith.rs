//! The exact arithmetic and the step-size rule of the Taylor step, written once for the
//! scalar stepper ([`taylor`](super::taylor), whose module documentation derives them) and the
//! lanes stepper ([`taylor_batch`](super::taylor_batch)), which does them lane by lane: Knuth's
//! TwoSum, the error-free product (Dekker's, or one FMA), and the step-size rule with its
//! `log2` and `2^y` written in plain arithmetic (so a vector of lanes computes them with the
//! scalar code's bits, and no lane calls libm's `pow`).

use crate::classical::core::{Error, Result};
use crate::classical::integrators::Tolerances;

/// The orders of a step's polynomial summed by compensated Horner in the state update and
/// the dense output; the orders from this one up are summed first by plain Horner (`s x + c`,
/// two roundings an order, no error kept), their sum then entering the compensated part as
/// its highest coefficient. The step is `e^-u` of the radius of convergence that the last
/// two orders estimate, measured against the scale `s = max(‖x‖, atol/rtol)` of the step
/// rule, with `u = -ln(ε e^-0.7)/(p - 1)`: at least 1.6 at the tightest tolerances
/// (`ε ≤ 1e-16`, even at the highest order, 24), at least 1.03 at `ε = 1e-10` and 0.63 at
/// `ε = 1e-6` (a field so cheap that it runs at the highest order). For coefficients falling
/// like that radius's powers the terms `|c_k| h^k` fall like `s e^{-uk}`, so the plain part
/// sums terms below `e^{-4u}` of `s`, and its rounding errors, about an ulp of each partial
/// sum, come to `e^{-4u}/(1 - e^{-u})` ulps of `s` in all: 0.002 at the tightest tolerances,
/// 0.03 at 1e-10, 0.17 at 1e-6. That is far under the truncation each tolerance allows
/// (`tol · s`, at least `1e-16 s`) and, where the tolerance nears the rounding, under the one
/// rounding the compensated sum ends with. (A polynomial or nearly polynomial
/// solution, whose last two orders vanish or nearly, takes a step longer than its lower
/// orders' radius, which this bound does not cover: its orders from four up are summed
/// plain.) The compensated step costs about five times the plain one's operations, and the
/// plain part holds all but four orders. The measured accuracy floors are in
/// `benchmarks/README.md`.
pub(crate) const COMPENSATED_ORDERS: usize = 4;

/// `a + b = s + e` exactly (Knuth's TwoSum).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Veltkamp's split of `a` into two halves of 26 bits (exact for `|a| < 2^996`).
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a b = p + e` exactly (Dekker's TwoProduct, without FMA: the path of CPUs without FMA).
#[inline(always)]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
}

/// `a b = p + e` exactly by one fused multiply-add, `e = fma(a, b, -p)`: the same `(p, e)` as
/// [`two_product`] wherever both are exact (operands below `2^996`, no underflow).
#[inline(always)]
pub(crate) fn two_product_fused(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `1.5 · 2^52`: a double `y` with `|y| < 2^51` plus this rounds `y` to an integer, held
/// in the sum's low mantissa bits.
const MAGIC: f64 = 6_755_399_441_055_744.0;

/// `2^64`, which lifts a subnormal into the normal range.
const TWO_64: f64 = 18_446_744_073_709_551_616.0;

/// `1/(2n + 1)` for `n = 0..=9`: `atanh s = s Σ s^{2n}/(2n + 1)`, whose next term is below
/// `2^-55` of the sum for `|s| ≤ 3 - 2√2`.
const ATANH: [f64; 10] = [
    1.0,
    0.333_333_333_333_333_3,
    0.2,
    0.142_857_142_857_142_85,
    0.111_111_111_111_111_1,
    0.090_909_090_909_090_91,
    0.076_923_076_923_076_93,
    0.066_666_666_666_666_67,
    0.058_823_529_411_764_705,
    0.052_631_578_947_368_42,
];

/// `ln(2)^k / k!` for `k = 0..=13`: `2^f = Σ (f ln 2)^k / k!`, whose next term is below
/// `2^-57` for `|f| ≤ 1/2`.
const EXP2: [f64; 14] = [
    1.0,
    std::f64::consts::LN_2,
    0.240_226_506_959_100_72,
    0.055_504_108_664_821_58,
    0.009_618_129_107_628_477,
    0.001_333_355_814_642_844_3,
    0.000_154_035_303_933_816_1,
    1.525_273_380_405_984_1e-5,
    1.321_548_679_014_431e-6,
    1.017_808_600_923_97e-7,
    7.054_911_620_801_123e-9,
    4.445_538_271_870_811_6e-10,
    2.567_843_599_348_820_6e-11,
    1.369_148_885_390_412_8e-12,
];

/// `Σ c_k x^k` by Estrin's scheme: pairs `c_2i + c_2i+1 x`, then pairs of those in `x²`,
/// and so on, a chain of `⌈log2 N⌉` multiply-adds where Horner's is `N - 1` long. The step
/// size is on the Taylor step's critical path (the state update waits for it), so its
/// latency, not its work, is what costs.
#[inline(always)]
fn estrin<const N: usize>(c: &[f64; N], x: f64) -> f64 {
    let mut v = *c;
    let (mut len, mut x) = (N, x);
    while len > 1 {
        let half = len.div_ceil(2);
        for i in 0..half {
            v[i] = if 2 * i + 1 < len {
                v[2 * i] + v[2 * i + 1] * x
            } else {
                v[2 * i]
            };
        }
        len = half;
        x *= x;
    }
    v[0]
}

/// `log2 x` to within an ulp of its value (for `x` from `5e-324` to `f64::MAX`), with only
/// `+ − × ÷`, comparisons and the doubles' bits, no branch and no libm: the same bits on
/// every CPU and in every vector lane. `x = 2^e m` with `m` in `[√½, √2)`, and
/// `log2 m = 2 atanh(s)/ln 2` with `s = (m - 1)/(m + 1)`. `+inf` for `+inf`, `-inf` for 0, NaN
/// for a negative or NaN `x`.
#[inline(always)]
pub(crate) fn log2_portable(x: f64) -> f64 {
    let tiny = x < f64::MIN_POSITIVE;
    let lifted = if tiny { x * TWO_64 } else { x };
    let bits = lifted.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64 - if tiny { 1023 + 64 } else { 1023 };
    let m = f64::from_bits((bits & ((1 << 52) - 1)) | 1.0_f64.to_bits());
    let big = m > std::f64::consts::SQRT_2;
    let m = if big { 0.5 * m } else { m };
    // The exponent as a double through MAGIC's mantissa (an integer add: no `i64` to `f64`
    // conversion, which AVX2 lacks).
    let e = f64::from_bits(
        MAGIC
            .to_bits()
            .wrapping_add((biased + i64::from(big)) as u64),
    ) - MAGIC;
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let value = e + (2.0 * std::f64::consts::LOG2_E * s) * estrin(&ATANH, s2);
    if x == f64::INFINITY {
        f64::INFINITY
    } else if x == 0.0 {
        f64::NEG_INFINITY
    } else if x > 0.0 {
        value
    } else {
        f64::NAN
    }
}

/// `2^y` to within two ulps (0 below `-1075`, `+inf` from 1024, NaN for NaN), by the same
/// means as [`log2_portable`]: `y = n + f` with `n` an integer and `|f| ≤ ½`, `2^f` by its
/// series, `2^n` as two powers of two built from their bits (each within the normal range).
#[inline(always)]
pub(crate) fn exp2_portable(y: f64) -> f64 {
    let y = y.clamp(-1100.0, 1100.0);
    let shifted = y + MAGIC;
    let f = y - (shifted - MAGIC);
    let n = (shifted.to_bits() as i64).wrapping_sub(MAGIC.to_bits() as i64);
    let p = estrin(&EXP2, f);
    let n1 = n >> 1;
    let n2 = n.wrapping_sub(n1);
    let power = |n: i64| f64::from_bits((n.wrapping_add(1023) as u64) << 52);
    p * power(n1) * power(n2)
}

/// `ln(ε e^-0.7)`: the truncation error a step aims at, `ε = min(rtol, atol)`, with heyoka's
/// safety factor. An `ε` below `e^(-2 (MAX_ORDER - 1))` (about `1e-20`: only an `atol` can be,
/// `rtol` is at least [`MIN_RTOL`](super::taylor::MIN_RTOL)) is taken as that: Jorba and
/// Zou's rule at the highest order, where a far smaller `atol` beside a usable `rtol` would
/// otherwise shrink every step for a precision no double holds.
pub(crate) fn log_target(tolerances: &Tolerances) -> f64 {
    let floor = -2.0 * (crate::classical::integrators::taylor::MAX_ORDER - 1) as f64;
    tolerances.rtol.min(tolerances.atol).ln().max(floor) - 0.7
}

/// The Taylor step-size rule (Jorba and Zou, with heyoka's safety factor; the module
/// documentation of [`taylor`](super::taylor) derives it) at order `p`, for the scalar stepper
/// and each lane of the batch stepper alike.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepRule {
    rtol: f64,
    atol: f64,
    /// `1/(p - 1)` and `1/p`: the roots' exponents.
    inverse_orders: [f64; 2],
    /// `(ε e^-0.7)^(1/(p - 1))`, `ε = min(rtol, atol)`: the step over the radius that keeps
    /// the truncation error at `ε`, with heyoka's safety factor `e^(-0.7/(p - 1))`.
    factor: f64,
    /// `[0, p - 1, p]`: the orders whose norms [`radius`](Self::radius) takes.
    norm_orders: [usize; 3],
}

impl StepRule {
    /// The rule at order `p` (at least 2, as [`order_for`](super::taylor::order_for) gives).
    pub(crate) fn new(tolerances: &Tolerances, p: usize) -> Self {
        Self {
            rtol: tolerances.rtol,
            atol: tolerances.atol,
            inverse_orders: [1.0 / (p - 1) as f64, 1.0 / p as f64],
            factor: (log_target(tolerances) / (p - 1) as f64).exp(),
            norm_orders: [0, p - 1, p],
        }
    }

    /// The orders `[0, p - 1, p]` whose largest coefficient magnitudes, in this order, are
    /// [`radius`](Self::radius)'s norms.
    #[inline(always)]
    pub(crate) fn norm_orders(&self) -> [usize; 3] {
        self.norm_orders
    }

    /// The radius `ρ = min((s/‖x_{p-1}‖)^(1/(p-1)), (s/‖x_p‖)^(1/p))` from the expansion's
    /// norms `[‖x_0‖, ‖x_{p-1}‖, ‖x_p‖]`, `s` the absolute or relative scale: infinite where
    /// both norms are zero (a polynomial solution). The roots are `2^(log2(·)/k)` by
    /// [`log2_portable`] and [`exp2_portable`], not `powf`: within 1e-13 of it over the
    /// doubles' whole range and 1e-14 for arguments within `1e±60` (a step size needs far
    /// less), branch-free, so the lanes compute theirs in vector registers with the scalar
    /// stepper's bits.
    #[inline(always)]
    pub(crate) fn radius(&self, [norm, second_last, last]: [f64; 3]) -> f64 {
        let scale = if self.rtol * norm <= self.atol {
            1.0
        } else {
            norm
        };
        let first = log2_portable(scale / second_last) * self.inverse_orders[0];
        let second = log2_portable(scale / last) * self.inverse_orders[1];
        exp2_portable(first.min(second))
    }

    /// The step's length before the clamp to the end: the safety factor times the radius
    /// `rho`. A series that ends before order p - 1 (a polynomial solution, `rho` infinite)
    /// is exact: one step to the end, or over all time for a run without one (a session: the
    /// end infinite).
    #[inline(always)]
    fn length(&self, rho: f64, remaining: f64) -> f64 {
        if rho.is_infinite() {
            remaining.abs().min(f64::MAX)
        } else {
            rho * self.factor
        }
    }

    /// The step toward an end `remaining` away (signed; infinite for a run without an end)
    /// on an expansion of radius `rho` (from [`radius`](Self::radius)) whose coefficients
    /// were all finite or not, at the clock `t`, and whether it may be taken: `(step, true)`
    /// where [`step`](Self::step) gives `Ok(step)`, `false` where it refuses. Its choices
    /// are selects once inlined, so the lanes take their steps in vector registers.
    #[inline(always)]
    pub(crate) fn try_step(&self, rho: f64, finite: bool, t: f64, remaining: f64) -> (f64, bool) {
        let h = self.length(rho, remaining);
        // The span sets the scale of a step too small to move the clock; a run without an
        // end has only its clock's.
        let span = if remaining.is_finite() {
            remaining.abs()
        } else {
            0.0
        };
        let underflow = h <= f64::EPSILON * t.abs().max(span) * 4.0 && h < remaining.abs();
        (
            h.min(remaining.abs()).copysign(remaining),
            h.is_finite() && finite && !underflow,
        )
    }

    /// [`try_step`](Self::try_step)'s step, or why it may not be taken.
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] for coefficients that are not finite or a step too small
    /// to move the clock.
    pub(crate) fn step(&self, rho: f64, finite: bool, t: f64, remaining: f64) -> Result<f64> {
        let (step, ok) = self.try_step(rho, finite, t, remaining);
        if ok {
            return Ok(step);
        }
        let h = self.length(rho, remaining);
        let reason = if !h.is_finite() || !finite {
            "the Taylor coefficients are not finite (a singularity of the field?)"
        } else {
            "the step size underflowed (the solution's radius of convergence shrinks to zero: \
             a singularity?)"
        };
        Err(Error::StepSizeTooSmall {
            t,
            step: h,
            reason: reason.into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{exp2_portable, log2_portable, two_product, two_product_fused, StepRule};
    use crate::classical::integrators::Tolerances;

    /// A xorshift generator of uniform doubles in `[0, 1)`.
    fn uniform(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// `log2_portable` is within an ulp of std's `log2` (glibc's, correctly rounded or
    /// nearly) from the smallest subnormal to `f64::MAX`, and `exp2_portable` within two ulps
    /// of std's `exp2` from -1074 to 1024 (its series and its two scalings round three times).
    #[test]
    // Exact comparisons: the special values are exact.
    #[allow(clippy::float_cmp)]
    fn the_portable_log2_and_exp2_agree_with_std() {
        let mut u = uniform(0x2545_F491_4F6C_DD1D);
        for _ in 0..1_000_000 {
            let x = 2f64.powf(2098.0 * u() - 1074.0);
            let (ours, std) = (log2_portable(x), x.log2());
            let ulp = f64::EPSILON * std.abs().max(1.0);
            assert!(
                (ours - std).abs() <= ulp,
                "log2 {x:e}: {ours} against {std}"
            );
            let y = 2098.0 * u() - 1074.0;
            let (ours, std) = (exp2_portable(y), y.exp2());
            // Relative to the result where it is normal; in absolute terms (two of the
            // smallest subnormals) below.
            let bound = (2.0 * f64::EPSILON * std).max(2.0 * 5e-324);
            assert!(
                (ours - std).abs() <= bound,
                "exp2 {y}: {ours:e} against {std:e}"
            );
        }
        for (x, expected) in [
            (0.0, f64::NEG_INFINITY),
            (f64::INFINITY, f64::INFINITY),
            (1.0, 0.0),
            (0.5, -1.0),
            (5e-324, -1074.0),
        ] {
            assert_eq!(log2_portable(x), expected, "{x:e}");
        }
        assert!(log2_portable(-1.0).is_nan() && log2_portable(f64::NAN).is_nan());
        for (y, expected) in [
            (f64::NEG_INFINITY, 0.0),
            (-1076.0, 0.0),
            (1024.0, f64::INFINITY),
            (f64::INFINITY, f64::INFINITY),
            (0.0, 1.0),
            (-1074.0, 5e-324),
        ] {
            assert_eq!(exp2_portable(y), expected, "{y}");
        }
        assert!(exp2_portable(f64::NAN).is_nan());
    }

    /// The rule's radius equals `powf`'s smaller root (the rule as Jorba and Zou write it) to
    /// 1e-13 over norms from 1e-300 to 1e300 at every order: the rounding of `log2`'s value,
    /// up to half an ulp of 1074 (1.1e-13), divided by the order, is the largest error; and
    /// to 1e-14 where the arguments are within `1e±60` (ulps of `log2` below 2.8e-14).
    #[test]
    // Exact comparison: an infinite radius.
    #[allow(clippy::float_cmp)]
    fn the_radius_is_the_smaller_powf_root() {
        let mut u = uniform(0x9E37_79B9_7F4A_7C15);
        let tolerances = Tolerances::new(1e-10, 1e-12).expect("valid");
        for p in 2..=crate::classical::integrators::taylor::MAX_ORDER {
            let rule = StepRule::new(&tolerances, p);
            for _ in 0..5000 {
                let wide = u() < 0.5;
                let exponent = if wide { 300.0 } else { 30.0 };
                let mut draw = || 10f64.powf(exponent * (2.0 * u() - 1.0));
                let norms = [draw(), draw(), draw()];
                let scale = if 1e-10 * norms[0] <= 1e-12 {
                    1.0
                } else {
                    norms[0]
                };
                let expected = (scale / norms[1])
                    .powf(1.0 / (p - 1) as f64)
                    .min((scale / norms[2]).powf(1.0 / p as f64));
                if !expected.is_normal() {
                    continue;
                }
                let error = (rule.radius(norms) - expected).abs() / expected;
                let bound = if wide { 1e-13 } else { 1e-14 };
                assert!(error <= bound, "order {p}, {norms:?}: {error:e}");
            }
            // Zero norms: a polynomial; one zero norm leaves the other root.
            assert_eq!(rule.radius([1.0, 0.0, 0.0]), f64::INFINITY);
            let one = rule.radius([1.0, 0.0, 1e-20]);
            let expected = 1e20f64.powf(1.0 / p as f64);
            assert!(
                (one - expected).abs() <= 1e-14 * expected,
                "{one:e} {expected:e}"
            );
        }
    }

    /// Dekker's error-free product and the fused one give the same `(p, e)` on operands far
    /// from overflow and underflow (where both are exact): the lanes and the scalar stepper
    /// choose between them by the CPU, and must agree with each other's choice.
    #[test]
    fn the_two_error_free_products_agree() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..100_000 {
            let a = (uniform() * 2.0 - 1.0) * 10f64.powf(200.0 * uniform() - 100.0);
            let b = (uniform() * 2.0 - 1.0) * 10f64.powf(200.0 * uniform() - 100.0);
            assert_eq!(two_product(a, b), two_product_fused(a, b), "{a:e} {b:e}");
        }
    }
}
