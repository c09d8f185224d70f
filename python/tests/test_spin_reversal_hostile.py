"""Hostile input to ``_core.spin_reversal_time(t, spin, window)``: complex numbers, ints too
large for a float, NaN and infinities, wrong lengths and shapes, uneven or backward times and
windows that are not positive or do not fit the record. Each is a ``ValueError`` naming the
parameter (never pyo3's ``TypeError`` or ``OverflowError``, never a panic); array-likes (lists,
tuples, integer arrays) are accepted, as every other function of the package accepts them.

The reversal times of valid input are checked against the zero of a linear spin, which the
sliding mean keeps exactly (the mean of a line over a window is its value at the centre).
Hypothesis runs derandomized, with few examples, so the file is reproducible and takes
seconds."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from physicskit import _core

SETTINGS = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)

T = np.linspace(0.0, 1.0, 101)
#: Turns at 0.5: the averaged spin of a line is the line, so its zero is 0.5.
SPIN = 0.5 - T


def refused(name, *args):
    """The call raises a ValueError whose message names `name` (in backticks, as every
    message of the package names a parameter)."""
    with pytest.raises(ValueError) as info:
        _core.spin_reversal_time(*args)
    assert f"`{name}`" in str(info.value), str(info.value)
    return str(info.value)


def test_a_linear_spin_turns_at_its_zero():
    # The window (10 samples) is centred on each mean; a line's mean is its centre value, so
    # the interpolated zero is the line's own, to rounding (1e-12: a few ulps of sums of 101
    # samples of size 1).
    assert abs(_core.spin_reversal_time(T, SPIN, 0.1) - 0.5) < 1e-12
    assert _core.spin_reversal_time(T, SPIN + 1.0, 0.1) is None


def test_array_likes_give_the_array_result():
    expected = _core.spin_reversal_time(T, SPIN)
    assert _core.spin_reversal_time(list(T), list(SPIN)) == expected
    assert _core.spin_reversal_time(tuple(T), tuple(SPIN)) == expected
    # Integer samples: the times 0..100 and an integer spin turning at 50.
    ticks = np.arange(101)
    assert _core.spin_reversal_time(ticks, 50 - ticks, 10) == pytest.approx(50.0, abs=1e-9)
    assert _core.spin_reversal_time(list(ticks), list(50 - ticks), np.int64(10)) == \
        pytest.approx(50.0, abs=1e-9)
    # A window given as a 0-d array or a numpy float is a number.
    assert _core.spin_reversal_time(T, SPIN, np.array(0.1)) == expected
    assert _core.spin_reversal_time(T, SPIN, np.float32(0.1)) == pytest.approx(expected)


@pytest.mark.parametrize("which", ["t", "spin"])
def test_complex_samples_are_refused(which):
    for convert in (lambda a: a + 0j, lambda a: list(a + 1j), lambda a: a.astype(np.complex64)):
        args = {"t": T, "spin": SPIN}
        args[which] = convert(args[which])
        assert "complex" in refused(which, args["t"], args["spin"])


@pytest.mark.parametrize("window", [1 + 1j, 0.1 + 0j, np.complex128(0.1)])
def test_a_complex_window_is_refused(window):
    assert "complex" in refused("window", T, SPIN, window)


def test_ints_too_large_for_a_float_are_refused():
    assert "too large" in refused("window", T, SPIN, 10**400)
    assert "too large" in refused("window", T, SPIN, -(10**400))
    huge = [10**400] + [0] * 100
    assert "too large" in refused("t", huge, SPIN)
    assert "too large" in refused("spin", T, huge)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_values_are_refused(bad):
    for which in ("t", "spin"):
        args = {"t": T.copy(), "spin": SPIN.copy()}
        args[which][37] = bad
        refused(which, args["t"], args["spin"])
    refused("window", T, SPIN, bad)


@pytest.mark.parametrize("window", [0.0, -0.0, -0.1, -1e300, 5e-324])
def test_windows_not_positive_or_shorter_than_a_sample_are_refused(window):
    refused("window", T, SPIN, window)


@pytest.mark.parametrize("window", [1.02, 2.0, 1e300])
def test_windows_longer_than_the_record_are_refused(window):
    refused("window", T, SPIN, window)


def test_a_window_of_the_whole_record_has_one_mean_and_no_zero():
    # One window, one mean: no sign change to find.
    assert _core.spin_reversal_time(T, SPIN, 1.0) is None


@pytest.mark.parametrize("window", [True, "0.1", [0.1], None, object()])
def test_windows_that_are_not_numbers_are_refused(window):
    refused("window", T, SPIN, window)


def test_wrong_lengths_and_shapes_are_refused():
    refused("spin", T, SPIN[:-1])
    refused("spin", T[:-1], SPIN)
    refused("t", T[:1], SPIN[:1])
    refused("t", [], [])
    refused("t", T.reshape(1, -1), SPIN)
    refused("spin", T, SPIN.reshape(-1, 1))
    refused("t", "0 1 2", SPIN)
    refused("t", [True] * 101, SPIN)


def test_backward_or_uneven_times_are_refused():
    refused("t", T[::-1], SPIN)
    refused("t", np.zeros(101), SPIN)
    uneven = T.copy()
    uneven[50] += 1e-3
    refused("t", uneven, SPIN)
    skipped = np.delete(T, 50)
    refused("t", skipped, np.delete(SPIN, 50))


@SETTINGS
@given(
    t=st.lists(st.floats(allow_nan=True, allow_infinity=True) | st.integers(), max_size=12)
    | st.lists(st.complex_numbers(), min_size=1, max_size=12),
    spin=st.lists(st.floats(allow_nan=True, allow_infinity=True) | st.integers(), max_size=12),
    window=st.floats(allow_nan=True, allow_infinity=True)
    | st.integers()
    | st.complex_numbers()
    | st.booleans(),
)
def test_any_input_is_a_result_or_a_named_value_error(t, spin, window):
    # Whatever arrives: a number or None (a valid call), or a ValueError naming one of the
    # three parameters. A TypeError, an OverflowError or a panic fails the test.
    try:
        out = _core.spin_reversal_time(t, spin, window)
    except ValueError as e:
        assert any(f"`{name}`" in str(e) for name in ("t", "spin", "window")), str(e)
    else:
        assert out is None or np.isfinite(out)
