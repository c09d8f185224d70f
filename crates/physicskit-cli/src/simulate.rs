//! `physicskit simulate`: parse, build, integrate, write.
//!
//! The system is built through the catalogue (`catalog::find(name)`, its entry's checked
//! values, its builder) into a `Box<dyn DynSystem>`, which integrates with the library's
//! generic loop. Everything that can be checked before the integration is checked first
//! ([`prepare`](crate::prepare): system, method, parameters, the constructor's checks, the
//! time grid, the output path), so a bad invocation fails at once and a long run is never
//! wasted on a typo.

use anyhow::Result;
use physicskit::classical::{IntegrateOptions, Sampling};

use anyhow::anyhow;
use physicskit::classical::{Error, Method, Tolerances};

use crate::cli::{Simulate, SystemCall};
use crate::output::Record;
use crate::prepare::{count, number, Call, RunObserver};
use crate::progress::OBSERVE_EVERY;
use crate::signals::Stop;

/// The tolerances of `--rtol`, `--atol` and `--max-steps`, checked for `method` (an error naming
/// the flag for a value that is not a number > 0 (an integer >= 1 for `--max-steps`), or for a
/// fixed-step method).
fn tolerances(checked: &Call<'_, Simulate>, method: Method) -> Result<Option<Tolerances>> {
    let text = |library_name: &str| checked.option(&library_name.replace('_', "-"));
    let rtol = text("rtol").map(|t| number("rtol", t)).transpose()?;
    let atol = text("atol").map(|t| number("atol", t)).transpose()?;
    let max_steps = text("max_steps")
        .map(|t| count("max-steps", t, 1).map(|n| n as u64))
        .transpose()?;
    Tolerances::for_method(rtol, atol, max_steps, method).map_err(|e| match e {
        Error::InvalidParameter { name, reason, .. } | Error::InvalidArgument { name, reason } => {
            anyhow!(
                "invalid value `{}` for `--{}`: {reason}",
                text(&name).unwrap_or_default(),
                name.replace('_', "-")
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
pub fn run(call: &SystemCall<Simulate>, stop: &Stop) -> Result<()> {
    let checked = Call::check(call)?;
    let stride = count("stride", checked.option("stride").unwrap_or("1"), 1)?;
    let mut run = checked.start()?;
    let tolerances = tolerances(&checked, run.method)?;

    let mut observer = RunObserver::new(run.grid.n_steps(), stop);
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
    let (t0, t1, dt) = (checked.t0, checked.t1, checked.dt);
    let result = run.system.integrate((t0, t1), dt, run.method, options);
    let result = observer.finish(result, &call.out)?;
    run.pending.commit(&Record {
        system: checked.entry.name,
        family: checked.entry.family,
        t0,
        t1,
        dt,
        params: &checked.values,
        result: &result,
    })
}
