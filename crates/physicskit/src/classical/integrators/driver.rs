//! The drivers behind every `integrate`: validate, allocate once, dispatch, loop, record.
//!
//! Each system family has a driver ([`integrate_hamiltonian`], [`integrate_lagrangian`],
//! [`integrate_ode`]) that validates the inputs and hands a [`Dispatch`] to
//! [`Method::dispatch`], which calls the family's handler for the method's kind: a splitting
//! method, an explicit, an implicit or an adaptive method on a vector field. Each handler builds the
//! stepper and runs one generic loop (`Setup::run_from`) over a [`Stepper`]. The loop is
//! monomorphized for each system and stepper, so no trait object is called in a step (the SIMD
//! clones of long slice loops and of the trig are reached through one cached function pointer
//! each, see `core/trig.rs`); the observer (progress bar, Ctrl-C) is consulted every few
//! thousand steps only.

use std::collections::BTreeMap;
use std::ops::ControlFlow;

use super::field::{Canonical, FirstOrder, VectorField};
use super::splitting::{check_system, Coefficients, SplittingStepper};
use super::stepper::{splitting_refused, AdaptiveStepper, Dispatch, FieldStepper, Report, Stepper};
use crate::classical::core::{
    error::check_finite, Error, ExtraValue, Recorder, Result, SimulationResult, TimeGrid,
};
use crate::classical::integrators::options::check_adaptive;
use crate::classical::integrators::system::Family;
use crate::classical::integrators::{
    DynamicalSystem, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method, OdeSystem,
};

/// Integrates a Hamiltonian system (see [`HamiltonianSystem::integrate`]).
///
/// Splitting methods run on `[q, p]` with the force; the others on the system's first-order
/// form.
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
    let setup = Setup::new(&*system, t_span, dt, Some(ndof), method, &options)?;
    method.dispatch(Hamiltonian(Run {
        system,
        setup,
        options,
    }))
}

/// Integrates a Lagrangian system (see [`LagrangianSystem::integrate`]).
///
/// Implicit methods (symplectic ones among them) run on the canonical state `[q, p]` and
/// convert each stored sample back to `[q, qdot]`; explicit methods run on `[q, qdot]`.
/// Splitting methods are refused: the canonical form is not separable in general.
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
    let setup = Setup::new(&*system, t_span, dt, Some(ndof), method, &options)?;
    method.dispatch(Lagrangian(Run {
        system,
        setup,
        options,
    }))
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
    let setup = Setup::new(&*system, t_span, dt, None, method, &options)?;
    method.dispatch(Ode(Run {
        system,
        setup,
        options,
    }))
}

/// One validated call of a driver, waiting for its method's kind.
struct Run<'s, 'o, S> {
    system: &'s mut S,
    setup: Setup,
    options: IntegrateOptions<'o>,
}

/// The Hamiltonian family's handlers.
struct Hamiltonian<'s, 'o, S>(Run<'s, 'o, S>);

impl<S: HamiltonianSystem> Dispatch for Hamiltonian<'_, '_, S> {
    type Output = Result<SimulationResult>;

    fn splitting<const N: usize>(self, method: Method, weights: Coefficients<N>) -> Self::Output {
        integrate_splitting(self.0, method, weights)
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_first_order(self.0, method, St::new)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_first_order(self.0, method, St::new)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        integrate_adaptive::<St, S>(self.0, method)
    }
}

/// The Lagrangian family's handlers.
struct Lagrangian<'s, 'o, S>(Run<'s, 'o, S>);

impl<S: LagrangianSystem> Dispatch for Lagrangian<'_, '_, S> {
    type Output = Result<SimulationResult>;

    fn splitting<const N: usize>(self, method: Method, _: Coefficients<N>) -> Self::Output {
        Err(splitting_refused(method, Family::Lagrangian))
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_first_order(self.0, method, St::new)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_canonical::<St, S>(self.0, method)
    }

    /// On `[q, qdot]`, as the explicit methods.
    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        integrate_adaptive::<St, S>(self.0, method)
    }
}

/// The general-ODE family's handlers.
struct Ode<'s, 'o, S>(Run<'s, 'o, S>);

impl<S: OdeSystem> Dispatch for Ode<'_, '_, S> {
    type Output = Result<SimulationResult>;

    fn splitting<const N: usize>(self, method: Method, _: Coefficients<N>) -> Self::Output {
        Err(splitting_refused(method, Family::Ode))
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_first_order(self.0, method, St::new)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        integrate_first_order(self.0, method, St::new)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        integrate_adaptive::<St, S>(self.0, method)
    }
}

