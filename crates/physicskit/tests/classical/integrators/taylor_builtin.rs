//! `taylor` on the built-in systems: the Lagrangian ones have a Taylor form by tracing their
//! generic `L` (`symbolic/trace.rs`), whose field equals the system's own closed-form
//! `derivatives` at random states and whose runs follow dop853 at tight tolerance and keep the
//! energy; every other catalogue system refuses `taylor` by name; a Lagrangian that decides on
//! a value is refused naming the operation. Kepler's and Hénon–Heiles' Hamiltonians, written
//! once over any number type, trace into Taylor forms whose field is their hand-written force,
//! and the work–precision problems run `taylor` on all three.

use crate::fixtures::pseudo_random;
use physicskit::classical::analysis::work_precision::{double_pendulum_reference, Problem};
use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::integrators::Family;
use physicskit::classical::lagrangian::{Lagrangian, LagrangianModel, Scalar};
use physicskit::classical::model::DynSystem;
use physicskit::classical::symbolic::trace_lagrangian;
use physicskit::classical::symbolic::{TaylorProgram, TracedHamiltonian};
use physicskit::classical::systems::{HenonHeilesSystem, KeplerPerturbations, KeplerSystem};
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method,
    Tolerances,
};

/// Every catalogue entry built from its defaults, with its name.
fn catalogue() -> Vec<(&'static str, Box<dyn DynSystem>)> {
    SYSTEMS
        .iter()
        .map(|entry| (entry.name, entry.build_from([]).unwrap()))
        .collect()
}

fn lagrangian_systems() -> Vec<(&'static str, Box<dyn DynSystem>)> {
    let systems: Vec<_> = catalogue()
        .into_iter()
        .filter(|(_, s)| s.family() == Family::Lagrangian)
        .collect();
    // Double pendulum, coupled oscillators, elastic pendulum, hoop, symmetric top: a catalogue
    // that lost them would make the tests below vacuous.
    assert!(systems.len() >= 5, "{} Lagrangian systems", systems.len());
    systems
}

/// The traced Taylor form's field (its first-order coefficients `y^[1] = f(t, y)`) against
/// the system's own `derivatives` (closed forms: hand-derived accelerations) at random states
/// around the default start. Both are the Euler–Lagrange acceleration to rounding, computed
/// along different paths (symbolic derivatives of the traced `L` and elimination, against the
/// hand-derived solution); each is a few dozen operations of relative rounding 1.1e-16
/// amplified by the mass matrix's condition number (below 1e2 at these states), so they
/// agree to a few 1e-14 relative to the acceleration's scale: 1e-12 is that with a margin of
/// about 30, and a wrong term (a missing factor, a sign) is off by order one.
#[test]
fn the_traced_field_equals_the_hand_written_one() {
    for (name, system) in lagrangian_systems() {
        let dynamical = system.dynamical();
        let mut field = dynamical
            .taylor_field()
            .unwrap_or_else(|| panic!("{name}: no Taylor form"))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let y0 = dynamical.state().to_vec();
        let dim = y0.len();
        assert_eq!(field.dim(), dim, "{name}");
        for seed in 0..20 {
            let noise = pseudo_random(dim, 1000 + seed);
            // Within 0.05 (radians or metres) of the start: inside every system's domain (the
            // elastic pendulum's r > 0, the top's 0 < theta < pi).
            let y: Vec<f64> = y0.iter().zip(&noise).map(|(a, b)| a + 0.1 * b).collect();
            let t = 0.3;
            let mut own = vec![0.0; dim];
            dynamical.derivatives(t, &y, &mut own).unwrap();
            let mut coefficients = vec![0.0; 2 * dim];
            field.coefficients(t, &y, 1, &mut coefficients).unwrap();
            let scale = own.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
            for i in 0..dim {
                let traced = coefficients[2 * i + 1];
                assert!(
                    (traced - own[i]).abs() <= 1e-12 * scale,
                    "{name} seed {seed} component {i}: traced {traced} vs own {}",
                    own[i]
                );
            }
        }
    }
}

