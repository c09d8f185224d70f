//! A terminal progress bar fed by the library's [`Observer`] hook.

use std::io::IsTerminal;
use std::ops::ControlFlow;

use indicatif::{ProgressBar, ProgressStyle};
use physicskit::classical::Observer;

/// Steps between observer calls: often enough for a smooth bar, rare enough to cost nothing.
pub const OBSERVE_EVERY: usize = 1024;

/// Drives an indicatif bar from [`Observer::observe`].
#[derive(Debug)]
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A bar for a run of `n_steps` steps, or `None` when stderr is not a terminal (pipes,
    /// logs and tests get no control characters).
    pub fn for_terminal(n_steps: usize) -> Option<Self> {
        if !std::io::stderr().is_terminal() {
            return None;
        }
        let bar = ProgressBar::new(n_steps as u64);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} steps  t = {msg}  eta {eta}")
        {
            bar.set_style(style);
        }
        Some(Self { bar })
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Observer for Progress {
    fn observe(&mut self, step: usize, _n_steps: usize, t: f64) -> ControlFlow<()> {
        self.bar.set_position(step as u64);
        self.bar.set_message(format!("{t:.4}"));
        ControlFlow::Continue(())
    }
}
