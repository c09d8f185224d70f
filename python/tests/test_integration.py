"""Every system integrates with its default method through Python, meets the conservation
acceptance bars of the Hamiltonian and Lagrangian systems, and returns arrays of the
documented dtype, shape and layout."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import physicskit.classical as pc

from conftest import make_systems
from spec_table import CLASSES

def spec_default(system):
    """The spec's default method: ``integrate(..., method='implicit_midpoint')`` on
    LagrangianSystem and ODESystem, ``'yoshida4'`` on HamiltonianSystem."""
    if isinstance(system, (pc.LagrangianSystem, pc.ODESystem)):
        return "implicit_midpoint"
    return "yoshida4"


def rel_drift(e):
    return float(np.max(np.abs(e - e[0])) / abs(e[0]))


def test_default_method_and_result_arrays(system_name):
    s = make_systems()[system_name]()
    dt, n = 1e-3, 200
    r = s.integrate((0.0, n * dt), dt)
    cls = system_name.partition(".")[0]
    # The spec's classes default to the spec's method; the others to their catalogue entry's.
    entry = next(e for e in pc.catalog() if e["python"] == system_name)
    assert r.method == (spec_default(s) if cls in CLASSES else entry["default_method"])
    dim = len(s.state)
    arrays = {"t": (n + 1,), "y": (n + 1, dim), "energy": (n + 1,)}
    if entry["family"] == "ode":
        # A first-order system has a state, not coordinates and momenta.
        assert r.q is None and r.p is None
    else:
        arrays["q"] = arrays["p"] = (n + 1, s.ndof)
    for name, shape in arrays.items():
        a = getattr(r, name)
        assert isinstance(a, np.ndarray), name
        assert a.dtype == np.float64 and a.shape == shape, name
        assert a.flags["C_CONTIGUOUS"], name
        assert a.flags["WRITEABLE"], name
    # t_i = t0 + i dt, computed by one multiplication (no accumulated clock): bit-identical
    # to numpy's i * dt for t0 = 0.
    assert np.array_equal(r.t, np.arange(n + 1) * dt)
    assert isinstance(r.extra, dict) and r.extra["n_steps"] == n
    if r.q is not None:
        # q and p are the two halves of y (p = qdot for Lagrangian systems).
        assert np.array_equal(np.hstack([r.q, r.p]), r.y)
    assert np.array_equal(r.y[0], make_systems()[system_name]().state)


def _peer_workloads():
    """The peer-comparison workloads (benchmarks/peer/workloads.py, which reads the one table
    benchmarks/peer/workloads.json): name to (constructor, method, dt)."""
    path = Path(__file__).resolve().parents[2] / "benchmarks" / "peer" / "workloads.py"
    spec = importlib.util.spec_from_file_location("peer_workloads", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module._cases(pc)


# The conservation cases of the Lagrangian and rigid-body acceptance list: the peer's workloads
# that run implicit midpoint (the double pendulum, the hoop, the coupled oscillators and both
# tops), each over 1e5 of its steps.
LAGRANGIAN_BARS = {
    name: (make, dt)
    for name, (make, method, dt) in _peer_workloads().items()
    if method == "implicit_midpoint"
}


def test_the_lagrangian_bars_cover_both_families():
    # The list above is read from the workload table: it must still hold the Lagrangian
    # systems and the rigid bodies of the acceptance list.
    kinds = {type(make()).__name__ for make, _ in LAGRANGIAN_BARS.values()}
    assert kinds == {"DoublePendulum", "BeadOnRotatingHoop", "CoupledOscillators",
                     "HeavySymmetricTop", "EulerTop"}, kinds


@pytest.mark.parametrize("name", sorted(LAGRANGIAN_BARS))
def test_lagrangian_and_rigid_body_energy_bar(name):
    factory, dt = LAGRANGIAN_BARS[name]
    s = factory()
    r = s.integrate((0.0, 1e5 * dt), dt)  # 1e5 implicit_midpoint steps (the case)
    assert r.t.shape == (100_001,)
    # The Lagrangian acceptance bar: relative energy drift below 1e-6 over 1e5 steps.
    assert rel_drift(r.energy) < 1e-6, rel_drift(r.energy)


def test_euler_top_quadratic_invariants():
    s = pc.EulerTop([0.01, 1.0, 0.01])
    l0 = s.angular_momentum_squared()
    r = s.integrate((0.0, 100.0), 1e-3)
    # Implicit midpoint keeps quadratic invariants up to the solver tolerance and rounding
    # accumulated over 1e5 steps: the Lagrangian acceptance bar is 1e-12 relative.
    assert rel_drift(r.energy) < 1e-12
    lf = s.angular_momentum_squared()
    # Quadratic invariants of implicit midpoint: rounding only (~1e-14 over 1e5 steps); the
    # issue's bar is 1e-12.
    assert abs(lf - l0) / l0 < 1e-12
    assert abs(np.linalg.norm(s.quaternion) - 1.0) < 1e-12
    # The intermediate-axis flip of the spec's example happens before t = 100.
    assert np.max(np.abs(r.y[:, 0])) > 0.5
    rm = s.rotation_matrix()
    # R R^T = I to the rounding of a unit quaternion's products (~1e-15); 1e-12 as above.
    assert rm.shape == (3, 3) and np.allclose(rm @ rm.T, np.eye(3), rtol=0, atol=1e-12)


def test_henon_heiles_bar():
    s = pc.HenonHeilesSystem([0.0, 0.3], [0.3, 0.0])
    r = s.integrate((0.0, 500.0), 5e-3)  # 1e5 yoshida4 steps
    assert rel_drift(r.energy) < 1e-9  # the Hamiltonian acceptance bar


def test_fput_bar():
    s = pc.FPUTChain(n=32, beta=0.7, mode=1, amplitude=0.5)
    r = s.integrate((0.0, 5000.0), 0.05)  # 1e5 yoshida4 steps
    assert rel_drift(r.energy) < 1e-6  # the Hamiltonian acceptance bar
    e = s.modal_energies(r.q[0], r.p[0])
    assert e.shape == (32,) and e[0] / e.sum() > 0.999  # all energy starts in mode 1


def test_kepler_energy_and_lrl():
    s = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    a0 = s.lrl_vector()
    l0 = s.angular_momentum()
    # 100 orbits (period 2 pi) at 8000 steps per orbit, dt = 7.9e-4, inside the acceptance bar's
    # dt = 1e-3 (a whole number of steps per orbit, so the LRL vector is compared at perihelion).
    r = s.integrate((0.0, 200 * np.pi), 2 * np.pi / 8000)
    # Symplectic yoshida4, e = 0.5: the energy error stays bounded, ~1e-11 here.
    assert rel_drift(r.energy) < 1e-8
    a1 = s.lrl_vector()
    assert np.linalg.norm(a1 - a0) / np.linalg.norm(a0) < 1e-8  # the Hamiltonian acceptance bar for the LRL vector
    assert abs(s.angular_momentum() - l0) / abs(l0) < 1e-12  # exact for central forces (up to rounding)


def test_projectile_matches_parabola():
    s = pc.ProjectileMotion.from_launch(20.0, 45.0)
    r = s.integrate((0.0, 2.0), 1e-3)
    x, y = pc.ProjectileMotion.analytic_trajectory(20.0, 45.0, 9.81, r.t)
    # Constant force: yoshida4 is exact up to rounding; the acceptance bar is 1e-9.
    assert np.max(np.abs(r.q[:, 0] - x)) < 1e-9 and np.max(np.abs(r.q[:, 1] - y)) < 1e-9
    rng, h = pc.ProjectileMotion.range_and_max_height(20.0, 45.0, 9.81)
    # Closed forms v^2 sin(2a)/g and (v sin a)^2/(2g): a few roundings.
    assert rng == pytest.approx(400.0 / 9.81, rel=1e-14) and h == pytest.approx(100.0 / 9.81, rel=1e-14)


def test_swarm_per_particle_energy_and_area():
    s = pc.PendulumSwarm.from_box(1.0, 0.0, 0.05, 0.05, n=200)
    e0 = s.per_particle_energy()
    a0 = s.phase_space_area()
    s.integrate((0.0, 5.0), 1e-3)
    # yoshida4 at dt 1e-3: energy error ~ (dt w)^4 ~ 1e-12 per pendulum, bounded; 1e-10 margin.
    assert np.max(np.abs(s.per_particle_energy() - e0)) < 1e-10
    assert abs(s.phase_space_area() - a0) / a0 < 0.05  # the acceptance bar: 5%


def test_all_methods_on_a_separable_system():
    for method in ("yoshida4", "verlet", "rk4", "implicit_midpoint"):
        s = pc.HenonHeilesSystem([0.0, 0.3], [0.3, 0.0])
        r = s.integrate((0.0, 10.0), 1e-3, method=method)
        assert r.method == method
        assert rel_drift(r.energy) < 1e-6, method


def test_top_analysis_functions():
    v = pc.effective_potential_symmetric_top(np.array([0.4, 0.5, 0.6]), 1.0, 2.0, 1.0, 0.5, 9.81)
    th = np.array([0.4, 0.5, 0.6])
    expected = (1.0 - 2.0 * np.cos(th)) ** 2 / (2 * np.sin(th) ** 2) + 4.0 / 1.0 + 9.81 * np.cos(th)
    # Same formula, different operation order: a few ulps (atol=0: relative only).
    assert v.shape == (3,) and np.allclose(v, expected, rtol=1e-14, atol=0)
    th_eq = pc.find_theta_equilibrium(3.0, 4.0, 1.0, 0.5, 9.81)
    # A minimum of V_eff: lower than its neighbours 1e-3 away (Brent converges to ~1e-8).
    around = pc.effective_potential_symmetric_top(
        np.array([th_eq - 1e-3, th_eq, th_eq + 1e-3]), 3.0, 4.0, 1.0, 0.5, 9.81)
    assert around[1] < around[0] and around[1] < around[2]
    assert pc.nutation_frequency(3.0, 4.0, 1.0, 0.5, 9.81) > 0
    # Same formula, different operation order: a few ulps.
    assert pc.precession_frequency(3.0, 4.0, 1.0, th_eq) == pytest.approx(
        (3.0 - 4.0 * np.cos(th_eq)) / np.sin(th_eq) ** 2, rel=1e-14)
    J, T = pc.pendulum_action_angle(0.0)
    assert J > 0 and T > 2 * np.pi  # a finite-amplitude pendulum is slower than 2 pi


def test_long_integration_releases_the_gil():
    import threading
    import time

    s = pc.DoublePendulum([2.0, 1.0], [0.5, -0.3])
    done = threading.Event()
    ticks = 0

    def work():
        s.integrate((0.0, 6.0), 3e-5)  # 2e5 steps, ~1 s
        done.set()

    th = threading.Thread(target=work)
    th.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    th.join()
    # Python kept running in the main thread while Rust integrated in the worker.
    assert ticks > 5


def test_ctrl_c_interrupts_integration():
    import os
    import signal
    import threading
    import time

    from conftest import sympy_double_pendulum

    # The expression-tree double pendulum: ~30 us per step and 80 bytes per stored sample, so
    # 1e6 steps are half a minute of work in 80 MB.
    s = sympy_double_pendulum().system([2.0, 1.0], [0.5, -0.3])
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.integrate((0.0, 10.0), 1e-5)
    timer.join()
    assert time.perf_counter() - start < 5.0
    assert s.t == 0.0  # the state is left at its start on interruption