fn run(system: &mut dyn DynSystem, method: Method, span: f64, tol: f64) -> Vec<f64> {
    let y0 = system.dynamical().state().to_vec();
    system.reset(Some(&y0), 0.0).unwrap();
    let result = system
        .integrate(
            (0.0, span),
            span / 10.0,
            method,
            IntegrateOptions {
                tolerances: Some(Tolerances::new(tol, tol).unwrap()),
                ..IntegrateOptions::final_only()
            },
        )
        .unwrap_or_else(|e| panic!("{method}: {e}"));
    system.reset(Some(&y0), 0.0).unwrap();
    result.y.row(result.y.nrows() - 1).to_vec()
}

/// `taylor` at tolerance 1e-14 against dop853 at 1e-14 over 5 time units from each default
/// start, and its own energy (the Jacobi integral `p . qdot - L`, conserved: no Lagrangian
/// here depends on time). Each method's global error at 1e-14 is about 1e-12 of the state's
/// scale after 5 units (the double pendulum's largest Lyapunov exponent at its default start
/// is about 1/s, stretching the local errors of ~1e-14 by e^5 ~ 150), so the two agree to
/// 1e-10 with a margin of 100; a wrong force is off by order one. The energy of one run to
/// 1e-14 drifts by the sum of its steps' errors, a few hundred steps of ~1e-15 relative:
/// 1e-11 of the energy's scale bounds it by more than 10x.
#[test]
fn taylor_follows_dop853_and_keeps_the_energy_on_every_lagrangian_system() {
    for (name, mut system) in lagrangian_systems() {
        let span = 5.0;
        let taylor = run(system.as_mut(), Method::Taylor, span, 1e-14);
        let dop853 = run(system.as_mut(), Method::Dop853, span, 1e-14);
        let scale = dop853.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        for (i, (a, b)) in taylor.iter().zip(&dop853).enumerate() {
            assert!(
                (a - b).abs() <= 1e-10 * scale,
                "{name} component {i}: taylor {a} vs dop853 {b}"
            );
        }
        let dynamical = system.dynamical();
        let e0 = dynamical.energy(dynamical.state());
        let e1 = dynamical.energy(&taylor);
        assert!(
            (e1 - e0).abs() <= 1e-11 * e0.abs().max(1.0),
            "{name}: energy {e0} -> {e1}"
        );
    }
}

/// The catalogue's `taylor_form` is what the built systems offer: an entry with one builds a
/// system with a Taylor form; every other has only a hand-written `f64` field, and `taylor` is
/// refused as unsupported, the reason naming the systems that have one (the Lagrangian ones
/// among them).
#[test]
fn the_systems_without_a_taylor_form_refuse_taylor_and_say_which_have_it() {
    let (mut refused, mut offered) = (0, 0);
    for entry in SYSTEMS {
        let name = entry.name;
        let mut system = entry.build_from([]).unwrap();
        if entry.taylor_form {
            assert!(system.dynamical().taylor_field().is_some(), "{name}");
            offered += 1;
            continue;
        }
        assert!(system.dynamical().taylor_field().is_none(), "{name}");
        let err = system
            .integrate((0.0, 1.0), 0.1, Method::Taylor, IntegrateOptions::default())
            .unwrap_err();
        let Error::UnsupportedMethod { method, reason } = &err else {
            panic!("{name}: {err}");
        };
        assert_eq!(method, "taylor", "{name}");
        assert!(reason.contains("Lagrangian"), "{name}: {reason}");
        refused += 1;
    }
    assert!(
        refused > 0 && offered > 0,
        "{refused} refused, {offered} offered"
    );
}

/// A Lagrangian whose code branches on a value (`|v|` written as a comparison) cannot be
/// traced: the trace is refused, naming the comparison, and so is its `taylor` run.
struct Branching;

impl Lagrangian for Branching {
    fn ndof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        let speed = if qdot[0] < D::from(0.0) {
            -qdot[0]
        } else {
            qdot[0]
        };
        speed * speed * 0.5 - q[0] * q[0] * 0.5
    }
}

#[test]
fn a_lagrangian_that_branches_on_a_value_is_refused() {
    let err = trace_lagrangian(&Branching).unwrap_err();
    let Error::UnsupportedMethod { method, reason } = &err else {
        panic!("{err}");
    };
    assert_eq!(method, "taylor");
    assert!(reason.contains("comparison"), "{reason}");
    let mut model = LagrangianModel::new(Branching, &[0.5], &[0.0]).unwrap();
    let err = model
        .integrate((0.0, 1.0), 0.1, Method::Taylor)
        .unwrap_err();
    assert!(err.to_string().contains("comparison"), "{err}");
}

