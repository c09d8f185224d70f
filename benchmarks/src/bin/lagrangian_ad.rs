//! Lagrangians that go through the automatic-differentiation engine (no closed forms): the
//! workloads of the "Hand-written dual numbers vs num-dual" comparison in benchmarks/README.md.
//!
//! `lagrangian_ad CASE METHOD STEPS` integrates one case for `STEPS` steps once and prints the
//! final state and the energy drift (run it under `valgrind --tool=callgrind` and difference
//! two step counts for instructions per step: `benchmarks/lagrangian_ad.sh` does that for both
//! builds of the engine); `lagrangian_ad CASE METHOD STEPS REPEATS` prints the best wall time
//! per step of `REPEATS` runs. `lagrangian_ad list` lists the cases.
//!
//! The cases: three Lagrangians written in Rust generic over the number type (the built-in
//! hoop, double pendulum and heavy top wrapped in [`AutoDiff`], which hides their closed forms,
//! as a user's own Lagrangian would lack them), and two run-time expressions
//! ([`ExprLagrangian`], the path of a SymPy Lagrangian from Python) of the double pendulum and
//! the heavy top. Initial states and steps are those of the peer-comparison workloads.

use std::time::Instant;

use physicskit::classical::lagrangian::{AutoDiff, Lagrangian, LagrangianModel};
use physicskit::classical::symbolic::{Expr, ExprLagrangian};
use physicskit::classical::systems::{DoublePendulumParams, HoopParams, SymmetricTopParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method, Result, SimulationResult};

/// A double pendulum as SymPy would hand it over (params `m1, m2, l1, l2, g`).
const DOUBLE_PENDULUM: &str = "(+ (* 0.5 (+ param0 param1) (^ param2 2) (^ qdot0 2)) \
     (* 0.5 param1 (^ param3 2) (^ qdot1 2)) \
     (* param1 param2 param3 qdot0 qdot1 (cos (+ q0 (* -1 q1)))) \
     (* (+ param0 param1) param4 param2 (cos q0)) \
     (* param1 param4 param3 (cos q1)))";

/// A heavy symmetric top in Euler angles `(phi, theta, psi)` (params `I1, I3, M g l`).
const HEAVY_TOP: &str = "(+ (* 0.5 param0 (+ (^ qdot1 2) (* (^ qdot0 2) (^ (sin q1) 2)))) \
     (* 0.5 param1 (^ (+ qdot2 (* qdot0 (cos q1))) 2)) \
     (* -1 param2 (cos q1)))";

/// The trajectory of a run and the final state `[q, qdot]`.
type Run = Result<(SimulationResult, Vec<f64>)>;

/// One case: name, time step, and a run of `steps` steps with a method.
struct Case {
    name: &'static str,
    dt: f64,
    run: fn(usize, f64, Method) -> Run,
}

fn run<L: Lagrangian>(
    lagrangian: L,
    q0: &[f64],
    qdot0: &[f64],
    steps: usize,
    dt: f64,
    method: Method,
) -> Run {
    let mut system = LagrangianModel::new(lagrangian, q0, qdot0)?;
    let result = system.integrate((0.0, steps as f64 * dt), dt, method)?;
    Ok((result, system.phase().state().to_vec()))
}

fn expr(text: &str, ndof: usize, params: Vec<f64>) -> Result<ExprLagrangian> {
    ExprLagrangian::new(Expr::parse(text)?, ndof, params)
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "user-hoop",
            dt: 2.2e-5,
            run: |n, dt, m| {
                let params = HoopParams {
                    omega: 3.0,
                    ..Default::default()
                };
                run(AutoDiff(params), &[0.3], &[0.0], n, dt, m)
            },
        },
        Case {
            name: "user-double-pendulum",
            dt: 3e-5,
            run: |n, dt, m| {
                let params = DoublePendulumParams::default();
                run(AutoDiff(params), &[2.0, 1.0], &[0.5, -0.3], n, dt, m)
            },
        },
        Case {
            name: "user-heavy-top",
            dt: 5e-5,
            run: |n, dt, m| {
                let params = SymmetricTopParams::default();
                run(
                    AutoDiff(params),
                    &[0.0, 0.5, 0.0],
                    &[0.0, 0.0, 20.0],
                    n,
                    dt,
                    m,
                )
            },
        },
        Case {
            name: "expr-double-pendulum",
            dt: 3e-5,
            run: |n, dt, m| {
                let p = DoublePendulumParams::default();
                let l = expr(DOUBLE_PENDULUM, 2, vec![p.m1, p.m2, p.l1, p.l2, p.g])?;
                run(l, &[2.0, 1.0], &[0.5, -0.3], n, dt, m)
            },
        },
        Case {
            name: "expr-heavy-top",
            dt: 5e-5,
            run: |n, dt, m| {
                let p = SymmetricTopParams::default();
                let l = expr(HEAVY_TOP, 3, vec![p.i1, p.i3, p.mgl()])?;
                run(l, &[0.0, 0.5, 0.0], &[0.0, 0.0, 20.0], n, dt, m)
            },
        },
    ]
}

fn usage() -> ! {
    eprintln!(
        "usage: lagrangian_ad CASE implicit_midpoint|rk4 STEPS [REPEATS] | lagrangian_ad list"
    );
    std::process::exit(2);
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("list") {
        for c in cases() {
            println!("{}", c.name);
        }
        return;
    }
    let [name, method, steps, rest @ ..] = args.as_slice() else {
        usage()
    };
    let Some(case) = cases().into_iter().find(|c| c.name == name) else {
        usage()
    };
    let method = match method.as_str() {
        "implicit_midpoint" => Method::ImplicitMidpoint,
        "rk4" => Method::Rk4,
        _ => usage(),
    };
    let Ok(steps) = steps.parse::<usize>() else {
        usage()
    };
    let repeats: usize = rest.first().and_then(|r| r.parse().ok()).unwrap_or(1);
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeats {
        let start = Instant::now();
        let out = std::hint::black_box((case.run)(steps, case.dt, method)).expect("runs");
        best = best.min(start.elapsed().as_secs_f64());
        last = Some(out);
    }
    let (result, state) = last.expect("at least one run");
    let drift = result.max_relative_energy_error().unwrap_or(f64::NAN);
    println!("{name} {method:?} {steps} steps: final state {state:?}, max|dE/E0| {drift:.2e}");
    if repeats > 1 {
        let ns = best * 1e9 / steps.max(1) as f64;
        println!("{name} {method:?}: {ns:.1} ns/step, best of {repeats}");
    }
}
