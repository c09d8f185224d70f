//! The command-line grammar (clap derive), with one subcommand per catalogue entry under each
//! of `simulate`, `lyapunov` and `poincare`, generated from the entry, so that
//! `physicskit simulate SYSTEM --help` lists that system's parameters with their units, ranges
//! and defaults. The three share the system, method and time flags; each adds its own
//! ([`RunKind::FLAGS`]).

use std::marker::PhantomData;
use std::path::PathBuf;

use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches, Parser, Subcommand};

use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::analysis::sali::CHAOS_THRESHOLD;
use physicskit::classical::catalog::{self, SYSTEMS};
use physicskit::classical::ensemble::MAX_THREADS;
use physicskit::classical::model::SystemEntry;
use physicskit::classical::{Method, Tolerances};

use crate::params;

/// Classical-mechanics demonstrations: export trajectories and render the gallery.
#[derive(Debug, Parser)]
#[command(name = "physicskit", version, about, propagate_version = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Action,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Action {
    /// List every system with its parameters, defaults and valid methods, and the methods.
    List(ListArgs),
    /// Integrate one system and write t, q, p (or y), energy and the parameters used.
    ///
    /// The output format follows the extension of --out: .npz (numpy.load), .csv or .json.
    /// Run `physicskit simulate SYSTEM --help` for a system's parameters.
    #[command(
        override_usage = "physicskit simulate SYSTEM [--PARAM VALUE ...] [--method M] [--rtol R --atol A --max-steps N] --dt DT --t1 T1 [--t0 T0] --out FILE"
    )]
    Simulate(Box<SimulateArgs>),
    /// Lyapunov spectrum of one orbit (Benettin et al. 1980, QR every K steps): the exponents
    /// and their running estimates against time.
    ///
    /// The output format follows the extension of --out: .npz (numpy.load), .csv or .json.
    /// Run `physicskit lyapunov SYSTEM --help` for a system's parameters.
    #[command(
        override_usage = "physicskit lyapunov SYSTEM [--PARAM VALUE ...] [--method M] [--n-exponents K] [--renormalize-every M] [--history-stride S] --dt DT --t1 T1 [--t0 T0] --out FILE"
    )]
    Lyapunov(Box<LyapunovArgs>),
    /// Poincaré section of one orbit: the crossings of the state's component COORDINATE through
    /// VALUE, each located inside its step to the method's order.
    ///
    /// The output format follows the extension of --out: .npz (numpy.load), .csv or .json.
    /// Run `physicskit poincare SYSTEM --help` for a system's parameters.
    #[command(
        override_usage = "physicskit poincare SYSTEM [--PARAM VALUE ...] [--method M] --coordinate I [--value X] [--direction D] --dt DT --t1 T1 [--t0 T0] --out FILE"
    )]
    Poincare(Box<PoincareArgs>),
    /// Render every demonstration (figures, animations, index.html) into a directory.
    Gallery(GalleryArgs),
    /// Integrate an ensemble (a grid and/or a list of members) of one system on all cores;
    /// write an .npz.
    ///
    /// Outputs are shaped by the members' axes (the --values list first, then each --grid):
    /// `final_state` (axes + state length; none with --no-final-state), `steps` (steps each
    /// member took), `trajectory` with --stride, `max_energy_error` with --energy-error,
    /// `event_<name>` per --event, `max_lyapunov`, `sali`, `grid_<k>` the values of each grid
    /// axis, `values_<name>` and `states` the listed members.
    ///
    /// --scenario FILE reads all of this from a JSON or TOML file with the flags' names as
    /// keys (`_` for `-`; see the README); flags given beside it replace its settings, `--set`
    /// its value of that parameter, and switches add to it; --grid, --values and --event beside
    /// a file that has members or events are an error.
    #[command(
        override_usage = "physicskit ensemble SYSTEM --grid NAME=A:B:N [--grid ...] [--set NAME=VALUE ...] --dt DT --t1 T1 --out FILE.npz\n       physicskit ensemble --scenario FILE [FLAGS]"
    )]
    Ensemble(Box<EnsembleArgs>),
}

