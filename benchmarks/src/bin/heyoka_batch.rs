//! Our side of the batch workload of `benchmarks/heyoka_compare.py`: 1000 Hénon–Heiles orbits
//! at `E = 1/6` launched on the surface `x = 0`, integrated to `t = 100` by the adaptive Taylor
//! method, on one thread and on two. One JSON object per line:
//!
//! - `starts`: the 1000 initial states (the script launches heyoka's orbits from these, so
//!   both sides start from the same bits);
//! - `ensemble`: the ensemble API as a user runs it (`ensemble::run` on the catalogue's
//!   `henon-heiles`, method `taylor`), its plan without tolerances, so at the default ones
//!   (`rtol` 1e-10, `atol` 1e-12): the members share one Taylor form and run in SIMD lanes
//!   (16 with AVX-512, 8 with AVX2; `integrators::taylor_batch`);
//! - `lanes`: the same API with the plan's tolerances `rtol = atol = tol` for `tol` at every
//!   half decade from 1e-6 to 1e-16 ([`half_decades`]: heyoka's error at its tightest
//!   tolerance, 1e-14, takes one of ours below that), whether its final states are the
//!   `compiled` run's bits at that `tol`, and the time to compile the recurrences for the
//!   ensemble's lanes at that `tol`'s order (measured first, before any run has compiled
//!   them);
//! - `compiled`: the same members' Taylor form (the catalogue system's trace) built once,
//!   its recurrences compiled by the JIT outside the timing (as heyoka compiles in its
//!   constructor), each member integrated by `integrate_taylor` on a clone (clones share the
//!   code) in parallel with rayon, at the same tolerances.
//!
//! Each time is the best of five after one untimed run. The final states are printed for
//! one thread; the two-thread runs report whether they are the same bits. The compiled run at
//! the default tolerances is checked once against the ensemble's result (same recurrences, so
//! the same bits). The script measures the errors against its extended-precision reference.

use std::time::Instant;

use physicskit_benchmarks::half_decades;

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Members, Plan};
use physicskit::classical::integrators::taylor::{integrate_taylor, order_for, TaylorField};
use physicskit::classical::symbolic::{native_lanes, trace_hamiltonian, Backend, TaylorProgram};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{Error, Method, Result, Tolerances};
use rayon::prelude::*;

/// Orbits: a lattice of 50 heights `y` by 20 momenta `p_x` on `x = 0`.
const ROWS: usize = 50;
const COLUMNS: usize = 20;
/// The span.
const T_END: f64 = 100.0;
/// Members per parallel task: 1000 members make 63 tasks, enough to balance two threads.
const CHUNK: usize = 16;

/// The initial states `(x, y, p_x, p_y)`: `x = 0`, `y` in [-0.2, 0.3], `p_x` at the midpoints
/// of 20 equal parts of [-0.4, 0.4], `p_y > 0` from `E = 1/6` (positive over the whole
/// lattice: `2 (1/6 - V(0, y)) >= 0.26 > 0.16 >= p_x^2`). No `p_x` is zero: an orbit started
/// with `x = p_x = 0` stays on the line `x = 0` and, at `E = 1/6` rounded up, runs through the
/// saddle at `y = 1` and escapes to infinity in finite time, where the Taylor method stops
/// (its step underflows) and heyoka reports non-finite states.
fn starts() -> Vec<[f64; 4]> {
    let mut out = Vec::with_capacity(ROWS * COLUMNS);
    for j in 0..ROWS {
        let y = -0.2 + 0.5 * j as f64 / (ROWS - 1) as f64;
        for k in 0..COLUMNS {
            let px = -0.4 + 0.8 * (k as f64 + 0.5) / COLUMNS as f64;
            let v = 0.5 * y * y - y * y * y / 3.0;
            let py = (2.0 * (1.0 / 6.0 - v) - px * px).sqrt();
            out.push([0.0, y, px, py]);
        }
    }
    out
}

