//! Figure helpers: a [`Panel`] of [`Series`] (lines, dashed lines, points) with title, axis
//! labels (with units), legend and automatic ranges, drawn into any region of a bitmap; and
//! [`save_png`] to lay out several panels in one PNG file.

use std::path::Path;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::{DrawContext, Result};
use crate::font::{ensure_registered, FAMILY};

/// A chart on linear `f64` axes drawn into a bitmap.
pub type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A region of a bitmap.
pub type Area<'b> = DrawingArea<BitMapBackend<'b>, Shift>;

/// Colours of successive series: a colour-blind-friendly palette (Okabe & Ito, 2008).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

/// The `i`-th palette colour (cycling).
pub fn color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Colours after the palette's eight, for figures with more series (the work–precision
/// diagrams have a line per method): dark red, purple, brown and grey, each far from the
/// palette's colours and from each other.
const BEYOND_PALETTE: [RGBColor; 4] = [
    RGBColor(153, 0, 0),
    RGBColor(110, 60, 170),
    RGBColor(140, 90, 40),
    RGBColor(120, 120, 120),
];

/// The `i`-th colour of the palette followed by the four `BEYOND_PALETTE` colours (cycling after
/// twelve): distinct colours for up to twelve series.
pub fn color_of_many(i: usize) -> RGBColor {
    let i = i % (PALETTE.len() + BEYOND_PALETTE.len());
    if i < PALETTE.len() {
        PALETTE[i]
    } else {
        BEYOND_PALETTE[i - PALETTE.len()]
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark {
    /// A solid polyline of the given width in pixels.
    Line(u32),
    /// A dashed polyline of the given width.
    Dashed(u32),
    /// Filled dots of the given radius in pixels.
    Dots(u32),
}

/// One data series of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry; `None` keeps it out of the legend.
    pub label: Option<String>,
    /// Points `(x, y)`; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBAColor,
    /// Line or dots.
    pub mark: Mark,
}

impl Series {
    /// A solid 2-pixel line.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>, color: RGBColor) -> Self {
        Self {
            label: Some(label.into()),
            points,
            color: color.to_rgba(),
            mark: Mark::Line(2),
        }
    }

    /// Dots of radius 1 pixel (for Poincaré sections and clouds).
    pub fn dots(label: impl Into<String>, points: Vec<(f64, f64)>, color: RGBColor) -> Self {
        Self {
            label: Some(label.into()),
            points,
            color: color.to_rgba(),
            mark: Mark::Dots(1),
        }
    }

    /// From separate `x` and `y` slices.
    pub fn xy(label: impl Into<String>, x: &[f64], y: &[f64], color: RGBColor) -> Self {
        Self::line(
            label,
            x.iter().copied().zip(y.iter().copied()).collect(),
            color,
        )
    }

    /// The same series without a legend entry.
    pub fn unlabeled(mut self) -> Self {
        self.label = None;
        self
    }

    /// The same series drawn with `mark`.
    pub fn with_mark(mut self, mark: Mark) -> Self {
        self.mark = mark;
        self
    }

    /// The same series with transparency `alpha` (0 transparent, 1 opaque).
    pub fn with_alpha(mut self, alpha: f64) -> Self {
        self.color.3 = alpha;
        self
    }
}

/// Where the legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Upper right corner.
    #[default]
    UpperRight,
    /// Upper left corner.
    UpperLeft,
    /// Lower right corner.
    LowerRight,
    /// Lower left corner.
    LowerLeft,
    /// No legend.
    None,
}

/// One chart: title, axis labels with units, ranges and series.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Title above the chart.
    pub title: String,
    /// x-axis label, with unit, e.g. `"t (s)"`.
    pub x_label: String,
    /// y-axis label, with unit.
    pub y_label: String,
    /// x range; `None` fits the data with a 3 % margin.
    pub x_range: Option<(f64, f64)>,
    /// y range; `None` fits the data with a 5 % margin.
    pub y_range: Option<(f64, f64)>,
    /// The data.
    pub series: Vec<Series>,
    /// Legend position.
    pub legend: Legend,
    /// Make one unit on x as long as one unit on y (for orbits and shapes), by widening the
    /// shorter range.
    pub equal_aspect: bool,
}

