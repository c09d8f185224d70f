"""The chaos toolkit's plots (``plot_lyapunov``, ``plot_sali``, ``plot_chaos_map``) under Agg,
on real results of ``physicskit.classical.chaos``: the lines, meshes and colour bars drawn, their
labels and units, and that the drawn numbers are the library's (history, index, threshold, map
values on the user's grid)."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import physicskit.classical as pc  # noqa: E402
from physicskit.classical import plotting as pl  # noqa: E402

from test_plotting import assert_drawn  # noqa: E402

#: Hénon–Heiles energies: E = 1/6 has a wide chaotic sea, E = 1/12 is almost all tori.
E_CHAOTIC, E_REGULAR = 1.0 / 6.0, 1.0 / 12.0


def section_state(e, y, py):
    """The Hénon–Heiles state at energy ``e`` on the section ``x = 0`` at ``(y, p_y)``,
    ``p_x >= 0`` from the energy (NaN outside the energy surface)."""
    px2 = 2.0 * e - py * py - y * y + 2.0 * y**3 / 3.0
    return np.array([0.0, y, np.sqrt(px2) if px2 >= 0 else np.nan, py])


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
    chaotic = pc.HenonHeilesSystem([0.0, 0.0], [0.1, np.sqrt(2 * E_CHAOTIC - 0.01)])
    regular = pc.HenonHeilesSystem([0.0, -0.1], [0.0, np.sqrt(2 * E_REGULAR - 0.01
                                                              - 2 * 0.001 / 3)])
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
    assert threshold.get_linestyle() == "--" and "1e-08" in threshold.get_label()
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
    values[inside] = pc.chaos_map(pc.HenonHeilesSystem([0, 0], [0, 0]), states[inside],
                                  (0.0, 300.0), 0.02, indicator="sali")
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


@pytest.mark.parametrize("call, match", [
    (lambda: pl.plot_chaos_map(np.zeros(5), [0, 1], [0, 1]), "shape"),
    (lambda: pl.plot_chaos_map(np.zeros(4), [0, 1], [0, 1], indicator="x"), "indicator"),
    (lambda: pl.plot_chaos_map(np.zeros(4), [0, 1], [0, 1], components=(0, 1)), "system"),
    (lambda: pl.plot_chaos_map(np.zeros(4), [0, 1], [0, 1], components=(0, 9),
                               system=pc.HenonHeilesSystem([0, 0], [0, 0])), "out of range"),
    (lambda: pl.plot_chaos_map(np.zeros(4), [0, 1], [0, 1], components=(True, 1),
                               system=pc.HenonHeilesSystem([0, 0], [0, 0])), "components"),
    (lambda: pl.plot_chaos_map(np.full(4, np.nan), [0, 1], [0, 1]), "finite"),
    (lambda: pl.plot_chaos_map(np.zeros(2), [[0, 1]]), "1-D"),
    (lambda: pl.plot_lyapunov(np.zeros(3)), "LyapunovSpectrum"),
    (lambda: pl.plot_sali([]), "AlignmentIndex"),
])
def test_bad_inputs_are_value_errors(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_lyapunov_refuses_a_bad_scale_and_label_count(alignment):
    spectrum = pc.max_lyapunov(hh_on_section(E_REGULAR, 0.1, 0.0), (0.0, 1.0), 0.1)
    with pytest.raises(ValueError, match="yscale"):
        pl.plot_lyapunov(spectrum, yscale="symlog")
    with pytest.raises(ValueError, match="labels"):
        pl.plot_sali(list(alignment), labels=["one"])