/// A rayon pool of `threads` threads.
fn pool(threads: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Unsupported {
            operation: "thread pool".into(),
            reason: e.to_string(),
        })
}

/// The best wall time of five runs of `f` after one untimed run, and the last run's output.
fn best_of_five<T>(mut f: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut last = f()?;
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = Instant::now();
        last = f()?;
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok((best, last))
}

/// Every member by `integrate_taylor` on clones of `program`: the final states, row-major,
/// and the steps taken in all.
fn compiled_run(
    program: &TaylorProgram,
    starts: &[[f64; 4]],
    tolerances: Tolerances,
    pool: &rayon::ThreadPool,
) -> Result<(Vec<f64>, f64)> {
    pool.install(|| {
        let chunks: Vec<Result<(Vec<f64>, f64)>> = starts
            .par_chunks(CHUNK)
            .map_init(
                || program.clone(),
                |program, chunk| {
                    let mut finals = Vec::with_capacity(4 * chunk.len());
                    let mut steps = 0.0;
                    for y0 in chunk {
                        let r = integrate_taylor(program, y0, (0.0, T_END), T_END, tolerances)?;
                        finals.extend(r.y.row(r.y.nrows() - 1).iter());
                        steps += r.extra_scalar("steps").unwrap_or(f64::NAN);
                    }
                    Ok((finals, steps))
                },
            )
            .collect();
        let mut finals = Vec::with_capacity(4 * starts.len());
        let mut steps = 0.0;
        for chunk in chunks {
            let (f, s) = chunk?;
            finals.extend(f);
            steps += s;
        }
        Ok((finals, steps))
    })
}

/// The ensemble API's plan: method `taylor`, final states, on `threads` threads, at
/// `tolerances` (`None`: the defaults).
fn plan(threads: usize, tolerances: Option<Tolerances>) -> Plan {
    Plan {
        t_span: (0.0, T_END),
        dt: T_END,
        method: Some(Method::Taylor),
        stride: None,
        reductions: vec![],
        final_state: true,
        threads: Some(threads),
        tolerances,
    }
}

/// The time to compile `program`'s recurrences at `order` for the lanes an ensemble takes on
/// this CPU (fresh lanes, so the code is compiled, not found), and whether they were compiled.
fn lanes_compile(program: &TaylorProgram, order: usize) -> (f64, bool) {
    fn time<const L: usize>(program: &TaylorProgram, order: usize) -> (f64, bool) {
        let lanes = program.lanes::<L>();
        let start = Instant::now();
        let backend = lanes.compile_native(order);
        (start.elapsed().as_secs_f64(), backend == Backend::Native)
    }
    match native_lanes() {
        16 => time::<16>(program, order),
        8 => time::<8>(program, order),
        _ => time::<4>(program, order),
    }
}

/// `values` as a JSON array (shortest round-trip digits).
fn json(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
    format!("[{}]", items.join(", "))
}

