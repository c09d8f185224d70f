//! [`LagrangianEngine`]: every equation of motion of a Lagrangian system, derived from
//! `L(q, qdot, t)` alone by forward-mode automatic differentiation (num-dual), or taken from
//! hand-derived closed forms the Lagrangian supplies.
//!
//! A system writes its Lagrangian once, generic over the number type ([`Lagrangian`]). With
//! `v = qdot`, the engine evaluates it on dual and hyper-dual numbers to obtain
//!
//! ```text
//! mass matrix    M      = d2L/dv2
//! momentum       p      = dL/dv
//! acceleration   qddot  = M^-1 (dL/dq - (d2L/dv dq) v - d2L/dv dt)      (Euler–Lagrange)
//! energy         H      = p . v - L                                     (Jacobi integral)
//! velocity       v(q, p): the root of dL/dv(q, v) - p = 0                (inverse Legendre map)
//! canonical      dq/dt  = v(q, p),   dp/dt = dL/dq(q, v(q, p), t)
//! ```
//!
//! (Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed. (2002), §1.4 and §8.1.) Every
//! derivative is exact to rounding: a hyper-dual number `x + e1 a + e2 b + e1 e2 c` carries one
//! second derivative through the evaluation of `L` (Fike & Alonso, AIAA 2011-886).
//!
//! # Closed forms
//!
//! A [`Lagrangian`] may also supply any of these quantities in closed form through its
//! provided `closed_*` methods (mass matrix, momentum, velocity, `dL/dq`, acceleration,
//! canonical field, energy); each engine method calls the closed form first and differentiates
//! `L` only when it returns `None`, the default. Dispatch is static, so a Lagrangian without
//! closed forms pays nothing for the check, and a closed form is plain `f64` arithmetic on the
//! caller's slices: no allocation, no dual numbers. The built-in systems (double
//! pendulum, hoop, coupled oscillators, heavy top, elastic pendulum) supply all seven, derived
//! in their module docs (the chain gets the canonical field from the provided
//! `closed_canonical`, which composes its velocity and `dL/dq`). Wrapping a Lagrangian in
//! [`AutoDiff`] hides its closed forms: that engine is the independent check of them
//! (`tests/classical/lagrangian/closed_forms.rs`).
//!
//! # Jacobians
//!
//! The tangent dynamics (`integrators/tangent.rs`) and the implicit solvers' Newton fallback
//! need the Jacobians of the two fields a Lagrangian system is integrated as. A Lagrangian
//! that writes its acceleration and canonical field once, generic over the number type
//! ([`Lagrangian::closed_acceleration_in`], [`Lagrangian::closed_canonical_in`]: the
//! double pendulum, hoop, heavy top and elastic pendulum do), gets both by one forward-mode
//! evaluation on dual vectors ([`forward_jacobian`]): [`first_order_jacobian`]
//! (`d[qdot, qddot]/d[q, qdot]`, the `DynamicalSystem::jacobian` of `rk4`'s form) and
//! [`closed_canonical_jacobian`](LagrangianEngine::closed_canonical_jacobian). Otherwise
//! [`first_order_jacobian`] is `None` (it would need third derivatives of `L`), so the tangent
//! dynamics of `[q, qdot]` fall back to central differences: the coupled oscillators (`ndof`
//! beyond the fixed-size duals) and users' Lagrangians. [`canonical_jacobian`], which the
//! implicit methods' Newton fallback and tangent dynamics use, differentiates `L` twice
//! (below) for every Lagrangian: exact too, and switching it would change the bits of
//! trajectories whose steps use Newton.
//!
//! [`first_order_jacobian`]: LagrangianEngine::first_order_jacobian
//! [`canonical_jacobian`]: LagrangianEngine::canonical_jacobian
//!
//! A closed form thus replaces a dual-number evaluation of `L` and a linear solve by a few
//! dozen flops; what remains of an implicit-midpoint step is mostly the solver itself. The
//! instruction counts per step, closed forms against automatic differentiation, are in
//! `benchmarks/README.md`.
//!
//! # Cost per call of automatic differentiation, in evaluations of `L` (`n` = ndof)
//!
//! For `n <= 3` (every built-in system) each kernel evaluates `L` **once**, on fixed-size
//! vector duals over plain arrays ([`dual`](super::dual): the rules of num-dual's
//! `DualSVec64`/`Dual2SVec64`/`HyperDualSVec64` term by term, so the derivatives are
//! bit-identical, without their `Option`-wrapped nalgebra storage). A flag on each number marks
//! a constant (and, for the hyper-dual, a value independent of the `e1` directions), so
//! sub-expressions of `q` alone inside the mass-matrix evaluation cost plain `f64` arithmetic
//! and one `cos`, not a dual product. `sin`/`cos` of the coordinates are computed once per
//! kernel, and the rest of the call works in exactly sized stack arrays with an unrolled LU:
//!
//! | operation (`n <= 3`)              | evaluations of `L` | number type (components)         |
//! |-----------------------------------|--------------------|----------------------------------|
//! | [`acceleration`](LagrangianEngine::acceleration) | 1 | hyper-dual vector, `e1 = v`, `e2 = (q, v, t)`: `1 + 3n + 1 + n(2n+1)` |
//! | [`canonical_derivatives`](LagrangianEngine::canonical_derivatives), [`velocity`](LagrangianEngine::velocity) | 2 per call for a Lagrangian quadratic in `v` | second-order dual vector in `v` (`1 + n + n^2`), then dual vector in `(q, v)` (`1 + 2n`) |
//!
//! The hand-written duals stay because they take fewer instructions per step than num-dual's
//! vector duals on these kernels for 2- and 3-dof Lagrangians, and as many for 1 dof
//! (measured in `benchmarks/README.md`, "Hand-written dual numbers vs num-dual"). The crate
//! feature `num-dual-kernels` builds the three kernels on num-dual's
//! `DualSVec64`/`Dual2SVec64`/`HyperDualSVec64` instead, for that comparison only.
//!
//! Larger systems, and the rarely used paths (`mass_matrix`, the Newton re-linearization of a
//! non-quadratic `L`, `canonical_jacobian`), use one scalar (hyper-)dual evaluation per
//! derivative direction:
//!
//! | operation (any `n`)               | hyper-dual evaluations | dual evaluations |
//! |-----------------------------------|------------------------|------------------|
//! | [`acceleration`](LagrangianEngine::acceleration) | `n(n+1)/2 + n`  | `n`              |
//! | [`canonical_derivatives`](LagrangianEngine::canonical_derivatives), [`velocity`](LagrangianEngine::velocity) | `n(n+1)/2 + n` per Newton iteration | 0 |
//! | [`canonical_jacobian`](LagrangianEngine::canonical_jacobian) | `n(2n+1)` plus one velocity solve | 0 |
//! | [`momentum`](LagrangianEngine::momentum) | 0                         | `n`              |
//! | [`energy`](LagrangianEngine::energy)     | 0                         | 1                |
//!
//! plus one `n x n` LU factorization per acceleration or Newton iteration. The inverse Legendre
//! map starts with the step that is exact when `L` is quadratic in `v` (every mechanical
//! Lagrangian `T(q, v) - V(q)`): `v = M(q, 0)^-1 (p - dL/dv(q, 0))`; one residual check
//! (which also yields `dL/dq`) confirms it. Non-quadratic Lagrangians continue with Newton's
//! method, halving any step that fails to reduce the residual or leaves the domain of `L`.
//! Both kernel families give the same derivatives to rounding (the implicit-midpoint
//! trajectories of the built-in systems are bit-identical; `rk4` ones agree to 4e-14 over
//! 1e5 steps).
//!
//! Up to [`MAX_STACK_NDOF`](super::MAX_STACK_NDOF) degrees of freedom all work buffers are on
//! the stack: no evaluation allocates. Larger systems use heap buffers per call.

