//! NPY arrays (`numpy.lib.format`, version 1.0) written by ndarray-npy: `<f8` and `<i8`
//! arrays of any layout, and 0-d unicode strings `<U{n}` (the `system`, `family` and `method`
//! entries; none needs pickle, so `numpy.load(..., allow_pickle=False)` reads them).
//!
//! ndarray-npy writes numbers but has no string element type (its element types give their
//! dtype statically, and `<U{n}` depends on the text), so a string is ndarray-npy's header
//! for `<U{n}` followed by the text in UTF-32LE, padded with NULs to `n` characters.

use std::io::{self, BufWriter, Write};

use ndarray::ArrayViewD;
use ndarray_npy::npy::header::{Header, Layout};
use ndarray_npy::WriteNpyExt;
use py_literal::Value as PyValue;

/// Bytes buffered before each write to the sink: a strided array is written element by
/// element, and each write into a zip entry updates its checksum.
const CHUNK: usize = 1 << 16;

/// Writes an `f64` or `i64` array in C order (Fortran order if the view is laid out so).
///
/// # Errors
/// I/O errors of `w`.
pub fn write<A: ndarray_npy::WritableElement>(
    w: &mut impl Write,
    array: ArrayViewD<'_, A>,
) -> io::Result<()> {
    let mut buffered = BufWriter::with_capacity(CHUNK, w);
    array.write_npy(&mut buffered).map_err(io::Error::other)?;
    buffered.flush()
}

/// Writes the C-order elements `data` as an array of `shape`.
///
/// # Errors
/// I/O errors of `w`; `InvalidInput` if `data` does not hold `shape`'s element count.
pub fn write_slice<A: ndarray_npy::WritableElement>(
    w: &mut impl Write,
    shape: &[usize],
    data: &[A],
) -> io::Result<()> {
    let array = ArrayViewD::from_shape(shape, data).map_err(|_| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("array of shape {shape:?} given {} elements", data.len()),
        )
    })?;
    write(w, array)
}

/// Writes a 0-d unicode string array (dtype `<U{n}`, `n` = number of characters, at least 1).
///
/// # Errors
/// I/O errors of `w`.
pub fn write_str(w: &mut impl Write, s: &str) -> io::Result<()> {
    let n = s.chars().count().max(1);
    let header = Header {
        type_descriptor: PyValue::String(format!("<U{n}")),
        layout: Layout::Standard,
        shape: Vec::new(),
    };
    header.write(&mut *w).map_err(io::Error::other)?;
    let mut data: Vec<u8> = s.chars().flat_map(|c| u32::from(c).to_le_bytes()).collect();
    data.resize(4 * n, 0);
    w.write_all(&data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_count_is_checked() {
        let mut out = Vec::new();
        let err = write_slice(&mut out, &[2, 2], &[1.0, 2.0, 3.0]).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
    }

    /// The header is 64-byte aligned, names the dtype from the text's length, and the data is
    /// the text's code points in UTF-32LE, NUL-padded.
    #[test]
    fn strings_are_utf32() {
        for (text, n) in [("ab", 2), ("", 1), ("θ₁", 2)] {
            let mut out = Vec::new();
            write_str(&mut out, text).unwrap();
            let header_len = out.len() - 4 * n;
            assert_eq!(header_len % 64, 0);
            let header = std::str::from_utf8(&out[10..header_len]).unwrap();
            assert!(header.contains(&format!("'descr': '<U{n}'")), "{header}");
            assert!(header.contains("'shape': ()"), "{header}");
            let mut expected: Vec<u8> = text
                .chars()
                .flat_map(|c| (c as u32).to_le_bytes())
                .collect();
            expected.resize(4 * n, 0);
            assert_eq!(&out[header_len..], &expected[..]);
        }
    }
}