impl Panel {
    /// A panel with a title and axis labels and no data yet.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            ..Self::default()
        }
    }

    /// Adds a series.
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Sets the x range.
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }

    /// Sets the y range.
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }

    /// Sets the legend position.
    pub fn legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// Equal scales on both axes.
    pub fn equal_aspect(mut self) -> Self {
        self.equal_aspect = true;
        self
    }

    /// The ranges the panel will use.
    fn ranges(&self, pixel_aspect: f64) -> ((f64, f64), (f64, f64)) {
        let pts = || {
            self.series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|p| p.0.is_finite() && p.1.is_finite())
        };
        let fit = |vals: &mut dyn Iterator<Item = f64>, pad: f64| {
            let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
            padded(lo, hi, pad)
        };
        let mut xr = self
            .x_range
            .unwrap_or_else(|| fit(&mut pts().map(|p| p.0), 0.03));
        let mut yr = self
            .y_range
            .unwrap_or_else(|| fit(&mut pts().map(|p| p.1), 0.05));
        if self.equal_aspect {
            // Units per pixel must agree: widen whichever axis is tighter.
            let (wx, wy) = (xr.1 - xr.0, yr.1 - yr.0);
            if wx / wy < pixel_aspect {
                let c = 0.5 * (xr.0 + xr.1);
                let half = 0.5 * wy * pixel_aspect;
                xr = (c - half, c + half);
            } else {
                let c = 0.5 * (yr.0 + yr.1);
                let half = 0.5 * wx / pixel_aspect;
                yr = (c - half, c + half);
            }
        }
        (xr, yr)
    }

    /// Draws the panel into `area` and returns the chart, for extra drawing in data
    /// coordinates.
    ///
    /// # Errors
    /// [`VizError::Draw`](crate::VizError::Draw) naming `path` if plotters fails.
    pub fn draw<'a, 'b>(&self, area: &'a Area<'b>, path: &Path) -> Result<Chart<'a, 'b>> {
        ensure_registered()?;
        let (w, h) = area.dim_in_pixel();
        let label_x = 48;
        let label_y = 78;
        let title_h = if self.title.is_empty() { 8 } else { 34 };
        // Plot area size in pixels, for equal aspect.
        let pw = (w as f64 - label_y as f64 - 20.0).max(10.0);
        let ph = (h as f64 - label_x as f64 - title_h as f64 - 10.0).max(10.0);
        let (xr, yr) = self.ranges(pw / ph);
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(10)
            .margin_right(20)
            .x_label_area_size(label_x)
            .y_label_area_size(label_y);
        if !self.title.is_empty() {
            builder.caption(&self.title, (FAMILY, 20).into_font().style(FontStyle::Bold));
        }
        let mut chart = builder
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .at(path)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FAMILY, 14))
            .axis_desc_style((FAMILY, 16))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(215, 215, 215))
            .x_labels(7)
            .y_labels(7)
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .at(path)?;
        let mut any_label = false;
        for s in &self.series {
            let pts = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite());
            let color = s.color;
            let anno = match s.mark {
                Mark::Line(wd) => chart
                    .draw_series(LineSeries::new(decimate(pts), color.stroke_width(wd)))
                    .at(path)?,
                Mark::Dashed(wd) => chart
                    .draw_series(DashedLineSeries::new(
                        decimate(pts),
                        8,
                        5,
                        color.stroke_width(wd),
                    ))
                    .at(path)?,
                Mark::Dots(r) => chart
                    .draw_series(pts.map(|p| Circle::new(p, r, color.filled())))
                    .at(path)?,
            };
            if let Some(label) = &s.label {
                any_label = true;
                let mark = s.mark;
                anno.label(label).legend(
                    move |(x, y)| -> DynElement<'static, BitMapBackend<'b>, (i32, i32)> {
                        match mark {
                            Mark::Dots(_) => {
                                Circle::new((x + 10, y), 4, color.mix(1.0).filled()).into_dyn()
                            }
                            _ => PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(3))
                                .into_dyn(),
                        }
                    },
                );
            }
        }
        let position = match self.legend {
            Legend::UpperRight => Some(SeriesLabelPosition::UpperRight),
            Legend::UpperLeft => Some(SeriesLabelPosition::UpperLeft),
            Legend::LowerRight => Some(SeriesLabelPosition::LowerRight),
            Legend::LowerLeft => Some(SeriesLabelPosition::LowerLeft),
            Legend::None => None,
        };
        if let (true, Some(position)) = (any_label, position) {
            chart
                .configure_series_labels()
                .position(position)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .label_font((FAMILY, 14))
                .draw()
                .at(path)?;
        }
        Ok(chart)
    }
}

