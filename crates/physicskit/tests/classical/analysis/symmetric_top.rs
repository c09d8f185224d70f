//! The heavy symmetric top against its reduced one-dimensional dynamics: the effective
//! potential, steady precession, and the nutation and precession frequencies measured on
//! trajectories integrated by the engine.

use physicskit::classical::analysis::{
    brent_minimize, effective_potential_symmetric_top, effective_potential_symmetric_top_many,
    find_theta_equilibrium, nutation_frequency, precession_frequency, DEFAULT_NUTATION_DTHETA,
    DEFAULT_THETA_BRACKET,
};
use physicskit::classical::systems::{HeavySymmetricTop, SymmetricTopParams};
use physicskit::classical::{DynamicalSystem, Error, LagrangianSystem, Method};

const I1: f64 = 1.0;
const I3: f64 = 0.5;

fn params() -> SymmetricTopParams {
    SymmetricTopParams::default()
}

#[test]
fn energy_is_radial_kinetic_plus_effective_potential() {
    // E = I1 theta'^2 / 2 + V_eff(theta) is an identity of the reduction (Goldstein eq. 5.63),
    // independent of how the system computes its energy; agreement to 1e-12 relative is
    // rounding.
    let p = params();
    for (i, theta) in [0.3, 0.5, 1.0, 1.7, 2.6].into_iter().enumerate() {
        let rates = [0.7 - 0.4 * i as f64, 0.9, 20.0 - 3.0 * i as f64];
        let top = HeavySymmetricTop::new(&[0.1, theta, -0.4], &rates, p).unwrap();
        let state = top.state().to_vec();
        let (p_phi, p_psi) = p.conserved_momenta(&state).unwrap();
        let v =
            effective_potential_symmetric_top(theta, p_phi, p_psi, p.i1, p.i3, p.mgl()).unwrap();
        let e = 0.5 * p.i1 * rates[1] * rates[1] + v;
        let got = top.energy(&state);
        assert!((got - e).abs() < 1e-12 * e.abs(), "{got} vs {e}");
    }
    let many =
        effective_potential_symmetric_top_many(&[0.4, 0.8], 8.0, 10.0, I1, I3, 9.81).unwrap();
    assert_eq!(
        many[1].to_bits(),
        effective_potential_symmetric_top(0.8, 8.0, 10.0, I1, I3, 9.81)
            .unwrap()
            .to_bits()
    );
}

/// Rates `(phi', 0, psi')` that give the momenta `(p_phi, p_psi)` at `theta`.
fn rates_for(p_phi: f64, p_psi: f64, theta: f64) -> [f64; 3] {
    let (s, c) = theta.sin_cos();
    let phid = (p_phi - p_psi * c) / (I1 * s * s);
    [phid, 0.0, p_psi / I3 - phid * c]
}

/// Goldstein's steady-precession condition (eq. 5.75), `I1 phi'^2 cos(theta) - p_psi phi' +
/// M g l`, with `phi' = (p_phi - p_psi cos theta) / (I1 sin^2 theta)`: `-V_eff'(theta) /
/// sin(theta)`, written independently of the library's slope.
fn steady_precession_residual(p_phi: f64, p_psi: f64, mgl: f64, theta: f64) -> f64 {
    let phid = rates_for(p_phi, p_psi, theta)[0];
    I1 * phid * phid * theta.cos() - p_psi * phid + mgl
}

/// `x` moved by `k` units in the last place.
fn ulps_away(x: f64, k: i64) -> f64 {
    f64::from_bits((x.to_bits() as i64 + k) as u64)
}

