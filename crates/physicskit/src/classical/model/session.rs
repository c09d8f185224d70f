//! [`Session`]: a system being stepped a few steps at a time, with its stepper, working state
//! and buffers kept between calls; for front ends that advance a run frame by frame (the
//! browser lab) without allocating per frame.
//!
//! [`DynSystem::start`] hands the system to a
//! session for one method and step `dt` ([`DynSystem::start_with`] with the tolerances of an
//! adaptive method). The session is generic over the concrete system and
//! stepper inside (the same [`Method::dispatch`](crate::classical::Method::dispatch) as
//! `integrate` chooses the stepper), and erased once, at construction: a frame costs one
//! dynamic call, its steps none.
//!
//! **Same bits as `integrate`.** `advance` runs the loop of the drivers: step `i` (counted
//! from the session's start) goes from `t0 + i dt` to `t0 + (i + 1) dt`, the splitting
//! methods keep their cached force between steps (first same as last), and a Lagrangian
//! system under an implicit method keeps its canonical state `[q, p]` between frames (it is
//! converted to `[q, qdot]` for the system's state after each frame, as `integrate` converts
//! each stored sample). So `advance(a)` then `advance(b)` reaches the very bits of one
//! `integrate` over `a + b` steps from the same start (tested for every catalogue system and
//! method in `tests/classical/integrators/session.rs`).
//!
//! **Adaptive methods** (`dop853`, `taylor`) run as `integrate` runs them, on the system's
//! own first-order form with `dt` the output spacing: each step of `dt` is a call of the
//! stepper from `t` to `t + dt`, which takes as many internal steps as its tolerances need
//! and interpolates at `t + dt` (dense output). A session has no end, so its stepper is built
//! with `t_bound = +inf`, where `integrate`'s steps onto `t_end`. The bound enters only the
//! internal steps that reach it: `integrate` shortens its last internal step to land on
//! `t_end`, and `dop853` also caps its first step at the span. So a session's samples equal
//! `integrate`'s over the same grid with the same tolerances, bit for bit, at every sample
//! before the start of `integrate`'s last internal step, as long as `integrate`'s first step
//! is not capped by its span (a span longer than that step); the samples inside the last
//! internal step, and the final one, differ by the two runs' different internal steps there
//! (within the tolerances). [`Session::set_dt`] changes only the output spacing (the internal
//! steps do not depend on it, and the run continues them); [`Session::restart`] and a failed
//! frame build the stepper afresh (on the system's Taylor form again, for `taylor`).
//!
//! **No allocation per frame.** The working state, the state at the frame's start (restored
//! when a step fails) and the stored-form buffer are allocated by `start`; the stepper's own
//! buffers by its constructor. `advance` allocates nothing (a failing frame does: it rebuilds
//! the stepper, whose buffers may hold a half-finished step). An adaptive stepper's buffers
//! are sized once for the state (its internal steps reuse them), so its frames allocate
//! nothing either.

use std::ops::DerefMut;

use super::DynSystem;
use crate::classical::core::{error::check_finite, Error, Result, TimeGrid};
use crate::classical::integrators::field::{Canonical, FirstOrder, VectorField};
use crate::classical::integrators::options::check_adaptive;
use crate::classical::integrators::splitting::Coefficients;
use crate::classical::integrators::splitting::{check_system, SplittingStepper};
use crate::classical::integrators::stepper::{
    splitting_refused, AdaptiveStepper, Dispatch, FieldStepper,
};
use crate::classical::integrators::Family;
use crate::classical::integrators::{
    DynamicalSystem, HamiltonianSystem, LagrangianSystem, Method, OdeSystem, Tolerances,
};

/// A run in progress: a system, a method and a step, advanced `n` steps at a time.
pub trait Session {
    /// Advances `n_steps` steps of [`dt`](Self::dt); the system's state and clock then hold
    /// the new state (`[q, qdot]` for Lagrangian systems).
    ///
    /// # Errors
    /// Whatever a step reports (a force that fails, an implicit solve that does not
    /// converge), or [`Error::NonFinite`] if the state is no longer finite after the frame;
    /// the session is then back where the frame started.
    fn advance(&mut self, n_steps: usize) -> Result<()>;

