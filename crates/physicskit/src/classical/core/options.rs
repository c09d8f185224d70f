//! [`IntegrateOptions`]: what to store and whom to tell while integrating.

use std::ops::ControlFlow;

use super::error::{Error, Result};

/// Which steps of the grid are stored in the [`SimulationResult`](super::SimulationResult).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sampling {
    /// Every step: `n_steps + 1` samples, as the spec documents.
    #[default]
    All,
    /// Every `k`-th step, plus the final step when `n_steps` is not a multiple of `k`.
    Stride(usize),
    /// Only the initial and the final state (two samples; one if `n_steps = 0`). For large
    /// ensembles whose full trajectory would not fit in memory.
    FinalOnly,
}

impl Sampling {
    /// The first stored step after step `step`, for a grid of `n_steps` steps (the final step
    /// is always stored). Step 0 is always stored too.
    #[inline]
    pub(crate) fn next_stored(self, step: usize, n_steps: usize) -> usize {
        match self {
            Sampling::All => step + 1,
            Sampling::Stride(k) => ((step / k + 1) * k).min(n_steps),
            Sampling::FinalOnly => n_steps,
        }
    }

    /// Number of stored samples for a grid of `n_steps` steps.
    pub(crate) fn count(self, n_steps: usize) -> usize {
        match self {
            Sampling::All => n_steps + 1,
            Sampling::Stride(k) => n_steps / k + 1 + usize::from(!n_steps.is_multiple_of(k)),
            Sampling::FinalOnly => 1 + usize::from(n_steps > 0),
        }
    }

    pub(crate) fn validate(self) -> Result<()> {
        match self {
            Sampling::Stride(0) => Err(Error::invalid("stride", 0.0, "must be >= 1")),
            _ => Ok(()),
        }
    }
}

/// Told of progress every [`IntegrateOptions::observe_every`] steps; may stop the run.
///
/// Used by the command line for its progress bar and by the Python bindings to stop on Ctrl-C.
/// It is called outside the per-step work, so a `dyn` call here costs nothing measurable.
pub trait Observer {
    /// `step` of `n_steps` is done and the clock reads `t`. Return `Break` to stop; the
    /// integration then returns [`Error::Interrupted`].
    fn observe(&mut self, step: usize, n_steps: usize, t: f64) -> ControlFlow<()>;
}

/// Options of `integrate_with`. `IntegrateOptions::default()` is what `integrate` uses: every
/// sample and the energy stored, no observer.
#[derive(Default)]
pub struct IntegrateOptions<'a> {
    /// Which samples to keep.
    pub sampling: Sampling,
    /// Skip the energy diagnostic (saves one energy evaluation per stored sample).
    pub skip_energy: bool,
    /// Progress observer, called every `observe_every` steps.
    pub observer: Option<&'a mut dyn Observer>,
    /// Steps between observer calls; 0 means the default of 4096.
    pub observe_every: usize,
}

impl IntegrateOptions<'_> {
    /// Options storing every `k`-th sample.
    pub fn stride(k: usize) -> Self {
        Self {
            sampling: Sampling::Stride(k),
            ..Self::default()
        }
    }

    /// Options storing only the initial and final samples.
    pub fn final_only() -> Self {
        Self {
            sampling: Sampling::FinalOnly,
            ..Self::default()
        }
    }

    pub(crate) fn observe_interval(&self) -> usize {
        if self.observe_every == 0 {
            4096
        } else {
            self.observe_every
        }
    }
}
