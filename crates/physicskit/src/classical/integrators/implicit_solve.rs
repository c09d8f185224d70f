//! The shared implicit solve: one step of any implicit Runge–Kutta method, iterated to the
//! rounding floor.
//!
//! An `s`-stage implicit Runge–Kutta method with tableau `(A, b, c)` advances `y' = f(t, y)`
//! by
//!
//! ```text
//! k_i = f(t + c_i h, y0 + h sum_j a_ij k_j),   i = 1..s      (the stage equations)
//! y1  = y0 + h sum_i b_i k_i
//! ```
//!
//! [`ImplicitRk`] solves the stage equations for the stacked stage vector
//! `K = (k_1, ..., k_s)` (`s * dim` numbers) and takes the step. The method is data, a
//! [`Tableau`] named by a type ([`ButcherTableau`]); `implicit_midpoint` is the one-stage
//! tableau `a = 1/2, b = 1, c = 1/2`, and the Gauss–Legendre collocation methods are its
//! `s`-stage relatives: a new one is a file with its tableau, its `INFO` and a type alias of
//! `ImplicitRk`.
//!
//! # The solve
//!
//! Each step starts from the cubic extrapolation of the last four converged stage vectors,
//! `4 K_n - 6 K_{n-1} + 4 K_{n-2} - K_{n-3}` (an `O(h^4)`-accurate predictor; lower orders for
//! the first steps, and again after a change of step size; the very first step starts every
//! stage from the explicit slope `f(t0, y0)`), and runs fixed-point iteration `K <- F(K)`,
//! which contracts by about `theta = h L |A|` per sweep (`L` the Lipschitz constant of `f`) and
//! costs `s` evaluations per sweep. It stops at the rounding floor, when either
//!
//! - the correction is exactly zero, or no longer shrinks and is below `stall_tolerance` (the
//!   test Hairer, Lubich and Wanner recommend for implicit symplectic methods, GNI §VIII.6), or
//! - contracting at the measured rate `theta = |dK_i| / |dK_{i-1}|` (max norms), the distance
//!   left to the fixed point, at most `theta / (1 - theta)` times the last correction (Hairer &
//!   Wanner, *Solving ODEs II*, §IV.8), moves the state by less than `2^-10` ulp ([`FLOOR`]).
//!   Even with the same sign every step, such leftovers add up over `N` steps to less than the
//!   `sqrt(N)` ulps of the rounding random walk, for `N` up to 10^6.
//!
//! The second test needs two corrections, so two sweeps is the minimum; at the small steps
//! symplectic runs use, the predictor makes it the norm (`tests/classical/integrators/implicit_midpoint.rs` checks it).
//! Stopping at a fixed tolerance `tol` instead would leave an error of about `theta * tol`
//! with the same sign every step, which drifts the energy linearly.
//!
//! When fixed-point iteration contracts slowly (rate above 1/2) or diverges, and the field
//! supplies a Jacobian `J` (analytic or automatic differentiation), the solver switches to
//! simplified Newton iteration on `G(K) = K - F(K) = 0`, with the matrix
//! `I - h (A ⊗ J)` (`J` at the average of the stage states, the stage state itself for one
//! stage) factored once and refactored only when Newton itself slows down, and iterates until
//! the correction is zero or no longer shrinks. A step that converges neither way is an
//! [`Error::SolverDidNotConverge`] naming `t`, the iterations and the residual; an unconverged
//! state is never returned.
//!
//! # Cost
//!
//! Per step: `s` evaluations of `f` per sweep plus `O(s dim)` work; no allocation (Newton's
//! matrices are allocated on first need). States of up to eight components (up to four
//! degrees of freedom, the rigid body's seven) run through code compiled for their size, and
//! the number of stages is a compile-time constant, so the loops over stages and components
//! unroll.

use std::collections::BTreeMap;
use std::marker::PhantomData;

use super::field::VectorField;
use super::stepper::{FieldStepper, Report};
use crate::classical::core::linalg::{lu_factor, lu_solve};
use crate::classical::core::{Error, ExtraValue, Result};

/// Largest stage-system dimension (`s * dim`) for which Newton's dense matrix is allocated (on
/// first need): 4096^2 doubles are 128 MiB. Larger systems (big ensembles) rely on fixed-point
/// iteration, which needs no matrix and converges at the small steps they are run with.
pub const MAX_NEWTON_DIM: usize = 4096;

