//! Functions that take no system: closed forms and analyses of the built-in systems
//! (pendulum action-angle variables, the heavy top's effective potential, the projectile's
//! vacuum trajectory, Foucault's pendulum, the reduced Euler's disk, a rattleback's spin
//! reversal, sine-Gordon kink initial data). Each is a thin shell: numpy in, slices
//! to the core function, numpy out.

use numpy::PyArray1;
use physicskit::classical::analysis;
use physicskit::classical::model::entry::Value;
use physicskit::classical::systems::{
    eulers_disk_theta_analytic as disk_theta, spin_reversal_time as reversal, FoucaultPendulum,
    ProjectileMotion, SineGordonChain, SPIN_REVERSAL_WINDOW,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::convert::Vector;
use crate::errors::IntoPyResult;
use crate::params;

/// Two numpy vectors returned together (`(x, y)`, `(q0, p0)`).
type Pair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// Galileo's parabola `(x(t), y(t))`.
#[pyfunction]
pub fn projectile_analytic_trajectory<'py>(
    py: Python<'py>,
    speed: f64,
    angle_deg: f64,
    g: f64,
    t: Vector,
    height: f64,
) -> PyResult<Pair<'py>> {
    let (x, y) = ProjectileMotion::analytic_trajectory(speed, angle_deg, g, &t.0, height).py()?;
    Ok((PyArray1::from_vec(py, x), PyArray1::from_vec(py, y)))
}

/// `FoucaultPendulum.analytic_solution`: the exact `(x(t), y(t))` of the pendulum's
/// equations.
#[pyfunction]
pub fn foucault_analytic_solution<'py>(
    py: Python<'py>,
    q0: Vector,
    v0: Vector,
    omega0: f64,
    omega_z: f64,
    t: Vector,
) -> PyResult<Pair<'py>> {
    let (x, y) = FoucaultPendulum::analytic_solution(&q0.0, &v0.0, omega0, omega_z, &t.0).py()?;
    Ok((PyArray1::from_vec(py, x), PyArray1::from_vec(py, y)))
}

/// `eulers_disk_theta_analytic`: the reduced Euler's disk's `theta(t)`.
#[pyfunction]
pub fn eulers_disk_theta_analytic<'py>(
    py: Python<'py>,
    t: Vector,
    theta0: f64,
    decay_rate: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    Ok(PyArray1::from_vec(
        py,
        disk_theta(&t.0, theta0, decay_rate).py()?,
    ))
}

/// The `window` of [`spin_reversal_time`], read by the scalar rules of the catalogue's
/// parameters (`params`): a real number, so a complex number, a bool, a string or an int too
/// large for a float is a ValueError naming `window` rather than pyo3's TypeError or
/// OverflowError.
struct Window(f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Window {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match params::scalar("window", &obj, false)? {
            Value::Scalar(x) => Ok(Self(x)),
            other => Err(PyValueError::new_err(format!(
                "`window`: expected a real number, got {other:?}"
            ))),
        }
    }
}

/// `spin_reversal_time`: the first zero of a spin history averaged over `window` (s), or
/// `None`. `t` and `spin` are array-likes of reals (lists too), read as the catalogue's vector
/// parameters are; the core checks lengths, finiteness, spacing and the window.
#[pyfunction]
#[pyo3(signature = (t, spin, window = Window(SPIN_REVERSAL_WINDOW)))]
fn spin_reversal_time(
    t: &Bound<'_, PyAny>,
    spin: &Bound<'_, PyAny>,
    window: Window,
) -> PyResult<Option<f64>> {
    let (Value::Vector(t), Value::Vector(spin)) =
        (params::vector("t", t)?, params::vector("spin", spin)?)
    else {
        return Err(PyValueError::new_err(
            "`t`, `spin`: expected one-dimensional arrays of real numbers",
        ));
    };
    reversal(&t, &spin, window.0).py()
}

/// Vacuum range and maximum height.
#[pyfunction]
pub fn projectile_range_and_max_height(
    speed: f64,
    angle_deg: f64,
    g: f64,
    height: f64,
) -> PyResult<(f64, f64)> {
    ProjectileMotion::range_and_max_height(speed, angle_deg, g, height).py()
}

/// `SineGordonChain.kink`: boosted single-kink initial data `(q0, p0)`.
#[pyfunction]
pub fn sine_gordon_kink<'py>(
    py: Python<'py>,
    n: usize,
    center: f64,
    width: f64,
    velocity: f64,
    polarity: i32,
) -> PyResult<Pair<'py>> {
    let (q, p) = SineGordonChain::kink(n, center, width, velocity, polarity).py()?;
    Ok((PyArray1::from_vec(py, q), PyArray1::from_vec(py, p)))
}

/// Action and period of a librating pendulum orbit of energy `E`.
#[pyfunction]
#[allow(non_snake_case)]
pub fn pendulum_action_angle(E: f64, g_over_l: f64) -> PyResult<(f64, f64)> {
    analysis::pendulum_action_angle(E, g_over_l).py()
}

/// `V_eff(theta)` of the heavy symmetric top at each angle.
#[pyfunction]
#[allow(non_snake_case)]
pub fn effective_potential_symmetric_top<'py>(
    py: Python<'py>,
    theta: Vector,
    p_phi: f64,
    p_psi: f64,
    I1: f64,
    I3: f64,
    Mgl: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let v = analysis::effective_potential_symmetric_top_many(&theta.0, p_phi, p_psi, I1, I3, Mgl)
        .py()?;
    Ok(PyArray1::from_vec(py, v))
}

/// Minimum of `V_eff` in `bracket`: the root of its analytic slope, to a few ulps.
#[pyfunction]
#[allow(non_snake_case)]
pub fn find_theta_equilibrium(
    p_phi: f64,
    p_psi: f64,
    I1: f64,
    I3: f64,
    Mgl: f64,
    bracket: (f64, f64),
) -> PyResult<f64> {
    analysis::find_theta_equilibrium(p_phi, p_psi, I1, I3, Mgl, bracket).py()
}

/// Small-oscillation nutation frequency about `theta_eq`.
#[pyfunction]
#[allow(non_snake_case, clippy::too_many_arguments)]
#[pyo3(signature = (p_phi, p_psi, I1, I3, Mgl, theta_eq, dtheta))]
pub fn nutation_frequency(
    p_phi: f64,
    p_psi: f64,
    I1: f64,
    I3: f64,
    Mgl: f64,
    theta_eq: Option<f64>,
    dtheta: f64,
) -> PyResult<f64> {
    analysis::nutation_frequency(p_phi, p_psi, I1, I3, Mgl, theta_eq, dtheta).py()
}

/// Steady-precession rate at `theta_eq`.
#[pyfunction]
#[allow(non_snake_case)]
pub fn precession_frequency(p_phi: f64, p_psi: f64, I1: f64, theta_eq: f64) -> PyResult<f64> {
    analysis::precession_frequency(p_phi, p_psi, I1, theta_eq).py()
}

/// Registers every function.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    macro_rules! add {
        ($($f:ident),* $(,)?) => { $( m.add_function(wrap_pyfunction!($f, m)?)?; )* };
    }
    add!(
        projectile_analytic_trajectory,
        projectile_range_and_max_height,
        foucault_analytic_solution,
        eulers_disk_theta_analytic,
        spin_reversal_time,
        sine_gordon_kink,
        pendulum_action_angle,
        effective_potential_symmetric_top,
        find_theta_equilibrium,
        nutation_frequency,
        precession_frequency,
    );
    Ok(())
}
