//! Demonstration 16, the Kepler perihelion precession per orbit against the post-Newtonian
//! coefficient `c_pn`, measured on an ensemble of orbits, beside first-order perturbation
//! theory.
//!
//! For `V = -k/r + c_pn/r^3`, Landau & Lifshitz (*Mechanics*, §15, problem 3) give the
//! precession per orbit to first order in `c_pn`:
//! `delta_phi = d/dL (2 mu / L) ∫_0^pi r^2 dV dphi = -6 pi c_pn mu^2 k / L^4`
//! (prograde for `c_pn < 0`).

use std::f64::consts::{PI, TAU};

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Members, Plan, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::Method;

use super::common::unwrap;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};

const A: f64 = 1.0;
const E: f64 = 0.5;

/// The angle of the Laplace–Runge–Lenz vector `p x L - mu k r/|r|` of `[x, y, px, py]`
/// (`mu = k = 1`).
fn lrl_angle(s: &[f64]) -> f64 {
    let (x, y, px, py) = (s[0], s[1], s[2], s[3]);
    let l = x * py - y * px;
    let r = x.hypot(y);
    (-px * l - y / r).atan2(py * l - x / r)
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "kepler-precession",
    text: Physics::Own(
        "An ensemble of Kepler orbits with the post-Newtonian term c_pn/r³ added to the \
         potential −k/r, swept over a range of strengths. For each member the direction of the \
         Laplace–Runge–Lenz vector is followed along the run and its mean turning rate times \
         the orbital period gives the precession per orbit (dots). First-order perturbation \
         theory (Landau & Lifshitz §15) predicts Δφ = −6π c_pn μ² k / L⁴ per orbit (line): the \
         two agree for weak corrections and part at second order in c_pn.",
    ),
    figure: "Forty orbits of semi-major axis a = 1 and eccentricity e = 0.5 in units with μ = \
         k = 1, c_pn from −0.00025 to −0.01, each run for 20 periods with yoshida4 at 4000 \
         steps per period.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Kepler: perihelion precession against c_{pn}");
    let n = ctx.pick(12, 40);
    let c_pn: Vec<f64> = (0..n).map(|i| -0.01 * (i + 1) as f64 / n as f64).collect();
    let period = TAU * A.powf(1.5);
    let orbits = ctx.pick(5.0, 20.0);
    let samples_per_orbit = 200;
    let dt = period / 4000.0;
    let members = Members {
        common: vec![
            ("a".into(), Value::Scalar(A)),
            ("e".into(), Value::Scalar(E)),
        ],
        sweeps: vec![Sweep::new("c_pn", c_pn.clone())],
        states: None,
        n,
    };
    let plan = Plan {
        t_span: (0.0, orbits * period),
        dt,
        method: Some(Method::Yoshida4),
        stride: Some(4000 / samples_per_orbit),
        reductions: vec![],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let out = ensemble::run(catalog::find("kepler")?, &members, &plan, None)?;
    let (Some(t), Some(trajectory)) = (out.t, out.trajectory) else {
        return Err(super::common::missing("trajectory"));
    };
    // L of the initial state (conserved): sqrt(mu k a (1 - e^2)).
    let l4 = (A * (1.0 - E * E)).powi(2);
    let mut measured = Vec::with_capacity(n);
    for (m, &c) in c_pn.iter().enumerate() {
        let angles: Vec<f64> = trajectory
            .index_axis(ndarray::Axis(0), m)
            .rows()
            .into_iter()
            .map(|row| lrl_angle(&row.to_vec()))
            .collect();
        let angles = unwrap(&angles);
        // Least-squares slope of the angle against time, times the period.
        let nt = t.len() as f64;
        let (mt, ma) = (t.sum() / nt, angles.iter().sum::<f64>() / nt);
        let (mut sxy, mut sxx) = (0.0, 0.0);
        for (ti, ai) in t.iter().zip(&angles) {
            sxy += (ti - mt) * (ai - ma);
            sxx += (ti - mt) * (ti - mt);
        }
        measured.push((-c * 1e3, (sxy / sxx) * period * 180.0 / PI));
    }
    let theory: Vec<(f64, f64)> = (0..=50)
        .map(|i| {
            let c = -0.01 * i as f64 / 50.0;
            (-c * 1e3, -6.0 * PI * c / l4 * 180.0 / PI)
        })
        .collect();
    let panel = Panel::new(
        format!("Precession per orbit, {n} orbits of a = {A}, e = {E} over {orbits} periods"),
        "−c_{pn} (units of 10⁻³ k a²)",
        "precession per orbit (degrees)",
    )
    .legend(Legend::Auto)
    .with(Series::line(
        "first-order theory −6π c_{pn} μ²k/L⁴",
        theory,
        color(0),
    ))
    .with(Series::dots("measured (ensemble)", measured, color(1)).with_mark(Mark::Dots(4)));
    let path = ctx.path("kepler_precession.svg");
    save_panel(&path, (900, 600), &panel)?;
    d.add(path, "precession per orbit against the post-Newtonian coefficient c_{pn}: the ensemble's measurement beside first-order perturbation theory");
    Ok(d)
}
