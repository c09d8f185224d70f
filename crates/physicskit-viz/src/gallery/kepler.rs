//! Demonstration 7, Kepler: the closed ellipse against the precessing rosette of a post-Newtonian correction,
//! and the angle of the Laplace–Runge–Lenz vector against time.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{KeplerPerturbations, KeplerSystem};
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::common::{column, stride, unwrap};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, Legend, Panel, Series};

const A: f64 = 1.0;
const E: f64 = 0.6;
/// Strength of the attractive `c_pn / r^3` term (units k a^2): a few degrees per orbit.
const C_PN: f64 = -0.005;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "kepler",
    text: Physics::OfSystem(&physicskit::classical::systems::KEPLER_ENTRY),
    figure: "Units with G M = 1; semi-major axis 1, eccentricity 0.6.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Kepler orbits and perihelion precession");
    let period = std::f64::consts::TAU * A.powf(1.5);
    let orbits = ctx.pick(12.0, 30.0);
    let t1 = orbits * period;
    let dt = period / 2000.0;
    let every = 10;
    let mut panel = Panel::new(
        format!("Orbits over {orbits} periods (a = {A}, e = {E})"),
        "x (units of a)",
        "y (units of a)",
    )
    .legend(Legend::Auto)
    .equal_aspect();
    let mut angles = Panel::new(
        "Direction of the Laplace–Runge–Lenz vector (the perihelion)",
        "t (orbital periods)",
        "LRL angle (degrees)",
    )
    .legend(Legend::Auto);
    let cases = [
        (
            "Newtonian 1/r² (closed ellipse)",
            KeplerPerturbations::none(),
        ),
        (
            "with post-Newtonian c/r³ term (rosette)",
            KeplerPerturbations::none().with_post_newtonian(C_PN),
        ),
    ];
    for (i, (label, pert)) in cases.into_iter().enumerate() {
        let (k, mu) = (1.0, 1.0);
        let mut sys = KeplerSystem::from_orbital_elements(A, E, k, mu, pert)?;
        if i == 0 {
            // The lab opens on the closed ellipse (its catalogue entry has no c_pn term).
            d.lab = Some(ctx.lab_link(
                "kepler",
                &[
                    ("a", Value::Scalar(A)),
                    ("e", Value::Scalar(E)),
                    ("k", Value::Scalar(k)),
                    ("mu", Value::Scalar(mu)),
                ],
                Method::Yoshida4,
                dt,
                sys.state(),
            )?);
        }
        let r = sys.integrate_with((0.0, t1), dt, Method::Yoshida4, stride(every))?;
        let x = column(r.q(), 0);
        let y = column(r.q(), 1);
        let px = column(r.p(), 0);
        let py = column(r.p(), 1);
        let orbit = x.iter().copied().zip(y.iter().copied()).collect();
        panel = panel.with(
            Series::line(label, orbit, color(if i == 0 { 6 } else { 1 }))
                .with_mark(crate::figure::Mark::Line(1)),
        );
        let raw: Vec<f64> = (0..x.len())
            .map(|k| {
                let a = sys.lrl_vector(&[x[k], y[k]], &[px[k], py[k]]);
                a[1].atan2(a[0])
            })
            .collect();
        let pts =
            r.t.iter()
                .zip(unwrap(&raw))
                .map(|(&t, a)| (t / period, a.to_degrees()))
                .collect();
        angles = angles.with(Series::line(label, pts, color(if i == 0 { 6 } else { 1 })));
    }
    // The attracting centre at the focus (the origin), drawn over the orbits.
    panel = panel.with(
        Series::dots("attracting centre (focus)", vec![(0.0, 0.0)], color(2))
            .with_mark(crate::figure::Mark::Dots(6)),
    );
    let path = ctx.path("kepler_orbits.svg");
    save_panel(&path, (820, 720), &panel)?;
    d.add(path, "the closed Newtonian ellipse against the precessing rosette with a post-Newtonian 1/r³ term");
    let path = ctx.path("kepler_lrl.svg");
    save_panel(&path, (900, 520), &angles)?;
    d.add(path, "angle of the Laplace–Runge–Lenz vector against time: constant for 1/r², growing steadily with the correction");
    Ok(d)
}
