//! The work–precision problems (`analysis/work_precision.rs`): the double pendulum's reference
//! against a second, independent one, and each problem's error falling at the method's order
//! (so the error measures what it says) or with the tolerance for the adaptive method.

use crate::checks::loglog_slope;
use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::systems::DoublePendulum;
use physicskit::classical::{LagrangianSystem, Method};

/// dop853 at rtol = atol = 1e-14 (the reference) against gauss_legendre6 at dt = 1e-4: two
/// methods sharing no code but the vector field. GL6's truncation error at this step is
/// ~(1e-4)^6 times the problem's constant, so what separates them is rounding and dop853's
/// tolerance, both amplified by the chaotic flow. The amplification is measured here: the same
/// GL6 run started 1e-13 away (about 500 ulps of theta1 = 2, the size of the rounding one
/// run accumulates over its first steps) ends `spread` away at t = 10. Two accurate runs must
/// agree within a small multiple of that (10x: rounding is spread over the run, not all at the
/// start), and a reference worse than that would show as a floor in the diagram.
#[test]
fn the_double_pendulum_reference_agrees_with_an_independent_run() {
    let t_end = 10.0;
    let reference = double_pendulum_reference(t_end).unwrap();
    let gl6 = |theta1: f64| {
        DoublePendulum::new(&[theta1, 1.0], &[0.5, -0.3], Default::default())
            .unwrap()
            .integrate((0.0, t_end), 1e-4, Method::GaussLegendre6)
            .unwrap()
            .final_state()
            .to_vec()
    };
    let distance = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let run = gl6(2.0);
    let spread = distance(&run, &gl6(2.0 + 1e-13));
    let gap = distance(&run, &reference);
    println!(
        "dop853 reference vs gauss_legendre6 at 1e-4: {gap:e}; 1e-13 start spread: {spread:e}"
    );
    assert!(gap < 10.0 * spread, "gap {gap:e}, spread {spread:e}");
}

/// On each problem (the quick sizes), implicit_midpoint's error at two steps a factor 2 apart
/// (the ladder's second and third) falls at its order 2 (slope within 0.2: one halving in the
/// asymptotic regime), which checks that each error is the method's error against the right
/// exact value (a wrong reference or a wrong angle would flatten the slope at its own offset).
/// (rk4 on Kepler at e = 0.5 is still pre-asymptotic at these steps: 4.7 from 0.025 to
/// 0.0125, 4.4 from 0.00625 to 0.0031, its fifth-order term large at perihelion.)
#[test]
fn errors_fall_at_the_methods_order() {
    for problem in Problem::all(true) {
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end).unwrap(),
            _ => Vec::new(),
        };
        let steps = &problem.steps(Method::ImplicitMidpoint, 3)[1..];
        let errors: Vec<f64> = steps
            .iter()
            .map(|&dt| {
                problem.error(
                    &problem.run(Method::ImplicitMidpoint, dt).unwrap(),
                    &reference,
                )
            })
            .collect();
        let slope = loglog_slope(steps, &errors);
        println!(
            "{}: implicit_midpoint at {steps:?}: {errors:?}, slope {slope:.3}",
            problem.name()
        );
        assert!(
            (slope - 2.0).abs() < 0.2,
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
