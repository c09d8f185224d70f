//! Demonstration 2, Hénon–Heiles: Poincaré sections `(x, px)` at `y = 0`, `py > 0` for three energies.

use physicskit::classical::analysis::poincare::{
    poincare_section_separable, Direction, Section, SectionRun,
};
use physicskit::classical::model::Value;
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{Error, Method};

use super::henon_heiles_starts::SectionStarts;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::Result;
use crate::figure::{ramp, save_svg, Legend, Mark, Panel, Series};

/// Crossings of one orbit started on the section at `y0 = [x, y, p_x, p_y]`; `None` if the
/// orbit escapes over a saddle.
fn orbit(y0: [f64; 4], run: &SectionRun, section: &Section) -> Result<Option<Vec<(f64, f64)>>> {
    let sys = HenonHeilesSystem::new(&y0[..2], &y0[2..])?;
    match poincare_section_separable(&sys, 0.0, &y0, section, run, Method::Yoshida4) {
        Ok(cut) => Ok(Some(
            cut.component(0).into_iter().zip(cut.component(2)).collect(),
        )),
        // An orbit leaving over a saddle of the potential diverges: leave it out.
        Err(Error::NonFinite { .. }) => Ok(None),
        Err(e) => Err(e.into()),
    }
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "henon-heiles",
    text: Physics::OfSystem(&physicskit::classical::systems::HENON_HEILES_ENTRY),
    figure: "Each colour is one orbit; the three panels are at E = 1/12 (almost everything \
         regular), E = 1/8 (islands in a chaotic sea) and the saddles' energy.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Hénon–Heiles: KAM tori breaking up");
    let section = Section::new(1, 0.0, Direction::Increasing)?;
    let crossings = ctx.pick(250, 900);
    let n_orbits = ctx.pick(12, 30);
    // One crossing per ~6-7 time units; the time limit only guards against stuck orbits.
    let run = SectionRun::new(0.02, 10.0 * crossings as f64, crossings);
    let energies: [(f64, &str); 3] = [(1.0 / 12.0, "1/12"), (1.0 / 8.0, "1/8"), (1.0 / 6.0, "1/6")];
    // The lab opens on the first orbit at E = 1/6, where tori and chaos share the section:
    // the same start, method and step (the lab draws its crossings of the same section).
    if let Some(y0) = SectionStarts::new(1, energies[2].0)?.spread(0, n_orbits) {
        d.lab = Some(ctx.lab_link(
            "henon-heiles",
            &[
                ("q0", Value::Vector(y0[..2].to_vec())),
                ("p0", Value::Vector(y0[2..].to_vec())),
            ],
            Method::Yoshida4,
            run.dt,
            &y0,
        )?);
    }
    let path = ctx.path("henon_heiles_sections.svg");
    let mut panels = Vec::new();
    for (e, label) in energies {
        // The section y = 0, py > 0: its plane is (x, px).
        let starts = SectionStarts::new(1, e)?;
        let mut panel = Panel::new(format!("E = {label}"), "x", "pₓ").legend(Legend::None);
        for k in 0..n_orbits {
            let Some(y0) = starts.spread(k, n_orbits) else {
                continue;
            };
            if let Some(pts) = orbit(y0, &run, &section)? {
                panel =
                    panel.with(Series::dots("", pts, ramp(k, n_orbits)).with_mark(Mark::Dots(1)));
            }
        }
        panels.push(panel.equal_aspect());
    }
    save_svg(
        &path,
        (1500, 560),
        Some("Hénon–Heiles Poincaré sections at y = 0, p_{y} > 0 (dimensionless units)"),
        (1, 3),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "Poincaré sections (x, pₓ) at y = 0, p_{y} > 0 for E = 1/12, 1/8 and 1/6, one colour per orbit along viridis: regular tori giving way to chaos");
    Ok(d)
}
