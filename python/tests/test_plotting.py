"""physicskit.classical.plotting under the Agg backend, on real runs of each family.

Each figure is checked for content (a canvas that is not blank, the number of lines /
collections / points drawn, axis labels with units) and, where the plot shows a number the
library computes (modal energies, the phase-space area, the LRL vector, |L|), that the drawn
data are those numbers. Animations: the requested number of frames, and a GIF that reopens
with that many frames.
"""

from __future__ import annotations

import subprocess
import sys

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402

import physicskit.classical as pc  # noqa: E402
from physicskit.classical import plotting as pl  # noqa: E402

from conftest import make_systems  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def assert_drawn(fig):
    """The rendered canvas is not blank: its pixels vary (a blank figure is uniform white)."""
    fig.canvas.draw()
    pixels = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(float)
    # A figure with axes, ticks and one line has a standard deviation of tens of grey levels;
    # 5 is far above a blank canvas's 0 and below any real plot.
    assert pixels.std() > 5.0


def test_import_of_the_package_does_not_load_matplotlib():
    code = "import sys, physicskit.classical; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_missing_matplotlib_names_the_extra():
    code = (
        "import sys\n"
        "class Block:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name.split('.')[0] == 'matplotlib':\n"
        "            raise ImportError('no ' + name)\n"
        "sys.meta_path.insert(0, Block())\n"
        "import physicskit.classical as pc\n"
        "r = pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate((0, 1), 0.1)\n"
        "for f in (lambda: __import__('physicskit.classical.plotting'), r.plot):\n"
        "    try:\n"
        "        f()\n"
        "    except ImportError as e:\n"
        "        print(e)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    lines = out.stdout.strip().splitlines()
    assert len(lines) == 2 and all("pip install physicskit[plot]" in line for line in lines)


@pytest.fixture(scope="module")
def double():
    sys_ = pc.DoublePendulum([2.0, 2.5], [0.0, 0.0])
    return sys_, sys_.integrate((0, 2), 0.01)


def test_result_plot_has_q_p_and_energy_error_with_units(double):
    system, result = double
    fig = result.plot(system)
    assert_drawn(fig)
    a_q, a_p, a_e = fig.axes
    assert [len(a.lines) for a in fig.axes] == [2, 2, 1]
    np.testing.assert_array_equal(a_q.lines[1].get_ydata(), result.q[:, 1])
    # The system's own symbols and units, from its catalogue entry; the method in words.
    assert a_q.get_ylabel() == r"$\theta_1$, $\theta_2$ (rad)"
    assert a_p.get_ylabel() == r"$\dot{\theta_1}$, $\dot{\theta_2}$ (rad/s)"
    assert a_q.get_title() == "implicit midpoint"
    assert a_e.get_yscale() == "log" and a_e.get_xlabel() == "$t$ (s)"
    err = a_e.lines[0].get_ydata()
    expected = np.abs(result.energy - result.energy[0]) / abs(result.energy[0])
    np.testing.assert_array_equal(err[1:][expected[1:] > 0], expected[1:][expected[1:] > 0])


def test_result_plot_of_an_ode_run_has_state_and_energy():
    top = pc.EulerTop([0.01, 1.0, 0.01])
    fig = top.integrate((0, 1), 0.01).plot(top)
    assert_drawn(fig)
    assert [len(a.lines) for a in fig.axes] == [3, 1]  # the body rates, not the quaternion
    assert fig.axes[0].get_ylabel() == r"body $\omega$ (rad/s)"


def test_result_plot_without_system_and_in_given_axes(double):
    _, result = double
    fig, axes = plt.subplots(3)
    assert pl.plot_result(result, ax=axes) is fig
    assert "state units" in axes[0].get_ylabel()
    with pytest.raises(ValueError, match="3 axes"):
        pl.plot_result(result, ax=axes[:2])


def test_energy_error_compares_methods():
    kep = pc.KeplerSystem.from_orbital_elements(1.0, 0.5)
    runs = [pc.KeplerSystem.from_orbital_elements(1.0, 0.5).integrate((0, 10), 0.02, m)
            for m in ("verlet", "yoshida4", "rk4")]
    fig, ax = plt.subplots()
    lines = pl.energy_error(runs, system=kep, ax=ax)
    assert_drawn(fig)
    assert len(lines) == 3 and ax.get_yscale() == "log"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "Störmer–Verlet", "Yoshida 4", "RK4"]
    assert ax.get_xlabel() == "$t$ (time)"
    # Yoshida-4's error is far below Verlet's at this step (orders 4 and 2): the lines are the
    # runs' own, in order.
    assert np.nanmax(lines[1].get_ydata()) < 1e-2 * np.nanmax(lines[0].get_ydata())


