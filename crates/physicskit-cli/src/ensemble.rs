//! `physicskit ensemble`: the members of one catalogue system (a grid, a list, or a list by a
//! grid) on all cores, into an `.npz` shaped by the members' axes.
//!
//! The flags and the scenario file are read into one [`Scenario`] ([`crate::scenario`]); from
//! it the members are laid out, and then built, checked (a bad member is named by its index in
//! the flattened members, before any integration) and integrated by the library's ensemble
//! engine (`physicskit::classical::ensemble`). With only event times kept and no final state,
//! the engine stops each member at its last event (`steps` says how far each went).

use std::ops::ControlFlow;

use anyhow::{anyhow, bail, Context, Result};
use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::catalog;
use physicskit::classical::core::check_items_fit;
use physicskit::classical::ensemble::{self, FromCatalogue, Members, Plan, Reduction, Sweep};
use physicskit::classical::model::{SystemEntry, Value};
use physicskit::classical::{Error, Method, Observer, Tolerances};

use crate::cli::EnsembleArgs;
use crate::output::arrays::{write_npz, Entry};
use crate::output::Pending;
use crate::params;
use crate::scenario::{required, Scenario};
use crate::signals::Stop;

/// The common values, parsed by each parameter's kind.
fn common(entry: &SystemEntry, scenario: &Scenario) -> Result<Vec<(String, Value)>> {
    scenario
        .set
        .iter()
        .map(|(name, literal)| {
            let spec = entry.lookup(name)?;
            Ok((spec.name.to_string(), params::parse(spec, &literal.text())?))
        })
        .collect()
}

/// The members' axes: the listed members first (if any), then the grid's; and the members
/// they give, last axis fastest (C order, numpy's `indexing="ij"`).
struct Layout {
    /// Length of each axis.
    shape: Vec<usize>,
    /// The members.
    members: Members,
}

impl Layout {
    fn new(scenario: &Scenario, common: Vec<(String, Value)>) -> Result<Self> {
        let mut lists = scenario
            .values
            .iter()
            .map(|(name, v)| (name.as_str(), v.len()))
            .chain(scenario.states.as_ref().map(|rows| ("states", rows.len())));
        let first = lists.next();
        if let Some((name, m)) = first {
            if let Some((other, k)) = lists.find(|&(_, k)| k != m) {
                bail!("the listed members disagree in number: `{name}` has {m}, `{other}` {k}");
            }
        }
        let listed = first.map(|(_, m)| m);
        let mut shape: Vec<usize> = listed.into_iter().collect();
        shape.extend(scenario.grid.iter().map(|axis| axis.n));
        if shape.is_empty() {
            bail!(
                "give the members: at least one --grid NAME=A:B:N or --values NAME=V1,V2,.. \
                 (or `grid`, `values` or `states` in a --scenario file)"
            );
        }
        if let Some(axis) = scenario.grid.iter().find(|a| a.n == 0) {
            bail!("grid axis `{}`: `n` must be >= 1", axis.name);
        }
        let n = shape
            .iter()
            .try_fold(1usize, |acc, &k| acc.checked_mul(k))
            .filter(|&n| n > 0)
            .ok_or_else(|| {
                anyhow!("the members' axes give {shape:?} members: none, or too many")
            })?;
        // The members' swept values and states are spelled out per member below: refuse a
        // grid too large for memory before allocating (the engine then checks its outputs).
        let per_member = scenario.values.len()
            + scenario.grid.len()
            + scenario
                .states
                .as_ref()
                .and_then(|r| r.first())
                .map_or(0, Vec::len);
        check_items_fit("members", n, 8 * per_member.max(1))?;
        // Member i's index along axis k.
        let along = |k: usize, i: usize| (i / shape[k + 1..].iter().product::<usize>()) % shape[k];
        let offset = usize::from(listed.is_some());
        let mut sweeps: Vec<Sweep> = scenario
            .values
            .iter()
            .map(|(name, v)| Sweep::new(name.clone(), (0..n).map(|i| v[along(0, i)]).collect()))
            .collect();
        sweeps.extend(scenario.grid.iter().enumerate().map(|(k, axis)| {
            let values = axis.values();
            Sweep::new(
                axis.name.clone(),
                (0..n).map(|i| values[along(k + offset, i)]).collect(),
            )
        }));
        let states = match &scenario.states {
            Some(rows) => {
                let dim = rows.first().map_or(0, Vec::len);
                if let Some(j) = rows.iter().position(|r| r.len() != dim) {
                    bail!(
                        "`states` rows differ in length: row 0 has {dim}, row {j} has {}",
                        rows[j].len()
                    );
                }
                Some((0..n).flat_map(|i| rows[along(0, i)].clone()).collect())
            }
            None => None,
        };
        Ok(Self {
            members: Members {
                common,
                sweeps,
                states,
                n,
            },
            shape,
        })
    }
}

