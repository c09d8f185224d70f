//! The expression-defined systems (`ExprHamiltonian`, `ExprOde`: the paths of a SymPy
//! `HamiltonianEngine` and `ODEEngine` from Python) against the hand-written systems they
//! spell out: the "Expression engines" figures in benchmarks/README.md.
//!
//! `expr_engines CASE STEPS` integrates one case for `STEPS` steps and prints the final state
//! (run it under `valgrind --tool=callgrind` and difference two step counts for instructions
//! per step: `benchmarks/expr_engines.sh` does that); `expr_engines CASE STEPS REPEATS`
//! prints the best wall time per step of `REPEATS` runs.
//!
//! Cases, `yoshida4` from `(x, y, p_x, p_y) = (0, 0.1, 0.5, 0)`, `dt = 0.01`, every sample
//! and its energy stored: `builtin-henon-heiles` (`HenonHeilesSystem`, hand-written force),
//! `expr-henon-heiles` (the same `H` as SymPy hands it over, derived and compiled by
//! `ExprHamiltonian`, its tapes compiled to machine code up front) and
//! `expr-henon-heiles-interpreted` (the same, kept on the interpreter). `rk4` from
//! `(1, 1, 1)`, `dt = 0.001`, every sample stored, no energy: `builtin-lorenz` (the Lorenz
//! field written below), `expr-lorenz` (`ExprOde`, compiled) and `expr-lorenz-interpreted`.

use std::time::Instant;

use physicskit::classical::symbolic::{Backend, Expr, ExprHamiltonian, ExprOde};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{
    DynamicalSystem, HamiltonianSystem, IntegrateOptions, Method, OdeSystem, Phase, Result,
};

/// `H = p_x^2/2 + p_y^2/2 + x^2/2 + y^2/2 + x^2 y - y^3/3` as the Python `HamiltonianEngine`
/// translates SymPy's expression of it.
pub const HENON_HEILES: &str = "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* 0.5 (^ q0 2)) \
     (* 0.5 (^ q1 2)) (* (^ q0 2) q1) (* -0.3333333333333333 (^ q1 3)))";

/// The Lorenz field, `sigma = 10`, `rho = 28`, `beta = 8/3` as parameters 0, 1, 2, as the
/// Python `ODEEngine` translates SymPy's expressions of it.
pub const LORENZ: [&str; 3] = [
    "(* param0 (- y1 y0))",
    "(- (* y0 (- param1 y2)) y1)",
    "(- (* y0 y1) (* param2 y2))",
];

const Q0: [f64; 2] = [0.0, 0.1];
const P0: [f64; 2] = [0.5, 0.0];
const DT: f64 = 0.01;
const Y0: [f64; 3] = [1.0, 1.0, 1.0];
const DT_LORENZ: f64 = 0.001;
const SIGMA: f64 = 10.0;
const RHO: f64 = 28.0;
const BETA: f64 = 8.0 / 3.0;

/// The Lorenz system written by hand: the reference for `ExprOde`.
struct Lorenz {
    phase: Phase,
}

impl DynamicalSystem for Lorenz {
    fn phase(&self) -> &Phase {
        &self.phase
    }

    fn phase_mut(&mut self) -> &mut Phase {
        &mut self.phase
    }

    #[inline]
    fn derivatives(&self, _t: f64, y: &[f64], out: &mut [f64]) -> Result<()> {
        if let ([y0, y1, y2, ..], [f0, f1, f2, ..]) = (y, out) {
            *f0 = SIGMA * (*y1 - *y0);
            *f1 = *y0 * (RHO - *y2) - *y1;
            *f2 = *y0 * *y1 - BETA * *y2;
        }
        Ok(())
    }

    fn energy(&self, _state: &[f64]) -> f64 {
        f64::NAN
    }

    fn default_method(&self) -> Method {
        Method::Rk4
    }
}

impl OdeSystem for Lorenz {}

fn unknown(case: &str) -> physicskit::classical::Error {
    physicskit::classical::Error::invalid(
        "case",
        f64::NAN,
        format!(
            "unknown case `{case}`: builtin-henon-heiles, expr-henon-heiles, \
             expr-henon-heiles-interpreted, builtin-lorenz, expr-lorenz, expr-lorenz-interpreted"
        ),
    )
}

/// Compiles an expression system's tapes (`compile`) or keeps them on the interpreter
/// (`interpret`, for the `-interpreted` cases); with `EXPR_ENGINES_VERBOSE` set, prints the
/// operations per evaluation, the backend and the time taken.
fn prepare(
    case: &str,
    compile: impl FnOnce() -> Backend,
    interpret: impl FnOnce() -> Backend,
    operations: usize,
) {
    let start = Instant::now();
    let backend = if case.ends_with("-interpreted") {
        interpret()
    } else {
        compile()
    };
    if std::env::var_os("EXPR_ENGINES_VERBOSE").is_some() {
        let us = start.elapsed().as_secs_f64() * 1e6;
        eprintln!("{case}: {operations} operations per evaluation, {backend:?} ({us:.0} us)");
    }
}

fn run(case: &str, steps: usize) -> Result<Vec<f64>> {
    let span = (0.0, steps as f64 * DT);
    let lorenz_span = (0.0, steps as f64 * DT_LORENZ);
    // No energies: `ExprOde` without an energy expression stores none.
    let lorenz_options = || IntegrateOptions {
        skip_energy: true,
        ..IntegrateOptions::default()
    };
    match case {
        "builtin-henon-heiles" => {
            let mut s = HenonHeilesSystem::new(&Q0, &P0)?;
            s.integrate(span, DT, Method::Yoshida4)?;
            Ok(s.state().to_vec())
        }
        "expr-henon-heiles" | "expr-henon-heiles-interpreted" => {
            let mut s = ExprHamiltonian::new(Expr::parse(HENON_HEILES)?, 2, vec![], &Q0, &P0)?;
            prepare(
                case,
                || s.compile_native(),
                || s.compile_native_for_unsupported_host(),
                s.operations_per_evaluation(),
            );
            s.integrate(span, DT, Method::Yoshida4)?;
            Ok(s.state().to_vec())
        }
        "builtin-lorenz" => {
            let mut s = Lorenz {
                phase: Phase::new(Y0.to_vec(), 0.0)?,
            };
            s.integrate_with(lorenz_span, DT_LORENZ, Method::Rk4, lorenz_options())?;
            Ok(s.state().to_vec())
        }
        "expr-lorenz" | "expr-lorenz-interpreted" => {
            let f = LORENZ
                .iter()
                .map(|e| Expr::parse(e))
                .collect::<Result<_>>()?;
            let mut s = ExprOde::new(f, vec![SIGMA, RHO, BETA], &Y0, None)?;
            prepare(
                case,
                || s.compile_native(),
                || s.compile_native_for_unsupported_host(),
                s.operations_per_evaluation(),
            );
            s.integrate_with(lorenz_span, DT_LORENZ, Method::Rk4, lorenz_options())?;
            Ok(s.state().to_vec())
        }
        other => Err(unknown(other)),
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
