//! One run of a splitting-method case, for instruction counts under callgrind
//! (`benchmarks/step_cost.sh`, numbers in `benchmarks/README.md`):
//!
//! ```text
//! step_cost CASE METHOD STEPS
//! ```
//!
//! Cases (every step stored with its energy, as `integrate` does by default):
//!
//! - `henon-heiles`: SciML's Hénon–Heiles case, `q0 = (0.1, 0)`, `p0 = (0, 0.5)`, `dt = 1e-2`;
//! - `swarm-1000`: `PendulumSwarm::from_box(1, 0, 0.05, 0.05, 1000, 1, 0)` (the lab's
//!   1000-pendulum swarm size), `dt = 1e-3`.
//!
//! Prints the final energy error so that the run cannot be optimized away.

use std::process::ExitCode;

use physicskit::classical::systems::{HenonHeilesSystem, PendulumSwarm};
use physicskit::classical::{HamiltonianSystem, Method, Result, SimulationResult};

fn run(case: &str, method: Method, steps: usize) -> Result<Option<SimulationResult>> {
    Ok(Some(match case {
        "henon-heiles" => {
            let dt = 1e-2;
            HenonHeilesSystem::new(&[0.1, 0.0], &[0.0, 0.5])?.integrate(
                (0.0, steps as f64 * dt),
                dt,
                method,
            )?
        }
        "swarm-1000" => {
            let dt = 1e-3;
            PendulumSwarm::from_box(1.0, 0.0, 0.05, 0.05, 1000, 1.0, 0)?.integrate(
                (0.0, steps as f64 * dt),
                dt,
                method,
            )?
        }
        _ => return Ok(None),
    }))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let parsed = match args.as_slice() {
        [_, case, method, steps] => method
            .parse::<Method>()
            .ok()
            .zip(steps.parse::<usize>().ok())
            .map(|(m, n)| (case.as_str(), m, n)),
        _ => None,
    };
    let Some((case, method, steps)) = parsed else {
        eprintln!("usage: step_cost henon-heiles|swarm-1000 METHOD STEPS");
        return ExitCode::from(2);
    };
    match run(case, method, steps) {
        Ok(Some(result)) => {
            let e = result.energy.as_ref().expect("energy stored");
            println!(
                "{case} {method} {steps} steps: final dE {:e}",
                e[e.len() - 1] - e[0]
            );
            ExitCode::SUCCESS
        }
        Ok(None) => {
            eprintln!("unknown case {case}: henon-heiles or swarm-1000");
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
