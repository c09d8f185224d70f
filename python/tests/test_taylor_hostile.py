"""Hostile input on the ``taylor`` paths: ``integrate_sampled(..., method="taylor")`` with
tolerances that are NaN, infinite, zero, negative, huge (1e300) or tighter than double precision
can hold, on a SymPy engine's system and on the catalogue's traced double pendulum; and
``poincare_section(..., method="taylor")`` with a bad span or output spacing. Each is a
``ValueError`` naming the parameter, raised before any long run; the tolerances that are
accepted but extreme (an ``atol`` far below rounding, a huge ``atol``) finish at once with the
order capped. Which methods need a Taylor form is read from ``methods()``."""

import math
import time

import numpy as np
import pytest

import physicskit.classical as pc

sp = pytest.importorskip("sympy")
from physicskit.classical.utils.symbolic import HamiltonianEngine  # noqa: E402

TAYLOR = [m["name"] for m in pc.methods() if m["needs_taylor_form"]]

# Every refusal below comes from checks made before the first step; a run that got past them
# into a long integration (the step budget is ten million) would take minutes, so ten seconds
# tells the two apart on a loaded machine.
PROMPT = 10.0


def kepler_system():
    """The Kepler orbit a = 1, e = 0.5 from perihelion, as a HamiltonianEngine system."""
    x, y, px, py = sp.symbols("x y p_x p_y")
    H = (px**2 + py**2) / 2 - 1 / sp.sqrt(x**2 + y**2)
    return HamiltonianEngine([x, y], [px, py], H).system([0.5, 0.0], [0.0, math.sqrt(3.0)])


def systems():
    return [kepler_system(), pc.DoublePendulum([1.0, 0.5], [0.0, 0.0])]


def refused(call, name):
    """``call()`` raises a ValueError whose message names ``name``, promptly."""
    start = time.monotonic()
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        call()
    assert time.monotonic() - start < PROMPT


# 1e-17 is below 2^-54 = 5.6e-17, the least relative rounding of any double; 1 and 1e300 ask
# for no correct digit.
BAD_RTOL = [math.nan, math.inf, -math.inf, 0.0, -1e-10, 1.0, 1e300, 1e-17]
BAD_ATOL = [math.nan, math.inf, -math.inf, 0.0, -1e-10]


@pytest.mark.parametrize("method", TAYLOR)
@pytest.mark.parametrize("rtol", BAD_RTOL)
def test_a_bad_rtol_is_refused_naming_it(method, rtol):
    for s in systems():
        refused(lambda: s.integrate_sampled((0.0, 1.0), 0.1, method, rtol=rtol), "rtol")


@pytest.mark.parametrize("method", TAYLOR)
@pytest.mark.parametrize("atol", BAD_ATOL)
def test_a_bad_atol_is_refused_naming_it(method, atol):
    for s in systems():
        refused(lambda: s.integrate_sampled((0.0, 1.0), 0.1, method, atol=atol), "atol")


@pytest.mark.parametrize("method", TAYLOR)
def test_extreme_accepted_tolerances_finish_with_the_order_capped(method):
    # atol = 1e-300 asks for an order far beyond the cap (ceil(-ln(1e-300)/2 + 1) = 347): the
    # run takes the highest order, 24, and reports it; atol = 1e300 leaves rtol in charge (the
    # order of rtol = atol = 1e-10). Both take a handful of steps over a sixth of an orbit;
    # neither may hang.
    at_rtol = kepler_system().integrate_sampled((0.0, 1.0), 0.5, method, rtol=1e-10, atol=1e-10)
    for atol, order in [(1e-300, 24), (1e300, at_rtol.extra["order"])]:
        start = time.monotonic()
        r = kepler_system().integrate_sampled((0.0, 1.0), 0.5, method, rtol=1e-10, atol=atol)
        assert time.monotonic() - start < PROMPT
        assert r.extra["order"] == order
        assert 0 < r.extra["steps"] < 100
        assert np.all(np.isfinite(r.y))


@pytest.mark.parametrize("method", TAYLOR)
@pytest.mark.parametrize("t_span", [(0.0, math.nan), (math.nan, 1.0), (0.0, math.inf),
                                    (-math.inf, 0.0)])
def test_a_section_with_a_bad_span_is_refused(method, t_span):
    for s in systems():
        refused(lambda: pc.poincare_section(s, t_span, 0.1, coordinate=0, method=method),
                "t_span")


@pytest.mark.parametrize("method", TAYLOR)
@pytest.mark.parametrize("dt", [math.nan, math.inf, 0.0, -0.1])
def test_a_section_with_a_bad_spacing_is_refused(method, dt):
    for s in systems():
        refused(lambda: pc.poincare_section(s, (0.0, 1.0), dt, coordinate=0, method=method),
                "dt")
