//! Sums of many terms with eight interleaved partial sums, so they vectorize and still have one
//! fixed rounding.
//!
//! `iter.sum()` adds in index order: every addition waits for the previous one (4 cycles on
//! current x86-64), and the compiler may not reorder floating-point additions, so it cannot use
//! SIMD either. The energy of a 200-pendulum swarm, stored at every sample, spent ~800 cycles
//! per step in two such chains (`sum p^2` and `sum cos q`), a quarter of the whole step.
//!
//! [`lane_sum`] and friends instead keep `LANES = 8` partial sums, element `i` going to partial
//! sum `i mod 8`, and add the partial sums in a fixed tree at the end. That order is written in
//! the source, so it does not depend on the vector width the compiler picks (SSE2, AVX2 or
//! AVX-512 give the same bits), nor on the number of threads. The rounding error bound is that
//! of a sum of `n/8 + 3` terms instead of `n` (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, 2nd ed., §4.2): never worse than the sequential sum's.

/// Number of interleaved partial sums: one AVX-512 register, two AVX2 or four SSE2 registers.
const LANES: usize = 8;

/// The eight partial sums added pairwise in a fixed tree.
#[inline(always)]
fn combine<T: Copy + std::ops::Add<Output = T>>(acc: [T; LANES]) -> T {
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]))
}

/// Eight partial sums being filled: element `i` of the concatenation of every slice passed
/// to [`add_map`](Self::add_map) goes to partial sum `i mod 8`, as long as every slice but
/// the last has a length divisible by 8 (blocks of a longer sum).
#[derive(Debug, Clone, Copy)]
pub struct LaneSum([f64; LANES]);

impl Default for LaneSum {
    /// Every partial sum starts at `-0.0`, the exact identity of addition (`-0.0 + x` is `x`
    /// for every `x`, signed zeros included), so lanes left empty change nothing.
    fn default() -> Self {
        Self([-0.0; LANES])
    }
}

impl LaneSum {
    /// Adds `f(x[i])` for every element, element `i` into partial sum `i mod 8`.
    #[inline(always)]
    pub fn add_map(&mut self, x: &[f64], f: impl Fn(f64) -> f64) {
        self.add_map2(x, x, |v, _| f(v));
    }

    /// Adds `f(x[i], y[i])` over the common length, term `i` into partial sum `i mod 8`.
    #[inline(always)]
    pub fn add_map2(&mut self, x: &[f64], y: &[f64], f: impl Fn(f64, f64) -> f64) {
        let n = x.len().min(y.len());
        let full = n - n % LANES;
        let acc = &mut self.0;
        for (cx, cy) in x[..full]
            .chunks_exact(LANES)
            .zip(y[..full].chunks_exact(LANES))
        {
            for j in 0..LANES {
                acc[j] += f(cx[j], cy[j]);
            }
        }
        for ((a, &u), &v) in acc.iter_mut().zip(&x[full..n]).zip(&y[full..n]) {
            *a += f(u, v);
        }
    }

    /// The partial sums added in a fixed tree.
    #[inline(always)]
    pub fn total(self) -> f64 {
        combine(self.0)
    }
}

/// `sum_i f(x[i])`, element `i` added into partial sum `i mod 8` (see the module docs).
#[inline(always)]
pub fn lane_sum_map(x: &[f64], f: impl Fn(f64) -> f64) -> f64 {
    lane_sum_map2(x, x, |v, _| f(v))
}

/// `sum_i f(x[i], y[i])` over the common length, in the order of [`lane_sum_map`].
#[inline(always)]
pub fn lane_sum_map2(x: &[f64], y: &[f64], f: impl Fn(f64, f64) -> f64) -> f64 {
    let n = x.len().min(y.len());
    match short_lane_sum(n, -0.0, |i| f(x[i], y[i])) {
        Some(sum) => sum,
        None => lane_sum_map2_long(x, y, f),
    }
}

/// `t(0) + ... + t(n - 1)` for `n <= 4` in the order of [`lane_sum_map`], over any type with
/// addition (`f64`, or members in SIMD lanes, whose lanes then hold the `f64` sums); `zero`
/// for `n = 0`, `None` past four terms. The tree over lanes holding one term each or `-0.0`,
/// written out: the same bits, without the loop (the kinetic energy of a 1-3 dof system,
/// every sample).
#[inline(always)]
pub fn short_lane_sum<T: Copy + std::ops::Add<Output = T>>(
    n: usize,
    zero: T,
    t: impl Fn(usize) -> T,
) -> Option<T> {
    Some(match n {
        0 => zero,
        1 => t(0),
        2 => t(0) + t(1),
        3 => (t(0) + t(2)) + t(1),
        4 => (t(0) + t(2)) + (t(1) + t(3)),
        _ => return None,
    })
}

/// `t(0) + ... + t(n - 1)` in the order of [`lane_sum_map`] for any `n`, over any type with
/// addition (members in SIMD lanes, whose lanes then hold the `f64` sums of
/// [`lane_sum_map`]); `zero` must be `-0.0` (in every lane), the partial sums' start.
#[inline(always)]
pub fn lane_sum_of<T: Copy + std::ops::Add<Output = T>>(
    n: usize,
    zero: T,
    t: impl Fn(usize) -> T,
) -> T {
    if let Some(sum) = short_lane_sum(n, zero, &t) {
        return sum;
    }
    let mut acc = [zero; LANES];
    for i in 0..n {
        acc[i % LANES] = acc[i % LANES] + t(i);
    }
    combine(acc)
}

