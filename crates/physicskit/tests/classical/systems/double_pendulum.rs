//! The double pendulum's flip energy against the system's own energy minimized over the
//! inverted lines `theta1 = pi` and `theta2 = pi`, against the hand-derived costs `2 m2 g l2`
//! and `2 (m1 + m2) g l1` and the equal-arm condition `2 cos theta1 + cos theta2 < 1`, and a
//! start just inside the no-flip region followed in time.

use std::f64::consts::PI;

use physicskit::classical::systems::{DoublePendulum, DoublePendulumParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};

/// Equal arms, the lower arm longer, the upper bob heavier, no gravity, gravity upwards.
fn settings() -> [DoublePendulumParams; 5] {
    let p = |m1, m2, l1, l2, g| DoublePendulumParams { m1, m2, l1, l2, g };
    [
        DoublePendulumParams::default(),
        p(1.0, 2.0, 1.0, 3.0, 9.81),
        p(5.0, 0.5, 2.0, 0.7, 1.62),
        p(1.0, 1.0, 1.0, 1.0, 0.0),
        p(1.0, 3.0, 0.5, 1.0, -9.81),
    ]
}

/// The lowest energy at rest on the two inverted lines, from the system's own `energy` on a
/// grid of 3600 angles per line that contains 0 and pi (where the minima lie, so the grid's
/// minimum is the true one up to rounding, independently of the closed form under test).
fn lowest_inverted_energy(params: DoublePendulumParams) -> f64 {
    let dp = DoublePendulum::new(&[0.0, 0.0], &[0.0, 0.0], params).unwrap();
    let n = 3600;
    (0..=n)
        .map(|k| -PI + 2.0 * PI * k as f64 / n as f64)
        .flat_map(|t| [dp.energy(&[PI, t, 0.0, 0.0]), dp.energy(&[t, PI, 0.0, 0.0])])
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn flip_energy_is_the_lowest_energy_with_an_arm_inverted() {
    for params in settings() {
        let DoublePendulumParams { m1, m2, l1, l2, g } = params;
        let scale = (m1 + m2) * g.abs() * l1 + m2 * g.abs() * l2;
        let flip = params.flip_energy();
        // Energies of order `scale` (<= 60 J), rounded a few times, and cos of the grid's pi
        // within an ulp of -1: 1e-13 relative is a hundred times that.
        let lowest = lowest_inverted_energy(params);
        assert!(
            (flip - lowest).abs() <= 1e-13 * scale,
            "{params:?}: {flip} vs {lowest}"
        );
        if g > 0.0 {
            // The hand derivation: above the hanging rest -(g1 + g2), the cheaper of lifting
            // the lower bob over the upper one (2 m2 g l2) and the upper bob over the pivot
            // with the lower arm hanging below it (2 (m1 + m2) g l1).
            let rest = -((m1 + m2) * g * l1 + m2 * g * l2);
            let cost = (2.0 * m2 * g * l2).min(2.0 * (m1 + m2) * g * l1);
            assert!(
                (flip - rest - cost).abs() <= 1e-13 * scale,
                "{params:?}: {flip} - {rest} vs {cost}"
            );
        }
    }
}

#[test]
fn from_rest_flips_are_allowed_exactly_above_the_flip_energy() {
    let grid: Vec<f64> = (0..=90).map(|k| -PI + 2.0 * PI * k as f64 / 90.0).collect();
    for params in settings() {
        let dp = DoublePendulum::new(&[0.0, 0.0], &[0.0, 0.0], params).unwrap();
        for &a in &grid {
            for &b in &grid {
                // The predicate uses the system's own energy at rest: the same bits.
                let above = dp.energy(&[a, b, 0.0, 0.0]) > params.flip_energy();
                assert_eq!(params.can_flip_from_rest(a, b), above, "{params:?} {a} {b}");
            }
        }
    }
    // Equal masses and arms (g1 = 2 m g l, g2 = m g l, E_flip = -m g l): a start from rest
    // can flip iff 2 cos theta1 + cos theta2 < 1. Points within 1e-12 of the curve, where the
    // rounding of the two sides decides, are skipped.
    let params = DoublePendulumParams::default();
    let mut allowed = 0;
    for &a in &grid {
        for &b in &grid {
            let margin = 1.0 - (2.0 * a.cos() + b.cos());
            if margin.abs() > 1e-12 {
                assert_eq!(params.can_flip_from_rest(a, b), margin > 0.0, "{a} {b}");
                allowed += usize::from(margin > 0.0);
            }
        }
    }
    // Both outcomes occur on the grid (the test can fail either way).
    assert!(
        0 < allowed && allowed < grid.len() * grid.len(),
        "{allowed}"
    );
    // Without gravity nothing at rest moves; with it, the hanging rest never flips and the
    // inverted rest is above the flip energy.
    let weightless = DoublePendulumParams { g: 0.0, ..params };
    assert!(!weightless.can_flip_from_rest(3.0, -3.0));
    assert!(!params.can_flip_from_rest(0.0, 0.0));
    assert!(params.can_flip_from_rest(PI, PI));
}

/// Released from rest 1 % of the flip cost below the flip energy, near the upper arm's
/// threshold (`theta2 = 0`, `2 cos theta1 + 1` just above 1), the pendulum swings for 40 s
/// and no angle reaches pi: the energy bound holds along the motion (implicit midpoint keeps
/// the energy error to ~1e-6 relative here, far below the 1 % margin).
#[test]
fn a_start_below_the_flip_energy_never_flips() {
    let params = DoublePendulumParams::default();
    let DoublePendulumParams { m2, l2, g, .. } = params;
    // E(theta1, 0) = -2 g cos theta1 - g; 1 % of the cost 2 m2 g l2 below E_flip = -g.
    let target = params.flip_energy() - 0.01 * 2.0 * m2 * g * l2;
    let theta1 = ((-target - g) / (2.0 * g)).acos();
    assert!(!params.can_flip_from_rest(theta1, 0.0));
    let mut dp = DoublePendulum::new(&[theta1, 0.0], &[0.0, 0.0], params).unwrap();
    let r = dp
        .integrate((0.0, 40.0), 2e-3, Method::ImplicitMidpoint)
        .unwrap();
    let q = r.q().unwrap();
    let largest = q.iter().fold(0.0f64, |m, &a| m.max(a.abs()));
    assert!(largest < PI, "an arm reached {largest}");
    // Yet the start is chaotic enough to wander: the lower arm swings far from hanging.
    let lower = q.column(1).iter().fold(0.0f64, |m, &a| m.max(a.abs()));
    assert!(lower > 1.0, "{lower}");
}

/// The bobs are the rods' vectors summed from the pivot, to the bit: the closed form
/// `(l1 sin θ1, -l1 cos θ1)`, plus `(l2 sin θ2, -l2 cos θ2)` for the second, at angles over
/// several turns either way.
#[test]
fn positions_are_the_closed_form_to_the_bit() {
    let params = DoublePendulumParams {
        l1: 0.7,
        l2: 1.3,
        ..Default::default()
    };
    let (l1, l2) = (params.l1, params.l2);
    let p = DoublePendulum::new(&[0.0; 2], &[0.0; 2], params).unwrap();
    for i in 0..200 {
        let q = [f64::from(i) * 0.137 - 13.0, 11.0 - f64::from(i) * 0.291];
        let ((s1, c1), (s2, c2)) = (q[0].sin_cos(), q[1].sin_cos());
        let expected = [l1 * s1, -(l1 * c1), l1 * s1 + l2 * s2, -(l1 * c1) - l2 * c2];
        let at = p.positions(Some(&q)).unwrap();
        assert_eq!(at.map(f64::to_bits), expected.map(f64::to_bits), "{q:?}");
    }
}
