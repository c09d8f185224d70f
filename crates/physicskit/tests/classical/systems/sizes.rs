//! Sizes that cannot fit in memory are refused before anything is allocated.
//!
//! Each constructor that allocates storage of a user-given size `n` must return
//! [`Error::TooLarge`] for `n = 10^12` (tens of terabytes at any per-site cost: more than any
//! machine this runs on has) and for `n = 2^62` (whose byte count overflows `usize`: the check
//! must not wrap). These tests are their own proof that nothing was allocated first: an
//! allocation of that size aborts the process (or panics with "capacity overflow"), which would
//! fail the test binary.

use physicskit::classical::core::check_items_fit;
use physicskit::classical::systems::{
    ChainModes, FPUTChain, NormalModes, PendulumSwarm, SineGordonChain,
};
use physicskit::classical::Error;

/// The sizes of the issue: 10^12 and 2^62.
const HUGE: [usize; 2] = [1_000_000_000_000, 1 << 62];

/// Asserts that `result` is the size refusal naming `n` with the given value.
#[track_caller]
fn too_large<T>(result: physicskit::classical::Result<T>, n: usize) {
    match result {
        Err(Error::TooLarge { name, value, .. }) => {
            assert_eq!(name, "n");
            assert_eq!(value, n as u128);
        }
        Err(other) => panic!("expected TooLarge for n = {n}, got {other}"),
        Ok(_) => panic!("n = {n} was accepted"),
    }
}

#[test]
fn chain_modes_refuse_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(ChainModes::new(n, 1.0, 1.0), n);
    }
}

#[test]
fn fput_chain_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(FPUTChain::new(n, 1.0, 1.0, 0.5, 1, 1.0), n);
    }
}

#[test]
fn sine_gordon_chain_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(SineGordonChain::new(n, 1.0, 1.0, None, None), n);
    }
}

#[test]
fn sine_gordon_kink_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(SineGordonChain::kink(n, 10.0, 1.0, 0.0, 1), n);
    }
}

#[test]
fn sine_gordon_boosted_kink_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(
            SineGordonChain::boosted_kink(n, 1.0, 1.0, 10.0, 1.0, 0.1, -1),
            n,
        );
    }
}

#[test]
fn sine_gordon_kink_antikink_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(
            SineGordonChain::kink_antikink(n, 1.0, 1.0, 10.0, 50.0, 1.0, 0.2),
            n,
        );
    }
}

#[test]
fn pendulum_swarm_from_box_refuses_a_size_that_does_not_fit() {
    for n in HUGE {
        too_large(PendulumSwarm::from_box(1.0, 0.0, 0.1, 0.1, n, 1.0, 7), n);
    }
}

/// The size check itself: small blocks pass without a reading of the available memory, the
/// product of the largest inputs does not wrap, and the error says what was asked.
#[test]
fn check_items_fit_computes_the_bytes_without_overflow() {
    assert!(check_items_fit("n", 1000, 64).is_ok());
    assert!(check_items_fit("n", 0, usize::MAX).is_ok());
    match check_items_fit("n", usize::MAX, usize::MAX) {
        Err(Error::TooLarge {
            bytes, item_bytes, ..
        }) => {
            assert_eq!(bytes, usize::MAX as u128 * usize::MAX as u128);
            assert_eq!(item_bytes, usize::MAX as u128);
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    let message = check_items_fit("n", 1 << 62, 8).unwrap_err().to_string();
    assert!(
        message.starts_with("`n` = 4611686018427387904 is too large"),
        "{message}"
    );
}

/// A size that fits is still accepted: the guard is no stricter than the memory (2^19 sites
/// of an FPUT chain take about 38 MB, above the 16 MiB below which nothing is read).
#[test]
fn a_large_chain_that_fits_is_built() {
    let chain = FPUTChain::new(1 << 19, 1.0, 1.0, 0.5, 3, 1.0).unwrap();
    assert_eq!(chain.modes().n(), 1 << 19);
}
