//! The bundled font: DejaVu Sans, embedded in the binary so no system font is needed.
//!
//! The TTF files come from the `dejavu` crate (version 2.37, which embeds them with
//! `include_bytes!`). DejaVu fonts are free software under the Bitstream Vera / Arev licence
//! (permissive: use, copy, embed and redistribute allowed); see `FONT-LICENSE.md` in this
//! crate. They are registered with plotters' `ab_glyph` text renderer (which measures text for
//! plotters' layout) as `DejaVu Sans` and under the generic family names; the SVG files name
//! the family (with fallbacks, [`crate::svg::FONT_STACK`]) and resvg is handed the same font
//! ([`crate::svg::options`]), so every raster uses it too.

use std::sync::OnceLock;

use plotters::style::FontStyle;

use crate::error::{Result, VizError};

/// The font family name used throughout the crate.
pub const FAMILY: &str = "DejaVu Sans";

/// Registers DejaVu Sans with plotters (once per process).
///
/// # Errors
/// [`VizError::Font`] if the embedded font cannot be parsed (it always can; this guards a
/// broken build).
pub fn ensure_registered() -> Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        let regular = dejavu::sans::regular();
        let bold = dejavu::sans::bold();
        let oblique = dejavu::sans::oblique();
        [FAMILY, "sans-serif", "serif", "monospace"]
            .iter()
            .all(|name| {
                plotters::style::register_font(name, FontStyle::Normal, regular).is_ok()
                    && plotters::style::register_font(name, FontStyle::Bold, bold).is_ok()
                    && plotters::style::register_font(name, FontStyle::Italic, oblique).is_ok()
                    && plotters::style::register_font(name, FontStyle::Oblique, oblique).is_ok()
            })
    });
    if ok {
        Ok(())
    } else {
        Err(VizError::Font)
    }
}
