//! The system traits: [`DynamicalSystem`] and its three families [`HamiltonianSystem`],
//! [`LagrangianSystem`] and [`OdeSystem`].
//!
//! A system owns its [`Phase`] (state and clock) and says how the state moves. Each family
//! trait provides `integrate`, which is generic over the concrete system: the integrators are
//! monomorphized for it, so its force or right-hand side is inlined into the step loop.

use super::driver;
use super::options::IntegrateOptions;
use super::Method;
use crate::classical::core::error::{Error, Result};
use crate::classical::core::phase::Phase;
use crate::classical::core::result::SimulationResult;
use crate::classical::core::sum::{lane_sum_map, lane_sum_map2};

/// The provided `integrate` and `integrate_with` of a family trait, which differ only in the
/// driver they run and in what their errors add to [`HamiltonianSystem::integrate`]'s.
macro_rules! provided_integrate {
    ($driver:path, $errors:literal) => {
        /// Integrates over `t_span` with step `dt`, storing every sample and the energy.
        ///
        /// # Errors
        #[doc = $errors]
        fn integrate(
            &mut self,
            t_span: (f64, f64),
            dt: f64,
            method: Method,
        ) -> Result<SimulationResult>
        where
            Self: Sized,
        {
            self.integrate_with(t_span, dt, method, IntegrateOptions::default())
        }

        /// [`integrate`](Self::integrate) with sampling and observer options.
        ///
        /// # Errors
        /// As [`integrate`](Self::integrate).
        fn integrate_with(
            &mut self,
            t_span: (f64, f64),
            dt: f64,
            method: Method,
            options: IntegrateOptions<'_>,
        ) -> Result<SimulationResult>
        where
            Self: Sized,
        {
            $driver(self, t_span, dt, method, options)
        }
    };
}

/// The family of a system, which fixes its state layout and the methods that apply.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// `HamiltonianSystem`: state `[q, p]`.
    Hamiltonian,
    /// `LagrangianSystem`: state `[q, qdot]` (results hold `qdot` in `p`, as the spec says).
    Lagrangian,
    /// `ODESystem`: the system's own state layout.
    Ode,
}

impl Family {
    /// Lower-case name, as written in output files and `list --json`.
    pub fn name(self) -> &'static str {
        match self {
            Family::Hamiltonian => "hamiltonian",
            Family::Lagrangian => "lagrangian",
            Family::Ode => "ode",
        }
    }
}

/// Any system with a state vector evolving in time (the spec's `DynamicalSystem`).
pub trait DynamicalSystem {
    /// Current state and clock.
    fn phase(&self) -> &Phase;

    /// Mutable access to state and clock, for the integrators.
    fn phase_mut(&mut self) -> &mut Phase;

    /// Writes `dstate/dt` at `(t, state)` into `out`.
    ///
    /// # Errors
    /// Systems whose right-hand side can fail (a singular mass matrix) report it here.
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()>;

    /// Total mechanical energy of `state`.
    fn energy(&self, state: &[f64]) -> f64;

    /// Writes the Jacobian `d(derivatives)/d(state)` at `(t, state)` into `out`, row-major,
    /// `state_dim x state_dim`. Returns `None` when the system supplies no Jacobian; the
    /// implicit-midpoint solver then relies on fixed-point iteration alone.
    fn jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let _ = (t, state, out);
        None
    }

    /// The method `integrate` uses when none is given.
    fn default_method(&self) -> Method;

    /// The system's *Taylor form*: its field `d(state)/dt` (on the state `integrate` steps)
    /// compiled into Taylor-coefficient recurrences, which the `taylor` method steps. `None`
    /// (the default) for a system whose field is hand-written code; systems defined by
    /// expressions (the symbolic engines) override it. `Some(Err(..))` when the recurrences
    /// cannot be built.
    fn taylor_field(&self) -> Option<Result<Box<dyn super::taylor::TaylorField>>> {
        None
    }

    /// The system's force across SIMD lanes, where the ensemble engine runs members of a
    /// splitting method `L` at a time (`integrators/lanes.rs`); `None` (the default) for
    /// systems whose force is written for `f64` only.
    fn splitting_lanes(&self) -> Option<&dyn super::lanes::SplittingLanes> {
        None
    }

    /// Current state vector.
    fn state(&self) -> &[f64] {
        self.phase().state()
    }

    /// Current time.
    fn t(&self) -> f64 {
        self.phase().t()
    }

    /// Length of the state vector.
    fn state_dim(&self) -> usize {
        self.phase().len()
    }

    /// Energy of the current state.
    fn current_energy(&self) -> f64 {
        self.energy(self.state())
    }

    /// Resets the clock to `t0` and, if given, the state to `state0`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] or [`Error::NonFinite`] for a bad `state0`.
    fn reset(&mut self, state0: Option<&[f64]>, t0: f64) -> Result<()> {
        match state0 {
            Some(s) => self.phase_mut().set(s, t0),
            None => self.phase_mut().set_t(t0),
        }
    }
}

