//! GIF animations: each frame drawn as an SVG document (the same drawing as the static figures),
//! rendered by resvg at a chosen density ([`SCALE`] in the gallery, 1 in its quick mode), and
//! indexed into one palette shared by the whole GIF, which loops forever.
//!
//! The palette is learnt once per GIF by NeuQuant from a few frames spread over the run
//! (`PALETTE_FRAMES`): the frames of one animation are the same figure with its bodies moved,
//! so they share their colours, and learning a palette is the costliest part of quantizing a
//! frame (benchmarks/README.md, "Gallery render"). Frames are rasterized, indexed and LZW-compressed in parallel, a few at a
//! time, and written in order, so the file does not depend on the number of threads.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use color_quant::NeuQuant;
use rayon::prelude::*;

use crate::error::{DrawContext, Result, VizError};
use crate::figure::Area;
use crate::svg;

/// Device pixels per figure pixel of every frame: the GIF is twice the figure's size, shown at
/// the figure's size on the page (crisp on high-density screens).
pub const SCALE: f32 = 2.0;

/// NeuQuant's sampling factor when learning the palette (1 best, 30 fastest): 10 is the gif
/// crate's recommendation for a good palette at a moderate cost.
const QUANT_SPEED: i32 = 10;

/// How many frames, spread evenly from the first to the last, the palette is learnt from: the
/// colours of the drawing (axes, text, each body's colour and their anti-aliased edges over
/// white) are in every frame, and the first and last frames show where the motion starts and
/// ends up.
const PALETTE_FRAMES: usize = 4;

/// Frames rasterized at once: enough to keep every core busy, few enough that their pixels
/// (up to 1520x760x4 bytes each) stay small in memory.
const BATCH: usize = 8;

/// Writes an animated GIF of `frames` frames of a `size`-pixel figure rendered at `scale`
/// device pixels per figure pixel (the GIF is `scale` times larger: [`SCALE`] for a page, 1
/// where speed matters more than crispness), `delay_ms` per frame; `draw(k, area)` draws frame
/// `k` onto a white canvas, called once per frame in order.
///
/// Keep `size` and `frames` modest (the gallery uses at most about 760x380 and 140 frames) to
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
    // The drawing keeps per-document state on this thread, so the documents are drawn here, in
    // order; rasterizing them is independent per frame.
    let docs = (0..frames)
        .map(|k| svg::document(path, size, |root| draw(k, root)))
        .collect::<Result<Vec<String>>>()?;
    let (w, h) = (
        (size.0 as f32 * scale).round() as u16,
        (size.1 as f32 * scale).round() as u16,
    );
    let rgba = |doc: &String| svg::rasterize(doc, scale, path).map(|p| p.take());

    let samples: Vec<usize> = match frames {
        0 => Vec::new(),
        1 => vec![0],
        n => {
            let m = PALETTE_FRAMES.min(n);
            (0..m).map(|i| i * (n - 1) / (m - 1)).collect()
        }
    };
    let learnt = samples
        .par_iter()
        .map(|&k| rgba(&docs[k]))
        .collect::<Result<Vec<Vec<u8>>>>()?
        .concat();
    // An empty GIF (no frames) still gets a valid one-colour palette.
    let quant = NeuQuant::new(
        QUANT_SPEED,
        256,
        if learnt.is_empty() {
            &[255; 4]
        } else {
            &learnt
        },
    );
    drop(learnt);

    let file = File::create(path).map_err(|source| VizError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mut encoder =
        gif::Encoder::new(BufWriter::new(file), w, h, &quant.color_map_rgb()).at(path)?;
    encoder.set_repeat(gif::Repeat::Infinite).at(path)?;
    let delay = (delay_ms / 10).min(u32::from(u16::MAX)) as u16;
    for batch in docs.chunks(BATCH) {
        let encoded = batch
            .par_iter()
            .map(|doc| {
                let pixels = rgba(doc)?;
                let mut frame =
                    gif::Frame::from_indexed_pixels(w, h, &index(&quant, &pixels), None);
                frame.delay = delay;
                frame.make_lzw_pre_encoded();
                Ok(frame)
            })
            .collect::<Result<Vec<gif::Frame<'static>>>>()?;
        for frame in &encoded {
            encoder.write_lzw_pre_encoded_frame(frame).at(path)?;
        }
    }
    Ok(())
}

/// The palette index of every pixel of an opaque RGBA image (resvg's premultiplied RGBA on an
/// opaque white canvas is plain RGBA). A pixel equal to the one before it takes its index without
/// a search: most of a frame is runs of background.
fn index(quant: &NeuQuant, rgba: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(rgba.len() / 4);
    let mut last: Option<(&[u8], u8)> = None;
    for px in rgba.chunks_exact(4) {
        let i = match last {
            Some((p, i)) if p == px => i,
            _ => {
                // 256 colours: every index fits in a byte.
                let i = quant.index_of(px) as u8;
                last = Some((px, i));
                i
            }
        };
        out.push(i);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;

    /// A small animation (a red disk crossing a blue line, a caption) as GIF bytes, rendered on
    /// a pool of `threads` threads, and its frames' documents.
    fn render(threads: usize, dir: &Path) -> (Vec<u8>, Vec<String>) {
        let path = dir.join(format!("anim-{threads}.gif"));
        let size = (160, 90);
        let frames = 11;
        let draw = |k: usize, root: &Area<'_>| -> Result<()> {
            let x = 10 + 14 * k as i32;
            root.draw(&PathElement::new(
                vec![(0, 70), (160, 20)],
                BLUE.stroke_width(2),
            ))
            .at(&path)?;
            root.draw(&Circle::new((x, 45), 12, RED.filled()))
                .at(&path)?;
            root.draw(&Text::new(format!("t = {k}"), (5, 5), ("sans-serif", 14)))
                .at(&path)
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| save_gif(&path, size, 1.0, frames, 80, draw))
            .unwrap();
        let docs = (0..frames)
            .map(|k| svg::document(&path, size, |root| draw(k, root)).unwrap())
            .collect();
        (std::fs::read(&path).unwrap(), docs)
    }

    #[test]
    fn frames_share_one_palette_and_do_not_depend_on_the_threads() {
        let dir = std::env::temp_dir().join(format!("physicskit-viz-anim-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (one, docs) = render(1, &dir);
        let (three, _) = render(3, &dir);
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(one == three, "the GIF differs between 1 and 3 threads");

        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = opts.read_info(one.as_slice()).unwrap();
        assert!(decoder.global_palette().is_some(), "no global palette");
        let mut k = 0;
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            assert!(
                frame.palette.is_none(),
                "frame {k} has a palette of its own"
            );
            let want = svg::rasterize(&docs[k], 1.0, Path::new("frame"))
                .unwrap()
                .take();
            let got = &frame.buffer;
            assert_eq!(got.len(), want.len(), "frame {k}");
            let err = got
                .iter()
                .zip(&want)
                .map(|(a, b)| f64::from(a.abs_diff(*b)))
                .sum::<f64>()
                / want.len() as f64;
            // A few hundred anti-aliased colours in 256 entries: NeuQuant's palette is off by
            // well under one level per channel on average; a frame indexed into the wrong
            // colours, or a body whose colour the palette missed, is off by tens of levels on
            // its pixels, several levels on average.
            assert!(err < 1.5, "frame {k}: mean channel error {err}");
            k += 1;
        }
        assert_eq!(k, docs.len(), "frames");
    }
}