/// The reductions the scenario asks for, in output order: energy error, events, chaos.
fn reductions(scenario: &Scenario) -> Result<Vec<Reduction>> {
    let chaos = scenario.max_lyapunov || scenario.sali;
    let renormalize_every = match scenario.renormalize_every {
        Some(_) if !chaos => bail!(
            "`--renormalize-every` applies only with --max-lyapunov or --sali \
             (`renormalize_every` only with `max_lyapunov` or `sali`)"
        ),
        Some(0) => bail!("invalid value `0` for `renormalize_every`: expected an integer >= 1"),
        Some(m) => m,
        None => DEFAULT_RENORMALIZE_EVERY,
    };
    let mut out = Vec::new();
    if scenario.energy_error {
        out.push(Reduction::MaxEnergyError);
    }
    out.extend(scenario.events.iter().map(|e| e.reduction()));
    if scenario.max_lyapunov {
        out.push(Reduction::MaxLyapunov { renormalize_every });
    }
    if scenario.sali {
        out.push(Reduction::Sali { renormalize_every });
    }
    Ok(out)
}

/// The tolerances of `--rtol`, `--atol` and `--max-steps` (`rtol`, `atol`, `max_steps`),
/// checked for `method` as `simulate` checks its own: an error naming the flag and the key
/// for a value that is not > 0, or for a fixed-step method.
fn tolerances(scenario: &Scenario, method: Method) -> Result<Option<Tolerances>> {
    let (rtol, atol, max_steps) = (scenario.rtol, scenario.atol, scenario.max_steps);
    Tolerances::for_method(rtol, atol, max_steps, method).map_err(|e| match e {
        Error::InvalidParameter { name, reason, .. } | Error::InvalidArgument { name, reason } => {
            let value = match name.as_str() {
                "rtol" => rtol.map(|x| x.to_string()),
                "atol" => atol.map(|x| x.to_string()),
                _ => max_steps.map(|n| n.to_string()),
            };
            anyhow!(
                "invalid value `{}` for `--{}` (`{name}`): {reason}",
                value.unwrap_or_default(),
                name.replace('_', "-")
            )
        }
        other => other.into(),
    })
}

