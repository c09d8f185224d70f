//! Small helpers shared by the demonstrations: columns of result arrays, angle wrapping and
//! an orthographic 3-D projection for spheres and boxes.

use ndarray::{Array2, ArrayView2};
use physicskit::classical::{IntegrateOptions, Sampling};

use crate::error::{Result, VizError};

/// Column `j` of an optional `(samples, n)` array (empty if absent).
pub(crate) fn column(a: Option<ArrayView2<'_, f64>>, j: usize) -> Vec<f64> {
    match a {
        Some(a) if j < a.ncols() => a.column(j).to_vec(),
        _ => Vec::new(),
    }
}

/// Column `j` of the raw state array.
pub(crate) fn ycol(y: &Array2<f64>, j: usize) -> Vec<f64> {
    column(Some(y.view()), j)
}

/// The angle wrapped into `(-pi, pi]`.
pub(crate) fn wrap(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let w = a - two_pi * (a / two_pi).round();
    if w <= -std::f64::consts::PI {
        w + two_pi
    } else {
        w
    }
}

/// A continuous version of a sequence of angles given modulo `2 pi`.
pub(crate) fn unwrap(angles: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(angles.len());
    let mut offset = 0.0;
    let mut prev: Option<f64> = None;
    for &a in angles {
        if let Some(p) = prev {
            offset -= std::f64::consts::TAU * ((a - p) / std::f64::consts::TAU).round();
        }
        out.push(a + offset);
        prev = Some(a);
    }
    out
}

/// Options storing every `stride`-th sample (at least 1).
pub(crate) fn stride(k: usize) -> IntegrateOptions<'static> {
    IntegrateOptions {
        sampling: Sampling::Stride(k.max(1)),
        ..IntegrateOptions::default()
    }
}

/// Orthographic view: azimuth `az` about z, then elevation `el`; returns screen `(u, v)` and
/// depth (positive towards the viewer).
pub(crate) fn project(p: [f64; 3], az: f64, el: f64) -> (f64, f64, f64) {
    let (sa, ca) = az.sin_cos();
    let (se, ce) = el.sin_cos();
    let x1 = ca * p[0] + sa * p[1];
    let y1 = -sa * p[0] + ca * p[1];
    let u = y1;
    let v = ce * p[2] - se * x1;
    let depth = ce * x1 + se * p[2];
    (u, v, depth)
}

/// An error for a result that lacks an array a figure needs.
pub(crate) fn missing(what: &str) -> VizError {
    VizError::Physics(physicskit::classical::Error::Unsupported {
        operation: what.into(),
        reason: "the simulation result does not contain it".into(),
    })
}

/// `Ok(v)` unless `v` is empty.
pub(crate) fn nonempty(v: Vec<f64>, what: &str) -> Result<Vec<f64>> {
    if v.is_empty() {
        Err(missing(what))
    } else {
        Ok(v)
    }
}

/// A number as a physicist writes it in running text: a power of ten as `10⁻⁸` (superscript
/// exponent), any other number in Rust's shortest form.
pub(crate) fn power_of_ten(x: f64) -> String {
    // Rust's shortest exponent form is "1e-8" exactly when x is a power of ten.
    match format!("{x:e}").strip_prefix("1e") {
        Some(exponent) => {
            let digits: String = exponent
                .chars()
                .map(|c| match c.to_digit(10) {
                    Some(d) => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize],
                    None => '⁻',
                })
                .collect();
            format!("10{digits}")
        }
        None => format!("{x}"),
    }
}

/// The title and the grey subtitle at the top left of an animation frame drawn by hand (a body
/// in 3-D rather than a chart).
pub(crate) fn frame_caption(
    root: &crate::figure::Area<'_>,
    path: &std::path::Path,
    title: &str,
    subtitle: &str,
) -> Result<()> {
    use crate::error::DrawContext;
    use plotters::prelude::*;
    root.draw(&Text::new(
        title.to_string(),
        (12, 10),
        (crate::font::FAMILY, 20).into_font(),
    ))
    .at(path)?;
    root.draw(&Text::new(
        subtitle.to_string(),
        (12, 36),
        (crate::font::FAMILY, 13)
            .into_font()
            .color(&RGBColor(90, 90, 90)),
    ))
    .at(path)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::power_of_ten;

    #[test]
    fn powers_of_ten_are_written_with_superscripts() {
        assert_eq!(power_of_ten(1e-8), "10⁻⁸");
        assert_eq!(power_of_ten(1e12), "10¹²");
        assert_eq!(power_of_ten(1.0), "10⁰");
        assert_eq!(power_of_ten(2e-8), "0.00000002");
        assert_eq!(power_of_ten(0.0), "0");
        assert_eq!(power_of_ten(-1e-8), "-0.00000001");
    }
}
