//! Work–precision problems: the error each method reaches at a given step on three reference
//! problems, for the work–precision diagrams of the gallery and of `benchmarks/`
//! (`workprecision`), which time these runs.
//!
//! - [`Problem::Kepler`]: the two-body problem at eccentricity 0.5 (`a = k = mu = 1`, period
//!   `2 pi`), started at perihelion; the error is the phase error after a whole number of
//!   orbits (100 in the issue), `|atan2(y, x)|` wrapped to `(-pi, pi]`, against the analytic
//!   orbit, which is back at perihelion.
//! - [`Problem::HenonHeiles`]: SciML's Hénon–Heiles case, `q0 = (0.1, 0)`, `p0 = (0, 0.5)`
//!   (energy 0.1303, below the escape energy 1/6); the error is the largest relative energy
//!   error over the run, sampled at up to 10^4 evenly spaced steps.
//! - [`Problem::DoublePendulum`]: the peer's double pendulum (`theta = (2, 1)`,
//!   `theta' = (0.5, -0.3)`, unit masses and lengths), a chaotic Lagrangian system; the error is
//!   the max-norm distance of the final state from a reference run
//!   ([`double_pendulum_reference`]).
//!
//! Each problem lists the methods that apply ([`Problem::methods`]: every method in the
//! registry that accepts the system, so a new method appears without editing this file) and a
//! ladder of steps, or of tolerances for an adaptive method ([`Problem::steps`]). `taylor`
//! applies to all three: each system has a Taylor form (its `L` or `H` traced), and reports
//! its cost in field evaluations as the others do.

use crate::classical::integrators::options::{IntegrateOptions, Sampling, Tolerances};
use crate::classical::systems::KeplerPerturbations;
use crate::classical::systems::{DoublePendulum, HenonHeilesSystem, KeplerSystem};
use crate::classical::{HamiltonianSystem, LagrangianSystem, Method, Result, SimulationResult};

/// One of the three work–precision problems (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Problem {
    /// Kepler at `e = 0.5`: phase error after `orbits` orbits.
    Kepler {
        /// Whole orbits integrated (the 100).
        orbits: u32,
    },
    /// SciML's Hénon–Heiles case: largest relative energy error up to `t_end`.
    HenonHeiles {
        /// Length of the run.
        t_end: f64,
    },
    /// The peer's double pendulum: final-state error at `t_end` against a reference run.
    DoublePendulum {
        /// Length of the run.
        t_end: f64,
    },
}

/// The double pendulum of the peer's workload (and of `benchmarks/`).
///
/// # Errors
/// None for these parameters; the constructor's otherwise.
pub fn double_pendulum() -> Result<DoublePendulum> {
    DoublePendulum::new(&[2.0, 1.0], &[0.5, -0.3], Default::default())
}

/// The reference final state of the double pendulum at `t_end`, which its errors are measured
/// against: `dop853` at `rtol = atol = 1e-14` (as the issue asks), an adaptive eighth-order
/// method independent of every fixed-step method it is compared with. At `t_end = 10` it agrees
/// with `gauss_legendre6` at `dt = 1e-4` (truncation `~(1e-4)^6`, below that run's rounding) to
/// about 1e-12 (`tests/classical/analysis/work_precision.rs`), so errors above ~1e-11 in the
/// diagram are the methods' own.
///
/// # Errors
/// Whatever the integration reports.
pub fn double_pendulum_reference(t_end: f64) -> Result<Vec<f64>> {
    let options = IntegrateOptions {
        tolerances: Some(Tolerances::new(1e-14, 1e-14)?),
        ..final_only()
    };
    let result = double_pendulum()?.integrate_with((0.0, t_end), t_end, Method::Dop853, options)?;
    Ok(result.final_state().to_vec())
}

/// The tolerances (`rtol = atol`) an adaptive method is run at, coarsest first.
const TOLERANCES: [f64; 10] = [
    1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14,
];

fn final_only() -> IntegrateOptions<'static> {
    IntegrateOptions {
        sampling: Sampling::FinalOnly,
        skip_energy: true,
        ..Default::default()
    }
}

/// The Kepler orbit of [`Problem::Kepler`], at perihelion.
fn kepler() -> Result<KeplerSystem> {
    KeplerSystem::from_orbital_elements(1.0, 0.5, 1.0, 1.0, KeplerPerturbations::none())
}

/// SciML's Hénon–Heiles case of [`Problem::HenonHeiles`].
fn henon_heiles() -> Result<HenonHeilesSystem> {
    HenonHeilesSystem::new(&[0.1, 0.0], &[0.0, 0.5])
}

impl Problem {
    /// The problems at the sizes: 100 Kepler orbits, Hénon–Heiles to `t = 1000`, the
    /// double pendulum to `t = 10`; `quick` shortens each tenfold (for the gallery's quick mode).
    pub fn all(quick: bool) -> [Problem; 3] {
        let f = if quick { 0.1 } else { 1.0 };
        [
            Problem::Kepler {
                orbits: (100.0 * f) as u32,
            },
            Problem::HenonHeiles { t_end: 1000.0 * f },
            Problem::DoublePendulum { t_end: 10.0 * f },
        ]
    }

