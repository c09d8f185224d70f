//! Prints ns/step and energy drift of every workload through the Rust API.
//!
//! `cargo run --release -p physicskit-benchmarks --bin workloads [steps] [case] [lib|plain] [repeats]`
//!
//! `workloads ensemble` times a 10^6-pendulum swarm over 1000 yoshida4 steps on 1 thread and on
//! all cores, and checks the two results are bit-identical.
//!
//! With a case and `lib` or `plain`, runs only that, once (for instruction counting under
//! `valgrind --tool=callgrind`, which is repeatable on a busy machine), or `[repeats]` times,
//! printing the best ns/step (for comparing two builds on one case).

use std::time::Instant;

fn main() {
    let steps: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    println!(
        "{:<22} {:<18} {:>9} {:>10} {:>12} {:>10} {:>8}",
        "case", "method", "dt", "ns/step", "max|dE/E0|", "plain ns", "ratio"
    );
    if std::env::args().nth(1).as_deref() == Some("ensemble") {
        ensemble();
        return;
    }
    let only = std::env::args().nth(2);
    let side = std::env::args().nth(3);
    if let (Some(name), Some(side)) = (&only, &side) {
        let Some(w) = physicskit_benchmarks::workloads::all()
            .into_iter()
            .find(|w| w.name == *name)
        else {
            eprintln!("unknown case {name}");
            std::process::exit(2);
        };
        let repeats: usize = std::env::args()
            .nth(4)
            .and_then(|s| s.parse().ok())
            .unwrap_or(1);
        let ns = if side == "plain" {
            let run = physicskit_benchmarks::plain::case(name).expect("a plain version");
            let (q0, p0) = w.start().expect("builds").expect("a separable workload");
            best_ns(repeats, steps, || {
                std::hint::black_box(run(&q0, &p0, steps, w.dt));
            })
        } else {
            best_ns(repeats, steps, || {
                std::hint::black_box(w.run(steps).expect("runs"));
            })
        };
        if repeats > 1 {
            println!("{name:<22} {side:<6} {ns:>10.1} ns/step, best of {repeats}");
        }
        return;
    }
    for w in physicskit_benchmarks::workloads::all() {
        // One untimed run (the energy drift; errors), then the best of three (the machine is
        // shared); the plain loop likewise.
        let drift = match w.run(steps) {
            Ok(r) => r.max_relative_energy_error().unwrap_or(f64::NAN),
            Err(e) => {
                println!("{:<22} error: {e}", w.name);
                continue;
            }
        };
        let ns = best_ns(3, steps, || {
            std::hint::black_box(w.run(steps).expect("ran above"));
        });
        let plain = physicskit_benchmarks::plain::case(&w.name)
            .filter(|_| w.method == physicskit::classical::Method::Yoshida4)
            .map(|run| {
                let (q0, p0) = w.start().expect("ran above").expect("a separable workload");
                std::hint::black_box(run(&q0, &p0, steps, w.dt));
                best_ns(3, steps, || {
                    std::hint::black_box(run(&q0, &p0, steps, w.dt));
                })
            });
        match plain {
            Some(p) => println!(
                "{:<22} {:<18} {:>9.1e} {:>10.1} {:>12.3e} {:>10.1} {:>8.2}",
                w.name,
                w.method.name(),
                w.dt,
                ns,
                drift,
                p,
                ns / p
            ),
            None => println!(
                "{:<22} {:<18} {:>9.1e} {:>10.1} {:>12.3e}",
                w.name,
                w.method.name(),
                w.dt,
                ns,
                drift
            ),
        }
    }
}

/// The best of `repeats` timings of `run`, in ns per step of a `steps`-step run.
fn best_ns(repeats: usize, steps: usize, mut run: impl FnMut()) -> f64 {
    (0..repeats.max(1))
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64() * 1e9 / steps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn ensemble() {
    use physicskit::classical::systems::PendulumSwarm;
    use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Method};
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        pool.install(|| {
            let mut swarm = PendulumSwarm::from_box(1.0, 0.0, 0.5, 0.5, 1_000_000, 1.0, 0)
                .expect("valid swarm");
            let start = Instant::now();
            let r = swarm
                .integrate_with(
                    (0.0, 1.0),
                    1e-3,
                    Method::Yoshida4,
                    IntegrateOptions::final_only(),
                )
                .expect("runs");
            (start.elapsed().as_secs_f64(), r)
        })
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (t1, r1) = (0..2)
        .map(|_| run(1))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("two runs");
    let (tn, rn) = (0..2)
        .map(|_| run(cores))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("two runs");
    println!(
        "swarm n = 1e6, 1000 yoshida4 steps, final state only: 1 thread {t1:.2} s, {cores} threads {tn:.2} s; \
         speed-up {:.2}, parallel efficiency {:.0}%; bit-identical: {}",
        t1 / tn,
        100.0 * t1 / (tn * cores as f64),
        r1 == rn
    );
}
