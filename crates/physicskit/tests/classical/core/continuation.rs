//! A second `integrate` call continues the trajectory of the first.

use physicskit::classical::core::method::Scheme;
use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, Method};

#[test]
fn two_calls_equal_one_call() {
    // The pendulum is hand-written, without a Taylor form: a method that needs one is checked
    // on an expression system in integrators/taylor.rs.
    for method in Method::ALL.into_iter().filter(|m| !m.needs_taylor_form()) {
        let mut whole = Pendulum::new(2.0, 0.0, 1.0).unwrap();
        let one = whole.integrate((0.0, 2.0), 0.01, method).unwrap();
        let mut split = Pendulum::new(2.0, 0.0, 1.0).unwrap();
        split.integrate((0.0, 1.0), 0.01, method).unwrap();
        let second = split.integrate((1.0, 2.0), 0.01, method).unwrap();
        let (a, b) = (one.final_state(), second.final_state());
        let diff = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
        if method.is_adaptive() {
            // The second call starts its step-size control afresh, so it steps elsewhere: the
            // two runs agree to their global error at the default tolerances (rtol 1e-10 per
            // step on |y| ~ 2 over some tens of steps: ~1e-9 at most), not bit for bit.
            assert!(diff <= 1e-9, "{method}: {diff:e}");
        } else if matches!(method.info().scheme, Scheme::ImplicitRk) {
            // The second call restarts the predictor from scratch, so its solves start
            // elsewhere and stop at the rounding floor on possibly different last bits: allow
            // a few ulps of |y| ~ 2 (4.4e-16 each) accumulated over the 100 further steps.
            assert!(diff <= 1e-13, "{method}: {diff:e}");
        } else {
            // Explicit methods repeat the same arithmetic: bit-identical.
            assert_eq!(a, b, "{method}");
        }
    }
}
