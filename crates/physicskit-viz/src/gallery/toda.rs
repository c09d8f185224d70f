//! Demonstration 13, Toda lattice: the energy per particle sloshing around the ring (space–time
//! map and two particles) beside the n Lax eigenvalues, flat in time.

use physicskit::classical::model::Value;
use physicskit::classical::systems::TodaLattice;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::common::stride;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, ramp, save_svg, Legend, Panel, Series};
use crate::heatmap::HeatMap;

/// Particles on the ring.
const N: usize = 16;
/// Momentum kicks: `(particle, p)`. Two pulses of different heights, hence speeds.
const KICKS: [(usize, f64); 2] = [(0, 3.0), (8, -1.5)];

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "toda",
    text: Physics::OfSystem(&physicskit::classical::systems::TODA_ENTRY),
    figure: "Sixteen masses, a = b = 1; two particles are kicked with 3 and −1.5 units of \
         momentum. Left: the energy of each particle above its equilibrium share a/b; middle: \
         two particles; right: the sixteen eigenvalues of L, flat lines.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Toda lattice: n conserved quantities");
    let (a, b) = (1.0, 1.0);
    let mut p0 = [0.0; N];
    for (i, p) in KICKS {
        p0[i] = p;
    }
    let mut toda = TodaLattice::new(&[0.0; N], &p0, a, b)?;
    let lambda0 = toda.conserved_quantities(None)?;
    let dt = 0.01;
    // The lab opens on the two pulses: the same ring, kicks, method and step.
    d.lab = Some(ctx.lab_link(
        "toda",
        &[
            ("q0", Value::Vector(vec![0.0; N])),
            ("p0", Value::Vector(p0.to_vec())),
            ("a", Value::Scalar(a)),
            ("b", Value::Scalar(b)),
        ],
        Method::Yoshida4,
        dt,
        toda.state(),
    )?);
    let t1 = ctx.pick(40.0, 60.0);
    let rows = ctx.pick(200, 400);
    let every = ((t1 / dt) as usize / rows).max(1);
    let r = toda.integrate_with((0.0, t1), dt, Method::Yoshida4, stride(every))?;
    let t = r.t.to_vec();
    let ny = t.len();

    // Energy of each particle above a/b, and the eigenvalues, per stored sample.
    let mut values = Vec::with_capacity(ny * N);
    let mut traces: Vec<Vec<(f64, f64)>> = (0..2).map(|_| Vec::with_capacity(ny)).collect();
    let mut eigen: Vec<Vec<(f64, f64)>> = (0..N).map(|_| Vec::with_capacity(ny)).collect();
    let mut drift = 0.0_f64;
    let watched = [0, N / 2 + N / 4];
    for (row, &ti) in r.y.rows().into_iter().zip(&t) {
        let state = row.to_vec();
        let e = toda.particle_energies(Some(&state))?;
        values.extend(e.iter().map(|ei| ei - a / b));
        for (trace, &i) in traces.iter_mut().zip(&watched) {
            trace.push((ti, e[i] - a / b));
        }
        let lambda = toda.conserved_quantities(Some(&state))?;
        for (j, (l, l0)) in lambda.iter().zip(&lambda0).enumerate() {
            eigen[j].push((ti, *l));
            drift = drift.max((l - l0).abs());
        }
    }

    let map = HeatMap {
        title: "Energy per particle eᵢ − a/b".into(),
        x_label: "particle i".into(),
        y_label: "t (units of 1/√(ab))".into(),
        value_label: "e_{i} − a/b".into(),
        x_range: (1.0, N as f64),
        y_range: (t[0], t[ny - 1]),
        nx: N,
        ny,
        values,
    };
    let mut sloshing = Panel::new(
        "Two particles: energy comes and goes",
        "t (units of 1/√(ab))",
        "e_{i} − a/b (units of a/b)",
    )
    .legend(Legend::Auto);
    for (k, (trace, &i)) in traces.into_iter().zip(&watched).enumerate() {
        sloshing = sloshing.with(Series::line(format!("particle {}", i + 1), trace, color(k)));
    }
    let mut spectrum = Panel::new(
        format!("The {N} Lax eigenvalues (largest change in the run: {drift:.0e})"),
        "t (units of 1/√(ab))",
        "eigenvalue λ_{j} of L (momentum units)",
    )
    .legend(Legend::None);
    for (j, line) in eigen.into_iter().enumerate() {
        spectrum = spectrum.with(Series::line("", line, ramp(j, N)).unlabeled());
    }
    let path = ctx.path("toda.svg");
    save_svg(
        &path,
        (1800, 640),
        Some(
            "Periodic Toda lattice, N = 16, a = b = 1: the energy moves, the Lax spectrum does not",
        ),
        (1, 1),
        |_, area| {
            let (w, _) = area.dim_in_pixel();
            let (left, rest) = area.split_horizontally(w * 2 / 5);
            // A gap between the colour bar's label and the next panel's axis label.
            let (_, rest) = rest.split_horizontally(w / 30);
            let (middle, right) = rest.split_horizontally(w * 3 / 10 - w / 30);
            map.draw(&left, &path)?;
            sloshing.draw(&middle, &path)?;
            spectrum.draw(&right, &path)?;
            Ok(())
        },
    )?;
    d.add(
        path,
        "energy per particle around the ring against time (space–time map and two particles) beside the sixteen Lax eigenvalues, constant in time",
    );
    Ok(d)
}
