"""``dop853`` from Python: against SciPy's DOP853 on a pendulum and on the
projectile with drag, its tolerances ``rtol``/``atol`` (validated, refused for fixed-step
methods), its step budget ``max_steps`` (likewise), its step counts in ``result.extra``, and
its step failure as ``ConvergenceError``.

SciPy is used only here, as an independent implementation of the same method (Hairer's
DOP853, with its own step-size selection): both runs must meet the tolerance, so they agree to
within their global errors, not bit for bit.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import physicskit.classical as pc
from physicskit.classical import ConvergenceError

RTOL, ATOL = 1e-10, 1e-12


class Pendulum(pc.HamiltonianSystem):
    """``H = p^2/2 - cos q``, written in Python (the run calls back into it)."""

    def kinetic_energy(self, p):
        return 0.5 * float(p @ p)

    def potential_energy(self, q):
        return float(-np.cos(q[0]))

    def force(self, q, t=0.0):
        return -np.sin(q)


def scipy_run(system, t, y0, rtol, atol):
    """SciPy's DOP853 on the system's own right-hand side, sampled at ``t``."""
    sol = solve_ivp(lambda tt, y: system.derivatives(tt, y), (t[0], t[-1]), y0,
                    method="DOP853", rtol=rtol, atol=atol, t_eval=t)
    assert sol.success, sol.message
    return sol.y.T


def test_pendulum_matches_scipy_dop853_to_the_tolerance():
    y0 = np.array([2.0, 0.0])
    ours = Pendulum([2.0], [0.0]).integrate_sampled((0.0, 10.0), 0.1, "dop853",
                                                    rtol=RTOL, atol=ATOL)
    theirs = scipy_run(Pendulum([2.0], [0.0]), ours.t, y0, RTOL, ATOL)
    reference = scipy_run(Pendulum([2.0], [0.0]), ours.t, y0, 1e-13, 1e-15)
    our_error = np.max(np.abs(ours.y - reference))
    their_error = np.max(np.abs(theirs - reference))
    # Both are controlled to rtol 1e-10 per step over ~50 steps of an order-one state: measured
    # ours 1.5e-10 and SciPy's 2.0e-10 from the solution, 2.8e-10 apart; 3e-9 apart is ten
    # times that, and ours must be no worse than 5x SciPy's (the two controllers differ only in
    # their first step and safety factors, so a factor 5 means a defect, not a choice).
    assert np.max(np.abs(ours.y - theirs)) < 3e-9
    assert our_error < max(5 * their_error, 1e-12), (our_error, their_error)
    assert ours.extra["accepted_steps"] > 0 and ours.method == "dop853"


def test_drag_projectile_matches_a_tight_scipy_solution():
    # 45 degrees at 20 m/s with drag: no closed form; SciPy's DOP853 at rtol 1e-13 is the
    # reference. Values up to 25: rtol 1e-10 gives a few 1e-9 absolute (measured 2.3e-9);
    # 3e-8 is ten times that.
    make = lambda: pc.ProjectileMotion([0.0, 0.0], [20.0, 20.0], m=1.0, g=9.81, drag_coeff=0.05)
    system = make()
    ours = system.integrate_sampled((0.0, 3.0), 0.01, "dop853")
    reference = scipy_run(make(), ours.t, make().state.copy(), 1e-13, 1e-15)
    assert np.max(np.abs(ours.y - reference)) < 3e-8
    # Dissipative: the energy falls monotonically (a sample's energy is the system's energy).
    assert np.all(np.diff(ours.energy) < 0)
    assert ours.energy[-1] == pytest.approx(system.energy(ours.y[-1]), rel=0, abs=0)


def test_the_defaults_are_the_documented_tolerances():
    make = lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    default = make().integrate_sampled((0.0, 6.0), 0.1, "dop853")
    explicit = make().integrate_sampled((0.0, 6.0), 0.1, "dop853", rtol=1e-10, atol=1e-12)
    looser = make().integrate_sampled((0.0, 6.0), 0.1, "dop853", rtol=1e-6)
    assert np.array_equal(default.y, explicit.y)
    assert looser.extra["accepted_steps"] < default.extra["accepted_steps"]
    for key in ("accepted_steps", "rejected_steps", "rhs_evaluations"):
        assert default.extra[key] == explicit.extra[key] >= 0
    # The grid is the fixed-step one; the final sample is t1 exactly.
    assert np.array_equal(default.t, make().integrate((0.0, 6.0), 0.1, "rk4").t)
    assert default.t[-1] == 6.0


def test_repeated_runs_are_bit_identical():
    runs = [pc.DoublePendulum([2.0, 2.5], [0.0, 0.0]).integrate_sampled((0.0, 5.0), 0.01, "dop853") for _ in range(2)]
    assert runs[0].y.tobytes() == runs[1].y.tobytes()
    assert runs[0].energy.tobytes() == runs[1].energy.tobytes()


@pytest.mark.parametrize("name", ["rtol", "atol"])
@pytest.mark.parametrize("bad", [0.0, -1e-8, float("nan"), float("inf"), "1e-8", 1j, True])
def test_bad_tolerances_are_value_errors_naming_them(name, bad):
    with pytest.raises(ValueError, match=name):
        pc.KeplerSystem([1.0, 0.0], [0.0, 1.0]).integrate_sampled((0.0, 1.0), 0.1, "dop853", **{name: bad})


@pytest.mark.parametrize("name", ["rtol", "atol"])
@pytest.mark.parametrize("method", ["rk4", "yoshida4", "implicit_midpoint", None])
def test_tolerances_are_refused_for_fixed_step_methods(name, method):
    # KeplerSystem's default method (None) is yoshida4, a fixed-step method.
    with pytest.raises(ValueError, match=rf"{name}.*dop853"):
        pc.KeplerSystem([1.0, 0.0], [0.0, 1.0]).integrate_sampled((0.0, 1.0), 0.1, method, **{name: 1e-8})


def test_tolerances_are_keyword_only():
    with pytest.raises(TypeError):
        pc.KeplerSystem([1.0, 0.0], [0.0, 1.0]).integrate_sampled((0.0, 1.0), 0.1, "dop853", 1, False, True, 1e-8)


class Decay(pc.ODESystem):
    """``y' = -y``, written in Python (the run calls back into it)."""

    def derivatives(self, t, state):
        return -state

    def energy(self, state=None):
        return 0.0


