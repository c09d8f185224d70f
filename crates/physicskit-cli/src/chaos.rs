//! `physicskit lyapunov` and `physicskit poincare`: the library's Lyapunov spectrum and
//! Poincaré section of one orbit of a catalogue system, written as named arrays.
//!
//! Checks, build and output are `simulate`'s ([`prepare`](crate::prepare)); the analyses are
//! the library's own loops on the system's `Flow` (`analysis::lyapunov::lyapunov_on_flow`,
//! `analysis::section::section_on_flow`), so a file holds the same bits as the Rust API's
//! `lyapunov_spectrum` / `poincare_section` for the same run. The progress bar and the
//! stopping signals are checked every [`OBSERVE_EVERY`] steps, as for `simulate`.

use anyhow::{anyhow, Result};
use physicskit::classical::analysis::lyapunov::{check_vectors, lyapunov_on_flow};
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::section::{section_on_flow, SurfaceOfSection};
use physicskit::classical::analysis::watch::AnalysisOptions;
use physicskit::classical::model::Value;

use crate::cli::{Lyapunov, Poincare, SystemCall};
use crate::output::{Arrays, Named};
use crate::prepare::{count, number, Call, Run, RunObserver};
use crate::progress::OBSERVE_EVERY;
use crate::signals::Stop;

/// Runs `lyapunov` for one parsed invocation.
///
/// Output arrays: `exponents` (k, descending), `t` (renormalization times kept) and `history`
/// (running estimates at those times, in the deviation vectors' order); settings `t0`, `t1`,
/// `dt`, `n_exponents`, `renormalize_every`, `history_stride`.
///
/// # Errors
/// As `simulate`: no output file exists after any error or a stopping signal.
pub fn lyapunov(call: &SystemCall<Lyapunov>, stop: &Stop) -> Result<()> {
    let checked = Call::check(call)?;
    let flag = |name| checked.option(name).unwrap_or("1");
    let every = count("renormalize-every", flag("renormalize-every"), 1)?;
    let stride = count("history-stride", flag("history-stride"), 1)?;
    // The temporary output goes with `run` if the number of exponents is refused.
    let run = checked.start()?;
    let state0 = run.system.dynamical().state().to_vec();
    let k = n_exponents(
        checked.option("n-exponents"),
        state0.len(),
        checked.entry.name,
        every,
    )?;
    let mut observer = RunObserver::new(run.grid.n_steps(), stop);
    let outcome = run
        .system
        .flow(run.method, k)
        .and_then(|mut flow| {
            let options =
                AnalysisOptions::observed(&mut observer, OBSERVE_EVERY).with_history_stride(stride);
            lyapunov_on_flow(flow.as_mut(), &state0, &run.grid, k, every, options)
        })
        .map_err(|e| with_flag(e, "n_exponents", "--n-exponents"));
    let (spectrum, _) = observer.finish(outcome, &call.out)?;
    let settings = vec![
        ("n_exponents", integer(k)),
        ("renormalize_every", integer(every)),
        ("history_stride", integer(stride)),
    ];
    let arrays = vec![
        Named::vector("exponents", spectrum.exponents),
        Named::vector("t", spectrum.t),
        Named::matrix("history", k, spectrum.history),
    ];
    write(&checked, run, settings, arrays)
}

/// Largest state dimension whose full spectrum `lyapunov` computes without `--n-exponents`.
pub const FULL_SPECTRUM_MAX_DIM: usize = 20;

/// The number of exponents: `--n-exponents` (`text`), a whole number from 1 to the state
/// dimension `dim` of `system`, or without it the full spectrum up to
/// [`FULL_SPECTRUM_MAX_DIM`]. A larger system's full spectrum is refused rather than started:
/// `dim` deviation vectors cost about `dim + 1` times the orbit's work per step, and each
/// renormalization (every `every` steps) a Gram–Schmidt of about `2 dim^3` operations.
///
/// # Errors
/// A text that is not such a number (`1e23`, `2.5`, `0`, more than `dim`), naming the flag and
/// the range; no `--n-exponents` for a system larger than [`FULL_SPECTRUM_MAX_DIM`].
fn n_exponents(text: Option<&str>, dim: usize, system: &str, every: usize) -> Result<usize> {
    match text {
        // The range is the library's (`check_vectors`), checked before the flow is built
        // for `k` vectors.
        Some(text) => count("n-exponents", text, 0)
            .ok()
            .filter(|&k| check_vectors(k, dim, every, "n_exponents").is_ok())
            .ok_or_else(|| {
                anyhow!(
                    "invalid value `{text}` for `--n-exponents`: expected a whole number from 1 \
                     to {dim}, the state dimension of `{system}`"
                )
            }),
        None if dim > FULL_SPECTRUM_MAX_DIM => {
            let gram_schmidt = 2.0 * (dim as f64).powi(3);
            Err(anyhow!(
                "`{system}`: pass --n-exponents K (1 to {dim}; 1 gives the largest exponent): \
                 the full spectrum of this {dim}-dimensional system costs {dim} deviation \
                 vectors, about {} times the orbit's work per step, plus a Gram–Schmidt of \
                 about {gram_schmidt:.1e} operations every {every} steps (without the flag the \
                 full spectrum is computed only up to dimension {FULL_SPECTRUM_MAX_DIM})",
                dim + 1
            ))
        }
        None => Ok(dim),
    }
}

