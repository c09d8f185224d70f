//! [`SimulationResult`]: the output of `integrate`, and the recorder that fills it.

use std::collections::BTreeMap;

use ndarray::{s, Array1, Array2, ArrayD, ArrayView2};

use super::error::Result;
use super::memory::{check_fits, zeroed};

/// One named extra diagnostic of a [`SimulationResult`].
#[derive(Debug, Clone, PartialEq)]
pub enum ExtraValue {
    /// A number (an iteration count, a residual, a step size).
    Scalar(f64),
    /// An array (a per-sample diagnostic).
    Array(ArrayD<f64>),
}

/// The trajectory and diagnostics of one `integrate` call.
///
/// Every array is a contiguous row-major (C-order) `ndarray`, so the Python bindings hand them
/// to numpy without copying. With the default sampling there are `n_steps + 1` samples.
///
/// The states are stored once, in `y`; [`q`](Self::q) and [`p`](Self::p) are views of its two
/// halves (no copy: storing them as arrays as well doubled the memory a run writes, and for a
/// 2-dof system cost more per step than the step itself).
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationResult {
    /// Sample times, shape `(n_samples,)`.
    pub t: Array1<f64>,
    /// Raw stacked states, shape `(n_samples, state_dim)`: `[q, p]` for Hamiltonian systems,
    /// `[q, qdot]` for Lagrangian systems, the system's own layout for ODE systems.
    pub y: Array2<f64>,
    /// Degrees of freedom when `y` stacks `[q, p]` (Hamiltonian) or `[q, qdot]` (Lagrangian)
    /// halves; `None` for general ODE systems, whose state has no such split.
    pub ndof: Option<usize>,
    /// Total energy at each sample, shape `(n_samples,)`; `None` if it was not requested.
    pub energy: Option<Array1<f64>>,
    /// Spec name of the integrator used, e.g. `"yoshida4"`.
    pub method: String,
    /// Named extra diagnostics (solver iterations, force evaluations, ...).
    pub extra: BTreeMap<String, ExtraValue>,
}

impl SimulationResult {
    /// Number of stored samples.
    pub fn n_samples(&self) -> usize {
        self.t.len()
    }

    /// Generalized positions, shape `(n_samples, ndof)`: a view of the first `ndof` columns of
    /// `y`; `None` for general ODE systems.
    pub fn q(&self) -> Option<ArrayView2<'_, f64>> {
        self.ndof.map(|n| self.y.slice(s![.., ..n]))
    }

    /// Canonical momenta (Hamiltonian systems) or velocities `qdot` (Lagrangian systems), shape
    /// `(n_samples, ndof)`: a view of columns `ndof..2 ndof` of `y`; `None` for general ODE
    /// systems.
    pub fn p(&self) -> Option<ArrayView2<'_, f64>> {
        self.ndof.map(|n| self.y.slice(s![.., n..2 * n]))
    }

    /// Largest relative energy error `max_i |E_i - E_0| / |E_0|` (absolute if `E_0 = 0`);
    /// `None` without an energy diagnostic.
    pub fn max_relative_energy_error(&self) -> Option<f64> {
        let e = self.energy.as_ref()?;
        let e0 = *e.first()?;
        let scale = if e0 == 0.0 { 1.0 } else { e0.abs() };
        Some(
            e.iter()
                .fold(0.0_f64, |m, &v| m.max((v - e0).abs() / scale)),
        )
    }

    /// The last stored state.
    pub fn final_state(&self) -> ndarray::ArrayView1<'_, f64> {
        self.y.row(self.y.nrows() - 1)
    }

    /// A scalar extra diagnostic by name.
    pub fn extra_scalar(&self, name: &str) -> Option<f64> {
        match self.extra.get(name)? {
            ExtraValue::Scalar(v) => Some(*v),
            ExtraValue::Array(_) => None,
        }
    }
}

/// Writes samples into storage allocated once, in [`Recorder::new`].
///
/// The arrays are zero-initialized by [`zeroed`] (fresh pages from the OS, advised to be huge
/// pages); `t`, `y` and the energy are filled row by row in place, with no capacity checks.
pub(crate) struct Recorder {
    dim: usize,
    ndof: Option<usize>,
    rows: usize,
    filled: usize,
    t: Vec<f64>,
    y: Vec<f64>,
    energy: Option<Vec<f64>>,
}

