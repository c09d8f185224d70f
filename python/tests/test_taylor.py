"""The ``taylor`` method from Python: on the SymPy engines' systems (Hamiltonian, Lagrangian,
ODE), whose equations are expressions and so have a Taylor form, and on the catalogue's
Lagrangian systems (their generic L traced into an expression), against closed forms and
DOP853 at tight tolerance; Poincaré sections with it; refused by the catalogue's hand-written
Hamiltonian and ODE systems, naming them. Which methods need a Taylor form is read from
``methods()``, not listed here."""

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


def kepler_system():
    """The orbit of ``kepler_closed_form`` from a HamiltonianEngine at perihelion."""
    x, y, px, py = sp.symbols("x y p_x p_y")
    H = (px**2 + py**2) / 2 - 1 / sp.sqrt(x**2 + y**2)
    y0 = kepler_closed_form(0.0)
    return HamiltonianEngine([x, y], [px, py], H).system(y0[:2], y0[2:])


def test_the_table_has_a_taylor_method():
    assert TAYLOR == ["taylor"]
    (info,) = [m for m in pc.methods() if m["name"] == "taylor"]
    assert info["adaptive"] and not info["separable_only"] and not info["symplectic"]


@pytest.mark.parametrize("method", TAYLOR)
def test_kepler_from_a_hamiltonian_engine_follows_the_closed_form(method):
    s = kepler_system()
    r = s.integrate_sampled((0.0, 10 * 2 * np.pi), 2 * np.pi / 10, method, rtol=1e-14,
                            atol=1e-14)
    assert r.method == method
    error = np.max(np.abs(r.y - kepler_closed_form(r.t)))
    # Ten orbits at tolerance 1e-14: the global error grows from per-step errors of ~tol to
    # tens of tol per orbit (the Rust tests measure it), so 1e-11 bounds it with room; an
    # expansion wrong in any order misses by far more.
    assert error < 1e-11, error
    # The order weighs the recurrences' work against the step's length (the Rust tests check
    # the choice): at least Jorba and Zou's ceil(-ln(1e-14)/2 + 1) = 18, the best order of a
    # step made of products only, and at most the cap, 24.
    assert 18 <= r.extra["order"] <= 24


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
def test_a_catalogue_system_without_a_taylor_form_refuses_it_by_name(method):
    s = pc.TodaLattice([0.1, 0.0, -0.1], [0.0, 0.2, 0.0])
    with pytest.raises(ValueError, match=r"cannot integrate.*`toda.*HamiltonianEngine"):
        s.integrate_sampled((0.0, 1.0), 0.1, method)


@pytest.mark.parametrize("method", TAYLOR)
def test_the_catalogue_kepler_runs_it_to_the_closed_form(method):
    # The catalogue's KeplerSystem (its H traced, no expression written here), 5 orbits from
    # perihelion at rtol = atol = 1e-14: the phase error after ~31 time units is ~1e-12 at that
    # tolerance, so 1e-10 has a margin of ~100, and a wrong force misses by order one.
    s = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    r = s.integrate_sampled((0.0, 10 * np.pi), np.pi, method, rtol=1e-14, atol=1e-14)
    assert r.method == method
    assert np.max(np.abs(r.y - kepler_closed_form(r.t))) < 1e-10


@pytest.mark.parametrize("method", TAYLOR)
def test_a_catalogue_lagrangian_system_runs_it(method):
    # The catalogue's double pendulum (its L traced, no expression written here) against
    # dop853 on the same system at rtol 1e-13, 5 s from (1, 0.5) rad at rest: both within
    # ~1e-10 of the solution (the chaotic stretching over 5 s is ~e^5), so 1e-9 bounds their
    # difference, and a wrong force misses by order one.
    ours = pc.DoublePendulum([1.0, 0.5], [0.0, 0.0]).integrate_sampled(
        (0.0, 5.0), 0.1, method, rtol=1e-15, atol=1e-15)
    reference = pc.DoublePendulum([1.0, 0.5], [0.0, 0.0]).integrate_sampled(
        (0.0, 5.0), 0.1, "dop853", rtol=1e-13, atol=1e-15)
    assert ours.method == method
    assert np.max(np.abs(ours.y - reference.y)) < 1e-9


@pytest.mark.parametrize("method", TAYLOR)
def test_a_poincare_section_with_it_follows_keplers_equation(method):
    # The Kepler orbit e = 0.5 from perihelion crosses x = 0 upwards at eccentric anomaly
    # 5 pi/3, at t = 5 pi/3 + sqrt(3)/4 + 2 pi k (Kepler's equation t = E - e sin E). The
    # section runs at the default tolerances (rtol 1e-10, atol 1e-12), which keep the orbit's
    # phase within ~1e-10 over three orbits; the crossings are roots of the step polynomial,
    # so 1e-8 bounds their error with room, while a root of the wrong step, or a run that
    # ignored the method, misses by far more.
    s = kepler_system()
    cut = pc.poincare_section(s, (0.0, 3 * 2 * np.pi), 2 * np.pi / 10, coordinate=0, value=0.0,
                              direction=1, method=method)
    expected = 5 * np.pi / 3 + math.sqrt(3) / 4 + 2 * np.pi * np.arange(3)
    assert len(cut.t) == 3
    assert np.max(np.abs(cut.t - expected)) < 1e-8
    assert np.max(np.abs(cut.y - kepler_closed_form(cut.t))) < 1e-8
