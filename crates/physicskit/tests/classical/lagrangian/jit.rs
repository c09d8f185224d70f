//! Tapes compiled to machine code (feature `jit`) against the interpreter: every operation
//! and function bit for bit on many inputs, every way of evaluating, whole trajectories of
//! the expression systems, the lazy compilation, and the fallback to the interpreter where
//! Cranelift cannot compile. Without the feature every tape is interpreted, which the tests
//! then check instead (`fixtures::native`).

use physicskit::classical::symbolic::{
    Backend, Expr, ExprHamiltonian, ExprOde, Tape, COMPILE_AFTER,
};
use physicskit::classical::{
    DynamicalSystem, HamiltonianSystem, Method, OdeSystem, SimulationResult,
};

use crate::fixtures::{native, pseudo_random, same};

/// One expression per operation of the tape (the name is the operation it compiles to), in
/// `q0`, `q1`, `qdot0` and `t`.
const OPERATIONS: [(&str, &str); 36] = [
    ("Add", "(+ q0 q1)"),
    ("Sub", "(- q0 q1)"),
    ("Mul", "(* q0 q1)"),
    ("Div", "(/ q0 q1)"),
    ("AddC", "(+ q0 1.25)"),
    ("MulC", "(* 0.3 q0)"),
    ("SubC", "(- q0 0.7)"),
    ("CSub", "(- 0.7 q0)"),
    ("DivC", "(/ q0 3)"),
    ("CDiv", "(/ 3 q0)"),
    ("Neg", "(+ (neg q0) q1)"),
    ("Square", "(^ q0 2)"),
    ("Powi 3", "(^ q0 3)"),
    ("Powi -2", "(^ q0 -2)"),
    ("Powi 7", "(^ (+ q0 q1) 7)"),
    ("Powf", "(^ q0 2.5)"),
    ("Powf negative", "(^ q1 -0.5)"),
    ("Pow", "(^ q0 qdot0)"),
    ("PowC", "(^ q0 (+ 1 0.25))"),
    ("CPow", "(^ 2 q0)"),
    ("Func sin", "(sin q0)"),
    ("Func cos", "(cos q0)"),
    ("Func tan", "(tan q0)"),
    ("Func exp", "(exp q0)"),
    ("Func ln", "(ln q0)"),
    ("Func sqrt", "(sqrt q0)"),
    ("Func sinh", "(sinh q0)"),
    ("Func cosh", "(cosh q0)"),
    ("Func tanh", "(tanh q0)"),
    ("Func asin", "(asin q0)"),
    ("Func acos", "(acos q0)"),
    ("Func atan", "(atan q0)"),
    ("Func abs", "(abs q0)"),
    ("time", "(* t (sin q1))"),
    ("negated output", "(neg (+ q0 (cos q1)))"),
    ("constant output", "(+ 1 2.5)"),
];

fn expressions() -> Vec<Expr> {
    OPERATIONS
        .iter()
        .map(|(_, text)| Expr::parse(text).unwrap())
        .collect()
}

/// A tape compiled to machine code and the same tape kept on the interpreter.
fn pair(outputs: &[Expr]) -> (Tape, Tape) {
    let native_tape = Tape::new(outputs, 2, 1, &[]).unwrap();
    assert_eq!(native_tape.compile_native(), native());
    let interpreted = Tape::new(outputs, 2, 1, &[]).unwrap();
    assert_eq!(
        interpreted.compile_native_for_unsupported_host(),
        Backend::Interpreter
    );
    (native_tape, interpreted)
}

/// Inputs `(q0, q1, qdot0, t)` in [-4, 4]: every domain edge crossed (logs and roots of
/// negatives, asin beyond 1, divisions by small numbers).
fn inputs() -> Vec<[f64; 4]> {
    pseudo_random(4 * 5000, 17)
        .chunks(4)
        .map(|z| [8.0 * z[0], 8.0 * z[1], 8.0 * z[2], 8.0 * z[3]])
        .collect()
}

#[test]
fn every_operation_runs_native_with_the_interpreters_bits() {
    let exprs = expressions();
    for ((name, _), e) in OPERATIONS.iter().zip(&exprs) {
        let (a, b) = pair(std::slice::from_ref(e));
        for [q0, q1, v, t] in inputs() {
            let (x, y) = (
                a.eval_scalar(&[q0, q1], &[v], t),
                b.eval_scalar(&[q0, q1], &[v], t),
            );
            assert!(same(x, y), "{name} at {:?}: {x:e} vs {y:e}", [q0, q1, v, t]);
            // The interpreter is the tree's operations (expr_systems.rs): so is the code.
            assert!(same(x, e.eval(&[q0, q1], &[v], t, &[])), "{name}");
        }
    }
}

