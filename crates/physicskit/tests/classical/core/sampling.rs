//! Sampling options, result layout and reproducibility.

use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Method, Sampling};
use proptest::prelude::*;

#[test]
fn full_sampling_has_n_plus_one_contiguous_samples() {
    let mut p = Pendulum::new(1.0, 0.2, 1.0).unwrap();
    let r = p.integrate((0.0, 1.0), 0.01, Method::Yoshida4).unwrap();
    assert_eq!(r.n_samples(), 101);
    assert_eq!(r.y.dim(), (101, 2));
    let (q, pm) = (r.q().unwrap(), r.p().unwrap());
    // The stored arrays are C-contiguous, so numpy takes them without copying.
    assert!(r.y.is_standard_layout() && r.t.is_standard_layout());
    // q and p are views of the halves of y, sample by sample.
    assert_eq!(q.dim(), (101, 1));
    assert_eq!(pm.dim(), (101, 1));
    assert_eq!(q.column(0), r.y.column(0));
    assert_eq!(pm.column(0), r.y.column(1));
    assert_eq!(r.method, "yoshida4");
    // The clock is t0 + i dt, not an accumulated sum.
    assert_eq!(r.t[100], 1.0);
    assert_eq!(r.t[37], 37.0 * 0.01);
}

#[test]
fn the_system_is_left_at_the_final_sample() {
    let mut p = Pendulum::new(1.0, 0.2, 1.0).unwrap();
    let r = p.integrate((0.5, 1.5), 0.01, Method::Verlet).unwrap();
    assert_eq!(physicskit::classical::DynamicalSystem::t(&p), 1.5);
    assert_eq!(
        physicskit::classical::DynamicalSystem::state(&p),
        r.final_state().as_slice().unwrap()
    );
}

fn run(sampling: Sampling, n: usize) -> physicskit::classical::SimulationResult {
    let mut p = Pendulum::new(1.0, 0.2, 1.0).unwrap();
    let options = IntegrateOptions {
        sampling,
        ..Default::default()
    };
    p.integrate_with((0.0, n as f64 * 0.01), 0.01, Method::Yoshida4, options)
        .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A strided run stores exactly the strided rows of the full run (bit for bit), plus the
    /// final row, and nothing else.
    #[test]
    fn stride_stores_the_strided_rows_of_the_full_run(n in 0usize..300, k in 1usize..40) {
        let full = run(Sampling::All, n);
        let strided = run(Sampling::Stride(k), n);
        let mut expected: Vec<usize> = (0..=n).step_by(k).collect();
        if n % k != 0 {
            expected.push(n);
        }
        prop_assert_eq!(strided.n_samples(), expected.len());
        for (row, &i) in expected.iter().enumerate() {
            prop_assert_eq!(strided.y.row(row), full.y.row(i));
            prop_assert_eq!(strided.t[row], full.t[i]);
        }
    }

    /// Final-only sampling keeps the first and last rows of the full run.
    #[test]
    fn final_only_keeps_first_and_last(n in 1usize..300) {
        let full = run(Sampling::All, n);
        let fin = run(Sampling::FinalOnly, n);
        prop_assert_eq!(fin.n_samples(), 2);
        prop_assert_eq!(fin.y.row(0), full.y.row(0));
        prop_assert_eq!(fin.y.row(1), full.y.row(n));
    }
}

#[test]
fn identical_inputs_give_bit_identical_outputs() {
    // The pendulum is hand-written, without a Taylor form: a method that needs one is checked
    // on an expression system in integrators/taylor.rs.
    for method in Method::ALL.into_iter().filter(|m| !m.needs_taylor_form()) {
        let a = Pendulum::new(2.0, 0.1, 1.0)
            .unwrap()
            .integrate((0.0, 10.0), 0.01, method)
            .unwrap();
        let b = Pendulum::new(2.0, 0.1, 1.0)
            .unwrap()
            .integrate((0.0, 10.0), 0.01, method)
            .unwrap();
        assert_eq!(a, b, "{method}");
    }
}

/// The driver runs systems of one and two degrees of freedom on fixed-length arrays and larger
/// ones on vectors; either way it must take exactly the steps of the public
/// [`SplittingStepper`](physicskit::classical::integrators::SplittingStepper) on a `Vec`, bit
/// for bit, every row, for every splitting method of the table.
#[test]
fn the_driver_takes_the_steps_of_the_public_stepper() {
    use physicskit::classical::integrators::splitting::Coefficients;
    use physicskit::classical::integrators::{
        AdaptiveStepper, Dispatch, FieldStepper, SplittingStepper,
    };
    use physicskit::classical::systems::{
        HenonHeilesSystem, KeplerSystem, PendulumSwarm, ProjectileMotion,
    };

    /// Compares one system's driver run with the public stepper, for a splitting method.
    struct Compare<'a, S> {
        name: &'a str,
        system: &'a S,
    }

    impl<S: HamiltonianSystem + Clone> Dispatch for Compare<'_, S> {
        type Output = ();

        fn splitting<const N: usize>(self, method: Method, weights: Coefficients<N>) {
            let (dt, n) = (0.01, 300);
            let (name, system) = (self.name, self.system);
            let ndof = system.ndof();
            let mut s = system.clone();
            let r = s.integrate((0.0, n as f64 * dt), dt, method).unwrap();
            let mut state = system.state().to_vec();
            let mut stepper = SplittingStepper::new(weights, ndof);
            for (i, row) in r.y.rows().into_iter().enumerate() {
                assert!(
                    row.iter()
                        .zip(&state)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "{name}, {method}, row {i}"
                );
                let (q, p) = state.split_at_mut(ndof);
                stepper.step(system, i as f64 * dt, q, p, dt).unwrap();
            }
        }

        fn explicit_rk<St: FieldStepper>(self, _method: Method) {}

        fn implicit_rk<St: FieldStepper>(self, _method: Method) {}

        fn adaptive<St: AdaptiveStepper>(self, _method: Method) {}
    }

    fn check<S: HamiltonianSystem + Clone>(name: &str, system: &S) {
        for method in Method::ALL {
            method.dispatch(Compare { name, system });
        }
    }
    check("pendulum", &Pendulum::new(1.0, 0.2, 1.0).unwrap());
    check(
        "projectile",
        &ProjectileMotion::from_launch(20.0, 45.0, 1.0, 9.81, 0.0, 0.0).unwrap(),
    );
    check(
        "Kepler",
        &KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, Default::default()).unwrap(),
    );
    check(
        "Henon-Heiles",
        &HenonHeilesSystem::new(&[0.0, 0.3], &[0.3, 0.0]).unwrap(),
    );
    check(
        "swarm of 3",
        &PendulumSwarm::new(&[0.1, 0.5, -1.0], &[0.0, 0.2, 0.3], 1.0).unwrap(),
    );
}
