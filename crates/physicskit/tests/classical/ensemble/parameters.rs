//! Members built by a closure from named parameters (`FromParameters`, how the SymPy engines'
//! expression systems run as ensembles): each member equal to the system built alone from its
//! numbers, the same bits on any thread count, its chaos reduction equal to the single-orbit
//! call (tangent dynamics by automatic differentiation), and the refusals.

use physicskit::classical::analysis::lyapunov::max_lyapunov;
use physicskit::classical::ensemble::{
    self, EnsembleResult, FromParameters, Members, Plan, Reduction, Sweep,
};
use physicskit::classical::model::erased::{DynSystem, Ode};
use physicskit::classical::model::Value;
use physicskit::classical::symbolic::{Expr, ExprOde};
use physicskit::classical::{Error, IntegrateOptions, Method, Result};

/// The Lorenz system `(sigma, rho, beta)` as expressions.
const LORENZ: [&str; 3] = [
    "(* param0 (- y1 y0))",
    "(- (* y0 (- param1 y2)) y1)",
    "(- (* y0 y1) (* param2 y2))",
];

/// Lorenz at `params` from `state`, as the Python `ODEEngine` builds it.
fn lorenz(params: &[f64], state: &[f64]) -> Result<Box<dyn DynSystem>> {
    let f = LORENZ
        .iter()
        .map(|s| Expr::parse(s))
        .collect::<Result<_>>()?;
    Ok(Box::new(Ode(ExprOde::new(
        f,
        params.to_vec(),
        state,
        None,
    )?)))
}

fn params() -> Vec<(String, f64)> {
    vec![
        ("sigma".into(), 10.0),
        ("rho".into(), 28.0),
        ("beta".into(), 8.0 / 3.0),
    ]
}

/// 20 members (a full chunk and a partial one): `rho` from 0.5 (a stable fixed point) to 28
/// (chaos), each from its own state.
fn members() -> Members {
    let n = 20;
    let rho = (0..n).map(|i| 0.5 + 27.5 * i as f64 / 19.0).collect();
    let states = (0..n)
        .flat_map(|i| [1.0, 1.0 + 0.01 * i as f64, 1.0])
        .collect();
    Members {
        sweeps: vec![Sweep::new("rho", rho)],
        states: Some(states),
        n,
        ..Members::default()
    }
}

fn plan(threads: Option<usize>) -> Plan {
    Plan {
        t_span: (0.0, 5.0),
        dt: 0.005,
        method: Some(Method::Rk4),
        stride: None,
        reductions: vec![
            Reduction::MaxEnergyError,
            Reduction::MaxLyapunov {
                renormalize_every: 10,
            },
        ],
        final_state: true,
        threads,
        tolerances: None,
    }
}

fn run(threads: Option<usize>) -> EnsembleResult {
    let m = members();
    let source = FromParameters::new(params(), vec![1.0, 1.0, 1.0], &m, lorenz).unwrap();
    ensemble::run_source(&source, &plan(threads), None).unwrap()
}

fn bits(r: &EnsembleResult) -> Vec<u64> {
    r.final_state
        .iter()
        .chain(r.reductions.iter().flat_map(|(_, a)| a.iter()))
        .map(|x| x.to_bits())
        .collect()
}

#[test]
fn members_equal_the_system_built_alone_bit_for_bit() {
    let out = run(None);
    let m = members();
    let p = plan(None);
    // Something to compare: rho = 0.5 decays to the origin (exponent about -0.48, the
    // origin's largest eigenvalue), rho = 28 is chaotic (about +0.9): only the signs are
    // asked of a finite-time estimate at t = 5.
    let lyapunov = &out.reductions[1].1;
    assert!(lyapunov[0] < 0.0 && lyapunov[19] > 0.0, "{lyapunov:?}");
    for i in [0, 7, 16, 19] {
        let state = &m.states.as_ref().unwrap()[3 * i..3 * i + 3];
        let alone = || lorenz(&[10.0, m.sweeps[0].values[i], 8.0 / 3.0], state).unwrap();
        let mut single = alone();
        let r = single
            .integrate(p.t_span, p.dt, Method::Rk4, IntegrateOptions::default())
            .unwrap();
        assert_eq!(
            out.final_state.row(i),
            r.y.row(r.y.nrows() - 1),
            "member {i}"
        );
        // Without an energy expression the energy is NaN, and so is its error, in both.
        assert!(out.reductions[0].1[i].is_nan());
        let single = max_lyapunov(&mut *alone(), p.t_span, p.dt, Some(Method::Rk4), 10).unwrap();
        assert_eq!(lyapunov[i], single.exponents[0], "member {i}");
    }
}

#[test]
fn one_two_and_three_threads_give_the_same_bits() {
    let one = bits(&run(Some(1)));
    for threads in [2, 3] {
        assert_eq!(one, bits(&run(Some(threads))), "{threads} threads");
    }
}

#[test]
fn common_values_replace_the_given_ones() {
    let m = Members {
        common: vec![("sigma".into(), Value::Scalar(3.0))],
        states: None,
        n: 1,
        ..Members::default()
    };
    let source = FromParameters::new(params(), vec![1.0, 2.0, 3.0], &m, lorenz).unwrap();
    let out = ensemble::run_source(&source, &plan(None), None).unwrap();
    let mut alone = lorenz(&[3.0, 28.0, 8.0 / 3.0], &[1.0, 2.0, 3.0]).unwrap();
    let r = alone
        .integrate((0.0, 5.0), 0.005, Method::Rk4, IntegrateOptions::default())
        .unwrap();
    assert_eq!(out.final_state.row(0), r.y.row(r.y.nrows() - 1));
}

#[test]
fn bad_names_and_members_are_refused_before_any_work() {
    let p = plan(Some(1));
    let refuse = |m: &Members, given: Vec<(String, f64)>| match FromParameters::new(
        given,
        vec![1.0, 1.0, 1.0],
        m,
        lorenz,
    ) {
        Err(e) => e,
        Ok(source) => ensemble::run_source(&source, &p, None).unwrap_err(),
    };
    let mut m = members();
    m.sweeps[0].target = "r".into();
    let e = refuse(&m, params()).to_string();
    assert!(
        e.contains("no such parameter") && e.contains("sigma, rho, beta"),
        "{e}"
    );
    let e = refuse(&m, vec![]).to_string();
    assert!(e.contains("no parameters"), "{e}");
    let twice = vec![("rho".into(), 1.0), ("rho".into(), 2.0)];
    assert!(refuse(&members(), twice)
        .to_string()
        .contains("two parameters"));
    let mut m = members();
    m.states.as_mut().unwrap().pop();
    assert!(matches!(
        refuse(&m, params()),
        Error::DimensionMismatch {
            expected: 60,
            found: 59,
            ..
        }
    ));
    let mut m = members();
    m.common = vec![("rho".into(), Value::Vector(vec![1.0]))];
    assert!(refuse(&m, params()).to_string().contains("real number"));
    // A swept value or a state that is not finite: named by member and parameter.
    let mut m = members();
    m.sweeps[0].values[13] = f64::NAN;
    let e = refuse(&m, params());
    assert!(
        matches!(&e, Error::InvalidParameter { name, .. } if name == "member 13: rho"),
        "{e}"
    );
    let mut m = members();
    m.states.as_mut().unwrap()[3 * 17 + 2] = f64::INFINITY;
    let e = refuse(&m, params()).to_string();
    assert!(e.contains("member 17"), "{e}");
}
