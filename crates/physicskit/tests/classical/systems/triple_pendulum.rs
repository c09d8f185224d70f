//! The triple pendulum against a hand-written N-link pendulum (its mass matrix, Coriolis and
//! gravity terms, solved here), its conserved energy over a long chaotic run, the normal-mode
//! frequencies of equal links measured from small swings, the double pendulum as the limit
//! of a vanishing third bob, and one test per validation error.

use crate::fixtures::pseudo_random;
use physicskit::classical::catalog::find;
use physicskit::classical::model::{DynSystem, Value};
use physicskit::classical::systems::{TriplePendulum, TriplePendulumParams};
use physicskit::classical::{Error, IntegrateOptions, LagrangianSystem, Method, Tolerances};

/// `mu_j`, the mass at or below rod `j`, and the lengths, of the hand-written chain.
fn links(p: &TriplePendulumParams) -> ([f64; 3], [f64; 3]) {
    ([p.m1 + p.m2 + p.m3, p.m2 + p.m3, p.m3], [p.l1, p.l2, p.l3])
}

/// The N-link mass matrix `M_ij = mu_max(i,j) l_i l_j cos(theta_i - theta_j)`.
fn mass_matrix(p: &TriplePendulumParams, q: &[f64]) -> [[f64; 3]; 3] {
    let (mu, l) = links(p);
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = mu[i.max(j)] * l[i] * l[j] * (q[i] - q[j]).cos();
        }
    }
    m
}