/// Inverse masses of a Hamiltonian system, `dq_i/dt = mass_inv_i * p_i`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MassInv<'a> {
    /// The same `1/m` for every coordinate.
    Uniform(f64),
    /// One `1/m_i` per coordinate.
    PerCoordinate(&'a [f64]),
}

impl MassInv<'_> {
    /// `1/m` of coordinate `i`.
    pub fn get(&self, i: usize) -> f64 {
        match self {
            MassInv::Uniform(m) => *m,
            MassInv::PerCoordinate(m) => m[i],
        }
    }
}

/// Splits a stacked state `[a, b]` into its two halves of length `ndof`.
///
/// # Errors
/// [`Error::DimensionMismatch`] unless `state.len() == 2 * ndof`.
pub fn split(state: &[f64], ndof: usize) -> Result<(&[f64], &[f64])> {
    if state.len() != 2 * ndof {
        return Err(Error::DimensionMismatch {
            name: "state".into(),
            expected: 2 * ndof,
            found: state.len(),
        });
    }
    Ok(state.split_at(ndof))
}

/// A canonical Hamiltonian system `H(q, p, t)` with state `[q, p]` (the spec's
/// `HamiltonianSystem`).
///
/// Separable systems, `H = T(p) + V(q)` with `T = sum_i mass_inv_i p_i^2 / 2`, implement
/// [`force`](Self::force) and may use [`separable_derivatives`] and [`hamiltonian_energy`] for
/// their [`DynamicalSystem`] methods. Non-separable systems set `separable` to false and
/// implement `derivatives` themselves.
pub trait HamiltonianSystem: DynamicalSystem {
    /// Number of degrees of freedom.
    fn ndof(&self) -> usize;

    /// Kinetic energy `T(p) = sum_i mass_inv_i p_i^2 / 2`, from [`mass_inv`](Self::mass_inv):
    /// the same masses the splitting drift uses, so the two cannot disagree. Override only for
    /// non-separable systems (where `T` is not used by the integrators).
    #[inline]
    fn kinetic_energy(&self, p: &[f64]) -> f64 {
        quadratic_kinetic_energy(self.mass_inv(), p)
    }

    /// Potential energy `V(q)`.
    fn potential_energy(&self, q: &[f64]) -> f64;

    /// Whether `H = T(p) + V(q)`, enabling `verlet` and `yoshida4`.
    fn separable(&self) -> bool {
        true
    }

    /// False when `derivatives` holds non-conservative forces (drag) that
    /// [`force`](Self::force) does not: the splitting methods would silently drop them, so they
    /// are refused.
    fn conservative(&self) -> bool {
        true
    }

    /// Inverse masses, `dq/dt = mass_inv * p`.
    fn mass_inv(&self) -> MassInv<'_> {
        MassInv::Uniform(1.0)
    }

    /// Writes the conservative force `-dV/dq` at `(q, t)` into `out`.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for non-separable systems (the default).
    fn force(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let _ = (q, t, out);
        Err(Error::Unsupported {
            operation: "force".into(),
            reason: "the system is not separable (H != T(p) + V(q))".into(),
        })
    }

    /// Writes the force at `(q, t)` into `out` exactly as [`force`](Self::force) does and,
    /// where the system gets the potential almost for free on the way, returns `Some(V(q))`.
    ///
    /// The splitting integrators call this for the last force of each step whose sample is
    /// stored with its energy, and store `kinetic_energy(p) + V` instead of calling
    /// [`energy`](DynamicalSystem::energy), which would evaluate the potential a second time
    /// (the pendulum swarm's cosines were an eighth of its step). So return `Some` only if
    /// `V` has the same bits as [`potential_energy`](Self::potential_energy) and `energy` is
    /// [`hamiltonian_energy`] (as [`impl_separable_dynamics!`](crate::impl_separable_dynamics)
    /// makes it). The default returns `None`, and the sample's energy comes from `energy`.
    ///
    /// # Errors
    /// As [`force`](Self::force).
    #[inline]
    fn force_and_potential(&self, q: &[f64], t: f64, out: &mut [f64]) -> Result<Option<f64>> {
        self.force(q, t, out)?;
        Ok(None)
    }

    /// Writes the force Jacobian `dF_i/dq_j = -d2V/dq_i dq_j` (row-major `ndof x ndof`);
    /// `None` if not supplied. Used by the implicit-midpoint Newton solve.
    fn force_jacobian(&self, q: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let _ = (q, t, out);
        None
    }

    /// Current positions.
    fn q(&self) -> &[f64] {
        &self.state()[..self.ndof()]
    }

    /// Current momenta.
    fn p(&self) -> &[f64] {
        &self.state()[self.ndof()..]
    }

    provided_integrate!(
        driver::integrate_hamiltonian,
        "Invalid time span or step, a method the system cannot honour (splitting methods on a \
         non-separable or non-conservative system), non-finite states, solver failure."
    );
}

