//! What `physicskit ensemble` runs, as one [`Scenario`]: filled from the flags, or read from a
//! scenario file (`--scenario FILE`, JSON or TOML by its extension) with the flags over it.
//! Everything after this point ([`crate::ensemble`]) sees only the `Scenario`, so a file and
//! the flags that say the same thing run the same ensemble, bit for bit.
//!
//! A file has the flags' keys, with `_` for `-` (`renormalize_every`), structured rather than
//! as flag text:
//!
//! ```json
//! {
//!   "system": "double-pendulum",
//!   "set": {"thetadot0": [0, 0]},
//!   "grid": [{"name": "theta0[0]", "from": -3, "to": 3, "n": 100},
//!            {"name": "theta0[1]", "from": -3, "to": 3, "n": 100}],
//!   "events": [{"name": "flip", "kind": "abs_above", "index": 1, "value": 3.141592653589793}],
//!   "final_state": false,
//!   "dt": 0.01, "t1": 10, "out": "flips.npz"
//! }
//! ```
//!
//! plus what is unwieldy as flags: `states` (one initial state per member). Unknown keys are
//! errors naming the key. Paths are relative to the working directory, as on the command line.
//!
//! Flags given with a file ([`Scenario::overridden_by`]): a setting (SYSTEM, `--method`,
//! `--dt`, `--t0`, `--t1`, `--stride`, `--renormalize-every`, `--threads`, `--rtol`, `--atol`,
//! `--max-steps`, `--out`) replaces
//! the file's; `--set NAME=VALUE` replaces that parameter's value only; a switch
//! (`--energy-error`, `--max-lyapunov`, `--sali`, `--no-final-state`) adds to the file's.
//! The members (`--grid`, `--values`; `grid`, `values`, `states`) and the events are given in
//! one place: flags for them beside a file that has them are an error naming both.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use physicskit::classical::ensemble::{Condition, Direction, Event, Reduction};
use serde::Deserialize;

use crate::cli::EnsembleArgs;
use crate::prepare::{count, number};

/// One ensemble run: the system, its members, the time grid and what to keep of each member.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// The catalogue system.
    pub system: Option<String>,
    /// Values shared by every member, by parameter name.
    #[serde(default)]
    pub set: BTreeMap<String, Literal>,
    /// Grid axes; the members are their product (last axis fastest).
    #[serde(default)]
    pub grid: Vec<Axis>,
    /// Listed members: one value per member for each named parameter (or `name[i]`); with
    /// `states`, the same number of members. The list is the first axis, before the grid's.
    #[serde(default)]
    pub values: BTreeMap<String, Vec<f64>>,
    /// Listed members' initial states (`[q, p]`, or `[q, qdot]` for Lagrangian systems).
    pub states: Option<Vec<Vec<f64>>>,
    /// Integrator (default: the system's).
    pub method: Option<String>,
    /// Start time (default 0).
    pub t0: Option<f64>,
    /// End time.
    pub t1: Option<f64>,
    /// Step.
    pub dt: Option<f64>,
    /// Keep each member's trajectory every `stride` steps.
    pub stride: Option<usize>,
    /// Keep each member's maximum relative energy error.
    #[serde(default)]
    pub energy_error: bool,
    /// First-event times to keep.
    #[serde(default)]
    pub events: Vec<EventSpec>,
    /// Keep each member's largest Lyapunov exponent.
    #[serde(default)]
    pub max_lyapunov: bool,
    /// Keep each member's SALI.
    #[serde(default)]
    pub sali: bool,
    /// Steps between renormalizations of the chaos reductions' deviation vectors.
    pub renormalize_every: Option<usize>,
    /// Keep each member's final state (default true).
    pub final_state: Option<bool>,
    /// Worker threads.
    pub threads: Option<usize>,
    /// Relative tolerance of an adaptive method.
    pub rtol: Option<f64>,
    /// Absolute tolerance of an adaptive method.
    pub atol: Option<f64>,
    /// Most steps an adaptive method may attempt per member.
    pub max_steps: Option<u64>,
    /// Output file (.npz).
    pub out: Option<PathBuf>,
}

/// A grid axis: `n` values from `from` to `to`, both included (`numpy.linspace`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// A real or integer parameter, or `name[i]` for one entry of a vector parameter.
    pub name: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of values, >= 1.
    pub n: usize,
}

/// A first-event time to keep, as `event_<name>`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventSpec {
    /// Output name.
    pub name: String,
    /// What happens.
    pub kind: EventKind,
    /// Entry of the state.
    pub index: usize,
    /// The level.
    pub value: f64,
}

/// What happens to the state's entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// Crosses the value either way.
    Crosses,
    /// Crosses it upwards.
    Rising,
    /// Crosses it downwards.
    Falling,
    /// Its magnitude exceeds the value.
    AbsAbove,
}

