//! Hénon–Heiles: hand-derived force and long-time energy conservation.

use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Method};

use crate::checks::check_force_against_potential;

#[test]
fn force_is_minus_gradient() {
    let sys = HenonHeilesSystem::new(&[0.1, 0.3], &[0.3, 0.0]).unwrap();
    check_force_against_potential(&sys, &[0.1, 0.3]);
    check_force_against_potential(&sys, &[-0.4, 0.25]);
}

#[test]
fn yoshida4_conserves_energy_over_1e5_steps() {
    let mut sys = HenonHeilesSystem::new(&[0.0, 0.3], &[0.3, 0.0]).unwrap();
    // E = 0.045 + 0.045 - 0.009 = 0.081, on a regular torus well below the 1/6 saddle.
    let res = sys
        .integrate_with(
            (0.0, 500.0),
            5e-3,
            Method::Yoshida4,
            IntegrateOptions::stride(10),
        )
        .unwrap();
    let e0 = res.energy.as_ref().unwrap()[0];
    // H(0, 0.3, 0.3, 0) = 0.045 + 0.045 - 0.009 = 0.081, to the rounding of three terms.
    assert!((e0 - 0.081).abs() < 1e-15);
    let drift = res.max_relative_energy_error().unwrap();
    println!("henon-heiles: relative energy drift {drift:e}");
    // The bound: Yoshida4 error O(dt^4) ~ 6e-10 * (frequency ~1)^4, bounded in time.
    assert!(drift < 1e-9);
}