/// Arguments of `ensemble`.
#[derive(Debug, Args)]
pub struct EnsembleArgs {
    /// The catalogue system (see `physicskit list`); or `system` in the --scenario file.
    pub system: Option<String>,
    /// A JSON (.json) or TOML (.toml) file describing the run; the flags given override it.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// A grid axis: N values from A to B (both included) of a real or integer parameter, or
    /// of one entry `name[i]` of a vector parameter. Repeat for more axes (the product).
    #[arg(long = "grid", value_name = "NAME=A:B:N", allow_hyphen_values = true)]
    pub grid: Vec<String>,
    /// Listed members: member j takes the j-th value. Repeat for more parameters (same
    /// count, zipped); the list is one axis, before the grid's.
    #[arg(
        long = "values",
        value_name = "NAME=V1,V2,..",
        allow_hyphen_values = true
    )]
    pub values: Vec<String>,
    /// A value shared by every member, as `simulate --NAME VALUE` takes it.
    #[arg(long = "set", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub set: Vec<String>,
    /// Integrator (default: the system's).
    #[arg(long, value_name = "M")]
    pub method: Option<String>,
    /// Time step, > 0.
    #[arg(long, value_name = "DT", allow_negative_numbers = true)]
    pub dt: Option<String>,
    /// Start time [default: 0].
    #[arg(long, value_name = "T0", allow_negative_numbers = true)]
    pub t0: Option<String>,
    /// End time.
    #[arg(long, value_name = "T1", allow_negative_numbers = true)]
    pub t1: Option<String>,
    /// Keep each member's trajectory every K steps.
    #[arg(long, value_name = "K")]
    pub stride: Option<usize>,
    /// Keep each member's maximum relative energy error.
    #[arg(long)]
    pub energy_error: bool,
    /// The first time of an event per member: KIND is crosses, rising, falling or abs_above,
    /// INDEX an entry of the state ([q, p]; [q, qdot] for Lagrangian systems).
    #[arg(
        long = "event",
        value_name = "NAME=KIND:INDEX:VALUE",
        allow_hyphen_values = true
    )]
    pub events: Vec<String>,
    /// Keep no final state. With only --event outputs (and a fixed-step method) each member
    /// then stops at its last event instead of running to T1: the same event times, for the
    /// cost of reaching them (`steps` shows how far each member went).
    #[arg(long)]
    pub no_final_state: bool,
    /// Keep each member's largest Lyapunov exponent at T1 (`max_lyapunov`).
    #[arg(long)]
    pub max_lyapunov: bool,
    /// Keep each member's SALI at T1 (`sali`; above the chaos threshold: regular over the span).
    #[arg(long, help = format!(
        "Keep each member's SALI at T1 (`sali`; above {CHAOS_THRESHOLD:e}: regular over the span)"
    ))]
    pub sali: bool,
    /// Steps between renormalizations of the deviation vectors of --max-lyapunov and --sali,
    /// >= 1 (default [`DEFAULT_RENORMALIZE_EVERY`]); an error without either.
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help = format!(
            "Steps between renormalizations of the deviation vectors of --max-lyapunov and \
             --sali, >= 1 [default: {DEFAULT_RENORMALIZE_EVERY}]"
        )
    )]
    pub renormalize_every: Option<String>,
    /// Relative tolerance of an adaptive method for every member, > 0, as `simulate --rtol`.
    #[arg(long, value_name = "RTOL", allow_negative_numbers = true, help = format!(
        "Relative tolerance of an adaptive method ({}) for every member, > 0 [default: {:e}]",
        adaptive_methods(),
        Tolerances::default().rtol
    ))]
    pub rtol: Option<String>,
    /// Absolute tolerance of an adaptive method for every member, > 0, as `simulate --atol`.
    #[arg(long, value_name = "ATOL", allow_negative_numbers = true, help = format!(
        "Absolute tolerance of an adaptive method ({}) for every member, > 0 [default: {:e}]",
        adaptive_methods(),
        Tolerances::default().atol
    ))]
    pub atol: Option<String>,
    /// Most steps an adaptive method may attempt per member, >= 1, as `simulate --max-steps`.
    #[arg(long, value_name = "N", allow_negative_numbers = true, help = format!(
        "Most steps (accepted and rejected) an adaptive method ({}) may attempt per member \
         before it stops with an error, >= 1 [default: {}]",
        adaptive_methods(),
        Tolerances::default().max_steps
    ))]
    pub max_steps: Option<String>,
    /// Worker threads, 1 to [`MAX_THREADS`] (default: one per core); the results do
    /// not depend on it.
    #[arg(long, value_name = "N", help = format!(
        "Worker threads, 1 to {MAX_THREADS} [default: one per core]; the results do not \
         depend on it"
    ))]
    pub threads: Option<usize>,
    /// Output file (.npz).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// Arguments of `simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// The system and its arguments.
    #[command(subcommand)]
    pub system: SystemCall<Simulate>,
}

