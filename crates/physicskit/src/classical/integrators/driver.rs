//! The drivers behind every `integrate`: validate, allocate once, loop, record.
//!
//! One generic loop (`Setup::run_from`) serves every method and family. It is monomorphized for each
//! system and stepper, so no trait object is called in a step (the SIMD clones of long slice
//! loops and of the trig are reached through one cached function pointer each, see
//! `core/trig.rs`); the observer (progress bar, Ctrl-C) is consulted every few thousand steps
//! only.

use std::cell::Cell;
use std::collections::BTreeMap;
use std::ops::ControlFlow;

use super::field::{Canonical, FirstOrder, VectorField};
use super::implicit_midpoint::ImplicitMidpoint;
use super::rk4::Rk4;
use super::splitting::{check_system, SplittingStepper};
use crate::classical::core::{
    error::check_finite, DynamicalSystem, Error, ExtraValue, HamiltonianSystem, IntegrateOptions,
    LagrangianSystem, Method, OdeSystem, Recorder, Result, SimulationResult, TimeGrid,
};

/// Integrates a Hamiltonian system (see [`HamiltonianSystem::integrate`]).
///
/// # Errors
/// See [`HamiltonianSystem::integrate`].
pub fn integrate_hamiltonian<S: HamiltonianSystem>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Method,
    options: IntegrateOptions<'_>,
) -> Result<SimulationResult> {
    let ndof = system.ndof();
    let setup = Setup::new(&*system, t_span, dt, Some(ndof), &options)?;
    match method {
        Method::Verlet => {
            integrate_splitting(system, setup, method, options, super::verlet::DRIFTS)
        }
        Method::Yoshida4 => {
            integrate_splitting(system, setup, method, options, super::yoshida4::DRIFTS)
        }
        Method::Rk4 | Method::ImplicitMidpoint => {
            integrate_first_order(system, setup, method, options)
        }
    }
}

/// Integrates a Lagrangian system (see [`LagrangianSystem::integrate`]).
///
/// `implicit_midpoint` runs on the canonical state `[q, p]` and converts each stored sample back
/// to `[q, qdot]`; `rk4` runs on `[q, qdot]`.
///
/// # Errors
/// See [`LagrangianSystem::integrate`].
pub fn integrate_lagrangian<S: LagrangianSystem>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Method,
    options: IntegrateOptions<'_>,
) -> Result<SimulationResult> {
    let ndof = system.ndof();
    let setup = Setup::new(&*system, t_span, dt, Some(ndof), &options)?;
    match method {
        Method::Rk4 => integrate_first_order(system, setup, method, options),
        Method::ImplicitMidpoint => {
            let sys = &*system;
            // Canonical start: p = dL/dqdot at (q0, qdot0).
            let initial = setup.start.clone();
            let mut work = initial.clone();
            sys.momentum(
                &initial[..ndof],
                &initial[ndof..],
                setup.grid.t0(),
                &mut work[ndof..],
            )?;
            // The first sample is the initial state as given: converting qdot -> p -> qdot
            // would change its last bits.
            let mut first = Some(initial);
            let field = Canonical(sys);
            let mut stepper = ImplicitMidpoint::new(2 * ndof);
            let (result, y) = setup.run_from(
                work,
                method,
                options,
                |t, y, _| stepper.step(&field, t, y, dt),
                |recorder: &mut Recorder, t: f64, y: &[f64]| {
                    let energy = recorder.stores_energy();
                    recorder.push_with(t, |out| {
                        if let Some(initial) = first.take() {
                            out.copy_from_slice(&initial);
                        } else {
                            let (q, p) = y.split_at(ndof);
                            out[..ndof].copy_from_slice(q);
                            sys.velocity(q, p, t, &mut out[ndof..])?;
                        }
                        Ok(if energy { sys.energy(out) } else { 0.0 })
                    })
                },
            )?;
            let stats = stepper.stats();
            finish(system, result, &y, |extra| solver_extras(extra, &stats))
        }
        Method::Verlet | Method::Yoshida4 => Err(Error::UnsupportedMethod {
            method: method.name().into(),
            reason: "Lagrangian systems are integrated in canonical form, which is not \
                     separable in general; use implicit_midpoint (symplectic) or rk4"
                .into(),
        }),
    }
}

