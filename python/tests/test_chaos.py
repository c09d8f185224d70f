"""The chaos toolkit (``physicskit.classical.chaos``): Poincaré sections, Lyapunov spectra,
SALI/GALI and chaos maps, on built-in systems and on systems written in Python, checked
against an independent implementation (scipy's DOP853 on the variational equations)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import physicskit.classical as pc


def hh_at(e, x, y, px):
    """Hénon–Heiles at energy ``e`` from ``(x, y, px)``, ``py >= 0`` from the energy."""
    v = 0.5 * (x * x + y * y) + x * x * y - y**3 / 3.0
    return pc.HenonHeilesSystem([x, y], [px, np.sqrt(2.0 * (e - v) - px * px)])


#: A chaotic orbit at E = 1/6 (λ1 ≈ 0.15) and a regular one at E = 1/12.
CHAOTIC = (1.0 / 6.0, 0.0, 0.0, 0.1)
REGULAR = (1.0 / 12.0, 0.0, -0.1, 0.0)


def test_section_crossings_lie_on_the_energy_surface():
    # yoshida4 at dt = 0.002 keeps the energy to ~1e-13 (Rust test of the same orbit), and
    # each crossing is a step of the same method: 1e-12 is the bound.
    e0 = 1.0 / 8.0
    hh = hh_at(e0, 0.0, -0.2, 0.2)
    cut = pc.poincare_section(hh, (0.0, 100.0), 0.002, coordinate=1, value=0.0, direction=1)
    assert cut.y.shape == (len(cut.t), 4) and len(cut) > 10
    assert np.all(cut.y[:, 1] == 0.0) and np.all(cut.y[:, 3] > 0.0)
    energies = np.array([hh.energy(s) for s in cut.y])
    assert np.max(np.abs(energies - e0)) < 1e-12
    # The system continues from the end of the run, as after integrate.
    assert hh.t == 100.0


def test_section_times_of_a_python_oscillator():
    # A harmonic oscillator written in Python: x = cos t crosses x = 0 upwards at 3π/2 + 2πj.
    # rk4's phase error at dt = 0.01 over t = 20 is ~t dt^4 / 120 ~ 2e-9.
    class Oscillator(pc.HamiltonianSystem):
        def kinetic_energy(self, p):
            return 0.5 * float(p[0] ** 2)

        def potential_energy(self, q):
            return 0.5 * float(q[0] ** 2)

        def force(self, q, t):
            return -q

    osc = Oscillator([1.0], [0.0])
    cut = pc.poincare_section(osc, (0.0, 20.0), 0.01, coordinate=0, method="rk4")
    exact = 1.5 * np.pi + 2.0 * np.pi * np.arange(3)
    np.testing.assert_allclose(cut.t, exact, atol=1e-8)
    # The plane a·y = c with a = (1, 0): the same crossings.
    osc = Oscillator([1.0], [0.0])
    cut2 = pc.poincare_section(osc, (0.0, 20.0), 0.01, normal=[1.0, 0.0], method="rk4")
    np.testing.assert_allclose(cut2.t, cut.t, atol=1e-13)


def hh_variational(t, z):
    """Hénon–Heiles with one deviation vector: z = (x, y, px, py, dx, dy, dpx, dpy)."""
    x, y, px, py, dx, dy, dpx, dpy = z
    return [
        px, py, -x - 2.0 * x * y, -y - x * x + y * y,
        dpx, dpy, -(1.0 + 2.0 * y) * dx - 2.0 * x * dy, -2.0 * x * dx - (1.0 - 2.0 * y) * dy,
    ]


def reference_max_lyapunov(state, t_end, segment=10.0):
    """The largest exponent by Benettin's method on scipy's DOP853 (rtol 1e-12), the deviation
    renormalized every ``segment`` time units: an implementation independent of physicskit."""
    z = np.concatenate([state, np.ones(4) / 2.0])
    total = 0.0
    for i in range(int(round(t_end / segment))):
        sol = solve_ivp(hh_variational, (i * segment, (i + 1) * segment), z, method="DOP853",
                        rtol=1e-12, atol=1e-12)
        z = sol.y[:, -1]
        norm = np.linalg.norm(z[4:])
        total += np.log(norm)
        z[4:] /= norm
    return total / t_end


def test_max_lyapunov_matches_an_independent_implementation():
    # The check: within 5% at t = 1e4 (the two runs follow the chaotic orbit
    # differently after t ~ 200, so what agrees is the ergodic average over the chaotic sea,
    # to the few-percent spread of finite-time estimates).
    hh = hh_at(*CHAOTIC)
    state = hh.state.copy()
    ours = pc.max_lyapunov(hh, (0.0, 1e4), 0.01).exponents[0]
    theirs = reference_max_lyapunov(state, 1e4)
    assert ours > 0.05
    assert abs(ours - theirs) < 0.05 * theirs, (ours, theirs)


def test_spectrum_of_a_hamiltonian_system_sums_to_zero():
    # Splitting methods have an exact tangent map of determinant one: the sum is rounding
    # (1e-10 of the largest is the bound; measured ~1e-15 absolute).
    hh = hh_at(*CHAOTIC)
    s = pc.lyapunov_spectrum(hh, (0.0, 500.0), 0.01, renormalize_every=10)
    assert s.exponents.shape == (4,) and np.all(np.diff(s.exponents) <= 0)
    assert s.history.shape == (len(s.t), 4)
    assert np.all(np.abs(s.history.sum(axis=1)) < 1e-10 * s.exponents[0])


def test_python_subclass_with_and_without_its_jacobian():
    # A Python Hénon–Heiles: with force_jacobian the tangent map is the built-in one, so the
    # orbit and the exponent agree with the native system to rounding; without it, central
    # differences (relative error ~1e-10) change the exponent at the 1e-8 level over t = 50.
    class PyHH(pc.HamiltonianSystem):
        def kinetic_energy(self, p):
            return 0.5 * float(p @ p)

        def potential_energy(self, q):
            x, y = q
            return 0.5 * (x * x + y * y) + x * x * y - y**3 / 3.0

        def force(self, q, t):
            x, y = q
            return np.array([-x - 2.0 * x * y, -y - x * x + y * y])

    class PyHHJacobian(PyHH):
        def force_jacobian(self, q, t):
            x, y = q
            return np.array([[-1.0 - 2.0 * y, -2.0 * x], [-2.0 * x, -1.0 + 2.0 * y]])

    native = hh_at(*CHAOTIC)
    q, p = native.q.copy(), native.p.copy()
    expected = pc.max_lyapunov(native, (0.0, 50.0), 0.01).exponents[0]
    with_jac = pc.max_lyapunov(PyHHJacobian(q, p), (0.0, 50.0), 0.01).exponents[0]
    without = pc.max_lyapunov(PyHH(q, p), (0.0, 50.0), 0.01).exponents[0]
    assert abs(with_jac - expected) < 1e-12
    assert abs(without - expected) < 1e-6 * abs(expected)


def test_ode_spectrum_sums_to_the_divergence():
    # Lorenz in Python: the spectrum sums to the constant divergence -(σ + 1 + β) (Liouville),
    # to O(dt^4) of rk4's determinant and the Jacobian's rounding: 1e-6 relative.
    class Lorenz(pc.ODESystem):
        def derivatives(self, t, s):
            x, y, z = s
            return np.array([10.0 * (y - x), x * (28.0 - z) - y, x * y - 8.0 / 3.0 * z])

        def jacobian(self, t, s):
            x, y, z = s
            return np.array([[-10.0, 10.0, 0.0], [28.0 - z, -1.0, -x], [y, x, -8.0 / 3.0]])

        def energy(self, state=None):
            return 0.0

    s = pc.lyapunov_spectrum(Lorenz([1.0, 1.0, 20.0]), (0.0, 20.0), 0.005, method="rk4")
    divergence = -(10.0 + 1.0 + 8.0 / 3.0)
    assert abs(s.exponents.sum() - divergence) < 1e-6 * abs(divergence)


def test_sali_and_gali_classify_the_orbits():
    # The bounds at t = 1e3: chaotic SALI < 1e-8, regular > 1e-2; GALI_2 the same.
    chaotic = pc.sali(hh_at(*CHAOTIC), (0.0, 1e3), 0.01)
    regular = pc.sali(hh_at(*REGULAR), (0.0, 1e3), 0.01)
    assert chaotic.index[-1] < 1e-8 and chaotic.verdict == "chaotic"
    assert regular.index[len(regular.index) // 2:].min() > 1e-2 and regular.verdict == "regular"
    assert pc.chaos_verdict(chaotic) == "chaotic" and pc.chaos_verdict(regular.index) == "regular"
    assert pc.gali(hh_at(*CHAOTIC), (0.0, 1e3), 0.01, 2).verdict == "chaotic"
    assert pc.gali(hh_at(*REGULAR), (0.0, 1e3), 0.01, 2).verdict == "regular"


def test_chaos_map_from_states_and_from_a_function():
    e = 1.0 / 8.0
    ys = np.linspace(-0.3, 0.3, 5)
    states = np.array([[0.0, y, 0.0, np.sqrt(2 * (e - 0.5 * y * y + y**3 / 3))] for y in ys])
    hh = hh_at(*CHAOTIC)
    values = pc.chaos_map(hh, states, (0.0, 50.0), 0.01)
    assert values.shape == (5,) and np.all(np.isfinite(values))
    # A point's value is its orbit's, computed alone.
    alone = pc.HenonHeilesSystem(states[2, :2], states[2, 2:])
    assert values[2] == pc.max_lyapunov(alone, (0.0, 50.0), 0.01).exponents[0]
    # The same map from a function of the grid values.
    def make(y):
        return pc.HenonHeilesSystem([0.0, y], [0.0, np.sqrt(2 * (e - 0.5 * y * y + y**3 / 3))])
    np.testing.assert_array_equal(pc.chaos_map(make, ys, (0.0, 50.0), 0.01), values)
    crossings = pc.chaos_map(hh, states, (0.0, 50.0), 0.01, indicator="crossings",
                             coordinate=1)
    assert np.all(crossings >= 5)  # periods ~ 2π: about 8 upward crossings in t = 50


@pytest.mark.parametrize("call, match", [
    (lambda hh: pc.poincare_section(hh, (0, 1), 0.1), "coordinate"),
    (lambda hh: pc.poincare_section(hh, (0, 1), 0.1, coordinate=9), "coordinate"),
    (lambda hh: pc.poincare_section(hh, (0, 1), 0.1, coordinate=0, direction=2), "direction"),
    (lambda hh: pc.lyapunov_spectrum(hh, (0, 1), 0.1, n_exponents=5), "n_exponents"),
    (lambda hh: pc.gali(hh, (0, 1), 0.1, 1), "k"),
    (lambda hh: pc.sali(hh, (0, 1), 0.1, method="nope"), "method"),
    (lambda hh: pc.chaos_map(hh, [[0.0, 0.1, 0.2, 0.3]], (0, 1), 0.1, indicator="x"),
     "indicator"),
])
def test_bad_arguments_are_value_errors(call, match):
    hh = hh_at(*CHAOTIC)
    state = hh.state.copy()
    with pytest.raises(ValueError, match=match):
        call(hh)
    np.testing.assert_array_equal(hh.state, state)


def test_renormalize_every_defaults_are_the_cores():
    """The issue's signatures spell the default out (``renormalize_every=10``); it must be the
    core's ``DEFAULT_RENORMALIZE_EVERY``, which the CLI and the gallery use, in every
    function that takes it."""
    import inspect

    from physicskit import _core

    functions = [pc.lyapunov_spectrum, pc.max_lyapunov, pc.sali, pc.gali, pc.chaos_map,
                 pc.ensemble]
    for f in functions:
        default = inspect.signature(f).parameters["renormalize_every"].default
        assert default == _core.DEFAULT_RENORMALIZE_EVERY, f.__name__
