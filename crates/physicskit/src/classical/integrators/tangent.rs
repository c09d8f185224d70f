//! [`Flow`]: one step of a method on a system, with or without its tangent dynamics.
//!
//! The chaos indicators (`analysis::lyapunov`, `analysis::sali`) follow deviation vectors
//! `w` along an orbit; the Poincaré section (`analysis::section`) re-runs a step with another
//! length. Both need the method's step as an object. A `Flow` is built once per run by
//! [`hamiltonian_flow`], [`lagrangian_flow`] or [`ode_flow`] (or `DynSystem::flow`) through
//! [`Method::dispatch`], so every method of the registry has a flow with no per-method code;
//! inside, everything is monomorphized for the system and method, and a run pays one dynamic
//! call per step.
//!
//! **Tangent dynamics.** Linearizing the step map `Φ_h` gives `w ↦ DΦ_h(y) w`.
//!
//! - *Splitting methods* (Verlet compositions on `H = T(p) + V(q)`): the step is a sequence
//!   of kicks `p ← p + a h F(q)` and drifts `q ← q + b h M⁻¹ p`; its exact derivative is the
//!   same sequence on the deviation `(δq, δp)`:
//!
//!   ```text
//!   kick:  δp ← δp + a h J(q) δq,   J = ∂F/∂q = -∂²V/∂q²
//!   drift: δq ← δq + b h M⁻¹ δp
//!   ```
//!
//!   with `J` at the `q` of the kick. Each factor is a shear of determinant one (symplectic
//!   when `J` is symmetric), so the discrete tangent map has `det DΦ_h = 1` exactly, and a
//!   full Lyapunov spectrum sums to zero to rounding (Skokos & Gerlach, "Numerical integration
//!   of variational equations", Phys. Rev. E 82, 036704, 2010, call this the tangent map
//!   method). Like the force, `J` after the last drift is reused by the next step's first kick.
//! - *Methods on a vector field*: the variational equations `dw/dt = Df(y) w` are appended to
//!   the orbit's (`n (1 + k)` components for `k` vectors) and integrated by the same method.
//!   For an explicit Runge–Kutta method the orbit part is computed with the same operations as
//!   without the vectors, so the orbit is bit-identical to the plain run.
//!
//! **Jacobians.** The system's own (`HamiltonianSystem::force_jacobian`,
//! `DynamicalSystem::jacobian`, `LagrangianSystem::canonical_jacobian`) where it has one;
//! otherwise central differences with the step `h_j = ε^(1/3) max(1, |x_j|)`
//! (`ε` = 2.2e-16, so `h ≈ 6e-6`): truncation `O(h²)` and rounding `O(ε/h)` are then both
//! about `ε^(2/3) ≈ 4e-11` relative, the best a central difference can do. `2 n` evaluations
//! per Jacobian. Which systems have which:
//!
//! | systems | Jacobian |
//! |---|---|
//! | Kepler, Hénon–Heiles, harmonic / FPUT / sine-Gordon chains, Toda, pendulum swarm, projectile, Euler top, the examples | analytic (hand-derived `force_jacobian` / `jacobian`) |
//! | double pendulum, hoop, heavy symmetric top, elastic pendulum | `[q, qdot]` (explicit methods): automatic differentiation (num-dual, forward mode) of the closed-form acceleration the integrator steps (`lagrangian/forward.rs`); `[q, p]` (implicit methods): automatic differentiation of `L` (`LagrangianEngine::canonical_jacobian`) |
//! | coupled oscillators, `LagrangianModel` (users' and SymPy Lagrangians) | `[q, p]`: automatic differentiation of `L`; `[q, qdot]`: central differences |
//! | SymPy `HamiltonianEngine` / `ODEEngine` (`ExprHamiltonian`, `ExprOde`) | automatic differentiation of the compiled expressions (`lagrangian/tape.rs`) |
//! | Python subclasses | their `force_jacobian(q, t)` / `jacobian(t, state)` if defined, else central differences |

use std::cell::RefCell;

