//! Per-member reductions: one number per member, computed from its run as soon as the member
//! is done, so that only the numbers are kept.
//!
//! * [`Reduction::MaxEnergyError`]: `max_i |E_i - E_0| / |E_0|` (absolute if `E_0 = 0`) over
//!   every step, with the energies `integrate` itself reports, so it equals
//!   [`SimulationResult::max_relative_energy_error`] of the member's own run bit for bit.
//! * [`Reduction::FirstEvent`]: the first time a coordinate of the stored state crosses a
//!   value (in a given direction), or its magnitude exceeds a value (a double pendulum flips
//!   when `|theta2| > pi`); `NaN` if it never happens, `t0` if the initial state is already
//!   beyond.
//! * [`Reduction::MaxLyapunov`]: the largest Lyapunov exponent at `t1`, by the chaos toolkit's
//!   own loop ([`lyapunov`](crate::classical::analysis::lyapunov), one deviation vector
//!   renormalized every `renormalize_every` steps) on the member's
//!   [`Flow`](crate::classical::integrators::Flow) with the plan's
//!   method and grid: the same bits as
//!   [`max_lyapunov`](crate::classical::analysis::lyapunov::max_lyapunov)`(member, ...)
//!   .exponents[0]`.
//! * [`Reduction::Sali`]: SALI at `t1` ([`sali`](crate::classical::analysis::sali), its two
//!   deviation vectors as the library chooses them), the same bits as the last value of
//!   [`alignment_index`](crate::classical::analysis::sali::alignment_index)`(member, ...,
//!   Alignment::Sali, ...)`; above [`CHAOS_THRESHOLD`](crate::classical::analysis::sali::CHAOS_THRESHOLD)
//!   an orbit is regular over the span, below it chaotic. No early stop at a floor (unlike
//!   the chaos maps), so that a member equals its single run.
//!
//! The chaos reductions follow their deviation vectors in their own run of the member's flow
//! (the ensemble's `integrate` run still gives the final state and the other reductions); a
//! splitting method on a non-separable system is refused before any work, as by `integrate`.
//!
//! # Locating an event inside a step
//! The step `[t_k, t_{k+1}]` whose end states bracket the event is interpolated by the cubic
//! Hermite polynomial through the two states and their time derivatives (the system's own
//! `derivatives`, evaluated only for that step), and the crossing of the cubic is found by
//! bisection to rounding. The interpolant's error is `O(dt^4)` (Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, §II.6), so the event time carries the method's global error `O(dt^p)` for
//! the methods of order `p <= 4` (all of physicskit's), not the `O(dt)` of taking the step's
//! end. A grazing event that enters and leaves within one step is missed, as by any method
//! that looks at step ends.
//!
//! # Adding a reduction
//! One variant, its [`name`](Reduction::name) and its arm in [`Reduction::reduce`], which sees
//! the member's whole run ([`MemberRun`]): its system at the initial state, the time grid and
//! method, and every stored step. Reductions that integrate something of their own (the chaos
//! toolkit's max Lyapunov exponent and SALI, which follow deviation vectors) get the system,
//! initial state and grid from there and run their own integration.

use crate::classical::analysis::lyapunov::{check_vectors, max_exponent_on_flow};
use crate::classical::analysis::sali::sali_on_flow;
use crate::classical::analysis::watch::AnalysisOptions;
use crate::classical::core::result::EnergyError;
use crate::classical::core::{Error, Result, SimulationResult, TimeGrid};
use crate::classical::integrators::{Method, Observer};
use crate::classical::model::DynSystem;

/// Which way a [`Condition::Crosses`] event must cross.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Direction {
    /// Either way.
    #[default]
    Either,
    /// From below the value to above it.
    Rising,
    /// From above the value to below it.
    Falling,
}

/// What happens to the coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Condition {
    /// `y[index]` crosses `value` in `direction` (touching it from one side counts).
    Crosses {
        /// The level.
        value: f64,
        /// Which way.
        direction: Direction,
    },
    /// `|y[index]| > value`.
    AbsExceeds(f64),
}

