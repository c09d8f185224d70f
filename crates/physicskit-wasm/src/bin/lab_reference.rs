//! The native run that the WebAssembly build is compared with: every catalogue system from
//! its defaults, with every method it takes, stepped `FRAMES` frames of `STEPS` steps of
//! `DT` through the same [`Lab`] the page uses. Prints one JSON object per run and line:
//! `{"system", "method", "t", "energy_error", "state"}`, the state as the 16 hex digits of
//! each f64's bits, so a comparison is bit for bit (`web/test/node_compare.mjs` runs the same
//! in the .wasm under Node and compares).

use physicskit::classical::catalog::SYSTEMS;
use physicskit_wasm::Lab;

/// The run: 4 frames of 25 steps of 1 ms (0.1 s: long enough that every force term has
/// acted, short enough for the slowest system's implicit solve under Node's debug-free
/// build to take well under a second).
const FRAMES: u32 = 4;
const STEPS: u32 = 25;
const DT: f64 = 1e-3;

fn main() {
    for entry in SYSTEMS {
        for method in entry.methods() {
            let line = run(entry.name, method.name());
            println!("{line}");
        }
    }
}

fn run(system: &str, method: &str) -> String {
    let outcome = Lab::new(system, "{}").and_then(|mut lab| {
        lab.set_method(method)?;
        for _ in 0..FRAMES {
            lab.step(STEPS, DT)?;
        }
        Ok(lab)
    });
    match outcome {
        Ok(lab) => {
            let state: Vec<String> = lab
                .state()
                .iter()
                .map(|x| format!("\"{:016x}\"", x.to_bits()))
                .collect();
            format!(
                "{{\"system\":\"{system}\",\"method\":\"{method}\",\"t\":\"{:016x}\",\
                 \"energy_error\":\"{:016x}\",\"state\":[{}]}}",
                lab.time().to_bits(),
                lab.energy_error().to_bits(),
                state.join(",")
            )
        }
        Err(e) => format!(
            "{{\"system\":\"{system}\",\"method\":\"{method}\",\"error\":{}}}",
            serde_json::Value::String(e)
        ),
    }
}