/// Integrates a general ODE system (see [`OdeSystem::integrate`]).
///
/// # Errors
/// See [`OdeSystem::integrate`].
pub fn integrate_ode<S: OdeSystem>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Method,
    options: IntegrateOptions<'_>,
) -> Result<SimulationResult> {
    let setup = Setup::new(&*system, t_span, dt, None, &options)?;
    match method {
        Method::Rk4 | Method::ImplicitMidpoint => {
            integrate_first_order(system, setup, method, options)
        }
        Method::Verlet | Method::Yoshida4 => Err(Error::UnsupportedMethod {
            method: method.name().into(),
            reason: "a general ODE system has no separable Hamiltonian structure; use \
                     implicit_midpoint or rk4"
                .into(),
        }),
    }
}

/// A splitting method with `N` substeps (drift weights `drifts`), after checking that the
/// system is separable and conservative.
///
/// Systems of one or two degrees of freedom run with their state and force in fixed-length
/// arrays, which the compiler keeps in registers across substeps and steps: through a `Vec`
/// every kick waited for the previous substep's store to be forwarded to its load (the
/// projectile: 17.4 -> 7.6 ns/step, Hénon–Heiles 33.5 -> 30.1; Rust API, best of 9).
fn integrate_splitting<S: HamiltonianSystem, const N: usize>(
    system: &mut S,
    setup: Setup,
    method: Method,
    options: IntegrateOptions<'_>,
    drifts: [f64; N],
) -> Result<SimulationResult> {
    check_system(method, &*system)?;
    let ndof = system.ndof();
    match ndof {
        1 => {
            let work = setup.start_in([0.0; 2]);
            run_splitting(system, setup, method, options, drifts, [0.0; 1], work)
        }
        2 => {
            let work = setup.start_in([0.0; 4]);
            run_splitting(system, setup, method, options, drifts, [0.0; 2], work)
        }
        _ => {
            let mut setup = setup;
            let work = std::mem::take(&mut setup.start);
            run_splitting(
                system,
                setup,
                method,
                options,
                drifts,
                vec![0.0; ndof],
                work,
            )
        }
    }
}

/// The loop of [`integrate_splitting`] with the force cached in `force` and the state in
/// `work`.
#[allow(clippy::too_many_arguments)]
fn run_splitting<S, const N: usize, B, W>(
    system: &mut S,
    setup: Setup,
    method: Method,
    options: IntegrateOptions<'_>,
    drifts: [f64; N],
    force: B,
    work: W,
) -> Result<SimulationResult>
where
    S: HamiltonianSystem,
    B: AsRef<[f64]> + AsMut<[f64]>,
    W: AsRef<[f64]> + AsMut<[f64]>,
{
    let ndof = system.ndof();
    let dt = setup.grid.dt();
    let mut stepper = SplittingStepper::with_buffer(drifts, force);
    let sys = &*system;
    // The potential of the state a step leaves, where the system computes it with the force.
    let potential = Cell::new(None);
    let (result, y) = setup.run_from(
        work,
        method,
        options,
        |t, y, stored| {
            let (q, p) = y.split_at_mut(ndof);
            potential.set(stepper.step_with_potential(sys, t, q, p, dt, stored)?);
            Ok(())
        },
        StoreWithPotential {
            system: sys,
            potential: &potential,
        },
    )?;
    finish(system, result, &y, |extra| {
        extra.insert(
            "force_evaluations".into(),
            ExtraValue::Scalar(stepper.force_evaluations() as f64),
        );
    })
}

/// `rk4` or `implicit_midpoint` on the system's own first-order form.
fn integrate_first_order<S: DynamicalSystem>(
    system: &mut S,
    setup: Setup,
    method: Method,
    options: IntegrateOptions<'_>,
) -> Result<SimulationResult> {
    let sys = &*system;
    let field = FirstOrder(sys);
    let dt = setup.grid.dt();
    if method == Method::Rk4 {
        let mut stepper = Rk4::new(field.dim());
        let (result, y) = setup.run(
            method,
            options,
            |t, y, _| stepper.step(&field, t, y, dt),
            StoreAsIs(sys),
        )?;
        let evaluations = stepper.evaluations();
        finish(system, result, &y, |extra| {
            extra.insert(
                "rhs_evaluations".into(),
                ExtraValue::Scalar(evaluations as f64),
            );
        })
    } else {
        let mut stepper = ImplicitMidpoint::new(field.dim());
        let (result, y) = setup.run(
            method,
            options,
            |t, y, _| stepper.step(&field, t, y, dt),
            StoreAsIs(sys),
        )?;
        let stats = stepper.stats();
        finish(system, result, &y, |extra| solver_extras(extra, &stats))
    }
}

