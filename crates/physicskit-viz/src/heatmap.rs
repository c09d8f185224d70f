//! A heat map: a field `u(x, y)` on a regular grid drawn as an image of coloured cells (viridis)
//! with a colour bar. The cells are one embedded PNG of one pixel per cell, scaled without
//! smoothing (a vector file of one rectangle per cell would weigh megabytes); the axes, ticks,
//! labels and the colour bar are vector. Non-finite cells (outside a domain) are left blank.

use std::path::Path;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;

use crate::error::{DrawContext, Result, VizError};
use crate::figure::{tick, title_lines, title_svg, Area, Chart, Mapping, TITLE_SIZE};
use crate::font::FAMILY;
use crate::svg::{self, hex, num};
use crate::text;

/// A field sampled on a regular `nx x ny` grid.
#[derive(Debug, Clone)]
pub struct HeatMap {
    /// Title above the map (wrapped to its width).
    pub title: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Label of the colour bar (the field and its unit).
    pub value_label: String,
    /// Cell centres span `x_range` ...
    pub x_range: (f64, f64),
    /// ... and `y_range`.
    pub y_range: (f64, f64),
    /// Number of cells along x.
    pub nx: usize,
    /// Number of cells along y.
    pub ny: usize,
    /// Values, row-major: row `j` (y index) holds `nx` values; a non-finite value is left
    /// blank.
    pub values: Vec<f64>,
}

/// Tick label size (as in [`crate::figure`]: plotters' 16 is 12.9 px in the SVG).
const TICK_PX: f64 = 16.0 / 1.24;
/// Axis label size.
const DESC_PX: f64 = 18.0 / 1.24;

impl HeatMap {
    /// Draws the map into `area`: the map on the left, the colour bar on the right.
    ///
    /// # Errors
    /// [`VizError::Draw`] if the grid does not match the values or plotters fails.
    pub fn draw(&self, area: &Area<'_>, path: &Path) -> Result<()> {
        self.draw_with(area, path, |_| Ok(()))
    }

