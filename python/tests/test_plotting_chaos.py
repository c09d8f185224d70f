"""The chaos toolkit's plots (``plot_lyapunov``, ``plot_sali``, ``plot_chaos_map``) under Agg,
on real results of ``physicskit.classical.chaos``: the lines, meshes and colour bars drawn, their
labels and units, and that the drawn numbers are the library's (history, index, threshold, map
values on the user's grid)."""

from __future__ import annotations

import traceback
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import physicskit.classical as pc  # noqa: E402
from physicskit.classical import plotting as pl  # noqa: E402
from physicskit.classical.chaos import AlignmentIndex, LyapunovSpectrum  # noqa: E402

from test_plotting import assert_drawn  # noqa: E402

#: Hénon–Heiles energies: E = 1/6 has a wide chaotic sea, E = 1/12 is almost all tori.
E_CHAOTIC, E_REGULAR = 1.0 / 6.0, 1.0 / 12.0
HH = pc.HenonHeilesSystem([0.0, 0.0], [0.0, 0.0])


def at_energy(e, q, p, solve):
    """The Hénon–Heiles state at ``(q, p)`` whose momentum ``p[solve] >= 0`` gives it the
    energy ``e``, from the system's own ``V`` and ``T``: with ``T = |p|^2 / 2`` that momentum
    carries ``e - V(q) - T(the others)`` (NaN outside the energy surface)."""
    p = np.array(p, dtype=float)
    p[solve] = 0.0
    rest = HH.potential_energy(q) + HH.kinetic_energy(p)
    p[solve] = np.sqrt(2.0 * (e - rest)) if e >= rest else np.nan
    return np.concatenate([np.asarray(q, dtype=float), p])


def section_state(e, y, py):
    """The state at energy ``e`` on the section ``x = 0`` at ``(y, p_y)``, ``p_x >= 0``."""
    return at_energy(e, [0.0, y], [0.0, py], solve=0)


def hh_on_section(e, y, py):
    state = section_state(e, y, py)
    return pc.HenonHeilesSystem(state[:2], state[2:])


def assert_drawn_on_log_axis(drawn, values):
    """``drawn`` is ``values`` where they are positive, NaN (not drawn) where not."""
    np.testing.assert_array_equal(np.isnan(drawn), ~(values > 0))
    np.testing.assert_array_equal(drawn[values > 0], values[values > 0])


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def alignment():
    # The chaotic and regular orbits of test_chaos.py: SALI at t = 1e3 below 1e-8 and above
    # 1e-2 (so the verdicts, which the labels show, are not borderline).
    chaotic, regular = (pc.HenonHeilesSystem(s[:2], s[2:]) for s in (
        at_energy(E_CHAOTIC, [0.0, 0.0], [0.1, 0.0], solve=1),
        at_energy(E_REGULAR, [0.0, -0.1], [0.0, 0.0], solve=1)))
    return (pc.sali(chaotic, (0.0, 1e3), 0.01, history_stride=10),
            pc.sali(regular, (0.0, 1e3), 0.01, history_stride=10),
            pc.gali(regular, (0.0, 1e3), 0.01, 3, history_stride=10))


def test_lyapunov_lines_are_the_running_estimates_with_units():
    # A double pendulum (time in s): units 1/s. 400 steps of the implicit midpoint rule.
    system = pc.DoublePendulum([2.0, 2.5], [0.0, 0.0])
    spectrum = pc.lyapunov_spectrum(system, (0.0, 2.0), 0.005)
    fig, ax = plt.subplots()
    lines = pl.plot_lyapunov(spectrum, system, ax=ax)
    assert_drawn(fig)
    assert len(lines) == 4 and ax.get_xscale() == "log" and ax.get_yscale() == "linear"
    shown = spectrum.t > 0
    for j, line in enumerate(lines):
        np.testing.assert_array_equal(line.get_xdata(), spectrum.t[shown])
        np.testing.assert_array_equal(line.get_ydata(), spectrum.history[shown, j])
    assert ax.get_xlabel() == "$t$ (s)" and ax.get_ylabel().endswith("(1/s)")
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[0] == rf"$\lambda_{{1}}$ = {spectrum.history[-1, 0]:.3g}" and len(texts) == 4


