//! [`Lab`]: one system running in the lab, stepped a frame at a time.
//!
//! The system runs in a [`Session`] (`DynSystem::start_with`): a frame advances it `n` steps
//! with the stepper and buffers kept from frame to frame, so frames allocate nothing and a run
//! has the bits of one `integrate` over all its steps, whatever the frames. An adaptive method
//! (`dop853`, `taylor`) runs at the lab's tolerance (`rtol = atol`, [`Lab::set_tolerance`])
//! with `dt` the output spacing: each step of a frame is one output, reached by as many
//! internal steps as the tolerance needs (the session's documentation says which samples
//! match `integrate`'s). With a section the
//! frame advances one step at a time, and each step that carries the section coordinate
//! across its value in the section's direction is refined to the crossing by Hénon's trick
//! (M. Hénon, Physica D 5, 412, 1982), as `analysis::poincare` does.
//!
//! The energy error is `|E - E0| / |E0|` with `E0` the energy of the run's initial state
//! (absolute when `E0 = 0`). What the page reads lives in buffers the lab owns (`positions`,
//! `crossings`), refilled in place each frame (`Capabilities::positions_into`); the crossings
//! grow by doubling up to [`MAX_CROSSINGS`], then drop the oldest first.
//!
//! Crossings accumulate over orbits: each run carries an orbit number, recorded with each of
//! its crossings, so the page colours orbits apart. A launch on the section
//! ([`Lab::launch_at_energy`]) starts a new orbit on the same energy surface and keeps the
//! earlier orbits' crossings; a new state of another energy ([`Lab::set_state`]), a new
//! section or [`Lab::clear_crossings`] forgets them; [`Lab::reset`] forgets only the current
//! orbit's (its rerun records them again).

use physicskit::classical::analysis::poincare::{Direction, HenonWork, Section};
use physicskit::classical::catalog;
use physicskit::classical::integrators::{taylor, FirstOrder};
use physicskit::classical::model::erased::DynSystem;
use physicskit::classical::model::Session;
use physicskit::classical::model::SystemEntry;
use physicskit::classical::{Method, Tolerances};

use crate::params::values_from_json;

/// RK4 substeps of each Hénon step: two keep its error far below a frame's own steps'
/// (`poincare::SectionRun` uses the same).
const HENON_SUBSTEPS: usize = 2;

/// Crossings kept; older ones are dropped first (a section shows a few thousand points).
const MAX_CROSSINGS: usize = 20_000;

/// The step a lab starts with, before its first frame names one (the page's default).
const INITIAL_DT: f64 = 1e-3;

/// The tolerance (`rtol = atol`) an adaptive method runs at until one is set: the core's
/// default relative tolerance ([`Tolerances::default`]), the middle of the page's menu.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;

/// The tolerances of the lab's tolerance `tol` (`rtol = atol = tol`), for `method`: `None`
/// for a fixed-step method, which takes none.
///
/// # Errors
/// A `tol` that is not finite and positive, with the core's message (naming `rtol`).
fn tolerances_for(method: Method, tol: f64) -> Result<Option<Tolerances>, String> {
    let tolerances = Tolerances::new(tol, tol).map_err(|e| e.to_string())?;
    Ok(method.is_adaptive().then_some(tolerances))
}

/// The order the method `name` steps at on the catalogue system `system`, built from its
/// defaults overridden by the JSON object `params`, with the lab's tolerance `tol`
/// (`rtol = atol`): the Taylor method's order is chosen by its tolerances and the work of its
/// recurrences on that system (`taylor::order_for`, the rule its stepper follows), every other
/// method's is the one its catalogue row gives. The page's facts line shows it, so it asks
/// here rather than repeat the rule.
///
/// # Errors
/// An unknown method name, a `tol` that is not finite and positive, or one the Taylor method
/// refuses (as its stepper does: `taylor::check_tolerances`); for `taylor`, an unknown system,
/// refused parameters, or a system without a Taylor form, with the catalogue's message.
pub fn method_order(system: &str, params: &str, name: &str, tol: f64) -> Result<u32, String> {
    let method = name
        .parse::<Method>()
        .map_err(|_| format!("no method is called `{name}`"))?;
    Ok(match tolerances_for(method, tol)? {
        Some(tolerances) if method == Method::Taylor => {
            taylor::check_tolerances(&tolerances).map_err(|e| e.to_string())?;
            let entry = catalog::find(system).map_err(|e| e.to_string())?;
            let built = entry
                .build_from(values_from_json(entry, params)?)
                .map_err(|e| e.to_string())?;
            let field = built
                .dynamical()
                .taylor_field()
                .ok_or_else(|| format!("{} has no Taylor form", entry.name))?
                .map_err(|e| e.to_string())?;
            let order = taylor::order_for(&tolerances, &field.step_cost());
            u32::try_from(order).unwrap_or(u32::MAX)
        }
        _ => method.order(),
    })
}

