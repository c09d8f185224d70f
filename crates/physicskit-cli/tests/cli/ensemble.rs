//! `ensemble`: the npz read back (ndarray-npy's reader) equals the library's ensemble bit for
//! bit and is shaped by the grid; bad members are refused by index with no file left.

use std::fs::File;

use ndarray::{Array1, Array2, Array3, ArrayD};
use ndarray_npy::NpzReader;
use physicskit::classical::catalog;
use physicskit::classical::ensemble::{
    self, Condition, Direction, Event, Members, Plan, Reduction, Sweep,
};

use crate::common::{entries, run_in, scratch, stderr};

/// Runs `ensemble harmonic-oscillator ARGS --dt 0.01 --out e.npz` in `dir`.
fn oscillator(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    let mut all = vec!["ensemble", "harmonic-oscillator"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--dt", "0.01", "--out", "e.npz"]);
    run_in(dir, &all)
}

#[test]
fn the_npz_is_the_library_ensemble_shaped_by_the_grid() {
    let dir = scratch();
    let out = oscillator(
        dir.path(),
        &[
            "--grid",
            "q0=0.5:1.5:3",
            "--grid",
            "k=1:4:2",
            "--set",
            "p0=0",
            "--event",
            "x=falling:0:0",
            "--energy-error",
            "--stride",
            "50",
            "--t1",
            "3",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mut npz = NpzReader::new(File::open(dir.path().join("e.npz")).unwrap()).unwrap();
    let final_state: ArrayD<f64> = npz.by_name("final_state.npy").unwrap();
    let trajectory: ArrayD<f64> = npz.by_name("trajectory.npy").unwrap();
    let event: Array2<f64> = npz.by_name("event_x.npy").unwrap();
    let energy: Array2<f64> = npz.by_name("max_energy_error.npy").unwrap();
    let grid_1: Array1<f64> = npz.by_name("grid_1.npy").unwrap();
    assert_eq!(final_state.shape(), &[3, 2, 2]);
    assert_eq!(trajectory.shape(), &[3, 2, 7, 2]);
    assert_eq!(grid_1.to_vec(), vec![1.0, 4.0]);
    // The same members through the library: q0 slowest, k fastest (C order).
    let members = Members {
        common: vec![],
        sweeps: vec![
            Sweep::new("q0", vec![0.5, 0.5, 1.0, 1.0, 1.5, 1.5]),
            Sweep::new("k", vec![1.0, 4.0, 1.0, 4.0, 1.0, 4.0]),
        ],
        states: None,
        n: 6,
    };
    let plan = Plan {
        t_span: (0.0, 3.0),
        dt: 0.01,
        method: None,
        stride: Some(50),
        reductions: vec![
            Reduction::MaxEnergyError,
            Reduction::FirstEvent(Event {
                index: 0,
                condition: Condition::Crosses {
                    value: 0.0,
                    direction: Direction::Falling,
                },
            }),
        ],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let lib = ensemble::run(entry, &members, &plan, None).unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let lib_traj: &Array3<f64> = lib.trajectory.as_ref().unwrap();
    assert_eq!(
        bits(final_state.as_slice().unwrap()),
        bits(lib.final_state.as_slice().unwrap())
    );
    assert_eq!(
        bits(trajectory.as_slice().unwrap()),
        bits(lib_traj.as_slice().unwrap())
    );
    assert_eq!(
        bits(energy.as_slice().unwrap()),
        bits(lib.reductions[0].1.as_slice().unwrap())
    );
    assert_eq!(
        bits(event.as_slice().unwrap()),
        bits(lib.reductions[1].1.as_slice().unwrap())
    );
}

/// [`oscillator_fails_with`] over `grid`.
fn oscillator_fails(grid: &str) -> String {
    oscillator_fails_with(&["--grid", grid])
}

/// Runs the oscillator's ensemble with `args` for 1 s, which must fail with status 2 and leave
/// no file; returns stderr.
fn oscillator_fails_with(args: &[&str]) -> String {
    let dir = scratch();
    let mut all = args.to_vec();
    all.extend_from_slice(&["--t1", "1"]);
    let out = oscillator(dir.path(), &all);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(entries(dir.path()).is_empty());
    stderr(&out)
}

#[test]
fn a_bad_member_is_named_and_no_file_is_left() {
    // m = 0 for the first member: out of range.
    let message = oscillator_fails("m=0:1:3");
    assert!(message.contains("member 0: m"), "{message}");
    let message = oscillator_fails("q0=0:1:x");
    assert!(message.contains("NAME=A:B:N"), "{message}");
    // 1e11 members need 800 GB for their swept values alone: refused before allocating (it
    // aborted on the failed allocation before), naming the members; 2^64 - 1 likewise.
    for n in ["100000000000", "18446744073709551615"] {
        let message = oscillator_fails(&format!("q0=0:1:{n}"));
        assert!(message.contains("members"), "{n}: {message}");
    }
}

#[test]
fn chaos_reductions_are_the_library_ones() {
    let dir = scratch();
    let out = run_in(
        dir.path(),
        &[
            "ensemble",
            "henon-heiles",
            "--grid",
            "q0[1]=-0.2:0.2:3",
            "--set",
            "p0=0.4,0.1",
            "--max-lyapunov",
            "--sali",
            "--renormalize-every",
            "5",
            "--dt",
            "0.05",
            "--t1",
            "20",
            "--out",
            "e.npz",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mut npz = NpzReader::new(File::open(dir.path().join("e.npz")).unwrap()).unwrap();
    let lyapunov: Array1<f64> = npz.by_name("max_lyapunov.npy").unwrap();
    let sali: Array1<f64> = npz.by_name("sali.npy").unwrap();
    let members = Members {
        common: vec![(
            "p0".into(),
            physicskit::classical::model::Value::Vector(vec![0.4, 0.1]),
        )],
        sweeps: vec![Sweep::new("q0[1]", vec![-0.2, 0.0, 0.2])],
        states: None,
        n: 3,
    };
    let plan = Plan {
        t_span: (0.0, 20.0),
        dt: 0.05,
        method: None,
        stride: None,
        reductions: vec![
            Reduction::MaxLyapunov {
                renormalize_every: 5,
            },
            Reduction::Sali {
                renormalize_every: 5,
            },
        ],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let entry = catalog::find("henon-heiles").unwrap();
    let lib = ensemble::run(entry, &members, &plan, None).unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(lyapunov.as_slice().unwrap()),
        bits(lib.reductions[0].1.as_slice().unwrap())
    );
    assert_eq!(
        bits(sali.as_slice().unwrap()),
        bits(lib.reductions[1].1.as_slice().unwrap())
    );
}

/// `ensemble`'s chaos options: a bad `--renormalize-every` names the flag, the flag without
/// `--max-lyapunov` or `--sali` is refused rather than ignored, and SALI with a method the
/// system cannot take is refused; one error line, exit 2, no file each time.
#[test]
fn bad_chaos_options_name_their_flag() {
    let chaos = |extra: &[&'static str]| {
        let mut args = vec![
            "ensemble",
            "harmonic-oscillator",
            "--grid",
            "q0=0.5:1:2",
            "--dt",
            "0.1",
            "--t1",
            "1",
            "--out",
            "e.npz",
        ];
        args.extend_from_slice(extra);
        crate::errors::fails(&args)
    };
    for bad in [
        "0",
        "-1",
        "nan",
        "inf",
        "1e23",
        "18446744073709551616",
        "2.5",
    ] {
        let err = chaos(&["--max-lyapunov", "--renormalize-every", bad]);
        assert!(
            err.contains(&format!("invalid value `{bad}` for `--renormalize-every`")),
            "{bad}: {err}"
        );
    }
    let err = chaos(&["--renormalize-every", "5"]);
    assert!(
        err.contains("--renormalize-every") && err.contains("--max-lyapunov"),
        "{err}"
    );
    let err = crate::errors::fails(&[
        "ensemble",
        "double-pendulum",
        "--grid",
        "theta0[0]=0.1:0.2:2",
        "--sali",
        "--method",
        "yoshida4",
        "--dt",
        "0.01",
        "--t1",
        "0.1",
        "--out",
        "e.npz",
    ]);
    assert!(
        err.contains("yoshida4") && err.contains("double-pendulum"),
        "{err}"
    );
}

/// `--threads` outside 1 to the library's `MAX_THREADS` is refused with the flag's name and
/// its limit, before any thread starts and with no file left; the help states the limit.
#[test]
fn thread_counts_beyond_the_library_limit_are_refused() {
    let limit = ensemble::MAX_THREADS;
    for bad in [0, limit + 1, usize::MAX] {
        let message = oscillator_fails_with(&["--grid", "q0=0:1:3", "--threads", &bad.to_string()]);
        assert!(message.contains("threads"), "{bad}: {message}");
        if bad > 0 {
            assert!(message.contains(&limit.to_string()), "{bad}: {message}");
        }
    }
    let help = crate::common::help(&["ensemble"]);
    assert!(help.contains(&format!("1 to {limit}")), "{help}");
}

/// The help gives the default interval and the SALI threshold of the library's constants.
#[test]
fn help_states_the_library_constants() {
    let help = crate::common::help(&["ensemble"]);
    let every = physicskit::classical::analysis::lyapunov::DEFAULT_RENORMALIZE_EVERY;
    let threshold = physicskit::classical::analysis::sali::CHAOS_THRESHOLD;
    let line = |flag: &str| {
        let at = help
            .find(flag)
            .unwrap_or_else(|| panic!("{flag} missing: {help}"));
        help[at..]
            .split("\n      --")
            .next()
            .unwrap_or_default()
            .to_string()
    };
    let every_line = line("--renormalize-every");
    assert!(
        every_line.contains(&format!("[default: {every}]")),
        "{every_line}"
    );
    let sali_line = line("--sali");
    assert!(
        sali_line.contains(&format!("above {threshold:e}: regular")),
        "{sali_line}"
    );
}

/// Kepler orbits (`a = 1`, `k = mu = 1`: period `2 pi`) at `e = 0.1, 0.4, 0.7` over two
/// periods by `method` with `extra` flags into `e.npz` in `dir`; the run's output and, if it
/// succeeded, each member's largest distance from its start.
fn kepler_orbits(
    dir: &std::path::Path,
    method: &str,
    extra: &[&str],
) -> (std::process::Output, Vec<f64>) {
    let (t1, dt) = (4.0 * std::f64::consts::PI, std::f64::consts::TAU / 64.0);
    let (t1, dt) = (t1.to_string(), dt.to_string());
    let mut args = vec!["ensemble", "kepler", "--values", "e=0.1,0.4,0.7"];
    args.extend_from_slice(&["--method", method, "--t1", &t1, "--dt", &dt]);
    args.extend_from_slice(&["--out", "e.npz"]);
    args.extend_from_slice(extra);
    let out = run_in(dir, &args);
    if out.status.code() != Some(0) {
        return (out, vec![]);
    }
    let mut npz = NpzReader::new(File::open(dir.join("e.npz")).unwrap()).unwrap();
    let final_state: Array2<f64> = npz.by_name("final_state.npy").unwrap();
    let errors = [0.1f64, 0.4, 0.7]
        .iter()
        .zip(final_state.rows())
        .map(|(&e, y)| {
            // The closed form's start, perihelion, where every period returns the orbit.
            let start = [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()];
            y.iter()
                .zip(start)
                .map(|(y, y0)| (y - y0).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    (out, errors)
}

#[test]
fn rtol_and_atol_reach_every_member() {
    let dir = scratch();
    let (out, loose) = kepler_orbits(dir.path(), "taylor", &["--rtol", "1e-6", "--atol", "1e-6"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let (out, tight) = kepler_orbits(
        dir.path(),
        "taylor",
        &["--rtol", "1e-12", "--atol", "1e-12"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for (k, (l, t)) in loose.iter().zip(&tight).enumerate() {
        // Tolerances 1e6 times tighter: measured, the distance from the start after two
        // periods falls from 6e-8 .. 7e-6 to 8e-13 .. 1.6e-11, by 8e4 to 7e5; 100 keeps a
        // margin of over 800. Flags not passed on would leave both runs at the defaults, the
        // same bits: ratio 1.
        assert!(100.0 * t < *l, "member {k}: {t:e} at 1e-12, {l:e} at 1e-6");
    }
    // The same from a scenario file's keys, and a bad value or a fixed-step method refused
    // naming the flag and the key, with no file left.
    std::fs::write(
        dir.path().join("s.json"),
        r#"{"rtol": 1e-12, "atol": 1e-12}"#,
    )
    .unwrap();
    let (out, from_file) = kepler_orbits(dir.path(), "taylor", &["--scenario", "s.json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(bits(&from_file), bits(&tight));
    for (method, flags, expected) in [
        (
            "taylor",
            &["--rtol", "0"][..],
            "invalid value `0` for `--rtol` (`rtol`): ",
        ),
        (
            "taylor",
            &["--atol", "nan"][..],
            "invalid value `NaN` for `--atol` (`atol`): ",
        ),
        (
            "dop853",
            &["--max-steps", "0"][..],
            "invalid value `0` for `--max-steps`",
        ),
        (
            "yoshida4",
            &["--rtol", "1e-9"][..],
            "invalid value `0.000000001` for `--rtol` (`rtol`): `yoshida4` is a fixed-step method",
        ),
    ] {
        let dir = scratch();
        let (out, _) = kepler_orbits(dir.path(), method, flags);
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
        assert!(
            stderr(&out).contains(expected),
            "{flags:?}: {}",
            stderr(&out)
        );
        assert!(entries(dir.path()).is_empty(), "{flags:?}");
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}
