//! What every run on one system checks before it starts: the system, method, parameters and
//! times ([`Call`]), then the time grid, the built system and the output file ([`Run`]), and
//! the observer that shows progress and stops on a signal ([`RunObserver`]).
//!
//! The checks come in this order so that a bad invocation fails at once and a long run is
//! never wasted on a typo; the kind's own flags are read between the two stages, so that their
//! mistakes are reported before the output file is opened.

use std::ops::ControlFlow;

use anyhow::{anyhow, Result};
use physicskit::classical::catalog;
use physicskit::classical::model::{DynSystem, SystemEntry, Values};
use physicskit::classical::{Method, Observer, TimeGrid};

use crate::cli::SystemCall;
use crate::output::Pending;
use crate::params;
use crate::progress::Progress;
use crate::signals::Stop;

/// Reads `text` as the number of `--flag`.
///
/// # Errors
/// Text that is not a number, naming the flag.
pub fn number(flag: &str, text: &str) -> Result<f64> {
    text.trim()
        .parse()
        .map_err(|_| anyhow!("invalid value `{text}` for `--{flag}`: expected a number"))
}

/// Reads `text` as an integer of `--flag` at least `min`.
///
/// # Errors
/// Text that is not such an integer, naming the flag.
pub fn count(flag: &str, text: &str, min: usize) -> Result<usize> {
    text.trim()
        .parse()
        .ok()
        .filter(|&k| k >= min)
        .ok_or_else(|| {
            anyhow!("invalid value `{text}` for `--{flag}`: expected an integer >= {min}")
        })
}

/// A call's system, method, parameter values and times, checked.
pub struct Call<'c, K> {
    /// The command line as parsed.
    pub call: &'c SystemCall<K>,
    /// The catalogue entry.
    pub entry: &'static SystemEntry,
    /// `--method`, if given.
    method: Option<Method>,
    /// Every parameter's value, defaults included.
    pub values: Values,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    /// Step.
    pub dt: f64,
}

/// A run ready to start.
pub struct Run {
    /// The system, at its initial state.
    pub system: Box<dyn DynSystem>,
    /// The method: `--method`, or the built system's default.
    pub method: Method,
    /// The time grid.
    pub grid: TimeGrid,
    /// The output file, written by its `commit`.
    pub pending: Pending,
}

impl<'c, K> Call<'c, K> {
    /// Checks the system, method, parameters and times.
    ///
    /// # Errors
    /// The first of them that is wrong.
    pub fn check(call: &'c SystemCall<K>) -> Result<Self> {
        let entry =
            catalog::find(&call.name).map_err(|e| anyhow!("{e} (see `physicskit list`)"))?;
        let method = call
            .method
            .as_deref()
            .map(|m| params::method(entry, m))
            .transpose()?;
        let values = params::values(entry, &call.params)?;
        Ok(Self {
            call,
            entry,
            method,
            values,
            dt: number("dt", &call.dt)?,
            t0: number("t0", &call.t0)?,
            t1: number("t1", &call.t1)?,
        })
    }

    /// The text of the kind's flag `name`; flags with defaults always have one.
    pub fn option(&self, name: &str) -> Option<&'c str> {
        self.call.option(name)
    }

    /// Checks the grid, builds the system and opens the output file.
    ///
    /// # Errors
    /// A grid the library refuses, a system the constructor refuses, an unwritable output.
    pub fn start(&self) -> Result<Run> {
        let grid = TimeGrid::new((self.t0, self.t1), self.dt)?;
        // The built system has the last word on its default (a projectile with drag: rk4).
        let system = params::build(self.entry, &self.call.params, &self.values)?;
        let method = self.method.unwrap_or_else(|| system.default_method());
        let pending = Pending::create(&self.call.out)?;
        Ok(Run {
            system,
            method,
            grid,
            pending,
        })
    }
}

/// The progress bar (when stderr is a terminal) and the stopping signals, checked every
/// [`OBSERVE_EVERY`](crate::progress::OBSERVE_EVERY) steps.
pub struct RunObserver<'a> {
    bar: Option<Progress>,
    stop: &'a Stop,
}

impl<'a> RunObserver<'a> {
    /// For a run of `n_steps` steps.
    pub fn new(n_steps: usize, stop: &'a Stop) -> Self {
        Self {
            bar: Progress::for_terminal(n_steps),
            stop,
        }
    }

    /// Removes the bar and passes on the run's `outcome`, unless a signal arrived after the
    /// last check of the run: then nothing is to be written.
    ///
    /// # Errors
    /// The run's error, or the signal, naming the file not written.
    pub fn finish<T>(
        &self,
        outcome: physicskit::classical::Result<T>,
        out: &std::path::Path,
    ) -> Result<T> {
        if let Some(bar) = &self.bar {
            bar.finish();
        }
        let value = outcome?;
        if self.stop.requested() {
            // The temporary file goes with the `Pending` dropped by the caller.
            anyhow::bail!("interrupted before writing `{}`", out.display());
        }
        Ok(value)
    }
}

impl Observer for RunObserver<'_> {
    fn observe(&mut self, step: usize, n_steps: usize, t: f64) -> ControlFlow<()> {
        if self.stop.requested() {
            return ControlFlow::Break(());
        }
        match &mut self.bar {
            Some(bar) => bar.observe(step, n_steps, t),
            None => ControlFlow::Continue(()),
        }
    }
}
