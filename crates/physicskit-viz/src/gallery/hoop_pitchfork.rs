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
use super::{Ctx, Demo, Explanation, Physics};
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

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "hoop-pitchfork",
    text: Physics::Own(
        "The bead on the rotating hoop as a bifurcation diagram. Left: the equilibria at \
         rest against the rotation rate ω, from the library's analysis of V_eff = −R²ω² sin²θ/2 \
         + gR(1 − cos θ): the bottom is stable up to ω_c = √(g/R), then gives way to the pair \
         θ* = ±arccos(g/(Rω²)); the top is always unstable. Right: the largest Lyapunov \
         exponent at the bottom. Linearized about θ = 0 the motion is x'' = (ω² − g/R)x: a \
         centre below ω_c, with exponent zero, and a saddle above it, whose deviations grow as \
         exp(t√(ω² − g/R)) (line). The orbit resting exactly at the bottom has these tangent \
         dynamics, and its measured finite-time exponent follows the line, crossing zero at \
         ω_c; below ω_c it scatters about zero by the 1/t of a bounded rotation. An orbit \
         started slightly off the bottom is different: with one degree of freedom every orbit \
         lies on a regular curve, here a libration about one of the new minima that passes \
         close to the saddle. Over a short window near the saddle its deviations grow at the \
         saddle's rate, but over a long run they only grow linearly, and its exponent tends to \
         zero like ln(t)/t: the hoop is not chaotic, the exponent at the bottom measures the \
         instability of the equilibrium.",
    ),
    figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; implicit midpoint at dt = 0.001 s; the \
         orbit at rest at the bottom (orange dots) run for 10 s, the one started 0.01 rad from \
         it (green dots) for 200 s.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d =
        ctx.demo("Bead on a rotating hoop: the pitchfork and the Lyapunov exponent at the bottom");
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
