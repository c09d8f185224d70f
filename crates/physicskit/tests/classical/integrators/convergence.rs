//! Measured convergence orders of every method in the table against its declared order: on an
//! exact solution (harmonic oscillator) and against a reference run at a 64x smaller step
//! (nonlinear pendulum). The steps follow each method's declared order, so a method added to
//! the registry is measured here without editing this file. Adaptive methods choose their own
//! steps (`dt` is their output spacing): their formula's order is measured at fixed steps in
//! `dop853.rs`.

use crate::checks::loglog_slope;
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::{HamiltonianSystem, Method};

/// The methods whose error is set by `dt`: all but the adaptive ones.
fn fixed_step_methods() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|m| !m.is_adaptive())
}

/// Acceptance band for a measured slope around the theoretical order: +-0.15 up to order 4
/// (which those methods meet with room), +-0.2 above (the
/// fits of orders 6 to 10 span at most a factor 4 in step between ~1e-7 and the floor, where
/// the next term of the error expansion still moves the slope by ~0.1).
fn slope_tolerance(order: u32) -> f64 {
    if order <= 4 {
        0.15
    } else {
        0.2
    }
}

/// Steps at which errors are measured up to order 4: halving four times keeps every error
/// above 1e-12 (well clear of the ~1e-15 rounding floor) for the fourth-order methods, yet
/// small enough for the asymptotic regime (h w <= 0.2).
const STEPS: [f64; 5] = [0.2, 0.1, 0.05, 0.025, 0.0125];
/// The amplitude-2 pendulum leaves the pre-asymptotic regime of rk4 only below h ~ 0.05
/// (measured error ratios per halving: 8.8, 10, 13.4, 14.8 from h = 0.2), so it is measured
/// one octave lower: the finest errors (~1e-12 for the fourth-order methods) stay well above
/// the ~1e-14 rounding floor of a 10^4-step run.
const PENDULUM_STEPS: [f64; 4] = [0.05, 0.025, 0.0125, 0.00625];
const T_END: f64 = 10.0;

/// Errors above this are 100 times the rounding floor of the runs below (~1e-14 after 10^2 to
/// 10^4 steps of an order-one state), so rounding changes a fitted slope by under 0.01.
const ERROR_FLOOR: f64 = 1e-12;

/// The steps and errors a method's order is fitted on. Up to order 4, the fixed grid `base`
/// (chosen and checked above). Higher orders would reach the rounding floor on that grid, and
/// their error constants vary by orders of magnitude between methods of one order (a triple
/// jump's large negative weights against an optimized composition's), so no fixed grid suits
/// them all: the step is reduced from `T_END / 8` until the error falls below
/// [`ERROR_FLOOR`], and the fit uses the three finest steps above it, where the error is
/// smallest but still clear of rounding (the asymptotic regime, when any step is). Orders 8
/// and 10 fall from ~1e-7 to the floor within two or three halvings, so their steps shrink by
/// about sqrt(2) instead (`T_END / n` for whole `n`), never below `T_END / 2^10`: the three
/// points then lie between ~1e-9 and 1e-12, h from ~0.31 to ~0.16 for kahan_li8 on the
/// pendulum, where halving from 0.625 to 0.156 measured a pre-asymptotic 8.3.
fn errors(base: &[f64], order: u32, error_at: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    if order <= 4 {
        return (base.to_vec(), base.iter().map(|&h| error_at(h)).collect());
    }
    let per_halving = if order >= 8 { 2 } else { 1 };
    let mut points: Vec<(f64, f64)> = Vec::new();
    for k in 3 * per_halving..=10 * per_halving {
        // A whole number of steps in T_END (the driver refuses others): 8, 11, 16, 23, ...
        let n = 2f64.powf(f64::from(k) / f64::from(per_halving)).round();
        let h = T_END / n;
        let e = error_at(h);
        if e < ERROR_FLOOR {
            break;
        }
        points.push((h, e));
    }
    let finest = &points[points.len().saturating_sub(3)..];
    finest.iter().copied().unzip()
}

fn final_state<S: HamiltonianSystem>(mut system: S, dt: f64, method: Method) -> Vec<f64> {
    let result = system.integrate((0.0, T_END), dt, method).unwrap();
    result.final_state().to_vec()
}

fn assert_order(method: Method, steps: &[f64], errors: &[f64]) {
    let slope = loglog_slope(steps, errors);
    let expected = f64::from(method.order());
    assert!(
        (slope - expected).abs() <= slope_tolerance(method.order()),
        "{method}: measured order {slope:.3}, expected {expected} (steps {steps:?}, errors \
         {errors:?})"
    );
}

#[test]
fn orders_on_the_harmonic_oscillator_match_the_table() {
    let (q0, p0) = (1.0, 0.5);
    for method in fixed_step_methods() {
        let oscillator = HarmonicOscillator::new(q0, p0, 1.0, 1.0).unwrap();
        let (q_exact, p_exact) = oscillator.exact(q0, p0, T_END);
        let (steps, errors) = errors(&STEPS, method.order(), |dt| {
            let y = final_state(oscillator.clone(), dt, method);
            (y[0] - q_exact).hypot(y[1] - p_exact)
        });
        println!(
            "{method}: steps {steps:?}, errors {errors:?}, slope {:.3}",
            loglog_slope(&steps, &errors)
        );
        assert_order(method, &steps, &errors);
    }
}

#[test]
fn orders_on_the_nonlinear_pendulum_match_the_table() {
    // Amplitude 2 rad: far from the linear regime, so the nonlinear terms set the error.
    let pendulum = Pendulum::new(2.0, 0.0, 1.0).unwrap();
    // Order 10 is not measurable here in double precision: sofroniou_spaletta10's error falls
    // from 1.4e-6 at h = 0.91 to 2.9e-11 at 0.43 with local slopes of 11.5 and 17.9, then to
    // 6.9e-13 at 0.31, where its own reference's rounding floor (~2.5e-13 at 8192 steps of 35
    // stages) is reached before the asymptotic regime. Its order is measured on the
    // oscillator above (9.97), on the section crossing times (`analysis/section.rs`), and its
    // coefficients satisfy the order conditions (`integrators/coefficients.rs`).
    for method in fixed_step_methods().filter(|m| m.order() < 10) {
        // The same method at a step far below any it is compared with, so its own error
        // cannot bias the slope: up to order 4, 64 times finer than the finest fixed step
        // (64^4 = 1.7e7 times more accurate); above, T_END / 2^13, 8 times finer than any step
        // the search of `errors` can reach (8^6 = 2.6e5 times more accurate). Not finer: the
        // rounding of a run grows with its steps, and a reference of 5e5 steps (T_END / 2^19)
        // measured a floor of ~7e-13 for kahan_li8, which hid sofroniou_spaletta10's asymptotic
        // regime; at 8192 steps the floor is below 1e-13.
        let reference_step = if method.order() <= 4 {
            PENDULUM_STEPS[PENDULUM_STEPS.len() - 1] / 64.0
        } else {
            T_END / 2f64.powi(13)
        };
        let reference = final_state(pendulum.clone(), reference_step, method);
        let (steps, errors) = errors(&PENDULUM_STEPS, method.order(), |dt| {
            let y = final_state(pendulum.clone(), dt, method);
            (y[0] - reference[0]).hypot(y[1] - reference[1])
        });
        println!(
            "{method}: steps {steps:?}, errors {errors:?}, slope {:.3}",
            loglog_slope(&steps, &errors)
        );
        assert_order(method, &steps, &errors);
    }
}
