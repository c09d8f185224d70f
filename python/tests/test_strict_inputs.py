"""Inputs that used to slip through: a one-element list where a number is wanted, a
``SimulationResult`` built by hand with inconsistent arrays, and a callback's value too large
for a float. Each is a ValueError naming what is wrong."""

from __future__ import annotations

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit.classical import SimulationResult

from test_hostile import GOOD_CALLS


def _entries_by_class():
    return {e["python"]: e for e in pc.catalog() if e["python"] and "." not in e["python"]}


def _scalar_constants():
    """(class name, call, keyword) for every scalar constant a good call passes by keyword."""
    entries = _entries_by_class()
    cases = []
    for name, (cls, args, kwargs) in GOOD_CALLS.items():
        entry = entries.get(name)
        if entry is None:
            continue
        kinds = {p["name"]: p for p in entry["params"]}
        for key, value in kwargs.items():
            spec = kinds.get(key)
            if spec and spec["kind"] == "scalar" and not spec["initial_state"]:
                cases.append((name, cls, args, kwargs, key, value))
    return cases


CONSTANTS = _scalar_constants()


def test_there_are_constants_to_try():
    # The parametrization below must not be empty by accident (GOOD_CALLS passes many scalar
    # constants by keyword: masses, g, R, omega, ...).
    assert len(CONSTANTS) >= 10


@pytest.mark.parametrize("name, cls, args, kwargs, key, value", CONSTANTS,
                         ids=[f"{c[0]}.{c[4]}" for c in CONSTANTS])
def test_a_one_element_list_is_not_a_number(name, cls, args, kwargs, key, value):
    cls(*args, **kwargs)  # the good call itself is accepted
    for wrapped in ([value], (value,), np.array([value])):
        # The catalogue's words, or the package's converter's where a class converts first.
        with pytest.raises(ValueError, match="sequence of length 1|single real number|"
                                             "must be a real number") as info:
            cls(*args, **{**kwargs, key: wrapped})
        assert f"`{key}`" in str(info.value)
    # A 0-d array is a number.
    cls(*args, **{**kwargs, key: np.array(value)})


def test_a_scalar_initial_state_may_be_a_one_element_sequence():
    # A one-dimensional system's initial angle is its state vector: the peer takes [0.3].
    for theta0 in ([0.3], (0.3,), np.array([0.3])):
        assert pc.BeadOnRotatingHoop(theta0, [0.0]).state.tolist() == [0.3, 0.0]
    entry = _entries_by_class()["BeadOnRotatingHoop"]
    flags = {p["name"]: p["initial_state"] for p in entry["params"]}
    assert flags["theta0"] and flags["thetadot0"] and not flags["R"]


def _valid():
    t = np.linspace(0.0, 1.0, 5)
    y = np.zeros((5, 4))
    return dict(t=t, y=y, q=y[:, :2].copy(), p=y[:, 2:].copy(), energy=np.ones(5))


def test_a_valid_result_by_hand_is_kept_as_given():
    parts = _valid()
    r = SimulationResult(**parts, method="rk4")
    assert r.t is parts["t"] and r.y is parts["y"]  # no copy of float64 C-order arrays
    # Lists are converted.
    r = SimulationResult([0.0, 1.0], [[1.0, 2.0], [3.0, 4.0]])
    assert r.y.dtype == np.float64 and r.y.shape == (2, 2)


@pytest.mark.parametrize("change, match", [
    (dict(t=None), "needs t and y"),
    (dict(y=None), "needs t and y"),
    (dict(t=np.zeros((5, 1))), "t must have 1 dimension"),
    (dict(t=[0.0, np.nan, 1.0, 2.0, 3.0]), "NaN or infinity"),
    (dict(t=[0.0, 1.0, 0.5, 2.0, 3.0]), "must not decrease"),
    (dict(y=np.zeros(5)), "y must have 2 dimension"),
    (dict(y=np.zeros((4, 4))), "4 rows for 5 times"),
    (dict(energy=np.ones(4)), "energy has 4 values for 5 times"),
    (dict(energy=np.ones((5, 2))), "energy must have 1 dimension"),
    (dict(q=None), "q and p go together"),
    (dict(p=np.zeros((5, 3))), "must match"),
    (dict(q=np.zeros((4, 2)), p=np.zeros((4, 2))), "rows for 5 times"),
    (dict(q=np.zeros((5, 1)), p=np.zeros((5, 1))), "y is \\[q, p\\]"),
    (dict(t=[0.0, 1j, 2.0, 3.0, 4.0]), "complex"),
    (dict(method=3), "method must be a string"),
    (dict(extra=[1]), "extra must be a dict"),
])
def test_an_inconsistent_result_by_hand_is_refused(change, match):
    parts = {**_valid(), **change}
    with pytest.raises(ValueError, match=match):
        SimulationResult(**parts)


class _Huge(pc.HamiltonianSystem):
    def kinetic_energy(self, p):
        return 0.5 * float(p @ p)

    def potential_energy(self, q):
        return 10**400

    def force(self, q, t=0.0):
        return -q


def test_a_callback_value_too_large_for_a_float_names_the_callback():
    s = _Huge([1.0], [0.0])
    with pytest.raises(ValueError, match=r"potential_energy\(q\).*too large for a float"):
        s.energy()
