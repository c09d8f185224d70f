//! Foucault's pendulum, the reduced Euler's disk and the reduced rattleback: closed forms,
//! invariants, the rattleback's mirror symmetry, and one validation error each.

use physicskit::classical::systems::{
    eulers_disk_theta_analytic, EulersDisk, EulersDiskParams, FoucaultParams, FoucaultPendulum,
    Rattleback, RattlebackParams,
};
use physicskit::classical::{DynamicalSystem, Error, Method, OdeSystem};

#[test]
fn foucault_rk4_and_dop853_follow_the_closed_form() {
    // A fast-turning Earth (one turn in 600 s) so a short run sees the plane turn.
    let params = FoucaultParams {
        length: 20.0,
        omega_earth: 2.0 * std::f64::consts::PI / 600.0,
        ..FoucaultParams::default()
    };
    let (q0, v0) = ([0.4, -0.1], [0.05, 0.2]);
    for (method, dt, bound) in [
        // RK4 at dt = 0.01 on a 9 s period: global error ~ (omega dt)^4 t ~ 1e-9 of the
        // amplitude over 200 s.
        (Method::Rk4, 0.01, 1e-8),
        // Implicit midpoint is second order: (omega dt)^2 / 24 phase error per unit time.
        (Method::ImplicitMidpoint, 0.001, 1e-5),
    ] {
        let mut p = FoucaultPendulum::new(&q0, &v0, params).unwrap();
        let res = p.integrate((0.0, 200.0), dt, method).unwrap();
        let t = res.t.as_slice().unwrap();
        let (x, y) =
            FoucaultPendulum::analytic_solution(&q0, &v0, params.omega0(), params.omega_z(), t)
                .unwrap();
        let err = (0..t.len())
            .map(|i| {
                (res.y[[i, 0]] - x[i])
                    .abs()
                    .max((res.y[[i, 1]] - y[i]).abs())
            })
            .fold(0.0, f64::max);
        println!("foucault {}: max deviation {err:e}", method.name());
        assert!(err < bound, "{} {err:e}", method.name());
    }
}

#[test]
fn foucault_energy_is_a_quadratic_invariant_of_implicit_midpoint() {
    let mut p = FoucaultPendulum::new(&[1.0, 0.0], &[0.0, 0.3], FoucaultParams::default()).unwrap();
    let e0 = p.current_energy();
    let res = p
        .integrate((0.0, 2000.0), 0.05, Method::ImplicitMidpoint)
        .unwrap();
    let worst = res
        .energy
        .as_ref()
        .unwrap()
        .iter()
        .map(|e| (e - e0).abs() / e0)
        .fold(0.0, f64::max);
    // Exactly conserved up to the solve's rounding, 4e4 steps: 1e-12 relative.
    assert!(worst < 1e-12, "{worst:e}");
    let period = p.precession_period();
    let expected = 86164.0905 / 48.85_f64.to_radians().sin();
    assert!((period - expected).abs() < 1e-9 * expected);
}

#[test]
fn eulers_disk_theta_matches_its_closed_form() {
    let params = EulersDiskParams::default();
    let theta0 = 0.5;
    let collapse = theta0 * theta0 / (2.0 * params.decay_rate);
    let mut disk = EulersDisk::new(theta0, 0.0, params).unwrap();
    // The same formula: equal to the bit.
    assert_eq!(disk.collapse_time(theta0).to_bits(), collapse.to_bits());
    let res = disk
        .integrate((0.0, 0.9 * collapse), 1e-4, Method::Rk4)
        .unwrap();
    let t = res.t.as_slice().unwrap();
    let exact = eulers_disk_theta_analytic(t, theta0, params.decay_rate).unwrap();
    let err = (0..t.len())
        .map(|i| (res.y[[i, 0]] - exact[i]).abs())
        .fold(0.0, f64::max);
    // RK4 at dt = 1e-4 with theta >= 0.16: ~1e-13 per step near the end; 1e-9 in all.
    assert!(err < 1e-9, "{err:e}");
    assert_eq!(
        eulers_disk_theta_analytic(&[collapse * 1.5], theta0, 0.05).unwrap(),
        [0.0]
    );
}

#[test]
fn rattleback_mirror_run_is_exact_and_reverses() {
    let params = RattlebackParams::default();
    let run = |n0: [f64; 3]| {
        let mut r = Rattleback::new(&n0, params).unwrap();
        r.integrate((0.0, 10.0), 1e-3, Method::Rk4).unwrap()
    };
    let a = run([0.01, 0.01, 3.0]);
    let b = run([0.01, -0.01, -3.0]);
    for i in 0..a.y.nrows() {
        // The exact mirror image: every bit, sign flips aside.
        assert_eq!(a.y[[i, 0]].to_bits(), b.y[[i, 0]].to_bits());
        assert_eq!(a.y[[i, 1]].to_bits(), (-b.y[[i, 1]]).to_bits());
        assert_eq!(a.y[[i, 2]].to_bits(), (-b.y[[i, 2]]).to_bits());
    }
    assert!(a.y.column(2).iter().any(|&n3| n3 < 0.0), "no reversal");
}

#[test]
fn bad_parameters_are_named() {
    let lat = FoucaultParams {
        latitude_deg: 120.0,
        ..FoucaultParams::default()
    };
    assert!(matches!(
        FoucaultPendulum::new(&[1.0, 0.0], &[0.0, 0.0], lat),
        Err(Error::InvalidParameter { ref name, .. }) if name == "latitude_deg"
    ));
    let floor = EulersDiskParams {
        theta_floor: 0.0,
        ..EulersDiskParams::default()
    };
    assert!(matches!(
        EulersDisk::new(0.5, 0.0, floor),
        Err(Error::InvalidParameter { ref name, .. }) if name == "theta_floor"
    ));
    assert!(matches!(
        Rattleback::new(&[0.0, 1.0], RattlebackParams::default()),
        Err(Error::DimensionMismatch { .. })
    ));
}