/// A parameter's value as a file writes it (a number, a list of numbers, a word) or as a flag
/// types it (text); read by the parameter's kind, as `simulate --NAME TEXT` is.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum Literal {
    /// A number.
    Number(f64),
    /// Numbers.
    List(Vec<f64>),
    /// Text: a word, or a flag's text.
    Text(String),
}

impl Literal {
    /// The text `simulate --NAME` would take for it; numbers as the shortest text that reads
    /// back to the same bits.
    pub fn text(&self) -> String {
        match self {
            Literal::Number(x) => x.to_string(),
            Literal::List(xs) => xs.iter().map(f64::to_string).collect::<Vec<_>>().join(","),
            Literal::Text(text) => text.clone(),
        }
    }
}

impl Axis {
    /// `NAME=A:B:N`.
    ///
    /// # Errors
    /// Any other text.
    fn parse(text: &str) -> Result<Self> {
        let bad =
            || anyhow!("invalid `--grid {text}`: expected NAME=A:B:N (e.g. theta0[0]=-3:3:100)");
        let (name, range) = text.split_once('=').ok_or_else(bad)?;
        let parts: Vec<&str> = range.split(':').collect();
        let [from, to, n] = parts[..] else {
            return Err(bad());
        };
        Ok(Self {
            name: name.trim().to_string(),
            from: number("grid", from)?,
            to: number("grid", to)?,
            n: n.trim()
                .parse::<usize>()
                .ok()
                .filter(|&n| n >= 1)
                .ok_or_else(bad)?,
        })
    }

    /// The `n` values, the ends exactly as given.
    pub fn values(&self) -> Vec<f64> {
        let (a, b, n) = (self.from, self.to, self.n);
        (0..n)
            .map(|i| match i {
                0 => a,
                i if i == n - 1 => b,
                i => a + (b - a) * (i as f64 / (n - 1) as f64),
            })
            .collect()
    }
}

impl EventSpec {
    /// `NAME=KIND:INDEX:VALUE`.
    ///
    /// # Errors
    /// Any other text.
    fn parse(text: &str) -> Result<Self> {
        let bad = || {
            anyhow!(
                "invalid `--event {text}`: expected NAME=KIND:INDEX:VALUE with KIND one of \
                 crosses, rising, falling, abs_above (e.g. flip=abs_above:1:3.141592653589793)"
            )
        };
        let (name, spec) = text.split_once('=').ok_or_else(bad)?;
        let parts: Vec<&str> = spec.split(':').collect();
        let [kind, index, value] = parts[..] else {
            return Err(bad());
        };
        let kind = match kind.trim() {
            "crosses" => EventKind::Crosses,
            "rising" => EventKind::Rising,
            "falling" => EventKind::Falling,
            "abs_above" => EventKind::AbsAbove,
            _ => return Err(bad()),
        };
        Ok(Self {
            name: name.trim().to_string(),
            kind,
            index: index.trim().parse::<usize>().map_err(|_| bad())?,
            value: number("event", value)?,
        })
    }

    /// The library's reduction.
    pub fn reduction(&self) -> Reduction {
        let value = self.value;
        let crosses = |direction| Condition::Crosses { value, direction };
        let condition = match self.kind {
            EventKind::Crosses => crosses(Direction::Either),
            EventKind::Rising => crosses(Direction::Rising),
            EventKind::Falling => crosses(Direction::Falling),
            EventKind::AbsAbove => Condition::AbsExceeds(value),
        };
        Reduction::FirstEvent(Event {
            index: self.index,
            condition,
        })
    }
}

/// `NAME=TEXT` of `--flag`, split.
fn pair<'t>(flag: &str, text: &'t str, what: &str) -> Result<(String, &'t str)> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| anyhow!("invalid `--{flag} {text}`: expected NAME={what}"))?;
    Ok((name.trim().to_string(), value))
}

impl Scenario {
    /// The run `args` describe: its flags, over its `--scenario` file if any.
    ///
    /// # Errors
    /// A flag's text that does not parse (naming the flag), a file that cannot be read or
    /// parsed (naming an unknown key), or flags that conflict with the file.
    pub fn from_args(args: &EnsembleArgs) -> Result<Self> {
        let flags = Self::from_flags(args)?;
        match &args.scenario {
            Some(path) => Self::load(path)?.overridden_by(flags, path),
            None => Ok(flags),
        }
    }