#[test]
fn every_way_of_evaluating_a_many_output_tape_agrees() {
    // All the operations as outputs of one tape: shared inputs, outputs stored through the
    // pointer and the last returned.
    let (a, b) = pair(&expressions());
    let n = OPERATIONS.len();
    for [q0, q1, v, t] in inputs().into_iter().take(500) {
        let (first, second) = ([q0, q1], [v]);
        let (mut x, mut y) = (vec![0.0; n], vec![0.0; n]);
        a.eval(&first, &second, t, &mut x);
        b.eval(&first, &second, t, &mut y);
        let (mut xs, mut ys) = (vec![0.0; n - 1], vec![0.0; n - 1]);
        let (xl, yl) = (
            a.eval_with_last(&first, &second, t, &mut xs),
            b.eval_with_last(&first, &second, t, &mut ys),
        );
        for i in 0..n {
            assert!(same(x[i], y[i]), "{} (eval)", OPERATIONS[i].0);
        }
        for i in 0..n - 1 {
            assert!(
                same(xs[i], ys[i]) && same(xs[i], x[i]),
                "{}",
                OPERATIONS[i].0
            );
        }
        assert!(same(xl, yl) && same(xl, x[n - 1]), "last output");
    }
    // Short slices give NaN, never a read out of bounds.
    let mut out = vec![0.0; n];
    a.eval(&[1.0], &[1.0], 0.0, &mut out);
    assert!(out.iter().all(|o| o.is_nan()));
    assert!(a.eval_with_last(&[1.0, 2.0], &[], 0.0, &mut out).is_nan());
    assert!(a.eval_with_last(&[1.0, 2.0], &[1.0], 0.0, &mut []).is_nan());
}

#[test]
fn a_tape_compiles_after_compile_after_evaluations_and_its_clones_share_the_code() {
    let e = Expr::parse("(+ (* q0 q1) (sin qdot0))").unwrap();
    let tape = Tape::new(std::slice::from_ref(&e), 2, 1, &[]).unwrap();
    let clone = tape.clone();
    let mut values = Vec::new();
    for k in 0..=COMPILE_AFTER {
        assert_eq!(
            tape.backend(),
            Backend::Interpreter,
            "after {k} evaluations"
        );
        values.push(tape.eval_scalar(&[0.5, f64::from(k)], &[0.25], 0.0));
    }
    assert_eq!(tape.backend(), native());
    assert_eq!(clone.backend(), native());
    // The switch is invisible: every value is the tree's.
    for (k, v) in values.iter().enumerate() {
        assert!(same(*v, e.eval(&[0.5, k as f64], &[0.25], 0.0, &[])));
    }
    assert!(same(
        clone.eval_scalar(&[0.5, 3.0], &[0.25], 0.0),
        values[3]
    ));
}

#[test]
fn threads_racing_to_compile_one_tape_get_one_code_and_the_same_bits() {
    let e = Expr::parse("(- (* q0 (exp q1)) (/ qdot0 (+ 1 (^ q0 2))))").unwrap();
    let tape = Tape::new(std::slice::from_ref(&e), 2, 1, &[]).unwrap();
    std::thread::scope(|s| {
        for k in 0..4 {
            let tape = tape.clone();
            let e = &e;
            s.spawn(move || {
                for i in 0..COMPILE_AFTER / 2 {
                    let q = [0.001 * f64::from(i), 0.1 * f64::from(k)];
                    let v = tape.eval_scalar(&q, &[0.3], 0.0);
                    assert!(same(v, e.eval(&q, &[0.3], 0.0, &[])));
                }
            });
        }
    });
    // Twice COMPILE_AFTER evaluations in all.
    assert_eq!(tape.backend(), native());
}

