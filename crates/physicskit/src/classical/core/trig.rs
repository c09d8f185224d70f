//! Sine and cosine of whole slices, written so the compiler vectorizes them.
//!
//! Trig-heavy forces (the pendulum swarm, the sine-Gordon chain) spend most of their time in
//! `sin`/`cos`. libm evaluates one element at a time behind a branchy range reduction; these
//! functions use a branch-free scheme over the slice, which LLVM turns into SIMD code:
//!
//! 1. Cody–Waite reduction `r = x - n pi/2`, `n = round(x 2/pi)`, with `pi/2` split into four
//!    parts (33 + 33 + 53 bits and a tail) so that the leading `n * part` are exact for
//!    `|n| < 2^20`.
//! 2. fdlibm's minimax kernels `__kernel_sin` / `__kernel_cos` on `|r| <= pi/4` (Sun
//!    Microsystems, 1993; error below 1 ulp on the kernel interval).
//! 3. The quadrant `n mod 4` selects `+-sin r` or `+-cos r` by arithmetic, not branches.
//!
//! [`sum_cos`] computes its cosines in blocks of 128 into a stack buffer and adds them into
//! eight interleaved partial sums ([`LaneSum`]), so both the cosines and the sum vectorize and
//! the rounding is the same on every instruction set.
//!
//! # Instruction sets
//!
//! Each public function is compiled three times by `#[multiversion]` (the `multiversion`
//! crate): for baseline x86-64 (SSE2, 2 doubles per vector), with AVX2 (4 per vector, `ymm`
//! registers) and with AVX-512 (F, DQ, VL: 8 per vector, `zmm`). The first call detects the CPU (std's `is_x86_feature_detected!`, cached) and
//! stores the chosen clone in an atomic function pointer; later calls cost one load and an
//! indirect call. Other architectures compile only the portable body. `fma` is deliberately
//! not enabled, and Rust never contracts `a * b + c` on its own, so both clones perform the
//! same IEEE operations in the same order: their results are bit-identical (the test runs the
//! clone this CPU selects against the baseline build), checked on 3.9 x
//! 10^6 arguments including the neighbours of `k pi/2`, signed zeros, subnormals, the vector
//! limit, NaN and infinities (`dispatched_and_baseline_paths_are_bit_identical`). A result
//! therefore does not depend on which x86-64 machine computed it.
//!
//! The wider clones exist for speed: per element the AVX2 and AVX-512 sines take about half
//! and a third of the SSE2 baseline's time, which is about libm's (measurements:
//! `benchmarks/README.md`, "History moved from module docs").
//!
//! # Accuracy
//!
//! Measured against libm over 2 x 10^6 results with `|x| <= 1e4` (tests below): 86.5%
//! bit-identical, 13.5% one ulp apart, 0.002% two ulps apart (fdlibm's tail word of the
//! reduced argument is dropped to keep the loop branch-free), i.e. the same 1-ulp class.
//! Slices with any `|x| > 1e6` (where the three-part reduction would lose bits) or any NaN fall
//! back to libm element by element, so results are always within the bound.

// The constants are quoted with fdlibm's published digits, so they can be checked against the
// source; the parsed doubles are the same.
#![allow(clippy::excessive_precision)]

use multiversion::multiversion;

use super::sum::LaneSum;

/// Largest `|x|` handled by the vector path: `2^20 pi/2 ~ 1.6e6`, rounded down.
const VECTOR_LIMIT: f64 = 1e6;

const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
/// `pi/2` = PIO2_1 + PIO2_2 + PIO2_3 + PIO2_3T (fdlibm's 33 + 33 + 53-bit split and tail).
const PIO2_1: f64 = 1.570_796_326_734_125_614_17;
const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
const PIO2_3: f64 = 2.022_266_248_711_166_455_80e-21;
const PIO2_3T: f64 = 8.478_427_660_368_899_569_97e-32;

const S1: f64 = -1.666_666_666_666_663_243_48e-1;
const S2: f64 = 8.333_333_333_322_489_461_24e-3;
const S3: f64 = -1.984_126_982_985_794_931_34e-4;
const S4: f64 = 2.755_731_370_707_006_767_89e-6;
const S5: f64 = -2.505_076_025_340_686_341_95e-8;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;