use num_dual::{Dual64, DualNum, HyperDual64};

use super::buffer::{MatBuf, VecBuf};
#[cfg(not(feature = "num-dual-kernels"))]
use super::dual::{Dual2Arr, DualArr, HyperArr};
use super::forward::{forward_jacobian, FieldScalar};
use crate::classical::core::error::{check_len, check_vector};
#[cfg(doc)]
use crate::classical::core::linalg::negligible_pivot;
use crate::classical::core::linalg::{lu_factor, lu_solve, Singular};
#[cfg(feature = "num-dual-kernels")]
use num_dual::{Dual2SVec64, DualSVec64, HyperDualSVec64};

use crate::classical::core::{check_items_fit, Error, Phase, Result};

/// The number types a [`Lagrangian`] is evaluated on: `f64` and num-dual's (hyper-)dual
/// numbers over `f64`. Bring [`DualNum`](num_dual::DualNum) into scope for `sin`, `cos`,
/// `powi`, ... on them.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}

impl<D: DualNum<Primitive = f64> + Copy> Scalar for D {}

/// A Lagrangian `L(q, qdot, t)`, written once, generic over the number type.
///
/// # Example
/// ```
/// use physicskit::classical::lagrangian::{DualNum, Lagrangian, LagrangianEngine, Scalar};
///
/// /// A pendulum of unit mass and length: L = v^2/2 + g cos q.
/// struct Pendulum { g: f64 }
///
/// impl Lagrangian for Pendulum {
///     fn ndof(&self) -> usize { 1 }
///     fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], _t: D) -> D {
///         qdot[0] * qdot[0] * 0.5 + q[0].cos() * self.g
///     }
/// }
///
/// let engine = LagrangianEngine::new(Pendulum { g: 9.81 }).unwrap();
/// let mut qddot = [0.0];
/// engine.acceleration(&[0.3], &[0.0], 0.0, &mut qddot).unwrap();
/// assert!((qddot[0] + 9.81 * 0.3_f64.sin()).abs() < 1e-14);
/// ```
pub trait Lagrangian {
    /// Number of degrees of freedom (length of `q` and `qdot`).
    fn ndof(&self) -> usize;