/// An `S`-stage Runge–Kutta tableau (Butcher array): stage coefficients `a`, weights `b`,
/// nodes `c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau<const S: usize> {
    /// `a[i][j]`: weight of stage `j`'s slope in stage `i`'s state.
    pub a: [[f64; S]; S],
    /// `b[i]`: weight of stage `i`'s slope in the step.
    pub b: [f64; S],
    /// `c[i]`: time of stage `i`, as a fraction of the step.
    pub c: [f64; S],
}

/// A method's tableau as a compile-time constant: the type parameter of [`ImplicitRk`] that
/// names the method. Being constants, the coefficients fold into the step's arithmetic
/// (`b h` with `b = 1` is `h`, `a h` a multiplication by a constant).
pub trait ButcherTableau<const S: usize> {
    /// The coefficients.
    const TABLEAU: Tableau<S>;
}

/// Tolerances and iteration limits of the implicit solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Converged when `max_i |h dK_i| <= tolerance * max(|y0|_inf, |h K|_inf)`. The default,
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

impl SolverStats {
    /// Adds the statistics to a result's `extra`: `rhs_evaluations`, `jacobian_evaluations`,
    /// `newton_steps`, `solver_iterations_max`, `solver_evaluations_mean` (per step) and
    /// `solver_residual_max`.
    pub fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        let steps = self.steps.max(1) as f64;
        for (name, value) in [
            ("rhs_evaluations", self.evaluations as f64),
            ("jacobian_evaluations", self.jacobians as f64),
            ("newton_steps", self.newton_steps as f64),
            ("solver_iterations_max", self.max_iterations as f64),
            ("solver_evaluations_mean", self.evaluations as f64 / steps),
            ("solver_residual_max", self.max_residual),
        ] {
            extra.insert(name.into(), ExtraValue::Scalar(value));
        }
    }
}

/// Converged stage vectors kept for the predictor: it extrapolates them with a polynomial of
/// degree `HISTORY - 1`.
const HISTORY: usize = 4;

/// `EXTRAPOLATION[p - 1][j]` multiplies the stage vector `j` steps back in the extrapolation
/// from the last `p` of them to the next one: `(-1)^j binom(p, j + 1)` (Newton's
/// backward-difference formula, `K_{n+1} = sum_{i<p} nabla^i K_n` up to `O(h^p)`).
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
/// A floor of one ulp of the state, or of the slope, leaves a measurable energy drift on an
/// oscillator over 1e5 steps; this one leaves the rounding level (figures in
/// `benchmarks/README.md`).
pub const FLOOR: f64 = f64::EPSILON / 1024.0;

/// One step of the `S`-stage implicit Runge–Kutta method with tableau `T`, solved to the
/// rounding floor (see the module docs), with its work buffers, allocated once.
#[derive(Debug, Clone)]
pub struct ImplicitRk<const S: usize, T> {
    dim: usize,
    /// The stage vector `K` (`S * dim`).
    k: Vec<f64>,
    /// The next iterate of `K`, or Newton's residual and correction.
    k_new: Vec<f64>,
    /// The stage states `y0 + h sum_j a_ij k_j` (`S * dim`).
    stage: Vec<f64>,
    /// The last `HISTORY` converged stage vectors, a ring of `HISTORY` rows of `S * dim`
    /// (row-major); rows not yet written in the current run are zero.
    history: Vec<f64>,
    /// Row of `history` holding the newest stage vector.
    newest: usize,
    /// Newton's matrix `I - h (A ⊗ J)` and its LU factors (`(S dim)^2`, on first need).
    lu: Vec<f64>,
    piv: Vec<usize>,
    /// `J` at the average stage state, for more than one stage (`dim^2`, on first need).
    jac: Vec<f64>,
    /// Rows of `history` that hold stage vectors of the current run: 0 to `HISTORY`.
    slopes: usize,
    /// The step those stage vectors were taken with; another step size restarts the predictor.
    last_h: f64,
    /// Tolerances and limits.
    pub settings: SolverSettings,
    stats: SolverStats,
    method: PhantomData<T>,
}

/// How a solve ended: `(iterations, residual)`, whether it converged or stalled at the
/// rounding floor (the two are reported alike).
type Outcome = (usize, f64);

/// The tableau scaled by one step: `a h`, `b h` and the stage times `t + c h`.
#[derive(Clone, Copy)]
struct Scaled<const S: usize> {
    ah: [[f64; S]; S],
    bh: [f64; S],
    tc: [f64; S],
}

