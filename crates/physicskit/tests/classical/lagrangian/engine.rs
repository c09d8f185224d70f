//! The Lagrangian engine against equations of motion derived by hand.
//!
//! Each system's Lagrangian is written once in the library; here the textbook equations of
//! motion (Euler–Lagrange worked out on paper, cited per test) are written out independently
//! and compared at 100 random states, through `AutoDiff` engines, so that it is automatic
//! differentiation that is checked (the built-in systems' closed forms are checked against
//! it in `lagrangian_closed_forms.rs`). Also: the Euler–Lagrange residual of a computed
//! trajectory by finite differences, the canonical form and its Jacobian, a non-quadratic
//! Lagrangian, singular mass matrices, and expression Lagrangians.

use physicskit::classical::lagrangian::{
    AutoDiff, Lagrangian, LagrangianEngine, LagrangianModel, Scalar, MAX_STACK_NDOF,
};
use physicskit::classical::symbolic::{Expr, ExprLagrangian};
use physicskit::classical::systems::{
    CoupledOscillatorsParams, DoublePendulum, DoublePendulumParams, HeavySymmetricTop, HoopParams,
    SymmetricTopParams,
};
use physicskit::classical::{DynamicalSystem, Error, LagrangianSystem, Method};

/// A small deterministic generator (SplitMix64), so the "random" states are reproducible.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    let diff: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    inf_norm(&diff) / inf_norm(b).max(f64::MIN_POSITIVE)
}

/// Hand-derived double-pendulum equations (Taylor, *Classical Mechanics* §11.4; with
/// `D = theta1 - theta2`):
/// `(m1+m2) l1 a1 + m2 l2 a2 cos D = -m2 l2 w2^2 sin D - (m1+m2) g sin theta1`,
/// `l1 a1 cos D + l2 a2 = l1 w1^2 sin D - g sin theta2`, solved by Cramer's rule.
fn double_pendulum_hand(p: &DoublePendulumParams, q: &[f64], w: &[f64]) -> [f64; 2] {
    let DoublePendulumParams { m1, m2, l1, l2, g } = *p;
    let d = q[0] - q[1];
    let (a11, a12, a21, a22) = ((m1 + m2) * l1, m2 * l2 * d.cos(), l1 * d.cos(), l2);
    let b1 = -m2 * l2 * w[1] * w[1] * d.sin() - (m1 + m2) * g * q[0].sin();
    let b2 = l1 * w[0] * w[0] * d.sin() - g * q[1].sin();
    let det = a11 * a22 - a12 * a21;
    [(b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det]
}

fn random_double_pendulum(rng: &mut Rng) -> (DoublePendulumParams, [f64; 2], [f64; 2]) {
    let params = DoublePendulumParams {
        m1: rng.uniform(0.5, 2.0),
        m2: rng.uniform(0.5, 2.0),
        l1: rng.uniform(0.5, 2.0),
        l2: rng.uniform(0.5, 2.0),
        g: 9.81,
    };
    let q = [rng.uniform(-3.1, 3.1), rng.uniform(-3.1, 3.1)];
    let w = [rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)];
    (params, q, w)
}

// Tolerance 1e-12 (relative, max norm) throughout the hand-derived comparisons: both sides are
// the same function evaluated along different rounding paths; the mass matrices here have
// condition numbers below ~100, so the two agree to ~100 ulps, far inside 1e-12, while any
// wrong term would be O(1).
const HAND_TOL: f64 = 1e-12;

