//! Splitting-method members run in SIMD lanes (Kepler, Hénon–Heiles): each member's final
//! state and strided trajectory are its own `integrate`'s bit for bit, for every splitting
//! method, on one thread and on two, for member counts 1, 3, a lane width, twice it plus one
//! (so batches that do not fill their lanes), and members of different forces in one
//! ensemble (Kepler with swept `c_pn`: one group per value); a member that escapes fails with
//! its own run's error, named by index, beside members that do not.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Members, Plan, Sweep};
use physicskit::classical::symbolic::native_lanes;
use physicskit::classical::{Error, IntegrateOptions, Method, Sampling};
use std::f64::consts::TAU;

const STRIDE: usize = 7;

fn plan(t1: f64, dt: f64, method: Method, threads: usize) -> Plan {
    Plan {
        t_span: (0.0, t1),
        dt,
        method: Some(method),
        stride: Some(STRIDE),
        reductions: vec![],
        final_state: true,
        threads: Some(threads),
        tolerances: None,
    }
}

/// Hénon–Heiles states at `E = 1/8` on `x = 0`, `n` of them, with `escaping` members at
/// `E = 0.565` (above the saddles' 1/6: they leave and their states overflow).
fn henon_heiles_states(n: usize, escaping: &[usize]) -> Vec<f64> {
    (0..n)
        .flat_map(|m| {
            if escaping.contains(&m) {
                return [0.0, 0.0, 0.8, 0.7];
            }
            let y = -0.25 + 0.45 * m as f64 / n as f64;
            let px = 0.2 - 0.3 * m as f64 / n as f64;
            let v = 0.5 * y * y - y * y * y / 3.0;
            [0.0, y, px, (2.0 * (0.125 - v) - px * px).sqrt()]
        })
        .collect()
}

/// The ensembles of `n` members: catalogue name, members, span and step.
fn ensembles(n: usize) -> Vec<(&'static str, Members, f64, f64)> {
    let kepler = Members {
        sweeps: vec![Sweep::new(
            "e",
            (0..n).map(|i| 0.05 + 0.6 * i as f64 / n as f64).collect(),
        )],
        n,
        ..Members::default()
    };
    // Two forces (c_pn = 0 and -0.01) interleaved, and a perturbation through `powf`.
    let precessing = Members {
        common: vec![
            (
                "eps".into(),
                physicskit::classical::model::Value::Scalar(0.3),
            ),
            (
                "c_eps".into(),
                physicskit::classical::model::Value::Scalar(0.002),
            ),
        ],
        sweeps: vec![
            Sweep::new(
                "e",
                (0..n).map(|i| 0.1 + 0.5 * i as f64 / n as f64).collect(),
            ),
            Sweep::new("c_pn", (0..n).map(|i| -0.01 * (i % 2) as f64).collect()),
        ],
        n,
        ..Members::default()
    };
    let henon_heiles = Members {
        states: Some(henon_heiles_states(n, &[])),
        n,
        ..Members::default()
    };
    vec![
        ("kepler", kepler, 2.0 * TAU, TAU / 500.0),
        ("kepler", precessing, 2.0 * TAU, TAU / 500.0),
        ("henon-heiles", henon_heiles, 20.0, 0.02),
    ]
}

/// The splitting methods, read from the method table.
fn splitting_methods() -> Vec<Method> {
    Method::ALL
        .into_iter()
        .filter(|m| m.needs_separable())
        .collect()
}

#[test]
fn members_in_lanes_equal_their_own_integrate_on_one_and_two_threads() {
    let l = native_lanes();
    let methods = splitting_methods();
    assert!(methods.len() >= 7, "{methods:?}");
    for n in [1, 3, l, 2 * l + 1] {
        for (name, members, t1, dt) in ensembles(n) {
            let entry = catalog::find(name).unwrap();
            let source = FromCatalogue::new(entry, &members).unwrap();
            for &method in &methods {
                let one = ensemble::run(entry, &members, &plan(t1, dt, method, 1), None).unwrap();
                let two = ensemble::run(entry, &members, &plan(t1, dt, method, 2), None).unwrap();
                assert_eq!(one, two, "{name}, {method:?}, {n} members: 1 and 2 threads");
                let trajectory = one.trajectory.as_ref().unwrap();
                for i in 0..n {
                    let alone = source
                        .build(i, 0.0)
                        .unwrap()
                        .integrate(
                            (0.0, t1),
                            dt,
                            method,
                            IntegrateOptions {
                                sampling: Sampling::Stride(STRIDE),
                                ..IntegrateOptions::default()
                            },
                        )
                        .unwrap();
                    let last = alone.y.nrows() - 1;
                    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
                    assert_eq!(
                        bits(one.final_state.row(i).to_vec()),
                        bits(alone.y.row(last).to_vec()),
                        "{name}, {method:?}, {n} members, member {i}: final state"
                    );
                    let mine = trajectory.index_axis(ndarray::Axis(0), i);
                    assert_eq!(mine.dim(), alone.y.dim(), "{name}: trajectory shape");
                    assert_eq!(
                        bits(mine.iter().copied().collect()),
                        bits(alone.y.iter().copied().collect()),
                        "{name}, {method:?}, {n} members, member {i}: trajectory"
                    );
                    assert_eq!(one.steps[i], (t1 / dt).round() as usize, "{name}: steps");
                }
            }
        }
    }
}

/// Members 5 and 9 of 12 escape: the ensemble reports member 5's error, as its own run
/// reports it, prefixed with its index; on two threads too. The others' runs are unharmed:
/// without the escaping members' rows the same ensemble's final states are theirs.
#[test]
fn an_escaping_member_fails_with_its_own_error_beside_good_ones() {
    let entry = catalog::find("henon-heiles").unwrap();
    let members = Members {
        states: Some(henon_heiles_states(12, &[5, 9])),
        n: 12,
        ..Members::default()
    };
    let (t1, dt) = (40.0, 0.05);
    let source = FromCatalogue::new(entry, &members).unwrap();
    for method in splitting_methods() {
        let alone = source
            .build(5, 0.0)
            .unwrap()
            .integrate(
                (0.0, t1),
                dt,
                method,
                IntegrateOptions {
                    // The plan's sampling: the error names the first stored non-finite row.
                    sampling: Sampling::Stride(STRIDE),
                    ..IntegrateOptions::default()
                },
            )
            .unwrap_err();
        let Error::NonFinite { name, t } = alone else {
            panic!("{method:?}: the escaping member ran: {alone}");
        };
        let want = Error::NonFinite {
            name: format!("member 5: {name}"),
            t,
        };
        for threads in [1, 2] {
            let got =
                ensemble::run(entry, &members, &plan(t1, dt, method, threads), None).unwrap_err();
            assert_eq!(got, want, "{method:?}, {threads} threads");
        }
    }
}
