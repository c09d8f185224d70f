//! The exact arithmetic and the step-size rule of the Taylor step, written once for the
//! scalar stepper ([`taylor`](super::taylor), whose module documentation derives them) and the
//! lanes stepper ([`taylor_batch`](super::taylor_batch)), which does them lane by lane: Knuth's
//! TwoSum, the error-free product (Dekker's, or one FMA), the comparison of the step-size rule's
//! two roots from the doubles' bits, and the rule itself.

use crate::classical::core::{Error, Result};
use crate::classical::integrators::Tolerances;

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

/// `log2 x` within [`LOG2_NEAR_ERROR`] either way, for a positive normal `x`: its exponent
/// plus its mantissa's fraction `m` plus `m (1 - m)(0.4229 - 0.1592 m)`, a fit of the gap
/// between `log2(1 + m)` and its chord `m` (largest error 0.00089 over `[0, 1)`).
#[inline(always)]
fn log2_near(x: f64) -> f64 {
    let bits = x.to_bits();
    let exponent = (bits >> 52) as i64 - 1023;
    let m = f64::from_bits((bits & ((1 << 52) - 1)) | 1.0_f64.to_bits()) - 1.0;
    exponent as f64 + (m + m * (1.0 - m) * (0.4229 - 0.1592 * m))
}

/// Largest error of [`log2_near`], rounded up.
const LOG2_NEAR_ERROR: f64 = 0.001;

/// Whether `x1^(1/k1)` is the smaller of the two roots (`Some(true)`), `x2^(1/k2)` is
/// (`Some(false)`), or neither is told apart from their logarithms by [`log2_near`] (`None`:
/// roots within a factor `2^(0.001/k1 + 0.001/k2 + 1e-9)` of each other, 0.007 % at
/// `k = 20`, or an argument not positive and normal). The margin of 1e-9 in `log2` is far
/// above the rounding of the estimates (about 1e-13) and of `powf` (an ulp, 3e-16 in `log2`),
/// so the roots, once rounded by `powf`, keep the order told.
#[inline]
pub(crate) fn smaller_root(x1: f64, k1: usize, x2: f64, k2: usize) -> Option<bool> {
    if !(x1.is_normal() && x2.is_normal() && x1 > 0.0 && x2 > 0.0) {
        return None;
    }
    let (k1, k2) = (k1 as f64, k2 as f64);
    let (mid1, mid2) = (log2_near(x1) / k1, log2_near(x2) / k2);
    let gap = LOG2_NEAR_ERROR / k1 + LOG2_NEAR_ERROR / k2 + 1e-9;
    if mid1 + gap < mid2 {
        Some(true)
    } else if mid2 + gap < mid1 {
        Some(false)
    } else {
        None
    }
}