#[test]
fn double_pendulum_matches_hand_derived_equations_at_random_states() {
    let mut rng = Rng(1);
    for _ in 0..100 {
        let (params, q, w) = random_double_pendulum(&mut rng);
        let dp = LagrangianEngine::new(AutoDiff(params)).unwrap();
        let mut a = [0.0; 2];
        dp.acceleration(&q, &w, 0.0, &mut a).unwrap();
        let want = double_pendulum_hand(&params, &q, &w);
        assert!(rel_err(&a, &want) < HAND_TOL, "{a:?} vs {want:?}");

        // Momenta and energy, also by hand.
        let DoublePendulumParams { m1, m2, l1, l2, g } = params;
        let c = (q[0] - q[1]).cos();
        let p_hand = [
            (m1 + m2) * l1 * l1 * w[0] + m2 * l1 * l2 * w[1] * c,
            m2 * l2 * l2 * w[1] + m2 * l1 * l2 * w[0] * c,
        ];
        let mut p = [0.0; 2];
        dp.momentum(&q, &w, 0.0, &mut p).unwrap();
        assert!(rel_err(&p, &p_hand) < HAND_TOL);
        let t = 0.5 * (m1 + m2) * l1 * l1 * w[0] * w[0]
            + 0.5 * m2 * l2 * l2 * w[1] * w[1]
            + m2 * l1 * l2 * w[0] * w[1] * c;
        let v = -(m1 + m2) * g * l1 * q[0].cos() - m2 * g * l2 * q[1].cos();
        let e = dp.energy_of_state(&[q[0], q[1], w[0], w[1]], 0.0);
        // Energy: |T| + |V| sets the rounding scale of T + V.
        assert!((e - (t + v)).abs() < HAND_TOL * (t.abs() + v.abs()));

        // Canonical form: the velocity inverts the momentum, and dp/dt = dL/dq by hand.
        let mut back = [0.0; 2];
        dp.velocity(&q, &p_hand, 0.0, &mut back).unwrap();
        assert!(rel_err(&back, &w) < HAND_TOL, "{back:?} vs {w:?}");
        let s = (q[0] - q[1]).sin();
        let dldq = [
            -m2 * l1 * l2 * w[0] * w[1] * s - (m1 + m2) * g * l1 * q[0].sin(),
            m2 * l1 * l2 * w[0] * w[1] * s - m2 * g * l2 * q[1].sin(),
        ];
        let mut canon = [0.0; 4];
        dp.canonical_derivatives(0.0, &[q[0], q[1], p_hand[0], p_hand[1]], &mut canon)
            .unwrap();
        assert!(rel_err(&canon[..2], &w) < HAND_TOL);
        // dL/dq at the recovered velocity: its error is the velocity's error times the
        // velocity-scale of dL/dq, so compare on the scale of the largest force term.
        let scale = (m1 + m2) * g * l1 + m2 * l1 * l2 * inf_norm(&w).powi(2);
        assert!(inf_norm(&[canon[2] - dldq[0], canon[3] - dldq[1]]) < HAND_TOL * scale);
    }
}

#[test]
fn hoop_matches_hand_derived_equation_at_random_states() {
    // Taylor §7.6 (rotating-frame Lagrangian): theta'' = sin(theta) (omega^2 cos(theta) - g/R).
    let mut rng = Rng(2);
    for _ in 0..100 {
        let params = HoopParams {
            r: rng.uniform(0.3, 3.0),
            omega: rng.uniform(-6.0, 6.0),
            g: 9.81,
        };
        let (th, w) = (rng.uniform(-3.1, 3.1), rng.uniform(-5.0, 5.0));
        let hoop = LagrangianEngine::new(AutoDiff(params)).unwrap();
        let mut a = [0.0];
        hoop.acceleration(&[th], &[w], 0.0, &mut a).unwrap();
        let want = th.sin() * (params.omega * params.omega * th.cos() - params.g / params.r);
        // Absolute scale: the two terms of the bracket, omega^2 and g/R.
        let scale = params.omega * params.omega + params.g / params.r;
        assert!((a[0] - want).abs() < HAND_TOL * scale, "{} vs {want}", a[0]);
        let r2 = params.r * params.r;
        let jacobi = 0.5 * r2 * w * w - 0.5 * r2 * (params.omega * th.sin()).powi(2)
            + params.g * params.r * (1.0 - th.cos());
        let e = hoop.energy_of_state(&[th, w], 0.0);
        let e_scale = r2 * (w * w + params.omega * params.omega) + params.g * params.r;
        assert!((e - jacobi).abs() < HAND_TOL * e_scale);
    }
}

