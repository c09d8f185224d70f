//! An adaptive method's tolerances in an ensemble: every member runs at the plan's
//! tolerances (its bits are those of its own `integrate` with them, on any thread count),
//! tighter tolerances bring the members closer to Kepler's closed form, and a fixed-step
//! method given tolerances is refused as `integrate` refuses it.

use std::f64::consts::TAU;

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, EnsembleResult, Members, Plan, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::{Error, IntegrateOptions, Method, Sampling, Tolerances};

/// Kepler orbits from their elements (`a = 1`, `k = mu = 1`: period `2 pi`), eccentricities
/// from nearly circular to `0.7`, where the step near perihelion is some 30 times shorter
/// than at aphelion.
const ECCENTRICITIES: [f64; 5] = [0.05, 0.2, 0.4, 0.55, 0.7];

/// Three periods, sampled every `2 pi / 64`.
const ORBITS: f64 = 3.0;
const SAMPLES_PER_ORBIT: f64 = 64.0;
const STRIDE: usize = 16;

fn members() -> Members {
    Members {
        sweeps: vec![Sweep::new("e", ECCENTRICITIES.to_vec())],
        n: ECCENTRICITIES.len(),
        ..Members::default()
    }
}

fn plan(method: Method, tolerances: Option<Tolerances>, threads: Option<usize>) -> Plan {
    Plan {
        t_span: (0.0, ORBITS * TAU),
        dt: TAU / SAMPLES_PER_ORBIT,
        method: Some(method),
        stride: Some(STRIDE),
        reductions: vec![],
        final_state: true,
        threads,
        tolerances,
    }
}

fn run(plan: &Plan) -> EnsembleResult {
    ensemble::run(catalog::find("kepler").unwrap(), &members(), plan, None).unwrap()
}

/// Member `i` built alone.
fn member(i: usize) -> Box<dyn physicskit::classical::model::DynSystem> {
    catalog::build(
        "kepler",
        [("e".to_string(), Value::Scalar(ECCENTRICITIES[i]))],
    )
    .unwrap()
}

/// The bits of the final states and trajectories.
fn bits(r: &EnsembleResult) -> Vec<u64> {
    let mut v: Vec<u64> = r.final_state.iter().map(|x| x.to_bits()).collect();
    v.extend(r.trajectory.iter().flatten().map(|x| x.to_bits()));
    v
}

/// Each member's largest state error after whole periods: the closed form returns every
/// orbit to its start (perihelion) after each period `2 pi sqrt(mu a^3 / k)`.
fn periodic_errors(r: &EnsembleResult) -> Vec<f64> {
    (0..ECCENTRICITIES.len())
        .map(|i| {
            let start = member(i).dynamical().state().to_vec();
            r.final_state
                .row(i)
                .iter()
                .zip(&start)
                .map(|(y, y0)| (y - y0).abs())
                .fold(0.0, f64::max)
        })
        .collect()
}

#[test]
fn members_run_at_the_plan_tolerances_bit_for_bit_on_any_thread_count() {
    let tight = Tolerances::new(1e-13, 1e-13).unwrap();
    for method in [Method::Taylor, Method::Dop853] {
        let one = run(&plan(method, Some(tight), Some(1)));
        let two = run(&plan(method, Some(tight), Some(2)));
        assert_eq!(bits(&one), bits(&two), "{method}: 1 and 2 threads");
        assert_eq!(one.method, method);
        // The tolerances reach the members: the default tolerances give other bits.
        let default = run(&plan(method, None, Some(2)));
        assert_ne!(bits(&one), bits(&default), "{method}: tolerances ignored");
        let p = plan(method, Some(tight), None);
        let trajectory = one.trajectory.as_ref().unwrap();
        for i in 0..ECCENTRICITIES.len() {
            let alone = member(i)
                .integrate(
                    p.t_span,
                    p.dt,
                    method,
                    IntegrateOptions {
                        sampling: Sampling::Stride(STRIDE),
                        tolerances: Some(tight),
                        ..IntegrateOptions::default()
                    },
                )
                .unwrap();
            let last = alone.y.nrows() - 1;
            assert_eq!(
                one.final_state.row(i),
                alone.y.row(last),
                "{method} member {i}"
            );
            assert_eq!(
                trajectory.index_axis(ndarray::Axis(0), i),
                alone.y,
                "{method} member {i}"
            );
            assert_eq!(one.t.as_ref().unwrap(), alone.t);
        }
    }
}