/// `[dq/dt, dp/dt] = [mass_inv * p, force(q, t)]`: the derivatives of a separable system.
///
/// # Errors
/// Whatever [`HamiltonianSystem::force`] returns.
pub fn separable_derivatives<S: HamiltonianSystem + ?Sized>(
    system: &S,
    t: f64,
    state: &[f64],
    out: &mut [f64],
) -> Result<()> {
    let n = system.ndof();
    let (q, p) = state.split_at(n);
    let (dq, dp) = out.split_at_mut(n);
    match system.mass_inv() {
        MassInv::Uniform(m) => dq.iter_mut().zip(p).for_each(|(d, &pi)| *d = m * pi),
        MassInv::PerCoordinate(m) => dq
            .iter_mut()
            .zip(p.iter().zip(m))
            .for_each(|(d, (&pi, &mi))| *d = mi * pi),
    }
    system.force(q, t, dp)
}

/// The Jacobian of [`separable_derivatives`], `[[0, diag(mass_inv)], [dF/dq, 0]]`, from
/// [`HamiltonianSystem::force_jacobian`]; `None` if the system supplies no force Jacobian.
pub fn separable_jacobian<S: HamiltonianSystem + ?Sized>(
    system: &S,
    t: f64,
    state: &[f64],
    out: &mut [f64],
) -> Option<Result<()>> {
    let n = system.ndof();
    let dim = 2 * n;
    // The force Jacobian is computed into the first n*n entries and then moved to the
    // lower-left block, which starts at index 2 n^2, so source and destination never overlap.
    match system.force_jacobian(&state[..n], t, &mut out[..n * n]) {
        None => return None,
        Some(Err(e)) => return Some(Err(e)),
        Some(Ok(())) => {}
    }
    for i in 0..n {
        for j in 0..n {
            out[(n + i) * dim + j] = out[i * n + j];
        }
    }
    let mass_inv = system.mass_inv();
    for i in 0..n {
        for j in 0..dim {
            out[i * dim + j] = if j == n + i { mass_inv.get(i) } else { 0.0 };
        }
        for j in n..dim {
            out[(n + i) * dim + j] = 0.0;
        }
    }
    Some(Ok(()))
}

