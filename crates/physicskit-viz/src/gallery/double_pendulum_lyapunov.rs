//! Demonstration 19, the double pendulum's Lyapunov map: over the plane of initial angles
//! `(theta1, theta2)`, released from rest, the largest Lyapunov exponent at the end of the run
//! ([`chaos_map`] with [`Indicator::MaxLyapunov`], all cores, bit-identical for any thread
//! count), with the contour of the energy below which neither arm can swing over the top.
//!
//! The contour is `E(theta1, theta2, 0, 0) = E_flip`, `E_flip` the lowest energy of a state
//! with an arm upside down, `min(E(0, pi, 0, 0), E(pi, 0, 0, 0))`: inside it the energy
//! forbids a flip. Both come from the system's own `energy`, the contour by bisection along
//! rays from the origin (the potential rises along each ray while both angles stay in
//! `[-pi, pi]`).

use std::f64::consts::PI;

use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun};
use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::core::erased::Lagrangian;
use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
use physicskit::classical::{DynamicalSystem, Method};
use plotters::prelude::*;

use super::{demo, Ctx, Demo};
use crate::error::{DrawContext, Result};
use crate::figure::save_png;
use crate::heatmap::HeatMap;

/// `n` cell centres from `-pi` to `pi` (the edges, inverted, left out).
fn axis(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -PI + (i as f64 + 0.5) * 2.0 * PI / n as f64)
        .collect()
}

/// The closed curve `E(theta1, theta2, 0, 0) = level` around the origin, `n` points.
fn energy_contour(dp: &DoublePendulum, level: f64, n: usize) -> Vec<(f64, f64)> {
    let energy = |r: f64, (c, s): (f64, f64)| dp.energy(&[r * c, r * s, 0.0, 0.0]);
    (0..=n)
        .filter_map(|k| {
            let dir = (2.0 * PI * k as f64 / n as f64).sin_cos();
            let dir = (dir.1, dir.0);
            // The ray leaves the square [-pi, pi]^2 at r_max.
            let (mut lo, mut hi) = (0.0, PI / dir.0.abs().max(dir.1.abs()));
            if energy(hi, dir) < level {
                return None;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if energy(mid, dir) < level {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            Some((lo * dir.0, lo * dir.1))
        })
        .collect()
}

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = demo(
        "double-pendulum-lyapunov",
        "19. Double pendulum: a Lyapunov map of the initial angles",
    );
    let n = ctx.pick(32, 100);
    let t_max = ctx.pick(10.0, 20.0);
    let dt = 0.01;
    let params = DoublePendulumParams::default();
    let dp = DoublePendulum::new(&[0.0, 0.0], &[0.0, 0.0], params)?;
    let theta = axis(n);
    // Row j of the map holds theta2 = theta[j], x = theta1.
    let mut states = Vec::with_capacity(4 * n * n);
    for &b in &theta {
        for &a in &theta {
            states.extend_from_slice(&[a, b, 0.0, 0.0]);
        }
    }
    let run = MapRun {
        t_span: (0.0, t_max),
        dt,
        method: Some(Method::Rk4),
        indicator: Indicator::MaxLyapunov {
            renormalize_every: DEFAULT_RENORMALIZE_EVERY,
        },
    };
    let values = chaos_map(&Lagrangian(dp.clone()), &states, &run)?;
    let flip = dp
        .energy(&[0.0, PI, 0.0, 0.0])
        .min(dp.energy(&[PI, 0.0, 0.0, 0.0]));
    let contour = energy_contour(&dp, flip, 720);
    let map = HeatMap {
        title: format!("Largest Lyapunov exponent at t = {t_max} s, {n} × {n} orbits"),
        x_label: "θ₁ (rad)".into(),
        y_label: "θ₂ (rad)".into(),
        value_label: "λ_max (1/s)".into(),
        x_range: (theta[0], theta[n - 1]),
        y_range: (theta[0], theta[n - 1]),
        nx: n,
        ny: n,
        values,
    };
    let path = ctx.path("19_double_pendulum_lyapunov.png");
    save_png(
        &path,
        (860, 760),
        Some("Double pendulum from rest; inside the white curve neither arm can flip"),
        (1, 1),
        |_, area| {
            map.draw_with(area, &path, |chart| {
                chart
                    .draw_series(LineSeries::new(
                        contour.iter().copied(),
                        WHITE.stroke_width(2),
                    ))
                    .at(&path)?;
                Ok(())
            })
        },
    )?;
    d.add(path, "largest Lyapunov exponent over the plane of initial angles, with the energy contour inside which no arm can flip");
    Ok(d)
}