/// Arguments of `lyapunov`.
#[derive(Debug, Args)]
pub struct LyapunovArgs {
    /// The system and its arguments.
    #[command(subcommand)]
    pub system: SystemCall<Lyapunov>,
}

/// Arguments of `poincare`.
#[derive(Debug, Args)]
pub struct PoincareArgs {
    /// The system and its arguments.
    #[command(subcommand)]
    pub system: SystemCall<Poincare>,
}

/// A flag of one kind of run, beyond the shared ones.
#[derive(Debug, Clone, Copy)]
pub struct Flag {
    /// Long name, also the clap id.
    pub name: &'static str,
    /// Placeholder in the help.
    pub value_name: &'static str,
    /// Default text, if any.
    pub default: Option<Text>,
    /// Whether it must be given.
    pub required: bool,
    /// Help line.
    pub help: Text,
}

/// A flag's help or default: written out, or formatted from a library constant when the
/// command is built, so that the help cannot drift from the value the code uses.
#[derive(Debug, Clone, Copy)]
pub enum Text {
    /// Fixed text.
    Fixed(&'static str),
    /// Text made from constants.
    Made(fn() -> String),
}

impl Text {
    fn text(self) -> String {
        match self {
            Text::Fixed(text) => text.to_string(),
            Text::Made(make) => make(),
        }
    }
}

impl Flag {
    const fn optional(
        name: &'static str,
        value_name: &'static str,
        default: Option<&'static str>,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            value_name,
            default: match default {
                Some(text) => Some(Text::Fixed(text)),
                None => None,
            },
            required: false,
            help: Text::Fixed(help),
        }
    }
}

/// The adaptive methods' names, from the method registry: what the tolerance flags apply to.
pub fn adaptive_methods() -> String {
    Method::ALL
        .iter()
        .filter(|m| m.is_adaptive())
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A kind of run on one system: its subcommand name and its own flags.
pub trait RunKind: std::fmt::Debug + Clone + Send + Sync + 'static {
    /// The subcommand, e.g. `simulate`.
    const ACTION: &'static str;
    /// Its flags beyond `--method`, `--dt`, `--t0`, `--t1` and `--out`.
    const FLAGS: &'static [Flag];
}

/// `simulate`.
#[derive(Debug, Clone)]
pub struct Simulate;

impl RunKind for Simulate {
    const ACTION: &'static str = "simulate";
    const FLAGS: &'static [Flag] = &[
        Flag::optional(
            "stride",
            "K",
            Some("1"),
            "store every K-th step (and the last)",
        ),
        Flag {
            name: "rtol",
            value_name: "RTOL",
            default: None,
            required: false,
            help: Text::Made(|| {
                format!(
                    "relative tolerance of an adaptive method ({}), > 0; default {:e}",
                    adaptive_methods(),
                    Tolerances::default().rtol
                )
            }),
        },
        Flag {
            name: "atol",
            value_name: "ATOL",
            default: None,
            required: false,
            help: Text::Made(|| {
                format!(
                    "absolute tolerance of an adaptive method ({}), > 0; default {:e}",
                    adaptive_methods(),
                    Tolerances::default().atol
                )
            }),
        },
        Flag {
            name: "max-steps",
            value_name: "N",
            default: None,
            required: false,
            help: Text::Made(|| {
                format!(
                    "most steps (accepted and rejected) an adaptive method ({}) may attempt before \
                     it stops with an error, >= 1; default {}",
                    adaptive_methods(),
                    Tolerances::default().max_steps
                )
            }),
        },
    ];
}

