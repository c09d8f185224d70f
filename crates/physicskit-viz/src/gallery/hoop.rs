//! Demonstration 10, Bead on a rotating hoop: the pitchfork bifurcation and phase portraits below and above
//! the critical speed.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{BeadOnRotatingHoop, HoopBranch, HoopParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};

use super::common::{column, nonempty};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, ramp, save_svg, Legend, Mark, Panel, Series};

/// Largest rotation rate of the pitchfork diagrams (this demonstration's and demonstration
/// 20's), in units of `omega_c`.
pub(super) const MAX_RATIO: f64 = 2.5;

/// Step of the phase-portrait orbits (s).
const DT: f64 = 0.002;

/// The figure title of a hoop demonstration, stating the parameters it was drawn with.
pub(super) fn title(params: &HoopParams) -> String {
    format!(
        "Bead on a hoop rotating about its vertical diameter (R = {} m, g = {} m/s²)",
        params.r, params.g
    )
}

/// The equilibria at rest against `omega / omega_c` from 0 to [`MAX_RATIO`], from the library
/// ([`HoopParams::equilibria`]), one line per branch ([`HoopBranch`]: bottom, top, the
/// off-axis pair), solid where stable and dashed where unstable.
pub(super) fn pitchfork_panel(params0: HoopParams) -> Panel {
    let wc = params0.critical_omega();
    // Uniform below omega_c; above it, closer near omega_c, where the branches leave the
    // bottom like sqrt(omega - omega_c).
    let n = 150;
    let ratios = (0..n)
        .map(|k| k as f64 / n as f64)
        .chain((0..=2 * n).map(|k| 1.0 + (MAX_RATIO - 1.0) * (k as f64 / (2 * n) as f64).powi(2)));
    // Branch points (omega / omega_c, theta in degrees, stable).
    let mut branches: [Vec<(f64, f64, bool)>; 4] = Default::default();
    for ratio in ratios {
        let params = HoopParams {
            omega: ratio * wc,
            ..params0
        };
        for e in params.equilibria() {
            let b = match e.kind {
                HoopBranch::Bottom => 0,
                HoopBranch::Left => 1,
                HoopBranch::Right => 2,
                HoopBranch::Top => 3,
            };
            branches[b].push((ratio, e.theta.to_degrees(), e.is_stable()));
        }
    }
    let mut panel = Panel::new(
        format!("Equilibria (Ω_{{c}} = √(g/R) = {wc:.2} rad/s)"),
        "ω / Ω_{c}",
        "equilibrium angle θ* (degrees)",
    );
    let (mut stable_named, mut unstable_named) = (false, false);
    for branch in &branches {
        // Runs of equal stability; each run starts at the previous run's last point.
        let mut start = 0;
        while start < branch.len() {
            let stable = branch[start].2;
            let end = branch[start..]
                .iter()
                .position(|p| p.2 != stable)
                .map_or(branch.len(), |k| start + k);
            let pts = branch[start.saturating_sub(1)..end]
                .iter()
                .map(|p| (p.0, p.1))
                .collect();
            let named = if stable {
                &mut stable_named
            } else {
                &mut unstable_named
            };
            let series = if stable {
                Series::line("stable", pts, color(0)).with_mark(Mark::Line(3))
            } else {
                Series::line("unstable", pts, color(1)).with_mark(Mark::Dashed(2))
            };
            panel = panel.with(if *named { series.unlabeled() } else { series });
            *named = true;
            start = end;
        }
    }
    panel.y_range(-200.0, 200.0).legend(Legend::Auto)
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "hoop",
    text: Physics::OfSystem(&physicskit::classical::systems::HOOP_ENTRY),
    figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; the phase portraits are at ω = 0.7 ω_c \
         and 1.6 ω_c.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Bead on a rotating hoop: a pitchfork bifurcation");
    let params0 = HoopParams::default();
    let wc = params0.critical_omega();
    let diagram = pitchfork_panel(params0);

    let t1 = ctx.pick(6.0, 10.0);
    let mut portraits = Vec::new();
    for ratio in [0.7, 1.6] {
        let params = HoopParams {
            omega: ratio * wc,
            ..params0
        };
        let mut panel = Panel::new(
            format!("Phase portrait at ω = {ratio} Ω_{{c}}"),
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
                if d.lab.is_none() && ratio > 1.0 {
                    // The lab opens on the first orbit above the critical speed.
                    d.lab = Some(ctx.lab_link(
                        "hoop",
                        &[
                            ("theta0", Value::Scalar(sign * th0)),
                            ("thetadot0", Value::Scalar(0.0)),
                            ("R", Value::Scalar(params.r)),
                            ("omega", Value::Scalar(params.omega)),
                            ("g", Value::Scalar(params.g)),
                        ],
                        Method::ImplicitMidpoint,
                        DT,
                        bead.state(),
                    )?);
                }
                let r = bead.integrate((0.0, t1), DT, Method::ImplicitMidpoint)?;
                let th = nonempty(column(r.q(), 0), "theta")?;
                let om = column(r.p(), 0);
                let pts = th
                    .iter()
                    .map(|&a| super::common::wrap(a))
                    .zip(om.iter().copied())
                    .collect();
                panel = panel.with(Series::dots("", pts, ramp(k, starts)).with_mark(Mark::Dots(1)));
            }
        }
        let eq = params
            .stable_equilibria()
            .into_iter()
            .map(|theta| (theta, 0.0))
            .collect();
        panel =
            panel.with(Series::dots("stable equilibria", eq, color(6)).with_mark(Mark::Dots(5)));
        portraits.push(panel);
    }
    let path = ctx.path("hoop_bifurcation.svg");
    let panels = [diagram, portraits.remove(0), portraits.remove(0)];
    save_svg(
        &path,
        (1500, 540),
        Some(&title(&params0)),
        (1, 3),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "pitchfork bifurcation diagram (stable solid, unstable dashed) and phase portraits below and above the critical speed");
    Ok(d)
}