use super::compensated;
use super::field::{Canonical, FirstOrder, VectorField};
use super::splitting::{check_system, Coefficients, SplittingStepper};
use super::stepper::{splitting_refused, AdaptiveStepper, Dispatch, FieldStepper};
use crate::classical::core::{Error, Result};
use crate::classical::integrators::system::Family;
use crate::classical::integrators::{
    HamiltonianSystem, LagrangianSystem, MassInv, Method, OdeSystem,
};

/// The relative step of the central differences: `ε^(1/3)` (see the module docs).
pub const FD_STEP: f64 = 6.055_454_452_393_343e-6;

/// One step of a method on a system, with or without deviation vectors.
///
/// The flow works in its own coordinates `y` of length [`dim`](Self::dim) (the system's state,
/// except for a Lagrangian system on an implicit method, which runs on `[q, p]`);
/// [`enter`](Self::enter) and [`leave`](Self::leave) convert.
pub trait Flow {
    /// Length of the working state.
    fn dim(&self) -> usize;

    /// The working state of the system state `state` at `t`, written into `y`.
    ///
    /// # Errors
    /// Evaluation failures of the conversion (a singular mass matrix).
    fn enter(&self, t: f64, state: &[f64], y: &mut [f64]) -> Result<()>;

    /// The system state of the working state `y` at `t`, written into `state`.
    ///
    /// # Errors
    /// As [`enter`](Self::enter).
    fn leave(&self, t: f64, y: &[f64], state: &mut [f64]) -> Result<()>;