/// `lyapunov`.
#[derive(Debug, Clone)]
pub struct Lyapunov;

impl RunKind for Lyapunov {
    const ACTION: &'static str = "lyapunov";
    const FLAGS: &'static [Flag] = &[
        Flag {
            name: "n-exponents",
            value_name: "K",
            default: None,
            required: false,
            help: Text::Made(|| {
                format!(
                    "number of exponents, 1 to the state dimension [default: all; required above \
                     dimension {}]",
                    crate::chaos::FULL_SPECTRUM_MAX_DIM
                )
            }),
        },
        Flag {
            name: "renormalize-every",
            value_name: "M",
            default: Some(Text::Made(|| DEFAULT_RENORMALIZE_EVERY.to_string())),
            required: false,
            help: Text::Fixed("steps between QR re-orthonormalizations of the deviation vectors"),
        },
        Flag::optional(
            "history-stride",
            "S",
            Some("1"),
            "keep the running estimates of every S-th renormalization (and the last)",
        ),
    ];
}

/// `poincare`.
#[derive(Debug, Clone)]
pub struct Poincare;

impl RunKind for Poincare {
    const ACTION: &'static str = "poincare";
    const FLAGS: &'static [Flag] = &[
        Flag {
            name: "coordinate",
            value_name: "I",
            default: None,
            required: true,
            help: Text::Fixed(
                "index into the state of the section's coordinate: q_0.., then p_0.. (or y)",
            ),
        },
        Flag::optional("value", "X", Some("0"), "the section is state[I] = X"),
        Flag::optional(
            "direction",
            "D",
            Some("1"),
            "crossings counted: 1 increasing, -1 decreasing, 0 both",
        ),
    ];
}

/// The flags of the run kind `action` beyond the shared ones, for messages.
pub fn kind_flags(action: &str) -> Option<&'static [Flag]> {
    [Simulate::ACTION, Lyapunov::ACTION, Poincare::ACTION]
        .into_iter()
        .zip([Simulate::FLAGS, Lyapunov::FLAGS, Poincare::FLAGS])
        .find(|(a, _)| *a == action)
        .map(|(_, flags)| flags)
}

/// Arguments of `list`.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Print the whole catalogue as one JSON object, for tools and the browser lab.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `gallery`.
#[derive(Debug, Args)]
pub struct GalleryArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "gallery")]
    pub out: PathBuf,
    /// Fewer orbits, shorter runs and fewer frames: the whole gallery in under a minute.
    #[arg(long)]
    pub quick: bool,
}

/// `simulate SYSTEM ...` (or `lyapunov`, `poincare`) as parsed: the system's name and its raw
/// argument texts. Values are parsed against the catalogue afterwards, so every mistake gets
/// the same one-line message.
#[derive(Debug, Clone)]
pub struct SystemCall<K> {
    /// System name as typed.
    pub name: String,
    /// `--PARAM VALUE` pairs for the system's own parameters, in command-line order.
    pub params: Vec<(String, String)>,
    /// `--method`.
    pub method: Option<String>,
    /// `--dt`.
    pub dt: String,
    /// `--t0`.
    pub t0: String,
    /// `--t1`.
    pub t1: String,
    /// `--out`.
    pub out: PathBuf,
    /// The kind's own flags ([`RunKind::FLAGS`]) as typed or defaulted, in their order.
    pub options: Vec<(&'static str, Option<String>)>,
    kind: PhantomData<K>,
}

impl<K> SystemCall<K> {
    /// The text of the kind's flag `name` (given or its default).
    pub fn option(&self, name: &str) -> Option<&str> {
        self.options
            .iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, v)| v.as_deref())
    }
}

