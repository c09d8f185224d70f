//! The torque-free rigid body (`EulerTop`): quadratic invariants, the intermediate-axis flip
//! and its elliptic-integral period (Landau & Lifshitz, *Mechanics*, §37), the quaternion
//! convention, and input validation.

use physicskit::classical::systems::{EulerTop, EulerTopParams};
use physicskit::classical::{DynamicalSystem, Error, Method, OdeSystem};

fn tumbling() -> EulerTop {
    EulerTop::new(&[0.01, 1.0, 0.01], EulerTopParams::default(), None).unwrap()
}

#[test]
fn quadratic_invariants_are_conserved_over_1e5_steps() {
    // Implicit midpoint conserves every quadratic invariant exactly up to the solve tolerance
    // (2 ulps per step) and rounding; over 1e5 steps the rounding random walk reaches
    // ~sqrt(1e5) * 1e-16 ~ 3e-14. 1e-12 is the bar.
    let mut top = tumbling();
    let dt = 1e-3;
    let result = top
        .integrate((0.0, 1e5 * dt), dt, Method::ImplicitMidpoint)
        .unwrap();
    let e0 = top.energy(result.y.row(0).as_slice().unwrap());
    let l0 = top
        .angular_momentum_squared(Some(result.y.row(0).as_slice().unwrap()))
        .unwrap();
    let (mut de, mut dl, mut dn) = (0.0_f64, 0.0_f64, 0.0_f64);
    for row in result.y.rows() {
        let s = row.as_slice().unwrap();
        de = de.max((top.energy(s) - e0).abs() / e0);
        dl = dl.max((top.angular_momentum_squared(Some(s)).unwrap() - l0).abs() / l0);
        dn = dn.max((s[3..].iter().map(|x| x * x).sum::<f64>() - 1.0).abs());
    }
    println!("Euler top over 1e5 steps: energy {de:e}, |L|^2 {dl:e}, |q|^2 - 1 {dn:e}");
    assert!(de < 1e-12 && dl < 1e-12 && dn < 1e-12, "{de} {dl} {dn}");
    assert_eq!(result.method, "implicit_midpoint");
    assert_eq!(top.default_method(), Method::ImplicitMidpoint);
}

#[test]
fn energy_and_angular_momentum_match_their_definitions() {
    let top = EulerTop::new(&[0.3, -0.5, 0.7], EulerTopParams::default(), None).unwrap();
    let e = 0.5 * (0.3_f64.powi(2) + 2.0 * 0.25 + 3.0 * 0.49);
    let l2 = 0.09 + 1.0 + 2.1_f64.powi(2);
    // Values of order 1 and 5 evaluated in a different operation order: a few ulps each.
    assert!((top.current_energy() - e).abs() < 1e-15);
    assert!((top.angular_momentum_squared(None).unwrap() - l2).abs() < 1e-14);
    assert!(top.angular_momentum_squared(Some(&[0.0; 6])).is_err());
}

#[test]
fn spin_near_the_intermediate_axis_flips() {
    let mut top = tumbling();
    let result = top
        .integrate((0.0, 100.0), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let max_w1 = result
        .y
        .column(0)
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(max_w1 > 0.5, "{max_w1}");
    // w2 reverses: the body turns over.
    let min_w2 = result
        .y
        .column(1)
        .iter()
        .fold(f64::INFINITY, |m, v| m.min(*v));
    assert!(min_w2 < -0.9, "{min_w2}");
}

#[test]
fn spins_about_the_smallest_and_largest_axes_do_not_flip() {
    // Stable axes: the small components stay small (bounded by ~0.01 times a ratio of inertia
    // differences of order 1), so the main component stays above 0.99.
    for (omega0, axis) in [([1.0, 0.01, 0.01], 0), ([0.01, 0.01, 1.0], 2)] {
        let mut top = EulerTop::new(&omega0, EulerTopParams::default(), None).unwrap();
        let result = top
            .integrate((0.0, 100.0), 1e-3, Method::ImplicitMidpoint)
            .unwrap();
        let min = result
            .y
            .column(axis)
            .iter()
            .fold(f64::INFINITY, |m, v| m.min(*v));
        assert!(min > 0.99, "axis {axis}: {min}");
    }
}

/// Complete elliptic integral of the first kind `K(m)`, `m = k^2`, by the arithmetic-geometric
/// mean: `K = pi / (2 AGM(1, sqrt(1 - m)))` (Abramowitz & Stegun 17.6), converging
/// quadratically to machine precision.
fn ellip_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - m).sqrt());
    while (a - b).abs() > 1e-15 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Period of the body-frame angular velocity (Landau & Lifshitz §37, I1 < I2 < I3): with