#[test]
fn tighter_tolerances_come_closer_to_the_closed_form() {
    let loose = Tolerances::new(1e-6, 1e-6).unwrap();
    let tight = Tolerances::new(1e-13, 1e-13).unwrap();
    for method in [Method::Taylor, Method::Dop853] {
        let loose_errors = periodic_errors(&run(&plan(method, Some(loose), None)));
        let tight_errors = periodic_errors(&run(&plan(method, Some(tight), None)));
        for (i, (&l, &t)) in loose_errors.iter().zip(&tight_errors).enumerate() {
            // Tolerances 1e7 times tighter. Measured, the error falls by 5e3 to 7e5 (taylor)
            // and 3e6 to 2e8 (dop853), to 2e-14 .. 2.5e-12 and 3e-12 .. 1.2e-11: 1e3 is the
            // smallest fall with a margin of 5, and 1e-9 the largest tight error with a margin
            // of about 100.
            assert!(
                t * 1e3 < l,
                "{method} member {i}: {t:e} at 1e-13, {l:e} at 1e-6"
            );
            assert!(t < 1e-9, "{method} member {i}: {t:e} at 1e-13");
        }
    }
}

#[test]
fn a_fixed_step_method_given_tolerances_is_refused_as_integrate_refuses_it() {
    let tol = Some(Tolerances::default());
    let alone = member(0)
        .integrate(
            (0.0, 1.0),
            0.01,
            Method::Yoshida4,
            IntegrateOptions {
                tolerances: tol,
                ..IntegrateOptions::default()
            },
        )
        .unwrap_err();
    let entry = catalog::find("kepler").unwrap();
    // Named, or the members' default (Kepler's is yoshida4): refused before any work.
    for method in [Some(Method::Yoshida4), None] {
        let p = Plan {
            method,
            ..plan(Method::Yoshida4, tol, None)
        };
        let err = ensemble::run(entry, &members(), &p, None).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidArgument { name, .. } if name == "tolerances"),
            "{err}"
        );
        assert_eq!(err.to_string(), alone.to_string());
        assert_eq!(
            ensemble::check(entry, &members(), &p)
                .unwrap_err()
                .to_string(),
            err.to_string()
        );
    }
    // What the front ends check their tolerances against: the named method, else the
    // members' default.
    let m = members();
    let source = ensemble::FromCatalogue::new(entry, &m).unwrap();
    let named = plan(Method::Taylor, tol, None);
    assert_eq!(ensemble::method(&source, &named).unwrap(), Method::Taylor);
    let unnamed = Plan {
        method: None,
        ..named
    };
    let default = member(0).default_method();
    assert_eq!(ensemble::method(&source, &unnamed).unwrap(), default);
}

#[test]
fn invalid_tolerances_are_refused_by_name_before_any_work() {
    let entry = catalog::find("kepler").unwrap();
    let bad = [
        (
            "rtol",
            Tolerances {
                rtol: 0.0,
                ..Tolerances::default()
            },
        ),
        (
            "rtol",
            Tolerances {
                rtol: f64::NAN,
                ..Tolerances::default()
            },
        ),
        (
            "atol",
            Tolerances {
                atol: -1e-9,
                ..Tolerances::default()
            },
        ),
        (
            "atol",
            Tolerances {
                atol: f64::INFINITY,
                ..Tolerances::default()
            },
        ),
        (
            "max_steps",
            Tolerances {
                max_steps: 0,
                ..Tolerances::default()
            },
        ),
    ];
    for (name, tol) in bad {
        let err =
            ensemble::check(entry, &members(), &plan(Method::Taylor, Some(tol), None)).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidParameter { name: n, .. } if n == name),
            "{name}: {err}"
        );
    }
}

#[test]
fn a_spent_step_budget_is_a_step_failure_of_the_member_that_spent_it() {
    // Three steps cannot cover three orbits (taylor takes some 40 steps an orbit at 1e-10).
    let tol = Tolerances {
        max_steps: 3,
        ..Tolerances::default()
    };
    let err = ensemble::run(
        catalog::find("kepler").unwrap(),
        &members(),
        &plan(Method::Taylor, Some(tol), Some(2)),
        None,
    )
    .unwrap_err();
    assert!(
        matches!(&err, Error::StepSizeTooSmall { reason, .. } if reason.starts_with("member 0: ")),
        "{err}"
    );
}
