//! Our side of `benchmarks/heyoka_compare.py`: the adaptive Taylor method
//! ([`integrate_taylor`] on a [`TaylorProgram`]) on the comparison's workloads at every half
//! decade of tolerance from 1e-6 to 1e-16 ([`half_decades`]), one JSON object per line:
//! workload, tolerance, the best wall time of five runs after one untimed run with the
//! recurrences compiled by the JIT (built and compiled once, outside the timing, as heyoka's
//! integrator is), the same with the recurrences interpreted, the time to build them and to
//! compile them, the steps, the order and the final state (or, for `hh-energy`, the largest
//! energy error on a grid of unit spacing). The script measures the errors against its
//! extended-precision reference.
//!
//! Workloads (their initial states are the script's too):
//! - `kepler`: `e = 0.5`, `a = 1`, from perihelion, 100 orbits (`t = 200 pi`);
//! - `hh-state`: Hénon–Heiles at `E = 1/6` from `q = (0, 0.1)`, `p_x = 0.4`, `t = 100`;
//! - `hh-energy`: the same start, `t = 1000`, largest energy error;
//! - `pendulum`: the double pendulum (unit masses and arms, `g = 9.81`) from rest at
//!   `(2, 1.5)` rad, `t = 10`, state `(q, p)`; its program is Hamilton's equations from the
//!   system's traced `L`.
//!
//! Arguments (all optional, for timing one side alone): `--only WORKLOAD` and `--tol TOL`
//! run that workload or tolerance alone, `--no-interpreted` skips the interpreted timing
//! (its field is then `NaN`), `--repeats N` takes the best of `N` runs instead of five,
//! `--form compact` or `--form unrolled` compiles the recurrences in that form whatever the
//! program's size (by default the library picks it by size), `--pendulum-from-h` builds the
//! pendulum's program from its `H` (the inverse mass matrix written out, differentiated)
//! instead of from its `L` (`TaylorProgram::lagrangian_canonical`), `--convolution-scale F`
//! weighs the convolutions of the program's [`StepCost`] by `F` (below 1 a higher order and
//! longer steps, above 1 a lower order: how the time to an error depends on the order the
//! cost picks).

use std::time::Instant;

use physicskit_benchmarks::half_decades;

use physicskit::classical::integrators::taylor::{
    integrate_taylor, order_for, InBlocks, StepCost, TaylorField,
};
use physicskit::classical::symbolic::{trace_lagrangian, Expr, ExprHamiltonian};
use physicskit::classical::symbolic::{Backend, TaylorProgram};
use physicskit::classical::systems::DoublePendulumParams;
use physicskit::classical::{Result, Tolerances};

/// `H` of each workload as the expression the program is built from, and its start.
fn workload(name: &str) -> Result<(ExprHamiltonian, Vec<f64>, f64)> {
    let parse = Expr::parse;
    Ok(match name {
        "kepler" => {
            let h = parse("(- (* 0.5 (+ (^ p0 2) (^ p1 2))) (^ (+ (^ q0 2) (^ q1 2)) -0.5))")?;
            let y0 = vec![0.5, 0.0, 0.0, 3f64.sqrt()];
            (
                ExprHamiltonian::new(h, 2, vec![], &y0[..2], &y0[2..])?,
                y0,
                200.0 * std::f64::consts::PI,
            )
        }
        "hh-state" | "hh-energy" => {
            let h = parse(
                "(+ (* 0.5 (+ (^ p0 2) (^ p1 2) (^ q0 2) (^ q1 2))) (* (^ q0 2) q1) \
                 (* (/ -1 3) (^ q1 3)))",
            )?;
            let (x, y, px) = (0.0_f64, 0.1_f64, 0.4_f64);
            let v = 0.5 * (x * x + y * y) + x * x * y - y * y * y / 3.0;
            let py = (2.0 * (1.0 / 6.0 - v) - px * px).sqrt();
            let y0 = vec![x, y, px, py];
            let t = if name == "hh-state" { 100.0 } else { 1000.0 };
            (
                ExprHamiltonian::new(h, 2, vec![], &y0[..2], &y0[2..])?,
                y0,
                t,
            )
        }
        _ => {
            // a = (m1 + m2) l1^2, b = m2 l1 l2, d = m2 l2^2, g1 = (m1 + m2) g l1, g2 = m2 g l2.
            let h = parse(
                "(- (- (/ (+ (* param2 (^ p0 2)) (* param0 (^ p1 2)) \
                 (* -2 param1 (cos (- q0 q1)) p0 p1)) \
                 (* 2 (- (* param0 param2) (^ (* param1 (cos (- q0 q1))) 2)))) \
                 (* param3 (cos q0))) (* param4 (cos q1)))",
            )?;
            let y0 = vec![2.0, 1.5, 0.0, 0.0];
            let params = vec![2.0, 1.0, 1.0, 2.0 * 9.81, 9.81];
            (
                ExprHamiltonian::new(h, 2, params, &y0[..2], &y0[2..])?,
                y0,
                10.0,
            )
        }
    })
}

/// `cost` with its convolutions weighed by `scale`.
fn scaled(cost: StepCost, scale: f64) -> StepCost {
    StepCost {
        convolution: cost.convolution * scale,
        ..cost
    }
}

/// A program whose step cost weighs its convolutions by `scale` (`--convolution-scale`).
struct Reweighted {
    program: TaylorProgram,
    scale: f64,
}

impl TaylorField for Reweighted {
    fn dim(&self) -> usize {
        self.program.dim()
    }

    fn step_cost(&self) -> StepCost {
        scaled(self.program.step_cost(), self.scale)
    }

