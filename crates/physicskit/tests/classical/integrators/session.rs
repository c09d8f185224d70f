//! Sessions (`DynSystem::start`) against `integrate`: for every catalogue system and every
//! method it lists, frames of a session reach the bits of one `integrate` over the same steps
//! (for an adaptive method, up to `integrate`'s last internal step, where it lands on its
//! end), and a refusal by one is a refusal by the other.

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::{DynSystem, SystemEntry};
use physicskit::classical::{Error, IntegrateOptions, Method, Sampling, Tolerances};

/// Steps compared per system and method: enough for the splitting methods' cached force and
/// an implicit Lagrangian run's canonical state to be carried across several frames.
const STEPS: usize = 40;

/// Frames the session advances in, summing to [`STEPS`]; uneven, with an empty one.
const FRAMES: [usize; 5] = [1, 16, 0, 7, 16];

/// A step small enough for every catalogue system's defaults to stay finite over [`STEPS`].
const DT: f64 = 1e-3;

fn build(entry: &physicskit::classical::model::SystemEntry) -> Box<dyn DynSystem> {
    entry
        .build_from([])
        .unwrap_or_else(|e| panic!("{}: {e}", entry.name))
}

#[test]
fn frames_of_a_session_have_the_bits_of_one_integrate() {
    assert_eq!(FRAMES.iter().sum::<usize>(), STEPS);
    let mut compared = 0;
    for entry in SYSTEMS {
        for method in entry.methods() {
            if method.is_adaptive() {
                // Compared up to integrate's last internal step, below.
                continue;
            }
            let mut reference = build(entry);
            let expected = reference.integrate(
                (0.0, STEPS as f64 * DT),
                DT,
                method,
                IntegrateOptions::final_only(),
            );
            let started = build(entry).start(method, DT);
            let (expected, mut session) = match (expected, started) {
                (Ok(r), Ok(s)) => (r, s),
                (Err(_), Err(refused)) => {
                    // Refused alike, and the system comes back unchanged.
                    assert_eq!(
                        refused.system.dynamical().state(),
                        build(entry).dynamical().state()
                    );
                    continue;
                }
                (a, b) => panic!(
                    "{} {}: integrate {:?}, start {:?}",
                    entry.name,
                    method.name(),
                    a.err(),
                    b.err()
                ),
            };
            for n in FRAMES {
                session.advance(n).unwrap();
            }
            let last = expected.y.row(expected.y.nrows() - 1).to_vec();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(session.state()),
                bits(&last),
                "{} {}",
                entry.name,
                method.name()
            );
            assert_eq!(session.t(), reference.dynamical().t());
            assert_eq!(session.steps(), STEPS as u64);
            // Given back, the system holds the session's state.
            let back = session.into_system();
            assert_eq!(bits(back.dynamical().state()), bits(&last));
            compared += 1;
        }
    }
    // Every system runs with at least rk4: fewer comparisons means the loop skipped some.
    assert!(compared >= SYSTEMS.len(), "{compared} comparisons");
}

