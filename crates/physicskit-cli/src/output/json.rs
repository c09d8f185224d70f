//! JSON: one object `{"system", "family", "method", "t0", "t1", "dt", "parameters": {..},
//! "extra": {..} (the library's scalar diagnostics), "t": [..], "q": [[..], ..], "p": [[..], ..] (or "y"), "energy": [..]}`, streamed so a long
//! trajectory is never held twice in memory. Absent optional parameters are `null`.

use std::io::{self, Write};

use physicskit::classical::model::{Value, Values};
use physicskit::classical::ExtraValue;

use super::number::push_f64;
use super::Record;

pub(super) fn write(w: &mut impl Write, record: &Record<'_>) -> io::Result<()> {
    let result = record.result;
    let mut s = String::from("{\n");
    s.push_str(&format!("  \"system\": {},\n", quote(record.system)));
    s.push_str(&format!("  \"family\": {},\n", quote(record.family.name())));
    s.push_str(&format!("  \"method\": {},\n", quote(&result.method)));
    for (name, value) in record.settings() {
        s.push_str(&format!("  \"{name}\": "));
        push_f64(&mut s, value);
        s.push_str(",\n");
    }
    push_parameters(&mut s, record.params);
    s.push_str(",\n  \"extra\": {");
    let scalars = result.extra.iter().filter_map(|(name, value)| match value {
        ExtraValue::Scalar(v) => Some((name, *v)),
        ExtraValue::Array(_) => None,
    });
    for (k, (name, value)) in scalars.enumerate() {
        s.push_str(if k == 0 { "\n    " } else { ",\n    " });
        s.push_str(&quote(name));
        s.push_str(": ");
        push_f64(&mut s, value);
    }
    s.push_str("\n  },\n  \"t\": ");
    push_list(&mut s, result.t.iter().copied());
    w.write_all(s.as_bytes())?;

    for (name, array) in record.state_arrays() {
        w.write_all(format!(",\n  \"{name}\": [").as_bytes())?;
        for (i, row) in array.rows().into_iter().enumerate() {
            s.clear();
            s.push_str(if i == 0 { "\n    " } else { ",\n    " });
            push_list(&mut s, row.iter().copied());
            w.write_all(s.as_bytes())?;
        }
        w.write_all(b"\n  ]")?;
    }
    if let Some(energy) = record.energy() {
        s.clear();
        s.push_str(",\n  \"energy\": ");
        push_list(&mut s, energy.iter().copied());
        w.write_all(s.as_bytes())?;
    }
    w.write_all(b"\n}\n")
}

/// `"parameters": {..}` (without a trailing comma or newline).
pub(super) fn push_parameters(s: &mut String, params: &Values) {
    s.push_str("  \"parameters\": {");
    for (k, (name, value)) in params.iter().enumerate() {
        s.push_str(if k == 0 { "\n    " } else { ",\n    " });
        s.push_str(&quote(name));
        s.push_str(": ");
        push_value(s, value);
    }
    s.push_str("\n  }");
}

pub(super) fn push_list(out: &mut String, items: impl Iterator<Item = f64>) {
    out.push('[');
    for (k, v) in items.enumerate() {
        if k > 0 {
            out.push_str(", ");
        }
        push_f64(out, v);
    }
    out.push(']');
}

pub(super) fn push_value(out: &mut String, value: Option<&Value>) {
    match value {
        Some(Value::Scalar(v)) => push_f64(out, *v),
        Some(Value::Integer(n)) => out.push_str(&n.to_string()),
        Some(Value::Vector(items)) => push_list(out, items.iter().copied()),
        Some(Value::Choice(word)) => out.push_str(&quote(word)),
        None => out.push_str("null"),
    }
}

/// A JSON string literal. Names here come from the catalogue, but escaping keeps the output
/// valid whatever they hold.
pub(super) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if u32::from(c) < 0x20 => out.push_str(&format!("\\u{:04x}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::quote;

    #[test]
    fn strings_are_escaped() {
        assert_eq!(quote("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\"");
    }
}