    /// [`draw`](Self::draw), then `overlay` on the map's chart (data coordinates), e.g. a
    /// contour line.
    ///
    /// # Errors
    /// As [`draw`](Self::draw), and what `overlay` returns.
    pub fn draw_with<'b>(
        &self,
        area: &Area<'b>,
        path: &Path,
        overlay: impl FnOnce(&mut Chart<'_, 'b>) -> Result<()>,
    ) -> Result<()> {
        if self.nx == 0 || self.ny == 0 || self.values.len() != self.nx * self.ny {
            return Err(VizError::Draw {
                path: path.to_path_buf(),
                message: format!(
                    "heat map grid {}x{} does not match {} values",
                    self.nx,
                    self.ny,
                    self.values.len()
                ),
            });
        }
        let (lo, hi) = self
            .values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let (lo, hi) = if lo < hi {
            (lo, hi)
        } else {
            (lo - 1.0, lo + 1.0)
        };
        let (w, _) = area.dim_in_pixel();
        let (ox, oy) = area.get_base_pixel();
        let (lines, top) = title_lines(&self.title, TITLE_SIZE, f64::from(w) - 16.0);
        if !lines.is_empty() {
            svg::place(
                area,
                title_svg(
                    &lines,
                    TITLE_SIZE,
                    f64::from(ox) + 0.5 * f64::from(w),
                    f64::from(oy) + 6.0,
                ),
                path,
            )?;
        }
        // The colour bar's ticks decide its width: gap, bar, tick, label, gap, rotated label.
        let bar_ticks: Vec<f64> = RangedCoordf64::from(lo..hi).key_points(6);
        let widest = bar_ticks
            .iter()
            .map(|v| text::width(&tick(*v), TICK_PX, false))
            .fold(0.0, f64::max);
        let bar_gap = 16.0;
        let bar_w = 16.0;
        let bar_total = bar_gap + bar_w + 4.0 + 4.0 + widest + 10.0 + DESC_PX * text::LINE_HEIGHT;

        let dx = (self.x_range.1 - self.x_range.0) / self.nx.max(2).saturating_sub(1) as f64;
        let dy = (self.y_range.1 - self.y_range.0) / self.ny.max(2).saturating_sub(1) as f64;
        let xr = (self.x_range.0 - 0.5 * dx, self.x_range.1 + 0.5 * dx);
        let yr = (self.y_range.0 - 0.5 * dy, self.y_range.1 + 0.5 * dy);
        let y_ticks = RangedCoordf64::from(yr.0..yr.1)
            .key_points(7)
            .iter()
            .map(|v| text::width(&tick(*v), TICK_PX, false))
            .fold(0.0, f64::max);
        let x_area = 14.0 + TICK_PX * 1.2 + DESC_PX * text::LINE_HEIGHT;
        let y_area = 14.0 + y_ticks + 8.0 + DESC_PX * text::LINE_HEIGHT;
        let mut chart = ChartBuilder::on(area)
            // The top tick labels reach half a line above the plot: keep them off the title.
            .margin_top((top + 10.0).ceil() as u32)
            .margin_bottom(10)
            .margin_left(6)
            .margin_right((10.0 + bar_total).ceil() as u32)
            .x_label_area_size(x_area.ceil() as u32)
            .y_label_area_size(y_area.ceil() as u32)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .at(path)?;
        let mapping = Mapping::of(&chart, xr, yr);
        let plot = mapping.plot();
        svg::place(area, self.image_svg(plot, lo, hi, path)?, path)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FAMILY, 16))
            .axis_desc_style((FAMILY, 18))
            .axis_style(RGBColor(90, 90, 90))
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .at(path)?;
        overlay(&mut chart)?;

        // The colour bar: a gradient the height of the map, ticks and labels 4 px off its
        // right edge, the label of the field beyond the widest tick label.
        let x0 = plot.x1 + bar_gap;
        let id = svg::next_id();
        let mut s =
            format!("<defs><linearGradient id=\"pkbar{id}\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">");
        for k in 0..=10 {
            let f = f64::from(k) / 10.0;
            let c = ViridisRGB::get_color_normalized(f, 0.0, 1.0);
            s.push_str(&format!(
                "<stop offset=\"{}\" stop-color=\"{}\"/>",
                num(f),
                hex(c)
            ));
        }
        s.push_str("</linearGradient></defs>\n<g class=\"pk-colorbar\">\n");
        s.push_str(&format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{bar_w}\" height=\"{}\" fill=\"url(#pkbar{id})\" stroke=\"#5A5A5A\" stroke-width=\"1\"/>\n",
            num(x0),
            num(plot.y0),
            num(plot.y1 - plot.y0)
        ));
        for v in &bar_ticks {
            let y = plot.y1 - (v - lo) / (hi - lo) * (plot.y1 - plot.y0);
            s.push_str(&format!(
                "<path d=\"M{} {}h4\" stroke=\"#5A5A5A\" stroke-width=\"1\"/>\n",
                num(x0 + bar_w),
                num(y)
            ));
            s.push_str(&svg::text(
                x0 + bar_w + 8.0,
                y + 0.36 * TICK_PX,
                TICK_PX,
                false,
                "start",
                "#222222",
                &tick(*v),
            ));
        }
        let lx = x0 + bar_w + 8.0 + widest + 10.0 + 0.93 * DESC_PX;
        let ly = 0.5 * (plot.y0 + plot.y1);
        s.push_str(&svg::text_rotated(lx, ly, DESC_PX, &self.value_label));
        s.push_str("</g>\n");
        svg::place(area, s, path)
    }

    /// The cells as an `<image>` covering `plot`: an embedded PNG, one pixel per cell, row 0
    /// at the top (largest y), blank cells transparent.
    fn image_svg(
        &self,
        plot: crate::figure::Rect,
        lo: f64,
        hi: f64,
        path: &Path,
    ) -> Result<String> {
        let mut rgba = Vec::with_capacity(self.nx * self.ny * 4);
        for r in 0..self.ny {
            let j = self.ny - 1 - r;
            for i in 0..self.nx {
                let v = self.values[j * self.nx + i];
                if v.is_finite() {
                    let c = ViridisRGB::get_color_normalized(v, lo, hi);
                    rgba.extend_from_slice(&[c.0, c.1, c.2, 255]);
                } else {
                    rgba.extend_from_slice(&[0, 0, 0, 0]);
                }
            }
        }
        let mut png = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut png, self.nx as u32, self.ny as u32);
            enc.set_color(png::ColorType::Rgba);
            enc.set_depth(png::BitDepth::Eight);
            let mut writer = enc.write_header().at(path)?;
            writer.write_image_data(&rgba).at(path)?;
        }
        Ok(format!(
            "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{}\"/>\n",
            num(plot.x0),
            num(plot.y0),
            num(plot.x1 - plot.x0),
            num(plot.y1 - plot.y0),
            svg::base64(&png)
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number after `name="` in the first `<image` element of `svg`.
    fn image_attr(svg: &str, name: &str) -> f64 {
        let image = &svg[svg.find("<image ").expect("an <image> element")..];
        let from = image.find(&format!(" {name}=\"")).expect(name) + name.len() + 3;
        let len = image[from..].find('"').unwrap();
        image[from..from + len].parse().unwrap()
    }

    /// A map rasterized by resvg (as GIF frames and any PNG are made) shows its cells: the
    /// centre of every cell of a 4 x 3 map with twelve different values has the cell's
    /// viridis colour, so twelve different colours and none of them the white canvas.
    #[test]
    fn cells_appear_in_the_raster() {
        let (nx, ny) = (4, 3);
        let map = HeatMap {
            title: "cells".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            value_label: "u".into(),
            x_range: (0.0, 3.0),
            y_range: (0.0, 2.0),
            nx,
            ny,
            values: (0..nx * ny).map(|k| k as f64).collect(),
        };
        let path = Path::new("cells.svg");
        let doc = svg::document(path, (500, 400), |root| map.draw(root, path)).unwrap();
        let scale = 2.0;
        let pixmap = svg::rasterize(&doc, scale, path).unwrap();
        let (x0, y0) = (image_attr(&doc, "x"), image_attr(&doc, "y"));
        let (w, h) = (image_attr(&doc, "width"), image_attr(&doc, "height"));
        let mut seen = Vec::new();
        for row in 0..ny {
            for i in 0..nx {
                let px = (x0 + (i as f64 + 0.5) * w / nx as f64) * f64::from(scale);
                let py = (y0 + (row as f64 + 0.5) * h / ny as f64) * f64::from(scale);
                let c = pixmap.pixel(px as u32, py as u32).unwrap();
                let rgb = (c.red(), c.green(), c.blue());
                // Row 0 of the image is the top row, the largest y index.
                let v = map.values[(ny - 1 - row) * nx + i];
                let want = ViridisRGB::get_color_normalized(v, 0.0, (nx * ny - 1) as f64);
                assert_eq!(rgb, (want.0, want.1, want.2), "cell ({i}, {row})");
                seen.push(rgb);
            }
        }
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), nx * ny);
        assert!(!seen.contains(&(255, 255, 255)));
    }
}
