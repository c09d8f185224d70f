//! `lyapunov` and `poincare` (`src/chaos.rs`): the files hold the Rust API's numbers for the
//! same run, bit for bit, in every format; bad options fail like `simulate`'s; a signal stops
//! a long run and leaves nothing behind.

use std::fs::File;
use std::path::Path;

use ndarray::{Array0, Array1, Array2};
use ndarray_npy::NpzReader;
use physicskit::classical::analysis::lyapunov::{lyapunov_spectrum, DEFAULT_RENORMALIZE_EVERY};
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::section::{poincare_section, SurfaceOfSection};
use physicskit::classical::model::erased::Hamiltonian;
use physicskit::classical::systems::HenonHeilesSystem;

use crate::common::{run_in, scratch, stderr};
use crate::errors::fails;

/// p_y of the chaotic Hénon–Heiles orbit at E = 1/6 from (0, 0) with p_x = 0.1.
fn py() -> f64 {
    (2.0 / 6.0 - 0.01_f64).sqrt()
}

fn henon_heiles() -> Hamiltonian<HenonHeilesSystem> {
    Hamiltonian(HenonHeilesSystem::new(&[0.0, 0.0], &[0.1, py()]).unwrap())
}

/// Runs `action henon-heiles` on the orbit above with `flags`, writing `file`.
fn run_hh(dir: &Path, action: &str, file: &str, flags: &[&str]) -> std::path::PathBuf {
    let p0 = format!("0.1,{:?}", py());
    let mut args = vec![action, "henon-heiles", "--q0", "0,0", "--p0", &p0];
    args.extend_from_slice(flags);
    args.extend_from_slice(&["--out", file]);
    let out = run_in(dir, &args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    dir.join(file)
}

fn bits(v: impl IntoIterator<Item = f64>) -> Vec<u64> {
    v.into_iter().map(f64::to_bits).collect()
}

const LYAPUNOV: [&str; 8] = [
    "--dt",
    "0.01",
    "--t1",
    "50",
    "--renormalize-every",
    "10",
    "--history-stride",
    "3",
];

/// 5000 steps, 500 renormalizations; stride 3 keeps rows 2, 5, ..., 497 and 499. The
/// exponents are `lyapunov_spectrum`'s for the same orbit, method and renormalization, bit for
/// bit; the kept history rows are its rows.
#[test]
fn lyapunov_npz_is_the_librarys_spectrum() {
    let dir = scratch();
    let path = run_hh(dir.path(), "lyapunov", "l.npz", &LYAPUNOV);
    let want = lyapunov_spectrum(&mut henon_heiles(), (0.0, 50.0), 0.01, None, None, 10).unwrap();
    let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
    let exponents: Array1<f64> = npz.by_name("exponents").unwrap();
    let t: Array1<f64> = npz.by_name("t").unwrap();
    let history: Array2<f64> = npz.by_name("history").unwrap();
    assert_eq!(
        bits(exponents.iter().copied()),
        bits(want.exponents.clone())
    );
    let rows: Vec<usize> = (2..500).step_by(3).chain([499]).collect();
    assert_eq!(history.shape(), [rows.len(), 4]);
    for (j, &i) in rows.iter().enumerate() {
        assert_eq!(t[j].to_bits(), want.t[i].to_bits());
        assert_eq!(
            bits(history.row(j).iter().copied()),
            bits(want.history[4 * i..4 * i + 4].iter().copied())
        );
    }
    let every: Array0<i64> = npz.by_name("renormalize_every").unwrap();
    assert_eq!(every.into_scalar(), 10);
}

/// The same run as CSV (one row per kept renormalization, the exponents as constant columns)
/// and JSON (read with serde_json) holds the same bits.
#[test]
fn lyapunov_csv_and_json_hold_the_same_numbers() {
    let dir = scratch();
    let want = lyapunov_spectrum(&mut henon_heiles(), (0.0, 50.0), 0.01, None, None, 10).unwrap();
    let csv = std::fs::read_to_string(run_hh(dir.path(), "lyapunov", "l.csv", &LYAPUNOV)).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[..9],
        [
            "t",
            "history_0",
            "history_1",
            "history_2",
            "history_3",
            "exponents_0",
            "exponents_1",
            "exponents_2",
            "exponents_3"
        ]
    );
    assert!(header.contains(&"param_p0_1") && header.contains(&"history_stride"));
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(
        bits(last[5..9].iter().copied()),
        bits(want.exponents.clone())
    );
    assert_eq!(last[0].to_bits(), 50.0_f64.to_bits());

    let json =
        std::fs::read_to_string(run_hh(dir.path(), "lyapunov", "l.json", &LYAPUNOV)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let exponents: Vec<f64> = serde_json::from_value(v["exponents"].clone()).unwrap();
    assert_eq!(bits(exponents), bits(want.exponents));
    assert_eq!(v["system"], "henon-heiles");
    assert_eq!(v["method"], "yoshida4");
    assert_eq!(v["history_stride"], 3);
    assert_eq!(v["parameters"]["q0"], serde_json::json!([0.0, 0.0]));
    assert_eq!(v["history"].as_array().unwrap().len(), 167);
}

/// The section x = 0 (coordinate 0) crossed upwards: `poincare_section`'s crossings, bit for
/// bit, in the npz and in the CSV's `t`, `y_0..y_3` columns.
#[test]
fn poincare_files_are_the_librarys_section() {
    let dir = scratch();
    let flags = ["--coordinate", "0", "--dt", "0.01", "--t1", "200"];
    let surface = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing).unwrap();
    let want = poincare_section(
        &mut henon_heiles(),
        (0.0, 200.0),
        0.01,
        None,
        &surface,
        usize::MAX,
    )
    .unwrap();
    assert!(want.len() > 10, "{} crossings", want.len());
    let mut npz =
        NpzReader::new(File::open(run_hh(dir.path(), "poincare", "s.npz", &flags)).unwrap())
            .unwrap();
    let t: Array1<f64> = npz.by_name("t").unwrap();
    let y: Array2<f64> = npz.by_name("y").unwrap();
    assert_eq!(bits(t.iter().copied()), bits(want.t.clone()));
    assert_eq!(y.shape(), [want.len(), 4]);
    assert_eq!(bits(y.iter().copied()), bits(want.states.clone()));

    let csv = std::fs::read_to_string(run_hh(dir.path(), "poincare", "s.csv", &flags)).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[..5], ["t", "y_0", "y_1", "y_2", "y_3"]);
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), want.len());
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row[0].to_bits(), want.t[i].to_bits());
        assert_eq!(
            bits(row[1..5].iter().copied()),
            bits(want.states[4 * i..4 * i + 4].to_vec())
        );
    }
}

