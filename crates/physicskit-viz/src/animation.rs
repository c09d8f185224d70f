//! GIF animations: each frame drawn as an SVG document (the same drawing as the static figures),
//! rendered by resvg at a chosen density ([`SCALE`] in the gallery, 1 in its quick mode), and
//! quantized into a GIF that loops forever.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use crate::error::{DrawContext, Result, VizError};
use crate::figure::Area;
use crate::svg;

/// Device pixels per figure pixel of every frame: the GIF is twice the figure's size, shown at
/// the figure's size on the page (crisp on high-density screens).
pub const SCALE: f32 = 2.0;

/// NeuQuant's sampling factor when quantizing a frame to 256 colours (1 best, 30 fastest):
/// 10 is the gif crate's recommendation for a good palette at a moderate cost.
const QUANT_SPEED: i32 = 10;

/// Writes an animated GIF of `frames` frames of a `size`-pixel figure rendered at `scale`
/// device pixels per figure pixel (the GIF is `scale` times larger: [`SCALE`] for a page, 1
/// where speed matters more than crispness), `delay_ms` per frame; `draw(k, area)` draws frame
/// `k` onto a white canvas.
///
/// Keep `size` and `frames` modest (the gallery uses at most about 760x380 and 120 frames) to
/// keep files small.
///
/// # Errors
/// [`VizError::Draw`] if the file cannot be created or encoded, or whatever `draw` returns.
pub fn save_gif<F>(
    path: &Path,
    size: (u32, u32),
    scale: f32,
    frames: usize,
    delay_ms: u32,
    mut draw: F,
) -> Result<()>
where
    F: FnMut(usize, &Area<'_>) -> Result<()>,
{
    let file = File::create(path).map_err(|source| VizError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let (w, h) = (
        (size.0 as f32 * scale).round() as u16,
        (size.1 as f32 * scale).round() as u16,
    );
    let mut encoder = gif::Encoder::new(BufWriter::new(file), w, h, &[]).at(path)?;
    encoder.set_repeat(gif::Repeat::Infinite).at(path)?;
    for k in 0..frames {
        let doc = svg::document(path, size, |root| draw(k, root))?;
        let pixmap = svg::rasterize(&doc, scale, path)?;
        // The canvas is opaque white, so premultiplied RGBA is plain RGBA.
        let mut rgba = pixmap.take();
        let mut frame = gif::Frame::from_rgba_speed(w, h, &mut rgba, QUANT_SPEED);
        frame.delay = (delay_ms / 10).min(u32::from(u16::MAX)) as u16;
        encoder.write_frame(&frame).at(path)?;
    }
    Ok(())
}
