//! The Taylor recurrences for several states at once, one per vector lane (`TaylorLanes`),
//! against the interpreter run on each state alone: every recurrence and the expression
//! forms of Kepler, Hénon–Heiles and the double pendulum, at every order, bit for bit, in
//! 4, 8 and 16 lanes (each lane at its own state and time); and the batch stepper's members
//! against the registry's stepper on each alone.

use physicskit::classical::core::TimeGrid;
use physicskit::classical::integrators::taylor::TaylorField;
use physicskit::classical::integrators::taylor_batch::{integrate_batch, LanesField};
use physicskit::classical::integrators::TaylorStepper;
use physicskit::classical::symbolic::{Expr, ExprOde, TaylorProgram};
use physicskit::classical::{Error, Tolerances};

use super::taylor::henon_heiles_expr;
use crate::fixtures::{avx_code, native, pseudo_random, same};

/// The programs the compiled recurrences are tested on (every recurrence, and the
/// mechanical expression forms), and one in the time.
fn programs() -> Vec<(String, TaylorProgram, Vec<f64>, f64)> {
    let mut out = super::taylor_jit::programs();
    let text = "(* t (cos (* q1 q0)))";
    let y0 = vec![0.25, 0.3];
    let f = Expr::parse(text).unwrap();
    let ode = ExprOde::new(vec![f, Expr::constant(1.0)], vec![], &y0, None).unwrap();
    out.push((text.to_string(), TaylorProgram::ode(&ode).unwrap(), y0, 0.1));
    out
}

/// Orders 1 to 24, lanes at distinct pseudo-random states and times: each lane's
/// coefficients are the interpreter's at that lane's state, bit for bit.
fn lanes_equal_the_interpreter<const L: usize>() {
    for (name, program, y0, spread) in programs() {
        let mut reference = program.interpreted_only();
        let mut lanes = program.lanes::<L>();
        let dim = reference.dim();
        assert_eq!(LanesField::<L>::dim(&lanes), dim);
        for order in 1..=24 {
            let states: Vec<Vec<f64>> = (0..L)
                .map(|l| {
                    pseudo_random(dim, 131 * order as u64 + l as u64)
                        .iter()
                        .zip(&y0)
                        .map(|(r, y)| y + spread * (2.0 * r - 1.0))
                        .collect()
                })
                .collect();
            let t: [f64; L] = std::array::from_fn(|l| 0.1 * l as f64 - 0.2);
            let y: Vec<[f64; L]> = (0..dim)
                .map(|i| std::array::from_fn(|l| states[l][i]))
                .collect();
            lanes.expand(&t, &y, order).unwrap();
            let mut want = vec![0.0; dim * (order + 1)];
            let mut got = want.clone();
            for (l, state) in states.iter().enumerate() {
                reference
                    .coefficients(t[l], state, order, &mut want)
                    .unwrap();
                lanes.lane(l, &mut got);
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    assert!(
                        same(*g, *w),
                        "{name}, {L} lanes, order {order}, lane {l}, coefficient {i}: {g:e} vs {w:e}"
                    );
                }
            }
        }
    }
}

/// Orders 1 to 24, each compiled on its own (whatever the program's size), lanes at distinct
/// pseudo-random states and times: the compiled lanes' coefficients are the lanes
/// interpreter's, bit for bit (the state's coefficients, which every node's feed). The
/// default code (written for AVX where the host has it, else Cranelift's), or Cranelift's
/// alone.
fn compiled_lanes_equal_the_interpreted<const L: usize>(cranelift: bool) {
    for (name, program, y0, spread) in programs() {
        let dim = program.dim();
        let mut reference = program.lanes::<L>().interpreted_only();
        for order in 1..=24 {
            let mut compiled = program.lanes::<L>();
            if cranelift {
                compiled = compiled.cranelift_only();
            }
            assert_eq!(
                compiled.compile_native_any_size(order),
                native(),
                "{name}, {L} lanes, order {order}"
            );
            let t: [f64; L] = std::array::from_fn(|l| 0.3 - 0.07 * l as f64);
            let y: Vec<[f64; L]> = (0..dim)
                .map(|i| {
                    std::array::from_fn(|l| {
                        let r = pseudo_random(dim, 977 * order as u64 + l as u64)[i];
                        y0[i] + spread * (2.0 * r - 1.0)
                    })
                })
                .collect();
            reference.expand(&t, &y, order).unwrap();
            compiled.expand(&t, &y, order).unwrap();
            assert_eq!(compiled.backend(order), native());
            // The code written for AVX wherever the host has it, unless Cranelift's is asked
            // for.
            let avx = !cranelift && avx_code(L);
            assert_eq!(compiled.written_for_avx(order), avx, "{name}, {L} lanes");
            for (i, (g, w)) in compiled
                .coefficients()
                .iter()
                .zip(reference.coefficients())
                .enumerate()
            {
                for l in 0..L {
                    assert!(
                        same(g[l], w[l]),
                        "{name}, {L} lanes, order {order}, lane {l}, coefficient {i}: {:e} vs \
                         {:e}",
                        g[l],
                        w[l]
                    );
                }
            }
        }
    }
}

