//! Long-time energy behaviour: bounded for the symplectic methods, drifting for rk4.

use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, Method};

const STEPS: usize = 1_000_000;
/// A large step (about 1/60 of the small-oscillation period at amplitude 2.5 rad) so that
/// rk4's secular drift is visible within 10^6 steps.
const DT: f64 = 0.1;

/// `(max |dE| over the first tenth, max |dE| over the last tenth)` of `STEPS` steps of `dt`.
fn first_and_last_tenth(method: Method, dt: f64) -> (f64, f64) {
    let mut pendulum = Pendulum::new(2.5, 0.0, 1.0).unwrap();
    let result = pendulum
        .integrate((0.0, STEPS as f64 * dt), dt, method)
        .unwrap();
    let e = result.energy.unwrap();
    let e0 = e[0];
    let tenth = e.len() / 10;
    let max_err = |s: &[f64]| s.iter().fold(0.0_f64, |m, v| m.max((v - e0).abs()));
    let all = e.as_slice().unwrap();
    (max_err(&all[..tenth]), max_err(&all[all.len() - tenth..]))
}

/// A step for `method` at which its energy error on the pendulum stands far above the
/// rounding walk of 10^6 steps (~1e-13): `DT` up to order 4; the higher orders' errors at `DT`
/// (1e-9 to 1e-14, measured) would be at or near it, so they step 3x (order 6) or 5x (orders
/// 8, 10) longer, still well inside every substep's stability interval.
fn bounded_energy_step(method: Method) -> f64 {
    match method.order() {
        0..=4 => DT,
        5..=6 => 3.0 * DT,
        _ => 5.0 * DT,
    }
}

#[test]
fn symplectic_methods_keep_the_energy_error_bounded() {
    for method in Method::ALL.into_iter().filter(|m| m.is_symplectic()) {
        let (first, last) = first_and_last_tenth(method, bounded_energy_step(method));
        println!("{method}: max |dE| first tenth {first:e}, last tenth {last:e}");
        // A bounded, oscillating error reaches the same envelope in every tenth of the run;
        // a secular drift would make the last tenth ~10x the first. 1.5 leaves room for the
        // envelope being sampled differently in the two windows.
        assert!(
            last <= 1.5 * first,
            "{method}: energy error grew from {first:e} to {last:e}"
        );
    }
}

#[test]
fn rk4_visibly_drifts_at_the_same_step() {
    let (first, last) = first_and_last_tenth(Method::Rk4, DT);
    // rk4 is dissipative on the pendulum: its error grows linearly, so the last tenth is about
    // ten times the first. Requiring 5x separates it clearly from the bounded methods above.
    assert!(
        last >= 5.0 * first,
        "rk4 error went from {first:e} to {last:e}: no visible drift"
    );
}
