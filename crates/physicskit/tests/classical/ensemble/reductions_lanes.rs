//! Reductions of members run in SIMD lanes: each member's maximum energy error and first
//! event time equal those of its own `integrate` (every step stored, reduced by
//! `Reduction::reduce`, the member-by-member path's code) bit for bit, for Kepler (swept
//! eccentricities: groups by equal forces and equal Taylor recurrences) and Hénon–Heiles
//! (per-member states: the same system), by `yoshida4` and by `taylor`, for 1, 3, `L` and
//! `2L + 1` members (`L` the lanes), on one thread and on two; also, by the splitting method,
//! pendulums, oscillators of two masses and Toda rings (whose energies the lanes compute, the
//! rings' over slices). A plan that mixes them with a
//! chaos reduction (run member by member on its own flow; `yoshida4`, as the chaos
//! reductions need a fixed step) gives the same numbers, and a member whose energy stops
//! being finite fails with its own run's error.

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{
    self, Condition, Direction, Event, FromCatalogue, MemberRun, MemberSource, Members, Plan,
    Reduction, Sweep,
};
use physicskit::classical::symbolic::native_lanes;
use physicskit::classical::{Error, IntegrateOptions, Method, Sampling, TimeGrid};

use super::taylor_lanes::henon_heiles_states;

/// `q[0]` crosses 0 upward.
const CROSSING: Event = Event {
    index: 0,
    condition: Condition::Crosses {
        value: 0.0,
        direction: Direction::Rising,
    },
};

/// `n` Kepler orbits of eccentricities 0.05 to about 0.65, over two periods.
fn kepler(n: usize) -> Members {
    Members {
        sweeps: vec![Sweep::new(
            "e",
            (0..n).map(|i| 0.05 + 0.6 * i as f64 / n as f64).collect(),
        )],
        n,
        ..Members::default()
    }
}

/// `n` Hénon–Heiles members at `E = 1/8` on `x = 0`, and `escaping` members at `E = 0.565`
/// (above the saddles' 1/6: they leave and run to infinity in finite time).
fn henon_heiles(n: usize, escaping: &[usize]) -> Members {
    Members {
        states: Some(henon_heiles_states(n, escaping)),
        n,
        ..Members::default()
    }
}