    /// `L(q, qdot, t)`. `q` and `qdot` have length [`ndof`](Self::ndof).
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], t: D) -> D;

    /// The equations of motion on `[q, qdot]` as Taylor recurrences (the system's
    /// [`taylor_field`](crate::classical::DynamicalSystem::taylor_field)). The default traces
    /// [`lagrangian`](Self::lagrangian) once into an expression
    /// ([`traced_taylor_field`](crate::classical::symbolic::traced_taylor_field)), so every
    /// Lagrangian written generically has one; `Some(Err(_))` when `L` decides on a value
    /// of its arguments (a comparison, `re()`), which a trace cannot follow.
    fn taylor_field(
        &self,
    ) -> Option<Result<Box<dyn crate::classical::integrators::taylor::TaylorField>>>
    where
        Self: Sized,
    {
        Some(crate::classical::symbolic::traced_taylor_field(self))
    }

    // Optional closed forms. The engine calls each of these first and differentiates `L`
    // only when it returns `None` (the default). Each receives slices already checked to
    // have length `ndof` (`n x n` for the mass matrix) and must agree with the derivatives
    // of `L` to rounding: `tests/classical/lagrangian/closed_forms.rs` checks the built-in systems'
    // against the engine on [`AutoDiff`]. Generic dispatch makes an absent closed form free.

    /// Closed form of the mass matrix `d2L/dqdot2` (row-major `n x n`), or `None`.
    #[inline(always)]
    fn closed_mass_matrix(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Option<()> {
        let _ = (q, qdot, t, out);
        None
    }

    /// Closed form of the momentum `p = dL/dqdot`, or `None`.
    #[inline(always)]
    fn closed_momentum(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Option<()> {
        let _ = (q, qdot, t, out);
        None
    }

    /// Closed form of the generalized force `dL/dq`, or `None`.
    #[inline(always)]
    fn closed_generalized_force(
        &self,
        q: &[f64],
        qdot: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Option<()> {
        let _ = (q, qdot, t, out);
        None
    }

    /// Closed form of the energy function `p . qdot - L`, or `None`.
    #[inline(always)]
    fn closed_energy(&self, q: &[f64], qdot: &[f64], t: f64) -> Option<f64> {
        let _ = (q, qdot, t);
        None
    }

    /// Closed form of the Euler–Lagrange acceleration `qddot(q, qdot, t)`, or `None`.
    /// `Some(Err(_))` ([`singular_mass_matrix`]) where the mass matrix is singular by the
    /// criterion of [`lu_factor`] (see [`negligible_pivot`]). The default is the generic
    /// [`closed_acceleration_in`](Self::closed_acceleration_in) at `f64`.
    #[inline(always)]
    fn closed_acceleration(
        &self,
        q: &[f64],
        qdot: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Option<Result<()>> {
        self.closed_acceleration_in(q, qdot, t, out)
    }

    /// Closed form of the inverse Legendre map `qdot(q, p, t)`, or `None`; errors as
    /// [`closed_acceleration`](Self::closed_acceleration).
    #[inline(always)]
    fn closed_velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Option<Result<()>> {
        let _ = (q, p, t, out);
        None
    }

    /// Closed form of the canonical field at `(q, p)`: `qdot = qdot(q, p, t)` and
    /// `pdot = dL/dq(q, qdot, t)`, or `None`; errors as
    /// [`closed_acceleration`](Self::closed_acceleration).
    ///
    /// The default is the generic [`closed_canonical_in`](Self::closed_canonical_in) at
    /// `f64` if supplied, else the composition of [`closed_velocity`](Self::closed_velocity)
    /// and [`closed_generalized_force`](Self::closed_generalized_force) when both are
    /// supplied (`None` otherwise); override it only to share work between the two.
    #[inline(always)]
    fn closed_canonical(
        &self,
        q: &[f64],
        p: &[f64],
        t: f64,
        qdot: &mut [f64],
        pdot: &mut [f64],
    ) -> Option<Result<()>> {
        if let Some(r) = self.closed_canonical_in(q, p, t, qdot, pdot) {
            return Some(r);
        }
        if let Err(e) = self.closed_velocity(q, p, t, qdot)? {
            return Some(Err(e));
        }
        self.closed_generalized_force(q, qdot, t, pdot)?;
        Some(Ok(()))
    }

    // Generic closed forms: the same equations on any `FieldScalar`, so that automatic
    // differentiation of them gives the Jacobians of the fields the integrators step
    // (`forward.rs`). The default `f64` closed forms call them at `f64` (one source).

    /// [`closed_acceleration`](Self::closed_acceleration) on any [`FieldScalar`], or `None`.
    /// With it, the first-order field `[qdot, qddot]` has an exact Jacobian
    /// ([`LagrangianEngine::first_order_jacobian`]) for `ndof <= 3`.
    #[inline(always)]
    fn closed_acceleration_in<D: FieldScalar>(
        &self,
        q: &[D],
        qdot: &[D],
        t: f64,
        out: &mut [D],
    ) -> Option<Result<()>> {
        let _ = (q, qdot, t, out);
        None
    }

    /// [`closed_canonical`](Self::closed_canonical) on any [`FieldScalar`], or `None`. With
    /// it, [`LagrangianEngine::closed_canonical_jacobian`] differentiates this field directly
    /// (one dual evaluation) for `ndof <= 3`.
    #[inline(always)]
    fn closed_canonical_in<D: FieldScalar>(
        &self,
        q: &[D],
        p: &[D],
        t: f64,
        qdot: &mut [D],
        pdot: &mut [D],
    ) -> Option<Result<()>> {
        let _ = (q, p, t, qdot, pdot);
        None
    }
}

/// A [`Lagrangian`] with its closed forms hidden: the engine derives every equation of motion
/// of `L` by automatic differentiation. The independent check of hand-derived closed forms,
/// and the way to time the generic path.
///
/// # Example
/// ```
/// use physicskit::classical::lagrangian::{AutoDiff, LagrangianEngine};
/// use physicskit::classical::systems::DoublePendulumParams;
///
/// let closed = LagrangianEngine::new(DoublePendulumParams::default()).unwrap();
/// let automatic = LagrangianEngine::new(AutoDiff(DoublePendulumParams::default())).unwrap();
/// let (q, qdot) = ([2.0, 1.0], [0.5, -0.3]);
/// let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
/// closed.acceleration(&q, &qdot, 0.0, &mut a).unwrap();
/// automatic.acceleration(&q, &qdot, 0.0, &mut b).unwrap();
/// assert!((a[0] - b[0]).abs() < 1e-13 && (a[1] - b[1]).abs() < 1e-13);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AutoDiff<L>(pub L);

impl<L: Lagrangian> Lagrangian for AutoDiff<L> {
    #[inline]
    fn ndof(&self) -> usize {
        self.0.ndof()
    }

    #[inline]
    fn lagrangian<D: Scalar>(&self, q: &[D], qdot: &[D], t: D) -> D {
        self.0.lagrangian(q, qdot, t)
    }
}

/// The error of a singular mass matrix `d2L/dqdot2` at time `t`
/// ([`Error::SingularMatrix`]), for closed forms that detect it.
#[cold]
#[inline(never)]
pub fn singular_mass_matrix(t: f64) -> Error {
    Error::SingularMatrix {
        what: "mass matrix d2L/dqdot2".into(),
        t,
    }
}

/// Tolerances of the iterative inverse Legendre map `v(q, p)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegendreSettings {
    /// Converged when `|p - dL/dv(q, v)|_inf <= tolerance * scale`, `scale` the largest of
    /// `|p|`, `|dL/dv|` and `|M| |v|`. The default, 1e-13 (about 450 ulps), sits above the
    /// rounding floor of the residual of an `n <= 16` system and far below any physical scale.
    pub tolerance: f64,
    /// A residual this small (default 1e-9) that a Newton step no longer halves is the
    /// rounding floor of an ill-conditioned mass matrix and is accepted.
    pub stall_tolerance: f64,
    /// Newton iterations, counting each halving of a step that failed to reduce the residual
    /// (or left the domain of `L`), before [`Error::SolverDidNotConverge`] (default 100).
    pub max_iterations: usize,
}

impl Default for LegendreSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-13,
            stall_tolerance: 1e-9,
            max_iterations: 100,
        }
    }
}

/// Equations of motion of a [`Lagrangian`] by automatic differentiation (see the module
/// documentation for the equations and the cost of each call).
#[derive(Debug, Clone, PartialEq)]
pub struct LagrangianEngine<L> {
    lagrangian: L,
    settings: LegendreSettings,
}

fn lift<D: Scalar>(x: &[f64]) -> VecBuf<D> {
    let mut buf = VecBuf::new(x.len(), D::zero());
    for (b, &xi) in buf.as_mut_slice().iter_mut().zip(x) {
        *b = D::from(xi);
    }
    buf
}

fn hd(re: f64) -> HyperDual64 {
    HyperDual64::new(re, 0.0, 0.0, 0.0)
}

fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Checks that `q`, `x` (named `name`: `qdot` or `p`) and `out` all have length `n`.
fn check_args(n: usize, q: &[f64], name: &str, x: &[f64], out: &[f64]) -> Result<()> {
    check_len("q", q, n)?;
    check_len(name, x, n)?;
    check_len("out", out, n)
}

impl<L: Lagrangian> LagrangianEngine<L> {
    /// An engine for `lagrangian`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if `lagrangian.ndof()` is 0; [`Error::TooLarge`] if the
    /// `ndof x ndof` work matrices of an evaluation would not fit in memory (a chain of `10^5`
    /// masses would need 240 GB: refused here, not aborted at the first evaluation).
    pub fn new(lagrangian: L) -> Result<Self> {
        let n = lagrangian.ndof();
        if n == 0 {
            return Err(Error::invalid("ndof", 0.0, "must be at least 1"));
        }
        // The most an evaluation holds at once: three `n x n` matrices
        // (`canonical_jacobian`), i.e. per degree of freedom three rows of `n` values.
        check_items_fit("ndof", n, n.saturating_mul(3 * 8))?;
        Ok(Self {
            lagrangian,
            settings: LegendreSettings::default(),
        })
    }

