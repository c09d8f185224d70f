//! Demonstration 8, Euler top: the `omega` components with the Dzhanibekov flips, polhodes on the
//! angular-momentum sphere, and an animated tumbling plate.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{EulerTop, EulerTopParams};
use physicskit::classical::{DynamicalSystem, Method, OdeSystem};
use plotters::prelude::*;

use super::common::{frame_caption, project, stride, ycol};
use super::{Ctx, Demo, Explanation, Physics};
use crate::animation::save_gif;
use crate::error::{DrawContext, Result};
use crate::figure::{color, save_panel, Legend, Panel, Series};
use crate::font::FAMILY;

const OMEGA0: [f64; 3] = [0.01, 1.0, 0.01];
/// View direction of the 3-D drawings (radians).
const AZ: f64 = 0.7;
const EL: f64 = 0.35;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "euler-top",
    text: Physics::OfSystem(&physicskit::classical::systems::EULER_TOP_ENTRY),
    figure: "I₁ = 1, I₂ = 2, I₃ = 3 (a flat plate), spun almost exactly about axis 2.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Euler top: the tennis-racket (Dzhanibekov) effect");
    let params = EulerTopParams::default();
    let dt = 0.01;
    let t1 = ctx.pick(60.0, 120.0);
    let mut top = EulerTop::new(&OMEGA0, params, None)?;
    // The lab opens on this run: the same spin, moments of inertia, method and step.
    d.lab = Some(ctx.lab_link(
        "euler-top",
        &[
            ("omega0", Value::Vector(OMEGA0.to_vec())),
            ("I1", Value::Scalar(params.i1)),
            ("I2", Value::Scalar(params.i2)),
            ("I3", Value::Scalar(params.i3)),
        ],
        Method::ImplicitMidpoint,
        dt,
        top.state(),
    )?);
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
    .legend(Legend::Auto);
    for (j, name) in ["ω₁ (I₁ = 1)", "ω₂ (I₂ = 2)", "ω₃ (I₃ = 3)"]
        .iter()
        .enumerate()
    {
        panel = panel.with(Series::xy(*name, &t, &ycol(&r.y, j), color(j)));
    }
    let path = ctx.path("euler_omega.svg");
    save_panel(&path, (1000, 520), &panel)?;
    d.add(
        path,
        "body-frame ω components against time: ω₂ reverses periodically (the Dzhanibekov flips)",
    );

    // Polhodes on the unit angular-momentum sphere, drawn as a shaded sphere.
    let inertia = [params.i1, params.i2, params.i3];
    let mut loops: Vec<(Family, Vec<[f64; 3]>)> = Vec::new();
    for a in [0.3_f64, 0.6, 0.9, 1.2] {
        for (family, l0) in [
            (Family::Axis1, [a.cos(), a.sin(), 0.0]),
            (Family::Axis1, [-a.cos(), a.sin(), 0.0]),
            (Family::Axis3, [0.0, a.sin(), a.cos()]),
            (Family::Axis3, [0.0, a.sin(), -a.cos()]),
        ] {
            let w0: Vec<f64> = (0..3).map(|i| l0[i] / inertia[i]).collect();
            let mut body = EulerTop::new(&w0, params, None)?;
            let r = body.integrate_with(
                (0.0, ctx.pick(40.0, 60.0)),
                0.02,
                Method::ImplicitMidpoint,
                stride(2),
            )?;
            let pts =
                r.y.rows()
                    .into_iter()
                    .map(|row| {
                        let l = [
                            inertia[0] * row[0],
                            inertia[1] * row[1],
                            inertia[2] * row[2],
                        ];
                        let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
                        [l[0] / n, l[1] / n, l[2] / n]
                    })
                    .collect();
            loops.push((family, pts));
        }
    }
    // The separatrix: where 2E I₂ = L², i.e. L₃ = ±k L₁ with k² = (1/I₁ − 1/I₂)/(1/I₂ − 1/I₃),
    // two great circles through ±axis 2.
    let k = ((1.0 / inertia[0] - 1.0 / inertia[1]) / (1.0 / inertia[1] - 1.0 / inertia[2])).sqrt();
    for sign in [1.0, -1.0] {
        let n = (1.0 + k * k).sqrt();
        let u = [1.0 / n, 0.0, sign * k / n];
        let circle = (0..=360)
            .map(|j| {
                let s = std::f64::consts::TAU * f64::from(j) / 360.0;
                let (sn, cs) = s.sin_cos();
                [cs * u[0], sn, cs * u[2]]
            })
            .collect();
        loops.push((Family::Separatrix, circle));
    }
    let path = ctx.path("euler_polhodes.svg");
    crate::svg::save(&path, (760, 700), |root| {
        crate::svg::place(root, polhode_svg((760.0, 700.0), &loops), &path)
    })?;
    d.add(path, "polhodes, the paths of the angular momentum L/|L| in the body frame, on the sphere |L| = 1 seen obliquely: closed loops around the stable axes 1 and 3, and the separatrix (two great circles crossing at the unstable axis 2) between the two families");

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
    let inertia = [params.i1, params.i2, params.i3];
    let mut spin = EulerTop::new(&OMEGA0, params, None)?;
    let ra = spin.integrate_with((0.0, t_anim), 0.01, Method::ImplicitMidpoint, stride(1))?;
    let per = (ra.t.len() / frames).max(1);
    let path = ctx.path("euler_tumbling.gif");
    save_gif(&path, (420, 420), ctx.gif_scale(), frames, 70, |k, root| {
        let i = (k * per).min(ra.t.len() - 1);
        let state = ra.y.row(i).to_vec();
        let rot = spin.rotation_matrix(Some(&state))?;
        // The angular momentum in space, R (I ω): the same direction in every frame.
        let l_body = [
            inertia[0] * state[0],
            inertia[1] * state[1],
            inertia[2] * state[2],
        ];
        let mut l = [0.0; 3];
        for (o, row) in l.iter_mut().zip(&rot) {
            *o = row[0] * l_body[0] + row[1] * l_body[1] + row[2] * l_body[2];
        }
        draw_box(root, &path, &rot, half, l, ra.t[i])
    })?;
    d.add(path, "animation: the plate spun about its intermediate axis flips over and over (orientation in the space frame)");
    Ok(d)
}

