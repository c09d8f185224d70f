//! Jacobians of the built-in Lagrangian systems by forward-mode automatic differentiation of
//! their generic closed forms (`lagrangian/forward.rs`), checked against three independent
//! computations: central differences of the `f64` fields (at their documented accuracy), the
//! second derivatives of `L` (the `AutoDiff` engine, which never sees the closed forms), and
//! linearizations derived by hand.

// The structural zeros and ones of the Jacobians are exact: exact comparisons are intended.
#![allow(clippy::float_cmp)]

use physicskit::classical::integrators::tangent::central_difference;
use physicskit::classical::lagrangian::{AutoDiff, LagrangianEngine, LagrangianModel};
use physicskit::classical::systems::{
    BeadOnRotatingHoop, CoupledOscillators, CoupledOscillatorsParams, DoublePendulum,
    DoublePendulumParams, ElasticPendulum, ElasticPendulumParams, HeavySymmetricTop, HoopParams,
    SymmetricTopParams,
};
use physicskit::classical::{DynamicalSystem, Error, LagrangianSystem, Result};

const EPS: f64 = f64::EPSILON;

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

fn hoop_params() -> HoopParams {
    HoopParams {
        r: 1.5,
        omega: 3.1,
        g: 9.81,
    }
}

fn pendulum_params() -> DoublePendulumParams {
    DoublePendulumParams {
        m1: 1.3,
        m2: 0.7,
        l1: 1.1,
        l2: 0.8,
        g: 9.81,
    }
}

/// A Jacobian `(t, state, out)`.
type JacobianFn = dyn Fn(f64, &[f64], &mut [f64]) -> Result<()>;

/// A Jacobian that a system may not supply.
type OptionalJacobianFn = dyn Fn(f64, &[f64], &mut [f64]) -> Option<Result<()>>;

/// Each built-in Lagrangian system at a few states `[q, qdot]` away from any symmetry (so no
/// derivative vanishes by accident), with its engine on `AutoDiff` (the same `L`, no closed
/// forms).
struct Case {
    name: &'static str,
    system: Box<dyn LagrangianSystem>,
    autodiff: Box<JacobianFn>,
    /// The engine's `closed_canonical_jacobian` (automatic differentiation of the closed form).
    closed: Box<OptionalJacobianFn>,
    states: Vec<Vec<f64>>,
}

fn cases() -> Vec<Case> {
    let hoop = hoop_params();
    let dp = pendulum_params();
    let ep = ElasticPendulumParams::default();
    let top = SymmetricTopParams::default();
    let hoop_ad = LagrangianEngine::new(AutoDiff(hoop)).unwrap();
    let dp_ad = LagrangianEngine::new(AutoDiff(dp)).unwrap();
    let ep_ad = LagrangianEngine::new(AutoDiff(ep)).unwrap();
    let top_ad = LagrangianEngine::new(AutoDiff(top)).unwrap();
    let hoop_cf = LagrangianEngine::new(hoop).unwrap();
    let dp_cf = LagrangianEngine::new(dp).unwrap();
    let ep_cf = LagrangianEngine::new(ep).unwrap();
    let top_cf = LagrangianEngine::new(top).unwrap();
    vec![
        Case {
            name: "hoop",
            system: Box::new(BeadOnRotatingHoop::new(0.3, 0.0, hoop).unwrap()),
            autodiff: Box::new(move |t, s, o| hoop_ad.canonical_jacobian(t, s, o)),
            closed: Box::new(move |t, s, o| hoop_cf.closed_canonical_jacobian(t, s, o)),
            states: vec![vec![0.3, 0.5], vec![2.0, -1.7], vec![-1.1, 3.0]],
        },
        Case {
            name: "double pendulum",
            system: Box::new(DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], dp).unwrap()),
            autodiff: Box::new(move |t, s, o| dp_ad.canonical_jacobian(t, s, o)),
            closed: Box::new(move |t, s, o| dp_cf.closed_canonical_jacobian(t, s, o)),
            states: vec![
                vec![2.0, 1.0, 0.5, -0.3],
                vec![0.1, -0.4, 2.5, 1.0],
                vec![-2.9, 1.2, -0.7, 4.0],
            ],
        },
        Case {
            name: "elastic pendulum",
            system: Box::new(ElasticPendulum::new(&[0.3, 0.8], &[0.2, -0.5], ep).unwrap()),
            autodiff: Box::new(move |t, s, o| ep_ad.canonical_jacobian(t, s, o)),
            closed: Box::new(move |t, s, o| ep_cf.closed_canonical_jacobian(t, s, o)),
            // Stretched, compressed (length 0.6 of L0 = 1) and stretched far.
            states: vec![
                vec![0.3, 0.8, 0.2, -0.5],
                vec![-0.4, -2.0, -1.5, 2.0],
                vec![1.2, 0.1, 0.9, 0.3],
            ],
        },
        Case {
            name: "heavy top",
            system: Box::new(
                HeavySymmetricTop::new(&[0.2, 0.9, 0.1], &[0.3, 0.4, 5.0], top).unwrap(),
            ),
            autodiff: Box::new(move |t, s, o| top_ad.canonical_jacobian(t, s, o)),
            closed: Box::new(move |t, s, o| top_cf.closed_canonical_jacobian(t, s, o)),
            states: vec![
                vec![0.2, 0.9, 0.1, 0.3, 0.4, 5.0],
                vec![-1.0, 2.1, 0.7, -1.2, 0.8, -3.0],
                vec![0.5, 0.4, -2.0, 2.0, -0.6, 1.0],
            ],
        },
    ]
}

