//! `rk4`: the classical fourth-order Runge–Kutta method.
//!
//! ```text
//! k1 = f(t, y)            k2 = f(t + h/2, y + h k1/2)
//! k3 = f(t + h/2, y + h k2/2)   k4 = f(t + h, y + h k3)
//! y1 = y + h (k1 + 2 k2 + 2 k3 + k4) / 6
//! ```
//!
//! W. Kutta (1901). Order 4, four evaluations per step, not symplectic: on conservative
//! systems the energy error grows linearly in time.

use std::collections::BTreeMap;

use super::field::VectorField;
use super::stepper::{FieldStepper, Report};
use crate::classical::core::method::{MethodInfo, Scheme};
use crate::classical::core::{ExtraValue, Result};

/// The facts about `rk4`.
pub const INFO: MethodInfo = MethodInfo {
    name: "rk4",
    label: "RK4",
    summary: "classical fourth-order Runge–Kutta; energy drifts",
    order: 4,
    symplectic: false,
    separable_only: false,
    evaluations_per_step: 4,
    evaluations: "right-hand-side evaluations, exact",
    reference: "W. Kutta, Z. Math. Phys. 46 (1901) 435–453",
    scheme: Scheme::ExplicitRk,
};

/// Work buffers of the classical Runge–Kutta method, allocated once.
#[derive(Debug, Clone)]
pub struct Rk4 {
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    tmp: Vec<f64>,
    evaluations: u64,
}

impl Rk4 {
    /// Buffers for a `dim`-dimensional state.
    pub fn new(dim: usize) -> Self {
        Self {
            k1: vec![0.0; dim],
            k2: vec![0.0; dim],
            k3: vec![0.0; dim],
            k4: vec![0.0; dim],
            tmp: vec![0.0; dim],
            evaluations: 0,
        }
    }

    /// Right-hand-side evaluations so far.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Advances `y` from `t` to `t + h`.
    ///
    /// # Errors
    /// Whatever the field's evaluation returns.
    #[inline]
    pub fn step<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        let half = 0.5 * h;
        f.eval(t, y, &mut self.k1)?;
        axpy(&mut self.tmp, y, half, &self.k1);
        f.eval(t + half, &self.tmp, &mut self.k2)?;
        axpy(&mut self.tmp, y, half, &self.k2);
        f.eval(t + half, &self.tmp, &mut self.k3)?;
        axpy(&mut self.tmp, y, h, &self.k3);
        f.eval(t + h, &self.tmp, &mut self.k4)?;
        self.evaluations += 4;
        let sixth = h / 6.0;
        combine(y, sixth, &self.k1, &self.k2, &self.k3, &self.k4);
        Ok(())
    }
}

impl FieldStepper for Rk4 {
    fn new(dim: usize) -> Self {
        Rk4::new(dim)
    }

    #[inline(always)]
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.step(f, t, y, h)
    }
}

impl Report for Rk4 {
    /// `rhs_evaluations`.
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        extra.insert(
            "rhs_evaluations".into(),
            ExtraValue::Scalar(self.evaluations as f64),
        );
    }
}

/// `out = y + a x`.
///
/// On x86-64 in explicit SSE2 pairs: the field evaluation that follows reads the state back
/// in 16-byte pairs, and a 16-byte load of two 8-byte stores is not forwarded but stalls (the
/// compiler chooses scalar stores once the stepper is inlined into the generic loop; the
/// measured cost is in `benchmarks/README.md`). Each lane computes `y + a x` exactly as the
/// scalar code does, so results are bit-identical.
#[inline(always)]
#[allow(unsafe_code)]
pub(crate) fn axpy(out: &mut [f64], y: &[f64], a: f64, x: &[f64]) {
    let n = out.len();
    let (y, x) = (&y[..n], &x[..n]);
    // Advanced by the SSE2 pairs on x86-64 only (elsewhere, e.g. the lab's wasm32, it stays 0).
    #[cfg_attr(not(target_arch = "x86_64"), allow(unused_mut))]
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_add_pd, _mm_loadu_pd, _mm_mul_pd, _mm_set1_pd, _mm_storeu_pd};
        while done + 2 <= n {
            // SAFETY: `done + 1 < n` and `out`, `y`, `x` all have `n` elements, so both lanes
            // of each unaligned load and store are in bounds; SSE2 is part of x86-64.
            unsafe {
                let av = _mm_set1_pd(a);
                let xv = _mm_loadu_pd(x.as_ptr().add(done));
                let yv = _mm_loadu_pd(y.as_ptr().add(done));
                _mm_storeu_pd(out.as_mut_ptr().add(done), _mm_add_pd(yv, _mm_mul_pd(av, xv)));
            }
            done += 2;
        }
    }
    for i in done..n {
        out[i] = y[i] + a * x[i];
    }
}

/// `y += sixth (k1 + 2 (k2 + k3) + k4)`, over one length like [`axpy`].
#[inline(always)]
fn combine(y: &mut [f64], sixth: f64, k1: &[f64], k2: &[f64], k3: &[f64], k4: &[f64]) {
    let n = y.len();
    let (k1, k2, k3, k4) = (&k1[..n], &k2[..n], &k3[..n], &k4[..n]);
    for i in 0..n {
        y[i] += sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    }
}
