//! [`Lab`]: one system running in the lab, stepped a frame at a time.
//!
//! A frame is one `integrate` call of `n` steps from the current time (the system keeps its
//! state and clock between calls, so frames continue each other). Without a section only the
//! final sample is stored; with one, every sample of the frame is, and each step that
//! carries the section coordinate across its value in the section's direction is refined to
//! the crossing by Hénon's trick (M. Hénon, Physica D 5, 412, 1982), as
//! `analysis::poincare` does.
//!
//! The energy error is `|E - E0| / |E0|` with `E0` the energy of the run's initial state
//! (absolute when `E0 = 0`). What the page reads lives in buffers the lab owns (`positions`,
//! `crossings`), refilled in place each frame.

use physicskit::classical::analysis::poincare::{henon_step, Direction, Section};
use physicskit::classical::catalog;
use physicskit::classical::core::erased::DynSystem;
use physicskit::classical::core::{IntegrateOptions, SystemEntry};
use physicskit::classical::integrators::FirstOrder;
use physicskit::classical::Method;

use crate::params::values_from_json;

/// RK4 substeps of each Hénon step: two keep its error far below a frame's own steps'
/// (`poincare::SectionRun` uses the same).
const HENON_SUBSTEPS: usize = 2;

/// Crossings kept; older ones are dropped first (a section shows a few thousand points).
const MAX_CROSSINGS: usize = 20_000;

/// One running system.
pub struct Lab {
    entry: &'static SystemEntry,
    system: Box<dyn DynSystem>,
    method: Method,
    /// The run's initial state (what `reset` returns to) and its energy.
    state0: Vec<f64>,
    energy0: f64,
    positions: Vec<f64>,
    /// Positions of a configuration the page asks about (dragging inverts `positions`).
    probe: Vec<f64>,
    section: Option<Section>,
    /// Crossing states, one after another (`state_len` values each).
    crossings: Vec<f64>,
    crossing: Vec<f64>,
}

