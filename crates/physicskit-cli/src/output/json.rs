//! JSON, written by serde_json: one object `{"system", "family", "method", "t0", "t1", "dt",
//! "parameters": {..}, "extra": {..} (the library's scalar diagnostics), "t": [..], "q":
//! [[..], ..], "p": [[..], ..] (or "y"), "energy": [..]}`, streamed row by row so a long
//! trajectory is never held twice in memory. Absent optional parameters are `null`.
//!
//! The layout is [`Layout`]'s: one member per line, indented two spaces a level; a list of
//! numbers on one line (`[0.5, 1.0]`), a list of lists one row per line; every number in the
//! shortest text that reads back to its bits ([`push_f64`]).

use std::io::{self, Write};

use ndarray::ArrayView2;
use physicskit::classical::model::{Value, Values};
use physicskit::classical::ExtraValue;
use serde::ser::{SerializeMap, SerializeSeq, Serializer};
use serde::Serialize;
use serde_json::ser::Formatter;

use super::number::push_f64;
use super::Record;

/// The command line's JSON layout, as a serde_json [`Formatter`] (see the module docs).
#[derive(Debug, Default)]
pub(super) struct Layout {
    /// The open containers, outermost first.
    open: Vec<Open>,
}

#[derive(Debug)]
struct Open {
    array: bool,
    /// An array whose elements are arrays: one per line.
    rows: bool,
    /// The next array element's separator, written with the element once its kind is known:
    /// `Some(true)` before the first.
    pending: Option<bool>,
}

impl Layout {
    fn indent(w: &mut (impl ?Sized + Write), depth: usize) -> io::Result<()> {
        w.write_all(b"\n")?;
        w.write_all(&b"  ".repeat(depth))
    }

    /// Writes the separator of a scalar array element, if one is pending.
    fn scalar(&mut self, w: &mut (impl ?Sized + Write)) -> io::Result<()> {
        if let Some(open) = self.open.last_mut() {
            if let Some(first) = open.pending.take() {
                if !first {
                    w.write_all(b", ")?;
                }
            }
        }
        Ok(())
    }
}

impl Formatter for Layout {
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let depth = self.open.len();
        if let Some(parent) = self.open.last_mut() {
            if let Some(first) = parent.pending.take() {
                parent.rows = true;
                if !first {
                    w.write_all(b",")?;
                }
                Self::indent(w, depth)?;
            }
        }
        self.open.push(Open {
            array: true,
            rows: false,
            pending: None,
        });
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let closed = self.open.pop();
        if closed.is_some_and(|c| c.rows) {
            Self::indent(w, self.open.len())?;
        }
        w.write_all(b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, _: &mut W, first: bool) -> io::Result<()> {
        if let Some(open) = self.open.last_mut() {
            open.pending = Some(first);
        }
        Ok(())
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, _: &mut W) -> io::Result<()> {
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.scalar(w)?;
        self.open.push(Open {
            array: false,
            rows: false,
            pending: None,
        });
        w.write_all(b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open.pop();
        Self::indent(w, self.open.len())?;
        w.write_all(b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if !first {
            w.write_all(b",")?;
        }
        Self::indent(w, self.open.len())
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn write_null<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.scalar(w)?;
        w.write_all(b"null")
    }

    fn write_bool<W: ?Sized + Write>(&mut self, w: &mut W, value: bool) -> io::Result<()> {
        self.scalar(w)?;
        w.write_all(if value { b"true" } else { b"false" })
    }

    fn write_i64<W: ?Sized + Write>(&mut self, w: &mut W, value: i64) -> io::Result<()> {
        self.scalar(w)?;
        write!(w, "{value}")
    }

    fn write_u64<W: ?Sized + Write>(&mut self, w: &mut W, value: u64) -> io::Result<()> {
        self.scalar(w)?;
        write!(w, "{value}")
    }

    fn write_f64<W: ?Sized + Write>(&mut self, w: &mut W, value: f64) -> io::Result<()> {
        self.scalar(w)?;
        let mut text = String::with_capacity(24);
        push_f64(&mut text, value);
        w.write_all(text.as_bytes())
    }

    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        // Keys are strings too; only an array element has a pending separator.
        if self.open.last().is_some_and(|o| o.array) {
            self.scalar(w)?;
        }
        w.write_all(b"\"")
    }
}

/// Serializes `value` to `w` in the [`Layout`], then a newline.
pub(super) fn write_document(w: &mut impl Write, value: &impl Serialize) -> io::Result<()> {
    let mut serializer = serde_json::Serializer::with_formatter(&mut *w, Layout::default());
    value.serialize(&mut serializer).map_err(io::Error::other)?;
    w.write_all(b"\n")
}

/// A parameter's value as JSON (`null` when absent).
pub(super) struct ParamValue<'a>(pub Option<&'a Value>);

