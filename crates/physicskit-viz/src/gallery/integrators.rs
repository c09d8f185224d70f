//! Demonstration 12, Integrators compared: energy error against time for the four methods on one system (a
//! large-amplitude pendulum) and a log–log convergence plot with the measured orders.

use physicskit::classical::analysis::convergence::fit_order;
use physicskit::classical::examples::Pendulum;
use physicskit::classical::model::Value;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::work_precision::words;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};

const METHODS: [Method; 4] = [
    Method::Verlet,
    Method::Yoshida4,
    Method::Rk4,
    Method::ImplicitMidpoint,
];

/// Initial angle (rad): a swing to 115°, far from the small-angle regime.
const Q0: f64 = 2.0;

/// log10 of a relative error, floored at 1e-17 so exact zeros stay plottable.
pub(crate) fn log10_rel(x: f64) -> f64 {
    x.abs().max(1e-17).log10()
}

/// The maximum of `|v|` over each of `windows` equal time windows, as `(window end, log10 max)`:
/// the envelope of an oscillating error, which shows bounded against growing at a glance.
pub(crate) fn window_max(t: &[f64], v: &[f64], windows: usize) -> Vec<(f64, f64)> {
    let n = t.len().min(v.len());
    let per = n.div_ceil(windows.max(1)).max(1);
    (0..n)
        .step_by(per)
        .map(|start| {
            let end = (start + per).min(n);
            let m = v[start..end].iter().fold(0.0_f64, |a, b| a.max(b.abs()));
            (t[end - 1], log10_rel(m))
        })
        .collect()
}

/// The running maximum of `|v|` sampled at `n` times spaced evenly in log t, as
/// `(log10 t, log10 max over [0, t])`: on these axes an error that stays bounded is a plateau
/// and one that drifts like t^k a line of slope k, with no oscillation to read through.
pub(crate) fn log_envelope(t: &[f64], v: &[f64], n: usize) -> Vec<(f64, f64)> {
    let len = t.len().min(v.len());
    let Some(first) = t.iter().position(|&x| x > 0.0) else {
        return Vec::new();
    };
    let (a, b) = (t[first].log10(), t[len - 1].log10());
    let mut out = Vec::with_capacity(n);
    let mut m = 0.0_f64;
    let mut i = 0;
    for k in 0..n {
        let tk = 10f64.powf(a + (b - a) * k as f64 / (n.max(2) - 1) as f64);
        while i < len && t[i] <= tk * (1.0 + 1e-12) {
            m = m.max(v[i].abs());
            i += 1;
        }
        if i > first {
            out.push((tk.log10(), log10_rel(m)));
        }
    }
    out
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "integrators",
    text: Physics::OfSystem(&physicskit::classical::examples::PENDULUM_ENTRY),
    figure: "The same pendulum (released from 115°, g/l = 1 s⁻²) integrated with the four methods \
         of the specification, and the convergence plot of their errors.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Integrators compared");

    // Energy error against time at a coarse step, where the differences are visible.
    let dt = 0.1;
    let t1 = ctx.pick(1000.0, 5000.0);
    let mut energy = Panel::new(
        format!("Energy error of a pendulum, dt = {dt} s"),
        "t (s)",
        format!(
            "log₁₀ |E − E(0)| / |E(0)|, max over {} s windows",
            t1 / 200.0
        ),
    )
    .legend(Legend::Auto);
    for (i, &m) in METHODS.iter().enumerate() {
        let mut p = Pendulum::new(Q0, 0.0, 1.0)?;
        if i == 0 {
            // The lab opens on the first method's run: the same pendulum and coarse step.
            d.lab = Some(ctx.lab_link(
                "pendulum",
                &[
                    ("q0", Value::Scalar(Q0)),
                    ("p0", Value::Scalar(0.0)),
                    ("g_over_l", Value::Scalar(1.0)),
                ],
                m,
                dt,
                p.state(),
            )?);
        }
        let r = p.integrate((0.0, t1), dt, m)?;
        let e = r.energy.as_ref().map(|e| e.to_vec()).unwrap_or_default();
        let e0 = e.first().copied().unwrap_or(1.0);
        let rel: Vec<f64> = e.iter().map(|&ei| (ei - e0) / e0).collect();
        let pts = window_max(r.t.as_slice().unwrap_or(&[]), &rel, 200);
        energy = energy.with(Series::line(words(m), pts, color(i)));
    }
    let path = ctx.path("integrators_energy.svg");
    save_panel(&path, (1000, 560), &energy)?;
    d.add(path, "relative energy error against time for Verlet, Yoshida 4, RK4 and the implicit midpoint rule on a pendulum (log scale)");

    // Convergence: error of the state at t = 10 s against a fine-step reference.
    let t_end = 10.0;
    let mut reference = Pendulum::new(Q0, 0.0, 1.0)?;
    let r = reference.integrate_with(
        (0.0, t_end),
        2e-4,
        Method::Yoshida4,
        physicskit::classical::IntegrateOptions {
            sampling: physicskit::classical::Sampling::FinalOnly,
            skip_energy: true,
            ..Default::default()
        },
    )?;
    let exact = r.final_state().to_vec();
    let dts = [0.1, 0.05, 0.025, 0.0125, 0.00625];
    let mut conv = Panel::new(
        "Convergence at t = 10 s (measured order p in the legend)",
        "log₁₀ dt (dt in s)",
        "log₁₀ |error of (q, p) at t = 10 s|",
    )
    .legend(Legend::Auto);
    for (i, &m) in METHODS.iter().enumerate() {
        let mut errs = Vec::with_capacity(dts.len());
        for &h in &dts {
            let mut p = Pendulum::new(Q0, 0.0, 1.0)?;
            let r = p.integrate_with(
                (0.0, t_end),
                h,
                m,
                physicskit::classical::IntegrateOptions {
                    sampling: physicskit::classical::Sampling::FinalOnly,
                    skip_energy: true,
                    ..Default::default()
                },
            )?;
            let y = r.final_state();
            errs.push(((y[0] - exact[0]).powi(2) + (y[1] - exact[1]).powi(2)).sqrt());
        }
        let fit = fit_order(&dts, &errs)?;
        let pts: Vec<_> = dts
            .iter()
            .zip(&errs)
            .map(|(h, e)| (h.log10(), e.log10()))
            .collect();
        conv = conv.with(Series::line(
            format!("{} (p = {:.2})", words(m), fit.order),
            pts.clone(),
            color(i),
        ));
        conv = conv.with(
            Series::dots("", pts, color(i))
                .with_mark(Mark::Dots(4))
                .unlabeled(),
        );
    }
    let path = ctx.path("integrators_convergence.svg");
    save_panel(&path, (900, 620), &conv)?;
    d.add(path, "log–log error against step size for the four methods, with the measured orders (2, 4, 4, 2)");
    Ok(d)
}
