//! Benchmarks of physicskit: the peer-comparison workloads ([`workloads`]), the plain-loop
//! references ([`plain`]) that the library's per-step time is held against, and what the
//! ensemble binaries share ([`ensembles`]).

pub mod ensembles;
pub mod plain;
pub mod workloads;

/// The tolerances our side of `heyoka_compare.py` runs: every half decade from `10^-first`
/// to `10^-last`, so that the script's "our fastest run to heyoka's error" is searched on a
/// grid finer than heyoka's (its tolerances are the whole decades among these). Parsed from
/// decimals, so the decades are the doubles of their literals (`1e-10` is `1e-10`).
pub fn half_decades(first: u32, last: u32) -> Vec<f64> {
    let mut out = Vec::new();
    for n in first..=last {
        out.extend(format!("1e-{n}").parse::<f64>());
        if n < last {
            out.extend(format!("3.1622776601683795e-{}", n + 1).parse::<f64>());
        }
    }
    out
}

// A unit test rather than an integration test: an integration test makes `cargo test` build
// the package's six binaries too (about a minute of CI on two cores).
#[cfg(test)]
mod plain_agrees;