    /// The system, with the state and clock of the last completed frame.
    fn system(&self) -> &dyn DynSystem;

    /// The method.
    fn method(&self) -> Method;

    /// The step (for an adaptive method, the output spacing).
    fn dt(&self) -> f64;

    /// The tolerances of an adaptive method (the defaults when none were given); `None` for
    /// a fixed-step method.
    fn tolerances(&self) -> Option<Tolerances>;

    /// Steps taken since the session started, or since the last
    /// [`restart`](Self::restart) or [`set_dt`](Self::set_dt).
    fn steps(&self) -> u64;

    /// Changes the step; the run continues from the current state and time (a splitting
    /// method keeps its cached force, an implicit Lagrangian run its canonical state, an
    /// adaptive method its internal steps: only the output spacing changes).
    ///
    /// # Errors
    /// [`Error::InvalidTimeSpan`] for a `dt` that is not finite and positive.
    fn set_dt(&mut self, dt: f64) -> Result<()>;

    /// Starts again from `state` (or the current state) at time `t0`, as a new session would.
    ///
    /// # Errors
    /// As [`DynSystem::reset`], or a state a new session would refuse (not finite).
    fn restart(&mut self, state: Option<&[f64]>, t0: f64) -> Result<()>;

    /// Ends the session, giving the system back with the state and clock of the last frame.
    fn into_system(self: Box<Self>) -> Box<dyn DynSystem>;

    /// The current state (`[q, qdot]` for Lagrangian systems).
    fn state(&self) -> &[f64] {
        self.system().dynamical().state()
    }

    /// The clock.
    fn t(&self) -> f64 {
        self.system().dynamical().t()
    }

    /// The energy of the current state.
    fn energy(&self) -> f64 {
        let d = self.system().dynamical();
        d.energy(d.state())
    }
}

impl std::fmt::Debug for dyn Session {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session")
            .field("method", &self.method())
            .field("dt", &self.dt())
            .field("t", &self.t())
            .field("steps", &self.steps())
            .finish_non_exhaustive()
    }
}

/// What [`DynSystem::start`] returns when it refuses: the reason, and the system back.
pub struct Refused {
    /// Why (a method the system cannot use, a `dt` that is not finite and positive, a
    /// state that is not finite, tolerances that are invalid or given to a fixed-step
    /// method).
    pub error: Error,
    /// The system, unchanged.
    pub system: Box<dyn DynSystem>,
}

impl std::fmt::Debug for Refused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Refused")
            .field("error", &self.error)
            .finish_non_exhaustive()
    }
}

/// How one kind of method steps the system `S` on its working state, and how the working
/// state relates to the system's stored state.
trait Kind<S: ?Sized> {
    fn step(&mut self, system: &S, t: f64, y: &mut [f64], h: f64) -> Result<()>;

    /// Forgets what the stepper carries from one step to the next (after the state changed
    /// outside it, or a failed step).
    ///
    /// # Errors
    /// Whatever rebuilding the stepper on `system` reports (it succeeded when the session
    /// started, on the same system).
    fn forget(&mut self, system: &S, dim: usize) -> Result<()>;

    /// The working state of the stored state `stored` at `t` (into `work`, of its length).
    fn to_working(&self, system: &S, stored: &[f64], t: f64, work: &mut [f64]) -> Result<()> {
        let _ = (system, t);
        work.copy_from_slice(stored);
        Ok(())
    }

    /// The stored state of the working state `work` at `t` (into `stored`).
    fn to_stored(&self, system: &S, work: &[f64], t: f64, stored: &mut [f64]) -> Result<()> {
        let _ = (system, t);
        stored.copy_from_slice(work);
        Ok(())
    }
}

/// A splitting method on a separable Hamiltonian system's `[q, p]`.
struct Split<const N: usize>(SplittingStepper<N>);

impl<S: HamiltonianSystem + ?Sized, const N: usize> Kind<S> for Split<N> {
    #[inline(always)]
    fn step(&mut self, system: &S, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        let (q, p) = y.split_at_mut(y.len() / 2);
        self.0.step(system, t, q, p, h)
    }

    fn forget(&mut self, _: &S, _dim: usize) -> Result<()> {
        self.0.invalidate();
        Ok(())
    }
}

