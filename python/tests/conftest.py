"""Shared fixtures: every built-in system of the catalogue, built from its entry's defaults and
demonstration values, and the cargo profile of the Rust programs some tests build and run."""

import os

import pytest

import physicskit.classical as pc


def resolve(path: str):
    """The callable a catalogue ``python`` path names: a class, or a class's classmethod
    (``"KeplerSystem.from_orbital_elements"``)."""
    cls_name, _dot, method = path.partition(".")
    cls = getattr(pc, cls_name)
    return getattr(cls, method) if method else cls


def catalogue_calls():
    """catalogue ``python`` path -> (callable, keyword arguments) of a valid call: every
    parameter with a spec default or a demonstration value, by keyword, with that value (the
    values the command line and the lab start from), an initial velocity the other front ends
    start at rest as zeros; parameters whose default is None are left out. Every entry with a Python counterpart, so a new system is in every test that
    iterates this."""
    calls = {}
    for entry in pc.catalog():
        if entry["python"] is None:
            continue
        kwargs = {}
        for p in entry["params"]:
            if p["default_kind"] in ("value", "demo"):
                kwargs[p["name"]] = p["default"]
            elif p["default_kind"] == "demo_absent" and p["initial_state"]:
                # The spec requires it, the other front ends start it at rest: zeros as long
                # as the initial state's given half.
                given = next(v for k, v in kwargs.items()
                             if any(q["name"] == k and q["initial_state"] for q in entry["params"]))
                kwargs[p["name"]] = [0.0] * len(given)
            else:
                # A required parameter without a demonstration value could not be built here.
                assert p["default_kind"] == "absent", (entry["name"], p)
        calls[entry["python"]] = (resolve(entry["python"]), kwargs)
    return calls


def make_systems():
    """catalogue ``python`` path -> zero-argument factory of each built-in system, built from its
    catalogue entry's defaults and demonstration values (``catalogue_calls``)."""
    return {path: (lambda fn=fn, kw=kw: fn(**kw)) for path, (fn, kw) in catalogue_calls().items()}


@pytest.fixture(scope="session")
def cargo_profile():
    """``["--profile", name]`` for the cargo and maturin commands of the tests: the profile
    ``python/dev.sh env`` built the extension and the Rust programs in (``PHYSICSKIT_PROFILE``,
    default ``release``; ``scripts/test`` uses ``ci``), so that they reuse that build."""
    return ["--profile", os.environ.get("PHYSICSKIT_PROFILE", "release")]


@pytest.fixture(params=sorted(make_systems()))
def system_name(request):
    """Name of a built-in system (parametrizes a test over all of them)."""
    return request.param


def sympy_double_pendulum(m1=1.0, m2=1.0, l1=1.0, l2=1.0, g=9.81):
    """The double pendulum's Lagrangian written in SymPy from the bob coordinates (independent
    of the built-in's hand-written Lagrangian), as a LagrangianEngine."""
    sp = pytest.importorskip("sympy")
    from physicskit.classical.utils.symbolic import LagrangianEngine

    th1, th2, w1, w2 = sp.symbols("theta1 theta2 omega1 omega2")
    M1, M2, L1, L2, G = sp.symbols("m1 m2 l1 l2 g", positive=True)
    x1, y1 = L1 * sp.sin(th1), -L1 * sp.cos(th1)
    x2, y2 = x1 + L2 * sp.sin(th2), y1 - L2 * sp.cos(th2)
    # Velocities by the chain rule d/dt f(theta) = sum df/dtheta_i * omega_i.
    def ddt(f):
        return sp.diff(f, th1) * w1 + sp.diff(f, th2) * w2

    T = M1 * (ddt(x1) ** 2 + ddt(y1) ** 2) / 2 + M2 * (ddt(x2) ** 2 + ddt(y2) ** 2) / 2
    V = M1 * G * y1 + M2 * G * y2
    return LagrangianEngine([th1, th2], [w1, w2], T - V,
                            params={M1: m1, M2: m2, L1: l1, L2: l2, G: g})