    /// Advances `y` by one step `h`, continuing from the previous call (a splitting method
    /// reuses the force of the last step).
    ///
    /// # Errors
    /// Whatever the system or the method reports.
    fn step(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()>;

    /// Advances `y` by one step `h` from a state unrelated to the previous steps, leaving the
    /// state of [`step`](Self::step) untouched (the Poincaré section re-runs the step before a
    /// crossing with shorter lengths).
    ///
    /// # Errors
    /// As [`step`](Self::step).
    fn step_fresh(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()>;

    /// Advances `y` and the deviation vectors `w` (row-major, `k x dim`, `k = w.len() / dim`)
    /// by one step `h`, continuing from the previous call of this method.
    ///
    /// # Errors
    /// As [`step`](Self::step); [`Error::DimensionMismatch`] if `w.len()` is not a multiple
    /// of `dim` or exceeds the vectors the flow was built for.
    fn step_tangent(&mut self, t: f64, y: &mut [f64], w: &mut [f64], h: f64) -> Result<()>;
}

fn check_vectors(w: &[f64], dim: usize, max: usize) -> Result<usize> {
    if dim == 0 || !w.len().is_multiple_of(dim) || w.len() / dim > max {
        return Err(Error::DimensionMismatch {
            name: "deviation vectors (k x dim, k at most the flow's)".into(),
            expected: max * dim,
            found: w.len(),
        });
    }
    Ok(w.len() / dim)
}

/// Central-difference Jacobian of `f: R^n -> R^m` at `x` into `jac` (row-major `m x n`),
/// with the step of [`FD_STEP`]. `xp` is a scratch copy of `x`; `fp`, `fm` scratch of
/// length `m`.
///
/// # Errors
/// Whatever `f` reports.
pub fn central_difference<E>(
    mut f: E,
    x: &[f64],
    xp: &mut [f64],
    fp: &mut [f64],
    fm: &mut [f64],
    jac: &mut [f64],
) -> Result<()>
where
    E: FnMut(&[f64], &mut [f64]) -> Result<()>,
{
    let n = x.len();
    let m = fp.len();
    xp.copy_from_slice(x);
    for j in 0..n {
        let h = FD_STEP * x[j].abs().max(1.0);
        xp[j] = x[j] + h;
        f(xp, fp)?;
        xp[j] = x[j] - h;
        f(xp, fm)?;
        xp[j] = x[j];
        // The step actually taken, after rounding of x ± h.
        let inv = 1.0 / ((x[j] + h) - (x[j] - h));
        for i in 0..m {
            jac[i * n + j] = (fp[i] - fm[i]) * inv;
        }
    }
    Ok(())
}

/// Scratch for the central differences of an `n`-component function.
#[derive(Debug, Clone)]
struct FdScratch {
    x: Vec<f64>,
    fp: Vec<f64>,
    fm: Vec<f64>,
}

impl FdScratch {
    fn new(n: usize) -> Self {
        Self {
            x: vec![0.0; n],
            fp: vec![0.0; n],
            fm: vec![0.0; n],
        }
    }
}

/// `dF/dq` of a Hamiltonian system: its own, or central differences of its force.
fn force_jacobian<S: HamiltonianSystem + ?Sized>(
    system: &S,
    q: &[f64],
    t: f64,
    jac: &mut [f64],
    fd: &mut FdScratch,
) -> Result<()> {
    if let Some(r) = system.force_jacobian(q, t, jac) {
        return r;
    }
    let FdScratch { x, fp, fm } = fd;
    central_difference(|x, out| system.force(x, t, out), q, x, fp, fm, jac)
}

/// `df/dy` of a vector field: its own, or central differences.
fn field_jacobian<F: VectorField + ?Sized>(
    field: &F,
    t: f64,
    y: &[f64],
    jac: &mut [f64],
    fd: &mut FdScratch,
) -> Result<()> {
    if let Some(r) = field.jacobian(t, y, jac) {
        return r;
    }
    let FdScratch { x, fp, fm } = fd;
    central_difference(|x, out| field.eval(t, x, out), y, x, fp, fm, jac)
}

/// `out += a * J x` for the row-major `n x n` matrix `J`.
#[inline]
fn add_mat_vec(out: &mut [f64], a: f64, jac: &[f64], x: &[f64]) {
    let n = x.len();
    for (i, o) in out.iter_mut().enumerate() {
        let row = &jac[i * n..(i + 1) * n];
        let dot: f64 = row.iter().zip(x).map(|(r, v)| r * v).sum();
        *o += a * dot;
    }
}

/// `δq += b M⁻¹ δp` (a deviation vector's drift).
#[inline]
fn drift(mass_inv: MassInv<'_>, q: &mut [f64], p: &[f64], b: f64) {
    for (i, (qi, pi)) in q.iter_mut().zip(p).enumerate() {
        *qi += b * mass_inv.get(i) * pi;
    }
}

/// A splitting method on a separable Hamiltonian, with its exact tangent map.
struct SplittingFlow<'a, S: ?Sized, const N: usize> {
    system: &'a S,
    orbit: SplittingStepper<N>,
    fresh: SplittingStepper<N>,
    /// The method's kick and drift weights, the same as the orbit's stepper.
    coefficients: Coefficients<N>,
    ends: [f64; N],
    force: Vec<f64>,
    jac: Vec<f64>,
    /// The compensated sums' corrections of the orbit's `q` and `p` within a step, as in the
    /// orbit's [`SplittingStepper`] (unused by plain steps).
    carry_q: Vec<f64>,
    carry_p: Vec<f64>,
    /// Force and Jacobian belong to the current `q` (first same as last).
    cached: bool,
    fd: FdScratch,
    max_vectors: usize,
}

impl<'a, S: HamiltonianSystem + ?Sized, const N: usize> SplittingFlow<'a, S, N> {
    fn new(system: &'a S, coefficients: Coefficients<N>, max_vectors: usize) -> Self {
        let n = system.ndof();
        // The time at which each drift ends (the force after it is evaluated there).
        let mut ends = [0.0; N];
        let mut elapsed = 0.0;
        for (i, end) in ends.iter_mut().enumerate() {
            elapsed += coefficients.drifts[i];
            *end = if i + 1 == N { 1.0 } else { elapsed };
        }
        Self {
            system,
            orbit: SplittingStepper::new(coefficients, n),
            fresh: SplittingStepper::new(coefficients, n),
            coefficients,
            ends,
            force: vec![0.0; n],
            jac: vec![0.0; n * n],
            carry_q: vec![0.0; n],
            carry_p: vec![0.0; n],
            cached: false,
            fd: FdScratch::new(n),
            max_vectors,
        }
    }

    fn evaluate(&mut self, q: &[f64], t: f64) -> Result<()> {
        self.system.force(q, t, &mut self.force)?;
        force_jacobian(self.system, q, t, &mut self.jac, &mut self.fd)
    }

