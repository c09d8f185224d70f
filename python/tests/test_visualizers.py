"""The peer's visualizers (physicskit.classical.visualizers) under the Agg backend: each draws
the run's own numbers (checked on the drawn data), animations have one frame per sample
drawn, the array Poincaré section finds known crossings, and the plotly figures hold the
trajectory."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import physicskit.classical as pc  # noqa: E402
from physicskit.classical.visualizers import animations, modal_analysis, phase_space  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def render(anim, tmp_path, name="a.gif"):
    """Write ``anim`` as a small GIF (every frame drawn) and return the file's size."""
    path = tmp_path / name
    pc.plotting.save_animation(anim, str(path), fps=10, dpi=20)
    return path.stat().st_size


def test_phase_portrait_draws_each_column():
    run = pc.CoupledOscillators([0.1, 0.0, -0.1], [0.0, 0.0, 0.0]).integrate((0.0, 2.0), 0.01)
    ax = phase_space.plot_phase_portrait(run.q, run.p, label="run", color="k")
    assert len(ax.lines) == 3
    for i, line in enumerate(ax.lines):
        np.testing.assert_array_equal(line.get_xdata(), run.q[:, i])
        np.testing.assert_array_equal(line.get_ydata(), run.p[:, i])
        assert line.get_label() == f"run [{i}]" and line.get_color() == "k"
    ax1 = phase_space.plot_phase_portrait(run.q[:, 0], run.p[:, 0])
    assert len(ax1.lines) == 1


def test_phase_swarm_scatters_the_points():
    swarm = pc.PendulumSwarm.from_box(0.5, 0.0, 0.2, 0.2, n=50)
    ax = phase_space.plot_phase_swarm(swarm.q, swarm.p, s=2)
    offsets = ax.collections[0].get_offsets()
    np.testing.assert_array_equal(offsets, np.column_stack([swarm.q, swarm.p]))


def test_poincare_section_finds_known_crossings():
    t = np.linspace(0.0, 20.0, 20001)
    s = np.sin(t)
    cq, cp = phase_space.poincare_section(t, np.cos(t), s, np.cos(t), value=0.0, direction=1)
    # sin t rises through zero at t = 2 pi k (k = 1..3 inside (0, 20]); linear interpolation
    # between samples 1e-3 apart is exact to O(dt^2 sin'') ~ 1e-7 here (sin'' ~ 0 there).
    np.testing.assert_allclose(cq, 2 * np.pi * np.arange(1, 4), atol=1e-7)
    np.testing.assert_allclose(cp, 1.0, atol=1e-6)
    down, _ = phase_space.poincare_section(t, t, s, s, value=0.0, direction=-1)
    np.testing.assert_allclose(down, np.pi * np.array([1, 3, 5]), atol=1e-7)
    ax = phase_space.plot_poincare_section(t, np.cos(t), s, np.cos(t), s=5)
    np.testing.assert_allclose(ax.collections[0].get_offsets()[:, 0], cq)
    with pytest.raises(ValueError, match="direction"):
        phase_space.poincare_section(t, t, s, s, direction=0)


def test_so3_sphere_draws_the_body_angular_momentum():
    top = pc.EulerTop([0.01, 1.0, 0.01])
    run = top.integrate((0.0, 10.0), 0.01)
    ax = phase_space.plot_so3_momentum_sphere(run.y[:, :3], 1.0, 2.0, 3.0)
    (line,) = ax.lines
    xs, ys, zs = line.get_data_3d()
    np.testing.assert_allclose(xs, 1.0 * run.y[:, 0])
    np.testing.assert_allclose(zs, 3.0 * run.y[:, 2])


def test_modal_energy_bars_and_animation(tmp_path):
    chain = pc.FPUTChain(n=8, beta=0.5)
    run = chain.integrate((0.0, 1.0), 0.05)
    ax = modal_analysis.plot_modal_energy_bars(chain, run.q[0], run.p[0])
    heights = [b.get_height() for b in ax.patches]
    np.testing.assert_array_equal(heights, chain.modal_energies(run.q[0], run.p[0]))
    anim = modal_analysis.animate_modal_energies(chain, run, stride=4)
    assert len(list(anim.new_frame_seq())) == len(run.t[::4])
    assert render(anim, tmp_path) > 0


def test_side_by_side_and_ready_made_animators(tmp_path):
    bob = pc.DoublePendulum([1.0, 0.5], [0.0, 0.0])
    run = bob.integrate((0.0, 1.0), 0.01)
    anim = animations.pendulum_animation(run, bob.positions, stride=10)
    assert isinstance(anim, animations.SideBySideAnimator)
    built = anim.build(interval=40)
    assert len(list(built.new_frame_seq())) == 11
    anim.save(str(tmp_path / "p.gif"), fps=10)
    assert (tmp_path / "p.gif").stat().st_size > 0
    kep = pc.KeplerSystem.from_orbital_elements(1.0, 0.3)
    orbit = kep.integrate((0.0, 6.0), 0.01)
    energy = animations.orbit_trace_animation(orbit, mode="energy", stride=100).build()
    assert len(list(energy.new_frame_seq())) == len(orbit.t[::100])
    assert render(energy, tmp_path) > 0
    with pytest.raises(ValueError, match="mode"):
        animations.orbit_trace_animation(orbit, mode="polar")


@pytest.mark.parametrize("make, fn", [
    (lambda: pc.ElasticPendulum([0.2, 0.3], [0.0, 0.0]), animations.animate_elastic_pendulum),
    (lambda: pc.EulerTop([0.01, 1.0, 0.01]), animations.animate_rigid_body_tumble),
    (lambda: pc.EulersDisk(0.5), animations.animate_eulers_disk),
    (lambda: pc.Rattleback([0.01, 0.01, 3.0]), animations.animate_rattleback),
])
def test_system_animations(make, fn, tmp_path):
    system = make()
    run = system.integrate((0.0, 0.1), 0.01)
    anim = fn(system, run)
    assert len(anim.frame_indices) == len(run.t)
    assert render(anim, tmp_path) > 0


def test_foucault_animation_draws_the_bob_from_above(tmp_path):
    f = pc.FoucaultPendulum.from_deflection(2.0, omega_earth=0.01)
    run = f.integrate((0.0, 20.0), 0.05)
    anim = pc.plotting.animate(f, run, stride=10)
    anim._func(5)  # noqa: SLF001 (draw frame 5)
    bob = anim._fig.axes[0].lines[2]  # noqa: SLF001
    np.testing.assert_array_equal(bob.get_xdata(), [run.y[50, 0]])
    np.testing.assert_array_equal(bob.get_ydata(), [run.y[50, 1]])
    assert render(anim, tmp_path) > 0


def test_interactive_figures_hold_the_trajectory():
    pytest.importorskip("plotly")
    from physicskit.classical.visualizers import interactive

    kep = pc.KeplerSystem.from_orbital_elements(1.0, 0.3)
    run = kep.integrate((0.0, 6.0), 0.01)
    fig = interactive.interactive_orbit(run, kep, title="orbit")
    np.testing.assert_array_equal(fig.data[0].x, run.q[:, 0])
    assert len(fig.data) == 4  # orbit, centre, LRL vector at the start and the end
    top = pc.EulerTop([0.01, 1.0, 0.01])
    trun = top.integrate((0.0, 5.0), 0.01)
    sphere = interactive.interactive_so3_momentum_sphere(trun.y[:, :3], 1.0, 2.0, 3.0, n_grid=6)
    np.testing.assert_allclose(sphere.data[-1].y, 2.0 * trun.y[:, 1])
