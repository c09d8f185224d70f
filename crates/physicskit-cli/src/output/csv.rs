//! CSV: `#` comment lines with the settings and parameters (skipped by `numpy.loadtxt`,
//! `numpy.genfromtxt` and `pandas.read_csv(comment="#")`), then a header row
//! `t,q_0,..,p_0,..,energy` (or `y_0,..` for ODE systems), then one row per sample.

use std::io::{self, Write};

use super::number::push_f64;
use super::Record;
use crate::registry::Value;

pub(super) fn write(w: &mut impl Write, record: &Record<'_>) -> io::Result<()> {
    let result = record.result;
    let mut line = format!(
        "# physicskit simulate {} (family {}, method {})\n#",
        record.system,
        record.family.name(),
        result.method
    );
    for (name, value) in record.settings() {
        line.push_str(&format!(" {name}="));
        push_f64(&mut line, value);
    }
    line.push_str("\n# parameters:");
    for (name, value) in record.params.iter() {
        line.push_str(&format!(" {name}="));
        push_value(&mut line, value);
    }
    line.push('\n');
    w.write_all(line.as_bytes())?;

    let states = record.state_arrays();
    let energy = record.energy();
    let mut header = String::from("t");
    for (name, array) in &states {
        for j in 0..array.ncols() {
            header.push_str(&format!(",{name}_{j}"));
        }
    }
    if energy.is_some() {
        header.push_str(",energy");
    }
    header.push('\n');
    w.write_all(header.as_bytes())?;

    let mut row = String::new();
    for (i, &t) in result.t.iter().enumerate() {
        row.clear();
        push_f64(&mut row, t);
        for (_, array) in &states {
            for &x in array.row(i) {
                row.push(',');
                push_f64(&mut row, x);
            }
        }
        if let Some(e) = energy {
            row.push(',');
            push_f64(&mut row, e[i]);
        }
        row.push('\n');
        w.write_all(row.as_bytes())?;
    }
    Ok(())
}

/// Parameter text in the form the command line accepts back (`1.5`, `0.1;0.2` for lists,
/// since commas separate columns), `none` when absent.
fn push_value(out: &mut String, value: &Value) {
    match value {
        Value::Real(v) => push_f64(out, *v),
        Value::Count(n) => out.push_str(&n.to_string()),
        Value::List(items) => {
            for (k, &v) in items.iter().enumerate() {
                if k > 0 {
                    out.push(';');
                }
                push_f64(out, v);
            }
        }
        Value::Choice(word) => out.push_str(word),
        Value::Absent => out.push_str("none"),
    }
}