    /// One kick of weight `a` on the deviations.
    fn kick_vectors(&self, w: &mut [f64], a: f64) {
        let n = self.force.len();
        for v in w.chunks_exact_mut(2 * n) {
            let (dq, dp) = v.split_at_mut(n);
            add_mat_vec(dp, a, &self.jac, dq);
        }
    }
}

impl<S: HamiltonianSystem + ?Sized, const N: usize> Flow for SplittingFlow<'_, S, N> {
    fn dim(&self) -> usize {
        2 * self.system.ndof()
    }

    fn enter(&self, _t: f64, state: &[f64], y: &mut [f64]) -> Result<()> {
        y.copy_from_slice(state);
        Ok(())
    }

    fn leave(&self, _t: f64, y: &[f64], state: &mut [f64]) -> Result<()> {
        state.copy_from_slice(y);
        Ok(())
    }

    fn step(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        let (q, p) = y.split_at_mut(self.system.ndof());
        self.orbit.step(self.system, t, q, p, h)
    }

    fn step_fresh(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        let (q, p) = y.split_at_mut(self.system.ndof());
        self.fresh.invalidate();
        self.fresh.step(self.system, t, q, p, h)
    }

    fn step_tangent(&mut self, t: f64, y: &mut [f64], w: &mut [f64], h: f64) -> Result<()> {
        let n = self.system.ndof();
        check_vectors(w, 2 * n, self.max_vectors)?;
        let (q, p) = y.split_at_mut(n);
        if !self.cached {
            self.evaluate(q, t)?;
        }
        self.cached = false;
        let mass_inv = self.system.mass_inv();
        let c = self.coefficients;
        // The orbit takes exactly the operations of `SplittingStepper::step` (the same
        // compensated kernels in the same order), so it is the orbit of a run without vectors,
        // bit for bit.
        compensated::begin_step::<N>(&mut self.carry_q, &mut self.carry_p);
        for i in 0..N {
            let (a, b) = (c.kicks[i] * h, c.drifts[i] * h);
            self.kick_vectors(w, a);
            let (carry_q, carry_p, force) = (&mut self.carry_q, &mut self.carry_p, &self.force);
            compensated::substep::<N>(i, mass_inv, q, p, carry_q, carry_p, force, a, b);
            for v in w.chunks_exact_mut(2 * n) {
                let (dq, dp) = v.split_at_mut(n);
                drift(mass_inv, dq, dp, b);
            }
            self.evaluate(q, t + self.ends[i] * h)?;
        }
        let a = c.last_kick * h;
        self.kick_vectors(w, a);
        compensated::end_step::<N>(p, &self.carry_p, &self.force, a);
        self.cached = true;
        Ok(())
    }
}

/// The variational equations of a field: `[y, w_1..w_k]' = [f(y), J w_1, .., J w_k]`.
struct Variational<'f, F> {
    field: &'f F,
    k: usize,
    /// The Jacobian and the central differences' scratch (`eval` takes `&self`).
    scratch: &'f RefCell<(Vec<f64>, FdScratch)>,
}

impl<F: VectorField> VectorField for Variational<'_, F> {
    fn dim(&self) -> usize {
        self.field.dim() * (1 + self.k)
    }

    fn eval(&self, t: f64, z: &[f64], dz: &mut [f64]) -> Result<()> {
        let n = self.field.dim();
        let (y, w) = z.split_at(n);
        let (dy, dw) = dz.split_at_mut(n);
        self.field.eval(t, y, dy)?;
        let mut scratch = self.scratch.borrow_mut();
        let (jac, fd) = &mut *scratch;
        field_jacobian(self.field, t, y, jac, fd)?;
        for (v, dv) in w.chunks_exact(n).zip(dw.chunks_exact_mut(n)) {
            dv.fill(0.0);
            add_mat_vec(dv, 1.0, jac, v);
        }
        Ok(())
    }
}

/// How a field flow's working state relates to the system's state.
#[derive(Clone, Copy)]
enum Coordinates<'a> {
    /// The same vector.
    Same,
    /// `[q, p]` for the system's `[q, qdot]`.
    Canonical(&'a dyn LagrangianSystem),
}