/// The method `name`, if `entry` takes it in the lab. The name is untrusted (a share link, a
/// script call): an unknown name and a method the system does not take are each refused with
/// a message naming it and the methods the lab runs this system with.
fn method_of(entry: &SystemEntry, name: &str) -> Result<Method, String> {
    let runs = || {
        entry
            .methods()
            .map(Method::name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Ok(method) = name.parse::<Method>() else {
        return Err(format!(
            "no method is called `{name}`; the lab runs `{}` with {}",
            entry.name,
            runs()
        ));
    };
    if !entry.methods().any(|m| m == method) {
        return Err(format!(
            "`{}` cannot be integrated with {name}; the lab runs it with {}",
            entry.name,
            runs()
        ));
    }
    Ok(method)
}

/// One running system.
pub struct Lab {
    entry: &'static SystemEntry,
    /// Always `Some` between calls; taken only while the method or tolerance changes.
    session: Option<Box<dyn Session>>,
    /// The tolerance (`rtol = atol`) of an adaptive method; kept while a fixed-step method
    /// runs, for the next adaptive one.
    tolerance: f64,
    /// The run's initial state (what `reset` returns to) and its energy.
    state0: Vec<f64>,
    energy0: f64,
    positions: Vec<f64>,
    /// Positions of a configuration the page asks about (dragging inverts `positions`).
    probe: Vec<f64>,
    section: Option<Section>,
    /// Crossing states, one after another (`state_len` values each).
    crossings: Vec<f64>,
    /// The orbit number of each crossing.
    crossing_orbits: Vec<u32>,
    /// The current run's orbit number.
    orbit: u32,
    crossing: Vec<f64>,
    /// The state before the step being checked for a crossing.
    before: Vec<f64>,
    henon: HenonWork,
}

impl Lab {
    /// Builds the catalogue entry `name` from its defaults overridden by the JSON object
    /// `params`, with its default method (an adaptive one at the lab's
    /// default tolerance, `DEFAULT_TOLERANCE`).
    ///
    /// # Errors
    /// The catalogue's message for an unknown system or a refused value.
    pub fn new(name: &str, params: &str) -> Result<Self, String> {
        Self::with_method(name, params, None)
    }

    /// [`Lab::new`] with the method named by `method` (`None`: the default). Some parameter
    /// values run only with some methods (a projectile with drag is not separable, so the
    /// splitting methods refuse it): a setup is built with its method, never with the default
    /// first.
    ///
    /// # Errors
    /// The catalogue's message for an unknown system or a refused value; an unknown method,
    /// or one this system cannot use with these values.
    pub fn with_method(name: &str, params: &str, method: Option<&str>) -> Result<Self, String> {
        Self::with_tolerance(name, params, method, DEFAULT_TOLERANCE)
    }

    /// [`Lab::with_method`] with the tolerance `tol` (`rtol = atol`) of an adaptive method
    /// (kept, and unused, by a fixed-step one).
    ///
    /// # Errors
    /// As [`Lab::with_method`]; a `tol` that is not finite and positive, or one the method
    /// refuses (`taylor` takes `rtol` from `2^-54` to below 1), with the core's message.
    pub fn with_tolerance(
        name: &str,
        params: &str,
        method: Option<&str>,
        tol: f64,
    ) -> Result<Self, String> {
        let entry = catalog::find(name).map_err(|e| e.to_string())?;
        let given = values_from_json(entry, params)?;
        let method = match method {
            Some(name) => method_of(entry, name)?,
            None => entry.default_method,
        };
        let tolerances = tolerances_for(method, tol)?;
        let system = entry.build_from(given).map_err(|e| e.to_string())?;
        let state0 = system.dynamical().state().to_vec();
        let energy0 = system.dynamical().energy(&state0);
        let n = state0.len();
        let session = system
            .start_with(method, INITIAL_DT, tolerances)
            .map_err(|r| r.error.to_string())?;
        let mut lab = Self {
            entry,
            session: Some(session),
            tolerance: tol,
            state0,
            energy0,
            positions: Vec::new(),
            probe: Vec::new(),
            section: None,
            crossings: Vec::with_capacity(n * 1024),
            crossing_orbits: Vec::with_capacity(1024),
            orbit: 0,
            crossing: vec![0.0; n],
            before: vec![0.0; n],
            henon: HenonWork::new(n),
        };
        lab.refresh_positions();
        Ok(lab)
    }

    /// The catalogue entry.
    pub fn entry(&self) -> &'static SystemEntry {
        self.entry
    }

    /// Chooses the method by name.
    ///
    /// # Errors
    /// An unknown name, or a method this system cannot use.
    pub fn set_method(&mut self, name: &str) -> Result<(), String> {
        let method = method_of(self.entry, name)?;
        if method == self.method() {
            return Ok(());
        }
        self.restart_session(method, self.tolerance)
    }

    /// Sets the tolerance (`rtol = atol`) of an adaptive method; a fixed-step method keeps
    /// it for the next adaptive one. An adaptive run continues from its current state and
    /// clock with a stepper at the new tolerance.
    ///
    /// # Errors
    /// A `tol` that is not finite and positive, or one the method in use refuses, with the
    /// core's message; the lab then runs on as it was.
    pub fn set_tolerance(&mut self, tol: f64) -> Result<(), String> {
        let method = self.method();
        let tolerances = tolerances_for(method, tol)?;
        if tolerances.is_some() && tol.to_bits() != self.tolerance.to_bits() {
            self.restart_session(method, tol)?;
        }
        self.tolerance = tol;
        Ok(())
    }

    /// The tolerance (`rtol = atol`) an adaptive method runs at.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// A new session of `method` at the tolerance `tol` from the current state and clock,
    /// or, if it is refused, the one in use again (it ran this system at this `dt` a moment
    /// ago).
    fn restart_session(&mut self, method: Method, tol: f64) -> Result<(), String> {
        let tolerances = tolerances_for(method, tol)?;
        let old = self.session.take().expect("a lab always holds its session");
        let (dt, previous, before) = (old.dt(), old.method(), old.tolerances());
        match old.into_system().start_with(method, dt, tolerances) {
            Ok(session) => {
                self.session = Some(session);
                self.tolerance = tol;
                Ok(())
            }
            Err(refused) => {
                let error = refused.error.to_string();
                let back = refused
                    .system
                    .start_with(previous, dt, before)
                    .map_err(|r| r.error.to_string())?;
                self.session = Some(back);
                Err(error)
            }
        }
    }

    /// The method in use.
    pub fn method(&self) -> Method {
        self.session().method()
    }

    fn session(&self) -> &dyn Session {
        self.session
            .as_deref()
            .expect("a lab always holds its session")
    }

    fn session_mut(&mut self) -> &mut dyn Session {
        self.session
            .as_deref_mut()
            .expect("a lab always holds its session")
    }

    fn system(&self) -> &dyn DynSystem {
        self.session().system()
    }

    /// Advances `n` steps of `dt`, recording section crossings if a section is set.
    ///
    /// # Errors
    /// The integrator's message (a refused step, a non-finite state, a `dt` that is not
    /// finite and positive); the state is then left where the failed frame started.
    pub fn step(&mut self, n: u32, dt: f64) -> Result<(), String> {
        if n == 0 {
            return Ok(());
        }
        let session = self
            .session
            .as_deref_mut()
            .expect("a lab always holds its session");
        if dt.to_bits() != session.dt().to_bits() {
            session.set_dt(dt).map_err(|e| e.to_string())?;
        }
        let Some(section) = self.section else {
            return session
                .advance(n as usize)
                .map_err(|e| e.to_string())
                .map(|()| {
                    self.refresh_positions();
                });
        };
        let k = section.coordinate();
        let c = section.value();
        for _ in 0..n {
            self.before.copy_from_slice(session.state());
            let t_before = session.t();
            session.advance(1).map_err(|e| e.to_string())?;
            let (a, b) = (self.before[k] - c, session.state()[k] - c);
            let up = a < 0.0 && b >= 0.0;
            let down = a > 0.0 && b <= 0.0;
            let wanted = match section.direction() {
                Direction::Increasing => up,
                Direction::Decreasing => down,
                Direction::Both => up || down,
            };
            if !wanted {
                continue;
            }
            let field = FirstOrder(session.system().dynamical());
            // A tangency (no transversal crossing) is skipped, as the section runs do.
            if self
                .henon
                .step(
                    &field,
                    t_before,
                    &self.before,
                    &section,
                    HENON_SUBSTEPS,
                    &mut self.crossing,
                )
                .is_ok()
            {
                if self.crossing_orbits.len() >= MAX_CROSSINGS {
                    self.crossings.drain(..self.crossing.len());
                    self.crossing_orbits.remove(0);
                }
                self.crossings.extend_from_slice(&self.crossing);
                self.crossing_orbits.push(self.orbit);
            }
        }
        self.refresh_positions();
        Ok(())
    }

    /// The current state (`[q, p]`, `[q, qdot]` for Lagrangian systems, or the ODE state).
    pub fn state(&self) -> &[f64] {
        self.session().state()
    }

    /// The clock.
    pub fn time(&self) -> f64 {
        self.session().t()
    }

    /// The energy of the current state.
    pub fn energy(&self) -> f64 {
        self.session().energy()
    }

    /// The energy of the run's initial state.
    pub fn energy0(&self) -> f64 {
        self.energy0
    }

    /// `|E - E0| / |E0|` (`|E - E0|` when `E0 = 0`).
    pub fn energy_error(&self) -> f64 {
        let d = (self.energy() - self.energy0).abs();
        if self.energy0 == 0.0 {
            d
        } else {
            d / self.energy0.abs()
        }
    }

    /// Drawing positions `[x1, y1, ...]` of the current configuration (empty when the system
    /// does not offer the `positions` capability).
    pub fn positions(&self) -> &[f64] {
        &self.positions
    }

    /// Drawing positions of the configuration `q` (empty when the system does not offer
    /// them), for the page's drag, which solves `positions(q) = pointer` numerically.
    ///
    /// # Errors
    /// A configuration of the wrong length.
    pub fn positions_of(&mut self, q: &[f64]) -> Result<&[f64], String> {
        self.probe.clear();
        let system = self
            .session
            .as_deref()
            .expect("a lab always holds its session")
            .system();
        if let Some(done) = system.capabilities().positions_into(q, &mut self.probe) {
            done.map_err(|e| e.to_string())?;
        }
        Ok(&self.probe)
    }

    /// The positions [`positions_of`](Self::positions_of) computed last.
    pub fn probe(&self) -> &[f64] {
        &self.probe
    }

    /// Starts a new run from `state` at `t = 0`: it becomes the initial state that `reset`
    /// returns to and the energy reference. The recorded crossings are forgotten (they lie
    /// on another energy surface).
    ///
    /// # Errors
    /// A state of the wrong length or with non-finite entries; the lab is then unchanged.
    pub fn set_state(&mut self, state: &[f64]) -> Result<(), String> {
        self.start_run(state)?;
        self.clear_crossings();
        Ok(())
    }

    /// The energy of any `state` of this system (the page traces the energy surface's edge
    /// on a section with it).
    ///
    /// # Errors
    /// A state of the wrong length or with non-finite entries.
    pub fn energy_of(&self, state: &[f64]) -> Result<f64, String> {
        let n = self.state0.len();
        if state.len() != n {
            return Err(format!(
                "a state of this system has {n} entries, not {}",
                state.len()
            ));
        }
        if !state.iter().all(|x| x.is_finite()) {
            return Err("a state must be finite".into());
        }
        Ok(self.system().dynamical().energy(state))
    }

    fn start_run(&mut self, state: &[f64]) -> Result<(), String> {
        self.session_mut()
            .restart(Some(state), 0.0)
            .map_err(|e| e.to_string())?;
        self.state0.clear();
        self.state0.extend_from_slice(state);
        self.energy0 = self.system().dynamical().energy(state);
        self.orbit = self.orbit.wrapping_add(1);
        self.refresh_positions();
        Ok(())
    }

    /// Returns to the run's initial state at `t = 0`, forgetting the current orbit's
    /// crossings (the rerun records them again).
    ///
    /// # Errors
    /// None in practice (the initial state was accepted before).
    pub fn reset(&mut self) -> Result<(), String> {
        let session = self
            .session
            .as_deref_mut()
            .expect("a lab always holds its session");
        session
            .restart(Some(&self.state0), 0.0)
            .map_err(|e| e.to_string())?;
        let kept = self
            .crossing_orbits
            .iter()
            .rposition(|&o| o != self.orbit)
            .map_or(0, |i| i + 1);
        self.crossing_orbits.truncate(kept);
        self.crossings.truncate(kept * self.crossing.len());
        self.refresh_positions();
        Ok(())
    }

    /// The run's initial state.
    pub fn initial_state(&self) -> &[f64] {
        &self.state0
    }

    /// Records crossings of `state[coordinate] = value` in `direction` (`+1` increasing,
    /// `-1` decreasing, `0` both) from now on; clears those recorded.
    ///
    /// # Errors
    /// A coordinate past the state or a non-finite value.
    pub fn set_section(
        &mut self,
        coordinate: usize,
        value: f64,
        direction: i32,
    ) -> Result<(), String> {
        if coordinate >= self.state0.len() {
            return Err(format!(
                "section coordinate {coordinate} is past the state (length {})",
                self.state0.len()
            ));
        }
        let direction = match direction.signum() {
            1 => Direction::Increasing,
            -1 => Direction::Decreasing,
            _ => Direction::Both,
        };
        self.section = Some(Section::new(coordinate, value, direction).map_err(|e| e.to_string())?);
        self.clear_crossings();
        Ok(())
    }

    /// The crossings recorded, one state after another, oldest first.
    pub fn crossings(&self) -> &[f64] {
        &self.crossings
    }

    /// The orbit number of each crossing (one per state in [`crossings`](Self::crossings)):
    /// equal numbers, one orbit.
    pub fn crossing_orbits(&self) -> &[u32] {
        &self.crossing_orbits
    }

    /// Forgets the recorded crossings.
    pub fn clear_crossings(&mut self) {
        self.crossings.clear();
        self.crossing_orbits.clear();
    }

    /// Starts a new run (as [`set_state`](Self::set_state)) at the energy of the current
    /// run's initial state: entries `assign` of the current state are replaced, and entry
    /// `solve` (a momentum, entering the energy as a quadratic kinetic term) is chosen `>= 0`
    /// so that the energy is `E0`. For the Hénon–Heiles section: `x, px` clicked, `y = 0`,
    /// `py` solved. The new run is a new orbit: the crossings recorded so far stay.
    ///
    /// # Errors
    /// No such state at this energy (the point lies outside the energy surface's section), or
    /// indices past the state.
    pub fn launch_at_energy(
        &mut self,
        assign: &[(usize, f64)],
        solve: usize,
    ) -> Result<(), String> {
        let target = self.energy0;
        let mut state = self.state().to_vec();
        let n = state.len();
        for &(i, x) in assign {
            *state
                .get_mut(i)
                .ok_or_else(|| format!("index {i} is past the state (length {n})"))? = x;
        }
        if solve >= n {
            return Err(format!("index {solve} is past the state (length {n})"));
        }
        let d = self.system().dynamical();
        let energy_at = |s: &mut Vec<f64>, p: f64| {
            s[solve] = p;
            d.energy(s)
        };
        if energy_at(&mut state, 0.0) > target {
            return Err(format!(
                "no orbit through this point at the energy E = {target:.6}: its potential \
                 energy is higher"
            ));
        }
        // The energy grows with |p| (a kinetic term): bracket, then bisect to the last bit.
        let mut hi = 1.0;
        while energy_at(&mut state, hi) < target {
            hi *= 2.0;
            if hi > 1e150 {
                return Err("no momentum reaches this energy".into());
            }
        }
        let mut lo = 0.0;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if energy_at(&mut state, mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        state[solve] = lo;
        self.start_run(&state)?;
        // The run stays on the chosen energy surface: keep E0, not the bisection's rounding.
        self.energy0 = target;
        Ok(())
    }

    fn refresh_positions(&mut self) {
        let system = self
            .session
            .as_deref()
            .expect("a lab always holds its session")
            .system();
        let state = system.dynamical().state();
        let q = match system.ndof() {
            Some(n) if n <= state.len() => &state[..n],
            _ => state,
        };
        if !matches!(
            system.capabilities().positions_into(q, &mut self.positions),
            Some(Ok(()))
        ) {
            self.positions.clear();
        }
    }
}
