//! `taylor`: every recurrence against quadrature of its function, the expression forms of
//! Kepler, Hénon–Heiles and the double pendulum against their hand-written fields, the
//! measured local order against the closed-form Kepler orbit, the error following the
//! tolerance, the floor over 100 Kepler orbits, the energy error's growth over long runs,
//! dense output independent of the output spacing, failures as errors, and hostile tolerances
//! refused naming the field.

use crate::checks::loglog_slope;
use crate::fixtures::pseudo_random;
use physicskit::classical::analysis::poincare::Direction;
use physicskit::classical::analysis::section::{
    poincare_section, taylor_section, SurfaceOfSection,
};
use physicskit::classical::integrators::taylor::{
    compensated_horner, integrate_taylor, order_for, InBlocks, StepCost, Taylor, TaylorField,
    LANES, MAX_ORDER, MIN_RTOL,
};
use physicskit::classical::lagrangian::LagrangianModel;
use physicskit::classical::model::erased::{DynSystem, Hamiltonian};
use physicskit::classical::symbolic::{trace_lagrangian, TaylorProgram};
use physicskit::classical::symbolic::{Expr, ExprHamiltonian, ExprLagrangian, ExprOde};
use physicskit::classical::systems::{
    DoublePendulum, DoublePendulumParams, HenonHeilesSystem, KeplerPerturbations, KeplerSystem,
    TodaLattice,
};
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method,
    Tolerances,
};

const PERIOD: f64 = 2.0 * std::f64::consts::PI;

/// The Kepler orbit `a = 1`, `e = 0.5`, `k = mu = 1` (period `2 pi`) from perihelion, by
/// Kepler's equation `E - e sin E = t` solved by Newton's method to rounding: position and
/// momentum.
pub(crate) fn kepler_state(t: f64) -> [f64; 4] {
    let e = 0.5;
    let m = t.rem_euclid(PERIOD);
    let mut ecc = m + e * m.sin();
    for _ in 0..50 {
        let step = (ecc - e * ecc.sin() - m) / (1.0 - e * ecc.cos());
        ecc -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    let edot = 1.0 / (1.0 - e * ecc.cos());
    let b = (1.0 - e * e).sqrt();
    [
        ecc.cos() - e,
        b * ecc.sin(),
        -ecc.sin() * edot,
        b * ecc.cos() * edot,
    ]
}

/// `H = |p|^2/2 - 1/|q|` (k = mu = 1).
pub(crate) fn kepler_expr() -> ExprHamiltonian {
    let h =
        Expr::parse("(- (* 0.5 (+ (^ p0 2) (^ p1 2))) (^ (+ (^ q0 2) (^ q1 2)) -0.5))").unwrap();
    let s = kepler_state(0.0);
    ExprHamiltonian::new(h, 2, vec![], &s[..2], &s[2..]).unwrap()
}

fn kepler_energy(y: &[f64]) -> f64 {
    0.5 * (y[2] * y[2] + y[3] * y[3]) - 1.0 / y[0].hypot(y[1])
}

/// `H = |p|^2/2 + |q|^2/2 + x^2 y - y^3/3`.
pub(crate) fn henon_heiles_expr() -> ExprHamiltonian {
    let h = Expr::parse(
        "(+ (* 0.5 (+ (^ p0 2) (^ p1 2) (^ q0 2) (^ q1 2))) (* (^ q0 2) q1) (* -0.333333333333333333 (^ q1 3)))",
    )
    .unwrap();
    ExprHamiltonian::new(h, 2, vec![], &[0.0, 0.1], &[0.3, 0.0]).unwrap()
}

/// The parameters `(a, b, d, g1, g2)` of the double pendulum's expressions: `a = (m1 + m2) l1²`,
/// `b = m2 l1 l2`, `d = m2 l2²`, `g1 = (m1 + m2) g l1`, `g2 = m2 g l2`.
fn double_pendulum_params(params: DoublePendulumParams) -> Vec<f64> {
    let DoublePendulumParams { m1, m2, l1, l2, g } = params;
    vec![
        (m1 + m2) * l1 * l1,
        m2 * l1 * l2,
        m2 * l2 * l2,
        (m1 + m2) * g * l1,
        m2 * g * l2,
    ]
}

/// The double pendulum's `H = p^T M^-1 p / 2 - g1 cos q0 - g2 cos q1` with
/// `M = [[a, b cos D], [b cos D, d]]`, `D = q0 - q1` (the hand-written system's notation),
/// parameters `(a, b, d, g1, g2)`.
pub(crate) fn double_pendulum_expr(params: DoublePendulumParams) -> ExprHamiltonian {
    let values = double_pendulum_params(params);
    let h = Expr::parse(
        "(- (- (/ (+ (* param2 (^ p0 2)) (* param0 (^ p1 2)) (* -2 param1 (cos (- q0 q1)) p0 p1)) \
            (* 2 (- (* param0 param2) (^ (* param1 (cos (- q0 q1))) 2)))) \
           (* param3 (cos q0))) (* param4 (cos q1)))",
    )
    .unwrap();
    ExprHamiltonian::new(h, 2, values, &[1.0, 0.5], &[0.0, 0.0]).unwrap()
}

/// The field `f(t, y)`, as the order-0 term of the derivative coefficients: `y^[1]`.
fn first_order(program: &mut TaylorProgram, y: &[f64]) -> Vec<f64> {
    let n = y.len();
    let mut c = vec![0.0; n * 2];
    program.coefficients(0.0, y, 1, &mut c).unwrap();
    (0..n).map(|i| c[2 * i + 1]).collect()
}

/// The expression forms give the hand-written fields (the double pendulum's canonical one, on
/// `(q, p)`): at 50 pseudo-random states each, every
/// component agrees to 1e-13 relative to the field's size (the two compute in different
/// operation orders, ~10 roundings of quantities of the field's size).
#[test]
fn expression_forms_match_the_hand_written_fields() {
    let params = DoublePendulumParams::default();
    let kepler =
        KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())
            .unwrap();
    let henon = HenonHeilesSystem::new(&[0.0, 0.1], &[0.3, 0.0]).unwrap();
    let pendulum = DoublePendulum::new(&[1.0, 0.5], &[0.0, 0.0], params).unwrap();
    type Field<'a> = Box<dyn Fn(&[f64], &mut [f64]) + 'a>;
    let cases: [(Field, ExprHamiltonian); 3] = [
        (
            Box::new(|y, dy| kepler.derivatives(0.0, y, dy).unwrap()),
            kepler_expr(),
        ),
        (
            Box::new(|y, dy| henon.derivatives(0.0, y, dy).unwrap()),
            henon_heiles_expr(),
        ),
        (
            Box::new(|y, dy| pendulum.canonical_derivatives(0.0, y, dy).unwrap()),
            double_pendulum_expr(params),
        ),
    ];
    for (k, (field, expr)) in cases.into_iter().enumerate() {
        let mut program = TaylorProgram::hamiltonian(&expr).unwrap();
        for s in 0..50 {
            let y: Vec<f64> = pseudo_random(4, 1000 * k as u64 + s)
                .iter()
                .map(|v| 0.5 + 2.0 * v)
                .collect();
            let mut want = vec![0.0; 4];
            field(&y, &mut want);
            let got = first_order(&mut program, &y);
            let size = want.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    (g - w).abs() <= 1e-13 * size,
                    "system {k}, {y:?}: {got:?} {want:?}"
                );
            }
        }
    }
}

