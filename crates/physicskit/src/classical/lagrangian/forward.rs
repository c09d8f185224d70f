//! Jacobians of closed-form equations of motion by forward-mode automatic differentiation
//! (num-dual), from the same source as their `f64` values.
//!
//! A built-in Lagrangian system writes its acceleration `qddot(q, qdot)` and its canonical
//! field `[qdot(q, p), dL/dq(q, qdot(q, p))]` once, generic over a [`FieldScalar`]
//! ([`Lagrangian::closed_acceleration_in`](super::Lagrangian::closed_acceleration_in),
//! [`Lagrangian::closed_canonical_in`](super::Lagrangian::closed_canonical_in)). At `f64` that
//! code is the integrators' right-hand side; on num-dual's first-order dual vector
//! `DualSVec64<M>`, seeded with the unit vectors `e_j` of the `M = 2 n` state components,
//!
//! ```text
//! x_j = x_j + e_j   =>   f_i(x) = f_i(x) + sum_j (df_i/dx_j) e_j
//! ```
//!
//! one evaluation carries the whole Jacobian `df/dx` in its derivative parts, exact to
//! rounding (forward mode: Griewank & Walther, *Evaluating Derivatives*, 2nd ed. (2008),
//! ch. 3). [`forward_jacobian`] is that seeding and read-out, written once.
//!
//! # Why a scalar trait of our own
//!
//! The closed forms take sines and cosines from the crate's branch-free kernels
//! (`core::trig`), not libm, and their `f64` trajectories are pinned bit for bit
//! (`tests/classical/digests.rs`). [`FieldScalar`] supplies those kernels for `f64`, and for a
//! dual number the chain rule on them: `sin(x + d) = sin x + cos x d`, `cos(x + d) = cos x -
//! sin x d` with the value parts from the same kernel. Everything else is num-dual's
//! arithmetic, which at `f64` is plain IEEE arithmetic, so the generic code performs the same
//! operations in the same order as the hand-written `f64` code it replaced.
//!
//! # Cost
//!
//! One evaluation of the field on `M`-component duals: each operation costs about `M + 1`
//! times its `f64` version (num-dual keeps the derivative part in an `Option` of an nalgebra
//! vector, so a constant costs nothing). Central differences cost `2 M` evaluations and are
//! accurate to about `4e-11` (`integrators/tangent.rs`); instruction counts in
//! `benchmarks/README.md` ("Tangent dynamics of the Lagrangian systems").

use num_dual::DualSVec64;

use super::engine::Scalar;
use crate::classical::core::trig::{sin_cos, sin_cos_array};
use crate::classical::core::{Phase, Result};
use crate::classical::integrators::{DynamicalSystem, LagrangianSystem, Method};
use crate::classical::model::Capabilities;

/// The number types the generic closed forms are evaluated on: `f64` for the integrators and
/// num-dual's `DualSVec64<M>` for their Jacobians. Sine and cosine go through the crate's
/// kernels ([`sin_cos`], [`sin_cos_array`]), so the `f64` values keep their bits (module
/// documentation); everything else is [`DualNum`](num_dual::DualNum) arithmetic.
pub trait FieldScalar: Scalar {
    /// `(sin x, cos x)`, the value parts from [`sin_cos`].
    fn sin_cos_kernel(self) -> (Self, Self);

    /// `(sin, cos)` of `N` arguments, the value parts from [`sin_cos_array`].
    fn sin_cos_kernel_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]);
}

impl FieldScalar for f64 {
    #[inline(always)]
    fn sin_cos_kernel(self) -> (f64, f64) {
        sin_cos(self)
    }

    #[inline(always)]
    fn sin_cos_kernel_array<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
        sin_cos_array(x)
    }
}

impl<const M: usize> FieldScalar for DualSVec64<M> {
    #[inline(always)]
    fn sin_cos_kernel(self) -> (Self, Self) {
        let (s, c) = sin_cos(self.re);
        (
            DualSVec64::new(s, self.eps * c),
            DualSVec64::new(c, self.eps * -s),
        )
    }

    #[inline(always)]
    fn sin_cos_kernel_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        let (s, c) = sin_cos_array(x.map(|xi| xi.re));
        let mut sin = x;
        let mut cos = x;
        for i in 0..N {
            sin[i] = DualSVec64::new(s[i], x[i].eps * c[i]);
            cos[i] = DualSVec64::new(c[i], x[i].eps * -s[i]);
        }
        (sin, cos)
    }
}