/// Solves `a x = b` by Gaussian elimination with partial pivoting.
fn solve(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> [f64; 3] {
    for col in 0..3 {
        let pivot = (col..3)
            .max_by(|&r, &s| a[r][col].abs().total_cmp(&a[s][col].abs()))
            .unwrap();
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..3 {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col];
            for (x, p) in a[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let tail: f64 = (row + 1..3).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    x
}

/// The accelerations of the N-link pendulum written by hand: `M qddot = f` with
/// `f_i = -sum_j mu_max(i,j) l_i l_j sin(theta_i - theta_j) theta_j'^2 - mu_i g l_i sin theta_i`
/// (the Coriolis/centripetal terms of `d/dt dT/dtheta_i'` and `dT/dtheta_i` combined, and
/// gravity).
fn hand_acceleration(p: &TriplePendulumParams, q: &[f64], w: &[f64]) -> [f64; 3] {
    let (mu, l) = links(p);
    let mut f = [0.0; 3];
    for i in 0..3 {
        f[i] = -mu[i] * p.g * l[i] * q[i].sin();
        for j in 0..3 {
            f[i] -= mu[i.max(j)] * l[i] * l[j] * (q[i] - q[j]).sin() * w[j] * w[j];
        }
    }
    solve(mass_matrix(p, q), f)
}

/// The engine's accelerations (automatic differentiation of `L`) against the hand-written
/// N-link form, at 200 random states (angles anywhere, angular velocities up to 4 rad/s) of
/// random chains (masses and lengths 0.3 to 2.3, `g` from -5 to 15). Both are the same
/// acceleration to rounding: a few dozen operations of relative rounding 1.1e-16, amplified
/// by the mass matrix's condition number (below 1e3 for these ratios of masses and lengths),
/// so they agree to ~1e-13 of the acceleration's scale; 1e-11 leaves a margin of 100, and a
/// wrong or missing term is off by order one.
#[test]
fn accelerations_match_the_hand_written_n_link_pendulum() {
    for k in 0..200 {
        let r = pseudo_random(13, 7 + k);
        let params = TriplePendulumParams {
            m1: 1.3 + 2.0 * r[0],
            m2: 1.3 + 2.0 * r[1],
            m3: 1.3 + 2.0 * r[2],
            l1: 1.3 + 2.0 * r[3],
            l2: 1.3 + 2.0 * r[4],
            l3: 1.3 + 2.0 * r[5],
            g: 5.0 + 20.0 * r[6],
        };
        let q: Vec<f64> = r[7..10]
            .iter()
            .map(|x| 2.0 * std::f64::consts::PI * x)
            .collect();
        let w: Vec<f64> = r[10..13].iter().map(|x| 8.0 * x).collect();
        let system = TriplePendulum::new(&q, &w, params).unwrap();
        let mut engine = [0.0; 3];
        system.acceleration(&q, &w, 0.0, &mut engine).unwrap();
        let hand = hand_acceleration(&params, &q, &w);
        let scale = hand
            .iter()
            .fold(params.g.abs() + 1.0, |m, x| m.max(x.abs()));
        for i in 0..3 {
            assert!(
                (engine[i] - hand[i]).abs() <= 1e-11 * scale,
                "{params:?} q {q:?} w {w:?}: component {i}: engine {} vs hand {}",
                engine[i],
                hand[i]
            );
        }
    }
}

/// The catalogue's entry built with `given`.
fn from_catalogue(name: &str, given: Vec<(&str, Value)>) -> Box<dyn DynSystem> {
    find(name)
        .unwrap()
        .build_from(given.into_iter().map(|(n, v)| (n.to_string(), v)))
        .unwrap()
}

/// From the catalogue's demonstration start (the three rods above the horizontal, at rest:
/// chaotic, with the lower rods whipping over the top) implicit midpoint at `dt = 1e-3` for
/// 60 s keeps the relative energy error bounded: below 2e-3 throughout (measured: 7.6e-4,
/// the `O(dt^2)` oscillation of a symplectic method, largest when a rod whips fast), and not
/// drifting: the largest error in the last tenth of the run is no more than 3 times that of
/// the first tenth (measured 0.5; a linear drift would make it about 10, a random walk of the
/// rounding about 3).
#[test]
fn energy_stays_bounded_over_a_long_chaotic_run() {
    let mut system = from_catalogue("triple-pendulum", vec![]);
    let dt = 1e-3;
    let steps = 60_000;
    let run = system
        .integrate(
            (0.0, steps as f64 * dt),
            dt,
            Method::ImplicitMidpoint,
            IntegrateOptions::stride(10),
        )
        .unwrap();
    let energy = run.energy.clone().unwrap();
    let e0 = energy[0];
    let error: Vec<f64> = energy.iter().map(|e| ((e - e0) / e0).abs()).collect();
    let worst = error.iter().fold(0.0_f64, |m, &x| m.max(x));
    let tenth = error.len() / 10;
    let first = error[1..tenth].iter().fold(0.0_f64, |m, &x| m.max(x));
    let last = error[error.len() - tenth..]
        .iter()
        .fold(0.0_f64, |m, &x| m.max(x));
    println!("triple pendulum energy error {worst:e}, first tenth {first:e}, last {last:e}");
    assert!(worst < 2e-3, "relative energy error {worst:e}");
    assert!(last <= 3.0 * first, "first tenth {first:e}, last {last:e}");
    // The run is chaotic as claimed: some rod passes over the top.
    let q = run.q().unwrap();
    assert!(q.iter().any(|a| a.abs() > std::f64::consts::PI));
}

/// The roots of `lambda^3 - 9 lambda^2 + 18 lambda - 6`, by bisection in the brackets where
/// its sign changes (`p(0) < 0 < p(1)`, `p(4) < 0 < p(8)`).
fn mode_lambdas() -> [f64; 3] {
    let p = |x: f64| ((x - 9.0) * x + 18.0) * x - 6.0;
    let root = |mut lo: f64, mut hi: f64| {
        let rising = p(hi) > p(lo);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if (p(mid) > 0.0) == rising {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    };
    [root(0.0, 1.0), root(1.0, 4.0), root(4.0, 8.0)]
}

/// Times where `x` (sampled every `dt`) changes sign, by linear interpolation.
fn zero_crossings(x: &[f64], dt: f64) -> Vec<f64> {
    x.windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] * w[1] < 0.0)
        .map(|(k, w)| (k as f64 + w[0] / (w[0] - w[1])) * dt)
        .collect()
}

/// Equal masses and rods: the cubic's roots make `det(K - lambda M(0))` vanish, with
/// `M(0)` from the hand-written N-link mass matrix and `K = diag(mu_j g l_j)` (the Hessian of
/// `V = -g sum mu_j l_j cos theta_j`), so the polynomial is this chain's (derived in the
/// module documentation, checked here). Started at rest on each mode's shape (the null
/// vector of `K - lambda M(0)`) at an amplitude of 1e-3 rad, the chain swings at
/// `omega = sqrt(lambda g / l)`: measured from the zero crossings of its largest component
/// over 20 periods, with Gauss–Legendre 6 at 200 steps per period of the fastest mode (its
/// phase error, ~(omega dt)^6, is negligible). The measured frequency differs from the linear
/// one by the amplitude's anharmonic shift, relative `O(amplitude^2)`: measured 3.6e-8,
/// 4.2e-7 and 2.0e-6 for the three modes, largest for the fastest, whose neighbouring rods
/// swing opposed so that the angle differences in `M` are twice the amplitude. The crossings'
/// linear interpolation adds ~(omega dt)^3 of a period once, ~1e-7 after dividing by 20
/// periods. 1e-5 is above both (the runs are deterministic, so a margin of 5 over the largest
/// cannot flicker), while mixing up two modes is off by 50 %.
#[test]
fn small_swings_have_the_normal_mode_frequencies() {
    let params = TriplePendulumParams {
        l1: 0.7,
        l2: 0.7,
        l3: 0.7,
        m1: 0.4,
        m2: 0.4,
        m3: 0.4,
        g: 9.81,
    };
    let (l, g) = (params.l1, params.g);
    let m0 = mass_matrix(&params, &[0.0; 3]);
    let (mu, lengths) = links(&params);
    for lambda in mode_lambdas() {
        let omega2 = lambda * g / l;
        let mut a = m0;
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] = -omega2 * m0[i][j];
            }
            a[i][i] += mu[i] * g * lengths[i];
        }
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        // Entries up to ~30 (kg m^2/s^2): their products of three are ~3e4, rounded to
        // ~1e-11 each; a wrong root leaves a determinant of order 1.
        assert!(det.abs() < 1e-9, "lambda {lambda}: det {det:e}");
        // The mode's shape: the cross product of two rows of the singular matrix.
        let v = [
            a[0][1] * a[1][2] - a[0][2] * a[1][1],
            a[0][2] * a[1][0] - a[0][0] * a[1][2],
            a[0][0] * a[1][1] - a[0][1] * a[1][0],
        ];
        let norm = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let amplitude = 1e-3;
        let q0: Vec<f64> = v.iter().map(|x| amplitude * x / norm).collect();
        let mut system = TriplePendulum::new(&q0, &[0.0; 3], params).unwrap();
        let omega = omega2.sqrt();
        let period = 2.0 * std::f64::consts::PI / omega;
        let fastest = 2.0 * std::f64::consts::PI / (mode_lambdas()[2] * g / l).sqrt();
        let dt = fastest / 200.0;
        // A whole number of steps covering 20.5 periods.
        let steps = (20.5 * period / dt).ceil();
        let run = system
            .integrate((0.0, steps * dt), dt, Method::GaussLegendre6)
            .unwrap();
        let q = run.q().unwrap();
        let big = (0..3)
            .max_by(|&i, &j| q0[i].abs().total_cmp(&q0[j].abs()))
            .unwrap();
        let crossings = zero_crossings(&q.column(big).to_vec(), dt);
        let half_periods = (crossings.len() - 1) as f64;
        let measured =
            std::f64::consts::PI * half_periods / (crossings[crossings.len() - 1] - crossings[0]);
        println!("lambda {lambda}: omega {omega}, measured {measured}");
        assert!(
            (measured - omega).abs() <= 1e-5 * omega,
            "lambda {lambda}: omega {omega} vs measured {measured}"
        );
    }
}

