//! Parallel ensembles give the serial result, bit for bit, on any number of threads.

use crate::fixtures::PendulumBank;
use physicskit::classical::integrators::{integrate_ensemble, ENSEMBLE_CHUNK};
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, IntegrateOptions, Method};

fn parallel(threads: usize, n: usize) -> physicskit::classical::SimulationResult {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut bank = PendulumBank::new(n);
        integrate_ensemble(
            &mut bank,
            (0.0, 0.5),
            1e-3,
            Method::Yoshida4,
            IntegrateOptions::stride(100),
        )
        .unwrap()
    })
}

#[test]
fn ensemble_equals_serial_bit_for_bit_on_any_thread_count() {
    // More than two chunks, the last one partial.
    let n = 2 * ENSEMBLE_CHUNK + 123;
    let mut serial_bank = PendulumBank::new(n);
    let serial = serial_bank
        .integrate_with(
            (0.0, 0.5),
            1e-3,
            Method::Yoshida4,
            IntegrateOptions::stride(100),
        )
        .unwrap();
    for threads in [1, 2, 3] {
        let par = parallel(threads, n);
        assert_eq!(par.t, serial.t, "{threads} threads");
        assert_eq!(par.y, serial.y, "{threads} threads");
        assert_eq!(par.energy, serial.energy, "{threads} threads");
    }
    // The system is left at the final state, as after a serial run.
    let mut bank = PendulumBank::new(n);
    integrate_ensemble(
        &mut bank,
        (0.0, 0.5),
        1e-3,
        Method::Yoshida4,
        IntegrateOptions::final_only(),
    )
    .unwrap();
    assert_eq!(bank.state(), serial_bank.state());
    assert_eq!(bank.t(), serial_bank.t());
}

#[test]
fn a_large_pendulum_swarm_runs_in_parallel_and_equals_the_serial_run() {
    use physicskit::classical::integrators::driver::integrate_hamiltonian;
    use physicskit::classical::systems::{PendulumSwarm, PARALLEL_MEMBERS};
    let n = PARALLEL_MEMBERS + 77;
    let make = || PendulumSwarm::from_box(1.0, 0.0, 0.5, 0.5, n, 1.0, 7).unwrap();
    let mut serial_swarm = make();
    let serial = integrate_hamiltonian(
        &mut serial_swarm,
        (0.0, 0.2),
        1e-3,
        Method::Yoshida4,
        IntegrateOptions::stride(50),
    )
    .unwrap();
    for threads in [1, 2, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let par = pool.install(|| {
            let mut swarm = make();
            let r = swarm
                .integrate_with(
                    (0.0, 0.2),
                    1e-3,
                    Method::Yoshida4,
                    IntegrateOptions::stride(50),
                )
                .unwrap();
            assert_eq!(swarm.state(), serial_swarm.state());
            r
        });
        // The parallel path really ran (it reports its chunk count).
        assert!(par.extra_scalar("chunks").unwrap() >= 2.0);
        assert_eq!(par.y, serial.y, "{threads} threads");
        assert_eq!(par.energy, serial.energy, "{threads} threads");
    }
}

#[test]
fn an_ensemble_too_large_for_memory_is_refused() {
    use physicskit::classical::systems::PendulumSwarm;
    let mut swarm = PendulumSwarm::from_box(1.0, 0.0, 0.5, 0.5, 1_000_000, 1.0, 0).unwrap();
    // 1e6 pendulums x 1e5 stored samples is ~3 PB.
    let err = swarm
        .integrate((0.0, 100.0), 1e-3, Method::Yoshida4)
        .unwrap_err();
    assert!(
        matches!(err, physicskit::classical::Error::TrajectoryTooLarge { .. }),
        "{err}"
    );
}