/// A method on the system's own first-order form.
struct Field<St>(St);

impl<S: DynamicalSystem + ?Sized, St: FieldStepper> Kind<S> for Field<St> {
    #[inline(always)]
    fn step(&mut self, system: &S, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.0.step_field(&FirstOrder(system), t, y, h)
    }

    fn forget(&mut self, _: &S, dim: usize) -> Result<()> {
        self.0 = St::new(dim);
        Ok(())
    }
}

/// A method on a Lagrangian system's canonical form `[q, p]`.
struct Canon<St>(St);

impl<S: LagrangianSystem + ?Sized, St: FieldStepper> Kind<S> for Canon<St> {
    #[inline(always)]
    fn step(&mut self, system: &S, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.0.step_field(&Canonical(system), t, y, h)
    }

    fn forget(&mut self, _: &S, dim: usize) -> Result<()> {
        self.0 = St::new(dim);
        Ok(())
    }

    /// `p = dL/dqdot` at `(q, qdot)`, as `integrate` starts its canonical runs.
    fn to_working(&self, system: &S, stored: &[f64], t: f64, work: &mut [f64]) -> Result<()> {
        let n = system.ndof();
        work[..n].copy_from_slice(&stored[..n]);
        system.momentum(&stored[..n], &stored[n..], t, &mut work[n..])
    }

    /// `qdot` from `(q, p)`, as `integrate` converts its stored samples.
    fn to_stored(&self, system: &S, work: &[f64], t: f64, stored: &mut [f64]) -> Result<()> {
        let n = system.ndof();
        let (q, p) = work.split_at(n);
        stored[..n].copy_from_slice(q);
        system.velocity(q, p, t, &mut stored[n..])
    }
}

/// An adaptive method on the system's own first-order form, as `integrate` runs it, with no
/// end (`t_bound = +inf`).
struct Adaptive<St> {
    stepper: St,
    tolerances: Tolerances,
}

impl<St: AdaptiveStepper> Adaptive<St> {
    fn on<S: DynamicalSystem + ?Sized>(system: &S, tolerances: Tolerances) -> Result<Self> {
        Ok(Self {
            stepper: St::for_system(system, tolerances, f64::INFINITY)?,
            tolerances,
        })
    }
}

impl<S: DynamicalSystem + ?Sized, St: AdaptiveStepper> Kind<S> for Adaptive<St> {
    #[inline(always)]
    fn step(&mut self, system: &S, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.stepper.step_field(&FirstOrder(system), t, y, h)
    }

    /// A new stepper: one that continued from a state equal to its last output would
    /// continue its internal steps, where a new session starts afresh.
    fn forget(&mut self, system: &S, _dim: usize) -> Result<()> {
        *self = Self::on(system, self.tolerances)?;
        Ok(())
    }
}

/// The session of the system wrapper `W` (its concrete system is `W::Target`) under the
/// stepper kind `K`.
struct Running<W, K> {
    system: Box<W>,
    kind: K,
    method: Method,
    /// The tolerances of an adaptive method.
    tolerances: Option<Tolerances>,
    /// `t0` and `dt` of the run: step `i` starts at `grid.time(i)`, as in `integrate`.
    grid: TimeGrid,
    steps: usize,
    /// The working state (`[q, p]` for an implicit method on a Lagrangian system).
    work: Vec<f64>,
    /// The working state at the start of the frame, restored if the frame fails.
    saved: Vec<f64>,
    /// The stored form of `work`, copied into the system after each frame.
    stored: Vec<f64>,
}

