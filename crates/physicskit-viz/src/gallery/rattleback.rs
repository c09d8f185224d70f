//! Demonstration 23, rolling rattleback: the spin about the vertical against time for both
//! senses (one reverses early, the other much later), with its mean over two pitching periods,
//! whose first zero is the reversal time ([`spin_reversal_time`]), and the body drawn in 3-D as
//! it rattles and turns round (an animation).

use physicskit::classical::model::Value;
use physicskit::classical::systems::{
    averaged_spin, spin_reversal_time, RollingRattleback, RollingRattlebackParams,
    SPIN_REVERSAL_WINDOW,
};
use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
use plotters::prelude::*;

use super::common::{frame_caption, project, stride};
use super::{Ctx, Demo, Explanation, Physics};
use crate::animation::save_gif;
use crate::error::{DrawContext, Result};
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};

/// Spin about the vertical at the start (rad/s): clockwise seen from above reverses.
const SPIN: f64 = 5.0;
/// Step of rk4 (s): the catalogue's doc example keeps the energy to 1e-8 at it.
const DT: f64 = 1e-4;
/// Viewing direction of the 3-D frames: azimuth about the vertical and elevation.
const AZ: f64 = 0.6;
const EL: f64 = 0.45;

/// A run's legend entry: its start and when it first turns round.
fn spin_label(start: &str, reversal: Option<f64>, t1: f64) -> String {
    match reversal {
        Some(t) => format!("{start} start: turns round at t ≈ {t:.1} s"),
        None => format!("{start} start: keeps its sense up to t = {t1} s"),
    }
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "rolling-rattleback",
    text: Physics::OfSystem(&physicskit::classical::systems::ROLLING_RATTLEBACK_ENTRY),
    figure: "Kane and Levinson's body (semi-axes 0.2, 0.03 and 0.02 m, 1 kg, principal axes \
         turned from the geometric ones) started tilted 0.5° in roll and pitch and spun at \
         −5 and +5 rad/s; rk4 at dt = 10⁻⁴ s, no slip and no dissipation.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Rattleback: spin reversal");
    let params = RollingRattlebackParams::default();
    // Long enough for the anticlockwise start to turn round too: without dissipation that sense
    // is only held longer, not for ever (the legend gives both times, read from the runs).
    let t1 = ctx.pick(16.0, 30.0);
    // The animation shows the first reversal of the clockwise start.
    let t_gif = ctx.pick(8.0, 12.0);
    // The spin's mean is taken from one sample per 1 ms (at 0.01 s, about six samples a pitching
    // period, the trapezoidal mean would move the reversal by 2 ms; at 1 ms it moves by 0.02
    // ms); one sample in ten is drawn.
    let every = 10;
    let drawn = 10;
    let mut panel = Panel::new(
        format!(
            "Spin about the vertical, started at −{SPIN} and +{SPIN} rad/s (RK4, dt = {DT} s); \
             faint: sampled, bold: its mean over {SPIN_REVERSAL_WINDOW} s"
        ),
        "t (s)",
        "ω · ẑ (rad/s)",
    )
    .legend(Legend::Auto);
    let mut turns = Vec::new();
    let mut reversing = None;
    let mut reversals = [None; 2];
    for (i, (sign, start)) in [(-1.0, "clockwise"), (1.0, "anticlockwise")]
        .into_iter()
        .enumerate()
    {
        let omega0 = [0.0, 0.0, sign * SPIN];
        let mut body = RollingRattleback::new(&omega0, params, None)?;
        if i == 0 {
            // The lab opens on the reversing run: the same body, spin, method and step.
            d.lab = Some(ctx.lab_link(
                "rolling-rattleback",
                &[
                    ("omega0", Value::Vector(omega0.to_vec())),
                    ("a", Value::Scalar(params.a)),
                    ("b", Value::Scalar(params.b)),
                    ("c", Value::Scalar(params.c)),
                    ("h", Value::Scalar(params.h)),
                    ("m", Value::Scalar(params.m)),
                    ("I1", Value::Scalar(params.i1)),
                    ("I2", Value::Scalar(params.i2)),
                    ("I3", Value::Scalar(params.i3)),
                    ("delta", Value::Scalar(params.delta)),
                    ("g", Value::Scalar(params.g)),
                ],
                Method::Rk4,
                DT,
                body.state(),
            )?);
        }
        let r = body.integrate_with((0.0, t1), DT, Method::Rk4, stride(every))?;
        let states: Vec<Vec<f64>> = r.y.rows().into_iter().map(|s| s.to_vec()).collect();
        let spin = states
            .iter()
            .map(|s| body.vertical_spin(Some(s.as_slice())))
            .collect::<std::result::Result<Vec<f64>, _>>()?;
        let t = r.t.to_vec();
        reversals[i] = spin_reversal_time(&t, &spin, SPIN_REVERSAL_WINDOW)?;
        let (centres, means) = averaged_spin(&t, &spin, SPIN_REVERSAL_WINDOW)?;
        let sampled = t.iter().copied().zip(spin).step_by(drawn).collect();
        let mean = centres.into_iter().zip(means).step_by(drawn).collect();
        panel = panel
            .with(
                Series::line(spin_label(start, reversals[i], t1), sampled, color(i))
                    .with_mark(Mark::Line(1))
                    .with_alpha(0.4),
            )
            .with(Series::line("", mean, color(i)).unlabeled());
        turns.extend(reversals[i].map(|t| (t, 0.0)));
        if i == 0 {
            let frames: (Vec<f64>, Vec<Vec<f64>>) =
                t.into_iter().zip(states).step_by(drawn).unzip();
            reversing = Some((frames, body));
        }
    }
    panel = panel.with(
        Series::dots("reversal: the bold mean crosses zero", turns, BLACK).with_mark(Mark::Dots(4)),
    );
    let path = ctx.path("rattleback_spin.svg");
    save_panel(&path, (900, 520), &panel)?;
    let when = |r: Option<f64>| match r {
        Some(t) => format!("turns round at t ≈ {t:.1} s"),
        None => format!("keeps its sense up to t = {t1} s"),
    };
    d.add(
        path,
        &format!(
            "the spin about the vertical against time, faint as sampled and bold as its mean \
             over two pitching periods, whose zero (dot) is the reversal: spun clockwise the \
             body rattles, stops turning and {}; spun anticlockwise its rocking grows more \
             slowly, and it {}{}",
            when(reversals[0]),
            when(reversals[1]),
            if reversals[1].is_some() {
                " (the model has no dissipation: the favoured sense is held longer, not for ever)"
            } else {
                ""
            }
        ),
    );

    let Some(((t, states), body)) = reversing else {
        return Err(super::common::missing("the reversing run"));
    };
    let frames = ctx.pick(40, 100);
    let shown = t.iter().take_while(|&&ti| ti <= t_gif).count().max(1);
    let per = (shown / frames).max(1);
    let path = ctx.path("rattleback.gif");
    save_gif(&path, (560, 420), ctx.gif_scale(), frames, 80, |k, root| {
        let i = (k * per).min(shown - 1);
        draw_body(root, &path, &body, &params, &states[i], t[i])
    })?;
    d.add(
        path,
        "animation of the reversing run, the table seen obliquely from above: the ellipsoidal body, its long axis marked, rattles and turns round",
    );
    Ok(d)
}

