//! Poincaré sections of any system, with any method: the crossings of an orbit with a
//! hyperplane `g(y) = a·y = c` of the state space.
//!
//! The orbit is integrated with the method's fixed step `dt`, exactly as `integrate` steps it
//! (the step sequence never changes). When the step from `t` to `t + dt` carries
//! `s(y) = a·y - c` across zero in the requested [`Direction`], the crossing is located as the
//! root `τ ∈ (0, dt]` of
//!
//! ```text
//! σ(τ) = s(Φ_τ(y(t))),
//! ```
//!
//! `Φ_τ` being one step of the *same method* with length `τ` from the state before the
//! crossing. `Φ_τ` is the method's own approximation of the flow over `τ`, accurate to its
//! order, so the crossing time and state carry the method's error and no more: no
//! interpolant of lower order, no separate integrator (Hénon's trick with RK4,
//! [`poincare`](super::poincare), is limited to fourth order). For a symplectic method the
//! crossing state is the image of a symplectic map, so it stays on the method's modified
//! energy surface. The root is found by the Illinois variant of regula falsi (Dowell & Jarratt,
//! BIT 11, 168–174, 1971), which keeps the bracket and converges superlinearly: about six to
//! ten extra steps per crossing, to a residual at the rounding level of `a·y`.
//!
//! With the Taylor method ([`taylor_section`]) each step is a polynomial in time, the
//! solution over the whole step: a crossing is the root of `σ(τ) = a·P(τ) - c` on the step's
//! polynomial `P`, found by Newton's method on `σ` and its derivative (kept inside the step's
//! bracket), so the crossing carries the method's error and the rounding of `P`, and costs
//! no further expansion of the field.
//!
//! For a coordinate section `y_k = c` the stored `y_k` is set to `c` exactly. The section is
//! taken in the system's own state (`[q, qdot]` for Lagrangian systems, even where an implicit
//! method runs on `[q, p]`).

use super::poincare::{Direction, PoincareSection};
use super::watch::AnalysisOptions;
use crate::classical::core::error::{check_finite, check_finite_scalar};
use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::taylor::{no_taylor_form, Taylor};
use crate::classical::integrators::Method;
use crate::classical::integrators::{Flow, Tolerances};
use crate::classical::model::erased::DynSystem;

/// Iteration cap of the crossing search; the Illinois iteration needs about ten.
const MAX_ITERATIONS: usize = 100;

/// A hyperplane of the state space.
#[derive(Debug, Clone, PartialEq)]
pub enum Plane {
    /// `y[index] = value`.
    Coordinate {
        /// Index into the state vector.
        index: usize,
        /// The section value.
        value: f64,
    },
    /// `a·y = c`.
    Linear {
        /// The functional's coefficients, one per state component.
        a: Vec<f64>,
        /// The right-hand side.
        c: f64,
    },
}

/// A surface of section: a [`Plane`] and the direction a crossing must go.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceOfSection {
    plane: Plane,
    direction: Direction,
}

impl SurfaceOfSection {
    /// The plane `y[index] = value`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite `value`.
    pub fn coordinate(index: usize, value: f64, direction: Direction) -> Result<Self> {
        Ok(Self {
            plane: Plane::Coordinate {
                index,
                value: check_finite_scalar("value", value)?,
            },
            direction,
        })
    }

    /// The plane `a·y = c`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-finite `c` or coefficient, or `a = 0`.
    pub fn linear(a: Vec<f64>, c: f64, direction: Direction) -> Result<Self> {
        check_finite_scalar("c", c)?;
        check_finite("a", &a, 0.0)?;
        if a.iter().all(|&v| v == 0.0) {
            return Err(Error::invalid("a", 0.0, "must have a non-zero coefficient"));
        }
        Ok(Self {
            plane: Plane::Linear { a, c },
            direction,
        })
    }

    /// The plane.
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The required direction.
    pub fn direction(&self) -> Direction {
        self.direction
    }

