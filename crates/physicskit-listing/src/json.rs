//! `list --json`: the whole catalogue as one JSON object, keys in a fixed order.
//!
//! ```text
//! {"version": "0.1.0",
//!  "systems": [{"name", "python", "title", "summary", "summary_text", "family", "separable",
//!               "methods": [..], "default_method", "note", "note_text", "physics",
//!               "physics_text", "presentation": {..}, "capabilities": [..],
//!               "params": [{"name", "kind", "length", "choices", "default",
//!                           "default_origin", "unit", "range", "help", "initial_state",
//!                           "label", "unit_text", "help_text"}, ..]}, ..],
//!  "methods": [{"name", "label", "order", "symplectic", "separable_only", "adaptive",
//!               "needs_taylor_form", "evaluations_per_step", "evaluations", "reference"},
//!              ..]}
//! ```
//!
//! - `kind`: `scalar`, `integer`, `vector` or `choice`; `choices` lists the words of a choice
//!   (else `null`); `length` is a vector's length rule (else `null`): `{"rule": "fixed",
//!   "n": 2}`, `{"rule": "any"}`, `{"rule": "same_as", "param": "q0"}` or `{"rule": "count",
//!   "param": "n"}`.
//! - `default`: the value a front end without required arguments starts from (a number, an
//!   integer, an array or a word), or `null` when the parameter is left to the constructor.
//!   `default_origin` says whose it is: `spec` (the Python signature's; `null` there is the
//!   spec's `None`), `demo` (the spec requires the value; the command line and the lab start
//!   from this demonstration) or `required`.
//! - `range`: for scalars and integers `{"min": B, "max": B}` with `B` `null` (unbounded) or
//!   `{"value": x, "inclusive": bool}`; `null` for vectors and choices (entries must be
//!   finite). Every number must be finite.
//! - `initial_state`: the parameter is part of the initial state (`q0`, `theta0`), not a
//!   constant of the system; its unit is a state component's.
//! - `capabilities`: the optional accessors the system built from its defaults offers
//!   (`physicskit::classical::model::erased::CAPABILITY_NAMES`).
//! - `physics`: the system's physics paragraph (`SystemEntry::physics`), the lab's caption and
//!   the opening of the gallery demonstration that shows it; `null` if none.
//! - `presentation`: how front ends show the system (`SystemEntry::presentation`):
//!   `{"title", "symbols": [TeX, ..], "time_unit", "state_units": null or [coordinate, momentum],
//!   "drawing": {"kind", and the kind's attributes: "springs" and
//!   "scale" (bobs, the length its positions are in units of, if any), "ends" (chains),
//!   "central_body" and "ground" (orbits), "shape" (rolling bodies)}, "pace": {"kind": "own"}
//!   or {"kind": "fixed", "method", "dt", "steps_per_frame", "energy_error"} or
//!   {"kind": "time_lapse", "dt", "steps_per_frame"}, "section_first": bool,
//!   "energy_conserved": bool}`.
//! - `methods` per system: those that can integrate it, as `simulate --method` takes them.
//! - `title`: the entry's `presentation.title` (also inside `presentation`).
//! - `summary_text`, `note_text`, `physics_text` (the paragraph's powers as
//!   superscripts), and per parameter `label`, `unit_text`, `help_text`: the
//!   same text for people (the lab's), in Unicode mathematics, without class names, flags or
//!   remarks about state columns (`crate::people`); `note_text` is `null` when nothing is
//!   left.

use std::io::{self, Write};

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::entry::{Bound, Default, Length, Literal, ParamKind, Range};
use physicskit::classical::model::erased::offered;
use physicskit::classical::model::{Attribute, ParamSpec, Presentation, SystemEntry};
use serde::Serialize;

use crate::{method_rows, people, MethodRow};

#[derive(Serialize)]
struct Catalogue {
    version: &'static str,
    systems: Vec<System>,
    methods: Vec<MethodRow>,
}

#[derive(Serialize)]
struct System {
    name: &'static str,
    python: Option<&'static str>,
    title: &'static str,
    summary: &'static str,
    summary_text: String,
    family: &'static str,
    separable: bool,
    methods: Vec<&'static str>,
    default_method: &'static str,
    note: Option<&'static str>,
    note_text: Option<String>,
    physics: Option<&'static str>,
    physics_text: Option<String>,
    presentation: PresentationJson,
    capabilities: Vec<&'static str>,
    params: Vec<Param>,
}

#[derive(Serialize)]
struct PresentationJson {
    title: &'static str,
    symbols: &'static [&'static str],
    time_unit: &'static str,
    state_units: Option<[&'static str; 2]>,
    drawing: serde_json::Map<String, serde_json::Value>,
    pace: serde_json::Map<String, serde_json::Value>,
    section_first: bool,
    energy_conserved: bool,
}

#[derive(Serialize)]
struct Param {
    name: &'static str,
    kind: &'static str,
    length: Option<LengthRule>,
    choices: Option<&'static [&'static str]>,
    default: Option<DefaultValue>,
    default_origin: &'static str,
    unit: &'static str,
    range: Option<RangeJson>,
    help: &'static str,
    initial_state: bool,
    label: String,
    unit_text: String,
    help_text: String,
}