/// `dst = src` for the short rows of small systems without a `memcpy` call: the common
/// state sizes get a fixed-length element loop the compiler turns into a few vector moves (a
/// call per sample was a tenth of a 2-dof step).
#[inline(always)]
pub(crate) fn copy_state(dst: &mut [f64], src: &[f64]) {
    debug_assert_eq!(dst.len(), src.len());
    match src.len() {
        2 => copy_fixed::<2>(dst, src),
        4 => copy_fixed::<4>(dst, src),
        6 => copy_fixed::<6>(dst, src),
        _ => dst.copy_from_slice(src),
    }
}

/// An element loop on purpose: with `copy_from_slice` in each arm, LLVM merged the arms back
/// into one variable-length `memcpy` call.
#[inline(always)]
#[allow(clippy::manual_memcpy)]
fn copy_fixed<const N: usize>(dst: &mut [f64], src: &[f64]) {
    if let (Ok(d), Ok(s)) = (<&mut [f64; N]>::try_from(dst), <&[f64; N]>::try_from(src)) {
        for i in 0..N {
            d[i] = s[i];
        }
    }
}

impl Recorder {
    /// Storage for `samples` samples of a `dim`-dimensional state; `ndof` marks each state as
    /// `q` and `p` halves.
    pub(crate) fn new(
        samples: usize,
        dim: usize,
        ndof: Option<usize>,
        with_energy: bool,
    ) -> Result<Self> {
        let per_sample = 1 + dim + usize::from(with_energy);
        check_fits(samples, per_sample)?;
        Ok(Self {
            dim,
            ndof,
            rows: samples,
            filled: 0,
            t: zeroed(samples),
            y: zeroed(samples * dim),
            energy: with_energy.then(|| zeroed(samples)),
        })
    }

    /// Stores one sample: the state `state` at time `t` with energy `energy` (ignored when
    /// energies are not stored).
    #[inline(always)]
    pub(crate) fn push(&mut self, t: f64, state: &[f64], energy: f64) {
        let r = self.filled;
        debug_assert!(r < self.rows);
        let d = self.dim;
        copy_state(&mut self.y[r * d..(r + 1) * d], state);
        self.t[r] = t;
        if let Some(e) = self.energy.as_mut() {
            e[r] = energy;
        }
        self.filled = r + 1;
    }

    /// Stores one sample whose stored form differs from the working state: `fill(row)` writes
    /// it into the next row of `y` and returns its energy.
    #[inline]
    pub(crate) fn push_with(
        &mut self,
        t: f64,
        fill: impl FnOnce(&mut [f64]) -> Result<f64>,
    ) -> Result<()> {
        let r = self.filled;
        debug_assert!(r < self.rows);
        let d = self.dim;
        let energy = fill(&mut self.y[r * d..(r + 1) * d])?;
        self.t[r] = t;
        if let Some(e) = self.energy.as_mut() {
            e[r] = energy;
        }
        self.filled = r + 1;
        Ok(())
    }

    /// Whether energies are stored.
    #[inline(always)]
    pub(crate) fn stores_energy(&self) -> bool {
        self.energy.is_some()
    }

    /// Time of the first stored sample whose state holds NaN or infinity.
    pub(crate) fn first_non_finite(&self) -> Option<f64> {
        (0..self.filled)
            .find(|&r| {
                !self.y[r * self.dim..(r + 1) * self.dim]
                    .iter()
                    .all(|v| v.is_finite())
            })
            .map(|r| self.t[r])
    }

    /// The last stored row of `y`.
    pub(crate) fn last_row(&self) -> &[f64] {
        let r = self.filled - 1;
        &self.y[r * self.dim..(r + 1) * self.dim]
    }

    pub(crate) fn finish(
        self,
        method: &str,
        extra: BTreeMap<String, ExtraValue>,
    ) -> SimulationResult {
        debug_assert_eq!(self.filled, self.rows);
        let y = Array2::from_shape_vec((self.filled, self.dim), self.y)
            .expect("recorder stores whole rows");
        SimulationResult {
            t: Array1::from(self.t),
            y,
            ndof: self.ndof,
            energy: self.energy.map(Array1::from),
            method: method.to_string(),
            extra,
        }
    }
}
