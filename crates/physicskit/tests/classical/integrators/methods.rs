//! The method table: each entry's declared facts against its own data and against what a run
//! measures, and the dispatch from a method to its loop. Everything iterates the registry, so
//! a new method is checked here without editing this file.

use crate::fixtures::{LagrangianPendulum, NonSeparable, Scalar};
use physicskit::classical::core::method::Scheme;
use physicskit::classical::examples::Pendulum;
use physicskit::classical::integrators::splitting::Coefficients;
use physicskit::classical::integrators::{AdaptiveStepper, Dispatch, FieldStepper};
use physicskit::classical::symbolic::{Expr, ExprHamiltonian, ExprOde};
use physicskit::classical::{
    methods, Error, HamiltonianSystem, LagrangianSystem, Method, OdeSystem, Phase, Result,
    SimulationResult,
};

#[test]
fn names_round_trip_through_from_str() {
    for info in methods() {
        let method: Method = info.name.parse().unwrap();
        assert_eq!(method.info(), info, "{}", info.name);
        assert_eq!(method.to_string(), info.name);
    }
    // The names are distinct, so each parses to one method only.
    for (i, a) in methods().iter().enumerate() {
        assert!(
            methods()[..i].iter().all(|b| b.name != a.name),
            "{}",
            a.name
        );
    }
}

#[test]
fn splitting_weights_sum_to_one_and_are_symmetric() {
    let mut splitting = 0;
    for method in Method::ALL {
        let info = method.info();
        let Scheme::Splitting { kicks, drifts } = info.scheme else {
            continue;
        };
        splitting += 1;
        // A splitting method integrates only H = T(p) + V(q), is symplectic, and its kicks and
        // its drifts each add up to one step. Each weight is rounded once (the completing one
        // of a published set a few times), so a sum is within a few roundings per weight of 1
        // in the largest weight's ulp.
        assert!(info.separable_only && info.symplectic, "{method}");
        assert_eq!(kicks.len(), drifts.len() + 1, "{method}");
        for (what, weights) in [("kicks", kicks), ("drifts", drifts)] {
            let sum: f64 = weights.iter().sum();
            let largest = weights.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
            let tolerance = 2.0 * weights.len() as f64 * f64::EPSILON * largest;
            assert!(
                (sum - 1.0).abs() <= tolerance,
                "{method}: {what} sum to {sum}"
            );
            // The methods are symmetric (time-reversible, even order): the weights read the
            // same backwards, bit for bit.
            assert!(
                weights
                    .iter()
                    .zip(weights.iter().rev())
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "{method}: {what} not symmetric: {weights:?}"
            );
        }
    }
    assert!(splitting > 0, "no splitting method in the table");
}

#[test]
fn only_splitting_methods_are_separable_only() {
    for method in Method::ALL {
        let info = method.info();
        let splitting = matches!(info.scheme, Scheme::Splitting { .. });
        assert_eq!(info.separable_only, splitting, "{method}");
    }
}

