//! The integrators, one file per method, the steppers they share and the drivers that run
//! them.
//!
//! Each method's file declares its facts as `pub const INFO: MethodInfo` (name, order,
//! symplecticity, whether it needs a separable Hamiltonian, evaluations per step, reference,
//! and its [`Scheme`](crate::classical::core::method::Scheme)); the list below is the one
//! registry of methods, from which [`Method`], [`Method::ALL`], [`Method::info`],
//! [`Method::dispatch`] and [`methods`] are generated (by the macro in `registry.rs`).
//!
//! - Splitting methods (`verlet`, `yoshida4`, `yoshida6`, `kahan_li6`, `kahan_li8`,
//!   `blanes_moan6`, `sofroniou_spaletta10`) are coefficient arrays (kicks and drifts) in their
//!   file; one kick–drift–kick loop ([`splitting`]) runs them all. Adding one is a new file with
//!   its `KICKS`, `DRIFTS` and `INFO` plus one line below.
//! - Methods on a vector field name their [`FieldStepper`]: `rk4` ([`rk4`]) and the implicit
//!   Runge–Kutta methods, which share one solve ([`implicit_solve`]): `implicit_midpoint`,
//!   `gauss_legendre4` and `gauss_legendre6` are its one-, two- and three-stage Gauss–Legendre
//!   tableaus.
//! - Adaptive methods (`dop853`) name their [`AdaptiveStepper`], which steps with its own
//!   step sizes and interpolates the output grid from its dense output. `taylor` is one too,
//!   of the [`Taylor`](crate::classical::core::method::Scheme::Taylor) kind: its stepper
//!   steps the system's Taylor form, which only expression-defined systems have.
//!
//! The steppers are public for users who drive steps themselves (with either sign of `dt`);
//! `integrate` goes through [`driver`], which validates inputs, allocates once, dispatches on
//! the method's kind and runs one generic loop over a [`Stepper`].

mod registry;

registry::registry! {
    Rk4 = rk4(Rk4),
    Verlet = verlet,
    Yoshida4 = yoshida4,
    ImplicitMidpoint = implicit_midpoint(ImplicitMidpoint),
    Yoshida6 = yoshida6,
    KahanLi6 = kahan_li6,
    KahanLi8 = kahan_li8,
    BlanesMoan6 = blanes_moan6,
    SofroniouSpaletta10 = sofroniou_spaletta10,
    GaussLegendre4 = gauss_legendre4(GaussLegendre4),
    GaussLegendre6 = gauss_legendre6(GaussLegendre6),
    Dop853 = dop853(adaptive: Dop853),
    Taylor = taylor(adaptive: TaylorStepper),
}

pub mod compensated;
pub mod driver;
pub mod ensemble;
pub mod field;
pub mod implicit_solve;
pub mod lanes;
mod method;
pub mod options;
pub mod splitting;
pub mod stepper;
pub mod system;
pub mod tangent;
mod taylor_arith;
pub mod taylor_batch;

pub use dop853::Dop853;
pub use ensemble::{integrate_ensemble, Ensemble, ENSEMBLE_CHUNK};
pub use field::{Canonical, FirstOrder, VectorField};
pub use gauss_legendre4::GaussLegendre4;
pub use gauss_legendre6::GaussLegendre6;
pub use implicit_midpoint::ImplicitMidpoint;
pub use implicit_solve::{ButcherTableau, ImplicitRk, SolverSettings, SolverStats, Tableau};
pub use options::{IntegrateOptions, Observer, Sampling, Tolerances};
pub use rk4::Rk4;
pub use splitting::{SplittingStepper, VerletStepper, Yoshida4Stepper};
pub use stepper::{AdaptiveStepper, Dispatch, FieldStepper, Report, Stepper};
pub use system::{
    hamiltonian_energy, lagrangian_derivatives, quadratic_kinetic_energy, separable_derivatives,
    separable_jacobian, split, DynamicalSystem, Family, HamiltonianSystem, LagrangianSystem,
    MassInv, OdeSystem,
};
pub use tangent::{hamiltonian_flow, lagrangian_flow, ode_flow, Flow};
pub use taylor::{TaylorField, TaylorStepper};
