//! The exact arithmetic of the Taylor step that the lanes stepper
//! ([`taylor_batch`](super::taylor_batch)) does lane by lane: Knuth's TwoSum, the error-free
//! product (Dekker's, or one FMA), and the comparison of the step-size rule's two roots from
//! the doubles' exponents. These are the operations of [`taylor`](super::taylor)'s step, in
//! its order (its module documentation derives them); the lanes' bit-for-bit tests against
//! the scalar stepper (`tests/classical/integrators/taylor_lanes.rs`) fail if the two differ.

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

/// `log2 x` from below, within 0.087, for a positive normal `x`: its exponent plus its
/// mantissa's fraction (the chord of `log2` over each binade).
#[inline(always)]
fn log2_below(x: f64) -> f64 {
    let bits = x.to_bits();
    let exponent = (bits >> 52) as i64 - 1023;
    let mantissa = f64::from_bits((bits & ((1 << 52) - 1)) | 1.0_f64.to_bits());
    exponent as f64 + (mantissa - 1.0)
}

/// Largest error of [`log2_below`] (`1 - (1 + ln ln 2)/ln 2`, rounded up).
const LOG2_BELOW_ERROR: f64 = 0.087;

/// Whether `x1^(1/k1)` is the smaller of the two roots (`Some(true)`), `x2^(1/k2)` is
/// (`Some(false)`), or neither is told apart from their logarithms' bounds (`None`: roots
/// within a factor `2^(0.087/k + 0.001)` of each other, or an argument not positive and
/// normal). The margin of 1e-3 in `log2` beyond the bounds keeps the roots, once rounded by
/// `powf`, in the same order; so the root it names is the smaller `powf` (the test below).
#[inline]
pub(crate) fn smaller_root(x1: f64, k1: usize, x2: f64, k2: usize) -> Option<bool> {
    if !(x1.is_normal() && x2.is_normal() && x1 > 0.0 && x2 > 0.0) {
        return None;
    }
    let (k1, k2) = (k1 as f64, k2 as f64);
    // log2 of each root lies in [low, low + LOG2_BELOW_ERROR / k].
    let (low1, low2) = (log2_below(x1) / k1, log2_below(x2) / k2);
    let margin = 1e-3;
    if low1 + LOG2_BELOW_ERROR / k1 + margin < low2 {
        Some(true)
    } else if low2 + LOG2_BELOW_ERROR / k2 + margin < low1 {
        Some(false)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::{smaller_root, two_product, two_product_fused};

    /// The root `smaller_root` names is the smaller `powf`, over arguments from 1e-300 to
    /// 1e300 and orders 2 to 24, in pseudo-random pairs; and the two error-free products
    /// agree on them (exact both, far from overflow and underflow).
    #[test]
    fn smaller_root_names_the_smaller_powf() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut told = 0;
        for k in 2..=24 {
            for _ in 0..2000 {
                let x1 = 10f64.powf(600.0 * uniform() - 300.0);
                let x2 = 10f64.powf(600.0 * uniform() - 300.0);
                let (r1, r2) = (x1.powf(1.0 / (k - 1) as f64), x2.powf(1.0 / k as f64));
                match smaller_root(x1, k - 1, x2, k) {
                    Some(true) => assert!(r1 < r2, "{x1:e} {x2:e} {k}"),
                    Some(false) => assert!(r2 < r1, "{x1:e} {x2:e} {k}"),
                    None => continue,
                }
                told += 1;
                let (a, b) = (uniform() * 2.0 - 1.0, 1e3 * uniform());
                assert_eq!(two_product(a, b), two_product_fused(a, b));
            }
        }
        // Pairs drawn over 600 decades are almost all told apart.
        assert!(told > 40_000, "{told}");
    }
}
