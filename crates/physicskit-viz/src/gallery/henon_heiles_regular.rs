//! Demonstration 21, the Hénon–Heiles fraction of regular orbits against energy (Hénon & Heiles,
//! *Astron. J.* 69, 73–79, 1964, their figure of the "relative area covered by curves"),
//! measured by SALI on one ensemble.
//!
//! For each energy `E` of a ladder, a grid of starts on the surface of section `x = 0` with
//! `p_x >= 0` from the energy (the cells inside the energy curve, the gallery's shared
//! [`SectionStarts`]); each start is one ensemble member, and its SALI at `t1`
//! classifies it: regular when above the chaos toolkit's threshold [`CHAOS_THRESHOLD`]. The regular fraction of the cells estimates the relative area of the
//! section covered by invariant curves. A chaotic orbit whose SALI has not yet fallen below the
//! threshold at `t1` counts as regular, so the fraction is an upper estimate that a longer run
//! lowers.

use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::analysis::sali::CHAOS_THRESHOLD;
use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Members, Plan, Reduction};
use physicskit::classical::Method;

use super::henon_heiles_starts::SectionStarts;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{color, save_panel, Legend, Mark, Panel, Series};

/// The starts `[x, y, p_x, p_y]` of an `n x n` grid of cell centres over the energy curve's
/// extent on the section `x = 0` at `energy`, those strictly inside the curve.
fn section_starts(energy: f64, n: usize) -> Result<Vec<[f64; 4]>> {
    let starts = SectionStarts::new(0, energy)?;
    let ((y0, y1), (p0, p1)) = starts.extent();
    let cell = |i: usize, lo: f64, hi: f64| lo + (i as f64 + 0.5) * (hi - lo) / n as f64;
    Ok((0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .filter_map(|(i, j)| starts.start(cell(i, y0, y1), cell(j, p0, p1)))
        .collect())
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "henon-heiles-regular-fraction",
    text: Physics::Own(
        "How much of the Hénon–Heiles energy surface is regular, energy by energy. At \
         each energy E a grid of starts fills the surface of section x = 0 inside its \
         zero-velocity curve (p_x ≥ 0 from the energy); each start is one ensemble member whose \
         SALI (the smaller alignment index of two deviation vectors, Skokos 2001) is computed \
         on all cores. An orbit on an invariant torus keeps SALI away from zero; a chaotic one \
         drives it below the library's threshold of 10⁻⁸. The fraction of regular starts \
         estimates the relative area of the section covered by invariant curves, the quantity \
         Hénon & Heiles (1964) plotted against E: close to one up to about E = 0.11, then \
         falling steeply as the tori break up, with only small islands left near the escape \
         energy 1/6. A chaotic orbit that has not yet shown its chaos by the end of the run \
         counts as regular, so the curve is an upper estimate that longer runs lower.",
    ),
    figure: "Eleven energies from 1/24 to 0.16; at each, the cells of a 60 × 60 grid over the \
         energy curve's extent that lie inside it, each run to t = 3000 with yoshida4 at dt = \
         0.1.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Hénon–Heiles: the fraction of regular orbits against energy");
    let energies = [
        1.0 / 24.0,
        1.0 / 16.0,
        1.0 / 12.0,
        0.1,
        0.11,
        0.12,
        0.125,
        0.13,
        0.14,
        0.15,
        0.16,
    ];
    // Quick: about 2 s on one core (1.2e3 members of 1e4 steps).
    let n = ctx.pick(12, 60);
    let t1 = ctx.pick(1000.0, 3000.0);
    let starts = energies
        .iter()
        .map(|&e| section_starts(e, n))
        .collect::<Result<Vec<_>>>()?;
    let states: Vec<f64> = starts.iter().flatten().flatten().copied().collect();
    let members = Members {
        states: Some(states),
        n: starts.iter().map(Vec::len).sum(),
        ..Members::default()
    };
    let plan = Plan {
        t_span: (0.0, t1),
        dt: 0.1,
        method: Some(Method::Yoshida4),
        stride: None,
        reductions: vec![Reduction::Sali {
            renormalize_every: DEFAULT_RENORMALIZE_EVERY,
        }],
        final_state: false,
        threads: None,
        tolerances: None,
    };
    let out = ensemble::run(catalog::find("henon-heiles")?, &members, &plan, None)?;
    let sali = &out.reductions[0].1;
    let mut fraction = Vec::with_capacity(energies.len());
    let mut offset = 0;
    for (&e, s) in energies.iter().zip(&starts) {
        let members = sali.slice(ndarray::s![offset..offset + s.len()]);
        let regular = members.iter().filter(|&&v| v > CHAOS_THRESHOLD).count();
        fraction.push((e, regular as f64 / s.len() as f64));
        offset += s.len();
    }
    let panel = Panel::new(
        format!(
            "Regular fraction of the section x = 0: SALI > {} at t = {t1}, \
             {n} × {n} grid per energy",
            super::common::power_of_ten(CHAOS_THRESHOLD)
        ),
        "energy E",
        "fraction of regular orbits",
    )
    .legend(Legend::Auto)
    .x_range(0.0, 1.0 / 6.0)
    .y_range(0.0, 1.05)
    .with(Series::line("", fraction.clone(), color(0)).unlabeled())
    .with(
        Series::dots("ensemble of SALI runs (one per cell)", fraction, color(0))
            .with_mark(Mark::Dots(5)),
    );
    let path = ctx.path("henon_heiles_regular_fraction.svg");
    save_panel(&path, (900, 600), &panel)?;
    d.add(
        path,
        "fraction of regular orbits against energy: near 1 up to E ≈ 0.11, then falling (Hénon & Heiles 1964)",
    );
    Ok(d)
}
