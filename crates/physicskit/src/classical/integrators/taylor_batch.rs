//! The adaptive Taylor method ([`taylor`](super::taylor)) on `L` members at once: one
//! expansion of a shared field computes the Taylor coefficients of `L` states, one per vector
//! lane ([`LanesField`]), and each member then steps by its own scalar [`Taylor`] stepper.
//!
//! Each member's run is the one [`TaylorStepper`](super::TaylorStepper) gives it on the
//! output grid (what `integrate` with `method = taylor` does), bit for bit:
//!
//! - a member's [`Taylor`] takes the coefficients of its lane in place of a scalar expansion
//!   (the lanes do the scalar recurrences' operations in their order, so the same bits), and
//!   everything else of the step is [`Taylor::advance`]'s own code: the order, the step size
//!   from the last two coefficients, clamping to the output time and the end, the state
//!   update, dense output and its errors;
//! - the outputs are those of the grid, `t_i + dt` from output `i` (snapped to the end as
//!   [`TaylorStepper`](super::TaylorStepper) snaps it), each member restarting its stepper
//!   where `TaylorStepper` would.
//!
//! A member asks for an expansion when [`Taylor::advance`] needs one: its lane's field
//! records the state and declines; once every running member has asked (or finished its
//! outputs), one expansion serves them all, and the members resume. A member that finishes
//! hands its lane to the next member, so lanes stay busy while members take different
//! numbers of steps; a lane without a member computes a copy of a running lane's state.
//!
//! A member whose run fails (its stepper's error, or an output that is not finite) is
//! reported with the error; the caller reruns it alone for the error its single run gives.
//! Per-step data (energy errors, events, Lyapunov exponents) is not computed here: callers
//! that need it run members one at a time.

use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::taylor::{order_for, same_time, Taylor, TaylorField};
use crate::classical::integrators::Tolerances;

/// A field whose Taylor coefficients can be computed for `L` states at once, one per lane.
pub trait LanesField<const L: usize> {
    /// Dimension of the state.
    fn dim(&self) -> usize;

    /// Expands the solution through `(t[l], y[.][l])` for every lane `l` (`y` holds `dim`
    /// components, each an `[f64; L]`) to `order`; the coefficients stay in the field until
    /// the next expansion ([`lane`](Self::lane)).
    ///
    /// # Errors
    /// An `order` or a state length the field cannot expand.
    fn expand(&mut self, t: &[f64; L], y: &[[f64; L]], order: usize) -> Result<()>;

    /// Lane `lane`'s coefficients of the last expansion into `coefficients` (`dim` rows of
    /// `order + 1`, as [`TaylorField::coefficients`] fills them).
    fn lane(&self, lane: usize, coefficients: &mut [f64]);
}

/// One lane's scalar field: the coefficients of the lane's last expansion, handed to the
/// member's [`Taylor`] once, or a request for the next expansion.
#[derive(Debug)]
struct Slot {
    dim: usize,
    coefficients: Vec<f64>,
    /// The coefficients are fresh, at the state the member asked for.
    ready: bool,
    /// The member asked for an expansion at `(t, y)`.
    wanted: bool,
    t: f64,
    y: Vec<f64>,
}

impl TaylorField for Slot {
    fn dim(&self) -> usize {
        self.dim
    }

    /// The fresh coefficients of the lane, once; else records the request and declines
    /// with [`Error::Interrupted`] (no allocation), which the batch tells from a failure by
    /// `wanted`.
    fn coefficients(
        &mut self,
        t: f64,
        y: &[f64],
        _order: usize,
        coefficients: &mut [f64],
    ) -> Result<()> {
        if self.ready {
            debug_assert!(t.to_bits() == self.t.to_bits() && y == self.y.as_slice());
            self.ready = false;
            coefficients.copy_from_slice(&self.coefficients);
            Ok(())
        } else {
            self.wanted = true;
            self.t = t;
            self.y.copy_from_slice(y);
            Err(Error::Interrupted { t })
        }
    }
}

/// A lane: its member's run from output to output.
#[derive(Debug)]
struct Lane {
    /// The member running here, if any.
    member: Option<usize>,
    slot: Slot,
    stepper: Option<Taylor>,
    /// The output being computed (`1..=n_steps`).
    step: usize,
    /// Its time, once the output has begun.
    target: Option<f64>,
    /// The last output, and its time.
    out: Vec<f64>,
    out_t: f64,
    next: Vec<f64>,
}

/// What a lane does next.
enum Serve {
    /// Its member waits for an expansion.
    Expand,
    /// Its member has every output, or failed: the lane is free.
    Free,
}

impl Lane {
    fn new(dim: usize, order: usize) -> Self {
        Self {
            member: None,
            slot: Slot {
                dim,
                coefficients: vec![0.0; dim * (order + 1)],
                ready: false,
                wanted: false,
                t: 0.0,
                y: vec![0.0; dim],
            },
            stepper: None,
            step: 1,
            target: None,
            out: vec![0.0; dim],
            out_t: f64::NAN,
            next: vec![0.0; dim],
        }
    }

    /// Starts member `member` from `y0`.
    fn load(&mut self, member: usize, y0: &[f64]) {
        self.member = Some(member);
        self.stepper = None;
        self.step = 1;
        self.target = None;
        self.out.copy_from_slice(y0);
        self.out_t = f64::NAN;
        self.slot.ready = false;
        self.slot.wanted = false;
    }