/// A splitting method with `N` drifts (weights `weights`), after checking that the
/// system is separable and conservative.
///
/// Systems of one or two degrees of freedom run with their state and force in fixed-length
/// arrays, which the compiler keeps in registers across substeps and steps: through a `Vec`
/// every kick waits for the previous substep's store to be forwarded to its load.
fn integrate_splitting<S: HamiltonianSystem, const N: usize>(
    run: Run<'_, '_, S>,
    method: Method,
    weights: Coefficients<N>,
) -> Result<SimulationResult> {
    check_system(method, &*run.system)?;
    let ndof = run.system.ndof();
    match ndof {
        1 => {
            let work = run.setup.start_in([0.0; 2]);
            run_splitting(run, method, weights, [0.0; 1], work)
        }
        2 => {
            let work = run.setup.start_in([0.0; 4]);
            run_splitting(run, method, weights, [0.0; 2], work)
        }
        _ => {
            let mut run = run;
            let work = std::mem::take(&mut run.setup.start);
            run_splitting(run, method, weights, vec![0.0; ndof], work)
        }
    }
}

/// The loop of [`integrate_splitting`] with the force cached in `force` and the state in
/// `work`.
fn run_splitting<S, const N: usize, B, W>(
    run: Run<'_, '_, S>,
    method: Method,
    weights: Coefficients<N>,
    force: B,
    work: W,
) -> Result<SimulationResult>
where
    S: HamiltonianSystem,
    B: AsRef<[f64]> + AsMut<[f64]> + Clone,
    W: AsRef<[f64]> + AsMut<[f64]>,
{
    let Run {
        system,
        setup,
        options,
    } = run;
    let mut stepper = SplittingStepper::with_buffer(weights, force);
    let sys = &*system;
    let (result, y) = setup.run_from(
        work,
        method,
        options,
        sys,
        &mut stepper,
        StoreWithPotential(sys),
    )?;
    finish(system, result, &y, &stepper)
}

/// An adaptive method on the system's own first-order form (`[q, p]` of a Hamiltonian,
/// `[q, qdot]` of a Lagrangian system), with the run's tolerances, stepping onto the grid's
/// end exactly.
fn integrate_adaptive<St: AdaptiveStepper, S: DynamicalSystem>(
    run: Run<'_, '_, S>,
    method: Method,
) -> Result<SimulationResult> {
    let tolerances = run.options.tolerances.unwrap_or_default();
    let t_end = run.setup.grid.t_end();
    let stepper = St::for_system(&*run.system, tolerances, t_end)?;
    integrate_first_order(run, method, |_| stepper)
}

/// A method on the system's own first-order form, `derivatives(t, y)`, stepped by the
/// stepper `new_stepper(dim)` builds.
fn integrate_first_order<St: FieldStepper, S: DynamicalSystem>(
    run: Run<'_, '_, S>,
    method: Method,
    new_stepper: impl FnOnce(usize) -> St,
) -> Result<SimulationResult> {
    let Run {
        system,
        setup,
        options,
    } = run;
    let sys = &*system;
    let field = FirstOrder(sys);
    let mut stepper = new_stepper(field.dim());
    let (result, y) = setup.run(method, options, &field, &mut stepper, StoreAsIs(sys))?;
    finish(system, result, &y, &stepper)
}

/// A method on a Lagrangian system's canonical form `[q, p]`, stepped by `St`; each stored
/// sample is converted back to `[q, qdot]`.
fn integrate_canonical<St: FieldStepper, S: LagrangianSystem>(
    run: Run<'_, '_, S>,
    method: Method,
) -> Result<SimulationResult> {
    let Run {
        system,
        setup,
        options,
    } = run;
    let sys = &*system;
    let ndof = sys.ndof();
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
    let mut stepper = St::new(2 * ndof);
    let (result, y) = setup.run_from(
        work,
        method,
        options,
        &field,
        &mut stepper,
        |recorder: &mut Recorder, t: f64, y: &[f64], _potential: Option<f64>| {
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
    finish(system, result, &y, &stepper)
}

/// How the loop stores a sample of the working state: `store(recorder, t, y, potential)`
/// appends the stored form of `y` and returns its stored energy (0 when energies are not
/// stored); `potential` is what the step that produced `y` returned from
/// [`Stepper::step_sampled`].
///
/// A trait rather than a closure so the common case, [`StoreAsIs`], is forced inline into the
/// loop (as a call it costs tens of instructions per sample of a small system). Closures (the
/// Lagrangian conversion to `[q, qdot]`) implement it too.
trait Sampler {
    fn store(
        &mut self,
        recorder: &mut Recorder,
        t: f64,
        y: &[f64],
        potential: Option<f64>,
    ) -> Result<f64>;
}

/// Stores the working state as it is, with the system's energy.
struct StoreAsIs<'a, S: ?Sized>(&'a S);

impl<S: DynamicalSystem + ?Sized> Sampler for StoreAsIs<'_, S> {
    #[inline(always)]
    fn store(
        &mut self,
        recorder: &mut Recorder,
        t: f64,
        y: &[f64],
        _potential: Option<f64>,
    ) -> Result<f64> {
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
struct StoreWithPotential<'a, S: ?Sized>(&'a S);

impl<S: HamiltonianSystem + ?Sized> Sampler for StoreWithPotential<'_, S> {
    #[inline(always)]
    fn store(
        &mut self,
        recorder: &mut Recorder,
        t: f64,
        y: &[f64],
        potential: Option<f64>,
    ) -> Result<f64> {
        let e = if recorder.stores_energy() {
            match potential {
                Some(v) => self.0.kinetic_energy(&y[self.0.ndof()..]) + v,
                None => self.0.energy(y),
            }
        } else {
            0.0
        };
        recorder.push(t, y, e);
        Ok(e)
    }
}