/// A user's generic Lagrangian gets the Taylor form with no code of its own: a pendulum
/// `L = v²/2 + cos q` traced, against its closed form `qddot = -sin q` at a few angles (the
/// recurrences give `y^[1]` exactly as the field to rounding: 1e-15 is a few ulps of values
/// below 1).
struct Pendulum;

impl Lagrangian for Pendulum {
    fn ndof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
        qdot[0] * qdot[0] * 0.5 + q[0].cos()
    }
}

#[test]
fn a_users_generic_lagrangian_has_a_taylor_form() {
    let mut field = Pendulum.taylor_field().unwrap().unwrap();
    for q in [-2.0, -0.3, 0.0, 0.7, 3.0] {
        let mut c = vec![0.0; 4];
        field.coefficients(0.0, &[q, 0.2], 1, &mut c).unwrap();
        assert!((c[1] - 0.2).abs() <= 1e-15, "{c:?}");
        assert!((c[3] + f64::sin(q)).abs() <= 1e-15, "{q}: {c:?}");
    }
}

/// The traced form's field (`y^[1]`) against the hand-written `derivatives` (`q' = p/mu`,
/// `p' = F(q)` from the force) at 50 random states around `system`'s start (within 0.15 of it):
/// two computations of the same field in different operation orders, ~10 roundings of
/// quantities of the field's size, so they agree to a few 1e-16 relative to it; 1e-13 leaves a
/// margin of ~100, and a wrong term (a sign, a missing factor, a dropped perturbation) is off
/// by far more.
fn traced_field_matches<S: TracedHamiltonian + DynamicalSystem>(name: &str, system: &S) {
    // The system's own Taylor form (what `Method::Taylor` steps) is its traced H.
    let mut field = system
        .taylor_field()
        .expect("the system offers a Taylor form")
        .unwrap();
    let y0 = system.state().to_vec();
    let dim = y0.len();
    assert_eq!(field.dim(), dim, "{name}");
    for seed in 0..50 {
        let y: Vec<f64> = y0
            .iter()
            .zip(pseudo_random(dim, 2000 + seed))
            .map(|(a, b)| a + 0.3 * b)
            .collect();
        let mut own = vec![0.0; dim];
        system.derivatives(0.0, &y, &mut own).unwrap();
        let mut c = vec![0.0; dim * 2];
        field.coefficients(0.0, &y, 1, &mut c).unwrap();
        let size = own.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        for (i, want) in own.iter().enumerate() {
            let got = c[2 * i + 1];
            assert!(
                (got - want).abs() <= 1e-13 * size,
                "{name} at {y:?}: component {i}: {got} against {want}"
            );
        }
    }
}

/// Kepler (the point mass, and with every perturbation: power law, post-Newtonian term,
/// softening, a reduced mass and coupling that are not 1) and Hénon–Heiles: their generic `H`
/// traces into a Taylor form whose field is the hand-written force's.
#[test]
fn the_traced_hamiltonians_equal_the_hand_written_force() {
    let perturbed = KeplerPerturbations::none()
        .with_power_law(0.3, 0.05)
        .with_post_newtonian(-0.01)
        .with_softening(0.1);
    for (name, pert) in [
        ("kepler", KeplerPerturbations::none()),
        ("perturbed kepler", perturbed),
    ] {
        let system = KeplerSystem::new(&[1.0, 0.2], &[0.1, 1.0], 1.3, 0.7, pert).unwrap();
        traced_field_matches(name, &system);
    }
    let henon = HenonHeilesSystem::new(&[0.1, -0.2], &[0.3, 0.2]).unwrap();
    traced_field_matches("henon_heiles", &henon);
}

