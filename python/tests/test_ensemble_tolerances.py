"""An adaptive method's tolerances in ``pc.ensemble``: ``rtol``/``atol``/``max_steps`` reach
every member (its bits are its own ``integrate_sampled`` with them; scipy's DOP853 at tighter
tolerances agrees with a ``taylor`` ensemble), and hostile values are a ``ValueError`` naming
the parameter, as ``integrate_sampled`` gives."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import physicskit.classical as pc

#: Kepler orbits from their elements (a = 1, k = mu = 1: period 2 pi), started at perihelion.
E = np.array([0.1, 0.4, 0.7])
T1 = 2 * 2 * np.pi
DT = 2 * np.pi / 64


def _kepler(**kw):
    return pc.ensemble("kepler", (0.0, T1), DT, kw.pop("method", "taylor"), sweep={"e": E}, **kw)


def _kepler_rhs(_t, y):
    q, p = y[:2], y[2:]
    r3 = np.hypot(*q) ** 3
    return np.concatenate([p, -q / r3])


def _scipy(e):
    # The closed form's start at perihelion: r = a (1 - e), speed sqrt((1 + e) / (1 - e)).
    y0 = [1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))]
    return solve_ivp(_kepler_rhs, (0.0, T1), y0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]


def test_a_taylor_ensemble_follows_scipy_dop853_at_its_tolerances():
    tight = _kepler(rtol=1e-12, atol=1e-12)
    loose = _kepler(rtol=1e-6, atol=1e-6)
    for i, e in enumerate(E):
        reference = _scipy(e)
        # The start is the closed form's (a wrong state would fail every bound below), to
        # 1e-15: a few roundings of 1 - e and the square root, each 1.1e-16 relative.
        start = pc.KeplerSystem.from_orbital_elements(1.0, float(e)).state
        assert np.allclose(start, [1.0 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))], rtol=1e-15)
        tight_error = np.max(np.abs(tight.final_state[i] - reference))
        loose_error = np.max(np.abs(loose.final_state[i] - reference))
        # Both runs meet 1e-12 and 1e-13 per step over two orbits: their states agree to a
        # global error of about 1e-11 (measured 4e-12 to 3.5e-11, growing with e); 1e-9
        # leaves a margin of about 30. The loose run's error (measured 6e-8 to 7e-6) is at
        # least 1.4e4 times the tight one's: 100 keeps a margin of over 100. Tolerances not
        # passed on would leave both runs at the defaults, the same bits: ratio 1.
        assert tight_error < 1e-9, (e, tight_error)
        assert loose_error > 100 * tight_error, (e, loose_error, tight_error)


@pytest.mark.parametrize("method", ["taylor", "dop853"])
def test_members_equal_their_own_integrate_sampled_with_the_same_tolerances(method):
    out = _kepler(method=method, rtol=1e-13, atol=1e-13, max_steps=100_000, stride=8)
    default = _kepler(method=method, stride=8)
    assert out.method == method
    assert not np.array_equal(out.final_state, default.final_state)
    for i, e in enumerate(E):
        alone = pc.KeplerSystem.from_orbital_elements(1.0, float(e)).integrate_sampled(
            (0.0, T1), DT, method, stride=8, rtol=1e-13, atol=1e-13, max_steps=100_000)
        assert np.array_equal(out.trajectory[i], alone.y)
        assert np.array_equal(out.final_state[i], alone.y[-1])


def test_a_step_budget_too_small_stops_the_run():
    with pytest.raises(pc.ConvergenceError, match="member 0: .*max_steps = 3"):
        _kepler(max_steps=3)


def test_threads_give_the_same_bits_at_given_tolerances():
    one = _kepler(rtol=1e-9, atol=1e-11, threads=1)
    two = _kepler(rtol=1e-9, atol=1e-11, threads=2)
    assert one.final_state.tobytes() == two.final_state.tobytes()


HOSTILE = [float("nan"), float("inf"), -float("inf"), 0.0, -1e-9, 1e-9 + 1j, 10**400, "1e-9",
           None.__class__, [1e-9]]


@pytest.mark.parametrize("name", ["rtol", "atol"])
@pytest.mark.parametrize("value", HOSTILE, ids=repr)
def test_hostile_tolerances_are_a_value_error_naming_the_parameter(name, value):
    with pytest.raises(ValueError, match=name):
        _kepler(**{name: value})


@pytest.mark.parametrize("value", [0, -1, 1.5, 3.0, "10", 1j, 10**400, True, float("nan")],
                         ids=repr)
def test_hostile_step_budgets_are_a_value_error_naming_the_parameter(value):
    with pytest.raises(ValueError, match="max_steps"):
        _kepler(max_steps=value)


@pytest.mark.parametrize("name", ["rtol", "atol", "max_steps"])
def test_a_fixed_step_method_takes_no_tolerances_as_integrate_sampled_says(name):
    value = 100 if name == "max_steps" else 1e-9
    with pytest.raises(ValueError) as alone:
        pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate_sampled(
            (0.0, T1), DT, "yoshida4", **{name: value})
    # Named, or Kepler's default method (yoshida4, fixed-step): the same message.
    for method in ["yoshida4", None]:
        with pytest.raises(ValueError, match=name) as err:
            _kepler(method=method, **{name: value})
        assert str(err.value) == str(alone.value)