/// Where the dispatch sent a method: its kind, the method it was told, and the kick and drift
/// weights (bits) or the stepper type.
#[derive(Debug, Clone, PartialEq)]
enum Route {
    Splitting(Method, Vec<u64>),
    Explicit(Method, &'static str),
    Implicit(Method, &'static str),
    Adaptive(Method, &'static str),
}

struct Probe;

impl Dispatch for Probe {
    type Output = Route;

    fn splitting<const N: usize>(self, method: Method, weights: Coefficients<N>) -> Route {
        let all = weights.kicks.iter().chain(&weights.drifts);
        let bits = all.chain([&weights.last_kick]).map(|w| w.to_bits());
        Route::Splitting(method, bits.collect())
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Route {
        Route::Explicit(method, std::any::type_name::<St>())
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Route {
        Route::Implicit(method, std::any::type_name::<St>())
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Route {
        Route::Adaptive(method, std::any::type_name::<St>())
    }
}

#[test]
fn every_method_is_dispatched_to_its_own_path() {
    let mut paths = Vec::new();
    for method in Method::ALL {
        let route = method.dispatch(Probe);
        // The kind the registry dispatched on is the one the method's file declares, with the
        // file's own coefficients.
        let path = match (&route, method.info().scheme) {
            (Route::Splitting(m, bits), Scheme::Splitting { kicks, drifts }) if *m == method => {
                let (last, first) = kicks.split_last().unwrap();
                let declared: Vec<u64> = first
                    .iter()
                    .chain(drifts)
                    .chain([last])
                    .map(|w| w.to_bits())
                    .collect();
                assert_eq!(bits, &declared, "{method}");
                format!("splitting {bits:?}")
            }
            (Route::Explicit(m, stepper), Scheme::ExplicitRk) if *m == method => {
                format!("explicit {stepper}")
            }
            (Route::Implicit(m, stepper), Scheme::ImplicitRk) if *m == method => {
                format!("implicit {stepper}")
            }
            (Route::Adaptive(m, stepper), Scheme::Adaptive | Scheme::Taylor) if *m == method => {
                format!("adaptive {stepper}")
            }
            (route, scheme) => panic!("{method}: dispatched as {route:?}, declared {scheme:?}"),
        };
        // No two methods share a path (coefficients or stepper): none runs as another.
        assert!(
            !paths.contains(&path),
            "{method} runs on the path of another: {path}"
        );
        paths.push(path);
    }
}

/// Right-hand-side or force evaluations of a run, as its stepper reported them.
fn evaluations(result: &SimulationResult) -> f64 {
    result
        .extra_scalar("force_evaluations")
        .or_else(|| result.extra_scalar("rhs_evaluations"))
        .expect("every stepper reports its evaluations")
}

#[test]
fn each_method_spends_the_evaluations_it_declares() {
    // A pendulum at a small step, where the implicit solve takes its typical count. The count
    // tells most methods apart (1, 3, 7, 9, 10, 17, 35 for the splittings; 4 and ~2, ~4, ~6
    // for the others), so a method sent down another's loop
    // fails here even where its order would not give it away.
    let n = 10_000;
    let dt = 1e-3;
    for method in Method::ALL {
        let info = method.info();
        // A method that needs a Taylor form runs on the pendulum as an expression.
        let result = if method.needs_taylor_form() {
            expression_pendulum().integrate((0.0, n as f64 * dt), dt, method)
        } else {
            Pendulum::new(1.0, 0.0, 1.0)
                .unwrap()
                .integrate((0.0, n as f64 * dt), dt, method)
        }
        .unwrap();
        assert_eq!(result.method, info.name);
        if let Scheme::Taylor = info.scheme {
            // One Taylor expansion per step, each step far longer than dt.
            let steps = result.extra_scalar("steps").unwrap();
            assert_eq!(info.evaluations_per_step, 1, "{method}");
            assert!(
                steps > 0.0 && steps < n as f64 / 10.0,
                "{method}: {steps} steps"
            );
            continue;
        }
        let declared = f64::from(info.evaluations_per_step) * n as f64;
        let spent = evaluations(&result);
        println!("{method}: {} evaluations per step", spent / n as f64);
        match info.scheme {
            // The first force of the run is evaluated once more; after that, first same as last.
            Scheme::Splitting { .. } => assert_eq!(spent, declared + 1.0, "{method}"),
            Scheme::ExplicitRk => assert_eq!(spent, declared, "{method}"),
            // Typical count: the solve's first step adds an explicit evaluation and a few steps
            // may take a third sweep; 0.5% over the declared count allows 50 of those in 1e4
            // steps (measured for implicit_midpoint: 2.0001 per step).
            Scheme::ImplicitRk => {
                assert!(
                    spent >= declared && spent <= 1.005 * declared,
                    "{method}: {} evaluations per step, declared {}",
                    spent / n as f64,
                    info.evaluations_per_step
                );
            }
            // Per accepted step the declared 12, per rejected step 11, 2 to start; every
            // accepted step holds samples here (its steps are far longer than dt), so each
            // also pays the 3 evaluations of its dense output. Counted exactly.
            Scheme::Adaptive => {
                let accepted = result.extra_scalar("accepted_steps").unwrap();
                let rejected = result.extra_scalar("rejected_steps").unwrap();
                let per_step = f64::from(info.evaluations_per_step);
                assert!(accepted > 0.0 && accepted < n as f64 / 10.0, "{method}");
                assert_eq!(
                    spent,
                    2.0 + (per_step + 3.0) * accepted + (per_step - 1.0) * rejected,
                    "{method}"
                );
            }
            Scheme::Taylor => unreachable!("counted above"),
        }
    }
}

/// The pendulum `H = p^2/2 - cos q` from `(1, 0)` as an expression (it has a Taylor form).
fn expression_pendulum() -> ExprHamiltonian {
    let h = Expr::parse("(- (* 0.5 (^ p0 2)) (cos q0))").unwrap();
    ExprHamiltonian::new(h, 1, vec![], &[1.0], &[0.0]).unwrap()
}

/// `Ok` or the refusal a method not built for the family must give.
fn accepted(result: Result<SimulationResult>, method: Method) -> bool {
    match result {
        Ok(r) => {
            assert_eq!(r.method, method.name());
            true
        }
        Err(Error::UnsupportedMethod { method: name, .. }) => {
            assert_eq!(name, method.name());
            false
        }
        Err(e) => panic!("{method}: unexpected error {e}"),
    }
}

#[test]
fn each_family_accepts_exactly_the_methods_the_table_allows() {
    for method in Method::ALL {
        let general = !method.info().separable_only;
        // The fixtures' fields are hand-written: no Taylor form.
        let hand_written = !method.needs_taylor_form();
        let span = (0.0, 0.1);
        let separable = Pendulum::new(1.0, 0.0, 1.0)
            .unwrap()
            .integrate(span, 0.01, method);
        assert_eq!(
            accepted(separable, method),
            hand_written,
            "{method} on a separable system"
        );
        let non_separable = NonSeparable::new(0.5, 0.1).integrate(span, 0.01, method);
        assert_eq!(
            accepted(non_separable, method),
            general && hand_written,
            "{method}"
        );
        let lagrangian = LagrangianPendulum::new(0.5, 0.1).integrate(span, 0.01, method);
        assert_eq!(
            accepted(lagrangian, method),
            general && hand_written,
            "{method}"
        );
        let mut decay = Scalar {
            phase: Phase::new(vec![1.0], 0.0).unwrap(),
            f: |y| -y,
        };
        let ode = decay.integrate(span, 0.01, method);
        assert_eq!(accepted(ode, method), general && hand_written, "{method}");
        // Expression systems have a Taylor form: every method their family allows (the
        // splitting methods where the engine recognized `H = T(p) + V(q)`).
        let mut expr = expression_pendulum();
        let separable = expr.separable();
        let pendulum = expr.integrate(span, 0.01, method);
        assert_eq!(
            accepted(pendulum, method),
            separable || general,
            "{method} on an expression"
        );
        let mut expr_decay =
            ExprOde::new(vec![Expr::parse("(neg y0)").unwrap()], vec![], &[1.0], None).unwrap();
        let ode = expr_decay.integrate(span, 0.01, method);
        assert_eq!(accepted(ode, method), general, "{method} on an expression");
    }
}
