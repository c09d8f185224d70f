//! Demonstration 20, the hoop's pitchfork as a bifurcation diagram: the equilibria against
//! the rotation rate `omega` (the library's [`HoopParams::equilibria`]) and, against the same
//! axis, the largest Lyapunov exponent of orbits at and near the bottom `theta = 0`.
//!
//! Below `omega_c = sqrt(g/R)` the bottom is a centre; above, a saddle whose linearization
//! has the exponent `sqrt(omega^2 - g/R)` ([`HoopEquilibrium::linear_exponent`]). Two
//! measured exponents go with that curve (library [`chaos_map_by`], implicit midpoint):
//! the orbit resting at the bottom (its tangent dynamics are the linearization: the measured
//! finite-time exponent is the saddle's rate), and an orbit started 0.01 rad from it, a
//! one-degree-of-freedom libration near the separatrix, regular, whose exponent tends to zero
//! over a long run.
//!
//! [`HoopEquilibrium::linear_exponent`]: physicskit::classical::systems::HoopEquilibrium::linear_exponent

use physicskit::classical::analysis::chaos_map::{chaos_map_by, Indicator, MapRun};
use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::model::erased::{DynSystem, Lagrangian};
use physicskit::classical::systems::{BeadOnRotatingHoop, HoopBranch, HoopParams};
use physicskit::classical::Method;

use super::hoop::{pitchfork_panel, title, MAX_RATIO};
use super::{Ctx, Demo};
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Mark, Panel, Series};
/// Step: the fastest saddle rate here is 7.2/s, so `h lambda` <= 0.007.
const DT: f64 = 1e-3;

/// The largest Lyapunov exponent of the bead started at `theta0` at rest, for each rate
/// `ratios[i] * omega_c`, over `t_max`.
fn exponents(params0: HoopParams, ratios: &[f64], theta0: f64, t_max: f64) -> Result<Vec<f64>> {
    let wc = params0.critical_omega();
    let beads = ratios
        .iter()
        .map(|r| {
            let params = HoopParams {
                omega: r * wc,
                ..params0
            };
            Ok(Lagrangian(BeadOnRotatingHoop::new(theta0, 0.0, params)?))
        })
        .collect::<Result<Vec<_>>>()?;
    let state = [theta0, 0.0];
    let run = MapRun {
        t_span: (0.0, t_max),
        dt: DT,
        method: Some(Method::ImplicitMidpoint),
        indicator: Indicator::MaxLyapunov {
            renormalize_every: DEFAULT_RENORMALIZE_EVERY,
        },
    };
    Ok(chaos_map_by(
        beads.len(),
        |i| (&beads[i] as &dyn DynSystem, &state[..]),
        &run,
    )?)
}

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo(
        "hoop-pitchfork",
        "Bead on a rotating hoop: the pitchfork and the Lyapunov exponent at the bottom",
    );
    let params0 = HoopParams::default();
    let wc = params0.critical_omega();
    let diagram = pitchfork_panel(params0);

    let n = ctx.pick(20, 50);
    let ratios: Vec<f64> = (1..=n).map(|k| MAX_RATIO * k as f64 / n as f64).collect();
    let (t_short, t_long, near) = (10.0, ctx.pick(40.0, 200.0), 0.01);
    let at_bottom = exponents(params0, &ratios, 0.0, t_short)?;
    let nearby = exponents(params0, &ratios, near, t_long)?;
    let fine: Vec<f64> = (0..=400).map(|k| MAX_RATIO * k as f64 / 400.0).collect();
    let linear: Vec<(f64, f64)> = fine
        .iter()
        .map(|&r| {
            let params = HoopParams {
                omega: r * wc,
                ..params0
            };
            let bottom = params
                .equilibria()
                .into_iter()
                .find(|e| e.kind == HoopBranch::Bottom);
            (r, bottom.map_or(f64::NAN, |e| e.linear_exponent()))
        })
        .collect();
    let zip = |v: &[f64]| ratios.iter().copied().zip(v.iter().copied()).collect();
    let lyapunov = Panel::new(
        "Largest Lyapunov exponent at the bottom θ = 0",
        "ω / Ω_{c}",
        "λ_{max} (1/s)",
    )
    .legend(Legend::Auto)
    .with(
        Series::line(
            "linearization: √(ω² − g/R), 0 below Ω_{c}",
            linear,
            color(0),
        )
        .with_mark(Mark::Line(2)),
    )
    .with(
        Series::dots(
            format!("measured, at rest at θ = 0, t = {t_short} s"),
            zip(&at_bottom),
            color(1),
        )
        .with_mark(Mark::Dots(4)),
    )
    .with(
        Series::dots(
            format!("measured, from θ = {near} rad, t = {t_long} s"),
            zip(&nearby),
            color(2),
        )
        .with_mark(Mark::Dots(4)),
    );

    let path = ctx.path("hoop_pitchfork.svg");
    let panels = [diagram, lyapunov];
    save_svg(
        &path,
        (1400, 560),
        Some(&title(&params0)),
        (1, 2),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "pitchfork bifurcation diagram (the library's equilibria) and the largest Lyapunov exponent at the bottom against the rotation rate, with the linearization's sqrt(ω² − g/R)");
    Ok(d)
}
