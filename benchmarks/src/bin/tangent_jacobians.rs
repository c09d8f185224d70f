//! The double pendulum's Jacobians by automatic differentiation of its closed forms against
//! central differences and against the second derivatives of `L`, alone and inside
//! `max_lyapunov`: the "Tangent dynamics of the Lagrangian systems" figures in
//! benchmarks/README.md.
//!
//! `tangent_jacobians CASE N` runs `N` repetitions of one case and prints a checksum (run it
//! under `valgrind --tool=callgrind` and difference two values of `N` for instructions per
//! repetition: `benchmarks/tangent_jacobians.sh` does that; `list` prints the cases).
//!
//! Cases (`N` Jacobians at slightly different states, or `N` steps of `dt = 0.01` from the
//! chaotic `(2, 1)`, `(0.5, -0.3)`):
//!
//! - `jacobian-ad`, `jacobian-fd`: `d[qdot, qddot]/d[q, qdot]` (the form `rk4` steps);
//! - `canonical-ad`, `canonical-l`, `canonical-fd`: `d[qdot, pdot]/d[q, p]` (the implicit
//!   methods' form): closed forms on duals, second derivatives of `L` (`AutoDiff` engine, what
//!   every Lagrangian system used before the generic closed forms), central differences;
//! - `orbit-rk4`, `orbit-midpoint`: the orbit alone on the same flow;
//! - `lyapunov-rk4-ad`, `lyapunov-rk4-fd`, `lyapunov-midpoint-ad`, `lyapunov-midpoint-fd`: a
//!   step of `max_lyapunov` (one deviation vector, renormalized every 10 steps).

use std::hint::black_box;

use physicskit::classical::analysis::lyapunov::max_lyapunov;
use physicskit::classical::integrators::tangent::{central_difference, lagrangian_flow};
use physicskit::classical::lagrangian::{AutoDiff, CentralDifferences, LagrangianEngine};
use physicskit::classical::model::erased::Lagrangian as Erased;
use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
use physicskit::classical::{DynamicalSystem, Error, LagrangianSystem, Method, Result};

const CASES: [&str; 11] = [
    "jacobian-ad",
    "jacobian-fd",
    "canonical-ad",
    "canonical-l",
    "canonical-fd",
    "orbit-rk4",
    "orbit-midpoint",
    "lyapunov-rk4-ad",
    "lyapunov-rk4-fd",
    "lyapunov-midpoint-ad",
    "lyapunov-midpoint-fd",
];

const DT: f64 = 0.01;

/// `n` Jacobians of `jac` at states drifting by `1e-9` per call (nothing to hoist).
fn jacobians(n: usize, mut jac: impl FnMut(&[f64], &mut [f64]) -> Result<()>) -> Result<f64> {
    let mut state = [2.0, 1.0, 0.5, -0.3];
    let mut out = [0.0; 16];
    let mut sum = 0.0;
    for _ in 0..n {
        state[0] += 1e-9;
        jac(black_box(&state), &mut out)?;
        sum += black_box(out)[10];
    }
    Ok(sum)
}

/// Central differences as `integrators/tangent.rs` takes them.
fn central(
    field: impl Fn(&[f64], &mut [f64]) -> Result<()>,
    x: &[f64],
    out: &mut [f64],
) -> Result<()> {
    let (mut xp, mut fp, mut fm) = ([0.0; 4], [0.0; 4], [0.0; 4]);
    central_difference(field, x, &mut xp, &mut fp, &mut fm, out)
}

fn lyapunov<S>(system: S, method: Method, n: usize) -> Result<f64>
where
    S: LagrangianSystem + physicskit::classical::model::Capabilities + Send + Sync + 'static,
{
    let mut s = Erased(system);
    Ok(max_lyapunov(&mut s, (0.0, n as f64 * DT), DT, Some(method), 10)?.exponents[0])
}

fn run(case: &str, n: usize) -> Result<f64> {
    let params = DoublePendulumParams::default();
    let dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], params)?;
    let from_l = LagrangianEngine::new(AutoDiff(params))?;
    match case {
        "jacobian-ad" => jacobians(n, |x, o| dp.jacobian(0.0, x, o).unwrap_or(Ok(()))),
        "jacobian-fd" => jacobians(n, |x, o| central(|y, f| dp.derivatives(0.0, y, f), x, o)),
        "canonical-ad" => jacobians(n, |x, o| dp.canonical_jacobian(0.0, x, o).unwrap_or(Ok(()))),
        "canonical-l" => jacobians(n, |x, o| from_l.canonical_jacobian(0.0, x, o)),
        "canonical-fd" => jacobians(n, |x, o| {
            central(|y, f| dp.canonical_derivatives(0.0, y, f), x, o)
        }),
        "orbit-rk4" | "orbit-midpoint" => {
            let method = if case == "orbit-rk4" {
                Method::Rk4
            } else {
                Method::ImplicitMidpoint
            };
            let mut flow = lagrangian_flow(&dp, method, 1)?;
            let mut y = [0.0; 4];
            flow.enter(0.0, dp.state(), &mut y)?;
            for i in 0..n {
                flow.step(i as f64 * DT, &mut y, DT)?;
            }
            Ok(y[0])
        }
        "lyapunov-rk4-ad" => lyapunov(dp, Method::Rk4, n),
        "lyapunov-rk4-fd" => lyapunov(CentralDifferences(dp), Method::Rk4, n),
        "lyapunov-midpoint-ad" => lyapunov(dp, Method::ImplicitMidpoint, n),
        "lyapunov-midpoint-fd" => lyapunov(CentralDifferences(dp), Method::ImplicitMidpoint, n),
        other => Err(Error::invalid(
            "case",
            f64::NAN,
            format!("unknown case `{other}`: one of {CASES:?}"),
        )),
    }
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let case = args.first().map_or("list", String::as_str);
    if case == "list" {
        CASES.iter().for_each(|c| println!("{c}"));
        return Ok(());
    }
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    println!("{}", run(case, n)?);
    Ok(())
}
