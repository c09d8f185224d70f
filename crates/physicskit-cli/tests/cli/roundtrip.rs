//! `simulate` output read back and compared with the library's own result for the same run:
//! bit for bit in every format (the text formats print the shortest digits that round-trip,
//! so parsing them must give back the same `f64`). The `.npz` is read with ndarray-npy's
//! reader and the `.json` with serde_json, independent of the writers under test.

use std::fs::File;
use std::path::Path;

use ndarray::{Array0, Array1, Array2, ArrayView2};
use ndarray_npy::NpzReader;
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::systems::{
    DoublePendulum, DoublePendulumParams, EulerTop, EulerTopParams, KeplerPerturbations,
    KeplerSystem,
};
use physicskit::classical::{
    HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method, OdeSystem, SimulationResult,
};

use crate::common::{run_in, scratch, stderr};

/// Runs `simulate` and returns the output path.
fn simulate(dir: &Path, file: &str, args: &[&str]) -> std::path::PathBuf {
    let mut all = vec!["simulate"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", file]);
    let out = run_in(dir, &all);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    dir.join(file)
}

fn same_bits(what: &str, got: impl IntoIterator<Item = f64>, want: impl IntoIterator<Item = f64>) {
    let got: Vec<u64> = got.into_iter().map(f64::to_bits).collect();
    let want: Vec<u64> = want.into_iter().map(f64::to_bits).collect();
    assert_eq!(got.len(), want.len(), "{what}: length");
    assert!(got == want, "{what}: values differ");
}

/// The library's run equal to `pendulum --q0 2.5 --p0 0.1 --g_over_l 3 --dt 0.01 --t1 5`.
fn pendulum_reference(method: Method) -> SimulationResult {
    Pendulum::new(2.5, 0.1, 3.0)
        .unwrap()
        .integrate((0.0, 5.0), 0.01, method)
        .unwrap()
}

const PENDULUM: [&str; 10] = [
    "pendulum",
    "--q0",
    "2.5",
    "--p0",
    "0.1",
    "--g_over_l",
    "3",
    "--dt",
    "0.01",
    "--t1",
];

fn pendulum_args(method: &str) -> Vec<&str> {
    let mut v = PENDULUM.to_vec();
    v.extend_from_slice(&["5", "--method", method]);
    v
}

#[test]
fn npz_round_trips_bit_for_bit() {
    let dir = scratch();
    // The CLI runs catalogue systems, whose fields are hand-written: a method that needs a
    // Taylor form is refused (errors.rs checks the refusal).
    for method in Method::ALL.into_iter().filter(|m| !m.needs_taylor_form()) {
        let path = simulate(dir.path(), "run.npz", &pendulum_args(method.name()));
        let want = pendulum_reference(method);
        let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
        let t: Array1<f64> = npz.by_name("t").unwrap();
        let q: Array2<f64> = npz.by_name("q").unwrap();
        let p: Array2<f64> = npz.by_name("p").unwrap();
        let e: Array1<f64> = npz.by_name("energy").unwrap();
        assert_eq!(q.shape(), want.q().unwrap().shape());
        same_bits("t", t.iter().copied(), want.t.iter().copied());
        same_bits("q", q.iter().copied(), want.q().unwrap().iter().copied());
        same_bits("p", p.iter().copied(), want.p().unwrap().iter().copied());
        same_bits(
            "energy",
            e.iter().copied(),
            want.energy.as_ref().unwrap().iter().copied(),
        );
        let g: Array0<f64> = npz.by_name("param_g_over_l").unwrap();
        let dt: Array0<f64> = npz.by_name("dt").unwrap();
        assert_eq!(g.into_scalar().to_bits(), 3.0_f64.to_bits());
        assert_eq!(dt.into_scalar().to_bits(), 0.01_f64.to_bits());
        let names = npz.names().unwrap();
        for key in ["system", "method", "family", "t0", "t1"] {
            assert!(names.iter().any(|n| n == key), "{key} missing: {names:?}");
        }
    }
}

/// Parses the CSV: a header, then rows of numbers; returns (header, columns).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let mut cols = vec![Vec::new(); header.len()];
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len(), "ragged row {line}");
        for (c, cell) in cols.iter_mut().zip(cells) {
            c.push(cell.parse::<f64>().unwrap());
        }
    }
    (header, cols)
}

