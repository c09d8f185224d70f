//! The `taylor` method's members run in SIMD lanes on one shared Taylor form: each member's
//! final state and trajectory are its own `integrate`'s bit for bit, on one thread and on
//! two, for Kepler (members of different eccentricities: equal recurrences found by
//! comparison), Hénon–Heiles (per-member states: the same system) and the double pendulum
//! (swept angles), member counts that are not a multiple of the lanes (11, 37 and 10: lanes
//! that finish take the next member); a member that escapes fails with its own run's error,
//! named by index, beside members that do not.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Members, Plan, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::{Error, IntegrateOptions, Method, Sampling, Tolerances};

const STRIDE: usize = 7;

fn plan(t1: f64, dt: f64, threads: usize, tol: Option<f64>) -> Plan {
    Plan {
        t_span: (0.0, t1),
        dt,
        method: Some(Method::Taylor),
        stride: Some(STRIDE),
        reductions: vec![],
        final_state: true,
        threads: Some(threads),
        tolerances: tol.map(|t| Tolerances::new(t, t).unwrap()),
    }
}

/// Hénon–Heiles states at `E = 1/8` on `x = 0`, `n` of them, with `escaping` members at
/// `E = 0.565` (above the saddles' 1/6: they leave and run to infinity in finite time).
pub(super) fn henon_heiles_states(n: usize, escaping: &[usize]) -> Vec<f64> {
    (0..n)
        .flat_map(|m| {
            if escaping.contains(&m) {
                return [0.0, 0.0, 0.8, 0.7];
            }
            let y = -0.25 + 0.012 * m as f64;
            let px = 0.2 - 0.01 * m as f64;
            let v = 0.5 * y * y - y * y * y / 3.0;
            [0.0, y, px, (2.0 * (0.125 - v) - px * px).sqrt()]
        })
        .collect()
}

/// The three ensembles: catalogue name, members, span and output spacing.
fn ensembles() -> Vec<(&'static str, Members, f64, f64)> {
    let kepler = Members {
        sweeps: vec![Sweep::new(
            "e",
            (0..11).map(|i| 0.05 + 0.06 * i as f64).collect(),
        )],
        n: 11,
        ..Members::default()
    };
    let henon_heiles = Members {
        states: Some(henon_heiles_states(37, &[])),
        n: 37,
        ..Members::default()
    };
    let pendulum = Members {
        common: vec![("thetadot0".into(), Value::Vector(vec![0.0, 0.0]))],
        sweeps: vec![Sweep::new(
            "theta0[0]",
            (0..10).map(|i| -2.5 + 0.5 * i as f64).collect(),
        )],
        n: 10,
        ..Members::default()
    };
    vec![
        (
            "kepler",
            kepler,
            3.0 * std::f64::consts::TAU,
            std::f64::consts::TAU / 64.0,
        ),
        ("henon-heiles", henon_heiles, 40.0, 0.25),
        ("double-pendulum", pendulum, 5.0, 0.05),
    ]
}

#[test]
fn members_in_lanes_equal_their_own_integrate_on_one_and_two_threads() {
    for (name, members, t1, dt) in ensembles() {
        let entry = catalog::find(name).unwrap();
        for tol in [None, Some(1e-13)] {
            let one = ensemble::run(entry, &members, &plan(t1, dt, 1, tol), None).unwrap();
            let two = ensemble::run(entry, &members, &plan(t1, dt, 2, tol), None).unwrap();
            assert_eq!(one, two, "{name}, tol {tol:?}: 1 and 2 threads");
            let source = FromCatalogue::new(entry, &members).unwrap();
            let trajectory = one.trajectory.as_ref().unwrap();
            for i in 0..members.n {
                let alone = source
                    .build(i, 0.0)
                    .unwrap()
                    .integrate(
                        (0.0, t1),
                        dt,
                        Method::Taylor,
                        IntegrateOptions {
                            sampling: Sampling::Stride(STRIDE),
                            tolerances: tol.map(|t| Tolerances::new(t, t).unwrap()),
                            ..IntegrateOptions::default()
                        },
                    )
                    .unwrap();
                let last = alone.y.nrows() - 1;
                let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
                assert!(
                    one.final_state
                        .row(i)
                        .iter()
                        .zip(alone.y.row(last))
                        .all(|(a, b)| same(*a, *b)),
                    "{name}, tol {tol:?}, member {i}: final state"
                );
                assert!(
                    trajectory
                        .index_axis(ndarray::Axis(0), i)
                        .iter()
                        .zip(alone.y.iter())
                        .all(|(a, b)| same(*a, *b)),
                    "{name}, tol {tol:?}, member {i}: trajectory"
                );
                assert_eq!(one.steps[i], ((t1 / dt).round()) as usize, "{name}: steps");
            }
        }
    }
}

/// Members 5 and 9 of 12 escape: the ensemble reports member 5's error, as its own run
/// reports it, prefixed with its index; on two threads too.
#[test]
fn an_escaping_member_fails_with_its_own_error_beside_good_ones() {
    let entry = catalog::find("henon-heiles").unwrap();
    let members = Members {
        states: Some(henon_heiles_states(12, &[5, 9])),
        n: 12,
        ..Members::default()
    };
    let source = FromCatalogue::new(entry, &members).unwrap();
    let alone = source
        .build(5, 0.0)
        .unwrap()
        .integrate(
            (0.0, 40.0),
            0.25,
            Method::Taylor,
            IntegrateOptions {
                sampling: Sampling::FinalOnly,
                ..IntegrateOptions::default()
            },
        )
        .unwrap_err();
    let Error::StepSizeTooSmall { t, step, reason } = alone else {
        panic!("the escaping member ran: {alone}");
    };
    let want = Error::StepSizeTooSmall {
        t,
        step,
        reason: format!("member 5: {reason}"),
    };
    for threads in [1, 2] {
        let got =
            ensemble::run(entry, &members, &plan(40.0, 0.25, threads, None), None).unwrap_err();
        assert_eq!(got, want, "{threads} threads");
    }
}
