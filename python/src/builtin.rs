//! Constructors of the built-in systems, one `#[pyfunction]` each, returning a
//! [`NativeSystem`]. The Python classes call them from `__init__`; all validation happens in
//! the Rust constructors, so a bad parameter raises `ValueError` before any state exists.

use numpy::PyReadonlyArray1;
use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use pyo3::prelude::*;

use crate::convert::to_vec;
use crate::errors::IntoPyResult;
use crate::native::{check_len, NativeSystem};

crate::native_hamiltonian!(Pendulum);
crate::native_hamiltonian!(HarmonicOscillator);

fn scalar(name: &str, v: &PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
    let v = to_vec(v);
    check_len(name, &v, 1).py()?;
    Ok(v[0])
}

/// The simple pendulum `H = p^2/2 - (g/l) cos q` (a reference system of the core).
#[pyfunction]
#[pyo3(signature = (q0, p0, g_over_l=1.0))]
pub fn pendulum(
    q0: PyReadonlyArray1<'_, f64>,
    p0: PyReadonlyArray1<'_, f64>,
    g_over_l: f64,
) -> PyResult<NativeSystem> {
    let s = Pendulum::new(scalar("q0", &q0)?, scalar("p0", &p0)?, g_over_l).py()?;
    Ok(NativeSystem::new(s))
}

/// The harmonic oscillator `H = p^2/(2m) + k q^2/2` (a reference system of the core).
#[pyfunction]
#[pyo3(signature = (q0, p0, m=1.0, k=1.0))]
pub fn harmonic_oscillator(
    q0: PyReadonlyArray1<'_, f64>,
    p0: PyReadonlyArray1<'_, f64>,
    m: f64,
    k: f64,
) -> PyResult<NativeSystem> {
    let s = HarmonicOscillator::new(scalar("q0", &q0)?, scalar("p0", &p0)?, m, k).py()?;
    Ok(NativeSystem::new(s))
}

/// Registers the constructors.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pendulum, m)?)?;
    m.add_function(wrap_pyfunction!(harmonic_oscillator, m)?)?;
    Ok(())
}
