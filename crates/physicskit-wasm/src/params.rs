//! Parameters given as a JSON object, turned into catalogue [`Value`]s by each parameter's
//! kind; [`SystemEntry::values`](physicskit::classical::model::SystemEntry::values) then checks
//! ranges, lengths and unknown names, as for the command line and Python.

use physicskit::classical::model::entry::{ParamKind, Value};
use physicskit::classical::model::SystemEntry;
use serde_json::Value as Json;

/// The largest count the lab accepts: the parameter `n` (as the spec names every count of
/// masses, sites or members). A page stepping a state of `2 * 10^5` numbers a few hundred
/// times a frame is already slow, and a count of `10^12` from a hostile link would ask the
/// browser for terabytes (an allocation failure aborts the WebAssembly module, leaving a
/// dead page).
pub const MAX_LAB_COUNT: i64 = 100_000;

/// The parameter name of a count.
const COUNT: &str = "n";

/// The `(name, value)` pairs of the JSON object `text` for `entry`.
///
/// A number is read as the parameter's kind asks (an integer must be whole), an array as a
/// vector, a string as a choice; `null` leaves the parameter at its default. A name the entry
/// does not declare is passed on by its JSON type, for the catalogue to refuse by name.
///
/// # Errors
/// A message naming the parameter, for text that is not a JSON object, a value of the
/// wrong type, or a count `n` above [`MAX_LAB_COUNT`].
pub fn values_from_json(entry: &SystemEntry, text: &str) -> Result<Vec<(String, Value)>, String> {
    let json: Json =
        serde_json::from_str(text).map_err(|e| format!("parameters are not JSON: {e}"))?;
    let Json::Object(map) = json else {
        return Err("parameters must be a JSON object".into());
    };
    let mut out = Vec::with_capacity(map.len());
    for (name, value) in map {
        if value.is_null() {
            continue;
        }
        let kind = entry.param(&name).map(|spec| spec.kind);
        let converted = convert(&name, kind, &value)?;
        if let (COUNT, Value::Integer(n)) = (name.as_str(), &converted) {
            if *n > MAX_LAB_COUNT {
                return Err(format!(
                    "`{name}` = {n} is more than the lab runs (at most {MAX_LAB_COUNT})"
                ));
            }
        }
        out.push((name, converted));
    }
    Ok(out)
}

fn convert(name: &str, kind: Option<ParamKind>, value: &Json) -> Result<Value, String> {
    let wrong = |what: &str| format!("`{name}` must be {what}, got {value}");
    match (kind, value) {
        (Some(ParamKind::Integer), Json::Number(n)) => n
            .as_i64()
            .or_else(|| {
                // 3.0 from a slider is the integer 3; 3.5 is refused.
                n.as_f64()
                    .filter(|x| x.fract() == 0.0 && x.abs() < 9.0e15)
                    .map(|x| x as i64)
            })
            .map(Value::Integer)
            .ok_or_else(|| wrong("an integer")),
        (Some(ParamKind::Scalar) | None, Json::Number(n)) => n
            .as_f64()
            .map(Value::Scalar)
            .ok_or_else(|| wrong("a number")),
        (Some(ParamKind::Vector(_)) | None, Json::Array(items)) => items
            .iter()
            .map(Json::as_f64)
            .collect::<Option<Vec<f64>>>()
            .map(Value::Vector)
            .ok_or_else(|| wrong("an array of numbers")),
        (Some(ParamKind::Choice(_)) | None, Json::String(w)) => Ok(Value::Choice(w.clone())),
        (Some(k), _) => Err(wrong(&format!("a {}", k.name()))),
        (None, _) => Err(wrong("a number, an array of numbers or a word")),
    }
}
