//! Demonstration 11, Projectile: trajectories at several angles with and without drag, and range against
//! angle.

use physicskit::classical::model::Value;
use physicskit::classical::systems::ProjectileMotion;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::common::column;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Mark, Panel, Series};

const SPEED: f64 = 40.0;
const G: f64 = 9.81;
/// Quadratic drag coefficient (kg/m) for a 1 kg ball: terminal speed sqrt(m g / c) = 22 m/s.
const DRAG: f64 = 0.02;
const MASS: f64 = 1.0;
/// Step of every flight (s).
const DT: f64 = 2e-3;
/// Launch angle of the flight the lab link opens (degrees).
const LAB_ANGLE: f64 = 45.0;

/// The flight until landing (y = 0), the landing point linearly interpolated between the two
/// samples that bracket it.
fn flight(angle: f64, drag: f64) -> Result<Vec<(f64, f64)>> {
    let mut ball = ProjectileMotion::from_launch(SPEED, angle, MASS, G, drag, 0.0)?;
    let dt = DT;
    // The vacuum flight time plus a margin, as a whole number of steps.
    let steps = ((ProjectileMotion::flight_time(SPEED, angle, G, 0.0)? + 0.5) / dt).ceil();
    let r = ball.integrate((0.0, steps * dt), dt, Method::Rk4)?;
    let x = column(r.q(), 0);
    let y = column(r.q(), 1);
    let mut pts = vec![(x[0], y[0])];
    for i in 1..x.len() {
        if y[i] < 0.0 {
            let f = y[i - 1] / (y[i - 1] - y[i]);
            pts.push((x[i - 1] + f * (x[i] - x[i - 1]), 0.0));
            break;
        }
        pts.push((x[i], y[i]));
    }
    Ok(pts)
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "projectile",
    text: Physics::OfSystem(&physicskit::classical::systems::PROJECTILE_ENTRY),
    figure: "A 1 kg ball launched at 40 m/s; with drag its terminal speed is 22 m/s.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Projectile motion with and without air drag");
    // The lab opens on the 45° flight with drag, launched as `flight` launches it.
    let ball = ProjectileMotion::from_launch(SPEED, LAB_ANGLE, MASS, G, DRAG, 0.0)?;
    d.lab = Some(ctx.lab_link(
        "projectile",
        &[
            ("speed", Value::Scalar(SPEED)),
            ("angle_deg", Value::Scalar(LAB_ANGLE)),
            ("m", Value::Scalar(MASS)),
            ("g", Value::Scalar(G)),
            ("drag_coeff", Value::Scalar(DRAG)),
            ("height", Value::Scalar(0.0)),
        ],
        Method::Rk4,
        DT,
        ball.state(),
    )?);
    let mut traj = Panel::new(
        "Trajectories (solid: no drag, dashed: with drag)",
        "x (m)",
        "y (m)",
    )
    .legend(Legend::Auto)
    .y_range(0.0, 85.0);
    for (i, angle) in [15.0, 30.0, 45.0, 60.0, 75.0].into_iter().enumerate() {
        traj = traj.with(Series::line(
            format!("{angle}°"),
            flight(angle, 0.0)?,
            color(i),
        ));
        traj = traj.with(
            Series::line("", flight(angle, DRAG)?, color(i))
                .with_mark(Mark::Dashed(2))
                .unlabeled(),
        );
    }
    let step = ctx.pick(5.0, 2.5);
    let angles: Vec<f64> = (1..)
        .map(|k| k as f64 * step)
        .take_while(|&a| a < 90.0)
        .collect();
    let mut vac = Vec::new();
    let mut air = Vec::new();
    let mut exact = Vec::new();
    for &a in &angles {
        vac.push((a, flight(a, 0.0)?.last().map_or(0.0, |p| p.0)));
        air.push((a, flight(a, DRAG)?.last().map_or(0.0, |p| p.0)));
        exact.push((
            a,
            ProjectileMotion::range_and_max_height(SPEED, a, G, 0.0)?.0,
        ));
    }
    let best = air
        .iter()
        .fold((0.0, 0.0), |b, &p| if p.1 > b.1 { p } else { b });
    let range = Panel::new(
        "Range against launch angle",
        "launch angle (degrees)",
        "range (m)",
    )
    .legend(Legend::Auto)
    .x_range(0.0, 90.0)
    .with(Series::line("analytic v² sin 2θ / g", exact, color(6)).with_mark(Mark::Line(1)))
    .with(Series::dots("simulated, no drag", vac, color(0)).with_mark(Mark::Dots(4)))
    .with(Series::line(
        format!("simulated with drag (best near {:.0}°)", best.0),
        air,
        color(1),
    ));
    let path = ctx.path("projectile.svg");
    let panels = [traj, range];
    save_svg(
        &path,
        (1400, 560),
        Some("Projectile launched at 40 m/s, g = 9.81 m/s², drag c = 0.02 kg/m"),
        (1, 2),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "trajectories at 15°–75° with and without quadratic drag, and the range against launch angle");
    Ok(d)
}
