//! Sessions (`DynSystem::start`) against `integrate`: for every catalogue system and every
//! method it lists, frames of a session reach the bits of one `integrate` over the same steps,
//! and a refusal by one is a refusal by the other.

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::DynSystem;
use physicskit::classical::{Error, IntegrateOptions, Method};

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
                // No session for an adaptive method (it needs the end of its span): refused
                // with the system handed back unchanged.
                let Err(refused) = build(entry).start(method, DT) else {
                    panic!("{} {method}: a session of an adaptive method", entry.name)
                };
                assert!(matches!(refused.error, Error::UnsupportedMethod { .. }));
                assert_eq!(
                    refused.system.dynamical().state(),
                    build(entry).dynamical().state()
                );
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
