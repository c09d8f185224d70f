//! Demonstration 17, Work–precision: error against wall time for every applicable method on
//! three problems (Kepler at e = 0.5, Hénon–Heiles, the double pendulum), from
//! [`physicskit::classical::analysis::work_precision`]. The methods come from the registry.

use std::time::Instant;

use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::Method;

use super::integrators::log10_rel;
use super::{Ctx, Demo};
use crate::error::Result;
use crate::figure::{color_of_many, save_panel, Legend, Mark, Panel, Series};

/// Errors below this are rounding: smaller steps would only add time.
const ROUNDING: f64 = 1e-14;

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("work-precision", "Work–precision");
    let points = ctx.pick(4, 7);
    for (k, problem) in Problem::all(ctx.quick).into_iter().enumerate() {
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end)?,
            _ => Vec::new(),
        };
        let mut panel = Panel::new(
            format!("{}, t = {:.0}", problem.name(), problem.t_end()),
            "log₁₀ wall time (s)",
            format!("log₁₀ {}", problem.error_label()),
        )
        // Lower left is fast and accurate, the corner no method reaches: the legend hides no
        // line there (upper right covered the slow methods' ends).
        .legend(Legend::LowerLeft);
        for method in problem.methods() {
            let mut pts = Vec::new();
            for dt in problem.steps(method, points) {
                let start = Instant::now();
                // A step too large for the method (an implicit solve that does not converge)
                // is no point of the diagram.
                let Ok(result) = problem.run(method, dt) else {
                    continue;
                };
                let seconds = start.elapsed().as_secs_f64().max(1e-6);
                let error = problem.error(&result, &reference);
                pts.push((seconds.log10(), log10_rel(error)));
                if error < ROUNDING {
                    break;
                }
            }
            let i = Method::ALL.iter().position(|m| *m == method).unwrap_or(0);
            panel = panel.with(Series::line(method.name(), pts.clone(), color_of_many(i)));
            panel = panel.with(
                Series::dots("", pts, color_of_many(i))
                    .with_mark(Mark::Dots(3))
                    .unlabeled(),
            );
        }
        let path = ctx.path(&format!("work_precision_{}.png", k + 1));
        save_panel(&path, (1000, 640), &panel)?;
        let what = format!(
            "log–log {} against wall time on {}, one line per method",
            problem.error_label(),
            problem.name()
        );
        d.add(path, &what);
    }
    Ok(d)
}
