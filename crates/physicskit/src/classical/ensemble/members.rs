//! The members of an ensemble: who they are ([`Members`]: values common to all, swept
//! parameters, initial states) and where they come from ([`MemberSource`]): a catalogue entry
//! ([`FromCatalogue`], every member built and checked through the catalogue), or any system
//! a closure builds from named real parameters ([`FromParameters`](super::FromParameters),
//! the SymPy engines' systems).

use crate::classical::core::{Error, Result};
use crate::classical::model::entry::{Default as ParamDefault, Literal, ParamKind};
use crate::classical::model::{DynSystem, SystemEntry, Value};

/// One swept parameter: `values[i]` is member `i`'s value of `target`.
///
/// `target` is a scalar or integer parameter (`"m2"`, `"c_pn"`) or one entry of a vector
/// parameter (`"theta0[1]"`), whose other entries come from the common values or the
/// parameter's default.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// The parameter, or `name[index]` for one entry of a vector parameter.
    pub target: String,
    /// One value per member (integers as exact whole numbers).
    pub values: Vec<f64>,
}

impl Sweep {
    /// `target` with its per-member `values`.
    pub fn new(target: impl Into<String>, values: Vec<f64>) -> Self {
        Self {
            target: target.into(),
            values,
        }
    }
}

/// Who the members are.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Members {
    /// Values shared by every member (others take the source's: the catalogue's defaults, or
    /// the values given to [`FromParameters`](super::FromParameters)).
    pub common: Vec<(String, Value)>,
    /// Per-member parameter values, applied over `common`.
    pub sweeps: Vec<Sweep>,
    /// Per-member initial states, row-major (`n x state length`), replacing the state the
    /// parameters give; `None` keeps it.
    pub states: Option<Vec<f64>>,
    /// The number of members (every sweep has this many values, `states` this many rows).
    pub n: usize,
}

/// Where a swept value goes.
#[derive(Debug, Clone, Copy)]
enum Slot {
    /// A scalar parameter.
    Scalar(usize),
    /// An integer parameter.
    Integer(usize),
    /// Entry `index` of the vector parameter at `given[slot]`.
    Element { slot: usize, index: usize },
}

/// Where an ensemble's members come from: member `index` built at its initial state with its
/// clock at `t0`.
///
/// The engine builds every member once to check it before any integration (unless the
/// caller has: `run_source_prechecked`), and again to run it, each time on whichever thread is
/// free: `build` must give the same system (the same
/// bits) every time it is asked for the same member, and must not panic.
pub trait MemberSource: Sync {
    /// The number of members (at least 1).
    fn count(&self) -> usize;

    /// Builds member `index` (`< count()`) at its initial state, clock at `t0`.
    ///
    /// # Errors
    /// Whatever makes the member invalid; the engine prefixes the argument's name with
    /// `member {index}: `.
    fn build(&self, index: usize, t0: f64) -> Result<Box<dyn DynSystem>>;

    /// Whether members `a` and `b` are the same system apart from their initial states (so
    /// the same field, and the same Taylor form): the `taylor` method then builds one Taylor
    /// form for both. `false`, the default, when the source cannot tell without building
    /// them; the engine then compares their Taylor forms.
    fn same_system(&self, a: usize, b: usize) -> bool {
        let _ = (a, b);
        false
    }
}

/// Whether every sweep gives members `a` and `b` the same value, bit for bit.
pub(crate) fn same_sweeps(members: &Members, a: usize, b: usize) -> bool {
    members
        .sweeps
        .iter()
        .all(|s| s.values[a].to_bits() == s.values[b].to_bits())
}

/// The members of a catalogue entry: the checked recipe of every member.
#[derive(Debug, Clone)]
pub struct FromCatalogue<'a> {
    entry: &'static SystemEntry,
    members: &'a Members,
    /// The common values, plus one slot per swept scalar and per swept vector.
    given: Vec<(String, Value)>,
    slots: Vec<Slot>,
}

