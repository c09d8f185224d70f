//! Constructors and analysis functions of the built-in systems, one `#[pyfunction]` each.
//!
//! The Python classes call the constructors from `__init__`; all validation happens in the
//! Rust constructors, so a bad parameter raises `ValueError` before any state exists. Methods
//! specific to one system (`lrl_vector`, `positions`, `modal_energies` ...) take the
//! [`NativeSystem`] and downcast it to the concrete type. Each function is a thin shell:
//! numpy in, slices to the core function, numpy out.

use numpy::{PyArray1, PyArray2, PyReadonlyArray1};
use physicskit::classical::analysis;
use physicskit::classical::lagrangian::{Expr, ExprLagrangian, LagrangianModel};
use physicskit::classical::systems::{
    BeadOnRotatingHoop, CoupledOscillators, CoupledOscillatorsParams, DoublePendulum,
    DoublePendulumParams, EulerTop, EulerTopParams, FPUTChain, HarmonicChain, HeavySymmetricTop,
    HenonHeilesSystem, HoopParams, KeplerPerturbations, KeplerSystem, NormalModes, PendulumSwarm,
    ProjectileMotion, SineGordonChain, SymmetricTopParams,
};
use pyo3::prelude::*;

use crate::convert::{array1, to_vec};
use crate::errors::IntoPyResult;
use crate::native::{check_len, NativeSystem};

crate::native_hamiltonian!(KeplerSystem);
crate::native_hamiltonian!(HenonHeilesSystem);
crate::native_hamiltonian!(PendulumSwarm);
crate::native_hamiltonian!(ProjectileMotion);
crate::native_hamiltonian!(HarmonicChain);
crate::native_hamiltonian!(FPUTChain);
crate::native_hamiltonian!(SineGordonChain);
crate::native_lagrangian!(DoublePendulum);
crate::native_lagrangian!(BeadOnRotatingHoop);
crate::native_lagrangian!(CoupledOscillators);
crate::native_lagrangian!(HeavySymmetricTop);
crate::native_lagrangian!(LagrangianModel<ExprLagrangian>);
crate::native_ode!(EulerTop);

type Arr<'a> = PyReadonlyArray1<'a, f64>;
/// Two numpy vectors returned together (`(x, y)`, `(q0, p0)`, `(Q, P)`).
type Pair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

fn wrap<S: crate::native::Native>(s: physicskit::classical::Result<S>) -> PyResult<NativeSystem> {
    Ok(NativeSystem::new(s.py()?))
}

// ---------------------------------------------------------------- Kepler

fn perturbations(eps: f64, c_eps: f64, c_pn: f64, softening: f64) -> KeplerPerturbations {
    KeplerPerturbations::none()
        .with_power_law(eps, c_eps)
        .with_post_newtonian(c_pn)
        .with_softening(softening)
}

/// `KeplerSystem(q0, p0, k, mu, eps, c_eps, c_pn, softening)`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn kepler(
    q0: Arr<'_>,
    p0: Arr<'_>,
    k: f64,
    mu: f64,
    eps: f64,
    c_eps: f64,
    c_pn: f64,
    softening: f64,
) -> PyResult<NativeSystem> {
    let pert = perturbations(eps, c_eps, c_pn, softening);
    wrap(KeplerSystem::new(&to_vec(&q0), &to_vec(&p0), k, mu, pert))
}

/// `KeplerSystem.from_orbital_elements`: start at perihelion of the orbit `(a, e)`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn kepler_from_orbital_elements(
    a: f64,
    e: f64,
    k: f64,
    mu: f64,
    eps: f64,
    c_eps: f64,
    c_pn: f64,
    softening: f64,
) -> PyResult<NativeSystem> {
    let pert = perturbations(eps, c_eps, c_pn, softening);
    wrap(KeplerSystem::from_orbital_elements(a, e, k, mu, pert))
}

fn qp(q: &Arr<'_>, p: &Arr<'_>, n: usize) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let (q, p) = (to_vec(q), to_vec(p));
    check_len("q", &q, n).py()?;
    check_len("p", &p, n).py()?;
    Ok((q, p))
}

/// Out-of-plane angular momentum `x p_y - y p_x`.
#[pyfunction]
pub fn kepler_angular_momentum(sys: &NativeSystem, q: Arr<'_>, p: Arr<'_>) -> PyResult<f64> {
    let s = sys.downcast::<KeplerSystem>()?;
    let (q, p) = qp(&q, &p, 2)?;
    Ok(s.angular_momentum(&q, &p))
}

