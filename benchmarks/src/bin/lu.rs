//! The LU factorization and solve of the implicit methods' Newton steps and the Lagrangian
//! engine's mass-matrix solves (`core::linalg`, in place, no allocation) against nalgebra's
//! (`DMatrix::lu` and `solve_mut`, the crate the workspace already has), on the sizes those
//! solves have: `n` = 2 to 24 (a stage system of three Gauss–Legendre stages on a state of 8).
//! Prints ns per factor-and-solve, best of 7 rounds, and the largest difference between the
//! two solutions relative to the solution's size.
//!
//! `cargo run --release -p physicskit-benchmarks --bin lu` (numbers in `benchmarks/README.md`).

use std::hint::black_box;
use std::time::Instant;

use nalgebra::{DMatrix, DVector};
use physicskit::classical::core::linalg::{lu_factor, lu_solve};

/// A well-conditioned `n x n` matrix of the shape of `I - h J` (diagonally dominant, the
/// off-diagonal part from a fixed pseudo-random sequence) and a right-hand side.
fn problem(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = 0.123_456_789_f64;
    let mut next = || {
        x = (x * 3.987_654_321 + 0.271_828_182).fract();
        x - 0.5
    };
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            a[i * n + j] = if i == j { 1.0 } else { 0.3 * next() / n as f64 };
        }
    }
    let b = (0..n).map(|_| next()).collect();
    (a, b)
}

fn best_ns(repeats: usize, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..7 {
        let start = Instant::now();
        for _ in 0..repeats {
            f();
        }
        best = best.min(start.elapsed().as_nanos() as f64 / repeats as f64);
    }
    best
}

fn main() {
    println!("n    in place (ns)   nalgebra (ns)   ratio   max |x_ours - x_nalgebra| / |x|");
    for n in [2, 3, 4, 6, 8, 12, 16, 24] {
        let (a, b) = problem(n);
        let repeats = 2_000_000 / (n * n);
        let (mut work, mut piv, mut x) = (a.clone(), vec![0usize; n], b.clone());
        let ours = best_ns(repeats, || {
            work.copy_from_slice(&a);
            x.copy_from_slice(&b);
            lu_factor(black_box(&mut work), n, &mut piv).expect("regular");
            lu_solve(&work, n, &piv, black_box(&mut x));
        });
        let matrix = DMatrix::from_row_slice(n, n, &a);
        let rhs = DVector::from_column_slice(&b);
        let mut y = rhs.clone();
        let theirs = best_ns(repeats, || {
            y.copy_from(&rhs);
            let lu = black_box(matrix.clone()).lu();
            assert!(lu.solve_mut(black_box(&mut y)));
        });
        let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let diff = x
            .iter()
            .zip(y.iter())
            .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
        println!(
            "{n:<4} {ours:>13.1} {theirs:>15.1} {:>7.2}   {:.1e}",
            theirs / ours,
            diff / scale
        );
    }
}
