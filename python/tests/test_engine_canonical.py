"""``LagrangianEngine``'s Hamiltonian side: ``hamiltonian``, ``velocity``,
``canonical_derivatives`` and the Numba peer's ``*_njit`` aliases.

Each is checked against something the engine does not compute: Hamiltonians and fields
derived by hand for 1- and 2-dof Lagrangians, a time-dependent one and one not quadratic in
the velocities; and Hamilton's equations ``dq/dt = dH/dp``, ``dp/dt = -dH/dq`` against
central differences of the engine's own ``H`` (so ``canonical_derivatives`` and
``hamiltonian`` are checked against each other through calculus, not through shared code).
"""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest

from physicskit.classical.utils.symbolic import LagrangianEngine

from conftest import sympy_double_pendulum

sp = pytest.importorskip("sympy")

# Central differences with step h of a smooth function of size O(1): truncation
# h^2 |f'''| / 6 ~ 2e-11 at h = 1e-5, rounding eps |f| / h ~ 2e-11; 1e-8 leaves a factor of
# several hundred for third derivatives of size up to ~100 (the double pendulum's H at these
# states) without hiding a wrong sign or a missing term (those are O(1)).
FD_STEP = 1e-5
FD_TOL = 1e-8
# Closed forms against the engine's automatic differentiation: a few roundings of O(1)
# numbers (a linear solve for velocity): 1e-12 is ~5000 ulp, far below any real error.
EXACT_TOL = 1e-12


def pendulum(m=1.3, l=0.7, g=9.81):
    th, w = sp.symbols("theta omega")
    M, Lp, G = sp.symbols("m l g", positive=True)
    L = M * Lp**2 * w**2 / 2 + M * G * Lp * sp.cos(th)
    return LagrangianEngine([th], [w], L, params={M: m, Lp: l, G: g}), (m, l, g)


def polar_oscillator(m=0.8, k=2.5):
    """A particle in a plane, isotropic spring, polar coordinates (q-dependent mass matrix)."""
    r, ph, rd, phd = sp.symbols("r phi rdot phidot")
    M, K = sp.symbols("m k", positive=True)
    L = M * (rd**2 + r**2 * phd**2) / 2 - K * r**2 / 2
    return LagrangianEngine([r, ph], [rd, phd], L, params={M: m, K: k}), (m, k)


def driven(m=1.1, b=0.4, k=2.0, eps=0.3, w=1.7):
    """Explicitly time-dependent: L = m qd^2/2 + b t q qd - k (1 + eps cos(w t)) q^2 / 2."""
    q, qd, t = sp.symbols("q qdot t")
    M, B, K, E, W = sp.symbols("m b k eps w")
    L = M * qd**2 / 2 + B * t * q * qd - K * (1 + E * sp.cos(W * t)) * q**2 / 2
    return LagrangianEngine([q], [qd], L, t=t, params={M: m, B: b, K: k, E: eps, W: w}), \
        (m, b, k, eps, w)


def relativistic(m=1.0, c=2.0, k=1.5):
    """Not quadratic in qdot: the Legendre map is inverted by Newton's method."""
    q, qd = sp.symbols("q qdot")
    M, C, K = sp.symbols("m c k", positive=True)
    L = -M * C**2 * sp.sqrt(1 - qd**2 / C**2) - K * q**2 / 2
    return LagrangianEngine([q], [qd], L, params={M: m, C: c, K: k}), (m, c, k)


def _fd_field(engine, q, p, t):
    """``[dH/dp, -dH/dq]`` by central differences of ``engine.hamiltonian``."""
    n = len(q)
    dq, dp = np.empty(n), np.empty(n)
    for i in range(n):
        e = np.zeros(n)
        e[i] = FD_STEP
        dq[i] = (engine.hamiltonian(q, p + e, t) - engine.hamiltonian(q, p - e, t)) / (2 * FD_STEP)
        dp[i] = -(engine.hamiltonian(q + e, p, t) - engine.hamiltonian(q - e, p, t)) / (
            2 * FD_STEP
        )
    return np.concatenate([dq, dp])