/// The canonical state `[q, p]` of `[q, qdot]`.
fn canonical(system: &dyn LagrangianSystem, state: &[f64]) -> Vec<f64> {
    let n = system.ndof();
    let mut y = state.to_vec();
    system
        .momentum(&state[..n], &state[n..], 0.0, &mut y[n..])
        .unwrap();
    y
}

/// Central differences of `field` at `x` (the tangent dynamics' fallback), and the field's
/// own magnitude there.
fn finite_differences(
    field: impl Fn(&[f64], &mut [f64]) -> Result<()>,
    x: &[f64],
) -> (Vec<f64>, f64) {
    let m = x.len();
    let (mut xp, mut fp, mut fm, mut jac) =
        (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m * m]);
    central_difference(&field, x, &mut xp, &mut fp, &mut fm, &mut jac).unwrap();
    let mut f = vec![0.0; m];
    field(x, &mut f).unwrap();
    (jac, max_abs(&f))
}

/// Central differences are accurate to about `ε^(2/3) ≈ 4e-11` relative to the field and its
/// third derivatives (`integrators/tangent.rs`): `1e-8` of the larger of the field and the
/// Jacobian leaves a margin of ~20 over the largest error measured here (4.5e-10, the heavy
/// top's canonical form; printed), while a wrong or missing term is `O(1)` of the Jacobian.
const FD_TOLERANCE: f64 = 1e-8;

/// Both forms' automatic-differentiation Jacobians against central differences of the field
/// the integrators step.
#[test]
fn ad_jacobians_match_central_differences() {
    for case in cases() {
        let s = case.system.as_ref();
        let dim = 2 * s.ndof();
        for state in &case.states {
            let mut ad = vec![0.0; dim * dim];
            s.jacobian(0.0, state, &mut ad).unwrap().unwrap();
            let (fd, scale) = finite_differences(|x, o| s.derivatives(0.0, x, o), state);
            let err = max_diff(&ad, &fd) / scale.max(max_abs(&ad)).max(1.0);
            println!(
                "{} [q, qdot] {state:?}: relative error {err:.1e}",
                case.name
            );
            assert!(
                err < FD_TOLERANCE,
                "{} [q, qdot] at {state:?}: {err:e}",
                case.name
            );

            let y = canonical(s, state);
            s.canonical_jacobian(0.0, &y, &mut ad).unwrap().unwrap();
            let (fd, scale) = finite_differences(|x, o| s.canonical_derivatives(0.0, x, o), &y);
            let err = max_diff(&ad, &fd) / scale.max(max_abs(&ad)).max(1.0);
            println!("{} [q, p] {y:?}: relative error {err:.1e}", case.name);
            assert!(err < FD_TOLERANCE, "{} [q, p] at {y:?}: {err:e}", case.name);
        }
    }
}

