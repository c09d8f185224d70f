//! Demonstration 3, Pendulum swarm: Liouville's theorem. A patch of phase points shears into a filament
//! along the separatrix while its area stays constant.

use physicskit::classical::model::Value;
use physicskit::classical::systems::{polygon_area, PendulumSwarm};
use physicskit::classical::{
    DynamicalSystem, HamiltonianSystem, IntegrateOptions, Method, Sampling,
};

use super::{Ctx, Demo, Explanation, Physics};
use crate::animation::save_gif;
use crate::error::Result;
use crate::figure::{color, save_svg, Legend, Mark, Panel, Series};

/// Patch centre and size in (q, p): just inside the separatrix top at (0, 2), where the
/// libration period grows without bound, so neighbouring pendulums drift apart fastest.
/// (Energies from -0.15 to 0.85 g/l, all below the separatrix energy g/l: a straddling patch
/// would be stretched exponentially at the saddle, beyond what a finite boundary resolves.)
const CENTER: (f64, f64) = (0.0, 1.75);
const SIZE: (f64, f64) = (0.6, 0.3);

/// Points evenly spaced along the patch boundary, counter-clockwise.
fn boundary(n_side: usize) -> (Vec<f64>, Vec<f64>) {
    let (q0, p0) = (CENTER.0 - 0.5 * SIZE.0, CENTER.1 - 0.5 * SIZE.1);
    let corners = [
        (q0, p0),
        (q0 + SIZE.0, p0),
        (q0 + SIZE.0, p0 + SIZE.1),
        (q0, p0 + SIZE.1),
    ];
    let mut q = Vec::with_capacity(4 * n_side);
    let mut p = Vec::with_capacity(4 * n_side);
    for c in 0..4 {
        let (a, b) = (corners[c], corners[(c + 1) % 4]);
        for k in 0..n_side {
            let f = k as f64 / n_side as f64;
            q.push(a.0 + f * (b.0 - a.0));
            p.push(a.1 + f * (b.1 - a.1));
        }
    }
    (q, p)
}

fn separatrix(swarm: &PendulumSwarm) -> Vec<Series> {
    let pts = |sign: f64| -> Vec<(f64, f64)> {
        (0..=400)
            .map(|i| {
                let q = -std::f64::consts::PI + std::f64::consts::TAU * i as f64 / 400.0;
                (q, sign * swarm.separatrix_momentum(q))
            })
            .collect()
    };
    vec![
        Series::line("separatrix E = g/l", pts(1.0), color(6)).with_mark(Mark::Dashed(1)),
        Series::line("", pts(-1.0), color(6))
            .with_mark(Mark::Dashed(1))
            .unlabeled(),
    ]
}

/// Wraps the cloud's angles into (-pi, pi] for display.
fn wrapped(q: &[f64], p: &[f64]) -> Vec<(f64, f64)> {
    q.iter()
        .zip(p)
        .map(|(&q, &p)| (super::common::wrap(q), p))
        .collect()
}

/// The paragraph under this demonstration: the physics, then what its figures show.
pub(super) const EXPLANATION: Explanation = Explanation {
    slug: "swarm",
    text: Physics::OfSystem(&physicskit::classical::systems::SWARM_ENTRY),
    figure: "g/l = 1 s⁻²; the patch starts just inside the separatrix, and its area is measured \
         on 2000 boundary points carried along with the flow.",
};

