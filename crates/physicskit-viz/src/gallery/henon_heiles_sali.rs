//! Demonstration 18, Hénon–Heiles at E = 1/8: the Poincaré section `(y, p_y)` at `x = 0`,
//! `p_x > 0` beside a SALI map of the same plane (one orbit per cell, started on the section;
//! colour the final `log10 SALI`, [`CHAOS_THRESHOLD`] separating chaotic orbits).
//!
//! Both panels take `p_x` from the energy (the gallery's shared [`SectionStarts`], from the
//! system's own `H`); cells outside the energy curve are left blank.

use physicskit::classical::analysis::chaos_map::{chaos_map, Indicator, MapRun, SALI_FLOOR};
use physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::sali::CHAOS_THRESHOLD;
use physicskit::classical::analysis::section::{poincare_section, SurfaceOfSection};
use physicskit::classical::model::erased::Hamiltonian;
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::Method;

use super::henon_heiles_starts::SectionStarts;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{ramp, save_svg, Legend, Mark, Panel, Series};
use crate::heatmap::HeatMap;

/// The energy of the section.
const ENERGY: f64 = 1.0 / 8.0;
/// The cell centres span the energy curve and this fraction of its width beyond on each side.
const MARGIN: f64 = 0.02;
/// Step of yoshida4 (energy error ~1e-7 at this energy).
const DT: f64 = 0.05;

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "henon-heiles-sali",
    text: Physics::Own(
        "The Hénon–Heiles system at one energy seen two ways on the same plane, the \
         section x = 0 with pₓ > 0 (pₓ fixed by the energy; the blank corners lie outside the \
         energy surface). Left, the Poincaré section: regular orbits draw closed curves, \
         sections of invariant tori, around the islands; chaotic ones scatter dots over a sea. \
         Right, every cell is one orbit started there, coloured by its Smaller Alignment Index \
         (Skokos 2001) at the end of the run: two deviation vectors follow the tangent dynamics \
         (the exact tangent map of the splitting step) and SALI measures how nearly they have \
         aligned. On a chaotic orbit both turn towards the most unstable direction and SALI \
         falls exponentially, as exp(−(λ₁ − λ₂)t); on a torus they stay apart and SALI stays of \
         order 0.1–1. Below the library's threshold of 10⁻⁸ (dark) an orbit is called chaotic; \
         the map draws the islands of the section in one run per cell, without following any \
         orbit by eye. Sticky orbits, which cling to an island's edge for a long time, have not \
         fallen below the threshold yet and show as intermediate colours.",
    ),
    figure: "E = 1/8; a 100 × 100 grid of starts run to t = 1000 with yoshida4 at dt = 0.05; \
         the section's 24 orbits cross the plane 800 times each.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Hénon–Heiles: a SALI map beside the Poincaré section");
    // The section x = 0, px > 0: its plane is (y, py).
    let starts = SectionStarts::new(0, ENERGY)?;
    let widen = |(lo, hi): (f64, f64)| (lo - MARGIN * (hi - lo), hi + MARGIN * (hi - lo));
    let (y_range, py_range) = starts.extent();
    let (y_range, py_range) = (widen(y_range), widen(py_range));
    let (ny, t_sali) = (ctx.pick(40, 100), ctx.pick(600.0, 1000.0));
    let (nx, npy) = (ny, ny);
    let cell =
        |i: usize, n: usize, (lo, hi): (f64, f64)| lo + (hi - lo) * i as f64 / (n - 1) as f64;
    let mut states = Vec::new();
    let mut inside = Vec::new();
    for j in 0..npy {
        for i in 0..nx {
            if let Some(s) = starts.start(cell(i, nx, y_range), cell(j, npy, py_range)) {
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
            renormalize_every: DEFAULT_RENORMALIZE_EVERY,
        },
    };
    let hh = HenonHeilesSystem::new(&[0.0, 0.0], &[0.0, 0.0])?;
    let sali = chaos_map(&Hamiltonian(hh), &states, &run)?;
    let mut values = vec![f64::NAN; nx * npy];
    for (&k, &s) in inside.iter().zip(&sali) {
        // Each run stops once SALI falls below the map's floor, so values under it say only
        // "chaotic"; exact zeros (vectors aligned to rounding) go to the floor too.
        values[k] = s.max(SALI_FLOOR).log10();
    }
    let chaotic = sali.iter().filter(|&&s| s < CHAOS_THRESHOLD).count();
    let map = HeatMap {
        title: format!(
            "SALI at t = {t_sali}: {:.0} % of {} orbits chaotic (< {})",
            100.0 * chaotic as f64 / sali.len() as f64,
            sali.len(),
            super::common::power_of_ten(CHAOS_THRESHOLD)
        ),
        x_label: "y".into(),
        y_label: "p_{y}".into(),
        value_label: format!(
            "log₁₀ SALI (chaotic below {})",
            CHAOS_THRESHOLD.log10().to_string().replace('-', "−")
        ),
        x_range: y_range,
        y_range: py_range,
        nx,
        ny: npy,
        values,
    };

    // The section: orbits started along p_y = 0 and y = 0 of the same plane.
    let surface = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing)?;
    let (n_orbits, crossings) = (ctx.pick(12, 24), ctx.pick(300, 800));
    let half = (
        0.5 * (y_range.1 - y_range.0) / (nx - 1) as f64,
        0.5 * (py_range.1 - py_range.0) / (npy - 1) as f64,
    );
    let mut section = Panel::new(
        format!("Poincaré section, {n_orbits} orbits (one colour each)"),
        "y",
        "p_{y}",
    )
    .x_range(y_range.0 - half.0, y_range.1 + half.0)
    .y_range(py_range.0 - half.1, py_range.1 + half.1)
    .legend(Legend::None);
    for k in 0..n_orbits {
        let Some(s) = starts.spread(k, n_orbits) else {
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
        section = section.with(Series::dots("", pts, ramp(k, n_orbits)).with_mark(Mark::Dots(1)));
    }

    let path = ctx.path("henon_heiles_sali.svg");
    save_svg(
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
    d.add(
        path,
        &format!(
            "Poincaré section (y, p_{{y}}) at x = 0 beside the SALI map of the same plane: chaotic \
             sea (SALI < {CHAOS_THRESHOLD:e}) and regular islands"
        ),
    );
    Ok(d)
}