/// How the loop stores a sample of the working state: `store(recorder, t, y)` appends the
/// stored form of `y` and returns its stored energy (0 when energies are not stored).
///
/// A trait rather than a closure so the common case, [`StoreAsIs`], is forced inline into the
/// loop: as a call it cost ~40 instructions per sample of a 2-dof run. Closures (the
/// Lagrangian conversion to `[q, qdot]`) implement it too.
trait Sampler {
    fn store(&mut self, recorder: &mut Recorder, t: f64, y: &[f64]) -> Result<f64>;
}

/// Stores the working state as it is, with the system's energy.
struct StoreAsIs<'a, S: ?Sized>(&'a S);

impl<S: DynamicalSystem + ?Sized> Sampler for StoreAsIs<'_, S> {
    #[inline(always)]
    fn store(&mut self, recorder: &mut Recorder, t: f64, y: &[f64]) -> Result<f64> {
        let e = if recorder.stores_energy() {
            self.0.energy(y)
        } else {
            0.0
        };
        recorder.push(t, y, e);
        Ok(e)
    }
}

/// Stores the working state `[q, p]` of a Hamiltonian system with the energy
/// `kinetic_energy(p) + V`, `V` the potential the step's last force evaluation returned
/// ([`HamiltonianSystem::force_and_potential`]); with none, with `energy`.
struct StoreWithPotential<'a, S: ?Sized> {
    system: &'a S,
    potential: &'a Cell<Option<f64>>,
}

impl<S: HamiltonianSystem + ?Sized> Sampler for StoreWithPotential<'_, S> {
    #[inline(always)]
    fn store(&mut self, recorder: &mut Recorder, t: f64, y: &[f64]) -> Result<f64> {
        let e = if recorder.stores_energy() {
            match self.potential.take() {
                Some(v) => self.system.kinetic_energy(&y[self.system.ndof()..]) + v,
                None => self.system.energy(y),
            }
        } else {
            0.0
        };
        recorder.push(t, y, e);
        Ok(e)
    }
}

impl<F: FnMut(&mut Recorder, f64, &[f64]) -> Result<f64>> Sampler for F {
    #[inline(always)]
    fn store(&mut self, recorder: &mut Recorder, t: f64, y: &[f64]) -> Result<f64> {
        self(recorder, t, y)
    }
}

fn solver_extras(
    extra: &mut BTreeMap<String, ExtraValue>,
    stats: &super::implicit_midpoint::SolverStats,
) {
    let steps = stats.steps.max(1) as f64;
    for (name, value) in [
        ("rhs_evaluations", stats.evaluations as f64),
        ("jacobian_evaluations", stats.jacobians as f64),
        ("newton_steps", stats.newton_steps as f64),
        ("solver_iterations_max", stats.max_iterations as f64),
        ("solver_evaluations_mean", stats.evaluations as f64 / steps),
        ("solver_residual_max", stats.max_residual),
    ] {
        extra.insert(name.into(), ExtraValue::Scalar(value));
    }
}

/// Writes the final sample back into the system and adds the extras.
fn finish<S: DynamicalSystem>(
    system: &mut S,
    (mut result, t_end): (SimulationResult, f64),
    final_state: &[f64],
    add: impl FnOnce(&mut BTreeMap<String, ExtraValue>),
) -> Result<SimulationResult> {
    system.phase_mut().assign_unchecked(final_state, t_end);
    add(&mut result.extra);
    Ok(result)
}

/// Validated inputs and preallocated storage of one call.
struct Setup {
    grid: TimeGrid,
    recorder: Recorder,
    start: Vec<f64>,
}