def test_lyapunov_of_two_orbits_on_a_log_axis():
    runs = [pc.max_lyapunov(hh_on_section(e, 0.1, 0.0), (0.0, 200.0), 0.02)
            for e in (E_CHAOTIC, E_REGULAR)]
    lines = pl.plot_lyapunov(runs, labels=["E = 1/6", "E = 1/12"], yscale="log")
    assert len(lines) == 2 and lines[0].axes.get_yscale() == "log"
    assert [ln.get_label().split(":")[0] for ln in lines] == ["E = 1/6", "E = 1/12"]
    # Non-positive estimates are not drawn on the log axis (NaN), the others unchanged.
    assert_drawn_on_log_axis(lines[1].get_ydata(), runs[1].history[runs[1].t > 0, 0])
    assert "(time units)" in lines[0].axes.get_xlabel()  # no system given: generic unit


def test_sali_and_gali_against_the_library_threshold(alignment):
    chaotic, regular, gali3 = alignment
    fig, ax = plt.subplots()
    lines = pl.plot_sali([chaotic, regular, gali3], ax=ax)
    assert_drawn(fig)
    assert len(lines) == 4 and ax.get_xscale() == ax.get_yscale() == "log"
    for line, run in zip(lines, alignment):
        # The chaotic orbit's SALI reaches exactly 0 (vectors aligned to rounding): not drawn.
        assert_drawn_on_log_axis(line.get_ydata(), run.index[run.t > 0])
    assert np.any(chaotic.index == 0.0)
    # The threshold is the library's constant, dashed, labelled with its value.
    threshold = lines[-1]
    assert list(threshold.get_ydata()) == [pc.CHAOS_THRESHOLD] * 2
    assert threshold.get_linestyle() == "--"
    assert f"({pc.CHAOS_THRESHOLD:g})" in threshold.get_label()
    assert [ln.get_label() for ln in lines[:3]] == [
        "SALI (chaotic)", "SALI (regular)", "GALI$_{3}$ (regular)"]
    assert ax.get_ylabel() == "alignment index"  # SALI and GALI mixed
    # The chaotic orbit's drawn index crosses the threshold, the regular one's does not.
    assert np.nanmin(lines[0].get_ydata()) < pc.CHAOS_THRESHOLD < np.nanmin(lines[1].get_ydata())
    only = pl.plot_sali(chaotic, threshold=False, labels=["chaotic orbit"])
    assert len(only) == 1 and only[0].axes.get_ylabel() == "SALI"


@pytest.fixture(scope="module")
def section_map():
    """A 6 x 5 SALI map of the section x = 0 at E = 1/6 over (y, p_y), computed by the
    library on the points inside the energy surface (NaN outside)."""
    ys, pys = np.linspace(-0.35, 0.6, 6), np.linspace(-0.5, 0.5, 5)
    yy, pp = np.meshgrid(ys, pys)
    states = np.array([section_state(E_CHAOTIC, y, py) for y, py in zip(yy.ravel(), pp.ravel())])
    inside = np.isfinite(states).all(axis=1)
    values = np.full(len(states), np.nan)
    values[inside] = pc.chaos_map(HH, states[inside], (0.0, 300.0), 0.02, indicator="sali")
    return ys, pys, values, inside


