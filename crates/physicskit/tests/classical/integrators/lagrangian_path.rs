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

/// A splitting method on a Lagrangian system is refused with one message by the three loops
/// that run methods (integrate, a frame-by-frame session, a chaos flow), naming exactly the
/// methods for non-separable systems of the method table.
#[test]
fn splitting_methods_are_refused_alike_by_every_loop() {
    use physicskit::classical::analysis::poincare::Direction;
    use physicskit::classical::analysis::section::{poincare_section, SurfaceOfSection};
    use physicskit::classical::model::erased::{DynSystem, Lagrangian};
    use physicskit::classical::systems::DoublePendulum;
    use physicskit::classical::Error;

    let reason = |e: Error| match e {
        Error::UnsupportedMethod { method, reason } => {
            assert_eq!(method, "yoshida4");
            reason
        }
        other => panic!("{other:?}"),
    };
    let pendulum = || DoublePendulum::new(&[2.0, 1.0], &[0.0, 0.0], Default::default()).unwrap();
    let mut lag = pendulum();
    let from_integrate = reason(
        LagrangianSystem::integrate(&mut lag, (0.0, 1.0), 0.01, Method::Yoshida4).unwrap_err(),
    );
    let Err(refused) = Box::new(Lagrangian(pendulum())).start(Method::Yoshida4, 0.01) else {
        panic!("a session of yoshida4 on a Lagrangian system")
    };
    let from_session = reason(refused.error);
    let plane = SurfaceOfSection::coordinate(0, 0.0, Direction::Both).unwrap();
    let mut erased = Lagrangian(pendulum());
    let from_flow = reason(
        poincare_section(
            &mut erased,
            (0.0, 1.0),
            0.01,
            Some(Method::Yoshida4),
            &plane,
            10,
        )
        .unwrap_err(),
    );
    assert_eq!(from_integrate, from_session);
    assert_eq!(from_integrate, from_flow);
    for m in Method::ALL {
        assert_eq!(
            from_integrate.contains(m.name()),
            !m.needs_separable(),
            "{m}: {from_integrate}"
        );
    }
}