#[test]
fn compiled_four_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<4>(false);
}

#[test]
fn cranelifts_four_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<4>(true);
}

#[test]
fn compiled_eight_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<8>(false);
}

#[test]
fn cranelifts_eight_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<8>(true);
}

#[test]
fn compiled_sixteen_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<16>(false);
}

#[test]
fn cranelifts_sixteen_lanes_have_the_interpreters_bits() {
    compiled_lanes_equal_the_interpreted::<16>(true);
}

#[test]
fn four_lanes_have_the_interpreters_bits() {
    lanes_equal_the_interpreter::<4>();
}

#[test]
fn eight_lanes_have_the_interpreters_bits() {
    lanes_equal_the_interpreter::<8>();
}

#[test]
fn sixteen_lanes_have_the_interpreters_bits() {
    lanes_equal_the_interpreter::<16>();
}

/// Member outputs (`[member][step]`, empty where none was given) and failures (in the order
/// reported).
type BatchRun = (Vec<Vec<Vec<f64>>>, Vec<(usize, Error)>);

/// The members whose initial states are the rows of `starts` in a batch of `L` lanes on `grid`
/// at `tolerances`.
fn batch_run<const L: usize>(
    program: &TaylorProgram,
    starts: &[f64],
    grid: &TimeGrid,
    tolerances: Tolerances,
) -> BatchRun {
    let n = starts.len() / program.dim();
    let mut outputs = vec![vec![Vec::new(); grid.n_steps() + 1]; n];
    let mut failures = Vec::new();
    integrate_batch(
        &mut program.lanes::<L>(),
        starts,
        grid,
        tolerances,
        |m, step, y| outputs[m][step] = y.to_vec(),
        |m, e| failures.push((m, e)),
        || false,
    )
    .unwrap();
    (outputs, failures)
}

/// Each member of `run` against the registry's stepper alone from its row of `starts`, from
/// output to output as `integrate` drives it: every output the same bits; member `failing`
/// (if any) fails where its run alone fails, with its error (which `check` inspects), and
/// gives no output after; no other member fails.
fn batch_equals_runs_alone(
    program: &TaylorProgram,
    starts: &[f64],
    grid: &TimeGrid,
    tolerances: Tolerances,
    (outputs, failures): &BatchRun,
    failing: Option<usize>,
    check: impl Fn(&Error),
) {
    let (n, dim) = (outputs.len(), program.dim());
    let failed_members: Vec<usize> = failures.iter().map(|(m, _)| *m).collect();
    assert_eq!(
        failed_members,
        Vec::from_iter(failing),
        "{n} members: {failures:?}"
    );
    for (m, outputs) in outputs.iter().enumerate() {
        let mut alone = TaylorStepper::on(Box::new(program.clone()), tolerances, grid.t_end());
        let mut y = starts[dim * m..dim * (m + 1)].to_vec();
        let mut failed = false;
        for (step, got) in outputs.iter().enumerate().skip(1) {
            match alone.advance(grid.time(step - 1), &mut y, grid.dt()) {
                Err(want) if Some(m) == failing => {
                    check(&want);
                    assert_eq!(failures[0].1.to_string(), want.to_string(), "{n} members");
                    assert!(got.is_empty(), "an output after the failure");
                    failed = true;
                    break;
                }
                run => run.unwrap(),
            }
            assert!(
                got.iter().zip(&y).all(|(g, w)| same(*g, *w)),
                "{n} members, member {m}, step {step}: {got:?} vs {y:?}"
            );
        }
        assert_eq!(failed, Some(m) == failing, "{n} members, member {m}");
    }
}