#[test]
fn where_compilation_fails_the_tape_stays_interpreted() {
    let e = Expr::parse("(* (cos q0) (+ q1 qdot0))").unwrap();
    let tape = Tape::new(std::slice::from_ref(&e), 2, 1, &[]).unwrap();
    assert_eq!(
        tape.compile_native_for_unsupported_host(),
        Backend::Interpreter
    );
    // Compilation is tried once: neither asking again nor more evaluations retry it.
    assert_eq!(tape.compile_native(), Backend::Interpreter);
    for i in 0..2 * COMPILE_AFTER {
        let q = [0.01 * f64::from(i), 0.5];
        assert!(same(
            tape.eval_scalar(&q, &[0.25], 0.0),
            e.eval(&q, &[0.25], 0.0, &[])
        ));
    }
    assert_eq!(tape.backend(), Backend::Interpreter);
}

/// Hénon–Heiles as the Python `HamiltonianEngine` hands SymPy's expression over.
const HENON_HEILES: &str = "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* 0.5 (^ q0 2)) \
     (* 0.5 (^ q1 2)) (* (^ q0 2) q1) (* -0.3333333333333333 (^ q1 3)))";

/// A pendulum whose momentum couples to the second coordinate: not separable.
const COUPLED: &str = "(+ (* 0.5 (^ p0 2)) (* 0.5 (^ p1 2)) (* -1 (cos q0)) (* 0.5 (^ q1 2)) \
     (* 0.1 p0 (sin q1)))";

/// Every state and energy of two runs in the same bits.
fn assert_same_run(a: &SimulationResult, b: &SimulationResult, method: Method) {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let (ya, yb) = (a.y.as_slice().unwrap(), b.y.as_slice().unwrap());
    assert_eq!(bits(ya), bits(yb), "{method:?}: states");
    let (ea, eb) = (a.energy.as_ref().unwrap(), b.energy.as_ref().unwrap());
    assert_eq!(
        bits(ea.as_slice().unwrap()),
        bits(eb.as_slice().unwrap()),
        "{method:?}: energies"
    );
}

#[test]
fn whole_runs_native_and_interpreted_end_in_the_same_bits() {
    let cases = [
        (HENON_HEILES, Method::Yoshida4),
        (HENON_HEILES, Method::Verlet),
        (COUPLED, Method::Rk4),
        (COUPLED, Method::ImplicitMidpoint),
    ];
    for (text, method) in cases {
        let build = || {
            ExprHamiltonian::new(
                Expr::parse(text).unwrap(),
                2,
                vec![],
                &[0.1, 0.2],
                &[0.5, 0.0],
            )
            .unwrap()
        };
        let (mut a, mut b) = (build(), build());
        assert_eq!(a.compile_native(), native());
        assert_eq!(
            b.compile_native_for_unsupported_host(),
            Backend::Interpreter
        );
        let ra = a.integrate((0.0, 20.0), 0.01, method).unwrap();
        let rb = b.integrate((0.0, 20.0), 0.01, method).unwrap();
        assert_same_run(&ra, &rb, method);
        assert_eq!(
            a.potential_energy(&[0.3, 0.4]).to_bits(),
            b.potential_energy(&[0.3, 0.4]).to_bits()
        );
    }
    let lorenz = || {
        let f = [
            "(* param0 (- y1 y0))",
            "(- (* y0 (- param1 y2)) y1)",
            "(- (* y0 y1) (* param2 y2))",
        ]
        .map(|s| Expr::parse(s).unwrap());
        let energy = Expr::parse("(+ (^ y0 2) (^ y1 2) (^ y2 2))").unwrap();
        ExprOde::new(
            f.to_vec(),
            vec![10.0, 28.0, 8.0 / 3.0],
            &[1.0, 1.0, 1.0],
            Some(energy),
        )
        .unwrap()
    };
    let (mut a, mut b) = (lorenz(), lorenz());
    assert_eq!(a.compile_native(), native());
    assert_eq!(
        b.compile_native_for_unsupported_host(),
        Backend::Interpreter
    );
    for method in [Method::Rk4, Method::ImplicitMidpoint] {
        // Chaotic: any difference in one bit would grow to O(1) over these 2000 steps.
        let ra = a.integrate((0.0, 2.0), 0.001, method).unwrap();
        let rb = b.integrate((0.0, 2.0), 0.001, method).unwrap();
        assert_same_run(&ra, &rb, method);
    }
    assert_eq!(a.state(), b.state());
}

#[test]
fn tapes_and_expression_systems_stay_send_sync_and_clone() {
    fn check<T: Send + Sync + Clone>() {}
    check::<Tape>();
    check::<ExprHamiltonian>();
    check::<ExprOde>();
}
