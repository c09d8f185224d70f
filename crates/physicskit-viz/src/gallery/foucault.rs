//! Demonstration 22, Foucault pendulum: the swing plane turning at Ω sin φ. A rosette drawn
//! with Earth's rotation exaggerated, the closed-form solution over it, and the swing-plane
//! azimuth at the Panthéon against time beside the rate Ω sin φ.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{FoucaultParams, FoucaultPendulum};
use physicskit::classical::{DynamicalSystem, Method, OdeSystem};

use super::common::{stride, ycol};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Mark, Panel, Series};

/// Initial swing amplitude (m), released at rest to the east.
const AMPLITUDE: f64 = 3.0;
/// In the rosette, the swing plane turns once in this many swings (Earth's rate at the
/// Panthéon makes it about 7000).
const SWINGS_PER_TURN: f64 = 40.0;
const DT: f64 = 0.05;

/// The swing-plane azimuth (degrees from east, counter-clockwise) at each turning point of the
/// sampled path, where `x² + y²` has a local maximum; folded onto one continuous branch, since
/// a plane at azimuth `a` is also at `a ± 180°`.
fn plane_azimuths(t: &[f64], x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    let r2: Vec<f64> = x.iter().zip(y).map(|(x, y)| x * x + y * y).collect();
    let mut out: Vec<(f64, f64)> = Vec::new();
    for i in 1..r2.len().saturating_sub(1) {
        if r2[i] > r2[i - 1] && r2[i] >= r2[i + 1] {
            let mut a = y[i].atan2(x[i]).to_degrees();
            if let Some(&(_, prev)) = out.last() {
                a -= 180.0 * ((a - prev) / 180.0).round();
            } else {
                a -= 180.0 * (a / 180.0).round();
            }
            out.push((t[i], a));
        }
    }
    out
}

/// Least-squares slope of `y` on `x`.
fn slope(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = pts.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "foucault",
    text: Physics::OfSystem(&physicskit::classical::systems::FOUCAULT_ENTRY),
    figure: "A 67 m pendulum (g = 9.81 m/s²) released at rest 3 m east of the vertical; \
         implicit midpoint at dt = 0.05 s. Left, Earth's rate is raised so that the plane turns \
         once in 40 swings; right, the Panthéon's latitude 48.85° N and Earth's sidereal rate.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Foucault pendulum: the swing plane turning");
    let pantheon = FoucaultParams::default();
    let q0 = [AMPLITUDE, 0.0];
    let v0 = [0.0, 0.0];

    // The rosette: Earth's rate raised until the plane turns once in SWINGS_PER_TURN swings,
    // run for half a turn (the plane is back on itself after 180°).
    let omega0 = pantheon.omega0();
    let sin_lat = pantheon.latitude_deg.to_radians().sin();
    let fast = FoucaultParams {
        omega_earth: omega0 / SWINGS_PER_TURN / sin_lat,
        ..pantheon
    };
    let mut bob = FoucaultPendulum::new(&q0, &v0, fast)?;
    d.lab = Some(ctx.lab_link(
        "foucault-pendulum",
        &[
            ("q0", Value::Vector(q0.to_vec())),
            ("v0", Value::Vector(v0.to_vec())),
            ("length", Value::Scalar(fast.length)),
            ("g", Value::Scalar(fast.g)),
            ("latitude_deg", Value::Scalar(fast.latitude_deg)),
            ("omega_earth", Value::Scalar(fast.omega_earth)),
        ],
        Method::ImplicitMidpoint,
        DT,
        bob.state(),
    )?);
    let half_turn = 0.5 * bob.precession_period();
    let t1 = (half_turn / DT).round() * DT;
    let r = bob.integrate_with((0.0, t1), DT, Method::ImplicitMidpoint, stride(1))?;
    let t = r.t.to_vec();
    let (x, y) = (ycol(&r.y, 0), ycol(&r.y, 1));
    let (ax, ay) = FoucaultPendulum::analytic_solution(&q0, &v0, omega0, fast.omega_z(), &t)?;
    // The closed form at every 8th sample: dots along the numerical path.
    let every = 8;
    let exact: Vec<(f64, f64)> = ax
        .iter()
        .zip(&ay)
        .step_by(every)
        .map(|(&x, &y)| (x, y))
        .collect();
    let rosette = Panel::new(
        format!(
            "Half a turn of the swing plane, Earth's rate raised so that it turns once in {SWINGS_PER_TURN} swings"
        ),
        "x, east (m)",
        "y, north (m)",
    )
    .legend(Legend::Auto)
    .equal_aspect()
    .with(
        Series::xy("numerical (implicit midpoint)", &x, &y, color(0)).with_mark(Mark::Line(1)),
    )
    .with(Series::dots("closed-form solution", exact, color(1)).with_mark(Mark::Dots(2)));

    // The Panthéon itself: Earth's sidereal rate, the plane's azimuth at each turning point.
    let hours = ctx.pick(2.0, 6.0);
    let mut real = FoucaultPendulum::new(&q0, &v0, pantheon)?;
    let period_h = real.precession_period() / 3600.0;
    let t_end = (hours * 3600.0 / DT).round() * DT;
    let r = real.integrate_with((0.0, t_end), DT, Method::ImplicitMidpoint, stride(1))?;
    let t: Vec<f64> = r.t.to_vec();
    let turns = plane_azimuths(&t, &ycol(&r.y, 0), &ycol(&r.y, 1));
    let measured_h = -360.0 / slope(&turns) / 3600.0;
    let rate = pantheon.omega_z().to_degrees() * 3600.0; // degrees per hour
    let shown: Vec<(f64, f64)> = turns
        .iter()
        .step_by(ctx.pick(8, 24))
        .map(|&(t, a)| (t / 3600.0, a))
        .collect();
    let line = vec![(0.0, 0.0), (hours, -rate * hours)];
    let azimuth = Panel::new(
        format!(
            "At the Panthéon (φ = {}° N): 2π / (Ω sin φ) = {period_h:.1} h; measured {measured_h:.1} h",
            pantheon.latitude_deg
        ),
        "t (hours)",
        "swing-plane azimuth (degrees from east)",
    )
    .legend(Legend::Auto)
    .with(Series::line("−Ω sin φ · t", line, color(1)).with_mark(Mark::Dashed(2)))
    .with(
        Series::dots("turning points (implicit midpoint)", shown, color(0))
            .with_mark(Mark::Dots(2)),
    );

    let panels = [rosette, azimuth];
    let path = ctx.path("foucault.svg");
    save_svg(
        &path,
        (1400, 640),
        Some("Foucault pendulum, 67 m long (dt = 0.05 s)"),
        (1, 2),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(
        path,
        &format!(
            "left: the bob's path seen from the ground with Earth's rotation raised, the closed-form solution as dots; right: the swing plane's azimuth at the Panthéon over {hours} h, turning clockwise once in {period_h:.1} h"
        ),
    );
    Ok(d)
}
