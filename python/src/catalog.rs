//! The catalogue as Python sees it: `build` a system by name, and `catalog` / `methods`
//! listings, all read from the core's one list of systems
//! ([`physicskit::classical::catalog::SYSTEMS`]) and of methods ([`Method::ALL`]).
//!
//! The Python classes construct through `build("<entry name>", {...their arguments...})`:
//! each argument is converted by its parameter's kind ([`crate::params`]) and checked by the
//! catalogue, so no list of systems, parameters or defaults exists in the extension.

use physicskit::classical::catalog as core_catalog;
use physicskit::classical::model::entry::{
    Attribute, Bound as Limit, Default, Length, Literal, ParamKind, ParamSpec, Presentation,
    SystemEntry,
};
use physicskit::classical::Method;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::IntoPyResult;
use crate::native::NativeSystem;
use crate::params::{key, to_value};

/// Builds the catalogue system `name` from `params` (parameter name -> value; a value of
/// `None` leaves the parameter out). As the Python signatures are the spec's, the catalogue
/// fills in only the spec's defaults: a parameter the spec gives no default must be given
/// ([`SystemEntry::values_as_in_spec`]). The checked values are the returned system's
/// `params`.
///
/// # Errors
/// `ValueError` for an unknown system or parameter, a value of the wrong kind, a missing
/// required value, a number out of range or a vector of the wrong length; `TypeError` for a
/// non-string parameter name.
#[pyfunction]
#[pyo3(signature = (name, params))]
pub fn build(name: &str, params: &Bound<'_, PyDict>) -> PyResult<NativeSystem> {
    let entry = core_catalog::find(name).py()?;
    let mut given = Vec::with_capacity(params.len());
    for (k, v) in params.iter() {
        let k = key(&k)?;
        let spec = entry.lookup(&k).py()?;
        if let Some(value) = to_value(spec, &v)? {
            given.push((k, value));
        }
    }
    let values = entry.values_as_in_spec(given).py()?;
    let system = (entry.build)(&values).py()?;
    Ok(NativeSystem::from_entry(entry, values, system))
}

fn literal<'py>(py: Python<'py>, l: Literal) -> PyResult<Bound<'py, PyAny>> {
    Ok(match l {
        Literal::Scalar(x) => x.into_pyobject(py)?.into_any(),
        Literal::Integer(n) => n.into_pyobject(py)?.into_any(),
        Literal::Vector(v) => PyList::new(py, v)?.into_any(),
        Literal::Choice(w) => w.into_pyobject(py)?.into_any(),
    })
}

fn limit<'py>(py: Python<'py>, b: Limit) -> PyResult<Bound<'py, PyAny>> {
    Ok(match b {
        Limit::Unbounded => py.None().into_bound(py),
        Limit::Inclusive(x) => (x, true).into_pyobject(py)?.into_any(),
        Limit::Exclusive(x) => (x, false).into_pyobject(py)?.into_any(),
    })
}

/// One parameter as a dict (see `_core.pyi`, `ParamInfo`).
fn param_info<'py>(py: Python<'py>, p: &ParamSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", p.name)?;
    d.set_item("kind", p.kind.name())?;
    let (default_kind, value) = match p.default {
        Default::Required => ("required", None),
        Default::Value(l) => ("value", Some(l)),
        Default::Absent => ("absent", None),
        Default::Demo(l) => ("demo", Some(l)),
        Default::DemoAbsent => ("demo_absent", None),
    };
    d.set_item("default_kind", default_kind)?;
    match value {
        Some(l) => d.set_item("default", literal(py, l)?)?,
        None => d.set_item("default", py.None())?,
    }
    d.set_item("spec_default", p.default.in_spec())?;
    d.set_item("unit", p.unit)?;
    let range = PyDict::new(py);
    range.set_item("min", limit(py, p.range.min)?)?;
    range.set_item("max", limit(py, p.range.max)?)?;
    range.set_item("text", p.range.to_string())?;
    d.set_item("range", range)?;
    let (length, choices): (Option<Bound<'py, PyAny>>, Option<Vec<&str>>) = match p.kind {
        ParamKind::Vector(Length::Fixed(n)) => (Some(n.into_pyobject(py)?.into_any()), None),
        ParamKind::Vector(Length::Any) => (Some("any".into_pyobject(py)?.into_any()), None),
        ParamKind::Vector(Length::SameAs(other)) => (
            Some(format!("same as {other}").into_pyobject(py)?.into_any()),
            None,
        ),
        ParamKind::Vector(Length::Count(count)) => (
            Some(format!("count {count}").into_pyobject(py)?.into_any()),
            None,
        ),
        ParamKind::Choice(words) => (None, Some(words.to_vec())),
        ParamKind::Scalar | ParamKind::Integer => (None, None),
    };
    d.set_item("length", length)?;
    d.set_item("choices", choices)?;
    d.set_item("expectation", p.expectation())?;
    d.set_item("help", p.help)?;
    d.set_item("initial_state", p.initial_state)?;
    Ok(d)
}

