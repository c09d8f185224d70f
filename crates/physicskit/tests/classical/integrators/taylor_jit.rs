//! The Taylor recurrences compiled to machine code (feature `jit`) against the interpreter:
//! every recurrence and the expression forms of Kepler, Hénon–Heiles and the double pendulum
//! (Hamiltonian and Lagrangian) bit for bit at every order, whole runs bit for bit, and the
//! lazy compilation. Without the feature the recurrences are always interpreted, which the
//! tests then check instead (`fixtures::native`).

use physicskit::classical::integrators::taylor::{integrate_taylor, order_for, TaylorField, LANES};
use physicskit::classical::symbolic::{Backend, Expr, ExprOde, TaylorProgram};
use physicskit::classical::systems::DoublePendulumParams;
use physicskit::classical::Tolerances;

use super::taylor::{
    double_pendulum_expr, double_pendulum_lagrangian, henon_heiles_expr, kepler_expr, kepler_state,
    RECURRENCES,
};
use crate::fixtures::{avx_code, native, pseudo_random, same};

/// The systems: every recurrence as the ODE `y0' = f(y1)`, `y1' = 1`, and the four
/// mechanical expression forms, each with a point to expand at and the spread of the
/// pseudo-random states around it.
pub(crate) fn programs() -> Vec<(String, TaylorProgram, Vec<f64>, f64)> {
    let mut out = Vec::new();
    for (text, x0) in RECURRENCES {
        let f = Expr::parse(text).unwrap();
        let y0 = vec![0.25, x0];
        let ode = ExprOde::new(vec![f, Expr::constant(1.0)], vec![], &y0, None).unwrap();
        // A spread of 0.1 keeps every point inside its function's domain.
        out.push((text.to_string(), TaylorProgram::ode(&ode).unwrap(), y0, 0.1));
    }
    let params = DoublePendulumParams::default();
    let mechanical = [
        (
            "Kepler",
            TaylorProgram::hamiltonian(&kepler_expr()).unwrap(),
            kepler_state(0.0).to_vec(),
        ),
        (
            "Hénon–Heiles",
            TaylorProgram::hamiltonian(&henon_heiles_expr()).unwrap(),
            vec![0.0, 0.1, 0.4, 0.3],
        ),
        (
            "double pendulum (H)",
            TaylorProgram::hamiltonian(&double_pendulum_expr(params)).unwrap(),
            vec![2.0, 1.5, 0.3, -0.2],
        ),
        (
            "double pendulum (L)",
            TaylorProgram::lagrangian(&double_pendulum_lagrangian(params)).unwrap(),
            vec![2.0, 1.5, 0.3, -0.2],
        ),
    ];
    for (name, program, y0) in mechanical {
        out.push((name.to_string(), program, y0, 0.3));
    }
    out
}

/// A pseudo-random state within `spread` of `y0` in every component, drawn from `seed`.
fn near(y0: &[f64], spread: f64, seed: u64) -> Vec<f64> {
    pseudo_random(y0.len(), seed)
        .iter()
        .zip(y0)
        .map(|(r, y)| y + spread * (2.0 * r - 1.0))
        .collect()
}

