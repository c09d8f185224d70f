//! Demonstration 8, Euler top: the `omega` components with the Dzhanibekov flips, polhodes on the
//! angular-momentum sphere, and an animated tumbling plate.

use physicskit::classical::systems::{EulerTop, EulerTopParams};
use physicskit::classical::{Method, OdeSystem};
use plotters::prelude::*;

use super::common::{project, stride, ycol};
use super::{Ctx, Demo};
use crate::animation::save_gif;
use crate::error::{DrawContext, Result};
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};
use crate::font::FAMILY;

const OMEGA0: [f64; 3] = [0.01, 1.0, 0.01];
/// View direction of the 3-D drawings (radians).
const AZ: f64 = 0.7;
const EL: f64 = 0.35;

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo(
        "euler-top",
        "Euler top: the tennis-racket (Dzhanibekov) effect",
    );
    let params = EulerTopParams::default();
    let dt = 0.01;
    let t1 = ctx.pick(60.0, 120.0);
    let mut top = EulerTop::new(&OMEGA0, params, None)?;
    let r = top.integrate_with((0.0, t1), dt, Method::ImplicitMidpoint, stride(5))?;
    let t = r.t.to_vec();
    let mut panel = Panel::new(
        format!(
            "Spin about the intermediate axis, ω(0) = ({}, {}, {}) rad/s",
            OMEGA0[0], OMEGA0[1], OMEGA0[2]
        ),
        "t (s)",
        "body-frame angular velocity (rad/s)",
    )
    .legend(Legend::UpperRight);
    for (j, name) in ["ω₁ (I₁ = 1)", "ω₂ (I₂ = 2)", "ω₃ (I₃ = 3)"]
        .iter()
        .enumerate()
    {
        panel = panel.with(Series::xy(*name, &t, &ycol(&r.y, j), color(j)));
    }
    let path = ctx.path("euler_omega.png");
    save_panel(&path, (1000, 520), &panel)?;
    d.add(
        path,
        "body-frame ω components against time: ω₂ reverses periodically (the Dzhanibekov flips)",
    );

    // Polhodes on the unit angular-momentum sphere.
    let inertia = [params.i1, params.i2, params.i3];
    let mut starts: Vec<[f64; 3]> = Vec::new();
    for a in [0.25_f64, 0.5, 0.8, 1.1] {
        starts.push([a.cos(), a.sin(), 0.0]); // loops around axis 1
        starts.push([0.0, a.sin(), a.cos()]); // loops around axis 3
        starts.push([0.0, a.sin(), -a.cos()]);
        starts.push([-a.cos(), a.sin(), 0.0]);
    }
    starts.push([0.02, 1.0, 0.02]); // next to the separatrix
    let mut sphere = Panel::new("Polhodes: L/|L| in the body frame (oblique view)", "", "")
        .x_range(-1.25, 1.25)
        .y_range(-1.25, 1.25)
        .legend(Legend::LowerRight)
        .equal_aspect();
    let outline = (0..=200)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 200.0;
            (a.cos(), a.sin())
        })
        .collect();
    sphere = sphere.with(
        Series::line("", outline, RGBColor(150, 150, 150))
            .with_mark(Mark::Line(1))
            .unlabeled(),
    );
    for (k, l0) in starts.iter().enumerate() {
        let norm = (l0[0] * l0[0] + l0[1] * l0[1] + l0[2] * l0[2]).sqrt();
        let w0: Vec<f64> = (0..3).map(|i| l0[i] / norm / inertia[i]).collect();
        let mut body = EulerTop::new(&w0, params, None)?;
        let r = body.integrate_with(
            (0.0, ctx.pick(40.0, 60.0)),
            0.02,
            Method::ImplicitMidpoint,
            stride(2),
        )?;
        let (mut front, mut back) = (Vec::new(), Vec::new());
        for row in r.y.rows() {
            let l = [
                inertia[0] * row[0],
                inertia[1] * row[1],
                inertia[2] * row[2],
            ];
            let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            let (u, v, depth) = project([l[0] / n, l[1] / n, l[2] / n], AZ, EL);
            if depth >= 0.0 {
                front.push((u, v))
            } else {
                back.push((u, v))
            }
        }
        let c = if k + 1 == starts.len() {
            color(1)
        } else {
            color(0)
        };
        sphere = sphere.with(Series::dots("", back, c).with_alpha(0.15).unlabeled());
        sphere = sphere.with(Series::dots("", front, c).unlabeled());
    }
    for (i, name) in ["1", "2", "3"].iter().enumerate() {
        let mut e = [0.0; 3];
        e[i] = 1.12;
        let (u, v, _) = project(e, AZ, EL);
        sphere = sphere.with(
            Series::line(
                format!("axis {name}"),
                vec![(0.0, 0.0), (u, v)],
                color(2 + i),
            )
            .unlabeled(),
        );
    }
    let path = ctx.path("euler_polhodes.png");
    crate::figure::save_png(&path, (760, 760), None, (1, 1), |_, area| {
        let mut chart = sphere.draw(area, &path)?;
        for (i, name) in ["axis 1", "axis 2 (unstable)", "axis 3"].iter().enumerate() {
            let mut e = [0.0; 3];
            e[i] = 1.15;
            let (u, v, _) = project(e, AZ, EL);
            chart
                .draw_series(std::iter::once(Text::new(
                    name.to_string(),
                    (u, v),
                    (FAMILY, 16).into_font().color(&color(2 + i)),
                )))
                .at(&path)?;
        }
        Ok(())
    })?;
    d.add(path, "polhodes on the angular-momentum sphere: loops around the stable axes 1 and 3, the separatrix (orange) through axis 2");

    // Tumbling plate: half-extents from I1 : I2 : I3 = (b²+c²) : (a²+c²) : (a²+b²).
    let half = {
        let s = |x: f64| x.max(0.0).sqrt();
        let (i1, i2, i3) = (params.i1, params.i2, params.i3);
        let k = 0.55 / s(0.5 * (i2 + i3 - i1)).max(1e-9);
        [
            k * s(0.5 * (i2 + i3 - i1)),
            k * s(0.5 * (i1 + i3 - i2)),
            (k * s(0.5 * (i1 + i2 - i3))).max(0.06),
        ]
    };
    let frames = ctx.pick(48, 140);
    let t_anim = ctx.pick(35.0, 70.0);
    let mut spin = EulerTop::new(&OMEGA0, params, None)?;
    let ra = spin.integrate_with((0.0, t_anim), 0.01, Method::ImplicitMidpoint, stride(1))?;
    let per = (ra.t.len() / frames).max(1);
    let path = ctx.path("euler_tumbling.gif");
    save_gif(&path, (420, 420), frames, 70, |k, root| {
        let i = (k * per).min(ra.t.len() - 1);
        let state = ra.y.row(i).to_vec();
        let rot = spin.rotation_matrix(Some(&state))?;
        draw_box(root, &path, &rot, half, ra.t[i])
    })?;
    d.add(path, "animation: the plate spun about its intermediate axis flips over and over (orientation in the space frame)");
    Ok(d)
}