def test_phase_portrait_of_a_swarm_with_separatrix():
    swarm = pc.PendulumSwarm([0.5, 1.5, 2.5, 3.0], [0.0, 0.0, 0.0, 0.0])
    result = swarm.integrate((0, 8), 0.02)
    fig, ax = plt.subplots()
    artists = pl.phase_portrait(result, swarm, dof=None, ax=ax)
    assert_drawn(fig)
    orbits = [a for a in artists if isinstance(a, matplotlib.lines.Line2D)]
    contours = [a for a in artists if isinstance(a, matplotlib.contour.ContourSet)]
    assert len(orbits) == 4 and len(contours) == 1
    # The separatrix is the energy level of the hanging-up pendulum, E = g/l (= 1 here).
    assert contours[0].levels == pytest.approx([1.0], rel=1e-12)
    assert ax.get_xlabel() == r"$\theta$ (rad)" and "(rad/s)" in ax.get_ylabel()


def test_phase_portrait_of_the_hoop_above_critical_rate_draws_the_inner_separatrix():
    hoop = pc.BeadOnRotatingHoop(0.1, 0.0, omega=5.0)
    runs = [pc.BeadOnRotatingHoop(th, 0.0, omega=5.0).integrate((0, 2), 0.01)
            for th in (0.1, 0.8)]
    artists = pl.phase_portrait(runs, hoop, labels=["near 0", "off axis"])
    contours = [a for a in artists if isinstance(a, matplotlib.contour.ContourSet)]
    # Above omega_c = sqrt(g/R) the bottom (theta = 0) is a saddle: its energy level is drawn
    # (the top's, theta = pi, lies outside this window).
    bottom, top = hoop.energy(np.zeros(2)), hoop.energy(np.array([np.pi, 0.0]))
    assert len(contours) == 1 and list(contours[0].levels) == [bottom] and bottom != top
    with pytest.raises(ValueError, match="out of range"):
        pl.phase_portrait(runs, hoop, dof=1)


def test_poincare_one_colour_per_orbit():
    hh = pc.HenonHeilesSystem([0.0, 0.1], [0.35, 0.2])
    result = hh.integrate((0, 20), 0.01)
    sections = [result.y[::40], result.y[7::40]]
    fig, ax = plt.subplots()
    cols = pl.poincare(sections, system=hh, labels=["a", "b"], ax=ax)
    assert_drawn(fig)
    assert len(cols) == 2 and len(ax.collections) == 2
    assert [len(c.get_offsets()) for c in cols] == [len(s) for s in sections]
    np.testing.assert_array_equal(cols[0].get_offsets()[:, 1], sections[0][:, 2])
    assert not np.allclose(cols[0].get_facecolor(), cols[1].get_facecolor())
    assert ax.get_xlabel() == "$x$ (dimensionless)" and ax.get_ylabel() == "$p_x$ (dimensionless)"


@pytest.fixture(scope="module")
def fput():
    chain = pc.FPUTChain(n=8, beta=1.0, mode=1, amplitude=1.5)
    return chain, chain.integrate_sampled((0, 200), 0.05, stride=20)


def test_modal_energy_lines_stacked_and_heatmap_are_the_library_numbers(fput):
    chain, result = fput
    fig, axes = plt.subplots(1, 3)
    lines = pl.modal_energies(chain, result, modes=[1, 3], ax=axes[0])
    assert len(lines) == 2
    e = chain.modal_energies(result.q[5], result.p[5])
    assert lines[1].get_ydata()[5] == e[2]
    stacks = pl.modal_energies(chain, result, modes=[1, 3], stacked=True, ax=axes[1])
    assert len(stacks) == 2
    mesh = pl.modal_heatmap(chain, result, log=False, ax=axes[2])
    assert mesh.get_array().shape == (8, len(result.t))
    assert mesh.get_array()[0, 5] == e[0]
    assert_drawn(fig)
    assert axes[0].get_ylabel() == "$E_j$ (energy)" and axes[2].get_ylabel() == "mode number $j$"
    with pytest.raises(ValueError, match="out of range"):
        pl.modal_energies(chain, result, modes=[9])


