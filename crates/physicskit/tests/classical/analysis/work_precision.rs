//! The work–precision problems (`analysis/work_precision.rs`): the double pendulum's reference
//! against a second, independent one, and each problem's error falling at the method's order
//! (so the error measures what it says) or with the tolerance for the adaptive method.

use crate::checks::loglog_slope;
use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::{LagrangianSystem, Method};

/// dop853 at rtol = atol = 1e-14 (the reference) against gauss_legendre6 at dt = 1e-4: two
/// methods sharing no code but the vector field. GL6's truncation error at this step is
/// ~(1e-4)^6 ~ 1e-24 times the problem's constant, so what separates them is rounding (~1e-13
/// after 10^5 steps, amplified by the chaotic flow over t = 10 by at most e^(lambda t) ~ 10 with
/// the largest exponent measured for this orbit below 0.3) and dop853's tolerance; 1e-10 bounds
/// both with a margin and is 10^4 below the errors the diagram shows for the coarsest steps.
#[test]
fn the_double_pendulum_reference_agrees_with_an_independent_run() {
    let t_end = 10.0;
    let reference = double_pendulum_reference(t_end).unwrap();
    let gl6 = physicskit::classical::analysis::work_precision::double_pendulum()
        .unwrap()
        .integrate((0.0, t_end), 1e-4, Method::GaussLegendre6)
        .unwrap();
    let distance = gl6
        .final_state()
        .iter()
        .zip(&reference)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!("dop853 reference vs gauss_legendre6 at 1e-4: {distance:e}");
    assert!(distance < 1e-10, "{distance:e}");
}

/// On each problem (the quick sizes), rk4's error at two steps a factor 2 apart falls at its
/// order 4 (slope within 0.3: one halving in the asymptotic regime), which checks that each
/// error is the method's error against the right exact value (a wrong reference or a wrong
/// angle would flatten the slope at its own offset).
#[test]
fn errors_fall_at_the_methods_order() {
    for problem in Problem::all(true) {
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end).unwrap(),
            _ => Vec::new(),
        };
        let steps = &problem.steps(Method::Rk4, 3)[1..];
        let errors: Vec<f64> = steps
            .iter()
            .map(|&dt| problem.error(&problem.run(Method::Rk4, dt).unwrap(), &reference))
            .collect();
        let slope = loglog_slope(steps, &errors);
        println!(
            "{}: rk4 at {steps:?}: {errors:?}, slope {slope:.3}",
            problem.name()
        );
        assert!(
            (slope - 4.0).abs() < 0.3,
            "{}: slope {slope}",
            problem.name()
        );
    }
}

/// dop853's settings are tolerances, and its error follows them down: over the ladder's first
/// three (1e-5, 1e-6, 1e-7) the error shrinks on every problem, and stays within a factor 1e3
/// of the tolerance times the span (the global error of a tolerance-controlled method grows at
/// most about linearly with time: 100 Kepler orbits are 628 time units).
#[test]
fn the_adaptive_method_follows_its_tolerance() {
    for problem in Problem::all(true) {
        assert!(problem.methods().contains(&Method::Dop853));
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end).unwrap(),
            _ => Vec::new(),
        };
        let tolerances = problem.steps(Method::Dop853, 3);
        assert_eq!(tolerances, [1e-5, 1e-6, 1e-7]);
        let errors: Vec<f64> = tolerances
            .iter()
            .map(|&tol| problem.error(&problem.run(Method::Dop853, tol).unwrap(), &reference))
            .collect();
        println!("{}: dop853 at {tolerances:?}: {errors:?}", problem.name());
        assert!(errors[0] > errors[2], "{}: {errors:?}", problem.name());
        for (tol, e) in tolerances.iter().zip(&errors) {
            assert!(
                *e < 1e3 * tol * problem.t_end().max(1.0),
                "{}: {e:e}",
                problem.name()
            );
        }
    }
}