/// Which family a polhode belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    /// Loops around the axis of least inertia.
    Axis1,
    /// Loops around the axis of greatest inertia.
    Axis3,
    /// The separatrix through the intermediate axis.
    Separatrix,
}

/// View of the polhode sphere: from between axes 1 and 2, above the 1–2 plane, so loops around
/// axes 1 and 3 are both seen open and the separatrix's crossing at axis 2 faces the reader.
const POLHODE_AZ: f64 = 0.85;
const POLHODE_EL: f64 = 0.45;

/// The polhode figure: a shaded sphere, the curves (their hidden halves faint and dashed), the
/// three body axes as arrows with labels outside the sphere, a title and a legend in the
/// lower left corner, which the sphere leaves empty.
fn polhode_svg(size: (f64, f64), loops: &[(Family, Vec<[f64; 3]>)]) -> String {
    use crate::svg::{hex, num, text};
    use std::fmt::Write as _;
    let r = 0.34 * size.0.min(size.1);
    let (cx, cy) = (0.5 * size.0, 0.53 * size.1);
    let px = |p: [f64; 3]| {
        let (u, v, depth) = project(p, POLHODE_AZ, POLHODE_EL);
        (cx + r * u, cy - r * v, depth)
    };
    let mut s = String::new();
    s.push_str(&crate::figure::title_svg(
        &["Polhodes on the angular-momentum sphere".to_string()],
        crate::figure::FIGURE_TITLE_SIZE,
        cx,
        6.0,
    ));
    let _ = writeln!(
        s,
        "<defs><radialGradient id=\"pkshade\" cx=\"0.38\" cy=\"0.32\" r=\"0.75\">\
         <stop offset=\"0\" stop-color=\"#FFFFFF\"/><stop offset=\"1\" stop-color=\"#C9D3DD\"/>\
         </radialGradient></defs>\n<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"url(#pkshade)\" stroke=\"#8A949E\" stroke-width=\"1\"/>",
        num(cx),
        num(cy),
        num(r)
    );
    let style = |f: Family| match f {
        Family::Axis1 => (hex(color(0)), 1.6),
        Family::Axis3 => (hex(color(2)), 1.6),
        Family::Separatrix => (hex(color(1)), 2.6),
    };
    // Hidden halves first, then the visible ones on top.
    for front in [false, true] {
        for (family, pts) in loops {
            let (c, w) = style(*family);
            let mut d = String::new();
            let mut pen_up = true;
            for p in pts {
                let (x, y, depth) = px(*p);
                if (depth >= 0.0) == front {
                    let _ = write!(d, "{}{} {}", if pen_up { 'M' } else { 'L' }, num(x), num(y));
                    pen_up = false;
                } else {
                    pen_up = true;
                }
            }
            if d.is_empty() {
                continue;
            }
            let look = if front {
                format!("stroke-width=\"{w}\"")
            } else {
                format!(
                    "stroke-width=\"{}\" stroke-opacity=\"0.35\" stroke-dasharray=\"3 3\"",
                    w * 0.7
                )
            };
            let _ = writeln!(
                s,
                "<path d=\"{d}\" fill=\"none\" stroke=\"{c}\" stroke-linejoin=\"round\" {look}/>"
            );
        }
    }
    // Body axes: an arrow from the surface outwards, the label beyond its tip.
    for (i, name) in [
        "axis 1 (I₁ = 1)",
        "axis 2 (I₂ = 2, unstable)",
        "axis 3 (I₃ = 3)",
    ]
    .iter()
    .enumerate()
    {
        let mut a = [0.0; 3];
        let mut b = [0.0; 3];
        let mut l = [0.0; 3];
        a[i] = 1.0;
        b[i] = 1.22;
        l[i] = 1.3;
        let (x0, y0, depth) = px(a);
        let (x1, y1, _) = px(b);
        let (lx, ly, _) = px(l);
        let dash = if depth < 0.0 {
            " stroke-dasharray=\"3 3\""
        } else {
            ""
        };
        let _ = writeln!(
            s,
            "<path d=\"M{} {}L{} {}\" stroke=\"#333333\" stroke-width=\"1.5\"{dash}/>\n<circle cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"#333333\"/>",
            num(x0),
            num(y0),
            num(x1),
            num(y1),
            num(x1),
            num(y1)
        );
        let anchor = if lx < cx - 0.2 * r {
            "end"
        } else if lx > cx + 0.2 * r {
            "start"
        } else {
            "middle"
        };
        let ty = if ly < cy { ly - 2.0 } else { ly + 12.0 };
        s.push_str(&text(lx, ty, 14.0, false, anchor, "#222222", name));
    }
    // Legend: lower left, below the sphere's lowest point's left tangent.
    let entries = [
        (Family::Axis1, "loops around axis 1 (stable)"),
        (Family::Axis3, "loops around axis 3 (stable)"),
        (Family::Separatrix, "separatrix through axis 2"),
        (Family::Axis1, "hidden side (dashed, faint)"),
    ];
    let lw = 10.0
        + 26.0
        + 8.0
        + entries
            .iter()
            .map(|e| crate::text::width(e.1, 13.0, false))
            .fold(0.0, f64::max)
        + 10.0;
    let lh = 8.0 + 19.0 * entries.len() as f64;
    let (x0, y0) = (10.0, size.1 - 10.0 - lh);
    let _ = writeln!(
        s,
        "<g class=\"pk-legend\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"3\" fill=\"#FFFFFF\" fill-opacity=\"0.92\" stroke=\"#B4B4B4\" stroke-width=\"1\"/>",
        num(x0),
        num(y0),
        num(lw),
        num(lh)
    );
    for (k, (family, label)) in entries.iter().enumerate() {
        let y = y0 + 4.0 + (k as f64 + 0.5) * 19.0;
        let (c, w) = style(*family);
        let look = if k == 3 {
            format!(
                "stroke-width=\"{}\" stroke-opacity=\"0.35\" stroke-dasharray=\"3 3\"",
                w * 0.7
            )
        } else {
            format!("stroke-width=\"{w}\"")
        };
        let _ = writeln!(
            s,
            "<path d=\"M{} {}h26\" fill=\"none\" stroke=\"{c}\" {look}/>",
            num(x0 + 10.0),
            num(y)
        );
        s.push_str(&text(
            x0 + 44.0,
            y + 4.5,
            13.0,
            false,
            "start",
            "#222222",
            label,
        ));
    }
    s.push_str("</g>\n");
    s
}

/// Draws the box with half-extents `half` rotated by `rot` (body to world), faces shaded and
/// painted back to front.
fn draw_box(
    root: &crate::figure::Area<'_>,
    path: &std::path::Path,
    rot: &[[f64; 3]; 3],
    half: [f64; 3],
    l: [f64; 3],
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
    frame_caption(
        root,
        path,
        &format!("Tumbling plate, t = {t:.1} s"),
        "space frame; the angular momentum L stays fixed",
    )?;
    let face_colors = [color(0), color(1), color(4)];
    // The L arrow through the plate's centre: its hidden part (behind the plate) is drawn
    // first, the part in front of the plate after the faces.
    let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt().max(1e-300);
    let tip = [0.95 * l[0] / n, 0.95 * l[1] / n, 0.95 * l[2] / n];
    let ((tx, ty), _) = to_px(tip);
    let ((ox, oy), _) = to_px([0.0; 3]);
    let arrow = RGBColor(30, 30, 30);
    root.draw(&PathElement::new(
        vec![(ox, oy), (tx, ty)],
        arrow.mix(0.35).stroke_width(2),
    ))
    .at(path)?;
    for (_, axis, poly) in &faces {
        root.draw(&Polygon::new(poly.to_vec(), face_colors[*axis].filled()))
            .at(path)?;
        let mut closed = poly.to_vec();
        closed.push(poly[0]);
        root.draw(&PathElement::new(closed, BLACK.stroke_width(1)))
            .at(path)?;
    }
    // The visible stretch: from the plate's outline along L to the tip, with a head.
    let start = [0.5 * tip[0], 0.5 * tip[1], 0.5 * tip[2]];
    let ((sx, sy), _) = to_px(start);
    root.draw(&PathElement::new(
        vec![(sx, sy), (tx, ty)],
        arrow.stroke_width(3),
    ))
    .at(path)?;
    let (dx, dy) = (f64::from(tx - sx), f64::from(ty - sy));
    let len = dx.hypot(dy).max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let head = |side: f64| {
        (
            (f64::from(tx) - 12.0 * ux + side * 6.0 * uy) as i32,
            (f64::from(ty) - 12.0 * uy - side * 6.0 * ux) as i32,
        )
    };
    root.draw(&Polygon::new(
        vec![(tx, ty), head(1.0), head(-1.0)],
        arrow.filled(),
    ))
    .at(path)?;
    root.draw(&Text::new(
        "L".to_string(),
        (
            (f64::from(tx) + 10.0 * ux + 6.0) as i32,
            (f64::from(ty) + 10.0 * uy - 8.0) as i32,
        ),
        (FAMILY, 20).into_font().style(FontStyle::Bold),
    ))
    .at(path)?;
    Ok(())
}