/// `E` the energy and `L^2` the squared angular momentum, for `L^2 > 2 E I2`
/// `rate = sqrt((I3 - I2)(L^2 - 2 E I1) / (I1 I2 I3))`,
/// `k^2 = (I2 - I1)(2 E I3 - L^2) / ((I3 - I2)(L^2 - 2 E I1))`, and for `L^2 < 2 E I2` the
/// same with I1 and I3 exchanged; then `T = 4 K(k) / rate`.
fn analytic_period(i: [f64; 3], e: f64, l2: f64) -> f64 {
    let [mut i1, i2, mut i3] = i;
    if l2 < 2.0 * e * i2 {
        std::mem::swap(&mut i1, &mut i3);
    }
    let rate = ((i3 - i2) * (l2 - 2.0 * e * i1) / (i1 * i2 * i3)).sqrt();
    let k2 = (i2 - i1) * (2.0 * e * i3 - l2) / ((i3 - i2) * (l2 - 2.0 * e * i1));
    4.0 * ellip_k(k2) / rate
}

#[test]
fn flip_period_matches_the_elliptic_integral() {
    // The bar is 1%. Implicit midpoint at dt = 1e-3 shifts frequencies by
    // ~(w dt)^2 / 12 ~ 1e-7; near the separatrix the period depends on the invariants only
    // logarithmically, and those are conserved to 1e-13.
    for omega0 in [[0.01, 1.0, 0.01], [0.05, 1.0, -0.03], [0.02, 1.0, 0.2]] {
        let mut top = EulerTop::new(&omega0, EulerTopParams::default(), None).unwrap();
        let e = top.current_energy();
        let l2 = top.angular_momentum_squared(None).unwrap();
        let want = analytic_period([1.0, 2.0, 3.0], e, l2);
        let result = top
            .integrate((0.0, 200.0), 1e-3, Method::ImplicitMidpoint)
            .unwrap();
        // w2 ~ sn (or cn): upward zero crossings are one full period apart, and every zero
        // crossing (a flip) half a period apart.
        let t = result.t.to_vec();
        let w2 = result.y.column(1).to_vec();
        let mut up = Vec::new();
        let mut all = Vec::new();
        for k in 1..w2.len() {
            if (w2[k - 1] < 0.0) != (w2[k] < 0.0) {
                let tc = t[k - 1] + (t[k] - t[k - 1]) * w2[k - 1] / (w2[k - 1] - w2[k]);
                all.push(tc);
                if w2[k] >= 0.0 {
                    up.push(tc);
                }
            }
        }
        assert!(up.len() >= 2, "{omega0:?}: {} upward crossings", up.len());
        let period = (up[up.len() - 1] - up[0]) / (up.len() - 1) as f64;
        let flip = (all[all.len() - 1] - all[0]) / (all.len() - 1) as f64;
        println!(
            "omega0 {omega0:?}: period {period} vs {want} ({:e}), flip interval {flip}",
            (period - want) / want
        );
        assert!((period - want).abs() < 0.01 * want, "{period} vs {want}");
        assert!((flip - 0.5 * want).abs() < 0.01 * want);
    }
}