    /// The flags alone.
    fn from_flags(args: &EnsembleArgs) -> Result<Self> {
        let mut set = BTreeMap::new();
        for text in &args.set {
            let (name, value) = pair("set", text, "VALUE")?;
            if set
                .insert(name.clone(), Literal::Text(value.into()))
                .is_some()
            {
                bail!("`--set {name}=...` given twice");
            }
        }
        let mut values = BTreeMap::new();
        for text in &args.values {
            let (name, list) = pair("values", text, "V1,V2,..")?;
            let list: Vec<f64> = list
                .split(',')
                .map(|v| number("values", v))
                .collect::<Result<_>>()?;
            if values.insert(name.clone(), list).is_some() {
                bail!("`--values {name}=...` given twice");
            }
        }
        let time = |flag, text: &Option<String>| text.as_deref().map(|t| number(flag, t));
        Ok(Self {
            system: args.system.clone(),
            set,
            grid: args
                .grid
                .iter()
                .map(|g| Axis::parse(g))
                .collect::<Result<_>>()?,
            values,
            states: None,
            method: args.method.clone(),
            t0: time("t0", &args.t0).transpose()?,
            t1: time("t1", &args.t1).transpose()?,
            dt: time("dt", &args.dt).transpose()?,
            stride: args.stride,
            energy_error: args.energy_error,
            events: args
                .events
                .iter()
                .map(|e| EventSpec::parse(e))
                .collect::<Result<_>>()?,
            max_lyapunov: args.max_lyapunov,
            sali: args.sali,
            renormalize_every: args
                .renormalize_every
                .as_deref()
                .map(|t| count("renormalize-every", t, 1))
                .transpose()?,
            final_state: args.no_final_state.then_some(false),
            threads: args.threads,
            rtol: args
                .rtol
                .as_deref()
                .map(|t| number("rtol", t))
                .transpose()?,
            atol: args
                .atol
                .as_deref()
                .map(|t| number("atol", t))
                .transpose()?,
            max_steps: args
                .max_steps
                .as_deref()
                .map(|t| count("max-steps", t, 1).map(|n| n as u64))
                .transpose()?,
            out: args.out.clone(),
        })
    }

    /// Reads a scenario file: JSON (`.json`) or TOML (`.toml`).
    ///
    /// # Errors
    /// An unreadable file, another extension, or text that is not a scenario (an unknown
    /// key is named).
    pub fn load(path: &Path) -> Result<Self> {
        let context = || format!("scenario `{}`", path.display());
        let text = std::fs::read_to_string(path).with_context(context)?;
        let ext = path.extension().and_then(|e| e.to_str());
        match ext.map(str::to_ascii_lowercase).as_deref() {
            Some("json") => serde_json::from_str::<Self>(&text).map_err(anyhow::Error::from),
            Some("toml") => toml::from_str::<Self>(&text).map_err(anyhow::Error::from),
            _ => Err(anyhow!("expected a .json or .toml file")),
        }
        .with_context(context)
    }

    /// `self` (a file's) with `flags` over it, as the module docs say.
    ///
    /// # Errors
    /// Flags for the members or events beside a file that has them.
    pub fn overridden_by(self, flags: Scenario, file: &Path) -> Result<Self> {
        let file_has_members = !self.grid.is_empty() || !self.values.is_empty();
        let file_has_members = file_has_members || self.states.is_some();
        let conflict = |flag: &str, keys: &str| {
            anyhow!(
                "`--{flag}` conflicts with {keys} in `{}`: give them in one place",
                file.display()
            )
        };
        let members = "the members (`grid`, `values`, `states`)";
        if !flags.grid.is_empty() && file_has_members {
            return Err(conflict("grid", members));
        }
        if !flags.values.is_empty() && file_has_members {
            return Err(conflict("values", members));
        }
        if !flags.events.is_empty() && !self.events.is_empty() {
            return Err(conflict("event", "`events`"));
        }
        let mut set = self.set;
        set.extend(flags.set);
        let (grid, values, states) = if file_has_members {
            (self.grid, self.values, self.states)
        } else {
            (flags.grid, flags.values, flags.states)
        };
        Ok(Self {
            system: flags.system.or(self.system),
            set,
            grid,
            values,
            states,
            method: flags.method.or(self.method),
            t0: flags.t0.or(self.t0),
            t1: flags.t1.or(self.t1),
            dt: flags.dt.or(self.dt),
            stride: flags.stride.or(self.stride),
            energy_error: flags.energy_error || self.energy_error,
            events: [self.events, flags.events].concat(),
            max_lyapunov: flags.max_lyapunov || self.max_lyapunov,
            sali: flags.sali || self.sali,
            renormalize_every: flags.renormalize_every.or(self.renormalize_every),
            final_state: flags.final_state.or(self.final_state),
            threads: flags.threads.or(self.threads),
            rtol: flags.rtol.or(self.rtol),
            atol: flags.atol.or(self.atol),
            max_steps: flags.max_steps.or(self.max_steps),
            out: flags.out.or(self.out),
        })
    }
}

/// A required setting, or an error naming the flag and the key.
pub fn required<T: Clone>(value: &Option<T>, flag: &str, key: &str) -> Result<T> {
    value
        .clone()
        .ok_or_else(|| anyhow!("give `--{flag}` (or `{key}` in a --scenario file)"))
}
