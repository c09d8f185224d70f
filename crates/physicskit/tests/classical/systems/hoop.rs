//! The bead on a rotating hoop's separatrix energies against its equilibria classified
//! numerically: an equilibrium is where the system's acceleration vanishes, a saddle where the
//! system's energy curves down along `theta` (central second difference).

use std::f64::consts::PI;

use physicskit::classical::systems::{BeadOnRotatingHoop, HoopParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem};

/// Energies of the saddles among the candidate equilibria `theta = 0, pi` and
/// `cos theta = g / (R omega^2)`, found with the system's own acceleration and energy.
fn saddle_energies(bead: &BeadOnRotatingHoop) -> Vec<f64> {
    let HoopParams { r, omega, g } = *bead.params();
    let mut candidates = vec![0.0, PI];
    let c = g / (r * omega * omega);
    if c.abs() < 1.0 {
        candidates.push(c.acos());
    }
    let energy = |theta: f64| bead.energy(&[theta, 0.0]);
    let h = 1e-4;
    let mut levels = Vec::new();
    for theta in candidates {
        let mut a = [0.0];
        bead.acceleration(&[theta], &[0.0], 0.0, &mut a).unwrap();
        // An equilibrium up to the rounding of sin(pi) ~ 1e-16 times forces of order 30.
        assert!(a[0].abs() < 1e-13, "theta = {theta}: {}", a[0]);
        // Second difference: V'' h^2 with V'' of order 10 is ~1e-7, far above the ~1e-15
        // rounding of the energies, so the sign is reliable away from the bifurcation.
        let curvature = energy(theta + h) + energy(theta - h) - 2.0 * energy(theta);
        if curvature < -1e-12 {
            levels.push(energy(theta));
        }
    }
    levels.sort_by(f64::total_cmp);
    levels.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    levels
}

#[test]
fn separatrix_energies_are_the_saddle_levels() {
    let cases = [
        (1.0, 2.0, 9.81),  // below critical: only the top
        (1.0, 5.0, 9.81),  // above: the bottom too
        (0.5, 3.0, -9.81), // gravity up, bottom a saddle, top stable
        (2.0, 1.5, 0.0),   // no gravity: top and bottom both at E = 0
    ];
    for (r, omega, g) in cases {
        let bead = BeadOnRotatingHoop::new(0.3, 0.0, HoopParams { r, omega, g }).unwrap();
        let want = saddle_energies(&bead);
        let got = bead.separatrix_energies();
        assert_eq!(
            got.len(),
            want.len(),
            "{r} {omega} {g}: {got:?} vs {want:?}"
        );
        for (a, b) in got.iter().zip(&want) {
            // The energy at sin(pi) ~ 1e-16 differs from 2 g R by that rounding times R^2
            // omega^2: 1e-13 absolute.
            assert!(
                (a - b).abs() < 1e-13,
                "{r} {omega} {g}: {got:?} vs {want:?}"
            );
        }
    }
}
