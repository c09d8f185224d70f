//! Figure helpers: a [`Panel`] of [`Series`] (lines, dashed lines, dots) with a wrapped title,
//! axis labels (with units), a legend and automatic ranges, drawn into any region of an SVG
//! document; and [`save_svg`] to lay out several panels in one SVG file.
//!
//! Axes, ticks and axis labels are plotters'; the data and the legend are written by this module
//! (compact paths, dash patterns and marker shapes plotters lacks) into groups the layout checks
//! ([`crate::layout`]) recognise: `<g class="pk-data">` holds a panel's plotted points and
//! `<g class="pk-legend">` its legend box, both tagged with the panel's plot rectangle.

use std::fmt::Write as _;
use std::path::Path;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;

use crate::error::{DrawContext, Result};
use crate::font::FAMILY;
use crate::svg::{self, hex, num};
use crate::text;

/// A chart on linear `f64` axes drawn into an SVG document.
pub type Chart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A region of an SVG document.
pub type Area<'b> = DrawingArea<SVGBackend<'b>, Shift>;

/// Colours of successive series: Okabe & Ito's colour-blind-safe palette (2008), its yellow,
/// too pale on white, replaced by a mid grey.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(136, 136, 136),
];

/// The `i`-th palette colour (cycling).
pub fn color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// The `i`-th of `n` colours along viridis (perceptually uniform and colour-blind-safe), for
/// families of many orbits where each needs its own colour; its palest tenth is left out,
/// which would vanish on white.
pub fn ramp(i: usize, n: usize) -> RGBColor {
    let x = if n <= 1 {
        0.0
    } else {
        0.9 * i as f64 / (n - 1) as f64
    };
    ViridisRGB::get_color_normalized(x, 0.0, 1.0)
}

/// The `i`-th of many series told apart by colour and line style: the eight palette colours
/// solid, then again dashed, then dotted.
pub fn styled_line(i: usize) -> (RGBColor, Mark) {
    let mark = match (i / PALETTE.len()) % 3 {
        0 => Mark::Line(2),
        1 => Mark::Dashed(2),
        _ => Mark::Dotted(2),
    };
    (color(i), mark)
}

