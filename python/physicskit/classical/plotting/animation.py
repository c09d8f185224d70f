"""Animations of a run: ``animate(system, result)`` returns a matplotlib ``FuncAnimation``.

What is drawn depends on the system: the pendulum family as bobs on rods (the double
pendulum's lower bob with a fading trail), chains as moving masses, the pendulum swarm as a
cloud in phase space, orbits with a trail, the Euler top as a tumbling box (its orientation
from the system's ``rotation_matrix``), the heavy top as its axis on the unit sphere,
Foucault's pendulum from above (its rosette), the reduced Euler's disk as its contact point
seen from above, the reduced rattleback as its spin against time.

In Jupyter: ``HTML(anim.to_jshtml())`` (or ``%matplotlib`` widget backends play it directly);
``save_animation(anim, "run.gif")`` writes a GIF with pillow (``.mp4`` with ffmpeg).
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .._native import as_int
from ._data import frame_indices, has_qp
from ._labels import Labels, drawing_of
from ._mpl import new_axes

#: Update function of a frame (its position in the frame list) -> artists changed.
_Update = Callable[[int], list[Any]]


def _fading_trail(ax: Any, colour: str) -> Any:
    from matplotlib.collections import LineCollection

    trail = LineCollection([], colors=colour, linewidths=1.5)
    ax.add_collection(trail)
    return trail


def _set_trail(trail: Any, xy: np.ndarray, base: Any) -> None:
    """Segments of ``xy`` (oldest first), alpha rising from 0 to 1 toward the newest."""
    from matplotlib.colors import to_rgba

    if len(xy) < 2:
        trail.set_segments([])
        return
    segs = np.stack([xy[:-1], xy[1:]], axis=1)
    rgba = np.tile(to_rgba(base), (len(segs), 1))
    rgba[:, 3] = np.linspace(0.0, 1.0, len(segs)) ** 1.5
    trail.set_segments(segs)
    trail.set_color(rgba)


def _coil(a: np.ndarray, b: np.ndarray, turns: int = 10, width: float = 0.06) -> np.ndarray:
    """A spring from ``a`` to ``b`` as a zig-zag of ``turns`` turns, straight for a tenth of
    its length at each end; ``width`` is its half-width relative to its rest length scale."""
    d = b - a
    length = float(np.hypot(*d)) or 1e-12
    u, n = d / length, np.array([-d[1], d[0]]) / length
    s = np.concatenate([[0.0, 0.1], np.linspace(0.1, 0.9, 2 * turns + 1)[1:-1], [0.9, 1.0]])
    side = np.zeros_like(s)
    side[2:-2] = np.where(np.arange(len(s) - 4) % 2 == 0, 1.0, -1.0)
    return a + np.outer(s * length, u) + np.outer(side * width, n)


def _bobs(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int,
          springs: bool = False) -> _Update:
    """Pendulums drawn from the system's ``positions(q)``: rods (or, on springs, coils) from
    the pivot through each bob."""
    pos = np.array([system.positions(result.q[i]) for i in idx]).reshape(len(idx), -1, 2)
    reach = 1.1 * np.abs(pos).max()
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.plot([0.0], [0.0], "ks", ms=5)
    (rods,) = ax.plot([], [], "-", color="0.3", lw=2)
    (bobs,) = ax.plot([], [], "o", color="C0", ms=10)
    fade = _fading_trail(ax, "C3")
    ax.set_xlabel("$x$ (m)")
    ax.set_ylabel("$y$ (m)")

    width = 0.04 * reach

    def update(k: int) -> list[Any]:
        pts = np.vstack([[0.0, 0.0], pos[k]])
        if springs:
            pts = np.vstack([_coil(pts[i], pts[i + 1], width=width) for i in range(len(pts) - 1)])
        rods.set_data(pts[:, 0], pts[:, 1])
        bobs.set_data(pos[k, :, 0], pos[k, :, 1])
        _set_trail(fade, pos[max(0, k - trail) : k + 1, -1], "C3")
        return [rods, bobs, fade]

    return update


def _hoop(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int) -> _Update:
    """The bead on its hoop, seen in the hoop's rotating frame (the system's ``positions``)."""
    radius = system.R
    xy = np.array([system.positions(result.q[i]) for i in idx]).reshape(-1, 2)
    ring = np.linspace(0.0, 2.0 * np.pi, 200)
    ax.plot(radius * np.cos(ring), radius * np.sin(ring), color="0.5", lw=2)
    ax.plot([0, 0], [-1.2 * radius, 1.2 * radius], "k:", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlim(-1.3 * radius, 1.3 * radius)
    ax.set_ylim(-1.3 * radius, 1.3 * radius)
    (bead,) = ax.plot([], [], "o", color="C0", ms=10)
    fade = _fading_trail(ax, "C3")
    ax.set_xlabel("$x$ in the hoop's rotating frame (m)")
    ax.set_ylabel("$y$ (m)")

    def update(k: int) -> list[Any]:
        bead.set_data(xy[k : k + 1, 0], xy[k : k + 1, 1])
        _set_trail(fade, xy[max(0, k - trail) : k + 1], "C3")
        return [bead, fade]

    return update


def _chain(system: Any, result: Any, idx: np.ndarray, ax: Any, walls: bool) -> _Update:
    """Masses at their sites ``i``, displaced by ``q_i`` (drawn across the chain), joined by
    the springs; fixed walls at both ends where the chain has them."""
    q = result.q[idx]
    n = q.shape[1]
    sites = np.arange(1, n + 1)
    lab = Labels(system, n)
    top = 1.15 * max(np.abs(q).max(), 1e-12)
    ax.set_xlim(0, n + 1)
    ax.set_ylim(-top, top)
    ax.axhline(0.0, color="0.8", lw=0.8)
    if walls:
        ax.axvline(0, color="k", lw=3)
        ax.axvline(n + 1, color="k", lw=3)
    (springs,) = ax.plot([], [], "-", color="0.4", lw=1)
    (masses,) = ax.plot([], [], "o", color="C0", ms=max(2.0, min(8.0, 240.0 / n)))
    ax.set_xlabel("site $i$")
    ax.set_ylabel(f"displacement ${lab._family() or 'q'}_i$ ({lab.q_unit})")

    def update(k: int) -> list[Any]:
        xs = np.concatenate([[0], sites, [n + 1]]) if walls else sites
        ys = np.concatenate([[0.0], q[k], [0.0]]) if walls else q[k]
        springs.set_data(xs, ys)
        masses.set_data(sites, q[k])
        return [springs, masses]

    return update


def _field(system: Any, result: Any, idx: np.ndarray, ax: Any) -> _Update:
    """A field on the lattice's sites: each site's value ``q_i`` against the site, joined
    (the sine–Gordon angles; a kink is a step of 2π)."""
    q = result.q[idx]
    n = q.shape[1]
    sites = np.arange(1, n + 1)
    lab = Labels(system, n)
    lo, hi = float(q.min()), float(q.max())
    pad = 0.08 * max(hi - lo, 1e-12)
    ax.set_xlim(0.5, n + 0.5)
    ax.set_ylim(lo - pad, hi + pad)
    (line,) = ax.plot([], [], "-", color="C0", lw=1.2)
    (dots,) = ax.plot([], [], "o", color="C3", ms=max(1.5, min(5.0, 160.0 / n)))
    ax.set_xlabel("site $i$")
    ax.set_ylabel(f"${lab._family() or 'q'}_i$ ({lab.q_unit})")

    def update(k: int) -> list[Any]:
        line.set_data(sites, q[k])
        dots.set_data(sites, q[k])
        return [line, dots]

    return update


def _cloud(system: Any, result: Any, idx: np.ndarray, ax: Any) -> _Update:
    """The swarm's points in phase space."""
    from .phase import draw_separatrix

    q, p = result.q[idx], result.p[idx]
    ax.set_xlim(q.min() - 0.2, q.max() + 0.2)
    ax.set_ylim(p.min() - 0.2, p.max() + 0.2)
    lab = Labels(system, 1)
    draw_separatrix(ax, system, linewidth=0.8)
    pts = ax.scatter(q[0], p[0], s=3, color="C0", linewidths=0)
    ax.set_xlabel(lab.q(0))
    ax.set_ylabel(lab.p(0))

    def update(k: int) -> list[Any]:
        pts.set_offsets(np.column_stack([q[k], p[k]]))
        return [pts]

    return update