/// Hand-derived heavy-top equations (Goldstein §5.7), with `w3 = psi' + phi' cos(theta)`:
/// `I1 theta'' = I1 phi'^2 sin cos - I3 w3 phi' sin + M g l sin`,
/// `phi'' = theta' (I3 w3 - 2 I1 phi' cos) / (I1 sin)` (from `d p_phi / dt = 0`),
/// `psi'' = phi' theta' sin - phi'' cos` (from `d w3 / dt = 0`).
fn top_hand(p: &SymmetricTopParams, q: &[f64], w: &[f64]) -> [f64; 3] {
    let (s, c) = q[1].sin_cos();
    let (phid, thd, psid) = (w[0], w[1], w[2]);
    let w3 = psid + phid * c;
    let mgl = p.m * p.g * p.l;
    let thdd = (p.i1 * phid * phid * s * c - p.i3 * w3 * phid * s + mgl * s) / p.i1;
    let phidd = thd * (p.i3 * w3 - 2.0 * p.i1 * phid * c) / (p.i1 * s);
    let psidd = phid * thd * s - phidd * c;
    [phidd, thdd, psidd]
}

#[test]
fn symmetric_top_matches_hand_derived_equations_at_random_states() {
    let mut rng = Rng(3);
    for _ in 0..100 {
        let params = SymmetricTopParams {
            i1: rng.uniform(0.5, 2.0),
            i3: rng.uniform(0.2, 1.0),
            m: rng.uniform(0.5, 2.0),
            l: rng.uniform(0.2, 1.5),
            g: 9.81,
        };
        let q = [
            rng.uniform(-3.0, 3.0),
            rng.uniform(0.3, 2.8),
            rng.uniform(-3.0, 3.0),
        ];
        let w = [
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
            rng.uniform(-30.0, 30.0),
        ];
        let top = LagrangianEngine::new(AutoDiff(params)).unwrap();
        let mut a = [0.0; 3];
        top.acceleration(&q, &w, 0.0, &mut a).unwrap();
        let want = top_hand(&params, &q, &w);
        // The mass matrix has condition ~ 1/sin^2(theta) <= 12 here; scale by the largest
        // product of rates that enters (|w|^2) as well as the result, since phi'' and psi''
        // can nearly cancel.
        let scale = inf_norm(&want).max(inf_norm(&w).powi(2) * params.i3 / params.i1);
        let diff: Vec<f64> = a.iter().zip(&want).map(|(x, y)| x - y).collect();
        assert!(inf_norm(&diff) < HAND_TOL * scale, "{a:?} vs {want:?}");
        // Conserved momenta by hand.
        let (p_phi, p_psi) = params
            .conserved_momenta(&[q[0], q[1], q[2], w[0], w[1], w[2]])
            .unwrap();
        let mut p = [0.0; 3];
        top.momentum(&q, &w, 0.0, &mut p).unwrap();
        let (s, c) = q[1].sin_cos();
        let p_psi_hand = params.i3 * (w[2] + w[0] * c);
        let p_phi_hand = params.i1 * w[0] * s * s + p_psi_hand * c;
        assert!(rel_err(&p, &[p_phi_hand, params.i1 * w[1], p_psi_hand]) < HAND_TOL);
        // `conserved_momenta` evaluates these same expressions; 1e-14 (~50 ulps) only leaves
        // room for a reordering of its arithmetic.
        assert!((p_phi - p_phi_hand).abs() <= 1e-14 * p_phi_hand.abs().max(1.0));
        assert!((p_psi - p_psi_hand).abs() <= 1e-14 * p_psi_hand.abs().max(1.0));
    }
}

/// `L` of the double pendulum, written again here for finite differences.
fn dp_lagrangian(p: &DoublePendulumParams, q: [f64; 2], w: [f64; 2]) -> f64 {
    let DoublePendulumParams { m1, m2, l1, l2, g } = *p;
    0.5 * (m1 + m2) * l1 * l1 * w[0] * w[0]
        + 0.5 * m2 * l2 * l2 * w[1] * w[1]
        + m2 * l1 * l2 * w[0] * w[1] * (q[0] - q[1]).cos()
        + (m1 + m2) * g * l1 * q[0].cos()
        + m2 * g * l2 * q[1].cos()
}

