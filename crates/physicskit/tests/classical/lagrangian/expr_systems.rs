//! Expression-defined Hamiltonians and ODEs (`ExprHamiltonian`, `ExprOde`; the native half of
//! the Python `HamiltonianEngine` and `ODEEngine`), their symbolic derivatives, the compiled
//! tapes and the Jacobians by automatic differentiation, each against something written
//! independently: the built-in Hénon–Heiles system and its hand-written force Jacobian, the
//! non-separable fixture, central differences, the exact solution of a linear system.

// Separability is decided exactly (mass_inv read off as exact constants): exact comparisons
// are intended where noted.
#![allow(clippy::float_cmp)]

use physicskit::classical::symbolic::{Expr, ExprHamiltonian, ExprOde, Tape, Var};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, MassInv, Method, OdeSystem,
};

use crate::checks::check_force_against_potential;
use crate::fixtures::{pseudo_random, NonSeparable};

/// Hénon–Heiles as the Python `HamiltonianEngine` hands SymPy's expression over.
const HENON_HEILES: &str = "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* 0.5 (^ q0 2)) \
     (* 0.5 (^ q1 2)) (* (^ q0 2) q1) (* -0.3333333333333333 (^ q1 3)))";

fn hamiltonian(text: &str, ndof: usize, params: Vec<f64>) -> ExprHamiltonian {
    let zeros = vec![0.1; ndof];
    ExprHamiltonian::new(Expr::parse(text).unwrap(), ndof, params, &zeros, &zeros).unwrap()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn henon_heiles_from_an_expression_follows_the_builtin_system() {
    let (q0, p0) = ([0.0, 0.1], [0.5, 0.0]);
    let mut expr =
        ExprHamiltonian::new(Expr::parse(HENON_HEILES).unwrap(), 2, vec![], &q0, &p0).unwrap();
    let mut builtin = HenonHeilesSystem::new(&q0, &p0).unwrap();
    assert!(expr.separable());
    assert_eq!(expr.default_method(), Method::Yoshida4);
    for method in [Method::Yoshida4, Method::Verlet, Method::Rk4] {
        let a = expr.integrate((0.0, 100.0), 0.01, method).unwrap();
        let b = builtin.integrate((0.0, 100.0), 0.01, method).unwrap();
        // 1e4 steps at E = 0.13 (a regular orbit). The derived force -(x + 2 y x) and the
        // built-in -x - 2 x y are the same operations up to order, and -1/3 * 3 folds to
        // -1 exactly, so the runs agree to rounding; rounding differences would grow at most
        // linearly on a regular orbit (~1e4 * 1e-16): 1e-12.
        let dy =
            a.y.iter()
                .zip(b.y.iter())
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(dy < 1e-12, "{method:?}: trajectories differ by {dy}");
        let (ea, eb) = (a.energy.unwrap(), b.energy.unwrap());
        let de = ea
            .iter()
            .zip(eb.iter())
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(de < 1e-12, "{method:?}: energies differ by {de}");
    }
}

#[test]
fn henon_heiles_force_and_jacobian_match_the_hand_written_ones() {
    let system = hamiltonian(HENON_HEILES, 2, vec![]);
    let builtin = HenonHeilesSystem::new(&[0.0, 0.0], &[0.0, 0.0]).unwrap();
    let data = pseudo_random(200, 7);
    for q in data.chunks(2) {
        let (mut fa, mut fb) = ([0.0; 2], [0.0; 2]);
        system.force(q, 0.0, &mut fa).unwrap();
        builtin.force(q, 0.0, &mut fb).unwrap();
        // Same formula with the operations reordered: a few ulps of O(1) values.
        assert!(max_abs_diff(&fa, &fb) < 1e-15, "{fa:?} vs {fb:?}");
        let (mut ja, mut jb) = ([0.0; 4], [0.0; 4]);
        system.force_jacobian(q, 0.0, &mut ja).unwrap().unwrap();
        builtin.force_jacobian(q, 0.0, &mut jb).unwrap().unwrap();
        // Forward-mode AD of the derived force against the hand-derived -Hessian: the
        // derivative parts are computed with one or two roundings each.
        assert!(max_abs_diff(&ja, &jb) < 1e-15, "{ja:?} vs {jb:?}");
        assert!(
            (system.potential_energy(q) - builtin.potential_energy(q)).abs() < 1e-15,
            "potential at {q:?}"
        );
        check_force_against_potential(&system, q);
    }
}

#[test]
fn separability_is_detected_both_ways() {
    // Masses as parameters: T = p0^2 / (2 m0) + p1^2 / (2 m1) + 3 (a constant kinetic term).
    let s = hamiltonian(
        "(+ (/ (^ p0 2) (* 2 param0)) (/ (^ p1 2) (* 2 param1)) 3 (cos q0) (* q0 q1))",
        2,
        vec![2.0, 4.0],
    );
    assert!(s.separable());
    let MassInv::PerCoordinate(m) = s.mass_inv() else {
        panic!("per-coordinate masses expected")
    };
    // d2T/dp^2 = 1/m, derived and folded exactly (1/(2 m) * 2 with m a power of two).
    assert_eq!(m, &[0.5, 0.25]);
    // The constant kinetic term goes to the potential, so the energy is H itself.
    let state = [0.3, -0.2, 0.7, 1.1];
    let h = 0.7 * 0.7 / 4.0 + 1.1 * 1.1 / 8.0 + 3.0 + 0.3_f64.cos() + 0.3 * -0.2;
    assert!((s.energy(&state) - h).abs() < 1e-15);
    assert!((s.hamiltonian(&state[..2], &state[2..], 0.0) - h).abs() < 1e-15);

    for (text, why) in [
        (
            "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ q0 2)) (* q0 p0))",
            "a term mixes q and p",
        ),
        (
            "(+ (sqrt (+ 1 (^ p0 2))) (* 0.5 (^ q0 2)))",
            "relativistic T is not quadratic",
        ),
        (
            "(+ (* 0.5 (^ p0 2)) p0 (* 0.5 (^ q0 2)))",
            "T has a linear term",
        ),
        (
            "(+ (* 0.5 (^ (+ p0 p1) 2)) (* 0.5 (^ q0 2)) (* 0.5 (^ q1 2)))",
            "T is not diagonal",
        ),
        (
            "(+ (* 0.5 (^ p0 2) (cos t)) (* 0.5 (^ q0 2)))",
            "the mass depends on time",
        ),
        ("(* 0.5 (+ (^ p0 2) (^ q0 2)))", "not written as a sum"),
    ] {
        let ndof = if text.contains("p1") { 2 } else { 1 };
        let s = hamiltonian(text, ndof, vec![]);
        assert!(!s.separable(), "{text}: {why}");
        assert_eq!(s.default_method(), Method::ImplicitMidpoint);
        assert!(s
            .force(&vec![0.0; ndof], 0.0, &mut vec![0.0; ndof])
            .is_err());
        let mut s = s;
        let refused = s.integrate((0.0, 1.0), 0.1, Method::Yoshida4).unwrap_err();
        assert!(
            matches!(refused, Error::UnsupportedMethod { .. }),
            "{refused}"
        );
    }
}

#[test]
fn non_separable_field_and_jacobian_match_the_fixture_and_central_differences() {
    // The fixture's H = p^2 (1 + q^2) / 2 + q^2 / 2, written as an expression.
    let expr = hamiltonian(
        "(+ (* 0.5 (^ p0 2) (+ 1 (^ q0 2))) (* 0.5 (^ q0 2)))",
        1,
        vec![],
    );
    assert!(!expr.separable());
    let fixture = NonSeparable::new(0.0, 0.0);
    let data = pseudo_random(40, 3);
    for y in data.chunks(2) {
        let (mut da, mut db) = ([0.0; 2], [0.0; 2]);
        expr.derivatives(0.0, y, &mut da).unwrap();
        fixture.derivatives(0.0, y, &mut db).unwrap();
        // The same polynomial, the derived one in another operation order: a few ulps.
        assert!(max_abs_diff(&da, &db) < 1e-15, "{da:?} vs {db:?}");
        assert!((expr.energy(y) - fixture.energy(y)).abs() < 1e-15);
        let mut jac = [0.0; 4];
        expr.jacobian(0.0, y, &mut jac).unwrap().unwrap();
        let h = 1e-6;
        for j in 0..2 {
            let (mut yp, mut ym) = (y.to_vec(), y.to_vec());
            yp[j] += h;
            ym[j] -= h;
            let (mut fp, mut fm) = ([0.0; 2], [0.0; 2]);
            expr.derivatives(0.0, &yp, &mut fp).unwrap();
            expr.derivatives(0.0, &ym, &mut fm).unwrap();
            for i in 0..2 {
                let numeric = (fp[i] - fm[i]) / (2.0 * h);
                // Central differences: truncation h^2 f''' / 6 ~ 1e-12 and rounding
                // eps / h ~ 2e-10 for this O(1) cubic field: 1e-8 fails only on a wrong
                // derivative.
                assert!((numeric - jac[i * 2 + j]).abs() < 1e-8, "J[{i},{j}]");
            }
        }
    }
}

#[test]
fn implicit_midpoint_on_a_derived_linear_field_matches_its_exact_solution() {
    // H = (p^2 + q^2)/2 + a q p is non-separable; Hamilton's equations are linear,
    // q' = p + a q, p' = -q - a p, a rotation at omega = sqrt(1 - a^2): with z = (q, p),
    // z(t) = [cos(w t) I + sin(w t) / w * A] z0, A = [[a, 1], [-1, -a]] (A^2 = -w^2 I).
    let a = 0.6;
    let mut s = ExprHamiltonian::new(
        Expr::parse("(+ (* 0.5 (^ p0 2)) (* 0.5 (^ q0 2)) (* param0 q0 p0))").unwrap(),
        1,
        vec![a],
        &[1.0],
        &[0.0],
    )
    .unwrap();
    let r = s
        .integrate((0.0, 10.0), 1e-3, Method::ImplicitMidpoint)
        .unwrap();
    let w = (1.0_f64 - a * a).sqrt();
    let (t, y) = (10.0, s.state());
    let exact = [(w * t).cos() + (w * t).sin() / w * a, -(w * t).sin() / w];
    // Midpoint's phase error is h^2 w^3 t / 12 ~ 4e-8 here: 1e-6.
    assert!(max_abs_diff(y, &exact) < 1e-6, "{y:?} vs {exact:?}");
    // Implicit midpoint conserves quadratic invariants up to the solve's tolerance.
    let e = r.energy.unwrap();
    let drift = e.iter().fold(0.0_f64, |m, v| m.max((v - e[0]).abs()));
    assert!(drift < 1e-13, "energy drift {drift}");
}

#[test]
fn symbolic_derivatives_of_every_function_match_central_differences() {
    let x = || Expr::q(0);
    let y = || Expr::qdot(0);
    let cases: Vec<Expr> = vec![
        x().sin() * y(),
        x().cos().powi(3),
        Expr::Func(physicskit::classical::symbolic::Func::Tan, Box::new(x())),
        (x() * y()).apply(physicskit::classical::symbolic::Func::Exp),
        (x() + Expr::constant(2.0)).apply(physicskit::classical::symbolic::Func::Ln),
        (x() + Expr::constant(2.0)).apply(physicskit::classical::symbolic::Func::Sqrt),
        x().apply(physicskit::classical::symbolic::Func::Sinh),
        x().apply(physicskit::classical::symbolic::Func::Cosh),
        x().apply(physicskit::classical::symbolic::Func::Tanh),
        (x() * Expr::constant(0.5)).apply(physicskit::classical::symbolic::Func::Asin),
        (x() * Expr::constant(0.5)).apply(physicskit::classical::symbolic::Func::Acos),
        x().apply(physicskit::classical::symbolic::Func::Atan),
        (x() - Expr::constant(0.01)).apply(physicskit::classical::symbolic::Func::Abs),
        (x() + Expr::constant(2.0)).powf(1.7),
        Expr::Pow(Box::new(x() + Expr::constant(2.0)), Box::new(y())),
        y() / (x() * x() + Expr::constant(1.0)),
        -(x() - y()) * Expr::T,
    ];
    let data = pseudo_random(20, 11);
    for e in &cases {
        let tape = Tape::new(std::slice::from_ref(e), 1, 1, &[]).unwrap();
        for var in [Var::First(0), Var::Second(0), Var::Time] {
            let d = Tape::new(&[e.diff(var)], 1, 1, &[]).unwrap();
            for z in data.chunks(2) {
                let (q, v, t) = (z[0], z[1] + 0.1, 0.7);
                let h = 1e-6;
                let at = |dq: f64, dv: f64, dt: f64| tape.eval_scalar(&[q + dq], &[v + dv], t + dt);
                let numeric = match var {
                    Var::First(_) => (at(h, 0.0, 0.0) - at(-h, 0.0, 0.0)) / (2.0 * h),
                    Var::Second(_) => (at(0.0, h, 0.0) - at(0.0, -h, 0.0)) / (2.0 * h),
                    Var::Time => (at(0.0, 0.0, h) - at(0.0, 0.0, -h)) / (2.0 * h),
                };
                let exact = d.eval_scalar(&[q], &[v], t);
                // Central differences of O(1) smooth functions (arguments kept 0.01 away from
                // |x|'s kink and inside every domain): truncation ~1e-12, rounding ~1e-10.
                assert!(
                    (numeric - exact).abs() < 1e-7 * (1.0 + exact.abs()),
                    "d/d{var:?} of {e} at ({q}, {v}): {exact} vs {numeric}"
                );
            }
        }
    }
}

#[test]
fn a_tape_agrees_with_the_tree_bit_for_bit() {
    // Shared subexpressions (cos(q0 - q1) twice), constants on either side of - and /,
    // folded constant subtrees and parameters: the tape must do the tree's operations.
    // Negative terms (* -1 ...) become subtractions and a negated output a sign flip, both
    // exact rewrites.
    let text = "(+ (* param0 (cos (- q0 q1)) qdot0) (/ 2 (+ 1 (^ q1 2))) (- 3 (* qdot1 \
                (cos (- q0 q1)))) (/ (^ q0 3) 7) (* (+ 1 2) (sin t)) (^ (+ 1.5 q0) qdot1) \
                (* -1 q1 qdot0) (* -1 (exp q0)))";
    let e = Expr::parse(text).unwrap();
    let negated = Expr::parse("(neg (+ q0 (* -1 q1 qdot1)))").unwrap();
    let params = [1.25];
    let tape = Tape::new(&[e.clone(), negated.clone()], 2, 2, &params).unwrap();
    // Counted by hand, one per operation node: 24 for the first output and 2 for the second
    // (its negation is the output's), with cos(q0 - q1) computed once (else 28), (+ 1 2)
    // folded (else 27) and each (* -1 ...) a subtraction (else 29).
    assert_eq!(tape.n_operations(), 26);
    let data = pseudo_random(400, 5);
    for z in data.chunks(4) {
        let (q, v) = (&z[..2], &z[2..]);
        let mut out = [0.0; 2];
        tape.eval(q, v, 0.3, &mut out);
        let tree = [e.eval(q, v, 0.3, &params), negated.eval(q, v, 0.3, &params)];
        assert_eq!(out.map(f64::to_bits), tree.map(f64::to_bits), "at {z:?}");
    }
}

const LORENZ: [&str; 3] = [
    "(* param0 (- y1 y0))",
    "(- (* y0 (- param1 y2)) y1)",
    "(- (* y0 y1) (* param2 y2))",
];

fn lorenz(y0: &[f64], energy: Option<&str>) -> ExprOde {
    let f = LORENZ.iter().map(|s| Expr::parse(s).unwrap()).collect();
    ExprOde::new(
        f,
        vec![10.0, 28.0, 8.0 / 3.0],
        y0,
        energy.map(|s| Expr::parse(s).unwrap()),
    )
    .unwrap()
}

#[test]
fn lorenz_field_and_jacobian_match_the_textbook_ones() {
    let (s, r, b) = (10.0, 28.0, 8.0 / 3.0);
    let system = lorenz(&[1.0, 1.0, 1.0], None);
    for z in pseudo_random(300, 9).chunks(3) {
        let y: Vec<f64> = z.iter().map(|v| 40.0 * v).collect();
        let mut f = [0.0; 3];
        system.derivatives(0.0, &y, &mut f).unwrap();
        let expected = [
            s * (y[1] - y[0]),
            y[0] * (r - y[2]) - y[1],
            y[0] * y[1] - b * y[2],
        ];
        // The same operations in the same order: exact.
        assert_eq!(f, expected);
        let mut jac = [0.0; 9];
        system.jacobian(0.0, &y, &mut jac).unwrap().unwrap();
        let exact = [-s, s, 0.0, r - y[2], -1.0, -y[0], y[1], y[0], -b];
        // Forward-mode AD of products and differences: the derivative parts are exact sums
        // of exact products here, up to one rounding of r - y2.
        assert!(max_abs_diff(&jac, &exact) < 1e-14, "{jac:?} vs {exact:?}");
    }
}

#[test]
fn an_ode_without_energy_stores_none_and_one_with_energy_stores_it() {
    let mut plain = lorenz(&[1.0, 1.0, 1.0], None);
    assert!(plain.energy(&[1.0, 2.0, 3.0]).is_nan());
    let r = plain.integrate((0.0, 0.5), 0.01, Method::Rk4).unwrap();
    assert!(r.energy.is_none());
    assert_eq!(plain.default_method(), Method::ImplicitMidpoint);
    let r = plain
        .integrate((0.5, 1.0), 0.01, Method::ImplicitMidpoint)
        .unwrap();
    assert!(r.energy.is_none() && r.y.nrows() == 51);
    let mut with = lorenz(&[1.0, 1.0, 1.0], Some("(+ (^ y0 2) (^ y1 2) (^ y2 2))"));
    let r = with.integrate((0.0, 0.1), 0.01, Method::Rk4).unwrap();
    let e = r.energy.unwrap();
    assert_eq!(e[0], 3.0);
}

#[test]
fn invalid_expressions_and_inputs_are_refused() {
    let parse = |s: &str| Expr::parse(s).unwrap();
    let refused = |r: Result<ExprHamiltonian, Error>, name: &str| {
        let e = r.unwrap_err();
        assert!(e.to_string().contains(name), "{e}");
    };
    let h = || parse("(+ (* 0.5 (^ p0 2)) (* param0 (^ q0 2)))");
    refused(
        ExprHamiltonian::new(h(), 1, vec![], &[0.0], &[0.0]),
        "param0",
    );
    refused(
        ExprHamiltonian::new(h(), 1, vec![f64::NAN], &[0.0], &[0.0]),
        "params",
    );
    refused(
        ExprHamiltonian::new(h(), 1, vec![1.0], &[0.0, 1.0], &[0.0]),
        "q0",
    );
    refused(
        ExprHamiltonian::new(h(), 1, vec![1.0], &[0.0], &[f64::INFINITY]),
        "p0",
    );
    refused(
        ExprHamiltonian::new(parse("(* q1 p0)"), 1, vec![], &[0.0], &[0.0]),
        "q1",
    );
    refused(ExprHamiltonian::new(h(), 0, vec![1.0], &[], &[]), "ndof");
    // The log of zero among constants is found at compile time.
    refused(
        ExprHamiltonian::new(
            parse("(+ (^ p0 2) (ln (- param0 1)))"),
            1,
            vec![1.0],
            &[0.0],
            &[0.0],
        ),
        "non-finite",
    );
    let ode = |f: Vec<&str>, y0: &[f64]| {
        ExprOde::new(f.into_iter().map(parse).collect(), vec![], y0, None).map(|_| ())
    };
    assert!(ode(vec![], &[])
        .unwrap_err()
        .to_string()
        .contains("one component"));
    assert!(ode(vec!["y1"], &[0.0])
        .unwrap_err()
        .to_string()
        .contains("q1"));
    assert!(ode(vec!["p0"], &[0.0])
        .unwrap_err()
        .to_string()
        .contains("p<i>"));
    assert!(ode(vec!["y0"], &[0.0, 1.0])
        .unwrap_err()
        .to_string()
        .contains("y0"));
    assert!(ode(vec!["y0"], &[f64::NAN])
        .unwrap_err()
        .to_string()
        .contains("y0"));
    // Wrong lengths through the trait methods are errors, not panics.
    let s = lorenz(&[1.0, 1.0, 1.0], None);
    assert!(s.derivatives(0.0, &[1.0], &mut [0.0; 3]).is_err());
    assert!(s
        .jacobian(0.0, &[1.0, 2.0, 3.0], &mut [0.0; 4])
        .unwrap()
        .is_err());
    let h = hamiltonian(HENON_HEILES, 2, vec![]);
    assert!(h.force(&[1.0], 0.0, &mut [0.0; 2]).is_err());
    assert!(h.potential_energy(&[1.0]).is_nan());
    assert!(h.derivatives(0.0, &[1.0; 3], &mut [0.0; 4]).is_err());
    assert!(h.hamiltonian(&[1.0], &[1.0, 2.0], 0.0).is_nan());
    // The tape itself answers short slices with NaN rather than an index panic.
    let tape = Tape::new(&[Expr::parse("(* q0 qdot1)").unwrap()], 1, 2, &[]).unwrap();
    assert!(tape.eval_scalar(&[1.0], &[1.0], 0.0).is_nan());
    let mut out = [0.0_f64];
    tape.eval(&[1.0], &[1.0], 0.0, &mut out);
    assert!(out[0].is_nan());
    let mut jac = [0.0; 2];
    tape.jacobian(&[], &[1.0, 2.0], 0.0, 0..2, &mut jac);
    assert!(jac.iter().all(|v| v.is_nan()));
}