/// An event on entry `index` of the stored state (`[q, p]`; `[q, qdot]` for Lagrangian
/// systems; an ODE system's own layout).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Which entry of the state.
    pub index: usize,
    /// What must happen to it.
    pub condition: Condition,
}

/// One number per member.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Reduction {
    /// The largest relative energy error over every step.
    MaxEnergyError,
    /// The time of the first event (`NaN` if none).
    FirstEvent(Event),
    /// The largest Lyapunov exponent at the end of the span.
    MaxLyapunov {
        /// Steps between renormalizations of the deviation vector (>= 1).
        renormalize_every: usize,
    },
    /// SALI at the end of the span.
    Sali {
        /// Steps between evaluations of the index (>= 1).
        renormalize_every: usize,
    },
}

/// What a reduction sees of one member's run.
pub struct MemberRun<'a> {
    /// The member's system after the run (its parameters; its initial state is the run's
    /// first row).
    pub system: &'a dyn DynSystem,
    /// The method.
    pub method: Method,
    /// The run, storing every step when a reduction needs them (energies when one asked for
    /// them), else only the final state.
    pub result: &'a SimulationResult,
    /// The member's initial state.
    pub state0: &'a [f64],
    /// The time grid of the run.
    pub grid: &'a TimeGrid,
}

impl Reduction {
    /// The output's name: `max_energy_error`, `event_time`, `max_lyapunov`, `sali`.
    pub fn name(&self) -> &'static str {
        match self {
            Reduction::MaxEnergyError => "max_energy_error",
            Reduction::FirstEvent(_) => "event_time",
            Reduction::MaxLyapunov { .. } => "max_lyapunov",
            Reduction::Sali { .. } => "sali",
        }
    }

    /// Whether the run must store energies.
    pub(crate) fn needs_energy(&self) -> bool {
        matches!(self, Reduction::MaxEnergyError)
    }

    /// Whether the run must store every step (the chaos reductions run their own flow).
    pub(crate) fn needs_steps(&self) -> bool {
        matches!(self, Reduction::MaxEnergyError | Reduction::FirstEvent(_))
    }

    /// The deviation vectors the reduction's own flow carries (0: it has none).
    pub(crate) fn vectors(&self) -> usize {
        match self {
            Reduction::MaxEnergyError | Reduction::FirstEvent(_) => 0,
            Reduction::MaxLyapunov { .. } => 1,
            Reduction::Sali { .. } => 2,
        }
    }

    /// Checks the reduction against a state of `dim` entries.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an index beyond the state or a non-finite level;
    /// [`Error::InvalidParameter`] for `renormalize_every = 0` or a state too short for the
    /// deviation vectors (SALI needs two entries).
    pub fn check(&self, dim: usize) -> Result<()> {
        match self {
            Reduction::MaxEnergyError => Ok(()),
            Reduction::MaxLyapunov { renormalize_every }
            | Reduction::Sali { renormalize_every } => {
                check_vectors(self.vectors(), dim, *renormalize_every, "deviation vectors")
            }
            Reduction::FirstEvent(Event { index, condition }) => {
                if *index >= dim {
                    return Err(Error::InvalidArgument {
                        name: "event".into(),
                        reason: format!(
                            "index {index} is beyond the state, which has {dim} entries"
                        ),
                    });
                }
                let level = match condition {
                    Condition::Crosses { value, .. } => *value,
                    Condition::AbsExceeds(v) => *v,
                };
                if level.is_finite() {
                    Ok(())
                } else {
                    Err(Error::invalid("event value", level, "must be finite"))
                }
            }
        }
    }

    /// The reduction of one member's run. `observer` is consulted every `observe_every`
    /// steps of a chaos reduction's own run and may stop it.
    ///
    /// # Errors
    /// Whatever the system's `derivatives` returns at an event; for the chaos reductions, what
    /// their loops return (a method the system cannot run, a diverging orbit,
    /// [`Error::Interrupted`] when the observer stops).
    pub fn reduce(
        &self,
        run: &MemberRun<'_>,
        observer: Option<&mut dyn Observer>,
        observe_every: usize,
    ) -> Result<f64> {
        match self {
            Reduction::MaxEnergyError => {
                Ok(run.result.max_relative_energy_error().unwrap_or(f64::NAN))
            }
            Reduction::FirstEvent(event) => first_event(event, run),
            Reduction::MaxLyapunov { .. } | Reduction::Sali { .. } => self.on_own_flow(
                run.system,
                run.method,
                run.state0,
                run.grid,
                observer,
                observe_every,
            ),
        }
    }

    /// Whether the reduction follows the member's steps (as [`Stepwise`] does in lanes),
    /// rather than integrating a flow of its own.
    pub(crate) fn is_stepwise(&self) -> bool {
        self.vectors() == 0
    }

    /// A chaos reduction of the member `system` started at `state0`, on its own flow with
    /// `method` over `grid` (what [`reduce`](Self::reduce) does for it).
    ///
    /// # Errors
    /// As [`reduce`](Self::reduce); [`Error::Unsupported`] for a reduction of the member's
    /// steps.
    pub(crate) fn on_own_flow(
        &self,
        system: &dyn DynSystem,
        method: Method,
        state0: &[f64],
        grid: &TimeGrid,
        observer: Option<&mut dyn Observer>,
        observe_every: usize,
    ) -> Result<f64> {
        let options = AnalysisOptions {
            observer,
            observe_every,
            history_stride: 1,
        };
        match self {
            Reduction::MaxLyapunov { renormalize_every } => max_exponent_on_flow(
                system.flow(method, 1)?.as_mut(),
                state0,
                grid,
                *renormalize_every,
                options,
            ),
            Reduction::Sali { renormalize_every } => sali_on_flow(
                system.flow(method, 2)?.as_mut(),
                state0,
                grid,
                *renormalize_every,
                0.0,
                options,
            ),
            Reduction::MaxEnergyError | Reduction::FirstEvent(_) => Err(Error::Unsupported {
                operation: self.name().into(),
                reason: "reduced from the member's steps, not on a flow of its own".into(),
            }),
        }
    }
}