/// `action system` over one time unit in steps of 0.1 into `a.npz`, then `extra`.
fn short_run<'a>(action: &'a str, system: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![action, system, "--dt", "0.1", "--t1", "1", "--out", "a.npz"];
    args.extend_from_slice(extra);
    args
}

/// Bad analysis options: one error line naming the flag, exit 2, no file.
#[test]
fn bad_options_name_their_flag() {
    let base = |action, extra: &[&str]| fails(&short_run(action, "henon-heiles", extra));
    let cases: [(&str, &[&str], &str); 8] = [
        ("lyapunov", &["--n-exponents", "5"], "--n-exponents"),
        ("lyapunov", &["--n-exponents", "0"], "--n-exponents"),
        (
            "lyapunov",
            &["--renormalize-every", "0"],
            "--renormalize-every",
        ),
        ("lyapunov", &["--history-stride", "-1"], "--history-stride"),
        ("poincare", &["--coordinate", "4"], "--coordinate"),
        (
            "poincare",
            &["--coordinate", "0", "--direction", "2"],
            "--direction",
        ),
        (
            "poincare",
            &["--coordinate", "0", "--value", "x"],
            "--value",
        ),
        (
            "poincare",
            &["--coordinate", "0", "--value", "nan"],
            "--value",
        ),
    ];
    for (action, extra, flag) in cases {
        let err = base(action, extra);
        assert!(err.contains(flag), "{action} {extra:?}: {err}");
    }
    // Missing --coordinate is clap's message; a typo lists the system's and the kind's flags.
    assert!(base("poincare", &[]).contains("--coordinate"));
    let err = base("lyapunov", &["--renormalise-every", "3"]);
    assert!(
        err.contains("--renormalize-every") && err.contains("q0"),
        "{err}"
    );
}

