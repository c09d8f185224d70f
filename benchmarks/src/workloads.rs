//! The peer-comparison workloads through the Rust API: the peer's canonical cases, 10^5 steps
//! at the peer's dt, full trajectory and energy stored, from the peer's initial conditions.
//!
//! The cases are `peer/workloads.json`, the one table that `peer/workloads.py` reads too: each
//! names a system by its Python name (`"KeplerSystem.from_orbital_elements"`), which this side
//! builds through the catalogue entry of that name with the same keyword arguments, so the
//! Rust and the Python figures are of one workload.

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::entry::{ParamKind, Value};
use physicskit::classical::model::{DynSystem, SystemEntry};
use physicskit::classical::systems::{sine_mode, SineGordonChain};
use physicskit::classical::{IntegrateOptions, Method, Result, SimulationResult};
use serde_json::Value as Json;

/// The table, embedded when the crate is built.
const TABLE: &str = include_str!("../peer/workloads.json");

/// One benchmark case.
#[derive(Debug, Clone)]
pub struct Workload {
    /// Name shared with the Python comparison script.
    pub name: String,
    /// Integrator.
    pub method: Method,
    /// Step.
    pub dt: f64,
    entry: &'static SystemEntry,
    args: Vec<(String, Value)>,
}

impl Workload {
    /// The case's system at its initial condition.
    ///
    /// # Errors
    /// Whatever the catalogue refuses in the table's arguments.
    pub fn system(&self) -> Result<Box<dyn DynSystem>> {
        self.entry.build_from(self.args.iter().cloned())
    }

    /// Builds the system and runs `steps` steps of the case's step with its method.
    ///
    /// # Errors
    /// As [`run_with`](Self::run_with).
    pub fn run(&self, steps: usize) -> Result<SimulationResult> {
        self.run_with(steps, self.dt, self.method)
    }

    /// Builds the system and runs `steps` steps of `dt` with `method`, storing the whole
    /// trajectory and its energy.
    ///
    /// # Errors
    /// Whatever building or integrating returns.
    pub fn run_with(&self, steps: usize, dt: f64, method: Method) -> Result<SimulationResult> {
        let mut system = self.system()?;
        system.integrate(
            (0.0, steps as f64 * dt),
            dt,
            method,
            IntegrateOptions::default(),
        )
    }

    /// The initial `(q, p)` of a system with a `q`/`p` split (the plain loops' start), `None`
    /// for a first-order system.
    ///
    /// # Errors
    /// As [`system`](Self::system).
    pub fn start(&self) -> Result<Option<(Vec<f64>, Vec<f64>)>> {
        let system = self.system()?;
        let state = system.dynamical().state();
        Ok(system.ndof().map(|n| {
            let (q, p) = state.split_at(n);
            (q.to_vec(), p.to_vec())
        }))
    }
}

/// Every workload, in the table's order.
///
/// # Panics
/// If the embedded table is malformed (a case without its fields, a system or method no one
/// knows): a defect of the table that the crate's test catches, not an input.
pub fn all() -> Vec<Workload> {
    let table: Json = serde_json::from_str(TABLE).expect("peer/workloads.json is JSON");
    table["cases"]
        .as_array()
        .expect("peer/workloads.json has a list of cases")
        .iter()
        .map(|case| workload(case).unwrap_or_else(|e| panic!("peer/workloads.json: {e}")))
        .collect()
}

fn workload(case: &Json) -> std::result::Result<Workload, String> {
    let field = |key: &str| {
        case.get(key)
            .ok_or(format!("a case without `{key}`: {case}"))
    };
    let name = field("name")?
        .as_str()
        .ok_or("a name that is not a string")?;
    let system = field("system")?
        .as_str()
        .ok_or("a system that is not a string")?;
    let entry = SYSTEMS
        .iter()
        .copied()
        .find(|e| e.python == Some(system))
        .ok_or(format!(
            "{name}: no catalogue entry has the Python name {system}"
        ))?;
    let method = field("method")?
        .as_str()
        .and_then(|m| m.parse::<Method>().ok())
        .ok_or(format!("{name}: an unknown method"))?;
    let dt = field("dt")?
        .as_f64()
        .ok_or(format!("{name}: dt is not a number"))?;
    let args = field("args")?
        .as_object()
        .ok_or(format!("{name}: args is not an object"))?
        .iter()
        .map(|(key, value)| {
            let kind = entry.param(key).map(|p| p.kind);
            argument(kind, value)
                .map(|v| (key.clone(), v))
                .map_err(|e| format!("{name}: `{key}`: {e}"))
        })
        .collect::<std::result::Result<_, _>>()?;
    Ok(Workload {
        name: name.into(),
        method,
        dt,
        entry,
        args,
    })
}

/// A table argument as the catalogue takes it: a number by the parameter's kind, an array as a
/// vector, or one of the table's two generated starts (see its `about`).
fn argument(kind: Option<ParamKind>, value: &Json) -> std::result::Result<Value, String> {
    let number = |key: &str, of: &Json| of[key].as_f64().ok_or(format!("`{key}` is not a number"));
    match value {
        Json::Number(x) if kind == Some(ParamKind::Integer) => x
            .as_i64()
            .map(Value::Integer)
            .ok_or("not an integer".into()),
        Json::Number(x) => x.as_f64().map(Value::Scalar).ok_or("not a number".into()),
        Json::Array(items) => items
            .iter()
            .map(Json::as_f64)
            .collect::<Option<Vec<f64>>>()
            .map(Value::Vector)
            .ok_or("not an array of numbers".into()),
        Json::Object(start) if start.contains_key("sine_mode") => {
            let mode = &start["sine_mode"];
            let n = number("n", mode)? as usize;
            let index = mode["mode"]
                .as_u64()
                .ok_or("`mode` is not a non-negative integer")?;
            let amplitude = number("amplitude", mode)?;
            Ok(Value::Vector(sine_mode(n, index as usize, amplitude)))
        }
        Json::Object(start) if start.contains_key("kink") => {
            let kink = &start["kink"];
            let or =
                |key: &str, default: f64| kink.get(key).map_or(Ok(default), |_| number(key, kink));
            let (q0, p0) = SineGordonChain::kink(
                number("n", kink)? as usize,
                number("center", kink)?,
                or("width", 1.0)?,
                or("velocity", 0.0)?,
                or("polarity", 1.0)? as i32,
            )
            .map_err(|e| e.to_string())?;
            match start.get("part").and_then(Json::as_u64) {
                Some(0) => Ok(Value::Vector(q0)),
                Some(1) => Ok(Value::Vector(p0)),
                _ => Err("a kink start needs `part`: 0 (q0) or 1 (p0)".into()),
            }
        }
        other => Err(format!(
            "{other} is not a number, an array or a known start"
        )),
    }
}
