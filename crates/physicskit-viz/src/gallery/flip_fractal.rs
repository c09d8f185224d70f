//! Demonstration 15, the double pendulum's flip-time fractal (Heyl 2008): over the plane of
//! initial angles `(theta1, theta2)`, released from rest, the time until either arm first
//! flips over the top (`|theta| > pi`), one ensemble member per pixel, with the curve inside
//! which the energy forbids any flip (the library's
//! [`DoublePendulumParams::can_flip_from_rest`]).

use std::f64::consts::PI;

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Condition, Event, Members, Plan, Reduction, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::systems::DoublePendulumParams;
use physicskit::classical::Method;
use plotters::prelude::BLACK;

use super::double_pendulum_plane::{axis, save_with_no_flip_contour};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::heatmap::HeatMap;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "flip-fractal",
    text: Physics::Own(
        "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂); its \
         colour is the time until either arm first swings over the top (|θ| > π), located \
         inside the integration step. Energy alone forbids a flip where the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (for \
         point bobs min(g₁ − |g₂|, g₂ − |g₁|), with g₁ = (m₁ + m₂) g l₁ and g₂ = m₂ g l₂: the \
         library's DoublePendulumParams::flip_energy). No member inside the black curve can \
         flip; those and the members that did not flip within the run are drawn at the top of \
         the scale. The boundaries between flip times are fractal (Heyl 2008): nearby starts \
         that straddle them flip at very different times, the fingerprint of chaos. Computed as \
         one ensemble on all cores (physicskit::classical::ensemble), bit-identical for any \
         number of threads.",
    ),
    figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1 (Heyl's 3 cos θ₁ + cos θ₂ = 2 is for uniform rods); 240 × 240 starts \
         run for 30 s with rk4 at dt = 0.01 s; times in units of √(l/g).",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Double pendulum: the flip-time fractal");
    let n = ctx.pick(64, 240);
    let t_max = ctx.pick(10.0, 30.0);
    let theta = axis(n);
    let (mut t1, mut t2) = (Vec::with_capacity(n * n), Vec::with_capacity(n * n));
    for &a in &theta {
        for &b in &theta {
            t1.push(a);
            t2.push(b);
        }
    }
    let params = DoublePendulumParams::default();
    let DoublePendulumParams { m1, m2, l1, l2, g } = params;
    let mut common = vec![("thetadot0".into(), Value::Vector(vec![0.0, 0.0]))];
    for (name, value) in [("m1", m1), ("m2", m2), ("l1", l1), ("l2", l2), ("g", g)] {
        common.push((name.into(), Value::Scalar(value)));
    }
    let members = Members {
        common,
        sweeps: vec![Sweep::new("theta0[0]", t1), Sweep::new("theta0[1]", t2)],
        states: None,
        n: n * n,
    };
    let flip = |index| {
        Reduction::FirstEvent(Event {
            index,
            condition: Condition::AbsExceeds(PI),
        })
    };
    let plan = Plan {
        t_span: (0.0, t_max),
        dt: 0.01,
        method: Some(Method::Rk4),
        stride: None,
        reductions: vec![flip(0), flip(1)],
        final_state: false,
        threads: None,
        tolerances: None,
    };
    let out = ensemble::run(catalog::find("double-pendulum")?, &members, &plan, None)?;
    let (first, second) = (&out.reductions[0].1, &out.reductions[1].1);
    // Times in units of sqrt(l1 / g), the upper arm's small-swing time scale.
    let scale = (l1 / g).sqrt();
    // Member (i, j) is theta1 = theta[i], theta2 = theta[j]; the map's row j holds x = theta1.
    let mut values = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let m = i * n + j;
            let t = first[m].min(second[m]);
            let t = if t.is_finite() { t } else { t_max };
            values[j * n + i] = (t / scale).max(1e-3).log10();
        }
    }
    let map = HeatMap {
        title: format!("Time to first flip, {n} × {n} members, run to t = {t_max} s"),
        x_label: "θ₁ (rad)".into(),
        y_label: "θ₂ (rad)".into(),
        value_label: "log₁₀ (t_{flip} / √(l₁/g))".into(),
        x_range: (theta[0], theta[n - 1]),
        y_range: (theta[0], theta[n - 1]),
        nx: n,
        ny: n,
        values,
    };
    let path = ctx.path("flip_fractal.svg");
    save_with_no_flip_contour(&path, &map, &params, (BLACK, "black"))?;
    d.add(path, "time to first flip over the plane of initial angles: fractal boundaries between flip times, and the curve inside which the energy forbids a flip");
    Ok(d)
}