#[test]
fn csv_round_trips_bit_for_bit() {
    let dir = scratch();
    let path = simulate(dir.path(), "run.csv", &pendulum_args("rk4"));
    let want = pendulum_reference(Method::Rk4);
    let (header, cols) = read_csv(&path);
    assert_eq!(
        header,
        [
            "t",
            "q_0",
            "p_0",
            "energy",
            "dt",
            "param_q0",
            "param_p0",
            "param_g_over_l"
        ]
    );
    assert_eq!(cols[0].len(), want.n_samples());
    same_bits("t", cols[0].iter().copied(), want.t.iter().copied());
    same_bits(
        "q",
        cols[1].iter().copied(),
        want.q().unwrap().iter().copied(),
    );
    same_bits(
        "p",
        cols[2].iter().copied(),
        want.p().unwrap().iter().copied(),
    );
    same_bits(
        "energy",
        cols[3].iter().copied(),
        want.energy.unwrap().iter().copied(),
    );
    for (col, value) in [(4, 0.01), (5, 2.5), (6, 0.1), (7, 3.0)] {
        assert!(
            cols[col].iter().all(|v| v.to_bits() == f64::to_bits(value)),
            "{} should be {value} on every row",
            header[col]
        );
    }
}

#[test]
fn json_round_trips_bit_for_bit() {
    let dir = scratch();
    let path = simulate(dir.path(), "run.json", &pendulum_args("implicit_midpoint"));
    let want = pendulum_reference(Method::ImplicitMidpoint);
    let v: serde_json::Value = serde_json::from_reader(File::open(&path).unwrap()).unwrap();
    let floats = |key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let rows = |key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect()
    };
    same_bits("t", floats("t"), want.t.iter().copied());
    same_bits("q", rows("q"), want.q().unwrap().iter().copied());
    same_bits("p", rows("p"), want.p().unwrap().iter().copied());
    same_bits(
        "energy",
        floats("energy"),
        want.energy.unwrap().iter().copied(),
    );
    assert_eq!(v["system"], "pendulum");
    assert_eq!(v["method"], "implicit_midpoint");
    assert_eq!(v["parameters"]["q0"].as_f64(), Some(2.5));
    assert_eq!(v["parameters"]["g_over_l"].as_f64(), Some(3.0));
    assert_eq!(v["dt"].as_f64(), Some(0.01));
}

/// Defaults, a non-zero start time and a stride reach the library as given.
#[test]
fn defaults_start_time_and_stride_match_the_library() {
    let dir = scratch();
    let path = simulate(
        dir.path(),
        "run.npz",
        &[
            "harmonic-oscillator",
            "--k",
            "4",
            "--t0",
            "-1",
            "--dt",
            "0.001",
            "--t1",
            "2",
            "--stride",
            "7",
        ],
    );
    // Registry defaults: q0 = 1, p0 = 0, m = 1; default method yoshida4.
    let want = HarmonicOscillator::new(1.0, 0.0, 1.0, 4.0)
        .unwrap()
        .integrate_with(
            (-1.0, 2.0),
            0.001,
            Method::Yoshida4,
            IntegrateOptions::stride(7),
        )
        .unwrap();
    let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
    let t: Array1<f64> = npz.by_name("t").unwrap();
    let q: Array2<f64> = npz.by_name("q").unwrap();
    same_bits("t", t.iter().copied(), want.t.iter().copied());
    same_bits("q", q.iter().copied(), want.q().unwrap().iter().copied());
    let m: Array0<f64> = npz.by_name("param_m").unwrap();
    assert_eq!(m.into_scalar().to_bits(), 1.0_f64.to_bits());
}

/// A zero-length span is valid and gives the single initial sample.
#[test]
fn empty_span_gives_the_initial_state() {
    let dir = scratch();
    let path = simulate(
        dir.path(),
        "run.csv",
        &["pendulum", "--q0", "0.5", "--dt", "0.1", "--t1", "0"],
    );
    let (_, cols) = read_csv(&path);
    assert_eq!(cols[0], [0.0]);
    assert_eq!(cols[1], [0.5]);
}

