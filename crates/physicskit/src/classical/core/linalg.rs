//! Small dense linear algebra that works in caller-owned buffers.
//!
//! The implicit-midpoint Newton solve and the Lagrangian engine's mass-matrix solve need
//! `LU` factorizations of matrices of a handful of rows, once or more per step. General crates
//! (nalgebra, faer) allocate a new matrix per factorization; these routines factor in place so
//! that the step loop stays allocation-free, and their rounding is what the stored digests of
//! the implicit methods hold (nalgebra's LU differs in the last bits; benchmarks/README.md
//! compares the two). Matrices are row-major `n x n` slices.

/// Pivots smaller than this times the largest entry of the matrix count as zero: an LU pivot
/// that small means the matrix is singular to working precision (about 50 ulps of the scale).
const SINGULAR_RELATIVE_PIVOT: f64 = 1e-14;

/// `true` if `pivot` counts as zero against a matrix whose largest entry is `scale`: the
/// criterion of [`lu_factor`], for closed-form solves that compute their pivots by hand (the
/// built-in Lagrangian systems), so that they call the same matrices singular. A NaN pivot or
/// scale counts as zero.
#[inline(always)]
pub fn negligible_pivot(pivot: f64, scale: f64) -> bool {
    !(pivot.abs() > SINGULAR_RELATIVE_PIVOT * scale && scale.is_finite())
}

/// The matrix is singular to working precision.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Singular;

/// LU-factorizes the row-major `n x n` matrix `a` in place with partial pivoting, recording
/// row swaps in `piv`.
///
/// # Errors
/// [`Singular`] if a pivot falls below `1e-14` times the largest entry, or the matrix holds a
/// non-finite number.
///
/// Always inlined: called with a constant `n` (the Lagrangian engine's fixed-size kernels) the
/// loops unroll.
#[inline(always)]
pub fn lu_factor(a: &mut [f64], n: usize, piv: &mut [usize]) -> Result<(), Singular> {
    debug_assert!(a.len() >= n * n && piv.len() >= n);
    // `f64::max` skips NaN, so finiteness is checked on its own.
    if !a[..n * n].iter().all(|v| v.is_finite()) {
        return Err(Singular);
    }
    let scale = a[..n * n].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if scale == 0.0 {
        return Err(Singular);
    }
    for k in 0..n {
        let (mut best, mut best_row) = (a[k * n + k].abs(), k);
        for r in k + 1..n {
            let v = a[r * n + k].abs();
            if v > best {
                best = v;
                best_row = r;
            }
        }
        if negligible_pivot(best, scale) {
            return Err(Singular);
        }
        piv[k] = best_row;
        if best_row != k {
            for c in 0..n {
                a.swap(k * n + c, best_row * n + c);
            }
        }
        let inv = 1.0 / a[k * n + k];
        for r in k + 1..n {
            let factor = a[r * n + k] * inv;
            a[r * n + k] = factor;
            for c in k + 1..n {
                a[r * n + c] -= factor * a[k * n + c];
            }
        }
    }
    Ok(())
}

/// Solves `A x = b` in place (`b` becomes `x`) from the factors of [`lu_factor`].
#[inline(always)]
pub fn lu_solve(lu: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    for (k, &swap) in piv.iter().enumerate().take(n) {
        b.swap(k, swap);
    }
    for r in 1..n {
        let s: f64 = (0..r).map(|c| lu[r * n + c] * b[c]).sum();
        b[r] -= s;
    }
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|c| lu[r * n + c] * b[c]).sum();
        b[r] = (b[r] - s) / lu[r * n + r];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_pivoting_system_exactly() {
        // A permutation-heavy 3x3 with a zero leading pivot; x = (1, 2, 3) is representable
        // and every intermediate is an integer, so the solve is exact.
        let mut a = [0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 0.0];
        let mut b = [7.0, 6.0, 4.0];
        let mut piv = [0; 3];
        lu_factor(&mut a, 3, &mut piv).unwrap();
        lu_solve(&a, 3, &piv, &mut b);
        for (x, want) in b.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - want).abs() < 1e-15, "{x} vs {want}");
        }
    }

    #[test]
    fn detects_singular_matrices() {
        let mut a = [1.0, 2.0, 2.0, 4.0];
        assert_eq!(lu_factor(&mut a, 2, &mut [0; 2]), Err(Singular));
        let mut nan = [f64::NAN, 0.0, 0.0, 1.0];
        assert_eq!(lu_factor(&mut nan, 2, &mut [0; 2]), Err(Singular));
    }
}