/// The Jacobian `df/dx` (row-major `M x M`) at `x` (length `M`) into `out`, from one
/// evaluation of `f` on dual vectors seeded with the unit vectors: `f(x, y)` writes `f(x)`
/// into `y` and returns `None` if it has no generic form (then `out` is untouched and the
/// answer is `None`), else `Some` of its result. No allocation: the duals live on the stack.
///
/// # Example
/// ```
/// use physicskit::classical::lagrangian::forward_jacobian;
///
/// // f(x) = (x0 x1, x0 + 3 x1): df/dx = [[x1, x0], [1, 3]].
/// let mut jac = [0.0; 4];
/// forward_jacobian::<2>(&[2.0, 5.0], &mut jac, |x, y| {
///     y[0] = x[0] * x[1];
///     y[1] = x[0] + x[1] * 3.0;
///     Some(Ok(()))
/// })
/// .unwrap()
/// .unwrap();
/// assert_eq!(jac, [5.0, 2.0, 1.0, 3.0]);
/// ```
#[inline]
pub fn forward_jacobian<const M: usize>(
    x: &[f64],
    out: &mut [f64],
    f: impl FnOnce(&[DualSVec64<M>], &mut [DualSVec64<M>]) -> Option<Result<()>>,
) -> Option<Result<()>> {
    debug_assert!(x.len() == M && out.len() == M * M);
    let mut z = [DualSVec64::<M>::from_re(0.0); M];
    for (j, (zj, &xj)) in z.iter_mut().zip(x).enumerate() {
        *zj = DualSVec64::from_re(xj).derivative(j);
    }
    let mut y = [DualSVec64::<M>::from_re(0.0); M];
    if let Err(e) = f(&z, &mut y)? {
        return Some(Err(e));
    }
    for (row, yi) in out.chunks_exact_mut(M).zip(&y) {
        match &yi.eps.0 {
            Some(d) => row.iter_mut().enumerate().for_each(|(j, o)| *o = d[j]),
            // A component that does not depend on the state (a cyclic momentum's zero rate).
            None => row.fill(0.0),
        }
    }
    Some(Ok(()))
}

/// A Lagrangian system with its Jacobians hidden (`jacobian` and `canonical_jacobian` are
/// `None`), everything else delegated: its tangent dynamics then take the central differences
/// of `integrators/tangent.rs`, and the implicit solvers have no Newton fallback. The
/// comparison point for the automatic-differentiation Jacobians (tests, benchmarks), as
/// [`AutoDiff`](super::AutoDiff) is for the closed forms.
///
/// # Example
/// ```
/// use physicskit::classical::lagrangian::CentralDifferences;
/// use physicskit::classical::systems::{BeadOnRotatingHoop, HoopParams};
/// use physicskit::classical::DynamicalSystem;
///
/// let hoop = BeadOnRotatingHoop::new(0.3, 0.0, HoopParams::default()).unwrap();
/// let mut jac = [0.0; 4];
/// assert!(hoop.jacobian(0.0, &[0.3, 0.0], &mut jac).is_some());
/// assert!(CentralDifferences(hoop).jacobian(0.0, &[0.3, 0.0], &mut jac).is_none());
/// ```
#[derive(Debug, Clone)]
pub struct CentralDifferences<S>(pub S);

impl<S: LagrangianSystem> DynamicalSystem for CentralDifferences<S> {
    fn phase(&self) -> &Phase {
        self.0.phase()
    }
    fn phase_mut(&mut self) -> &mut Phase {
        self.0.phase_mut()
    }
    fn derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        self.0.derivatives(t, state, out)
    }
    fn energy(&self, state: &[f64]) -> f64 {
        self.0.energy(state)
    }
    fn default_method(&self) -> Method {
        self.0.default_method()
    }
}

impl<S: LagrangianSystem> LagrangianSystem for CentralDifferences<S> {
    fn ndof(&self) -> usize {
        self.0.ndof()
    }
    fn acceleration(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        self.0.acceleration(q, qdot, t, out)
    }
    fn momentum(&self, q: &[f64], qdot: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        self.0.momentum(q, qdot, t, out)
    }
    fn velocity(&self, q: &[f64], p: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        self.0.velocity(q, p, t, out)
    }
    fn canonical_derivatives(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<()> {
        self.0.canonical_derivatives(t, state, out)
    }
}

/// No capabilities: the wrapper is for comparing Jacobians.
impl<S> Capabilities for CentralDifferences<S> {}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::DualStruct;

    /// The dual kernel's value parts are the `f64` kernel's, bit for bit, and its derivative
    /// parts are `cos` and `-sin` times the seed.
    #[test]
    fn dual_kernel_values_are_the_f64_kernel() {
        for x in [0.3, -2.0, 1e3, 3e6] {
            let d = DualSVec64::<2>::from_re(x).derivative(1);
            let (s, c) = d.sin_cos_kernel();
            let (s0, c0) = x.sin_cos_kernel();
            assert_eq!(
                (s.re().to_bits(), c.re().to_bits()),
                (s0.to_bits(), c0.to_bits())
            );
            let (ds, dc) = (s.eps.0.unwrap(), c.eps.0.unwrap());
            assert_eq!((ds[0], ds[1], dc[0], dc[1]), (0.0, c0, 0.0, -s0));
            let ([sa], [ca]) = DualSVec64::<2>::sin_cos_kernel_array([d]);
            assert_eq!(
                (sa.re().to_bits(), ca.re().to_bits()),
                (s0.to_bits(), c0.to_bits())
            );
        }
    }
}