impl Serialize for ParamValue<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            Some(Value::Scalar(v)) => s.serialize_f64(*v),
            Some(Value::Integer(n)) => s.serialize_i64(*n),
            Some(Value::Vector(items)) => items.serialize(s),
            Some(Value::Choice(word)) => s.serialize_str(word),
            None => s.serialize_none(),
        }
    }
}

/// `{"name": value, ..}` of every parameter, in the catalogue's order.
pub(super) struct Parameters<'a>(pub &'a Values);

impl Serialize for Parameters<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for (name, value) in self.0.iter() {
            map.serialize_entry(name, &ParamValue(value))?;
        }
        map.end()
    }
}

/// A 2-d array as a list of rows, read in place.
pub(super) struct Rows<'a>(pub ArrayView2<'a, f64>);

impl Serialize for Rows<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.nrows()))?;
        for row in self.0.rows() {
            seq.serialize_element(&Numbers(row.iter().copied()))?;
        }
        seq.end()
    }
}

/// Numbers from an iterator, as one list, without collecting them.
pub(super) struct Numbers<I>(pub I);

impl<I: Iterator<Item = f64> + Clone> Serialize for Numbers<I> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.clone())
    }
}

/// The trajectory document of the module docs.
struct Trajectory<'a, 'r>(&'a Record<'r>);

impl Serialize for Trajectory<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let record = self.0;
        let result = record.result;
        let mut map = s.serialize_map(None)?;
        map.serialize_entry("system", record.system)?;
        map.serialize_entry("family", record.family.name())?;
        map.serialize_entry("method", &result.method)?;
        for (name, value) in record.settings() {
            map.serialize_entry(name, &value)?;
        }
        map.serialize_entry("parameters", &Parameters(record.params))?;
        map.serialize_entry("extra", &Extra(&result.extra))?;
        map.serialize_entry("t", &Numbers(result.t.iter().copied()))?;
        for (name, array) in record.state_arrays() {
            map.serialize_entry(name, &Rows(array))?;
        }
        if let Some(energy) = record.energy() {
            map.serialize_entry("energy", &Numbers(energy.iter().copied()))?;
        }
        map.end()
    }
}

/// The scalar diagnostics of a run, by name.
struct Extra<'a>(&'a std::collections::BTreeMap<String, ExtraValue>);

impl Serialize for Extra<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for (name, value) in self.0 {
            if let ExtraValue::Scalar(v) = value {
                map.serialize_entry(name, v)?;
            }
        }
        map.end()
    }
}

pub(super) fn write(w: &mut impl Write, record: &Record<'_>) -> io::Result<()> {
    write_document(w, &Trajectory(record))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn text(value: &impl Serialize) -> String {
        let mut out = Vec::new();
        write_document(&mut out, value).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn members_on_lines_numbers_inline_rows_on_lines() {
        let doc = json!({"a": "x\"y\n", "n": null, "v": [0.5, 1.0], "m": [[1.0, 2.0], [3.0, 4.0]],
                         "o": {"k": 7}, "e": {}});
        assert_eq!(
            text(&doc),
            "{\n  \"a\": \"x\\\"y\\n\",\n  \"e\": {\n  },\n  \"m\": [\n    [1.0, 2.0],\n    \
             [3.0, 4.0]\n  ],\n  \"n\": null,\n  \"o\": {\n    \"k\": 7\n  },\n  \"v\": [0.5, 1.0]\n}\n"
        );
    }

    #[test]
    fn numbers_read_back_to_their_bits() {
        let values = [0.1, -0.0, 1e-300, 5e-324, f64::MAX, 1.0 / 3.0, 1e16, 123.0];
        let back: Vec<f64> = serde_json::from_str(&text(&values.to_vec())).unwrap();
        for (a, b) in values.iter().zip(&back) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a:e}");
        }
    }
}