/// The state arrays the writers promise: `q`, `p` when the result splits, else `y`.
fn state_arrays(want: &SimulationResult) -> Vec<(&'static str, ArrayView2<'_, f64>)> {
    match (want.q(), want.p()) {
        (Some(q), Some(p)) => vec![("q", q), ("p", p)],
        _ => vec![("y", want.y.view())],
    }
}

/// Writes `args` in all three formats and compares each with `want`, bit for bit.
fn check_all_formats(args: &[&str], want: &SimulationResult) {
    let dir = scratch();
    let energy = want.energy.as_ref().unwrap();

    let path = simulate(dir.path(), "run.npz", args);
    let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
    let t: Array1<f64> = npz.by_name("t").unwrap();
    same_bits("npz t", t.iter().copied(), want.t.iter().copied());
    for (name, array) in state_arrays(want) {
        let got: Array2<f64> = npz.by_name(name).unwrap();
        assert_eq!(got.shape(), array.shape(), "npz {name}");
        same_bits(name, got.iter().copied(), array.iter().copied());
    }
    let e: Array1<f64> = npz.by_name("energy").unwrap();
    same_bits("npz energy", e.iter().copied(), energy.iter().copied());

    let path = simulate(dir.path(), "run.csv", args);
    let (header, cols) = read_csv(&path);
    let mut expected_header = vec!["t".to_string()];
    let mut expected_cols: Vec<Vec<f64>> = vec![want.t.to_vec()];
    for (name, array) in state_arrays(want) {
        for (j, col) in array.columns().into_iter().enumerate() {
            expected_header.push(format!("{name}_{j}"));
            expected_cols.push(col.to_vec());
        }
    }
    expected_header.push("energy".into());
    expected_cols.push(energy.to_vec());
    // The trajectory columns come first; the constant parameter columns follow.
    assert_eq!(header[..expected_header.len()], expected_header[..]);
    for ((name, got), want) in header.iter().zip(&cols).zip(&expected_cols) {
        same_bits(name, got.iter().copied(), want.iter().copied());
    }

    let path = simulate(dir.path(), "run.json", args);
    let v: serde_json::Value = serde_json::from_reader(File::open(&path).unwrap()).unwrap();
    let flat = |x: &serde_json::Value| -> Vec<f64> {
        let mut out = Vec::new();
        let mut stack = vec![x];
        while let Some(x) = stack.pop() {
            match x {
                serde_json::Value::Array(items) => stack.extend(items.iter().rev()),
                other => out.push(other.as_f64().unwrap()),
            }
        }
        out
    };
    same_bits("json t", flat(&v["t"]), want.t.iter().copied());
    for (name, array) in state_arrays(want) {
        same_bits(name, flat(&v[name]), array.iter().copied());
        assert_eq!(v[name].as_array().unwrap().len(), array.nrows());
    }
    same_bits("json energy", flat(&v["energy"]), energy.iter().copied());
    assert_eq!(v["method"], want.method.as_str());
}

/// A Lagrangian system: `p` holds `thetadot`; rk4 and the default implicit midpoint.
#[test]
fn lagrangian_system_round_trips() {
    let params = DoublePendulumParams {
        m2: 2.0,
        ..DoublePendulumParams::default()
    };
    for (method, flag) in [(Method::ImplicitMidpoint, None), (Method::Rk4, Some("rk4"))] {
        let want = DoublePendulum::new(&[1.0, -0.5], &[0.0, 0.25], params)
            .unwrap()
            .integrate((0.0, 2.0), 0.01, method)
            .unwrap();
        let mut args = vec![
            "double-pendulum",
            "--theta0",
            "1,-0.5",
            "--thetadot0",
            "0,0.25",
            "--m2",
            "2",
            "--dt",
            "0.01",
            "--t1",
            "2",
        ];
        if let Some(flag) = flag {
            args.extend_from_slice(&["--method", flag]);
        }
        check_all_formats(&args, &want);
    }
}

/// A general ODE system writes its raw state `y` (here 7 columns) and no `q`, `p`.
#[test]
fn ode_system_writes_y() {
    let want = EulerTop::new(
        &[0.01, 1.0, 0.01],
        EulerTopParams {
            i1: 1.0,
            i2: 2.0,
            i3: 3.5,
        },
        Some(&[1.0, 0.0, 0.0, 1.0]),
    )
    .unwrap()
    .integrate((0.0, 3.0), 0.005, Method::ImplicitMidpoint)
    .unwrap();
    assert!(want.q().is_none(), "EulerTop should have no q/p split");
    check_all_formats(
        &[
            "euler-top",
            "--I3",
            "3.5",
            "--quat0",
            "1,0,0,1",
            "--dt",
            "0.005",
            "--t1",
            "3",
        ],
        &want,
    );
}