/// System, members, span and step for `method`: a few hundred steps of the splitting method,
/// a few dozen outputs of `taylor`.
fn workloads(n: usize, method: Method) -> Vec<(&'static str, Members, f64, f64)> {
    let taylor = method == Method::Taylor;
    let period = std::f64::consts::TAU;
    let mut all = vec![
        (
            "kepler",
            kepler(n),
            2.0 * period,
            period / if taylor { 32.0 } else { 200.0 },
        ),
        (
            "henon-heiles",
            henon_heiles(n, &[]),
            20.0,
            if taylor { 0.5 } else { 0.05 },
        ),
    ];
    if !taylor {
        // Two forces (or masses) interleaved; every member crosses `q = 0` upward by t = 20
        // (periods 2 pi sqrt(m) <= 10 for the oscillators; the widest pendulum swing, 2.8 rad
        // at g/l = 1, about 17).
        let spread = |a: f64, b: f64| (0..n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
        let alternating = |x: f64, y: f64| (0..n).map(|i| if i % 2 == 0 { x } else { y }).collect();
        let swept = |sweeps: Vec<Sweep>| Members {
            sweeps,
            n,
            ..Members::default()
        };
        all.extend([
            (
                "pendulum",
                swept(vec![
                    Sweep::new("q0", spread(0.2, 2.8)),
                    Sweep::new("g_over_l", alternating(1.0, 2.0)),
                ]),
                20.0,
                0.05,
            ),
            (
                "harmonic-oscillator",
                swept(vec![
                    Sweep::new("q0", spread(-1.0, 1.0)),
                    Sweep::new("m", alternating(1.0, 2.5)),
                ]),
                20.0,
                0.05,
            ),
            (
                "toda",
                swept(vec![Sweep::new("a", alternating(1.0, 1.5))]),
                20.0,
                0.05,
            ),
        ]);
    }
    all
}

fn plan(t1: f64, dt: f64, method: Method, reductions: Vec<Reduction>, threads: usize) -> Plan {
    Plan {
        t_span: (0.0, t1),
        dt,
        method: Some(method),
        stride: None,
        reductions,
        final_state: true,
        threads: Some(threads),
        tolerances: None,
    }
}

/// Member `i`'s reductions by its own run: `integrate` storing every step (and energies),
/// reduced by `Reduction::reduce`.
fn own_reductions(
    source: &FromCatalogue<'_>,
    i: usize,
    plan: &Plan,
    method: Method,
) -> (Vec<f64>, Vec<f64>) {
    let mut system = source.build(i, 0.0).unwrap();
    let state0 = system.dynamical().state().to_vec();
    let result = system
        .integrate(
            plan.t_span,
            plan.dt,
            method,
            IntegrateOptions {
                sampling: Sampling::All,
                ..IntegrateOptions::default()
            },
        )
        .unwrap();
    let grid = TimeGrid::new(plan.t_span, plan.dt).unwrap();
    let run = MemberRun {
        system: &*system,
        method,
        result: &result,
        state0: &state0,
        grid: &grid,
    };
    let values = plan
        .reductions
        .iter()
        .map(|r| r.reduce(&run, None, 1024).unwrap())
        .collect();
    (values, result.final_state().to_vec())
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Runs `reductions` on every workload and member count, on one and two threads, and checks
/// each member's reductions and final state against its own run's, bit for bit.
fn check_against_own_runs(method: Method, reductions: &[Reduction]) {
    let l = native_lanes();
    for n in [1, 3, l, 2 * l + 1] {
        for (name, members, t1, dt) in workloads(n, method) {
            let entry = catalog::find(name).unwrap();
            let source = FromCatalogue::new(entry, &members).unwrap();
            let plan1 = plan(t1, dt, method, reductions.to_vec(), 1);
            let out = ensemble::run(entry, &members, &plan1, None).unwrap();
            let two = ensemble::run(
                entry,
                &members,
                &plan(t1, dt, method, reductions.to_vec(), 2),
                None,
            )
            .unwrap();
            // By bits: an event that never happens is NaN, which `==` calls unequal.
            let columns = |r: &ensemble::EnsembleResult| -> Vec<u64> {
                let reduced = r.reductions.iter().flat_map(|(_, v)| v.iter());
                r.final_state
                    .iter()
                    .chain(reduced)
                    .map(|x| x.to_bits())
                    .collect()
            };
            assert_eq!(
                columns(&out),
                columns(&two),
                "{name}, {n} members: 1 and 2 threads"
            );
            let mut events = 0;
            for i in 0..n {
                let (values, last) = own_reductions(&source, i, &plan1, method);
                let got: Vec<f64> = out.reductions.iter().map(|(_, v)| v[i]).collect();
                let what = format!("{name}, {}, {n} members, member {i}", method.name());
                assert_eq!(bits(&got), bits(&values), "{what}: {got:?} vs {values:?}");
                assert_eq!(
                    bits(&out.final_state.row(i).to_vec()),
                    bits(&last),
                    "{what}"
                );
                events += usize::from(
                    reductions
                        .iter()
                        .zip(&values)
                        .any(|(r, v)| matches!(r, Reduction::FirstEvent(_)) && !v.is_nan()),
                );
            }
            // The crossing happens within two Kepler periods and within t = 20 of
            // Hénon–Heiles for most members: the comparison is of located times, not of
            // NaNs.
            if reductions.contains(&Reduction::FirstEvent(CROSSING)) {
                assert!(2 * events > n, "{name}, {n} members: {events} crossings");
            }
        }
    }
}

#[test]
fn energy_errors_and_events_in_lanes_equal_each_members_own_run() {
    for method in [Method::Yoshida4, Method::Taylor] {
        check_against_own_runs(
            method,
            &[Reduction::MaxEnergyError, Reduction::FirstEvent(CROSSING)],
        );
    }
}

/// The energy error alone: the splitting lanes fold it themselves and record only the last
/// step, the `taylor` lanes report every output as before; the same numbers either way.
#[test]
fn the_energy_error_alone_equals_each_members_own_run() {
    for method in [Method::Yoshida4, Method::Taylor] {
        check_against_own_runs(method, &[Reduction::MaxEnergyError]);
    }
}

/// The chaos reductions need a fixed-step flow (the `taylor` method is refused for them, by
/// the ensemble as by `max_lyapunov`), so the mixed plan runs by `yoshida4`.
#[test]
fn a_chaos_reduction_beside_them_gives_the_same_numbers() {
    check_against_own_runs(
        Method::Yoshida4,
        &[
            Reduction::MaxLyapunov {
                renormalize_every: 10,
            },
            Reduction::MaxEnergyError,
            Reduction::FirstEvent(CROSSING),
        ],
    );
}

/// Without an event, the energy error is the only reduction the lanes see beside a chaos
/// reduction (run on its own flow), so they fold it themselves: the same numbers again.
#[test]
fn the_folded_energy_error_beside_a_chaos_reduction_gives_the_same_numbers() {
    check_against_own_runs(
        Method::Yoshida4,
        &[
            Reduction::MaxLyapunov {
                renormalize_every: 10,
            },
            Reduction::MaxEnergyError,
        ],
    );
}

/// Members 1 and 4 of 6 escape: their energies stop being finite, so the ensemble reports
/// member 1's error as its own run (every step stored, with energies) reports it.
#[test]
fn a_member_whose_energy_blows_up_fails_with_its_own_error() {
    let entry = catalog::find("henon-heiles").unwrap();
    let members = henon_heiles(6, &[1, 4]);
    let source = FromCatalogue::new(entry, &members).unwrap();
    for (method, dt) in [(Method::Yoshida4, 0.05), (Method::Taylor, 0.25)] {
        let alone = source
            .build(1, 0.0)
            .unwrap()
            .integrate(
                (0.0, 40.0),
                dt,
                method,
                IntegrateOptions {
                    sampling: Sampling::All,
                    ..IntegrateOptions::default()
                },
            )
            .unwrap_err();
        // The ensemble names the member in the error (`in_member`).
        let want = match alone {
            Error::NonFinite { name, t } => Error::NonFinite {
                name: format!("member 1: {name}"),
                t,
            },
            Error::StepSizeTooSmall { t, step, reason } => Error::StepSizeTooSmall {
                t,
                step,
                reason: format!("member 1: {reason}"),
            },
            other => panic!(
                "{}: unexpected error of the member's own run: {other}",
                method.name()
            ),
        };
        for threads in [1, 2] {
            let plan = plan(40.0, dt, method, vec![Reduction::MaxEnergyError], threads);
            let got = ensemble::run(entry, &members, &plan, None).unwrap_err();
            assert_eq!(got, want, "{}, {threads} threads", method.name());
        }
    }
}
