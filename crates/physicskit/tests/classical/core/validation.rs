//! One test per validation rule of the core engine, each checking the error variant.

use std::ops::ControlFlow;

use crate::fixtures::{Damped, FreeRigidBody, LagrangianPendulum, NonSeparable, Scalar};
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method,
    Observer, OdeSystem, Phase, Sampling,
};

fn pendulum() -> Pendulum {
    Pendulum::new(1.0, 0.0, 1.0).unwrap()
}

#[test]
fn non_positive_dt_is_refused() {
    for dt in [0.0, -0.1] {
        let err = pendulum()
            .integrate((0.0, 1.0), dt, Method::Verlet)
            .unwrap_err();
        assert!(matches!(err, Error::InvalidTimeSpan { .. }), "{err}");
    }
}

#[test]
fn non_finite_dt_or_span_is_refused() {
    for (span, dt) in [
        ((0.0, 1.0), f64::NAN),
        ((0.0, 1.0), f64::INFINITY),
        ((0.0, f64::NAN), 0.1),
        ((f64::NEG_INFINITY, 1.0), 0.1),
    ] {
        let err = pendulum().integrate(span, dt, Method::Rk4).unwrap_err();
        assert!(matches!(err, Error::InvalidTimeSpan { .. }), "{err}");
    }
}

#[test]
fn backwards_span_is_refused() {
    let err = pendulum()
        .integrate((1.0, 0.0), 0.1, Method::Rk4)
        .unwrap_err();
    assert!(matches!(err, Error::InvalidTimeSpan { .. }), "{err}");
}

#[test]
fn span_that_is_not_a_whole_number_of_steps_is_refused_with_a_suggestion() {
    let err = pendulum()
        .integrate((0.0, 1.0), 0.3, Method::Rk4)
        .unwrap_err();
    let Error::InvalidTimeSpan { reason, .. } = &err else {
        panic!("wrong variant: {err}");
    };
    assert!(reason.contains("dt = 0.333"), "{reason}");
    // Decimal inputs that are whole numbers of steps up to rounding are accepted.
    for (t1, dt) in [(3.0, 3e-5), (1.0, 0.1), (100.0, 1e-3), (0.3, 0.1)] {
        let grid = physicskit::classical::TimeGrid::new((0.0, t1), dt).unwrap();
        assert_eq!(grid.n_steps(), (t1 / dt).round() as usize);
    }
}