/// The work–precision problems list `taylor` (each has a Taylor form) and run it: from
/// tolerance 1e-6 to 1e-10 its error falls on every problem (by at least 10: the error
/// follows the tolerance, 1e4 apart; a run that ignored it, or the wrong system, would not),
/// and each run reports its cost as evaluations, as the other methods do.
#[test]
fn the_work_precision_problems_run_taylor() {
    for problem in Problem::all(true) {
        assert!(
            problem.methods().contains(&Method::Taylor),
            "{}",
            problem.name()
        );
        let reference = match problem {
            Problem::DoublePendulum { t_end } => double_pendulum_reference(t_end).unwrap(),
            _ => Vec::new(),
        };
        let runs: Vec<(f64, f64)> = [1e-6, 1e-10]
            .iter()
            .map(|&tol| {
                let r = problem.run(Method::Taylor, tol).unwrap();
                let cost = r.extra_scalar("rhs_evaluations").unwrap();
                (problem.error(&r, &reference), cost)
            })
            .collect();
        println!(
            "{}: taylor (error, evaluations) at 1e-6, 1e-10: {runs:?}",
            problem.name()
        );
        assert!(runs[1].0 * 10.0 < runs[0].0, "{}: {runs:?}", problem.name());
        assert!(
            runs[0].1 > 0.0 && runs[1].1 > runs[0].1,
            "{}: {runs:?}",
            problem.name()
        );
    }
}

/// The catalogue's Kepler system runs `taylor` through the registry like any other method: 10
/// orbits of `a = 1`, `e = 0.5` from perihelion at `rtol = atol = 1e-14` end on the closed form
/// (Kepler's equation solved to rounding). The error grows with the phase error over ~63 time
/// units, ~1e-12 at this tolerance; 1e-10 leaves a margin of ~100, and a wrong field misses by
/// order one.
#[test]
fn the_catalogue_kepler_runs_taylor_to_its_closed_form() {
    let mut kepler =
        KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())
            .unwrap();
    let t1 = 10.0 * 2.0 * std::f64::consts::PI;
    let options = IntegrateOptions {
        tolerances: Some(Tolerances::new(1e-14, 1e-14).unwrap()),
        ..IntegrateOptions::final_only()
    };
    let r = kepler
        .integrate_with((0.0, t1), t1, Method::Taylor, options)
        .unwrap();
    let want = super::taylor::kepler_state(t1);
    let got = r.final_state();
    let err = got
        .iter()
        .zip(want)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(err < 1e-10, "error {err:e} after 10 orbits");
}

/// The nodes of a catalogue system's Taylor form (the program its `taylor` runs).
fn taylor_nodes(system: &dyn DynSystem) -> usize {
    let field = system.dynamical().taylor_field().unwrap().unwrap();
    TaylorProgram::from_field(&*field).unwrap().nodes()
}

/// Merging never makes a program larger: for every catalogue system with a Taylor form, its
/// program has at most the nodes of the same builder taking every sum and product as written
/// (`TaylorProgram::without_merging`), computed here from the same system. A merge that
/// rewrites a sum whose partial sums other expressions share (the elimination's rows of the
/// triple pendulum reuse each other's sums: 112 nodes merged against 104 as written) must not
/// be kept.
#[test]
fn merging_like_terms_never_grows_a_catalogue_program() {
    let mut checked = 0;
    for entry in SYSTEMS.iter().filter(|e| e.taylor_form) {
        let system = entry.build_from([]).unwrap();
        let merged = taylor_nodes(&*system);
        let written = TaylorProgram::without_merging(|| taylor_nodes(&*system));
        println!("{}: {merged} nodes, {written} without merging", entry.name);
        assert!(merged <= written, "{}: {merged} > {written}", entry.name);
        checked += 1;
    }
    // Double pendulum, coupled oscillators, elastic pendulum, hoop, heavy top, triple
    // pendulum, Kepler (two entries), Hénon–Heiles.
    assert!(checked >= 9, "{checked} systems with a Taylor form");
}

/// Kepler's `H` as the system writes it (`-k / r` with `r = √(x² + y²)`, traced) gives a
/// program no larger than its expression form `-(x² + y²)^-1/2` (13 nodes): the factors
/// `r^-1`, `r^-1` and `1/r` of the traced derivative are powers of `x² + y²` and merge into
/// its power -3/2. Without merging it has 18, so the comparison sees a builder that stops
/// merging powers.
#[test]
fn keplers_traced_program_is_as_small_as_its_expression_form() {
    let system = physicskit::classical::catalog::build("kepler", []).unwrap();
    let traced = taylor_nodes(&*system);
    let written = TaylorProgram::without_merging(|| taylor_nodes(&*system));
    let expression = TaylorProgram::hamiltonian(&super::taylor::kepler_expr())
        .unwrap()
        .nodes();
    println!("kepler: traced {traced} nodes ({written} without merging), expression {expression}");
    assert!(traced <= expression, "{traced} > {expression}");
    assert!(written > expression, "{written} <= {expression}");
}
