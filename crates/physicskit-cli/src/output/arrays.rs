//! An NPZ archive of named f64 arrays, strings and catalogue values, for outputs that are not
//! one trajectory: `physicskit ensemble` and the analyses (`lyapunov`, `poincare`, through
//! [`analysis`](super::analysis)). The one NPZ writer of named entries.

use std::fs::File;
use std::io::{self, BufWriter, Write};

use physicskit::classical::core::Value;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::npy;
use super::npz::write_value;

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

/// Writes `entries` as an uncompressed NPZ, as `numpy.savez` would; zip64 when the f64 arrays
/// (not the strings and values, which are small) exceed 2 GiB, as entries over 4 GiB need it
/// and numpy reads it.
///
/// # Errors
/// I/O errors.
pub fn write_npz(file: &File, entries: &[Entry<'_>]) -> io::Result<()> {
    let values: usize = entries
        .iter()
        .map(|e| match e {
            Entry::F64 { data, .. } => data.len(),
            Entry::Str { .. } | Entry::Value { .. } => 0,
        })
        .sum();
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(values * 8 > u32::MAX as usize / 2);
    let mut zip = ZipWriter::new(BufWriter::new(file));
    for e in entries {
        let name = match e {
            Entry::F64 { name, .. } | Entry::Str { name, .. } | Entry::Value { name, .. } => name,
        };
        zip.start_file(format!("{name}.npy"), options)
            .map_err(io::Error::other)?;
        match e {
            Entry::F64 { shape, data, .. } => {
                npy::write_f64(&mut zip, shape, data.iter().copied())?
            }
            Entry::Str { text, .. } => npy::write_str(&mut zip, text)?,
            Entry::Value { value, .. } => write_value(&mut zip, value)?,
        }
    }
    zip.finish().map_err(io::Error::other)?.flush()
}