/// Laplace–Runge–Lenz vector.
#[pyfunction]
pub fn kepler_lrl_vector<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    q: Arr<'_>,
    p: Arr<'_>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let s = sys.downcast::<KeplerSystem>()?;
    let (q, p) = qp(&q, &p, 2)?;
    Ok(array1(py, &s.lrl_vector(&q, &p)))
}

// ---------------------------------------------------------------- Hénon–Heiles, swarm

/// `HenonHeilesSystem(q0, p0)`.
#[pyfunction]
pub fn henon_heiles(q0: Arr<'_>, p0: Arr<'_>) -> PyResult<NativeSystem> {
    wrap(HenonHeilesSystem::new(&to_vec(&q0), &to_vec(&p0)))
}

/// `PendulumSwarm(q0, p0, g_over_l)`.
#[pyfunction]
pub fn pendulum_swarm(q0: Arr<'_>, p0: Arr<'_>, g_over_l: f64) -> PyResult<NativeSystem> {
    wrap(PendulumSwarm::new(&to_vec(&q0), &to_vec(&p0), g_over_l))
}

/// `PendulumSwarm.from_box`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn pendulum_swarm_from_box(
    q_center: f64,
    p_center: f64,
    dq: f64,
    dp: f64,
    n: usize,
    g_over_l: f64,
    seed: u64,
) -> PyResult<NativeSystem> {
    wrap(PendulumSwarm::from_box(
        q_center, p_center, dq, dp, n, g_over_l, seed,
    ))
}

/// Energy of each pendulum of the swarm.
#[pyfunction]
pub fn swarm_per_particle_energy<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    q: Arr<'_>,
    p: Arr<'_>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let s = sys.downcast::<PendulumSwarm>()?;
    let e = s.per_particle_energy(&to_vec(&q), &to_vec(&p)).py()?;
    Ok(array1(py, &e))
}

/// Convex-hull area of the swarm's `(q, p)` points.
#[pyfunction]
pub fn swarm_phase_space_area(sys: &NativeSystem, q: Arr<'_>, p: Arr<'_>) -> PyResult<f64> {
    let s = sys.downcast::<PendulumSwarm>()?;
    s.phase_space_area(&to_vec(&q), &to_vec(&p)).py()
}

// ---------------------------------------------------------------- projectile

/// `ProjectileMotion(q0, p0, m, g, drag_coeff)`.
#[pyfunction]
pub fn projectile(
    q0: Arr<'_>,
    p0: Arr<'_>,
    m: f64,
    g: f64,
    drag_coeff: f64,
) -> PyResult<NativeSystem> {
    wrap(ProjectileMotion::new(
        &to_vec(&q0),
        &to_vec(&p0),
        m,
        g,
        drag_coeff,
    ))
}

/// `ProjectileMotion.from_launch`.
#[pyfunction]
pub fn projectile_from_launch(
    speed: f64,
    angle_deg: f64,
    m: f64,
    g: f64,
    drag_coeff: f64,
    height: f64,
) -> PyResult<NativeSystem> {
    wrap(ProjectileMotion::from_launch(
        speed, angle_deg, m, g, drag_coeff, height,
    ))
}

/// Galileo's parabola `(x(t), y(t))`.
#[pyfunction]
pub fn projectile_analytic_trajectory<'py>(
    py: Python<'py>,
    speed: f64,
    angle_deg: f64,
    g: f64,
    t: Arr<'_>,
    height: f64,
) -> PyResult<Pair<'py>> {
    let (x, y) =
        ProjectileMotion::analytic_trajectory(speed, angle_deg, g, &to_vec(&t), height).py()?;
    Ok((PyArray1::from_vec(py, x), PyArray1::from_vec(py, y)))
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

// ---------------------------------------------------------------- chains

/// `HarmonicChain(q0, p0, m, k)`.
#[pyfunction]
pub fn harmonic_chain(q0: Arr<'_>, p0: Arr<'_>, m: f64, k: f64) -> PyResult<NativeSystem> {
    wrap(HarmonicChain::new(&to_vec(&q0), &to_vec(&p0), m, k))
}

/// `FPUTChain(n, m, k, beta, mode, amplitude)`.
#[pyfunction]
pub fn fput_chain(
    n: usize,
    m: f64,
    k: f64,
    beta: f64,
    mode: usize,
    amplitude: f64,
) -> PyResult<NativeSystem> {
    wrap(FPUTChain::new(n, m, k, beta, mode, amplitude))
}