#[derive(Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
enum LengthRule {
    Fixed { n: usize },
    Any,
    SameAs { param: &'static str },
    Count { param: &'static str },
}

#[derive(Serialize)]
#[serde(untagged)]
enum DefaultValue {
    Scalar(f64),
    Integer(i64),
    Vector(&'static [f64]),
    Choice(&'static str),
}

#[derive(Serialize)]
struct RangeJson {
    min: Option<BoundJson>,
    max: Option<BoundJson>,
}

#[derive(Serialize)]
struct BoundJson {
    value: f64,
    inclusive: bool,
}

/// Writes the catalogue to `w`, pretty-printed, with a final newline (`physicskit list
/// --json`).
///
/// # Errors
/// I/O errors of `w` (a closed pipe).
pub fn write_json(w: &mut impl Write) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *w, &catalogue())?;
    writeln!(w)
}

/// The catalogue as the string [`write_json`] writes.
pub fn catalogue_json() -> String {
    let mut text = serde_json::to_string_pretty(&catalogue()).unwrap_or_default();
    text.push('\n');
    text
}

fn catalogue() -> Catalogue {
    Catalogue {
        version: env!("CARGO_PKG_VERSION"),
        systems: SYSTEMS.iter().map(|e| system(e)).collect(),
        methods: method_rows(),
    }
}

fn system(entry: &SystemEntry) -> System {
    System {
        name: entry.name,
        python: entry.python,
        title: entry.presentation.title,
        summary: entry.summary,
        summary_text: people::text(entry.summary),
        family: entry.family.name(),
        separable: entry.separable,
        methods: entry.methods().map(|m| m.name()).collect(),
        default_method: entry.default_method.name(),
        note: entry.note,
        note_text: entry.note.and_then(people::note),
        physics: entry.physics,
        physics_text: entry.physics.map(people::powers),
        presentation: presentation(&entry.presentation),
        // Every entry builds from its defaults (the catalogue's own tests check it); should
        // one not, it offers nothing rather than breaking the listing.
        capabilities: entry
            .build_from([])
            .map(|s| offered(s.as_ref()))
            .unwrap_or_default(),
        params: entry.params.iter().map(param).collect(),
    }
}

fn presentation(p: &Presentation) -> PresentationJson {
    PresentationJson {
        title: p.title,
        symbols: p.symbols,
        time_unit: p.time_unit,
        state_units: p.state_units.map(|(q, p)| [q, p]),
        drawing: kind_with(p.drawing.name(), p.drawing.attributes()),
        pace: kind_with(p.pace.name(), p.pace.attributes()),
        section_first: p.section_first,
        energy_conserved: p.energy_conserved,
    }
}

/// `{"kind": kind, attribute: value, ..}`.
fn kind_with(
    kind: &'static str,
    attributes: Vec<(&'static str, Attribute)>,
) -> serde_json::Map<String, serde_json::Value> {
    let mut map = serde_json::Map::new();
    map.insert("kind".into(), kind.into());
    for (name, value) in attributes {
        let value = match value {
            Attribute::Flag(b) => b.into(),
            Attribute::Word(w) => w.into(),
            Attribute::Number(x) => x.into(),
        };
        map.insert(name.into(), value);
    }
    map
}

fn param(spec: &ParamSpec) -> Param {
    let (default, default_origin) = match spec.default {
        Default::Required => (None, "required"),
        Default::Value(l) => (Some(literal(l)), "spec"),
        Default::Absent => (None, "spec"),
        Default::Demo(l) => (Some(literal(l)), "demo"),
        Default::DemoAbsent => (None, "demo"),
    };
    let length = match spec.kind {
        ParamKind::Vector(Length::Fixed(n)) => Some(LengthRule::Fixed { n }),
        ParamKind::Vector(Length::Any) => Some(LengthRule::Any),
        ParamKind::Vector(Length::SameAs(param)) => Some(LengthRule::SameAs { param }),
        ParamKind::Vector(Length::Count(param)) => Some(LengthRule::Count { param }),
        _ => None,
    };
    let choices = match spec.kind {
        ParamKind::Choice(words) => Some(words),
        _ => None,
    };
    let range =
        matches!(spec.kind, ParamKind::Scalar | ParamKind::Integer).then(|| range(spec.range));
    Param {
        name: spec.name,
        kind: spec.kind.name(),
        length,
        choices,
        default,
        default_origin,
        unit: spec.unit,
        range,
        help: spec.help,
        initial_state: spec.initial_state,
        label: people::label(spec.name),
        unit_text: people::text(spec.unit),
        help_text: people::text(spec.help),
    }
}

fn literal(l: Literal) -> DefaultValue {
    match l {
        Literal::Scalar(x) => DefaultValue::Scalar(x),
        Literal::Integer(n) => DefaultValue::Integer(n),
        Literal::Vector(v) => DefaultValue::Vector(v),
        Literal::Choice(w) => DefaultValue::Choice(w),
    }
}

fn range(r: Range) -> RangeJson {
    let bound = |b| match b {
        Bound::Unbounded => None,
        Bound::Inclusive(value) => Some(BoundJson {
            value,
            inclusive: true,
        }),
        Bound::Exclusive(value) => Some(BoundJson {
            value,
            inclusive: false,
        }),
    };
    RangeJson {
        min: bound(r.min),
        max: bound(r.max),
    }
}
