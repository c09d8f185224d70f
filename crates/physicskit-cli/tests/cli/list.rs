//! `list` names every system the spec asks for, each with its methods and defaults, and each
//! name it prints is accepted by `simulate`.

use crate::common::{run_in, scratch, stdout};

/// The systems the command line must offer: the spec's twelve (issue 6), their alternate
/// constructors, and the two reference examples.
const EXPECTED: &[&str] = &[
    "pendulum",
    "harmonic-oscillator",
    "kepler",
    "kepler-state",
    "henon-heiles",
    "pendulum-swarm",
    "pendulum-swarm-state",
    "projectile",
    "projectile-state",
    "harmonic-chain",
    "fput",
    "sine-gordon",
    "sine-gordon-state",
    "double-pendulum",
    "hoop",
    "coupled-oscillators",
    "heavy-top",
    "euler-top",
];

#[test]
fn list_mentions_every_system_with_methods_and_defaults() {
    let dir = scratch();
    let out = run_in(dir.path(), &["list"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    let listed: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with(' ') && !l.is_empty() && !l.starts_with("Usage"))
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    for name in EXPECTED {
        assert!(listed.contains(name), "`{name}` not listed:\n{text}");
    }
    assert_eq!(
        text.matches("(default)").count(),
        listed.len(),
        "every system marks one default method"
    );
    assert_eq!(text.matches("  methods: ").count(), listed.len());
    for name in listed {
        let help = run_in(dir.path(), &["simulate", name, "--help"]);
        assert_eq!(help.status.code(), Some(0), "simulate {name} --help");
    }
}
