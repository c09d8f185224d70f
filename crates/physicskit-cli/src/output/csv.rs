//! CSV: a header row, then one row per sample, nothing else, so that `pandas.read_csv`,
//! `numpy.genfromtxt(names=True)`, `numpy.loadtxt(skiprows=1)` and spreadsheets read it with
//! their defaults.
//!
//! Columns: `t`, `q_0..`, `p_0..` (or `y_0..` for ODE systems), `energy`, then the run's
//! numbers as constant columns: `dt` and `param_<name>` for every numeric parameter
//! (`param_<name>_<i>` for list entries). Text (system, method, choice parameters) has no
//! place in an all-numeric table; `.json` and `.npz` carry it.

use std::io::{self, Write};

use physicskit::classical::model::Value;

use super::number::push_f64;
use super::Record;

/// The constant trailing columns: names and values.
fn constants(record: &Record<'_>) -> (Vec<String>, Vec<f64>) {
    let mut names = vec!["dt".to_string()];
    let mut values = vec![record.dt];
    push_numeric("param_", record.params.iter(), &mut names, &mut values);
    (names, values)
}

/// Appends the numeric values among `items` as columns `<prefix><name>` (`<prefix><name>_<i>`
/// for list entries); text has no place in a numeric table.
pub(super) fn push_numeric<'n, 'v>(
    prefix: &str,
    items: impl Iterator<Item = (&'n str, Option<&'v Value>)>,
    names: &mut Vec<String>,
    values: &mut Vec<f64>,
) {
    for (name, value) in items {
        match value {
            Some(Value::Scalar(v)) => {
                names.push(format!("{prefix}{name}"));
                values.push(*v);
            }
            Some(Value::Integer(n)) => {
                names.push(format!("{prefix}{name}"));
                // Integers are sizes, seeds and mode numbers, far below 2^53: exact as f64.
                values.push(*n as f64);
            }
            Some(Value::Vector(items)) => {
                for (i, v) in items.iter().enumerate() {
                    names.push(format!("{prefix}{name}_{i}"));
                    values.push(*v);
                }
            }
            Some(Value::Choice(_)) | None => {}
        }
    }
}

pub(super) fn write(w: &mut impl Write, record: &Record<'_>) -> io::Result<()> {
    let result = record.result;
    let states = record.state_arrays();
    let energy = record.energy();
    let (const_names, const_values) = constants(record);

    let mut header = String::from("t");
    for (name, array) in &states {
        for j in 0..array.ncols() {
            header.push_str(&format!(",{name}_{j}"));
        }
    }
    if energy.is_some() {
        header.push_str(",energy");
    }
    for name in &const_names {
        header.push(',');
        header.push_str(name);
    }
    header.push('\n');
    w.write_all(header.as_bytes())?;

    let mut tail = String::new();
    for &v in &const_values {
        tail.push(',');
        push_f64(&mut tail, v);
    }
    tail.push('\n');

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
        row.push_str(&tail);
        w.write_all(row.as_bytes())?;
    }
    Ok(())
}