fn main() -> Result<()> {
    let starts = starts();
    let flat: Vec<f64> = starts.iter().flatten().copied().collect();
    println!("{{\"kind\": \"starts\", \"states\": {}}}", json(&flat));
    let pools = [pool(1)?, pool(2)?];

    // The lanes' compile times, first: later lanes of the same recurrences reuse the code.
    let system = HenonHeilesSystem::new(&starts[0][..2], &starts[0][2..])?;
    let traced = TaylorProgram::hamiltonian(&trace_hamiltonian(
        &system,
        &starts[0][..2],
        &starts[0][2..],
    )?)?;
    let tolerances = half_decades(6, 16);
    let mut lanes_compiles = Vec::new();
    for &tol in &tolerances {
        lanes_compiles.push(lanes_compile(
            &traced,
            order_for(&Tolerances::new(tol, tol)?, &traced.step_cost()),
        ));
    }

    // The ensemble API, at its (the default) tolerances.
    let entry = catalog::find("henon-heiles")?;
    let members = Members {
        states: Some(flat.clone()),
        n: starts.len(),
        ..Members::default()
    };
    let mut ensemble_finals = Vec::new();
    for (threads, _) in (1..).zip(&pools) {
        let plan = plan(threads, None);
        let (seconds, out) = best_of_five(|| ensemble::run(entry, &members, &plan, None))?;
        let finals: Vec<f64> = out.final_state.iter().copied().collect();
        let defaults = Tolerances::default();
        let head = format!(
            "{{\"kind\": \"ensemble\", \"threads\": {threads}, \"rtol\": {:e}, \"atol\": {:e}, \
             \"seconds\": {seconds:e}",
            defaults.rtol, defaults.atol
        );
        if threads == 1 {
            println!("{head}, \"final\": {}}}", json(&finals));
            ensemble_finals = finals;
        } else {
            println!("{head}, \"same_bits\": {}}}", finals == ensemble_finals);
        }
    }

    // The same recurrences (the catalogue system's trace), built and compiled once.
    let system = HenonHeilesSystem::new(&starts[0][..2], &starts[0][2..])?;
    let start = Instant::now();
    let program = TaylorProgram::hamiltonian(&trace_hamiltonian(
        &system,
        &starts[0][..2],
        &starts[0][2..],
    )?)?;
    let build = start.elapsed().as_secs_f64();

    // At the ensemble's tolerances: the same bits as the ensemble (checked, not timed).
    let defaults = Tolerances::default();
    program.compile_native(order_for(&defaults, &program.step_cost()));
    let (finals, _) = compiled_run(&program, &starts, defaults, &pools[0])?;
    println!(
        "{{\"kind\": \"check\", \"compiled_equals_ensemble\": {}}}",
        finals == ensemble_finals
    );

    let mut compiled_finals = Vec::new();
    for &tol in &tolerances {
        let tolerances = Tolerances::new(tol, tol)?;
        let start = Instant::now();
        let backend = program.compile_native(order_for(&tolerances, &program.step_cost()));
        let compile = start.elapsed().as_secs_f64();
        if backend != Backend::Native {
            eprintln!("tol {tol:e}: the recurrences were not compiled");
        }
        let mut first = Vec::new();
        for (threads, pool) in (1..).zip(&pools) {
            let (seconds, (finals, steps)) =
                best_of_five(|| compiled_run(&program, &starts, tolerances, pool))?;
            let head = format!(
                "{{\"kind\": \"compiled\", \"threads\": {threads}, \"tol\": {tol:e}, \
                 \"seconds\": {seconds:e}, \"steps\": {steps}, \"build_seconds\": {build:e}, \
                 \"compile_seconds\": {compile:e}, \"native\": {}",
                backend == Backend::Native
            );
            if threads == 1 {
                println!("{head}, \"final\": {}}}", json(&finals));
                first = finals;
            } else {
                println!("{head}, \"same_bits\": {}}}", finals == first);
            }
        }
        compiled_finals.push(first);
    }

    // The ensemble API (members in SIMD lanes) at the same tolerances.
    for (i, (&tol, compiled)) in tolerances.iter().zip(&compiled_finals).enumerate() {
        let (compile, native) = lanes_compiles[i];
        let mut first = Vec::new();
        for (threads, _) in (1..).zip(&pools) {
            let plan = plan(threads, Some(Tolerances::new(tol, tol)?));
            let (seconds, out) = best_of_five(|| ensemble::run(entry, &members, &plan, None))?;
            let finals: Vec<f64> = out.final_state.iter().copied().collect();
            let head = format!(
                "{{\"kind\": \"lanes\", \"threads\": {threads}, \"tol\": {tol:e}, \
                 \"seconds\": {seconds:e}, \"equals_compiled\": {}, \
                 \"compile_seconds\": {compile:e}, \"native\": {native}",
                &finals == compiled
            );
            if threads == 1 {
                println!("{head}, \"final\": {}}}", json(&finals));
                first = finals;
            } else {
                println!("{head}, \"same_bits\": {}}}", finals == first);
            }
        }
    }
    Ok(())
}