/// Implements [`DynamicalSystem`] for a separable [`HamiltonianSystem`] stored in a struct with
/// a `phase: Phase` field: derivatives from the force, energy `T + V`, Jacobian from
/// `force_jacobian`, default method `yoshida4`. With `taylor: path`, the system's Taylor form
/// is `path(&system)` (a function from `&Type` to `Result<Box<dyn TaylorField>>`, such as
/// `symbolic::traced_hamiltonian_taylor_field` for a system whose `H` is written once over any
/// number type); without, it has none. Items in braces after it (or in its place) go into
/// the impl too (e.g. `splitting_lanes`).
#[macro_export]
macro_rules! impl_separable_dynamics {
    ($ty:ty) => {
        $crate::impl_separable_dynamics!($ty, {});
    };
    ($ty:ty, taylor: $field:path) => {
        $crate::impl_separable_dynamics!($ty, taylor: $field, {});
    };
    ($ty:ty, taylor: $field:path, { $($extra:item)* }) => {
        $crate::impl_separable_dynamics!($ty, {
            $($extra)*
            fn taylor_field(
                &self,
            ) -> Option<
                $crate::classical::Result<
                    Box<dyn $crate::classical::integrators::TaylorField>,
                >,
            > {
                Some($field(self))
            }
        });
    };
    ($ty:ty, { $($extra:item)* }) => {
        impl $crate::classical::DynamicalSystem for $ty {
            $($extra)*
            fn phase(&self) -> &$crate::classical::Phase {
                &self.phase
            }
            fn phase_mut(&mut self) -> &mut $crate::classical::Phase {
                &mut self.phase
            }
            fn derivatives(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> $crate::classical::Result<()> {
                $crate::classical::integrators::separable_derivatives(self, t, state, out)
            }
            #[inline]
            fn energy(&self, state: &[f64]) -> f64 {
                $crate::classical::integrators::hamiltonian_energy(self, state)
            }
            fn jacobian(
                &self,
                t: f64,
                state: &[f64],
                out: &mut [f64],
            ) -> Option<$crate::classical::Result<()>> {
                $crate::classical::integrators::separable_jacobian(self, t, state, out)
            }
            fn default_method(&self) -> $crate::classical::Method {
                $crate::classical::Method::Yoshida4
            }
        }
    };
}

/// `T(p) + V(q)` of a stacked state `[q, p]`.
#[inline]
pub fn hamiltonian_energy<S: HamiltonianSystem + ?Sized>(system: &S, state: &[f64]) -> f64 {
    let (q, p) = state.split_at(system.ndof());
    system.kinetic_energy(p) + system.potential_energy(q)
}

/// `sum_i mass_inv_i p_i^2 / 2`, summed in the fixed order of
/// [`lane_sum`](crate::classical::core::sum::lane_sum).
#[inline]
pub fn quadratic_kinetic_energy(mass_inv: MassInv<'_>, p: &[f64]) -> f64 {
    match mass_inv {
        MassInv::Uniform(m) => 0.5 * m * lane_sum_map(p, |pi| pi * pi),
        MassInv::PerCoordinate(m) => 0.5 * lane_sum_map2(p, m, |pi, mi| mi * pi * pi),
    }
}

/// A system defined by a Lagrangian `L(q, qdot, t)`, with state `[q, qdot]` (the spec's
/// `LagrangianSystem`).
///
/// `integrate` with `implicit_midpoint` (the default) integrates the canonical form in
/// `(q, p)`, `p = dL/dqdot`, which is symplectic even when the mass matrix depends on `q`;
/// `rk4` integrates `(q, qdot)` directly. Results always hold `[q, qdot]`, and `result.p`
/// holds `qdot`.
pub trait LagrangianSystem: DynamicalSystem {
    /// Number of degrees of freedom.
    fn ndof(&self) -> usize;

    /// Writes `qddot` at `(q, qdot, t)` from the Euler–Lagrange equations.
    ///
    /// # Errors
    /// [`Error::SingularMatrix`] if the mass matrix `d2L/dqdot2` is singular.
    fn acceleration(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()>;

    /// Writes the canonical momentum `p = dL/dqdot` at `(q, qdot, t)`.
    ///
    /// # Errors
    /// Evaluation failures of the Lagrangian.
    fn momentum(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()>;

    /// Writes the velocity `qdot(q, p, t)` that inverts `p = dL/dqdot` (the Legendre map).
    ///
    /// # Errors
    /// [`Error::SingularMatrix`], or [`Error::SolverDidNotConverge`] for a Lagrangian whose
    /// Legendre map must be inverted iteratively.
    fn velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Result<()>;

    /// Writes `[dq/dt, dp/dt] = [qdot(q, p), dL/dq(q, qdot(q, p), t)]` at the canonical state
    /// `[q, p]`.
    ///
    /// # Errors
    /// As [`velocity`](Self::velocity).
    fn canonical_derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()>;

    /// Jacobian of [`canonical_derivatives`](Self::canonical_derivatives), row-major; `None`
    /// if not supplied (fixed-point iteration is then used).
    fn canonical_jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Option<Result<()>> {
        let _ = (t, state, out);
        None
    }

    /// Current positions.
    fn q(&self) -> &[f64] {
        &self.state()[..self.ndof()]
    }

    /// Current velocities.
    fn qdot(&self) -> &[f64] {
        &self.state()[self.ndof()..]
    }

    provided_integrate!(
        driver::integrate_lagrangian,
        "As [`HamiltonianSystem::integrate`]; the splitting methods are refused."
    );
}

/// `[dq/dt, dqdot/dt] = [qdot, acceleration(q, qdot, t)]`: the first-order form of a
/// Lagrangian system.
///
/// # Errors
/// Whatever [`LagrangianSystem::acceleration`] returns.
pub fn lagrangian_derivatives<S: LagrangianSystem + ?Sized>(
    system: &S,
    t: f64,
    state: &[f64],
    out: &mut [f64],
) -> Result<()> {
    let n = system.ndof();
    let (q, qdot) = state.split_at(n);
    let (dq, dqdot) = out.split_at_mut(n);
    dq.copy_from_slice(qdot);
    system.acceleration(q, qdot, t, dqdot)
}

/// A general first-order system `dy/dt = f(t, y)`, possibly non-conservative (the spec's
/// `ODESystem`): rigid bodies, drag. Integrated with `rk4` or `implicit_midpoint`.
pub trait OdeSystem: DynamicalSystem {
    provided_integrate!(
        driver::integrate_ode,
        "As [`HamiltonianSystem::integrate`]; the splitting methods are refused."
    );
}
