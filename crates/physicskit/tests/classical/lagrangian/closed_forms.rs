//! The built-in Lagrangian systems' hand-derived closed forms against automatic
//! differentiation of the same `L`.
//!
//! `LagrangianEngine::new(params)` uses the closed forms each system's `Lagrangian` impl
//! supplies; `LagrangianEngine::new(AutoDiff(params))` hides them, so every quantity is derived
//! from `L` by the dual-number engine instead: an independent computation of the same
//! function. They must agree to rounding at random states (proptest), call the same mass
//! matrices singular, and integrate to the same trajectories.
//!
//! Tolerances are in units of `EPS` (one ulp of 1) times the magnitude of the terms each
//! quantity is built from, not of the result (which can cancel):
//!
//! - `mnorm = |M|_inf`, `vnorm = |v|_inf`, `minv = |M^-1|_inf` (from the AD velocity of unit
//!   momenta: `v(q, e_j) = M^-1 e_j`, since no built-in `L` has a term linear in `v`) and
//!   `kappa = mnorm minv`;
//! - `fscale = 4 mnorm vnorm^2 + dV`, a bound on the terms of `dL/dq` (the mass matrix's
//!   `q`-derivative terms are at most twice its entries, times `|v|^2`, for these systems;
//!   `dV` is each system's bound on the potential's gradient terms);
//! - `escale = mnorm vnorm^2 + V`, the terms of the energy (`V` the potential's).
//!
//! Each side rounds at most ~20 operations on terms of that magnitude (half an ulp each) and
//! evaluates `sin`/`cos` within 2 ulps (libm for the engine, `trig::sin_cos` for the closed
//! forms), so agreement within `ULPS = 64` ulps of the scale leaves a margin of ~3 over the
//! worst case (measured: every case of every system below 6 ulps), while any wrong term is
//! `O(1)` of the scale (~10^15 ulps; a 1e-13 relative error in the hoop's force, ~450 ulps,
//! fails). Solves with `M`
//! amplify by the condition number: perturbations `dM ~ eps |M|`, `df ~ eps fscale` move
//! `a = M^-1 f` by at most `eps minv (fscale + mnorm |a|) <= eps minv fscale (1 + kappa)`.

use physicskit::classical::lagrangian::{AutoDiff, Lagrangian, LagrangianEngine, LagrangianModel};
use physicskit::classical::systems::{
    BeadOnRotatingHoop, CoupledOscillators, CoupledOscillatorsParams, DoublePendulum,
    DoublePendulumParams, ElasticPendulum, ElasticPendulumParams, HeavySymmetricTop, HoopParams,
    SymmetricTopParams,
};
use physicskit::classical::{Error, LagrangianSystem, Method};
use proptest::prelude::*;

const EPS: f64 = f64::EPSILON;

/// Rounding budget in ulps of each quantity's term scale (see the module documentation).
const ULPS: f64 = 64.0;

fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Max row sum of the row-major `n x n` matrix `m`.
fn matrix_norm(m: &[f64], n: usize) -> f64 {
    m.chunks(n)
        .map(|row| row.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// `|a - b| <= ULPS eps scale`, as a proptest failure naming the quantity and the ulps used.
fn check(what: &str, a: &[f64], b: &[f64], scale: f64) -> Result<(), TestCaseError> {
    let diff = max_diff(a, b);
    // 0/0 where both sides are exactly zero (e.g. the momentum at rest) is agreement.
    let ulps = if diff == 0.0 {
        0.0
    } else {
        diff / (EPS * scale)
    };
    prop_assert!(
        ulps <= ULPS,
        "{what}: closed {a:?} vs AD {b:?}: {ulps:.1} ulps of the scale {scale:e}"
    );
    Ok(())
}

/// Every closed form of `l` against automatic differentiation at `(q, v)`, `t = 0`. `dv` and
/// `potential` bound the potential's gradient and value terms.
fn compare<L: Lagrangian + Clone>(
    l: &L,
    q: &[f64],
    v: &[f64],
    dv: f64,
    potential: f64,
) -> Result<(), TestCaseError> {
    let n = l.ndof();
    let closed = LagrangianEngine::new(l.clone()).unwrap();
    let auto = LagrangianEngine::new(AutoDiff(l.clone())).unwrap();

    let (mut mc, mut ma) = (vec![0.0; n * n], vec![0.0; n * n]);
    closed.mass_matrix(q, v, 0.0, &mut mc).unwrap();
    auto.mass_matrix(q, v, 0.0, &mut ma).unwrap();
    let mnorm = matrix_norm(&ma, n);
    check("mass matrix", &mc, &ma, mnorm)?;

    // Columns of M^-1 from the AD inverse Legendre map.
    let mut minv = vec![0.0; n * n];
    let (mut unit, mut col) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..n {
        unit.fill(0.0);
        unit[j] = 1.0;
        auto.velocity(q, &unit, 0.0, &mut col).unwrap();
        for i in 0..n {
            minv[i * n + j] = col[i];
        }
    }
    let minv = matrix_norm(&minv, n);
    let kappa = mnorm * minv;
    let vnorm = inf_norm(v);
    let fscale = 4.0 * mnorm * vnorm * vnorm + dv;

    let (mut pc, mut pa) = (vec![0.0; n], vec![0.0; n]);
    closed.momentum(q, v, 0.0, &mut pc).unwrap();
    auto.momentum(q, v, 0.0, &mut pa).unwrap();
    check("momentum", &pc, &pa, mnorm * vnorm)?;

    let (mut fc, mut fa) = (vec![0.0; n], vec![0.0; n]);
    closed.generalized_force(q, v, 0.0, &mut fc).unwrap();
    auto.generalized_force(q, v, 0.0, &mut fa).unwrap();
    check("dL/dq", &fc, &fa, fscale)?;

    let (ec, ea) = (closed.energy(q, v, 0.0), auto.energy(q, v, 0.0));
    check("energy", &[ec], &[ea], mnorm * vnorm * vnorm + potential)?;

    let (mut ac, mut aa) = (vec![0.0; n], vec![0.0; n]);
    closed.acceleration(q, v, 0.0, &mut ac).unwrap();
    auto.acceleration(q, v, 0.0, &mut aa).unwrap();
    check("acceleration", &ac, &aa, minv * fscale * (1.0 + kappa))?;

    // Inverse Legendre map at p = M v (the AD momentum): |p| <= mnorm vnorm, |v| = vnorm.
    let vscale = minv * mnorm * vnorm + kappa * vnorm;
    let (mut vc, mut va) = (vec![0.0; n], vec![0.0; n]);
    closed.velocity(q, &pa, 0.0, &mut vc).unwrap();
    auto.velocity(q, &pa, 0.0, &mut va).unwrap();
    check("velocity", &vc, &va, vscale)?;

    // Canonical field: dq/dt is the velocity; dp/dt = dL/dq at it, which moves by at most
    // |d(dL/dq)/dv| |dv| <= 4 mnorm vnorm ULPS eps vscale from the velocity's rounding.
    let state: Vec<f64> = q.iter().chain(&pa).copied().collect();
    let (mut cc, mut ca) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    closed.canonical_derivatives(0.0, &state, &mut cc).unwrap();
    auto.canonical_derivatives(0.0, &state, &mut ca).unwrap();
    check("canonical dq/dt", &cc[..n], &ca[..n], vscale)?;
    check(
        "canonical dp/dt",
        &cc[n..],
        &ca[n..],
        fscale + 4.0 * mnorm * vnorm * ULPS * vscale,
    )?;
    Ok(())
}

/// Angles beyond `2 pi` exercise the range reduction of the closed forms' `sin_cos`.
fn angle() -> impl Strategy<Value = f64> {
    -20.0..20.0_f64
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn double_pendulum_closed_forms_match_automatic_differentiation(
        m1 in 0.05..3.0_f64, m2 in 0.05..3.0_f64, l1 in 0.2..3.0_f64, l2 in 0.2..3.0_f64,
        g in -20.0..20.0_f64,
        q in [angle(), angle()], v in [-8.0..8.0_f64, -8.0..8.0],
    ) {
        let params = DoublePendulumParams { m1, m2, l1, l2, g };
        let (g1, g2) = ((m1 + m2) * g.abs() * l1, m2 * g.abs() * l2);
        compare(&params, &q, &v, g1 + g2, g1 + g2)?;
    }

    #[test]
    fn hoop_closed_forms_match_automatic_differentiation(
        r in 0.1..5.0_f64, omega in -10.0..10.0_f64, g in -20.0..20.0_f64,
        q in angle(), v in -10.0..10.0_f64,
    ) {
        let params = HoopParams { r, omega, g };
        let terms = r * r * omega * omega + 2.0 * g.abs() * r;
        compare(&params, &[q], &[v], terms, terms)?;
    }

    #[test]
    fn elastic_pendulum_closed_forms_match_automatic_differentiation(
        m in 0.1..5.0_f64, k in 0.5..200.0_f64, l0 in 0.0..3.0_f64, g in -20.0..20.0_f64,
        // Lengths r = l0 + s in [0.2, 5] keep kappa = max(1, r^2) / min(1, r^2) <= 625; the
        // stretch s = r - l0 is the coordinate (negative: a compressed spring).
        r in 0.2..5.0_f64, theta in angle(), v in [-10.0..10.0_f64, -10.0..10.0],
    ) {
        let params = ElasticPendulumParams { m, k, l0, g };
        // dL/dq: m |g| (cos and r sin terms, r <= 5) and the spring k |s|; the mass matrix's
        // s-derivative term m r theta'^2 is within 4 mnorm vnorm^2. V: m |g| r and k s^2 / 2.
        let stretch = r - l0;
        let dv = m * g.abs() * (1.0 + r) + k * stretch.abs();
        let potential = m * g.abs() * r + 0.5 * k * stretch * stretch;
        compare(&params, &[stretch, theta], &v, dv, potential)?;
    }

    #[test]
    fn coupled_oscillator_closed_forms_match_automatic_differentiation(
        // Up to 8 masses: both the engine's fixed-size (n <= 3) and general kernels.
        n in 1..=8_usize, m in 0.1..5.0_f64, k in 0.1..5.0_f64,
        state in proptest::collection::vec(-3.0..3.0_f64, 16),
    ) {
        let params = CoupledOscillatorsParams { n, m, k };
        let (q, v) = (&state[..n], &state[8..8 + n]);
        let qnorm = inf_norm(q);
        // dL/dq_i = k (q_{i-1} - 2 q_i + q_{i+1}): terms up to 4 k |q|; V: n + 1 stretches
        // (k/2)(q_{i+1} - q_i)^2 <= 2 k |q|^2 each.
        compare(&params, q, v, 4.0 * k * qnorm, 2.0 * (n as f64 + 1.0) * k * qnorm * qnorm)?;
    }

    #[test]
    fn symmetric_top_closed_forms_match_automatic_differentiation(
        i1 in 0.2..3.0_f64, i3 in 0.1..3.0_f64, m in 0.2..3.0_f64, l in -2.0..2.0_f64,
        g in -20.0..20.0_f64,
        // |sin theta| >= 0.05 keeps kappa below ~1e4; the singular set is tested separately.
        phi in angle(), theta in 0.05..3.09_f64, flip in any::<bool>(), psi in angle(),
        v in [-5.0..5.0_f64, -5.0..5.0, -40.0..40.0],
    ) {
        let params = SymmetricTopParams { i1, i3, m, l, g };
        let theta = if flip { -theta } else { theta };
        let mgl = params.mgl().abs();
        compare(&params, &[phi, theta, psi], &v, mgl, mgl)?;
    }
}

#[test]
fn every_built_in_system_supplies_every_closed_form() {
    // The speed of the built-in systems rests on these: a closed form that silently fell back
    // to automatic differentiation would still pass the comparisons above.
    fn all_supplied<L: Lagrangian>(l: &L, q: &[f64], v: &[f64]) -> bool {
        let n = l.ndof();
        let (mut a, mut b, mut m) = (vec![0.0; n], vec![0.0; n], vec![0.0; n * n]);
        l.closed_mass_matrix(q, v, 0.0, &mut m).is_some()
            && l.closed_momentum(q, v, 0.0, &mut a).is_some()
            && l.closed_generalized_force(q, v, 0.0, &mut a).is_some()
            && l.closed_energy(q, v, 0.0).is_some()
            && matches!(l.closed_acceleration(q, v, 0.0, &mut a), Some(Ok(())))
            && matches!(l.closed_velocity(q, v, 0.0, &mut a), Some(Ok(())))
            && matches!(l.closed_canonical(q, v, 0.0, &mut a, &mut b), Some(Ok(())))
    }
    assert!(all_supplied(
        &DoublePendulumParams::default(),
        &[2.0, 1.0],
        &[0.5, -0.3]
    ));
    assert!(all_supplied(&HoopParams::default(), &[0.3], &[0.1]));
    assert!(all_supplied(
        &ElasticPendulumParams::default(),
        &[1.2, 0.4],
        &[0.3, -0.2]
    ));
    assert!(all_supplied(
        &CoupledOscillatorsParams::default(),
        &[0.1, -0.2, 0.15],
        &[0.0; 3]
    ));
    assert!(all_supplied(
        &SymmetricTopParams::default(),
        &[0.0, 0.5, 0.0],
        &[0.0, 0.0, 20.0]
    ));
    // ... and AutoDiff hides every one of them.
    let hidden = AutoDiff(DoublePendulumParams::default());
    let mut out = [0.0; 2];
    assert!(hidden
        .closed_acceleration(&[2.0, 1.0], &[0.5, -0.3], 0.0, &mut out)
        .is_none());
    assert!(hidden
        .closed_energy(&[2.0, 1.0], &[0.5, -0.3], 0.0)
        .is_none());
}

/// Whether the closed-form and AD engines of `l` both call the mass matrix singular at `q`
/// (velocity, acceleration and canonical field alike); panics if they disagree.
fn singular_in_both<L: Lagrangian + Clone>(l: &L, q: &[f64]) -> bool {
    let n = l.ndof();
    let closed = LagrangianEngine::new(l.clone()).unwrap();
    let auto = LagrangianEngine::new(AutoDiff(l.clone())).unwrap();
    let v = vec![0.5; n];
    let state: Vec<f64> = q.iter().chain(&v).copied().collect();
    let (mut a, mut b) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    let is_singular = |r: physicskit::classical::Result<()>| match r {
        Ok(()) => false,
        Err(Error::SingularMatrix { .. }) => true,
        Err(e) => panic!("unexpected error {e}"),
    };
    let verdicts = [
        is_singular(closed.velocity(q, &v, 0.0, &mut a[..n])),
        is_singular(auto.velocity(q, &v, 0.0, &mut b[..n])),
        is_singular(closed.acceleration(q, &v, 0.0, &mut a[..n])),
        is_singular(auto.acceleration(q, &v, 0.0, &mut b[..n])),
        is_singular(closed.canonical_derivatives(0.0, &state, &mut a)),
        is_singular(auto.canonical_derivatives(0.0, &state, &mut b)),
    ];
    assert!(
        verdicts.iter().all(|&s| s == verdicts[0]),
        "closed and AD disagree at {q:?}: {verdicts:?}"
    );
    verdicts[0]
}

#[test]
fn closed_forms_call_the_same_mass_matrices_singular() {
    // The top's pivot I1 sin^2(theta) against the largest entry, ~1: exactly singular at
    // theta = 0, negligible (1e-18 < 1e-14) at 1e-9, regular at 1e-3 (1e-6) and 0.5.
    let top = SymmetricTopParams::default();
    for (theta, singular) in [(0.0, true), (1e-9, true), (1e-3, false), (0.5, false)] {
        assert_eq!(
            singular_in_both(&top, &[0.2, theta, 0.1]),
            singular,
            "{theta}"
        );
    }
    assert!(singular_in_both(&top, &[0.2, std::f64::consts::PI, 0.1]));
    // Unvalidated parameters reach the engine directly. A massless upper bob: det M =
    // m2^2 l1^2 l2^2 sin^2(theta1 - theta2), singular where the rods align.
    let dp = DoublePendulumParams {
        m1: 0.0,
        ..Default::default()
    };
    assert!(singular_in_both(&dp, &[0.7, 0.7]));
    assert!(!singular_in_both(&dp, &[0.7, -0.3]));
    let hoop = HoopParams {
        r: 0.0,
        ..Default::default()
    };
    assert!(singular_in_both(&hoop, &[0.3]));
    // The elastic pendulum's m r^2 against m at the length r = L0 + s (L0 = 1: the stretch
    // s = r - 1 and the length 1 + s each round by at most 1.1e-16, far below these r):
    // singular at r = 0 and 1e-8 (1e-16 < 1e-14), regular at 1e-6 (1e-12). (At r < 0 the
    // closed forms refuse a state outside the chart that automatic differentiation, seeing
    // m r^2 > 0, would accept: not compared here, tested in tests/elastic_pendulum.rs.)
    let spring = ElasticPendulumParams::default();
    for (r, singular) in [(0.0, true), (1e-8, true), (1e-6, false), (1.0, false)] {
        assert_eq!(singular_in_both(&spring, &[r - 1.0, 0.4]), singular, "{r}");
    }
    let chain = CoupledOscillatorsParams {
        n: 2,
        m: 0.0,
        k: 1.0,
    };
    assert!(singular_in_both(&chain, &[0.1, 0.2]));
}

/// Max abs difference between two runs' stored states and energies.
fn run_difference(
    a: &physicskit::classical::SimulationResult,
    b: &physicskit::classical::SimulationResult,
) -> f64 {
    let dy = (&a.y - &b.y).iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let de = max_diff(
        a.energy.as_ref().unwrap().as_slice().unwrap(),
        b.energy.as_ref().unwrap().as_slice().unwrap(),
    );
    dy.max(de)
}

#[test]
fn closed_form_systems_integrate_like_automatic_differentiation() {
    // The same integrator on the same L, one evaluating closed forms, the other dual numbers:
    // per-step differences of a few ulps of the state (~1e-15) add up over 1e4 steps to
    // ~1e-12 at most for these non-chaotic runs (linear error growth: 1e4 * 1e-16 * |y|,
    // |y| <= 20 for the top's spin), so 1e-11 bounds it with margin; a wrong closed form
    // would differ at O(dt) = 1e-4 after the first step.
    let steps = 10_000.0;
    for method in [Method::ImplicitMidpoint, Method::Rk4] {
        let dt = 5e-5;
        let mut top =
            HeavySymmetricTop::new(&[0.0, 0.5, 0.0], &[0.0, 0.0, 20.0], Default::default())
                .unwrap();
        let mut model = LagrangianModel::new(
            AutoDiff(SymmetricTopParams::default()),
            &[0.0, 0.5, 0.0],
            &[0.0, 0.0, 20.0],
        )
        .unwrap();
        let a = top.integrate((0.0, steps * dt), dt, method).unwrap();
        let b = model.integrate((0.0, steps * dt), dt, method).unwrap();
        let d = run_difference(&a, &b);
        assert!(d < 1e-11, "top {method}: {d:e}");

        let params = HoopParams {
            omega: 3.0,
            ..Default::default()
        };
        let dt = 2.2e-5;
        let mut hoop = BeadOnRotatingHoop::new(0.3, 0.0, params).unwrap();
        let mut model = LagrangianModel::new(AutoDiff(params), &[0.3], &[0.0]).unwrap();
        let a = hoop.integrate((0.0, steps * dt), dt, method).unwrap();
        let b = model.integrate((0.0, steps * dt), dt, method).unwrap();
        let d = run_difference(&a, &b);
        assert!(d < 1e-11, "hoop {method}: {d:e}");

        let dt = 1e-4;
        let (q0, v0) = ([0.1, -0.2, 0.15], [0.0; 3]);
        let mut chain = CoupledOscillators::new(&q0, &v0, Default::default()).unwrap();
        let mut model =
            LagrangianModel::new(AutoDiff(CoupledOscillatorsParams::default()), &q0, &v0).unwrap();
        let a = chain.integrate((0.0, steps * dt), dt, method).unwrap();
        let b = model.integrate((0.0, steps * dt), dt, method).unwrap();
        let d = run_difference(&a, &b);
        assert!(d < 1e-11, "chain {method}: {d:e}");

        let dt = 1e-4;
        let (q0, v0) = ([0.4, 0.7], [0.3, -0.4]);
        let params = ElasticPendulumParams::default();
        let mut bob = ElasticPendulum::new(&q0, &v0, params).unwrap();
        let mut model = LagrangianModel::new(AutoDiff(params), &q0, &v0).unwrap();
        let a = bob.integrate((0.0, steps * dt), dt, method).unwrap();
        let b = model.integrate((0.0, steps * dt), dt, method).unwrap();
        let d = run_difference(&a, &b);
        assert!(d < 1e-11, "elastic pendulum {method}: {d:e}");
    }
}

#[test]
fn closed_form_double_pendulum_integrates_like_automatic_differentiation() {
    // The Python suite's comparison of the built-in pendulum with a SymPy Lagrangian (AD):
    // 1e4 steps of 3e-5 (t = 0.3, under a Lyapunov time, so rounding differences grow at
    // most ~10x) must agree to 1e-12 in every stored state and energy, with m2 = 1.5,
    // l2 = 0.8, for both methods.
    let params = DoublePendulumParams {
        m2: 1.5,
        l2: 0.8,
        ..Default::default()
    };
    let (q0, w0) = ([2.0, 1.0], [0.5, -0.3]);
    for method in [Method::ImplicitMidpoint, Method::Rk4] {
        let mut dp = DoublePendulum::new(&q0, &w0, params).unwrap();
        let mut model = LagrangianModel::new(AutoDiff(params), &q0, &w0).unwrap();
        let a = dp.integrate((0.0, 0.3), 3e-5, method).unwrap();
        let b = model.integrate((0.0, 0.3), 3e-5, method).unwrap();
        let d = run_difference(&a, &b);
        println!("double pendulum {method}: closed vs AD {d:e}");
        assert!(d < 1e-12, "{method}: {d:e}");
    }
}
