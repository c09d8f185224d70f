//! `implicit_midpoint`: the implicit midpoint rule.
//!
//! ```text
//! y1 = y0 + h f(t + h/2, (y0 + y1)/2)
//! ```
//!
//! written as an equation for the midpoint slope `k`, `k = f(t + h/2, y0 + (h/2) k)`,
//! `y1 = y0 + h k`. Order 2, symmetric (time-reversible), symplectic for every Hamiltonian
//! (separable or not), and it conserves every quadratic invariant of any ODE exactly, up to the
//! accuracy of the solve (G. J. Cooper, IMA J. Numer. Anal. 7 (1987) 1–13; Hairer, Lubich,
//! Wanner, *Geometric Numerical Integration* (2006), §IV.2).
//!
//! # The solve
//!
//! Each step starts from the cubic extrapolation of the last four slopes,
//! `4 k_n - 6 k_{n-1} + 4 k_{n-2} - k_{n-3}` (an `O(h^4)`-accurate predictor; lower orders for
//! the first steps, and again after a change of step size), and runs fixed-point iteration,
//! which contracts by about `theta = h L / 2` per sweep (`L` the Lipschitz constant) and costs
//! one evaluation per sweep. It stops at the rounding floor, when either
//!
//! - the correction is exactly zero, or no longer shrinks and is below `stall_tolerance` (the
//!   test Hairer, Lubich and Wanner recommend for implicit symplectic methods, GNI §VIII.6), or
//! - contracting at the measured rate `theta = |dk_i| / |dk_{i-1}|` (max norms), the distance
//!   left to the fixed point, at most `theta / (1 - theta)` times the last correction (Hairer &
//!   Wanner, *Solving ODEs II*, §IV.8), moves the state by less than `2^-10` ulp. Even with
//!   the same sign every step, such leftovers add up over `N` steps to less than the `sqrt(N)`
//!   ulps of the rounding random walk, for `N` up to 10^6.
//!
//! The second test needs two corrections, so two sweeps is the minimum; at the small steps
//! symplectic demonstrations use, the predictor makes it the norm: 2.0 evaluations per step for
//! the Euler top (dt = 1e-3), the double pendulum (dt = 3e-5), the coupled oscillators
//! (dt = 1e-4) and the heavy top (dt = 5e-5), against 3.0–3.75 with a quadratic predictor and
//! the first test alone; of these benchmark runs (1e5 steps), all but the heavy top's end
//! bit-identical to the longer iteration's. Stopping at a fixed tolerance `tol` instead leaves an error
//! of about `theta * tol` with the same sign every step, which drifts the energy linearly
//! (measured: 3e-12 over 1e5 steps of an oscillator at `tol` = 2 ulps).
//!
//! When fixed-point iteration contracts slowly (rate above 1/2) or diverges, and the field
//! supplies a Jacobian (analytic or automatic differentiation), the solver switches to Newton's
//! method on `k - f(t + h/2, y0 + h k/2) = 0`, refactoring `I - (h/2) J` only when Newton
//! itself slows down, and iterates until the correction is zero or no longer shrinks. A step
//! that converges neither way is an [`Error::SolverDidNotConverge`] naming `t`, the iterations
//! and the residual; an unconverged state is never returned.
//!
//! # Cost
//!
//! Per step: the sweeps' evaluations of `f` plus `O(dim)` work; no allocation (Newton's matrix is
//! allocated on first need). States of up to eight components (up to four degrees of freedom,
//! the rigid body's seven) run through code compiled for their size, with unrolled loops.

use super::field::VectorField;
use crate::classical::core::linalg::{lu_factor, lu_solve};
use crate::classical::core::{Error, Result};

/// Largest state dimension for which Newton's dense `dim x dim` matrix is allocated (on first
/// need): 4096^2 doubles are 128 MiB. Larger systems (big ensembles) rely on fixed-point
/// iteration, which needs no matrix and converges at the small steps they are run with.
pub const MAX_NEWTON_DIM: usize = 4096;

