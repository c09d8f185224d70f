"""HamiltonianEngine and ODEEngine: SymPy systems run natively, with Jacobians by automatic
differentiation; and find_theta_equilibrium to a few ulps against mpmath."""

import math
import runpy
from pathlib import Path

import numpy as np
import pytest

sp = pytest.importorskip("sympy")

import physicskit.classical as pc  # noqa: E402
from physicskit.classical.utils import HamiltonianEngine, ODEEngine  # noqa: E402


def henon_heiles_engine():
    x, y, px, py = sp.symbols("x y p_x p_y")
    H = (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3
    return HamiltonianEngine([x, y], [px, py], H)


def lorenz_engine(**params):
    x, y, z, s, r, b = sp.symbols("x y z sigma rho beta")
    values = {"sigma": 10.0, "rho": 28.0, "beta": 8.0 / 3.0}
    values.update(params)
    return ODEEngine([x, y, z], [s * (y - x), x * (r - z) - y, x * y - b * z], params=values)


def test_henon_heiles_engine_follows_the_builtin_system():
    engine = henon_heiles_engine()
    assert engine.separable and np.array_equal(engine.mass_inv, [1.0, 1.0])
    a = engine.system([0.0, 0.1], [0.5, 0.0])
    b = pc.HenonHeilesSystem([0.0, 0.1], [0.5, 0.0])
    assert isinstance(a, pc.HamiltonianSystem)
    ra = a.integrate((0.0, 100.0), 0.01)  # yoshida4 by default, as the built-in; 1e4 steps
    rb = b.integrate((0.0, 100.0), 0.01)
    assert ra.method == rb.method == "yoshida4"
    # Not bit-identical by construction: the force is SymPy's H differentiated in Rust, whose
    # operation order (and the folding of -1/3 * 3) may differ from the hand-written force by
    # an ulp per evaluation; on this regular orbit (E = 0.13) that stays far below 1e-12
    # over 1e4 steps.
    assert np.max(np.abs(ra.y - rb.y)) < 1e-12
    assert np.max(np.abs(ra.energy - rb.energy)) < 1e-12
    # The energy is H: T + V of the same state, to rounding (two operation orders, a few
    # ulps of 0.13).
    assert a.energy(rb.y[-1]) == pytest.approx(b.energy(rb.y[-1]), rel=1e-14, abs=0)


def test_separability_is_detected_both_ways():
    q, p, m, k = sp.symbols("q p m k")
    sep = HamiltonianEngine([q], [p], p**2 / (2 * m) + k * q**4 / 4, params={"m": 4.0, "k": 2.0})
    assert sep.separable and sep.mass_inv.tolist() == [0.25]
    r = sep.system([1.0], [0.0]).integrate((0.0, 1.0), 0.01)
    assert r.method == "yoshida4"
    for H in [p**2 / 2 * (1 + q**2) + q**2 / 2,   # position-dependent mass
              sp.sqrt(1 + p**2) + q**2 / 2,       # relativistic: T not quadratic
              (p + q)**2 / 2]:                    # a term mixing q and p
        eng = HamiltonianEngine([q], [p], H)
        assert not eng.separable and eng.mass_inv is None
        s = eng.system([0.5], [0.2])
        assert s.integrate((0.0, 0.1), 0.01).method == "implicit_midpoint"
        with pytest.raises(ValueError, match="separable"):
            s.integrate((0.0, 0.1), 0.01, method="yoshida4")
        with pytest.raises(NotImplementedError, match="separable"):
            eng.force([0.5])
        with pytest.raises(NotImplementedError, match="separable"):
            eng.force_jacobian([0.5])


def test_non_separable_engine_conserves_its_energy_with_implicit_midpoint():
    # H = p^2 (1 + q^2)/2 + q^2/2: implicit midpoint's energy error stays bounded (symplectic)
    # at O(h^2) ~ 1e-5 here, while rk4's drifts; checked against H evaluated by SymPy.
    q, p = sp.symbols("q p")
    H = p**2 * (1 + q**2) / 2 + q**2 / 2
    s = HamiltonianEngine([q], [p], H).system([1.0], [0.5])
    e0 = float(H.subs({q: 1.0, p: 0.5}))
    assert s.energy() == pytest.approx(e0, rel=1e-15)
    r = s.integrate((0.0, 50.0), 0.01)
    assert np.max(np.abs(r.energy - e0)) < 1e-4


def _central_jacobian(f, y, h=1e-6):
    y = np.asarray(y, dtype=float)
    cols = []
    for j in range(len(y)):
        e = np.zeros_like(y)
        e[j] = h
        cols.append((f(y + e) - f(y - e)) / (2 * h))
    return np.array(cols).T


def test_jacobians_by_automatic_differentiation_match_central_differences():
    q1, q2, p1, p2 = sp.symbols("q1 q2 p1 p2")
    H = p1**2 / 2 + p2**2 / 2 * sp.exp(-q1) + sp.cos(q1 - q2) * p1 * p2 / 3 + q1**2 * q2**2
    eng = HamiltonianEngine([q1, q2], [p1, p2], H)
    assert not eng.separable
    rng = np.random.default_rng(3)
    for _ in range(5):
        y = rng.uniform(-1, 1, 4)
        J = eng.jacobian(0.0, y)
        Jn = _central_jacobian(lambda s: eng.derivatives(0.0, s), y)
        # Central differences of an O(1) smooth field: truncation h^2 ~ 1e-12, rounding
        # eps/h ~ 1e-10: 1e-7 fails only on a wrong derivative.
        assert J.shape == (4, 4) and np.max(np.abs(J - Jn)) < 1e-7
    hh = henon_heiles_engine()
    x, y = 0.3, -0.2
    # The force Jacobian against the hand-derived -Hessian of V: exact to rounding.
    expected = [[-1 - 2 * y, -2 * x], [-2 * x, -1 + 2 * y]]
    assert np.allclose(hh.force_jacobian([x, y]), expected, rtol=0, atol=1e-15)
    lor = lorenz_engine()
    for _ in range(5):
        y = rng.uniform(-20, 20, 3)
        J = lor.jacobian(0.0, y)
        exact = [[-10, 10, 0], [28 - y[2], -1, -y[0]], [y[1], y[0], -8 / 3]]
        # Products and differences only: AD is exact up to the rounding of 28 - z.
        assert np.allclose(J, exact, rtol=0, atol=1e-13)


def test_lorenz_matches_scipy_dop853_at_fourth_order():
    integrate = pytest.importorskip("scipy.integrate")
    y0 = [1.0, 1.0, 1.0]
    t_end = 1.0  # short: chaos amplifies any difference by e^(0.9 t)
    ref = integrate.solve_ivp(
        lambda t, s: [10 * (s[1] - s[0]), s[0] * (28 - s[2]) - s[1], s[0] * s[1] - 8 / 3 * s[2]],
        (0.0, t_end), y0, method="DOP853", rtol=1e-13, atol=1e-13,
    ).y[:, -1]
    errors = []
    for dt in (2e-3, 1e-3):
        s = lorenz_engine().system(y0)
        r = s.integrate((0.0, t_end), dt, method="rk4")
        assert r.energy is None  # no energy expression was given
        errors.append(np.max(np.abs(r.y[-1] - ref)))
    # rk4's global error at dt = 1e-3 is ~1e-9 of states of order 10 (DOP853 at 1e-13 is
    # exact by comparison); halving dt divides it by 2^4 = 16 (12-20 allows for the
    # asymptotic regime not being exact).
    assert errors[1] < 1e-7, errors
    assert 12 < errors[0] / errors[1] < 20, errors
    # implicit midpoint (the default) through its Newton solve on the AD Jacobian: second
    # order, so ~dt^2 * |f'''| ~ 1e-3 at dt = 1e-3.
    r = lorenz_engine().system(y0).integrate((0.0, t_end), 1e-3)
    assert r.method == "implicit_midpoint" and np.max(np.abs(r.y[-1] - ref)) < 1e-2


def test_ode_energy_expression_and_time_dependence():
    x, v, t, w = sp.symbols("x v t w")
    # A driven oscillator x'' = -w^2 x + cos(t): exercises t; energy v^2/2 + w^2 x^2/2.
    eng = ODEEngine([x, v], [v, -w**2 * x + sp.cos(t)], t=t, params={w: 2.0},
                    energy=v**2 / 2 + w**2 * x**2 / 2)
    s = eng.system([1.0, 0.0])
    assert s.energy() == 2.0
    assert eng.derivatives(0.5, [1.0, 0.0]).tolist() == [0.0, -4.0 + math.cos(0.5)]
    r = s.integrate((0.0, 1.0), 1e-3, method="rk4")
    # Exact solution with x(0)=1, v(0)=0: x = (1 - 1/3) cos 2t + cos(t)/3.
    assert r.y[-1, 0] == pytest.approx(2 / 3 * math.cos(2.0) + math.cos(1.0) / 3, abs=1e-10)
    assert r.energy is not None and r.energy[0] == 2.0
    assert np.isnan(lorenz_engine().system([1.0, 1.0, 1.0]).energy())


@pytest.mark.parametrize("build, match", [
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2 + sp.Symbol("k") * q**2), "symbol k"),
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2, params={"k": math.nan}), "params"),
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2, params={"k": 1j}), "params"),
    (lambda q, p: HamiltonianEngine([q], [], p**2 / 2), "p"),
    (lambda q, p: HamiltonianEngine([q], [p, q], p**2 / 2), "equal lengths"),
    (lambda q, p: HamiltonianEngine([q], [p], sp.besselj(0, q)), "cannot translate"),
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2, params=[1.0]), "params"),
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2).system([0.0, 1.0], [0.0]), "q0"),
    (lambda q, p: HamiltonianEngine([q], [p], p**2 / 2).system([0.0], [math.inf]), "p0"),
    (lambda q, p: ODEEngine([q, p], [p]), "f has length 1"),
    (lambda q, p: ODEEngine([q], [sp.Symbol("a") * q]), "symbol a"),
    (lambda q, p: ODEEngine([q], 3.0), "f must be a sequence"),
    (lambda q, p: ODEEngine([q], [q], params={"a": -math.inf}), "params"),
    (lambda q, p: ODEEngine([q], [q]).system([1.0, 2.0]), "y0"),
    (lambda q, p: ODEEngine([q], [q]).system([math.nan]), "y0"),
    (lambda q, p: ODEEngine([q], [q]).jacobian(0.0, [1.0, 2.0]), "state"),
    (lambda q, p: ODEEngine([q], [q], energy=sp.Symbol("E")), "symbol E"),
])
def test_hostile_engine_inputs_are_value_errors(build, match):
    q, p = sp.symbols("q p")
    with pytest.raises(ValueError, match=match):
        build(q, p)