def test_chaos_map_mesh_is_the_library_values_on_the_grid(section_map):
    ys, pys, values, inside = section_map
    assert 0 < inside.sum() < len(inside)  # some points lie outside the energy surface
    system = hh_on_section(E_CHAOTIC, 0.0, 0.0)
    fig, ax = plt.subplots()
    mesh = pl.plot_chaos_map(values, ys, pys, indicator="sali", system=system,
                             components=(1, 3), ax=ax)
    assert_drawn(fig)
    drawn = mesh.get_array().reshape(len(pys), len(ys))
    np.testing.assert_array_equal(drawn.mask, ~inside.reshape(drawn.shape))
    np.testing.assert_array_equal(drawn[~drawn.mask], values[inside])
    assert ax.get_xlabel() == "$y$ (dimensionless)"
    assert ax.get_ylabel() == "$p_y$ (dimensionless)"
    bar = mesh.colorbar
    assert bar is not None and bar.ax.get_ylabel() == "SALI" and bar.ax.get_yscale() == "log"
    assert len(fig.axes) == 2
    # The map holds chaotic (SALI ~ 1e-14) and regular (SALI ~ 1e-2) orbits: the library's
    # threshold between them is marked on the colour bar.
    finite = values[inside]
    assert finite.min() < pc.CHAOS_THRESHOLD < finite.max()
    assert [list(ln.get_ydata()) for ln in bar.ax.lines] == [[pc.CHAOS_THRESHOLD] * 2]


def test_chaos_map_of_a_function_grid_with_given_labels():
    # The largest exponent of the double pendulum from rest, over its two initial angles.
    th1, th2 = np.linspace(0.5, 2.5, 4), np.linspace(-1.0, 1.0, 3)
    aa, bb = np.meshgrid(th1, th2)
    values = pc.chaos_map(lambda a, b: pc.DoublePendulum([a, b], [0.0, 0.0]),
                          np.column_stack([aa.ravel(), bb.ravel()]), (0.0, 1.0), 0.005)
    system = pc.DoublePendulum([1.0, 0.0], [0.0, 0.0])
    mesh = pl.plot_chaos_map(values.reshape(3, 4), th1, th2, system=system,
                             xlabel=r"$\theta_1(0)$ (rad)", ylabel=r"$\theta_2(0)$ (rad)")
    ax = mesh.axes
    np.testing.assert_array_equal(mesh.get_array().reshape(3, 4), values.reshape(3, 4))
    assert ax.get_xlabel() == r"$\theta_1(0)$ (rad)" and ax.get_ylabel() == r"$\theta_2(0)$ (rad)"
    assert mesh.colorbar.ax.get_ylabel() == r"largest exponent $\lambda_1$ (1/s)"
    assert mesh.colorbar.ax.get_yscale() == "linear"


def test_one_dimensional_chaos_map_is_a_line(section_map):
    ys, _, values, inside = section_map
    row = values[:len(ys)]  # p_y = -0.5, meshgrid order: the first row
    line = pl.plot_chaos_map(row, ys, indicator="sali", xlabel="$y$ at $x = 0$")
    np.testing.assert_array_equal(line.get_xdata(), ys)
    ax = line.axes
    assert ax.get_yscale() == "log" and ax.get_ylabel() == "SALI"
    assert [list(ln.get_ydata()) for ln in ax.lines[1:]] == [[pc.CHAOS_THRESHOLD] * 2]


# -- hostile input: small hand-made results and maps, each refused before anything is drawn --

T3 = np.array([0.0, 1.0, 2.0])
HISTORY = np.array([[0.0, 0.0], [0.5, -0.5], [0.3, -0.3]])
INDEX = np.array([1.4, 0.5, 1e-9])
X, Y = np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0])
MAP = np.arange(1.0, 7.0).reshape(2, 3)


def lyapunov(t=T3, history=HISTORY, **kw):
    return pl.plot_lyapunov(LyapunovSpectrum(np.zeros(2), t, history), **kw)


def sali(t=T3, index=INDEX, **kw):
    return pl.plot_sali(AlignmentIndex(t, index, "chaotic"), **kw)


