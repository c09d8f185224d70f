//! The system registry: every system the command line can build, by name.
//!
//! A [`SystemSpec`] is plain data: the system's name, a one-line summary, its parameters
//! ([`ParamSpec`]: name, kind, default as the text a user would type, help), the methods it
//! accepts and its default method, and a constructor that turns parsed [`Values`] into a
//! runnable [`Simulation`]. `list`, `simulate` and the per-system `--help` are all generated
//! from this table, so adding a system is one entry in [`crate::systems`].
//!
//! Values are parsed here, before any physics runs, so a typo is reported as a one-line
//! error naming the parameter. Physical ranges (a negative mass, `|velocity| >= 1`) are the
//! library's job: its constructors return `physicskit::Error`, which the caller prints.

use std::collections::BTreeMap;
use std::fmt;

use anyhow::{anyhow, bail, Context, Result};
use physicskit::classical::Method;

use crate::simulation::Simulation;

/// What a parameter's value looks like on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A real number, e.g. `--g 9.81`.
    Real,
    /// A non-negative integer, e.g. `--n 32`.
    Count,
    /// A comma-separated list of reals, e.g. `--q0 1,0`; `Some(len)` fixes its length.
    List(Option<usize>),
    /// One word from a fixed set, e.g. `--initial kink-antikink`.
    Choice(&'static [&'static str]),
}

impl Kind {
    /// Placeholder shown in help texts.
    pub fn placeholder(self) -> String {
        match self {
            Kind::Real => "X".into(),
            Kind::Count => "N".into(),
            Kind::List(Some(n)) if n <= 4 => (1..=n)
                .map(|i| format!("X{i}"))
                .collect::<Vec<_>>()
                .join(","),
            Kind::List(Some(n)) => format!("X1,..,X{n}"),
            Kind::List(None) => "X1,X2,..".into(),
            Kind::Choice(words) => words.join("|"),
        }
    }
}

/// One parameter of a system.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    /// Name, used as `--name` (the spec's Python keyword).
    pub name: &'static str,
    /// Value kind.
    pub kind: Kind,
    /// Default, as command-line text; `None` means optional with no value (the spec's
    /// `None`), left to the library.
    pub default: Option<&'static str>,
    /// One-line description with units.
    pub help: &'static str,
}

/// The family of a system, which decides the output arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// State `[q, p]`; output `q`, `p`.
    Hamiltonian,
    /// State `[q, qdot]`; output `q`, and `p` holding `qdot` as the spec says.
    Lagrangian,
    /// A general ODE; output the raw state `y`.
    Ode,
}

impl Family {
    /// Lower-case name written into output files.
    pub fn name(self) -> &'static str {
        match self {
            Family::Hamiltonian => "hamiltonian",
            Family::Lagrangian => "lagrangian",
            Family::Ode => "ode",
        }
    }
}

/// Builds a system from parsed values.
pub type Constructor = fn(&Values) -> Result<Box<dyn Simulation>>;

/// One entry of the registry.
#[derive(Clone, Copy)]
pub struct SystemSpec {
    /// Name used on the command line (kebab-case).
    pub name: &'static str,
    /// One-line description, with the library type it builds.
    pub summary: &'static str,
    /// Output layout.
    pub family: Family,
    /// Parameters, in the order they are listed.
    pub params: &'static [ParamSpec],
    /// Methods the system accepts.
    pub methods: &'static [Method],
    /// Method shown as the default by `list`: the library's `default_method()` for the
    /// default parameters (checked by a test). `simulate` asks the built system itself, since
    /// the default can depend on the parameters (a projectile with drag defaults to `rk4`).
    pub default_method: Method,
    /// Extra remark printed by `list` (which methods need which parameters, ...).
    pub note: Option<&'static str>,
    /// Constructor.
    pub build: Constructor,
}

impl fmt::Debug for SystemSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SystemSpec")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

impl ParamSpec {
    /// The help text with its default, `[default: ...]`, unless the help already says it.
    pub fn help_with_default(&self) -> String {
        if self.help.contains("[default:") {
            self.help.to_string()
        } else {
            format!(
                "{} [default: {}]",
                self.help,
                self.default.unwrap_or("none")
            )
        }
    }
}

impl SystemSpec {
    /// The parameter called `name`.
    pub fn param(&self, name: &str) -> Option<&ParamSpec> {
        self.params.iter().find(|p| p.name == name)
    }

