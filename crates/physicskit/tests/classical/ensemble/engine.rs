//! The engine: the same bits on any thread count, each member equal to its own `integrate`,
//! bad members refused by index before any integration.

use std::ops::ControlFlow;

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{
    self, Condition, EnsembleResult, Event, Members, Plan, Reduction, Sweep,
};
use physicskit::classical::model::Value;
use physicskit::classical::{Error, IntegrateOptions, Observer, Sampling};

/// A 6 x 6 grid of the double pendulum's initial angles (36 members: two full chunks and a
/// partial one), flip events, energy errors and strided trajectories.
fn pendulum_grid() -> Members {
    let side: Vec<f64> = (0..6).map(|i| -3.0 + 1.2 * i as f64).collect();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for &x in &side {
        for &y in &side {
            a.push(x);
            b.push(y);
        }
    }
    Members {
        common: vec![("thetadot0".into(), Value::Vector(vec![0.0, 0.0]))],
        sweeps: vec![Sweep::new("theta0[0]", a), Sweep::new("theta0[1]", b)],
        states: None,
        n: 36,
    }
}

fn pendulum_plan(threads: Option<usize>) -> Plan {
    Plan {
        t_span: (0.0, 3.0),
        dt: 0.01,
        method: None,
        stride: Some(40),
        reductions: vec![
            Reduction::MaxEnergyError,
            Reduction::FirstEvent(Event {
                index: 1,
                condition: Condition::AbsExceeds(std::f64::consts::PI),
            }),
        ],
        final_state: true,
        threads,
        tolerances: None,
    }
}

fn run_pendulums(threads: Option<usize>) -> EnsembleResult {
    let entry = catalog::find("double-pendulum").unwrap();
    ensemble::run(entry, &pendulum_grid(), &pendulum_plan(threads), None).unwrap()
}

/// The bits of every float output (compared by bits: events never reached are NaN).
fn bits(r: &EnsembleResult) -> Vec<u64> {
    let mut v: Vec<u64> = r.final_state.iter().map(|x| x.to_bits()).collect();
    v.extend(r.trajectory.iter().flatten().map(|x| x.to_bits()));
    for (_, a) in &r.reductions {
        v.extend(a.iter().map(|x| x.to_bits()));
    }
    v
}

#[test]
fn one_two_and_three_threads_give_the_same_bits() {
    let one = run_pendulums(Some(1));
    // Something happened to compare: some members flip within 3 s, some do not.
    let flips = &one.reductions[1].1;
    assert!(flips.iter().any(|t| t.is_finite()) && flips.iter().any(|t| t.is_nan()));
    for threads in [2, 3] {
        let other = run_pendulums(Some(threads));
        assert_eq!(bits(&one), bits(&other), "{threads} threads");
        assert_eq!(one.t, other.t);
    }
}

#[test]
fn every_member_equals_its_own_integrate_bit_for_bit() {
    let members = pendulum_grid();
    let plan = pendulum_plan(None);
    let out = run_pendulums(None);
    for i in [0, 7, 20, 35] {
        let theta0 = vec![members.sweeps[0].values[i], members.sweeps[1].values[i]];
        let mut single = catalog::build(
            "double-pendulum",
            [
                ("thetadot0".to_string(), Value::Vector(vec![0.0, 0.0])),
                ("theta0".to_string(), Value::Vector(theta0)),
            ],
        )
        .unwrap();
        let method = single.default_method();
        assert_eq!(method, out.method);
        let full = single
            .integrate(plan.t_span, plan.dt, method, IntegrateOptions::default())
            .unwrap();
        let last = full.y.nrows() - 1;
        assert_eq!(out.final_state.row(i), full.y.row(last), "member {i}");
        assert_eq!(
            out.reductions[0].1[i],
            full.max_relative_energy_error().unwrap(),
            "member {i}"
        );
        // The strided trajectory is what `integrate` stores with that stride.
        single
            .reset(Some(full.y.row(0).as_slice().unwrap()), 0.0)
            .unwrap();
        let strided = single
            .integrate(
                plan.t_span,
                plan.dt,
                method,
                IntegrateOptions {
                    sampling: Sampling::Stride(40),
                    ..IntegrateOptions::default()
                },
            )
            .unwrap();
        let trajectory = out.trajectory.as_ref().unwrap();
        assert_eq!(trajectory.index_axis(ndarray::Axis(0), i), strided.y);
        assert_eq!(out.t.as_ref().unwrap(), strided.t);
    }
}