/// Runs `ensemble`.
///
/// # Errors
/// Bad input (before any integration), a member the library refuses (named by index), a
/// stopping signal, or a file that cannot be written (no file is left behind).
pub fn run(args: &EnsembleArgs, stop: &Stop) -> Result<()> {
    let scenario = Scenario::from_args(args)?;
    let system = scenario
        .system
        .as_deref()
        .ok_or_else(|| anyhow!("give SYSTEM (or `system` in a --scenario file)"))?;
    let entry = catalog::find(system).map_err(|e| anyhow!("{e} (see `physicskit list`)"))?;
    let method = scenario
        .method
        .as_deref()
        .map(|m| params::method(entry, m))
        .transpose()?;
    let layout = Layout::new(&scenario, common(entry, &scenario)?)?;
    let reductions = reductions(&scenario)?;
    let final_state = scenario.final_state.unwrap_or(true);
    if !final_state && scenario.stride.is_none() && reductions.is_empty() {
        bail!("`--no-final-state` (`final_state: false`) leaves nothing to write: keep a reduction or --stride");
    }
    let mut plan = Plan {
        t_span: (
            scenario.t0.unwrap_or(0.0),
            required(&scenario.t1, "t1", "t1")?,
        ),
        dt: required(&scenario.dt, "dt", "dt")?,
        method,
        stride: scenario.stride,
        reductions,
        final_state,
        threads: scenario.threads,
        tolerances: None,
    };
    let source = FromCatalogue::new(entry, &layout.members)?;
    let given = [scenario.rtol, scenario.atol].iter().any(Option::is_some);
    if given || scenario.max_steps.is_some() {
        plan.tolerances = tolerances(&scenario, ensemble::method(&source, &plan)?)?;
    }
    let out_path = required(&scenario.out, "out", "out")?;
    let pending = Pending::create(&out_path)?;
    if !pending.is_npz() {
        bail!("`ensemble` writes .npz only, got `{}`", out_path.display());
    }
    let mut observer = StopObserver(stop);
    let out = ensemble::run_source(&source, &plan, Some(&mut observer)).context("ensemble run")?;
    if stop.requested() {
        bail!("interrupted before writing `{}`", out_path.display());
    }
    let shape = &layout.shape;
    let with = |extra: &[usize]| -> Vec<usize> { shape.iter().chain(extra).copied().collect() };
    let f64s = |name: String, shape: Vec<usize>, data| Entry::F64 { name, shape, data };
    let mut entries = vec![
        Entry::Str {
            name: "system".into(),
            text: entry.name,
        },
        Entry::Str {
            name: "method".into(),
            text: out.method.name(),
        },
    ];
    if plan.final_state {
        entries.push(Entry::View {
            name: "final_state".into(),
            view: out
                .final_state
                .view()
                .into_shape_with_order(with(&[out.final_state.ncols()]))
                .context("final state")?,
        });
    }
    entries.push(Entry::I64 {
        name: "steps".into(),
        shape: shape.clone(),
        data: out
            .steps
            .iter()
            .map(|&s| i64::try_from(s).unwrap_or(i64::MAX))
            .collect(),
    });
    let settings = [plan.t_span.0, plan.t_span.1, plan.dt];
    for (k, name) in ["t0", "t1", "dt"].into_iter().enumerate() {
        entries.push(f64s(name.into(), vec![], &settings[k..=k]));
    }
    let grids: Vec<Vec<f64>> = scenario.grid.iter().map(|a| a.values()).collect();
    for (k, values) in grids.iter().enumerate() {
        entries.push(f64s(format!("grid_{k}"), vec![values.len()], &values[..]));
    }
    let names: Vec<&str> = scenario.grid.iter().map(|a| a.name.as_str()).collect();
    let grid_names = names.join(",");
    if !names.is_empty() {
        entries.push(Entry::Str {
            name: "grid_names".into(),
            text: &grid_names,
        });
    }
    for (name, values) in &scenario.values {
        entries.push(f64s(
            format!("values_{name}"),
            vec![values.len()],
            &values[..],
        ));
    }
    let states: Vec<f64> = scenario
        .states
        .iter()
        .flatten()
        .flatten()
        .copied()
        .collect();
    if let Some(rows) = &scenario.states {
        let dim = states.len() / rows.len().max(1);
        entries.push(f64s("states".into(), vec![rows.len(), dim], &states[..]));
    }
    if let (Some(t), Some(trajectory)) = (&out.t, &out.trajectory) {
        entries.push(Entry::View {
            name: "t".into(),
            view: t.view().into_dyn(),
        });
        let (_, samples, dim) = trajectory.dim();
        entries.push(Entry::View {
            name: "trajectory".into(),
            view: trajectory
                .view()
                .into_shape_with_order(with(&[samples, dim]))
                .context("trajectory")?,
        });
    }
    // Each reduction named as the library names it, events as `event_<name>`.
    let mut event_names = scenario.events.iter().map(|e| format!("event_{}", e.name));
    for (name, values) in &out.reductions {
        let name = match *name {
            "event_time" => event_names.next().unwrap_or_default(),
            other => other.to_string(),
        };
        entries.push(Entry::View {
            name,
            view: values
                .view()
                .into_shape_with_order(shape.clone())
                .context("reduction")?,
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
