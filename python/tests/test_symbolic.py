"""LagrangianEngine: a SymPy Lagrangian translated once into the native expression tree."""

import numpy as np
import pytest

sp = pytest.importorskip("sympy")

import physicskit.classical as pc  # noqa: E402
from physicskit.classical.utils.symbolic import LagrangianEngine  # noqa: E402

from conftest import sympy_double_pendulum  # noqa: E402


def test_sympy_double_pendulum_equals_builtin():
    engine = sympy_double_pendulum(m1=1.0, m2=1.5, l1=1.0, l2=0.8)
    a = engine.system([2.0, 1.0], [0.5, -0.3])
    b = pc.DoublePendulum([2.0, 1.0], [0.5, -0.3], m2=1.5, l2=0.8)
    assert isinstance(a, pc.LagrangianSystem)
    # Same energy from two differently written Lagrangians: operation order only.
    assert a.energy() == pytest.approx(b.energy(), rel=1e-14)
    ra = a.integrate((0.0, 0.3), 3e-5, method="implicit_midpoint")  # 1e4 steps
    rb = b.integrate((0.0, 0.3), 3e-5, method="implicit_midpoint")
    # Same engine and integrator; the two Lagrangians differ only in the order of the
    # floating-point operations (SymPy's expanded form vs the hand-written one): the issue's
    # 1e-12 over 1e4 steps.
    assert ra.y.shape == rb.y.shape == (10_001, 4)
    assert np.max(np.abs(ra.y - rb.y)) < 1e-12
    assert np.max(np.abs(ra.energy - rb.energy)) < 1e-12
    rk_a = engine.system([2.0, 1.0], [0.5, -0.3]).integrate((0.0, 0.3), 3e-5, method="rk4")
    rk_b = pc.DoublePendulum([2.0, 1.0], [0.5, -0.3], m2=1.5, l2=0.8).integrate((0.0, 0.3), 3e-5, method="rk4")
    assert np.max(np.abs(rk_a.y - rk_b.y)) < 1e-12


def test_engine_attributes_and_native_evaluations():
    engine = sympy_double_pendulum()
    assert engine.n == 2 and len(engine.q) == 2 and len(engine.qdot) == 2
    dp = pc.DoublePendulum([0.3, -0.2], [0.1, 0.4])
    q, qd = np.array([0.3, -0.2]), np.array([0.1, 0.4])
    # Same quantities from two differently written Lagrangians: they differ only by the order
    # of floating-point operations, a few ulps of values of order 10 (atol=0: relative only).
    assert np.allclose(engine.acceleration(q, qd), dp.acceleration(q, qd, 0.0), rtol=1e-13, atol=0)
    assert np.allclose(engine.momentum(q, qd), dp.momentum(q, qd), rtol=1e-13, atol=0)
    # The symbolic mass matrix against the textbook one for unit masses and lengths:
    # [[2, cos(theta1 - theta2)], [cos(theta1 - theta2), 1]].
    M = engine.mass_matrix.subs(engine.params).subs({engine.q[0]: 0.3, engine.q[1]: -0.2})
    M = np.array(M.evalf(), dtype=float)
    c = np.cos(0.5)
    # evalf rounds each entry once: 1e-14.
    assert np.allclose(M, [[2.0, c], [c, 1.0]], rtol=0, atol=1e-14)


def test_subclass_with_engine_runs_natively():
    x, v, k = sp.symbols("x v k")

    class Oscillator(pc.LagrangianSystem):
        def __init__(self, q0, qdot0):
            super().__init__(q0, qdot0)
            self.engine = LagrangianEngine([x], [v], v**2 / 2 - k * x**2 / 2, params={"k": 4.0})

        def energy(self, state=None):
            q, qd = self.split(self.state if state is None else state, 1)
            return float(qd[0] ** 2 / 2 + 2.0 * q[0] ** 2)

    s = Oscillator([1.0], [0.0])
    r = s.integrate((0.0, 2.0), 1e-3)
    assert r.method == "implicit_midpoint"
    assert np.max(np.abs(r.q[:, 0] - np.cos(2.0 * r.t))) < 1e-5  # midpoint, dt^2 phase error


def test_time_dependent_lagrangian():
    # L = qdot^2/2 - q^2/2 + F0 cos(t) q: a driven oscillator, exercising the t symbol.
    q, v, t = sp.symbols("q v t")
    engine = LagrangianEngine([q], [v], v**2 / 2 - q**2 / 2 + sp.Rational(1, 2) * sp.cos(2 * t) * q, t=t)
    acc = engine.acceleration([0.3], [0.0], t=0.7)
    # qddot = -q + F0 cos(2t) exactly; the engine's AD reproduces it to rounding.
    assert acc[0] == pytest.approx(-0.3 + 0.5 * np.cos(1.4), rel=1e-14)


@pytest.mark.parametrize("build, match", [
    (lambda x, v: LagrangianEngine([x], [v], v**2 / 2 - sp.Symbol("g") * x), "symbol g"),
    (lambda x, v: LagrangianEngine([x], [v], v**2 / 2 + sp.besselj(0, x)), "cannot translate"),
    (lambda x, v: LagrangianEngine([x], [], v**2 / 2), "equal length"),
    (lambda x, v: LagrangianEngine([x], [v], v**2 / 2, params={"g": float("nan")}), "finite"),
])
def test_engine_errors(build, match):
    x, v = sp.symbols("x v")
    with pytest.raises(ValueError, match=match):
        build(x, v)