    fn expansion(&mut self, t: f64, y: &[f64], order: usize) -> Result<&[f64]> {
        self.program.expansion(t, y, order)
    }

    fn expansion_in_blocks(&mut self, t: f64, y: &[f64], order: usize) -> Result<InBlocks<'_>> {
        self.program.expansion_in_blocks(t, y, order)
    }
}

/// The command line's choices.
struct Options {
    only: Option<String>,
    tol: Option<f64>,
    interpreted: bool,
    repeats: usize,
    form: Option<String>,
    pendulum_from_h: bool,
    convolution_scale: f64,
}

fn options() -> Options {
    let mut o = Options {
        only: None,
        tol: None,
        interpreted: true,
        repeats: 5,
        form: None,
        pendulum_from_h: false,
        convolution_scale: 1.0,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--only" => o.only = args.next(),
            "--tol" => o.tol = args.next().and_then(|t| t.parse().ok()),
            "--no-interpreted" => o.interpreted = false,
            "--form" => o.form = args.next(),
            "--pendulum-from-h" => o.pendulum_from_h = true,
            "--convolution-scale" => match args.next().and_then(|f| f.parse::<f64>().ok()) {
                Some(f) if f.is_finite() && f > 0.0 => o.convolution_scale = f,
                _ => {
                    eprintln!("--convolution-scale takes a positive number");
                    std::process::exit(2);
                }
            },
            "--repeats" => o.repeats = args.next().and_then(|n| n.parse().ok()).unwrap_or(5),
            _ => {
                eprintln!(
                    "usage: heyoka_taylor [--only WORKLOAD] [--tol TOL] [--no-interpreted] \
                     [--repeats N] [--form compact|unrolled] [--pendulum-from-h] \
                     [--convolution-scale F]"
                );
                std::process::exit(2);
            }
        }
    }
    o
}

fn main() -> Result<()> {
    let options = options();
    let tolerances = half_decades(6, 16);
    for name in ["kepler", "hh-state", "hh-energy", "pendulum"] {
        if options.only.as_deref().is_some_and(|only| only != name) {
            continue;
        }
        let (system, y0, t1) = workload(name)?;
        for &tol in &tolerances {
            // Parsed from the same decimal as the list's, so the same double.
            if options
                .tol
                .is_some_and(|only| only.to_bits() != tol.to_bits())
            {
                continue;
            }
            let tol_pair = Tolerances::new(tol, tol)?;
            let start = Instant::now();
            let program = if name == "pendulum" && !options.pendulum_from_h {
                // The system's own L (traced): its kinetic energy is quadratic, so the
                // velocities `w = M^-1 p` are solved for once and shared, as in heyoka's
                // equations.
                let params = DoublePendulumParams {
                    m1: 1.0,
                    m2: 1.0,
                    l1: 1.0,
                    l2: 1.0,
                    g: 9.81,
                };
                TaylorProgram::lagrangian_canonical(&trace_lagrangian(&params)?)?
            } else {
                TaylorProgram::hamiltonian(&system)?
            };
            let build = start.elapsed().as_secs_f64();
            let start = Instant::now();
            let scale = options.convolution_scale;
            let order = order_for(&tol_pair, &scaled(program.step_cost(), scale));
            let backend = match options.form.as_deref() {
                Some("compact") => program.compile_native_compact(order),
                Some("unrolled") => program.compile_native_unrolled(order),
                _ => program.compile_native(order),
            };
            let compile = start.elapsed().as_secs_f64();
            if backend != Backend::Native {
                eprintln!("{name} at {tol:e}: the recurrences were not compiled");
            }
            let dt = if name == "hh-energy" { 1.0 } else { t1 };
            let timed = |program: TaylorProgram| -> Result<_> {
                let mut program = Reweighted { program, scale };
                let mut best = f64::INFINITY;
                let mut last = integrate_taylor(&mut program, &y0, (0.0, t1), dt, tol_pair)?;
                for _ in 0..options.repeats {
                    let start = Instant::now();
                    last = integrate_taylor(&mut program, &y0, (0.0, t1), dt, tol_pair)?;
                    best = best.min(start.elapsed().as_secs_f64());
                }
                Ok((best, last))
            };
            let interpreted = if options.interpreted {
                timed(program.interpreted_only())?.0
            } else {
                f64::NAN
            };
            let (best, r) = timed(program)?;
            let steps = r.extra_scalar("steps").unwrap_or(f64::NAN);
            let order = r.extra_scalar("order").unwrap_or(f64::NAN);
            let result = if name == "hh-energy" {
                let energy = |y: &[f64]| {
                    0.5 * (y[2] * y[2] + y[3] * y[3] + y[0] * y[0] + y[1] * y[1])
                        + y[0] * y[0] * y[1]
                        - y[1] * y[1] * y[1] / 3.0
                };
                let e0 = energy(&y0);
                let worst =
                    r.y.rows()
                        .into_iter()
                        .map(|row| (energy(&row.to_vec()) - e0).abs())
                        .fold(0.0, f64::max);
                format!("\"energy_error\": {worst:e}")
            } else {
                let last_row: Vec<String> =
                    r.y.row(r.y.nrows() - 1)
                        .iter()
                        .map(|v| format!("{v:e}"))
                        .collect();
                format!("\"final\": [{}]", last_row.join(", "))
            };
            println!(
                "{{\"workload\": \"{name}\", \"tol\": {tol:e}, \"seconds\": {best:e}, \
                 \"interpreted_seconds\": {interpreted:e}, \"build_seconds\": {build:e}, \
                 \"compile_seconds\": {compile:e}, \"steps\": {steps}, \"order\": {order}, {result}}}"
            );
        }
    }
    Ok(())
}