    /// `a·y - c`, and the scale `|a|·|y| + |c|` of its rounding.
    fn eval(&self, y: &[f64]) -> (f64, f64) {
        match &self.plane {
            Plane::Coordinate { index, value } => {
                (y[*index] - value, y[*index].abs() + value.abs())
            }
            Plane::Linear { a, c } => {
                let (mut s, mut scale) = (-c, c.abs());
                for (ai, yi) in a.iter().zip(y) {
                    s += ai * yi;
                    scale += (ai * yi).abs();
                }
                (s, scale)
            }
        }
    }

    /// Checks the plane against a state of length `dim`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for an index past the state or a functional of another
    /// length.
    pub fn check_dim(&self, dim: usize) -> Result<()> {
        let (expected, found, name) = match &self.plane {
            Plane::Coordinate { index, .. } if *index >= dim => {
                (dim, *index, "coordinate (an index into the state)")
            }
            Plane::Linear { a, .. } if a.len() != dim => {
                (dim, a.len(), "a (one per state component)")
            }
            _ => return Ok(()),
        };
        Err(Error::DimensionMismatch {
            name: name.into(),
            expected,
            found,
        })
    }

    fn pin(&self, y: &mut [f64]) {
        if let Plane::Coordinate { index, value } = self.plane {
            y[index] = value;
        }
    }
}

/// Where a run on a [`Flow`] ended: the system state and time to continue from.
#[derive(Debug, Clone, PartialEq)]
pub struct Continuation {
    /// The system's state at `t`.
    pub state: Vec<f64>,
    /// The final time.
    pub t: f64,
}

/// The crossings of the orbit from `state0` over `grid` on `flow`, at most `max_crossings`
/// of them (the run stops at the last one kept), and where the run ended. `options` has the
/// observer ([`AnalysisOptions`]; a section has no history to thin).
///
/// # Errors
/// [`Error::DimensionMismatch`] for a state or plane of the wrong length,
/// [`Error::NonFinite`] for a diverging orbit; [`Error::Interrupted`] when the observer stops
/// the run; whatever the system or method report.
pub fn section_on_flow(
    flow: &mut dyn Flow,
    state0: &[f64],
    grid: &TimeGrid,
    surface: &SurfaceOfSection,
    max_crossings: usize,
    mut options: AnalysisOptions<'_>,
) -> Result<(PoincareSection, Continuation)> {
    let n = flow.dim();
    let sdim = state0.len();
    surface.check_dim(sdim)?;
    check_finite("state", state0, grid.t0())?;
    let mut y = vec![0.0; n];
    flow.enter(grid.t0(), state0, &mut y)?;
    let mut before = y.clone();
    let mut state = state0.to_vec();
    let mut trial = y.clone();
    let mut trial_state = state.clone();
    let mut out = PoincareSection {
        dim: sdim,
        ..PoincareSection::default()
    };
    let (mut s_before, _) = surface.eval(&state);
    let dt = grid.dt();
    let mut t_end = grid.t0();
    let mut watch = options.watch(grid.n_steps());
    for i in 0..grid.n_steps() {
        if out.len() >= max_crossings {
            break;
        }
        let t = grid.time(i);
        before.copy_from_slice(&y);
        flow.step(t, &mut y, dt)?;
        t_end = grid.time(i + 1);
        check_finite("state", &y, t_end)?;
        flow.leave(t_end, &y, &mut state)?;
        let (s_after, _) = surface.eval(&state);
        if surface.direction().crossed(s_before, s_after) {
            let tau = locate(
                flow,
                surface,
                t,
                &before,
                (s_before, s_after, dt),
                &mut trial,
                &mut trial_state,
            )?;
            surface.pin(&mut trial_state);
            out.t.push(t + tau);
            out.states.extend_from_slice(&trial_state);
        }
        s_before = s_after;
        watch.tick(i + 1, t_end)?;
    }
    Ok((out, Continuation { state, t: t_end }))
}