fn system_command(entry: &SystemEntry, flags: &[Flag]) -> Command {
    let mut cmd = Command::new(entry.name)
        .about(entry.summary)
        .arg(
            Arg::new("method")
                .long("method")
                .value_name("M")
                .help(format!(
                    "integrator: {} (default {})",
                    params::method_names(entry),
                    entry.default_method
                )),
        )
        .arg(
            Arg::new("dt")
                .long("dt")
                .value_name("DT")
                .required(true)
                .allow_negative_numbers(true)
                .help("time step, > 0; (t1 - t0)/dt must be a whole number"),
        )
        .arg(
            Arg::new("t1")
                .long("t1")
                .value_name("T1")
                .required(true)
                .allow_negative_numbers(true)
                .help("end time, >= t0"),
        )
        .arg(
            Arg::new("t0")
                .long("t0")
                .value_name("T0")
                .default_value("0")
                .allow_negative_numbers(true)
                .help("start time"),
        )
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("FILE")
                .required(true)
                .value_parser(clap::value_parser!(PathBuf))
                .help("output file: .npz, .csv or .json"),
        );
    for f in flags {
        let mut arg = Arg::new(f.name)
            .long(f.name)
            .value_name(f.value_name)
            .required(f.required)
            .allow_negative_numbers(true)
            .help(f.help.text());
        if let Some(default) = f.default {
            arg = arg.default_value(default.text());
        }
        cmd = cmd.arg(arg);
    }
    for p in entry.params {
        cmd = cmd.arg(
            Arg::new(p.name)
                .long(p.name)
                .value_name(params::placeholder(p.kind))
                .allow_hyphen_values(true)
                .action(ArgAction::Set)
                .help_heading("Parameters")
                .help(params::help_line(p)),
        );
    }
    let after: Vec<&str> = entry
        .note
        .into_iter()
        .chain(params::has_demo_default(entry).then_some(params::DEMO_LEGEND))
        .collect();
    if !after.is_empty() {
        cmd = cmd.after_help(after.join("\n\n"));
    }
    cmd
}

fn text(m: &ArgMatches, id: &str) -> Option<String> {
    m.get_one::<String>(id).cloned()
}

impl<K: RunKind> FromArgMatches for SystemCall<K> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let Some((name, m)) = matches.subcommand() else {
            return Err(clap::Error::new(clap::error::ErrorKind::MissingSubcommand));
        };
        let Ok(entry) = catalog::find(name) else {
            // An unknown name parses as an external subcommand; `simulate` reports it.
            return Ok(Self {
                name: name.to_string(),
                params: Vec::new(),
                method: None,
                dt: String::new(),
                t0: String::new(),
                t1: String::new(),
                out: PathBuf::new(),
                options: Vec::new(),
                kind: PhantomData,
            });
        };
        let mut params: Vec<(usize, String, String)> = Vec::new();
        for p in entry.params {
            if let (Some(v), Some(idx)) = (text(m, p.name), m.index_of(p.name)) {
                params.push((idx, p.name.to_string(), v));
            }
        }
        params.sort_by_key(|(idx, _, _)| *idx);
        let required = |id: &str| {
            text(m, id)
                .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::MissingRequiredArgument))
        };
        Ok(Self {
            name: name.to_string(),
            params: params.into_iter().map(|(_, n, v)| (n, v)).collect(),
            method: text(m, "method"),
            dt: required("dt")?,
            t0: required("t0")?,
            t1: required("t1")?,
            out: m
                .get_one::<PathBuf>("out")
                .cloned()
                .ok_or_else(|| clap::Error::new(clap::error::ErrorKind::MissingRequiredArgument))?,
            options: K::FLAGS.iter().map(|f| (f.name, text(m, f.name))).collect(),
            kind: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl<K: RunKind> Subcommand for SystemCall<K> {
    fn augment_subcommands(mut cmd: Command) -> Command {
        for entry in SYSTEMS {
            cmd = cmd.subcommand(system_command(entry, K::FLAGS));
        }
        cmd.subcommand_required(true)
            .subcommand_value_name("SYSTEM")
            .subcommand_help_heading("Systems")
            .allow_external_subcommands(true)
    }

    fn augment_subcommands_for_update(cmd: Command) -> Command {
        Self::augment_subcommands(cmd)
    }

    fn has_subcommand(name: &str) -> bool {
        SYSTEMS.iter().any(|s| s.name == name)
    }
}
