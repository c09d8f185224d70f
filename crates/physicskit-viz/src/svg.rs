//! SVG documents: plotters' [`SVGBackend`] draws a figure into a string, fragments this crate
//! writes itself (data series, legends, colour bars, heat-map images) are spliced in at the
//! place in the drawing order where they were made, and [`rasterize`] turns a document into
//! pixels with resvg and the bundled font (for GIF frames).
//!
//! A fragment is placed by drawing a marker text (a private-use character and its index) through
//! plotters, so it lands between whatever was drawn before and after it; `document` replaces
//! each marker by its fragment when the drawing is done.

use std::cell::RefCell;
use std::path::Path;
use std::sync::{Arc, OnceLock};

use plotters::prelude::*;
use resvg::{tiny_skia, usvg};

use crate::error::{DrawContext, Result, VizError};
use crate::figure::Area;
use crate::font::{ensure_registered, FAMILY};

/// The font stack of every text element: the bundled DejaVu Sans, which resvg and the layout
/// checks use; a browser without it falls back to a narrower sans-serif face, so nothing that
/// fits in DejaVu Sans overflows there.
pub const FONT_STACK: &str = "DejaVu Sans, Verdana, sans-serif";

/// The marker character that starts a placeholder text.
const MARKER: char = '\u{E000}';

thread_local! {
    /// Fragments of the document being drawn on this thread, by index.
    static FRAGMENTS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
    /// The next element id of the document being drawn.
    static NEXT_ID: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// A number unique within the document being drawn, for element ids (clip paths).
pub(crate) fn next_id() -> usize {
    NEXT_ID.with(|n| {
        let id = n.get();
        n.set(id + 1);
        id
    })
}

/// Places `fragment` (SVG elements in the figure's pixel coordinates) at this point of the
/// drawing order of the document [`document`] is drawing.
///
/// # Errors
/// [`VizError::Draw`] naming `path` if plotters fails to draw the marker.
pub(crate) fn place(area: &Area<'_>, fragment: String, path: &Path) -> Result<()> {
    let index = FRAGMENTS.with(|f| {
        let mut f = f.borrow_mut();
        f.push(fragment);
        f.len() - 1
    });
    area.draw(&Text::new(
        format!("{MARKER}{index}"),
        (0, 0),
        (FAMILY, 10).into_font().color(&BLACK),
    ))
    .at(path)
}

/// Draws a `size` document (white background) with `draw` and returns its SVG text, fragments
/// spliced in and the font stack set. `path` only names the file in errors.
///
/// # Errors
/// [`VizError::Draw`] if plotters fails, or whatever `draw` returns.
pub(crate) fn document<F>(path: &Path, size: (u32, u32), draw: F) -> Result<String>
where
    F: FnOnce(&Area<'_>) -> Result<()>,
{
    ensure_registered()?;
    FRAGMENTS.with(|f| f.borrow_mut().clear());
    NEXT_ID.with(|n| n.set(0));
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, size).into_drawing_area();
        root.fill(&WHITE).at(path)?;
        draw(&root)?;
        root.present().at(path)?;
    }
    let fragments = FRAGMENTS.with(|f| std::mem::take(&mut *f.borrow_mut()));
    Ok(splice(&buf, &fragments))
}

