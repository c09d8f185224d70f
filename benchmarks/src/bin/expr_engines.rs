//! The expression-defined Hamiltonian (`ExprHamiltonian`, the path of a SymPy
//! `HamiltonianEngine` from Python) against the built-in system it spells out: the
//! "Expression engines" figures in benchmarks/README.md.
//!
//! `expr_engines CASE STEPS` integrates one case with `yoshida4` for `STEPS` steps and prints
//! the final state (run it under `valgrind --tool=callgrind` and difference two step counts
//! for instructions per step: `benchmarks/expr_engines.sh` does that); `expr_engines CASE
//! STEPS REPEATS` prints the best wall time per step of `REPEATS` runs.
//!
//! Cases: `builtin-henon-heiles` (`HenonHeilesSystem`, hand-written force) and
//! `expr-henon-heiles` (the same `H` as SymPy hands it over, derived and compiled by
//! `ExprHamiltonian`), both from `(x, y, p_x, p_y) = (0, 0.1, 0.5, 0)`, `dt = 0.01`.

use std::time::Instant;

use physicskit::classical::lagrangian::{Expr, ExprHamiltonian};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method, Result};

/// `H = p_x^2/2 + p_y^2/2 + x^2/2 + y^2/2 + x^2 y - y^3/3` as the Python `HamiltonianEngine`
/// translates SymPy's expression of it.
pub const HENON_HEILES: &str = "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* 0.5 (^ q0 2)) \
     (* 0.5 (^ q1 2)) (* (^ q0 2) q1) (* -0.3333333333333333 (^ q1 3)))";

const Q0: [f64; 2] = [0.0, 0.1];
const P0: [f64; 2] = [0.5, 0.0];
const DT: f64 = 0.01;

fn run(case: &str, steps: usize) -> Result<Vec<f64>> {
    let span = (0.0, steps as f64 * DT);
    match case {
        "builtin-henon-heiles" => {
            let mut s = HenonHeilesSystem::new(&Q0, &P0)?;
            s.integrate(span, DT, Method::Yoshida4)?;
            Ok(s.state().to_vec())
        }
        "expr-henon-heiles" => {
            let mut s = ExprHamiltonian::new(Expr::parse(HENON_HEILES)?, 2, vec![], &Q0, &P0)?;
            if std::env::var_os("EXPR_ENGINES_VERBOSE").is_some() {
                eprintln!("{} operations per force", s.operations_per_evaluation());
            }
            s.integrate(span, DT, Method::Yoshida4)?;
            Ok(s.state().to_vec())
        }
        other => Err(physicskit::classical::Error::invalid(
            "case",
            f64::NAN,
            format!("unknown case `{other}`: builtin-henon-heiles or expr-henon-heiles"),
        )),
    }
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let case = args.first().map_or("expr-henon-heiles", String::as_str);
    let steps: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    match args.get(2).and_then(|s| s.parse::<usize>().ok()) {
        None => println!("{:?}", run(case, steps)?),
        Some(repeats) => {
            let mut best = f64::INFINITY;
            for _ in 0..repeats.max(1) {
                let start = Instant::now();
                std::hint::black_box(run(case, steps)?);
                best = best.min(start.elapsed().as_secs_f64());
            }
            println!("{case}: {:.1} ns per step", best / steps as f64 * 1e9);
        }
    }
    Ok(())
}