fn mat_vec(r: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

#[test]
fn world_frame_angular_momentum_is_constant() {
    // L_world = R(q) I omega is conserved by the exact flow. It is not a quadratic invariant of
    // the (omega, q) system, so implicit midpoint keeps it to O(dt^2) ~ 1e-6 only; a wrong
    // quaternion convention (left instead of right multiplication by omega) makes it O(1).
    let mut top = EulerTop::new(
        &[0.05, 1.0, 0.1],
        EulerTopParams::default(),
        Some(&[0.9, 0.1, -0.3, 0.2]),
    )
    .unwrap();
    let result = top
        .integrate((0.0, 50.0), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let inertia = top.inertia();
    let l_world = |s: &[f64]| {
        let r = top.rotation_matrix(Some(s)).unwrap();
        mat_vec(&r, [0, 1, 2].map(|i| inertia[i] * s[i]))
    };
    let l0 = l_world(result.y.row(0).as_slice().unwrap());
    let mut worst = 0.0_f64;
    for row in result.y.rows() {
        let l = l_world(row.as_slice().unwrap());
        worst = worst.max((0..3).map(|i| (l[i] - l0[i]).abs()).fold(0.0, f64::max));
    }
    // O(dt^2) ~ 1e-6 per unit time accumulates over t = 50 to ~5e-5 at most; 1e-4 still
    // rejects the wrong convention by four orders of magnitude.
    assert!(worst < 1e-4, "{worst}");
}

#[test]
fn steady_spin_about_a_principal_axis_rotates_the_body_about_that_axis() {
    // omega = (0, 0, w) is a fixed point of Euler's equations; the orientation is then
    // Rz(w t) exactly. Implicit midpoint's phase error over t = 2 at w dt = 1.5e-3 is
    // ~w t (w dt)^2 / 12 ~ 6e-7.
    let w = 1.5;
    let mut top = EulerTop::new(&[0.0, 0.0, w], EulerTopParams::default(), None).unwrap();
    top.integrate((0.0, 2.0), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let r = top.rotation_matrix(None).unwrap();
    let (s, c) = (w * 2.0_f64).sin_cos();
    let want = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
    for i in 0..3 {
        for j in 0..3 {
            // ~6e-7 expected (see above); 1e-5 leaves a 15x margin.
            assert!((r[i][j] - want[i][j]).abs() < 1e-5, "{r:?}");
        }
    }
}

#[test]
fn rotation_matrix_is_body_to_world() {
    // q = (cos 0.25, 0, 0, sin 0.25): 0.5 rad about z; the body x axis points along
    // (cos 0.5, sin 0.5, 0) in the world (the peer's convention).
    let h = 0.25_f64;
    let top = EulerTop::new(
        &[0.0, 0.0, 0.0],
        EulerTopParams::default(),
        Some(&[h.cos(), 0.0, 0.0, h.sin()]),
    )
    .unwrap();
    let r = top.rotation_matrix(None).unwrap();
    let x = mat_vec(&r, [1.0, 0.0, 0.0]);
    assert!((x[0] - 0.5_f64.cos()).abs() < 1e-15 && (x[1] - 0.5_f64.sin()).abs() < 1e-15);
    // Any quaternion: orthonormal with determinant 1, also unnormalized (it is normalized).
    let state = [0.0, 0.0, 0.0, 2.0, -1.0, 0.5, 3.0];
    let r = top.rotation_matrix(Some(&state)).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((dot - want).abs() < 1e-15);
        }
    }
    let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
        - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
        + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    assert!((det - 1.0).abs() < 1e-15);
    assert!(top.rotation_matrix(Some(&[0.0; 7])).is_err());
}

#[test]
fn jacobian_matches_finite_differences() {
    // The right-hand side is quadratic, so central differences are exact up to rounding
    // (eps |f| / h ~ 1e-10 at h = 1e-6).
    let top = EulerTop::new(
        &[0.3, -0.7, 1.1],
        EulerTopParams::default(),
        Some(&[0.5, 0.5, -0.5, 0.5]),
    )
    .unwrap();
    let state = top.state().to_vec();
    let mut jac = [0.0; 49];
    top.jacobian(0.0, &state, &mut jac).unwrap().unwrap();
    let h = 1e-6;
    for j in 0..7 {
        let (mut sp, mut sm) = (state.clone(), state.clone());
        sp[j] += h;
        sm[j] -= h;
        let (mut fp, mut fm) = ([0.0; 7], [0.0; 7]);
        top.derivatives(0.0, &sp, &mut fp).unwrap();
        top.derivatives(0.0, &sm, &mut fm).unwrap();
        for i in 0..7 {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            assert!((jac[i * 7 + j] - fd).abs() < 1e-8, "J[{i}][{j}]");
        }
    }
}

#[test]
fn accessors_and_methods() {
    let mut top = tumbling();
    // Exact copies of the inputs: compare bit patterns.
    assert_eq!(
        top.omega().map(f64::to_bits),
        [0.01, 1.0, 0.01].map(f64::to_bits)
    );
    assert_eq!(
        top.quaternion().map(f64::to_bits),
        [1.0, 0.0, 0.0, 0.0].map(f64::to_bits)
    );
    assert!(top.integrate((0.0, 0.1), 1e-3, Method::Rk4).is_ok());
    assert!(matches!(
        top.integrate((0.0, 0.1), 1e-3, Method::Yoshida4),
        Err(Error::UnsupportedMethod { .. })
    ));
}

#[test]
fn quaternion_is_normalized() {
    let top = EulerTop::new(
        &[0.0, 1.0, 0.0],
        EulerTopParams::default(),
        Some(&[2.0, 0.0, 0.0, 0.0]),
    )
    .unwrap();
    // (2, 0, 0, 0) / 2 is exact.
    assert_eq!(
        top.quaternion().map(f64::to_bits),
        [1.0, 0.0, 0.0, 0.0].map(f64::to_bits)
    );
}

#[test]
fn zero_quaternion_is_an_error() {
    let e =
        EulerTop::new(&[0.0, 1.0, 0.0], EulerTopParams::default(), Some(&[0.0; 4])).unwrap_err();
    assert!(e.to_string().contains("quat0"), "{e}");
}

#[test]
fn quaternion_of_wrong_length_is_an_error() {
    let e =
        EulerTop::new(&[0.0, 1.0, 0.0], EulerTopParams::default(), Some(&[1.0; 3])).unwrap_err();
    assert!(matches!(e, Error::DimensionMismatch { .. }), "{e}");
}

#[test]
fn non_finite_quaternion_is_an_error() {
    assert!(EulerTop::new(
        &[0.0, 1.0, 0.0],
        EulerTopParams::default(),
        Some(&[1.0, f64::NAN, 0.0, 0.0])
    )
    .is_err());
}

#[test]
fn omega_of_wrong_length_is_an_error() {
    let e = EulerTop::new(&[0.0, 1.0], EulerTopParams::default(), None).unwrap_err();
    assert!(matches!(e, Error::DimensionMismatch { .. }), "{e}");
}

#[test]
fn non_positive_moment_is_an_error() {
    let params = EulerTopParams {
        i2: 0.0,
        ..Default::default()
    };
    let e = EulerTop::new(&[0.0, 1.0, 0.0], params, None).unwrap_err();
    assert!(e.to_string().contains("I2"), "{e}");
}

#[test]
#[ignore = "dt survey of long runs; run with --ignored --nocapture"]
fn energy_drift_versus_dt() {
    // Energy is a quadratic invariant, so implicit midpoint keeps it at any dt for which the
    // implicit solve converges; this survey records how far that goes over t = 100.
    for dt in [1e-3, 1e-2, 0.1, 0.25, 0.5, 1.0] {
        let mut top = tumbling();
        match top.integrate((0.0, 100.0), dt, Method::ImplicitMidpoint) {
            Ok(r) => println!(
                "dt {dt}: drift {:e}",
                r.max_relative_energy_error().unwrap()
            ),
            Err(e) => println!("dt {dt}: {e}"),
        }
    }
}

#[test]
// Exact values (single products, a zero half-extent, the default state) are the claim here.
#[allow(clippy::float_cmp)]
fn body_angular_momentum_is_i_omega_and_meets_the_invariants() {
    let top = EulerTop::new(&[0.3, -0.5, 0.7], EulerTopParams::default(), None).unwrap();
    let state = [0.3, -0.5, 0.7, 0.9, 0.1, -0.3, 0.2];
    let l = top.body_angular_momentum(Some(&state)).unwrap();
    // I = (1, 2, 3) times omega, the same single product each: equal to the bit.
    assert_eq!(l, [0.3, 2.0 * -0.5, 3.0 * 0.7]);
    // |L|^2 and 2E = L . omega, against the system's own invariants: sums of three order-1
    // terms, a few ulps apart.
    let l2: f64 = l.iter().map(|x| x * x).sum();
    assert!((l2 - top.angular_momentum_squared(Some(&state)).unwrap()).abs() < 1e-15 * l2);
    let two_e: f64 = (0..3).map(|i| l[i] * state[i]).sum();
    assert!((two_e - 2.0 * top.energy(&state)).abs() < 1e-15 * two_e);
    assert_eq!(top.body_angular_momentum(None).unwrap(), l);
    assert!(top.body_angular_momentum(Some(&state[..6])).is_err());
}

#[test]
fn body_angular_momentum_turned_to_space_is_conserved() {
    // Torque-free: R L_body is constant. rk4 at dt = 1e-3 has a global error bounded by
    // ~(w dt)^4 t ~ 1e-11 here (3e-14 measured); 1e-11 rejects a wrong frame (L_body itself
    // moves by order 1 on this tumbling orbit).
    let mut top = EulerTop::new(&[0.1, 1.0, 0.2], EulerTopParams::default(), None).unwrap();
    let result = top.integrate((0.0, 20.0), 1e-3, Method::Rk4).unwrap();
    let space = |s: &[f64]| {
        let r = top.rotation_matrix(Some(s)).unwrap();
        mat_vec(&r, top.body_angular_momentum(Some(s)).unwrap())
    };
    let l0 = space(result.y.row(0).as_slice().unwrap());
    let (mut worst, mut body_moves) = (0.0_f64, 0.0_f64);
    let b0 = top
        .body_angular_momentum(Some(result.y.row(0).as_slice().unwrap()))
        .unwrap();
    for row in result.y.rows() {
        let s = row.as_slice().unwrap();
        let l = space(s);
        let b = top.body_angular_momentum(Some(s)).unwrap();
        worst = worst.max((0..3).map(|i| (l[i] - l0[i]).abs()).fold(0.0, f64::max));
        body_moves = body_moves.max((0..3).map(|i| (b[i] - b0[i]).abs()).fold(0.0, f64::max));
    }
    println!("space-frame L drift {worst:e}, body-frame L moves {body_moves}");
    assert!(worst < 1e-11 && body_moves > 0.5, "{worst} {body_moves}");
}

/// The principal moments of a uniform box of mass `m` and half-extents `a`, by the midpoint
/// rule on an `n^3` grid of equal point masses: `I1 = sum m_k (y_k^2 + z_k^2)`, and cyclically.
fn box_moments_by_quadrature(a: [f64; 3], m: f64, n: usize) -> [f64; 3] {
    let coord = |half: f64, k: usize| half * (2.0 * (k as f64 + 0.5) / n as f64 - 1.0);
    let mut second = [0.0_f64; 3]; // sum m_k x_i^2 per axis
    let mk = m / (n * n * n) as f64;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let x = [coord(a[0], i), coord(a[1], j), coord(a[2], k)];
                for d in 0..3 {
                    second[d] += mk * x[d] * x[d];
                }
            }
        }
    }
    [
        second[1] + second[2],
        second[0] + second[2],
        second[0] + second[1],
    ]
}