/// The canonical Jacobian differentiated from the closed-form field
/// (`closed_canonical_jacobian`) against the one the `AutoDiff` engine assembles from the second derivatives of `L` (hyper-dual numbers and
/// implicit differentiation of the Legendre map: a different formula, the same function).
/// Both are exact up to rounding: a few hundred operations, amplified by the mass matrix's
/// condition number (up to ~30 at these states), stay below `1e-12` of the largest entry
/// (measured: at most 9.4e-16, printed); a wrong term would be `O(1)`.
#[test]
fn canonical_jacobian_matches_second_derivatives_of_l() {
    for case in cases() {
        let s = case.system.as_ref();
        let dim = 2 * s.ndof();
        for state in &case.states {
            let y = canonical(s, state);
            let (mut closed, mut from_l) = (vec![0.0; dim * dim], vec![0.0; dim * dim]);
            (case.closed)(0.0, &y, &mut closed).unwrap().unwrap();
            (case.autodiff)(0.0, &y, &mut from_l).unwrap();
            let err = max_diff(&closed, &from_l) / max_abs(&from_l).max(1.0);
            println!("{} at {y:?}: relative difference {err:.1e}", case.name);
            assert!(err < 1e-12, "{} at {y:?}: {err:e}", case.name);
        }
    }
}

/// The hoop by hand. `theta'' = (omega^2 cos theta - g/R) sin theta`, so
/// `d theta''/d theta = omega^2 cos 2 theta - (g/R) cos theta`; canonically
/// `theta' = p / R^2` and `p' = (R^2 omega^2 cos theta - g R) sin theta`, whose derivative is
/// `R^2 omega^2 cos 2 theta - g R cos theta`. The two sides round a handful of operations on
/// terms up to `omega^2 + g/R` (times `R^2` canonically), and libm's `cos` against the crate's
/// kernel differ by an ulp: 16 ulps of that scale.
#[test]
fn hoop_jacobian_is_the_hand_derived_one() {
    let params = hoop_params();
    let HoopParams { r, omega, g } = params;
    let hoop = BeadOnRotatingHoop::new(0.0, 0.0, params).unwrap();
    for theta in [0.0, 0.3, 1.0, 2.0, -2.7] {
        for w in [0.0, 1.5] {
            let mut jac = [0.0; 4];
            hoop.jacobian(0.0, &[theta, w], &mut jac).unwrap().unwrap();
            let stiffness = omega * omega * (2.0 * theta).cos() - g / r * theta.cos();
            let tol = 16.0 * EPS * (omega * omega + g / r);
            assert_eq!([jac[0], jac[1], jac[3]], [0.0, 1.0, 0.0]);
            assert!(
                (jac[2] - stiffness).abs() < tol,
                "theta {theta}: {} vs {stiffness}",
                jac[2]
            );

            let p = r * r * w;
            hoop.canonical_jacobian(0.0, &[theta, p], &mut jac)
                .unwrap()
                .unwrap();
            let force_slope = r * r * omega * omega * (2.0 * theta).cos() - g * r * theta.cos();
            assert_eq!([jac[0], jac[3]], [0.0, 0.0]);
            assert!((jac[1] - 1.0 / (r * r)).abs() <= EPS / (r * r));
            assert!(
                (jac[2] - force_slope).abs() < tol * r * r,
                "theta {theta}: {} vs {force_slope}",
                jac[2]
            );
        }
    }
}