/// [`lane_sum_map2`] past four terms: out of line, so that the short sums stay small enough
/// to inline into every caller (a 2-dof energy per sample).
#[inline(never)]
fn lane_sum_map2_long(x: &[f64], y: &[f64], f: impl Fn(f64, f64) -> f64) -> f64 {
    let mut sum = LaneSum::default();
    sum.add_map2(x, y, f);
    sum.total()
}

/// `sum_i x[i]` in the order of [`lane_sum_map`].
#[inline(always)]
pub fn lane_sum(x: &[f64]) -> f64 {
    lane_sum_map(x, |v| v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The order is the one documented: partial sum `j` holds elements `j, j + 8, ...` in
    /// index order, then the fixed tree. Checked against that order written out naively, for
    /// every length up to 40 (the written-out short sums, all remainders, several full
    /// chunks), bit for bit, with signed zeros among the terms.
    #[test]
    fn order_is_the_documented_one() {
        let mut xs: Vec<f64> = (0..40)
            .map(|i| (f64::from(i) * 0.7301).sin() * 10f64.powi(i % 7 - 3))
            .collect();
        xs[0] = -0.0;
        xs[2] = 0.0;
        for n in 0..=xs.len() {
            let x = &xs[..n];
            let mut acc = [-0.0; LANES];
            for (i, &v) in x.iter().enumerate() {
                acc[i % LANES] += v;
            }
            let expected = combine(acc);
            assert_eq!(lane_sum(x).to_bits(), expected.to_bits(), "n = {n}");
            let y: Vec<f64> = x.iter().map(|v| v * 0.5 + 1.0).collect();
            let mut acc = [-0.0; LANES];
            for i in 0..n {
                acc[i % LANES] += x[i] * y[i];
            }
            assert_eq!(
                lane_sum_map2(x, &y, |a, b| a * b).to_bits(),
                combine(acc).to_bits(),
                "n = {n}"
            );
        }
    }

    /// The generic sum (members in lanes) gives `lane_sum`'s bits at every length, on terms
    /// chosen so that a different order would round differently (mixed magnitudes, signed
    /// zeros).
    #[test]
    fn the_generic_sum_has_the_order_of_lane_sum() {
        let xs: Vec<f64> = (0..40)
            .map(|i| (f64::from(i) * 0.7301).sin() * 10f64.powi(i % 7 - 3))
            .chain([-0.0, 0.0, 1e16, -1e16])
            .collect();
        for n in 0..=xs.len() {
            let x = &xs[..n];
            assert_eq!(
                lane_sum_of(n, -0.0, |i| x[i]).to_bits(),
                lane_sum(x).to_bits(),
                "n = {n}"
            );
        }
    }

    /// Accuracy: integers times a power of two are summed exactly in any order as long as no
    /// partial sum exceeds 2^53, so the lane sum must give the exact value; for a sum with
    /// cancellation it must be within the error bound of the module docs, `gamma_k sum |x_i|`
    /// with `k = n/8 + 3` additions on any term's path and `gamma_k = k eps / (1 - k eps)`,
    /// around a compensated sum (itself within ~1 ulp of the exact one). A term lost or added
    /// twice would miss by about that term, more than a million times the bound here.
    #[test]
    fn exact_where_exact_and_within_the_error_bound() {
        let ints: Vec<f64> = (0..1001).map(|i| f64::from(i * 37 % 101) * 0.125).collect();
        let exact: f64 = (0..1001).map(|i| f64::from(i * 37 % 101)).sum::<f64>() * 0.125;
        assert_eq!(lane_sum(&ints).to_bits(), exact.to_bits());

        let xs: Vec<f64> = (0..10_000)
            .map(|i| (f64::from(i) * 1.618).sin() * (1.0 + f64::from(i % 13)))
            .collect();
        // Neumaier's compensated sum: error ~ eps |sum| + n eps^2 sum |x|.
        let (mut s, mut c) = (0.0f64, 0.0f64);
        for &v in &xs {
            let t = s + v;
            c += if s.abs() >= v.abs() {
                (s - t) + v
            } else {
                (v - t) + s
            };
            s = t;
        }
        let reference = s + c;
        let k = (xs.len() / LANES + 3) as f64;
        let gamma = k * f64::EPSILON / (1.0 - k * f64::EPSILON);
        let bound =
            gamma * xs.iter().map(|v| v.abs()).sum::<f64>() + f64::EPSILON * reference.abs();
        let lanes = lane_sum(&xs);
        assert!(
            (lanes - reference).abs() <= bound,
            "lanes {lanes:e}, reference {reference:e}, bound {bound:e}"
        );
        // The bound is tight enough to catch a lost or doubled term of typical size.
        let mean_term = xs.iter().map(|v| v.abs()).sum::<f64>() / xs.len() as f64;
        assert!(bound < 1e-6 * mean_term);
    }
}
