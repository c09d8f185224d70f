//! `physicskit simulate`: parse, build, integrate, write.
//!
//! The system is built through the catalogue (`catalog::find(name)`, its entry's checked
//! values, its builder) into a `Box<dyn DynSystem>`, which integrates with the library's
//! generic loop. Everything that can be checked before the integration is checked first
//! (system, method, parameters, the constructor's checks, the time grid, the output path), so
//! a bad invocation fails at once and a long run is never wasted on a typo.

use std::ops::ControlFlow;

use anyhow::{anyhow, Result};
use physicskit::classical::catalog;
use physicskit::classical::{
    Error, IntegrateOptions, Method, Observer, Sampling, TimeGrid, Tolerances,
};

use crate::cli::SystemCall;
use crate::output::{Pending, Record};
use crate::params;
use crate::progress::{Progress, OBSERVE_EVERY};
use crate::signals::Stop;

fn number(flag: &str, text: &str) -> Result<f64> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| anyhow!("invalid value `{text}` for `--{flag}`: expected a number"))?;
    Ok(v)
}

/// The tolerances of `--rtol` and `--atol`, checked for `method` (an error naming the flag for
/// a value that is not a number > 0, or for a fixed-step method).
fn tolerances(call: &SystemCall, method: Method) -> Result<Option<Tolerances>> {
    let rtol = call
        .rtol
        .as_deref()
        .map(|t| number("rtol", t))
        .transpose()?;
    let atol = call
        .atol
        .as_deref()
        .map(|t| number("atol", t))
        .transpose()?;
    Tolerances::for_method(rtol, atol, method).map_err(|e| match e {
        Error::InvalidParameter { name, reason, .. } | Error::InvalidArgument { name, reason } => {
            let text = if name == "rtol" {
                &call.rtol
            } else {
                &call.atol
            };
            anyhow!(
                "invalid value `{}` for `--{name}`: {reason}",
                text.as_deref().unwrap_or_default()
            )
        }
        other => other.into(),
    })
}

/// Runs `simulate` for one parsed invocation.
///
/// # Errors
/// Any bad input, a run the library refuses or fails, or a file that cannot be written. No
/// output file exists afterwards in any of these cases, nor after a stopping signal
/// ([`Stop`]) that arrives before the file is complete.
pub fn run(call: &SystemCall, stop: &Stop) -> Result<()> {
    let entry = catalog::find(&call.name).map_err(|e| anyhow!("{e} (see `physicskit list`)"))?;
    let method = call
        .method
        .as_deref()
        .map(|m| params::method(entry, m))
        .transpose()?;
    let values = params::values(entry, &call.params)?;
    let dt = number("dt", &call.dt)?;
    let t0 = number("t0", &call.t0)?;
    let t1 = number("t1", &call.t1)?;
    let stride: usize = call
        .stride
        .trim()
        .parse()
        .ok()
        .filter(|&k| k >= 1)
        .ok_or_else(|| {
            anyhow!(
                "invalid value `{}` for `--stride`: expected an integer >= 1",
                call.stride
            )
        })?;
    let grid = TimeGrid::new((t0, t1), dt)?;
    // The built system has the last word on its default (a projectile with drag: rk4).
    let mut system = params::build(entry, &call.params, &values)?;
    let method = method.unwrap_or_else(|| system.default_method());
    let tolerances = tolerances(call, method)?;
    let pending = Pending::create(&call.out)?;

    let mut observer = RunObserver {
        bar: Progress::for_terminal(grid.n_steps()),
        stop,
    };
    let options = IntegrateOptions {
        sampling: if stride == 1 {
            Sampling::All
        } else {
            Sampling::Stride(stride)
        },
        observer: Some(&mut observer),
        observe_every: OBSERVE_EVERY,
        tolerances,
        ..IntegrateOptions::default()
    };
    let result = system.integrate((t0, t1), dt, method, options);
    if let Some(bar) = &observer.bar {
        bar.finish();
    }
    let result = result?;
    if stop.requested() {
        // Arrived after the last check of the run: nothing is written (the temporary file
        // goes with `pending`).
        anyhow::bail!("interrupted before writing `{}`", call.out.display());
    }
    pending.commit(&Record {
        system: entry.name,
        family: entry.family,
        t0,
        t1,
        dt,
        params: &values,
        result: &result,
    })
}

/// The progress bar (when stderr is a terminal) and the stopping signals, checked every
/// [`OBSERVE_EVERY`] steps.
struct RunObserver<'a> {
    bar: Option<Progress>,
    stop: &'a Stop,
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