/// `SineGordonChain(n, m, k, q0, p0)`.
#[pyfunction]
#[pyo3(signature = (n, m, k, q0=None, p0=None))]
pub fn sine_gordon_chain(
    n: usize,
    m: f64,
    k: f64,
    q0: Option<Arr<'_>>,
    p0: Option<Arr<'_>>,
) -> PyResult<NativeSystem> {
    let q0 = q0.map(|a| to_vec(&a));
    let p0 = p0.map(|a| to_vec(&a));
    wrap(SineGordonChain::new(n, m, k, q0.as_deref(), p0.as_deref()))
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

fn modes(sys: &NativeSystem) -> PyResult<&dyn NormalModes> {
    let any = sys.inner.as_any();
    if let Some(s) = any.downcast_ref::<HarmonicChain>() {
        return Ok(s);
    }
    if let Some(s) = any.downcast_ref::<FPUTChain>() {
        return Ok(s);
    }
    if let Some(s) = any.downcast_ref::<SineGordonChain>() {
        return Ok(s);
    }
    Err(pyo3::exceptions::PyTypeError::new_err(
        "not a lattice chain",
    ))
}

/// Normal-mode angular frequencies of a chain.
#[pyfunction]
pub fn chain_normal_mode_frequencies<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    Ok(array1(py, modes(sys)?.normal_mode_frequencies()))
}

/// Normal-mode coordinates `(Q, P)` of a chain state.
#[pyfunction]
pub fn chain_normal_mode_coords<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    q: Arr<'_>,
    p: Arr<'_>,
) -> PyResult<Pair<'py>> {
    let (bq, bp) = modes(sys)?
        .normal_mode_coords(&to_vec(&q), &to_vec(&p))
        .py()?;
    Ok((PyArray1::from_vec(py, bq), PyArray1::from_vec(py, bp)))
}

/// Energy in each normal mode of a chain state.
#[pyfunction]
pub fn chain_modal_energies<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    q: Arr<'_>,
    p: Arr<'_>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let e = modes(sys)?.modal_energies(&to_vec(&q), &to_vec(&p)).py()?;
    Ok(PyArray1::from_vec(py, e))
}

// ---------------------------------------------------------------- Lagrangian systems

/// `DoublePendulum(theta0, thetadot0, m1, m2, l1, l2, g)`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn double_pendulum(
    theta0: Arr<'_>,
    thetadot0: Arr<'_>,
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
) -> PyResult<NativeSystem> {
    let params = DoublePendulumParams { m1, m2, l1, l2, g };
    wrap(DoublePendulum::new(
        &to_vec(&theta0),
        &to_vec(&thetadot0),
        params,
    ))
}

/// Cartesian bob positions `(x1, y1, x2, y2)`.
#[pyfunction]
pub fn double_pendulum_positions<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    q: Arr<'_>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let s = sys.downcast::<DoublePendulum>()?;
    Ok(array1(py, &s.positions(Some(&to_vec(&q))).py()?))
}

/// `BeadOnRotatingHoop(theta0, thetadot0, R, omega, g)`.
#[pyfunction]
#[allow(non_snake_case)]
pub fn bead_on_hoop(
    theta0: f64,
    thetadot0: f64,
    R: f64,
    omega: f64,
    g: f64,
) -> PyResult<NativeSystem> {
    wrap(BeadOnRotatingHoop::new(
        theta0,
        thetadot0,
        HoopParams { r: R, omega, g },
    ))
}

/// `CoupledOscillators(q0, qdot0, n, m, k)`.
#[pyfunction]
pub fn coupled_oscillators(
    q0: Arr<'_>,
    qdot0: Arr<'_>,
    n: usize,
    m: f64,
    k: f64,
) -> PyResult<NativeSystem> {
    let params = CoupledOscillatorsParams { n, m, k };
    wrap(CoupledOscillators::new(
        &to_vec(&q0),
        &to_vec(&qdot0),
        params,
    ))
}

/// `HeavySymmetricTop(angles0, angledots0, I1, I3, M, l, g)`.
#[pyfunction]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn heavy_symmetric_top(
    angles0: Arr<'_>,
    angledots0: Arr<'_>,
    I1: f64,
    I3: f64,
    M: f64,
    l: f64,
    g: f64,
) -> PyResult<NativeSystem> {
    let params = SymmetricTopParams {
        i1: I1,
        i3: I3,
        m: M,
        l,
        g,
    };
    wrap(HeavySymmetricTop::new(
        &to_vec(&angles0),
        &to_vec(&angledots0),
        params,
    ))
}

/// Instantaneous `(phidot, thetadot)` of a heavy top state.
#[pyfunction]
pub fn top_precession_nutation_rate(sys: &NativeSystem, state: Arr<'_>) -> PyResult<(f64, f64)> {
    let s = sys.downcast::<HeavySymmetricTop>()?;
    s.precession_nutation_rate(Some(&to_vec(&state))).py()
}

