//! Command-line text to catalogue values: `--name text` becomes a core [`Value`] of the kind
//! the parameter declares, and the catalogue checks it.
//!
//! Only the syntax is read here: a number (`--g 9.81`), an integer (`--n 32`; `1.5` is not
//! one), comma-separated numbers (`--q0 1,0`), a word (`--initial kink`). Whether a value is
//! allowed (finite, in range, of the right length, one of the words) is decided by
//! [`SystemEntry::values`], the one place where every front end's values are checked, and
//! then by the system's constructor. Their errors are only reworded here, so that each names
//! the flag and repeats the text as typed, on one line.
//!
//! The help texts of `list` and `simulate SYSTEM --help` are written here too, from the same
//! [`ParamSpec`]s: placeholder, unit, range and default.

use anyhow::{anyhow, bail, Result};
use physicskit::classical::core::Error;
use physicskit::classical::integrators::taylor::no_taylor_form;
use physicskit::classical::model::entry::{Default, Length, Literal, ParamKind, Range};
use physicskit::classical::model::{DynSystem, ParamSpec, SystemEntry, Value, Values};
use physicskit::classical::Method;

/// The placeholder shown after `--name` in help texts: `X`, `N`, `X1,X2`, `kink|antikink`.
pub fn placeholder(kind: ParamKind) -> String {
    match kind {
        ParamKind::Scalar => "X".into(),
        ParamKind::Integer => "N".into(),
        ParamKind::Vector(Length::Fixed(n)) if n <= 4 => (1..=n)
            .map(|i| format!("X{i}"))
            .collect::<Vec<_>>()
            .join(","),
        ParamKind::Vector(Length::Fixed(n)) => format!("X1,..,X{n}"),
        ParamKind::Vector(_) => "X1,X2,..".into(),
        ParamKind::Choice(words) => words.join("|"),
    }
}

/// A default as the text a user would type: `1.0`, `32`, `2.0,1.0`, `kink`.
pub fn literal_text(literal: Literal) -> String {
    match literal {
        // `{:?}` keeps the `.0` of whole numbers, so reals read as reals.
        Literal::Scalar(x) => format!("{x:?}"),
        Literal::Integer(n) => n.to_string(),
        Literal::Vector(v) => v
            .iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(","),
        Literal::Choice(w) => w.to_string(),
    }
}

/// Marks defaults that are not the spec's: the spec's Python constructor requires the value,
/// and the command line starts from this demonstration instead.
pub const DEMO_MARK: &str = "(demo)";

/// What [`DEMO_MARK`] means, for the foot of listings.
pub const DEMO_LEGEND: &str = "(demo): a demonstration value; the spec's Python constructor \
                               requires this argument";

/// Whether any parameter of `entry` has a default that is not the spec's.
pub fn has_demo_default(entry: &SystemEntry) -> bool {
    entry
        .params
        .iter()
        .any(|p| matches!(p.default, Default::Demo(_) | Default::DemoAbsent))
}

/// The default in brackets: `[default: 1.0]`, `[default: 2.0,1.0 (demo)]`,
/// `[default: none]` (left to the constructor, whose behaviour the help describes).
pub fn default_text(default: Default) -> String {
    match default {
        Default::Required => "[required]".into(),
        Default::Value(l) => format!("[default: {}]", literal_text(l)),
        Default::Absent => "[default: none]".into(),
        Default::Demo(l) => format!("[default: {} {DEMO_MARK}]", literal_text(l)),
        Default::DemoAbsent => format!("[default: none {DEMO_MARK}]"),
    }
}

/// One help line: description, unit in brackets, range, default, e.g.
/// `upper mass [kg], > 0 [default: 1.0]`.
pub fn help_line(spec: &ParamSpec) -> String {
    let mut line = spec.help.to_string();
    if !spec.unit.is_empty() {
        line.push_str(&format!(" [{}]", spec.unit));
    }
    let ranged = matches!(spec.kind, ParamKind::Scalar | ParamKind::Integer);
    if ranged && spec.range != Range::ANY {
        line.push_str(&format!(", {}", spec.range));
    }
    format!("{line} {}", default_text(spec.default))
}

