//! `ensemble --scenario FILE` (`src/scenario.rs`): the example files give the same file, byte
//! for byte, as the flags that say the same; flags override or conflict as `--help` says;
//! unknown keys and bad values are refused by name; listed members (`values`, `states`) are
//! the library's; `--no-final-state` stops members at their events with the same times.

use std::fs::File;
use std::path::{Path, PathBuf};

use ndarray::{Array1, Array2, Array3, ArrayD};
use ndarray_npy::NpzReader;
use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Members, Plan, Sweep};

use crate::common::{entries, run_in, scratch, stderr};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// Runs `physicskit args` in `dir`, which must succeed; returns the entries of the npz
/// `dir/out` in their order, each name with its bytes (NPY header and data). The zip's own
/// metadata is left out: it may carry the time of writing.
fn written(dir: &Path, args: &[&str], out: &str) -> Vec<(String, Vec<u8>)> {
    let run = run_in(dir, args);
    assert_eq!(run.status.code(), Some(0), "{args:?}: {}", stderr(&run));
    let mut zip = zip::ZipArchive::new(File::open(dir.join(out)).unwrap()).unwrap();
    (0..zip.len())
        .map(|i| {
            let mut entry = zip.by_index(i).unwrap();
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut entry, &mut bytes).unwrap();
            (entry.name().to_string(), bytes)
        })
        .collect()
}

/// Writes `text` as `dir/name` and runs `ensemble --scenario name` with `flags`, which must
/// fail with one error line, status 2 and no file other than the scenario; returns stderr.
fn refused(name: &str, text: &str, flags: &[&str]) -> String {
    let dir = scratch();
    std::fs::write(dir.path().join(name), text).unwrap();
    let mut args = vec!["ensemble", "--scenario", name];
    args.extend_from_slice(flags);
    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.starts_with("error: ") && err.trim_end().lines().count() == 1,
        "{err}"
    );
    assert_eq!(entries(dir.path()), vec![dir.path().join(name)], "{err}");
    err
}

/// The examples run as shipped (with only `--out` added, which the npz does not record) and
/// write the same entries, byte for byte, as the flags spelling out the same run: same arrays, same bits, same
/// order. The flip-time example keeps no final state, so its members stop at their events.
#[test]
fn the_examples_equal_their_flag_runs_byte_for_byte() {
    let pi = "3.141592653589793";
    let (upper, lower) = (
        format!("upper=abs_above:0:{pi}"),
        format!("lower=abs_above:1:{pi}"),
    );
    let flip: Vec<&str> = vec![
        "ensemble",
        "double-pendulum",
        "--set",
        "thetadot0=0,0",
        "--grid",
        "theta0[0]=-3:3:21",
        "--grid",
        "theta0[1]=-3:3:21",
        "--method",
        "rk4",
        "--dt",
        "0.01",
        "--t1",
        "10",
        "--event",
        upper.as_str(),
        "--event",
        lower.as_str(),
        "--no-final-state",
    ];
    let henon_heiles = vec![
        "ensemble",
        "henon-heiles",
        "--set",
        "p0=0.4,0.1",
        "--grid",
        "q0[1]=-0.2:0.2:9",
        "--method",
        "yoshida4",
        "--dt",
        "0.05",
        "--t1",
        "200",
        "--max-lyapunov",
        "--sali",
        "--renormalize-every",
        "10",
    ];
    for (file, flags) in [
        ("flip_fractal.json", flip),
        ("henon_heiles_chaos.toml", henon_heiles),
    ] {
        let dir = scratch();
        let path = example(file);
        let path = path.to_str().unwrap();
        let from_file = written(
            dir.path(),
            &["ensemble", "--scenario", path, "--out", "s.npz"],
            "s.npz",
        );
        let from_flags = written(
            dir.path(),
            &[&flags[..], &["--out", "f.npz"][..]].concat(),
            "f.npz",
        );
        assert!(from_file == from_flags, "{file}: the files differ");
        assert!(from_file.len() >= 8, "{file}: {} entries", from_file.len());
        let mut npz = NpzReader::new(File::open(dir.path().join("s.npz")).unwrap()).unwrap();
        let steps: ArrayD<i64> = npz.by_name("steps").unwrap();
        let full = if file.ends_with("json") { 1000 } else { 4000 };
        assert!(steps.iter().all(|&s| s <= full), "{file}");
        assert_eq!(
            steps.iter().any(|&s| s < full),
            file.ends_with("json"),
            "{file}"
        );
    }
}

