//! Text form of an `f64` that parses back to the same bits.
//!
//! Rust's `Display` and `LowerExp` for `f64` print the shortest digit string that round-trips
//! exactly (Grisu/Ryu-style), so no precision is lost; this only picks the notation. `Display`
//! never uses an exponent, which would spell `1e-300` with 300 zeros, so very small and very
//! large magnitudes use `LowerExp`. A `.0` is added to integral values so that JSON readers
//! (Python's `json`) load every number as a float.

use std::fmt::Write;

/// Appends the shortest round-tripping text of `x` to `out`.
pub fn push_f64(out: &mut String, x: f64) {
    let start = out.len();
    let a = x.abs();
    // Between 1e-5 and 1e16 the positional form is at most ~22 characters.
    let positional = x == 0.0 || (1e-5..1e16).contains(&a) || !x.is_finite();
    // Writing into a String cannot fail.
    let _ = if positional {
        write!(out, "{x}")
    } else {
        write!(out, "{x:e}")
    };
    if x.is_finite() && !out[start..].contains(['.', 'e']) {
        out.push_str(".0");
    }
}

/// [`push_f64`] into a new string.
#[cfg(test)]
pub fn f64_text(x: f64) -> String {
    let mut s = String::new();
    push_f64(&mut s, x);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_bit_for_bit() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            0.1,
            1.0 / 3.0,
            1e-5,
            9.999_999_999_999_999e-6,
            1e16,
            -1e300,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            std::f64::consts::PI * 1e-200,
            123_456_789.012_345_68,
        ];
        for x in values {
            let s = f64_text(x);
            let back: f64 = s.parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:e} -> {s}");
            assert!(s.contains(['.', 'e']), "{s} would load as an integer");
            assert!(s.len() <= 24, "{s} is needlessly long");
        }
    }
}
