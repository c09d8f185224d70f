//! [`TimeGrid`]: the validated, fixed-step time grid of one `integrate` call.
//!
//! # The step-count rule
//!
//! As in the spec's implementation, the number of steps is `n_steps = round((t1 - t0) / dt)`
//! and sample `i` sits at `t0 + i * dt` (computed by multiplication, never by accumulating
//! `dt`, so the clock does not drift over long runs). physicskit adds one rule: the span must
//! hold a whole number of steps up to rounding, `|(t1 - t0)/dt - n_steps| <= 1e-9 *
//! max(1, (t1 - t0)/dt)`. Otherwise the last sample would silently miss `t1` by up to `dt/2`,
//! and the call is refused with a message that suggests a step that divides the span.

use super::error::{Error, Result};

/// Relative slack allowed between `(t1 - t0)/dt` and the nearest integer. Floating-point
/// division of decimal inputs (`3.0 / 3e-5`) is off by a few ulps (~1e-16 relative), so 1e-9
/// accepts every intended whole number of steps while rejecting any real mismatch.
const WHOLE_STEPS_TOLERANCE: f64 = 1e-9;

/// Largest step count accepted: beyond 2^53 the sample times `t0 + i*dt` stop being distinct.
const MAX_STEPS: f64 = 9_007_199_254_740_992.0;

/// A fixed-step time grid `t_i = t0 + i * dt`, `i = 0..=n_steps`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeGrid {
    t0: f64,
    dt: f64,
    n_steps: usize,
}

impl TimeGrid {
    /// Validates `t_span = (t0, t1)` and `dt` and counts the steps.
    ///
    /// # Errors
    /// [`Error::InvalidTimeSpan`] when `dt <= 0`, a value is not finite, `t1 < t0`, or the span
    /// is not a whole number of steps (see the module docs).
    ///
    /// # Example
    /// ```
    /// use physicskit::classical::TimeGrid;
    /// let grid = TimeGrid::new((0.0, 3.0), 3e-5).unwrap();
    /// assert_eq!(grid.n_steps(), 100_000);
    /// assert!(TimeGrid::new((0.0, 1.0), 0.3).is_err());
    /// ```
    pub fn new(t_span: (f64, f64), dt: f64) -> Result<Self> {
        let (t0, t1) = t_span;
        let fail = |reason: String| Error::InvalidTimeSpan { t0, t1, dt, reason };
        if !(t0.is_finite() && t1.is_finite()) {
            return Err(fail("t0 and t1 must be finite".into()));
        }
        if !dt.is_finite() || dt <= 0.0 {
            return Err(fail("dt must be finite and > 0".into()));
        }
        if t1 < t0 {
            return Err(fail(
                "t1 must be >= t0 (integration runs forward in time)".into(),
            ));
        }
        let ratio = (t1 - t0) / dt;
        if !ratio.is_finite() || ratio > MAX_STEPS {
            return Err(fail(format!(
                "(t1 - t0)/dt = {ratio:e} steps is more than can be represented"
            )));
        }
        let n = ratio.round();
        if (ratio - n).abs() > WHOLE_STEPS_TOLERANCE * ratio.max(1.0) {
            let suggestion = if n >= 1.0 { (t1 - t0) / n } else { t1 - t0 };
            return Err(fail(format!(
                "the span is {ratio} steps, not a whole number; use a dt that divides t1 - t0, \
                 e.g. dt = {suggestion}"
            )));
        }
        Ok(Self {
            t0,
            dt,
            // `n` is a non-negative whole number below 2^53, so the cast is exact.
            n_steps: n as usize,
        })
    }

    /// Start time.
    pub fn t0(&self) -> f64 {
        self.t0
    }

    /// Step size.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Number of steps; the full trajectory has `n_steps + 1` samples.
    pub fn n_steps(&self) -> usize {
        self.n_steps
    }

    /// Time of step index `i`.
    pub fn time(&self, i: usize) -> f64 {
        self.t0 + i as f64 * self.dt
    }

    /// Final time `t0 + n_steps * dt`.
    pub fn t_end(&self) -> f64 {
        self.time(self.n_steps)
    }
}
