//! Pure-Rust reference runs for the Python bit-identity test (`tests/test_bit_identity.py`).
//!
//! Runs a few systems directly through the `physicskit` crate (no PyO3 involved) and writes,
//! for each, the raw little-endian f64 bytes of `t`, `y` (row-major) and `energy`, one file per
//! case, into the directory given as the only argument. The Python test runs the same cases
//! through `physicskit.classical` and requires byte-for-byte equal arrays: this proves the
//! binding layer changes nothing (no parameter re-derivation, no copy through another dtype,
//! same integrator path).
//!
//! `cargo run --release -p physicskit-python --example reference_run -- <out_dir>`

use std::fs;
use std::io::Write;
use std::path::Path;

use physicskit::classical::systems::{
    DoublePendulum, DoublePendulumParams, EulerTop, EulerTopParams, FPUTChain, KeplerPerturbations,
    KeplerSystem,
};
use physicskit::classical::{
    HamiltonianSystem, LagrangianSystem, Method, OdeSystem, SimulationResult,
};

fn write(dir: &Path, name: &str, r: &SimulationResult) -> std::io::Result<()> {
    let mut f = fs::File::create(dir.join(format!("{name}.f64")))?;
    let energy = r.energy.as_ref().map(|e| e.to_vec()).unwrap_or_default();
    for v in r.t.iter().chain(r.y.iter()).chain(energy.iter()) {
        f.write_all(&v.to_le_bytes())?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .ok_or("usage: reference_run <out_dir>")?;
    let dir = Path::new(&dir);
    fs::create_dir_all(dir)?;

    let mut kepler =
        KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())?;
    write(
        dir,
        "kepler_yoshida4",
        &kepler.integrate((0.0, 20.0), 1e-3, Method::Yoshida4)?,
    )?;

    let mut dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], DoublePendulumParams::default())?;
    write(
        dir,
        "double_pendulum_implicit_midpoint",
        &dp.integrate((0.0, 3.0), 3e-4, Method::ImplicitMidpoint)?,
    )?;

    let mut top = EulerTop::new(&[0.01, 1.0, 0.01], EulerTopParams::default(), None)?;
    write(
        dir,
        "euler_top_rk4",
        &top.integrate((0.0, 10.0), 1e-3, Method::Rk4)?,
    )?;

    let mut fput = FPUTChain::new(16, 1.0, 1.0, 1.0, 1, 1.0)?;
    write(
        dir,
        "fput_verlet",
        &fput.integrate((0.0, 50.0), 5e-3, Method::Verlet)?,
    )?;
    Ok(())
}