def test_swarm_patch_area_is_the_library_area():
    swarm = pc.PendulumSwarm.from_box(1.0, 0.0, 0.3, 0.3, n=50)
    result = swarm.integrate_sampled((0, 4), 0.01, stride=50)
    snaps, area = pl.swarm_patch(swarm, result, times=3)
    assert_drawn(area.figure)
    assert len(snaps) == 3 and all(len(s.get_offsets()) == 50 for s in snaps)
    assert area.get_ydata()[-1] == swarm.phase_space_area(result.q[-1], result.p[-1])
    assert "rad" in area.axes.get_ylabel() and area.axes.get_xlabel() == "$t$ (s)"


def test_kepler_orbit_lrl_arrows_and_precession():
    kep = pc.KeplerSystem.from_orbital_elements(1.0, 0.5, c_pn=0.01)
    result = kep.integrate((0, 30), 0.01)
    fig, (ax, ax2) = plt.subplots(1, 2)
    orbit, quiver, line = pl.kepler_orbit(kep, result, arrows=4, ax=ax, precession_ax=ax2)
    assert_drawn(fig)
    np.testing.assert_array_equal(orbit.get_xdata(), result.q[:, 0])
    assert quiver.N == 4
    # The arrows point along the library's LRL vector at their times.
    a_end = kep.lrl_vector(result.q[-1], result.p[-1])
    assert np.arctan2(quiver.V[-1], quiver.U[-1]) == pytest.approx(np.arctan2(*a_end[::-1]))
    # The perturbation makes the perihelion move: the direction changes over the run.
    assert abs(line.get_ydata()[-1]) > 1.0
    assert ax.get_xlabel() == "$x$ (length)" and "(deg)" in ax2.get_ylabel()


def test_top_axis_on_the_unit_sphere():
    top = pc.HeavySymmetricTop([0.0, 0.5, 0.0], [0.0, 0.0, 20.0])
    result = top.integrate((0, 1), 0.01)
    line = pl.top_axis(top, result)
    x, y, z = line.get_data_3d()
    assert len(x) == len(result.t)
    # A unit vector by construction; 1e-12 allows the rounding of sin^2 + cos^2.
    np.testing.assert_allclose(x**2 + y**2 + z**2, 1.0, atol=1e-12)
    np.testing.assert_allclose(z, np.cos(result.q[:, 1]), atol=0)
    # The library's axis, not a recomputation.
    np.testing.assert_array_equal(np.column_stack([x, y, z])[-1], top.symmetry_axis(result.q[-1]))
    assert_drawn(line.figure)
    assert "unit sphere" in line.axes.get_zlabel()


def test_polhodes_lie_on_the_angular_momentum_sphere():
    top = pc.EulerTop([0.1, 1.0, 0.1])
    runs = [pc.EulerTop(w).integrate((0, 10), 0.02)
            for w in ([1.0, 0.1, 0.0], [0.02, 0.5, 0.05], [0.0, 0.1, 1 / 3])]
    lines = pl.polhodes(top, runs)
    assert len(lines) == 3
    for line, run in zip(lines, runs):
        x, y, z = line.get_data_3d()
        # Implicit midpoint keeps |L|^2 to rounding; 1e-12 relative covers 500 steps of it.
        r2 = top.angular_momentum_squared(run.y[0])
        np.testing.assert_allclose(x**2 + y**2 + z**2, r2, rtol=1e-12)
        np.testing.assert_array_equal([x[-1], y[-1], z[-1]], top.body_angular_momentum(run.y[-1]))
    assert_drawn(lines[0].figure)
    assert "kg m" in lines[0].axes.get_xlabel()


