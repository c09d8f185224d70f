//! Named arrays of an analysis (a Lyapunov spectrum, a Poincaré section), written in the three
//! formats as a trajectory is: the same settings, parameters and number text, so the files
//! read back to the same bits.
//!
//! - `.npz`: one array per name with its shape; each setting as a 0-d array (`<i8` for
//!   integers); `system`, `family`, `method` as 0-d strings; `param_<name>` per parameter.
//! - `.json`: one object: `system`, `family`, `method`, the settings, `"parameters": {..}`,
//!   then each array as a (nested) list.
//! - `.csv`: one row per entry of the row arrays (those whose first dimension is the length
//!   of `t`: columns `name` or `name_<j>`), then as constant columns the other arrays
//!   (`name_<i>`), the numeric settings and `param_<name>`.

use std::fs::File;
use std::io::{self, Write};

use ndarray::ArrayView2;
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

use physicskit::classical::integrators::Family;
use physicskit::classical::model::{Value, Values};

use super::arrays::{write_npz as write_npz_entries, Entry};
use super::csv;
use super::json::{self, Numbers, ParamValue, Parameters, Rows};
use super::number::push_f64;

/// One named array: C-order data and its shape (`[n]` or `[n, m]`).
#[derive(Debug, Clone)]
pub struct Named {
    /// Its name in the file.
    pub name: &'static str,
    /// Its shape.
    pub shape: Vec<usize>,
    /// Its elements in C order.
    pub data: Vec<f64>,
}

impl Named {
    /// A 1-d array.
    pub fn vector(name: &'static str, data: Vec<f64>) -> Self {
        Self {
            name,
            shape: vec![data.len()],
            data,
        }
    }

    /// An `(rows, data.len() / rows)` array; `cols` gives the width when `rows` is 0.
    pub fn matrix(name: &'static str, cols: usize, data: Vec<f64>) -> Self {
        Self {
            name,
            shape: vec![data.len() / cols.max(1), cols],
            data,
        }
    }

    fn width(&self) -> usize {
        self.shape.get(1).copied().unwrap_or(1)
    }
}

/// Everything written about one analysis.
#[derive(Debug)]
pub struct Arrays<'a> {
    /// Catalogue name of the system.
    pub system: &'a str,
    /// Its family.
    pub family: Family,
    /// The method's name.
    pub method: &'a str,
    /// The run's settings (`t0`, `t1`, `dt` and the analysis's own), by name.
    pub settings: Vec<(&'static str, Value)>,
    /// Every parameter with the value used.
    pub params: &'a Values,
    /// The results; the one named `t` gives the rows of the CSV.
    pub arrays: Vec<Named>,
}

impl Arrays<'_> {
    fn rows(&self) -> usize {
        self.arrays
            .iter()
            .find(|a| a.name == "t")
            .map_or(0, |a| a.shape[0])
    }

    fn texts(&self) -> [(&'static str, &str); 3] {
        [
            ("system", self.system),
            ("family", self.family.name()),
            ("method", self.method),
        ]
    }
}

/// The arrays, the settings, the texts and the given parameters, in that order.
pub(super) fn write_npz(file: &File, record: &Arrays<'_>) -> io::Result<()> {
    let arrays = record.arrays.iter().map(|a| Entry::F64 {
        name: a.name.into(),
        shape: a.shape.clone(),
        data: &a.data,
    });
    let settings = record.settings.iter().map(|(name, value)| Entry::Value {
        name: (*name).into(),
        value,
    });
    let texts = record.texts().into_iter().map(|(name, text)| Entry::Str {
        name: name.into(),
        text,
    });
    let params = record.params.iter().filter_map(|(name, value)| {
        value.map(|value| Entry::Value {
            name: format!("param_{name}"),
            value,
        })
    });
    let entries: Vec<Entry<'_>> = arrays.chain(settings).chain(texts).chain(params).collect();
    write_npz_entries(file, &entries)
}

/// The analysis document of the module docs, for [`json::write_document`].
struct Document<'a, 'r>(&'a Arrays<'r>);

impl Serialize for Document<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let record = self.0;
        let mut map = s.serialize_map(None)?;
        for (name, text) in record.texts() {
            map.serialize_entry(name, text)?;
        }
        for (name, value) in &record.settings {
            map.serialize_entry(name, &ParamValue(Some(value)))?;
        }
        map.serialize_entry("parameters", &Parameters(record.params))?;
        for a in &record.arrays {
            if a.shape.len() == 1 {
                map.serialize_entry(a.name, &Numbers(a.data.iter().copied()))?;
            } else {
                let rows = ArrayView2::from_shape((a.shape[0], a.width()), &a.data)
                    .map_err(serde::ser::Error::custom)?;
                map.serialize_entry(a.name, &Rows(rows))?;
            }
        }
        map.end()
    }
}

pub(super) fn write_json(w: &mut impl Write, record: &Arrays<'_>) -> io::Result<()> {
    json::write_document(w, &Document(record))
}

pub(super) fn write_csv(w: &mut impl Write, record: &Arrays<'_>) -> io::Result<()> {
    let rows = record.rows();
    let (columns, constants): (Vec<&Named>, Vec<&Named>) = record
        .arrays
        .iter()
        .partition(|a| a.shape[0] == rows && (a.shape.len() == 2 || a.name == "t"));
    let mut header = Vec::new();
    for a in &columns {
        match a.shape.len() {
            1 => header.push(a.name.to_string()),
            _ => header.extend((0..a.width()).map(|j| format!("{}_{j}", a.name))),
        }
    }
    let (mut names, mut values) = (Vec::new(), Vec::new());
    for a in &constants {
        for (i, v) in a.data.iter().enumerate() {
            names.push(format!("{}_{i}", a.name));
            values.push(*v);
        }
    }
    let settings = record.settings.iter().map(|(n, v)| (*n, Some(v)));
    csv::push_numeric("", settings, &mut names, &mut values);
    csv::push_numeric("param_", record.params.iter(), &mut names, &mut values);
    header.extend(names);
    w.write_all(header.join(",").as_bytes())?;
    w.write_all(b"\n")?;

    let mut tail = String::new();
    for &v in &values {
        tail.push(',');
        push_f64(&mut tail, v);
    }
    tail.push('\n');
    let mut row = String::new();
    for i in 0..rows {
        row.clear();
        for a in &columns {
            let width = a.width();
            for &x in &a.data[i * width..(i + 1) * width] {
                push_f64(&mut row, x);
                row.push(',');
            }
        }
        row.pop();
        row.push_str(&tail);
        w.write_all(row.as_bytes())?;
    }
    Ok(())
}
