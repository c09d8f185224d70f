//! Integrates a large-amplitude pendulum with each method and prints the energy error.
//!
//! `cargo run --release -p physicskit --example pendulum_drift`

use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, Method};

fn main() -> Result<(), physicskit::classical::Error> {
    let (t1, dt) = (1000.0, 0.05);
    println!("pendulum H = p^2/2 - cos q from q = 2.5 rad, t = 0..{t1}, dt = {dt}");
    println!(
        "{:<18} {:>16} {:>16}",
        "method", "max |dE/E0|", "final dE/E0"
    );
    for method in Method::ALL {
        let mut pendulum = Pendulum::new(2.5, 0.0, 1.0)?;
        let result = pendulum.integrate((0.0, t1), dt, method)?;
        let e = result.energy.as_ref().expect("energy is stored by default");
        let e0 = e[0];
        println!(
            "{:<18} {:>16.3e} {:>16.3e}",
            method.name(),
            result.max_relative_energy_error().unwrap_or(f64::NAN),
            (e[e.len() - 1] - e0) / e0.abs()
        );
    }
    Ok(())
}
