//! Measured convergence orders against an exact solution (harmonic oscillator) and against a
//! reference run at a 64x smaller step (nonlinear pendulum).

use crate::checks::loglog_slope;
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::{HamiltonianSystem, Method};

/// The acceptance band for a measured slope: +-0.15 around the theoretical order.
const SLOPE_TOLERANCE: f64 = 0.15;

/// Steps at which errors are measured: halving four times keeps every error above 1e-12 (well
/// clear of the ~1e-15 rounding floor) for the fourth-order methods, yet small enough for the
/// asymptotic regime (h w <= 0.2).
const STEPS: [f64; 5] = [0.2, 0.1, 0.05, 0.025, 0.0125];
/// The amplitude-2 pendulum leaves the pre-asymptotic regime of rk4 only below h ~ 0.05
/// (measured error ratios per halving: 8.8, 10, 13.4, 14.8 from h = 0.2), so it is measured
/// one octave lower: the finest errors (~1e-12 for the fourth-order methods) stay well above
/// the ~1e-14 rounding floor of a 10^4-step run.
const PENDULUM_STEPS: [f64; 4] = [0.05, 0.025, 0.0125, 0.00625];
const T_END: f64 = 10.0;

fn final_state<S: HamiltonianSystem>(mut system: S, dt: f64, method: Method) -> Vec<f64> {
    let result = system.integrate((0.0, T_END), dt, method).unwrap();
    result.final_state().to_vec()
}

fn assert_order(method: Method, steps: &[f64], errors: &[f64]) {
    let slope = loglog_slope(steps, errors);
    let expected = f64::from(method.order());
    assert!(
        (slope - expected).abs() <= SLOPE_TOLERANCE,
        "{method}: measured order {slope:.3}, expected {expected} (errors {errors:?})"
    );
}

#[test]
fn orders_on_the_harmonic_oscillator_match_theory() {
    let (q0, p0) = (1.0, 0.5);
    for method in Method::ALL {
        let oscillator = HarmonicOscillator::new(q0, p0, 1.0, 1.0).unwrap();
        let (q_exact, p_exact) = oscillator.exact(q0, p0, T_END);
        let errors: Vec<f64> = STEPS
            .iter()
            .map(|&dt| {
                let y = final_state(oscillator.clone(), dt, method);
                (y[0] - q_exact).hypot(y[1] - p_exact)
            })
            .collect();
        assert_order(method, &STEPS, &errors);
    }
}

#[test]
fn orders_on_the_nonlinear_pendulum_match_theory() {
    // Amplitude 2 rad: far from the linear regime, so the nonlinear terms set the error.
    let pendulum = Pendulum::new(2.0, 0.0, 1.0).unwrap();
    for method in Method::ALL {
        let finest = PENDULUM_STEPS[PENDULUM_STEPS.len() - 1];
        let reference = final_state(pendulum.clone(), finest / 64.0, method);
        let errors: Vec<f64> = PENDULUM_STEPS
            .iter()
            .map(|&dt| {
                let y = final_state(pendulum.clone(), dt, method);
                (y[0] - reference[0]).hypot(y[1] - reference[1])
            })
            .collect();
        // The reference is 64^order times more accurate than the finest run, so it cannot
        // bias the slope.
        assert_order(method, &PENDULUM_STEPS, &errors);
    }
}
