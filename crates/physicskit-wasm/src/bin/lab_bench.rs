//! The native side of the lab benchmark (benchmarks/README.md, "The lab in the browser"):
//! steps per second through the same [`Lab`] frames the page runs (16 steps of 1 ms a frame,
//! each system's default method), for the systems `web/test/bench.mjs` times in Chromium.
//! Not a test: it prints timings.

use std::time::Instant;

use physicskit_wasm::Lab;

/// The systems timed, from their catalogue defaults.
const SYSTEMS: [&str; 3] = ["double-pendulum", "henon-heiles", "pendulum-swarm"];
const STEPS_PER_FRAME: u32 = 16;
const DT: f64 = 1e-3;

fn main() {
    for name in SYSTEMS {
        match time(name) {
            Ok(rate) => println!("{{\"system\":\"{name}\",\"steps_per_second\":{rate:.0}}}"),
            Err(e) => println!("{{\"system\":\"{name}\",\"error\":{:?}}}", e),
        }
    }
}

/// Steps per second over at least one second of frames, after a warm-up frame.
fn time(name: &str) -> Result<f64, String> {
    let mut lab = Lab::new(name, "{}")?;
    lab.step(STEPS_PER_FRAME, DT)?;
    let start = Instant::now();
    let mut steps = 0u64;
    while start.elapsed().as_secs_f64() < 1.0 {
        lab.step(STEPS_PER_FRAME, DT)?;
        steps += u64::from(STEPS_PER_FRAME);
    }
    Ok(steps as f64 / start.elapsed().as_secs_f64())
}
