//! Ctrl-C during long integrations.
//!
//! Built-in systems integrate with the GIL released. Every few thousand steps the core calls
//! the [`SignalObserver`], which re-attaches to the interpreter for a moment and runs
//! `PyErr_CheckSignals`. If a handler raised (`KeyboardInterrupt` on Ctrl-C), the observer
//! keeps that exception and stops the run; [`crate::errors`] then raises it.

use std::ops::ControlFlow;

use physicskit::classical::Observer;
use pyo3::{PyErr, Python};

/// Steps between signal checks: about a millisecond for small systems, so Ctrl-C is felt at
/// once while the check (a few hundred nanoseconds) costs nothing measurable.
pub const CHECK_EVERY: usize = 2048;

/// An [`Observer`] that stops the integration when a Python signal handler raises.
#[derive(Default)]
pub struct SignalObserver {
    /// The exception raised by the signal handler, if any.
    pub raised: Option<PyErr>,
}

impl Observer for SignalObserver {
    fn observe(&mut self, _step: usize, _n_steps: usize, _t: f64) -> ControlFlow<()> {
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.raised = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}
