//! The native side of the lab benchmark (benchmarks/README.md, "The lab in the browser"):
//! steps per second through the same [`Lab`] frames the page runs (16 steps of 1 ms a frame,
//! and 10 000, each system's default method), for the systems `web/test/bench.mjs` times in Chromium.
//! Not a test: it prints timings.

use std::time::Instant;

use physicskit_wasm::Lab;

/// The systems timed, from their catalogue defaults.
const SYSTEMS: [&str; 3] = ["double-pendulum", "henon-heiles", "pendulum-swarm"];
/// The page's frame (16 steps: 60 fps at dt = 1 ms is real time) and a long one that
/// amortizes the per-call cost of `integrate` (validation, work buffers, and natively the
/// memory check's read of /proc/meminfo).
const FRAME_SIZES: [u32; 2] = [16, 10_000];
const DT: f64 = 1e-3;

fn main() {
    for name in SYSTEMS {
        for frame in FRAME_SIZES {
            match time(name, frame) {
                Ok(rate) => println!(
                    "{{\"system\":\"{name}\",\"steps_per_frame\":{frame},\"native_steps_per_second\":{rate:.0}}}"
                ),
                Err(e) => println!("{{\"system\":\"{name}\",\"error\":{e:?}}}"),
            }
        }
    }
}

/// Steps per second over at least one second of frames, after a warm-up frame.
fn time(name: &str, frame: u32) -> Result<f64, String> {
    let mut lab = Lab::new(name, "{}")?;
    lab.step(frame, DT)?;
    let start = Instant::now();
    let mut steps = 0u64;
    while start.elapsed().as_secs_f64() < 1.0 {
        lab.step(frame, DT)?;
        steps += u64::from(frame);
    }
    Ok(steps as f64 / start.elapsed().as_secs_f64())
}