#[test]
fn equilibrium_angle_gives_steady_precession() {
    // At theta_eq a top started with theta' = 0 precesses steadily: theta'' = 0 there, the
    // root of Goldstein's condition (eq. 5.75), a hand-written form of -V_eff'/sin(theta).
    let (p_phi, p_psi) = (8.775_825_618_903_728, 10.0);
    let mgl = params().mgl();
    let th = find_theta_equilibrium(p_phi, p_psi, I1, I3, mgl, DEFAULT_THETA_BRACKET).unwrap();
    // The condition changes sign (+ to -) within 4 ulps either side of theta_eq: its terms
    // (~30) carry rounding ~1e-14, and its slope (~50 per radian) moves it by more than that
    // over 4 ulps of theta (~4.4e-16 rad): found to a few ulps, not to Brent's 3e-8.
    let (below, above) = (ulps_away(th, -4), ulps_away(th, 4));
    let (rb, ra) = (
        steady_precession_residual(p_phi, p_psi, mgl, below),
        steady_precession_residual(p_phi, p_psi, mgl, above),
    );
    assert!(
        rb > 0.0 && ra < 0.0,
        "residual {rb} at -4 ulps, {ra} at +4 ulps"
    );
    // And the integrated top holds theta: with theta_eq exact to rounding, the wander is the
    // integrator's (implicit midpoint, h = 1e-3, 5e3 steps), far below the 1e-6 that a
    // 3e-8 error in theta_eq gave.
    let r = rates_for(p_phi, p_psi, th);
    let mut top = HeavySymmetricTop::new(&[0.0, th, 0.0], &r, params()).unwrap();
    let result = top
        .integrate((0.0, 5.0), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let wander = result
        .y
        .column(1)
        .iter()
        .fold(0.0_f64, |m, v| m.max((v - th).abs()));
    assert!(wander < 1e-9, "{wander}");
}

#[test]
fn equilibrium_is_found_to_a_few_ulps_over_many_tops() {
    // Tops across regimes (fast and slow, p_phi above and below p_psi, inverted Mgl < 0 with
    // the default bracket, where V_eff also has a single minimum): the independent condition
    // changes sign within 8 ulps of theta_eq (condition-number headroom for the slow tops,
    // whose terms are larger relative to the slope).
    for (p_phi, p_psi, i3, mgl) in [
        (8.0, 10.0, 0.5, 9.81),
        (3.0, 4.0, 0.5, 9.81),
        (1.0, 20.0, 2.0, 1.0),
        (-2.0, 5.0, 0.3, 4.0),
        (5.0, 1.0, 0.5, -3.0),
        (0.5, 0.7, 1.0, 0.2),
    ] {
        let th = find_theta_equilibrium(p_phi, p_psi, I1, i3, mgl, DEFAULT_THETA_BRACKET).unwrap();
        let g = |x: f64| steady_precession_residual(p_phi, p_psi, mgl, x);
        let (rb, ra) = (g(ulps_away(th, -8)), g(ulps_away(th, 8)));
        assert!(
            rb > 0.0 && ra < 0.0,
            "({p_phi}, {p_psi}, {i3}, {mgl}): theta_eq = {th}, residual {rb} / {ra}"
        );
        // It is the minimum the old minimizer found, to its 3e-8.
        let brent = brent_minimize(
            |x| effective_potential_symmetric_top(x, p_phi, p_psi, I1, i3, mgl).unwrap(),
            DEFAULT_THETA_BRACKET,
            3e-8,
            1e-12,
            500,
        )
        .unwrap();
        assert!((brent.x - th).abs() < 1e-7, "{} vs {th}", brent.x);
    }
}

/// Mean spacing of the upward zero crossings of `x`, and the first and last crossing index.
fn crossings(t: &[f64], x: &[f64]) -> (f64, usize, usize) {
    let mut idx = Vec::new();
    let mut times = Vec::new();
    for i in 1..x.len() {
        if x[i - 1] < 0.0 && x[i] >= 0.0 {
            idx.push(i);
            times.push(t[i - 1] + (t[i] - t[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]));
        }
    }
    assert!(times.len() >= 3, "too few crossings");
    let period = (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64;
    (period, idx[0], idx[idx.len() - 1])
}

/// Measured (nutation frequency, mean precession rate) of a top started at `theta0` with
/// `theta' = 0` and the given momenta.
fn measure(p_phi: f64, p_psi: f64, theta0: f64) -> (f64, f64) {
    let mut top = HeavySymmetricTop::new(
        &[0.0, theta0, 0.0],
        &rates_for(p_phi, p_psi, theta0),
        params(),
    )
    .unwrap();
    let result = top
        .integrate((0.0, 12.0), 2e-4, Method::ImplicitMidpoint)
        .unwrap();
    let t = result.t.to_vec();
    let thetadot = result.y.column(4).to_vec();
    let (period, first, last) = crossings(&t, &thetadot);
    // Mean phi' over whole nutation periods (trapezoid rule).
    let phid = result.y.column(3);
    let integral: f64 = (first..last)
        .map(|i| 0.5 * (phid[i] + phid[i + 1]) * (t[i + 1] - t[i]))
        .sum();
    (
        2.0 * std::f64::consts::PI / period,
        integral / (t[last] - t[first]),
    )
}

// The bar is 1%. With a nutation amplitude of 0.01 rad the harmonic approximation is
// off by O(amplitude^2) ~ 1e-4, and implicit midpoint at dt = 2e-4 shifts a frequency of ~10
// by (w dt)^2 / 12 ~ 3e-7.
const FREQ_TOL: f64 = 0.01;

#[test]
fn nutation_and_precession_frequencies_match_a_small_nutation_run() {
    let (p_phi, p_psi) = (8.775_825_618_903_728, 10.0);
    let mgl = params().mgl();
    let th = find_theta_equilibrium(p_phi, p_psi, I1, I3, mgl, DEFAULT_THETA_BRACKET).unwrap();
    let nut = nutation_frequency(p_phi, p_psi, I1, I3, mgl, None, DEFAULT_NUTATION_DTHETA).unwrap();
    let prec = precession_frequency(p_phi, p_psi, I1, th).unwrap();
    let (nut_measured, prec_measured) = measure(p_phi, p_psi, th + 0.01);
    println!(
        "small nutation: frequency {nut_measured} vs {nut} ({:e}), precession {prec_measured} \
         vs {prec} ({:e})",
        (nut_measured - nut) / nut,
        (prec_measured - prec) / prec
    );
    assert!((nut_measured - nut).abs() < FREQ_TOL * nut);
    assert!((prec_measured - prec).abs() < FREQ_TOL * prec.abs());
}

#[test]
fn nutation_and_precession_frequencies_match_the_fast_top_released_at_rest() {
    // The top: theta0 = 0.5, psi' = 20, phi' = 0. It nutates between 0.5 and ~0.6
    // (amplitude ~0.05, a cuspidal motion); the harmonic estimates about theta_eq are then
    // off by O(amplitude^2 * stiffness ratios): measured 0.34% (nutation) and 0.46%
    // (precession), inside the 1%.
    let p = params();
    let (p_phi, p_psi) = p
        .conserved_momenta(&[0.0, 0.5, 0.0, 0.0, 0.0, 20.0])
        .unwrap();
    let mgl = p.mgl();
    let th = find_theta_equilibrium(p_phi, p_psi, I1, I3, mgl, DEFAULT_THETA_BRACKET).unwrap();
    let nut = nutation_frequency(p_phi, p_psi, I1, I3, mgl, Some(th), 1e-5).unwrap();
    let prec = precession_frequency(p_phi, p_psi, I1, th).unwrap();
    let (nut_measured, prec_measured) = measure(p_phi, p_psi, 0.5);
    println!(
        "fast top: frequency {nut_measured} vs {nut} ({:e}), precession {prec_measured} vs \
         {prec} ({:e})",
        (nut_measured - nut) / nut,
        (prec_measured - prec) / prec
    );
    assert!((nut_measured - nut).abs() < FREQ_TOL * nut);
    assert!((prec_measured - prec).abs() < FREQ_TOL * prec.abs());
}

#[test]
fn bracket_without_an_interior_minimum_is_an_error() {
    // theta_eq ~ 0.55 for these momenta; on (0.1, 0.3) V_eff only decreases.
    let e =
        find_theta_equilibrium(8.775_825_618_903_728, 10.0, I1, I3, 9.81, (0.1, 0.3)).unwrap_err();
    assert!(e.to_string().contains("no interior minimum"), "{e}");
}

#[test]
fn bracket_outside_zero_pi_is_an_error() {
    for bracket in [(0.0, 1.0), (0.5, 3.2), (1.0, 0.5), (f64::NAN, 1.0)] {
        let e = find_theta_equilibrium(8.0, 10.0, I1, I3, 9.81, bracket).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { .. }), "{e}");
    }
}