def chaos_map(values=MAP, x=X, y=Y, **kw):
    return pl.plot_chaos_map(values, x, y, **kw)


def test_the_hand_made_inputs_draw():
    # The hostile cases below each change one thing of these calls, which are good.
    for lines in (lyapunov(), lyapunov(yscale="log"), sali(), sali(threshold=False)):
        assert_drawn(lines[0].figure)
    assert_drawn(chaos_map(log=True, cmap="viridis", xlabel="a", ylabel="b").figure)
    assert_drawn(chaos_map(MAP[0], y=None, components=1, system=HH).figure)


#: Entries that are not a finite real number (NaN is a map's "not computed": not for values).
BAD_ENTRIES = [np.nan, np.inf, -np.inf, 1j, 10**400, "a"]
#: Arrays whose dtype is not real numbers.
BAD_DTYPES = [MAP.astype(complex), MAP > 3, MAP.astype(str),
              np.array([[1, 2, 3], [4, 5, 10**400]], dtype=object)]

HOSTILE = [
    *[(lambda b=b: lyapunov(t=[0.0, 1.0, b]), "spectra.t") for b in BAD_ENTRIES],
    *[(lambda b=b: lyapunov(history=[[0, 0], [0.5, -0.5], [0.3, b]]), "spectra.history")
      for b in BAD_ENTRIES],
    *[(lambda b=b: sali(t=[0.0, 1.0, b]), "indices.t") for b in BAD_ENTRIES],
    *[(lambda b=b: sali(index=[1.4, 0.5, b]), "indices.index") for b in BAD_ENTRIES],
    *[(lambda b=b: chaos_map(values=[[1, 2, 3], [4, 5, b]]), "values") for b in BAD_ENTRIES
      if b is not np.nan],
    *[(lambda b=b: chaos_map(x=[0, 1, b]), "x") for b in BAD_ENTRIES],
    *[(lambda b=b: chaos_map(y=[0, b]), "y") for b in BAD_ENTRIES],
    *[(lambda b=b: chaos_map(values=b), "values") for b in BAD_DTYPES],
    *[(lambda b=b: lyapunov(history=np.resize(b, (3, 2))), "spectra.history")
      for b in BAD_DTYPES],
    *[(lambda b=b: sali(index=b[-1]), "indices.index") for b in BAD_DTYPES],
    # wrong shapes and empty runs, maps and grids
    (lambda: lyapunov(history=HISTORY[:2]), r"spectra.history has shape \(2, 2\) for 3"),
    (lambda: lyapunov(history=np.zeros((3, 2, 1))), "spectra.history"),
    (lambda: lyapunov(t=[T3]), "spectra.t"),
    (lambda: lyapunov(t=[], history=np.zeros((0, 2))), "spectra has no sample after t = 0"),
    (lambda: sali(index=INDEX[:2]), "indices.index"),
    (lambda: sali(index=INDEX[:, None]), "indices.index"),
    (lambda: sali(t=[0.0], index=[1.0]), "indices has no sample after t = 0"),
    (lambda: chaos_map(values=MAP.T), r"\(3, 2\).*\(2, 3\).*transposed"),
    (lambda: chaos_map(values=np.zeros(5)), r"values has shape \(5,\)"),
    (lambda: chaos_map(values=[]), "values"),
    (lambda: chaos_map(values=MAP[None]), "values"),
    (lambda: chaos_map(values=MAP, y=None), r"values has shape \(2, 3\).*\(3,\)"),
    (lambda: chaos_map(values=np.full((2, 3), np.nan)), "values has no finite entry"),
    (lambda: chaos_map(values=np.zeros((2, 3)), log=True), "values has no positive entry"),
    (lambda: chaos_map(values=np.zeros(3), y=None, indicator="sali"), "no positive entry"),
    (lambda: chaos_map(x=[]), "x is empty"),
    (lambda: chaos_map(x=[X]), "x must be one-dimensional"),
    (lambda: chaos_map(x=[0.0, 2.0, 1.0]), "x must be strictly"),
    (lambda: chaos_map(y=[1.0, 1.0]), "y must be strictly"),
    (lambda: pl.plot_lyapunov(np.zeros(3)), "LyapunovSpectrum"),
    (lambda: pl.plot_lyapunov([]), "LyapunovSpectrum"),
    (lambda: pl.plot_sali([]), "AlignmentIndex"),
    (lambda: pl.plot_sali(object()), "AlignmentIndex"),
    # options: strings and flags are not numbers, numbers not flags (threshold=1 is refused)
    *[(lambda b=b: lyapunov(labels=b), "labels") for b in ("ab", ["a", "b"], [1], 5, [None])],
    *[(lambda b=b: sali(labels=b), "labels") for b in ("a", [], [b"a"])],
    *[(lambda b=b: lyapunov(yscale=b), "yscale")
      for b in ("symlog", 1, None, np.array(["log"]))],
    *[(lambda b=b: sali(threshold=b), "threshold")
      for b in (1, 0, "yes", None, np.array([True, False]), 1.0)],
    *[(lambda b=b: chaos_map(indicator=b), "indicator") for b in ("x", 1, None, ["sali"])],
    *[(lambda b=b: chaos_map(log=b), "log") for b in (1, "yes", np.array([True]))],
    *[(lambda b=b: chaos_map(components=b, system=HH), "components")
      for b in ((True, 1), (0, 9), (0.0, 1), (2**64, 1), (1j, 0), (0, 1, 2), (-1, 0), (),
                [[0, 1]], np.array([0.5, 1.0]), "ab")],
    (lambda: chaos_map(MAP[0], y=None, components=(1, 3), system=HH), "components"),
    (lambda: chaos_map(components=(0, 1)), "system"),
    (lambda: chaos_map(components=(0, 1), system=object()), "system"),
    (lambda: chaos_map(xlabel=1), "xlabel"),
    (lambda: chaos_map(ylabel=b"y"), "ylabel"),
    *[(lambda b=b: chaos_map(cmap=b), "cmap") for b in ("no-such-map", 3, ["magma"])],
]


