//! Demonstration 14, Elastic pendulum: the 2:1 resonance between bounce and swing, at the exact
//! resonant spring constant and at a detuned one.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{ElasticPendulum, ElasticPendulumParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};

use super::common::stride;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Panel, Series};

/// Initial stretch beyond the one the bob hangs at (m) and initial swing angle (rad): almost
/// pure bouncing.
const STRETCH: f64 = 0.1;
const THETA0: f64 = 0.02;
/// The detuned spring constant (N/m): the default, near the naive `4 m g / L0`.
const K_DETUNED: f64 = 40.0;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "elastic-pendulum",
    text: Physics::OfSystem(&physicskit::classical::systems::ELASTIC_PENDULUM_ENTRY),
    figure: "A 1 kg bob, rest length 1 m, g = 9.81 m/s², pulled 10 cm below its hanging position \
         and let go with a 1° swing: at the resonance, k = 29.43 N/m (r_eq = 4/3 m), the \
         energy passes to the swing; at k = 40 N/m (ω_s/ω_p = 2.25, close to the quoted rule) \
         the same start keeps bouncing with a swing that never grows.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Elastic pendulum: the 2:1 resonance");
    let base = ElasticPendulumParams::default();
    let k_res = ElasticPendulumParams::resonant_k(base.m, base.l0, base.g)?;
    let t1 = ctx.pick(40.0, 60.0);
    let dt = 2e-3;
    let every = 10; // one stored sample per 0.02 s
    let mut panels = Vec::new();
    for (k, label) in [(k_res, "exact resonance"), (K_DETUNED, "detuned")] {
        let params = ElasticPendulumParams { k, ..base };
        // q = (s, theta): the stretch beyond L0, STRETCH more than the one it hangs at.
        let s0 = params.equilibrium_stretch() + STRETCH;
        let ratio = params.spring_frequency() / params.swing_frequency();
        let mut bob = ElasticPendulum::new(&[s0, THETA0], &[0.0, 0.0], params)?;
        if d.lab.is_none() {
            // The lab opens on the exact resonance: the same spring, start, method and step.
            d.lab = Some(ctx.lab_link(
                "elastic-pendulum",
                &[
                    ("q0", Value::Vector(vec![s0, THETA0])),
                    ("qdot0", Value::Vector(vec![0.0, 0.0])),
                    ("m", Value::Scalar(params.m)),
                    ("k", Value::Scalar(params.k)),
                    ("L0", Value::Scalar(params.l0)),
                    ("g", Value::Scalar(params.g)),
                ],
                Method::ImplicitMidpoint,
                dt,
                bob.state(),
            )?);
        }
        let total = bob.current_energy() - params.equilibrium_energy();
        let r = bob.integrate_with((0.0, t1), dt, Method::ImplicitMidpoint, stride(every))?;
        let mut path_xy = Vec::with_capacity(r.t.len());
        let (mut bounce, mut swing) = (Vec::new(), Vec::new());
        for (row, &t) in r.y.rows().into_iter().zip(&r.t) {
            let state = row.to_vec();
            let [x, y] = bob.positions(Some(&state[..2]))?;
            path_xy.push((x, y));
            let [eb, es] = bob.mode_energies(Some(&state))?;
            bounce.push((t, eb / total));
            swing.push((t, es / total));
        }
        let trajectory = Panel::new(
            format!("{label}: k = {k:.2} N/m, ωₛ/ωₚ = {ratio:.2}"),
            "x (m)",
            "y (m)",
        )
        // The same window for both runs (the pivot is 1.2–1.3 m above it).
        .x_range(-0.3, 0.3)
        .y_range(-1.5, -1.1)
        .equal_aspect()
        .legend(Legend::None)
        .with(Series::line("", path_xy, color(0)).with_alpha(0.6));
        let energies = Panel::new(
            format!("{label}: energy in each mode (k = {k:.2} N/m)"),
            "t (s)",
            "share of the energy E − E_{eq}",
        )
        // Head room above 1 for the legend.
        .y_range(0.0, 1.35)
        .legend(Legend::Auto)
        .with(Series::line("bounce (spring)", bounce, color(1)))
        .with(Series::line("swing (pendulum)", swing, color(2)));
        panels.push((trajectory, energies));
    }
    let path = ctx.path("elastic_pendulum.svg");
    let (res, det) = (panels.remove(0), panels.remove(0));
    let grid = [res.0, res.1, det.0, det.1];
    save_svg(
        &path,
        (1500, 900),
        Some(
            "Elastic pendulum (m = 1 kg, L₀ = 1 m): bounce and swing trade energy only at ωₛ = 2ωₚ",
        ),
        (2, 2),
        |i, area| grid[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(
        path,
        "bob trajectories and the energy in the bounce and swing modes against time, at the exact 2:1 resonance k = 3mg/L₀ (top) and at k = 40 N/m (bottom)",
    );
    Ok(d)
}
