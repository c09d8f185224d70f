//! The catalogue's presentation facts hold for every entry: a title people can read, a pace
//! whose stated energy error a run at that pace keeps, a drawing its system can be drawn by.

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::{Drawing, Pace, PACE_CHECK_FRAMES};
use physicskit::classical::{IntegrateOptions, Sampling};

/// Every title is set, distinct, starts with a capital and carries none of the code's
/// spellings (the entry name's hyphens, an underscore, a path).
#[test]
fn titles_are_for_people() {
    let mut seen = std::collections::BTreeSet::new();
    for entry in SYSTEMS {
        let title = entry.presentation.title;
        assert!(
            title.chars().next().is_some_and(char::is_uppercase),
            "{}: title {title:?}",
            entry.name
        );
        for bad in ["_", "::", "-"] {
            assert!(!title.contains(bad), "{}: title {title:?}", entry.name);
        }
        assert!(seen.insert(title), "{}: title {title:?} twice", entry.name);
    }
}

/// A fixed pace keeps the energy error it states: `PACE_CHECK_FRAMES` frames (a minute at 60
/// frames a second) from the entry's defaults, with its method and step, keep the relative
/// energy error below its `energy_error`. That bound is what the lab tells its users; this is
/// the run that makes it true.
#[test]
fn fixed_paces_keep_their_energy_error() {
    let mut checked = 0;
    for entry in SYSTEMS {
        let Pace::Fixed {
            method,
            dt,
            steps_per_frame,
            energy_error,
        } = entry.presentation.pace
        else {
            continue;
        };
        assert!(
            entry.methods().any(|m| m == method),
            "{}: {method}",
            entry.name
        );
        let mut system = entry.build_from([]).unwrap();
        let steps = PACE_CHECK_FRAMES as usize * steps_per_frame as usize;
        // Every 100th sample: the error is checked along the run, not only at its end.
        let options = IntegrateOptions {
            sampling: Sampling::Stride(100),
            ..IntegrateOptions::default()
        };
        let run = system
            .integrate((0.0, steps as f64 * dt), dt, method, options)
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        let energy = run.energy.expect("the energy is stored");
        let e0 = energy[0];
        let worst = energy
            .iter()
            .map(|e| ((e - e0) / e0.abs().max(f64::MIN_POSITIVE)).abs())
            .fold(0.0, f64::max);
        assert!(
            worst < energy_error,
            "{}: {method} at dt = {dt}: relative energy error {worst:e} over \
             {PACE_CHECK_FRAMES} frames, the catalogue states < {energy_error:e}",
            entry.name
        );
        checked += 1;
    }
    assert!(
        checked > 0,
        "no entry has a fixed pace: the test checks nothing"
    );
}

/// A time-lapse's step is one the entry's default method takes, and its frames advance
/// faster than real time (else it is no time-lapse).
#[test]
fn time_lapses_run_faster_than_real_time() {
    for entry in SYSTEMS {
        let Pace::TimeLapse {
            dt,
            steps_per_frame,
        } = entry.presentation.pace
        else {
            continue;
        };
        // 60 frames a second: a frame is 1/60 s of real time.
        assert!(
            dt * f64::from(steps_per_frame) > 1.0 / 60.0,
            "{}",
            entry.name
        );
        let mut system = entry.build_from([]).unwrap();
        system
            .integrate(
                (0.0, dt * f64::from(steps_per_frame)),
                dt,
                entry.default_method,
                IntegrateOptions::default(),
            )
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
    }
}

/// Each drawing asks of its system what the system has: bobs and orbits need positions in
/// the plane, a field or chain a `[q, p]` state, a rolling body its shape's parameters.
#[test]
fn drawings_fit_their_systems() {
    for entry in SYSTEMS {
        let system = entry.build_from([]).unwrap();
        let state = system.dynamical().state().to_vec();
        let has = |name: &str| entry.params.iter().any(|p| p.name == name);
        match entry.presentation.drawing {
            Drawing::Bobs { .. } | Drawing::Hoop => {
                // The drawing's lengths have a unit: a parameter in metres, or the length of
                // the system's own that the positions are in units of (never both).
                let metres = entry.params.iter().any(|p| p.unit == "m");
                if let Drawing::Bobs { scale, .. } = entry.presentation.drawing {
                    assert!(metres != scale.is_some(), "{}: scale {scale:?}", entry.name);
                }
                let ndof = system.ndof().expect("a [q, p] or [q, qdot] state");
                let pos = system
                    .capabilities()
                    .positions(&state[..ndof])
                    .and_then(Result::ok)
                    .unwrap_or_default();
                assert!(
                    !pos.is_empty() && pos.len() % 2 == 0,
                    "{}: positions {pos:?}",
                    entry.name
                );
            }
            Drawing::Chain { .. } | Drawing::Field | Drawing::Orbit { .. } => {
                assert!(system.ndof().is_some(), "{}", entry.name);
            }
            Drawing::Rolling { shape } => {
                let needs: &[&str] = match shape {
                    physicskit::classical::model::Shape::Ellipsoid => &["a", "b", "c", "h"],
                    physicskit::classical::model::Shape::Disk => &["a"],
                };
                for name in needs {
                    assert!(has(name), "{}: no parameter {name}", entry.name);
                }
            }
            _ => {}
        }
    }
}

/// An entry that says its energy is not conserved does not conserve it: over one second from
/// the defaults with its default method, its `energy` moves by more than a millionth of
/// itself (far above any integrator's error at that length), so the front ends that hide the
/// energy error for it hide no conserved quantity.
#[test]
fn energies_said_not_conserved_are_not() {
    let mut checked = 0;
    for entry in SYSTEMS.iter().filter(|e| !e.presentation.energy_conserved) {
        let mut system = entry.build_from([]).unwrap();
        let run = system
            .integrate(
                (0.0, 1.0),
                1e-3,
                entry.default_method,
                IntegrateOptions::default(),
            )
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        let energy = run.energy.expect("the energy is stored");
        let (first, last) = (energy[0], energy[energy.len() - 1]);
        assert!(
            ((last - first) / first.abs().max(f64::MIN_POSITIVE)).abs() > 1e-6,
            "{}: energy {first} then {last}",
            entry.name
        );
        checked += 1;
    }
    assert!(checked > 0, "no entry says its energy is not conserved");
}
