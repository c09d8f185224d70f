//! The bead on a rotating hoop's separatrix energies against its equilibria classified
//! numerically: an equilibrium is where the system's acceleration vanishes, a saddle where the
//! system's energy curves down along `theta` (central second difference). Its listed
//! equilibria against the hand-derived pitchfork `cos theta* = g / (R omega^2)` and the
//! system's own acceleration, and the finite-time Lyapunov exponent at the bottom (the
//! gallery's pitchfork page) against the linearization's `sqrt(omega^2 - g / R)`.

use std::f64::consts::PI;

use physicskit::classical::analysis::lyapunov::max_lyapunov;
use physicskit::classical::model::erased::Lagrangian;
use physicskit::classical::systems::{BeadOnRotatingHoop, HoopBranch, HoopParams};
use physicskit::classical::{DynamicalSystem, LagrangianSystem, Method};

/// Energies of the saddles among the candidate equilibria `theta = 0, pi` and
/// `cos theta = g / (R omega^2)`, found with the system's own acceleration and energy.
fn saddle_energies(bead: &BeadOnRotatingHoop) -> Vec<f64> {
    let HoopParams { r, omega, g } = *bead.params();
    let mut candidates = vec![0.0, PI];
    let c = g / (r * omega * omega);
    if c.abs() < 1.0 {
        candidates.push(c.acos());
    }
    let energy = |theta: f64| bead.energy(&[theta, 0.0]);
    let h = 1e-4;
    let mut levels = Vec::new();
    for theta in candidates {
        let mut a = [0.0];
        bead.acceleration(&[theta], &[0.0], 0.0, &mut a).unwrap();
        // An equilibrium up to the rounding of sin(pi) ~ 1e-16 times forces of order 30.
        assert!(a[0].abs() < 1e-13, "theta = {theta}: {}", a[0]);
        // Second difference: V'' h^2 with V'' of order 10 is ~1e-7, far above the ~1e-15
        // rounding of the energies, so the sign is reliable away from the bifurcation.
        let curvature = energy(theta + h) + energy(theta - h) - 2.0 * energy(theta);
        if curvature < -1e-12 {
            levels.push(energy(theta));
        }
    }
    levels.sort_by(f64::total_cmp);
    levels.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    levels
}

#[test]
fn separatrix_energies_are_the_saddle_levels() {
    let cases = [
        (1.0, 2.0, 9.81),  // below critical: only the top
        (1.0, 5.0, 9.81),  // above: the bottom too
        (0.5, 3.0, -9.81), // gravity up, bottom a saddle, top stable
        (2.0, 1.5, 0.0),   // no gravity: top and bottom both at E = 0
    ];
    for (r, omega, g) in cases {
        let bead = BeadOnRotatingHoop::new(0.3, 0.0, HoopParams { r, omega, g }).unwrap();
        let want = saddle_energies(&bead);
        let got = bead.separatrix_energies();
        assert_eq!(
            got.len(),
            want.len(),
            "{r} {omega} {g}: {got:?} vs {want:?}"
        );
        for (a, b) in got.iter().zip(&want) {
            // The energy at sin(pi) ~ 1e-16 differs from 2 g R by that rounding times R^2
            // omega^2: 1e-13 absolute.
            assert!(
                (a - b).abs() < 1e-13,
                "{r} {omega} {g}: {got:?} vs {want:?}"
            );
        }
    }
}