/// The double pendulum's canonical equations written by hand as heyoka is given them
/// (`w = M^-1 p` computed once: `dq = w`, `dp_0 = -b w_0 w_1 sin D - g1 sin q0`,
/// `dp_1 = b w_0 w_1 sin D - g2 sin q1`), parameters `(a, b, d, g1, g2)`.
fn double_pendulum_hand_written() -> Vec<Expr> {
    let det = "(- (* param0 param2) (* (^ param1 2) (^ (cos (- q0 q1)) 2)))";
    let w0 = format!("(/ (- (* param2 p0) (* param1 (cos (- q0 q1)) p1)) {det})");
    let w1 = format!("(/ (- (* param0 p1) (* param1 (cos (- q0 q1)) p0)) {det})");
    let lift = format!("(* param1 {w0} {w1} (sin (- q0 q1)))");
    [
        w0.clone(),
        w1.clone(),
        format!("(- (neg {lift}) (* param3 (sin q0)))"),
        format!("(- {lift} (* param4 (sin q1)))"),
    ]
    .iter()
    .map(|text| Expr::parse(text).unwrap())
    .collect()
}

/// The programs built from the double pendulum's `H` by symbolic differentiation and from
/// the built-in system's own `L` (traced) are the hand-written equations' vector field on
/// `(q, p)` (at 50 pseudo-random states every component agrees to 1e-13 relative to the
/// field's size: each is ~20 roundings of quantities of that size, in different orders, and a
/// wrong term is off by order one).
///
/// Their sizes: from `H`, the derivatives of the quotient `N/D` reuse `N/D` and the constant
/// factors move out of the products, which are then shared: at most 1.5 times the
/// hand-written equations' nodes (a program that writes out every constant factor where it
/// stands has 69, 2.3 times). From `L`, whose kinetic energy is quadratic in `qdot`, the
/// velocities `w = M^-1 p` are solved for once and shared by `dp/dt = ∂L/∂q` at `qdot = w`:
/// no more nodes than the hand-written equations (30), where `H` differentiated entry by
/// entry of `M^-1` gives 41. The Euler–Lagrange program on `(q, qdot)` from the same `L`
/// merges the terms of `∂L/∂q` and `d/dt ∂L/∂qdot` that cancel (the sum `-b sin D v0 v1` of
/// `∂L/∂q0` against the same product from `d/dt ∂L/∂qdot0`): at most one node more than the
/// hand-written equations (a builder that keeps them has 38).
#[test]
fn the_derived_double_pendulum_program_is_the_hand_written_one() {
    let params = DoublePendulumParams::default();
    let values = double_pendulum_params(params);
    let mut derived = TaylorProgram::hamiltonian(&double_pendulum_expr(params)).unwrap();
    let mut hand = TaylorProgram::new(&double_pendulum_hand_written(), 2, 2, &values).unwrap();
    let traced = trace_lagrangian(&params).unwrap();
    let mut from_l = TaylorProgram::lagrangian_canonical(&traced).unwrap();
    let euler_lagrange = TaylorProgram::lagrangian(&traced).unwrap();
    println!(
        "double pendulum: {} nodes derived from H, {} from L on (q, p), {} from L on \
         (q, qdot), {} from the hand-written equations",
        derived.nodes(),
        from_l.nodes(),
        euler_lagrange.nodes(),
        hand.nodes()
    );
    assert!(
        2 * derived.nodes() <= 3 * hand.nodes(),
        "{} nodes against {}",
        derived.nodes(),
        hand.nodes()
    );
    assert!(
        from_l.nodes() <= hand.nodes(),
        "{} nodes against {}",
        from_l.nodes(),
        hand.nodes()
    );
    assert!(
        euler_lagrange.nodes() <= hand.nodes() + 1,
        "{} nodes against {}",
        euler_lagrange.nodes(),
        hand.nodes()
    );
    for s in 0..50 {
        let y: Vec<f64> = pseudo_random(4, 7000 + s).iter().map(|v| 3.0 * v).collect();
        let want = first_order(&mut hand, &y);
        let size = want.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for program in [&mut derived, &mut from_l] {
            let got = first_order(program, &y);
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-13 * size, "{y:?}: {got:?} {want:?}");
            }
        }
    }
}

/// A Lagrangian whose kinetic energy is not quadratic in `qdot` (`L = qdot^4/4 - q^2/2`: the
/// momentum `qdot^3` is not linear in it) has no canonical program built by solving for the
/// velocities, and says so, naming the Lagrangian.
#[test]
fn a_canonical_program_needs_a_quadratic_kinetic_energy() {
    let l = Expr::parse("(- (* 0.25 (^ qdot0 4)) (* 0.5 (^ q0 2)))").unwrap();
    let system = ExprLagrangian::new(l, 1, vec![]).unwrap();
    let err = TaylorProgram::lagrangian_canonical(&system).unwrap_err();
    let Error::InvalidParameter { name, .. } = &err else {
        panic!("{err}");
    };
    assert_eq!(name, "lagrangian", "{err}");
}

