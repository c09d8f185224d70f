//! [`SimulationResult`]: the output of `integrate`, and the recorder that fills it.

use std::collections::BTreeMap;

use ndarray::{Array1, Array2, ArrayD};

use super::error::{Error, Result};
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

/// Appends samples into preallocated storage; allocates once, in [`Recorder::new`].
pub(crate) struct Recorder {
    dim: usize,
    ndof: Option<usize>,
    t: Vec<f64>,
    y: Vec<f64>,
    q: Vec<f64>,
    p: Vec<f64>,
    energy: Option<Vec<f64>>,
}

fn reserve(len: usize, per_sample: usize) -> Result<Vec<f64>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| Error::TrajectoryTooLarge {
            samples: (len / per_sample.max(1)) as u128,
            values_per_sample: per_sample,
            bytes: len as u128 * 8,
            available: 0,
        })?;
    Ok(v)
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
            t: reserve(samples, per_sample)?,
            y: reserve(samples * dim, per_sample)?,
            q: reserve(samples * n, per_sample)?,
            p: reserve(samples * n, per_sample)?,
            energy: if with_energy {
                Some(reserve(samples, per_sample)?)
            } else {
                None
            },
        })
    }

    pub(crate) fn wants_energy(&self) -> bool {
        self.energy.is_some()
    }

    /// Stores one sample. Capacity was reserved for every sample, so this never allocates.
    pub(crate) fn push(&mut self, t: f64, y: &[f64], energy: f64) {
        debug_assert_eq!(y.len(), self.dim);
        self.t.push(t);
        self.y.extend_from_slice(y);
        if let Some(n) = self.ndof {
            self.q.extend_from_slice(&y[..n]);
            self.p.extend_from_slice(&y[n..2 * n]);
        }
        if let Some(e) = self.energy.as_mut() {
            e.push(energy);
        }
    }

    pub(crate) fn finish(
        self,
        method: &str,
        extra: BTreeMap<String, ExtraValue>,
    ) -> SimulationResult {
        let rows = self.t.len();
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
