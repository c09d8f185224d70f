//! An NPZ archive of named f64 arrays, strings and catalogue values: the one NPZ writer of the
//! command line, used by the trajectory files ([`npz`](super::npz)), the analyses (`lyapunov`,
//! `poincare`, through [`analysis`](super::analysis)) and `physicskit ensemble`.

use std::fs::File;
use std::io::{self, BufWriter, Write};

use ndarray::ArrayViewD;
use physicskit::classical::model::Value;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::npy;

/// One entry of the archive.
#[derive(Debug)]
pub enum Entry<'a> {
    /// An f64 array of `shape` (C order).
    F64 {
        /// Entry name (without `.npy`).
        name: String,
        /// Shape.
        shape: Vec<usize>,
        /// Elements in C order.
        data: &'a [f64],
    },
    /// An f64 array of any layout (the strided `q` and `p` columns of a trajectory), written
    /// in C order without a copy.
    View {
        /// Entry name.
        name: String,
        /// The array.
        view: ArrayViewD<'a, f64>,
    },
    /// An i64 array of `shape` (C order): counts, such as the steps each ensemble member took.
    I64 {
        /// Entry name.
        name: String,
        /// Shape.
        shape: Vec<usize>,
        /// Elements in C order.
        data: Vec<i64>,
    },
    /// A 0-d string.
    Str {
        /// Entry name.
        name: String,
        /// The text.
        text: &'a str,
    },
    /// A catalogue value (a setting or parameter), as the trajectory files write it: `<f8`
    /// (0-d or 1-d), `<i8` for an integer, a string for a word.
    Value {
        /// Entry name.
        name: String,
        /// The value.
        value: &'a Value,
    },
}

/// Writes `entries` as an uncompressed NPZ, as `numpy.savez` would; zip64 when the arrays (not
/// the strings and values, which are small) exceed 2 GiB, as entries over 4 GiB need it and
/// numpy reads it.
///
/// # Errors
/// I/O errors.
pub fn write_npz(file: &File, entries: &[Entry<'_>]) -> io::Result<()> {
    let values: usize = entries
        .iter()
        .map(|e| match e {
            Entry::F64 { data, .. } => data.len(),
            Entry::View { view, .. } => view.len(),
            Entry::I64 { data, .. } => data.len(),
            Entry::Str { .. } | Entry::Value { .. } => 0,
        })
        .sum();
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(values * 8 > u32::MAX as usize / 2);
    let mut zip = ZipWriter::new(BufWriter::new(file));
    for e in entries {
        let name = match e {
            Entry::F64 { name, .. }
            | Entry::View { name, .. }
            | Entry::I64 { name, .. }
            | Entry::Str { name, .. }
            | Entry::Value { name, .. } => name,
        };
        zip.start_file(format!("{name}.npy"), options)
            .map_err(io::Error::other)?;
        match e {
            Entry::F64 { shape, data, .. } => npy::write_slice(&mut zip, shape, data)?,
            Entry::View { view, .. } => npy::write(&mut zip, view.view())?,
            Entry::I64 { shape, data, .. } => npy::write_slice(&mut zip, shape, data)?,
            Entry::Str { text, .. } => npy::write_str(&mut zip, text)?,
            Entry::Value { value, .. } => write_value(&mut zip, value)?,
        }
    }
    zip.finish().map_err(io::Error::other)?.flush()
}

/// One catalogue value as a 0-d or 1-d array: `<f8`, `<i8`, or a string for a word.
fn write_value(w: &mut impl Write, value: &Value) -> io::Result<()> {
    match value {
        Value::Scalar(v) => npy::write_slice(w, &[], std::slice::from_ref(v)),
        Value::Integer(n) => npy::write_slice(w, &[], std::slice::from_ref(n)),
        Value::Vector(items) => npy::write_slice(w, &[items.len()], items),
        Value::Choice(word) => npy::write_str(w, word),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::{Array0, Array1, Array2, ArrayD};
    use ndarray_npy::NpzReader;

    fn bits<'a>(v: impl IntoIterator<Item = &'a f64>) -> Vec<u64> {
        v.into_iter().map(|x| x.to_bits()).collect()
    }

    /// Every kind of entry read back by ndarray-npy with its name, shape and bits; a strided
    /// view (a transposed matrix, as the trajectory's `q` and `p` columns are strided) in its
    /// logical C order; values that are not round decimals, and the signed zero and NaN.
    #[test]
    fn every_entry_reads_back_bit_for_bit() {
        let data = [0.1, -0.0, f64::NAN, 1e-310, -2.5, f64::INFINITY];
        let matrix = ndarray::Array2::from_shape_vec((2, 3), data.to_vec()).unwrap();
        let transposed = matrix.t();
        let vector = Value::Vector(vec![1.0 / 3.0, 2.0]);
        let (scalar, integer) = (Value::Scalar(-7.25e-3), Value::Integer(-42));
        let word = Value::Choice("kink".into());
        let entries = [
            Entry::F64 {
                name: "a".into(),
                shape: vec![3, 2],
                data: &data,
            },
            Entry::View {
                name: "b".into(),
                view: transposed.into_dyn(),
            },
            Entry::I64 {
                name: "steps".into(),
                shape: vec![2],
                data: vec![1000, i64::MAX],
            },
            Entry::Str {
                name: "system".into(),
                text: "double-pendulum",
            },
            Entry::Value {
                name: "v".into(),
                value: &vector,
            },
            Entry::Value {
                name: "s".into(),
                value: &scalar,
            },
            Entry::Value {
                name: "i".into(),
                value: &integer,
            },
            Entry::Value {
                name: "w".into(),
                value: &word,
            },
        ];
        let file = tempfile::tempfile().unwrap();
        write_npz(&file, &entries).unwrap();
        let mut npz = NpzReader::new(file).unwrap();
        let mut names: Vec<String> = (npz.names().unwrap().iter())
            .map(|n| n.trim_end_matches(".npy").to_string())
            .collect();
        names.sort();
        assert_eq!(names, ["a", "b", "i", "s", "steps", "system", "v", "w"]);
        let a: Array2<f64> = npz.by_name("a.npy").unwrap();
        assert_eq!(a.shape(), [3, 2]);
        assert_eq!(bits(&a), bits(&data));
        let b: ArrayD<f64> = npz.by_name("b.npy").unwrap();
        assert_eq!(b.shape(), [3, 2]);
        assert_eq!(bits(&b), bits(&transposed.to_owned()));
        let steps: Array1<i64> = npz.by_name("steps.npy").unwrap();
        assert_eq!(steps.to_vec(), [1000, i64::MAX]);
        let v: Array1<f64> = npz.by_name("v.npy").unwrap();
        assert_eq!(bits(&v), bits(&[1.0 / 3.0, 2.0]));
        let s: Array0<f64> = npz.by_name("s.npy").unwrap();
        assert_eq!(s.into_scalar().to_bits(), (-7.25e-3_f64).to_bits());
        let i: Array0<i64> = npz.by_name("i.npy").unwrap();
        assert_eq!(i.into_scalar(), -42);
    }
}