/// The marker of the `i`-th of many point series: circles for the first eight, squares for the
/// next eight, then circles again.
pub fn styled_dots(i: usize, radius: u32) -> Mark {
    if (i / PALETTE.len()).is_multiple_of(2) {
        Mark::Dots(radius)
    } else {
        Mark::Squares(radius)
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark {
    /// A solid polyline of the given width in pixels.
    Line(u32),
    /// A dashed polyline of the given width.
    Dashed(u32),
    /// A dotted polyline of the given width.
    Dotted(u32),
    /// Filled round dots of the given radius in pixels.
    Dots(u32),
    /// Filled square markers of the given half-width in pixels.
    Squares(u32),
}

impl Mark {
    /// Whether the series is a polyline (else separate points).
    fn is_line(self) -> bool {
        matches!(self, Mark::Line(_) | Mark::Dashed(_) | Mark::Dotted(_))
    }

    /// The SVG stroke attributes of the mark in `color` (with opacity `alpha`).
    fn stroke(self, color: &str, alpha: f64) -> String {
        let opacity = if alpha < 1.0 {
            format!(" stroke-opacity=\"{}\"", num(alpha))
        } else {
            String::new()
        };
        match self {
            Mark::Line(w) => format!(
                "fill=\"none\" stroke=\"{color}\" stroke-width=\"{w}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"{opacity}"
            ),
            Mark::Dashed(w) => format!(
                "fill=\"none\" stroke=\"{color}\" stroke-width=\"{w}\" stroke-linejoin=\"round\" stroke-dasharray=\"{} {}\"{opacity}",
                4 * w + 2,
                2 * w + 2
            ),
            Mark::Dotted(w) => format!(
                "fill=\"none\" stroke=\"{color}\" stroke-width=\"{w}\" stroke-linecap=\"round\" stroke-dasharray=\"0 {}\"{opacity}",
                2 * w + 2
            ),
            Mark::Dots(r) => format!(
                "fill=\"none\" stroke=\"{color}\" stroke-width=\"{}\" stroke-linecap=\"round\"{opacity}",
                2 * r
            ),
            Mark::Squares(r) => format!(
                "fill=\"none\" stroke=\"{color}\" stroke-width=\"{}\" stroke-linecap=\"square\"{opacity}",
                2 * r
            ),
        }
    }

    /// Half the drawn extent across the data, in pixels.
    fn half_width(self) -> f64 {
        match self {
            Mark::Line(w) | Mark::Dashed(w) | Mark::Dotted(w) => 0.5 * f64::from(w),
            Mark::Dots(r) => f64::from(r),
            Mark::Squares(r) => std::f64::consts::SQRT_2 * f64::from(r),
        }
    }
}

/// One data series of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry; `None` keeps it out of the legend.
    pub label: Option<String>,
    /// Points `(x, y)`; non-finite points are skipped (a line breaks there).
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

/// Whether a panel has a legend.
///
/// Where it goes is computed from the data: the first corner of the plot (upper right, upper
/// left, lower right, lower left) that no plotted point or line segment enters, else outside
/// the plot: on its right, or above it for an equal-aspect plot (which would lose width).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// A legend of the labelled series, placed where it hides no data.
    #[default]
    Auto,
    /// No legend.
    None,
}

/// One chart: title, axis labels with units, ranges and series.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Title above the chart (wrapped to the panel's width).
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
    /// Legend or none.
    pub legend: Legend,
    /// Make one unit on x as long as one unit on y (for orbits and shapes), by widening the
    /// shorter range.
    pub equal_aspect: bool,
}

/// Title size of a panel (CSS pixels, bold).
pub const TITLE_SIZE: f64 = 16.0;
/// Title size of a figure of several panels.
pub const FIGURE_TITLE_SIZE: f64 = 19.0;
/// Tick label size as plotters takes it (it writes `size / 1.24` into the SVG).
const TICK_FONT: u32 = 16;
/// Axis label size as plotters takes it.
const DESC_FONT: u32 = 18;
/// Legend text size.
const LEGEND_SIZE: f64 = 13.0;
/// Height of one legend row.
const LEGEND_ROW: f64 = 19.0;
/// Length of a legend's line sample.
const LEGEND_SAMPLE: f64 = 26.0;

/// Plotters' size of a font in the SVG's pixels.
fn svg_size(plotters_size: u32) -> f64 {
    f64::from(plotters_size) / 1.24
}

/// A pixel rectangle `(x0, y0, x1, y1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    fn grown(self, d: f64) -> Self {
        Self {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }

    pub(crate) fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }

    /// Whether the segment `a`–`b` enters the rectangle (Liang–Barsky clipping).
    pub(crate) fn meets_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let mut t0 = 0.0_f64;
        let mut t1 = 1.0_f64;
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }

    fn attr(&self) -> String {
        format!(
            "{} {} {} {}",
            num(self.x0),
            num(self.y0),
            num(self.x1),
            num(self.y1)
        )
    }
}

/// A series in pixel coordinates.
struct Pixels {
    points: Vec<(f64, f64)>,
    mark: Mark,
}

impl Pixels {
    fn meets(&self, r: &Rect) -> bool {
        let r = r.grown(self.mark.half_width() + 2.0);
        if self.mark.is_line() {
            self.points
                .windows(2)
                .any(|w| w[0].0.is_finite() && w[1].0.is_finite() && r.meets_segment(w[0], w[1]))
                || self.points.iter().any(|p| r.contains(*p))
        } else {
            self.points.iter().any(|p| r.contains(*p))
        }
    }
}