@pytest.mark.parametrize("name", sorted(make_systems()))
def test_animate_every_built_in_system_to_a_gif(name, tmp_path):
    system = make_systems()[name]()
    result = system.integrate_sampled((0, 0.5), 0.01, stride=5)
    entry = next(e for e in pc.catalog() if e["python"] == name)
    if entry["presentation"]["drawing"]["kind"] in ("plots", "rolling"):
        # A system with no picture in matplotlib (the rolling bodies, drawn in 3-D by the lab
        # and the gallery): refused in words rather than drawn wrong.
        with pytest.raises(ValueError, match="cannot draw"):
            pl.animate(system, result, frames=4, fps=10)
        return
    anim = pl.animate(system, result, frames=4, fps=10)
    assert len(list(anim.new_frame_seq())) == 4 and len(anim.frame_indices) == 4
    path = tmp_path / f"{name}.gif"
    pl.save_animation(anim, str(path), dpi=30)
    with Image.open(path) as gif:
        assert gif.n_frames == 4
    assert_drawn(anim._fig)


def test_animation_stride_and_jshtml(double):
    system, result = double
    anim = pl.animate(system, result, stride=50, fps=5, trail=3)
    # 201 samples, every 50th: 0, 50, 100, 150, 200.
    assert list(anim.frame_indices) == [0, 50, 100, 150, 200]
    html = anim.to_jshtml()
    assert html.count("data:image/png;base64") == 5
    trail = [c for c in anim._fig.axes[0].collections][0]
    assert len(trail.get_segments()) == 3  # frame 4: the last 3 segments of the lower bob


def test_animate_refuses_what_it_cannot_draw(double, tmp_path):
    system, result = double
    with pytest.raises(ValueError, match="stride"):
        pl.animate(system, result, stride=0)
    with pytest.raises(ValueError, match="fps"):
        pl.animate(system, result, fps=0)
    anim = pl.animate(system, result, frames=2)
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        pl.save_animation(anim, str(tmp_path / "x.avi"))
    pl.save_animation(anim, str(tmp_path / "x.gif"), dpi=20)
    with pytest.raises(ValueError, match="cannot draw"):
        pl.animate(object(), result)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), 1j, True, 2.0, "3", None, 10**30, 0])
def test_integer_options_refuse_what_is_not_a_positive_integer(double, bad):
    # The package's own converter: ValueError naming the argument, never OverflowError /
    # TypeError from int(), never a float silently truncated. (None is refused: stride has no
    # None default; frames=None is the documented "use stride".)
    system, result = double
    calls = {
        "stride": lambda: pl.animate(system, result, stride=bad),
        "fps": lambda: pl.animate(system, result, frames=2, fps=bad),
    }
    if bad is not None:
        calls["frames"] = lambda: pl.animate(system, result, frames=bad)
    for name, call in calls.items():
        with pytest.raises(ValueError, match=name):
            call()


def test_tumbling_box_has_the_library_shape_or_says_it_has_none():
    from mpl_toolkits.mplot3d.art3d import Line3D

    for moments, shape in (((1.0, 2.0, 2.5), "box with the body's moments"),
                           ((1.0, 2.0, 10.0), "cube: no rigid body has these moments")):
        top = pc.EulerTop([0.1, 1.0, 0.1], I1=moments[0], I2=moments[1], I3=moments[2])
        result = top.integrate_sampled((0, 0.2), 0.01)
        anim = pl.animate(top, result, frames=2)
        ax = anim._fig.axes[0]
        assert [t.get_text() for t in ax.texts] == [shape]
        edges = [a for a in ax.get_children() if isinstance(a, Line3D)]
        assert len(edges) == 12
        if shape.startswith("box"):  # (before rendering: frame 0 is drawn)
            # Frame 0 at the identity orientation: the box's extent along each axis is the
            # library's half-extents, scaled so that the largest is 1.
            half = top.inertia_box()
            pts = np.concatenate([np.array(e.get_data_3d()).T for e in edges])
            np.testing.assert_allclose(pts.max(axis=0), half / half.max(), rtol=1e-15)
        assert anim.to_jshtml().count("data:image/png;base64") == 2


def test_hoop_animation_draws_the_library_positions():
    bead = pc.BeadOnRotatingHoop(1.0, 0.5, R=1.5)
    result = bead.integrate_sampled((0, 0.5), 0.01)
    anim = pl.animate(bead, result, frames=3)
    assert anim.to_jshtml().count("data:image/png;base64") == 3
    # After rendering, the bead sits where the last frame put it.
    bead_line = [ln for ln in anim._fig.axes[0].lines if ln.get_marker() == "o"][0]
    xy = bead_line.get_xydata()[0]
    np.testing.assert_array_equal(xy, bead.positions(result.q[anim.frame_indices[-1]]))
