//! Watched ensembles (with an observer, as the front ends run them: progress and Ctrl-C) cost
//! their work, not a whole polling period: the calling thread waits on the workers, and the
//! observer is still called when they finish.

use std::ops::ControlFlow;
use std::time::Instant;

use crate::fixtures::PendulumBank;
use physicskit::classical::catalog;
use physicskit::classical::ensemble::{self, Members, Plan, Sweep};
use physicskit::classical::integrators::ensemble::PROGRESS_PERIOD;
use physicskit::classical::integrators::integrate_ensemble;
use physicskit::classical::{IntegrateOptions, Method, Observer};

/// Counts its calls.
struct Count(usize);

impl Observer for Count {
    fn observe(&mut self, _: usize, _: usize, _: f64) -> ControlFlow<()> {
        self.0 += 1;
        ControlFlow::Continue(())
    }
}

/// Twenty tiny watched runs (4 members of 10 steps: microseconds of work each) take less than
/// ten polling periods in all; a loop that slept a period before looking took at least twenty
/// (400 ms). Ten periods leave 190 ms of slack for thread start-up on a loaded machine. Each
/// run calls its observer at least once (the final report).
#[test]
fn short_watched_ensembles_cost_their_work() {
    let entry = catalog::find("harmonic-oscillator").unwrap();
    let members = Members {
        sweeps: vec![Sweep::new("q0", vec![0.1, 0.2, 0.3, 0.4])],
        n: 4,
        ..Members::default()
    };
    let plan = Plan {
        t_span: (0.0, 0.1),
        dt: 0.01,
        method: None,
        stride: None,
        reductions: vec![],
        final_state: true,
        threads: None,
        tolerances: None,
    };
    let start = Instant::now();
    for _ in 0..20 {
        let mut count = Count(0);
        ensemble::run(entry, &members, &plan, Some(&mut count)).unwrap();
        assert!(count.0 >= 1, "the observer was not called");
    }
    let engine = start.elapsed();
    let start = Instant::now();
    for _ in 0..20 {
        let mut count = Count(0);
        let mut bank = PendulumBank::new(4);
        integrate_ensemble(
            &mut bank,
            (0.0, 0.01),
            1e-3,
            Method::Yoshida4,
            IntegrateOptions {
                observer: Some(&mut count),
                ..IntegrateOptions::final_only()
            },
        )
        .unwrap();
        assert!(count.0 >= 1, "the observer was not called");
    }
    let chunks = start.elapsed();
    println!("20 watched runs: engine {engine:?}, chunked {chunks:?}");
    assert!(engine < 10 * PROGRESS_PERIOD, "{engine:?}");
    assert!(chunks < 10 * PROGRESS_PERIOD, "{chunks:?}");
}