const C1: f64 = 4.166_666_666_666_660_190_37e-2;
const C2: f64 = -1.388_888_888_887_410_957_49e-3;
const C3: f64 = 2.480_158_728_947_672_941_78e-5;
const C4: f64 = -2.755_731_435_139_066_330_35e-7;
const C5: f64 = 2.087_572_321_298_174_827_90e-9;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

#[inline(always)]
fn kernel_sin(x: f64) -> f64 {
    let z = x * x;
    let r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    x + z * x * (S1 + z * r)
}

#[inline(always)]
fn kernel_cos(x: f64) -> f64 {
    let z = x * x;
    let r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + z * r)
}

/// `1.5 * 2^52`: adding it rounds a double of magnitude below `2^51` to the nearest integer
/// (ties to even), which then sits in the low mantissa bits.
const ROUNDING_MAGIC: f64 = 6_755_399_441_055_744.0;

/// The reduction of `x` (`|x| <= VECTOR_LIMIT`): `(quadrant, sin r, cos r)` with
/// `x = r + quadrant pi/2 (mod 2 pi)`, `|r| <= pi/4`, `quadrant` in its low two bits.
///
/// Only additions, multiplications and bit operations: baseline x86-64 (SSE2) has no vector
/// `round`/`floor`, so those would turn into library calls and stop vectorization.
#[inline(always)]
fn reduce(x: f64) -> (u64, f64, f64) {
    let t = x * TWO_OVER_PI + ROUNDING_MAGIC;
    let n = t - ROUNDING_MAGIC;
    // The first two products are exact (33-bit parts, |n| < 2^20) and each subtraction is
    // exact by Sterbenz's lemma; the tail matters when r is tiny (x within 1e-13 of k pi/2).
    let r = (((x - n * PIO2_1) - n * PIO2_2) - n * PIO2_3) - n * PIO2_3T;
    // The mantissa of t holds 2^51 + n, so its low two bits are n mod 4 (also for n < 0).
    (t.to_bits(), kernel_sin(r), kernel_cos(r))
}

/// `sin` of `r + quadrant pi/2` from `sin r` and `cos r`: odd quadrants take the cosine,
/// quadrants 2 and 3 flip the sign.
#[inline(always)]
fn select(quadrant: u64, s: f64, c: f64) -> f64 {
    let odd = 0_u64.wrapping_sub(quadrant & 1);
    let bits = (c.to_bits() & odd) | (s.to_bits() & !odd);
    f64::from_bits(bits ^ ((quadrant & 2) << 62))
}

/// `sin x` (`shift = 0`) or `cos x = sin(x + pi/2)` (`shift = 1`), for `|x| <= VECTOR_LIMIT`.
#[inline(always)]
fn sin_cos_reduced(x: f64, shift: u64) -> f64 {
    let (quadrant, s, c) = reduce(x);
    select(quadrant.wrapping_add(shift), s, c)
}

/// `(sin x, cos x)` from one reduction, branch-free for `|x| <= 1e6` (libm beyond, and for
/// NaN): the same values as [`sin_into`] and [`cos_into`], at about a third of the cost of
/// libm's `sincos` for one scalar. For closed-form equations of motion evaluated one state at
/// a time (the Lagrangian systems).
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() <= VECTOR_LIMIT {
        let (quadrant, s, c) = reduce(x);
        (
            select(quadrant, s, c),
            select(quadrant.wrapping_add(1), s, c),
        )
    } else {
        x.sin_cos()
    }
}

fn fits_vector_path(x: &[f64]) -> bool {
    // A fold without early exit, so that the check vectorizes too. NaN fails the comparison
    // and takes the libm path, which propagates it.
    x.iter().fold(true, |ok, v| ok & (v.abs() <= VECTOR_LIMIT))
}

