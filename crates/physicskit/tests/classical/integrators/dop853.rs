//! `dop853`: the measured order of its formula, the analytic Kepler orbit and the falling body
//! with quadratic drag to its tolerance, interpolated samples against steps onto each sample,
//! the error following the tolerance, the output grid of the fixed-step methods, and each
//! failure's error.

use crate::checks::loglog_slope;
use crate::fixtures::Scalar;
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::integrators::{Dop853, FirstOrder};
use physicskit::classical::systems::{
    DoublePendulum, DoublePendulumParams, KeplerPerturbations, KeplerSystem, ProjectileMotion,
};
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method,
    OdeSystem, Phase, Sampling, SimulationResult, Tolerances,
};

fn tolerances(rtol: f64, atol: f64) -> IntegrateOptions<'static> {
    IntegrateOptions {
        tolerances: Some(Tolerances::new(rtol, atol).unwrap()),
        ..IntegrateOptions::default()
    }
}

/// The fit of `error(h)` over the three finest of `h = span / 2^k` whose error is above
/// `1e-12` (100 times the rounding floor of these runs, so rounding moves the slope by < 0.01),
/// stepping the 8th-order formula at fixed steps.
fn measured_order(span: f64, error_at: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>, f64) {
    let mut points = Vec::new();
    for k in 2..12 {
        let h = span / 2f64.powi(k);
        let e = error_at(h);
        if e < 1e-12 {
            break;
        }
        points.push((h, e));
    }
    let finest = &points[points.len().saturating_sub(3)..];
    let (steps, errors): (Vec<f64>, Vec<f64>) = finest.iter().copied().unzip();
    let slope = loglog_slope(&steps, &errors);
    (steps, errors, slope)
}

fn fixed_steps<S: DynamicalSystem>(system: &S, y0: &[f64], span: f64, h: f64) -> Vec<f64> {
    let field = FirstOrder(system);
    let mut stepper = Dop853::new(y0.len(), Tolerances::default(), None);
    let mut y = y0.to_vec();
    let n = (span / h).round() as usize;
    for i in 0..n {
        stepper.step_fixed(&field, i as f64 * h, &mut y, h).unwrap();
    }
    y
}

/// The formula's order (the adaptive runs choose their own steps, so it is measured at fixed
/// steps): within the issue's +-0.2 of 8 on the oscillator (exact solution) and the
/// amplitude-0.5 pendulum (against a run 64 times finer, 64^8 times more accurate). Over a span
/// of 10 both fit h = 1.25, 0.625, 0.3125 (errors 5e-6 .. 7e-11 and 2e-6 .. 3e-11; the next
/// halving reaches 1e-13, within a decade of the ~1e-14 rounding floor). Larger amplitudes are
/// still pre-asymptotic above their floor (measured local slopes 8.5-9.3 at amplitude 1-2,
/// whose floor is 1e-14-2e-13): this method's leading error constant is small.
#[test]
fn the_formula_is_of_order_eight() {
    let span = 10.0;
    let oscillator = HarmonicOscillator::new(1.0, 0.5, 1.0, 1.0).unwrap();
    let (q, p) = oscillator.exact(1.0, 0.5, span);
    let (steps, errors, slope) = measured_order(span, |h| {
        let y = fixed_steps(&oscillator, &[1.0, 0.5], span, h);
        (y[0] - q).hypot(y[1] - p)
    });
    println!("oscillator: steps {steps:?}, errors {errors:?}, slope {slope:.3}");
    assert!((slope - 8.0).abs() <= 0.2, "oscillator: {slope}");

    let pendulum = Pendulum::new(0.5, 0.0, 1.0).unwrap();
    let reference = fixed_steps(&pendulum, &[0.5, 0.0], span, span / 2f64.powi(11) / 64.0);
    let (steps, errors, slope) = measured_order(span, |h| {
        let y = fixed_steps(&pendulum, &[0.5, 0.0], span, h);
        (y[0] - reference[0]).hypot(y[1] - reference[1])
    });
    println!("pendulum: steps {steps:?}, errors {errors:?}, slope {slope:.3}");
    assert!((slope - 8.0).abs() <= 0.2, "pendulum: {slope}");
}

