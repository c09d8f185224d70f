"""The ``taylor`` method from Python: on the SymPy engines' systems (Hamiltonian, Lagrangian,
ODE), whose equations are expressions and so have a Taylor form, against closed forms and
SciPy's DOP853 at tight tolerance; refused by the catalogue's hand-written systems, naming
them. Which methods need a Taylor form is read from ``methods()``, not listed here."""

import math

import numpy as np
import pytest

import physicskit.classical as pc

from conftest import sympy_double_pendulum

sp = pytest.importorskip("sympy")
from physicskit.classical.utils.symbolic import HamiltonianEngine, ODEEngine  # noqa: E402

TAYLOR = [m["name"] for m in pc.methods() if m["needs_taylor_form"]]


def kepler_closed_form(t, e=0.5):
    """The orbit a = 1, k = mu = 1 (period 2 pi) from perihelion, by Kepler's equation
    ``E - e sin E = t`` solved by Newton's method to rounding: ``(x, y, px, py)``."""
    m = np.mod(t, 2 * np.pi)
    ecc = m + e * np.sin(m)
    for _ in range(50):
        ecc = ecc - (ecc - e * np.sin(ecc) - m) / (1 - e * np.cos(ecc))
    edot = 1 / (1 - e * np.cos(ecc))
    b = math.sqrt(1 - e * e)
    return np.stack([np.cos(ecc) - e, b * np.sin(ecc), -np.sin(ecc) * edot,
                     b * np.cos(ecc) * edot], axis=-1)


def test_the_table_has_a_taylor_method():
    assert TAYLOR == ["taylor"]
    (info,) = [m for m in pc.methods() if m["name"] == "taylor"]
    assert info["adaptive"] and not info["separable_only"] and not info["symplectic"]


@pytest.mark.parametrize("method", TAYLOR)
def test_kepler_from_a_hamiltonian_engine_follows_the_closed_form(method):
    x, y, px, py = sp.symbols("x y p_x p_y")
    H = (px**2 + py**2) / 2 - 1 / sp.sqrt(x**2 + y**2)
    y0 = kepler_closed_form(0.0)
    s = HamiltonianEngine([x, y], [px, py], H).system(y0[:2], y0[2:])
    r = s.integrate_sampled((0.0, 10 * 2 * np.pi), 2 * np.pi / 10, method, rtol=1e-14,
                            atol=1e-14)
    assert r.method == method
    error = np.max(np.abs(r.y - kepler_closed_form(r.t)))
    # Ten orbits at tolerance 1e-14: the global error grows from per-step errors of ~tol to
    # tens of tol per orbit (the Rust tests measure it), so 1e-11 bounds it with room; an
    # expansion wrong in any order misses by far more.
    assert error < 1e-11, error
    assert r.extra["order"] == 18  # ceil(-ln(1e-14)/2 + 1)


@pytest.mark.parametrize("method", TAYLOR)
def test_lagrangian_and_ode_engines_agree_with_dop853(method):
    # The double pendulum from a LagrangianEngine against dop853 at rtol 1e-13 on the
    # hand-written one, 5 s from (1, 0.5) rad at rest: both within ~1e-10 of the solution.
    engine = sympy_double_pendulum()
    ours = engine.system([1.0, 0.5], [0.0, 0.0]).integrate_sampled(
        (0.0, 5.0), 0.1, method, rtol=1e-15, atol=1e-15)
    reference = pc.DoublePendulum([1.0, 0.5], [0.0, 0.0]).integrate_sampled(
        (0.0, 5.0), 0.1, "dop853", rtol=1e-13, atol=1e-15)
    assert np.max(np.abs(ours.y - reference.y)) < 1e-9
    # A forced oscillator x'' = -4 x + cos t from rest: x = (cos t - cos 2t)/3.
    x, v, t = sp.symbols("x v t")
    s = ODEEngine([x, v], [v, -4 * x + sp.cos(t)], t=t).system([0.0, 0.0])
    r = s.integrate_sampled((0.0, 10.0), 0.5, method, rtol=1e-14, atol=1e-14)
    exact = (np.cos(r.t) - np.cos(2 * r.t)) / 3
    # Tolerance 1e-14 on a state of size ~1 over ~10 radians of phase: 1e-12 is tens of tol.
    assert np.max(np.abs(r.y[:, 0] - exact)) < 1e-12


@pytest.mark.parametrize("method", TAYLOR)
def test_a_catalogue_system_refuses_it_by_name(method):
    s = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    with pytest.raises(ValueError, match=r"cannot integrate.*`kepler.*HamiltonianEngine"):
        s.integrate_sampled((0.0, 1.0), 0.1, method)
