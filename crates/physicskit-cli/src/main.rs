//! `physicskit`: list the systems, export a trajectory, an ensemble, a Lyapunov spectrum or a
//! Poincaré section, render the gallery.
//!
//! Exit status: 0 on success; 2 on any error, printed as one line `error: ...` on stderr
//! (bad input, a run the library refuses, an unwritable output); `128 + signal` after a run
//! stopped by Ctrl-C (130), SIGTERM (143) or SIGHUP (129), with no file left behind
//! ([`signals`]). No physics lives here: systems, their parameters and defaults come from the
//! library's catalogue (`physicskit::classical::catalog`).

mod chaos;
mod cli;
mod ensemble;
mod gallery;
mod list;
mod output;
mod params;
mod prepare;
mod progress;
mod scenario;
mod signals;
mod simulate;

use std::process::ExitCode;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::Parser;

use crate::cli::{Action, Cli};

/// Exit status for every error.
const EXIT_ERROR: u8 = 2;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => return clap_failure(&err),
    };
    let stop = signals::Stop::install();
    let outcome = match &cli.command {
        Action::List(args) => match list::print(&mut std::io::stdout().lock(), args.json) {
            // `physicskit list | head` closes the pipe early; that is not an error.
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
            other => other.map_err(anyhow::Error::from),
        },
        Action::Simulate(args) => simulate::run(&args.system, &stop),
        Action::Lyapunov(args) => chaos::lyapunov(&args.system, &stop),
        Action::Poincare(args) => chaos::poincare(&args.system, &stop),
        Action::Gallery(args) => gallery::render(&args.out, args.quick),
        Action::Ensemble(args) => ensemble::run(args, &stop),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => match stop.exit_status() {
            Some(status) => {
                let message = one_line(&format!("{err:#}"));
                eprintln!("error: {message} (by {})", stop.name());
                ExitCode::from(status)
            }
            None => {
                eprintln!("error: {}", one_line(&format!("{err:#}")));
                ExitCode::from(EXIT_ERROR)
            }
        },
    }
}

/// Help and version are printed as clap prints them; errors are cut to one line.
fn clap_failure(err: &clap::Error) -> ExitCode {
    match err.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = err.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = err.print();
            ExitCode::from(EXIT_ERROR)
        }
        ErrorKind::UnknownArgument => {
            if let Some(message) = unknown_parameter(err) {
                eprintln!("error: {message}");
                return ExitCode::from(EXIT_ERROR);
            }
            short_clap_error(err)
        }
        _ => short_clap_error(err),
    }
}

/// For `simulate SYSTEM --typo` (or `lyapunov`, `poincare`), names the system's parameters
/// instead of clap's message.
fn unknown_parameter(err: &clap::Error) -> Option<String> {
    let ContextValue::String(arg) = err.get(ContextKind::InvalidArg)? else {
        return None;
    };
    let args: Vec<String> = std::env::args().collect();
    let (at, flags) = args
        .iter()
        .enumerate()
        .find_map(|(i, a)| cli::kind_flags(a).map(|f| (i, f)))?;
    let spec = physicskit::classical::catalog::find(args.get(at + 1)?).ok()?;
    let names: Vec<&str> = spec.params.iter().map(|p| p.name).collect();
    let own: String = flags.iter().map(|f| format!(", --{}", f.name)).collect();
    Some(format!(
        "unknown parameter `{arg}` for `{}`; its parameters are: {} (and --method, --dt, --t0, \
         --t1{own}, --out)",
        spec.name,
        names.join(", ")
    ))
}

fn short_clap_error(err: &clap::Error) -> ExitCode {
    // clap's first paragraph is the message (with the missing arguments or the possible
    // values); tips and usage follow after a blank line.
    let rendered = err.render().to_string();
    let paragraph = rendered
        .trim_start()
        .split("\n\n")
        .next()
        .unwrap_or("invalid arguments");
    let message = one_line(paragraph);
    let message = message.strip_prefix("error: ").unwrap_or(&message);
    eprintln!("error: {message} (see --help)");
    ExitCode::from(EXIT_ERROR)
}

fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}