/// Tolerances and iteration limits of the implicit solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Converged when `max_i |h dk_i| <= tolerance * max(|y0|_inf, |h k|_inf)`. The default,
    /// 0, iterates to the rounding floor (see the module docs); a positive value trades exact
    /// conservation for speed.
    pub tolerance: f64,
    /// A correction at most this large that no longer shrinks is at the rounding floor of `f`
    /// and is accepted (default 1e-13, ~500 ulps: badly conditioned fields stall above 1 ulp).
    pub stall_tolerance: f64,
    /// Fixed-point sweeps before giving up on that iteration.
    pub max_fixed_point: usize,
    /// Newton iterations before reporting non-convergence.
    pub max_newton: usize,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            tolerance: 0.0,
            stall_tolerance: 1e-13,
            max_fixed_point: 50,
            max_newton: 30,
        }
    }
}

/// What the solver did, over all steps so far.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverStats {
    /// Steps taken.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub evaluations: u64,
    /// Jacobian evaluations (each followed by one LU factorization).
    pub jacobians: u64,
    /// Steps that needed Newton's method.
    pub newton_steps: u64,
    /// Most iterations (fixed-point plus Newton) in one step.
    pub max_iterations: usize,
    /// Largest relative error left in any step's state: the last correction, relative to the
    /// state's max norm, or where the contraction rate was measured, the distance to the fixed
    /// point it implies.
    pub max_residual: f64,
}

/// Converged slopes kept for the predictor: it extrapolates them with a polynomial of degree
/// `HISTORY - 1`.
const HISTORY: usize = 4;

/// `EXTRAPOLATION[p - 1][j]` multiplies the slope `j` steps back in the extrapolation from the
/// last `p` slopes to the next one: `(-1)^j binom(p, j + 1)` (Newton's backward-difference
/// formula, `k_{n+1} = sum_{i<p} nabla^i k_n` up to `O(h^p)`).
const EXTRAPOLATION: [[f64; HISTORY]; HISTORY] = [
    [1.0, 0.0, 0.0, 0.0],
    [2.0, -1.0, 0.0, 0.0],
    [3.0, -3.0, 1.0, 0.0],
    [4.0, -6.0, 4.0, -1.0],
];

/// The rounding floor of the solve, relative to the state: the fixed-point iteration stops
/// when the distance left to the fixed point, estimated from the measured contraction rate, is
/// below `2^-10` ulp of the state. A leftover that small changes the state's rounding only
/// rarely, and even if it had the same sign every step it would add up over `N` steps to
/// `N 2^-10` ulps, less than the `sqrt(N)` ulps rounding itself random-walks up to `N = 10^6`.
/// Measured on an oscillator over 1e5 steps: a floor of one ulp of the state drifted the energy
/// by 9e-12 at `h w` = 0.012, one ulp of the slope (`eps |k|`) by 5e-13 at `h w` = 0.12; this
/// floor leaves 2e-14 and 4e-14, the rounding level.
const FLOOR: f64 = f64::EPSILON / 1024.0;

/// The implicit midpoint stepper and its work buffers, allocated once.
#[derive(Debug, Clone)]
pub struct ImplicitMidpoint {
    dim: usize,
    k: Vec<f64>,
    k_new: Vec<f64>,
    mid: Vec<f64>,
    /// The last `HISTORY` converged slopes, a ring of `HISTORY` rows of `dim` (row-major);
    /// rows not yet written in the current run are zero.
    history: Vec<f64>,
    /// Row of `history` holding the newest slope.
    newest: usize,
    lu: Vec<f64>,
    piv: Vec<usize>,
    /// Rows of `history` that hold slopes of the current run: 0 to `HISTORY`.
    slopes: usize,
    /// The step those slopes were taken with; another step size restarts the predictor.
    last_h: f64,
    /// Tolerances and limits.
    pub settings: SolverSettings,
    stats: SolverStats,
}

/// How a solve ended: `(iterations, residual)`, whether it converged or stalled at the
/// rounding floor (the two are reported alike).
type Outcome = (usize, f64);

impl ImplicitMidpoint {
    /// Buffers for a `dim`-dimensional state.
    pub fn new(dim: usize) -> Self {
        Self {
            dim,
            k: vec![0.0; dim],
            k_new: vec![0.0; dim],
            mid: vec![0.0; dim],
            history: vec![0.0; HISTORY * dim],
            newest: 0,
            lu: Vec::new(),
            piv: Vec::new(),
            slopes: 0,
            last_h: 0.0,
            settings: SolverSettings::default(),
            stats: SolverStats::default(),
        }
    }