/// One expression in `q1` per recurrence (every function, power and quotient form), with a
/// point `x0` inside its domain, at least 0.4 from its nearest singularity.
pub(crate) const RECURRENCES: [(&str, f64); 26] = [
    ("(sin q1)", 0.3),
    ("(cos q1)", 0.3),
    ("(tan q1)", 0.3),
    ("(exp q1)", 0.3),
    ("(ln q1)", 0.7),
    ("(sqrt q1)", 0.7),
    ("(sinh q1)", 0.3),
    ("(cosh q1)", 0.3),
    ("(tanh q1)", 0.3),
    ("(asin q1)", 0.2),
    ("(acos q1)", 0.2),
    ("(atan q1)", 0.3),
    ("(abs q1)", -0.7),
    ("(^ q1 1.5)", 0.7),
    ("(^ q1 -1.5)", 0.7),
    ("(^ q1 -0.5)", 0.7),
    ("(^ q1 2.5)", 0.7),
    ("(^ q1 -2.5)", 0.7),
    ("(^ q1 3)", -0.3),
    ("(^ q1 -2)", 0.7),
    ("(^ q1 q1)", 0.7),
    ("(^ 2 q1)", 0.3),
    ("(/ 1 (+ 1 (^ q1 2)))", 0.3),
    ("(/ (sin q1) (+ 2 (cos q1)))", 0.3),
    ("(* (exp (neg q1)) (cos (* 3 q1)) (- 1 q1))", 0.3),
    ("(- (sin (* 2 q1)) (* 2 (sin q1) (cos q1)))", 0.3),
];

/// Each function's recurrence: the ODE `y0' = f(y1)`, `y1' = 1` from `y1 = x0` has the
/// Taylor polynomial of `∫ f` over the step; at order 24 and a step of 0.1 inside the radius
/// of convergence (>= 0.4 from x0 for every function of `RECURRENCES`) its truncation is below 1e-16,
/// and Simpson's rule on 4000 intervals (truncation ~1e-20) gives the integral to its
/// rounding. 2e-14 absolute bounds the sum of both roundings on integrals of size <= 1.
#[test]
fn every_recurrence_integrates_its_function() {
    let cases = RECURRENCES;
    let (order, h) = (24, 0.1);
    for (text, x0) in cases {
        let f = Expr::parse(text).unwrap();
        let y0 = [0.0, x0];
        let ode = ExprOde::new(vec![f.clone(), Expr::constant(1.0)], vec![], &y0, None).unwrap();
        let mut program = TaylorProgram::ode(&ode).unwrap();
        let mut c = vec![0.0; 2 * (order + 1)];
        program.coefficients(0.0, &y0, order, &mut c).unwrap();
        let got = compensated_horner(&c[..order + 1], h);
        let n = 4000;
        let w = h / n as f64;
        let value = |x: f64| f.eval(&[0.0, x], &[], 0.0, &[]);
        let mut sum = value(x0) + value(x0 + h);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * value(x0 + i as f64 * w);
        }
        let want = sum * w / 3.0;
        assert!((got - want).abs() <= 2e-14, "{text}: {got:e} vs {want:e}");
    }
}

