//! Bad input: one line `error: ...` on stderr, exit status 2, no panic, and no file written
//! (not even a temporary one) — one test per case the issue lists, plus the value checks.

use std::path::Path;

use crate::common::{entries, run_in, scratch, stderr};
use physicskit::classical::Method;

/// A valid run; each case below breaks one argument of it.
const GOOD: [&str; 8] = [
    "simulate", "pendulum", "--dt", "0.1", "--t1", "1", "--out", "a.csv",
];

/// Runs `args` in a fresh directory and checks the failure contract; returns stderr.
pub fn fails(args: &[&str]) -> String {
    let dir = scratch();
    let out = run_in(dir.path(), args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "args {args:?}, stderr: {err}");
    assert!(out.stdout.is_empty(), "args {args:?} printed to stdout");
    assert!(err.starts_with("error: "), "not an error line: {err:?}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err:?}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        entries(dir.path()).is_empty(),
        "args {args:?} left files: {:?}",
        entries(dir.path())
    );
    err
}

/// `simulate pendulum` with the valid run's options, each replaceable: `dt = 0.1`,
/// `t1 = 1`, `out = a.csv`, followed by `extra`.
fn pendulum(dt: &str, t1: &str, out: &str, extra: &[&str]) -> String {
    let mut args = vec!["simulate", "pendulum", "--dt", dt, "--t1", t1, "--out", out];
    args.extend_from_slice(extra);
    fails(&args)
}

/// `simulate <system> <flags> --dt 0.1 --t1 1 --out <out>`, which must fail; returns stderr.
fn system_fails(system: &str, flags: &[&str], out: &str) -> String {
    let mut args = vec!["simulate", system];
    args.extend_from_slice(flags);
    args.extend_from_slice(&["--dt", "0.1", "--t1", "1", "--out", out]);
    fails(&args)
}

#[test]
fn the_good_run_succeeds() {
    // Guards the cases below: each must fail because of its one change, not the baseline.
    let dir = scratch();
    let out = run_in(dir.path(), &GOOD);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // No progress bar or chatter when stderr is not a terminal.
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
    assert_eq!(entries(dir.path()), vec![dir.path().join("a.csv")]);
}

#[test]
fn unknown_system() {
    let err = system_fails("warp-drive", &[], "a.csv");
    assert!(err.contains("unknown system `warp-drive`"), "{err}");
    assert!(
        err.contains("pendulum"),
        "should list the known systems: {err}"
    );
}

#[test]
fn unknown_parameter() {
    let err = pendulum("0.1", "1", "a.csv", &["--length", "2"]);
    assert!(err.contains("unknown parameter `--length`"), "{err}");
    assert!(
        err.contains("g_over_l"),
        "should list the parameters: {err}"
    );
}

#[test]
fn unknown_method() {
    let err = pendulum("0.1", "1", "a.csv", &["--method", "euler"]);
    assert!(err.contains("unknown method `euler`"), "{err}");
}

#[test]
fn unknown_method_lists_the_methods_of_that_system() {
    // The list is the catalogue's for the system: every method for a separable pendulum, only
    // those for non-separable systems for the (Lagrangian) double pendulum.
    for system in ["pendulum", "double-pendulum"] {
        let err = system_fails(system, &["--method", "euler"], "a.csv");
        let entry = physicskit::classical::catalog::find(system).unwrap();
        let listed = err.split("valid methods are: ").nth(1).unwrap_or("").trim();
        let want: Vec<&str> = entry.methods().map(|m| m.name()).collect();
        assert_eq!(listed, want.join(", "), "{system}: {err}");
        assert!(listed.contains("gauss_legendre6"), "{err}");
        assert_eq!(listed.contains("verlet"), system == "pendulum", "{err}");
    }
}