    /// A short name for legends and tables.
    pub fn name(self) -> &'static str {
        match self {
            Problem::Kepler { .. } => "kepler_e0.5",
            Problem::HenonHeiles { .. } => "henon_heiles",
            Problem::DoublePendulum { .. } => "double_pendulum",
        }
    }

    /// What the error measures, for axis labels.
    pub fn error_label(self) -> &'static str {
        match self {
            Problem::Kepler { .. } => "phase error after the run (rad)",
            Problem::HenonHeiles { .. } => "max relative energy error",
            Problem::DoublePendulum { .. } => "final-state error vs reference",
        }
    }

    /// The methods that apply, in the registry's order: all of them on the separable
    /// Hamiltonians, those not restricted to separable systems on the Lagrangian double
    /// pendulum. Every problem's system has a Taylor form (see the module docs).
    pub fn methods(self) -> Vec<Method> {
        let lagrangian = matches!(self, Problem::DoublePendulum { .. });
        Method::ALL
            .into_iter()
            .filter(|m| !(lagrangian && m.needs_separable()))
            .collect()
    }

    /// The settings to try for `method`, coarsest first, `points` of them. For a fixed-step
    /// method these are steps: halvings from a step where every method is stable and in its
    /// asymptotic regime or close to it, starting lower for the low-order methods (which would
    /// otherwise take the longest runs at errors no one wants). For an adaptive method they are
    /// tolerances (`rtol = atol`), from `1e-5` down by a factor 10 each (at most ten): its step follows from
    /// them, and [`run`](Self::run) takes them in place of a step.
    pub fn steps(self, method: Method, points: usize) -> Vec<f64> {
        if method.is_adaptive() {
            return TOLERANCES.iter().copied().take(points).collect();
        }
        let largest = match self {
            Problem::Kepler { .. } => 0.05,
            Problem::HenonHeiles { .. } => 0.5,
            Problem::DoublePendulum { .. } => 0.05,
        };
        let low_order = if method.order() <= 2 { 0.25 } else { 1.0 };
        // Each step a whole fraction of the span (the driver refuses others): 100 Kepler
        // periods are no multiple of 0.05.
        let t_end = self.t_end();
        (0..points)
            .map(|k| {
                let dt = largest * low_order / 2f64.powi(k as i32);
                t_end / (t_end / dt).round().max(1.0)
            })
            .collect()
    }

    /// The span of the run.
    pub fn t_end(self) -> f64 {
        match self {
            Problem::Kepler { orbits } => f64::from(orbits) * std::f64::consts::TAU,
            Problem::HenonHeiles { t_end } | Problem::DoublePendulum { t_end } => t_end,
        }
    }

    /// Integrates the problem with `method` at `setting`, one of [`steps`](Self::steps): the
    /// step of a fixed-step method, the tolerance of an adaptive one (whose output spacing is
    /// then the whole span, or `t_end / 10^4` on Hénon–Heiles, where the energy is sampled).
    /// The run's result, for [`error`](Self::error). This is the part to time.
    ///
    /// # Errors
    /// Whatever the integration reports.
    pub fn run(self, method: Method, setting: f64) -> Result<SimulationResult> {
        let t_end = self.t_end();
        let span = (0.0, t_end);
        let (dt, tolerances) = if method.is_adaptive() {
            let dt = match self {
                Problem::HenonHeiles { .. } => t_end / 10_000.0,
                _ => t_end,
            };
            (dt, Some(Tolerances::new(setting, setting)?))
        } else {
            (setting, None)
        };
        let final_only = IntegrateOptions {
            tolerances,
            ..final_only()
        };
        match self {
            Problem::Kepler { .. } => kepler()?.integrate_with(span, dt, method, final_only),
            Problem::HenonHeiles { .. } => {
                let steps = (t_end / dt).round() as usize;
                let options = IntegrateOptions {
                    sampling: Sampling::Stride((steps / 10_000).max(1)),
                    tolerances,
                    ..Default::default()
                };
                henon_heiles()?.integrate_with(span, dt, method, options)
            }
            Problem::DoublePendulum { .. } => {
                double_pendulum()?.integrate_with(span, dt, method, final_only)
            }
        }
    }

    /// The error of a run of [`run`](Self::run); `reference` is the double pendulum's
    /// reference final state ([`double_pendulum_reference`]), unused by the other problems.
    pub fn error(self, result: &SimulationResult, reference: &[f64]) -> f64 {
        match self {
            Problem::Kepler { .. } => {
                let y = result.final_state();
                y[1].atan2(y[0]).abs()
            }
            Problem::HenonHeiles { .. } => {
                let e = result
                    .energy
                    .as_ref()
                    .map(|e| e.to_vec())
                    .unwrap_or_default();
                let e0 = e.first().copied().unwrap_or(f64::NAN);
                e.iter()
                    .fold(0.0_f64, |m, ei| m.max(((ei - e0) / e0).abs()))
            }
            Problem::DoublePendulum { .. } => result
                .final_state()
                .iter()
                .zip(reference)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs())),
        }
    }
}