impl<const S: usize> Scaled<S> {
    #[inline(always)]
    fn new(tableau: &Tableau<S>, t: f64, h: f64) -> Self {
        let mut ah = [[0.0; S]; S];
        for (row, a) in ah.iter_mut().zip(&tableau.a) {
            for (x, aij) in row.iter_mut().zip(a) {
                *x = aij * h;
            }
        }
        Self {
            ah,
            bh: tableau.b.map(|b| b * h),
            tc: tableau.c.map(|c| t + c * h),
        }
    }
}

impl<const S: usize, T: ButcherTableau<S>> ImplicitRk<S, T> {
    /// Buffers for `dim`-dimensional states.
    pub fn new(dim: usize) -> Self {
        Self {
            dim,
            k: vec![0.0; S * dim],
            k_new: vec![0.0; S * dim],
            stage: vec![0.0; S * dim],
            history: vec![0.0; HISTORY * S * dim],
            newest: 0,
            lu: Vec::new(),
            piv: Vec::new(),
            jac: Vec::new(),
            slopes: 0,
            last_h: 0.0,
            settings: SolverSettings::default(),
            stats: SolverStats::default(),
            method: PhantomData,
        }
    }

    /// What the solver did so far.
    pub fn stats(&self) -> SolverStats {
        self.stats
    }