/// The stepwise reductions ([`Reduction::is_stepwise`]: the energy error, first events) of
/// the members of a lanes run, fed each member's state at every step of the grid in order
/// ([`start`](Self::start), then [`step`](Self::step) for steps `1..=n`), with the bits
/// [`Reduction::reduce`] gives on the member's own run: the same energies (the system's
/// `energy` of each stored state, as `integrate` stores them) folded in the same order, and
/// an event located in the same step from the same two states. Storage for every member is
/// allocated once; a step allocates nothing (locating an event, once per event, does).
pub(crate) struct Stepwise<'r> {
    reductions: &'r [Reduction],
    dim: usize,
    /// Per member, one value per reduction (a chaos reduction's is left for the caller).
    values: Vec<f64>,
    /// Per member, the error against its `E_0`, with an energy error to reduce.
    energy: Vec<EnergyError>,
    /// Per member, the last state, with events to locate.
    previous: Vec<f64>,
    /// Per member: its own run fails where this one did not (an energy not finite, an
    /// event's derivatives refused), so it must be run alone for its error.
    spoilt: Vec<bool>,
}

impl<'r> Stepwise<'r> {
    /// Storage for `members` members of states of `dim` entries.
    pub(crate) fn new(reductions: &'r [Reduction], members: usize, dim: usize) -> Self {
        let energy = reductions.contains(&Reduction::MaxEnergyError);
        let events = reductions
            .iter()
            .any(|r| matches!(r, Reduction::FirstEvent(_)));
        Self {
            reductions,
            dim,
            values: vec![f64::NAN; members * reductions.len()],
            energy: vec![EnergyError::new(0.0); if energy { members } else { 0 }],
            previous: vec![0.0; if events { members * dim } else { 0 }],
            spoilt: vec![false; members],
        }
    }