/// A method that needs a Taylor form, asked of a catalogue system: refused, naming the method,
/// the system and the systems that have one. The method is found from the table's facts.
#[test]
fn a_method_needing_a_taylor_form_is_refused_by_name() {
    for method in Method::ALL.into_iter().filter(|m| m.needs_taylor_form()) {
        let err = system_fails("pendulum", &["--method", method.name()], "a.csv");
        assert!(err.contains(&format!("`{method}`")), "{err}");
        assert!(err.contains("`pendulum`"), "{err}");
        assert!(err.contains("HamiltonianEngine"), "{err}");
    }
}

#[test]
fn zero_step() {
    let err = pendulum("0", "1", "a.csv", &[]);
    assert!(err.contains("dt must be finite and > 0"), "{err}");
}

#[test]
fn negative_step() {
    pendulum("-0.1", "1", "a.csv", &[]);
}

#[test]
fn end_before_start() {
    let err = pendulum("0.1", "1", "a.csv", &["--t0", "2"]);
    assert!(err.contains("t1 must be >= t0"), "{err}");
}

#[test]
fn unwritable_path() {
    let err = pendulum("0.1", "1", "no/such/dir/a.csv", &[]);
    assert!(err.contains("does not exist"), "{err}");
}

#[cfg(unix)]
#[test]
fn read_only_directory() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch();
    let ro = dir.path().join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    // root ignores directory permissions; the check is then meaningless, so skip it.
    if std::fs::write(ro.join("probe"), b"").is_ok() {
        eprintln!("running as root: permission check skipped");
        return;
    }
    let out = run_in(
        dir.path(),
        &GOOD.map(|a| if a == "a.csv" { "ro/a.csv" } else { a }),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(entries(&ro).is_empty());
}

#[test]
fn output_is_a_directory() {
    // `out.csv` exists as a directory, so the name has a valid extension but cannot be a file.
    let dir = scratch();
    std::fs::create_dir(dir.path().join("out.csv")).unwrap();
    let out = run_in(
        dir.path(),
        &GOOD.map(|a| if a == "a.csv" { "out.csv" } else { a }),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("is a directory"));
    assert_eq!(entries(dir.path()), vec![dir.path().join("out.csv")]);
}

#[test]
fn unknown_extension() {
    let err = pendulum("0.1", "1", "a.txt", &[]);
    assert!(err.contains("unknown output extension `.txt`"), "{err}");
    pendulum("0.1", "1", "no-extension", &[]);
}

#[test]
fn non_numeric_value() {
    let err = pendulum("0.1", "1", "a.csv", &["--q0", "one"]);
    assert!(err.contains("`--q0`"), "{err}");
    pendulum("fast", "1", "a.csv", &[]);
    pendulum("0.1", "1", "a.csv", &["--q0", "nan"]);
}

#[test]
fn out_of_range_physics_parameter() {
    // The catalogue's range for g/l is > 0; the message names the flag and the range.
    let err = pendulum("0.1", "1", "a.csv", &["--g_over_l", "-9.81"]);
    assert!(err.contains("`--g_over_l`") && err.contains("> 0"), "{err}");
}

#[test]
fn integers_are_integers() {
    let err = system_fails("pendulum-swarm", &["--n", "1.5"], "a.csv");
    assert!(
        err.contains("`--n`") && err.contains("expected an integer"),
        "{err}"
    );
    let err = system_fails("pendulum-swarm", &["--n", "0"], "a.csv");
    assert!(err.contains("`--n`") && err.contains(">= 1"), "{err}");
    let err = system_fails("pendulum-swarm", &["--n", "99999999999999999999"], "a.csv");
    assert!(
        err.contains("`--n`") && err.contains("out of range"),
        "{err}"
    );
    let err = system_fails("pendulum-swarm", &["--seed", "-1"], "a.csv");
    assert!(err.contains("`--seed`"), "{err}");
}

#[test]
fn a_word_outside_its_choice() {
    let err = system_fails("sine-gordon", &["--initial", "breather"], "a.csv");
    assert!(
        err.contains("`--initial`") && err.contains("kink-antikink"),
        "{err}"
    );
}

#[test]
fn span_not_a_whole_number_of_steps() {
    pendulum("0.3", "1", "a.csv", &[]);
}