/// Max over the trajectory of `|d/dt dL/dqdot - dL/dq|`, all derivatives by central
/// differences: in time with spacing `k` samples, in `q` and `qdot` with step `h`.
fn euler_lagrange_residual(
    params: &DoublePendulumParams,
    y: &ndarray::Array2<f64>,
    dt: f64,
    k: usize,
) -> f64 {
    let h = 1e-5;
    let grad = |q: [f64; 2], w: [f64; 2], wrt_velocity: bool, i: usize| {
        let (mut qp, mut qm, mut wp, mut wm) = (q, q, w, w);
        if wrt_velocity {
            wp[i] += h;
            wm[i] -= h;
        } else {
            qp[i] += h;
            qm[i] -= h;
        }
        (dp_lagrangian(params, qp, wp) - dp_lagrangian(params, qm, wm)) / (2.0 * h)
    };
    let row = |j: usize| ([y[[j, 0]], y[[j, 1]]], [y[[j, 2]], y[[j, 3]]]);
    let mut worst = 0.0_f64;
    for j in (k..y.nrows() - k).step_by(k) {
        let (qa, wa) = row(j + k);
        let (qb, wb) = row(j - k);
        let (q, w) = row(j);
        for i in 0..2 {
            let dpdt = (grad(qa, wa, true, i) - grad(qb, wb, true, i)) / (2.0 * k as f64 * dt);
            worst = worst.max((dpdt - grad(q, w, false, i)).abs());
        }
    }
    worst
}

#[test]
fn euler_lagrange_residual_along_a_trajectory_is_at_truncation_level() {
    // An rk4 trajectory at dt = 1e-4 (global error ~1e-12) satisfies the Euler–Lagrange
    // equations; differencing it in time with spacing Delta leaves only the O(Delta^2)
    // truncation of the central difference. Halving Delta must then divide the residual by
    // about 4 (3.5..4.5 allows for the O(Delta^4) term), and the residual must be small: an
    // error in the equations of motion would leave an O(1) residual independent of Delta.
    let params = DoublePendulumParams::default();
    let mut dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], params).unwrap();
    let dt = 1e-4;
    let res = dp.integrate((0.0, 2.0), dt, Method::Rk4).unwrap();
    let coarse = euler_lagrange_residual(&params, &res.y, dt, 20);
    let fine = euler_lagrange_residual(&params, &res.y, dt, 10);
    let ratio = coarse / fine;
    println!("EL residual: coarse {coarse:e} fine {fine:e} ratio {ratio}");
    assert!(
        (3.5..4.5).contains(&ratio),
        "ratio {ratio} ({coarse} / {fine})"
    );
    // At Delta = 1e-3 the truncation term Delta^2/6 |p'''| is ~6e-4 for this whipping
    // pendulum (|p'''| up to ~4e3); the finite-difference noise, eps |L| / (h Delta) ~ 1e-7,
    // is far below it.
    assert!(fine < 1e-3, "{fine}");
}