/// Runs `poincare` for one parsed invocation.
///
/// Output arrays: `t` (crossing times) and `y` (crossing states, one row each, in the
/// system's state layout); settings `t0`, `t1`, `dt`, `coordinate`, `value`, `direction`.
///
/// # Errors
/// As `simulate`: no output file exists after any error or a stopping signal.
pub fn poincare(call: &SystemCall<Poincare>, stop: &Stop) -> Result<()> {
    let checked = Call::check(call)?;
    let coordinate = checked
        .option("coordinate")
        .ok_or_else(|| anyhow!("`--coordinate` is required"))?;
    let coordinate = count("coordinate", coordinate, 0)?;
    let value = number("value", checked.option("value").unwrap_or("0"))?;
    let direction_text = checked.option("direction").unwrap_or("1");
    let direction = match direction_text.trim() {
        "1" | "+1" => Direction::Increasing,
        "-1" => Direction::Decreasing,
        "0" => Direction::Both,
        _ => {
            return Err(anyhow!(
                "invalid value `{direction_text}` for `--direction`: expected 1 (increasing), \
                 -1 (decreasing) or 0 (both)"
            ))
        }
    };
    let surface = SurfaceOfSection::coordinate(coordinate, value, direction)
        .map_err(|e| with_flag(e, "value", "--value"))?;
    // The temporary output goes with `run` if the index is refused.
    let run = checked.start()?;
    let state0 = run.system.dynamical().state().to_vec();
    let dim = state0.len();
    if coordinate >= dim {
        return Err(anyhow!(
            "invalid value `{coordinate}` for `--coordinate`: the state of `{}` has {dim} \
             components (0 to {})",
            checked.entry.name,
            dim - 1
        ));
    }
    let mut observer = RunObserver::new(run.grid.n_steps(), stop);
    let outcome = run.system.flow(run.method, 0).and_then(|mut flow| {
        let options = AnalysisOptions::observed(&mut observer, OBSERVE_EVERY);
        section_on_flow(
            flow.as_mut(),
            &state0,
            &run.grid,
            &surface,
            usize::MAX,
            options,
        )
    });
    let (cut, _) = observer.finish(outcome, &call.out)?;
    let settings = vec![
        ("coordinate", integer(coordinate)),
        ("value", Value::Scalar(value)),
        ("direction", Value::Integer(direction_sign(direction))),
    ];
    let arrays = vec![
        Named::vector("t", cut.t),
        Named::matrix("y", dim, cut.states),
    ];
    write(&checked, run, settings, arrays)
}

fn direction_sign(direction: Direction) -> i64 {
    match direction {
        Direction::Increasing => 1,
        Direction::Decreasing => -1,
        Direction::Both => 0,
    }
}

/// Counts and indices are far below 2^63.
fn integer(n: usize) -> Value {
    Value::Integer(i64::try_from(n).unwrap_or(i64::MAX))
}

/// The library names its argument `name`; the command line calls it `flag`.
fn with_flag(
    err: physicskit::classical::Error,
    name: &str,
    flag: &str,
) -> physicskit::classical::Error {
    match err {
        physicskit::classical::Error::InvalidParameter {
            name: n,
            value,
            reason,
        } if n == name => physicskit::classical::Error::InvalidParameter {
            name: flag.to_string(),
            value,
            reason,
        },
        other => other,
    }
}

fn write<K>(
    checked: &Call<'_, K>,
    run: Run,
    own: Vec<(&'static str, Value)>,
    arrays: Vec<Named>,
) -> Result<()> {
    let mut settings = vec![
        ("t0", Value::Scalar(checked.t0)),
        ("t1", Value::Scalar(checked.t1)),
        ("dt", Value::Scalar(checked.dt)),
    ];
    settings.extend(own);
    run.pending.commit_arrays(&Arrays {
        system: checked.entry.name,
        family: checked.entry.family,
        method: run.method.name(),
        settings,
        params: &checked.values,
        arrays,
    })
}