    /// Forgets the previous stage vectors (call after changing `y` outside the stepper).
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
        let m = S * n;
        let y = &mut y[..n];
        let scaled = Scaled::new(&T::TABLEAU, t, h);
        if h.to_bits() != self.last_h.to_bits() {
            self.slopes = 0;
            self.last_h = h;
        }
        if self.slopes == 0 {
            // Rows of an earlier run could hold anything, even non-finite values, and would
            // be multiplied by the zero coefficients of the low-order predictors.
            self.history.fill(0.0);
            explicit_slope(f, t, y, &mut self.k[..S * n], n)?;
            self.stats.evaluations += 1;
        } else {
            self.predict(m);
        }
        let scale_y = y.iter().fold(0.0_f64, |acc, v| max(acc, v.abs()));
        let outcome = match self.fixed_point(f, t, &scaled, y, h, scale_y, n)? {
            Ok(done) => done,
            Err((iterations, residual)) => {
                self.newton(f, t, &scaled, y, h, scale_y, iterations, residual)?
            }
        };
        let (iterations, residual) = outcome;
        let k = &self.k[..m];
        self.newest = (self.newest + 1) % HISTORY;
        self.history[self.newest * m..(self.newest + 1) * m].copy_from_slice(k);
        // y1 = y0 + sum_i (b_i h) k_i, summed in stage order.
        for (i, bh) in scaled.bh.iter().enumerate() {
            for (yl, kl) in y.iter_mut().zip(&k[i * n..(i + 1) * n]) {
                *yl += bh * kl;
            }
        }
        self.slopes = (self.slopes + 1).min(HISTORY);
        self.stats.steps += 1;
        self.stats.max_iterations = self.stats.max_iterations.max(iterations);
        self.stats.max_residual = self.stats.max_residual.max(residual);
        Ok(())
    }

    /// Writes the extrapolation of the stored stage vectors (of `m` numbers) into `k`.
    #[inline(always)]
    fn predict(&mut self, m: usize) {
        let [c0, c1, c2, c3] = EXTRAPOLATION[self.slopes - 1];
        let history = &self.history[..HISTORY * m];
        let row = |j: usize| {
            let r = (self.newest + HISTORY - j) % HISTORY;
            &history[r * m..(r + 1) * m]
        };
        let (k0, k1, k2, k3) = (row(0), row(1), row(2), row(3));
        for (i, k) in self.k[..m].iter_mut().enumerate() {
            *k = c0 * k0[i] + c1 * k1[i] + c2 * k2[i] + c3 * k3[i];
        }
    }

    /// Fixed-point sweeps `K <- F(K)`. `Ok(Err((iterations, residual)))` hands over to Newton.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn fixed_point<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        scaled: &Scaled<S>,
        y: &[f64],
        h: f64,
        scale_y: f64,
        n: usize,
    ) -> Result<std::result::Result<Outcome, (usize, f64)>> {
        let s = self.settings;
        let m = S * n;
        let (mut k, mut k_new, stage) =
            (&mut self.k[..m], &mut self.k_new[..m], &mut self.stage[..m]);
        // Max-norm of the last correction of the stage vector, `max_i |k_new_i - k_i|`.
        let mut previous = f64::INFINITY;
        let mut outcome = Err((s.max_fixed_point, f64::INFINITY));
        let mut swapped = false;
        for it in 1..=s.max_fixed_point {
            stage_states(stage, y, k, scaled, n);
            evaluate_stages(f, scaled, stage, k_new, n)?;
            self.stats.evaluations += S as u64;
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
            // The stage vector's max-norm, and the correction of the state relative to its
            // scale (the reported residual).
            let k_max = k.iter().fold(0.0_f64, |acc, v| max(acc, v.abs()));
            let delta = relative(h.abs() * dk, scale_y.max(h.abs() * k_max));
            if !delta.is_finite() {
                // Diverged to overflow: restart Newton from the explicit slope.
                explicit_slope(f, t, y, k, n)?;
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
        // The sweeps alternate between the two buffers; the converged stages belong in `k`.
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

    /// Simplified Newton iteration on `K - F(K) = 0`, with the matrix `I - h (A ⊗ J)`
    /// refactored only when convergence slows.
    #[allow(clippy::too_many_arguments)]
    fn newton<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        scaled: &Scaled<S>,
        y: &[f64],
        h: f64,
        scale_y: f64,
        spent: usize,
        last_residual: f64,
    ) -> Result<Outcome> {
        let s = self.settings;
        let n = self.dim;
        let m = S * n;
        let fail = |iterations: usize, residual: f64| Error::SolverDidNotConverge {
            t,
            iterations,
            residual,
        };
        if self.lu.is_empty() {
            if m > MAX_NEWTON_DIM {
                // A dense Newton matrix would not fit: only fixed-point iteration applies.
                return Err(fail(spent, last_residual));
            }
            self.lu = vec![0.0; m * m];
            self.piv = vec![0; m];
            if S > 1 {
                self.jac = vec![0.0; n * n];
            }
        }
        self.stats.newton_steps += 1;
        let mut fresh_jacobian = false;
        let mut previous = f64::INFINITY;
        let mut residual = last_residual;
        for it in 1..=s.max_newton {
            stage_states(&mut self.stage, y, &self.k, scaled, n);
            if it == 1 || !fresh_jacobian {
                if self.newton_matrix(f, scaled, n)?.is_none() {
                    return Err(fail(spent, residual));
                }
                self.stats.jacobians += 1;
                if lu_factor(&mut self.lu, m, &mut self.piv).is_err() {
                    return Err(fail(spent + it, residual));
                }
                fresh_jacobian = true;
            }
            // G(K) = K - F(K); K <- K - M^-1 G
            evaluate_stages(f, scaled, &mut self.stage, &mut self.k_new, n)?;
            self.stats.evaluations += S as u64;
            for (g, ki) in self.k_new.iter_mut().zip(&self.k) {
                *g = ki - *g;
            }
            lu_solve(&self.lu, m, &self.piv, &mut self.k_new);
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

    /// Writes Newton's matrix `I - h (A ⊗ J)` into `lu`, `J` the field's Jacobian at the
    /// average of the current stage states (for one stage, at the stage state, in place).
    /// `Ok(None)` if the field has no Jacobian.
    fn newton_matrix<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        scaled: &Scaled<S>,
        n: usize,
    ) -> Result<Option<()>> {
        let m = S * n;
        if S == 1 {
            match f.jacobian(scaled.tc[0], &self.stage[..n], &mut self.lu) {
                None => return Ok(None),
                Some(r) => r?,
            }
            // A = I - (a h) J
            let scale = -scaled.ah[0][0];
            for (idx, a) in self.lu.iter_mut().enumerate() {
                *a *= scale;
                if idx / n == idx % n {
                    *a += 1.0;
                }
            }
            return Ok(Some(()));
        }
        // The average stage state and time; `k_new` is free until the stages are evaluated.
        let inv = 1.0 / S as f64;
        let mean = &mut self.k_new[..n];
        mean.copy_from_slice(&self.stage[..n]);
        for i in 1..S {
            for (x, s) in mean.iter_mut().zip(&self.stage[i * n..(i + 1) * n]) {
                *x += s;
            }
        }
        mean.iter_mut().for_each(|x| *x *= inv);
        let t_mean = scaled.tc.iter().sum::<f64>() * inv;
        match f.jacobian(t_mean, mean, &mut self.jac) {
            None => return Ok(None),
            Some(r) => r?,
        }
        for (i, ah_i) in scaled.ah.iter().enumerate() {
            for (j, &ah_ij) in ah_i.iter().enumerate() {
                for r in 0..n {
                    let row = &mut self.lu[(i * n + r) * m + j * n..][..n];
                    for (x, jac) in row.iter_mut().zip(&self.jac[r * n..(r + 1) * n]) {
                        *x = -ah_ij * jac;
                    }
                    if i == j {
                        row[r] += 1.0;
                    }
                }
            }
        }
        Ok(Some(()))
    }
}

/// Every stage of `k` (`S` rows of `n`) set to the explicit slope `f(t, y)`: one evaluation.
#[inline(always)]
fn explicit_slope<F: VectorField + ?Sized>(
    f: &F,
    t: f64,
    y: &[f64],
    k: &mut [f64],
    n: usize,
) -> Result<()> {
    f.eval(t, y, &mut k[..n])?;
    for i in 1..k.len() / n.max(1) {
        k.copy_within(..n, i * n);
    }
    Ok(())
}

/// `stage_i = y + sum_j (a_ij h) k_j` for each stage `i`.
#[inline(always)]
fn stage_states<const S: usize>(
    stage: &mut [f64],
    y: &[f64],
    k: &[f64],
    scaled: &Scaled<S>,
    n: usize,
) {
    for (i, ah_i) in scaled.ah.iter().enumerate() {
        let stage_i = &mut stage[i * n..(i + 1) * n];
        for ((x, yl), kl) in stage_i.iter_mut().zip(&y[..n]).zip(&k[..n]) {
            *x = yl + ah_i[0] * kl;
        }
        for (j, ah_ij) in ah_i.iter().enumerate().skip(1) {
            for (x, kl) in stage_i.iter_mut().zip(&k[j * n..(j + 1) * n]) {
                *x += ah_ij * kl;
            }
        }
    }
}

/// `out_i = f(t + c_i h, stage_i)` for each stage `i`.
#[inline(always)]
fn evaluate_stages<F: VectorField + ?Sized, const S: usize>(
    f: &F,
    scaled: &Scaled<S>,
    stage: &mut [f64],
    out: &mut [f64],
    n: usize,
) -> Result<()> {
    for (i, &t_i) in scaled.tc.iter().enumerate() {
        f.eval(
            t_i,
            &stage[i * n..(i + 1) * n],
            &mut out[i * n..(i + 1) * n],
        )?;
    }
    Ok(())
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

impl<const S: usize, T> Report for ImplicitRk<S, T> {
    /// The [`SolverStats`] ([`SolverStats::report`]).
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        self.stats.report(extra);
    }
}

impl<const S: usize, T: ButcherTableau<S> + 'static> FieldStepper for ImplicitRk<S, T> {
    fn new(dim: usize) -> Self {
        ImplicitRk::new(dim)
    }

    #[inline(always)]
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.step(f, t, y, h)
    }
}