#[test]
fn non_positive_inertia_is_an_error() {
    assert!(effective_potential_symmetric_top(0.5, 8.0, 10.0, 0.0, I3, 9.81).is_err());
    assert!(find_theta_equilibrium(8.0, 10.0, I1, -1.0, 9.81, DEFAULT_THETA_BRACKET).is_err());
    assert!(precession_frequency(8.0, 10.0, -1.0, 0.5).is_err());
}

#[test]
fn nutation_frequency_rejects_a_non_positive_step() {
    assert!(nutation_frequency(8.0, 10.0, I1, I3, 9.81, Some(0.5), 0.0).is_err());
}

#[test]
fn nutation_frequency_rejects_an_angle_at_the_boundary() {
    assert!(nutation_frequency(8.0, 10.0, I1, I3, 9.81, Some(1e-6), 1e-5).is_err());
}

#[test]
fn nutation_frequency_rejects_a_maximum() {
    // A non-spinning top (p_phi = p_psi = 0): V_eff = M g l cos(theta) has V'' < 0 for
    // theta < pi/2.
    let e = nutation_frequency(0.0, 0.0, I1, I3, 9.81, Some(0.5), 1e-5).unwrap_err();
    assert!(e.to_string().contains("not a minimum"), "{e}");
}

#[test]
fn precession_frequency_rejects_the_axis() {
    assert!(precession_frequency(8.0, 10.0, I1, 0.0).is_err());
}

