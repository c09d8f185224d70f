//! The built-in systems, one file per family, each with its catalogue entry.
//!
//! Hamiltonian: `kepler`, `henon_heiles`, `swarm`, `projectile`, `chains`, and the integrable
//! `toda` lattice. Lagrangian and rigid bodies: `double_pendulum`, `triple_pendulum`, `hoop`,
//! `coupled_oscillators`, `symmetric_top`, `rigid_body`, `elastic_pendulum`.

use crate::classical::model::entry::catalogue_static;
use crate::classical::model::SystemEntry;

/// Implements [`DynamicalSystem`](crate::classical::DynamicalSystem) and
/// [`OdeSystem`](crate::classical::OdeSystem) for a first-order system whose state has the fixed
/// length `dim`, stored in a struct with a `phase: Phase` field: the boilerplate every ODE
/// system here shares, written once. The macro checks the lengths (the state and `out` of
/// `derivatives` and `jacobian`; a state of another length has a `NaN` energy) and then calls
/// the system's inherent
///
/// - `fn field(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()>`, the right-hand
///   side;
/// - `fn field_energy(&self, state: &[f64]) -> f64`, what the system reports as its energy;
/// - with `jacobian` named: `fn field_jacobian(&self, t: f64, state: &[f64], out: &mut [f64])
///   -> Result<()>`, the row-major `dim x dim` Jacobian (without it the drivers difference the
///   field).
///
/// `method` is the default method. A generic struct is written
/// `impl_ode_dynamics!(impl [S: Bound] Body<S>, dim = 9, method = Dop853)`.
macro_rules! impl_ode_dynamics {
    (@jacobian $dim:expr) => {
        fn jacobian(
            &self,
            t: f64,
            state: &[f64],
            out: &mut [f64],
        ) -> Option<crate::classical::Result<()>> {
            Some(
                crate::classical::core::error::check_len("state", state, $dim)
                    .and_then(|()| {
                        crate::classical::core::error::check_len("jacobian", out, $dim * $dim)
                    })
                    .and_then(|()| self.field_jacobian(t, state, out)),
            )
        }
    };
    (impl [$($gen:tt)*] $ty:ty, dim = $dim:expr, method = $method:ident $(, $jac:ident)?) => {
        impl<$($gen)*> crate::classical::DynamicalSystem for $ty {
            fn phase(&self) -> &crate::classical::Phase {
                &self.phase
            }

            fn phase_mut(&mut self) -> &mut crate::classical::Phase {
                &mut self.phase
            }

            #[inline]
            fn derivatives(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> crate::classical::Result<()> {
                crate::classical::core::error::check_len("state", state, $dim)?;
                crate::classical::core::error::check_len("out", out, $dim)?;
                self.field(t, state, out)
            }

            fn energy(&self, state: &[f64]) -> f64 {
                if state.len() == $dim {
                    self.field_energy(state)
                } else {
                    f64::NAN
                }
            }

            $(impl_ode_dynamics!(@$jac $dim);)?

            fn default_method(&self) -> crate::classical::Method {
                crate::classical::Method::$method
            }
        }

        impl<$($gen)*> crate::classical::OdeSystem for $ty {}
    };
    ($ty:ty, $($rest:tt)*) => {
        impl_ode_dynamics!(impl [] $ty, $($rest)*);
    };
}

mod kepler;
pub use kepler::*;
mod henon_heiles;
pub use henon_heiles::*;
mod swarm;
pub use swarm::*;
mod projectile;
pub use projectile::*;
mod chains;
pub use chains::*;
mod toda;
pub use toda::*;
mod double_pendulum;
pub use double_pendulum::*;
mod triple_pendulum;
pub use triple_pendulum::*;
mod hoop;
mod rod_chain;
pub use hoop::*;
mod coupled_oscillators;
pub use coupled_oscillators::*;
mod symmetric_top;
pub use symmetric_top::*;
mod rigid_body;
pub use rigid_body::*;
mod elastic_pendulum;
pub use elastic_pendulum::*;
mod foucault;
pub use foucault::*;
mod eulers_disk;
pub use eulers_disk::*;
mod rattleback;
pub use rattleback::*;
mod rolling;
pub use rolling::*;

catalogue_static! {
    /// Every built-in system of the catalogue, in the order listings show them: one line per
    /// entry, each written next to its system.
    ///
    /// Like every entry, a `const` in the library's unit-test harness (`catalogue_static!` in
    /// `model/entry.rs`).
    pub static SYSTEMS: &[&SystemEntry] = &[
        &crate::classical::examples::PENDULUM_ENTRY,
        &crate::classical::examples::HARMONIC_OSCILLATOR_ENTRY,
        &KEPLER_ENTRY,
        &KEPLER_STATE_ENTRY,
        &HENON_HEILES_ENTRY,
        &SWARM_ENTRY,
        &SWARM_STATE_ENTRY,
        &PROJECTILE_ENTRY,
        &PROJECTILE_STATE_ENTRY,
        &HARMONIC_CHAIN_ENTRY,
        &FPUT_ENTRY,
        &SINE_GORDON_KINK_ENTRY,
        &SINE_GORDON_STATE_ENTRY,
        &DOUBLE_PENDULUM_ENTRY,
        &TRIPLE_PENDULUM_ENTRY,
        &HOOP_ENTRY,
        &COUPLED_OSCILLATORS_ENTRY,
        &HEAVY_TOP_ENTRY,
        &EULER_TOP_ENTRY,
        &TODA_ENTRY,
        &ELASTIC_PENDULUM_ENTRY,
        &ROLLING_RATTLEBACK_ENTRY,
        &ROLLING_DISK_ENTRY,
        &ROLLING_DISK_STEADY_ENTRY,
        &FOUCAULT_ENTRY,
        &EULERS_DISK_ENTRY,
        &RATTLEBACK_ENTRY,
    ];
}
