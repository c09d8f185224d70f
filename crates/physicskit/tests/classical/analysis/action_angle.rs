//! Elliptic integrals and the pendulum's action and period.

use std::f64::consts::PI;

use physicskit::classical::analysis::{ellipe, ellipk, ellipke, pendulum_action_angle};
use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, Method};

use crate::checks::upward_zero_crossings;

/// Trapezoid rule on `[0, pi/2]` of an even, pi-periodic integrand: spectrally accurate, an
/// independent quadrature of the defining integrals.
fn quadrature(f: impl Fn(f64) -> f64) -> f64 {
    let n = 4000;
    let h = PI / n as f64;
    // Integral over [0, pi] of a pi-periodic function = h * sum over one period; halve it.
    0.5 * h * (0..n).map(|i| f(i as f64 * h)).sum::<f64>()
}

#[test]
fn elliptic_integrals_match_tabulated_values() {
    // Abramowitz & Stegun Table 17.1 / DLMF 19.6: K(0) = E(0) = pi/2; K(1/2), E(1/2) to 16 digits
    // (Gauss: K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi))).
    assert!((ellipk(0.0).unwrap() - PI / 2.0).abs() < 1e-15);
    assert!((ellipe(0.0).unwrap() - PI / 2.0).abs() < 1e-15);
    assert!((ellipk(0.5).unwrap() - 1.854_074_677_301_371_9).abs() < 1e-15);
    assert!((ellipe(0.5).unwrap() - 1.350_643_881_047_675_5).abs() < 1e-15);
    // Legendre's relation at m = 1/2: 2 K E - K^2 = pi/2.
    let (k, e) = ellipke(0.5).unwrap();
    assert!((2.0 * k * e - k * k - PI / 2.0).abs() < 1e-14);
}

#[test]
fn elliptic_integrals_match_quadrature() {
    for m in [0.01, 0.2, 0.5, 0.8, 0.95, 0.99] {
        let k_quad = quadrature(|t| 1.0 / (1.0 - m * t.sin().powi(2)).sqrt());
        let e_quad = quadrature(|t| (1.0 - m * t.sin().powi(2)).sqrt());
        let (k, e) = ellipke(m).unwrap();
        // The periodic trapezoid rule converges like exp(-n * acosh(...)); 4000 points reach
        // rounding even at m = 0.99, so agreement is to ~1e-14.
        assert!((k - k_quad).abs() < 1e-13 * k, "K({m}): {k} vs {k_quad}");
        assert!((e - e_quad).abs() < 1e-13 * e, "E({m}): {e} vs {e_quad}");
    }
}

/// `closed-integral p dq` by the substitution `q = q_max sin(phi)`, which turns it into
/// `int_0^{2pi} q_max cos^2(phi) g(phi) dphi` with `g` smooth and periodic: the trapezoid rule
/// converges spectrally. `cos q - cos q_max` is evaluated as a product of sines to avoid
/// cancellation near the turning points.
fn action_by_quadrature(energy: f64, g: f64) -> f64 {
    let q_max = (-energy / g).acos();
    let n = 4000;
    let h = 2.0 * PI / n as f64;
    let loop_integral: f64 = (0..n)
        .map(|i| {
            let phi = i as f64 * h;
            let q = q_max * phi.sin();
            let diff = 2.0 * ((q_max + q) / 2.0).sin() * ((q_max - q) / 2.0).sin();
            let p = phi.cos().signum() * (2.0 * g * diff).sqrt();
            p * q_max * phi.cos()
        })
        .sum::<f64>()
        * h;
    loop_integral / (2.0 * PI)
}

#[test]
fn action_matches_the_closed_orbit_integral() {
    for (energy, g) in [(-0.9, 1.0), (0.0, 1.0), (0.5, 4.0), (0.95, 1.0)] {
        let (j, _) = pendulum_action_angle(energy, g).unwrap();
        let j_num = action_by_quadrature(energy, g);
        println!("action E={energy} g/l={g}: J = {j}, quadrature {j_num}");
        // The bound (quadrature is accurate to ~1e-14).
        assert!((j - j_num).abs() < 1e-8 * j);
    }
}

#[test]
fn period_matches_the_integrated_pendulum() {
    for (energy, g) in [(-0.5, 1.0), (0.0, 1.0), (0.9, 1.0), (0.5, 4.0)] {
        let (_, period) = pendulum_action_angle(energy, g).unwrap();
        // Start at q = 0 with p = sqrt(2 (E + g/l)).
        let p0 = (2.0 * (energy + g)).sqrt();
        let mut pendulum = Pendulum::new(0.0, p0, g).unwrap();
        let res = pendulum
            .integrate(
                (0.0, (10.5 * period / 1e-3).round() * 1e-3),
                1e-3,
                Method::Yoshida4,
            )
            .unwrap();
        let (q, p) = (res.q().unwrap(), res.p().unwrap());
        // q(0) = 0 is not counted (the test is y < 0 before the crossing): first crossing ~T.
        let qs: Vec<f64> = q.column(0).to_vec();
        let ps: Vec<f64> = p.column(0).to_vec();
        let crossings = upward_zero_crossings(res.t.as_slice().unwrap(), &qs, &ps);
        let n = crossings.len();
        assert!(n >= 10);
        let measured = (crossings[n - 1] - crossings[0]) / (n - 1) as f64;
        let rel = (measured - period).abs() / period;
        println!("pendulum E={energy} g/l={g}: T = {period}, measured {measured}, rel {rel:e}");
        // The bound; Yoshida4's phase error at dt = 1e-3 is ~1e-12 per period.
        assert!(rel < 1e-8);
    }
}

#[test]
fn small_oscillation_limit() {
    // Near the bottom: T -> 2 pi/sqrt(g/l) and J -> (E + g/l)/sqrt(g/l) (harmonic oscillator).
    // The anharmonic corrections are relative O(de/(8 g/l)) ~ 5e-8, the cancellation in
    // E(m) - (1-m) K(m) ~ eps/m ~ 1e-9: a 1e-6 relative tolerance tests the limit, not them.
    let g = 2.5_f64;
    let de = 1e-6;
    let (j, t) = pendulum_action_angle(-g + de, g).unwrap();
    assert!((t - 2.0 * PI / g.sqrt()).abs() < 1e-6 * t);
    assert!((j - de / g.sqrt()).abs() < 1e-6 * j);
}