    /// What the solver did so far.
    pub fn stats(&self) -> SolverStats {
        self.stats
    }

    /// Forgets the previous slopes (call after changing `y` outside the stepper).
    pub fn invalidate(&mut self) {
        self.slopes = 0;
    }

    /// Advances `y` from `t` to `t + h` (`h` may be negative).
    ///
    /// # Errors
    /// [`Error::SolverDidNotConverge`], or whatever the field reports.
    pub fn step<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        debug_assert_eq!(y.len(), self.dim);
        // The same code, with the dimension a constant in each arm for small states.
        match self.dim {
            1 => self.step_sized(f, t, y, h, 1),
            2 => self.step_sized(f, t, y, h, 2),
            3 => self.step_sized(f, t, y, h, 3),
            4 => self.step_sized(f, t, y, h, 4),
            5 => self.step_sized(f, t, y, h, 5),
            6 => self.step_sized(f, t, y, h, 6),
            7 => self.step_sized(f, t, y, h, 7),
            8 => self.step_sized(f, t, y, h, 8),
            n => self.step_sized(f, t, y, h, n),
        }
    }

    /// One step on states of `n` components; inlined so that a constant `n` unrolls the loops.
    #[inline(always)]
    fn step_sized<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
        n: usize,
    ) -> Result<()> {
        let y = &mut y[..n];
        if h.to_bits() != self.last_h.to_bits() {
            self.slopes = 0;
            self.last_h = h;
        }
        if self.slopes == 0 {
            // Rows of an earlier run could hold anything, even non-finite values, and would
            // be multiplied by the zero coefficients of the low-order predictors.
            self.history.fill(0.0);
            f.eval(t, y, &mut self.k[..n])?;
            self.stats.evaluations += 1;
        } else {
            self.predict(n);
        }
        let scale_y = y.iter().fold(0.0_f64, |m, v| max(m, v.abs()));
        let outcome = match self.fixed_point(f, t, y, h, scale_y, n)? {
            Ok(done) => done,
            Err((iterations, residual)) => {
                self.newton(f, t, y, h, scale_y, iterations, residual)?
            }
        };
        let (iterations, residual) = outcome;
        let k = &self.k[..n];
        self.newest = (self.newest + 1) % HISTORY;
        self.history[self.newest * n..(self.newest + 1) * n].copy_from_slice(k);
        for (yi, ki) in y.iter_mut().zip(k) {
            *yi += h * ki;
        }
        self.slopes = (self.slopes + 1).min(HISTORY);
        self.stats.steps += 1;
        self.stats.max_iterations = self.stats.max_iterations.max(iterations);
        self.stats.max_residual = self.stats.max_residual.max(residual);
        Ok(())
    }

    /// Writes the extrapolation of the stored slopes into `k`.
    #[inline(always)]
    fn predict(&mut self, n: usize) {
        let [c0, c1, c2, c3] = EXTRAPOLATION[self.slopes - 1];
        let history = &self.history[..HISTORY * n];
        let row = |j: usize| {
            let r = (self.newest + HISTORY - j) % HISTORY;
            &history[r * n..(r + 1) * n]
        };
        let (k0, k1, k2, k3) = (row(0), row(1), row(2), row(3));
        for (i, k) in self.k[..n].iter_mut().enumerate() {
            *k = c0 * k0[i] + c1 * k1[i] + c2 * k2[i] + c3 * k3[i];
        }
    }

    /// Fixed-point sweeps. `Ok(Err((iterations, residual)))` hands over to Newton.
    #[inline(always)]
    fn fixed_point<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &[f64],
        h: f64,
        scale_y: f64,
        n: usize,
    ) -> Result<std::result::Result<Outcome, (usize, f64)>> {
        let s = self.settings;
        let half = 0.5 * h;
        let tm = t + half;
        let (mut k, mut k_new, mid) = (&mut self.k[..n], &mut self.k_new[..n], &mut self.mid[..n]);
        // Max-norm of the last correction of the slope, `max_i |k_new_i - k_i|`.
        let mut previous = f64::INFINITY;
        let mut outcome = Err((s.max_fixed_point, f64::INFINITY));
        let mut swapped = false;
        for it in 1..=s.max_fixed_point {
            for ((m, yi), ki) in mid.iter_mut().zip(y).zip(k.iter()) {
                *m = yi + half * ki;
            }
            f.eval(tm, mid, k_new)?;
            self.stats.evaluations += 1;
            let mut dk = 0.0_f64;
            for (a, b) in k_new.iter().zip(k.iter()) {
                dk = max(dk, (a - b).abs());
            }
            std::mem::swap(&mut k, &mut k_new);
            swapped = !swapped;
            if dk == 0.0 {
                // A fixed point of the rounded map: nothing left to iterate.
                outcome = Ok((it, 0.0));
                break;
            }
            // The slope's max-norm, and the correction of the state relative to its scale (the
            // reported residual).
            let k_max = k.iter().fold(0.0_f64, |m, v| max(m, v.abs()));
            let delta = relative(h.abs() * dk, scale_y.max(h.abs() * k_max));
            if !delta.is_finite() {
                // Diverged to overflow: restart Newton from the explicit predictor.
                f.eval(t, y, k)?;
                self.stats.evaluations += 1;
                outcome = Err((it, delta));
                break;
            }
            if delta <= s.tolerance {
                outcome = Ok((it, delta));
                break;
            }
            if it >= 2 {
                if dk < previous && delta * dk <= FLOOR * (previous - dk) {
                    // Contracting at the rate theta = dk / previous: the distance left to the
                    // fixed point, at most theta / (1 - theta) times this correction, is below
                    // the floor.
                    outcome = Ok((it, delta * dk / (previous - dk)));
                    break;
                }
                let stall = delta <= s.stall_tolerance;
                if dk >= previous && stall {
                    // No longer shrinking: the rounding floor of f is reached.
                    outcome = Ok((it, delta));
                    break;
                }
                if 2.0 * dk >= previous && !stall {
                    // Contracting too slowly (or diverging): hand over to Newton.
                    outcome = Err((it, delta));
                    break;
                }
            }
            previous = dk;
            outcome = Err((it, delta));
        }
        // The sweeps alternate between the two buffers; the converged slope belongs in `k`.
        if swapped {
            std::mem::swap(&mut self.k, &mut self.k_new);
        }
        match outcome {
            Err((it, delta)) if it == s.max_fixed_point && delta <= s.stall_tolerance => {
                Ok(Ok((it, delta)))
            }
            other => Ok(other),
        }
    }

    /// Newton's method with a Jacobian refreshed only when convergence slows.
    #[allow(clippy::too_many_arguments)]
    fn newton<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &[f64],
        h: f64,
        scale_y: f64,
        spent: usize,
        last_residual: f64,
    ) -> Result<Outcome> {
        let s = self.settings;
        let n = self.dim;
        let tm = t + 0.5 * h;
        let fail = |iterations: usize, residual: f64| Error::SolverDidNotConverge {
            t,
            iterations,
            residual,
        };
        if self.lu.is_empty() {
            if n > MAX_NEWTON_DIM {
                // A dense Newton matrix would not fit: only fixed-point iteration applies.
                return Err(fail(spent, last_residual));
            }
            self.lu = vec![0.0; n * n];
            self.piv = vec![0; n];
        }
        self.stats.newton_steps += 1;
        let mut fresh_jacobian = false;
        let mut previous = f64::INFINITY;
        let mut residual = last_residual;
        for it in 1..=s.max_newton {
            for ((m, yi), ki) in self.mid.iter_mut().zip(y).zip(&self.k) {
                *m = yi + 0.5 * h * ki;
            }
            if it == 1 || !fresh_jacobian {
                match f.jacobian(tm, &self.mid, &mut self.lu) {
                    None => return Err(fail(spent, residual)),
                    Some(r) => r?,
                }
                self.stats.jacobians += 1;
                // A = I - (h/2) J
                for (idx, a) in self.lu.iter_mut().enumerate() {
                    *a *= -0.5 * h;
                    if idx / n == idx % n {
                        *a += 1.0;
                    }
                }
                if lu_factor(&mut self.lu, n, &mut self.piv).is_err() {
                    return Err(fail(spent + it, residual));
                }
                fresh_jacobian = true;
            }
            // G(k) = k - f(tm, y0 + h k / 2); k <- k - A^-1 G
            f.eval(tm, &self.mid, &mut self.k_new)?;
            self.stats.evaluations += 1;
            for (g, ki) in self.k_new.iter_mut().zip(&self.k) {
                *g = ki - *g;
            }
            lu_solve(&self.lu, n, &self.piv, &mut self.k_new);
            let mut num = 0.0_f64;
            let mut hk = 0.0_f64;
            for (ki, d) in self.k.iter_mut().zip(&self.k_new) {
                *ki -= d;
                num = num.max((h * d).abs());
                hk = hk.max((h * *ki).abs());
            }
            residual = relative(num, scale_y.max(hk));
            if !residual.is_finite() {
                return Err(fail(spent + it, residual));
            }
            if residual <= s.tolerance {
                return Ok((spent + it, residual));
            }
            let rate = residual / previous;
            if it >= 2 && rate >= 1.0 && residual <= s.stall_tolerance {
                return Ok((spent + it, residual));
            }
            if it >= 2 && rate >= 0.5 && residual > s.stall_tolerance {
                // Simplified Newton slowed down: refresh the Jacobian next iteration.
                fresh_jacobian = false;
            }
            previous = residual;
        }
        if residual <= s.stall_tolerance {
            return Ok((spent + s.max_newton, residual));
        }
        Err(fail(spent + s.max_newton, residual))
    }
}