#[test]
fn inertia_box_has_the_body_s_moments() {
    let n = 40;
    for (moments, mass) in [
        ([1.0, 2.0, 2.5], 1.0),
        ([0.7, 0.9, 1.3], 2.5),
        ([2.0, 2.0, 2.0], 0.3),
    ] {
        let [i1, i2, i3] = moments;
        let top = EulerTop::new(&[0.0, 0.0, 1.0], EulerTopParams { i1, i2, i3 }, None).unwrap();
        let half = top.inertia_box(mass).unwrap();
        let got = box_moments_by_quadrature(half, mass, n);
        for d in 0..3 {
            // The midpoint rule's error for a quadratic is exact: over [-a, a] with n cells it
            // misses 2a h^2 f''/24 = 2a^3/(3 n^2) of 2a^3/3, so the grid's moments are exactly
            // I (1 - 1/n^2); summing 64000 terms adds ~1e-13 of rounding, hence 1e-12.
            let want = moments[d] * (1.0 - 1.0 / (n * n) as f64);
            assert!((got[d] - want).abs() < 1e-12 * want, "{moments:?}: {got:?}");
        }
    }
}

#[test]
// Exact values (single products, a zero half-extent, the default state) are the claim here.
#[allow(clippy::float_cmp)]
fn inertia_box_of_the_default_moments_is_a_plate_and_bad_input_is_an_error() {
    // I = (1, 2, 3): I3 = I1 + I2, the perpendicular-axis theorem of a lamina: a3 = 0.
    let top = tumbling();
    let [a1, a2, a3] = top.inertia_box(1.0).unwrap();
    assert_eq!(a3, 0.0);
    // a1^2 = 3 (2 + 3 - 1) / 2 = 6, a2^2 = 3: one rounding in each square root.
    assert!((a1 - 6.0_f64.sqrt()).abs() < 1e-15 * a1 && (a2 - 3.0_f64.sqrt()).abs() < 1e-15 * a2);
    for mass in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(top.inertia_box(mass), Err(Error::InvalidParameter { .. })),
            "{mass}"
        );
    }
    let rod_too_long = EulerTop::new(
        &[0.0, 0.0, 1.0],
        EulerTopParams {
            i1: 1.0,
            i2: 2.0,
            i3: 10.0,
        },
        None,
    )
    .unwrap();
    let err = rod_too_long.inertia_box(1.0).unwrap_err();
    assert!(err.to_string().contains("I3"), "{err}");
}