/// The root `τ` of `s(Φ_τ(before))` in `(0, dt]` by the Illinois iteration; the crossing's
/// system state is left in `trial_state`.
fn locate(
    flow: &mut dyn Flow,
    surface: &SurfaceOfSection,
    t: f64,
    before: &[f64],
    (s_before, s_after, dt): (f64, f64, f64),
    trial: &mut [f64],
    trial_state: &mut [f64],
) -> Result<f64> {
    let (mut a, mut fa, mut b, mut fb) = (0.0, s_before, dt, s_after);
    let mut side = 0i8;
    let mut tau = dt;
    for _ in 0..MAX_ITERATIONS {
        // Regula falsi; bisection where it leaves the bracket (fa = fb gives a non-finite or
        // outside point, caught by the same test).
        tau = (a * fb - b * fa) / (fb - fa);
        if !(tau > a && tau <= b) {
            tau = 0.5 * (a + b);
        }
        trial.copy_from_slice(before);
        flow.step_fresh(t, trial, tau)?;
        check_finite("section state", trial, t + tau)?;
        flow.leave(t + tau, trial, trial_state)?;
        let (f, scale) = surface.eval(trial_state);
        if f.abs() <= 4.0 * f64::EPSILON * scale || b - a <= 4.0 * f64::EPSILON * dt {
            break;
        }
        if (f > 0.0) == (fb > 0.0) {
            b = tau;
            fb = f;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = tau;
            fa = f;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    Ok(tau)
}

/// The Poincaré section of `system` over `t_span` with step `dt` and `method` (the system's
/// default for `None`), keeping at most `max_crossings`; the system is left at the end of the
/// run, as `integrate` leaves it, so a second call continues the orbit.
///
/// # Errors
/// As [`section_on_flow`]; [`Error::InvalidTimeSpan`] for a bad span or step;
/// [`Error::UnsupportedMethod`] for a method the system cannot run.
///
/// # Example
/// The oscillator `x'' = -x` from `(1, 0)` crosses `x = 0` upwards at `t = 3π/2 + 2πj`:
///
/// ```
/// use physicskit::classical::analysis::poincare::Direction;
/// use physicskit::classical::analysis::section::{poincare_section, SurfaceOfSection};
/// use physicskit::classical::model::erased::Hamiltonian;
/// use physicskit::classical::examples::HarmonicOscillator;
/// use physicskit::classical::Method;
///
/// let mut osc = Hamiltonian(HarmonicOscillator::new(1.0, 0.0, 1.0, 1.0).unwrap());
/// let plane = SurfaceOfSection::coordinate(0, 0.0, Direction::Increasing).unwrap();
/// let cut = poincare_section(&mut osc, (0.0, 20.0), 0.01, Some(Method::Yoshida4), &plane, usize::MAX)
///     .unwrap();
/// assert_eq!(cut.len(), 3);
/// // yoshida4's phase error at dt = 0.01 is ~5e-9 by t = 3π/2.
/// assert!((cut.t[0] - 1.5 * std::f64::consts::PI).abs() < 1e-7);
/// ```
pub fn poincare_section<S: DynSystem + ?Sized>(
    system: &mut S,
    t_span: (f64, f64),
    dt: f64,
    method: Option<Method>,
    surface: &SurfaceOfSection,
    max_crossings: usize,
) -> Result<PoincareSection> {
    let grid = TimeGrid::new(t_span, dt)?;
    let method = method.unwrap_or_else(|| system.default_method());
    if method.needs_taylor_form() {
        // The Taylor method chooses its own steps: `dt` is not used.
        return taylor_section(
            system,
            t_span,
            Tolerances::default(),
            surface,
            max_crossings,
        );
    }
    let state0 = system.dynamical().state().to_vec();
    let (cut, end) = {
        let mut flow = system.flow(method, 0)?;
        section_on_flow(
            flow.as_mut(),
            &state0,
            &grid,
            surface,
            max_crossings,
            AnalysisOptions::default(),
        )?
    };
    system.reset(Some(&end.state), end.t)?;
    Ok(cut)
}

/// The crossings of `system`'s orbit over `t_span` with `surface`, by the adaptive Taylor
/// method at `tolerances`, at most `max_crossings` of them (the run stops at the last one
/// kept); each located by Newton's method on the step's Taylor polynomial (see the module
/// docs). The system is left where the run ended, so a second call continues the orbit.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for a system without a Taylor form
/// ([`DynamicalSystem::taylor_field`](crate::classical::DynamicalSystem::taylor_field));
/// [`Error::InvalidTimeSpan`] for a bad span; [`Error::DimensionMismatch`] for a plane of
/// the wrong length; [`Error::NonFinite`] for a diverging orbit; as
/// [`Taylor::step`](crate::classical::integrators::taylor::Taylor::step).
pub fn taylor_section<S: DynSystem + ?Sized>(
    system: &mut S,
    t_span: (f64, f64),
    tolerances: Tolerances,
    surface: &SurfaceOfSection,
    max_crossings: usize,
) -> Result<PoincareSection> {
    TimeGrid::new(t_span, t_span.1 - t_span.0)?;
    let dynamical = system.dynamical();
    let state0 = dynamical.state().to_vec();
    let dim = state0.len();
    surface.check_dim(dim)?;
    check_finite("state", &state0, t_span.0)?;
    let mut field = dynamical
        .taylor_field()
        .ok_or_else(|| no_taylor_form("this system"))??;
    let mut taylor = Taylor::new(&*field, tolerances, t_span.0, &state0, t_span.1)?;
    let mut out = PoincareSection {
        dim,
        ..PoincareSection::default()
    };
    let (mut s_before, _) = surface.eval(&state0);
    let mut crossing = vec![0.0; dim];
    while out.len() < max_crossings && taylor.step(field.as_mut())? {
        check_finite("state", taylor.state(), taylor.time().0)?;
        let (s_after, _) = surface.eval(taylor.state());
        if surface.direction().crossed(s_before, s_after) {
            let tau = root_on_polynomial(&taylor, surface.plane(), s_before, s_after);
            taylor.eval_state(tau, &mut crossing);
            surface.pin(&mut crossing);
            let (hi, lo) = taylor.step_start();
            out.t.push(hi + (lo + tau));
            out.states.extend_from_slice(&crossing);
        }
        s_before = s_after;
    }
    let end = taylor.state().to_vec();
    system.reset(Some(&end), taylor.time().0)?;
    Ok(out)
}

/// The root `τ` of `σ(τ) = a·P(τ) - c` on the current step of `taylor`, where
/// `σ(0) = s0` and `σ(h) = s1` have opposite signs: Newton's method from the secant's root,
/// each iterate kept inside the shrinking bracket (bisection when Newton leaves it), until the
/// update or the bracket is at the rounding level of `τ`.
fn root_on_polynomial(taylor: &Taylor, plane: &Plane, s0: f64, s1: f64) -> f64 {
    let sigma = |tau: f64| -> (f64, f64) {
        match plane {
            Plane::Coordinate { index, value } => {
                let (v, d) = taylor.eval_component(*index, tau);
                (v - value, d)
            }
            Plane::Linear { a, c } => {
                let (mut v, mut d) = (-c, 0.0);
                for (i, ai) in a.iter().enumerate().filter(|(_, ai)| **ai != 0.0) {
                    let (vi, di) = taylor.eval_component(i, tau);
                    v += ai * vi;
                    d += ai * di;
                }
                (v, d)
            }
        }
    };
    let h = taylor.step_length();
    // The bracket [a, b] (as signed offsets, `h` may be negative) with `σ(a)` of `s0`'s sign.
    let (mut a, mut b) = (0.0_f64, h);
    let mut tau = h * s0 / (s0 - s1);
    if !tau.is_finite() {
        tau = 0.5 * h;
    }
    let inside = |x: f64, a: f64, b: f64| x > a.min(b) && x < a.max(b);
    for _ in 0..MAX_ITERATIONS {
        let (f, df) = sigma(tau);
        if f == 0.0 {
            return tau;
        }
        if (f > 0.0) == (s0 > 0.0) {
            a = tau;
        } else {
            b = tau;
        }
        let mut next = tau - f / df;
        if !inside(next, a, b) {
            next = 0.5 * (a + b);
        }
        let done = (next - tau).abs() <= 2.0 * f64::EPSILON * tau.abs()
            || (b - a).abs() <= 2.0 * f64::EPSILON * h.abs();
        tau = next;
        if done {
            break;
        }
    }
    tau
}