    /// The same engine with other inverse-Legendre tolerances.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a tolerance that is not finite and positive or zero
    /// iterations.
    pub fn with_settings(mut self, settings: LegendreSettings) -> Result<Self> {
        for (name, value) in [
            ("tolerance", settings.tolerance),
            ("stall_tolerance", settings.stall_tolerance),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(name, value, "must be finite and > 0"));
            }
        }
        if settings.max_iterations == 0 {
            return Err(Error::invalid("max_iterations", 0.0, "must be at least 1"));
        }
        self.settings = settings;
        Ok(self)
    }

    /// The Lagrangian.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }

    /// Number of degrees of freedom.
    pub fn ndof(&self) -> usize {
        self.lagrangian.ndof()
    }

    /// A [`Phase`] at `t = 0` holding `[q0, qdot0]`, checked for a regular mass matrix.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`], [`Error::NonFinite`], or [`Error::SingularMatrix`] if
    /// `d2L/dqdot2` is singular at the initial state.
    pub fn initial_phase(&self, q0: &[f64], qdot0: &[f64]) -> Result<Phase> {
        let n = self.ndof();
        check_vector("q0", q0, n)?;
        check_vector("qdot0", qdot0, n)?;
        self.check_regular(q0, qdot0, 0.0)?;
        Phase::from_halves("q0", q0, "qdot0", qdot0)
    }

    /// `L(q, qdot, t)` in plain `f64`.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for wrong lengths.
    pub fn value(&self, q: &[f64], qdot: &[f64], t: f64) -> Result<f64> {
        let n = self.ndof();
        check_len("q", q, n)?;
        check_len("qdot", qdot, n)?;
        Ok(self.lagrangian.lagrangian(q, qdot, t))
    }

    /// Checks that the mass matrix is regular at `(q, qdot, t)`.
    ///
    /// # Errors
    /// [`Error::SingularMatrix`], or [`Error::DimensionMismatch`] for wrong lengths.
    pub fn check_regular(&self, q: &[f64], qdot: &[f64], t: f64) -> Result<()> {
        let n = self.ndof();
        let mut m = MatBuf::new(n * n, 0.0);
        self.mass_matrix(q, qdot, t, m.as_mut_slice())?;
        let mut piv = VecBuf::new(n, 0_usize);
        lu_factor(m.as_mut_slice(), n, piv.as_mut_slice()).map_err(|_| singular_mass_matrix(t))
    }

    /// Writes the mass matrix `M = d2L/dqdot2` (row-major `n x n`) into `out`.
    /// Costs `n(n+1)/2` hyper-dual evaluations.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for wrong lengths.
    pub fn mass_matrix(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        check_len("q", q, n)?;
        check_len("qdot", qdot, n)?;
        check_len("mass matrix", out, n * n)?;
        if self
            .lagrangian
            .closed_mass_matrix(q, qdot, t, out)
            .is_some()
        {
            return Ok(());
        }
        self.hessian_vv_scalar(q, qdot, t, out, None);
        Ok(())
    }

    /// Writes the generalized force `dL/dq` at `(q, qdot, t)` into `out` (`n` dual
    /// evaluations).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for wrong lengths.
    pub fn generalized_force(
        &self,
        q: &[f64],
        qdot: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.ndof();
        check_args(n, q, "qdot", qdot, out)?;
        if self
            .lagrangian
            .closed_generalized_force(q, qdot, t, out)
            .is_some()
        {
            return Ok(());
        }
        let mut qd = lift::<Dual64>(q);
        let vd = lift::<Dual64>(qdot);
        let td = Dual64::from(t);
        for (i, o) in out.iter_mut().enumerate() {
            qd.as_mut_slice()[i].eps = 1.0;
            *o = self
                .lagrangian
                .lagrangian(qd.as_slice(), vd.as_slice(), td)
                .eps;
            qd.as_mut_slice()[i].eps = 0.0;
        }
        Ok(())
    }

    /// Writes the canonical momentum `p = dL/dqdot` into `out` (`n` dual evaluations).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for wrong lengths.
    pub fn momentum(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        check_args(n, q, "qdot", qdot, out)?;
        if self.lagrangian.closed_momentum(q, qdot, t, out).is_some() {
            return Ok(());
        }
        let qd = lift::<Dual64>(q);
        let mut vd = lift::<Dual64>(qdot);
        let td = Dual64::from(t);
        for (i, o) in out.iter_mut().enumerate() {
            vd.as_mut_slice()[i].eps = 1.0;
            *o = self
                .lagrangian
                .lagrangian(qd.as_slice(), vd.as_slice(), td)
                .eps;
            vd.as_mut_slice()[i].eps = 0.0;
        }
        Ok(())
    }

    /// The energy function `H = p . qdot - L` (one dual evaluation: `p . qdot` is the
    /// derivative of `L` along `qdot` in velocity space). Equals `T + V` for `L = T - V` with
    /// `T` quadratic in `qdot`; in a rotating frame it is the Jacobi integral. `NaN` for wrong
    /// lengths.
    pub fn energy(&self, q: &[f64], qdot: &[f64], t: f64) -> f64 {
        let n = self.ndof();
        if q.len() != n || qdot.len() != n {
            return f64::NAN;
        }
        if let Some(e) = self.lagrangian.closed_energy(q, qdot, t) {
            return e;
        }
        let qd = lift::<Dual64>(q);
        let mut vd = lift::<Dual64>(qdot);
        for (d, &v) in vd.as_mut_slice().iter_mut().zip(qdot) {
            d.eps = v;
        }
        let l = self
            .lagrangian
            .lagrangian(qd.as_slice(), vd.as_slice(), Dual64::from(t));
        l.eps - l.re
    }

    /// [`energy`](Self::energy) of a stacked state `[q, qdot]`; `NaN` for a wrong length.
    pub fn energy_of_state(&self, state: &[f64], t: f64) -> f64 {
        let n = self.ndof();
        if state.len() != 2 * n {
            return f64::NAN;
        }
        let (q, qdot) = state.split_at(n);
        self.energy(q, qdot, t)
    }

    /// Writes the acceleration `qddot` from the Euler–Lagrange equations into `out`.
    ///
    /// # Errors
    /// [`Error::SingularMatrix`] if `d2L/dqdot2` is singular; [`Error::DimensionMismatch`] for
    /// wrong lengths.
    pub fn acceleration(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        check_args(n, q, "qdot", qdot, out)?;
        if let Some(r) = self.lagrangian.closed_acceleration(q, qdot, t, out) {
            return r;
        }
        match n {
            1 => return self.acceleration_fixed::<1, 3>(q, qdot, t, out),
            2 => return self.acceleration_fixed::<2, 5>(q, qdot, t, out),
            3 => return self.acceleration_fixed::<3, 7>(q, qdot, t, out),
            _ => {}
        }
        let mut m = MatBuf::new(n * n, 0.0);
        self.hessian_vv_scalar(q, qdot, t, m.as_mut_slice(), None);
        let mut mixed = VecBuf::new(n, 0.0);
        self.mixed_time_derivative(q, qdot, t, mixed.as_mut_slice());
        self.generalized_force(q, qdot, t, out)?;
        for (o, c) in out.iter_mut().zip(mixed.as_slice()) {
            *o -= c;
        }
        let mut piv = VecBuf::new(n, 0_usize);
        lu_factor(m.as_mut_slice(), n, piv.as_mut_slice()).map_err(|_| singular_mass_matrix(t))?;
        lu_solve(m.as_slice(), n, piv.as_slice(), out);
        Ok(())
    }

    /// [`acceleration`](Self::acceleration) for `N` degrees of freedom (`Z = 2N + 1`): one
    /// evaluation of `L` on hyper-dual vectors, `e1` seeding `v` and `e2` seeding `(q, v, t)`,
    /// gives `dL/dq`, `M` and the mixed derivatives `d2L/dv dq`, `d2L/dv dt` at once.
    #[inline(never)]
    fn acceleration_fixed<const N: usize, const Z: usize>(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Result<()> {
        debug_assert_eq!(Z, 2 * N + 1);
        let mut m = [0.0; FIXED_NDOF * FIXED_NDOF];
        let m = &mut m[..N * N];
        let out = &mut out[..N];
        #[cfg(not(feature = "num-dual-kernels"))]
        {
            let mut qd = [HyperArr::<N, Z>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = HyperArr::from_re(q[i]).derivative2(i);
                vd[i] = HyperArr::from_re(v[i]).derivative1(i).derivative2(N + i);
            }
            let td = HyperArr::from_re(t).derivative2(2 * N);
            let l = self.lagrangian.lagrangian(&qd, &vd, td);
            out.copy_from_slice(&l.e2[..N]);
            let h = &l.e12;
            for i in 0..N {
                let mut mixed = h[i][2 * N];
                for (j, &vj) in v.iter().enumerate().take(N) {
                    mixed += h[i][j] * vj;
                    m[i * N + j] = h[i][N + j];
                }
                out[i] -= mixed;
            }
        }
        #[cfg(feature = "num-dual-kernels")]
        {
            let mut qd = [HyperDualSVec64::<N, Z>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = HyperDualSVec64::from_re(q[i]).derivative2(i);
                vd[i] = HyperDualSVec64::from_re(v[i])
                    .derivative1(i)
                    .derivative2(N + i);
            }
            let td = HyperDualSVec64::from_re(t).derivative2(2 * N);
            let l = self.lagrangian.lagrangian(&qd, &vd, td);
            match &l.eps2.0 {
                Some(g) => out.iter_mut().enumerate().for_each(|(i, o)| *o = g[i]),
                None => out.fill(0.0),
            }
            if let Some(h) = &l.eps1eps2.0 {
                for i in 0..N {
                    let mut mixed = h[(i, 2 * N)];
                    for (j, &vj) in v.iter().enumerate().take(N) {
                        mixed += h[(i, j)] * vj;
                        m[i * N + j] = h[(i, N + j)];
                    }
                    out[i] -= mixed;
                }
            }
        }
        let mut piv = [0_usize; FIXED_NDOF];
        factor::<N>(m, N, &mut piv[..N]).map_err(|_| singular_mass_matrix(t))?;
        solve::<N>(m, N, &piv[..N], out);
        Ok(())
    }

    /// Writes the velocity `qdot(q, p, t)` that inverts `p = dL/dqdot` into `out`.
    ///
    /// # Errors
    /// [`Error::SingularMatrix`]; [`Error::SolverDidNotConverge`] if Newton's method fails
    /// (only possible for a Lagrangian that is not quadratic in `qdot`);
    /// [`Error::DimensionMismatch`] for wrong lengths.
    pub fn velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        check_args(n, q, "p", p, out)?;
        if let Some(r) = self.lagrangian.closed_velocity(q, p, t, out) {
            return r;
        }
        let mut force = VecBuf::new(n, 0.0);
        self.solve_velocity(q, p, t, out, force.as_mut_slice())
            .map(|_| ())
    }

    /// Writes `[dq/dt, dp/dt] = [qdot(q, p), dL/dq(q, qdot(q, p), t)]` at the canonical state
    /// `[q, p]` into `out`.
    ///
    /// # Errors
    /// As [`velocity`](Self::velocity).
    pub fn canonical_derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        check_len("state", state, 2 * n)?;
        check_len("out", out, 2 * n)?;
        let (q, p) = state.split_at(n);
        let (v, force) = out.split_at_mut(n);
        if let Some(r) = self.lagrangian.closed_canonical(q, p, t, v, force) {
            return r;
        }
        self.solve_velocity(q, p, t, v, force).map(|_| ())
    }

    /// Writes the Jacobian of [`canonical_derivatives`](Self::canonical_derivatives)
    /// (row-major `2n x 2n`) into `out`. With `v = qdot(q, p)` and the second derivatives of
    /// `L` at `(q, v)`, implicit differentiation of `p = dL/dv(q, v)` gives
    ///
    /// ```text
    /// d(dq/dt)/dq = -M^-1 L_vq        d(dq/dt)/dp = M^-1
    /// d(dp/dt)/dq = L_qq - L_qv M^-1 L_vq   d(dp/dt)/dp = L_qv M^-1
    /// ```
    ///
    /// # Errors
    /// As [`velocity`](Self::velocity).
    pub fn canonical_jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        let n = self.ndof();
        let dim = 2 * n;
        check_len("state", state, dim)?;
        check_len("out", out, dim * dim)?;
        let (q, p) = state.split_at(n);
        let mut v = VecBuf::new(n, 0.0);
        let mut force = VecBuf::new(n, 0.0);
        self.solve_velocity(q, p, t, v.as_mut_slice(), force.as_mut_slice())?;
        self.hessian_full(q, v.as_slice(), t, out);
        let mut lvq = MatBuf::new(n * n, 0.0);
        let mut lu = MatBuf::new(n * n, 0.0);
        {
            let (lvq, lu) = (lvq.as_mut_slice(), lu.as_mut_slice());
            for i in 0..n {
                for j in 0..n {
                    lvq[i * n + j] = out[(n + i) * dim + j];
                    lu[i * n + j] = out[(n + i) * dim + n + j];
                }
            }
        }
        let mut piv = VecBuf::new(n, 0_usize);
        lu_factor(lu.as_mut_slice(), n, piv.as_mut_slice()).map_err(|_| singular_mass_matrix(t))?;
        let (lu, piv) = (lu.as_slice(), piv.as_slice());
        // X = M^-1 L_vq, column by column.
        let mut x = MatBuf::new(n * n, 0.0);
        let mut col = VecBuf::new(n, 0.0);
        for j in 0..n {
            let c = col.as_mut_slice();
            for (i, ci) in c.iter_mut().enumerate() {
                *ci = lvq.as_slice()[i * n + j];
            }
            lu_solve(lu, n, piv, c);
            for (i, &ci) in c.iter().enumerate() {
                x.as_mut_slice()[i * n + j] = ci;
            }
        }
        let (x, lvq) = (x.as_slice(), lvq.as_slice());
        // Lower left first: it reads L_qq from the upper-left block before that is overwritten.
        for i in 0..n {
            for j in 0..n {
                let s: f64 = (0..n).map(|k| lvq[k * n + i] * x[k * n + j]).sum();
                out[(n + i) * dim + j] = out[i * dim + j] - s;
                out[(n + i) * dim + n + j] = x[j * n + i];
                out[i * dim + j] = -x[i * n + j];
            }
        }
        // Upper right: M^-1, column by column.
        for j in 0..n {
            let c = col.as_mut_slice();
            c.iter_mut()
                .enumerate()
                .for_each(|(i, ci)| *ci = f64::from(u8::from(i == j)));
            lu_solve(lu, n, piv, c);
            for (i, &ci) in c.iter().enumerate() {
                out[i * dim + n + j] = ci;
            }
        }
        Ok(())
    }

    /// Writes the Jacobian of the first-order field `[qdot, qddot(q, qdot, t)]` with respect
    /// to the state `[q, qdot]` (row-major `2n x 2n`: `[[0, I], [dqddot/dq, dqddot/dqdot]]`)
    /// into `out`, by one forward-mode dual evaluation of the Lagrangian's generic closed
    /// acceleration ([`Lagrangian::closed_acceleration_in`]). `None` when the Lagrangian
    /// supplies none or `ndof > 3` (the tangent dynamics then take central differences).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for wrong lengths; [`Error::SingularMatrix`] as
    /// [`acceleration`](Self::acceleration).
    pub fn first_order_jacobian(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
    ) -> Option<Result<()>> {
        self.closed_jacobian(t, state, out, Field::FirstOrder)
    }

    /// Writes the Jacobian of the closed-form canonical field
    /// ([`Lagrangian::closed_canonical_in`], which at `f64` is what `canonical_derivatives`
    /// evaluates) into `out` by one forward-mode dual evaluation; `None` when the Lagrangian
    /// supplies none or `ndof > 3`. It agrees with [`canonical_jacobian`](Self::canonical_jacobian)
    /// to ~1e-15 relative, at a fraction of its cost; the integrators keep
    /// `canonical_jacobian`, because a different Newton matrix changes the last bits of the
    /// steps that use Newton (the hoop with `gauss_legendre4` at `dt = 0.5`), and trajectories
    /// are pinned bit for bit.
    ///
    /// # Errors
    /// As [`first_order_jacobian`](Self::first_order_jacobian).
    pub fn closed_canonical_jacobian(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
    ) -> Option<Result<()>> {
        self.closed_jacobian(t, state, out, Field::Canonical)
    }

    /// The Jacobian of `field` at `state` from the generic closed forms, for `ndof <= 3`;
    /// `None` if there are none, a dimension error for wrong lengths.
    #[inline]
    fn closed_jacobian(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
        field: Field,
    ) -> Option<Result<()>> {
        let dim = 2 * self.ndof();
        if let Err(e) = check_len("state", state, dim).and(check_len("out", out, dim * dim)) {
            return Some(Err(e));
        }
        match self.ndof() {
            1 => self.closed_jacobian_fixed::<1, 2>(t, state, out, field),
            2 => self.closed_jacobian_fixed::<2, 4>(t, state, out, field),
            3 => self.closed_jacobian_fixed::<3, 6>(t, state, out, field),
            _ => None,
        }
    }

    /// [`closed_jacobian`](Self::closed_jacobian) for `N` degrees of freedom (`M = 2N`).
    fn closed_jacobian_fixed<const N: usize, const M: usize>(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
        field: Field,
    ) -> Option<Result<()>> {
        forward_jacobian::<M>(state, out, |z, f| {
            let (q, v) = z.split_at(N);
            let (dq, dv) = f.split_at_mut(N);
            match field {
                Field::FirstOrder => {
                    dq.copy_from_slice(v);
                    self.lagrangian.closed_acceleration_in(q, v, t, dv)
                }
                Field::Canonical => self.lagrangian.closed_canonical_in(q, v, t, dq, dv),
            }
        })
    }

    /// [`hessian_vv_scalar`](Self::hessian_vv_scalar) for `N` degrees of freedom: one
    /// evaluation of `L` on second-order vector duals seeded in `v`.
    #[inline]
    fn hessian_vv_static<const N: usize>(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        m: &mut [f64],
        grad: Option<&mut [f64]>,
    ) {
        #[cfg(not(feature = "num-dual-kernels"))]
        {
            let mut qd = [Dual2Arr::<N>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = Dual2Arr::from_re(q[i]);
                vd[i] = Dual2Arr::seeded(v[i], i);
            }
            let l = self.lagrangian.lagrangian(&qd, &vd, Dual2Arr::from_re(t));
            for i in 0..N {
                for j in i..N {
                    m[i * N + j] = l.v2[i][j];
                    m[j * N + i] = l.v2[i][j];
                }
            }
            if let Some(g) = grad {
                g[..N].copy_from_slice(&l.v1);
            }
        }
        #[cfg(feature = "num-dual-kernels")]
        {
            let mut qd = [Dual2SVec64::<N>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = Dual2SVec64::from_re(q[i]);
                vd[i] = Dual2SVec64::from_re(v[i]).derivative(i);
            }
            let l = self
                .lagrangian
                .lagrangian(&qd, &vd, Dual2SVec64::from_re(t));
            match &l.v2.0 {
                Some(h) => {
                    for i in 0..N {
                        for j in i..N {
                            m[i * N + j] = h[(i, j)];
                            m[j * N + i] = h[(i, j)];
                        }
                    }
                }
                None => m[..N * N].fill(0.0),
            }
            if let Some(g) = grad {
                match &l.v1.0 {
                    Some(d) => g[..N].iter_mut().enumerate().for_each(|(i, gi)| *gi = d[i]),
                    None => g[..N].fill(0.0),
                }
            }
        }
    }

    /// `M = d2L/dv2` into `m`, and `dL/dv` into `grad` if given, for any `n`: `n(n+1)/2`
    /// hyper-dual evaluations.
    fn hessian_vv_scalar(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        m: &mut [f64],
        mut grad: Option<&mut [f64]>,
    ) {
        let n = q.len();
        let qd = lift::<HyperDual64>(q);
        let mut vd = lift::<HyperDual64>(v);
        let td = hd(t);
        for i in 0..n {
            for j in i..n {
                vd.as_mut_slice()[i].eps1 = 1.0;
                vd.as_mut_slice()[j].eps2 = 1.0;
                let l = self.lagrangian.lagrangian(qd.as_slice(), vd.as_slice(), td);
                vd.as_mut_slice()[i].eps1 = 0.0;
                vd.as_mut_slice()[j].eps2 = 0.0;
                m[i * n + j] = l.eps1eps2;
                m[j * n + i] = l.eps1eps2;
                if i == j {
                    if let Some(g) = grad.as_deref_mut() {
                        g[i] = l.eps1;
                    }
                }
            }
        }
    }

    /// The full Hessian of `L` in `z = (q, v)`, row-major `2n x 2n`, into `out`.
    fn hessian_full(&self, q: &[f64], v: &[f64], t: f64, out: &mut [f64]) {
        let n = q.len();
        let dim = 2 * n;
        let mut qd = lift::<HyperDual64>(q);
        let mut vd = lift::<HyperDual64>(v);
        let td = hd(t);
        for a in 0..dim {
            for b in a..dim {
                let mut seed = |k: usize, first: bool, on: f64| {
                    let d = if k < n {
                        &mut qd.as_mut_slice()[k]
                    } else {
                        &mut vd.as_mut_slice()[k - n]
                    };
                    if first {
                        d.eps1 = on;
                    } else {
                        d.eps2 = on;
                    }
                };
                seed(a, true, 1.0);
                seed(b, false, 1.0);
                let l = self.lagrangian.lagrangian(qd.as_slice(), vd.as_slice(), td);
                let mut reset = |k: usize, first: bool| {
                    let d = if k < n {
                        &mut qd.as_mut_slice()[k]
                    } else {
                        &mut vd.as_mut_slice()[k - n]
                    };
                    if first {
                        d.eps1 = 0.0;
                    } else {
                        d.eps2 = 0.0;
                    }
                };
                reset(a, true);
                reset(b, false);
                out[a * dim + b] = l.eps1eps2;
                out[b * dim + a] = l.eps1eps2;
            }
        }
    }

    /// `(d2L/dv dq) v + d2L/dv dt` into `out`: the part of `d/dt (dL/dv)` not involving the
    /// acceleration. One hyper-dual evaluation per component: `e1` seeds `v_i`, `e2` the
    /// direction `(dq, dt) = (v, 1)`.
    fn mixed_time_derivative(&self, q: &[f64], v: &[f64], t: f64, out: &mut [f64]) {
        let mut qd = lift::<HyperDual64>(q);
        for (d, &vi) in qd.as_mut_slice().iter_mut().zip(v) {
            d.eps2 = vi;
        }
        let mut vd = lift::<HyperDual64>(v);
        let td = HyperDual64::new(t, 0.0, 1.0, 0.0);
        for (i, o) in out.iter_mut().enumerate() {
            vd.as_mut_slice()[i].eps1 = 1.0;
            *o = self
                .lagrangian
                .lagrangian(qd.as_slice(), vd.as_slice(), td)
                .eps1eps2;
            vd.as_mut_slice()[i].eps1 = 0.0;
        }
    }

    /// `dL/dv` and `dL/dq` at `(q, v)` for `N` degrees of freedom (`N2 = 2N`):
    /// one evaluation of `L` on vector duals seeded in `(q, v)`.
    #[inline]
    fn momentum_and_force_static<const N: usize, const N2: usize>(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        p: &mut [f64],
        force: &mut [f64],
    ) {
        debug_assert_eq!(N2, 2 * N);
        #[cfg(not(feature = "num-dual-kernels"))]
        {
            let mut qd = [DualArr::<N2>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = DualArr::seeded(q[i], i);
                vd[i] = DualArr::seeded(v[i], N + i);
            }
            let l = self.lagrangian.lagrangian(&qd, &vd, DualArr::from_re(t));
            force[..N].copy_from_slice(&l.eps[..N]);
            p[..N].copy_from_slice(&l.eps[N..]);
        }
        #[cfg(feature = "num-dual-kernels")]
        {
            let mut qd = [DualSVec64::<N2>::from_re(0.0); N];
            let mut vd = qd;
            for i in 0..N {
                qd[i] = DualSVec64::from_re(q[i]).derivative(i);
                vd[i] = DualSVec64::from_re(v[i]).derivative(N + i);
            }
            let l = self.lagrangian.lagrangian(&qd, &vd, DualSVec64::from_re(t));
            match &l.eps.0 {
                Some(d) => {
                    for i in 0..N {
                        force[i] = d[i];
                        p[i] = d[N + i];
                    }
                }
                None => {
                    force[..N].fill(0.0);
                    p[..N].fill(0.0);
                }
            }
        }
    }

    /// `dL/dv` and `dL/dq` at `(q, v)` for any `n`: one hyper-dual evaluation
    /// per component (`e1` seeds `v_i`, `e2` seeds `q_i`).
    fn momentum_and_force_scalar(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        p: &mut [f64],
        force: &mut [f64],
    ) {
        let n = q.len();
        let mut qd = lift::<HyperDual64>(q);
        let mut vd = lift::<HyperDual64>(v);
        let td = hd(t);
        for i in 0..n {
            vd.as_mut_slice()[i].eps1 = 1.0;
            qd.as_mut_slice()[i].eps2 = 1.0;
            let l = self.lagrangian.lagrangian(qd.as_slice(), vd.as_slice(), td);
            vd.as_mut_slice()[i].eps1 = 0.0;
            qd.as_mut_slice()[i].eps2 = 0.0;
            p[i] = l.eps1;
            force[i] = l.eps2;
        }
    }

    /// Newton's method on `dL/dv(q, v) = p`, starting with the step from `v = 0` that is exact
    /// for a Lagrangian quadratic in `v`, halving steps that do not reduce the residual.
    /// Writes `v` and `dL/dq(q, v)`; returns the iterations.
    fn solve_velocity(
        &self,
        q: &[f64],
        p: &[f64],
        t: f64,
        v: &mut [f64],
        force: &mut [f64],
    ) -> Result<usize> {
        match q.len() {
            1 => self.solve_velocity_fixed::<1>(q, p, t, v, force),
            2 => self.solve_velocity_fixed::<2>(q, p, t, v, force),
            3 => self.solve_velocity_fixed::<3>(q, p, t, v, force),
            n => {
                let mut m = MatBuf::new(n * n, 0.0);
                let mut piv = VecBuf::new(n, 0_usize);
                let mut r = VecBuf::new(n, 0.0);
                let mut pv = VecBuf::new(n, 0.0);
                let mut base = VecBuf::new(n, 0.0);
                let mut step = VecBuf::new(n, 0.0);
                let work = VelocityWork {
                    m: m.as_mut_slice(),
                    piv: piv.as_mut_slice(),
                    r: r.as_mut_slice(),
                    pv: pv.as_mut_slice(),
                    base: base.as_mut_slice(),
                    step: step.as_mut_slice(),
                };
                self.newton_velocity::<0>(q, p, t, v, force, work)
            }
        }
    }

    /// [`solve_velocity`](Self::solve_velocity) for `N <= FIXED_NDOF` degrees of freedom, with
    /// exactly sized stack buffers.
    fn solve_velocity_fixed<const N: usize>(
        &self,
        q: &[f64],
        p: &[f64],
        t: f64,
        v: &mut [f64],
        force: &mut [f64],
    ) -> Result<usize> {
        let mut m = [0.0; FIXED_NDOF * FIXED_NDOF];
        let mut piv = [0_usize; FIXED_NDOF];
        let mut r = [0.0; FIXED_NDOF];
        let mut pv = [0.0; FIXED_NDOF];
        let mut base = [0.0; FIXED_NDOF];
        let mut step = [0.0; FIXED_NDOF];
        let work = VelocityWork {
            m: &mut m[..N * N],
            piv: &mut piv[..N],
            r: &mut r[..N],
            pv: &mut pv[..N],
            base: &mut base[..N],
            step: &mut step[..N],
        };
        self.newton_velocity::<N>(q, p, t, v, force, work)
    }

    /// `M = d2L/dv2` and optionally `dL/dv` for `N` degrees of freedom (`N = 0`: any).
    #[inline(always)]
    fn hessian_vv_n<const N: usize>(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        m: &mut [f64],
        grad: Option<&mut [f64]>,
    ) {
        match N {
            1 => self.hessian_vv_static::<1>(q, v, t, m, grad),
            2 => self.hessian_vv_static::<2>(q, v, t, m, grad),
            3 => self.hessian_vv_static::<3>(q, v, t, m, grad),
            _ => self.hessian_vv_scalar(q, v, t, m, grad),
        }
    }

    /// `dL/dv` and `dL/dq` for `N` degrees of freedom (`N = 0`: any).
    #[inline(always)]
    fn momentum_and_force_n<const N: usize>(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        p: &mut [f64],
        force: &mut [f64],
    ) {
        match N {
            1 => self.momentum_and_force_static::<1, 2>(q, v, t, p, force),
            2 => self.momentum_and_force_static::<2, 4>(q, v, t, p, force),
            3 => self.momentum_and_force_static::<3, 6>(q, v, t, p, force),
            _ => self.momentum_and_force_scalar(q, v, t, p, force),
        }
    }

    /// The Newton iteration of [`solve_velocity`](Self::solve_velocity), for `N` degrees of
    /// freedom known at compile time (`N = 0`: any, taken from `q`).
    #[inline(always)]
    fn newton_velocity<const N: usize>(
        &self,
        q: &[f64],
        p: &[f64],
        t: f64,
        v: &mut [f64],
        force: &mut [f64],
        work: VelocityWork<'_>,
    ) -> Result<usize> {
        let n = if N == 0 { q.len() } else { N };
        let s = self.settings;
        // `base` is the last accepted iterate, `step` the Newton step from it.
        let VelocityWork {
            m,
            piv,
            r,
            pv,
            base,
            step,
        } = work;
        self.hessian_vv_n::<N>(q, base, t, m, Some(pv));
        let mut m_norm = inf_norm(m);
        let mut accepted_r = 0.0_f64;
        for ((si, &pi), &p0) in step.iter_mut().zip(p).zip(pv.iter()) {
            *si = pi - p0;
            accepted_r = accepted_r.max(si.abs());
        }
        factor::<N>(m, n, piv).map_err(|_| singular_mass_matrix(t))?;
        solve::<N>(m, n, piv, step);
        let p_norm = inf_norm(p).max(inf_norm(pv));
        let mut lambda = 1.0_f64;
        let mut residual = f64::INFINITY;
        for it in 1..=s.max_iterations {
            for ((vi, &bi), &di) in v.iter_mut().zip(base.iter()).zip(step.iter()) {
                *vi = bi + lambda * di;
            }
            self.momentum_and_force_n::<N>(q, v, t, pv, force);
            let mut r_norm = 0.0_f64;
            for ((ri, &pi), &pvi) in r.iter_mut().zip(p).zip(pv.iter()) {
                *ri = pi - pvi;
                // `max` would skip a NaN; a non-finite residual must count as infinite.
                r_norm = if ri.is_finite() {
                    r_norm.max(ri.abs())
                } else {
                    f64::INFINITY
                };
            }
            let scale = p_norm.max(inf_norm(pv)).max(m_norm * inf_norm(v));
            residual = if r_norm == 0.0 { 0.0 } else { r_norm / scale };
            if residual <= s.tolerance {
                return Ok(it);
            }
            if r_norm >= accepted_r {
                if residual <= s.stall_tolerance {
                    // At the rounding floor of an ill-conditioned mass matrix.
                    return Ok(it);
                }
                // The full step left the domain of L (NaN) or overshot: backtrack.
                lambda *= 0.5;
                continue;
            }
            base.copy_from_slice(v);
            accepted_r = r_norm;
            lambda = 1.0;
            // Rare (non-quadratic L): the scalar kernel keeps the vector-dual instantiations of
            // L at one call site each, which lets them inline into this loop.
            self.hessian_vv_scalar(q, v, t, m, None);
            m_norm = m_norm.max(inf_norm(m));
            factor::<N>(m, n, piv).map_err(|_| singular_mass_matrix(t))?;
            step.copy_from_slice(r);
            solve::<N>(m, n, piv, step);
        }
        Err(Error::SolverDidNotConverge {
            t,
            iterations: s.max_iterations,
            residual,
        })
    }
}