/// Draws the box with half-extents `half` rotated by `rot` (body to world), faces shaded and
/// painted back to front.
fn draw_box(
    root: &crate::figure::Area<'_>,
    path: &std::path::Path,
    rot: &[[f64; 3]; 3],
    half: [f64; 3],
    t: f64,
) -> Result<()> {
    let (w, h) = root.dim_in_pixel();
    let scale = 0.42 * w.min(h) as f64;
    let (cx, cy) = (0.5 * w as f64, 0.55 * h as f64);
    let world = |b: [f64; 3]| -> [f64; 3] {
        let mut out = [0.0; 3];
        for (r, o) in rot.iter().zip(out.iter_mut()) {
            *o = r[0] * b[0] + r[1] * b[1] + r[2] * b[2];
        }
        out
    };
    let to_px = |p: [f64; 3]| -> ((i32, i32), f64) {
        let (u, v, depth) = project(p, AZ, EL);
        (((cx + scale * u) as i32, (cy - scale * v) as i32), depth)
    };
    // Faces: (axis, sign); the face colours tell the body axes apart.
    let mut faces = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0, 1.0] {
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(s1, s2)| {
                let mut p = [0.0; 3];
                p[axis] = sign * half[axis];
                p[a] = s1 * half[a];
                p[b] = s2 * half[b];
                to_px(world(p))
            });
            let depth = corners.iter().map(|c| c.1).sum::<f64>() / 4.0;
            faces.push((depth, axis, corners.map(|c| c.0)));
        }
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0));
    root.draw(&Text::new(
        format!("Tumbling plate, t = {t:.1} s"),
        (12, 10),
        (FAMILY, 20).into_font(),
    ))
    .at(path)?;
    root.draw(&Text::new(
        "space frame; the angular momentum stays fixed".to_string(),
        (12, 36),
        (FAMILY, 13).into_font().color(&RGBColor(90, 90, 90)),
    ))
    .at(path)?;
    let face_colors = [color(0), color(1), color(4)];
    for (_, axis, poly) in &faces {
        root.draw(&Polygon::new(poly.to_vec(), face_colors[*axis].filled()))
            .at(path)?;
        let mut closed = poly.to_vec();
        closed.push(poly[0]);
        root.draw(&PathElement::new(closed, BLACK.stroke_width(1)))
            .at(path)?;
    }
    Ok(())
}