/// `error` as it concerns member `index`: the argument's name is prefixed with `member
/// {index}: `, so the message reads e.g. "invalid parameter `member 731: theta0` = NaN".
pub(crate) fn in_member(index: usize, error: Error) -> Error {
    let prefix = |name: String| format!("member {index}: {name}");
    match error {
        Error::InvalidParameter {
            name,
            value,
            reason,
        } => Error::InvalidParameter {
            name: prefix(name),
            value,
            reason,
        },
        Error::InvalidArgument { name, reason } => Error::InvalidArgument {
            name: prefix(name),
            reason,
        },
        Error::DimensionMismatch {
            name,
            expected,
            found,
        } => Error::DimensionMismatch {
            name: prefix(name),
            expected,
            found,
        },
        Error::NonFinite { name, t } => Error::NonFinite {
            name: prefix(name),
            t,
        },
        Error::UnsupportedMethod { method, reason } => Error::UnsupportedMethod {
            method,
            reason: format!("member {index}: {reason}"),
        },
        // Still a failure to converge (at the given tolerances or step budget), not a bad
        // argument: front ends map it as they map a single run's.
        Error::StepSizeTooSmall { t, step, reason } => Error::StepSizeTooSmall {
            t,
            step,
            reason: format!("member {index}: {reason}"),
        },
        other => Error::InvalidArgument {
            name: format!("member {index}"),
            reason: other.to_string(),
        },
    }
}

/// Splits `name[index]` into the name and the index.
fn element(target: &str) -> Option<(&str, &str)> {
    let (name, rest) = target.split_once('[')?;
    Some((name, rest.strip_suffix(']')?))
}

/// Checks what every source needs of `members`: at least one member, and one value per member
/// in every sweep.
pub(crate) fn check_counts(members: &Members) -> Result<()> {
    let n = members.n;
    check_count(n)?;
    match members.sweeps.iter().find(|s| s.values.len() != n) {
        Some(sweep) => Err(Error::DimensionMismatch {
            name: sweep.target.clone(),
            expected: n,
            found: sweep.values.len(),
        }),
        None => Ok(()),
    }
}

/// Refuses an ensemble of no members.
pub(crate) fn check_count(n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::invalid(
            "members",
            0.0,
            "an ensemble needs >= 1 member",
        ));
    }
    Ok(())
}

/// Row `index` of the per-member `states` (`None` without them), checked to hold `n` rows of
/// `dim`.
///
/// # Errors
/// [`Error::DimensionMismatch`] if `states` does not hold `n x dim` values.
pub(crate) fn state_row(members: &Members, index: usize, dim: usize) -> Result<Option<&[f64]>> {
    let Some(states) = &members.states else {
        return Ok(None);
    };
    if states.len() != members.n * dim {
        return Err(Error::DimensionMismatch {
            name: "states".into(),
            expected: members.n * dim,
            found: states.len(),
        });
    }
    Ok(Some(&states[index * dim..(index + 1) * dim]))
}