#[test]
fn restart_is_a_new_session_and_set_dt_continues_the_run() {
    let entry = physicskit::classical::catalog::find("double-pendulum").unwrap();
    let state0 = build(entry).dynamical().state().to_vec();
    for method in [Method::Rk4, Method::ImplicitMidpoint] {
        let mut session = build(entry).start(method, DT).unwrap();
        session.advance(25).unwrap();
        session.restart(Some(&state0), 0.0).unwrap();
        session.advance(10).unwrap();
        let mut fresh = build(entry).start(method, DT).unwrap();
        fresh.advance(10).unwrap();
        assert_eq!(session.state(), fresh.state(), "{}", method.name());

        // Halving dt at t = 10 dt: the next 20 steps are an integrate from there.
        session.set_dt(DT / 2.0).unwrap();
        session.advance(20).unwrap();
        let mut reference = build(entry);
        reference
            .integrate((0.0, 10.0 * DT), DT, method, IntegrateOptions::final_only())
            .unwrap();
        let t = reference.dynamical().t();
        let r = reference
            .integrate(
                (t, t + 10.0 * DT),
                DT / 2.0,
                method,
                IntegrateOptions::final_only(),
            )
            .unwrap();
        if method == Method::Rk4 {
            // On [q, qdot] the two runs hold the same state at the switch.
            assert_eq!(session.state(), r.y.row(r.y.nrows() - 1).to_vec());
        } else {
            // The session keeps p across the switch where two integrate calls convert
            // p -> qdot -> p: equal up to that rounding (a few ulps of states of order 1,
            // amplified over 20 steps of a chaotic system by far less than 1e3).
            for (a, b) in session.state().iter().zip(r.y.row(r.y.nrows() - 1)) {
                assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
        }
    }
}

#[test]
fn refusals_keep_the_system_and_the_run() {
    let entry = physicskit::classical::catalog::find("double-pendulum").unwrap();
    // A splitting method on a Lagrangian system, a step that is not positive.
    for (method, dt) in [
        (Method::Verlet, DT),
        (Method::Rk4, 0.0),
        (Method::Rk4, f64::NAN),
    ] {
        let refused = build(entry).start(method, dt).unwrap_err();
        assert_eq!(
            refused.system.dynamical().state(),
            build(entry).dynamical().state()
        );
    }
    let mut session = build(entry).start(Method::Rk4, DT).unwrap();
    session.advance(5).unwrap();
    let (state, t) = (session.state().to_vec(), session.t());
    assert!(session.set_dt(-1.0).is_err());
    assert!(session.restart(Some(&[f64::NAN; 4]), 0.0).is_err());
    assert!(session.restart(Some(&[0.0; 3]), 0.0).is_err());
    assert_eq!((session.state(), session.t()), (&state[..], t));
    session.advance(1).unwrap();
    assert_eq!(session.steps(), 6);
}

/// The output spacing of the adaptive runs: a power of two, so every output time
/// `t0 + i dt` is exact and a session whose spacing changes reaches the same times.
const ADAPTIVE_DT: f64 = 1.0 / 64.0;

/// The span of the `integrate` the adaptive sessions are compared with: eight time units,
/// far beyond the compared samples (`STEPS` of them, 0.625), so integrate's last internal
/// step (shortened to land on 8) and dop853's first (capped at the span) are not the ones
/// that produce the compared samples. No catalogue system takes internal steps of 7 time
/// units at these tolerances.
const ADAPTIVE_SPAN: f64 = 8.0;

/// Tolerances other than the defaults, so a session that ignored them would not match.
fn tolerances() -> Tolerances {
    Tolerances::new(1e-9, 1e-11).unwrap()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// `integrate` of `entry` with `method` at `tolerances` over [`ADAPTIVE_SPAN`], every sample.
fn integrate_adaptive(
    entry: &SystemEntry,
    method: Method,
    tolerances: Tolerances,
) -> physicskit::classical::Result<physicskit::classical::SimulationResult> {
    build(entry).integrate(
        (0.0, ADAPTIVE_SPAN),
        ADAPTIVE_DT,
        method,
        IntegrateOptions {
            sampling: Sampling::All,
            tolerances: Some(tolerances),
            ..IntegrateOptions::default()
        },
    )
}

#[test]
fn adaptive_sessions_have_the_bits_of_integrate_before_its_last_step() {
    let mut compared = 0;
    for entry in SYSTEMS {
        // Every adaptive method: those the entry takes are compared sample by sample; taylor
        // on a system without a Taylor form is refused by both, with one message.
        for method in Method::ALL.into_iter().filter(|m| m.is_adaptive()) {
            let expected = integrate_adaptive(entry, method, tolerances());
            let started = build(entry).start_with(method, ADAPTIVE_DT, Some(tolerances()));
            if !entry.methods().any(|m| m == method) {
                let (Err(a), Err(b)) = (expected, started) else {
                    panic!("{} {method}: not listed, yet run", entry.name)
                };
                assert_eq!(
                    a.to_string(),
                    b.error.to_string(),
                    "{} {method}",
                    entry.name
                );
                assert_eq!(
                    b.system.dynamical().state(),
                    build(entry).dynamical().state()
                );
                continue;
            }
            let expected = expected.unwrap_or_else(|e| panic!("{} {method}: {e}", entry.name));
            let mut session =
                started.unwrap_or_else(|r| panic!("{} {method}: {}", entry.name, r.error));
            assert_eq!(session.tolerances(), Some(tolerances()));
            let mut done = 0;
            for n in FRAMES {
                session.advance(n).unwrap();
                done += n;
                assert_eq!(
                    bits(session.state()),
                    bits(&expected.y.row(done).to_vec()),
                    "{} {method} after {done} samples",
                    entry.name
                );
                assert_eq!(session.t(), expected.t[done]);
            }
            assert_eq!(session.steps(), STEPS as u64);
            compared += 1;
        }
    }
    // dop853 runs on every system: fewer comparisons means the loop skipped some.
    assert!(compared > SYSTEMS.len(), "{compared} comparisons");
}

#[test]
fn adaptive_set_dt_changes_only_the_output_spacing_and_restart_starts_afresh() {
    let mut told_apart = std::collections::HashSet::new();
    let mut adaptive = std::collections::HashSet::new();
    for entry in SYSTEMS {
        for method in entry.methods().filter(|m| m.is_adaptive()) {
            let start = || {
                build(entry)
                    .start_with(method, ADAPTIVE_DT, Some(tolerances()))
                    .unwrap()
            };
            let what = format!("{} {method}", entry.name);
            adaptive.insert(method);
            // 16 samples, then 8 at twice the spacing: the internal steps are those of 32
            // samples at the first spacing, and the output time (exact) is the same.
            let mut switched = start();
            switched.advance(16).unwrap();
            switched.set_dt(2.0 * ADAPTIVE_DT).unwrap();
            assert_eq!(switched.steps(), 0);
            switched.advance(8).unwrap();
            let mut straight = start();
            straight.advance(32).unwrap();
            assert_eq!(switched.t(), straight.t(), "{what}");
            assert_eq!(bits(switched.state()), bits(straight.state()), "{what}");

            // A restart where the run is (its state, its clock) is a new session there, not
            // the run continued: the stepper starts afresh.
            let (state, t) = (straight.state().to_vec(), straight.t());
            straight.restart(None, t).unwrap();
            straight.advance(10).unwrap();
            let mut system = build(entry);
            system.reset(Some(&state), t).unwrap();
            let mut fresh = system
                .start_with(method, ADAPTIVE_DT, Some(tolerances()))
                .unwrap();
            fresh.advance(10).unwrap();
            assert_eq!(bits(straight.state()), bits(fresh.state()), "{what}");
            // ... which is not what the run continued would give (else the check above
            // could not tell): the continued run stepped from its internal steps. Both can
            // agree to the last bit where the steps are exact to rounding (a state at rest, as
            // the sine-Gordon chain's zero state; Kepler's circular orbit, whose coordinates
            // are entire functions of time, at a high Taylor order), so the difference is
            // required of some system for each method, not of every one.
            let mut continued = start();
            continued.advance(42).unwrap();
            if bits(continued.state()) != bits(fresh.state()) {
                told_apart.insert(method);
            }

            // Back to the initial state at 0: the first run's bits again.
            let state0 = build(entry).dynamical().state().to_vec();
            straight.restart(Some(&state0), 0.0).unwrap();
            straight.advance(32).unwrap();
            assert_eq!(bits(switched.state()), bits(straight.state()), "{what}");
        }
    }
    assert_eq!(
        told_apart, adaptive,
        "methods whose restart no system told apart"
    );
}

#[test]
fn hostile_tolerances_are_refused_as_integrate_refuses_them() {
    let kepler = physicskit::classical::catalog::find("kepler").unwrap();
    let pendulum = physicskit::classical::catalog::find("double-pendulum").unwrap();
    let default = Tolerances::default();
    let mut refusals = 0;
    for entry in [kepler, pendulum] {
        for method in [Method::Dop853, Method::Taylor, Method::Rk4] {
            for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, 0.0, -1e-8, 1e300] {
                for tol in [
                    Tolerances {
                        rtol: bad,
                        ..default
                    },
                    Tolerances {
                        atol: bad,
                        ..default
                    },
                ] {
                    let integrated = integrate_adaptive(entry, method, tol);
                    let started = build(entry).start_with(method, ADAPTIVE_DT, Some(tol));
                    let what = format!("{} {method} {tol:?}", entry.name);
                    match (integrated, started) {
                        (Err(a), Err(b)) => {
                            assert_eq!(a.to_string(), b.error.to_string(), "{what}");
                            assert!(
                                matches!(
                                    b.error,
                                    Error::InvalidParameter { .. } | Error::InvalidArgument { .. }
                                ),
                                "{what}: {}",
                                b.error
                            );
                            assert_eq!(
                                b.system.dynamical().state(),
                                build(entry).dynamical().state()
                            );
                            refusals += 1;
                        }
                        // A huge tolerance is valid for dop853 (its steps then grow until
                        // the run blows up) and for taylor's atol (under relative control):
                        // accepted by both, whatever the run then does.
                        (integrated, Ok(_)) => {
                            assert_eq!(bad, 1e300, "{what}");
                            assert!(
                                !matches!(
                                    integrated,
                                    Err(Error::InvalidParameter { .. }
                                        | Error::InvalidArgument { .. })
                                ),
                                "{what}: {:?}",
                                integrated.err()
                            );
                        }
                        (a, b) => panic!("{what}: integrate {:?}, start {:?}", a.err(), b.err()),
                    }
                }
            }
        }
    }
    // rk4 refuses any tolerances (6 values, both fields, 2 systems); dop853 and taylor every
    // non-finite or non-positive value (5 of 6); taylor also rtol = 1e300.
    assert_eq!(refusals, 6 * 2 * 2 + 5 * 2 * 2 * 2 + 2);
}