/// Every listed equilibrium is one (the system's acceleration vanishes), its stiffness is
/// `-d theta'' / d theta` of the system's acceleration, the branches are the hand-derived
/// `±arccos(g / (R omega^2))` above `omega_c` and absent below, and the stable ones are the
/// bottom below `omega_c` and the branches above. Each is named by its branch: bottom and top
/// at every rate, left (the negative angle) and right only above `omega_c`.
// The bottom is listed as exactly 0 and its exponent below omega_c is exactly 0; the branches
// are the same arccos of the same quotient: exact comparisons are the claim.
#[allow(clippy::float_cmp)]
#[test]
fn equilibria_are_the_pitchfork() {
    let wc = HoopParams::default().critical_omega();
    for ratio in [0.3, 0.9, 1.1, 2.0, 4.0] {
        let params = HoopParams {
            omega: ratio * wc,
            ..HoopParams::default()
        };
        let HoopParams { r, omega, g } = params;
        let bead = BeadOnRotatingHoop::new(0.0, 0.0, params).unwrap();
        let accel = |theta: f64| {
            let mut a = [0.0];
            bead.acceleration(&[theta], &[0.0], 0.0, &mut a).unwrap();
            a[0]
        };
        let eqs = params.equilibria();
        for e in &eqs {
            // Forces of order R omega^2 <= 160 times sin(pi) ~ 1e-16, or the rounding of
            // cos theta* (1 ulp) times that force: 1e-13.
            assert!(accel(e.theta).abs() < 1e-13, "{ratio}: {e:?}");
            // Central difference with h = 1e-5: truncation h^2/6 times the third derivative
            // (of order 160) ~ 3e-9, rounding 1e-16 * 160 / 1e-5 ~ 2e-9.
            let h = 1e-5;
            let fd = -(accel(e.theta + h) - accel(e.theta - h)) / (2.0 * h);
            assert!(
                (fd - e.stiffness).abs() < 1e-7 * (1.0 + omega * omega),
                "{ratio}: {e:?} vs {fd}"
            );
        }
        let bottom = eqs.iter().find(|e| e.kind == HoopBranch::Bottom).unwrap();
        // Two roundings of quantities of order omega^2.
        assert!((bottom.stiffness - (g / r - omega * omega)).abs() < 1e-13 * omega * omega);
        let stable = params.stable_equilibria();
        if ratio < 1.0 {
            assert_eq!(eqs.len(), 2, "{ratio}: bottom and top only");
            let kinds: Vec<_> = eqs.iter().map(|e| (e.kind, e.theta)).collect();
            assert_eq!(kinds, [(HoopBranch::Bottom, 0.0), (HoopBranch::Top, PI)]);
            assert_eq!(stable, vec![0.0]);
            assert_eq!(bottom.linear_exponent(), 0.0);
        } else {
            let theta = (g / (r * omega * omega)).acos();
            // So Left, listed first, is the negative angle.
            assert!(theta > 0.0, "{ratio}: {theta}");
            assert_eq!(eqs.len(), 4, "{ratio}: bottom, top and the pair");
            let kinds: Vec<_> = eqs.iter().map(|e| (e.kind, e.theta)).collect();
            let expected = [
                (HoopBranch::Left, -theta),
                (HoopBranch::Bottom, 0.0),
                (HoopBranch::Right, theta),
                (HoopBranch::Top, PI),
            ];
            assert_eq!(kinds, expected);
            assert_eq!(stable, vec![-theta, theta]);
            let rate = (omega * omega - g / r).sqrt();
            // The same expression rounded in another order: a few ulps.
            assert!((bottom.linear_exponent() - rate).abs() < 1e-14 * rate);
        }
    }
}

/// At the bottom the orbit stays at rest exactly (`sin 0 = 0`), so the tangent dynamics are
/// the linearization `x'' = (omega^2 - g / R) x`: above `omega_c` a saddle, whose deviations
/// grow as `exp(lambda t)`, `lambda = sqrt(omega^2 - g / R)`; below, a centre. Implicit
/// midpoint maps a linear flow by its Cayley transform, growth `mu = (1 + h lambda / 2) /
/// (1 - h lambda / 2)` per step, so the measured rate is `ln(mu) / h = lambda (1 + (h
/// lambda)^2 / 12 + ...)`. The growth between t = 5 and 10 (the initial vector's component
/// along the stable direction has decayed by exp(-2 lambda 5) < 1e-15 relative) is compared
/// with `ln(mu) / h` to 1e-9 relative (the rounding of 500 logarithms and of the implicit
/// solve, far below the O(h^2) bias that distinguishes it from lambda) and with lambda to 1e-5
/// relative (that bias, (h lambda)^2 / 12 <= 5e-6 here). Below `omega_c` a deviation rotates on
/// an ellipse whose axes differ by the factor `w = sqrt(g / R - omega^2)` in `(theta, p)`
/// (`R = 1`): the finite-time exponent is bounded by `|ln w| / t`.
#[test]
fn bottom_exponent_is_the_linearized_rate() {
    let wc = HoopParams::default().critical_omega();
    let h = 1e-3;
    for ratio in [0.5, 1.5, 2.0, 2.5] {
        let params = HoopParams {
            omega: ratio * wc,
            ..HoopParams::default()
        };
        let bottom = params
            .equilibria()
            .into_iter()
            .find(|e| e.kind == HoopBranch::Bottom)
            .unwrap();
        let mut bead = Lagrangian(BeadOnRotatingHoop::new(0.0, 0.0, params).unwrap());
        let s = max_lyapunov(
            &mut bead,
            (0.0, 10.0),
            h,
            Some(Method::ImplicitMidpoint),
            10,
        )
        .unwrap();
        let lambda = bottom.linear_exponent();
        if ratio < 1.0 {
            let w = bottom.stiffness.sqrt();
            assert!(
                s.exponents[0].abs() <= w.ln().abs() / 10.0,
                "{ratio}: {}",
                s.exponents[0]
            );
        } else {
            let growth = |t: f64| {
                let i = s.t.iter().position(|&x| (x - t).abs() < 1e-9).unwrap();
                s.history[i] * s.t[i]
            };
            let measured = (growth(10.0) - growth(5.0)) / 5.0;
            let mu = (1.0 + 0.5 * h * lambda) / (1.0 - 0.5 * h * lambda);
            let discrete = mu.ln() / h;
            println!("{ratio}: measured {measured} discrete {discrete} lambda {lambda}");
            assert!((measured - discrete).abs() < 1e-9 * lambda, "{ratio}");
            assert!((measured - lambda).abs() < 1e-5 * lambda, "{ratio}");
        }
    }
}
