//! Demonstration 5, Sine-Gordon chain: a kink–antikink collision as a space–time plot and an animation.

use physicskit::classical::model::Value;
use physicskit::classical::systems::SineGordonChain;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::common::stride;
use super::{Ctx, Demo, Explanation, Physics};
use crate::animation::save_gif;
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Panel, Series};
use crate::heatmap::HeatMap;

/// Coupling: the kink is sqrt(K) = 4 sites wide, so the lattice is close to the continuum.
const K: f64 = 16.0;
/// Speed of each soliton as a fraction of the wave speed sqrt(K/m) = 4 sites per unit time.
const BETA: f64 = 0.4;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "sine-gordon",
    text: Physics::OfSystem(&physicskit::classical::systems::SINE_GORDON_KINK_ENTRY),
    figure: "The kink and the antikink approach each other at 0.4 of the wave speed.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Sine-Gordon chain: kink–antikink collision");
    let n = ctx.pick(160, 240);
    let width = K.sqrt();
    let c = K.sqrt(); // wave speed for m = 1, in sites per unit time
    let (q0, p0) = SineGordonChain::kink_antikink(
        n,
        1.0,
        K,
        0.25 * n as f64,
        0.75 * n as f64,
        width,
        BETA * c,
    )?;
    let mut chain = SineGordonChain::new(n, 1.0, K, Some(&q0), Some(&p0))?;
    // They meet after each covers n/4 sites (t = n/(4v)); run on for as long again.
    let t1 = 0.5 * n as f64 / (BETA * c);
    let dt = 0.02;
    // The lab opens on the collision: the same chain, kink and antikink, method and step.
    d.lab = Some(ctx.lab_link(
        "sine-gordon-state",
        &[
            ("n", Value::Integer(n as i64)),
            ("m", Value::Scalar(1.0)),
            ("k", Value::Scalar(K)),
            ("q0", Value::Vector(q0.clone())),
            ("p0", Value::Vector(p0.clone())),
        ],
        Method::Yoshida4,
        dt,
        chain.state(),
    )?);
    let rows = ctx.pick(150, 300);
    let every = ((t1 / dt) as usize / rows).max(1);
    let r = chain.integrate_with((0.0, t1), dt, Method::Yoshida4, stride(every))?;
    let q = r.q().ok_or_else(|| super::common::missing("q"))?;
    let ny = q.nrows();
    let values: Vec<f64> = q.iter().map(|v| v / std::f64::consts::TAU).collect();
    let map = HeatMap {
        values: values.clone(),
        title: "Kink–antikink collision on a sine-Gordon chain".into(),
        x_label: "site i".into(),
        y_label: "t (dimensionless: 1/ω₀ of one pendulum)".into(),
        value_label: "twist qᵢ / 2π".into(),
        x_range: (0.0, (n - 1) as f64),
        y_range: (r.t[0], r.t[ny - 1]),
        nx: n,
        ny,
    };
    let path = ctx.path("sine_gordon_spacetime.svg");
    save_svg(&path, (900, 700), None, (1, 1), |_, area| {
        map.draw(area, &path)
    })?;
    d.add(path, "space–time plot of the twist q/2π along the chain: the kink and antikink approach, pass through each other and separate");

    // One y range for every frame, from the whole run: after the collision the chain rings
    // down to the -1 plateau between the separating pair.
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let pad = 0.06 * (hi - lo);
    let frames = ctx.pick(40, 120);
    let per = (ny / frames).max(1);
    let path = ctx.path("sine_gordon.gif");
    save_gif(&path, (640, 360), ctx.gif_scale(), frames, 80, |k, root| {
        let i = (k * per).min(ny - 1);
        let pts = q
            .row(i)
            .iter()
            .enumerate()
            .map(|(s, v)| (s as f64, v / std::f64::consts::TAU))
            .collect();
        Panel::new(
            format!("Sine-Gordon chain, t = {:.1}", r.t[i]),
            "site i",
            "twist qᵢ / 2π",
        )
        .x_range(0.0, (n - 1) as f64)
        .y_range(lo - pad, hi + pad)
        .legend(Legend::None)
        .with(Series::line("", pts, color(0)))
        .draw(root, &path)
        .map(|_| ())
    })?;
    d.add(
        path,
        "animation of the twist profile: kink and antikink colliding and re-emerging",
    );
    Ok(d)
}
