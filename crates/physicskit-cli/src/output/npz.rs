//! NPZ: a zip archive (stored, uncompressed) of NPY v1.0 arrays, as `numpy.savez` writes.
//!
//! Arrays: `t` (n,), `q` and `p` (n, ndof) or `y` (n, dim), `energy` (n,); 0-d arrays
//! `t0`, `t1`, `dt`; 0-d strings `system`, `family`, `method`; one `param_<name>` per given
//! parameter (`<f8` scalar or 1-d, `<i8` for integers, a string for choices; absent optional
//! parameters are omitted); scalar extra diagnostics as `extra_<name>`.

use std::fs::File;
use std::io::{self, BufWriter, Write};

use physicskit::classical::core::{Value, Values};
use physicskit::classical::ExtraValue;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::npy;
use super::Record;

pub(super) fn write(file: &File, record: &Record<'_>) -> io::Result<()> {
    let result = record.result;
    let state_values: usize = record.state_arrays().iter().map(|(_, a)| a.len()).sum();
    // Entries over 4 GiB need the zip64 extension, which numpy reads.
    let large = (state_values + 2 * result.t.len()) * 8 > u32::MAX as usize / 2;
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(large);
    let mut zip = ZipWriter::new(BufWriter::new(file));
    let entry = |zip: &mut ZipWriter<BufWriter<&File>>, name: &str| {
        zip.start_file(format!("{name}.npy"), options)
            .map_err(io::Error::other)
    };

    entry(&mut zip, "t")?;
    npy::write_f64(&mut zip, &[result.t.len()], result.t.iter().copied())?;
    for (name, array) in record.state_arrays() {
        entry(&mut zip, name)?;
        npy::write_f64(&mut zip, array.shape(), array.iter().copied())?;
    }
    if let Some(energy) = record.energy() {
        entry(&mut zip, "energy")?;
        npy::write_f64(&mut zip, &[energy.len()], energy.iter().copied())?;
    }
    for (name, value) in record.settings() {
        entry(&mut zip, name)?;
        npy::write_f64(&mut zip, &[], [value])?;
    }
    let texts = [
        ("system", record.system),
        ("family", record.family.name()),
        ("method", result.method.as_str()),
    ];
    write_labels(&mut zip, options, texts, record.params)?;
    for (name, value) in &result.extra {
        if let ExtraValue::Scalar(v) = value {
            entry(&mut zip, &format!("extra_{name}"))?;
            npy::write_f64(&mut zip, &[], [*v])?;
        }
    }
    let mut inner = zip.finish().map_err(io::Error::other)?;
    inner.flush()
}

/// The 0-d strings `texts`, then one `param_<name>` per given parameter.
pub(super) fn write_labels(
    zip: &mut ZipWriter<BufWriter<&File>>,
    options: SimpleFileOptions,
    texts: [(&str, &str); 3],
    params: &Values,
) -> io::Result<()> {
    for (name, text) in texts {
        zip.start_file(format!("{name}.npy"), options)
            .map_err(io::Error::other)?;
        npy::write_str(zip, text)?;
    }
    for (name, value) in params.iter() {
        if let Some(value) = value {
            zip.start_file(format!("param_{name}.npy"), options)
                .map_err(io::Error::other)?;
            write_value(zip, value)?;
        }
    }
    Ok(())
}

/// One catalogue value as a 0-d or 1-d array: `<f8`, `<i8`, or a string for a word.
pub(super) fn write_value(w: &mut impl Write, value: &Value) -> io::Result<()> {
    match value {
        Value::Scalar(v) => npy::write_f64(w, &[], [*v]),
        Value::Integer(n) => npy::write_i64(w, &[], [*n]),
        Value::Vector(items) => npy::write_f64(w, &[items.len()], items.iter().copied()),
        Value::Choice(word) => npy::write_str(w, word),
    }
}