/// A method on a vector field, with the variational equations for deviation vectors.
struct FieldFlow<'a, F, St> {
    field: F,
    coordinates: Coordinates<'a>,
    orbit: St,
    fresh: St,
    /// The stepper of the extended state for each number of vectors used (built on first use).
    tangent: Vec<Option<St>>,
    z: Vec<f64>,
    scratch: RefCell<(Vec<f64>, FdScratch)>,
    max_vectors: usize,
}

impl<'a, F: VectorField, St: FieldStepper> FieldFlow<'a, F, St> {
    fn new(field: F, coordinates: Coordinates<'a>, max_vectors: usize) -> Self {
        let n = field.dim();
        Self {
            orbit: St::new(n),
            fresh: St::new(n),
            tangent: (0..=max_vectors).map(|_| None).collect(),
            z: vec![0.0; n * (1 + max_vectors)],
            scratch: RefCell::new((vec![0.0; n * n], FdScratch::new(n))),
            field,
            coordinates,
            max_vectors,
        }
    }
}

impl<F: VectorField, St: FieldStepper> Flow for FieldFlow<'_, F, St> {
    fn dim(&self) -> usize {
        self.field.dim()
    }

    fn enter(&self, t: f64, state: &[f64], y: &mut [f64]) -> Result<()> {
        match self.coordinates {
            Coordinates::Same => y.copy_from_slice(state),
            Coordinates::Canonical(sys) => {
                let n = sys.ndof();
                y[..n].copy_from_slice(&state[..n]);
                sys.momentum(&state[..n], &state[n..], t, &mut y[n..])?;
            }
        }
        Ok(())
    }

    fn leave(&self, t: f64, y: &[f64], state: &mut [f64]) -> Result<()> {
        match self.coordinates {
            Coordinates::Same => state.copy_from_slice(y),
            Coordinates::Canonical(sys) => {
                let n = sys.ndof();
                state[..n].copy_from_slice(&y[..n]);
                sys.velocity(&y[..n], &y[n..], t, &mut state[n..])?;
            }
        }
        Ok(())
    }

    fn step(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        self.orbit.step_field(&self.field, t, y, h)
    }

    fn step_fresh(&mut self, t: f64, y: &mut [f64], h: f64) -> Result<()> {
        // A separate stepper keeps the orbit's history (an implicit method's predictor) intact;
        // what it carries between calls changes only a starting guess.
        self.fresh.step_field(&self.field, t, y, h)
    }

    fn step_tangent(&mut self, t: f64, y: &mut [f64], w: &mut [f64], h: f64) -> Result<()> {
        let n = self.field.dim();
        let k = check_vectors(w, n, self.max_vectors)?;
        let len = n * (1 + k);
        let stepper = self.tangent[k].get_or_insert_with(|| St::new(len));
        let var = Variational {
            field: &self.field,
            k,
            scratch: &self.scratch,
        };
        let z = &mut self.z[..len];
        z[..n].copy_from_slice(y);
        z[n..].copy_from_slice(w);
        stepper.step_field(&var, t, z, h)?;
        y.copy_from_slice(&z[..n]);
        w.copy_from_slice(&z[n..]);
        Ok(())
    }
}

/// The flow of `method` on a Hamiltonian system, for up to `max_vectors` deviation vectors.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for a splitting method on a system it cannot integrate.
pub fn hamiltonian_flow<'a, S: HamiltonianSystem + ?Sized>(
    system: &'a S,
    method: Method,
    max_vectors: usize,
) -> Result<Box<dyn Flow + 'a>> {
    method.dispatch(HamiltonianFlow {
        system,
        max_vectors,
    })
}

/// The flow of `method` on a Lagrangian system: implicit methods on the canonical form
/// `[q, p]` (as `integrate` runs them), explicit ones on `[q, qdot]`.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for a splitting method.
pub fn lagrangian_flow<'a, S: LagrangianSystem + Sized>(
    system: &'a S,
    method: Method,
    max_vectors: usize,
) -> Result<Box<dyn Flow + 'a>> {
    method.dispatch(LagrangianFlow {
        system,
        max_vectors,
    })
}

