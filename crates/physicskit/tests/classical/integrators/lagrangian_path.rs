//! The Lagrangian integration path: canonical implicit midpoint and direct rk4 on a
//! hand-written Lagrangian pendulum, against the Hamiltonian pendulum.

use crate::fixtures::LagrangianPendulum;
use physicskit::classical::examples::Pendulum;
use physicskit::classical::{HamiltonianSystem, LagrangianSystem, Method};

#[test]
fn lagrangian_and_hamiltonian_pendulum_agree() {
    // L = qdot^2/2 + cos q has p = qdot, so its canonical form is the Hamiltonian pendulum:
    // the two must follow the same trajectory. Both runs use identical arithmetic up to the
    // p -> qdot conversion (a division by 1), so they agree to rounding: 1e-12 over 1000 steps.
    for method in [Method::ImplicitMidpoint, Method::Rk4] {
        let mut lag = LagrangianPendulum::new(2.0, 0.5);
        let mut ham = Pendulum::new(2.0, 0.5, 1.0).unwrap();
        let a = LagrangianSystem::integrate(&mut lag, (0.0, 10.0), 0.01, method).unwrap();
        let b = HamiltonianSystem::integrate(&mut ham, (0.0, 10.0), 0.01, method).unwrap();
        let diff = (&a.y - &b.y).iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(diff <= 1e-12, "{method}: {diff:e}");
        assert_eq!(a.method, method.name());
        // result.p holds qdot for Lagrangian systems.
        assert_eq!(a.p().unwrap().column(0), a.y.column(1));
    }
}