/// How front ends show a system, as a dict: `title`, `symbols`, `time_unit`, `state_units`
/// (`None` or a pair), `drawing` (`kind` and the kind's attributes: `springs` and `scale` for
/// bobs, `ends` for chains, `central_body` and `ground` for orbits, `shape` for rolling
/// bodies), `pace` (`kind`: `own`, `fixed` with `method`, `dt`, `steps_per_frame`,
/// `energy_error`, or
/// `time_lapse` with `dt`, `steps_per_frame`), `section_first` and `energy_conserved`: the
/// same as `list --json`'s.
fn presentation_info<'py>(py: Python<'py>, p: &Presentation) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("title", p.title)?;
    d.set_item("symbols", p.symbols.to_vec())?;
    d.set_item("time_unit", p.time_unit)?;
    d.set_item("state_units", p.state_units.map(|(q, p)| vec![q, p]))?;
    d.set_item(
        "drawing",
        kind_with(py, p.drawing.name(), p.drawing.attributes())?,
    )?;
    d.set_item("pace", kind_with(py, p.pace.name(), p.pace.attributes())?)?;
    d.set_item("section_first", p.section_first)?;
    d.set_item("energy_conserved", p.energy_conserved)?;
    Ok(d)
}

/// `{"kind": kind, attribute: value, ..}`.
fn kind_with<'py>(
    py: Python<'py>,
    kind: &'static str,
    attributes: Vec<(&'static str, Attribute)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", kind)?;
    for (name, value) in attributes {
        match value {
            Attribute::Flag(b) => d.set_item(name, b)?,
            Attribute::Word(w) => d.set_item(name, w)?,
            Attribute::Number(x) => d.set_item(name, x)?,
        }
    }
    Ok(d)
}

/// One catalogue entry as a dict (see `_core.pyi`, `SystemInfo`).
fn entry_info<'py>(py: Python<'py>, e: &SystemEntry) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", e.name)?;
    d.set_item("python", e.python)?;
    d.set_item("summary", e.summary)?;
    d.set_item("family", e.family.name())?;
    d.set_item("separable", e.separable)?;
    d.set_item("methods", e.methods().map(Method::name).collect::<Vec<_>>())?;
    d.set_item("default_method", e.default_method.name())?;
    d.set_item("note", e.note)?;
    d.set_item("physics", e.physics)?;
    d.set_item("presentation", presentation_info(py, &e.presentation)?)?;
    let params = e
        .params
        .iter()
        .map(|p| param_info(py, p))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("params", params)?;
    Ok(d)
}

/// Every system of the catalogue, in listing order, as dicts: `name`, `python` (the class or
/// `Class.classmethod`, or `None`), `summary`, `family`, `separable`, `methods`,
/// `default_method`, `note`, `physics` (the system's physics paragraph, as in
/// `physicskit list --json`, or `None`) and `params` (each with `name`, `kind`, `default`,
/// `default_kind`, `spec_default`, `unit`, `range`, `length`, `choices`, `expectation`,
/// `help`, `initial_state`).
///
/// # Errors
/// Python allocation failures.
#[pyfunction]
pub fn catalog(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    core_catalog::SYSTEMS
        .iter()
        .map(|e| entry_info(py, e))
        .collect()
}

/// Every integrator, as dicts: `name`, `order`, `symplectic`, `separable_only`, `adaptive`,
/// `label`, `evaluations_per_step`, `evaluations`, `reference` and `summary`.
///
/// # Errors
/// Python allocation failures.
#[pyfunction]
pub fn methods(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    physicskit::classical::methods()
        .iter()
        .map(|m| {
            let d = PyDict::new(py);
            d.set_item("name", m.name)?;
            d.set_item("label", m.label)?;
            d.set_item("order", m.order)?;
            d.set_item("symplectic", m.symplectic)?;
            d.set_item("separable_only", m.separable_only)?;
            d.set_item("adaptive", m.is_adaptive())?;
            d.set_item("needs_taylor_form", m.needs_taylor_form())?;
            d.set_item("evaluations_per_step", m.evaluations_per_step)?;
            d.set_item("evaluations", m.evaluations)?;
            d.set_item("reference", m.reference)?;
            d.set_item("summary", m.summary)?;
            Ok(d)
        })
        .collect()
}

/// Registers `build`, `catalog` and `methods`.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(build, m)?)?;
    m.add_function(wrap_pyfunction!(catalog, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    Ok(())
}
