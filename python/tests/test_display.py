"""Rich display: ``repr(result)``, ``result._repr_html_()`` and the systems' reprs.

The HTML is parsed (``html.parser``, with a check that every element is closed in order) and
every number it claims is compared with one computed here from the result's arrays.
"""

from __future__ import annotations

import re
from html.parser import HTMLParser

import numpy as np
import pytest

import physicskit.classical as pc
from physicskit.classical import SimulationResult

from conftest import make_systems

# The card prints energy errors with 3 significant digits: a relative rounding of at most
# half a unit in the third digit, 5e-3.
THREE_DIGITS = 5e-3
# Times and dt are printed with 6 significant digits.
SIX_DIGITS = 5e-6

_VOID = {"br", "hr", "img", "input", "meta", "link", "col", "area", "base", "wbr", "source"}


class Card(HTMLParser):
    """Parses the card: checks nesting, collects table rows, SVG elements and all text."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack: list[str] = []
        self.errors: list[str] = []
        self.rows: dict[str, str] = {}
        self.tags: list[tuple[str, dict]] = []
        self._cell: list[str] | None = None
        self._th = ""
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag not in _VOID:
            self.stack.append(tag)
        if tag in ("th", "td"):
            self._cell = []

    def handle_startendtag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:] or 'nothing'}")
            return
        self.stack.pop()
        if tag == "th":
            self._th = "".join(self._cell or []).strip()
            self._cell = None
        elif tag == "td":
            if self._th:
                self.rows[self._th] = "".join(self._cell or []).strip()
            self._cell = None

    def handle_data(self, data):
        self.text.append(data)
        if self._cell is not None and "title" not in self.stack:
            self._cell.append(data)


def parse(card_html: str) -> Card:
    card = Card()
    card.feed(card_html)
    card.close()
    assert not card.errors, card.errors
    assert not card.stack, f"unclosed: {card.stack}"
    return card


def relative_energy_error(result) -> float:
    e = np.asarray(result.energy)
    return float(np.max(np.abs(e - e[0]) / abs(e[0])))


@pytest.fixture(scope="module")
def kepler_run():
    orbit = pc.KeplerSystem.from_orbital_elements(1.0, 0.6)
    return orbit.integrate((0.0, 20.0), 0.01, method="verlet")


def test_repr_is_a_short_summary(kepler_run):
    text = repr(kepler_run)
    assert text.startswith("SimulationResult(") and "\n" not in text
    assert "_SplitOnAccess" not in text and "array(" not in text
    # 2001 samples of 4 numbers: a wall of numbers would be >> 1000 characters.
    assert len(text) < 250, text
    assert "method='verlet'" in text and "steps=2000" in text and "y=(2001, 4)" in text
    shown = float(re.search(r"max relative energy error=([0-9.e+-]+)", text).group(1))
    assert shown == pytest.approx(relative_energy_error(kepler_run), rel=THREE_DIGITS)


def test_repr_does_not_split_q_and_p_off_y(kepler_run):
    fresh = pc.KeplerSystem.from_orbital_elements(1.0, 0.6).integrate((0.0, 1.0), 0.01)
    repr(fresh), fresh._repr_html_()
    assert fresh.__dict__.get("_q") is None and fresh.__dict__.get("_p") is None


def test_html_card_is_valid_and_its_numbers_are_the_results(kepler_run):
    card = parse(kepler_run._repr_html_())
    rows = card.rows
    assert rows["method"] == "verlet"
    assert int(rows["steps"]) == kepler_run.extra["n_steps"] == 2000
    assert float(rows["dt"]) == pytest.approx(kepler_run.extra["dt"], rel=SIX_DIGITS)
    t0, t1 = (float(x) for x in rows["t span"].strip("[]").split(","))
    assert (t0, t1) == (pytest.approx(kepler_run.t[0], abs=SIX_DIGITS),
                        pytest.approx(kepler_run.t[-1], rel=SIX_DIGITS))
    assert rows["samples"].split()[0] == str(len(kepler_run.t))
    for name in ("t", "y", "q", "p", "energy"):
        assert rows[f"{name} shape"] == str(getattr(kepler_run, name).shape)
    shown = float(rows["max relative energy error"])
    assert shown == pytest.approx(relative_energy_error(kepler_run), rel=THREE_DIGITS)


def test_sparkline_draws_the_energy_error(kepler_run):
    card = parse(kepler_run._repr_html_())
    svgs = [a for t, a in card.tags if t == "svg"]
    lines = [a for t, a in card.tags if t == "polyline"]
    assert len(svgs) == 1 and len(lines) == 1
    height = float(svgs[0]["height"])
    pts = np.array([[float(v) for v in p.split(",")] for p in lines[0]["points"].split()])
    # At most 120 points (bins of the 2001 samples), left to right.
    assert 2 <= len(pts) <= 120 and np.all(np.diff(pts[:, 0]) > 0)
    # Each point is a bin of samples: x at its first sample, y its largest error, from 0 at
    # the bottom to the run's largest error at the top (2 px padding). Recompute each bin's
    # maximum from the samples the x coordinates name; coordinates have 2 decimals.
    err = np.abs(kepler_run.energy - kepler_run.energy[0]) / abs(kepler_run.energy[0])
    width = float(svgs[0]["width"])
    starts = np.rint((pts[:, 0] - 2) * (len(err) - 1) / (width - 4)).astype(int)
    assert starts[0] == 0 and np.all(np.diff(starts) <= 17)  # ceil(2001 / 120)
    bins = np.maximum.reduceat(err, starts)
    np.testing.assert_allclose(pts[:, 1], height - 2 - (height - 4) * bins / err.max(),
                               atol=0.006)
    assert pts[:, 1].min() == pytest.approx(2.0, abs=0.006)


def test_card_escapes_what_it_shows():
    res = SimulationResult(t=np.linspace(0, 1, 5), y=np.zeros((5, 2)),
                           energy=np.ones(5), method="<script>alert(1)</script>&",
                           extra={"n_steps": 4.0, "dt": 0.25})
    card = parse(res._repr_html_())
    assert "script" not in [t for t, _ in card.tags]
    assert card.rows["method"] == "<script>alert(1)</script>&"


def test_zero_initial_energy_reports_the_absolute_error():
    e = np.array([0.0, 1e-9, -3e-9, 2e-9])
    res = SimulationResult(t=np.arange(4.0), y=np.zeros((4, 2)), energy=e, method="rk4")
    rows = parse(res._repr_html_()).rows
    assert float(rows["max absolute energy error"]) == pytest.approx(3e-9, rel=THREE_DIGITS)
    assert "max absolute energy error=3e-09" in repr(res)


def test_run_without_energy_says_so():
    res = pc.HenonHeilesSystem([0.1, 0.0], [0.0, 0.3]).integrate_sampled(
        (0.0, 1.0), 0.01, stride=10, energy=False)
    card = parse(res._repr_html_())
    assert card.rows["energy"] == "not stored"
    assert not [t for t, _ in card.tags if t == "svg"]
    assert card.rows["samples"] == "11 (every 10 steps)"
    assert "energy not stored" in repr(res)


def test_non_finite_energy_is_not_hidden():
    e = np.array([1.0, 1.0 + 1e-6, np.nan, np.nan])
    res = SimulationResult(t=np.arange(4.0), y=np.zeros((4, 2)), energy=e, method="rk4")
    card = parse(res._repr_html_())
    assert card.rows["max relative energy error"] == "nan"
    # The finite part is drawn, the blow-up marked in red.
    assert [a["fill"] for t, a in card.tags if t == "rect"] == ["#d62728"]


# -- systems -------------------------------------------------------------------------------

def test_every_built_in_system_shows_its_catalogue_parameters(system_name):
    system = make_systems()[system_name]()
    text = repr(system)
    assert text.startswith(f"{system_name}(") and text.endswith(")"), text
    assert "object at 0x" not in text and "\n" not in text
    for name, value in system._native.params.items():
        if value is not None:
            assert f"{name}=" in text, (name, text)
    # A long vector (the sine-Gordon chain's 40 sites) shows its ends and length only.
    assert len(text) < 600, text


def test_system_repr_values_round_trip():
    system = pc.DoublePendulum([2.0, 1.0], [0.5, -0.3], m2=0.25, g=1.5)
    text = repr(system)
    assert "theta0=[2.0, 1.0]" in text and "m2=0.25" in text and "g=1.5" in text
    # Evaluating it builds the same system.
    again = eval(text, {"DoublePendulum": pc.DoublePendulum})  # noqa: S307
    np.testing.assert_array_equal(again.state, system.state)
    assert (again.m2, again.g) == (0.25, 1.5)


def test_system_repr_shows_the_clock_once_it_moved():
    system = pc.BeadOnRotatingHoop(0.3, 0.5)
    system.integrate((0.0, 0.5), 0.01)
    assert "t=0.5" in repr(system) and "state=[" in repr(system)


def test_long_vectors_are_abbreviated():
    chain = pc.HarmonicChain(np.linspace(0.0, 1.0, 5000), np.zeros(5000))
    text = repr(chain)
    q0 = re.search(r"q0=\[(.*?)\] \(5000 values\)", text).group(1).split(", ")
    assert q0[3] == "..." and len(q0) == 7
    assert [float(v) for v in q0[:3] + q0[4:]] == [*chain.state[:3], *chain.state[4997:5000]]
    assert len(text) < 400


class Quartic(pc.HamiltonianSystem):
    def kinetic_energy(self, p):
        return 0.5 * float(p @ p)

    def potential_energy(self, q):
        return 0.25 * float(q[0] ** 4)

    def force(self, q, t=0.0):
        return -q**3


def test_user_subclass_repr_is_sensible():
    assert repr(Quartic([1.0], [0.0])) == "Quartic(ndof=1, t=0.0, state=[1.0, 0.0])"


def test_repr_of_a_broken_user_object_does_not_raise():
    system = Quartic([1.0], [0.0])
    system.state = object()
    assert repr(system).startswith("Quartic(")


def test_symbolic_system_and_engine_reprs():
    from conftest import sympy_double_pendulum

    engine = sympy_double_pendulum()
    assert repr(engine).startswith("LagrangianEngine(q=[theta1, theta2], qdot=[omega1, omega2]")
    text = repr(engine.system([0.1, 0.2], [0.0, 0.0]))
    assert text.startswith("SymbolicLagrangianSystem(L='") and "state=[0.1, 0.2, 0.0, 0.0]" in text
