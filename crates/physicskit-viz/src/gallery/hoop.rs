//! Demonstration 10, Bead on a rotating hoop: the pitchfork bifurcation and phase portraits below and above
//! the critical speed.

use physicskit::classical::systems::{BeadOnRotatingHoop, HoopParams};
use physicskit::classical::{LagrangianSystem, Method};

use super::common::{column, nonempty};
use super::{demo, Ctx, Demo};
use crate::error::Result;
use crate::figure::{color, save_png, Legend, Mark, Panel, Series};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = demo(
        "hoop",
        "10. Bead on a rotating hoop: a pitchfork bifurcation",
    );
    let params0 = HoopParams::default();
    let wc = params0.critical_omega();
    // Equilibria, from d V_eff/d theta = m R sin(theta) (g - R w^2 cos(theta)) = 0.
    let n = 300;
    let ws: Vec<f64> = (0..=n).map(|k| 2.5 * wc * k as f64 / n as f64).collect();
    let below: Vec<(f64, f64)> = ws
        .iter()
        .filter(|&&w| w <= wc)
        .map(|&w| (w / wc, 0.0))
        .collect();
    let above_zero: Vec<(f64, f64)> = ws
        .iter()
        .filter(|&&w| w >= wc)
        .map(|&w| (w / wc, 0.0))
        .collect();
    let branch = |sign: f64| -> Vec<(f64, f64)> {
        ws.iter()
            .filter(|&&w| w >= wc)
            .map(|&w| {
                (
                    w / wc,
                    sign * (params0.g / (params0.r * w * w))
                        .min(1.0)
                        .acos()
                        .to_degrees(),
                )
            })
            .collect()
    };
    let top: Vec<(f64, f64)> = ws.iter().map(|&w| (w / wc, 180.0)).collect();
    let diagram = Panel::new(
        format!("Equilibria (ω_c = √(g/R) = {wc:.2} rad/s)"),
        "ω / ω_c",
        "equilibrium angle θ* (degrees)",
    )
    .y_range(-200.0, 200.0)
    .legend(Legend::LowerLeft)
    .with(Series::line("stable", below, color(0)).with_mark(Mark::Line(3)))
    .with(Series::line("unstable", above_zero, color(1)).with_mark(Mark::Dashed(2)))
    .with(
        Series::line("", branch(1.0), color(0))
            .with_mark(Mark::Line(3))
            .unlabeled(),
    )
    .with(
        Series::line("", branch(-1.0), color(0))
            .with_mark(Mark::Line(3))
            .unlabeled(),
    )
    .with(
        Series::line("", top, color(1))
            .with_mark(Mark::Dashed(2))
            .unlabeled(),
    );

    let t1 = ctx.pick(6.0, 10.0);
    let mut portraits = Vec::new();
    for ratio in [0.7, 1.6] {
        let params = HoopParams {
            omega: ratio * wc,
            ..params0
        };
        let mut panel = Panel::new(
            format!("Phase portrait at ω = {ratio} ω_c"),
            "θ (rad)",
            "dθ/dt (rad/s)",
        )
        .x_range(-std::f64::consts::PI, std::f64::consts::PI)
        .legend(Legend::None);
        let starts = ctx.pick(7, 11);
        for k in 0..starts {
            let th0 = 0.1 + (std::f64::consts::PI - 0.3) * k as f64 / (starts - 1) as f64;
            for sign in [1.0, -1.0] {
                let mut bead = BeadOnRotatingHoop::new(sign * th0, 0.0, params)?;
                let r = bead.integrate((0.0, t1), 0.002, Method::ImplicitMidpoint)?;
                let th = nonempty(column(r.q(), 0), "theta")?;
                let om = column(r.p(), 0);
                let pts = th
                    .iter()
                    .map(|&a| super::common::wrap(a))
                    .zip(om.iter().copied())
                    .collect();
                panel = panel.with(Series::dots("", pts, color(k)).with_mark(Mark::Dots(1)));
            }
        }
        let eq: Vec<(f64, f64)> = if ratio > 1.0 {
            let a = (1.0 / (ratio * ratio)).acos();
            vec![(a, 0.0), (-a, 0.0)]
        } else {
            vec![(0.0, 0.0)]
        };
        panel =
            panel.with(Series::dots("stable equilibria", eq, color(6)).with_mark(Mark::Dots(5)));
        portraits.push(panel);
    }
    let path = ctx.path("10_hoop_bifurcation.png");
    let panels = [diagram, portraits.remove(0), portraits.remove(0)];
    save_png(
        &path,
        (1500, 540),
        Some("Bead on a hoop rotating about its vertical diameter (R = 1 m, g = 9.81 m/s²)"),
        (1, 3),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "pitchfork bifurcation diagram (stable solid, unstable dashed) and phase portraits below and above the critical speed");
    Ok(d)
}
