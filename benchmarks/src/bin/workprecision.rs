//! Work–precision of every applicable method, and the benchmarks of the high-order
//! methods (numbers in `benchmarks/README.md`).
//!
//! - `workprecision [quick]`: for each problem of
//!   [`work_precision`](physicskit::classical::analysis::work_precision) (Kepler e = 0.5
//!   phase error after 100 orbits, Hénon–Heiles energy error, double-pendulum error against a
//!   reference run) and each method that applies (from the registry), a ladder of steps: one
//!   line `problem method dt error seconds` per run, the best wall time of three.
//! - `workprecision sciml`: SciML's Hénon–Heiles case with `kahan_li8` (`q0 = (0.1, 0)`,
//!   `p0 = (0, 0.5)`, `dt = 1e-2`, `t = 1e4`, every step stored): max |dE| and the best wall
//!   time of five.
//! - `workprecision drift-bar`: the peer's double pendulum (its start, its 3 s span) with
//!   `implicit_midpoint` at the peer's `dt = 3e-5`, and with `gauss_legendre4`/`6` at the
//!   largest step of a doubling ladder that keeps the max relative energy error below the
//!   peer's bar of 1e-6: max relative energy error and best wall time of three, every step
//!   stored as in the workload.

use std::time::Instant;

use physicskit::classical::analysis::work_precision::{
    double_pendulum, double_pendulum_reference, Problem,
};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{HamiltonianSystem, LagrangianSystem, Method, Result};

/// Best wall time of `repeats` calls of `f`, and the last call's value.
fn best_of<T>(repeats: usize, mut f: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut best = f64::INFINITY;
    let mut value = None;
    for _ in 0..repeats {
        let start = Instant::now();
        let v = f()?;
        best = best.min(start.elapsed().as_secs_f64());
        value = Some(v);
    }
    Ok((best, value.expect("repeats >= 1")))
}

/// Largest relative deviation of `e` from its first entry.
fn max_relative_drift(e: &[f64]) -> f64 {
    let e0 = e[0];
    e.iter().fold(0.0_f64, |m, v| m.max(((v - e0) / e0).abs()))
}

fn work_precision(quick: bool) -> Result<()> {
    // `setting` is the step of a fixed-step method, the tolerance (rtol = atol) of dop853.
    println!("problem method setting error seconds");
    for problem in Problem::all(quick) {
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end)?,
            _ => Vec::new(),
        };
        for method in problem.methods() {
            for dt in problem.steps(method, if quick { 4 } else { 7 }) {
                let Ok((seconds, result)) = best_of(3, || problem.run(method, dt)) else {
                    println!("{} {method} {dt:e} failed", problem.name());
                    continue;
                };
                let error = problem.error(&result, &reference);
                println!(
                    "{} {method} {dt:e} {error:.3e} {seconds:.4e}",
                    problem.name()
                );
                // Below this the error is rounding, and smaller steps only cost time.
                if error < 1e-14 {
                    break;
                }
            }
        }
    }
    Ok(())
}

fn sciml() -> Result<()> {
    let (seconds, result) = best_of(5, || {
        HenonHeilesSystem::new(&[0.1, 0.0], &[0.0, 0.5])?.integrate(
            (0.0, 1e4),
            1e-2,
            Method::KahanLi8,
        )
    })?;
    let e = result.energy.as_ref().expect("energy stored").to_vec();
    let max_de = e.iter().fold(0.0_f64, |m, v| m.max((v - e[0]).abs()));
    println!(
        "henon_heiles kahan_li8 dt=1e-2 t=1e4 steps={} max|dE|={max_de:.3e} seconds={seconds:.4}",
        e.len() - 1
    );
    Ok(())
}

fn drift_bar() -> Result<()> {
    let span = (0.0, 1e5 * 3e-5);
    let run = |method: Method, dt: f64| -> Result<(f64, f64)> {
        let (seconds, result) = best_of(3, || double_pendulum()?.integrate(span, dt, method))?;
        let e = result.energy.as_ref().expect("energy stored").to_vec();
        Ok((seconds, max_relative_drift(&e)))
    };
    let (base, drift) = run(Method::ImplicitMidpoint, 3e-5)?;
    println!("double_pendulum implicit_midpoint dt=3e-5 max_rel_dE={drift:.3e} seconds={base:.4}");
    for method in [Method::GaussLegendre4, Method::GaussLegendre6] {
        // Halving the number of steps from the peer's 1e5 while the bar holds (each step a
        // whole fraction of the span, as the time grid requires); the last count that held is
        // timed.
        let mut steps: u32 = 100_000;
        while steps > 1 {
            let (_, drift) = run(method, span.1 / f64::from(steps / 2))?;
            if drift >= 1e-6 {
                break;
            }
            steps /= 2;
        }
        let dt = span.1 / f64::from(steps);
        let (seconds, drift) = run(method, dt)?;
        println!(
            "double_pendulum {method} dt={dt:e} max_rel_dE={drift:.3e} seconds={seconds:.4} \
             speedup={:.1}x",
            base / seconds
        );
    }
    Ok(())
}

fn main() -> Result<()> {
    match std::env::args().nth(1).as_deref() {
        None => work_precision(false),
        Some("quick") => work_precision(true),
        Some("sciml") => sciml(),
        Some("drift-bar") => drift_bar(),
        Some(other) => {
            eprintln!("unknown argument {other}: expected nothing, quick, sciml or drift-bar");
            std::process::exit(2)
        }
    }
}