    /// Runs the member until it needs an expansion, has all its outputs (each passed to
    /// `output(member, step, y)`) or fails (into `failed`).
    // Exact comparison: as TaylorStepper's, a grid time beyond the end.
    #[allow(clippy::float_cmp)]
    fn serve(
        &mut self,
        grid: &TimeGrid,
        tolerances: Tolerances,
        output: &mut impl FnMut(usize, usize, &[f64]),
        failed: &mut impl FnMut(usize, Error),
    ) -> Serve {
        let Some(member) = self.member else {
            return Serve::Free;
        };
        let (n, t_bound, dt) = (grid.n_steps(), grid.t_end(), grid.dt());
        let fail = |lane: &mut Self, failed: &mut dyn FnMut(usize, Error), e: Error| {
            lane.member = None;
            failed(member, e);
            Serve::Free
        };
        while self.step <= n {
            let target = match self.target {
                Some(target) => target,
                None => {
                    // TaylorStepper::advance from the grid's time of the last output.
                    let t = grid.time(self.step - 1);
                    let mut target = t + dt;
                    if same_time(target, t_bound) {
                        target = t_bound;
                    } else if (target - t_bound) * (t_bound - t).signum() > 0.0 {
                        let e = Error::InvalidArgument {
                            name: "h".into(),
                            reason: format!("t + h = {target} lies beyond the end {t_bound}"),
                        };
                        return fail(self, failed, e);
                    }
                    if self.stepper.is_none() || !same_time(t, self.out_t) {
                        match Taylor::new(self.slot.dim, tolerances, t, &self.out, t_bound) {
                            Ok(stepper) => self.stepper = Some(stepper),
                            Err(e) => return fail(self, failed, e),
                        }
                    }
                    self.target = Some(target);
                    target
                }
            };
            let Some(stepper) = self.stepper.as_mut() else {
                return Serve::Free;
            };
            match stepper.advance(&mut self.slot, target, &mut self.next) {
                Ok(()) => {
                    if !self.next.iter().all(|v| v.is_finite()) {
                        let e = Error::NonFinite {
                            name: "state".into(),
                            t: target,
                        };
                        return fail(self, failed, e);
                    }
                    self.out.copy_from_slice(&self.next);
                    self.out_t = target;
                    output(member, self.step, &self.out);
                    self.step += 1;
                    self.target = None;
                }
                Err(_) if self.slot.wanted => return Serve::Expand,
                Err(e) => return fail(self, failed, e),
            }
        }
        self.member = None;
        Serve::Free
    }
}

/// Integrates the members whose initial states are the rows of `starts` (`members x dim`,
/// row-major) on the grid `grid` by the adaptive Taylor method at `tolerances`, `L` at a
/// time on `field`: passes each output to `output(member, step, state)` (steps `1..=n_steps`,
/// in order per member) and each failed member's error to `failed(member, error)`, after
/// which that member gives no more outputs. `stop()` is asked before every expansion.
///
/// # Errors
/// [`Error::Interrupted`] once `stop()` says so; [`Error::DimensionMismatch`] for `starts`
/// not made of rows of the field's dimension; the field's refusal of an expansion.
pub fn integrate_batch<const L: usize, F: LanesField<L>>(
    field: &mut F,
    starts: &[f64],
    grid: &TimeGrid,
    tolerances: Tolerances,
    mut output: impl FnMut(usize, usize, &[f64]),
    mut failed: impl FnMut(usize, Error),
    stop: impl Fn() -> bool,
) -> Result<()> {
    let dim = field.dim();
    if dim == 0 || !starts.len().is_multiple_of(dim) {
        return Err(Error::DimensionMismatch {
            name: "starts".into(),
            expected: dim,
            found: starts.len(),
        });
    }
    let order = order_for(&tolerances);
    let mut members = starts.chunks_exact(dim).enumerate();
    let mut lanes: Vec<Lane> = (0..L).map(|_| Lane::new(dim, order)).collect();
    let mut t = [0.0; L];
    let mut y = vec![[0.0; L]; dim];
    loop {
        let mut any = None;
        for (l, lane) in lanes.iter_mut().enumerate() {
            loop {
                if lane.member.is_none() {
                    match members.next() {
                        Some((member, y0)) => lane.load(member, y0),
                        None => break,
                    }
                }
                if let Serve::Expand = lane.serve(grid, tolerances, &mut output, &mut failed) {
                    any = Some(l);
                    break;
                }
            }
        }
        let Some(running) = any else {
            return Ok(());
        };
        if stop() {
            return Err(Error::Interrupted { t: f64::NAN });
        }
        for (l, lane) in lanes.iter().enumerate() {
            // A lane without a request computes a running lane's state: finite work.
            let slot = if lane.slot.wanted {
                &lane.slot
            } else {
                &lanes[running].slot
            };
            t[l] = slot.t;
            for (yi, v) in y.iter_mut().zip(&slot.y) {
                yi[l] = *v;
            }
        }
        field.expand(&t, &y, order)?;
        for (l, lane) in lanes.iter_mut().enumerate() {
            if lane.slot.wanted {
                field.lane(l, &mut lane.slot.coefficients);
                lane.slot.wanted = false;
                lane.slot.ready = true;
            }
        }
    }
}