/// Elements per block of [`sum_cos`]: the cosines of a block are computed into a stack buffer
/// and then added into eight interleaved partial sums ([`LaneSum`]); a multiple of 8, so the
/// blocks continue each other's lanes.
const SUM_BLOCK: usize = 128;

// The bodies below are compiled once per instruction set: inlined into each clone that
// `#[multiversion]` makes of the public functions, and into the tests at the baseline.

/// `out[i] = sin(x[i])` (`SHIFT = 0`, `libm = f64::sin`) or `cos(x[i])` (`SHIFT = 1`,
/// `libm = f64::cos`): the quadrant shift selects the function on the vector path.
///
/// Each value is multiplied by `scale` (`1.0`, exact, for the plain functions).
#[inline(always)]
fn trig_into_body<const SHIFT: u64>(x: &[f64], out: &mut [f64], libm: fn(f64) -> f64, scale: f64) {
    if fits_vector_path(x) {
        for (o, &v) in out.iter_mut().zip(x) {
            *o = scale * sin_cos_reduced(v, SHIFT);
        }
    } else {
        for (o, &v) in out.iter_mut().zip(x) {
            *o = scale * libm(v);
        }
    }
}

#[inline(always)]
fn sin_into_body(x: &[f64], out: &mut [f64]) {
    trig_into_body::<0>(x, out, f64::sin, 1.0);
}

#[inline(always)]
fn sin_into_scaled_body(x: &[f64], out: &mut [f64], scale: f64) {
    trig_into_body::<0>(x, out, f64::sin, scale);
}

/// [`sin_cos`] of `N` arguments at once, `(sin, cos)` arrays: the same values, in SIMD lanes
/// where the target has them (two angles of a double pendulum in one pass).
#[inline(always)]
pub fn sin_cos_array<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let (mut s, mut c) = ([0.0; N], [0.0; N]);
    if fits_vector_path(&x) {
        for i in 0..N {
            let (quadrant, sr, cr) = reduce(x[i]);
            s[i] = select(quadrant, sr, cr);
            c[i] = select(quadrant.wrapping_add(1), sr, cr);
        }
    } else {
        for i in 0..N {
            (s[i], c[i]) = x[i].sin_cos();
        }
    }
    (s, c)
}

#[inline(always)]
fn cos_into_body(x: &[f64], out: &mut [f64]) {
    trig_into_body::<1>(x, out, f64::cos, 1.0);
}

#[inline(always)]
fn sum_cos_body(x: &[f64]) -> f64 {
    cos_sum_body::<false>(x, &mut [], 1.0)
}

/// [`sin_into_scaled_body`] and [`sum_cos_body`] in one pass: the cosines come from the
/// reductions the sines make anyway.
#[inline(always)]
fn sin_into_sum_cos_body(x: &[f64], out: &mut [f64], scale: f64) -> f64 {
    // Over the common length, like the zipped loops of the other functions.
    let x = &x[..x.len().min(out.len())];
    cos_sum_body::<true>(x, out, scale)
}

/// `sum_i cos(x[i])` and, with `SINES`, `out[i] = scale * sin(x[i])` (`out` at least as long
/// as `x`; unused without `SINES`). The cosines of a block go to a stack buffer, then into the
/// lane sum.
#[inline(always)]
fn cos_sum_body<const SINES: bool>(x: &[f64], out: &mut [f64], scale: f64) -> f64 {
    let mut sum = LaneSum::default();
    if fits_vector_path(x) {
        let mut block = [0.0; SUM_BLOCK];
        for (b, chunk) in x.chunks(SUM_BLOCK).enumerate() {
            let c = &mut block[..chunk.len()];
            if SINES {
                let o = &mut out[b * SUM_BLOCK..b * SUM_BLOCK + chunk.len()];
                for ((oi, ci), &v) in o.iter_mut().zip(c.iter_mut()).zip(chunk) {
                    let (quadrant, s, co) = reduce(v);
                    *oi = scale * select(quadrant, s, co);
                    *ci = select(quadrant.wrapping_add(1), s, co);
                }
            } else {
                for (ci, &v) in c.iter_mut().zip(chunk) {
                    *ci = sin_cos_reduced(v, 1);
                }
            }
            sum.add_map(c, |v| v);
        }
    } else {
        if SINES {
            for (o, &v) in out.iter_mut().zip(x) {
                *o = scale * v.sin();
            }
        }
        sum.add_map(x, f64::cos);
    }
    sum.total()
}