/// The number of exponents: without `--n-exponents` a system larger than dimension 20 (the
/// pendulum swarm's 1000 members: 2000) is refused with the flag to pass and what the full
/// spectrum would cost, before any step; a value that is no whole number from 1 to the state
/// dimension (`1e23`, too large, fractional) names the flag and the range. With the flag the
/// swarm runs.
#[test]
fn n_exponents_is_required_for_large_systems_and_checked() {
    let args = |extra: &[&'static str]| short_run("lyapunov", "pendulum-swarm", extra);
    let err = fails(&args(&[]));
    assert!(
        err.contains("pass --n-exponents K") && err.contains("2000-dimensional"),
        "{err}"
    );
    for bad in ["1e23", "100000000000000000000000", "2001", "2.5", "0", "-1"] {
        let err = fails(&args(&["--n-exponents", bad]));
        assert!(
            err.contains(&format!("invalid value `{bad}` for `--n-exponents`"))
                && err.contains("a whole number from 1 to 2000"),
            "{bad}: {err}"
        );
    }
    let dir = scratch();
    let out = run_in(dir.path(), &args(&["--n-exponents", "2"]));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mut npz = NpzReader::new(File::open(dir.path().join("a.npz")).unwrap()).unwrap();
    let exponents: Array1<f64> = npz.by_name("exponents").unwrap();
    assert_eq!(exponents.len(), 2);
}

/// The full-spectrum cap at its boundary: the swarm of 10 pendulums (dimension 20, the cap)
/// runs without `--n-exponents` and gives 20 exponents; 11 pendulums (dimension 22) are refused
/// with the flag to pass, before any file is written.
#[test]
fn the_full_spectrum_cap_is_dimension_20() {
    let args = |n: &'static str| short_run("lyapunov", "pendulum-swarm", &["--n", n]);
    let dir = scratch();
    let out = run_in(dir.path(), &args("10"));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mut npz = NpzReader::new(File::open(dir.path().join("a.npz")).unwrap()).unwrap();
    let exponents: Array1<f64> = npz.by_name("exponents").unwrap();
    assert_eq!(exponents.len(), 20);
    let err = fails(&args("11"));
    assert!(
        err.contains("pass --n-exponents K") && err.contains("22-dimensional"),
        "{err}"
    );
}

/// The help states the cap the code applies (20, tested above) and the library's default
/// renormalization interval.
#[test]
fn lyapunov_help_states_the_cap_and_the_default_interval() {
    let help = crate::common::help(&["lyapunov", "henon-heiles"]);
    assert!(help.contains("required above dimension 20]"), "{help}");
    let every = help
        .lines()
        .find(|l| l.contains("--renormalize-every"))
        .unwrap_or_default();
    assert!(
        every.contains(&format!("[default: {DEFAULT_RENORMALIZE_EVERY}]")),
        "{every}"
    );
}

/// Ctrl-C and SIGTERM stop a long Lyapunov run (checked every 1024 steps of the tangent
/// dynamics) with 130 and 143 and leave no file, as for `simulate`.
#[cfg(unix)]
#[test]
fn signals_stop_a_long_lyapunov_run() {
    // 10^9 steps: hours of work; stopped within a second of the signal.
    let args = [
        "lyapunov",
        "henon-heiles",
        "--dt",
        "0.01",
        "--t1",
        "1e7",
        "--history-stride",
        "1000000",
        "--out",
        "a.npz",
    ];
    crate::errors::signal_stops_a_run_and_leaves_nothing(&args, "INT", 130);
    crate::errors::signal_stops_a_run_and_leaves_nothing(&args, "TERM", 143);
}

/// `lyapunov SYSTEM --help` and `poincare SYSTEM --help` are generated like `simulate`'s: every
/// parameter of the catalogue entry, and the analysis's own flags.
#[test]
fn help_lists_the_systems_parameters_and_the_analysis_flags() {
    let dir = scratch();
    let kinds: [(&str, &[&str]); 2] = [
        (
            "lyapunov",
            &["--n-exponents", "--renormalize-every", "--history-stride"],
        ),
        ("poincare", &["--coordinate", "--value", "--direction"]),
    ];
    for entry in physicskit::classical::catalog::SYSTEMS {
        for (action, flags) in kinds {
            let out = run_in(dir.path(), &[action, entry.name, "--help"]);
            assert_eq!(out.status.code(), Some(0), "{action} {} --help", entry.name);
            let help = crate::common::stdout(&out);
            let params = entry.params.iter().map(|p| format!("--{} ", p.name));
            for flag in flags.iter().map(|f| format!("{f} ")).chain(params) {
                assert!(
                    help.contains(&flag),
                    "{action} {}: {flag}missing:\n{help}",
                    entry.name
                );
            }
        }
    }
}
