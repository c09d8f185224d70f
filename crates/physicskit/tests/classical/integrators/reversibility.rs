//! Time reversibility: N steps forward, then N steps with -dt, returns to the start.

use crate::fixtures::NonSeparable;
use physicskit::classical::examples::Pendulum;
use physicskit::classical::integrators::splitting::Coefficients;
use physicskit::classical::integrators::{
    AdaptiveStepper, Dispatch, FieldStepper, FirstOrder, ImplicitMidpoint, SplittingStepper,
    Stepper,
};
use physicskit::classical::{DynamicalSystem, Method};

const N: usize = 1000;
const DT: f64 = 0.1;
/// Forward and backward runs each accumulate rounding of ~sqrt(N) ulps; 1e-12 relative is what
/// the issue asks and sits two orders above that, while any non-symmetric method (rk4 here
/// returns with an O(h^4 N) error of ~1e-9) fails it.
const TOLERANCE: f64 = 1e-12;

fn relative_distance(a: &[f64], b: &[f64]) -> f64 {
    let norm = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / norm
}

#[test]
fn splitting_methods_are_reversible() {
    let pendulum = Pendulum::new(2.0, 0.3, 1.0).unwrap();
    let start = pendulum.state().to_vec();
    fn round_trip<const S: usize>(mut stepper: SplittingStepper<S>, system: &Pendulum) -> [f64; 2] {
        let start = system.state();
        let (mut q, mut p) = ([start[0]], [start[1]]);
        for i in 0..N {
            stepper
                .step(system, i as f64 * DT, &mut q, &mut p, DT)
                .unwrap();
        }
        for i in (1..=N).rev() {
            stepper
                .step(system, i as f64 * DT, &mut q, &mut p, -DT)
                .unwrap();
        }
        [q[0], p[0]]
    }
    for (method, end) in [
        (
            Method::Verlet,
            round_trip(SplittingStepper::verlet(1), &pendulum),
        ),
        (
            Method::Yoshida4,
            round_trip(SplittingStepper::yoshida4(1), &pendulum),
        ),
    ] {
        let d = relative_distance(&end, &start);
        assert!(d <= TOLERANCE, "{method}: returned {d:e} away");
    }
}

#[test]
fn implicit_midpoint_is_reversible_also_for_a_non_separable_hamiltonian() {
    let pendulum = Pendulum::new(2.0, 0.3, 1.0).unwrap();
    let nonsep = NonSeparable::new(0.8, 0.4);
    for (name, start, field) in [
        (
            "pendulum",
            pendulum.state().to_vec(),
            &pendulum as &dyn DynamicalSystem,
        ),
        (
            "non-separable",
            nonsep.state().to_vec(),
            &nonsep as &dyn DynamicalSystem,
        ),
    ] {
        let field = FirstOrder(field);
        let mut stepper = ImplicitMidpoint::new(2);
        let mut y = start.clone();
        for i in 0..N {
            stepper.step(&field, i as f64 * DT, &mut y, DT).unwrap();
        }
        for i in (1..=N).rev() {
            stepper.step(&field, i as f64 * DT, &mut y, -DT).unwrap();
        }
        let d = relative_distance(&y, &start);
        assert!(d <= TOLERANCE, "{name}: returned {d:e} away");
    }
}

#[test]
fn rk4_is_not_reversible() {
    // The control: the same round trip with rk4 misses the start by far more than the
    // tolerance, so the tests above can tell a reversible method from one that is not.
    let pendulum = Pendulum::new(2.0, 0.3, 1.0).unwrap();
    let start = pendulum.state().to_vec();
    let field = FirstOrder(&pendulum);
    let mut rk4 = physicskit::classical::integrators::Rk4::new(2);
    let mut y = start.clone();
    for i in 0..N {
        rk4.step(&field, i as f64 * DT, &mut y, DT).unwrap();
    }
    for i in (1..=N).rev() {
        rk4.step(&field, i as f64 * DT, &mut y, -DT).unwrap();
    }
    assert!(relative_distance(&y, &start) > 100.0 * TOLERANCE);
}

/// Round trips with a method's stepper, on the pendulum (every method) and, for the implicit
/// methods, on a non-separable Hamiltonian: the relative distance from the start of each.
struct RoundTrip;

/// `N` steps forward and `N` back from `start`: the relative distance from `start`.
fn there_and_back<P: ?Sized>(stepper: &mut impl Stepper<P>, problem: &P, start: &[f64]) -> f64 {
    let mut y = start.to_vec();
    for i in 0..N {
        stepper.step(problem, i as f64 * DT, &mut y, DT).unwrap();
    }
    for i in (1..=N).rev() {
        stepper.step(problem, i as f64 * DT, &mut y, -DT).unwrap();
    }
    relative_distance(&y, start)
}

impl Dispatch for RoundTrip {
    type Output = Vec<(&'static str, f64)>;

    fn splitting<const S: usize>(self, _: Method, weights: Coefficients<S>) -> Self::Output {
        let pendulum = Pendulum::new(2.0, 0.3, 1.0).unwrap();
        let mut stepper = SplittingStepper::new(weights, 1);
        vec![(
            "pendulum",
            there_and_back(&mut stepper, &pendulum, pendulum.state()),
        )]
    }

    fn explicit_rk<St: FieldStepper>(self, _: Method) -> Self::Output {
        Vec::new()
    }

    /// Not symplectic, and its steps are not symmetric: nothing to check.
    fn adaptive<St: AdaptiveStepper>(self, _: Method) -> Self::Output {
        Vec::new()
    }

    fn implicit_rk<St: FieldStepper>(self, _: Method) -> Self::Output {
        let pendulum = Pendulum::new(2.0, 0.3, 1.0).unwrap();
        let nonsep = NonSeparable::new(0.8, 0.4);
        vec![
            (
                "pendulum",
                there_and_back(&mut St::new(2), &FirstOrder(&pendulum), pendulum.state()),
            ),
            (
                "non-separable",
                there_and_back(&mut St::new(2), &FirstOrder(&nonsep), nonsep.state()),
            ),
        ]
    }
}

#[test]
fn every_symplectic_method_in_the_table_is_reversible() {
    // The registry's symplectic methods are all symmetric (their coefficients are palindromes,
    // methods.rs; Gauss–Legendre tableaus are symmetric), so each one's round trip returns to
    // the start up to rounding, through its own stepper as the registry dispatches it.
    let mut checked = 0;
    for method in Method::ALL.into_iter().filter(|m| m.is_symplectic()) {
        for (problem, d) in method.dispatch(RoundTrip) {
            println!("{method} on the {problem}: returned {d:e} away");
            assert!(
                d <= TOLERANCE,
                "{method} on the {problem}: returned {d:e} away"
            );
            checked += 1;
        }
    }
    assert!(checked >= 12, "only {checked} round trips");
}
