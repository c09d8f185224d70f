//! Demonstration 1, Double pendulum: animation with fading trail and `(theta2, p2)` phase panel; sensitivity
//! to initial conditions; energy error of implicit_midpoint against rk4.

use physicskit::classical::analysis::convergence::log_separation;
use physicskit::classical::model::Value;
use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};
use plotters::prelude::*;

use super::common::{column, nonempty, stride, wrap};
use super::integrators::log_envelope;
use super::work_precision::words;
use super::{Ctx, Demo, Explanation, Physics};
use crate::animation::save_gif;
use crate::error::{DrawContext, Result};
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};

const THETA0: [f64; 2] = [2.0, 2.4];

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "double-pendulum",
    text: Physics::OfSystem(&physicskit::classical::systems::DOUBLE_PENDULUM_ENTRY),
    figure: "Rods of 1 m with 1 kg bobs (g = 9.81 m/s²) released from 115° and 138°; the second \
         run starts 10⁻⁹ rad away; the integrators are the implicit midpoint rule and rk4.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Double pendulum");
    let params = DoublePendulumParams::default();
    let dt = 0.002;
    let t1 = ctx.pick(12.0, 30.0);
    let mut dp = DoublePendulum::new(&THETA0, &[0.0, 0.0], params)?;
    // The lab opens on the animation's run: the same start, masses, lengths, method and step.
    let DoublePendulumParams { m1, m2, l1, l2, g } = params;
    d.lab = Some(ctx.lab_link(
        "double-pendulum",
        &[
            ("theta0", Value::Vector(THETA0.to_vec())),
            ("thetadot0", Value::Vector(vec![0.0, 0.0])),
            ("m1", Value::Scalar(m1)),
            ("m2", Value::Scalar(m2)),
            ("l1", Value::Scalar(l1)),
            ("l2", Value::Scalar(l2)),
            ("g", Value::Scalar(g)),
        ],
        Method::Rk4,
        dt,
        dp.state(),
    )?);
    let every = 10; // one stored sample per 0.02 s
    let r = dp.integrate_with((0.0, t1), dt, Method::Rk4, stride(every))?;
    let th1 = nonempty(column(r.q(), 0), "theta1")?;
    let th2 = nonempty(column(r.q(), 1), "theta2")?;
    let w1 = column(r.p(), 0);
    let w2 = column(r.p(), 1);
    let t = r.t.to_vec();
    let mut p2 = Vec::with_capacity(t.len());
    let mut mom = [0.0; 2];
    for i in 0..t.len() {
        dp.momentum(&[th1[i], th2[i]], &[w1[i], w2[i]], t[i], &mut mom)?;
        p2.push(mom[1]);
    }
    let pos: Vec<[f64; 4]> = (0..t.len())
        .map(|i| dp.positions(Some(&[th1[i], th2[i]])))
        .collect::<std::result::Result<_, _>>()?;
    let p2_range = p2
        .iter()
        .fold((0.0_f64, 0.0_f64), |(a, b), &v| (a.min(v), b.max(v)));

    // Animation: bobs with a fading trail, and the phase point building up.
    let frames = ctx.pick(40, 100);
    let per = (t.len() / frames).max(1);
    let path = ctx.path("double_pendulum.gif");
    save_gif(&path, (760, 380), ctx.gif_scale(), frames, 80, |k, root| {
        let i = (k * per).min(t.len() - 1);
        let (left, right) = root.split_horizontally(380);
        let mut chart = Panel::new(
            format!("Double pendulum, t = {:.1} s", t[i]),
            "x (m)",
            "y (m)",
        )
        .x_range(-2.2, 2.2)
        .y_range(-2.2, 2.2)
        .equal_aspect()
        .legend(Legend::None)
        .draw(&left, &path)?;
        // A 1.5 s trail (75 samples of 0.02 s), fading out towards its tail.
        let start = i.saturating_sub(75);
        for j in start.max(1)..=i {
            let alpha = 0.08 + 0.9 * (j - start) as f64 / (i - start).max(1) as f64;
            let a = (pos[j - 1][2], pos[j - 1][3]);
            let b = (pos[j][2], pos[j][3]);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![a, b],
                    color(1).mix(alpha).stroke_width(2),
                )))
                .at(&path)?;
        }
        let [x1, y1, x2, y2] = pos[i];
        // The pivot: a short ceiling bar the upper rod hangs from.
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(-0.25, 0.0), (0.25, 0.0)],
                RGBColor(90, 90, 90).stroke_width(4),
            )))
            .at(&path)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), (x1, y1), (x2, y2)],
                BLACK.stroke_width(3),
            )))
            .at(&path)?;
        chart
            .draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, BLACK.filled())))
            .at(&path)?;
        chart
            .draw_series([(x1, y1), (x2, y2)].map(|p| Circle::new(p, 8, color(0).filled())))
            .at(&path)?;
        let pts = (0..=i).map(|j| (wrap(th2[j]), p2[j])).collect();
        Panel::new(
            "Phase space of the lower bob",
            "θ₂ (rad, wrapped)",
            "p₂ (kg m²/s)",
        )
        .x_range(-std::f64::consts::PI, std::f64::consts::PI)
        .y_range(p2_range.0 * 1.05, p2_range.1 * 1.05)
        .legend(Legend::None)
        .with(Series::dots("", pts, color(0)).with_mark(Mark::Dots(1)))
        .draw(&right, &path)?;
        Ok(())
    })?;
    d.add(path, "animation: the two bobs with a fading trail of the lower bob, next to the (θ₂, p₂) phase panel filling up");

    // Sensitivity: two runs 1e-9 apart.
    let t_sep = ctx.pick(15.0, 25.0);
    let mut a = DoublePendulum::new(&THETA0, &[0.0, 0.0], params)?;
    let mut b = DoublePendulum::new(&[THETA0[0] + 1e-9, THETA0[1]], &[0.0, 0.0], params)?;
    let ra = a.integrate_with((0.0, t_sep), dt, Method::Rk4, stride(every))?;
    let rb = b.integrate_with((0.0, t_sep), dt, Method::Rk4, stride(every))?;
    let sep = log_separation(
        ra.y.as_slice().unwrap_or(&[]),
        rb.y.as_slice().unwrap_or(&[]),
        ra.y.ncols(),
    )?;
    let pts =
        ra.t.iter()
            .zip(&sep)
            .map(|(&t, &s)| (t, s / std::f64::consts::LN_10))
            .collect();
    let panel = Panel::new(
        "Two double pendulums started 10⁻⁹ rad apart",
        "t (s)",
        "log₁₀ |Δ(θ₁, θ₂, ω₁, ω₂)|  (rad, rad/s)",
    )
    .legend(Legend::Auto)
    .with(Series::line("separation (RK4, dt = 2 ms)", pts, color(0)));
    let path = ctx.path("double_pendulum_chaos.svg");
    save_panel(&path, (900, 520), &panel)?;
    d.add(path, "log-separation of two runs started 1e-9 rad apart against time: exponential growth, then saturation");

    // Energy: implicit midpoint against rk4 at a coarse step.
    let dt_e = 0.01;
    let t_e = ctx.pick(100.0, 600.0);
    let mut panel = Panel::new(
        format!("Energy error of the double pendulum, dt = {dt_e} s (log–log)"),
        "log₁₀ t (t in s)",
        "log₁₀ max |E − E(0)| / |E(0)| up to t",
    )
    .legend(Legend::Auto);
    for (i, m) in [Method::ImplicitMidpoint, Method::Rk4]
        .into_iter()
        .enumerate()
    {
        let mut s = DoublePendulum::new(&THETA0, &[0.0, 0.0], params)?;
        let r = s.integrate((0.0, t_e), dt_e, m)?;
        let e = r.energy.as_ref().map(|e| e.to_vec()).unwrap_or_default();
        let e0 = e.first().copied().unwrap_or(1.0);
        let rel: Vec<f64> = e.iter().map(|v| (v - e0) / e0).collect();
        panel = panel.with(Series::line(
            words(m),
            log_envelope(r.t.as_slice().unwrap_or(&[]), &rel, 200),
            color(if i == 0 { 3 } else { 2 }),
        ));
    }
    let path = ctx.path("double_pendulum_energy.svg");
    save_panel(&path, (900, 520), &panel)?;
    d.add(
        path,
        "the largest relative energy error so far against time, both on log scales: a plateau for the implicit midpoint rule (bounded), a rising line for RK4 (drift)",
    );
    Ok(d)
}