#[test]
fn states_given_per_member_equal_single_runs() {
    // Hénon–Heiles from explicit states: final state only (the run stores two samples).
    let states: Vec<f64> = (0..40)
        .flat_map(|i| [0.0, 0.01 * i as f64, 0.3, 0.0])
        .collect();
    let members = Members {
        states: Some(states.clone()),
        n: 40,
        ..Members::default()
    };
    let plan = Plan {
        t_span: (0.0, 5.0),
        dt: 0.01,
        method: None,
        stride: None,
        reductions: vec![],
        final_state: true,
        threads: Some(2),
        tolerances: None,
    };
    let entry = catalog::find("henon-heiles").unwrap();
    let out = ensemble::run(entry, &members, &plan, None).unwrap();
    for i in [0, 17, 39] {
        let mut single = catalog::build("henon-heiles", []).unwrap();
        single.reset(Some(&states[4 * i..4 * i + 4]), 0.0).unwrap();
        let method = single.default_method();
        let r = single
            .integrate(plan.t_span, plan.dt, method, IntegrateOptions::default())
            .unwrap();
        assert_eq!(out.final_state.row(i), r.y.row(r.y.nrows() - 1));
    }
}

/// Counts its calls.
struct Count(usize);

impl Observer for Count {
    fn observe(&mut self, _: usize, _: usize, _: f64) -> ControlFlow<()> {
        self.0 += 1;
        ControlFlow::Continue(())
    }
}