impl Lab {
    /// Builds the catalogue entry `name` from its defaults overridden by the JSON object
    /// `params`, with its default method.
    ///
    /// # Errors
    /// The catalogue's message for an unknown system or a refused value.
    pub fn new(name: &str, params: &str) -> Result<Self, String> {
        let entry = catalog::find(name).map_err(|e| e.to_string())?;
        let given = values_from_json(entry, params)?;
        let system = entry.build_from(given).map_err(|e| e.to_string())?;
        let state0 = system.dynamical().state().to_vec();
        let energy0 = system.dynamical().energy(&state0);
        let n = state0.len();
        let mut lab = Self {
            entry,
            method: entry.default_method,
            system,
            state0,
            energy0,
            positions: Vec::new(),
            probe: Vec::new(),
            section: None,
            crossings: Vec::with_capacity(n * 1024),
            crossing: vec![0.0; n],
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
        let method: Method = name
            .parse()
            .map_err(|e: physicskit::classical::Error| e.to_string())?;
        if !self.entry.methods().any(|m| m == method) {
            return Err(format!(
                "`{}` cannot be integrated with {name}; it takes {}",
                self.entry.name,
                self.entry
                    .methods()
                    .map(Method::name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        self.method = method;
        Ok(())
    }

    /// The method in use.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Advances `n` steps of `dt`, recording section crossings if a section is set.
    ///
    /// # Errors
    /// The integrator's message (a refused step, a non-finite state); the state is then
    /// left where the failed frame started.
    pub fn step(&mut self, n: u32, dt: f64) -> Result<(), String> {
        if n == 0 {
            return Ok(());
        }
        let t0 = self.system.dynamical().t();
        let t1 = t0 + f64::from(n) * dt;
        let options = IntegrateOptions {
            skip_energy: true,
            ..if self.section.is_some() {
                IntegrateOptions::default()
            } else {
                IntegrateOptions::final_only()
            }
        };
        let result = self
            .system
            .integrate((t0, t1), dt, self.method, options)
            .map_err(|e| e.to_string())?;
        if let Some(section) = self.section {
            let field = FirstOrder(self.system.dynamical());
            let k = section.coordinate();
            let c = section.value();
            for i in 1..result.y.nrows() {
                let (a, b) = (result.y[[i - 1, k]] - c, result.y[[i, k]] - c);
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
                let before = result.y.row(i - 1);
                let Some(before) = before.as_slice() else {
                    continue;
                };
                // A tangency (no transversal crossing) is skipped, as the section runs do.
                if henon_step(
                    &field,
                    result.t[i - 1],
                    before,
                    &section,
                    HENON_SUBSTEPS,
                    &mut self.crossing,
                )
                .is_ok()
                {
                    if self.crossings.len() >= MAX_CROSSINGS * self.crossing.len() {
                        self.crossings.drain(..self.crossing.len());
                    }
                    self.crossings.extend_from_slice(&self.crossing);
                }
            }
        }
        self.refresh_positions();
        Ok(())
    }

    /// The current state (`[q, p]`, `[q, qdot]` for Lagrangian systems, or the ODE state).
    pub fn state(&self) -> &[f64] {
        self.system.dynamical().state()
    }

    /// The clock.
    pub fn time(&self) -> f64 {
        self.system.dynamical().t()
    }

    /// The energy of the current state.
    pub fn energy(&self) -> f64 {
        self.system.dynamical().energy(self.state())
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
        if let Some(p) = self.system.capabilities().positions(q) {
            self.probe.extend_from_slice(&p.map_err(|e| e.to_string())?);
        }
        Ok(&self.probe)
    }

    /// The positions [`positions_of`](Self::positions_of) computed last.
    pub fn probe(&self) -> &[f64] {
        &self.probe
    }

    /// Starts a new run from `state` at `t = 0`: it becomes the initial state that `reset`
    /// returns to and the energy reference.
    ///
    /// # Errors
    /// A state of the wrong length or with non-finite entries.
    pub fn set_state(&mut self, state: &[f64]) -> Result<(), String> {
        self.system
            .reset(Some(state), 0.0)
            .map_err(|e| e.to_string())?;
        self.state0.clear();
        self.state0.extend_from_slice(state);
        self.energy0 = self.system.dynamical().energy(state);
        self.refresh_positions();
        Ok(())
    }

    /// Returns to the run's initial state at `t = 0`.
    ///
    /// # Errors
    /// None in practice (the initial state was accepted before).
    pub fn reset(&mut self) -> Result<(), String> {
        self.system
            .reset(Some(&self.state0), 0.0)
            .map_err(|e| e.to_string())?;
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
        self.crossings.clear();
        Ok(())
    }

    /// The crossings recorded, one state after another.
    pub fn crossings(&self) -> &[f64] {
        &self.crossings
    }

    /// Forgets the recorded crossings.
    pub fn clear_crossings(&mut self) {
        self.crossings.clear();
    }

    /// Starts a new run (as [`set_state`](Self::set_state)) at the energy of the current
    /// run's initial state: entries `assign` of the current state are replaced, and entry
    /// `solve` (a momentum, entering the energy as a quadratic kinetic term) is chosen `>= 0`
    /// so that the energy is `E0`. For the Hénon–Heiles section: `x, px` clicked, `y = 0`,
    /// `py` solved.
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
        let d = self.system.dynamical();
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
        let energy0 = target;
        self.set_state(&state)?;
        // The run stays on the chosen energy surface: keep E0, not the bisection's rounding.
        self.energy0 = energy0;
        self.crossings.clear();
        Ok(())
    }

    fn refresh_positions(&mut self) {
        let d = self.system.dynamical();
        let state = d.state();
        let q = match self.system.ndof() {
            Some(n) if n <= state.len() => &state[..n],
            _ => state,
        };
        self.positions.clear();
        if let Some(Ok(p)) = self.system.capabilities().positions(q) {
            self.positions.extend_from_slice(&p);
        }
    }
}