    /// Whether a reduction reads each step's energy.
    pub(crate) fn reads_energy(&self) -> bool {
        !self.energy.is_empty()
    }

    /// Whether the maximum energy error is the only reduction that reads the steps (a lanes
    /// kind may then fold it itself: [`largest_energy_error`](Self::largest_energy_error)).
    pub(crate) fn reads_only_energy(&self) -> bool {
        self.reads_energy()
            && self
                .reductions
                .iter()
                .all(|r| !r.is_stepwise() || *r == Reduction::MaxEnergyError)
    }

    /// Member `m`'s largest energy error over every step, folded by the caller as
    /// [`step`](Self::step) folds it; NaN where an energy was not finite (the member's own
    /// run then gives its error).
    pub(crate) fn largest_energy_error(&mut self, m: usize, error: f64) {
        let r = self.reductions.len();
        for (reduction, value) in self.reductions.iter().zip(&mut self.values[m * r..]) {
            if *reduction == Reduction::MaxEnergyError {
                self.spoilt[m] |= error.is_nan();
                *value = value.max(error);
            }
        }
    }

    /// Whether any reduction reads the steps.
    pub(crate) fn reads_steps(&self) -> bool {
        self.reductions.iter().any(Reduction::is_stepwise)
    }

    /// Member `m` (its `system`) starts from `y0` at `t0`.
    pub(crate) fn start(&mut self, m: usize, system: &dyn DynSystem, t0: f64, y0: &[f64]) {
        let r = self.reductions.len();
        for (reduction, value) in self.reductions.iter().zip(&mut self.values[m * r..]) {
            match reduction {
                Reduction::MaxEnergyError => {
                    let e0 = system.dynamical().energy(y0);
                    self.spoilt[m] |= !e0.is_finite();
                    // As `SimulationResult::max_relative_energy_error`: folded from 0 over
                    // every stored energy; its first term, the error of `E_0` itself, is +0
                    // for a finite `E_0`.
                    self.energy[m] = EnergyError::new(e0);
                    *value = 0.0;
                }
                Reduction::FirstEvent(e) => {
                    *value = if e.condition.at_start(y0[e.index]) {
                        t0
                    } else {
                        f64::NAN
                    };
                }
                Reduction::MaxLyapunov { .. } | Reduction::Sali { .. } => {}
            }
        }
        if !self.previous.is_empty() {
            self.previous[m * self.dim..(m + 1) * self.dim].copy_from_slice(y0);
        }
    }

    /// Member `m` (its `system`) reached `y` at step `step` (`>= 1`) of `grid`; `energy` is
    /// `y`'s energy where the caller computed it (bit for bit `system`'s), else it is taken here.
    pub(crate) fn step(
        &mut self,
        m: usize,
        system: &dyn DynSystem,
        grid: &TimeGrid,
        step: usize,
        y: &[f64],
        energy: Option<f64>,
    ) {
        let (r, dim) = (self.reductions.len(), self.dim);
        for (reduction, value) in self.reductions.iter().zip(&mut self.values[m * r..]) {
            match reduction {
                Reduction::MaxEnergyError => {
                    let e = energy.unwrap_or_else(|| system.dynamical().energy(y));
                    // `integrate` refuses a stored energy that is not finite.
                    self.spoilt[m] |= !e.is_finite();
                    *value = value.max(self.energy[m].of(e));
                }
                Reduction::FirstEvent(event) if value.is_nan() => {
                    let c = event.index;
                    let previous = &self.previous[m * dim..(m + 1) * dim];
                    if let Some(target) = event.condition.target(previous[c], y[c]) {
                        let span = (grid.time(step - 1), grid.time(step));
                        match locate(system, span, previous, y, c, target) {
                            Ok(t) => *value = t,
                            Err(_) => self.spoilt[m] = true,
                        }
                    }
                }
                _ => {}
            }
        }
        if !self.previous.is_empty() {
            self.previous[m * dim..(m + 1) * dim].copy_from_slice(y);
        }
    }