impl<'a> FromCatalogue<'a> {
    /// Checks the shape of `members` against `entry` (sweep targets, lengths); members
    /// themselves are checked when built ([`MemberSource::build`]).
    ///
    /// # Errors
    /// No members, a sweep of the wrong length, an unknown parameter, or one that cannot be
    /// swept (only real and integer parameters, and entries `name[i]` of vector parameters).
    pub fn new(entry: &'static SystemEntry, members: &'a Members) -> Result<Self> {
        check_counts(members)?;
        let mut given = members.common.clone();
        let mut slots = Vec::with_capacity(members.sweeps.len());
        for sweep in &members.sweeps {
            let (name, index) = match element(&sweep.target) {
                Some((name, index)) => (name, Some(index)),
                None => (sweep.target.as_str(), None),
            };
            let spec = entry.lookup(name)?;
            let slot_of = |given: &mut Vec<(String, Value)>, value: Value| match given
                .iter()
                .position(|(g, _)| g == name)
            {
                Some(i) => i,
                None => {
                    given.push((name.to_string(), value));
                    given.len() - 1
                }
            };
            let slot = match (spec.kind, index) {
                (ParamKind::Scalar, None) => Slot::Scalar(slot_of(&mut given, Value::Scalar(0.0))),
                (ParamKind::Integer, None) => Slot::Integer(slot_of(&mut given, Value::Integer(0))),
                (ParamKind::Vector(_), Some(index)) => {
                    let index: usize =
                        index.trim().parse().map_err(|_| Error::InvalidArgument {
                            name: sweep.target.clone(),
                            reason: "expected `name[index]` with a whole-number index".into(),
                        })?;
                    let base = match spec.default {
                        ParamDefault::Value(Literal::Vector(v))
                        | ParamDefault::Demo(Literal::Vector(v)) => Some(Value::Vector(v.to_vec())),
                        _ => None,
                    };
                    let slot = match given.iter().position(|(g, _)| g == name) {
                        Some(i) => i,
                        None => {
                            let base = base.ok_or_else(|| Error::InvalidArgument {
                                name: sweep.target.clone(),
                                reason: format!(
                                    "`{name}` has no default: give its other entries as a \
                                     common value"
                                ),
                            })?;
                            given.push((name.to_string(), base));
                            given.len() - 1
                        }
                    };
                    let len = match &given[slot].1 {
                        Value::Vector(v) => v.len(),
                        other => {
                            return Err(Error::InvalidArgument {
                                name: name.into(),
                                reason: format!("expected a vector, got {}", other.kind_name()),
                            })
                        }
                    };
                    if index >= len {
                        return Err(Error::InvalidArgument {
                            name: sweep.target.clone(),
                            reason: format!("index out of range: `{name}` has {len} entries"),
                        });
                    }
                    Slot::Element { slot, index }
                }
                _ => {
                    return Err(Error::InvalidArgument {
                        name: sweep.target.clone(),
                        reason: format!(
                            "only real and integer parameters, and entries `{name}[i]` of \
                             vector parameters, can be swept; `{name}` expects {}",
                            spec.expectation()
                        ),
                    })
                }
            };
            slots.push(slot);
        }
        Ok(Self {
            entry,
            members,
            given,
            slots,
        })
    }
}

impl MemberSource for FromCatalogue<'_> {
    fn count(&self) -> usize {
        self.members.n
    }

    /// Builds member `index` through the catalogue at its initial state (clock at `t0`).
    ///
    /// # Errors
    /// Whatever the catalogue or the constructor refuses, and an initial state of the wrong
    /// length or not finite.
    fn build(&self, index: usize, t0: f64) -> Result<Box<dyn DynSystem>> {
        let mut given = self.given.clone();
        for (sweep, slot) in self.members.sweeps.iter().zip(&self.slots) {
            let x = sweep.values[index];
            match *slot {
                Slot::Scalar(i) => given[i].1 = Value::Scalar(x),
                Slot::Integer(i) => {
                    // Exact whole numbers only: 2.5 is refused, not truncated.
                    if x.fract() != 0.0 || !x.is_finite() || x.abs() > 9.0e15 {
                        return Err(Error::invalid(
                            sweep.target.clone(),
                            x,
                            "must be a whole number",
                        ));
                    }
                    given[i].1 = Value::Integer(x as i64);
                }
                Slot::Element { slot, index: k } => {
                    if let Value::Vector(v) = &mut given[slot].1 {
                        v[k] = x;
                    }
                }
            }
        }
        let mut system = self.entry.build_from(given)?;
        let dim = system.dynamical().state_dim();
        if let Some(state) = state_row(self.members, index, dim)? {
            system.reset(Some(state), t0)?;
        }
        Ok(system)
    }

    /// Equal swept values: equal parameters (the per-member states are only states).
    fn same_system(&self, a: usize, b: usize) -> bool {
        same_sweeps(self.members, a, b)
    }
}
