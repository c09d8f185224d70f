//! Helpers shared by the command-line tests: run the built binary in a scratch directory.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `physicskit args...` with `dir` as working directory.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_physicskit"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the physicskit binary runs")
}

/// A fresh empty scratch directory, removed when dropped.
pub fn scratch() -> tempfile::TempDir {
    tempfile::tempdir().expect("a scratch directory")
}

/// Every entry of `dir` (hidden files included), sorted.
pub fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("readable scratch directory")
        .map(|e| e.expect("entry").path())
        .collect();
    v.sort();
    v
}

/// Stderr as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Stdout as text.
pub fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The `--help` text of `physicskit args... --help`.
pub fn help(args: &[&str]) -> String {
    let dir = scratch();
    let out = run_in(dir.path(), &[args, &["--help"][..]].concat());
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    stdout(&out)
}