impl<W, K> Running<W, K>
where
    W: DynSystem + DerefMut + 'static,
    W::Target: DynamicalSystem,
    K: Kind<W::Target> + 'static,
{
    /// Validates and builds a session; on refusal, gives the system back. `tolerances` are
    /// checked as `integrate` checks them (valid, and given only to an adaptive method);
    /// an adaptive method's `kind` receives them (the defaults when none are given).
    fn start(
        system: Box<W>,
        method: Method,
        dt: f64,
        tolerances: Option<Tolerances>,
        kind: impl FnOnce(&W::Target, usize) -> Result<K>,
    ) -> std::result::Result<Box<dyn Session>, Refused> {
        let built = (|| {
            let d: &W::Target = &system;
            let t0 = d.t();
            let grid = TimeGrid::new((t0, t0 + dt), dt)?;
            if let Some(tolerances) = tolerances {
                check_adaptive("tolerances", method)?;
                tolerances.validate()?;
            }
            let tolerances = method.is_adaptive().then(|| tolerances.unwrap_or_default());
            let state = d.state();
            if let Some(ndof) = system.ndof() {
                if state.len() != 2 * ndof {
                    return Err(Error::DimensionMismatch {
                        name: "state".into(),
                        expected: 2 * ndof,
                        found: state.len(),
                    });
                }
            }
            check_finite("state", state, t0)?;
            let kind = kind(d, state.len())?;
            let mut work = state.to_vec();
            kind.to_working(d, state, t0, &mut work)?;
            Ok((grid, kind, work, tolerances))
        })();
        match built {
            Ok((grid, kind, work, tolerances)) => Ok(Box::new(Self {
                kind,
                method,
                tolerances,
                grid,
                steps: 0,
                saved: work.clone(),
                stored: work.clone(),
                work,
                system,
            })),
            Err(error) => Err(Refused { error, system }),
        }
    }

    /// The failed frame's start back, and a stepper without memory of it.
    ///
    /// # Errors
    /// As [`Kind::forget`].
    fn undo(&mut self) -> Result<()> {
        self.work.copy_from_slice(&self.saved);
        let dim = self.work.len();
        self.kind.forget(&self.system, dim)
    }
}

impl<W, K> Session for Running<W, K>
where
    W: DynSystem + DerefMut + 'static,
    W::Target: DynamicalSystem,
    K: Kind<W::Target> + 'static,
{
    fn advance(&mut self, n_steps: usize) -> Result<()> {
        if n_steps == 0 {
            return Ok(());
        }
        self.saved.copy_from_slice(&self.work);
        let system: &W::Target = &self.system;
        let (grid, dt) = (self.grid, self.grid.dt());
        let mut failed = None;
        for i in self.steps..self.steps + n_steps {
            if let Err(e) = self.kind.step(system, grid.time(i), &mut self.work, dt) {
                failed = Some(e);
                break;
            }
        }
        let t = grid.time(self.steps + n_steps);
        let outcome = match failed {
            Some(e) => Err(e),
            None if !self.work.iter().all(|v| v.is_finite()) => Err(Error::NonFinite {
                name: "state".into(),
                t,
            }),
            None => self.kind.to_stored(system, &self.work, t, &mut self.stored),
        };
        if let Err(e) = outcome {
            // A stepper that cannot be rebuilt (never: it was built on this system) reports
            // that instead.
            self.undo()?;
            return Err(e);
        }
        self.steps += n_steps;
        self.system.phase_mut().assign_unchecked(&self.stored, t);
        Ok(())
    }

    fn system(&self) -> &dyn DynSystem {
        &*self.system
    }

    fn method(&self) -> Method {
        self.method
    }

    fn dt(&self) -> f64 {
        self.grid.dt()
    }

    fn tolerances(&self) -> Option<Tolerances> {
        self.tolerances
    }

    fn steps(&self) -> u64 {
        self.steps as u64
    }

    fn set_dt(&mut self, dt: f64) -> Result<()> {
        let t = self.t();
        self.grid = TimeGrid::new((t, t + dt), dt)?;
        self.steps = 0;
        Ok(())
    }

    fn restart(&mut self, state: Option<&[f64]>, t0: f64) -> Result<()> {
        let grid = TimeGrid::new((t0, t0 + self.grid.dt()), self.grid.dt())?;
        let system: &mut W::Target = &mut self.system;
        let old_t = system.t();
        let old_state = self.stored.clone();
        system.reset(state, t0)?;
        let converted = check_finite("state", system.state(), t0).and_then(|()| {
            self.kind
                .to_working(system, system.state(), t0, &mut self.work)
        });
        if let Err(e) = converted {
            // Back to the run as it was: a refused restart changes nothing.
            system.phase_mut().assign_unchecked(&old_state, old_t);
            self.work.copy_from_slice(&self.saved);
            return Err(e);
        }
        self.stored.copy_from_slice(system.state());
        self.saved.copy_from_slice(&self.work);
        let dim = self.work.len();
        self.kind.forget(system, dim)?;
        self.grid = grid;
        self.steps = 0;
        Ok(())
    }

    fn into_system(self: Box<Self>) -> Box<dyn DynSystem> {
        self.system
    }
}