#[test]
fn missing_required_option() {
    let err = fails(&["simulate", "pendulum", "--t1", "1", "--out", "a.csv"]);
    assert!(err.contains("--dt"), "{err}");
}

#[test]
fn bad_stride() {
    pendulum("0.1", "1", "a.csv", &["--stride", "0"]);
}

/// A run that fails half-way (rk4 far outside its stability region overflows to infinity)
/// leaves no temporary file and does not touch an existing file at the destination.
#[test]
fn failed_run_leaves_existing_file_untouched() {
    let dir = scratch();
    let target = dir.path().join("a.json");
    std::fs::write(&target, b"previous").unwrap();
    let out = run_in(
        dir.path(),
        &[
            "simulate",
            "harmonic-oscillator",
            "--method",
            "rk4",
            // |R(i omega dt)| ~ 400 per step at omega dt = 10: overflow within ~120 steps.
            "--dt",
            "10",
            "--t1",
            "100000",
            "--out",
            "a.json",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("non-finite"), "{}", stderr(&out));
    assert_eq!(entries(dir.path()), vec![target.clone()]);
    assert_eq!(std::fs::read(Path::new(&target)).unwrap(), b"previous");
}

#[test]
fn wrong_array_length() {
    // Declared length 2: refused by the catalogue, naming the flag.
    let err = system_fails("henon-heiles", &["--q0", "0,0.1,0.2"], "a.csv");
    assert!(
        err.contains("`--q0`") && err.contains("expected 2"),
        "{err}"
    );
    // Length set by another parameter (n = 3): also the catalogue's.
    let err = system_fails("coupled-oscillators", &["--q0", "0.1,0.2"], "a.csv");
    assert!(err.contains("q0") && err.contains("expected 3"), "{err}");
}

#[test]
fn library_range_checks_reach_the_user() {
    // |velocity| >= 1 has no Lorentz boost (SineGordonChain::kink).
    let err = system_fails("sine-gordon", &["--velocity", "1.0"], "a.npz");
    assert!(err.contains("velocity"), "{err}");
    // Unbound orbits are refused by KeplerSystem::from_orbital_elements.
    let err = system_fails("kepler", &["--e", "1.2"], "a.npz");
    assert!(err.contains("eccentricity"), "{err}");
    // A zero quaternion is no rotation (EulerTop::new).
    let err = system_fails("euler-top", &["--quat0", "0,0,0,0"], "a.npz");
    assert!(err.contains("quat0") && err.contains("quaternion"), "{err}");
}

#[test]
fn method_the_system_cannot_use() {
    // Refused by the catalogue's methods for the entry: the double pendulum is not
    // separable.
    let err = system_fails("double-pendulum", &["--method", "verlet"], "a.csv");
    assert!(
        err.contains("verlet") && err.contains("implicit_midpoint"),
        "{err}"
    );
    // Refused by the library: drag is not conservative, so splitting would drop it.
    let err = system_fails(
        "projectile",
        &["--drag_coeff", "0.1", "--method", "yoshida4"],
        "a.csv",
    );
    assert!(err.contains("yoshida4"), "{err}");
}

/// A long `simulate` run.
const LONG_RUN: [&str; 12] = [
    "simulate",
    "pendulum-swarm",
    "--n",
    "2000",
    "--dt",
    "0.01",
    "--t1",
    "1e6",
    "--stride",
    "100000",
    "--out",
    "a.npz",
];

/// Starts the long run `args`, sends it `signal` (a `kill` name) once the run has started, and
/// checks that it stops with exit status `status` and one error line naming the signal,
/// leaving no file (the temporary `.physicskit-*.tmp` included) behind.
#[cfg(unix)]
pub fn signal_stops_a_run_and_leaves_nothing(args: &[&str], signal: &str, status: i32) {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let dir = scratch();
    let child = Command::new(env!("CARGO_BIN_EXE_physicskit"))
        .args(args)
        .current_dir(dir.path())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The temporary file appears once input is validated, just before integrating.
    let start = Instant::now();
    while entries(dir.path()).is_empty() {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "run never started"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(200));
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let out = child.wait_with_output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(status), "{err}");
    assert!(err.contains("interrupted"), "{err}");
    assert!(err.contains(&format!("SIG{signal}")), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err:?}");
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

/// Ctrl-C (SIGINT) stops a long run at the next progress check: exit status 130 (128 + 2, as
/// shells report it), and the temporary file is removed, so nothing is left behind.
#[cfg(unix)]
#[test]
fn interrupted_run_leaves_nothing() {
    signal_stops_a_run_and_leaves_nothing(&LONG_RUN, "INT", 130);
}

/// SIGTERM (what `kill`, systemd and container runtimes send) is handled as Ctrl-C: exit
/// status 143 (128 + 15), no temporary file left.
#[cfg(unix)]
#[test]
fn terminated_run_leaves_nothing() {
    signal_stops_a_run_and_leaves_nothing(&LONG_RUN, "TERM", 143);
}

/// SIGHUP (the terminal closed): exit status 129, no temporary file left.
#[cfg(unix)]
#[test]
fn hung_up_run_leaves_nothing() {
    signal_stops_a_run_and_leaves_nothing(&LONG_RUN, "HUP", 129);
}

/// Sizes that cannot fit in memory (the cases: 10^12 sites, and 2^62, whose byte
/// count overflows) are refused by the library before anything is allocated: exit 2, one line
/// naming `n`, no file. Before, 10^12 aborted (exit 134) and 2^62 panicked (exit 101).
#[test]
fn sizes_that_cannot_fit_in_memory_are_refused() {
    for n in ["1000000000000", "4611686018427387904"] {
        for (system, extra) in [
            ("fput", &[][..]),
            ("pendulum-swarm", &[][..]),
            ("sine-gordon", &[][..]),
            ("sine-gordon", &["--initial", "kink"][..]),
            ("sine-gordon", &["--initial", "rest"][..]),
            ("sine-gordon-state", &[][..]),
        ] {
            let mut flags = vec!["--n", n];
            flags.extend_from_slice(extra);
            let err = system_fails(system, &flags, "o.npz");
            assert!(
                err.contains(&format!("`{n}` for `--n`")) && err.contains("bytes, more than"),
                "{system}: {err}"
            );
        }
    }
    // A count beyond u64 is not a number the CLI takes: still one clean line.
    let err = system_fails("fput", &["--n", "18446744073709551616"], "o.npz");
    assert!(err.contains("--n"), "{err}");
}

#[test]
fn tolerances_with_a_fixed_step_method() {
    let err = pendulum("0.1", "1", "a.csv", &["--method", "rk4", "--rtol", "1e-8"]);
    assert!(err.contains("`--rtol`") && err.contains("dop853"), "{err}");
    let err = pendulum("0.1", "1", "a.csv", &["--atol", "1e-8"]);
    assert!(
        err.contains("`--atol`") && err.contains("fixed-step"),
        "{err}"
    );
}

#[test]
fn a_step_budget_with_a_fixed_step_method() {
    let err = pendulum("0.1", "1", "a.csv", &["--max-steps", "100"]);
    assert!(
        err.contains("`--max-steps`") && err.contains("fixed-step") && err.contains("dop853"),
        "{err}"
    );
}

#[test]
fn step_budgets_that_are_not_counts() {
    for value in ["0", "-1", "1.5", "x", "nan", "18446744073709551616"] {
        let err = pendulum(
            "0.1",
            "1",
            "a.csv",
            &["--method", "dop853", "--max-steps", value],
        );
        assert!(
            err.contains("`--max-steps`") && err.contains(value),
            "{err}"
        );
    }
}

#[test]
fn tolerances_that_are_not_positive_numbers() {
    for (flag, value) in [
        ("--rtol", "0"),
        ("--rtol", "-0.001"),
        ("--atol", "nan"),
        ("--atol", "x"),
    ] {
        let err = pendulum("0.1", "1", "a.csv", &["--method", "dop853", flag, value]);
        assert!(
            err.contains(&format!("`{flag}`")) && err.contains(value),
            "{err}"
        );
    }
}
