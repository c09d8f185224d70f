//! Demonstration 4, FPUT: energies of the first five normal modes against time, showing the recurrence.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{FPUTChain, NormalModes};
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

use super::common::stride;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, Legend, Panel, Series};

/// Chain size, nonlinearity and initial amplitude of mode 1.
const N: usize = 32;
const BETA: f64 = 1.0;
const AMPLITUDE: f64 = 3.0;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "fput",
    text: Physics::OfSystem(&physicskit::classical::systems::FPUT_ENTRY),
    figure: "32 masses; the figure follows the energies of the lowest modes.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Fermi–Pasta–Ulam–Tsingou recurrence");
    let dt = 0.05;
    let t1 = ctx.pick(10000.0, 20000.0);
    let (m, k, mode) = (1.0, 1.0, 1);
    let mut chain = FPUTChain::new(N, m, k, BETA, mode, AMPLITUDE)?;
    // The lab opens on this chain, method and step.
    d.lab = Some(ctx.lab_link(
        "fput",
        &[
            ("n", Value::Integer(N as i64)),
            ("m", Value::Scalar(m)),
            ("k", Value::Scalar(k)),
            ("beta", Value::Scalar(BETA)),
            ("mode", Value::Integer(mode as i64)),
            ("amplitude", Value::Scalar(AMPLITUDE)),
        ],
        Method::Yoshida4,
        dt,
        chain.state(),
    )?);
    let every = ctx.pick(200, 100);
    let r = chain.integrate_with((0.0, t1), dt, Method::Yoshida4, stride(every))?;
    let (q, p) = match (r.q(), r.p()) {
        (Some(q), Some(p)) => (q, p),
        _ => return Err(super::common::missing("q and p")),
    };
    let mut modes: Vec<Vec<(f64, f64)>> = (0..N).map(|_| Vec::with_capacity(r.t.len())).collect();
    let mut total = 0.0;
    for (i, &t) in r.t.iter().enumerate() {
        let e = chain.modal_energies(&q.row(i).to_vec(), &p.row(i).to_vec())?;
        if i == 0 {
            total = e.iter().sum();
        }
        for (m, ej) in modes.iter_mut().zip(&e) {
            m.push((t, ej / total));
        }
    }
    // The first five modes that take part: the cubic force couples mode 1 only to odd modes,
    // so the even ones stay at rounding level (a flat line on the axis, no information).
    // A mode counts if it ever holds a thousandth of the energy.
    let modes: Vec<(usize, Vec<(f64, f64)>)> = modes
        .into_iter()
        .enumerate()
        .filter(|(_, m)| m.iter().any(|p| p.1 > 1e-3))
        .take(5)
        .collect();
    let mut panel = Panel::new(
        format!("FPUT β-chain: N = {N}, β = {BETA}, mode 1 excited (amplitude {AMPLITUDE})"),
        "t (units of √(m/k))",
        "modal energy E_{j} / E(0)",
    )
    .y_range(0.0, 1.3)
    .legend(Legend::Auto);
    let shown: Vec<String> = modes.iter().map(|(j, _)| (j + 1).to_string()).collect();
    for (k, (j, m)) in modes.into_iter().enumerate() {
        panel = panel.with(Series::line(format!("mode {}", j + 1), m, color(k)));
    }
    let path = ctx.path("fput_modes.svg");
    save_panel(&path, (1000, 560), &panel)?;
    d.add(path, &format!("energies of normal modes {} against time (the even modes stay empty: the symmetric force never feeds them): energy leaves mode 1 and returns, the FPUT recurrence", shown.join(", ")));
    Ok(d)
}
