//! The chaos reductions (largest Lyapunov exponent, SALI): the same bits on any thread count,
//! each member's value equal to the chaos toolkit's single-orbit call on that member, and the
//! refusals of `integrate` and the chaos loops.

use physicskit::classical::analysis::lyapunov::max_lyapunov;
use physicskit::classical::analysis::sali::{alignment_index, Alignment};
use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, EnsembleResult, Members, Plan, Reduction, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::{Error, IntegrateOptions, Method};

/// Hénon–Heiles at `E = 1/8` from the section `x = 0`, `p_x >= 0`: 18 points on a line of
/// `(y, p_y)` (one full chunk of 16 and a partial one), as `[x, y, p_x, p_y]` rows.
fn henon_heiles_states() -> Vec<f64> {
    let energy = 0.125;
    (0..18)
        .flat_map(|i| {
            let y = -0.3 + 0.04 * f64::from(i);
            let py = 0.1;
            let potential = 0.5 * y * y - y * y * y / 3.0;
            let px = (2.0 * (energy - potential) - py * py).sqrt();
            [0.0, y, px, py]
        })
        .collect()
}

fn chaos_plan(threads: Option<usize>) -> Plan {
    Plan {
        t_span: (0.0, 60.0),
        dt: 0.05,
        method: None,
        stride: None,
        reductions: vec![
            Reduction::MaxLyapunov {
                renormalize_every: 5,
            },
            Reduction::Sali {
                renormalize_every: 3,
            },
        ],
        final_state: true,
        threads,
        tolerances: None,
    }
}

fn run_henon_heiles(threads: Option<usize>) -> EnsembleResult {
    let members = Members {
        states: Some(henon_heiles_states()),
        n: 18,
        ..Members::default()
    };
    let entry = catalog::find("henon-heiles").unwrap();
    ensemble::run(entry, &members, &chaos_plan(threads), None).unwrap()
}

#[test]
fn chaos_reductions_are_the_same_bits_on_one_two_and_three_threads() {
    let one = run_henon_heiles(Some(1));
    assert_eq!(one.reductions[0].0, "max_lyapunov");
    assert_eq!(one.reductions[1].0, "sali");
    let bits = |r: &EnsembleResult| -> Vec<u64> {
        r.reductions
            .iter()
            .flat_map(|(_, a)| a.iter().map(|x| x.to_bits()))
            .chain(r.final_state.iter().map(|x| x.to_bits()))
            .collect()
    };
    for threads in [2, 3] {
        assert_eq!(
            bits(&one),
            bits(&run_henon_heiles(Some(threads))),
            "{threads}"
        );
    }
}

#[test]
fn each_member_equals_the_single_orbit_max_lyapunov_and_sali() {
    let out = run_henon_heiles(None);
    let plan = chaos_plan(None);
    let states = henon_heiles_states();
    // Something to compare: the values differ between members (the line crosses islands and
    // the chaotic sea at E = 1/8).
    let sali = &out.reductions[1].1;
    assert!(sali.iter().any(|&s| s != sali[0]));
    for i in [0, 9, 16, 17] {
        let single = || {
            let mut s = catalog::build("henon-heiles", []).unwrap();
            s.reset(Some(&states[4 * i..4 * i + 4]), 0.0).unwrap();
            s
        };
        let lyapunov = max_lyapunov(&mut *single(), plan.t_span, plan.dt, None, 5).unwrap();
        assert_eq!(out.reductions[0].1[i], lyapunov.exponents[0], "member {i}");
        let index = alignment_index(
            &mut *single(),
            plan.t_span,
            plan.dt,
            None,
            Alignment::Sali,
            3,
        )
        .unwrap();
        assert_eq!(
            out.reductions[1].1[i],
            *index.index.last().unwrap(),
            "member {i}"
        );
    }
}

#[test]
fn a_lagrangian_member_equals_its_single_orbit_call() {
    // The double pendulum's stored state is [q, qdot]: the reduction starts its flow from the
    // member's own initial state, as the single call does.
    let members = Members {
        common: vec![
            ("theta0".into(), Value::Vector(vec![0.0, 0.0])),
            ("thetadot0".into(), Value::Vector(vec![0.0, 0.5])),
        ],
        sweeps: vec![Sweep::new("theta0[0]", vec![0.3, 2.0])],
        n: 2,
        ..Members::default()
    };
    let plan = Plan {
        t_span: (0.0, 2.0),
        dt: 0.01,
        method: Some(Method::Rk4),
        stride: None,
        reductions: vec![Reduction::MaxLyapunov {
            renormalize_every: 10,
        }],
        final_state: true,
        threads: Some(2),
        tolerances: None,
    };
    let entry = catalog::find("double-pendulum").unwrap();
    let out = ensemble::run(entry, &members, &plan, None).unwrap();
    for (i, theta) in [0.3, 2.0].into_iter().enumerate() {
        let mut single = catalog::build(
            "double-pendulum",
            [
                ("thetadot0".to_string(), Value::Vector(vec![0.0, 0.5])),
                ("theta0".to_string(), Value::Vector(vec![theta, 0.0])),
            ],
        )
        .unwrap();
        let s = max_lyapunov(&mut *single, plan.t_span, plan.dt, plan.method, 10).unwrap();
        assert_eq!(out.reductions[0].1[i], s.exponents[0], "member {i}");
    }
}

#[test]
fn splitting_on_a_non_separable_system_and_bad_settings_are_refused_up_front() {
    let members = Members {
        sweeps: vec![Sweep::new("theta0[0]", vec![0.3, 2.0])],
        n: 2,
        ..Members::default()
    };
    let entry = catalog::find("double-pendulum").unwrap();
    let mut plan = Plan {
        t_span: (0.0, 1.0),
        dt: 0.01,
        method: Some(Method::Yoshida4),
        stride: None,
        reductions: vec![Reduction::Sali {
            renormalize_every: 1,
        }],
        final_state: true,
        threads: Some(1),
        tolerances: None,
    };
    let err = ensemble::run(entry, &members, &plan, None).unwrap_err();
    // The refusal `integrate` gives a single member, word for word, not a member's failure.
    let mut single = catalog::build("double-pendulum", []).unwrap();
    let alone = single
        .integrate(
            plan.t_span,
            plan.dt,
            Method::Yoshida4,
            IntegrateOptions::default(),
        )
        .unwrap_err();
    assert!(matches!(&err, Error::UnsupportedMethod { .. }), "{err}");
    assert_eq!(err.to_string(), alone.to_string());
    plan.method = None;
    plan.reductions = vec![Reduction::MaxLyapunov {
        renormalize_every: 0,
    }];
    let err = ensemble::run(entry, &members, &plan, None).unwrap_err();
    assert!(err.to_string().contains("renormalize_every"), "{err}");
    // SALI needs two entries of state; a one-degree-of-freedom system has two.
    plan.reductions = vec![Reduction::Sali {
        renormalize_every: 0,
    }];
    assert!(ensemble::check(entry, &members, &plan).is_err());
}
