//! Fixed-step ensembles of splitting-method members, `t = 100`: 1000 Hénon–Heiles orbits
//! (`E = 1/8`, launched on `x = 0`) and 1000 Kepler orbits (eccentricities 0.1 to 0.6) by
//! `yoshida4` and `sofroniou_spaletta10`; 1000 pendulums (amplitudes 0.1 to 3), 1000 FPUT
//! chains of 32 sites (mode 1, amplitudes 0.5 to 2.5, `beta = 0.7`) and 1000 Toda rings of 8
//! particles (momenta 0.2 to 1.2 in a fixed pattern) by `yoshida4`. Name workloads (`fput`,
//! `kepler`, ...) after `N` to run only those.
//!
//! Per workload, three timings:
//! - `alone`: every member built through the catalogue and run by its own `integrate`, one
//!   after another on this thread (the member-by-member path, and the scalar step's cost);
//! - `ensemble1`, `ensemble2`: `ensemble::run` of the same members on one and two threads,
//!   final states only (with a splitting method, the members of a separable system whose
//!   force runs across lanes go in SIMD lanes; the FPUT chain, which has none, is the control:
//!   its ensemble runs member by member).
//!
//! Each time is the best of `N` (first argument, default 7) after one untimed run. The
//! ensemble's final states are checked against the `alone` runs bit for bit (`same_bits`).

use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, FromCatalogue, MemberSource, Members, Plan, Sweep};
use physicskit::classical::model::Value;
use physicskit::classical::{IntegrateOptions, Method, Sampling};
use physicskit_benchmarks::ensembles::{best_of, henon_heiles, MEMBERS};

const T_END: f64 = 100.0;

/// `target` swept linearly from `from` towards `to` over the members.
fn swept(target: &str, from: f64, to: f64) -> Members {
    Members {
        sweeps: vec![Sweep::new(
            target,
            (0..MEMBERS)
                .map(|i| from + (to - from) * i as f64 / MEMBERS as f64)
                .collect(),
        )],
        n: MEMBERS,
        ..Members::default()
    }
}

/// Toda rings of 8 particles at rest positions, momenta `s (1.5, 0, 0, 0, -0.5, 0, 0, -1)` (the
/// catalogue's pattern) scaled by `s` from 0.2 to 1.2.
fn toda() -> Members {
    let pattern = [1.5, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, -1.0];
    let states = (0..MEMBERS)
        .flat_map(|m| {
            let s = 0.2 + m as f64 / MEMBERS as f64;
            [0.0; 8].into_iter().chain(pattern.map(|p| s * p))
        })
        .collect();
    Members {
        states: Some(states),
        n: MEMBERS,
        ..Members::default()
    }
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let workloads = [
        ("henon-heiles", henon_heiles(), Method::Yoshida4, 0.01),
        (
            "henon-heiles",
            henon_heiles(),
            Method::SofroniouSpaletta10,
            0.05,
        ),
        // Kepler orbits of eccentricities 0.1 to 0.6 (`a = 1`, period `2 pi`).
        ("kepler", swept("e", 0.1, 0.6), Method::Yoshida4, 0.001),
        (
            "kepler",
            swept("e", 0.1, 0.6),
            Method::SofroniouSpaletta10,
            0.01,
        ),
        // Pendulums released from rest at amplitudes 0.1 to 3 rad.
        ("pendulum", swept("q0", 0.1, 3.0), Method::Yoshida4, 0.01),
        // FPUT chains of 32 sites (the default), mode 1 at amplitudes 0.5 to 2.5, beta 0.7.
        (
            "fput",
            Members {
                common: vec![("beta".into(), Value::Scalar(0.7))],
                ..swept("amplitude", 0.5, 2.5)
            },
            Method::Yoshida4,
            0.05,
        ),
        ("toda", toda(), Method::Yoshida4, 0.01),
    ];
    let only: Vec<String> = std::env::args().skip(2).collect();
    for (name, members, method, dt) in workloads {
        if !only.is_empty() && !only.iter().any(|o| o == name) {
            continue;
        }
        let entry = catalog::find(name).expect("catalogue entry");
        let source = FromCatalogue::new(entry, &members).expect("members");
        let (alone, reference) = best_of(n, || {
            (0..MEMBERS)
                .flat_map(|i| {
                    let result = source
                        .build(i, 0.0)
                        .expect("member")
                        .integrate(
                            (0.0, T_END),
                            dt,
                            method,
                            IntegrateOptions {
                                sampling: Sampling::FinalOnly,
                                skip_energy: true,
                                ..IntegrateOptions::default()
                            },
                        )
                        .expect("run");
                    result.y.row(result.y.nrows() - 1).to_vec()
                })
                .collect()
        });
        let run = |threads: usize| {
            let plan = Plan {
                t_span: (0.0, T_END),
                dt,
                method: Some(method),
                stride: None,
                reductions: vec![],
                final_state: true,
                threads: Some(threads),
                tolerances: None,
            };
            best_of(n, || {
                ensemble::run(entry, &members, &plan, None)
                    .expect("ensemble")
                    .final_state
                    .iter()
                    .copied()
                    .collect()
            })
        };
        let (one, out1) = run(1);
        let (two, out2) = run(2);
        let same = |a: &[f64]| {
            a.iter()
                .zip(&reference)
                .all(|(x, y)| x.to_bits() == y.to_bits())
        };
        println!(
            "{{\"system\": \"{name}\", \"method\": \"{}\", \"dt\": {dt}, \"steps\": {}, \
             \"alone_ms\": {alone:.2}, \"ensemble1_ms\": {one:.2}, \"ensemble2_ms\": {two:.2}, \
             \"same_bits\": {}}}",
            method.name(),
            (T_END / dt).round(),
            same(&out1) && same(&out2)
        );
    }
}