CASES = {
    "pendulum (1 dof)": (lambda: pendulum()[0], [0.9], [0.4], 0.0),
    "polar oscillator (2 dof)": (lambda: polar_oscillator()[0], [1.3, 0.4], [0.2, 0.7], 0.0),
    "double pendulum (2 dof, coupled M(q))": (
        lambda: sympy_double_pendulum(), [2.0, 1.0], [0.5, -0.3], 0.0),
    "driven (time-dependent)": (lambda: driven()[0], [0.6], [-0.3], 1.9),
    "relativistic (Newton inverse)": (lambda: relativistic()[0], [0.5], [1.2], 0.0),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_canonical_field_is_the_gradient_of_the_hamiltonian(case):
    make, q, p, t = CASES[case]
    engine = make()
    q, p = np.array(q), np.array(p)
    field = engine.canonical_derivatives(t, np.concatenate([q, p]))
    np.testing.assert_allclose(field, _fd_field(engine, q, p, t), rtol=FD_TOL, atol=FD_TOL)


@pytest.mark.parametrize("case", sorted(CASES))
def test_velocity_inverts_momentum(case):
    make, q, p, t = CASES[case]
    engine = make()
    qdot = engine.velocity(q, p, t)
    np.testing.assert_allclose(engine.momentum(q, qdot, t), p, rtol=EXACT_TOL, atol=EXACT_TOL)
    # dq/dt of the canonical field is that velocity.
    field = engine.canonical_derivatives(t, np.concatenate([q, p]))
    np.testing.assert_allclose(field[: len(q)], qdot, rtol=EXACT_TOL, atol=EXACT_TOL)


def test_pendulum_against_hand_derived_forms():
    engine, (m, l, g) = pendulum()
    th, pth = 0.9, 0.4
    I = m * l**2
    assert engine.velocity([th], [pth])[0] == pytest.approx(pth / I, rel=EXACT_TOL)
    assert engine.hamiltonian([th], [pth]) == pytest.approx(
        pth**2 / (2 * I) - m * g * l * math.cos(th), rel=EXACT_TOL)
    np.testing.assert_allclose(engine.canonical_derivatives(0.0, [th, pth]),
                               [pth / I, -m * g * l * math.sin(th)], rtol=EXACT_TOL)


def test_polar_oscillator_against_hand_derived_forms():
    engine, (m, k) = polar_oscillator()
    r, ph, pr, pph = 1.3, 0.4, 0.2, 0.7
    # p_r = m rdot, p_phi = m r^2 phidot; H = p_r^2/2m + p_phi^2/(2 m r^2) + k r^2/2.
    np.testing.assert_allclose(engine.velocity([r, ph], [pr, pph]),
                               [pr / m, pph / (m * r**2)], rtol=EXACT_TOL)
    assert engine.hamiltonian([r, ph], [pr, pph]) == pytest.approx(
        pr**2 / (2 * m) + pph**2 / (2 * m * r**2) + k * r**2 / 2, rel=EXACT_TOL)
    np.testing.assert_allclose(
        engine.canonical_derivatives(0.0, [r, ph, pr, pph]),
        [pr / m, pph / (m * r**2), pph**2 / (m * r**3) - k * r, 0.0], rtol=EXACT_TOL,
        atol=EXACT_TOL)


def test_time_dependent_lagrangian_against_hand_derived_forms():
    engine, (m, b, k, eps, w) = driven()
    q, p, t = 0.6, -0.3, 1.9
    kt = k * (1 + eps * math.cos(w * t))
    # p = m qdot + b t q, so qdot = (p - b t q)/m and H = (p - b t q)^2/2m + k(t) q^2/2;
    # dp/dt = dL/dq = b t qdot - k(t) q.
    qdot = (p - b * t * q) / m
    assert engine.velocity([q], [p], t)[0] == pytest.approx(qdot, rel=EXACT_TOL)
    assert engine.hamiltonian([q], [p], t) == pytest.approx(
        (p - b * t * q) ** 2 / (2 * m) + kt * q**2 / 2, rel=EXACT_TOL)
    np.testing.assert_allclose(engine.canonical_derivatives(t, [q, p]),
                               [qdot, b * t * qdot - kt * q], rtol=EXACT_TOL)
    # The clock matters: at t = 0 the same (q, p) has another H.
    assert engine.hamiltonian([q], [p], 0.0) == pytest.approx(
        p**2 / (2 * m) + k * (1 + eps) * q**2 / 2, rel=EXACT_TOL)
    # Euler-Lagrange: d/dt(m qd + b t q) = b t qd - k(t) q gives m qdd = -(b + k(t)) q, where
    # the b t q qd term's time derivative enters through d2L/(dqdot dt) = b q.
    assert engine.acceleration([q], [qdot], t)[0] == pytest.approx(
        -(b + kt) * q / m, rel=EXACT_TOL)


def test_relativistic_lagrangian_against_hand_derived_forms():
    engine, (m, c, k) = relativistic()
    q, p = 0.5, 1.2
    # p = m qd / sqrt(1 - qd^2/c^2), so qd = p / sqrt(m^2 + p^2/c^2), H = sqrt(p^2 c^2 +
    # m^2 c^4) + k q^2 / 2. Newton stops at the rounding floor: same tolerance.
    assert engine.velocity([q], [p])[0] == pytest.approx(p / math.sqrt(m**2 + p**2 / c**2),
                                                         rel=EXACT_TOL)
    assert engine.hamiltonian([q], [p]) == pytest.approx(
        math.sqrt(p**2 * c**2 + m**2 * c**4) + k * q**2 / 2, rel=EXACT_TOL)


def test_hamiltonian_is_conserved_along_the_native_run():
    """Integrating the engine's system and mapping each sample to (q, p): H(q, p) is the
    energy the run stores (a quantity computed independently, as p . qdot - L from qdot)."""
    engine = sympy_double_pendulum()
    system = engine.system([2.0, 1.0], [0.5, -0.3])
    res = system.integrate((0.0, 0.5), 1e-3)
    for i in (0, len(res.t) // 2, len(res.t) - 1):
        q, qdot = res.q[i], res.p[i]
        p = engine.momentum(q, qdot)
        # Two evaluations of the same H through different routes: rounding only.
        assert engine.hamiltonian(q, p) == pytest.approx(res.energy[i], rel=EXACT_TOL)


PEER_ALIASES = {
    # peer name: (engine method, the peer's parameters)
    "acceleration_njit": ("acceleration", ["q", "qdot", "t"]),
    "momentum_njit": ("momentum", ["q", "qdot"]),
    "hamiltonian_njit": ("hamiltonian", ["q", "p", "t"]),
    "canonical_deriv_njit": ("canonical_derivatives", ["t", "y"]),
}


@pytest.mark.parametrize("alias", sorted(PEER_ALIASES))
def test_peer_names_are_documented_aliases(alias):
    engine = driven()[0]
    method, params = PEER_ALIASES[alias]
    fn = getattr(engine, alias)
    assert list(inspect.signature(fn).parameters) == params
    assert method in fn.__doc__ and "alias" in fn.__doc__.lower()
    q, v, t = np.array([0.6]), np.array([-0.3]), 1.9
    args = {"q": q, "qdot": v, "p": v, "t": t, "y": np.concatenate([q, v])}
    got = fn(*(args[a] for a in params))
    want = getattr(engine, method)(*(args[a] for a in params))
    np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("call", [
    lambda e: e.hamiltonian([0.1, 0.2], [0.0]),
    lambda e: e.velocity([0.1], [float("nan")]),
    lambda e: e.hamiltonian([0.1], [0.2], t=float("inf")),
    lambda e: e.canonical_derivatives(0.0, [0.1, 0.2, 0.3]),
    lambda e: e.canonical_derivatives(0.0, [0.1, 1j]),
    lambda e: e.velocity("q", [0.0]),
])
def test_bad_arguments_are_value_errors(call):
    with pytest.raises(ValueError):
        call(pendulum()[0])


def test_singular_mass_matrix_is_a_value_error():
    q, qd = sp.symbols("q qdot")
    engine = LagrangianEngine([q], [qd], q**2 * qd**2 / 2 - q**2 / 2)
    with pytest.raises(ValueError, match="singular"):
        engine.velocity([0.0], [1.0])