/// The Kepler orbit `a = 1`, `e = 0.5`, `k = mu = 1` (period `2 pi`) from perihelion, by
/// Kepler's equation `E - e sin E = t` solved by Newton's method to rounding.
fn kepler_position(t: f64) -> [f64; 2] {
    let e = 0.5;
    let m = t.rem_euclid(2.0 * std::f64::consts::PI);
    let mut ecc = m + e * m.sin();
    for _ in 0..50 {
        let step = (ecc - e * ecc.sin() - m) / (1.0 - e * ecc.cos());
        ecc -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    [ecc.cos() - e, (1.0 - e * e).sqrt() * ecc.sin()]
}

/// Largest position error of a run of `orbits` Kepler orbits (100 samples per orbit) against
/// the analytic orbit.
fn kepler_error(orbits: f64, options: IntegrateOptions<'_>) -> (f64, SimulationResult) {
    let period = 2.0 * std::f64::consts::PI;
    let mut kepler =
        KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())
            .unwrap();
    let r = kepler
        .integrate_with(
            (0.0, orbits * period),
            period / 100.0,
            Method::Dop853,
            options,
        )
        .unwrap();
    let error =
        r.t.iter()
            .zip(r.y.rows())
            .map(|(&t, y)| {
                let [x, yy] = kepler_position(t);
                (y[0] - x).hypot(y[1] - yy)
            })
            .fold(0.0, f64::max);
    (error, r)
}

/// Over 5 orbits of the e = 0.5 orbit, every sample (interpolated from the dense output) is on
/// the analytic orbit to its tolerance: the control bounds each step's local error by ~rtol,
/// and the global error is their sum over the ~200 steps, amplified by the phase drift that an
/// error in the energy (the period) causes: measured 290 rtol at rtol 1e-10. 1000 rtol holds
/// that with margin and fails for a control or an interpolant off by an order.
#[test]
fn kepler_orbit_matches_the_analytic_solution_to_its_tolerance() {
    for rtol in [1e-10, 1e-12] {
        let (error, r) = kepler_error(5.0, tolerances(rtol, rtol * 1e-2));
        println!(
            "rtol {rtol:e}: max error {error:e}, {} accepted, {} rejected steps",
            r.extra_scalar("accepted_steps").unwrap(),
            r.extra_scalar("rejected_steps").unwrap()
        );
        assert!(error <= 1000.0 * rtol, "rtol {rtol:e}: {error:e}");
    }
}

/// The error follows the tolerance: between rtol 1e-6 and 1e-12 the global error of the Kepler
/// orbit falls as rtol^s with s near 7/8 (each step's local error ~ rtol, and there are
/// ~rtol^(-1/8) steps); the band [0.7, 1.1] holds that and fails for a control that ignored
/// the tolerance (s = 0) or a formula of lower order than its estimate.
#[test]
fn the_error_scales_with_the_tolerance() {
    let tols = [1e-6, 1e-8, 1e-10, 1e-12];
    let errors: Vec<f64> = tols
        .iter()
        .map(|&tol| kepler_error(2.0, tolerances(tol, tol * 1e-2)).0)
        .collect();
    let slope = loglog_slope(&tols, &errors);
    println!("tolerances {tols:?}: errors {errors:?}, slope {slope:.3}");
    assert!((0.7..=1.1).contains(&slope), "{slope}");
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}

/// Interpolated samples agree with a run that steps exactly onto each sample (one call per
/// sample interval, each landing on its end by a step): both are within their global error
/// (~1e-10 at the default tolerances on this pendulum) of the same solution, so they agree to
/// 1e-9; a wrong dense-output coefficient shows at the 1e-4 level.
#[test]
fn interpolated_samples_equal_steps_onto_each_sample() {
    let dt = 0.1;
    let n = 100;
    let make = || Pendulum::new(2.0, 0.0, 1.0).unwrap();
    let interpolated = make()
        .integrate((0.0, n as f64 * dt), dt, Method::Dop853)
        .unwrap();
    let mut stepped = make();
    let mut worst = 0.0_f64;
    for i in 0..n {
        let r = stepped
            .integrate((i as f64 * dt, (i + 1) as f64 * dt), dt, Method::Dop853)
            .unwrap();
        let row = interpolated.y.row(i + 1);
        let last = r.final_state();
        worst = worst.max((row[0] - last[0]).abs().max((row[1] - last[1]).abs()));
    }
    println!("largest difference {worst:e}");
    assert!(worst <= 1e-9, "{worst:e}");
}

