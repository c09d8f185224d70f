//! Demonstration 17, Work–precision: error against the number of force (right-hand-side)
//! evaluations for every applicable method on three problems (Kepler at e = 0.5, Hénon–Heiles,
//! the double pendulum), from [`physicskit::classical::analysis::work_precision`]. The methods
//! come from the registry. The cost is counted, not timed (as in Hairer, Nørsett & Wanner's
//! work–precision diagrams), so the figure is the same on every machine and every run, bit for
//! bit, and each method's line moves one way along the cost axis.

use std::path::Path;

use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::{Method, SimulationResult};

use super::integrators::log10_rel;
use super::{Ctx, Demo, Explanation, Physics};
use crate::error::{Result, VizError};
use crate::figure::{save_panel, styled_dots, styled_line, Legend, Panel, Series};

/// A problem's name as a reader writes it (the library's are identifiers).
fn title(problem: Problem) -> &'static str {
    match problem {
        Problem::Kepler { .. } => "Kepler orbit, e = 0.5",
        Problem::HenonHeiles { .. } => "Hénon–Heiles",
        Problem::DoublePendulum { .. } => "Double pendulum",
    }
}

/// A method's name as people write it (`Störmer–Verlet`, `Gauss–Legendre 4`, `implicit
/// midpoint`): its registry label.
pub(crate) fn words(method: Method) -> &'static str {
    method.info().label
}

/// Errors below this are rounding: smaller steps would only add cost.
const ROUNDING: f64 = 1e-14;

/// The cost of a run: its force evaluations (the splitting methods count those) or
/// right-hand-side evaluations (every other method), which on these Hamiltonian and Lagrangian
/// systems cost one force each. `None` if the run reports neither.
fn evaluations(result: &SimulationResult) -> Option<f64> {
    result
        .extra_scalar("force_evaluations")
        .or_else(|| result.extra_scalar("rhs_evaluations"))
}

/// One method's points `(log10 evaluations, log10 error)` on `problem`, coarsest setting first:
/// `points` settings of [`Problem::steps`], stopping at the rounding floor. A setting whose run
/// fails (an implicit solve that does not converge at a large step) is no point of the diagram.
/// Each point costs more than the one before it: a coarser setting that a finer one beats in
/// both cost and error is dropped, and so is a finer one that costs no more than its
/// predecessor otherwise.
///
/// # Errors
/// [`VizError::Draw`] naming `path` if a run reports no evaluation count.
fn curve(
    problem: Problem,
    method: Method,
    points: usize,
    reference: &[f64],
    path: &Path,
) -> Result<Vec<(f64, f64)>> {
    let mut pts = Vec::new();
    for setting in problem.steps(method, points) {
        let Ok(result) = problem.run(method, setting) else {
            continue;
        };
        let cost = evaluations(&result).ok_or_else(|| VizError::Draw {
            path: path.to_path_buf(),
            message: format!("{} reports no evaluation count", method.name()),
        })?;
        let error = problem.error(&result, reference);
        let point = (cost.log10(), log10_rel(error));
        // A finer setting that costs no more than coarser ones (an adaptive method's loosest
        // tolerance can spend more on rejected steps) makes them dominated: more cost for
        // more error. They leave the diagram, which then runs one way along the cost axis.
        while pts
            .last()
            .is_some_and(|p: &(f64, f64)| p.0 >= point.0 && p.1 >= point.1)
        {
            pts.pop();
        }
        if pts.last().is_none_or(|p| p.0 < point.0) {
            pts.push(point);
        }
        if error < ROUNDING {
            break;
        }
    }
    Ok(pts)
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "work-precision",
    text: Physics::Own(
        "How much accuracy each integrator buys per evaluation of the forces, the cost \
         Hairer, Nørsett and Wanner count in their work–precision diagrams: unlike a wall \
         time, the count is the same on every machine and every run. Each line is one \
         method, each point one step size (halved from point to point) or, for the adaptive \
         DOP853, one tolerance (tenfold apart); lower left is better. On the Kepler orbit (the \
         error is the phase lag after the run against the analytic orbit) and on Hénon–Heiles \
         (the largest energy error over the run), the high-order symplectic compositions \
         (Kahan and Li's of order eight, Sofroniou and Spaletta's of order ten) reach the \
         rounding floor at a small fraction of the cost of Störmer–Verlet or Yoshida's \
         fourth-order method, whose lines are steep but start far up. On the double \
         pendulum, a chaotic Lagrangian system where only the methods for non-separable systems \
         apply, the Gauss–Legendre methods of order 4 and 6 reach a given error at far lower \
         cost than the second-order implicit midpoint rule, whose fixed-point solve takes more \
         sweeps per step the larger the step.",
    ),
    figure: "Kepler at eccentricity e = 0.5 (a = k = μ = 1) over 100 orbits from perihelion; \
         SciML's Hénon–Heiles case, q = (0.1, 0) and p = (0, 0.5), to t = 1000; the double \
         pendulum with unit masses and arms from θ = (2, 1) rad and θ̇ = (0.5, −0.3) rad/s to t \
         = 10 s, against a DOP853 reference run.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Work–precision");
    let points = ctx.pick(4, 7);
    for (k, problem) in Problem::all(ctx.quick).into_iter().enumerate() {
        let path = ctx.path(&format!("work_precision_{}.svg", k + 1));
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end)?,
            _ => Vec::new(),
        };
        let mut panel = Panel::new(
            format!("{}, t = {:.0}", title(problem), problem.t_end()),
            "log₁₀ force evaluations",
            format!("log₁₀ {}", problem.error_label()),
        )
        .legend(Legend::Auto);
        for method in problem.methods() {
            let pts = curve(problem, method, points, &reference, &path)?;
            // Colour, line style and marker by the method's place in the registry, so a method
            // looks the same in all three panels: eight colours, then the same colours dashed
            // with square markers.
            let i = Method::ALL.iter().position(|m| *m == method).unwrap_or(0);
            let (colour, line) = styled_line(i);
            panel = panel.with(Series::line(words(method), pts.clone(), colour).with_mark(line));
            panel = panel.with(
                Series::dots("", pts, colour)
                    .with_mark(styled_dots(i, 3))
                    .unlabeled(),
            );
        }
        save_panel(&path, (1000, 640), &panel)?;
        let what = format!(
            "{}: log–log {} against the number of force evaluations, one line per method (a \
             setting beaten by a finer one in both cost and error left out)",
            title(problem),
            problem.error_label()
        );
        d.add(path, &what);
    }
    Ok(d)
}