# One system per path to the adaptive driver: a built-in (native), a Python Hamiltonian and a
# Python ODE (both called back from Rust).
BUDGET_SYSTEMS = {
    "native": lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5),
    "python_hamiltonian": lambda: Pendulum([2.0], [0.0]),
    "python_ode": lambda: Decay([1.0]),
}


@pytest.mark.parametrize("kind", sorted(BUDGET_SYSTEMS))
def test_the_step_budget_stops_the_run_exactly_at_its_count(kind):
    make = BUDGET_SYSTEMS[kind]
    free = make().integrate_sampled((0.0, 6.0), 0.5, "dop853")
    attempts = int(free.extra["accepted_steps"] + free.extra["rejected_steps"])
    # Enough steps that a budget one below them is a real budget, not a degenerate one.
    assert attempts > 5, attempts
    exact = make().integrate_sampled((0.0, 6.0), 0.5, "dop853", max_steps=attempts)
    assert exact.y.tobytes() == free.y.tobytes()
    with pytest.raises(ConvergenceError, match=rf"budget of {attempts - 1} steps \(max_steps\)"):
        make().integrate_sampled((0.0, 6.0), 0.5, "dop853", max_steps=attempts - 1)


def test_a_numpy_integer_is_a_budget():
    # Ten orbits take far more than 10 attempts at the default tolerances, so the run stops.
    with pytest.raises(ConvergenceError, match="budget of 10 steps"):
        pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate_sampled(
            (0.0, 60.0), 0.5, "dop853", max_steps=np.int64(10))


@pytest.mark.parametrize("bad", [0, -1, 1.5, 10.0, "10", 1j, True, 2**64])
def test_bad_step_budgets_are_value_errors_naming_them(bad):
    with pytest.raises(ValueError, match="max_steps"):
        pc.KeplerSystem([1.0, 0.0], [0.0, 1.0]).integrate_sampled((0.0, 1.0), 0.1, "dop853", max_steps=bad)


@pytest.mark.parametrize("method", ["rk4", "yoshida4", "implicit_midpoint", None])
def test_a_step_budget_is_refused_for_fixed_step_methods(method):
    with pytest.raises(ValueError, match=r"max_steps.*dop853"):
        pc.KeplerSystem([1.0, 0.0], [0.0, 1.0]).integrate_sampled((0.0, 1.0), 0.1, method, max_steps=100)


class Blowup(pc.ODESystem):
    """``y' = y^2``, ``y(0) = 1``: infinite at ``t = 1``."""

    def derivatives(self, t, state):
        return state**2

    def energy(self, state=None):
        return 0.0


def test_a_step_size_failure_is_a_convergence_error_naming_t():
    with pytest.raises(ConvergenceError, match=r"t = 1\.0000"):
        Blowup([1.0]).integrate_sampled((0.0, 2.0), 0.5, "dop853")


def test_every_system_lists_dop853():
    for entry in pc.catalog():
        assert "dop853" in entry["methods"], entry["name"]
    (info,) = [m for m in pc.methods() if m["name"] == "dop853"]
    assert info["order"] == 8 and not info["symplectic"] and not info["separable_only"]
    assert info["evaluations_per_step"] == 12