def _orbit(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int,
           central_body: bool, ground: bool = False) -> _Update:
    """A point moving in the ``(q_1, q_2)`` plane with a fading trail; a central body at the
    origin, or level ground at ``y = 0`` (a projectile's flight)."""
    xy = result.q[idx][:, :2]
    lab = Labels(system, 2)
    ax.plot(result.q[:, 0], result.q[:, 1], color="0.85", lw=0.6)
    if ground:
        ax.axhline(0.0, color="#8a7a50", lw=1.5)
        ax.set_aspect("equal", adjustable="datalim")
    if central_body:
        ax.plot([0.0], [0.0], marker="*", color="orange", ms=12)
        ax.set_aspect("equal", adjustable="datalim")
    (body,) = ax.plot([], [], "o", color="C0", ms=7)
    fade = _fading_trail(ax, "C0")
    ax.set_xlabel(lab.q(0))
    ax.set_ylabel(lab.q(1))

    def update(k: int) -> list[Any]:
        body.set_data(xy[k : k + 1, 0], xy[k : k + 1, 1])
        _set_trail(fade, xy[max(0, k - trail) : k + 1], "C0")
        return [body, fade]

    return update


#: The 12 edges of a box, as pairs of corner indices (corners = sign patterns of 3 bits).
_EDGES = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]


