//! Text measured with the bundled font's own metrics (DejaVu Sans, [`crate::font`]): widths of
//! labels before they are drawn, so titles are wrapped to the figure and legend boxes fit their
//! entries. Widths are sums of glyph advances without kerning, which only ever tightens a pair:
//! the measured width is never short of what a browser or resvg sets in the same font.

use std::sync::OnceLock;

use ttf_parser::Face;

/// Line height as a multiple of the font size: DejaVu Sans' ascent plus descent is 1.164 em,
/// so lines of wrapped text 1.25 em apart never overlap.
pub const LINE_HEIGHT: f64 = 1.25;

fn face(bold: bool) -> Option<&'static Face<'static>> {
    static REGULAR: OnceLock<Option<Face<'static>>> = OnceLock::new();
    static BOLD: OnceLock<Option<Face<'static>>> = OnceLock::new();
    let (cell, data) = if bold {
        (&BOLD, dejavu::sans::bold())
    } else {
        (&REGULAR, dejavu::sans::regular())
    };
    cell.get_or_init(|| Face::parse(data, 0).ok()).as_ref()
}

/// Width in pixels of `s` set at `size` pixels (the CSS font-size) in DejaVu Sans.
///
/// A character the font lacks is counted as one em (browsers substitute another font's glyph,
/// rarely wider than that).
///
/// Subscript markup (`λ_{max}`, see [`crate::svg`]) counts its subscript at the size it is set.
pub fn width(s: &str, size: f64, bold: bool) -> f64 {
    if let Some(start) = s.find("_{") {
        if let Some(len) = s[start + 2..].find('}') {
            let end = start + 2 + len;
            return plain_width(&s[..start], size, bold)
                + plain_width(&s[start + 2..end], 0.72 * size, bold)
                + width(&s[end + 1..], size, bold);
        }
    }
    plain_width(s, size, bold)
}

fn plain_width(s: &str, size: f64, bold: bool) -> f64 {
    let Some(face) = face(bold) else {
        // The embedded font always parses; without it, a generous estimate.
        return s.chars().count() as f64 * size * 0.7;
    };
    let em = f64::from(face.units_per_em());
    let units: f64 = s
        .chars()
        .map(|c| {
            face.glyph_index(c)
                .and_then(|g| face.glyph_hor_advance(g))
                .map_or(em, f64::from)
        })
        .sum();
    units / em * size
}

/// Greedy word wrap of `s` into lines no wider than `max_width` pixels at `size`; a single word
/// wider than that gets a line of its own.
pub fn wrap(s: &str, size: f64, bold: bool, max_width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in s.split_whitespace() {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if line.is_empty() || width(&candidate, size, bold) <= max_width {
            line = candidate;
        } else {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widths_grow_with_text_and_size() {
        let a = width("Energy", 14.0, false);
        // DejaVu Sans averages about 0.6 em per lower-case letter: 6 letters at 14 px are
        // 40-60 px, so these bounds catch a unit error (em vs pixels) but not font details.
        assert!((40.0..60.0).contains(&a), "{a}");
        assert!(width("Energy", 28.0, false) > 1.99 * a);
        assert!(width("Energy", 14.0, true) > a);
        assert!(width("", 14.0, false).abs() < f64::EPSILON);
    }

    #[test]
    fn wrapping_respects_the_width() {
        let s = "Hénon–Heiles surface of section at E = 1/6 with every orbit coloured";
        let lines = wrap(s, 16.0, true, 200.0);
        assert!(lines.len() > 1);
        for l in &lines {
            assert!(width(l, 16.0, true) <= 200.0, "{l}");
        }
        assert_eq!(lines.join(" "), s);
    }
}
