//! An NPZ archive of named f64 arrays and strings, for outputs that are not one trajectory
//! (`physicskit ensemble`).

use std::fs::File;
use std::io::{self, BufWriter, Write};

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
    /// A 0-d string.
    Str {
        /// Entry name.
        name: String,
        /// The text.
        text: &'a str,
    },
}

/// Writes `entries` as an uncompressed NPZ (zip64 when large), as `numpy.savez` would.
///
/// # Errors
/// I/O errors.
pub fn write_npz(file: &File, entries: &[Entry<'_>]) -> io::Result<()> {
    let values: usize = entries
        .iter()
        .map(|e| match e {
            Entry::F64 { data, .. } => data.len(),
            Entry::Str { .. } => 0,
        })
        .sum();
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(values * 8 > u32::MAX as usize / 2);
    let mut zip = ZipWriter::new(BufWriter::new(file));
    for e in entries {
        let name = match e {
            Entry::F64 { name, .. } | Entry::Str { name, .. } => name,
        };
        zip.start_file(format!("{name}.npy"), options)
            .map_err(io::Error::other)?;
        match e {
            Entry::F64 { shape, data, .. } => {
                npy::write_f64(&mut zip, shape, data.iter().copied())?
            }
            Entry::Str { text, .. } => npy::write_str(&mut zip, text)?,
        }
    }
    zip.finish().map_err(io::Error::other)?.flush()
}