/// The samples are the grid every other method stores: the same times, bit for bit, the same
/// count for every sampling, the final time exactly `t1`; and each stored energy is the
/// system's energy of its sample.
#[test]
fn samples_are_the_fixed_step_grid_with_their_energies() {
    let (span, dt) = ((0.0, 3.0), 3e-2);
    for sampling in [Sampling::All, Sampling::Stride(7), Sampling::FinalOnly] {
        let options = || IntegrateOptions {
            sampling,
            ..IntegrateOptions::default()
        };
        let pendulum = || Pendulum::new(1.0, 0.3, 1.0).unwrap();
        let fixed = pendulum()
            .integrate_with(span, dt, Method::Rk4, options())
            .unwrap();
        let mut system = pendulum();
        let adaptive = system
            .integrate_with(span, dt, Method::Dop853, options())
            .unwrap();
        assert_eq!(adaptive.t, fixed.t, "{sampling:?}");
        assert_eq!(*adaptive.t.last().unwrap(), 3.0);
        assert_eq!(system.t(), 3.0);
        let energy = adaptive.energy.as_ref().unwrap();
        for (row, &e) in adaptive.y.rows().into_iter().zip(energy) {
            assert_eq!(e, system.energy(row.as_slice().unwrap()));
        }
    }
}

/// A body falling from rest with quadratic drag `-c |v| v` has `v(t) = -v_T tanh(g t / v_T)`
/// and `y(t) = y0 - (v_T^2 / g) ln cosh(g t / v_T)`, `v_T = sqrt(m g / c)` (the terminal
/// speed). dop853 follows it over 3 s to 3e-8, 3e-10 of the 100 m fallen through: a few rtol
/// (measured 6e-9), as the control is asked for.
#[test]
fn falling_body_with_drag_matches_the_analytic_solution() {
    let (m, g, c, y0): (f64, f64, f64, f64) = (2.0, 9.81, 0.1, 100.0);
    let vt = (m * g / c).sqrt();
    let mut body = ProjectileMotion::new(&[0.0, y0], &[0.0, 0.0], m, g, c).unwrap();
    let r = body.integrate((0.0, 3.0), 0.01, Method::Dop853).unwrap();
    let mut worst = 0.0_f64;
    for (&t, row) in r.t.iter().zip(r.y.rows()) {
        let y = y0 - vt * vt / g * (g * t / vt).cosh().ln();
        let p = -m * vt * (g * t / vt).tanh();
        worst = worst.max((row[1] - y).abs()).max((row[3] - p).abs());
        assert_eq!(row[0], 0.0);
    }
    println!("largest error {worst:e}");
    assert!(worst <= 3e-8, "{worst:e}");
}

/// A Lagrangian system runs on `[q, qdot]` (as rk4 does): the double pendulum's energy, which
/// the method does not conserve by construction, stays within 1e-8 relative over 20 time units
/// of chaotic motion at the default tolerances (measured 2.1e-9: rtol 1e-10 per step over a
/// few hundred steps).
#[test]
fn double_pendulum_keeps_its_energy_to_the_tolerance() {
    let mut dp =
        DoublePendulum::new(&[2.0, 2.5], &[0.0, 0.0], DoublePendulumParams::default()).unwrap();
    let r = dp.integrate((0.0, 20.0), 0.01, Method::Dop853).unwrap();
    let energy = r.energy.as_ref().unwrap();
    let e0 = energy[0];
    let drift = energy
        .iter()
        .fold(0.0_f64, |m, e| m.max(((e - e0) / e0).abs()));
    println!("relative energy error {drift:e}");
    assert!(drift <= 1e-8, "{drift:e}");
    // result.p holds qdot: at t = 0, the given velocities.
    assert_eq!(r.y.row(0).to_vec(), vec![2.0, 2.5, 0.0, 0.0]);
    assert_eq!(dp.ndof(), 2);
}

fn scalar(f: fn(f64) -> f64) -> Scalar {
    Scalar {
        phase: Phase::new(vec![1.0], 0.0).unwrap(),
        f,
    }
}

