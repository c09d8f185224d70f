//! Ctrl-C and progress reports during long integrations.
//!
//! Built-in systems integrate with the GIL released. Every few thousand steps the core calls
//! the [`SignalObserver`], which re-attaches to the interpreter for a moment and runs
//! `PyErr_CheckSignals`, then, if the caller asked for progress (`integrate_sampled(...,
//! progress=True)`), calls its Python `progress(step, n_steps)` callable. If a signal handler
//! or the callable raised (`KeyboardInterrupt` on Ctrl-C), the observer keeps that exception
//! and stops the run; [`crate::errors`] then raises it.

use std::ops::ControlFlow;

use physicskit::classical::Observer;
use pyo3::prelude::*;
use pyo3::PyErr;

/// Steps between signal checks: about a millisecond for small systems, so Ctrl-C is felt at
/// once while the check (a few hundred nanoseconds) costs nothing measurable.
pub const CHECK_EVERY: usize = 2048;

/// An [`Observer`] that reports progress to an optional Python callable and stops the
/// integration when a Python signal handler (or that callable) raises.
#[derive(Default)]
pub struct SignalObserver {
    /// The exception raised by the signal handler or the progress callable, if any.
    pub raised: Option<PyErr>,
    /// `progress(step, n_steps)`, called at every check.
    progress: Option<Py<PyAny>>,
}

impl SignalObserver {
    /// An observer that also calls `progress(step, n_steps)` at every check, if given.
    pub fn new(progress: Option<Py<PyAny>>) -> Self {
        Self {
            raised: None,
            progress,
        }
    }
}

impl Observer for SignalObserver {
    fn observe(&mut self, step: usize, n_steps: usize, _t: f64) -> ControlFlow<()> {
        let progress = self.progress.as_ref();
        let outcome = Python::attach(|py| {
            py.check_signals()?;
            if let Some(callable) = progress {
                callable.call1(py, (step, n_steps))?;
            }
            Ok::<(), PyErr>(())
        });
        match outcome {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.raised = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}