#[test]
fn canonical_jacobian_matches_finite_differences() {
    // Central differences of the canonical derivatives with step 1e-6 are accurate to
    // ~h^2 |f'''| + eps |f| / h ~ 1e-9 relative; 1e-6 leaves margin and still catches any
    // wrong block (errors would be O(1)).
    let params = SymmetricTopParams::default();
    let top = HeavySymmetricTop::new(&[0.3, 0.7, -0.2], &[1.2, -0.8, 15.0], params).unwrap();
    let engine = top.engine();
    let mut p = [0.0; 3];
    engine
        .momentum(&[0.3, 0.7, -0.2], &[1.2, -0.8, 15.0], 0.0, &mut p)
        .unwrap();
    let state = [0.3, 0.7, -0.2, p[0], p[1], p[2]];
    let mut jac = [0.0; 36];
    engine.canonical_jacobian(0.0, &state, &mut jac).unwrap();
    let h = 1e-6;
    for j in 0..6 {
        let (mut sp, mut sm) = (state, state);
        sp[j] += h;
        sm[j] -= h;
        let (mut fp, mut fm) = ([0.0; 6], [0.0; 6]);
        engine.canonical_derivatives(0.0, &sp, &mut fp).unwrap();
        engine.canonical_derivatives(0.0, &sm, &mut fm).unwrap();
        for i in 0..6 {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            let got = jac[i * 6 + j];
            assert!(
                (got - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                "J[{i}][{j}] = {got} vs {fd}"
            );
        }
    }
}

/// A relativistic particle in a harmonic well, `L = -m c^2 sqrt(1 - v^2/c^2) - k x^2 / 2`:
/// not quadratic in `v`, so the inverse Legendre map needs Newton's method. Exact inverse:
/// `v = p / sqrt(m^2 + p^2 / c^2)`.
struct Relativistic {
    m: f64,
    c: f64,
    k: f64,
}

impl Lagrangian for Relativistic {
    fn ndof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, q: &[D], v: &[D], _t: D) -> D {
        let beta2 = v[0] * v[0] / (self.c * self.c);
        -(-beta2 + 1.0).sqrt() * (self.m * self.c * self.c) - q[0] * q[0] * (0.5 * self.k)
    }
}

#[test]
fn non_quadratic_lagrangian_inverts_the_legendre_map_by_newton() {
    let l = Relativistic {
        m: 1.3,
        c: 2.0,
        k: 0.7,
    };
    let (m, c) = (l.m, l.c);
    let engine = LagrangianEngine::new(l).unwrap();
    for p in [-20.0, -3.0, -0.1, 0.0, 0.5, 4.0, 40.0] {
        let mut v = [0.0];
        engine.velocity(&[0.2], &[p], 0.0, &mut v).unwrap();
        let exact = p / (m * m + p * p / (c * c)).sqrt();
        // Newton stops at a residual of 1e-13 relative (the default tolerance); the mass
        // m gamma^3 >= m maps that to a velocity error below ~1e-13 |v| + 1e-15.
        assert!(
            (v[0] - exact).abs() < 1e-12 * exact.abs().max(1e-3),
            "{p}: {v:?}"
        );
    }
    // Acceleration: d/dt (m gamma v) = -k x  =>  a = -k x / (m gamma^3).
    let (x, v) = (0.4, 1.5);
    let gamma = 1.0 / (1.0 - v * v / (c * c)).sqrt();
    let mut a = [0.0];
    engine.acceleration(&[x], &[v], 0.0, &mut a).unwrap();
    let want = -0.7 * x / (m * gamma.powi(3));
    // Derivatives exact to rounding on both sides, a dozen operations each: 1e-13 relative
    // (~450 ulps) is margin over their rounding, far below any error in the derivation.
    assert!((a[0] - want).abs() < 1e-13 * want.abs());
}

/// Two coordinates that enter only through `q0 + q1`: `M` has rank 1.
struct Degenerate;

impl Lagrangian for Degenerate {
    fn ndof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, q: &[D], v: &[D], _t: D) -> D {
        let s = v[0] + v[1];
        s * s * 0.5 - q[0] * q[0]
    }
}

#[test]
fn singular_mass_matrix_is_an_error() {
    let engine = LagrangianEngine::new(Degenerate).unwrap();
    let mut out = [0.0; 2];
    let err = engine
        .acceleration(&[0.1, 0.2], &[0.3, 0.4], 1.5, &mut out)
        .unwrap_err();
    assert!(
        matches!(err, Error::SingularMatrix { t, .. } if t.to_bits() == 1.5_f64.to_bits()),
        "{err}"
    );
    assert!(matches!(
        engine.velocity(&[0.1, 0.2], &[1.0, 1.0], 0.0, &mut out),
        Err(Error::SingularMatrix { .. })
    ));
    assert!(matches!(
        LagrangianModel::new(Degenerate, &[0.0, 0.0], &[0.0, 0.0]),
        Err(Error::SingularMatrix { .. })
    ));
}

