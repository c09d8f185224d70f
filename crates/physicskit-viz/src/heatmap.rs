//! A space–time heat map: a field `u(x, t)` on a regular grid drawn as coloured cells
//! (viridis colour map) with a colour bar. Non-finite cells (outside a domain) are left blank.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;

use crate::error::{DrawContext, Result, VizError};
use crate::figure::{tick, Area, Chart};
use crate::font::{ensure_registered, FAMILY};

/// A field sampled on a regular `nx x ny` grid.
#[derive(Debug, Clone)]
pub struct HeatMap {
    /// Title above the map.
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
        ensure_registered()?;
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
        let (map_area, bar_area) = area.split_horizontally(w.saturating_sub(110));
        let dx = (self.x_range.1 - self.x_range.0) / self.nx.max(2).saturating_sub(1) as f64;
        let dy = (self.y_range.1 - self.y_range.0) / self.ny.max(2).saturating_sub(1) as f64;
        let xr = (self.x_range.0 - 0.5 * dx, self.x_range.1 + 0.5 * dx);
        let yr = (self.y_range.0 - 0.5 * dy, self.y_range.1 + 0.5 * dy);
        let mut chart = ChartBuilder::on(&map_area)
            .caption(&self.title, (FAMILY, 20).into_font().style(FontStyle::Bold))
            .margin(10)
            .x_label_area_size(48)
            .y_label_area_size(70)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .at(path)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FAMILY, 14))
            .axis_desc_style((FAMILY, 16))
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .at(path)?;
        let cells = (0..self.ny)
            .flat_map(|j| (0..self.nx).map(move |i| (i, j)))
            .filter(|&(i, j)| self.values[j * self.nx + i].is_finite());
        chart
            .draw_series(cells.map(|(i, j)| {
                let x = self.x_range.0 + i as f64 * dx;
                let y = self.y_range.0 + j as f64 * dy;
                let v = self.values[j * self.nx + i];
                let c = ViridisRGB::get_color_normalized(v, lo, hi);
                Rectangle::new(
                    [(x - 0.5 * dx, y - 0.5 * dy), (x + 0.5 * dx, y + 0.5 * dy)],
                    c.filled(),
                )
            }))
            .at(path)?;
        overlay(&mut chart)?;
        // Labels on the right of the bar, left-aligned: right-aligned on its left, their ends
        // ran past the label area (the font's width estimate is short) and were cut off.
        let mut bar = ChartBuilder::on(&bar_area)
            .margin_top(44)
            .margin_bottom(58)
            .margin_left(16)
            .margin_right(4)
            .right_y_label_area_size(72)
            .build_cartesian_2d(0.0..1.0, lo..hi)
            .at(path)?;
        let steps = 120;
        bar.draw_series((0..steps).map(|k| {
            let a = lo + (hi - lo) * k as f64 / steps as f64;
            let b = lo + (hi - lo) * (k + 1) as f64 / steps as f64;
            let c = ViridisRGB::get_color_normalized(0.5 * (a + b), lo, hi);
            Rectangle::new([(0.0, a), (1.0, b)], c.filled())
        }))
        .at(path)?;
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(&self.value_label)
            .label_style((FAMILY, 13))
            .axis_desc_style((FAMILY, 15))
            .y_label_formatter(&|v| tick(*v))
            .y_labels(6)
            .draw()
            .at(path)?;
        Ok(())
    }
}
