//! Projectile: Galileo's parabola, closed-form range and height, drag.

use physicskit::classical::systems::ProjectileMotion;
use physicskit::classical::{DynamicalSystem, Error, HamiltonianSystem, Method};

use crate::checks::hermite_root;

#[test]
fn vacuum_flight_matches_the_parabola() {
    let (speed, angle, g) = (20.0, 45.0, 9.81);
    for method in [Method::Yoshida4, Method::Verlet, Method::Rk4] {
        let mut ball = ProjectileMotion::from_launch(speed, angle, 1.0, g, 0.0, 0.0).unwrap();
        let res = ball.integrate((0.0, 2.0), 1e-3, method).unwrap();
        let t = res.t.as_slice().unwrap();
        let (x, y) = ProjectileMotion::analytic_trajectory(speed, angle, g, t, 0.0).unwrap();
        let q = res.q().unwrap();
        let err = (0..t.len())
            .map(|i| (q[[i, 0]] - x[i]).abs().max((q[[i, 1]] - y[i]).abs()))
            .fold(0.0, f64::max);
        println!(
            "projectile {}: max deviation from parabola {err:e}",
            method.name()
        );
        // The bound. All three methods integrate a constant force exactly (quadratic
        // solution, order >= 2), so only rounding over 2000 steps remains (~1e-12).
        assert!(err < 1e-9);
    }
}

/// Numerical landing point and apex of an integrated flight, found with the cubic Hermite
/// interpolant (exact for the parabola) between samples.
fn measured_range_and_height(speed: f64, angle: f64, g: f64, h: f64) -> (f64, f64) {
    let mut ball = ProjectileMotion::from_launch(speed, angle, 1.0, g, 0.0, h).unwrap();
    let res = ball.integrate((0.0, 10.0), 1e-2, Method::Verlet).unwrap();
    let (t, q, p) = (
        res.t.as_slice().unwrap(),
        res.q().unwrap(),
        res.p().unwrap(),
    );
    let mut range = f64::NAN;
    let mut apex = h;
    for i in 0..t.len() - 1 {
        let (y0, y1) = (q[[i, 1]], q[[i + 1, 1]]);
        let (v0, v1) = (p[[i, 1]], p[[i + 1, 1]]);
        if v0 > 0.0 && v1 <= 0.0 {
            let tc = hermite_root(t[i], t[i + 1], v0, v1, -g, -g);
            apex = h + speed * angle.to_radians().sin() * tc - 0.5 * g * tc * tc;
            // Cross-check the apex height against the sampled trajectory.
            assert!(apex >= y0.max(y1));
        }
        if y0 > 0.0 && y1 <= 0.0 {
            let tl = hermite_root(t[i], t[i + 1], y0, y1, v0, v1);
            range = q[[i, 0]] + p[[i, 0]] * (tl - t[i]);
            break;
        }
    }
    (range, apex)
}

#[test]
fn range_and_max_height_match_the_closed_forms() {
    // Textbook level-ground formulas: R = v^2 sin(2 theta)/g, H = v^2 sin^2(theta)/(2 g).
    let (v, g) = (20.0_f64, 9.81);
    for angle in [15.0_f64, 45.0, 70.0] {
        let (r, hmax) = ProjectileMotion::range_and_max_height(v, angle, g, 0.0).unwrap();
        let th = angle.to_radians();
        assert!((r - v * v * (2.0 * th).sin() / g).abs() < 1e-12);
        assert!((hmax - (v * th.sin()).powi(2) / (2.0 * g)).abs() < 1e-12);
    }
    // Raised launch: against the landing point of an integrated flight (no closed form used).
    for (angle, h) in [(30.0, 5.0), (45.0, 12.0), (-10.0, 3.0)] {
        let (r, hmax) = ProjectileMotion::range_and_max_height(v, angle, g, h).unwrap();
        let (r_num, h_num) = measured_range_and_height(v, angle, g, h);
        println!("projectile h={h} angle={angle}: range {r} vs {r_num}, height {hmax} vs {h_num}");
        // Verlet is exact for constant force and the Hermite interpolant is exact for a
        // parabola, so agreement is to rounding; 1e-9 relative leaves room for the root solve.
        assert!((r - r_num).abs() < 1e-9 * r);
        assert!((hmax - h_num).abs() < 1e-9 * hmax);
    }
}

#[test]
fn drag_dissipates_energy_monotonically() {
    for method in [Method::Rk4, Method::ImplicitMidpoint] {
        let mut ball = ProjectileMotion::from_launch(20.0, 45.0, 1.0, 9.81, 0.05, 0.0).unwrap();
        let res = ball.integrate((0.0, 2.0), 1e-3, method).unwrap();
        let e = res.energy.as_ref().unwrap();
        // dE/dt = -c |v|^3 < 0 at every instant, so every step must lose energy.
        assert!(e.windows(2).into_iter().all(|w| w[1] < w[0]));
        assert!(e[e.len() - 1] < 0.8 * e[0]);
    }
}

#[test]
fn drag_refuses_splitting_methods() {
    let mut ball = ProjectileMotion::from_launch(20.0, 45.0, 1.0, 9.81, 0.05, 0.0).unwrap();
    assert!(!ball.conservative());
    assert_eq!(ball.default_method(), Method::Rk4);
    for method in [Method::Verlet, Method::Yoshida4] {
        let err = ball.integrate((0.0, 1.0), 1e-3, method).unwrap_err();
        assert!(matches!(err, Error::UnsupportedMethod { .. }), "{err}");
    }
}

/// Vertical fall from rest with quadratic drag has the closed form
/// `v(t) = -v_T tanh(g t / v_T)`, `y(t) = h - (v_T^2/g) ln cosh(g t / v_T)`,
/// `v_T = sqrt(m g / c)` (Taylor, *Classical Mechanics*, §2.4): an independent check that the
/// drag force is `-c |v| v` on the momentum.
#[test]
fn vertical_fall_with_drag_matches_the_terminal_velocity_solution() {
    let (m, g, c, h) = (2.0_f64, 9.81_f64, 0.3_f64, 100.0_f64);
    let vt = (m * g / c).sqrt();
    for method in [Method::Rk4, Method::ImplicitMidpoint] {
        let mut ball = ProjectileMotion::new(&[0.0, h], &[0.0, 0.0], m, g, c).unwrap();
        ball.integrate((0.0, 3.0), 1e-3, method).unwrap();
        let tau = g * 3.0 / vt;
        let v_exact = -vt * tau.tanh();
        let y_exact = h - vt * vt / g * tau.cosh().ln();
        let (v_err, y_err) = (
            (ball.p()[1] / m - v_exact).abs() / vt,
            (ball.q()[1] - y_exact).abs() / h,
        );
        println!(
            "drag fall {}: v err {v_err:e}, y err {y_err:e}",
            method.name()
        );
        // rk4: O(dt^4) ~ 1e-12; implicit midpoint: O(dt^2 * (g/v_T)^2) ~ 1e-6 * 1.5 relative.
        let tol = if method == Method::Rk4 { 1e-10 } else { 1e-5 };
        assert!(v_err < tol && y_err < tol);
    }
}
