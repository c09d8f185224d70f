"""Shared fixtures: every built-in system in a small, well-behaved configuration, and the
cargo profile of the Rust programs some tests build and run."""

import os

import pytest

import physicskit.classical as pc


def make_systems():
    """name -> zero-argument factory of a small instance of each built-in system."""
    return {
        "KeplerSystem": lambda: pc.KeplerSystem.from_orbital_elements(1.0, 0.5),
        "HenonHeilesSystem": lambda: pc.HenonHeilesSystem([0.1, 0.0], [0.0, 0.3]),
        "PendulumSwarm": lambda: pc.PendulumSwarm.from_box(1.0, 0.0, 0.1, 0.1, n=20),
        "ProjectileMotion": lambda: pc.ProjectileMotion.from_launch(20.0, 45.0),
        "HarmonicChain": lambda: pc.HarmonicChain([0.1, -0.05, 0.02, 0.0], [0.0, 0.1, 0.0, 0.0]),
        "FPUTChain": lambda: pc.FPUTChain(n=8, beta=1.0),
        "SineGordonChain": lambda: pc.SineGordonChain(40, q0=pc.SineGordonChain.kink(40, 20.0)[0]),
        "DoublePendulum": lambda: pc.DoublePendulum([2.0, 1.0], [0.5, -0.3]),
        "BeadOnRotatingHoop": lambda: pc.BeadOnRotatingHoop(0.3, 0.5),
        "CoupledOscillators": lambda: pc.CoupledOscillators([0.1, 0.0, -0.1], [0.0, 0.2, 0.0]),
        "EulerTop": lambda: pc.EulerTop([0.01, 1.0, 0.01]),
        "HeavySymmetricTop": lambda: pc.HeavySymmetricTop([0.0, 0.5, 0.0], [0.0, 0.0, 20.0]),
        "TodaLattice": lambda: pc.TodaLattice([0.0, 0.3, -0.2, 0.1], [0.5, 0.0, -0.5, 0.2]),
        "ElasticPendulum": lambda: pc.ElasticPendulum([1.2, 0.3], [0.0, 0.1]),
    }


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