/// `y' = y^2`, `y(0) = 1` blows up at `t = 1`: the steps shrink to the rounding of `t` there
/// and the run stops with the time, not a hang.
#[test]
fn step_size_underflow_names_the_time() {
    let err = scalar(|y| y * y)
        .integrate((0.0, 2.0), 0.5, Method::Dop853)
        .unwrap_err();
    let Error::StepSizeTooSmall { t, step, reason } = &err else {
        panic!("{err}");
    };
    // The singularity is at t = 1, shifted by the run's global error (measured: the run stops
    // at 1 + 8e-12).
    assert!((t - 1.0).abs() < 1e-6, "{err}");
    assert!(step.abs() < 1e-12 && reason.contains("rounding"), "{err}");
}

/// A field that returns NaN beyond `y < 0.5` (reached at `t = ln 2` by `y' = -y`): no step
/// across it is accepted, and the error says the estimate was not finite, at `t = ln 2`.
#[test]
fn a_non_finite_field_is_a_step_failure_at_its_time() {
    let err = scalar(|y| if y < 0.5 { f64::NAN } else { -y })
        .integrate((0.0, 2.0), 0.5, Method::Dop853)
        .unwrap_err();
    let Error::StepSizeTooSmall { t, reason, .. } = &err else {
        panic!("{err}");
    };
    assert!((t - 2f64.ln()).abs() < 1e-6, "{err}");
    assert!(reason.contains("not finite"), "{err}");
}

#[test]
fn the_step_budget_stops_a_run() {
    let options = IntegrateOptions {
        tolerances: Some(Tolerances {
            max_steps: 20,
            ..Tolerances::default()
        }),
        ..IntegrateOptions::default()
    };
    let err = Pendulum::new(1.0, 0.0, 1.0)
        .unwrap()
        .integrate_with((0.0, 100.0), 0.1, Method::Dop853, options)
        .unwrap_err();
    let Error::StepSizeTooSmall { t, reason, .. } = &err else {
        panic!("{err}");
    };
    assert!(
        *t > 0.0 && *t < 100.0 && reason.contains("budget of 20 steps"),
        "{err}"
    );
}

#[test]
fn tolerances_are_refused_for_fixed_step_methods() {
    let err = Pendulum::new(1.0, 0.0, 1.0)
        .unwrap()
        .integrate_with((0.0, 1.0), 0.1, Method::Rk4, tolerances(1e-8, 1e-10))
        .unwrap_err();
    let Error::InvalidArgument { name, reason } = &err else {
        panic!("{err}");
    };
    assert_eq!(name, "tolerances");
    assert!(reason.contains("dop853"), "{err}");
}

#[test]
fn invalid_tolerances_are_refused_naming_them() {
    for (rtol, atol, name) in [
        (0.0, 1e-12, "rtol"),
        (-1e-8, 1e-12, "rtol"),
        (f64::NAN, 1e-12, "rtol"),
        (1e-8, f64::INFINITY, "atol"),
        (1e-8, 0.0, "atol"),
    ] {
        let err = Tolerances::new(rtol, atol).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidParameter { name: n, .. } if n == name),
            "{err}"
        );
        // The same through the options, unvalidated by their constructor.
        let options = IntegrateOptions {
            tolerances: Some(Tolerances {
                rtol,
                atol,
                ..Tolerances::default()
            }),
            ..IntegrateOptions::default()
        };
        let err = Pendulum::new(1.0, 0.0, 1.0)
            .unwrap()
            .integrate_with((0.0, 1.0), 0.1, Method::Dop853, options)
            .unwrap_err();
        assert!(
            matches!(&err, Error::InvalidParameter { name: n, .. } if n == name),
            "{err}"
        );
    }
}

/// A general ODE (no Hamiltonian structure) runs too: `y' = -y` to `e^-t` within its
/// tolerance (rtol 1e-10 on values <= 1; 1e-10 absolute is met with margin, measured ~1e-12).
#[test]
fn a_general_ode_decays_exponentially() {
    let mut decay = scalar(|y| -y);
    let r = decay.integrate((0.0, 5.0), 0.25, Method::Dop853).unwrap();
    for (&t, y) in r.t.iter().zip(r.y.column(0)) {
        assert!((y - (-t).exp()).abs() < 1e-10, "t = {t}: {y}");
    }
}
