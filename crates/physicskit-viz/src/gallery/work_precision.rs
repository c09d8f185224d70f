//! Demonstration 17, Work–precision: error against wall time for every applicable method on
//! three problems (Kepler at e = 0.5, Hénon–Heiles, the double pendulum), from
//! [`physicskit::classical::analysis::work_precision`]. The methods come from the registry.

use std::time::Instant;

use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::Method;

use super::integrators::log10_rel;
use super::{Ctx, Demo};
use crate::error::Result;
use crate::figure::{save_panel, styled_dots, styled_line, Legend, Panel, Series};

/// A problem's name as a reader writes it (the library's are identifiers).
fn title(problem: Problem) -> &'static str {
    match problem {
        Problem::Kepler { .. } => "Kepler orbit, e = 0.5",
        Problem::HenonHeiles { .. } => "Hénon–Heiles",
        Problem::DoublePendulum { .. } => "Double pendulum",
    }
}

/// A method's registry name as words: `implicit_midpoint` becomes `implicit midpoint`.
pub(crate) fn words(name: &str) -> String {
    name.replace('_', " ")
}

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
            format!("{}, t = {:.0}", title(problem), problem.t_end()),
            "log₁₀ wall time (s)",
            format!("log₁₀ {}", problem.error_label()),
        )
        .legend(Legend::Auto);
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
            // Colour and line style and marker by the method's place in the registry, so a
            // method looks the same in all three panels.
            let i = Method::ALL.iter().position(|m| *m == method).unwrap_or(0);
            let (colour, line) = styled_line(i);
            panel =
                panel.with(Series::line(words(method.name()), pts.clone(), colour).with_mark(line));
            panel = panel.with(
                Series::dots("", pts, colour)
                    .with_mark(styled_dots(i, 3))
                    .unlabeled(),
            );
        }
        let path = ctx.path(&format!("work_precision_{}.svg", k + 1));
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