/// What every family's dispatch does alike: a session on the first-order field, and the
/// refusals.
type Started = std::result::Result<Box<dyn Session>, Refused>;

/// A session of the field stepper `St` on `dy/dt = derivatives(t, y)`.
fn on_first_order<W, St>(
    system: Box<W>,
    method: Method,
    dt: f64,
    tolerances: Option<Tolerances>,
) -> Started
where
    W: DynSystem + DerefMut + 'static,
    W::Target: DynamicalSystem + Sized,
    St: FieldStepper,
{
    Running::start(system, method, dt, tolerances, |s, _| {
        Ok(Field(St::new(FirstOrder(s).dim())))
    })
}

/// A session of the adaptive stepper `St` on the system's own first-order form (`[q, p]` of
/// a Hamiltonian, `[q, qdot]` of a Lagrangian system), as `integrate` runs it.
fn adaptive_on_first_order<W, St>(
    system: Box<W>,
    method: Method,
    dt: f64,
    tolerances: Option<Tolerances>,
) -> Started
where
    W: DynSystem + DerefMut + 'static,
    W::Target: DynamicalSystem + Sized,
    St: AdaptiveStepper,
{
    Running::start(system, method, dt, tolerances, |s, _| {
        Adaptive::<St>::on(s, tolerances.unwrap_or_default())
    })
}

/// The system back, with the reason.
fn refuse<W: DynSystem + 'static>(system: Box<W>, error: Error) -> Started {
    Err(Refused { error, system })
}

/// The Hamiltonian family's sessions.
pub(crate) struct StartHamiltonian<W> {
    pub(crate) system: Box<W>,
    pub(crate) dt: f64,
    pub(crate) tolerances: Option<Tolerances>,
}

impl<W> Dispatch for StartHamiltonian<W>
where
    W: DynSystem + DerefMut + 'static,
    W::Target: HamiltonianSystem + Sized,
{
    type Output = Started;

    fn splitting<const N: usize>(
        self,
        method: Method,
        coefficients: Coefficients<N>,
    ) -> Self::Output {
        Running::start(self.system, method, self.dt, self.tolerances, |s, dim| {
            check_system(method, s)?;
            Ok(Split(SplittingStepper::with_buffer(
                coefficients,
                vec![0.0; dim / 2],
            )))
        })
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        adaptive_on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }
}

/// The Lagrangian family's sessions: implicit methods on the canonical form `[q, p]`, explicit
/// and adaptive ones on `[q, qdot]`.
pub(crate) struct StartLagrangian<W> {
    pub(crate) system: Box<W>,
    pub(crate) dt: f64,
    pub(crate) tolerances: Option<Tolerances>,
}

impl<W> Dispatch for StartLagrangian<W>
where
    W: DynSystem + DerefMut + 'static,
    W::Target: LagrangianSystem + Sized,
{
    type Output = Started;

    fn splitting<const N: usize>(self, method: Method, _: Coefficients<N>) -> Self::Output {
        refuse(self.system, splitting_refused(method, Family::Lagrangian))
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        Running::start(self.system, method, self.dt, self.tolerances, |s, _| {
            Ok(Canon(St::new(Canonical(s).dim())))
        })
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        adaptive_on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }
}

/// The general-ODE family's sessions.
pub(crate) struct StartOde<W> {
    pub(crate) system: Box<W>,
    pub(crate) dt: f64,
    pub(crate) tolerances: Option<Tolerances>,
}

impl<W> Dispatch for StartOde<W>
where
    W: DynSystem + DerefMut + 'static,
    W::Target: OdeSystem + Sized,
{
    type Output = Started;

    fn splitting<const N: usize>(self, method: Method, _: Coefficients<N>) -> Self::Output {
        refuse(self.system, splitting_refused(method, Family::Ode))
    }

    fn explicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        adaptive_on_first_order::<W, St>(self.system, method, self.dt, self.tolerances)
    }
}