/// Flags beside a file: a setting replaces the file's (SYSTEM, `--dt`, `--t1`, `--out`),
/// `--set` replaces one parameter and keeps the file's others, a switch adds an output; the
/// result is the run the merged settings describe, byte for byte.
#[test]
fn flags_override_the_file() {
    let dir = scratch();
    let file = r#"{"system": "no-such-system", "set": {"q0": 0.3, "m": 2},
        "grid": [{"name": "p0", "from": 0, "to": 1, "n": 3}],
        "dt": 0.1, "t1": 1, "out": "ignored.npz"}"#;
    std::fs::write(dir.path().join("s.json"), file).unwrap();
    let times = ["--dt", "0.05", "--t1", "2", "--energy-error"];
    let merged = written(
        dir.path(),
        &[
            &[
                "ensemble",
                "harmonic-oscillator",
                "--scenario",
                "s.json",
                "--set",
                "q0=0.7",
            ][..],
            &times[..],
            &["--out", "m.npz"][..],
        ]
        .concat(),
        "m.npz",
    );
    let flags = written(
        dir.path(),
        &[
            &["ensemble", "harmonic-oscillator", "--grid", "p0=0:1:3"][..],
            &["--set", "q0=0.7", "--set", "m=2"][..],
            &times[..],
            &["--out", "f.npz"][..],
        ]
        .concat(),
        "f.npz",
    );
    assert!(merged == flags, "the merged run is not the flags' run");
    assert!(!dir.path().join("ignored.npz").exists());
    // Without SYSTEM on the command line, the file's is used.
    let err = refused("s.json", file, &[]);
    assert!(err.contains("no-such-system"), "{err}");
}

/// The members and the events are given in one place; unknown keys, values of the wrong type
/// and out-of-range counts are refused by name, before any file is written.
#[test]
fn conflicts_and_bad_files_are_refused_by_name() {
    let good = r#"{"system": "harmonic-oscillator", "grid": [{"name": "q0", "from": 0, "to": 1, "n": 2}],
        "events": [{"name": "x", "kind": "falling", "index": 0, "value": 0}], "dt": 0.1, "t1": 1, "out": "a.npz"}"#;
    let err = refused("s.json", good, &["--grid", "k=1:2:2"]);
    assert!(
        err.contains("`--grid` conflicts with") && err.contains("`grid`"),
        "{err}"
    );
    let err = refused("s.json", good, &["--values", "k=1,2"]);
    assert!(err.contains("`--values` conflicts with"), "{err}");
    let err = refused("s.json", good, &["--event", "y=rising:0:0"]);
    assert!(err.contains("`--event` conflicts with `events`"), "{err}");
    let with = |key: &str| good.replace("\"dt\": 0.1", &format!("\"dt\": 0.1, {key}"));
    let err = refused("s.json", &with("\"dtt\": 1"), &[]);
    assert!(err.contains("unknown field `dtt`"), "{err}");
    let err = refused("s.json", &good.replace("\"index\"", "\"indx\""), &[]);
    assert!(err.contains("unknown field `indx`"), "{err}");
    let err = refused(
        "s.json",
        &with("\"sali\": true, \"renormalize_every\": 0"),
        &[],
    );
    assert!(
        err.contains("`renormalize_every`") && err.contains(">= 1"),
        "{err}"
    );
    // A count that is no count: serde names the type and the place in the file.
    for bad in ["-1", "1e23", "18446744073709551616", "\"ten\""] {
        let err = refused(
            "s.json",
            &with(&format!("\"sali\": true, \"renormalize_every\": {bad}")),
            &[],
        );
        assert!(
            err.contains("scenario `s.json`") && err.contains("line"),
            "{bad}: {err}"
        );
    }
    let err = refused("s.json", &with("\"renormalize_every\": 5"), &[]);
    assert!(err.contains("`renormalize_every` only with"), "{err}");
    let err = refused("s.toml", "system = \"harmonic-oscillator\"\nfoo = 1\n", &[]);
    assert!(err.contains("unknown field `foo`"), "{err}");
    let err = refused("s.yaml", "system: x\n", &[]);
    assert!(err.contains(".json or .toml"), "{err}");
    let err = refused("s.json", &good.replace(", \"out\": \"a.npz\"", ""), &[]);
    assert!(err.contains("--out") && err.contains("`out`"), "{err}");
    let err = refused("s.json", &with("\"states\": [[0, 1], [0]]"), &[]);
    assert!(err.contains("row 1 has 1"), "{err}");
}

