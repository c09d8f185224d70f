//! Demonstration 19, the double pendulum's Lyapunov map: over the plane of initial angles
//! `(theta1, theta2)`, released from rest, the largest Lyapunov exponent at the end of the run
//! ([`chaos_map`] with [`Indicator::MaxLyapunov`], all cores, bit-identical for any thread
//! count), with the contour of the energy below which neither arm can swing over the top.
//!
//! The contour is the boundary of the library's
//! [`DoublePendulumParams::can_flip_from_rest`]: inside it the energy at rest is at or below
//! the flip energy, the lowest energy of a state with an arm upside down, and no arm can flip.

use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun};
use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::model::erased::Lagrangian;
use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
use physicskit::classical::Method;
use plotters::prelude::WHITE;

use super::double_pendulum_plane::{axis, save_with_no_flip_contour};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::heatmap::HeatMap;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "double-pendulum-lyapunov",
    text: Physics::Own(
        "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂), \
         coloured by its largest Lyapunov exponent: the growth rate, per second, of an \
         infinitesimal deviation carried by the tangent dynamics (Benettin's method, the \
         finite-time value at the end of the run). Inside the white curve the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (the \
         library's DoublePendulumParams::flip_energy), so neither arm can ever flip: there the \
         map is dark, small exponents of mostly regular motion (a finite run leaves a residue \
         of order ln(t)/t even on a torus). Starts that the energy would let flip may still \
         stay on regular tori and extend the dark region beyond the curve. Further out the map \
         is a speckle of chaotic starts, the same structure the flip-time fractal shows in its \
         boundaries. The map has the pendulum's symmetry (θ₁, θ₂) → (−θ₁, −θ₂) up to the finite \
         run. Computed with the library's chaos map on all cores, bit-identical for any number \
         of threads.",
    ),
    figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1; 100 × 100 starts run to t = 20 s with rk4 at dt = 0.01 s, the \
         deviation renormalized every 10 steps. The dark region reaches beyond the curve in two \
         arms; the chaotic starts have exponents of one to two per second.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Double pendulum: a Lyapunov map of the initial angles");
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
    let values = chaos_map(&Lagrangian(dp), &states, &run)?;
    let map = HeatMap {
        title: format!("Largest Lyapunov exponent at t = {t_max} s, {n} × {n} orbits"),
        x_label: "θ₁ (rad)".into(),
        y_label: "θ₂ (rad)".into(),
        value_label: "λ_{max} (1/s)".into(),
        x_range: (theta[0], theta[n - 1]),
        y_range: (theta[0], theta[n - 1]),
        nx: n,
        ny: n,
        values,
    };
    let path = ctx.path("double_pendulum_lyapunov.svg");
    save_with_no_flip_contour(&path, &map, &params, (WHITE, "white"))?;
    d.add(path, "largest Lyapunov exponent over the plane of initial angles, with the energy contour inside which no arm can flip");
    Ok(d)
}
