//! A minimal writer of NPY format version 1.0 arrays (`numpy.lib.format`).
//!
//! Layout: the magic `\x93NUMPY`, version bytes `1, 0`, a little-endian `u16` header length,
//! then an ASCII Python dict literal `{'descr': ..., 'fortran_order': False, 'shape': (...), }`
//! padded with spaces and ending in `\n` so that the data starts on a 64-byte boundary, then
//! the raw little-endian data in C order. Only the dtypes the command line writes are
//! supported: `<f8`, `<i8` and unicode strings `<U{n}` (UTF-32LE), none of which need pickle,
//! so `numpy.load(..., allow_pickle=False)` reads them.
//!
//! Written here rather than by a crate: ndarray-npy writes no unicode strings (`<U{n}`: the
//! `system`, `family` and `method` entries), and npyz, which does, brings a second, older
//! `zip` and num-bigint into the tree; the archive itself is the `zip` crate's (`arrays.rs`).

use std::io::{self, Write};

/// Alignment of the data start recommended by the NPY format description.
const ALIGN: usize = 64;

/// Magic string plus version 1.0.
const MAGIC: &[u8; 8] = b"\x93NUMPY\x01\x00";

/// Bytes buffered before each write to the sink, to keep per-element writes cheap.
const CHUNK: usize = 1 << 16;

fn header(descr: &str, shape: &[usize]) -> io::Result<Vec<u8>> {
    let dims = match shape {
        [] => String::new(),
        [n] => format!("{n},"),
        _ => shape
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(", "),
    };
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': ({dims}), }}");
    // Magic (8) + length field (2) + dict + newline must be a multiple of ALIGN.
    let unpadded = MAGIC.len() + 2 + dict.len() + 1;
    dict.push_str(&" ".repeat(unpadded.next_multiple_of(ALIGN) - unpadded));
    dict.push('\n');
    let len = u16::try_from(dict.len())
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "NPY header too long"))?;
    let mut out = Vec::with_capacity(MAGIC.len() + 2 + dict.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&len.to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    Ok(out)
}

/// Writes an `f64` array of `shape` whose C-order elements are `data`.
///
/// # Errors
/// I/O errors of `w`; `InvalidInput` if `data` does not hold `shape`'s element count.
pub fn write_f64(
    w: &mut impl Write,
    shape: &[usize],
    data: impl IntoIterator<Item = f64>,
) -> io::Result<()> {
    write_le(w, "<f8", shape, data.into_iter().map(f64::to_le_bytes))
}

/// Writes an `i64` array of `shape` whose C-order elements are `data`.
///
/// # Errors
/// As [`write_f64`].
pub fn write_i64(
    w: &mut impl Write,
    shape: &[usize],
    data: impl IntoIterator<Item = i64>,
) -> io::Result<()> {
    write_le(w, "<i8", shape, data.into_iter().map(i64::to_le_bytes))
}

/// Writes a 0-d unicode string array (dtype `<U{n}`, `n` = number of characters).
///
/// # Errors
/// I/O errors of `w`.
pub fn write_str(w: &mut impl Write, s: &str) -> io::Result<()> {
    let n = s.chars().count().max(1);
    w.write_all(&header(&format!("<U{n}"), &[])?)?;
    let mut data: Vec<u8> = s.chars().flat_map(|c| u32::from(c).to_le_bytes()).collect();
    data.resize(4 * n, 0);
    w.write_all(&data)
}

fn write_le<const N: usize>(
    w: &mut impl Write,
    descr: &str,
    shape: &[usize],
    data: impl Iterator<Item = [u8; N]>,
) -> io::Result<()> {
    let expected: usize = shape.iter().product();
    w.write_all(&header(descr, shape)?)?;
    let mut buf = Vec::with_capacity(CHUNK);
    let mut count = 0usize;
    for bytes in data {
        buf.extend_from_slice(&bytes);
        count += 1;
        if buf.len() >= CHUNK {
            w.write_all(&buf)?;
            buf.clear();
        }
    }
    w.write_all(&buf)?;
    if count == expected {
        Ok(())
    } else {
        Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("array of shape {shape:?} given {count} elements"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_aligned_and_parsable() {
        for shape in [&[][..], &[3], &[4, 2], &[1, 2, 3]] {
            let h = header("<f8", shape).unwrap();
            assert_eq!(h.len() % ALIGN, 0);
            assert_eq!(&h[..8], MAGIC);
            let len = u16::from_le_bytes([h[8], h[9]]) as usize;
            assert_eq!(len + 10, h.len());
            let text = std::str::from_utf8(&h[10..]).unwrap();
            assert!(text.ends_with('\n'));
            assert!(text.starts_with("{'descr': '<f8'"));
        }
        let one = header("<f8", &[3]).unwrap();
        assert!(std::str::from_utf8(&one[10..])
            .unwrap()
            .contains("'shape': (3,)"));
        let zero = header("<f8", &[]).unwrap();
        assert!(std::str::from_utf8(&zero[10..])
            .unwrap()
            .contains("'shape': ()"));
    }

    #[test]
    fn element_count_is_checked() {
        let mut out = Vec::new();
        assert!(write_f64(&mut out, &[2, 2], [1.0, 2.0, 3.0]).is_err());
    }

    #[test]
    fn strings_are_utf32() {
        let mut out = Vec::new();
        write_str(&mut out, "ab").unwrap();
        let data = &out[out.len() - 8..];
        assert_eq!(data, &[b'a', 0, 0, 0, b'b', 0, 0, 0]);
    }
}