/// A tick label with at most four significant digits and no trailing zeros.
pub fn tick(v: f64) -> String {
    // Ticks at zero come out of the axis arithmetic as +-1e-17 or so.
    if v.abs() < 1e-12 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.1e}");
        return s.replace(".0e", "e");
    }
    let digits = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn padded(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * (lo.abs() + hi.abs()).max(1e-300) {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - d, hi + d);
    }
    (lo - pad * span, hi + pad * span)
}

/// At most about 4000 points of a polyline, keeping the first and last.
fn decimate(pts: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let all: Vec<_> = pts.collect();
    let n = all.len();
    if n <= 4000 {
        return all;
    }
    let stride = n.div_ceil(4000);
    let mut out: Vec<_> = all.iter().copied().step_by(stride).collect();
    if (n - 1) % stride != 0 {
        out.push(all[n - 1]);
    }
    out
}

/// Writes a PNG of `size` pixels: a white canvas split into `rows x cols` equal cells, each
/// drawn by `draw(index, cell)`, with an optional bold figure title on top.
///
/// # Errors
/// [`VizError::Draw`](crate::VizError::Draw) if plotters fails, or whatever `draw` returns.
pub fn save_png<F>(
    path: &Path,
    size: (u32, u32),
    title: Option<&str>,
    grid: (usize, usize),
    mut draw: F,
) -> Result<()>
where
    F: FnMut(usize, &Area<'_>) -> Result<()>,
{
    ensure_registered()?;
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).at(path)?;
    let body = match title {
        Some(t) => root
            .titled(t, (FAMILY, 24).into_font().style(FontStyle::Bold))
            .at(path)?,
        None => root.clone(),
    };
    let cells = body.split_evenly(grid);
    for (i, cell) in cells.iter().enumerate() {
        draw(i, cell)?;
    }
    root.present().at(path)?;
    Ok(())
}

/// Writes a PNG with a single panel.
///
/// # Errors
/// As [`save_png`].
pub fn save_panel(path: &Path, size: (u32, u32), panel: &Panel) -> Result<()> {
    save_png(path, size, None, (1, 1), |_, area| {
        panel.draw(area, path).map(|_| ())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(0.0), "0");
        assert_eq!(tick(2.5), "2.5");
        assert_eq!(tick(100.0), "100");
        assert_eq!(tick(0.125), "0.125");
        assert_eq!(tick(1.0e-6), "1e-6");
    }

    #[test]
    fn padding_handles_flat_data() {
        let (a, b) = padded(3.0, 3.0, 0.05);
        assert!(a < 3.0 && b > 3.0);
        let (a, b) = padded(0.0, 0.0, 0.05);
        assert!(a < 0.0 && b > 0.0);
    }

    #[test]
    fn decimation_keeps_ends() {
        let v = decimate((0..10_001).map(|i| (i as f64, 0.0)));
        assert!(v.len() <= 4001);
        assert_eq!(v.first().map(|p| p.0), Some(0.0));
        assert_eq!(v.last().map(|p| p.0), Some(10_000.0));
    }
}