/// A Lagrangian system from a prefix S-expression (see `physicskit::classical::lagrangian::Expr`)
/// with `ndof` coordinates and parameter values `params`, starting at `(q0, qdot0)`.
#[pyfunction]
pub fn expr_lagrangian(
    sexpr: &str,
    ndof: usize,
    params: Arr<'_>,
    q0: Arr<'_>,
    qdot0: Arr<'_>,
) -> PyResult<NativeSystem> {
    let expr = Expr::parse(sexpr).py()?;
    let lagrangian = ExprLagrangian::new(expr, ndof, to_vec(&params)).py()?;
    wrap(LagrangianModel::new(
        lagrangian,
        &to_vec(&q0),
        &to_vec(&qdot0),
    ))
}

/// Parses `sexpr` and checks its variable and parameter indices against `ndof` and `nparams`.
#[pyfunction]
pub fn expr_validate(sexpr: &str, ndof: usize, nparams: usize) -> PyResult<()> {
    Expr::parse(sexpr).py()?.validate(ndof, nparams).py()
}

// ---------------------------------------------------------------- rigid bodies

/// `EulerTop(omega0, I1, I2, I3, quat0)`.
#[pyfunction]
#[allow(non_snake_case)]
#[pyo3(signature = (omega0, I1, I2, I3, quat0=None))]
pub fn euler_top(
    omega0: Arr<'_>,
    I1: f64,
    I2: f64,
    I3: f64,
    quat0: Option<Arr<'_>>,
) -> PyResult<NativeSystem> {
    let quat0 = quat0.map(|a| to_vec(&a));
    let params = EulerTopParams {
        i1: I1,
        i2: I2,
        i3: I3,
    };
    wrap(EulerTop::new(&to_vec(&omega0), params, quat0.as_deref()))
}

/// `|L|^2` of an Euler-top state.
#[pyfunction]
pub fn euler_top_angular_momentum_squared(sys: &NativeSystem, state: Arr<'_>) -> PyResult<f64> {
    let s = sys.downcast::<EulerTop>()?;
    s.angular_momentum_squared(Some(&to_vec(&state))).py()
}

/// Body-to-world rotation matrix of an Euler-top state.
#[pyfunction]
pub fn euler_top_rotation_matrix<'py>(
    py: Python<'py>,
    sys: &NativeSystem,
    state: Arr<'_>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = sys.downcast::<EulerTop>()?;
    let r = s.rotation_matrix(Some(&to_vec(&state))).py()?;
    let a = ndarray::Array2::from_shape_fn((3, 3), |(i, j)| r[i][j]);
    Ok(numpy::IntoPyArray::into_pyarray(a, py))
}

// ---------------------------------------------------------------- analysis functions

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
    theta: Arr<'_>,
    p_phi: f64,
    p_psi: f64,
    I1: f64,
    I3: f64,
    Mgl: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let v = analysis::effective_potential_symmetric_top_many(
        &to_vec(&theta),
        p_phi,
        p_psi,
        I1,
        I3,
        Mgl,
    )
    .py()?;
    Ok(PyArray1::from_vec(py, v))
}

/// Minimum of `V_eff` in `bracket`.
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

/// Registers every constructor and function.
///
/// # Errors
/// Python errors while adding to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    macro_rules! add {
        ($($f:ident),* $(,)?) => { $( m.add_function(wrap_pyfunction!($f, m)?)?; )* };
    }
    add!(
        kepler,
        kepler_from_orbital_elements,
        kepler_angular_momentum,
        kepler_lrl_vector,
        henon_heiles,
        pendulum_swarm,
        pendulum_swarm_from_box,
        swarm_per_particle_energy,
        swarm_phase_space_area,
        projectile,
        projectile_from_launch,
        projectile_analytic_trajectory,
        projectile_range_and_max_height,
        harmonic_chain,
        fput_chain,
        sine_gordon_chain,
        sine_gordon_kink,
        chain_normal_mode_frequencies,
        chain_normal_mode_coords,
        chain_modal_energies,
        double_pendulum,
        double_pendulum_positions,
        bead_on_hoop,
        coupled_oscillators,
        heavy_symmetric_top,
        top_precession_nutation_rate,
        expr_lagrangian,
        expr_validate,
        euler_top,
        euler_top_angular_momentum_squared,
        euler_top_rotation_matrix,
        pendulum_action_angle,
        effective_potential_symmetric_top,
        find_theta_equilibrium,
        nutation_frequency,
        precession_frequency,
    );
    Ok(())
}
