//! GIF animations: each frame drawn with plotters into the GIF backend (looping forever).

use std::path::Path;

use plotters::prelude::*;

use crate::error::{DrawContext, Result};
use crate::figure::Area;
use crate::font::ensure_registered;

/// Writes an animated GIF of `frames` frames, `size` pixels, `delay_ms` per frame;
/// `draw(k, area)` draws frame `k` onto a white canvas.
///
/// Frames are quantized to 256 colours each by the `gif` encoder; keep `size` and `frames`
/// modest (the gallery uses at most about 480x360 and 120 frames) to keep files small.
///
/// # Errors
/// [`VizError::Draw`](crate::VizError::Draw) if the file cannot be created or encoded, or
/// whatever `draw` returns.
pub fn save_gif<F>(
    path: &Path,
    size: (u32, u32),
    frames: usize,
    delay_ms: u32,
    mut draw: F,
) -> Result<()>
where
    F: FnMut(usize, &Area<'_>) -> Result<()>,
{
    ensure_registered()?;
    let root = BitMapBackend::gif(path, size, delay_ms)
        .at(path)?
        .into_drawing_area();
    for k in 0..frames {
        root.fill(&WHITE).at(path)?;
        draw(k, &root)?;
        root.present().at(path)?;
    }
    Ok(())
}