/// `a.max(b)` for non-negative, non-NaN `a` (a single `maxsd`; `f64::max` also handles NaN).
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// `num / scale`, with an exact zero kept zero and a zero scale making any nonzero `num`
/// infinite.
#[inline(always)]
fn relative(num: f64, scale: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else if scale > 0.0 {
        num / scale
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y' = (y1, -y0)`: slopes are sinusoids, smooth on the scale of the step.
    struct Rotation;

    impl VectorField for Rotation {
        fn dim(&self) -> usize {
            2
        }

        fn eval(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
            dy[0] = y[1];
            dy[1] = -y[0];
            Ok(())
        }
    }

    /// Max-norm distance between the predictor and the converged slope of one step, after
    /// `HISTORY` steps have filled the predictor's history.
    fn predictor_error(h: f64) -> f64 {
        let mut stepper = ImplicitMidpoint::new(2);
        let mut y = [1.0, 0.3];
        for i in 0..HISTORY {
            stepper.step(&Rotation, i as f64 * h, &mut y, h).unwrap();
        }
        stepper.predict(2);
        let predicted = [stepper.k[0], stepper.k[1]];
        stepper
            .step(&Rotation, HISTORY as f64 * h, &mut y, h)
            .unwrap();
        let converged = &stepper.k;
        (predicted[0] - converged[0])
            .abs()
            .max((predicted[1] - converged[1]).abs())
    }

    #[test]
    fn predictor_error_is_of_order_history() {
        // Extrapolating by a polynomial through the last `HISTORY` slopes errs by
        // O(h^HISTORY). Halving h from 0.02 divides the error by 2^HISTORY up to the next term,
        // O(h) relatively: the fitted order lies within 0.1 of HISTORY (a coefficient table one
        // order lower or with a wrong entry fits 3 or less). The errors (~1e-8 to 1e-10) stay
        // far above the rounding of the slopes (~1e-15), which would flatten the fit.
        let errors: Vec<f64> = [0.02, 0.01, 0.005]
            .iter()
            .map(|&h| predictor_error(h))
            .collect();
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!(
                (order - HISTORY as f64).abs() < 0.1,
                "measured predictor order {order} from errors {errors:?}"
            );
        }
    }

    #[test]
    fn extrapolation_reproduces_polynomials_of_its_degree() {
        // Row p - 1 extrapolates exactly from p samples of any polynomial of degree < p: the
        // coefficients are small integers, so the sums are exact in floating point.
        for (p, c) in EXTRAPOLATION.iter().enumerate().map(|(i, c)| (i + 1, c)) {
            for degree in 0..p as i32 {
                let poly = |x: f64| (0..=degree).map(|e| x.powi(e)).sum::<f64>();
                let extrapolated: f64 = (0..p).map(|j| c[j] * poly(-(j as f64))).sum();
                assert_eq!(
                    extrapolated.to_bits(),
                    poly(1.0).to_bits(),
                    "p = {p}, degree {degree}"
                );
            }
            assert!(
                c[p..].iter().all(|&x| x == 0.0),
                "row {p} uses only {p} slopes"
            );
        }
    }
}