/// Reads `text` as a value of `spec`'s kind, without judging it.
///
/// # Errors
/// Text that is not of the kind at all (`one` for a number, `1.5` for an integer), naming
/// the flag.
pub fn parse(spec: &ParamSpec, text: &str) -> Result<Value> {
    let value = match spec.kind {
        ParamKind::Scalar => number(text).map(Value::Scalar),
        ParamKind::Integer => integer(text).map(Value::Integer),
        ParamKind::Vector(_) => text
            .split(',')
            .map(number)
            .collect::<Result<Vec<_>, _>>()
            .map(Value::Vector)
            .map_err(|_| "expected comma-separated numbers".to_string()),
        ParamKind::Choice(_) => Ok(Value::Choice(text.trim().to_string())),
    };
    value.map_err(|reason| anyhow!("invalid value `{text}` for `--{}`: {reason}", spec.name))
}

fn number(text: &str) -> Result<f64, String> {
    text.trim()
        .parse()
        .map_err(|_| "expected a number".to_string())
}

fn integer(text: &str) -> Result<i64, String> {
    use std::num::IntErrorKind;
    text.trim().parse().map_err(|e: std::num::ParseIntError| {
        match e.kind() {
            IntErrorKind::PosOverflow | IntErrorKind::NegOverflow => "integer out of range",
            _ => "expected an integer",
        }
        .to_string()
    })
}

/// Parses `given` (parameter name and text, in command-line order) and has the catalogue
/// check them and fill in the defaults.
///
/// # Errors
/// Text that does not parse, or a value the catalogue refuses, naming the flag.
pub fn values(entry: &SystemEntry, given: &[(String, String)]) -> Result<Values> {
    let mut parsed = Vec::with_capacity(given.len());
    for (name, text) in given {
        let value = match entry.param(name) {
            Some(spec) => parse(spec, text)?,
            // Unknown names are clap's to refuse; should one get here, the catalogue refuses
            // it by name (whatever the value) and lists the parameters.
            None => Value::Choice(text.clone()),
        };
        parsed.push((name.clone(), value));
    }
    entry
        .values(parsed)
        .map_err(|e| flag_message(entry, given, &e).map_or_else(|| e.into(), |m| anyhow!(m)))
}

/// Builds the system from checked values.
///
/// # Errors
/// Whatever the constructor refuses, naming the flag where the error names a parameter.
pub fn build(
    entry: &SystemEntry,
    given: &[(String, String)],
    values: &Values,
) -> Result<Box<dyn DynSystem>> {
    (entry.build)(values).map_err(|e| match flag_message(entry, given, &e) {
        Some(message) => anyhow!(message),
        // Parameters that do not fit together: no one flag to name.
        None => anyhow::Error::from(e).context(format!("cannot build `{}`", entry.name)),
    })
}

/// A catalogue or constructor error about one parameter, reworded to name its flag, its
/// description and the text as typed (or that its default was used); `None` if the error
/// names no parameter of `entry`.
fn flag_message(entry: &SystemEntry, given: &[(String, String)], err: &Error) -> Option<String> {
    let (name, reason) = match err {
        Error::InvalidParameter { name, reason, .. } | Error::InvalidArgument { name, reason } => {
            (name, reason.clone())
        }
        Error::DimensionMismatch {
            name,
            expected,
            found,
        } => (name, format!("has {found} numbers, expected {expected}")),
        Error::TooLarge {
            name,
            bytes,
            available,
            ..
        } => (
            name,
            format!("the system would need {bytes} bytes, more than the {available} available"),
        ),
        _ => return None,
    };
    let help = entry.param(name)?.help;
    Some(match given.iter().rev().find(|(n, _)| n == name) {
        Some((_, text)) => format!("invalid value `{text}` for `--{name}` ({help}): {reason}"),
        None => format!("`--{name}` ({help}) left at its default: {reason}"),
    })
}

