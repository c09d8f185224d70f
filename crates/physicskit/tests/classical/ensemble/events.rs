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
        final_state: true,
        threads: Some(1),
        tolerances: None,
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
        final_state: true,
        threads: Some(1),
        tolerances: None,
    };
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let out = ensemble::run(entry, &members, &plan, None).unwrap();
    assert!(out.reductions[0].1[0].is_nan());
    assert_eq!(out.reductions[0].1[1], 1.0);
}

#[test]
fn members_of_an_events_only_plan_stop_at_their_last_event_with_the_same_times() {
    // Double pendulums released from rest at large angles: some flip early, some never.
    let theta: Vec<f64> = (0..12).map(|i| 1.5 + 0.14 * f64::from(i)).collect();
    let members = Members {
        common: vec![(
            "thetadot0".into(),
            physicskit::classical::model::Value::Vector(vec![0.0, 0.0]),
        )],
        sweeps: vec![
            Sweep::new("theta0[0]", theta.clone()),
            Sweep::new("theta0[1]", theta.iter().map(|t| -t).collect()),
        ],
        n: 12,
        ..Members::default()
    };
    let flip = |index| {
        Reduction::FirstEvent(Event {
            index,
            condition: Condition::AbsExceeds(std::f64::consts::PI),
        })
    };
    let mut plan = Plan {
        t_span: (0.0, 8.0),
        dt: 0.01,
        method: Some(Method::Rk4),
        stride: None,
        reductions: vec![flip(0), flip(1)],
        final_state: true,
        threads: Some(2),
        tolerances: None,
    };
    let entry = catalog::find("double-pendulum").unwrap();
    let full = ensemble::run(entry, &members, &plan, None).unwrap();
    plan.final_state = false;
    let early = ensemble::run(entry, &members, &plan, None).unwrap();
    assert_eq!(early.final_state.dim(), (12, 0));
    let n_steps = 800;
    assert!(full.steps.iter().all(|&s| s == n_steps));
    for i in 0..12 {
        let bits = |r: &ensemble::EnsembleResult, k: usize| r.reductions[k].1[i].to_bits();
        assert_eq!(bits(&full, 0), bits(&early, 0), "member {i}");
        assert_eq!(bits(&full, 1), bits(&early, 1), "member {i}");
        let (a, b) = (full.reductions[0].1[i], full.reductions[1].1[i]);
        if a.is_finite() && b.is_finite() {
            // Both arms flipped: the member stopped on the step that holds the later flip,
            // t_{k-1} < t <= t_k (1e-12: the rounding of t_k = k dt).
            let last = a.max(b);
            let k = early.steps[i] as f64;
            assert!(k * 0.01 >= last - 1e-12 && (k - 1.0) * 0.01 < last + 1e-12);
            assert!(early.steps[i] < n_steps);
        } else {
            assert_eq!(early.steps[i], n_steps, "member {i}");
        }
    }
    // Something was saved: some members had both arms flip well before the end.
    let saved: usize = early.steps.iter().map(|s| n_steps - s).sum();
    assert!(saved > n_steps, "{:?}", early.steps);
    // Nothing to keep is refused.
    plan.reductions.clear();
    assert!(ensemble::run(entry, &members, &plan, None)
        .unwrap_err()
        .to_string()
        .contains("nothing to keep"));
}