/// Replaces each marker text element of plotters' output by its fragment, and plotters' font
/// family by [`FONT_STACK`].
fn splice(svg: &str, fragments: &[String]) -> String {
    let family = format!("font-family=\"{FAMILY}\"");
    let stack = format!("font-family=\"{FONT_STACK}\"");
    let mut out =
        String::with_capacity(svg.len() + fragments.iter().map(String::len).sum::<usize>());
    let mut lines = svg.lines().peekable();
    while let Some(line) = lines.next() {
        if line.starts_with("<text ") {
            if let Some(next) = lines.peek() {
                if let Some(index) = next.strip_prefix(MARKER) {
                    if let Some(fragment) =
                        index.parse::<usize>().ok().and_then(|i| fragments.get(i))
                    {
                        out.push_str(fragment);
                        lines.next(); // the marker
                        lines.next(); // </text>
                        continue;
                    }
                }
            }
            out.push_str(&line.replace(&family, &stack));
            out.push('\n');
            // The content line: plotters escaped it; only the subscript markup is turned.
            if let Some(content) = lines.next() {
                out.push_str(&rich_escaped(content));
            }
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

/// [`rich`] of text that is already escaped.
fn rich_escaped(s: &str) -> String {
    if !s.contains("_{") {
        return s.to_string();
    }
    let mut out = String::with_capacity(s.len() + 64);
    let mut rest = s;
    while let Some(start) = rest.find("_{") {
        let Some(len) = rest[start + 2..].find('}') else {
            break;
        };
        out.push_str(&rest[..start]);
        out.push_str("<tspan baseline-shift=\"sub\" font-size=\"72%\">");
        out.push_str(&rest[start + 2..start + 2 + len]);
        out.push_str("</tspan>");
        rest = &rest[start + 2 + len + 1..];
    }
    out.push_str(rest);
    out
}

/// Writes a `size` SVG file drawn by `draw`.
///
/// # Errors
/// As [`document`], and [`VizError::Io`] if the file cannot be written.
pub(crate) fn save<F>(path: &Path, size: (u32, u32), draw: F) -> Result<()>
where
    F: FnOnce(&Area<'_>) -> Result<()>,
{
    let svg = document(path, size, draw)?;
    std::fs::write(path, svg).map_err(|source| VizError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// resvg's options: the bundled DejaVu Sans as the only font, also for the generic families.
pub fn options() -> &'static usvg::Options<'static> {
    static OPTIONS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        for face in [
            dejavu::sans::regular(),
            dejavu::sans::bold(),
            dejavu::sans::oblique(),
            dejavu::sans::bold_oblique(),
        ] {
            db.load_font_data(face.to_vec());
        }
        db.set_sans_serif_family("DejaVu Sans");
        db.set_serif_family("DejaVu Sans");
        db.set_monospace_family("DejaVu Sans");
        usvg::Options {
            font_family: "DejaVu Sans".into(),
            fontdb: Arc::new(db),
            image_href_resolver: usvg::ImageHrefResolver {
                resolve_data: Box::new(|_, data, options| png_as_svg(&data, options)),
                ..usvg::ImageHrefResolver::default()
            },
            ..usvg::Options::default()
        }
    })
}

/// An embedded PNG as an SVG image of one rectangle per run of equal pixels in a row,
/// without anti-aliasing (`crispEdges`, as the browser's `image-rendering: pixelated`).
///
/// resvg draws embedded raster images only with its `raster-images` feature, which brings
/// JPEG, WebP and GIF decoders; the gallery embeds one kind of raster, a heat map's PNG of
/// cells, which this decodes with the `png` crate already at hand. `None` (the image is left
/// out) for data that is no 8-bit RGB or RGBA PNG.
fn png_as_svg(data: &[u8], options: &usvg::Options) -> Option<usvg::ImageKind> {
    let mut reader = png::Decoder::new(data).read_info().ok()?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buf).ok()?;
    let channels = match (frame.color_type, frame.bit_depth) {
        (png::ColorType::Rgba, png::BitDepth::Eight) => 4,
        (png::ColorType::Rgb, png::BitDepth::Eight) => 3,
        _ => return None,
    };
    let (w, h) = (frame.width as usize, frame.height as usize);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" shape-rendering=\"crispEdges\">"
    );
    let pixel = |x: usize, y: usize| {
        let i = (y * w + x) * channels;
        let alpha = if channels == 4 { buf[i + 3] } else { 255 };
        (buf[i], buf[i + 1], buf[i + 2], alpha)
    };
    for y in 0..h {
        let mut x = 0;
        while x < w {
            let p = pixel(x, y);
            let mut end = x + 1;
            while end < w && pixel(end, y) == p {
                end += 1;
            }
            s.push_str(&format!(
                "<rect x=\"{x}\" y=\"{y}\" width=\"{}\" height=\"1\" fill=\"#{:02X}{:02X}{:02X}\" fill-opacity=\"{}\"/>",
                end - x,
                p.0,
                p.1,
                p.2,
                f32::from(p.3) / 255.0
            ));
            x = end;
        }
    }
    s.push_str("</svg>");
    usvg::Tree::from_str(&s, options)
        .ok()
        .map(usvg::ImageKind::SVG)
}

/// Parses an SVG document with [`options`].
///
/// # Errors
/// [`VizError::Draw`] naming `path` if the text is no valid SVG.
pub fn parse(svg: &str, path: &Path) -> Result<usvg::Tree> {
    usvg::Tree::from_str(svg, options()).at(path)
}

/// Renders an SVG document at `scale` device pixels per SVG pixel on white.
///
/// # Errors
/// [`VizError::Draw`] naming `path` if the SVG does not parse or the size is zero.
pub fn rasterize(svg: &str, scale: f32, path: &Path) -> Result<tiny_skia::Pixmap> {
    let tree = parse(svg, path)?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .ok_or_else(|| VizError::Draw {
            path: path.to_path_buf(),
            message: "empty figure".into(),
        })?;
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| VizError::Draw {
            path: path.to_path_buf(),
            message: "empty figure".into(),
        })?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

/// A number for an SVG attribute: two decimals (a hundredth of a pixel), no trailing zeros.
pub(crate) fn num(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// `#rrggbb` of a colour.
pub(crate) fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Escapes text for SVG/XML content and attributes.
pub(crate) fn escape(s: &str) -> String {
    crate::html::escape(s)
}

/// Standard base64 of `data` (for images embedded in a document).
pub(crate) fn base64(data: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Text content with subscripts: `_{max}` becomes a lowered, smaller `max` (`λ_{max}`), the
/// rest escaped.
pub(crate) fn rich(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(start) = rest.find("_{") {
        let Some(len) = rest[start + 2..].find('}') else {
            break;
        };
        out.push_str(&escape(&rest[..start]));
        out.push_str("<tspan baseline-shift=\"sub\" font-size=\"72%\">");
        out.push_str(&escape(&rest[start + 2..start + 2 + len]));
        out.push_str("</tspan>");
        rest = &rest[start + 2 + len + 1..];
    }
    out.push_str(&escape(rest));
    out
}

/// A text element turned a quarter counter-clockwise (reading upwards), centred on `(x, y)`
/// along its baseline.
pub(crate) fn text_rotated(x: f64, y: f64, size: f64, s: &str) -> String {
    format!(
        "<text x=\"{x}\" y=\"{y}\" transform=\"rotate(-90 {x} {y})\" font-family=\"{FONT_STACK}\" font-size=\"{}\" text-anchor=\"middle\" fill=\"#222222\">{}</text>\n",
        num(size),
        rich(s),
        x = num(x),
        y = num(y),
    )
}

/// A text element of this crate's own fragments. `anchor` is `start`, `middle` or `end`; `y`
/// is the baseline.
pub(crate) fn text(
    x: f64,
    y: f64,
    size: f64,
    bold: bool,
    anchor: &str,
    fill: &str,
    s: &str,
) -> String {
    format!(
        "<text x=\"{}\" y=\"{}\" font-family=\"{FONT_STACK}\" font-size=\"{}\"{} text-anchor=\"{anchor}\" fill=\"{fill}\">{}</text>\n",
        num(x),
        num(y),
        num(size),
        if bold { " font-weight=\"bold\"" } else { "" },
        rich(s)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fragments_land_where_they_were_placed() {
        let path = Path::new("test.svg");
        let svg = document(path, (200, 100), |root| {
            root.draw(&Rectangle::new([(0, 0), (10, 10)], RED.filled()))
                .at(path)?;
            place(root, "<g id=\"first\"/>\n".into(), path)?;
            root.draw(&Rectangle::new([(20, 0), (30, 10)], BLUE.filled()))
                .at(path)?;
            place(root, "<g id=\"second\"/>\n".into(), path)?;
            Ok(())
        })
        .unwrap();
        let red = svg.find("#FF0000").unwrap();
        let first = svg.find("id=\"first\"").unwrap();
        let blue = svg.find("#0000FF").unwrap();
        let second = svg.find("id=\"second\"").unwrap();
        assert!(red < first && first < blue && blue < second, "{svg}");
        assert!(!svg.contains(MARKER));
        // It is a document resvg reads and renders at twice the size.
        let pixmap = rasterize(&svg, 2.0, path).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), (400, 200));
    }

    #[test]
    fn subscripts_and_base64() {
        assert_eq!(
            rich("λ_{max} < 1"),
            "λ<tspan baseline-shift=\"sub\" font-size=\"72%\">max</tspan> &lt; 1"
        );
        assert_eq!(rich("a_b"), "a_b");
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
        assert_eq!(base64(b"M"), "TQ==");
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.256), "1.26");
        assert_eq!(num(-0.001), "0");
    }
}