/// Every order from 1 to 24 (each compiled on its own), at 10 pseudo-random states around each
/// system's point: the compiled coefficients are the interpreter's, bit for bit.
#[test]
fn compiled_coefficients_have_the_interpreters_bits() {
    for (name, program, y0, spread) in programs() {
        let interpreted = program.interpreted_only();
        let mut reference = interpreted.clone();
        let mut compiled = program;
        let dim = compiled.dim();
        for order in 1..=24 {
            assert_eq!(
                compiled.compile_native(order),
                native(),
                "{name}, order {order}"
            );
            assert_eq!(interpreted.backend(order), Backend::Interpreter);
            // The code written for AVX on such hosts, but for the pendulums, whose larger
            // orders take the compact form.
            if avx_code(1) && !name.starts_with("double pendulum") {
                assert!(compiled.written_for_avx(order), "{name}, order {order}");
            }
            for s in 0..10 {
                let y = near(&y0, spread, 97 * order as u64 + s);
                let t = 0.1 * s as f64;
                let mut want = vec![0.0; dim * (order + 1)];
                let mut got = want.clone();
                reference.coefficients(t, &y, order, &mut want).unwrap();
                compiled.coefficients(t, &y, order, &mut got).unwrap();
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    assert!(
                        same(*g, *w),
                        "{name}, order {order}, y = {y:?}, coefficient {i}: {g:e} vs {w:e}"
                    );
                }
                // The code written for AVX also writes the stepper's blocks: coefficient `k`
                // of row `i` in group `k`, lane `i % 4`, of block `i / 4`, zeros past the last
                // row; the interpreter leaves them to the stepper.
                let n1 = order + 1;
                let avx = compiled.written_for_avx(order);
                let (_, blocks) = compiled.expansion_in_blocks(t, &y, order).unwrap();
                assert_eq!(blocks.is_some(), avx, "{name}");
                if let Some(blocks) = blocks {
                    assert_eq!(blocks.len(), dim.div_ceil(LANES) * n1, "{name}");
                    for i in 0..dim.div_ceil(LANES) * LANES {
                        for k in 0..n1 {
                            let w = if i < dim { want[i * n1 + k] } else { 0.0 };
                            let g = blocks[i / LANES * n1 + k][i % LANES];
                            assert!(same(g, w), "{name}, order {order}, row {i}, order {k}");
                        }
                    }
                }
                let (_, none) = reference.expansion_in_blocks(t, &y, order).unwrap();
                assert!(none.is_none(), "{name}");
            }
        }
    }
}

/// The compact form (orders and sums as loops, what large programs are compiled to) and the
/// unrolled form, each forced on every system whatever its size, at every order from 1 to 24
/// and 3 pseudo-random states around each system's point: both give the interpreter's
/// coefficients, so each other's, bit for bit.
#[test]
fn compact_and_unrolled_forms_have_the_interpreters_bits() {
    for ((name, program, y0, spread), (_, twin, _, _)) in programs().into_iter().zip(programs()) {
        let mut reference = program.interpreted_only();
        let (mut compact, mut unrolled) = (program, twin);
        let dim = compact.dim();
        for order in 1..=24 {
            assert_eq!(
                compact.compile_native_compact(order),
                native(),
                "{name}, {order}"
            );
            assert_eq!(
                unrolled.compile_native_unrolled(order),
                native(),
                "{name}, {order}"
            );
            for s in 0..3 {
                let y = near(&y0, spread, 89 * order as u64 + s);
                let t = 0.3 * s as f64;
                let mut want = vec![0.0; dim * (order + 1)];
                let (mut a, mut b) = (want.clone(), want.clone());
                reference.coefficients(t, &y, order, &mut want).unwrap();
                compact.coefficients(t, &y, order, &mut a).unwrap();
                unrolled.coefficients(t, &y, order, &mut b).unwrap();
                for (i, ((a, b), w)) in a.iter().zip(&b).zip(&want).enumerate() {
                    assert!(
                        same(*a, *w) && same(*b, *w),
                        "{name}, order {order}, coefficient {i}: compact {a:e}, unrolled {b:e}, \
                         interpreted {w:e}"
                    );
                }
            }
        }
    }
}