/// Comma-separated names of `entry`'s methods.
pub fn method_names(entry: &SystemEntry) -> String {
    entry
        .methods()
        .map(Method::name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Parses a method name and checks that the catalogue lists it for `entry`.
///
/// # Errors
/// Unknown method names (listing the entry's methods), or methods the entry does not list.
pub fn method(entry: &SystemEntry, name: &str) -> Result<Method> {
    let method: Method = name.parse().map_err(|_| {
        anyhow!(
            "unknown method `{name}` for `{}`; valid methods are: {}",
            entry.name,
            method_names(entry)
        )
    })?;
    if !entry.methods().any(|m| m == method) {
        if method.needs_taylor_form() {
            bail!(no_taylor_form(&format!("`{}`", entry.name)));
        }
        bail!(
            "method `{method}` cannot integrate `{}`; valid methods are: {}",
            entry.name,
            method_names(entry)
        );
    }
    Ok(method)
}

#[cfg(test)]
mod tests {
    use super::*;
    use physicskit::classical::catalog::{find, SYSTEMS};

    fn spec(kind: ParamKind) -> ParamSpec {
        ParamSpec {
            name: "x",
            kind,
            default: Default::Absent,
            unit: "",
            range: Range::ANY,
            help: "",
            initial_state: false,
        }
    }

    fn given(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect()
    }

    /// Every flag must stay the system's own: a parameter called `dt` would be shadowed.
    #[test]
    fn parameters_do_not_shadow_run_options() {
        use crate::cli::{Lyapunov, Poincare, RunKind, Simulate};
        let mut reserved = vec!["method", "dt", "t0", "t1", "out", "help"];
        for flags in [Simulate::FLAGS, Lyapunov::FLAGS, Poincare::FLAGS] {
            reserved.extend(flags.iter().map(|f| f.name));
        }
        for entry in SYSTEMS {
            for p in entry.params {
                assert!(!reserved.contains(&p.name), "{}: --{}", entry.name, p.name);
            }
        }
    }

    #[test]
    fn text_is_read_by_kind() {
        let read = |kind, text| parse(&spec(kind), text);
        assert_eq!(
            read(ParamKind::Scalar, " -1.5e-3").unwrap(),
            Value::Scalar(-1.5e-3)
        );
        assert_eq!(
            read(ParamKind::Integer, "4611686018427387904").unwrap(),
            Value::Integer(1 << 62)
        );
        assert_eq!(
            read(ParamKind::Vector(Length::Fixed(2)), "1, -2.5").unwrap(),
            Value::Vector(vec![1.0, -2.5])
        );
        // Lengths are the catalogue's to judge, not the parser's.
        assert_eq!(
            read(ParamKind::Vector(Length::Fixed(2)), "1").unwrap(),
            Value::Vector(vec![1.0])
        );
        assert_eq!(
            read(ParamKind::Choice(&["a"]), "b").unwrap(),
            Value::Choice("b".into())
        );
        let err = |kind, text| read(kind, text).unwrap_err().to_string();
        assert!(err(ParamKind::Scalar, "one").contains("`--x`: expected a number"));
        assert!(err(ParamKind::Integer, "1.5").contains("expected an integer"));
        assert!(err(ParamKind::Integer, "99999999999999999999").contains("out of range"));
        assert!(err(ParamKind::Vector(Length::Any), "1,,2").contains("comma-separated numbers"));
    }

    #[test]
    fn the_catalogue_judges_and_the_message_names_the_flag() {
        let entry = find("harmonic-oscillator").unwrap();
        let values = values(entry, &given(&[("k", "4"), ("q0", "-1.5e-3")])).unwrap();
        assert_eq!(values.scalar("k").unwrap().to_bits(), 4.0_f64.to_bits());
        let err = |pairs| values_err(entry, pairs);
        assert!(err(&[("k", "inf")]).contains("`--k`"));
        assert!(err(&[("k", "-1")]).starts_with("invalid value `-1` for `--k`"));
        let chain = find("coupled-oscillators").unwrap();
        // A default that no longer fits: the message says the default was used.
        let e = values_err(chain, &[("n", "4")]);
        assert!(
            e.contains("`--q0`") && e.contains("left at its default"),
            "{e}"
        );
        let e = values_err(chain, &[("n", "-4")]);
        assert!(e.contains("`--n`") && e.contains(">= 1"), "{e}");
    }

    fn values_err(entry: &SystemEntry, pairs: &[(&str, &str)]) -> String {
        values(entry, &given(pairs)).unwrap_err().to_string()
    }

    #[test]
    fn methods_are_the_catalogues() {
        let entry = find("double-pendulum").unwrap();
        assert_eq!(method(entry, "rk4").unwrap(), Method::Rk4);
        let e = method(entry, "verlet").unwrap_err().to_string();
        assert!(e.contains("implicit_midpoint"), "{e}");
        assert!(method(entry, "euler").is_err());
    }

    #[test]
    fn help_lines_show_unit_range_and_default() {
        let entry = find("double-pendulum").unwrap();
        let line = |name| help_line(entry.param(name).unwrap());
        assert_eq!(line("m1"), "upper mass [kg], > 0 [default: 1.0]");
        assert_eq!(
            line("theta0"),
            format!("initial angles [rad] [default: 2.0,1.0 {DEMO_MARK}]")
        );
        assert_eq!(
            line("g"),
            "gravitational acceleration [m/s^2] [default: 9.81]"
        );
    }
}
