//! `physicskit ensemble`: a grid of members of one catalogue system on all cores, into an
//! `.npz` shaped by the grid.
//!
//! Parsing only: the members are built, checked (a bad member is named by its index in the
//! flattened grid, before any integration) and integrated by the library's ensemble engine
//! (`physicskit::classical::ensemble`).

use std::ops::ControlFlow;

use anyhow::{anyhow, bail, Context, Result};
use physicskit::classical::catalog;
use physicskit::classical::core::SystemEntry;
use physicskit::classical::ensemble::{
    self, Condition, Direction, Event, Members, Plan, Reduction, Sweep,
};
use physicskit::classical::Observer;

use crate::cli::EnsembleArgs;
use crate::output::arrays::{write_npz, Entry};
use crate::output::Pending;
use crate::params;
use crate::signals::Stop;

fn number(what: &str, text: &str) -> Result<f64> {
    text.trim()
        .parse()
        .map_err(|_| anyhow!("invalid value `{text}` for {what}: expected a number"))
}

/// `NAME=A:B:N` as the axis name and its `N` values from `A` to `B`.
fn axis(text: &str) -> Result<(String, Vec<f64>)> {
    let bad = || anyhow!("invalid `--grid {text}`: expected NAME=A:B:N (e.g. theta0[0]=-3:3:100)");
    let (name, range) = text.split_once('=').ok_or_else(bad)?;
    let parts: Vec<&str> = range.split(':').collect();
    let [a, b, n] = parts[..] else {
        return Err(bad());
    };
    let (a, b) = (number("--grid", a)?, number("--grid", b)?);
    let n: usize = n.trim().parse().ok().filter(|&n| n >= 1).ok_or_else(bad)?;
    // Both ends included, as numpy.linspace; the ends exactly as given.
    let values = (0..n)
        .map(|i| match (i, n) {
            (0, _) => a,
            (i, n) if i == n - 1 => b,
            (i, n) => a + (b - a) * (i as f64 / (n - 1) as f64),
        })
        .collect();
    Ok((name.trim().to_string(), values))
}

/// `NAME=KIND:INDEX:VALUE` as an event's name and reduction.
fn event(text: &str) -> Result<(String, Reduction)> {
    let bad = || {
        anyhow!(
            "invalid `--event {text}`: expected NAME=KIND:INDEX:VALUE with KIND one of crosses, \
             rising, falling, abs_above (e.g. flip=abs_above:1:3.141592653589793)"
        )
    };
    let (name, spec) = text.split_once('=').ok_or_else(bad)?;
    let parts: Vec<&str> = spec.split(':').collect();
    let [kind, index, value] = parts[..] else {
        return Err(bad());
    };
    let index: usize = index.trim().parse().map_err(|_| bad())?;
    let value = number("--event", value)?;
    let crosses = |direction| Condition::Crosses { value, direction };
    let condition = match kind.trim() {
        "crosses" => crosses(Direction::Either),
        "rising" => crosses(Direction::Rising),
        "falling" => crosses(Direction::Falling),
        "abs_above" => Condition::AbsExceeds(value),
        _ => return Err(bad()),
    };
    Ok((
        name.trim().to_string(),
        Reduction::FirstEvent(Event { index, condition }),
    ))
}

/// The common values, parsed by each parameter's kind.
fn common(
    entry: &SystemEntry,
    set: &[String],
) -> Result<Vec<(String, physicskit::classical::core::Value)>> {
    set.iter()
        .map(|text| {
            let (name, value) = text
                .split_once('=')
                .ok_or_else(|| anyhow!("invalid `--set {text}`: expected NAME=VALUE"))?;
            let spec = entry.lookup(name.trim())?;
            Ok((spec.name.to_string(), params::parse(spec, value)?))
        })
        .collect()
}