/// One step of fixed order `p` from perihelion has a local error of order `h^(p+1)` against
/// the closed-form orbit: the fitted slope over h = 0.4, 0.2, 0.1 is within 1 of p + 1
/// (higher-order terms bend it by less than that at these steps; an order lost in any
/// recurrence drops the slope by at least 1 more).
#[test]
fn the_local_error_has_the_order_of_the_series() {
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let y0 = kepler_state(0.0);
    for order in [6, 10] {
        let mut c = vec![0.0; 4 * (order + 1)];
        program.coefficients(0.0, &y0, order, &mut c).unwrap();
        let steps = [0.4, 0.2, 0.1];
        let errors: Vec<f64> = steps
            .iter()
            .map(|&h| {
                let exact = kepler_state(h);
                (0..4)
                    .map(|i| {
                        (compensated_horner(&c[i * (order + 1)..(i + 1) * (order + 1)], h)
                            - exact[i])
                            .abs()
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        let slope = loglog_slope(&steps, &errors);
        println!("order {order}: errors {errors:?}, slope {slope:.2}");
        assert!(
            ((order + 1) as f64 - 1.0..=(order + 2) as f64).contains(&slope),
            "{slope}"
        );
    }
}

/// Largest state error over `orbits` Kepler orbits (10 samples per orbit) against the closed
/// form, its largest energy error and the steps taken.
fn kepler_run(orbits: f64, tol: f64) -> (f64, f64, f64) {
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let y0 = kepler_state(0.0);
    let r = integrate_taylor(
        &mut program,
        &y0,
        (0.0, orbits * PERIOD),
        PERIOD / 10.0,
        Tolerances::new(tol, tol).unwrap(),
    )
    .unwrap();
    let e0 = kepler_energy(&y0);
    let (mut error, mut energy) = (0.0_f64, 0.0_f64);
    for (&t, y) in r.t.iter().zip(r.y.rows()) {
        let exact = kepler_state(t);
        let y = y.to_vec();
        for i in 0..4 {
            error = error.max((y[i] - exact[i]).abs());
        }
        energy = energy.max((kepler_energy(&y) - e0).abs());
    }
    (error, energy, r.extra_scalar("steps").unwrap())
}

/// The order weighs a step's work against its length. A step made of products only (work
/// `p(p + 1)/2`) takes Jorba and Zou's order `⌈-ln(ε)/2 + 1⌉`, or one or two above it: their
/// rule minimises `p²` per step of `ρ/e²`, and counting the orders `0..=p` and the safety
/// factor `e^-0.7` moves the least work up by less than two orders (worked by hand at `ε =
/// 1e-6`: orders 8, 9, 10, 11 cost `ln(36) + 14.52/7 = 5.657`, `5.621`, `5.620`, `5.641`).
/// Work that grows less with the order (per order or per step) only raises the order; the
/// work per unit of time is least at the order chosen among its neighbours' values computed
/// here from the documented step `ρ (ε e^-0.7)^(1/(p - 1))`; and hostile costs give an order
/// in range, without a panic.
#[test]
fn the_order_weighs_the_work_against_the_step() {
    let products = StepCost {
        convolution: 1.0,
        per_order: 0.0,
        per_step: 0.0,
    };
    assert_eq!(
        order_for(&Tolerances::new(1e-6, 1e-6).unwrap(), &products),
        10
    );
    for tol in [1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16] {
        let tolerances = Tolerances::new(tol, tol).unwrap();
        let jorba_zou = (-tol.ln() / 2.0 + 1.0).ceil() as usize;
        let p = order_for(&tolerances, &products);
        assert!(
            (jorba_zou..=jorba_zou + 2).contains(&p),
            "{tol:e}: {p} vs {jorba_zou}"
        );
        let mut last = p;
        for per_step in [10.0, 100.0, 1e3, 1e4, 1e6] {
            for per_order in [0.0, 10.0, 100.0] {
                let cost = StepCost {
                    per_order,
                    per_step,
                    ..products
                };
                let q = order_for(&tolerances, &cost);
                assert!(q >= p, "{tol:e}, {per_step}, {per_order}: {q} < {p}");
                if per_order == 0.0 {
                    assert!(q >= last, "{tol:e}, {per_step}: {q} < {last}");
                    last = q;
                }
                let per_time = |p: usize| {
                    let h = ((tol.ln() - 0.7) / (p - 1) as f64).exp();
                    cost.work(p) / h
                };
                for n in [q.saturating_sub(1).max(2), (q + 1).min(MAX_ORDER)] {
                    assert!(per_time(q) <= per_time(n), "{tol:e}: {q} vs {n}");
                }
            }
        }
        // Work that is all per step wants the longest steps: the highest order.
        assert_eq!(
            order_for(
                &tolerances,
                &StepCost {
                    convolution: 0.0,
                    per_order: 0.0,
                    per_step: 1.0
                }
            ),
            MAX_ORDER
        );
    }
    for bad in [f64::NAN, f64::INFINITY, -1.0, 0.0, f64::MAX] {
        let cost = StepCost {
            convolution: bad,
            per_order: bad,
            per_step: bad,
        };
        let p = order_for(&Tolerances::default(), &cost);
        assert!((2..=MAX_ORDER).contains(&p), "{bad}: {p}");
    }
}

/// The error follows the tolerance: over 10 orbits, from 1e-6 to 1e-12, the global error falls
/// by the tolerance's factor (the step keeps each local error near tol times the state; the
/// slope in [0.8, 1.2]), below 1000 tol at each (10 orbits of phase error growing linearly
/// from per-step errors of ~tol: measured in the tens of tol).
#[test]
fn the_error_follows_the_tolerance() {
    let tols = [1e-6, 1e-8, 1e-10, 1e-12];
    let runs: Vec<(f64, f64, f64)> = tols.iter().map(|&t| kepler_run(10.0, t)).collect();
    for (tol, (error, energy, steps)) in tols.iter().zip(&runs) {
        println!(
            "tol {tol:e}: order {}, {steps} steps, error {error:e}, energy error {energy:e}",
            order_for(
                &Tolerances::new(*tol, *tol).unwrap(),
                &TaylorProgram::hamiltonian(&kepler_expr())
                    .unwrap()
                    .step_cost()
            )
        );
        assert!(*error <= 1000.0 * tol, "tol {tol:e}: {error:e}");
    }
    let errors: Vec<f64> = runs.iter().map(|r| r.0).collect();
    let slope = loglog_slope(&tols, &errors);
    println!("slope {slope:.3}");
    assert!((0.8..=1.2).contains(&slope), "{slope}");
}

/// The floor: 100 orbits of e = 0.5 at tolerance 1e-16 end, over 40 starts spread over the
/// orbit, with a median error below 1e-12 (heyoka's median over such starts is 3.1e-12,
/// `benchmarks/taylor_floors.py`). One start is one draw of a random walk (the energy error's, per
/// step): equally valid roundings end the same run anywhere in two decades, so only a median
/// over many starts shows a floor. Measured: median 5.8e-13 (from 3.8e-14 to 8.1e-12); with
/// the state rounded to a double at each step instead of carried as a double-double, about
/// 3.6e-12, which fails. The reference is the start itself: the span is 100 periods of the double
/// nearest `2 pi`, 2.4e-14 from 100 true periods, which moves the state by at most 4e-14.
#[test]
fn one_hundred_kepler_orbits_to_the_floor() {
    let tol = Tolerances::new(1e-16, 1e-16).unwrap();
    let starts = 40;
    let mut errors: Vec<f64> = (0..starts)
        .map(|i| {
            let y0 = kepler_state(PERIOD * f64::from(i) / f64::from(starts));
            let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
            let span = 100.0 * PERIOD;
            let r = integrate_taylor(&mut program, &y0, (0.0, span), span, tol).unwrap();
            let last = r.y.row(r.n_samples() - 1).to_vec();
            (0..4).map(|k| (last[k] - y0[k]).abs()).fold(0.0, f64::max)
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let median = 0.5 * (errors[19] + errors[20]);
    println!(
        "100 orbits at 1e-16 from {starts} starts: min {:e}, median {median:e}, max {:e}",
        errors[0], errors[39]
    );
    assert!(median <= 1e-12, "{median:e}");
}

/// The energy error does not drift: over 10, 100 and 1000 orbits at tolerance 1e-16 its
/// maximum grows with an exponent of the step count below 0.75 (rounding errors of about one
/// ulp per step that do not correlate grow like the square root, Brouwer's law; a bias, such
/// as truncation above the rounding or a drifting clock, grows linearly, exponent 1).
#[test]
fn the_energy_error_does_not_drift() {
    let runs: Vec<(f64, f64, f64)> = [10.0, 100.0, 1000.0]
        .iter()
        .map(|&n| kepler_run(n, 1e-16))
        .collect();
    let steps: Vec<f64> = runs.iter().map(|r| r.2).collect();
    let energy: Vec<f64> = runs.iter().map(|r| r.1.max(1e-17)).collect();
    let slope = loglog_slope(&steps, &energy);
    println!("steps {steps:?}: energy errors {energy:?}, exponent {slope:.2}");
    assert!(slope < 0.75, "{slope}");
}

/// Steps do not depend on the output spacing: the samples the grids of dt and dt / 4 share
/// come from the same step polynomials at the same arguments, bit for bit.
#[test]
fn samples_do_not_depend_on_the_output_spacing() {
    let y0 = kepler_state(0.0);
    let tol = Tolerances::new(1e-12, 1e-12).unwrap();
    let run = |dt: f64| {
        let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
        integrate_taylor(&mut program, &y0, (0.0, 3.0 * PERIOD), dt, tol).unwrap()
    };
    let coarse = run(PERIOD / 8.0);
    let fine = run(PERIOD / 32.0);
    for i in 0..coarse.n_samples() {
        assert_eq!(coarse.t[i], fine.t[4 * i]);
        assert_eq!(coarse.y.row(i), fine.y.row(4 * i), "sample {i}");
    }
    assert_eq!(
        coarse.extra_scalar("steps"),
        fine.extra_scalar("steps"),
        "the output grid changed the steps"
    );
}

/// Hénon–Heiles (a regular orbit at E = 1/12, t = 100) and the double pendulum (10 s from
/// rest at (1, 0.5) rad) agree with dop853 at rtol 1e-13 on the hand-written fields to 1e-9:
/// both are within ~1e-10 of the solution there (dop853's global error at that tolerance,
/// measured in its own tests, amplified by these spans), so a wrong expansion of either field
/// (differences of 1e-3 and more) fails.
#[test]
fn henon_heiles_and_the_double_pendulum_agree_with_dop853() {
    let options = || IntegrateOptions {
        tolerances: Some(Tolerances::new(1e-13, 1e-15).unwrap()),
        ..IntegrateOptions::default()
    };
    let tol = Tolerances::new(1e-15, 1e-15).unwrap();
    // Hénon–Heiles.
    let y0 = [0.0, 0.1, 0.3, 0.0];
    let mut henon = HenonHeilesSystem::new(&y0[..2], &y0[2..]).unwrap();
    let reference = henon
        .integrate_with((0.0, 100.0), 1.0, Method::Dop853, options())
        .unwrap();
    let mut program = TaylorProgram::hamiltonian(&henon_heiles_expr()).unwrap();
    let ours = integrate_taylor(&mut program, &y0, (0.0, 100.0), 1.0, tol).unwrap();
    let diff = (&ours.y - &reference.y).fold(0.0_f64, |m, v| m.max(v.abs()));
    println!("Hénon–Heiles: largest difference {diff:e}");
    assert!(diff <= 1e-9, "{diff:e}");
    // The double pendulum, state (q, p).
    let params = DoublePendulumParams::default();
    let mut pendulum = DoublePendulum::new(&[1.0, 0.5], &[0.0, 0.0], params).unwrap();
    // Canonical start: p = M(q) qdot = 0 from rest.
    let y0 = [1.0, 0.5, 0.0, 0.0];
    let reference = LagrangianSystem::integrate_with(
        &mut pendulum,
        (0.0, 10.0),
        0.1,
        Method::Dop853,
        options(),
    )
    .unwrap();
    let mut program = TaylorProgram::hamiltonian(&double_pendulum_expr(params)).unwrap();
    let ours = integrate_taylor(&mut program, &y0, (0.0, 10.0), 0.1, tol).unwrap();
    // The angles (the reference stores (q, qdot), ours (q, p)).
    let diff = (&ours.y.slice(ndarray::s![.., ..2]) - &reference.y.slice(ndarray::s![.., ..2]))
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    println!("double pendulum: largest difference {diff:e}");
    assert!(diff <= 1e-9, "{diff:e}");
}

/// A field whose solution blows up (`y' = y^2`, `y = 1/(1 - t)`) stops with a step failure
/// before t = 1, not a panic or a hang; the step budget stops a run; a bad order, a state of
/// the wrong size and an expression for the wrong number of components are refused.
#[test]
fn failures_are_errors() {
    let f = Expr::parse("(^ q0 2)").unwrap();
    let ode = ExprOde::new(vec![f.clone()], vec![], &[1.0], None).unwrap();
    let mut program = TaylorProgram::ode(&ode).unwrap();
    let tol = Tolerances::new(1e-12, 1e-12).unwrap();
    let err = integrate_taylor(&mut program, &[1.0], (0.0, 2.0), 0.5, tol).unwrap_err();
    match err {
        // The computed solution's pole moves with the state's accumulated relative error
        // (~1e-14 after the growth to 1e13): 1e-9 past t = 1 leaves room for that, and a
        // stepper that jumped the pole would report a time of order 1 past it or none.
        Error::StepSizeTooSmall { t, .. } => assert!(t > 0.99 && t < 1.0 + 1e-9, "{t}"),
        e => panic!("{e}"),
    }
    let budget = Tolerances {
        max_steps: 5,
        ..tol
    };
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let err =
        integrate_taylor(&mut program, &kepler_state(0.0), (0.0, 100.0), 1.0, budget).unwrap_err();
    assert!(matches!(err, Error::StepSizeTooSmall { .. }), "{err}");
    let mut c = vec![0.0; 2 * 40];
    let err = program
        .coefficients(0.0, &[0.0; 4], 39, &mut c)
        .unwrap_err();
    assert!(err.to_string().contains("order"), "{err}");
    let err = program.coefficients(0.0, &[0.0; 3], 4, &mut c).unwrap_err();
    assert!(matches!(err, Error::DimensionMismatch { .. }), "{err}");
    // Room for other than the 4 rows of 5 coefficients that order 4 fills.
    let state = kepler_state(0.0);
    assert!(program.coefficients(0.0, &state, 4, &mut c).is_err());
    assert!(program.coefficients(0.0, &state, 4, &mut c[..20]).is_ok());
    assert!(integrate_taylor(&mut program, &[1.0], (0.0, 1.0), 0.5, tol).is_err());
    assert!(TaylorProgram::new(&[f], 2, 0, &[]).is_err());
    // At the origin the Kepler field's series is not finite: an error naming the time.
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let err =
        integrate_taylor(&mut program, &[0.0, 0.0, 1.0, 0.0], (0.0, 1.0), 0.5, tol).unwrap_err();
    assert!(
        matches!(err, Error::StepSizeTooSmall { t, .. } if t == 0.0),
        "{err}"
    );
}

/// The solution `y = y0 e^{-t}` of `y' = -y`, six components (a block of four rows and a
/// partly filled one in the stepper), its series exact; the second expansion gets one
/// coefficient replaced by `poison` (row, order, value).
struct PoisonedDecay {
    calls: usize,
    poison: (usize, usize, f64),
    rows: Vec<f64>,
}

impl PoisonedDecay {
    /// The field never poisoned (its poison's row past the six).
    fn clean() -> Self {
        PoisonedDecay {
            calls: 0,
            poison: (usize::MAX, 0, 0.0),
            rows: Vec::new(),
        }
    }
}

impl TaylorField for PoisonedDecay {
    fn dim(&self) -> usize {
        6
    }

    fn expansion(
        &mut self,
        _t: f64,
        y: &[f64],
        order: usize,
    ) -> physicskit::classical::Result<&[f64]> {
        let n1 = order + 1;
        self.rows.resize(6 * n1, 0.0);
        for (row, &yi) in self.rows.chunks_exact_mut(n1).zip(y) {
            let mut term = yi;
            for (k, c) in row.iter_mut().enumerate() {
                *c = term;
                term *= -1.0 / (k + 1) as f64;
            }
        }
        self.calls += 1;
        let (row, k, value) = self.poison;
        if self.calls == 2 && row < 6 {
            self.rows[row * n1 + k] = value;
        }
        Ok(&self.rows)
    }
}

/// `y' = -y` in six components (as [`PoisonedDecay`], never poisoned), its rows also given as
/// the stepper's blocks; with `off` = (block, order, lane), that block entry one ulp off its
/// row's coefficient: a field breaking `expansion_in_blocks`'s promise.
struct DecayInBlocks {
    decay: PoisonedDecay,
    blocks: Vec<[f64; LANES]>,
    off: Option<(usize, usize, usize)>,
}

impl DecayInBlocks {
    fn new(off: Option<(usize, usize, usize)>) -> Self {
        DecayInBlocks {
            decay: PoisonedDecay::clean(),
            blocks: Vec::new(),
            off,
        }
    }
}

impl TaylorField for DecayInBlocks {
    fn dim(&self) -> usize {
        6
    }

    fn expansion(
        &mut self,
        t: f64,
        y: &[f64],
        order: usize,
    ) -> physicskit::classical::Result<&[f64]> {
        self.decay.expansion(t, y, order)
    }

    fn expansion_in_blocks(
        &mut self,
        t: f64,
        y: &[f64],
        order: usize,
    ) -> physicskit::classical::Result<InBlocks<'_>> {
        let n1 = order + 1;
        let rows = self.decay.expansion(t, y, order)?;
        self.blocks = vec![[0.0; LANES]; 2 * n1];
        for (i, row) in rows.chunks_exact(n1).enumerate() {
            for (j, &c) in row.iter().enumerate() {
                self.blocks[(i / LANES) * n1 + j][i % LANES] = c;
            }
        }
        if let Some((b, j, lane)) = self.off {
            let entry = &mut self.blocks[b * n1 + j][lane];
            *entry = f64::from_bits(entry.to_bits() + 1);
        }
        Ok((rows, Some(&self.blocks)))
    }
}

/// Blocks that hold the rows (the lanes past the sixth row zero) run as the rows alone do,
/// bit for bit; blocks that disagree with them (a field's bug: the step would advance on
/// other coefficients than its step size was chosen from) stop a debug build at the first
/// step.
#[test]
fn blocks_must_hold_the_rows() {
    let tol = Tolerances::new(1e-10, 1e-10).unwrap();
    let y0 = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    let rows = integrate_taylor(&mut PoisonedDecay::clean(), &y0, (0.0, 3.0), 0.5, tol).unwrap();
    let blocks = integrate_taylor(&mut DecayInBlocks::new(None), &y0, (0.0, 3.0), 0.5, tol);
    let blocks = blocks.unwrap();
    assert_eq!(rows.t, blocks.t);
    assert_eq!(rows.y.map(|v| v.to_bits()), blocks.y.map(|v| v.to_bits()));
    if cfg!(debug_assertions) {
        let run = std::panic::catch_unwind(|| {
            let mut field = DecayInBlocks::new(Some((1, 3, 1)));
            integrate_taylor(&mut field, &y0, (0.0, 3.0), 0.5, tol)
        });
        let message = run.expect_err("the disagreement was not caught");
        let message = message
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| message.downcast_ref::<&str>().map(|m| (*m).to_owned()))
            .unwrap_or_default();
        assert!(
            message.contains("blocks disagree with its rows"),
            "{message}"
        );
    }
}

/// A field that gives one row of coefficients for its two components.
struct OneRowShort(Vec<f64>);

impl TaylorField for OneRowShort {
    fn dim(&self) -> usize {
        2
    }

    fn expansion(
        &mut self,
        _t: f64,
        y: &[f64],
        order: usize,
    ) -> physicskit::classical::Result<&[f64]> {
        self.0 = vec![y[0]; order + 1];
        Ok(&self.0)
    }
}

/// A field whose expansion has other than `dim` rows of `order + 1` (an implementation's
/// bug) stops the run with an error naming it, before any step, never a panic.
#[test]
fn an_expansion_of_the_wrong_size_is_an_error() {
    let tol = Tolerances::new(1e-10, 1e-10).unwrap();
    let err = integrate_taylor(
        &mut OneRowShort(Vec::new()),
        &[1.0, 2.0],
        (0.0, 1.0),
        0.5,
        tol,
    )
    .unwrap_err();
    assert!(err.to_string().contains("Taylor field"), "{err}");
}

/// A non-finite coefficient anywhere in an expansion (every row, the partly filled block of
/// four rows included, orders low, middle and high, an infinity or a NaN) stops the step with
/// an error naming it, even where the orders the step size reads are finite; and the
/// polynomial of the step before still gives the outputs, bit for bit.
#[test]
fn a_non_finite_coefficient_anywhere_stops_the_step() {
    let tol = Tolerances::new(1e-10, 1e-10).unwrap();
    let p = order_for(&tol, &PoisonedDecay::clean().step_cost());
    let y0 = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    for row in 0..6 {
        for k in [1, p / 2, p - 2] {
            for value in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
                let mut field = PoisonedDecay {
                    calls: 0,
                    poison: (row, k, value),
                    rows: Vec::new(),
                };
                let mut stepper = Taylor::new(&field, tol, 0.0, &y0, 10.0).unwrap();
                assert!(stepper.step(&mut field).unwrap());
                let half = stepper.step_length() / 2.0;
                let mut before = [0.0; 6];
                stepper.eval_state(half, &mut before);
                let components = |stepper: &Taylor| -> Vec<u64> {
                    (0..6)
                        .map(|i| stepper.eval_component(i, half).0.to_bits())
                        .collect()
                };
                let components_before = components(&stepper);
                // The step's truncation error is about tol relative to the state (the
                // step-size rule); 10x that.
                for (v, y) in before.iter().zip(y0) {
                    assert!((v - y * (-half).exp()).abs() <= 1e-9 * y, "{v} {y}");
                }
                let err = stepper.step(&mut field).unwrap_err();
                assert!(
                    matches!(err, Error::StepSizeTooSmall { .. })
                        && err.to_string().contains("not finite"),
                    "row {row}, order {k}, {value}: {err}"
                );
                let mut after = [0.0; 6];
                stepper.eval_state(half, &mut after);
                assert_eq!(before.map(f64::to_bits), after.map(f64::to_bits));
                assert_eq!(components(&stepper), components_before);
            }
        }
    }
}

/// `Method::Taylor` through `integrate` on an expression system runs the system's Taylor
/// form: the steps of `integrate_taylor` on the same recurrences, and the same bits on a
/// second run. The samples agree with `integrate_taylor`'s to 1e-14: the driver asks for
/// `t + dt` where `integrate_taylor` asks for the grid's `time(i + 1)`, an ulp or so apart
/// (ulp(20) = 3.6e-15, times a speed of at most 2).
#[test]
fn method_taylor_is_integrate_taylor_on_the_systems_taylor_form() {
    let tol = Tolerances::new(1e-13, 1e-13).unwrap();
    let options = || IntegrateOptions {
        tolerances: Some(tol),
        ..IntegrateOptions::default()
    };
    let run = || {
        kepler_expr()
            .integrate_with((0.0, 3.0 * PERIOD), PERIOD / 8.0, Method::Taylor, options())
            .unwrap()
    };
    let (a, b) = (run(), run());
    assert_eq!(a, b);
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let direct = integrate_taylor(
        &mut program,
        &kepler_state(0.0),
        (0.0, 3.0 * PERIOD),
        PERIOD / 8.0,
        tol,
    )
    .unwrap();
    assert_eq!(a.method, "taylor");
    let apart = (&a.y - &direct.y).fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(apart <= 1e-14, "{apart:e}");
    assert_eq!(a.extra_scalar("steps"), direct.extra_scalar("steps"));
    // A second call continues from the first's end: a fresh expansion there, the same
    // solution to the global error of tol 1e-13 over 3 orbits (~1e-12 measured in the tens of
    // tol per orbit, see `the_error_follows_the_tolerance`).
    let mut split = kepler_expr();
    split
        .integrate_with((0.0, 1.5 * PERIOD), PERIOD / 8.0, Method::Taylor, options())
        .unwrap();
    let second = split
        .integrate_with(
            (1.5 * PERIOD, 3.0 * PERIOD),
            PERIOD / 8.0,
            Method::Taylor,
            options(),
        )
        .unwrap();
    let diff = second
        .final_state()
        .iter()
        .zip(a.final_state())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(diff <= 1e-10, "{diff:e}");
}

/// The double pendulum as a Lagrangian expression (`L = T - V` in the hand-written system's
/// notation, parameters `(a, b, d, g1, g2)` as in [`double_pendulum_expr`]).
pub(crate) fn double_pendulum_lagrangian(params: DoublePendulumParams) -> ExprLagrangian {
    let values = double_pendulum_params(params);
    let l = Expr::parse(
        "(+ (* 0.5 param0 (^ qdot0 2)) (* 0.5 param2 (^ qdot1 2)) \
            (* param1 qdot0 qdot1 (cos (- q0 q1))) (* param3 (cos q0)) (* param4 (cos q1)))",
    )
    .unwrap();
    ExprLagrangian::new(l, 2, values).unwrap()
}

/// A Lagrangian expression's Taylor form (the Euler–Lagrange equations solved symbolically)
/// gives the engine's accelerations (automatic differentiation and an LU solve) at 50
/// pseudo-random states to 1e-12 relative to the field's size (two computations of the same
/// quantities in different orders, through a 2 x 2 solve whose condition stays below ~10 on
/// these states); and `Method::Taylor` on it follows dop853 at rtol 1e-13 on the hand-written
/// pendulum to 1e-9 over 10 s (both within ~1e-10 of the solution: see
/// `henon_heiles_and_the_double_pendulum_agree_with_dop853`).
#[test]
fn a_lagrangian_expression_has_the_equations_of_motion_as_its_taylor_form() {
    let params = DoublePendulumParams::default();
    let model =
        LagrangianModel::new(double_pendulum_lagrangian(params), &[1.0, 0.5], &[0.0, 0.0]).unwrap();
    let mut form = model
        .taylor_field()
        .expect("an expression has a Taylor form")
        .unwrap();
    for s in 0..50 {
        let y: Vec<f64> = pseudo_random(4, 7000 + s)
            .iter()
            .map(|v| 2.0 * v - 1.0)
            .collect();
        let mut want = vec![0.0; 4];
        model.derivatives(0.0, &y, &mut want).unwrap();
        let mut c = vec![0.0; 4 * 2];
        form.coefficients(0.0, &y, 1, &mut c).unwrap();
        let size = want.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for i in 0..4 {
            assert!(
                (c[2 * i + 1] - want[i]).abs() <= 1e-12 * size,
                "{y:?}: {c:?} {want:?}"
            );
        }
    }
    let options = |rtol: f64, atol: f64| IntegrateOptions {
        tolerances: Some(Tolerances::new(rtol, atol).unwrap()),
        ..IntegrateOptions::default()
    };
    let mut model = model;
    let ours = LagrangianSystem::integrate_with(
        &mut model,
        (0.0, 10.0),
        0.1,
        Method::Taylor,
        options(1e-15, 1e-15),
    )
    .unwrap();
    let mut pendulum = DoublePendulum::new(&[1.0, 0.5], &[0.0, 0.0], params).unwrap();
    let reference = LagrangianSystem::integrate_with(
        &mut pendulum,
        (0.0, 10.0),
        0.1,
        Method::Dop853,
        options(1e-13, 1e-15),
    )
    .unwrap();
    let diff = (&ours.y - &reference.y).fold(0.0_f64, |m, v| m.max(v.abs()));
    println!("Lagrangian double pendulum: largest difference {diff:e}");
    assert!(diff <= 1e-9, "{diff:e}");
}

/// A system whose field is only hand-written (the Toda lattice) has no Taylor form:
/// `Method::Taylor` is refused with `UnsupportedMethod`, naming the method and the systems
/// that have one; so is a Poincaré section with it.
#[test]
fn a_system_without_a_taylor_form_refuses_the_method() {
    let mut toda = TodaLattice::new(&[0.1, 0.0, -0.1], &[0.0, 0.2, 0.0], 1.0, 1.0).unwrap();
    let err = toda.integrate((0.0, 1.0), 0.1, Method::Taylor).unwrap_err();
    let Error::UnsupportedMethod { method, reason } = &err else {
        panic!("{err}");
    };
    assert_eq!(method, "taylor");
    assert!(reason.contains("HamiltonianEngine"), "{reason}");
    let plane = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing).unwrap();
    let mut erased = Hamiltonian(toda);
    let err = poincare_section(
        &mut erased,
        (0.0, 1.0),
        0.1,
        Some(Method::Taylor),
        &plane,
        5,
    )
    .unwrap_err();
    assert!(matches!(err, Error::UnsupportedMethod { .. }), "{err}");
}

/// Crossings located on the step polynomial: the Kepler orbit e = 0.5 (a = 1, period 2 pi,
/// from perihelion) crosses x = 0 upwards at eccentric anomaly E = 5 pi/3, at the times
/// `5 pi/3 + sqrt(3)/4 + 2 pi k` (Kepler's equation `t = E - e sin E`), with y = -3/4 and
/// p_x = (sqrt(3)/2)/(3/4). Over 3 orbits at tolerance 1e-16 every crossing time is within
/// 1e-13 of that: the orbit's own phase error there is a few 1e-15 (about 110 steps of one
/// rounding each, see `one_hundred_kepler_orbits_to_the_floor`), the times are below 20, whose
/// ulp is 3.6e-15, and Newton on the polynomial converges to its rounding; interpolating the
/// output samples instead (or a root of lower order) misses by orders of magnitude more.
#[test]
fn poincare_crossings_on_the_polynomial_match_keplers_equation() {
    let plane = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing).unwrap();
    let mut system = Hamiltonian(kepler_expr());
    let cut = taylor_section(
        &mut system,
        (0.0, 3.0 * PERIOD),
        Tolerances::new(1e-16, 1e-16).unwrap(),
        &plane,
        usize::MAX,
    )
    .unwrap();
    assert_eq!(cut.len(), 3);
    let root3 = 3.0_f64.sqrt();
    let mut worst = 0.0_f64;
    for k in 0..3 {
        let exact = 5.0 * PERIOD / 6.0 + root3 / 4.0 + PERIOD * k as f64;
        let state = cut.state(k).unwrap();
        worst = worst.max((cut.t[k] - exact).abs());
        assert_eq!(state[0], 0.0);
        assert!((state[1] + 0.75).abs() <= 1e-13, "{state:?}");
        assert!((state[2] - root3 / 1.5).abs() <= 1e-13, "{state:?}");
    }
    println!("largest crossing-time error {worst:e}");
    assert!(worst <= 1e-13, "{worst:e}");
    // The system is left at the end of the run, as `integrate` leaves it.
    assert_eq!(system.dynamical().t(), 3.0 * PERIOD);
    // Through `poincare_section` (default tolerances, rtol 1e-10), the same crossings to the
    // orbit's error at that tolerance (~1e-9 over 3 orbits: tens of tol per orbit).
    let mut system = Hamiltonian(kepler_expr());
    let coarse = poincare_section(
        &mut system,
        (0.0, 3.0 * PERIOD),
        PERIOD / 60.0,
        Some(Method::Taylor),
        &plane,
        usize::MAX,
    )
    .unwrap();
    assert_eq!(coarse.len(), 3);
    for k in 0..3 {
        assert!((coarse.t[k] - cut.t[k]).abs() <= 1e-8, "{:?}", coarse.t);
    }
}

/// Hostile tolerances: NaN, infinite, zero or negative `rtol`/`atol`, an `rtol` of 1 or more
/// (1e300) and one below what double precision can hold (`MIN_RTOL = 2^-54`) are refused with
/// an `InvalidParameter` naming the field, by the stepper, by `integrate_taylor` and through the
/// registry (`Method::Taylor` on an expression system); the smallest accepted `rtol` runs. An
/// `atol` far below rounding (1e-300) runs at the order cap `MAX_ORDER` (the report says so), and
/// a huge one (1e300) at the order `rtol` sets: neither explodes the order or the step count.
#[test]
fn hostile_tolerances_are_refused_naming_the_field() {
    let y0 = kepler_state(0.0);
    let span = (0.0, 1.0);
    let bad = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -1e-10,
        1.0,
        1e300,
        1e-17,
        MIN_RTOL / 2.0,
    ];
    for value in bad {
        let tol = Tolerances {
            rtol: value,
            ..Tolerances::default()
        };
        let named = |e: &Error| matches!(e, Error::InvalidParameter { name, .. } if name == "rtol");
        let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
        let err = integrate_taylor(&mut program, &y0, span, 0.5, tol).unwrap_err();
        assert!(named(&err), "rtol = {value:e}: {err}");
        let options = IntegrateOptions {
            tolerances: Some(tol),
            ..IntegrateOptions::default()
        };
        let err = kepler_expr()
            .integrate_with(span, 0.5, Method::Taylor, options)
            .unwrap_err();
        assert!(named(&err), "rtol = {value:e} through the registry: {err}");
    }
    for value in [f64::NAN, f64::INFINITY, 0.0, -1.0] {
        let tol = Tolerances {
            atol: value,
            ..Tolerances::default()
        };
        let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
        let err = integrate_taylor(&mut program, &y0, span, 0.5, tol).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidParameter { name, .. } if name == "atol"),
            "atol = {value:e}: {err}"
        );
    }
    let kepler = TaylorProgram::hamiltonian(&kepler_expr())
        .unwrap()
        .step_cost();
    for (rtol, atol, order) in [
        (
            MIN_RTOL,
            MIN_RTOL,
            order_for(&Tolerances::new(MIN_RTOL, MIN_RTOL).unwrap(), &kepler),
        ),
        (1e-10, 1e-300, MAX_ORDER),
        (
            1e-10,
            1e300,
            order_for(&Tolerances::new(1e-10, 1.0).unwrap(), &kepler),
        ),
    ] {
        let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
        let tol = Tolerances::new(rtol, atol).unwrap();
        let r = integrate_taylor(&mut program, &y0, span, 0.5, tol).unwrap();
        assert_eq!(
            r.extra_scalar("order"),
            Some(order as f64),
            "{rtol:e}, {atol:e}"
        );
        // One time unit of the orbit (a sixth of it) takes a handful of steps at any order.
        let steps = r.extra_scalar("steps").unwrap();
        assert!(steps < 100.0, "{rtol:e}, {atol:e}: {steps} steps");
    }
}