/// The flow of `method` on a general ODE system.
///
/// # Errors
/// [`Error::UnsupportedMethod`] for a splitting method.
pub fn ode_flow<'a, S: OdeSystem + ?Sized>(
    system: &'a S,
    method: Method,
    max_vectors: usize,
) -> Result<Box<dyn Flow + 'a>> {
    method.dispatch(OdeFlow {
        system,
        max_vectors,
    })
}

/// A field flow, boxed.
fn boxed_field<'a, St: FieldStepper, F: VectorField + 'a>(
    field: F,
    coordinates: Coordinates<'a>,
    max_vectors: usize,
) -> Box<dyn Flow + 'a> {
    Box::new(FieldFlow::<F, St>::new(field, coordinates, max_vectors))
}

/// An adaptive method has no flow here: a section or tangent run steps the orbit on a fixed
/// grid of `dt` (the crossing search re-runs a step of chosen length), while an adaptive
/// method picks its own steps, and its error control would act on the tangent vectors too.
fn no_adaptive(method: Method) -> Error {
    Error::UnsupportedMethod {
        method: method.name().into(),
        reason: "an adaptive method has no fixed-step flow for sections and tangent dynamics; \
                 use rk4, implicit_midpoint or a splitting method"
            .into(),
    }
}

struct HamiltonianFlow<'a, S: ?Sized> {
    system: &'a S,
    max_vectors: usize,
}

impl<'a, S: HamiltonianSystem + ?Sized> Dispatch for HamiltonianFlow<'a, S> {
    type Output = Result<Box<dyn Flow + 'a>>;

    fn splitting<const N: usize>(
        self,
        method: Method,
        coefficients: Coefficients<N>,
    ) -> Self::Output {
        check_system(method, self.system)?;
        Ok(Box::new(SplittingFlow::new(
            self.system,
            coefficients,
            self.max_vectors,
        )))
    }

    fn explicit_rk<St: FieldStepper>(self, _method: Method) -> Self::Output {
        Ok(boxed_field::<St, _>(
            FirstOrder(self.system),
            Coordinates::Same,
            self.max_vectors,
        ))
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        self.explicit_rk::<St>(method)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        Err(no_adaptive(method))
    }
}

struct LagrangianFlow<'a, S> {
    system: &'a S,
    max_vectors: usize,
}

impl<'a, S: LagrangianSystem> Dispatch for LagrangianFlow<'a, S> {
    type Output = Result<Box<dyn Flow + 'a>>;

    fn splitting<const N: usize>(
        self,
        method: Method,
        _coefficients: Coefficients<N>,
    ) -> Self::Output {
        Err(splitting_refused(method, Family::Lagrangian))
    }

    fn explicit_rk<St: FieldStepper>(self, _method: Method) -> Self::Output {
        Ok(boxed_field::<St, _>(
            FirstOrder(self.system),
            Coordinates::Same,
            self.max_vectors,
        ))
    }

    fn implicit_rk<St: FieldStepper>(self, _method: Method) -> Self::Output {
        Ok(boxed_field::<St, _>(
            Canonical(self.system),
            Coordinates::Canonical(self.system),
            self.max_vectors,
        ))
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        Err(no_adaptive(method))
    }
}

struct OdeFlow<'a, S: ?Sized> {
    system: &'a S,
    max_vectors: usize,
}

impl<'a, S: OdeSystem + ?Sized> Dispatch for OdeFlow<'a, S> {
    type Output = Result<Box<dyn Flow + 'a>>;

    fn splitting<const N: usize>(
        self,
        method: Method,
        _coefficients: Coefficients<N>,
    ) -> Self::Output {
        Err(splitting_refused(method, Family::Ode))
    }

    fn explicit_rk<St: FieldStepper>(self, _method: Method) -> Self::Output {
        Ok(boxed_field::<St, _>(
            FirstOrder(self.system),
            Coordinates::Same,
            self.max_vectors,
        ))
    }

    fn implicit_rk<St: FieldStepper>(self, method: Method) -> Self::Output {
        self.explicit_rk::<St>(method)
    }

    fn adaptive<St: AdaptiveStepper>(self, method: Method) -> Self::Output {
        Err(no_adaptive(method))
    }
}
