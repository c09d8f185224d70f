//! The plane of a double pendulum's initial angles `(theta1, theta2)`, released from rest,
//! shared by the flip-time fractal (demonstration 15) and the Lyapunov map (19): the grid of
//! cell centres and the curve inside which the energy forbids any flip
//! ([`DoublePendulumParams::can_flip_from_rest`], the library's physics).

use std::f64::consts::PI;
use std::path::Path;

use physicskit::classical::systems::DoublePendulumParams;
use plotters::prelude::*;

use crate::error::{DrawContext, Result};
use crate::figure::save_svg;
use crate::heatmap::HeatMap;

/// `n` cell centres from `-pi` to `pi` (the edges, where an arm stands inverted, left out).
pub(super) fn axis(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -PI + (i as f64 + 0.5) * 2.0 * PI / n as f64)
        .collect()
}

/// The closed curve around the origin, `n + 1` points, inside which no start from rest can
/// flip an arm: the boundary of [`DoublePendulumParams::can_flip_from_rest`], bisected along
/// `n` rays from the origin (for `g >= 0` the energy at rest rises along each ray while both
/// angles stay in `[-pi, pi]`, so each ray crosses the curve once; a ray that leaves the square first has no
/// point).
fn no_flip_contour(params: &DoublePendulumParams, n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .filter_map(|k| {
            let (s, c) = (2.0 * PI * k as f64 / n as f64).sin_cos();
            let flips = |r: f64| params.can_flip_from_rest(r * c, r * s);
            // The ray leaves the square [-pi, pi]^2 at r = hi.
            let (mut lo, mut hi) = (0.0, PI / c.abs().max(s.abs()));
            if !flips(hi) {
                return None;
            }
            // 60 halvings of a length below 4.5 reach adjacent floats.
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if flips(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            Some((lo * c, lo * s))
        })
        .collect()
}

/// Saves `map` (over this plane) with the curve of [`no_flip_contour`] drawn on it in
/// `colour` (named `colour_name` in the map's title; the figure's title states the parameters).
///
/// # Errors
/// As [`save_svg`].
pub(super) fn save_with_no_flip_contour(
    path: &Path,
    map: &HeatMap,
    params: &DoublePendulumParams,
    (colour, colour_name): (RGBColor, &str),
) -> Result<()> {
    let DoublePendulumParams { m1, m2, l1, l2, g } = *params;
    let title =
        format!("Double pendulum from rest: m = ({m1}, {m2}) kg, l = ({l1}, {l2}) m, g = {g} m/s²");
    let mut map = map.clone();
    map.title = format!("{}; none flips inside the {colour_name} curve", map.title);
    let contour = no_flip_contour(params, 720);
    save_svg(path, (860, 760), Some(&title), (1, 1), |_, area| {
        map.draw_with(area, path, |chart| {
            chart
                .draw_series(LineSeries::new(
                    contour.iter().copied(),
                    colour.stroke_width(2),
                ))
                .at(path)?;
            Ok(())
        })
    })
}