/// The double pendulum hanging at rest, by hand: linearized, `L` has the constant mass
/// matrix `M = [[a, b], [b, d]]` and the potential `(g1 theta1^2 + g2 theta2^2) / 2`
/// (module docs of `systems/double_pendulum.rs`; Goldstein §6.4), so `M qddot = -K q` with
/// `K = diag(g1, g2)`: the first-order Jacobian is `[[0, I], [-M^-1 K, 0]]` and the canonical
/// one `[[0, M^-1], [-K, 0]]` (velocity-dependent terms vanish at rest). At `theta = 0` the
/// sines are exactly 0 and the cosines 1, so both sides are a few roundings of the same
/// products: 4 ulps of each entry's scale.
#[test]
fn double_pendulum_linearization_at_rest_is_the_textbook_one() {
    let params = pendulum_params();
    let DoublePendulumParams { m1, m2, l1, l2, g } = params;
    let (a, b, d) = ((m1 + m2) * l1 * l1, m2 * l1 * l2, m2 * l2 * l2);
    let (g1, g2) = ((m1 + m2) * g * l1, m2 * g * l2);
    let det = a * d - b * b;
    let m_inv = [d / det, -b / det, -b / det, a / det];
    let dp = DoublePendulum::new(&[0.0, 0.0], &[0.0, 0.0], params).unwrap();
    let close = |x: f64, y: f64| (x - y).abs() <= 4.0 * EPS * y.abs().max(EPS);

    let mut jac = [0.0; 16];
    dp.jacobian(0.0, &[0.0; 4], &mut jac).unwrap().unwrap();
    let stiffness = [
        -m_inv[0] * g1,
        -m_inv[1] * g2,
        -m_inv[2] * g1,
        -m_inv[3] * g2,
    ];
    let expected = [
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
        [stiffness[0], stiffness[1], 0.0, 0.0],
        [stiffness[2], stiffness[3], 0.0, 0.0],
    ];
    for (i, row) in expected.iter().enumerate() {
        for (j, &e) in row.iter().enumerate() {
            assert!(
                close(jac[4 * i + j], e),
                "[q, qdot] ({i}, {j}): {} vs {e}",
                jac[4 * i + j]
            );
        }
    }

    dp.canonical_jacobian(0.0, &[0.0; 4], &mut jac)
        .unwrap()
        .unwrap();
    let expected = [
        [0.0, 0.0, m_inv[0], m_inv[1]],
        [0.0, 0.0, m_inv[2], m_inv[3]],
        [-g1, 0.0, 0.0, 0.0],
        [0.0, -g2, 0.0, 0.0],
    ];
    for (i, row) in expected.iter().enumerate() {
        for (j, &e) in row.iter().enumerate() {
            assert!(
                close(jac[4 * i + j], e),
                "[q, p] ({i}, {j}): {} vs {e}",
                jac[4 * i + j]
            );
        }
    }
}

/// A Lagrangian without generic closed forms has no first-order Jacobian (its tangent
/// dynamics take central differences) but keeps the canonical one from `L`; the coupled
/// oscillators' `ndof` is not fixed, so they are in that case too.
#[test]
fn systems_without_generic_closed_forms_fall_back() {
    let chain = CoupledOscillators::new(
        &[0.1, 0.0, -0.2],
        &[0.0; 3],
        CoupledOscillatorsParams::default(),
    )
    .unwrap();
    let mut jac = [0.0; 36];
    assert!(chain.jacobian(0.0, chain.state(), &mut jac).is_none());
    assert!(chain
        .canonical_jacobian(0.0, chain.state(), &mut jac)
        .is_some());
    let model =
        LagrangianModel::new(AutoDiff(pendulum_params()), &[2.0, 1.0], &[0.5, -0.3]).unwrap();
    let mut jac = [0.0; 16];
    assert!(model.jacobian(0.0, model.state(), &mut jac).is_none());
    assert!(model
        .engine()
        .closed_canonical_jacobian(0.0, model.state(), &mut jac)
        .is_none());
}

/// A state of the wrong length is a dimension error, not a panic.
#[test]
fn jacobian_of_a_wrong_length_state_is_an_error() {
    let dp = DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], pendulum_params()).unwrap();
    let mut jac = [0.0; 16];
    assert!(matches!(
        dp.jacobian(0.0, &[0.0; 3], &mut jac),
        Some(Err(Error::DimensionMismatch { .. }))
    ));
    assert!(matches!(
        dp.jacobian(0.0, &[0.0; 4], &mut jac[..15]),
        Some(Err(Error::DimensionMismatch { .. }))
    ));
}

/// Where the mass matrix is singular (the spring pendulum's bob at the pivot: stretch
/// `s = -L0`, or past it) the Jacobian reports it, as the field does.
#[test]
fn jacobian_at_a_singular_mass_matrix_is_an_error() {
    let ep =
        ElasticPendulum::new(&[0.3, 0.8], &[0.2, -0.5], ElasticPendulumParams::default()).unwrap();
    let mut jac = [0.0; 16];
    for result in [
        ep.jacobian(0.0, &[-1.0, 0.3, 0.1, 0.2], &mut jac),
        ep.canonical_jacobian(0.0, &[-1.0, 0.3, 0.1, 0.2], &mut jac),
        ep.engine()
            .closed_canonical_jacobian(0.0, &[-1.5, 0.3, 0.1, 0.2], &mut jac),
    ] {
        assert!(
            matches!(result, Some(Err(Error::SingularMatrix { .. }))),
            "{result:?}"
        );
    }
}