#[test]
fn brent_finds_the_minimum_of_a_smooth_function() {
    // (x - 1.234)^2 + 3 on (0, 5): the location to the requested 1e-10 absolute tolerance,
    // plus the sqrt(eps) floor of a quadratic minimum (values flat to rounding within 1e-8).
    let m = brent_minimize(|x| (x - 1.234).powi(2) + 3.0, (0.0, 5.0), 1e-10, 1e-10, 200).unwrap();
    assert!((m.x - 1.234).abs() < 2e-8, "{}", m.x);
    // A non-smooth one: |x - 0.3|, where the golden-section fallback does the work.
    let m = brent_minimize(|x| (x - 0.3).abs(), (-1.0, 2.0), 1e-12, 1e-12, 500).unwrap();
    // |x - 0.3| is not flat at its minimum, so the location converges to the requested
    // tolerance (1e-12) itself; 1e-10 allows for the golden-section last step.
    assert!((m.x - 0.3).abs() < 1e-10, "{}", m.x);
}

#[test]
fn brent_rejects_a_monotone_function_and_bad_brackets() {
    assert!(brent_minimize(|x| x, (0.0, 1.0), 1e-8, 1e-12, 100).is_err());
    assert!(brent_minimize(|x| x * x, (1.0, -1.0), 1e-8, 1e-12, 100).is_err());
    assert!(brent_minimize(|x| x * x, (-1.0, 1.0), 0.0, 1e-12, 100).is_err());
}

#[test]
fn top_through_the_trait_reports_ndof_three() {
    let top = HeavySymmetricTop::new(&[0.0, 0.5, 0.0], &[0.0, 0.0, 20.0], params()).unwrap();
    assert_eq!(top.ndof(), 3);
}

#[test]
fn analysis_agrees_with_the_peer_reference_values() {
    // Cross-check (not the physics reference) against values the Numba peer reports for
    // p_phi = 3, p_psi = 4, I1 = 1, I3 = 0.5, Mgl = 9.81 (/tmp/peer/FINDINGS.md): the angle
    // agrees to the minimizers' tolerances (~1e-8), the frequencies to ~1e-6 relative.
    let th = find_theta_equilibrium(3.0, 4.0, 1.0, 0.5, 9.81, DEFAULT_THETA_BRACKET).unwrap();
    assert!((th - 1.470_348_307_985_218_4).abs() < 1e-6, "{th}");
    let nut = nutation_frequency(3.0, 4.0, 1.0, 0.5, 9.81, None, DEFAULT_NUTATION_DTHETA).unwrap();
    assert!((nut - 4.346_016_585_885_943).abs() < 1e-5 * nut, "{nut}");
    let prec = precession_frequency(3.0, 4.0, 1.0, th).unwrap();
    assert!((prec - 2.625_282_873_660_156).abs() < 1e-5 * prec, "{prec}");
}