/// The legend's size in pixels for `labels`.
fn legend_size(labels: &[&str]) -> (f64, f64) {
    let w = labels
        .iter()
        .map(|l| text::width(l, LEGEND_SIZE, false))
        .fold(0.0, f64::max);
    (
        10.0 + LEGEND_SAMPLE + 8.0 + w + 10.0,
        8.0 + labels.len() as f64 * LEGEND_ROW,
    )
}

/// The lines of a title wrapped to `width` and the height they take.
pub(crate) fn title_lines(title: &str, size: f64, width: f64) -> (Vec<String>, f64) {
    if title.is_empty() {
        return (Vec::new(), 6.0);
    }
    let lines = text::wrap(title, size, true, width);
    let h = 8.0 + lines.len() as f64 * size * text::LINE_HEIGHT;
    (lines, h)
}

/// Text elements of a centred title at `(cx, top)`.
pub(crate) fn title_svg(lines: &[String], size: f64, cx: f64, top: f64) -> String {
    let mut s = String::new();
    for (k, l) in lines.iter().enumerate() {
        // Baseline at the line box's ascent (0.93 em for DejaVu Sans) below its top.
        let y =
            top + (k as f64 * text::LINE_HEIGHT + 0.93 + 0.5 * (text::LINE_HEIGHT - 1.164)) * size;
        s.push_str(&svg::text(cx, y, size, true, "middle", "#222222", l));
    }
    s
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

    /// Sets the legend.
    pub fn legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// Equal scales on both axes.
    pub fn equal_aspect(mut self) -> Self {
        self.equal_aspect = true;
        self
    }

    /// The ranges the panel will use for a plot area of `pixel_aspect` (width over height).
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

    /// Width of the y tick labels' column for range `yr`, in pixels.
    fn y_tick_width(yr: (f64, f64)) -> f64 {
        let r: RangedCoordf64 = (yr.0..yr.1).into();
        r.key_points(7)
            .iter()
            .map(|v| text::width(&tick(*v), svg_size(TICK_FONT), false))
            .fold(0.0, f64::max)
    }

    /// Builds the chart on `area` with `right` pixels of margin on the right and the plot's
    /// ranges; returns it with its pixel mapping.
    fn build<'a, 'b>(
        &self,
        area: &'a Area<'b>,
        top: f64,
        right: f64,
        path: &Path,
    ) -> Result<(Chart<'a, 'b>, Mapping)> {
        let (w, h) = area.dim_in_pixel();
        let x_area = 14.0 + svg_size(TICK_FONT) * 1.2 + svg_size(DESC_FONT) * text::LINE_HEIGHT;
        // The y ranges decide the tick labels' width, which decides the plot's width: fit the
        // ranges to the plot area estimated from the widest label of the data's own range.
        let mut y_area = 0.0;
        let mut ranges = self.ranges(1.0);
        for _ in 0..2 {
            y_area =
                14.0 + Self::y_tick_width(ranges.1) + 8.0 + svg_size(DESC_FONT) * text::LINE_HEIGHT;
            let pw = (f64::from(w) - y_area - 10.0 - right).max(10.0);
            let ph = (f64::from(h) - x_area - top - 10.0).max(10.0);
            ranges = self.ranges(pw / ph);
        }
        let (xr, yr) = ranges;
        let chart = ChartBuilder::on(area)
            // The top tick label reaches half a line above the plot: keep it off the title.
            .margin_top((top + 10.0).ceil() as u32)
            .margin_bottom(10)
            .margin_left(6)
            .margin_right((10.0 + right).ceil() as u32)
            .x_label_area_size(x_area.ceil() as u32)
            .y_label_area_size(y_area.ceil() as u32)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .at(path)?;
        let mapping = Mapping::of(&chart, xr, yr);
        Ok((chart, mapping))
    }

    /// Draws the panel into `area` and returns the chart, for extra drawing in data
    /// coordinates.
    ///
    /// # Errors
    /// [`VizError::Draw`](crate::VizError::Draw) naming `path` if plotters fails.
    pub fn draw<'a, 'b>(&self, area: &'a Area<'b>, path: &Path) -> Result<Chart<'a, 'b>> {
        let (w, _) = area.dim_in_pixel();
        let (ox, oy) = area.get_base_pixel();
        let (ox, oy) = (f64::from(ox), f64::from(oy));
        let (lines, top) = title_lines(&self.title, TITLE_SIZE, f64::from(w) - 16.0);
        if !lines.is_empty() {
            svg::place(
                area,
                title_svg(&lines, TITLE_SIZE, ox + 0.5 * f64::from(w), oy + 6.0),
                path,
            )?;
        }
        let labels: Vec<&str> = match self.legend {
            Legend::Auto => self
                .series
                .iter()
                .filter_map(|s| s.label.as_deref())
                .collect(),
            Legend::None => Vec::new(),
        };
        let legend = (!labels.is_empty()).then(|| legend_size(&labels));

        // Inside the plot if a corner is free of data, else on its right.
        let (mut chart, mut mapping) = self.build(area, top, 0.0, path)?;
        let mut pixels = self.pixels(&mapping);
        let mut legend_rect = None;
        if let Some((lw, lh)) = legend {
            let plot = mapping.plot();
            let inset = 8.0;
            let corners = [
                (plot.x1 - inset - lw, plot.y0 + inset),
                (plot.x0 + inset, plot.y0 + inset),
                (plot.x1 - inset - lw, plot.y1 - inset - lh),
                (plot.x0 + inset, plot.y1 - inset - lh),
            ];
            legend_rect = corners
                .iter()
                .map(|&(x, y)| Rect {
                    x0: x,
                    y0: y,
                    x1: x + lw,
                    y1: y + lh,
                })
                .find(|r| r.x0 >= plot.x0 && r.y1 <= plot.y1 && !pixels.iter().any(|p| p.meets(r)));
            if legend_rect.is_none() && self.equal_aspect {
                // Above the plot: beside it, an equal-aspect plot would lose its width.
                let (c, m) = self.build(area, top + lh + 8.0, 0.0, path)?;
                chart = c;
                mapping = m;
                pixels = self.pixels(&mapping);
                let plot = mapping.plot();
                legend_rect = Some(Rect {
                    x0: plot.x0,
                    y0: oy + top + 2.0,
                    x1: plot.x0 + lw,
                    y1: oy + top + 2.0 + lh,
                });
            } else if legend_rect.is_none() {
                let (c, m) = self.build(area, top, lw + 12.0, path)?;
                chart = c;
                mapping = m;
                pixels = self.pixels(&mapping);
                let plot = mapping.plot();
                legend_rect = Some(Rect {
                    x0: plot.x1 + 12.0,
                    y0: plot.y0,
                    x1: plot.x1 + 12.0 + lw,
                    y1: plot.y0 + lh,
                });
            }
        }
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FAMILY, TICK_FONT))
            .axis_desc_style((FAMILY, DESC_FONT))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(228, 228, 228))
            .axis_style(RGBColor(90, 90, 90))
            .x_labels(7)
            .y_labels(7)
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .at(path)?;
        svg::place(area, self.data_svg(&mapping, &pixels), path)?;
        if let Some(r) = legend_rect {
            svg::place(area, self.legend_svg(&mapping, r), path)?;
        }
        Ok(chart)
    }

    /// The series in pixel coordinates (lines decimated to about 4000 points).
    fn pixels(&self, m: &Mapping) -> Vec<Pixels> {
        self.series
            .iter()
            .map(|s| {
                let pts = s.points.iter().map(|&p| {
                    if p.0.is_finite() && p.1.is_finite() {
                        m.map(p)
                    } else {
                        (f64::NAN, f64::NAN)
                    }
                });
                let points = if s.mark.is_line() {
                    decimate(pts)
                } else {
                    pts.filter(|p| p.0.is_finite()).collect()
                };
                Pixels {
                    points,
                    mark: s.mark,
                }
            })
            .collect()
    }

    /// The data group: every series as one path, clipped to the plot.
    fn data_svg(&self, m: &Mapping, pixels: &[Pixels]) -> String {
        let plot = m.plot();
        let id = svg::next_id();
        let mut s = format!(
            "<defs><clipPath id=\"pkclip{id}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath></defs>\n\
             <g class=\"pk-data\" data-axes=\"{}\" clip-path=\"url(#pkclip{id})\">\n",
            num(plot.x0),
            num(plot.y0),
            num(plot.x1 - plot.x0),
            num(plot.y1 - plot.y0),
            plot.attr()
        );
        for (series, px) in self.series.iter().zip(pixels) {
            if px.points.is_empty() {
                continue;
            }
            let c = series.color;
            let color = hex(RGBColor(c.0, c.1, c.2));
            let mut d = String::with_capacity(px.points.len() * 14);
            let mut pen_up = true;
            for &(x, y) in &px.points {
                if !x.is_finite() {
                    pen_up = true;
                    continue;
                }
                if series.mark.is_line() {
                    let _ = write!(d, "{}{} {}", if pen_up { 'M' } else { 'L' }, num(x), num(y));
                    pen_up = false;
                } else {
                    let _ = write!(d, "M{} {}h0", num(x), num(y));
                }
            }
            let _ = writeln!(s, "<path d=\"{d}\" {}/>", series.mark.stroke(&color, c.3));
        }
        s.push_str("</g>\n");
        s
    }

    /// The legend group: a box at `r` with a sample and the label of each labelled series.
    fn legend_svg(&self, m: &Mapping, r: Rect) -> String {
        let mut s = format!(
            "<g class=\"pk-legend\" data-axes=\"{}\">\n<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"3\" fill=\"#FFFFFF\" fill-opacity=\"0.92\" stroke=\"#B4B4B4\" stroke-width=\"1\"/>\n",
            m.plot().attr(),
            num(r.x0),
            num(r.y0),
            num(r.x1 - r.x0),
            num(r.y1 - r.y0)
        );
        let labelled = self
            .series
            .iter()
            .filter_map(|se| se.label.as_deref().map(|l| (se, l)));
        for (k, (series, label)) in labelled.enumerate() {
            let cy = r.y0 + 4.0 + (k as f64 + 0.5) * LEGEND_ROW;
            let x = r.x0 + 10.0;
            let c = series.color;
            let color = hex(RGBColor(c.0, c.1, c.2));
            let d = if series.mark.is_line() {
                format!("M{} {}h{LEGEND_SAMPLE}", num(x), num(cy))
            } else {
                format!("M{} {}h0", num(x + 0.5 * LEGEND_SAMPLE), num(cy))
            };
            let mark = match series.mark {
                Mark::Dots(r) => Mark::Dots(r.max(3)),
                Mark::Squares(r) => Mark::Squares(r.max(3)),
                Mark::Line(w) => Mark::Line(w.max(2)),
                other => other,
            };
            let _ = writeln!(s, "<path d=\"{d}\" {}/>", mark.stroke(&color, 1.0));
            s.push_str(&svg::text(
                x + LEGEND_SAMPLE + 8.0,
                cy + 0.35 * LEGEND_SIZE,
                LEGEND_SIZE,
                false,
                "start",
                "#222222",
                label,
            ));
        }
        s.push_str("</g>\n");
        s
    }
}