impl Setup {
    fn new<S: DynamicalSystem + ?Sized>(
        system: &S,
        t_span: (f64, f64),
        dt: f64,
        ndof: Option<usize>,
        options: &IntegrateOptions<'_>,
    ) -> Result<Self> {
        let grid = TimeGrid::new(t_span, dt)?;
        options.sampling.validate()?;
        let start = system.state().to_vec();
        match ndof {
            // [q, p] or [q, qdot]: a system whose state and `ndof` disagree is refused here,
            // not left to index out of bounds in the loop.
            Some(ndof) if start.len() != 2 * ndof => {
                return Err(Error::DimensionMismatch {
                    name: "state".into(),
                    expected: 2 * ndof,
                    found: start.len(),
                });
            }
            _ => {}
        }
        check_finite("state", &start, grid.t0())?;
        let samples = options.sampling.count(grid.n_steps());
        let recorder = Recorder::new(samples, start.len(), ndof, !options.skip_energy)?;
        Ok(Self {
            grid,
            recorder,
            start,
        })
    }

    /// The validated initial state copied into `work` (of the state's length).
    fn start_in<W: AsMut<[f64]>>(&self, mut work: W) -> W {
        work.as_mut().copy_from_slice(&self.start);
        work
    }

    /// [`run_from`](Self::run_from) the validated initial state.
    fn run(
        mut self,
        method: Method,
        options: IntegrateOptions<'_>,
        step: impl FnMut(f64, &mut [f64], bool) -> Result<()>,
        sample: impl Sampler,
    ) -> Result<((SimulationResult, f64), Vec<f64>)> {
        let work = std::mem::take(&mut self.start);
        self.run_from(work, method, options, step, sample)
    }

    /// The loop: `step(t, y, stored)` advances the working state `y` by one step from `t`
    /// (`stored`: the new state is stored with its energy);
    /// `sample(recorder, t, y)` stores the stored form of `y` and returns its stored energy (0
    /// if energies are not stored). Returns the result, its final time and the final stored
    /// state.
    fn run_from<S2: Sampler, W: AsRef<[f64]> + AsMut<[f64]>>(
        self,
        mut work: W,
        method: Method,
        mut options: IntegrateOptions<'_>,
        mut step: impl FnMut(f64, &mut [f64], bool) -> Result<()>,
        mut sample: S2,
    ) -> Result<((SimulationResult, f64), Vec<f64>)> {
        let Setup {
            grid, mut recorder, ..
        } = self;
        let n = grid.n_steps();
        let sampling = options.sampling;
        let interval = options.observe_interval();
        // Per sample only the energy is checked (a scalar); the whole state is checked every
        // `interval` steps and at the end, and a blow-up is then reported at the first stored
        // sample that holds it.
        // A function, not a closure, so that it can be forced inline: as a call it cost ~40
        // instructions per sample of a 2-dof run.
        #[inline(always)]
        fn store<S2: Sampler>(
            recorder: &mut Recorder,
            t: f64,
            work: &[f64],
            sample: &mut S2,
        ) -> Result<()> {
            if sample.store(recorder, t, work)?.is_finite() {
                Ok(())
            } else {
                Err(Error::NonFinite {
                    name: "state".into(),
                    t,
                })
            }
        }
        let check = |recorder: &Recorder, work: &[f64], t: f64| {
            if work.iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(Error::NonFinite {
                    name: "state".into(),
                    t: recorder.first_non_finite().unwrap_or(t),
                })
            }
        };
        store(&mut recorder, grid.t0(), work.as_ref(), &mut sample)?;
        let mut next_stored = sampling.next_stored(0, n);
        let mut until_observe = interval;
        let energies = recorder.stores_energy();
        for i in 0..n {
            let done = i + 1;
            step(grid.time(i), work.as_mut(), energies && done == next_stored)?;
            let t = grid.time(done);
            if done == next_stored {
                store(&mut recorder, t, work.as_ref(), &mut sample)?;
                next_stored = sampling.next_stored(done, n);
            }
            until_observe -= 1;
            if until_observe == 0 {
                until_observe = interval;
                check(&recorder, work.as_ref(), t)?;
                if let Some(observer) = options.observer.as_deref_mut() {
                    if let ControlFlow::Break(()) = observer.observe(done, n, t) {
                        return Err(Error::Interrupted { t });
                    }
                }
            }
        }
        check(&recorder, work.as_ref(), grid.t_end())?;
        // Every sampling mode stores the final step.
        let last = recorder.last_row().to_vec();
        let mut extra = BTreeMap::new();
        extra.insert("n_steps".into(), ExtraValue::Scalar(n as f64));
        extra.insert("dt".into(), ExtraValue::Scalar(grid.dt()));
        Ok(((recorder.finish(method.name(), extra), grid.t_end()), last))
    }
}