def test_lorenz_example_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    example = Path(__file__).resolve().parents[1] / "examples" / "lorenz_sympy.py"
    runpy.run_path(str(example), run_name="lorenz_example")["main"](1.0)
    assert "final state" in capsys.readouterr().out


def test_theta_equilibrium_is_the_root_of_the_derivative_to_a_few_ulps():
    mpmath = pytest.importorskip("mpmath")
    th, p_phi, p_psi, I1, I3, Mgl = sp.symbols("theta p_phi p_psi I1 I3 Mgl")
    veff = (p_phi - p_psi * sp.cos(th))**2 / (2 * I1 * sp.sin(th)**2) \
        + p_psi**2 / (2 * I3) + Mgl * sp.cos(th)
    slope = sp.diff(veff, th)  # differentiated by SymPy, independently of the library
    mpmath.mp.dps = 50
    for args in [(8.775825618903728, 10.0, 1.0, 0.5, 9.81), (3.0, 4.0, 1.0, 0.5, 9.81),
                 (1.0, 20.0, 1.0, 2.0, 1.0), (5.0, 1.0, 1.0, 0.5, -3.0)]:
        got = pc.find_theta_equilibrium(*args)
        f = sp.lambdify(th, slope.subs(dict(zip((p_phi, p_psi, I1, I3, Mgl), args))), "mpmath")
        root = mpmath.findroot(f, mpmath.mpf(got))
        ulp = math.ulp(got)
        # Bisection of the float slope to adjacent floats: within a few ulps of the exact root
        # (the slope's own rounding, ~eps times its largest term over V_eff'', is ~1 ulp).
        assert abs(got - float(root)) <= 4 * ulp, (args, got, float(root))