/// Hénon–Heiles members in a batch over t = 50 with outputs every 0.5, in `L` lanes at `tol`:
/// every output of every member is the registry's stepper's alone, bit for bit, for member
/// counts below, at and above a multiple of the lanes (members take different numbers of
/// steps, so lanes finish at different times and take the next member); an escaping member
/// (E = 0.6, above the saddles' 1/6) fails with its own run's error, beside members that do
/// not.
fn batch_members_equal_their_runs_alone<const L: usize>(tol: f64) {
    let program = TaylorProgram::hamiltonian(&henon_heiles_expr()).unwrap();
    let tolerances = Tolerances::new(tol, tol).unwrap();
    let grid = TimeGrid::new((0.0, 50.0), 0.5).unwrap();
    let escaping = [0.0, 0.0, 0.8, 0.7];
    for n in [3, L, 2 * L + 1] {
        let mut starts: Vec<f64> = (0..n)
            .flat_map(|m| {
                let y = -0.2 + 0.4 * m as f64 / n as f64;
                let px = 0.1 - 0.2 * m as f64 / n as f64;
                let v = 0.5 * y * y - y * y * y / 3.0;
                let py = (2.0 * (0.12 - v) - px * px).sqrt();
                [0.0, y, px, py]
            })
            .collect();
        starts[4..8].copy_from_slice(&escaping);
        let run = batch_run::<L>(&program, &starts, &grid, tolerances);
        batch_equals_runs_alone(&program, &starts, &grid, tolerances, &run, Some(1), |e| {
            assert!(matches!(e, Error::StepSizeTooSmall { .. }), "{e}");
        });
    }
}

/// Four lanes (the plain or AVX2 loops) at the orders of tol 1e-12 and 1e-6.
#[test]
fn batch_members_in_four_lanes_equal_their_runs_alone() {
    batch_members_equal_their_runs_alone::<4>(1e-12);
    batch_members_equal_their_runs_alone::<4>(1e-6);
}

/// Sixteen lanes (the AVX-512 loops where the CPU has them) at tol 1e-14.
#[test]
fn batch_members_in_sixteen_lanes_equal_their_runs_alone() {
    batch_members_equal_their_runs_alone::<16>(1e-14);
}

/// A state of odd dimension (the state update takes the rows two at a time, and the last one
/// alone): Euler's equations of a free rigid body with moments of inertia (1, 2, 3), members
/// in 16 lanes over t = 20 with outputs every 0.25, each output the registry's stepper's
/// alone, bit for bit.
#[test]
fn batch_members_of_odd_dimension_equal_their_runs_alone() {
    let f = ["(neg (* q1 q2))", "(* q2 q0)", "(neg (/ (* q0 q1) 3))"]
        .map(|text| Expr::parse(text).unwrap());
    let y0 = [0.3, 1.0, 0.2];
    let ode = ExprOde::new(f.to_vec(), vec![], &y0, None).unwrap();
    let program = TaylorProgram::ode(&ode).unwrap();
    let tolerances = Tolerances::new(1e-12, 1e-12).unwrap();
    let grid = TimeGrid::new((0.0, 20.0), 0.25).unwrap();
    let n = 21;
    let starts: Vec<f64> = (0..n)
        .flat_map(|m| {
            let s = m as f64 / n as f64;
            [0.3 - 0.5 * s, 1.0 - 0.3 * s, 0.2 + 0.6 * s]
        })
        .collect();
    let run = batch_run::<16>(&program, &starts, &grid, tolerances);
    batch_equals_runs_alone(&program, &starts, &grid, tolerances, &run, None, |_| {});
}

/// `q0' = ln q1`, `q1' = -1` over t = 1 from `q1 = 2 + …` (the logarithm's argument stays
/// above 1), and member 3 from `q1 = -1`: its coefficients of `q0` above order 0 are NaN,
/// while the step rule's norms (NaN-free maxima) give an infinite radius, so only the check
/// for coefficients that are not finite stops it. In `L` lanes it fails with its own run's
/// error, at the clock its step started from, and the others give their runs' outputs.
fn a_member_with_coefficients_not_finite_fails_as_alone<const L: usize>() {
    let f = vec![Expr::parse("(ln q1)").unwrap(), Expr::constant(-1.0)];
    let ode = ExprOde::new(f, vec![], &[0.0, 2.0], None).unwrap();
    let program = TaylorProgram::ode(&ode).unwrap();
    let tolerances = Tolerances::new(1e-12, 1e-12).unwrap();
    let grid = TimeGrid::new((0.0, 1.0), 0.25).unwrap();
    let starts: Vec<f64> = (0..2 * L + 1)
        .flat_map(|m| {
            [
                0.1 * m as f64,
                if m == 3 { -1.0 } else { 2.0 + 0.1 * m as f64 },
            ]
        })
        .collect();
    let run = batch_run::<L>(&program, &starts, &grid, tolerances);
    batch_equals_runs_alone(&program, &starts, &grid, tolerances, &run, Some(3), |e| {
        assert!(e.to_string().contains("not finite"), "{e}");
        assert_eq!(*e, run.1[0].1, "{L} lanes");
    });
}

#[test]
fn a_member_with_coefficients_not_finite_fails_as_alone_in_four_and_sixteen_lanes() {
    a_member_with_coefficients_not_finite_fails_as_alone::<4>();
    a_member_with_coefficients_not_finite_fails_as_alone::<16>();
}