/// List parameters and the alternate constructor: `kepler` is `from_orbital_elements`,
/// `kepler-state` is `new`.
#[test]
fn kepler_constructors_round_trip() {
    let pert = KeplerPerturbations::none().with_post_newtonian(-0.01);
    let want = KeplerSystem::from_orbital_elements(1.5, 0.3, 1.0, 1.0, pert)
        .unwrap()
        .integrate((0.0, 4.0), 0.002, Method::Verlet)
        .unwrap();
    check_all_formats(
        &[
            "kepler", "--a", "1.5", "--e", "0.3", "--c_pn", "-0.01", "--method", "verlet", "--dt",
            "0.002", "--t1", "4",
        ],
        &want,
    );
    let want = KeplerSystem::new(
        &[1.0, 0.5],
        &[-0.2, 0.9],
        2.0,
        1.0,
        KeplerPerturbations::none(),
    )
    .unwrap()
    .integrate((0.0, 1.0), 0.001, Method::Yoshida4)
    .unwrap();
    check_all_formats(
        &[
            "kepler-state",
            "--q0",
            "1,0.5",
            "--p0",
            "-0.2,0.9",
            "--k",
            "2",
            "--dt",
            "0.001",
            "--t1",
            "1",
        ],
        &want,
    );
}

/// `--rtol`/`--atol` reach the adaptive method: the file holds the library's run with those
/// tolerances, bit for bit.
#[test]
fn tolerances_reach_dop853() {
    use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Tolerances};
    let dir = scratch();
    let mut args = pendulum_args("dop853");
    args.extend_from_slice(&["--rtol", "1e-6", "--atol", "1e-9"]);
    let path = simulate(dir.path(), "run.npz", &args);
    let want = Pendulum::new(2.5, 0.1, 3.0)
        .unwrap()
        .integrate_with(
            (0.0, 5.0),
            0.01,
            Method::Dop853,
            IntegrateOptions {
                tolerances: Some(Tolerances::new(1e-6, 1e-9).unwrap()),
                ..IntegrateOptions::default()
            },
        )
        .unwrap();
    let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
    let q: Array2<f64> = npz.by_name("q").unwrap();
    same_bits("q", q.iter().copied(), want.q().unwrap().iter().copied());
    // Looser than the default: a different run from the default-tolerance one.
    let default = pendulum_reference(Method::Dop853);
    assert!(q
        .iter()
        .zip(default.q().unwrap().iter())
        .any(|(a, b)| a.to_bits() != b.to_bits()));
}

/// `--max-steps` reaches the adaptive method: a budget of exactly the attempts (accepted and
/// rejected steps) the run needs gives the library's run bit for bit, one fewer stops it with
/// an error naming the budget and leaves no file.
#[test]
fn the_step_budget_reaches_dop853() {
    let dir = scratch();
    let want = pendulum_reference(Method::Dop853);
    let attempts =
        want.extra_scalar("accepted_steps").unwrap() + want.extra_scalar("rejected_steps").unwrap();
    // Non-trivial: the run takes many steps, so the budget below it is a real budget.
    assert!(attempts > 10.0, "{attempts}");
    let enough = format!("{attempts}");
    let mut args = pendulum_args("dop853");
    args.extend_from_slice(&["--max-steps", &enough]);
    let path = simulate(dir.path(), "run.npz", &args);
    let mut npz = NpzReader::new(File::open(&path).unwrap()).unwrap();
    let q: Array2<f64> = npz.by_name("q").unwrap();
    same_bits("q", q.iter().copied(), want.q().unwrap().iter().copied());

    let short = format!("{}", attempts - 1.0);
    let mut args = vec!["simulate"];
    args.extend(pendulum_args("dop853"));
    args.extend_from_slice(&["--max-steps", &short, "--out", "short.npz"]);
    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert_ne!(out.status.code(), Some(0), "{err}");
    assert!(err.contains(&format!("budget of {short} steps")), "{err}");
    assert!(!dir.path().join("short.npz").exists());
}