/// With a third bob a millionth of the others and its rod hanging at rest, the upper two
/// links follow the catalogue's `double-pendulum` from the same start over 2 s. The third
/// bob changes the forces on the others by a relative `O(m3 / m) = 1e-6`; the double
/// pendulum's chaos (largest Lyapunov exponent ~1/s at this start) stretches that by a few
/// e-foldings, so the angles agree to ~1e-5 rad (measured: 1.7e-5); 1e-4 bounds that with a
/// margin of 6, and a third bob of normal mass moves them by order one (measured 1.9 rad).
/// The difference shrinks with `m3` (measured: ten times smaller for a ten times lighter bob;
/// asserted to within a factor 2), so it is the third bob's, not the integrator's (both run
/// implicit midpoint at the same step, whose errors on the two nearly equal motions cancel).
#[test]
fn a_vanishing_third_bob_leaves_the_double_pendulum() {
    let (theta, thetadot) = ([2.0, 1.0], [0.5, -0.3]);
    let dt = 1e-3;
    let span = (0.0, 2.0);
    let angles = |system: &mut Box<dyn DynSystem>| {
        let run = system
            .integrate(
                span,
                dt,
                Method::ImplicitMidpoint,
                IntegrateOptions::default(),
            )
            .unwrap();
        let q = run.q().unwrap();
        (q.column(0).to_vec(), q.column(1).to_vec())
    };
    let mut double = from_catalogue(
        "double-pendulum",
        vec![
            ("theta0", Value::Vector(theta.to_vec())),
            ("thetadot0", Value::Vector(thetadot.to_vec())),
        ],
    );
    let (a1, a2) = angles(&mut double);
    let difference = |m3: f64| {
        let mut triple = from_catalogue(
            "triple-pendulum",
            vec![
                ("theta0", Value::Vector(vec![theta[0], theta[1], 0.0])),
                (
                    "thetadot0",
                    Value::Vector(vec![thetadot[0], thetadot[1], 0.0]),
                ),
                ("m3", Value::Scalar(m3)),
            ],
        );
        let (b1, b2) = angles(&mut triple);
        a1.iter()
            .zip(&b1)
            .chain(a2.iter().zip(&b2))
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let small = difference(1e-6);
    let smaller = difference(1e-7);
    let normal = difference(1.0);
    println!("m3 = 1e-6: {small:e}, 1e-7: {smaller:e}, 1: {normal:e}");
    assert!(small < 1e-4, "{small:e}");
    assert!(normal > 0.1, "{normal:e}");
    let ratio = small / smaller;
    assert!((5.0..20.0).contains(&ratio), "{small:e} / {smaller:e}");
}

/// `taylor` (the traced `L`) at tolerance 1e-13 agrees with dop853 at 1e-13 over 1 s from a
/// moderate start (rods at 0.5, -0.4 and 0.8 rad, below where they can flip): each has a
/// global error of ~1e-12 after a second of a mildly chaotic motion, so 1e-9 of the state's
/// scale is a margin of 1000 that still catches any wrong term of the traced equations.
#[test]
fn taylor_follows_dop853() {
    let start = vec![
        ("theta0", Value::Vector(vec![0.5, -0.4, 0.8])),
        ("thetadot0", Value::Vector(vec![0.0, 0.3, 0.0])),
    ];
    let end = |method| {
        let mut system = from_catalogue("triple-pendulum", start.clone());
        let options = IntegrateOptions {
            tolerances: Some(Tolerances::new(1e-13, 1e-13).unwrap()),
            ..IntegrateOptions::final_only()
        };
        let run = system.integrate((0.0, 1.0), 0.1, method, options).unwrap();
        run.y.row(run.y.nrows() - 1).to_vec()
    };
    let (taylor, dop853) = (end(Method::Taylor), end(Method::Dop853));
    let scale = dop853.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (i, (a, b)) in taylor.iter().zip(&dop853).enumerate() {
        assert!((a - b).abs() <= 1e-9 * scale, "component {i}: {a} vs {b}");
    }
}

/// Bob positions follow the rods from the pivot, `y` up.
#[test]
fn positions_hang_each_bob_from_the_last() {
    let params = TriplePendulumParams {
        l1: 1.0,
        l2: 2.0,
        l3: 0.5,
        ..Default::default()
    };
    let hanging = TriplePendulum::new(&[0.0; 3], &[0.0; 3], params).unwrap();
    let half_pi = std::f64::consts::FRAC_PI_2;
    let poses = [
        ([0.0, 0.0, 0.0], [0.0, -1.0, 0.0, -3.0, 0.0, -3.5]),
        ([half_pi, 0.0, -half_pi], [1.0, 0.0, 1.0, -2.0, 0.5, -2.0]),
    ];
    for (q, expected) in poses {
        let at = hanging.positions(Some(&q)).unwrap();
        for (a, b) in at.iter().zip(expected) {
            // sin and cos of 0 and pi/2 are exact to an ulp, times lengths of order 1.
            assert!((a - b).abs() < 1e-15, "{q:?}: {at:?}");
        }
    }
    assert!(matches!(
        hanging.positions(Some(&[0.0; 2])),
        Err(Error::DimensionMismatch { .. })
    ));
}

/// The bobs are the rods' vectors `l_i (sin θ_i, -cos θ_i)` summed from the pivot in chain
/// order, to the bit, at angles over several turns either way.
#[test]
fn positions_are_the_rods_summed_to_the_bit() {
    let params = TriplePendulumParams {
        l1: 0.7,
        l2: 1.3,
        l3: 0.4,
        ..Default::default()
    };
    let l = [params.l1, params.l2, params.l3];
    let p = TriplePendulum::new(&[0.0; 3], &[0.0; 3], params).unwrap();
    for i in 0..200 {
        let i = f64::from(i);
        let q = [i * 0.137 - 13.0, 11.0 - i * 0.291, i * 0.05 - 4.0];
        let (s, c): (Vec<f64>, Vec<f64>) = q.iter().map(|a| a.sin_cos()).unzip();
        let (x1, y1) = (l[0] * s[0], -(l[0] * c[0]));
        let (x2, y2) = (x1 + l[1] * s[1], y1 - l[1] * c[1]);
        let (x3, y3) = (x2 + l[2] * s[2], y2 - l[2] * c[2]);
        let at = p.positions(Some(&q)).unwrap();
        assert_eq!(
            at.map(f64::to_bits),
            [x1, y1, x2, y2, x3, y3].map(f64::to_bits),
            "{q:?}"
        );
    }
}

/// A bad parameter through the catalogue: the error names it.
fn refused(name: &str, value: Value) -> String {
    find("triple-pendulum")
        .unwrap()
        .build_from([(name.to_string(), value)])
        .err()
        .unwrap_or_else(|| panic!("{name} accepted"))
        .to_string()
}

#[test]
fn refuses_a_non_positive_mass() {
    for name in ["m1", "m2", "m3"] {
        assert!(refused(name, Value::Scalar(0.0)).contains(name));
        assert!(refused(name, Value::Scalar(-1.0)).contains(name));
    }
}

#[test]
fn refuses_a_non_positive_length() {
    for name in ["l1", "l2", "l3"] {
        assert!(refused(name, Value::Scalar(0.0)).contains(name));
        assert!(refused(name, Value::Scalar(f64::INFINITY)).contains(name));
    }
}

#[test]
fn refuses_non_finite_gravity() {
    assert!(refused("g", Value::Scalar(f64::NAN)).contains('g'));
    let params = TriplePendulumParams {
        g: f64::INFINITY,
        ..Default::default()
    };
    let err = TriplePendulum::new(&[0.0; 3], &[0.0; 3], params).unwrap_err();
    assert!(
        matches!(&err, Error::InvalidParameter { name, .. } if name == "g"),
        "{err}"
    );
}

#[test]
fn refuses_the_wrong_number_of_angles() {
    assert!(refused("theta0", Value::Vector(vec![1.0, 2.0])).contains("theta0"));
    let err =
        TriplePendulum::new(&[0.0; 3], &[0.0; 2], TriplePendulumParams::default()).unwrap_err();
    assert!(matches!(err, Error::DimensionMismatch { .. }), "{err}");
}

#[test]
fn refuses_a_non_finite_angle() {
    let err = TriplePendulum::new(
        &[0.0, f64::NAN, 0.0],
        &[0.0; 3],
        TriplePendulumParams::default(),
    )
    .unwrap_err();
    assert!(!err.to_string().is_empty());
    assert!(refused("theta0", Value::Vector(vec![0.0, f64::NAN, 0.0])).contains("theta0"));
}