#[test]
fn a_nan_in_member_731_of_1000_is_refused_by_index_before_any_integration() {
    let mut q0: Vec<f64> = (0..1000).map(|i| 1e-3 * i as f64).collect();
    q0[731] = f64::NAN;
    let members = Members {
        sweeps: vec![Sweep::new("q0", q0)],
        n: 1000,
        ..Members::default()
    };
    // 731 members of 2e4 steps take well over the observer's 20 ms period, so had any member
    // been integrated before the refusal, the observer would have been called.
    let plan = Plan {
        t_span: (0.0, 200.0),
        dt: 0.01,
        method: None,
        stride: None,
        reductions: vec![],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let mut count = Count(0);
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let err = ensemble::run(entry, &members, &plan, Some(&mut count)).unwrap_err();
    assert!(
        matches!(&err, Error::InvalidParameter { name, .. } if name == "member 731: q0"),
        "{err}"
    );
    assert_eq!(
        count.0, 0,
        "the observer was called: integration had started"
    );
}

#[test]
fn invalid_plans_and_sweeps_are_refused() {
    let entry = catalog::find("double-pendulum").unwrap();
    let plan = pendulum_plan(Some(1));
    let run = |members: &Members, plan: &Plan| ensemble::run(entry, members, plan, None);
    let mut m = pendulum_grid();
    m.sweeps[0].target = "theta0[2]".into();
    assert!(run(&m, &plan)
        .unwrap_err()
        .to_string()
        .contains("index out of range"));
    let mut m = pendulum_grid();
    m.sweeps[0].target = "nope".into();
    assert!(run(&m, &plan)
        .unwrap_err()
        .to_string()
        .contains("no such parameter"));
    let mut m = pendulum_grid();
    m.sweeps[0].values.pop();
    assert!(matches!(
        run(&m, &plan).unwrap_err(),
        Error::DimensionMismatch {
            expected: 36,
            found: 35,
            ..
        }
    ));
    let mut m = pendulum_grid();
    m.sweeps[1].target = "theta0".into();
    assert!(run(&m, &plan)
        .unwrap_err()
        .to_string()
        .contains("can be swept"));
    let m = pendulum_grid();
    let mut p = plan.clone();
    p.stride = Some(0);
    assert!(run(&m, &p).unwrap_err().to_string().contains("stride"));
    let mut p = plan.clone();
    p.reductions = vec![Reduction::FirstEvent(Event {
        index: 4,
        condition: Condition::AbsExceeds(1.0),
    })];
    assert!(run(&m, &p)
        .unwrap_err()
        .to_string()
        .contains("beyond the state"));
    let mut p = plan.clone();
    p.threads = Some(0);
    assert!(run(&m, &p).unwrap_err().to_string().contains("threads"));
    let empty = Members::default();
    assert!(run(&empty, &plan)
        .unwrap_err()
        .to_string()
        .contains("member"));
}

/// The harmonic oscillator's defaults, but a double pendulum (a longer state) as member 5.
struct OddMemberOut;

impl ensemble::MemberSource for OddMemberOut {
    fn count(&self) -> usize {
        8
    }

    fn build(
        &self,
        index: usize,
        _t0: f64,
    ) -> physicskit::classical::Result<Box<dyn physicskit::classical::model::erased::DynSystem>>
    {
        let name = if index == 5 {
            "double-pendulum"
        } else {
            "harmonic-oscillator"
        };
        catalog::find(name)?.build_from([])
    }
}

#[test]
fn prechecked_runs_give_the_same_bits_and_still_name_a_bad_member() {
    let entry = catalog::find("double-pendulum").unwrap();
    let members = pendulum_grid();
    let source = ensemble::FromCatalogue::new(entry, &members).unwrap();
    let plan = pendulum_plan(Some(2));
    ensemble::check_source(&source, &plan).unwrap();
    let prechecked = ensemble::run_source_prechecked(&source, &plan, None).unwrap();
    let checked = ensemble::run_source(&source, &plan, None).unwrap();
    assert_eq!(bits(&prechecked), bits(&checked));
    assert_eq!(prechecked.steps, checked.steps);
    // Something to compare: some members flip within the span, some do not.
    let flips = &prechecked.reductions[1].1;
    assert!(flips.iter().any(|t| t.is_finite()) && flips.iter().any(|t| t.is_nan()));
    // Members it was not told the truth about are still refused by index, when their run
    // builds them, not with a panic on a row of the wrong length.
    let mut q0: Vec<f64> = (0..40).map(|i| 1e-3 * f64::from(i)).collect();
    q0[31] = f64::NAN;
    let members = Members {
        sweeps: vec![Sweep::new("q0", q0)],
        n: 40,
        ..Members::default()
    };
    let oscillators = catalog::find("harmonic-oscillator").unwrap();
    let source = ensemble::FromCatalogue::new(oscillators, &members).unwrap();
    let plan = Plan {
        stride: None,
        reductions: vec![],
        method: None,
        ..pendulum_plan(Some(2))
    };
    let err = ensemble::run_source_prechecked(&source, &plan, None).unwrap_err();
    assert!(
        matches!(&err, Error::InvalidParameter { name, .. } if name == "member 31: q0"),
        "{err}"
    );
    let err = ensemble::run_source_prechecked(&OddMemberOut, &plan, None).unwrap_err();
    assert!(
        matches!(&err, Error::DimensionMismatch { name, expected: 2, found: 4 }
            if name == "member 5: state"),
        "{err}"
    );
    // check_source finds both up front.
    assert!(ensemble::check_source(&source, &plan).is_err());
    assert!(ensemble::check_source(&OddMemberOut, &plan).is_err());
}