    /// Parses a method name and checks that this system accepts it.
    ///
    /// # Errors
    /// Unknown method names, or methods the system refuses.
    pub fn method(&self, name: &str) -> Result<Method> {
        let method: Method = name.parse()?;
        if self.methods.contains(&method) {
            Ok(method)
        } else {
            bail!(
                "method `{method}` cannot integrate `{}`; valid methods are: {}",
                self.name,
                method_names(self.methods)
            )
        }
    }

    /// Parses `given` (parameter name to command-line text) over the defaults.
    ///
    /// # Errors
    /// Unknown parameter names, unparsable values, lists of the wrong length.
    pub fn parse_values<'a>(
        &self,
        given: impl IntoIterator<Item = (&'a str, &'a str)>,
    ) -> Result<Values> {
        let mut texts: BTreeMap<&'static str, &str> = BTreeMap::new();
        for (name, text) in given {
            let spec = self.param(name).ok_or_else(|| {
                anyhow!(
                    "unknown parameter `--{name}` for `{}`; its parameters are: {}",
                    self.name,
                    self.params
                        .iter()
                        .map(|p| p.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })?;
            texts.insert(spec.name, text);
        }
        let mut values = Values::default();
        for spec in self.params {
            let text = texts.get(spec.name).copied().or(spec.default);
            let value = match text {
                Some(text) => parse_value(spec, text)
                    .with_context(|| format!("invalid value `{text}` for `--{}`", spec.name))?,
                None => Value::Absent,
            };
            values.0.push((spec.name, value));
        }
        Ok(values)
    }
}

/// Comma-separated method names, for messages.
pub fn method_names(methods: &[Method]) -> String {
    methods
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A parsed parameter value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// [`Kind::Real`].
    Real(f64),
    /// [`Kind::Count`].
    Count(usize),
    /// [`Kind::List`].
    List(Vec<f64>),
    /// [`Kind::Choice`].
    Choice(&'static str),
    /// An optional parameter that was not given.
    Absent,
}

/// Every parameter of one system with its value, in the registry's order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Values(Vec<(&'static str, Value)>);

impl Values {
    /// `(name, value)` pairs in the registry's order.
    pub fn iter(&self) -> impl Iterator<Item = &(&'static str, Value)> {
        self.0.iter()
    }

    fn get(&self, name: &str) -> Result<&Value> {
        self.0
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v)
            // Only reachable if a constructor asks for a parameter its entry does not declare;
            // the registry tests build every system, so this would fail there first.
            .ok_or_else(|| anyhow!("internal: parameter `{name}` is not declared"))
    }

    /// A real parameter.
    ///
    /// # Errors
    /// Undeclared, absent or not a real (a registry bug).
    pub fn real(&self, name: &str) -> Result<f64> {
        self.opt_real(name)?
            .ok_or_else(|| anyhow!("parameter `--{name}` is required"))
    }

    /// An optional real parameter.
    ///
    /// # Errors
    /// Undeclared or not a real (a registry bug).
    pub fn opt_real(&self, name: &str) -> Result<Option<f64>> {
        match self.get(name)? {
            Value::Real(v) => Ok(Some(*v)),
            Value::Absent => Ok(None),
            other => bail!("internal: `{name}` is {other:?}, not a real"),
        }
    }

    /// A count parameter.
    ///
    /// # Errors
    /// Undeclared or not a count (a registry bug).
    pub fn count(&self, name: &str) -> Result<usize> {
        match self.get(name)? {
            Value::Count(v) => Ok(*v),
            other => bail!("internal: `{name}` is {other:?}, not a count"),
        }
    }

    /// A list parameter.
    ///
    /// # Errors
    /// Undeclared, absent or not a list (a registry bug).
    pub fn list(&self, name: &str) -> Result<&[f64]> {
        self.opt_list(name)?
            .ok_or_else(|| anyhow!("parameter `--{name}` is required"))
    }

    /// An optional list parameter.
    ///
    /// # Errors
    /// Undeclared or not a list (a registry bug).
    pub fn opt_list(&self, name: &str) -> Result<Option<&[f64]>> {
        match self.get(name)? {
            Value::List(v) => Ok(Some(v)),
            Value::Absent => Ok(None),
            other => bail!("internal: `{name}` is {other:?}, not a list"),
        }
    }

    /// A choice parameter.
    ///
    /// # Errors
    /// Undeclared or not a choice (a registry bug).
    pub fn choice(&self, name: &str) -> Result<&'static str> {
        match self.get(name)? {
            Value::Choice(v) => Ok(v),
            other => bail!("internal: `{name}` is {other:?}, not a choice"),
        }
    }
}