#[test]
fn wrong_state_length_is_refused() {
    let mut p = pendulum();
    let err = p.reset(Some(&[1.0, 2.0, 3.0]), 0.0).unwrap_err();
    assert!(
        matches!(
            err,
            Error::DimensionMismatch {
                expected: 2,
                found: 3,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(
        p.state(),
        &[1.0, 0.0],
        "a refused reset leaves the state alone"
    );
}

#[test]
fn non_finite_initial_state_is_refused() {
    assert!(matches!(
        Pendulum::new(f64::NAN, 0.0, 1.0).unwrap_err(),
        Error::InvalidParameter { .. }
    ));
    assert!(matches!(
        Phase::new(vec![0.0, f64::INFINITY], 0.0).unwrap_err(),
        Error::NonFinite { .. }
    ));
    let err = pendulum().reset(Some(&[f64::NAN, 0.0]), 0.0).unwrap_err();
    assert!(matches!(err, Error::NonFinite { .. }), "{err}");
}

#[test]
fn out_of_range_parameters_are_refused() {
    let err = HarmonicOscillator::new(0.0, 0.0, -1.0, 1.0).unwrap_err();
    assert!(
        matches!(err, Error::InvalidParameter { ref name, .. } if name == "m"),
        "{err}"
    );
}

#[test]
fn unknown_method_name_lists_the_valid_ones() {
    let err = "leapfrog".parse::<Method>().unwrap_err();
    let Error::UnknownMethod { name, valid } = &err else {
        panic!("wrong variant: {err}");
    };
    assert_eq!(name, "leapfrog");
    for m in Method::ALL {
        assert!(valid.contains(m.name()));
        assert_eq!(m.name().parse::<Method>().unwrap(), m);
    }
}

#[test]
fn trajectory_too_large_is_refused_before_allocating() {
    // 1e15 samples x 6 values: 48 PB, refused from arithmetic alone (an attempt to allocate
    // would abort the process, so reaching the assertion proves nothing was allocated).
    let err = pendulum()
        .integrate((0.0, 1e12), 1e-3, Method::Verlet)
        .unwrap_err();
    assert!(matches!(err, Error::TrajectoryTooLarge { .. }), "{err}");
    // The same run storing only the final state is fine to set up; run a short version.
    let ok = pendulum().integrate_with(
        (0.0, 10.0),
        1e-3,
        Method::Verlet,
        IntegrateOptions::final_only(),
    );
    assert_eq!(ok.unwrap().n_samples(), 2);
}

#[test]
fn splitting_methods_refuse_non_separable_systems() {
    for method in [Method::Verlet, Method::Yoshida4] {
        let err = NonSeparable::new(0.1, 0.2)
            .integrate((0.0, 1.0), 0.1, method)
            .unwrap_err();
        assert!(matches!(err, Error::UnsupportedMethod { .. }), "{err}");
    }
    // force() itself reports the missing separation.
    let err = NonSeparable::new(0.1, 0.2)
        .force(&[0.1], 0.0, &mut [0.0])
        .unwrap_err();
    assert!(matches!(err, Error::Unsupported { .. }), "{err}");
}

#[test]
fn splitting_methods_refuse_non_conservative_forces() {
    for method in [Method::Verlet, Method::Yoshida4] {
        let mut damped = Damped {
            phase: Phase::new(vec![1.0, 0.0], 0.0).unwrap(),
            gamma: 0.1,
        };
        let err = damped.integrate((0.0, 1.0), 0.1, method).unwrap_err();
        let Error::UnsupportedMethod { reason, .. } = &err else {
            panic!("wrong variant: {err}");
        };
        assert!(reason.contains("non-conservative"), "{reason}");
        // rk4 and implicit_midpoint honour the drag: the energy decays.
        for ok in [Method::Rk4, Method::ImplicitMidpoint] {
            let e = damped
                .integrate((0.0, 1.0), 0.1, ok)
                .unwrap()
                .energy
                .unwrap();
            assert!(e[e.len() - 1] < e[0]);
        }
    }
}

#[test]
fn splitting_methods_refuse_lagrangian_and_ode_systems() {
    for method in [Method::Verlet, Method::Yoshida4] {
        let err = LagrangianPendulum::new(0.1, 0.0)
            .integrate((0.0, 1.0), 0.1, method)
            .unwrap_err();
        assert!(matches!(err, Error::UnsupportedMethod { .. }), "{err}");
        let mut body = FreeRigidBody {
            phase: Phase::new(vec![0.0, 1.0, 0.0], 0.0).unwrap(),
            inertia: [1.0, 2.0, 3.0],
        };
        let err = body.integrate((0.0, 1.0), 0.1, method).unwrap_err();
        assert!(matches!(err, Error::UnsupportedMethod { .. }), "{err}");
    }
}

#[test]
fn implicit_solver_failure_names_time_iterations_and_residual() {
    // y' = -100 y with dt = 1: fixed-point iteration diverges (rate h L / 2 = 50) and there is
    // no Jacobian for Newton, so the step cannot be solved.
    let mut stiff = Scalar {
        phase: Phase::new(vec![1.0], 0.0).unwrap(),
        f: |y| -100.0 * y,
    };
    let err = stiff
        .integrate((0.0, 5.0), 1.0, Method::ImplicitMidpoint)
        .unwrap_err();
    let Error::SolverDidNotConverge {
        t,
        iterations,
        residual,
    } = err
    else {
        panic!("wrong variant: {err}");
    };
    assert_eq!(t, 0.0);
    assert!(iterations >= 2);
    assert!(residual > 1e-13 || residual.is_nan());
    assert_eq!(
        stiff.state(),
        &[1.0],
        "a failed run leaves the system untouched"
    );
}

#[test]
fn blow_up_during_integration_is_reported_not_returned() {
    // y' = y^2 from y = 1 reaches infinity at t = 1.
    let mut blowup = Scalar {
        phase: Phase::new(vec![1.0], 0.0).unwrap(),
        f: |y| y * y,
    };
    let err = blowup.integrate((0.0, 2.0), 0.01, Method::Rk4).unwrap_err();
    let Error::NonFinite { t, .. } = err else {
        panic!("wrong variant: {err}");
    };
    assert!(t > 0.9 && t < 1.2, "reported at t = {t}");
}

#[test]
fn zero_stride_is_refused() {
    let options = IntegrateOptions {
        sampling: Sampling::Stride(0),
        ..Default::default()
    };
    let err = pendulum()
        .integrate_with((0.0, 1.0), 0.1, Method::Verlet, options)
        .unwrap_err();
    assert!(matches!(err, Error::InvalidParameter { .. }), "{err}");
}

#[test]
fn an_observer_can_interrupt() {
    struct StopAt(usize);
    impl Observer for StopAt {
        fn observe(&mut self, step: usize, _n: usize, _t: f64) -> ControlFlow<()> {
            if step >= self.0 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        }
    }
    let mut stop = StopAt(200);
    let options = IntegrateOptions {
        observer: Some(&mut stop),
        observe_every: 100,
        ..Default::default()
    };
    let err = pendulum()
        .integrate_with((0.0, 100.0), 0.01, Method::Yoshida4, options)
        .unwrap_err();
    assert!(
        matches!(err, Error::Interrupted { t } if (t - 2.0).abs() < 1e-12),
        "{err}"
    );
}

#[test]
fn singular_mass_matrix_is_an_error() {
    let mut degenerate = LagrangianPendulum::new(0.1, 0.0);
    degenerate.mass = 0.0;
    for method in [Method::Rk4, Method::ImplicitMidpoint] {
        let err = degenerate.integrate((0.0, 1.0), 0.1, method).unwrap_err();
        assert!(
            matches!(err, Error::SingularMatrix { .. }),
            "{method}: {err}"
        );
    }
}

#[test]
fn a_state_that_disagrees_with_ndof_is_refused_not_a_panic() {
    // A user-written system whose `ndof` (1) does not match its state (4 values): every method
    // refuses it up front (the splitting loop would otherwise index a 2-value array).
    let mut d = Damped {
        phase: Phase::new(vec![0.1, 0.2, 0.3, 0.4], 0.0).unwrap(),
        gamma: 0.0,
    };
    for method in [
        Method::Rk4,
        Method::ImplicitMidpoint,
        Method::Verlet,
        Method::Yoshida4,
    ] {
        assert!(
            matches!(
                HamiltonianSystem::integrate(&mut d, (0.0, 1.0), 0.1, method),
                Err(Error::DimensionMismatch {
                    expected: 2,
                    found: 4,
                    ..
                })
            ),
            "{method:?}"
        );
    }
}