/// Draws the rattleback's ellipsoid in state `state` on the table: a latitude–longitude mesh
/// of its surface, shaded by a light from above and painted back to front, the end of its long
/// axis (+x) in the accent colour.
fn draw_body(
    root: &crate::figure::Area<'_>,
    path: &std::path::Path,
    body: &RollingRattleback,
    p: &RollingRattlebackParams,
    state: &[f64],
    t: f64,
) -> Result<()> {
    let rot = body.rotation_matrix(Some(state))?;
    let g = body.center_of_mass(Some(state))?;
    let (w, h) = root.dim_in_pixel();
    // The table in view: 1.5 semi-axes a around the contact point's start, so the body fills
    // the frame; the contact point wanders little over the run.
    let scale = 0.5 * f64::from(w.min(h)) / (1.3 * p.a);
    let (cx, cy) = (0.5 * f64::from(w), 0.62 * f64::from(h));
    let to_px = |q: [f64; 3]| -> ((i32, i32), f64) {
        let (u, v, depth) = project(q, AZ, EL);
        (((cx + scale * u) as i32, (cy - scale * v) as i32), depth)
    };
    let world = |b: [f64; 3]| -> [f64; 3] {
        let mut out = g;
        // The ellipsoid's centre is h above G along the body's z axis.
        let b = [b[0], b[1], b[2] + p.h];
        for (r, o) in rot.iter().zip(out.iter_mut()) {
            *o += r[0] * b[0] + r[1] * b[1] + r[2] * b[2];
        }
        out
    };
    // The table: a square grid around the origin, drawn first.
    let grey = RGBColor(200, 200, 200);
    let half = 1.4 * p.a;
    for k in -4..=4 {
        let s = half * f64::from(k) / 4.0;
        for (a, b) in [
            ([s, -half, 0.0], [s, half, 0.0]),
            ([-half, s, 0.0], [half, s, 0.0]),
        ] {
            root.draw(&PathElement::new(
                vec![to_px(a).0, to_px(b).0],
                grey.stroke_width(1),
            ))
            .at(path)?;
        }
    }
    // Mesh quads of the ellipsoid, in body coordinates (before the offset h).
    let (nu, nv) = (28, 12);
    let point = |iu: usize, iv: usize| -> [f64; 3] {
        let u = std::f64::consts::TAU * iu as f64 / nu as f64;
        let v = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * iv as f64 / nv as f64;
        [
            p.a * v.cos() * u.cos(),
            p.b * v.cos() * u.sin(),
            p.c * v.sin(),
        ]
    };
    let light = {
        let l: [f64; 3] = [0.3, -0.4, 1.0];
        let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        [l[0] / n, l[1] / n, l[2] / n]
    };
    let mut quads = Vec::with_capacity(nu * nv);
    for iu in 0..nu {
        for iv in 0..nv {
            let corners = [
                point(iu, iv),
                point(iu + 1, iv),
                point(iu + 1, iv + 1),
                point(iu, iv + 1),
            ]
            .map(world);
            // The outward normal from the quad's diagonals.
            let (a, b) = (sub(corners[2], corners[0]), sub(corners[3], corners[1]));
            let mut n = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-300);
            n = [n[0] / len, n[1] / len, n[2] / len];
            let shade = 0.35 + 0.65 * (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).abs();
            let px = corners.map(to_px);
            let depth = px.iter().map(|c| c.1).sum::<f64>() / 4.0;
            // The quarter of the surface around the +x end carries the accent colour.
            let nose = !(nu / 8..nu - nu / 8).contains(&iu);
            quads.push((depth, shade, nose, px.map(|c| c.0)));
        }
    }
    quads.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (base, accent) = (color(0), color(1));
    for (_, shade, nose, poly) in &quads {
        let c = if *nose { accent } else { base };
        let f = |x: u8| (f64::from(x) * shade).round().clamp(0.0, 255.0) as u8;
        root.draw(&Polygon::new(
            poly.to_vec(),
            RGBColor(f(c.0), f(c.1), f(c.2)).filled(),
        ))
        .at(path)?;
    }
    frame_caption(
        root,
        path,
        &format!("Rattleback, t = {t:.2} s"),
        "started clockwise (seen from above); the coloured end marks the long axis",
    )
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