fn parse_real(text: &str) -> Result<f64> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| anyhow!("expected a number"))?;
    // The library rejects non-finite inputs too; catching them here names the flag.
    if !v.is_finite() {
        bail!("expected a finite number");
    }
    Ok(v)
}

fn parse_value(spec: &ParamSpec, text: &str) -> Result<Value> {
    Ok(match spec.kind {
        Kind::Real => Value::Real(parse_real(text)?),
        Kind::Count => Value::Count(
            text.trim()
                .parse()
                .map_err(|_| anyhow!("expected a non-negative integer"))?,
        ),
        Kind::List(len) => {
            let items = text
                .split(',')
                .map(parse_real)
                .collect::<Result<Vec<_>>>()
                .context("expected comma-separated numbers")?;
            if let Some(n) = len {
                if items.len() != n {
                    bail!("expected {n} comma-separated numbers, got {}", items.len());
                }
            }
            Value::List(items)
        }
        Kind::Choice(words) => Value::Choice(
            words
                .iter()
                .copied()
                .find(|w| *w == text)
                .ok_or_else(|| anyhow!("expected one of: {}", words.join(", ")))?,
        ),
    })
}

/// Looks a system up by name.
///
/// # Errors
/// Unknown names, with the list of known ones.
pub fn find(name: &str) -> Result<&'static SystemSpec> {
    crate::systems::REGISTRY
        .iter()
        .find(|s| s.name == name)
        .ok_or_else(|| {
            anyhow!(
                "unknown system `{name}`; known systems are: {} (see `physicskit list`)",
                crate::systems::REGISTRY
                    .iter()
                    .map(|s| s.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::REGISTRY;

    #[test]
    fn names_are_unique_and_do_not_shadow_run_options() {
        let reserved = ["method", "dt", "t0", "t1", "out", "stride", "help"];
        let mut seen = std::collections::BTreeSet::new();
        for spec in REGISTRY {
            assert!(seen.insert(spec.name), "duplicate system {}", spec.name);
            let mut params = std::collections::BTreeSet::new();
            for p in spec.params {
                assert!(!reserved.contains(&p.name), "{}: --{}", spec.name, p.name);
                assert!(
                    params.insert(p.name),
                    "{}: duplicate --{}",
                    spec.name,
                    p.name
                );
            }
            assert!(spec.methods.contains(&spec.default_method), "{}", spec.name);
        }
    }

    /// Every default parses and builds, and the registry's default method is the library's.
    #[test]
    fn every_system_builds_from_its_defaults() {
        for spec in REGISTRY {
            let values = spec
                .parse_values([])
                .unwrap_or_else(|e| panic!("{}: {e:#}", spec.name));
            let sim = (spec.build)(&values).unwrap_or_else(|e| panic!("{}: {e:#}", spec.name));
            assert_eq!(
                sim.default_method(),
                spec.default_method,
                "{}: registry default differs from the library's",
                spec.name
            );
            assert!(sim.as_dynamical().state_dim() > 0);
        }
    }

    #[test]
    fn values_are_parsed_and_checked() {
        let spec = find("harmonic-oscillator").unwrap();
        let values = spec.parse_values([("k", "4"), ("q0", "-1.5e-3")]).unwrap();
        assert_eq!(values.real("k").unwrap().to_bits(), 4.0_f64.to_bits());
        assert_eq!(
            values.real("q0").unwrap().to_bits(),
            (-1.5e-3_f64).to_bits()
        );
        assert!(spec.parse_values([("k", "four")]).is_err());
        assert!(spec.parse_values([("k", "inf")]).is_err());
        assert!(spec.parse_values([("nope", "1")]).is_err());
        assert!(find("nope").is_err());
    }

    #[test]
    fn lists_check_their_length() {
        let spec = ParamSpec {
            name: "q0",
            kind: Kind::List(Some(2)),
            default: None,
            help: "",
        };
        assert_eq!(
            parse_value(&spec, "1, -2.5").unwrap(),
            Value::List(vec![1.0, -2.5])
        );
        assert!(parse_value(&spec, "1").is_err());
        assert!(parse_value(&spec, "1,2,3").is_err());
        assert!(parse_value(&spec, "1,,2").is_err());
    }
}
