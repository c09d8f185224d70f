//! [`SimulationResult`]: the output of `integrate`, and the recorder that fills it.

use std::collections::BTreeMap;

use ndarray::{s, Array1, Array2, ArrayD, ArrayView2};

use super::error::Result;
use super::memory::{check_fits, storage};

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
        let error = EnergyError::new(*e.first()?);
        Some(e.iter().fold(0.0_f64, |m, &v| m.max(error.of(v))))
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

/// The relative energy error against a starting energy `E_0`: `|E - E_0| / |E_0|`, or
/// `|E - E_0|` where `E_0 = 0` (no scale to divide by). Written once for
/// [`SimulationResult::max_relative_energy_error`] and the ensembles' stepwise reduction,
/// which must agree bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EnergyError {
    e0: f64,
    scale: f64,
}

impl EnergyError {
    /// The error against `e0`.
    pub(crate) fn new(e0: f64) -> Self {
        let scale = if e0 == 0.0 { 1.0 } else { e0.abs() };
        Self { e0, scale }
    }

    /// The error of `e`.
    #[inline]
    pub(crate) fn of(self, e: f64) -> f64 {
        (e - self.e0).abs() / self.scale
    }
}

/// Writes samples into storage allocated once, in [`Recorder::new`].
///
/// The vectors are reserved up front (by [`storage`]: never zeroed, faulted in with one
/// system call) and appended to, row by row; they never reallocate.
pub(crate) struct Recorder {
    dim: usize,
    ndof: Option<usize>,
    rows: usize,
    t: Vec<f64>,
    y: Vec<f64>,
    energy: Option<Vec<f64>>,
}

/// Appends `src` to `dst`, without a `memcpy` call for the short rows of small systems: the
/// common state sizes get a fixed-length append the compiler turns into a few vector moves (a
/// call per sample was a tenth of a 2-dof step).
#[inline(always)]
fn append_state(dst: &mut Vec<f64>, src: &[f64]) {
    #[inline(always)]
    fn fixed<const N: usize>(dst: &mut Vec<f64>, src: &[f64]) {
        if let Ok(s) = <&[f64; N]>::try_from(src) {
            dst.extend_from_slice(s);
        }
    }
    match src.len() {
        2 => fixed::<2>(dst, src),
        4 => fixed::<4>(dst, src),
        6 => fixed::<6>(dst, src),
        _ => dst.extend_from_slice(src),
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
            t: storage(samples)?,
            y: storage(samples * dim)?,
            energy: with_energy.then(|| storage(samples)).transpose()?,
        })
    }

    /// Whether energies are stored.
    #[inline(always)]
    pub(crate) fn stores_energy(&self) -> bool {
        self.energy.is_some()
    }

    /// Stores one sample: the state `state` at time `t` with energy `energy` (ignored when
    /// energies are not stored).
    #[inline(always)]
    pub(crate) fn push(&mut self, t: f64, state: &[f64], energy: f64) {
        debug_assert!(self.t.len() < self.rows && state.len() == self.dim);
        append_state(&mut self.y, state);
        self.t.push(t);
        if let Some(e) = self.energy.as_mut() {
            e.push(energy);
        }
    }

    /// Stores one sample whose stored form differs from the working state: `fill(row)` writes
    /// it into the next row of `y` and returns its energy, which is returned too. On an error
    /// the recorder is left with a partial row: the run is abandoned and the recorder dropped.
    #[inline]
    pub(crate) fn push_with(
        &mut self,
        t: f64,
        fill: impl FnOnce(&mut [f64]) -> Result<f64>,
    ) -> Result<f64> {
        debug_assert!(self.t.len() < self.rows);
        let start = self.y.len();
        self.y.resize(start + self.dim, 0.0);
        let energy = fill(&mut self.y[start..])?;
        self.t.push(t);
        if let Some(e) = self.energy.as_mut() {
            e.push(energy);
        }
        Ok(energy)
    }

    /// Time of the first stored sample whose state holds NaN or infinity.
    pub(crate) fn first_non_finite(&self) -> Option<f64> {
        self.y
            .chunks_exact(self.dim.max(1))
            .position(|row| !row.iter().all(|v| v.is_finite()))
            .map(|r| self.t[r])
    }

    /// The last stored row of `y`.
    pub(crate) fn last_row(&self) -> &[f64] {
        &self.y[self.y.len() - self.dim..]
    }

    pub(crate) fn finish(
        self,
        method: &str,
        extra: BTreeMap<String, ExtraValue>,
    ) -> SimulationResult {
        let rows = self.t.len();
        debug_assert_eq!(rows, self.rows);
        let y =
            Array2::from_shape_vec((rows, self.dim), self.y).expect("recorder stores whole rows");
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