def _box(system: Any, result: Any, idx: np.ndarray, ax: Any) -> _Update:
    """The uniform box with the top's principal moments (the system's ``inertia_box``, scaled
    to unit size; a plate where one half-extent is zero), turned by the system's
    ``rotation_matrix`` of each state. Moments that no rigid body has (one above the sum of
    the other two) have no box: a cube shows the orientation, and the axes say so."""
    try:
        half = system.inertia_box()
        shape = "box with the body's moments"
    except ValueError:
        half = np.ones(3)
        shape = "cube: no rigid body has these moments"
    half = half / half.max()
    corners = np.array([[(c >> k & 1) * 2 - 1 for k in range(3)] for c in range(8)]) * half
    rots = np.array([system.rotation_matrix(result.y[i]) for i in idx])
    lines = [ax.plot([], [], [], color="C0", lw=1.5)[0] for _ in _EDGES]
    ax.set_xlim(-1.2, 1.2)
    ax.set_ylim(-1.2, 1.2)
    ax.set_zlim(-1.2, 1.2)
    ax.set_box_aspect((1, 1, 1))
    ax.text2D(0.02, 0.95, shape, transform=ax.transAxes, fontsize="small")
    ax.set_xlabel("$x$ (space frame)")
    ax.set_ylabel("$y$ (space frame)")
    ax.set_zlabel("$z$ (space frame)")

    def update(k: int) -> list[Any]:
        world = corners @ rots[k].T
        for line, (a, b) in zip(lines, _EDGES):
            seg = world[[a, b]]
            line.set_data_3d(seg[:, 0], seg[:, 1], seg[:, 2])
        return lines

    return update


def _top(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int) -> _Update:
    """The heavy top's symmetry axis from the pivot, its tip tracing the unit sphere."""
    from .rigid import _sphere, axis_tip

    tip = axis_tip(system, result)[idx]
    _sphere(ax, 1.0)
    (stick,) = ax.plot([], [], [], color="C0", lw=3)
    (path,) = ax.plot([], [], [], color="C3", lw=1)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("$x$ (unit sphere)")
    ax.set_ylabel("$y$ (unit sphere)")
    ax.set_zlabel("$z$, up (unit sphere)")

    def update(k: int) -> list[Any]:
        stick.set_data_3d([0.0, tip[k, 0]], [0.0, tip[k, 1]], [0.0, tip[k, 2]])
        old = tip[max(0, k - trail) : k + 1]
        path.set_data_3d(old[:, 0], old[:, 1], old[:, 2])
        return [stick, path]

    return update