#[cfg(test)]
mod tests {
    use super::super::implicit_midpoint::MidpointRule;
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
        let mut stepper = ImplicitRk::<1, MidpointRule>::new(2);
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

    /// The two-stage Gauss–Legendre tableau (order 4; Hairer, Lubich, Wanner, GNI §II.1.3),
    /// to exercise the solve with more than one stage.
    struct GaussLegendre4;

    const R: f64 = 0.288_675_134_594_812_9; // sqrt(3) / 6

    impl ButcherTableau<2> for GaussLegendre4 {
        const TABLEAU: Tableau<2> = Tableau {
            a: [[0.25, 0.25 - R], [0.25 + R, 0.25]],
            b: [0.5, 0.5],
            c: [0.5 - R, 0.5 + R],
        };
    }

    /// A forced pendulum, `q' = p`, `p' = -sin q + cos(2 t) / 2`, with its Jacobian: nonlinear and
    /// time-dependent, so that the stage coupling `A` and the nodes `c` both show in the error.
    struct ForcedPendulum;

    impl VectorField for ForcedPendulum {
        fn dim(&self) -> usize {
            2
        }

        fn eval(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
            dy[0] = y[1];
            dy[1] = -y[0].sin() + 0.5 * (2.0 * t).cos();
            Ok(())
        }

        fn jacobian(&self, _t: f64, y: &[f64], jac: &mut [f64]) -> Option<Result<()>> {
            jac.copy_from_slice(&[0.0, 1.0, -y[0].cos(), 0.0]);
            Some(Ok(()))
        }
    }