    /// Whether member `m`'s own run fails where the lanes' did not.
    pub(crate) fn spoilt(&self, m: usize) -> bool {
        self.spoilt[m]
    }

    /// Member `m`'s values, one per reduction (a chaos reduction's `NaN`).
    pub(crate) fn values(&self, m: usize) -> &[f64] {
        let r = self.reductions.len();
        &self.values[m * r..(m + 1) * r]
    }
}

impl Condition {
    /// Whether the initial value `y0` is already beyond (the event is then at `t0`).
    pub(crate) fn at_start(self, y0: f64) -> bool {
        matches!(self, Condition::AbsExceeds(v) if y0.abs() > v)
    }

    /// The level the coordinate reaches inside the step from `a` to `b`, if the event
    /// happens in that step.
    pub(crate) fn target(self, a: f64, b: f64) -> Option<f64> {
        match self {
            Condition::Crosses { value, direction } => {
                let rising = a < value && b >= value;
                let falling = a > value && b <= value;
                let hit = match direction {
                    Direction::Either => rising || falling,
                    Direction::Rising => rising,
                    Direction::Falling => falling,
                };
                hit.then_some(value)
            }
            Condition::AbsExceeds(v) => (b.abs() > v).then(|| v.copysign(b)),
        }
    }
}

/// The time of the first `event` in `run`, located inside its step (see the module docs).
fn first_event(event: &Event, run: &MemberRun<'_>) -> Result<f64> {
    let y = &run.result.y;
    let t = &run.result.t;
    let c = event.index;
    if event.condition.at_start(y[[0, c]]) {
        return Ok(t[0]);
    }
    for k in 1..y.nrows() {
        if let Some(target) = event.condition.target(y[[k - 1, c]], y[[k, c]]) {
            let (start, end) = (y.row(k - 1).to_vec(), y.row(k).to_vec());
            return locate(run.system, (t[k - 1], t[k]), &start, &end, c, target);
        }
    }
    Ok(f64::NAN)
}

/// Where entry `c` of the cubic Hermite interpolant of the step from `start` at `t0` to `end`
/// at `t1` equals `target`, the step's end values bracketing it; the slopes are `system`'s
/// derivatives.
pub(crate) fn locate(
    system: &dyn DynSystem,
    (t0, t1): (f64, f64),
    start: &[f64],
    end: &[f64],
    c: usize,
    target: f64,
) -> Result<f64> {
    let h = t1 - t0;
    let dynamics = system.dynamical();
    let mut d0 = vec![0.0; start.len()];
    let mut d1 = vec![0.0; start.len()];
    dynamics.derivatives(t0, start, &mut d0)?;
    dynamics.derivatives(t1, end, &mut d1)?;
    let s = hermite_crossing(start[c], end[c], h * d0[c], h * d1[c], target);
    Ok(t0 + h * s)
}

/// The `s` in `[0, 1]` where the cubic Hermite polynomial with values `y0`, `y1` and scaled
/// slopes `m0 = h y0'`, `m1 = h y1'` at `s = 0, 1` equals `target`, by bisection (the ends
/// bracket it: `y0 - target` and `y1 - target` differ in sign or `y1 = target`).
///
/// The cubic may cross more than once inside the step when the slopes disagree with the
/// secant; bisection then returns one of the crossings, all within the step.
pub(crate) fn hermite_crossing(y0: f64, y1: f64, m0: f64, m1: f64, target: f64) -> f64 {
    let p = |s: f64| {
        let s2 = s * s;
        let s3 = s2 * s;
        (2.0 * s3 - 3.0 * s2 + 1.0) * y0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * y1
            + (s3 - s2) * m1
            - target
    };
    let below_at_start = y0 - target < 0.0;
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    // 60 halvings take the bracket below 1e-18 of the step: rounding, for any step.
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (p(mid) < 0.0) == below_at_start && p(mid) != 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}