def _swing(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int) -> _Update:
    """Foucault's pendulum seen from above: the bob's horizontal displacement (east, north)
    with a fading trail, so the turning swing plane shows as a rosette."""
    xy = np.ascontiguousarray(result.y[idx, :2])
    reach = 1.1 * max(float(np.abs(result.y[:, :2]).max()), np.finfo(float).tiny)
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.plot([0.0], [0.0], "k+", ms=8)
    (rod,) = ax.plot([], [], "-", color="0.5", lw=1)
    (bob,) = ax.plot([], [], "o", color="C0", ms=9)
    fade = _fading_trail(ax, "C3")
    ax.set_xlabel("$x$, east (m)")
    ax.set_ylabel("$y$, north (m)")

    def update(k: int) -> list[Any]:
        rod.set_data([0.0, xy[k, 0]], [0.0, xy[k, 1]])
        bob.set_data([xy[k, 0]], [xy[k, 1]])
        _set_trail(fade, xy[max(0, k - trail) : k + 1], "C3")
        return [rod, bob, fade]

    return update


def _disk(system: Any, result: Any, idx: np.ndarray, ax: Any, trail: int,
          radius: float = 1.0) -> _Update:
    """The reduced Euler's disk from above: its contact point at azimuth ``phi`` and at
    ``radius cos(theta)`` from the point under the disk's centre (a disk of that radius
    inclined by ``theta`` touches the table there), so the path spirals out to the full
    radius as the disk flattens, ever faster; with a trail."""
    theta, phi = result.y[idx, 0], result.y[idx, 1]
    xy = np.column_stack([radius * np.cos(theta) * np.cos(phi),
                          radius * np.cos(theta) * np.sin(phi)])
    reach = 1.15 * radius
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    (rim,) = ax.plot(radius * np.cos(np.linspace(0, 2 * np.pi, 121)),
                     radius * np.sin(np.linspace(0, 2 * np.pi, 121)), ":", color="0.6", lw=1)
    (spoke,) = ax.plot([], [], "-", color="0.4", lw=1)
    (dot,) = ax.plot([], [], "o", color="C0", ms=8)
    fade = _fading_trail(ax, "C3")
    ax.set_xlabel("$x$ (disk radii)")
    ax.set_ylabel("$y$ (disk radii)")

    def update(k: int) -> list[Any]:
        spoke.set_data([0.0, xy[k, 0]], [0.0, xy[k, 1]])
        dot.set_data([xy[k, 0]], [xy[k, 1]])
        _set_trail(fade, xy[max(0, k - trail) : k + 1], "C3")
        return [spoke, dot, fade]

    return update


def _spin(system: Any, result: Any, idx: np.ndarray, ax: Any) -> _Update:
    """The reduced rattleback's spin ``n3`` against time, drawn as it goes: a reversal is
    the curve crossing zero."""
    t, n3 = result.t[idx], result.y[idx, 2]
    span = max(float(np.abs(n3).max()), np.finfo(float).tiny)
    ax.set_xlim(float(t[0]), float(t[-1]) if t[-1] > t[0] else float(t[0]) + 1.0)
    ax.set_ylim(-1.1 * span, 1.1 * span)
    ax.axhline(0.0, color="0.6", lw=0.8)
    (line,) = ax.plot([], [], "-", color="C0", lw=1.5)
    (dot,) = ax.plot([], [], "o", color="C3", ms=7)
    ax.set_xlabel(Labels(system).t)
    ax.set_ylabel("spin $n_3$ (rad/s)")

    def update(k: int) -> list[Any]:
        line.set_data(t[: k + 1], n3[: k + 1])
        dot.set_data([t[k]], [n3[k]])
        return [line, dot]

    return update