pub(crate) fn render(ctx: &Ctx) -> Result<Demo> {
    let mut d = ctx.demo("Pendulum swarm: Liouville's theorem");
    let n = ctx.pick(1500, 5000);
    let n_side = ctx.pick(500, 1500);
    let snaps = [0.0, 10.0, 20.0, 40.0];
    let dt = 0.01;
    let (g_over_l, seed) = (1.0, 42);
    let mut cloud = PendulumSwarm::from_box(CENTER.0, CENTER.1, SIZE.0, SIZE.1, n, g_over_l, seed)?;
    // The lab opens on the cloud: the same box, fill, method and step.
    d.lab = Some(ctx.lab_link(
        "pendulum-swarm",
        &[
            ("q_center", Value::Scalar(CENTER.0)),
            ("p_center", Value::Scalar(CENTER.1)),
            ("dq", Value::Scalar(SIZE.0)),
            ("dp", Value::Scalar(SIZE.1)),
            ("n", Value::Integer(n as i64)),
            ("g_over_l", Value::Scalar(g_over_l)),
            ("seed", Value::Integer(seed as i64)),
        ],
        Method::Yoshida4,
        dt,
        cloud.state(),
    )?);
    let (bq, bp) = boundary(n_side);
    let mut edge = PendulumSwarm::new(&bq, &bp, 1.0)?;
    let a0 = polygon_area(&bq, &bp)?;
    let quiet = || IntegrateOptions {
        sampling: Sampling::FinalOnly,
        skip_energy: true,
        ..IntegrateOptions::default()
    };
    let mut panels = Vec::new();
    let mut t_prev = 0.0;
    for &t in &snaps {
        if t > t_prev {
            cloud.integrate_with((t_prev, t), dt, Method::Yoshida4, quiet())?;
            edge.integrate_with((t_prev, t), dt, Method::Yoshida4, quiet())?;
        }
        t_prev = t;
        let area = polygon_area(edge.q(), edge.p())?;
        let mut panel = Panel::new(
            format!("t = {t} s: enclosed area {area:.4} (t = 0: {a0:.4})"),
            "q (rad, wrapped)",
            "p (rad/s)",
        )
        .x_range(-std::f64::consts::PI, std::f64::consts::PI)
        .y_range(-2.6, 2.6)
        .legend(Legend::Auto);
        for s in separatrix(&cloud) {
            panel = panel.with(s);
        }
        panel = panel.with(
            Series::dots("pendulums", wrapped(cloud.q(), cloud.p()), color(0)).with_alpha(0.5),
        );
        panel = panel.with(Series::dots(
            "patch boundary",
            wrapped(edge.q(), edge.p()),
            color(1),
        ));
        panels.push(panel);
    }
    let path = ctx.path("swarm_liouville.svg");
    save_svg(
        &path,
        (1300, 900),
        Some("Liouville's theorem: a pendulum swarm shears but keeps its phase-space area"),
        (2, 2),
        |i, area| panels[i].draw(area, &path).map(|_| ()),
    )?;
    d.add(path, "four snapshots of the swarm over the separatrix, each titled with the conserved area enclosed by the patch boundary");

    // Animation of the cloud.
    let frames = ctx.pick(40, 80);
    let t_end = 40.0;
    let mut cloud = PendulumSwarm::from_box(
        CENTER.0,
        CENTER.1,
        SIZE.0,
        SIZE.1,
        ctx.pick(800, 2000),
        1.0,
        42,
    )?;
    let path = ctx.path("swarm.gif");
    let step = t_end / frames as f64;
    save_gif(&path, (560, 420), ctx.gif_scale(), frames, 80, |k, root| {
        if k > 0 {
            let t0 = (k - 1) as f64 * step;
            cloud.integrate_with(
                (t0, t0 + step),
                step / ((step / dt).round().max(1.0)),
                Method::Yoshida4,
                quiet(),
            )?;
        }
        let mut panel = Panel::new(
            format!("Pendulum swarm, t = {:.1} s", k as f64 * step),
            "q (rad, wrapped)",
            "p (rad/s)",
        )
        .x_range(-std::f64::consts::PI, std::f64::consts::PI)
        .y_range(-2.6, 2.6)
        .legend(Legend::None);
        for s in separatrix(&cloud) {
            panel = panel.with(s);
        }
        panel = panel.with(Series::dots("", wrapped(cloud.q(), cloud.p()), color(0)));
        panel.draw(root, &path).map(|_| ())
    })?;
    d.add(
        path,
        "animation of the swarm winding into a filament along the separatrix",
    );
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_initial_boundary_encloses_the_box_area() {
        let (q, p) = boundary(50);
        // Exact up to the rounding of ~200 cross products: 1e-12 of an area of 0.18.
        assert!((polygon_area(&q, &p).unwrap() - SIZE.0 * SIZE.1).abs() < 1e-12);
    }
}