/// The map from data to pixel coordinates of a built chart.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mapping {
    xr: (f64, f64),
    yr: (f64, f64),
    /// Pixel x of `xr.0` and `xr.1`.
    px: (f64, f64),
    /// Pixel y of `yr.0` and `yr.1`.
    py: (f64, f64),
}

impl Mapping {
    /// The mapping of `chart`, built on ranges `xr` and `yr`.
    pub(crate) fn of(chart: &Chart<'_, '_>, xr: (f64, f64), yr: (f64, f64)) -> Self {
        let a = chart.backend_coord(&(xr.0, yr.0));
        let b = chart.backend_coord(&(xr.1, yr.1));
        Mapping {
            xr,
            yr,
            px: (f64::from(a.0), f64::from(b.0)),
            py: (f64::from(a.1), f64::from(b.1)),
        }
    }

    fn map(&self, p: (f64, f64)) -> (f64, f64) {
        (
            self.px.0 + (p.0 - self.xr.0) / (self.xr.1 - self.xr.0) * (self.px.1 - self.px.0),
            self.py.0 + (p.1 - self.yr.0) / (self.yr.1 - self.yr.0) * (self.py.1 - self.py.0),
        )
    }

    pub(crate) fn plot(&self) -> Rect {
        Rect {
            x0: self.px.0.min(self.px.1),
            y0: self.py.0.min(self.py.1),
            x1: self.px.0.max(self.px.1),
            y1: self.py.0.max(self.py.1),
        }
    }
}

