//! First-event times against analytic ones, converging at the method's order.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{
    self, Condition, Direction, Event, Members, Plan, Reduction, Sweep,
};
use physicskit::classical::Method;

/// First downward zero crossings of `q` for harmonic oscillators `q0 = 1, p0 = 0` with `k = 1`
/// and `k = 4` (m = 1): `q = cos(omega t)`, so the crossing is at `pi / (2 omega)`.
fn crossing_errors(method: Method, dt: f64) -> [f64; 2] {
    let members = Members {
        sweeps: vec![Sweep::new("k", vec![1.0, 4.0])],
        n: 2,
        ..Members::default()
    };
    let plan = Plan {
        t_span: (0.0, 4.0),
        dt,
        method: Some(method),
        stride: None,
        reductions: vec![Reduction::FirstEvent(Event {
            index: 0,
            condition: Condition::Crosses {
                value: 0.0,
                direction: Direction::Falling,
            },
        })],
        threads: Some(1),
    };
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let out = ensemble::run(entry, &members, &plan, None).unwrap();
    let t = &out.reductions[0].1;
    let half_pi = std::f64::consts::FRAC_PI_2;
    [(t[0] - half_pi).abs(), (t[1] - half_pi / 2.0).abs()]
}

#[test]
fn harmonic_oscillator_crossing_time_converges_at_the_method_order() {
    for (method, order) in [
        (Method::Verlet, 2.0),
        (Method::Rk4, 4.0),
        (Method::Yoshida4, 4.0),
        (Method::ImplicitMidpoint, 2.0),
    ] {
        // Steps coarse enough that the error stays far above rounding (>= 1e-11 at rk4's
        // finest), fine enough to be in the asymptotic regime (omega dt <= 0.2).
        let coarse = crossing_errors(method, 0.1);
        let fine = crossing_errors(method, 0.05);
        for member in 0..2 {
            let measured = (coarse[member] / fine[member]).log2();
            // Halving dt divides the error by 2^p; 0.3 covers the higher-order terms still
            // present at omega dt = 0.2, and is far below the gap to a wrong order (a step-end
            // event, not interpolated, would measure order 1).
            assert!(
                (measured - order).abs() < 0.3,
                "{}: member {member}, errors {:e} -> {:e}, order {measured:.2}",
                method.name(),
                coarse[member],
                fine[member]
            );
        }
    }
}

#[test]
fn events_never_reached_are_nan_and_events_at_the_start_are_t0() {
    let members = Members {
        sweeps: vec![Sweep::new("q0", vec![0.5, 2.0])],
        n: 2,
        ..Members::default()
    };
    let plan = Plan {
        t_span: (1.0, 3.0),
        dt: 0.01,
        method: None,
        stride: None,
        // |q| <= q0 forever: |q| > 1 never happens for q0 = 0.5 and holds from t0 for q0 = 2.
        reductions: vec![Reduction::FirstEvent(Event {
            index: 0,
            condition: Condition::AbsExceeds(1.0),
        })],
        threads: Some(1),
    };
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let out = ensemble::run(entry, &members, &plan, None).unwrap();
    assert!(out.reductions[0].1[0].is_nan());
    assert_eq!(out.reductions[0].1[1], 1.0);
}
