//! What the chaos analyses' loops report and keep: the [`Observer`] (progress bar, Ctrl-C),
//! consulted every `observe_every` steps as `integrate` consults it, and the thinning of the
//! running estimates (`history_stride`).
//!
//! A Lyapunov run of `t1 / dt = 10^8` steps renormalized every 10 steps has `10^7` running
//! estimates per exponent; `history_stride = s` keeps every `s`-th of them (and always the
//! last), without changing any number: the exponents, and each kept row, are bit-identical to
//! the run that keeps every row. The rows to keep are counted before anything is stored and
//! refused with [`Error::TrajectoryTooLarge`] when they would not fit in memory.

use std::ops::ControlFlow;

use crate::classical::core::memory_check;
use crate::classical::core::{Error, Result};
use crate::classical::integrators::Observer;

/// Steps between observer calls when [`AnalysisOptions::observe_every`] is 0, as for
/// `integrate`.
const DEFAULT_OBSERVE_EVERY: usize = 4096;

/// Options of the chaos analyses' loops. `AnalysisOptions::default()` keeps every row of the
/// history and has no observer.
#[derive(Default)]
pub struct AnalysisOptions<'a> {
    /// Progress observer, called every `observe_every` steps; `Break` stops the run with
    /// [`Error::Interrupted`].
    pub observer: Option<&'a mut dyn Observer>,
    /// Steps between observer calls; 0 means 4096.
    pub observe_every: usize,
    /// Keep every `history_stride`-th row of a running history (and the last); 0 or 1 keeps
    /// every row.
    pub history_stride: usize,
}

impl<'a> AnalysisOptions<'a> {
    /// Options with `observer` called every `every` steps.
    pub fn observed(observer: &'a mut dyn Observer, every: usize) -> Self {
        Self {
            observer: Some(observer),
            observe_every: every,
            history_stride: 1,
        }
    }

    /// The same options keeping every `stride`-th history row.
    #[must_use]
    pub fn with_history_stride(self, stride: usize) -> Self {
        Self {
            history_stride: stride,
            ..self
        }
    }

    /// The observer countdown for a run of `n_steps` steps.
    pub(crate) fn watch(&mut self, n_steps: usize) -> Watch<'_, 'a> {
        let every = match self.observe_every {
            0 => DEFAULT_OBSERVE_EVERY,
            k => k,
        };
        Watch {
            options: self,
            every,
            left: every,
            n_steps,
        }
    }

    /// The rows of a history of `rows` rows of `per_row` numbers to keep, checked to fit in
    /// memory.
    ///
    /// # Errors
    /// [`Error::TrajectoryTooLarge`].
    pub(crate) fn thinning(&self, rows: usize, per_row: usize) -> Result<Thinning> {
        let thinning = Thinning {
            stride: self.history_stride.max(1),
            rows,
        };
        memory_check(thinning.kept(), per_row)?;
        Ok(thinning)
    }
}

/// Which rows of a running history are kept: rows `s-1, 2s-1, ...` (0-based) and the last.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Thinning {
    stride: usize,
    rows: usize,
}

impl Thinning {
    /// Number of rows kept.
    pub(crate) fn kept(self) -> usize {
        self.rows / self.stride + usize::from(!self.rows.is_multiple_of(self.stride))
    }

    /// Whether row `row` is kept.
    #[inline]
    pub(crate) fn keeps(self, row: usize) -> bool {
        (row + 1).is_multiple_of(self.stride) || row + 1 == self.rows
    }
}

/// Counts steps down to the next observer call.
pub(crate) struct Watch<'o, 'a> {
    options: &'o mut AnalysisOptions<'a>,
    every: usize,
    left: usize,
    n_steps: usize,
}

impl Watch<'_, '_> {
    /// Call after step `done` (1-based), ending at time `t`.
    ///
    /// # Errors
    /// [`Error::Interrupted`] when the observer asks to stop.
    #[inline]
    pub(crate) fn tick(&mut self, done: usize, t: f64) -> Result<()> {
        self.left -= 1;
        if self.left > 0 {
            return Ok(());
        }
        self.left = self.every;
        match self.options.observer.as_deref_mut() {
            Some(observer) => match observer.observe(done, self.n_steps, t) {
                ControlFlow::Break(()) => Err(Error::Interrupted { t }),
                ControlFlow::Continue(()) => Ok(()),
            },
            None => Ok(()),
        }
    }
}
