//! Demonstration 18, Hénon–Heiles at E = 1/8: the Poincaré section `(y, p_y)` at `x = 0`,
//! `p_x > 0` beside a SALI map of the same plane (one orbit per cell, started on the section;
//! colour the final `log10 SALI`, [`CHAOS_THRESHOLD`] = 1e-8 separating chaotic orbits).
//!
//! Both panels take `p_x` from the energy, `p_x = sqrt(2 (E - H(0, y, 0, p_y)))`, with the
//! system's own `H`; cells where that is imaginary lie outside the energy surface and are left
//! blank.

use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun};
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::sali::CHAOS_THRESHOLD;
use physicskit::classical::analysis::section::{poincare_section, SurfaceOfSection};
use physicskit::classical::core::erased::Hamiltonian;
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{DynamicalSystem, Method};

use super::{demo, Ctx, Demo};
use crate::error::Result;
use crate::figure::{color, save_png, Legend, Mark, Panel, Series};
use crate::heatmap::HeatMap;

/// The energy of the section.
const ENERGY: f64 = 1.0 / 8.0;
/// Cell centres span `y` ...
const Y_RANGE: (f64, f64) = (-0.46, 0.70);
/// ... and `p_y` (the energy surface at `x = 0` spans y in [-0.44, 0.67], |p_y| <= 0.5).
const PY_RANGE: (f64, f64) = (-0.52, 0.52);
/// Step of yoshida4 (energy error ~1e-7 at this energy).
const DT: f64 = 0.05;

/// The state on the section `x = 0` with `p_x > 0` at `(y, p_y)` and energy [`ENERGY`], if
/// the energy surface reaches there.
fn on_section(hh: &HenonHeilesSystem, y: f64, py: f64) -> Option<[f64; 4]> {
    let px2 = 2.0 * (ENERGY - hh.energy(&[0.0, y, 0.0, py]));
    (px2 > 0.0).then(|| [0.0, y, px2.sqrt(), py])
}

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = demo(
        "henon-heiles-sali",
        "18. Hénon–Heiles: a SALI map beside the Poincaré section",
    );
    let hh = HenonHeilesSystem::new(&[0.0, 0.0], &[0.5, 0.0])?;
    let (ny, t_sali) = (ctx.pick(40, 100), ctx.pick(600.0, 1000.0));
    let (nx, npy) = (ny, ny);
    let cell =
        |i: usize, n: usize, (lo, hi): (f64, f64)| lo + (hi - lo) * i as f64 / (n - 1) as f64;
    let mut states = Vec::new();
    let mut inside = Vec::new();
    for j in 0..npy {
        for i in 0..nx {
            if let Some(s) = on_section(&hh, cell(i, nx, Y_RANGE), cell(j, npy, PY_RANGE)) {
                states.extend_from_slice(&s);
                inside.push(j * nx + i);
            }
        }
    }
    let run = MapRun {
        t_span: (0.0, t_sali),
        dt: DT,
        method: Some(Method::Yoshida4),
        indicator: Indicator::Sali {
            renormalize_every: 10,
        },
    };
    let sali = chaos_map(&Hamiltonian(hh.clone()), &states, &run)?;
    let mut values = vec![f64::NAN; nx * npy];
    for (&k, &s) in inside.iter().zip(&sali) {
        // The runs stop below 1e-14; exact zeros (aligned to rounding) go to the floor.
        values[k] = s.max(1e-16).log10();
    }
    let chaotic = sali.iter().filter(|&&s| s < CHAOS_THRESHOLD).count();
    let map = HeatMap {
        title: format!(
            "SALI at t = {t_sali}: {:.0} % of {} orbits chaotic (< 10⁻⁸)",
            100.0 * chaotic as f64 / sali.len() as f64,
            sali.len()
        ),
        x_label: "y".into(),
        y_label: "p_y".into(),
        value_label: "log₁₀ SALI (chaotic below −8)".into(),
        x_range: Y_RANGE,
        y_range: PY_RANGE,
        nx,
        ny: npy,
        values,
    };

    // The section: orbits started along p_y = 0 and y = 0 of the same plane.
    let surface = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing)?;
    let (n_orbits, crossings) = (ctx.pick(12, 24), ctx.pick(300, 800));
    let half = (
        0.5 * (Y_RANGE.1 - Y_RANGE.0) / (nx - 1) as f64,
        0.5 * (PY_RANGE.1 - PY_RANGE.0) / (npy - 1) as f64,
    );
    let mut section = Panel::new(
        format!("Poincaré section, {n_orbits} orbits (one colour each)"),
        "y",
        "p_y",
    )
    .x_range(Y_RANGE.0 - half.0, Y_RANGE.1 + half.0)
    .y_range(PY_RANGE.0 - half.1, PY_RANGE.1 + half.1)
    .legend(Legend::None);
    for k in 0..n_orbits {
        let f = (k / 2) as f64 / (n_orbits / 2) as f64;
        let (y, py) = if k % 2 == 0 {
            (-0.43 + 1.08 * f, 0.0)
        } else {
            (0.0, 0.02 + 0.46 * f)
        };
        let Some(s) = on_section(&hh, y, py) else {
            continue;
        };
        let mut orbit = Hamiltonian(HenonHeilesSystem::new(&s[..2], &s[2..])?);
        // One crossing per ~6-7 time units; the time limit only guards against stuck orbits.
        let t_max = 10.0 * crossings as f64;
        // Bounded at E = 1/8 < 1/6 (the saddles' energy): a failure is an error, not skipped.
        let cut = poincare_section(
            &mut orbit,
            (0.0, t_max),
            DT,
            Some(Method::Yoshida4),
            &surface,
            crossings,
        )?;
        let pts = cut.component(1).into_iter().zip(cut.component(3)).collect();
        section = section.with(Series::dots("", pts, color(k)).with_mark(Mark::Dots(1)));
    }

    let path = ctx.path("18_henon_heiles_sali.png");
    save_png(
        &path,
        (1500, 640),
        Some("Hénon–Heiles at E = 1/8: section x = 0, pₓ > 0 (dimensionless units)"),
        (1, 2),
        |i, area| {
            if i == 0 {
                // Leave the colour bar's width blank, so both plots have the same size.
                let (w, _) = area.dim_in_pixel();
                let (left, _) = area.split_horizontally(w.saturating_sub(110));
                section.draw(&left, &path).map(|_| ())
            } else {
                map.draw(area, &path)
            }
        },
    )?;
    d.add(path, "Poincaré section (y, p_y) at x = 0 beside the SALI map of the same plane: chaotic sea (SALI < 1e-8) and regular islands");
    Ok(d)
}
