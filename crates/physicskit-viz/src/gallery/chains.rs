//! Demonstration 6, Harmonic chain and coupled oscillators: normal-mode shapes, and beats between two modes.

use physicskit::classical::systems::{
    CoupledOscillators, CoupledOscillatorsParams, HarmonicChain, NormalModes,
};
use physicskit::classical::{HamiltonianSystem, LagrangianSystem, Method};

use super::common::{column, nonempty};
use super::{demo, Ctx, Demo};
use crate::error::Result;
use crate::figure::{color, save_panel, save_png, Legend, Mark, Panel, Series};

/// Sites of the chain whose mode shapes are drawn.
const N: usize = 8;

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = demo(
        "chains",
        "6. Harmonic chain and coupled oscillators",
        "Masses joined by identical springs between two walls move, for small oscillations, as a \
         superposition of normal modes: standing waves in which every mass oscillates at the \
         same frequency ωⱼ = 2√(k/m) sin(jπ/2(N+1)). The first figure shows the shapes of the \
         four lowest modes of an 8-mass chain, each checked by simulation: started in a mode \
         shape, the chain stays in it (the dots are the displacements half a period later, \
         flipped in sign as a standing wave must be). The second shows beats: two coupled \
         oscillators with only the first one displaced. That start is a sum of the two normal \
         modes, which drift in and out of phase, so the motion passes back and forth between \
         the masses at the difference frequency.",
    );
    // Mode shapes from the chain's own modal transform, verified by integration.
    let probe = HarmonicChain::new(&[0.0; N], &[0.0; N], 1.0, 1.0)?;
    let omega = probe.normal_mode_frequencies().to_vec();
    let mut panel = Panel::new(
        format!("Normal modes of a {N}-mass chain with fixed ends (m = 1 kg, k = 1 N/m)"),
        "mass index i (0 and 9 are the walls)",
        "displacement qᵢ (m, mode normalised)",
    )
    .x_range(0.0, (N + 1) as f64)
    .legend(Legend::LowerLeft);
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
    let path = ctx.path("06_chain_modes.png");
    save_panel(&path, (1000, 600), &panel)?;
    d.add(path, "shapes of the four lowest normal modes of an 8-mass chain; dots: minus the simulated displacement half a period later");

    // Beats between the two modes of two coupled oscillators.
    let params = CoupledOscillatorsParams {
        n: 2,
        m: 1.0,
        k: 1.0,
    };
    let t1 = ctx.pick(60.0, 120.0);
    let mut osc = CoupledOscillators::new(&[1.0, 0.0], &[0.0, 0.0], params)?;
    let r = osc.integrate((0.0, t1), 0.01, Method::ImplicitMidpoint)?;
    let t = r.t.to_vec();
    let q1 = nonempty(column(r.q.as_ref(), 0), "q1")?;
    let q2 = nonempty(column(r.q.as_ref(), 1), "q2")?;
    let (w1, w2) = (params.mode_frequency(1), params.mode_frequency(2));
    let top = Panel::new(
        format!("Two coupled oscillators, mass 1 displaced by 1 m (mode frequencies {w1:.3} and {w2:.3} rad/s)"),
        "t (s)",
        "displacement (m)",
    )
    .y_range(-1.3, 1.3)
    .legend(Legend::UpperRight)
    .with(Series::xy("mass 1", &t, &q1, color(0)))
    .with(Series::xy("mass 2", &t, &q2, color(1)));
    // Energy in each mass's own spring-and-motion share shows the exchange more clearly.
    let v1 = column(r.p.as_ref(), 0);
    let v2 = column(r.p.as_ref(), 1);
    let e1: Vec<f64> = (0..t.len())
        .map(|i| 0.5 * v1[i] * v1[i] + 0.5 * q1[i] * q1[i])
        .collect();
    let e2: Vec<f64> = (0..t.len())
        .map(|i| 0.5 * v2[i] * v2[i] + 0.5 * q2[i] * q2[i])
        .collect();
    let bottom = Panel::new(
        format!(
            "Energy passing between the masses: beat period 2π/(ω₂ − ω₁) = {:.1} s",
            std::f64::consts::TAU / (w2 - w1)
        ),
        "t (s)",
        "mv²/2 + kq²/2 of each mass (J)",
    )
    .legend(Legend::UpperRight)
    .with(Series::xy("mass 1", &t, &e1, color(0)))
    .with(Series::xy("mass 2", &t, &e2, color(1)));
    let path = ctx.path("06_coupled_beats.png");
    let panels = [top, bottom];
    save_png(&path, (1000, 800), None, (2, 1), |i, area| {
        panels[i].draw(area, &path).map(|_| ())
    })?;
    d.add(path, "beats: displacements of two coupled oscillators and the energy passing back and forth between them");
    Ok(d)
}