/// Writes `scale * sin(x[i])` into `out[i]` and returns `sum_i cos(x[i])`, both over the
/// common length of `x` and `out`: the same bits as
/// [`sin_into_scaled`] and [`sum_cos`], for about the cost of the sines alone (a potential
/// `sum (1 - cos q_i)` stored with the force `-sin q_i`).
#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
pub fn sin_into_sum_cos(x: &[f64], out: &mut [f64], scale: f64) -> f64 {
    sin_into_sum_cos_body(x, out, scale)
}

/// Writes `scale * sin(x[i])` into `out[i]` (the same bits as [`sin_into`] followed by a
/// multiplication, in one pass: a force `-(g/l) sin q_i`).
#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
pub fn sin_into_scaled(x: &[f64], out: &mut [f64], scale: f64) {
    sin_into_scaled_body(x, out, scale);
}

/// Writes `sin(x[i])` into `out[i]`.
#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
pub fn sin_into(x: &[f64], out: &mut [f64]) {
    sin_into_body(x, out);
}

/// `sum_i cos(x[i])`, added in the fixed order of [`lane_sum`](super::sum::lane_sum).
#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
pub fn sum_cos(x: &[f64]) -> f64 {
    sum_cos_body(x)
}

/// Writes `cos(x[i])` into `out[i]`.
#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
pub fn cos_into(x: &[f64], out: &mut [f64]) {
    cos_into_body(x, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite doubles of the same sign
    /// (or both near zero).
    fn ulps(a: f64, b: f64) -> u64 {
        if a.to_bits() == b.to_bits() {
            return 0;
        }
        let key = |v: f64| {
            let bits = v.to_bits() as i64;
            if bits < 0 {
                i64::MIN - bits
            } else {
                bits
            }
        };
        key(a).abs_diff(key(b))
    }

    /// Marsaglia's xorshift64 (J. Stat. Softw. 8, 2003): a fixed stream of 64-bit words.
    fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    /// A deterministic spread of arguments: dense near zero and near multiples of pi/2 (where
    /// reduction is hardest), and uniform up to 1e4.
    fn arguments() -> Vec<f64> {
        let mut bits = xorshift(0x9E37_79B9_7F4A_7C15);
        let mut next = || (bits() >> 11) as f64 / (1u64 << 53) as f64;
        let mut xs = Vec::new();
        for _ in 0..400_000 {
            xs.push((next() - 0.5) * 2e4);
        }
        for _ in 0..300_000 {
            xs.push((next() - 0.5) * 8.0);
        }
        for k in -2000..2000 {
            let base = f64::from(k) * std::f64::consts::FRAC_PI_2;
            for j in -37..37 {
                xs.push(base + f64::from(j) * 1e-9);
            }
        }
        xs
    }

    #[test]
    fn within_the_one_ulp_class_of_libm() {
        // libm (glibc) is itself within 1 ulp of the true value (nearly always correctly
        // rounded). We allow 2 ulps from it at worst and require more than 99.99% within 1.
        let xs = arguments();
        let mut s = vec![0.0; xs.len()];
        let mut c = vec![0.0; xs.len()];
        sin_into(&xs, &mut s);
        cos_into(&xs, &mut c);
        let mut histogram = [0usize; 3];
        let mut worst = (0, 0.0);
        for ((&x, &sv), &cv) in xs.iter().zip(&s).zip(&c) {
            for (got, want) in [(sv, x.sin()), (cv, x.cos())] {
                let d = ulps(got, want);
                histogram[(d as usize).min(2)] += 1;
                if d > worst.0 {
                    worst = (d, x);
                }
            }
        }
        let total = 2 * xs.len();
        let beyond_one = histogram[2] as f64 / total as f64;
        println!("ulp histogram (0, 1, >=2): {histogram:?} of {total}; worst {worst:?}");
        // Without fdlibm's tail word the reduced argument carries its own half-ulp rounding,
        // so a rare argument lands 2 ulps from libm (~1.5 ulp from the true value at most).
        assert!(worst.0 <= 2, "{} ulps at x = {:e}", worst.0, worst.1);
        assert!(beyond_one < 1e-4, "{beyond_one} of results beyond 1 ulp");
    }

    /// Arguments that stress the vector path, all with `|x| <= VECTOR_LIMIT`: the bit
    /// neighbours of `k pi/2` across the whole range of `k` (reduction to a tiny `r`, and the
    /// quadrant boundaries), the midpoints `(k + 1/2) pi/2` (where `x 2/pi` rounds at a tie),
    /// magnitudes spread log-uniformly from the smallest subnormal up to the limit, and signed
    /// zeros, subnormals and the limit itself.
    fn vector_path_edge_cases() -> Vec<f64> {
        let mut next = xorshift(0x2545_F491_4F6C_DD1D);
        let mut xs = vec![
            0.0,
            -0.0,
            f64::from_bits(1),
            -f64::from_bits(1),
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::from_bits(f64::MIN_POSITIVE.to_bits() - 1),
            VECTOR_LIMIT,
            -VECTOR_LIMIT,
            f64::from_bits(VECTOR_LIMIT.to_bits() - 1),
        ];
        let neighbours = |v: f64, xs: &mut Vec<f64>| {
            for j in -20_i64..=20 {
                let w = f64::from_bits(v.to_bits().wrapping_add_signed(j));
                if w.abs() <= VECTOR_LIMIT {
                    xs.push(w);
                }
            }
        };
        // |k| <= 636_619 keeps k pi/2 within the limit.
        for k in (-636_619_i32..=636_619).step_by(61) {
            neighbours(f64::from(k) * std::f64::consts::FRAC_PI_2, &mut xs);
            neighbours((f64::from(k) + 0.5) * std::f64::consts::FRAC_PI_2, &mut xs);
        }
        for _ in 0..1_000_000 {
            let bits = next();
            // Exponent uniform over subnormals..2^19, mantissa and sign random.
            let exponent = (bits >> 53) % 1043;
            let x = f64::from_bits((exponent << 52) | (bits & ((1 << 52) - 1)));
            let x = if bits & (1 << 52) != 0 { -x } else { x };
            if x.abs() <= VECTOR_LIMIT {
                xs.push(x);
            }
        }
        xs
    }

    /// Arguments off the vector path: NaN (with payloads and either sign), infinities, and
    /// finite values beyond the limit, mixed with ordinary ones.
    fn libm_path_cases() -> Vec<f64> {
        let specials = [
            f64::NAN,
            -f64::NAN,
            f64::from_bits(0x7FF0_0000_0000_0001),
            f64::from_bits(0xFFF8_0000_DEAD_BEEF),
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            -f64::MAX,
            f64::from_bits(VECTOR_LIMIT.to_bits() + 1),
            -f64::from_bits(VECTOR_LIMIT.to_bits() + 1),
            1.7e6,
            -3e9,
            1e22,
            1e300,
        ];
        let mut xs = Vec::new();
        for (i, &s) in specials.iter().cycle().take(20_000).enumerate() {
            xs.push(s);
            xs.extend((0..7).map(|j| f64::from((i * 7 + j) as u32) * 0.37 - 5000.0));
        }
        xs
    }

    /// Runs the public functions (dispatched at run time: the AVX-512 or AVX2 clone on a CPU
    /// that has it) and the same bodies compiled here at the baseline (SSE2 on x86-64) over slices of
    /// every length from 1 to 300 (so the vector loops' remainders run too), comparing bits.
    #[test]
    fn dispatched_and_baseline_paths_are_bit_identical() {
        #[cfg(target_arch = "x86_64")]
        println!(
            "AVX2 detected: {}, AVX-512F: {} (otherwise both sides are the baseline build)",
            std::arch::is_x86_feature_detected!("avx2"),
            std::arch::is_x86_feature_detected!("avx512f")
        );
        let mut vector = arguments();
        vector.extend(vector_path_edge_cases());
        assert!(vector.iter().all(|x| x.abs() <= VECTOR_LIMIT));
        let libm = libm_path_cases();
        let (mut fast, mut base) = (vec![0.0; 300], vec![0.0; 300]);
        let mut compared = 0;
        for xs in [&vector, &libm] {
            let mut start = 0;
            let mut i = 0;
            while start < xs.len() {
                let end = (start + 1 + (i * 37) % 300).min(xs.len());
                let chunk = &xs[start..end];
                let (fast, base) = (&mut fast[..chunk.len()], &mut base[..chunk.len()]);
                sin_into(chunk, fast);
                sin_into_body(chunk, base);
                let same =
                    |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same(fast, base), "sin differs on {chunk:?}");
                cos_into(chunk, fast);
                cos_into_body(chunk, base);
                assert!(same(fast, base), "cos differs on {chunk:?}");
                // A sum with an infinity or NaN term is NaN either way; which NaN (sign,
                // payload) depends on the operand order the vectorizer gives each addition.
                let same_sum =
                    |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
                let (a, b) = (sum_cos(chunk), sum_cos_body(chunk));
                assert!(same_sum(a, b), "sum_cos differs on {chunk:?}");
                // The fused sine and cosine sum and the scaled sine: the same bits as the
                // separate calls followed by the multiplication (rounded once), dispatched and
                // at the baseline.
                sin_into(chunk, base);
                base.iter_mut().for_each(|v| *v *= -1.7);
                let fused = sin_into_sum_cos(chunk, fast, -1.7);
                assert!(same(fast, base) && same_sum(fused, a), "fused on {chunk:?}");
                let fused_base = sin_into_sum_cos_body(chunk, fast, -1.7);
                assert!(
                    same(fast, base) && same_sum(fused_base, a),
                    "fused, baseline"
                );
                sin_into_scaled(chunk, fast, -1.7);
                assert!(same(fast, base), "sin_into_scaled on {chunk:?}");
                sin_into_scaled_body(chunk, fast, -1.7);
                assert!(same(fast, base), "sin_into_scaled at the baseline");
                compared += chunk.len();
                start = end;
                i += 1;
            }
        }
        println!("{compared} arguments, {} on the vector path", vector.len());
        assert!(compared > 3_000_000);
    }

    #[test]
    fn large_and_non_finite_arguments_take_the_libm_path() {
        let xs = [1e7, -3e9, 0.5];
        let mut out = [0.0; 3];
        sin_into(&xs, &mut out);
        for (o, x) in out.iter().zip(xs) {
            assert_eq!(o.to_bits(), x.sin().to_bits());
        }
        sin_into(&[f64::NAN, 1.0], &mut out[..2]);
        assert!(out[0].is_nan());
        assert!(sum_cos(&[f64::INFINITY]).is_nan());
    }

    #[test]
    fn scalar_sin_cos_equals_the_slice_functions() {
        // One reduction shared by both results must give exactly the slice functions' values
        // (which the test above holds to libm), and libm's beyond the vector range: each
        // argument as a one-element slice takes the same path as the scalar.
        let mut xs = arguments();
        xs.extend([1e7, -3e9, f64::NAN]);
        for x in xs {
            let (mut s, mut c) = ([0.0], [0.0]);
            sin_into(&[x], &mut s);
            cos_into(&[x], &mut c);
            let (a, b) = sin_cos(x);
            assert_eq!(
                [a, b].map(f64::to_bits),
                [s[0], c[0]].map(f64::to_bits),
                "x = {x:e}"
            );
        }
    }

    #[test]
    fn sum_cos_is_the_lane_sum_of_the_cosines() {
        let xs: Vec<f64> = (0..1000).map(|i| f64::from(i) * 0.37 - 100.0).collect();
        let mut c = vec![0.0; xs.len()];
        cos_into(&xs, &mut c);
        assert_eq!(
            sum_cos(&xs).to_bits(),
            crate::classical::core::sum::lane_sum(&c).to_bits()
        );
    }
}