/// The step of the Taylor rule (Jorba and Zou, with heyoka's safety factor; the module
/// documentation of [`taylor`](super::taylor) derives it) toward an end `remaining` away
/// (signed; infinite for a run without an end), from the expansion's norms `[‖x_0‖, ‖x_{p-1}‖,
/// ‖x_p‖]` at order `p` and whether every coefficient was finite, at the clock `t`: the same
/// operations for the scalar stepper and for each lane of the batch stepper.
///
/// # Errors
/// [`Error::StepSizeTooSmall`] for coefficients that are not finite or a step too small to
/// move the clock.
pub(crate) fn step_size(
    tolerances: &Tolerances,
    safety: f64,
    p: usize,
    [norm, second_last, last]: [f64; 3],
    finite: bool,
    t: f64,
    remaining: f64,
) -> Result<f64> {
    let fail = |step: f64, reason: String| Error::StepSizeTooSmall { t, step, reason };
    let scale = if tolerances.rtol * norm <= tolerances.atol {
        1.0
    } else {
        norm
    };
    let radius = |c: f64, k: usize| {
        if c > 0.0 {
            (scale / c).powf(1.0 / k as f64)
        } else {
            f64::INFINITY
        }
    };
    // The smaller root alone where the two roots' logarithms, estimated from the doubles'
    // bits, tell it apart (the same `powf` of the same argument: the same ρ); both where
    // they are close or not normal.
    let rho = match smaller_root(scale / second_last, p - 1, scale / last, p) {
        Some(true) => radius(second_last, p - 1),
        Some(false) => radius(last, p),
        None => radius(second_last, p - 1).min(radius(last, p)),
    };
    // A series that ends before order p - 1 (a polynomial solution) is exact: one step
    // to the end, or over all time for a run without one (a session: the end infinite).
    let h = if rho.is_infinite() {
        remaining.abs().min(f64::MAX)
    } else {
        rho / std::f64::consts::E.powi(2) * safety
    };
    if !h.is_finite() || !finite {
        return Err(fail(
            h,
            "the Taylor coefficients are not finite (a singularity of the field?)".into(),
        ));
    }
    // The span sets the scale of a step too small to move the clock; a run without an
    // end has only its clock's.
    let span = if remaining.is_finite() {
        remaining.abs()
    } else {
        0.0
    };
    if h <= f64::EPSILON * t.abs().max(span) * 4.0 && h < remaining.abs() {
        return Err(fail(
            h,
            "the step size underflowed (the solution's radius of convergence shrinks to \
             zero: a singularity?)"
                .into(),
        ));
    }
    Ok(h.min(remaining.abs()).copysign(remaining))
}

#[cfg(test)]
mod tests {
    use super::{log2_near, smaller_root, two_product, two_product_fused, LOG2_NEAR_ERROR};

    /// `log2_near` is within its stated error of `log2` over doubles from 1e-300 to 1e300,
    /// and comes within 80 % of that bound somewhere (the bound is not loose by a factor).
    #[test]
    fn log2_near_is_within_its_error() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut worst = 0.0_f64;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let x = 10f64.powf(600.0 * ((state >> 11) as f64 / (1u64 << 53) as f64) - 300.0);
            let error = (log2_near(x) - x.log2()).abs();
            assert!(error <= LOG2_NEAR_ERROR, "{x:e}: {error}");
            worst = worst.max(error);
        }
        assert!(worst > 0.8 * LOG2_NEAR_ERROR, "{worst}");
    }

    /// The root `smaller_root` names is the smaller `powf`, over arguments from 1e-300 to
    /// 1e300 and every order, in pseudo-random pairs close (within 2.5 % in root) and far
    /// apart; and it leaves few pairs untold.
    #[test]
    fn smaller_root_agrees_with_powf() {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut told, mut close) = (0, 0);
        for k in 2..=crate::classical::integrators::taylor::MAX_ORDER {
            for _ in 0..2000 {
                let x1 = 10f64.powf(600.0 * uniform() - 300.0);
                // Half the pairs within a few per cent in root, half anywhere.
                let x2 = if uniform() < 0.5 {
                    (x1.powf(1.0 / (k - 1) as f64) * (1.0 + 0.05 * (uniform() - 0.5)))
                        .powi(k as i32)
                } else {
                    10f64.powf(600.0 * uniform() - 300.0)
                };
                let (r1, r2) = (x1.powf(1.0 / (k - 1) as f64), x2.powf(1.0 / k as f64));
                match smaller_root(x1, k - 1, x2, k) {
                    Some(true) => assert!(r1 < r2, "{x1:e} {x2:e} {k}"),
                    Some(false) => assert!(r2 < r1, "{x1:e} {x2:e} {k}"),
                    None => close += 1,
                }
                told += 1;
            }
        }
        // Untold are the pairs with an argument not normal (a close pair's second argument,
        // about the first's power k/(k - 1), overflows or underflows near the ends of the
        // range: about 5 % of all pairs, which no bound can tell) and the close pairs within
        // 2^(0.002/k) of each other (well under 1 %): 2 449 of 46 000 in this draw.
        assert!(close * 10 < told, "{close} of {told} not told apart");
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