/// Whole runs (Kepler over 10 orbits, Hénon–Heiles over t = 100, the double pendulum over
/// t = 10, at tolerances 1e-8 and 1e-15): every sample of the compiled run is the interpreted
/// run's, bit for bit. Where the compiled code writes the stepper's blocks of coefficients,
/// a series that is not finite stops its run as it stops the interpreted one (Kepler's at
/// the origin, `y' = y²`'s from `y = 1e200`).
#[test]
fn compiled_runs_have_the_interpreters_bits() {
    let params = DoublePendulumParams::default();
    let runs = [
        (
            TaylorProgram::hamiltonian(&kepler_expr()).unwrap(),
            kepler_state(0.0).to_vec(),
            20.0 * std::f64::consts::PI,
        ),
        (
            TaylorProgram::hamiltonian(&henon_heiles_expr()).unwrap(),
            vec![0.0, 0.1, 0.4, 0.3],
            100.0,
        ),
        (
            TaylorProgram::hamiltonian(&double_pendulum_expr(params)).unwrap(),
            vec![2.0, 1.5, 0.0, 0.0],
            10.0,
        ),
    ];
    for (k, (program, y0, t1)) in runs.into_iter().enumerate() {
        for tol in [1e-8, 1e-15] {
            let tolerances = Tolerances::new(tol, tol).unwrap();
            let mut interpreted = program.interpreted_only();
            let mut compiled = program.clone();
            let order = order_for(&tolerances, &program.step_cost());
            assert_eq!(compiled.compile_native(order), native());
            // Kepler and Hénon–Heiles by the code written for AVX, which writes the
            // stepper's blocks itself (the interpreted run's are transposed by the stepper).
            if avx_code(1) && k < 2 {
                assert!(compiled.written_for_avx(order), "run {k}");
            }
            let a =
                integrate_taylor(&mut interpreted, &y0, (0.0, t1), t1 / 50.0, tolerances).unwrap();
            let b = integrate_taylor(&mut compiled, &y0, (0.0, t1), t1 / 50.0, tolerances).unwrap();
            assert_eq!(a.extra_scalar("steps"), b.extra_scalar("steps"));
            for (x, y) in a.y.iter().zip(b.y.iter()) {
                assert!(same(*x, *y), "run {k}, tol {tol:e}: {x:e} vs {y:e}");
            }
        }
    }
    let tolerances = Tolerances::new(1e-12, 1e-12).unwrap();
    let blow_up = ExprOde::new(vec![Expr::parse("(^ q0 2)").unwrap()], vec![], &[1.0], None);
    let failing = [
        (
            TaylorProgram::hamiltonian(&kepler_expr()).unwrap(),
            vec![0.0, 0.0, 1.0, 0.0],
        ),
        // `y^[1] = y²` overflows.
        (TaylorProgram::ode(&blow_up.unwrap()).unwrap(), vec![1e200]),
    ];
    for (program, y0) in failing {
        let order = order_for(&tolerances, &program.step_cost());
        let mut interpreted = program.interpreted_only();
        let mut compiled = program;
        assert_eq!(compiled.compile_native(order), native());
        if avx_code(1) {
            assert!(compiled.written_for_avx(order));
        }
        let a = integrate_taylor(&mut interpreted, &y0, (0.0, 2.0), 0.5, tolerances).unwrap_err();
        let b = integrate_taylor(&mut compiled, &y0, (0.0, 2.0), 0.5, tolerances).unwrap_err();
        assert_eq!(a.to_string(), b.to_string());
        assert!(b.to_string().contains("not finite"), "{b}");
    }
}

/// The recurrences of an order are compiled by the expansion after the
/// `TaylorProgram::COMPILE_AFTER`-th, not before; clones share the code; an order compiled leaves the
/// others interpreted; an order above the highest is refused by the expansion, never compiled.
#[test]
fn recurrences_are_compiled_after_the_threshold() {
    let mut program = TaylorProgram::hamiltonian(&kepler_expr()).unwrap();
    let clone = program.clone();
    let y = kepler_state(0.0);
    let order = 12;
    let mut c = vec![0.0; 4 * (order + 1)];
    for _ in 0..TaylorProgram::COMPILE_AFTER {
        program.coefficients(0.0, &y, order, &mut c).unwrap();
    }
    assert_eq!(program.backend(order), Backend::Interpreter);
    program.coefficients(0.0, &y, order, &mut c).unwrap();
    assert_eq!(program.backend(order), native());
    assert_eq!(clone.backend(order), native());
    assert_eq!(program.backend(order + 1), Backend::Interpreter);
    assert_eq!(program.compile_native(25), Backend::Interpreter);
    let mut c25 = vec![0.0; 4 * 26];
    assert!(program.coefficients(0.0, &y, 25, &mut c25).is_err());
}
