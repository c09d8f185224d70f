//! The native run that the WebAssembly build is compared with: every catalogue system from
//! its defaults, with every method it takes, stepped `FRAMES` frames of `STEPS` steps of
//! `DT` through the same [`Lab`] the page uses (an adaptive method at the lab's default
//! tolerance, and `taylor` and `dop853` also at the ends of the page's tolerance menu on the
//! systems of [`TOLERANCE_CASES`]). Prints one JSON object per run and line:
//! `{"system", "method", "tol"?, "t", "energy_error", "state"}`, the state as the 16 hex
//! digits of each f64's bits, so a comparison is bit for bit (`web/test/node_compare.mjs`
//! runs the same in the .wasm under Node and compares).

use physicskit::classical::catalog::SYSTEMS;
use physicskit_wasm::Lab;

/// The run: 4 frames of 25 steps of 1 ms (0.1 s: long enough that every force term has
/// acted, short enough for the slowest system's implicit solve under Node's debug-free
/// build to take well under a second).
const FRAMES: u32 = 4;
const STEPS: u32 = 25;
const DT: f64 = 1e-3;

/// Adaptive runs at a tolerance of their own: the ends of the page's menu (its order and
/// steps depend on it), on a Hamiltonian system with a traced Taylor form and a Lagrangian one.
const TOLERANCE_CASES: [(&str, &str, f64); 6] = [
    ("kepler", "taylor", 1e-6),
    ("kepler", "taylor", 1e-14),
    ("double-pendulum", "taylor", 1e-6),
    ("double-pendulum", "taylor", 1e-14),
    ("double-pendulum", "dop853", 1e-6),
    ("double-pendulum", "dop853", 1e-14),
];

fn main() {
    for entry in SYSTEMS {
        for method in entry.methods() {
            let line = run(entry.name, method.name(), None);
            println!("{line}");
        }
    }
    for (system, method, tol) in TOLERANCE_CASES {
        println!("{}", run(system, method, Some(tol)));
    }
}

fn run(system: &str, method: &str, tol: Option<f64>) -> String {
    let outcome = Lab::new(system, "{}").and_then(|mut lab| {
        if let Some(tol) = tol {
            lab.set_tolerance(tol)?;
        }
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
                "{{\"system\":\"{system}\",\"method\":\"{method}\",{}\"t\":\"{:016x}\",\
                 \"energy_error\":\"{:016x}\",\"state\":[{}]}}",
                tol_field(tol),
                lab.time().to_bits(),
                lab.energy_error().to_bits(),
                state.join(",")
            )
        }
        Err(e) => format!(
            "{{\"system\":\"{system}\",\"method\":\"{method}\",{}\"error\":{}}}",
            tol_field(tol),
            serde_json::Value::String(e)
        ),
    }
}

/// `"tol":…,` for a run at a tolerance of its own (shortest round-trip decimal), else nothing.
fn tol_field(tol: Option<f64>) -> String {
    tol.map_or(String::new(), |t| format!("\"tol\":{t:e},"))
}