@pytest.mark.parametrize("call, match", HOSTILE, ids=[f"{m}-{i}" for i, (_, m) in
                                                       enumerate(HOSTILE)])
def test_hostile_input_is_a_value_error_from_physicskit(call, match):
    # A ValueError naming what is wrong, raised by physicskit's own checks: never a numpy or
    # matplotlib error (or warning: warnings are errors here) from inside the drawing.
    with pytest.raises(ValueError, match=match) as info:
        call()
    raised_in = Path(traceback.extract_tb(info.tb)[-1].filename).resolve()
    assert Path(pc.__file__).resolve().parent in raised_in.parents, raised_in
    assert not plt.get_fignums()  # refused before a figure was made


def test_an_index_of_zero_throughout_is_said_or_refused():
    # A strongly chaotic orbit's SALI can be exactly 0 (vectors aligned to the last bit) from
    # the first renormalization on: a log axis cannot show it.
    zero = AlignmentIndex(T3, np.array([1.4, 0.0, 0.0]), "chaotic")
    for threshold in (True, False):  # the threshold alone would be an empty plot
        with pytest.raises(ValueError, match="no index is positive after t = 0"):
            pl.plot_sali(zero, threshold=threshold)
    lines = pl.plot_sali([zero, AlignmentIndex(T3, INDEX, "chaotic")])
    assert lines[0].get_label() == "SALI (chaotic) (0 after t = 0: not drawn)"
    assert np.all(np.isnan(lines[0].get_ydata()))
    assert lines[1].get_label() == "SALI (chaotic)"
    assert_drawn(lines[0].figure)
    with pytest.raises(ValueError, match="no running estimate is positive"):
        lyapunov(history=-np.abs(HISTORY), yscale="log")