/// A tick label with at most four significant digits, no trailing zeros and a true minus sign.
pub fn tick(v: f64) -> String {
    // Ticks at zero come out of the axis arithmetic as +-1e-17 or so.
    if v.abs() < 1e-12 {
        return "0".into();
    }
    let a = v.abs();
    let s = if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.1e}");
        s.replace(".0e", "e")
    } else {
        let digits = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    s.replace('-', "−")
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

/// Writes an SVG of `size` pixels: a white canvas split into `rows x cols` equal cells, each
/// drawn by `draw(index, cell)`, with an optional bold figure title on top (wrapped).
///
/// # Errors
/// [`VizError::Draw`](crate::VizError::Draw) if plotters fails, or whatever `draw` returns.
pub fn save_svg<F>(
    path: &Path,
    size: (u32, u32),
    title: Option<&str>,
    grid: (usize, usize),
    mut draw: F,
) -> Result<()>
where
    F: FnMut(usize, &Area<'_>) -> Result<()>,
{
    svg::save(path, size, |root| {
        let (lines, h) = title_lines(
            title.unwrap_or(""),
            FIGURE_TITLE_SIZE,
            f64::from(size.0) - 24.0,
        );
        let body = if lines.is_empty() {
            root.clone()
        } else {
            svg::place(
                root,
                title_svg(&lines, FIGURE_TITLE_SIZE, 0.5 * f64::from(size.0), 6.0),
                path,
            )?;
            root.split_vertically(h.ceil() as u32).1
        };
        let cells = body.split_evenly(grid);
        for (i, cell) in cells.iter().enumerate() {
            draw(i, cell)?;
        }
        Ok(())
    })
}

/// Writes an SVG with a single panel.
///
/// # Errors
/// As [`save_svg`].
pub fn save_panel(path: &Path, size: (u32, u32), panel: &Panel) -> Result<()> {
    save_svg(path, size, None, (1, 1), |_, area| {
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
        assert_eq!(tick(-2.5), "−2.5");
        assert_eq!(tick(100.0), "100");
        assert_eq!(tick(0.125), "0.125");
        assert_eq!(tick(1.0e-6), "1e−6");
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

    #[test]
    fn segments_meet_rectangles() {
        let r = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 10.0,
            y1: 10.0,
        };
        assert!(r.meets_segment((-5.0, 5.0), (15.0, 5.0)));
        assert!(!r.meets_segment((-5.0, -5.0), (-1.0, 15.0)));
        assert!(r.meets_segment((-5.0, -5.0), (15.0, 15.0)));
        assert!(!r.meets_segment((11.0, 0.0), (20.0, 9.0)));
    }
}