    /// The state at t = 1 from `(1, 0)` with `stepper`.
    fn run_to_one(stepper: &mut impl FnMut(f64, &mut [f64], f64), h: f64) -> [f64; 2] {
        let mut y = [1.0, 0.0];
        let n = (1.0 / h).round() as usize;
        for i in 0..n {
            stepper(i as f64 * h, &mut y, h);
        }
        y
    }

    /// The two-stage method at step `h`: the state at t = 1 and the solver's statistics.
    fn gauss_legendre4(h: f64, newton: bool) -> ([f64; 2], SolverStats) {
        let mut stepper = ImplicitRk::<2, GaussLegendre4>::new(2);
        if newton {
            // One sweep, then Newton's method on the stacked stages.
            stepper.settings.max_fixed_point = 1;
        }
        let y = run_to_one(
            &mut |t, y, h| stepper.step(&ForcedPendulum, t, y, h).unwrap(),
            h,
        );
        (y, stepper.stats())
    }

    #[test]
    fn two_stage_gauss_legendre_has_order_four_by_fixed_point_and_by_newton() {
        // The reference: the classical Runge–Kutta method (independent of this solve) at
        // h = 1e-3, accurate to ~1e-13, far below the errors measured (~1e-7 to 1e-9).
        let mut rk4 = super::super::rk4::Rk4::new(2);
        let reference = run_to_one(
            &mut |t, y, h| rk4.step(&ForcedPendulum, t, y, h).unwrap(),
            1e-3,
        );
        // Order 4 (the collocation order 2s) through both solves: halving h divides the
        // error by 16 up to O(h) relative corrections, so the fitted order lies within 0.15
        // of 4; a wrong stage coupling or wrong nodes (a transposed A, c swapped) drop it.
        for newton in [false, true] {
            let runs: Vec<_> = [0.1, 0.05, 0.025]
                .iter()
                .map(|&h| gauss_legendre4(h, newton))
                .collect();
            let errors: Vec<f64> = runs
                .iter()
                .map(|(y, _)| (y[0] - reference[0]).hypot(y[1] - reference[1]))
                .collect();
            for pair in errors.windows(2) {
                let order = (pair[0] / pair[1]).log2();
                assert!(
                    (order - 4.0).abs() < 0.15,
                    "newton {newton}: order {order}, errors {errors:?}"
                );
            }
            for (_, stats) in &runs {
                assert_eq!(stats.newton_steps > 0, newton, "{stats:?}");
                assert_eq!(
                    stats.evaluations % 2,
                    1,
                    "two per sweep, one to start: {stats:?}"
                );
                if newton {
                    // Simplified Newton with the Jacobian at the average stage state converges
                    // fast here: one sweep and five Newton iterations to the rounding floor at
                    // every step size (measured: 6). A wrong block of I - h (A ⊗ J) would
                    // converge like the fixed point, at a rate ~h |A|: 9-12 iterations here.
                    assert!(stats.max_iterations <= 7, "{stats:?}");
                }
            }
        }
    }

    /// [`Rotation`] with its Jacobian, so that Newton's method can run.
    struct RotationWithJacobian;

    impl VectorField for RotationWithJacobian {
        fn dim(&self) -> usize {
            2
        }

        fn eval(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<()> {
            Rotation.eval(t, y, dy)
        }

        fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut [f64]) -> Option<Result<()>> {
            jac.copy_from_slice(&[0.0, 1.0, -1.0, 0.0]);
            Some(Ok(()))
        }
    }

    #[test]
    fn two_stage_gauss_legendre_keeps_a_quadratic_invariant() {
        // |y|^2 of the rotation is a quadratic invariant, which Gauss–Legendre methods keep
        // exactly; the solve, iterated to the rounding floor, leaves a few ulps per step: over
        // 100 steps, below 1e-14 (a solve stopped at 1e-10 would leave ~1e-11).
        for newton in [false, true] {
            let mut stepper = ImplicitRk::<2, GaussLegendre4>::new(2);
            if newton {
                stepper.settings.max_fixed_point = 1;
            }
            let mut y = [1.0, 0.5];
            for i in 0..100 {
                stepper
                    .step(&RotationWithJacobian, i as f64 * 0.1, &mut y, 0.1)
                    .unwrap();
            }
            let drift = y[0] * y[0] + y[1] * y[1] - 1.25;
            assert!(drift.abs() < 1e-14, "newton {newton}: {drift:e}");
        }
    }
}