impl<F: FnMut(&mut Recorder, f64, &[f64], Option<f64>) -> Result<f64>> Sampler for F {
    #[inline(always)]
    fn store(
        &mut self,
        recorder: &mut Recorder,
        t: f64,
        y: &[f64],
        potential: Option<f64>,
    ) -> Result<f64> {
        self(recorder, t, y, potential)
    }
}

/// Writes the final sample back into the system and adds the stepper's statistics to the
/// extras.
fn finish<S: DynamicalSystem>(
    system: &mut S,
    (mut result, t_end): (SimulationResult, f64),
    final_state: &[f64],
    stepper: &impl Report,
) -> Result<SimulationResult> {
    system.phase_mut().assign_unchecked(final_state, t_end);
    stepper.report(&mut result.extra);
    Ok(result)
}

/// Tolerances are valid, and given only to an adaptive method.
fn check_tolerances(method: Method, options: &IntegrateOptions<'_>) -> Result<()> {
    match options.tolerances {
        Some(tolerances) => {
            check_adaptive("tolerances", method)?;
            tolerances.validate()
        }
        None => Ok(()),
    }
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
        method: Method,
        options: &IntegrateOptions<'_>,
    ) -> Result<Self> {
        let grid = TimeGrid::new(t_span, dt)?;
        options.sampling.validate()?;
        check_tolerances(method, options)?;
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
    fn run<P: ?Sized, St: Stepper<P>>(
        mut self,
        method: Method,
        options: IntegrateOptions<'_>,
        problem: &P,
        stepper: &mut St,
        sample: impl Sampler,
    ) -> Result<((SimulationResult, f64), Vec<f64>)> {
        let work = std::mem::take(&mut self.start);
        self.run_from(work, method, options, problem, stepper, sample)
    }

    /// The loop: `stepper` advances the working state `work` on `problem` by one step of the
    /// grid's `dt` at a time; `sample(recorder, t, y, potential)` stores the stored form of `y`
    /// and returns its stored energy (0 if energies are not stored). Returns the result, its
    /// final time and the final stored state.
    fn run_from<P: ?Sized, St: Stepper<P>, S2: Sampler, W: AsRef<[f64]> + AsMut<[f64]>>(
        self,
        mut work: W,
        method: Method,
        mut options: IntegrateOptions<'_>,
        problem: &P,
        stepper: &mut St,
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
        // A function, not a closure, so that it can be forced inline: as a call it costs tens
        // of instructions per sample of a small system.
        #[inline(always)]
        fn store<S2: Sampler>(
            recorder: &mut Recorder,
            t: f64,
            work: &[f64],
            potential: Option<f64>,
            sample: &mut S2,
        ) -> Result<()> {
            if sample.store(recorder, t, work, potential)?.is_finite() {
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
        store(&mut recorder, grid.t0(), work.as_ref(), None, &mut sample)?;
        let dt = grid.dt();
        let mut next_stored = sampling.next_stored(0, n);
        let mut until_observe = interval;
        let energies = recorder.stores_energy();
        for i in 0..n {
            let done = i + 1;
            let stored = energies && done == next_stored;
            let potential =
                stepper.step_sampled(problem, grid.time(i), work.as_mut(), dt, stored)?;
            let t = grid.time(done);
            if done == next_stored {
                store(&mut recorder, t, work.as_ref(), potential, &mut sample)?;
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