def animate(system: Any, result: Any, *, stride: int = 1, frames: int | None = None,
            fps: int = 30, trail: int = 40, ax: Any = None) -> Any:
    """Animate a run of a built-in system.

    Parameters
    ----------
    system : the system that produced ``result``
    result : SimulationResult
    stride : int
        Draw every ``stride``-th stored sample.
    frames : int, optional
        Instead of ``stride``: this many evenly spaced samples.
    fps : int
        Frames per second of playback (and of a saved file).
    trail : int
        Length of the fading trail, in frames (pendulums, orbits, the top's tip).
    ax : Axes, optional
        Where to draw (a 3-D axes for the rigid bodies).

    Returns
    -------
    matplotlib.animation.FuncAnimation, with ``len(frame_indices)`` frames; its
    ``frame_indices`` attribute holds the sample index of each frame.

    Raises
    ------
    ValueError
        For a system it cannot draw, or a bad ``stride`` / ``frames`` / ``fps``.
    """
    from matplotlib.animation import FuncAnimation

    fps = as_int("fps", fps, minimum=1, maximum=1000)
    trail = as_int("trail", trail, minimum=0)
    idx = frame_indices(len(result.t), stride, frames)
    # What to draw is the catalogue's `presentation["drawing"]` of the system's class.
    drawing = drawing_of(system) or {"kind": "plots"}
    kind = drawing["kind"]
    three_d = kind in ("inertia_box", "top_axis")
    # Pictures drawn from the state itself, not from q and p.
    by_state = three_d or kind in ("swing", "contact_spiral", "spin")
    if kind in ("plots", "rolling"):
        raise ValueError(
            f"animate cannot draw a {type(system).__name__}: "
            + ("a rolling body is drawn in 3-D by the browser lab and the gallery; "
               if kind == "rolling" else "the catalogue gives it no picture; ")
            + "animate draws the pendulum family, the hoop, chains and fields, the pendulum "
            "swarm, orbits, the tops and the reduced models; plot_result draws any run"
        )
    if not by_state and not has_qp(result):
        raise ValueError("the result has no q and p to animate")
    ax = new_axes(ax, projection="3d" if three_d else None)
    builders: dict[str, Callable[[], _Update]] = {
        "bobs": lambda: _bobs(system, result, idx, ax, trail, bool(drawing.get("springs"))),
        "hoop": lambda: _hoop(system, result, idx, ax, trail),
        "swarm": lambda: _cloud(system, result, idx, ax),
        "chain": lambda: _chain(system, result, idx, ax, drawing.get("ends") == "fixed"),
        "field": lambda: _field(system, result, idx, ax),
        "orbit": lambda: _orbit(system, result, idx, ax, trail,
                                bool(drawing.get("central_body")), bool(drawing.get("ground"))),
        "inertia_box": lambda: _box(system, result, idx, ax),
        "top_axis": lambda: _top(system, result, idx, ax, trail),
        "swing": lambda: _swing(system, result, idx, ax, trail),
        "contact_spiral": lambda: _disk(system, result, idx, ax, trail),
        "spin": lambda: _spin(system, result, idx, ax),
    }
    if kind not in builders:
        raise ValueError(f"animate has no picture of kind {kind!r}")
    update = builders[kind]()
    title = ax.set_title("")
    t = result.t[idx]
    unit = Labels(system).time_unit
    unit = " s" if unit == "s" else ""

    def frame(k: int) -> list[Any]:
        title.set_text(f"$t$ = {t[k]:.2f}{unit}")
        return update(k) + [title]

    frame(0)
    anim = FuncAnimation(ax.figure, frame, frames=len(idx), interval=1000.0 / fps, blit=False)
    anim.frame_indices = idx  # type: ignore[attr-defined]
    anim.fps = int(fps)  # type: ignore[attr-defined]
    return anim


def save_animation(anim: Any, path: str, *, fps: int | None = None, dpi: int = 80) -> None:
    """Write ``anim`` to ``path``: ``.gif`` with pillow, ``.mp4`` with ffmpeg (ValueError naming
    what to install when the writer is missing)."""
    from matplotlib import animation as mpl_animation

    fps = as_int("fps", fps if fps is not None else getattr(anim, "fps", 30), minimum=1,
                 maximum=1000)
    dpi = as_int("dpi", dpi, minimum=1, maximum=1000)
    lower = str(path).lower()
    if lower.endswith(".gif"):
        try:
            import PIL  # noqa: F401
        except ImportError:
            raise ValueError("saving a GIF needs pillow: pip install physicskit[plot]") from None
        anim.save(path, writer=mpl_animation.PillowWriter(fps=fps), dpi=dpi)
    elif lower.endswith(".mp4"):
        if not mpl_animation.FFMpegWriter.isAvailable():
            raise ValueError("saving an MP4 needs ffmpeg on PATH; save a .gif instead")
        anim.save(path, writer=mpl_animation.FFMpegWriter(fps=fps), dpi=dpi)
    else:
        raise ValueError(f"path must end in .gif or .mp4, got {path!r}")