/// Listed members (`values`, `states`) by a grid axis: the list is axis 0, the grid axis 1;
/// the outputs are the library's ensemble of the same members, bit for bit.
#[test]
fn listed_members_by_a_grid_are_the_librarys() {
    let dir = scratch();
    std::fs::write(
        dir.path().join("s.json"),
        r#"{"system": "harmonic-oscillator",
            "values": {"m": [1, 2, 0.5]},
            "states": [[1, 0], [0.5, 0.25], [0, -1]],
            "grid": [{"name": "k", "from": 1, "to": 4, "n": 2}],
            "stride": 10, "dt": 0.1, "t1": 1, "out": "s.npz"}"#,
    )
    .unwrap();
    written(dir.path(), &["ensemble", "--scenario", "s.json"], "s.npz");
    let mut npz = NpzReader::new(File::open(dir.path().join("s.npz")).unwrap()).unwrap();
    let final_state: Array3<f64> = npz.by_name("final_state").unwrap();
    let trajectory: ArrayD<f64> = npz.by_name("trajectory").unwrap();
    let m: Array1<f64> = npz.by_name("values_m").unwrap();
    let states: Array2<f64> = npz.by_name("states").unwrap();
    assert_eq!(final_state.shape(), [3, 2, 2]);
    assert_eq!(trajectory.shape(), [3, 2, 2, 2]);
    assert_eq!(m.to_vec(), [1.0, 2.0, 0.5]);
    assert_eq!(states.shape(), [3, 2]);
    let members = Members {
        common: vec![],
        sweeps: vec![
            Sweep::new("m", vec![1.0, 1.0, 2.0, 2.0, 0.5, 0.5]),
            Sweep::new("k", vec![1.0, 4.0, 1.0, 4.0, 1.0, 4.0]),
        ],
        states: Some(vec![
            1.0, 0.0, 1.0, 0.0, 0.5, 0.25, 0.5, 0.25, 0.0, -1.0, 0.0, -1.0,
        ]),
        n: 6,
    };
    let plan = Plan {
        t_span: (0.0, 1.0),
        dt: 0.1,
        method: None,
        stride: Some(10),
        reductions: vec![],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let lib = ensemble::run(
        catalog::find("harmonic-oscillator").unwrap(),
        &members,
        &plan,
        None,
    )
    .unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(final_state.as_slice().unwrap()),
        bits(lib.final_state.as_slice().unwrap())
    );
    assert_eq!(
        bits(trajectory.as_slice().unwrap()),
        bits(lib.trajectory.as_ref().unwrap().as_slice().unwrap())
    );
    // Lists that disagree in length are refused by name.
    let err = refused(
        "s.json",
        r#"{"system": "harmonic-oscillator", "values": {"m": [1, 2]}, "states": [[1, 0]],
            "dt": 0.1, "t1": 1, "out": "a.npz"}"#,
        &[],
    );
    assert!(err.contains("`m` has 2, `states` 1"), "{err}");
}

/// `--no-final-state` with events only: every event time is the full run's, bit for bit;
/// each member stops at its event (the oscillator from x = q0 at rest falls through 0 at
/// t = pi/2 ~ 1.57, step 158 of 1000), and the file has no `final_state`.
#[test]
fn no_final_state_stops_members_at_their_events() {
    let dir = scratch();
    let base = [
        "ensemble",
        "harmonic-oscillator",
        "--grid",
        "q0=0.5:1.5:3",
        "--set",
        "p0=0",
        "--event",
        "x=falling:0:0",
        "--dt",
        "0.01",
        "--t1",
        "10",
    ];
    written(
        dir.path(),
        &[&base[..], &["--out", "full.npz"][..]].concat(),
        "full.npz",
    );
    written(
        dir.path(),
        &[&base[..], &["--no-final-state", "--out", "early.npz"][..]].concat(),
        "early.npz",
    );
    let read = |name: &str| NpzReader::new(File::open(dir.path().join(name)).unwrap()).unwrap();
    let (mut full, mut early) = (read("full.npz"), read("early.npz"));
    let times = |npz: &mut NpzReader<File>| -> Vec<u64> {
        let t: Array1<f64> = npz.by_name("event_x").unwrap();
        t.iter().map(|x| x.to_bits()).collect()
    };
    let t = times(&mut full);
    assert_eq!(t, times(&mut early));
    // The oscillator's period is 2 pi (m = k = 1): the first fall through 0 is at pi/2.
    // 1e-6: the event located inside its step carries Yoshida-4's global O(dt^4) = 1e-8
    // error times a constant, and the cubic interpolant's O(dt^4); 100x that is room enough.
    for bits in &t {
        assert!((f64::from_bits(*bits) - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    }
    let steps = |npz: &mut NpzReader<File>| -> Vec<i64> {
        let s: Array1<i64> = npz.by_name("steps").unwrap();
        s.to_vec()
    };
    assert_eq!(steps(&mut full), [1000; 3]);
    let early_steps = steps(&mut early);
    assert!(
        early_steps.iter().all(|&s| (158..=160).contains(&s)),
        "{early_steps:?}"
    );
    assert!(full
        .names()
        .unwrap()
        .iter()
        .any(|n| n.starts_with("final_state")));
    assert!(!early
        .names()
        .unwrap()
        .iter()
        .any(|n| n.starts_with("final_state")));
    // Nothing left to keep is refused.
    let err = crate::errors::fails(&[
        "ensemble",
        "harmonic-oscillator",
        "--grid",
        "q0=0.5:1.5:3",
        "--no-final-state",
        "--dt",
        "0.01",
        "--t1",
        "1",
        "--out",
        "a.npz",
    ]);
    assert!(err.contains("nothing to write"), "{err}");
}