/// Runs `ensemble`.
///
/// # Errors
/// Bad input (before any integration), a member the library refuses (named by index), a
/// stopping signal, or a file that cannot be written (no file is left behind).
pub fn run(args: &EnsembleArgs, stop: &Stop) -> Result<()> {
    let entry = catalog::find(&args.system).map_err(|e| anyhow!("{e} (see `physicskit list`)"))?;
    let method = args
        .method
        .as_deref()
        .map(|m| params::method(entry, m))
        .transpose()?;
    if args.grid.is_empty() {
        bail!("give at least one --grid NAME=A:B:N");
    }
    let axes: Vec<(String, Vec<f64>)> = args.grid.iter().map(|g| axis(g)).collect::<Result<_>>()?;
    let shape: Vec<usize> = axes.iter().map(|(_, v)| v.len()).collect();
    let n = shape
        .iter()
        .try_fold(1usize, |acc, &k| acc.checked_mul(k))
        .ok_or_else(|| anyhow!("the grid has too many members"))?;
    // The Cartesian product, last axis fastest (C order, numpy's `indexing="ij"`).
    let sweeps = axes
        .iter()
        .enumerate()
        .map(|(k, (name, values))| {
            let inner: usize = shape[k + 1..].iter().product();
            let column = (0..n).map(|i| values[(i / inner) % values.len()]).collect();
            Sweep::new(name.clone(), column)
        })
        .collect();
    let mut reductions = Vec::new();
    if args.energy_error {
        reductions.push(Reduction::MaxEnergyError);
    }
    let events: Vec<(String, Reduction)> = args
        .events
        .iter()
        .map(|e| event(e))
        .collect::<Result<_>>()?;
    reductions.extend(events.iter().map(|(_, r)| *r));
    let renormalize_every = args.renormalize_every;
    if args.max_lyapunov {
        reductions.push(Reduction::MaxLyapunov { renormalize_every });
    }
    if args.sali {
        reductions.push(Reduction::Sali { renormalize_every });
    }
    let members = Members {
        common: common(entry, &args.set)?,
        sweeps,
        states: None,
        n,
    };
    let plan = Plan {
        t_span: (number("--t0", &args.t0)?, number("--t1", &args.t1)?),
        dt: number("--dt", &args.dt)?,
        method,
        stride: args.stride,
        reductions,
        final_state: true,
        threads: args.threads,
    };
    let pending = Pending::create(&args.out)?;
    if !pending.is_npz() {
        bail!("`ensemble` writes .npz only, got `{}`", args.out.display());
    }
    let mut observer = StopObserver(stop);
    let out = ensemble::run(entry, &members, &plan, Some(&mut observer)).context("ensemble run")?;
    if stop.requested() {
        bail!("interrupted before writing `{}`", args.out.display());
    }
    let dim = out.final_state.ncols();
    let with = |extra: &[usize]| -> Vec<usize> { shape.iter().chain(extra).copied().collect() };
    let final_state = out.final_state.as_standard_layout().into_owned();
    let mut entries = vec![
        Entry::Str {
            name: "system".into(),
            text: entry.name,
        },
        Entry::Str {
            name: "method".into(),
            text: out.method.name(),
        },
        Entry::F64 {
            name: "final_state".into(),
            shape: with(&[dim]),
            data: final_state.as_slice().unwrap_or(&[]),
        },
    ];
    let settings = [plan.t_span.0, plan.t_span.1, plan.dt];
    for (k, name) in ["t0", "t1", "dt"].into_iter().enumerate() {
        entries.push(Entry::F64 {
            name: name.into(),
            shape: vec![],
            data: &settings[k..=k],
        });
    }
    for (k, (_, values)) in axes.iter().enumerate() {
        entries.push(Entry::F64 {
            name: format!("grid_{k}"),
            shape: vec![values.len()],
            data: values,
        });
    }
    let names: Vec<&str> = axes.iter().map(|(name, _)| name.as_str()).collect();
    let grid_names = names.join(",");
    entries.push(Entry::Str {
        name: "grid_names".into(),
        text: &grid_names,
    });
    if let (Some(t), Some(trajectory)) = (&out.t, &out.trajectory) {
        entries.push(Entry::F64 {
            name: "t".into(),
            shape: vec![t.len()],
            data: t.as_slice().unwrap_or(&[]),
        });
        entries.push(Entry::F64 {
            name: "trajectory".into(),
            shape: with(&[t.len(), dim]),
            data: trajectory.as_slice().unwrap_or(&[]),
        });
    }
    let mut reductions = out.reductions.iter();
    if args.energy_error {
        if let Some((_, values)) = reductions.next() {
            entries.push(Entry::F64 {
                name: "max_energy_error".into(),
                shape: shape.clone(),
                data: values.as_slice().unwrap_or(&[]),
            });
        }
    }
    for ((name, _), (_, values)) in events.iter().zip(reductions.by_ref()) {
        entries.push(Entry::F64 {
            name: format!("event_{name}"),
            shape: shape.clone(),
            data: values.as_slice().unwrap_or(&[]),
        });
    }
    // The chaos reductions, named as the library names them.
    for (name, values) in reductions {
        entries.push(Entry::F64 {
            name: (*name).into(),
            shape: shape.clone(),
            data: values.as_slice().unwrap_or(&[]),
        });
    }
    pending.commit_with(|_, file| write_npz(file, &entries))
}

/// Stops the run on a signal.
struct StopObserver<'a>(&'a Stop);

impl Observer for StopObserver<'_> {
    fn observe(&mut self, _: usize, _: usize, _: f64) -> ControlFlow<()> {
        if self.0.requested() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
