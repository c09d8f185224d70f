//! Demonstration 6, Harmonic chain and coupled oscillators: normal-mode shapes, and beats between two modes.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{
    CoupledOscillators, CoupledOscillatorsParams, HarmonicChain, NormalModes,
};
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, LagrangianSystem, Method};

use super::common::{column, nonempty};
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, save_svg, Legend, Mark, Panel, Series};

/// Sites of the chain whose mode shapes are drawn.
const N: usize = 8;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "chains",
    text: Physics::OfSystem(&physicskit::classical::systems::HARMONIC_CHAIN_ENTRY),
    figure: "The first figure shows the shapes of the four lowest modes of an 8-mass chain, each \
         checked by simulation (the dots are the displacements half a period later, flipped \
         in sign as a standing wave must be). The second shows beats in a 12-mass chain \
         started in a superposition of its two highest modes (ω₁₁ and ω₁₂).",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Harmonic chain and coupled oscillators");
    // Mode shapes from the chain's own modal transform, verified by integration.
    let probe = HarmonicChain::new(&[0.0; N], &[0.0; N], 1.0, 1.0)?;
    let omega = probe.normal_mode_frequencies().to_vec();
    let mut panel = Panel::new(
        format!("Normal modes of a {N}-mass chain with fixed ends (m = 1 kg, k = 1 N/m)"),
        "mass index i (0 and 9 are the walls)",
        "displacement qᵢ (m, mode normalised)",
    )
    .x_range(0.0, (N + 1) as f64)
    .legend(Legend::Auto);
    for j in 0..4 {
        // The sine transform is its own inverse: the coordinates of the unit modal vector e_j
        // are the mode shape.
        let mut e = [0.0; N];
        e[j] = 1.0;
        let (shape, _) = probe.normal_mode_coords(&e, &[0.0; N])?;
        let mut pts = vec![(0.0, 0.0)];
        pts.extend(shape.iter().enumerate().map(|(i, &v)| ((i + 1) as f64, v)));
        pts.push(((N + 1) as f64, 0.0));
        panel = panel.with(Series::line(
            format!("mode {} (ω = {:.3} rad/s)", j + 1, omega[j]),
            pts,
            color(j),
        ));
        let half = std::f64::consts::PI / omega[j];
        let mut chain = HarmonicChain::new(&shape, &[0.0; N], 1.0, 1.0)?;
        let r = chain.integrate((0.0, half), half / 400.0, Method::Yoshida4)?;
        let last = r.final_state();
        let flipped = (0..N).map(|i| ((i + 1) as f64, -last[i])).collect();
        panel = panel.with(
            Series::dots("", flipped, color(j))
                .with_mark(Mark::Dots(5))
                .unlabeled(),
        );
    }
    let path = ctx.path("chain_modes.svg");
    save_panel(&path, (1000, 600), &panel)?;
    d.add(path, "shapes of the four lowest normal modes of an 8-mass chain; dots: minus the simulated displacement half a period later");

    // Beats between two modes: a chain of 12 coupled oscillators started in a superposition
    // of its two highest modes, whose frequencies are close (the dispersion curve flattens at
    // the band edge). The weights give mass 1 equal amplitude from each mode, so its motion is
    // a pure beat: cos(w11 t) + cos(w12 t) = 2 cos(dw t / 2) cos(w_mean t).
    const NB: usize = 12;
    let params = CoupledOscillatorsParams {
        n: NB,
        m: 1.0,
        k: 1.0,
    };
    let (ja, jb) = (NB - 1, NB);
    let (wa, wb) = (params.mode_frequency(ja), params.mode_frequency(jb));
    // Mode shapes of 1-based mode j from the library's modal transform, as above (the fixed-end
    // chain has the same modes in its Hamiltonian and Lagrangian forms).
    let probe = HarmonicChain::new(&[0.0; NB], &[0.0; NB], params.m, params.k)?;
    let shape = |j: usize| -> Result<Vec<f64>> {
        let mut e = [0.0; NB];
        e[j - 1] = 1.0;
        Ok(probe.normal_mode_coords(&e, &[0.0; NB])?.0)
    };
    let (sa, sb) = (shape(ja)?, shape(jb)?);
    let amplitude = 0.5; // metres, per mode, at mass 1
    let q0: Vec<f64> = (0..NB)
        .map(|i| amplitude * (sa[i] / sa[0] + sb[i] / sb[0]))
        .collect();
    let beat_period = std::f64::consts::TAU / (wb - wa);
    let t1 = ctx.pick(2.0, 3.0) * beat_period;
    let dt = 0.02;
    let t1 = (t1 / dt).round() * dt;
    let mut osc = CoupledOscillators::new(&q0, &[0.0; NB], params)?;
    // The lab opens on the beats: the same chain, start, method and step.
    d.lab = Some(ctx.lab_link(
        "coupled-oscillators",
        &[
            ("q0", Value::Vector(q0.clone())),
            ("qdot0", Value::Vector(vec![0.0; NB])),
            ("n", Value::Integer(NB as i64)),
            ("m", Value::Scalar(params.m)),
            ("k", Value::Scalar(params.k)),
        ],
        Method::ImplicitMidpoint,
        dt,
        osc.state(),
    )?);
    let r = osc.integrate((0.0, t1), dt, Method::ImplicitMidpoint)?;
    let t = r.t.to_vec();
    let q1 = nonempty(column(r.q(), 0), "q1")?;
    let envelope: Vec<f64> = t
        .iter()
        .map(|&ti| 2.0 * amplitude * (0.5 * (wb - wa) * ti).cos().abs())
        .collect();
    let minus: Vec<f64> = envelope.iter().map(|e| -e).collect();
    let top = Panel::new(
        format!(
            "Mass 1 of a {NB}-mass chain started in modes {ja} + {jb} (ω = {wa:.4} and {wb:.4} rad/s): beats"
        ),
        "t (s)",
        "displacement of mass 1 (m)",
    )
    .y_range(-1.3, 1.3)
    .legend(Legend::Auto)
    .with(Series::xy("simulated q₁(t)", &t, &q1, color(0)))
    .with(Series::xy(
        format!("envelope ±2a|cos(Δω t/2)|, beat period 2π/Δω = {beat_period:.0} s"),
        &t,
        &envelope,
        color(1),
    ))
    .with(Series::xy("", &t, &minus, color(1)).unlabeled());
    // The two modal energies: each mode keeps its own energy (the modes are independent); the
    // beat is interference, not an exchange between modes.
    let modes = physicskit::classical::systems::ChainModes::new(NB, 1.0, 1.0)?;
    let (mut scratch, mut energies) = ([0.0; NB], [0.0; NB]);
    let (mut ea, mut eb) = (Vec::new(), Vec::new());
    let (qs, vs) = (r.q(), r.p());
    if let (Some(qs), Some(vs)) = (qs, vs) {
        for (q, v) in qs.rows().into_iter().zip(vs.rows()) {
            let (q, v) = (q.to_vec(), v.to_vec());
            modes.energies_into(&q, &v, &mut scratch, &mut energies)?;
            ea.push(energies[ja - 1]);
            eb.push(energies[jb - 1]);
        }
    }
    let bottom = Panel::new(
        "Energy of each normal mode: constant, so the beat is interference between the modes",
        "t (s)",
        "modal energy (J)",
    )
    .legend(Legend::Auto)
    .with(Series::xy(format!("mode {ja}"), &t, &ea, color(2)))
    .with(Series::xy(format!("mode {jb}"), &t, &eb, color(3)));
    let path = ctx.path("coupled_beats.svg");
    let panels = [top, bottom];
    save_svg(&path, (1000, 800), None, (2, 1), |i, area| {
        panels[i].draw(area, &path).map(|_| ())
    })?;
    d.add(path, "beats: one mass of a 12-mass chain started in its two highest modes, with the analytic envelope, and the constant modal energies");
    Ok(d)
}