#[test]
fn top_on_its_axis_is_a_singular_mass_matrix() {
    let err = HeavySymmetricTop::new(&[0.0, 0.0, 0.0], &[0.0, 0.0, 10.0], Default::default())
        .unwrap_err();
    assert!(matches!(err, Error::SingularMatrix { .. }), "{err}");
}

#[test]
fn engine_rejects_wrong_lengths_and_zero_ndof() {
    let engine = LagrangianEngine::new(DoublePendulumParams::default()).unwrap();
    let mut out = [0.0; 2];
    assert!(matches!(
        engine.acceleration(&[0.1], &[0.0, 0.0], 0.0, &mut out),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        engine.canonical_derivatives(0.0, &[0.0; 3], &mut [0.0; 4]),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(engine.energy(&[0.0], &[0.0, 0.0], 0.0).is_nan());
    assert!(matches!(
        LagrangianEngine::new(CoupledOscillatorsParams {
            n: 0,
            m: 1.0,
            k: 1.0
        }),
        Err(Error::InvalidParameter { .. })
    ));
}

/// A Lagrangian of `ndof` free particles, `L = |qdot|^2 / 2`, of any size.
struct FreeParticles(usize);

impl Lagrangian for FreeParticles {
    fn ndof(&self) -> usize {
        self.0
    }
    fn lagrangian<D: Scalar>(&self, _q: &[D], v: &[D], _t: D) -> D {
        v.iter().fold(D::zero(), |s, &x| s + x * x) * 0.5
    }
}

/// `ndof = 10^6` needs three `ndof x ndof` work matrices (24 TB); `2^62` overflows `usize` when
/// multiplied out. Both are refused by the constructor, before any evaluation allocates one
/// (which would abort); a size that fits is still accepted.
#[test]
fn engine_refuses_an_ndof_whose_matrices_do_not_fit() {
    for n in [1_000_000_usize, 1 << 62] {
        match LagrangianEngine::new(FreeParticles(n)) {
            Err(Error::TooLarge { name, value, .. }) => {
                assert_eq!(name, "ndof");
                assert_eq!(value, n as u128);
            }
            other => panic!("expected TooLarge for ndof = {n}, got {:?}", other.err()),
        }
    }
    assert!(LagrangianEngine::new(FreeParticles(100)).is_ok());
}

#[test]
fn large_systems_use_the_heap_fallback_and_agree() {
    // A chain longer than MAX_STACK_NDOF: the acceleration must still be -K q / m exactly as
    // the hand-written stiffness matrix gives (tridiagonal 2, -1); integers make both sides
    // exact up to one rounding per term.
    let n = MAX_STACK_NDOF + 4;
    let q: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
    let v = vec![0.0; n];
    // Through `AutoDiff`: the chain's closed-form acceleration would bypass the engine.
    let params = CoupledOscillatorsParams { n, m: 2.0, k: 3.0 };
    let chain = LagrangianEngine::new(AutoDiff(params)).unwrap();
    let mut a = vec![0.0; n];
    chain.acceleration(&q, &v, 0.0, &mut a).unwrap();
    for i in 0..n {
        let left = if i > 0 { q[i - 1] } else { 0.0 };
        let right = if i + 1 < n { q[i + 1] } else { 0.0 };
        let want = 3.0 * (left - 2.0 * q[i] + right) / 2.0;
        assert!((a[i] - want).abs() < 1e-13, "{i}: {} vs {want}", a[i]);
    }
}

/// The double pendulum as an expression, parameters `[m1, m2, l1, l2, g]`.
const DOUBLE_PENDULUM_EXPR: &str = "(+ \
    (* 0.5 (+ param0 param1) (^ param2 2) (^ qdot0 2)) \
    (* 0.5 param1 (^ param3 2) (^ qdot1 2)) \
    (* param1 param2 param3 qdot0 qdot1 (cos (- q0 q1))) \
    (* (+ param0 param1) param4 param2 (cos q0)) \
    (* param1 param4 param3 (cos q1)))";

#[test]
fn expression_double_pendulum_matches_the_native_one() {
    // Same Lagrangian, different evaluation order: agreement to 1e-14 relative (~50 ulps)
    // shows the expression path adds nothing but rounding.
    let expr = Expr::parse(DOUBLE_PENDULUM_EXPR).unwrap();
    let mut rng = Rng(4);
    for _ in 0..100 {
        let (params, q, w) = random_double_pendulum(&mut rng);
        let DoublePendulumParams { m1, m2, l1, l2, g } = params;
        let lag = ExprLagrangian::new(expr.clone(), 2, vec![m1, m2, l1, l2, g]).unwrap();
        let model = LagrangianModel::new(lag, &q, &w).unwrap();
        let native = DoublePendulum::new(&q, &w, params).unwrap();
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        model.acceleration(&q, &w, 0.0, &mut a).unwrap();
        native.acceleration(&q, &w, 0.0, &mut b).unwrap();
        assert!(rel_err(&a, &b) < 1e-14, "{a:?} vs {b:?}");
        let state = [q[0], q[1], w[0], w[1]];
        let (ea, eb) = (model.energy(&state), native.energy(&state));
        assert!((ea - eb).abs() < 1e-14 * ea.abs().max(1.0));
    }
}

#[test]
fn expression_model_integrates_like_the_native_system() {
    let expr = Expr::parse(DOUBLE_PENDULUM_EXPR).unwrap();
    let lag = ExprLagrangian::new(expr, 2, vec![1.0, 1.0, 1.0, 1.0, 9.81]).unwrap();
    let mut model = LagrangianModel::new(lag, &[2.0, 1.0], &[0.5, -0.3]).unwrap();
    let mut native =
        DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], DoublePendulumParams::default()).unwrap();
    let a = model
        .integrate((0.0, 0.5), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let b = native
        .integrate((0.0, 0.5), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    // 500 steps of a chaotic system amplify the ~1e-16 per-step rounding differences; after
    // t = 0.5 (well under one Lyapunov time) they remain below 1e-11.
    let diff = (&a.y - &b.y).iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(diff < 1e-11, "{diff}");
}

#[test]
fn expression_display_round_trips() {
    let expr = Expr::parse(DOUBLE_PENDULUM_EXPR).unwrap();
    let again = Expr::parse(&expr.to_string()).unwrap();
    assert_eq!(expr, again);
    let built = (Expr::qdot(0).powi(2) * Expr::constant(0.1)) - Expr::q(0).cos()
        + (-Expr::T).apply(physicskit::classical::symbolic::Func::Exp)
        + Expr::q(0).powf(1.5)
        + Expr::Pow(Box::new(Expr::q(0)), Box::new(Expr::T))
        + Expr::param(0) / Expr::q(1).sin();
    assert_eq!(built, Expr::parse(&built.to_string()).unwrap());
}

#[test]
fn expression_with_out_of_range_coordinate_is_rejected() {
    let err = ExprLagrangian::new(Expr::parse("(* qdot0 q2)").unwrap(), 2, vec![]).unwrap_err();
    assert!(err.to_string().contains("q2"), "{err}");
}

#[test]
fn expression_with_out_of_range_velocity_is_rejected() {
    let err = ExprLagrangian::new(Expr::parse("(^ qdot3 2)").unwrap(), 2, vec![]).unwrap_err();
    assert!(err.to_string().contains("qdot3"), "{err}");
}

#[test]
fn expression_with_out_of_range_parameter_is_rejected() {
    let err =
        ExprLagrangian::new(Expr::parse("(* param1 qdot0)").unwrap(), 1, vec![1.0]).unwrap_err();
    assert!(err.to_string().contains("param1"), "{err}");
}

#[test]
fn expression_with_zero_ndof_is_rejected() {
    assert!(ExprLagrangian::new(Expr::constant(1.0), 0, vec![]).is_err());
}

#[test]
fn expression_with_non_finite_parameter_or_constant_is_rejected() {
    assert!(ExprLagrangian::new(Expr::param(0), 1, vec![f64::NAN]).is_err());
    assert!(ExprLagrangian::new(Expr::constant(f64::INFINITY), 1, vec![]).is_err());
    assert!(Expr::parse("(+ inf q0)").is_err());
}

#[test]
fn model_with_wrong_initial_length_is_rejected() {
    let lag = ExprLagrangian::new(Expr::parse("(^ qdot0 2)").unwrap(), 1, vec![]).unwrap();
    assert!(matches!(
        LagrangianModel::new(lag, &[0.0, 1.0], &[0.0]),
        Err(Error::DimensionMismatch { .. })
    ));
}

#[test]
fn malformed_expressions_are_rejected_with_a_position() {
    for bad in [
        "(+ q0",
        "(foo q0)",
        "(sin q0 q1)",
        "(- q0 q1 q2)",
        "q0 q1",
        "()",
        "(+ x q0)",
        ")",
        "",
        "(/ q0)",
    ] {
        let err = Expr::parse(bad).unwrap_err();
        assert!(
            matches!(err, Error::InvalidParameter { .. }),
            "{bad}: {err}"
        );
    }
}

#[test]
fn too_deep_expressions_are_rejected() {
    let deep = format!("{}q0{}", "(sin ".repeat(300), ")".repeat(300));
    assert!(Expr::parse(&deep).is_err());
    let mut e = Expr::q(0);
    for _ in 0..300 {
        e = e.sin();
    }
    assert!(ExprLagrangian::new(e, 1, vec![]).is_err());
}

#[test]
#[ignore = "timing probe, run with --release --ignored --nocapture: canonical field per evaluation (closed forms where the system has them)"]
fn engine_cost_per_evaluation() {
    use std::hint::black_box;
    use std::time::Instant;
    let dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], Default::default()).unwrap();
    let top =
        HeavySymmetricTop::new(&[0.0, 0.5, 0.0], &[0.0, 0.0, 20.0], Default::default()).unwrap();
    let n = 1_000_000;
    let mut out4 = [0.0; 4];
    let start = Instant::now();
    for i in 0..n {
        let x = black_box([2.0 + 1e-9 * i as f64, 1.0, 0.8, -0.03]);
        dp.canonical_derivatives(0.0, &x, &mut out4).unwrap();
    }
    let canon = start.elapsed().as_nanos() as f64 / n as f64;
    let start = Instant::now();
    for i in 0..n {
        let q = black_box([2.0 + 1e-9 * i as f64, 1.0]);
        dp.acceleration(&q, &[0.5, -0.3], 0.0, &mut out4[..2])
            .unwrap();
    }
    let accel = start.elapsed().as_nanos() as f64 / n as f64;
    let mut out6 = [0.0; 6];
    let start = Instant::now();
    for i in 0..n {
        let x = black_box([0.0, 0.5 + 1e-9 * i as f64, 0.0, 8.7, 0.0, 10.0]);
        top.canonical_derivatives(0.0, &x, &mut out6).unwrap();
    }
    let top_canon = start.elapsed().as_nanos() as f64 / n as f64;
    println!(
        "double pendulum: canonical_derivatives {canon:.0} ns, acceleration {accel:.0} ns; \
         top: canonical_derivatives {top_canon:.0} ns"
    );
    // Whole implicit-midpoint steps (solver sweeps plus the per-sample velocity and energy).
    let mut dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], Default::default()).unwrap();
    let start = Instant::now();
    let r = dp
        .integrate((0.0, 3.0), 3e-5, Method::ImplicitMidpoint)
        .unwrap();
    let per_step = start.elapsed().as_nanos() as f64 / 1e5;
    println!(
        "double pendulum implicit_midpoint: {per_step:.0} ns/step, {:.2} evaluations/step",
        r.extra_scalar("solver_evaluations_mean").unwrap()
    );
}
