//! Demonstration 9, Heavy symmetric top: the path of the symmetry axis on the unit sphere (nutation loops),
//! and `theta(t)` next to `V_eff(theta)`.

use physicskit::classical::analysis::effective_potential_symmetric_top;
use physicskit::classical::model::Value;
use physicskit::classical::systems::{HeavySymmetricTop, SymmetricTopParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};

use super::common::{column, nonempty};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Mark, Panel, Series};

/// Initial tilt (rad), precession rate and spin (rad/s): a fast top given a small backward
/// push in phi, so the axis traces loops.
const THETA0: f64 = 0.8;
const PHIDOT0: f64 = -1.5;
const PSIDOT0: f64 = 30.0;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "heavy-top",
    text: Physics::OfSystem(&physicskit::classical::systems::HEAVY_TOP_ENTRY),
    figure: "I₁ = 1, I₃ = 0.5 kg m², M g l = 9.81 J, started with a small backward precession: \
         the tip draws loops.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Heavy symmetric top: precession and nutation");
    let params = SymmetricTopParams::default();
    let t1 = ctx.pick(6.0, 12.0);
    let mut top = HeavySymmetricTop::new(&[0.0, THETA0, 0.0], &[PHIDOT0, 0.0, PSIDOT0], params)?;
    let state0 = top.state().to_vec();
    let (p_phi, p_psi) = params.conserved_momenta(&state0)?;
    let e0 = top.current_energy();
    let dt = 5e-4;
    // The lab opens on this top: the same start, body, method and step.
    d.lab = Some(ctx.lab_link(
        "heavy-top",
        &[
            ("angles0", Value::Vector(vec![0.0, THETA0, 0.0])),
            ("angledots0", Value::Vector(vec![PHIDOT0, 0.0, PSIDOT0])),
            ("I1", Value::Scalar(params.i1)),
            ("I3", Value::Scalar(params.i3)),
            ("M", Value::Scalar(params.m)),
            ("l", Value::Scalar(params.l)),
            ("g", Value::Scalar(params.g)),
        ],
        Method::ImplicitMidpoint,
        dt,
        &state0,
    )?);
    let r = top.integrate((0.0, t1), dt, Method::ImplicitMidpoint)?;
    let phi = nonempty(column(r.q(), 0), "phi")?;
    let theta = nonempty(column(r.q(), 1), "theta")?;
    let t = r.t.to_vec();

    // Symmetry axis in space: (sin th sin phi, -sin th cos phi, cos th) for z-x-z angles.
    let axis: Vec<(f64, f64)> = phi
        .iter()
        .zip(&theta)
        .map(|(&f, &th)| (th.sin() * f.sin(), -th.sin() * f.cos()))
        .collect();
    let ring = |th: f64| -> Vec<(f64, f64)> {
        (0..=200)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 200.0;
                (th.sin() * a.cos(), th.sin() * a.sin())
            })
            .collect()
    };
    let (th_min, th_max) = theta
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let path_panel = Panel::new(
        "Tip of the symmetry axis, seen from above",
        "x (unit sphere)",
        "y (unit sphere)",
    )
    .legend(Legend::Auto)
    .equal_aspect()
    .with(
        Series::line(
            format!("turning circles θ = {th_min:.2}, {th_max:.2}"),
            ring(th_min),
            GREY,
        )
        .with_mark(Mark::Dashed(1)),
    )
    .with(
        Series::line("", ring(th_max), GREY)
            .with_mark(Mark::Dashed(1))
            .unlabeled(),
    )
    .with(Series::line("axis path", axis, color(0)));

    // A window of four nutation periods (the run holds dozens, which would print as a solid
    // band): the top starts at its smallest tilt (at rest in θ), so up to the fourth minimum
    // after the start, found in the data.
    let minima: Vec<usize> = (1..theta.len().saturating_sub(1))
        .filter(|&i| theta[i] < theta[i - 1] && theta[i] <= theta[i + 1])
        .collect();
    let end = minima.get(3).map_or(theta.len(), |&i| i + 1);
    let periods = minima.len().min(4);
    let theta_panel = Panel::new(
        format!("Nutation: tilt over {periods} periods"),
        "t (s)",
        "θ (rad)",
    )
    .legend(Legend::None)
    .with(Series::xy("θ(t)", &t[..end], &theta[..end], color(0)));

    let lo = (th_min - 0.35).max(0.05);
    let hi = (th_max + 0.35).min(std::f64::consts::PI - 0.05);
    let mut veff = Vec::new();
    for k in 0..=300 {
        let th = lo + (hi - lo) * k as f64 / 300.0;
        veff.push((
            th,
            effective_potential_symmetric_top(
                th,
                p_phi,
                p_psi,
                params.i1,
                params.i3,
                params.mgl(),
            )?,
        ));
    }
    let v_at_turn = veff.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    // Keep the curve inside the plotted window (plotters would clamp it onto the frame).
    let v_top = e0 + 1.5 * (e0 - v_at_turn).abs().max(0.5);
    veff.retain(|p| p.1 <= v_top);
    let veff_panel = Panel::new("Effective potential of the tilt", "θ (rad)", "energy (J)")
        .legend(Legend::Auto)
        .y_range(
            v_at_turn - 0.2 * (e0 - v_at_turn).abs().max(0.5),
            e0 + 1.5 * (e0 - v_at_turn).abs().max(0.5),
        )
        .with(Series::line("V_{eff}(θ)", veff, color(1)))
        .with(
            Series::line("total energy E", vec![(lo, e0), (hi, e0)], color(6))
                .with_mark(Mark::Dashed(2)),
        )
        .with(
            Series::dots("turning points", vec![(th_min, e0), (th_max, e0)], color(2))
                .with_mark(Mark::Dots(5)),
        );
    let path = ctx.path("heavy_top.svg");
    let panels = [path_panel, theta_panel, veff_panel];
    save_svg(
        &path,
        (1500, 540),
        Some("Heavy symmetric top: θ(0) = 0.8 rad, dφ/dt(0) = −1.5 rad/s, dψ/dt(0) = 30 rad/s"),
        (1, 3),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "the symmetry axis drawing nutation loops between two turning circles; θ(t) over four nutation periods; the effective potential with the energy line and turning points");
    Ok(d)
}

/// A neutral grey for reference curves.
const GREY: plotters::style::RGBColor = plotters::style::RGBColor(140, 140, 140);