/// Which vector field of a Lagrangian system a Jacobian is of.
#[derive(Clone, Copy)]
enum Field {
    /// `[qdot, qddot]` in `[q, qdot]`.
    FirstOrder,
    /// `[qdot(q, p), dL/dq]` in `[q, p]`.
    Canonical,
}

/// Largest number of degrees of freedom with compile-time-sized kernels (vector duals, one
/// evaluation of `L` per kernel, unrolled LU).
const FIXED_NDOF: usize = 3;

/// Work buffers of the inverse Legendre map, all of length `n` (`m`: `n x n`).
struct VelocityWork<'a> {
    m: &'a mut [f64],
    piv: &'a mut [usize],
    r: &'a mut [f64],
    pv: &'a mut [f64],
    base: &'a mut [f64],
    step: &'a mut [f64],
}

/// [`lu_factor`] with the size `N` known at compile time (`N = 0`: the runtime `n`): the core
/// routine is inlined, so with a constant size the compiler unrolls it; the operations (and
/// so the factors) are the same.
#[inline(always)]
fn factor<const N: usize>(
    a: &mut [f64],
    n: usize,
    piv: &mut [usize],
) -> std::result::Result<(), Singular> {
    if N == 0 {
        lu_factor(a, n, piv)
    } else {
        lu_factor(&mut a[..N * N], N, &mut piv[..N])
    }
}

/// [`lu_solve`] with the size `N` known at compile time (`N = 0`: the runtime `n`).
#[inline(always)]
fn solve<const N: usize>(lu: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    if N == 0 {
        lu_solve(lu, n, piv, b)
    } else {
        lu_solve(&lu[..N * N], N, &piv[..N], &mut b[..N])
    }
}
