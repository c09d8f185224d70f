"""Animations of a run (the peer's ``visualizers.animations``).

The system-specific ones (``animate_elastic_pendulum``, ``animate_rigid_body_tumble``,
``animate_eulers_disk``, ``animate_rattleback``) are
:func:`physicskit.classical.plotting.animate`, which draws each system from its own
geometry; :class:`SideBySideAnimator` puts a picture of your own (left) beside the phase
portrait or the energy (right).
"""

from __future__ import annotations

from typing import Any, Callable, Optional

import numpy as np

from .._native import as_int, as_scalar
from ..plotting import animate, save_animation
from ..plotting._mpl import pyplot

__all__ = [
    "SideBySideAnimator",
    "orbit_trace_animation",
    "pendulum_animation",
    "animate_elastic_pendulum",
    "animate_rigid_body_tumble",
    "animate_eulers_disk",
    "animate_rattleback",
]


def _fps(interval: Any) -> int:
    """Frames per second of a delay of ``interval`` ms between frames."""
    interval = as_int("interval", interval, minimum=1)
    return max(1, round(1000 / interval))


class SideBySideAnimator:
    """Physical space on the left (drawn by ``init_physical``/``update_physical``), and on
    the right a growing trace of ``(q[:, dof_index], p[:, dof_index])`` (``mode="phase"``) or
    of the energy against time (``mode="energy"``), over every ``stride``-th sample of
    ``result``.

    ``init_physical(ax)`` creates and returns the artists to animate;
    ``update_physical(artists, result, i)`` moves them to sample ``i`` and returns them.
    :meth:`build` makes the ``FuncAnimation``; :meth:`save` writes it.
    """

    def __init__(self, result, init_physical: Callable, update_physical: Callable,
                 mode: str = "phase", dof_index: int = 0, figsize=(11, 5),
                 physical_3d: bool = False, stride: int = 1,
                 left_title: str = "Physical space"):
        if mode not in ("phase", "energy"):
            raise ValueError(f"mode must be 'phase' or 'energy', got {mode!r}")
        if not callable(init_physical) or not callable(update_physical):
            raise TypeError("init_physical and update_physical must be callable")
        self.result = result
        self.init_physical = init_physical
        self.update_physical = update_physical
        self.mode = mode
        self.stride = as_int("stride", stride, minimum=1)
        if mode == "phase":
            if result.q is None or result.p is None:
                raise ValueError("mode='phase' needs a run with q and p; use mode='energy'")
            ndof = np.asarray(result.q).reshape(len(result.t), -1).shape[1]
            self.dof_index = as_int("dof_index", dof_index, minimum=0, maximum=ndof - 1)
        else:
            if result.energy is None:
                raise ValueError("mode='energy' needs a run with energy")
            self.dof_index = as_int("dof_index", dof_index, minimum=0)
        self.figsize = tuple(figsize)
        self.physical_3d = bool(physical_3d)
        self.left_title = str(left_title)
        self.frames = np.arange(0, len(result.t), self.stride)
        self.fig: Any = None
        self.anim: Any = None

    def _right_series(self) -> tuple[np.ndarray, np.ndarray, str, str]:
        r = self.result
        if self.mode == "phase":
            q = np.asarray(r.q).reshape(len(r.t), -1)[:, self.dof_index]
            p = np.asarray(r.p).reshape(len(r.t), -1)[:, self.dof_index]
            return q, p, f"$q_{self.dof_index}$", f"$p_{self.dof_index}$"
        return np.asarray(r.t), np.asarray(r.energy), "$t$", "energy"

    def build(self, interval: int = 30, blit: bool = False):
        """The ``FuncAnimation`` (one frame every ``interval`` ms), kept as ``self.anim``."""
        from matplotlib.animation import FuncAnimation

        interval = as_int("interval", interval, minimum=1)
        plt = pyplot()
        self.fig = plt.figure(figsize=self.figsize, layout="constrained")
        left = self.fig.add_subplot(1, 2, 1, projection="3d" if self.physical_3d else None)
        right = self.fig.add_subplot(1, 2, 2)
        left.set_title(self.left_title)
        artists = self.init_physical(left)
        x, y, xl, yl = self._right_series()
        right.plot(x, y, color="0.85", lw=0.8)
        (trace,) = right.plot([], [], color="C0", lw=1.2)
        (dot,) = right.plot([], [], "o", color="C3", ms=6)
        right.set_xlabel(xl)
        right.set_ylabel(yl)
        right.set_title("Phase space" if self.mode == "phase" else "Energy")

        def frame(k: int) -> list[Any]:
            i = int(self.frames[k])
            moved = self.update_physical(artists, self.result, i)
            trace.set_data(x[: i + 1], y[: i + 1])
            dot.set_data([x[i]], [y[i]])
            return list(moved or []) + [trace, dot]

        self.anim = FuncAnimation(self.fig, frame, frames=len(self.frames), interval=interval,
                                  blit=bool(blit))
        self.anim.fps = _fps(interval)
        return self.anim

    def save(self, filename: str, fps: Optional[int] = None, **kwargs):
        """Write the animation (built first if needed): with a ``writer`` in ``kwargs``,
        through ``FuncAnimation.save`` (``fps`` passed only when given); otherwise as GIF
        (pillow) or MP4 (ffmpeg) by :func:`physicskit.classical.plotting.save_animation`,
        at ``fps`` (default 30) and ``kwargs``' ``dpi``."""
        if self.anim is None:
            self.build()
        if "writer" in kwargs:
            if fps is not None:
                kwargs["fps"] = as_int("fps", fps, minimum=1)
            self.anim.save(filename, **kwargs)
            return
        extra = set(kwargs) - {"dpi"}
        if extra:
            raise TypeError(f"unexpected arguments without a writer: {sorted(extra)}")
        save_animation(self.anim, filename, fps=30 if fps is None else fps,
                       dpi=kwargs.get("dpi", 80))


def pendulum_animation(result, positions_func: Callable[[np.ndarray], np.ndarray],
                       **kwargs) -> SideBySideAnimator:
    """A :class:`SideBySideAnimator` of rods and bobs: ``positions_func(q)`` gives the bobs'
    ``(x, y)`` pairs (flat), joined from the pivot at the origin (e.g. a
    ``DoublePendulum``'s ``positions``)."""
    if not callable(positions_func):
        raise TypeError("positions_func must be callable")
    pts = np.array([np.asarray(positions_func(q), dtype=float).reshape(-1, 2)
                    for q in result.q])
    reach = 1.1 * max(float(np.abs(pts).max()), np.finfo(float).tiny)

    def init(ax):
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        ax.set_aspect("equal")
        ax.plot([0.0], [0.0], "ks", ms=5)
        (rods,) = ax.plot([], [], "-o", color="C0", lw=2, ms=8)
        return (rods,)

    def update(artists, _result, i):
        chain = np.vstack([[0.0, 0.0], pts[i]])
        artists[0].set_data(chain[:, 0], chain[:, 1])
        return artists

    return SideBySideAnimator(result, init, update, **kwargs)


def orbit_trace_animation(result, **kwargs) -> SideBySideAnimator:
    """A :class:`SideBySideAnimator` of a planar orbit (``result.q[:, :2]``, e.g. a
    ``KeplerSystem`` run): the path grows behind the body, the centre at the origin."""
    xy = np.asarray(result.q, dtype=float).reshape(len(result.t), -1)[:, :2]
    reach = 1.1 * max(float(np.abs(xy).max()), np.finfo(float).tiny)

    def init(ax):
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        ax.set_aspect("equal")
        ax.plot([0.0], [0.0], "k*", ms=9)
        (path,) = ax.plot([], [], color="C0", lw=1)
        (body,) = ax.plot([], [], "o", color="C3", ms=7)
        return (path, body)

    def update(artists, _result, i):
        artists[0].set_data(xy[: i + 1, 0], xy[: i + 1, 1])
        artists[1].set_data([xy[i, 0]], [xy[i, 1]])
        return artists

    return SideBySideAnimator(result, init, update, **kwargs)


def animate_elastic_pendulum(system, result, interval: int = 30, trail: int = 200,
                             n_coils: int = 12, coil_width: float = 0.06):
    """:func:`physicskit.classical.plotting.animate` of an ``ElasticPendulum`` run: the bob on
    its spring from the pivot with a fading trail of ``trail`` frames. The spring is drawn
    straight (``n_coils`` >= 1 and ``coil_width`` >= 0 are checked, for the peer's
    signature)."""
    as_int("n_coils", n_coils, minimum=1)
    if as_scalar("coil_width", coil_width) < 0.0:
        raise ValueError(f"coil_width must be >= 0, got {coil_width!r}")
    return animate(system, result, fps=_fps(interval), trail=as_int("trail", trail, minimum=0))


def animate_rigid_body_tumble(top, result, half_extents=(1.0, 0.6, 0.3), interval: int = 30,
                              stride: int = 1):
    """:func:`physicskit.classical.plotting.animate` of an ``EulerTop`` run: the body as the
    uniform box with its own principal moments (``top.inertia_box``), turned by each sample's
    rotation matrix. ``half_extents`` (three numbers > 0) is checked; the box drawn is the
    one the moments determine rather than a chosen one."""
    half = np.asarray(half_extents, dtype=float)
    if half.shape != (3,) or not np.all(half > 0.0):
        raise ValueError(f"half_extents must be three numbers > 0, got {half_extents!r}")
    return animate(top, result, stride=stride, fps=_fps(interval))


def animate_eulers_disk(system, result, radius: float = 1.0, interval: int = 30,
                        trail: int = 400):
    """:func:`physicskit.classical.plotting.animate` of an ``EulersDisk`` run: the contact
    point from above, at ``cos(theta)`` disk radii from the centre and azimuth ``phi``,
    spiralling faster as the disk runs down. The picture is in units of the disk's radius
    (``radius`` > 0 is checked; the model fixes no size)."""
    if not as_scalar("radius", radius) > 0.0:
        raise ValueError(f"radius must be > 0, got {radius!r}")
    return animate(system, result, fps=_fps(interval), trail=as_int("trail", trail, minimum=0))


def animate_rattleback(system, result, interval: int = 30, stride: int = 1):
    """:func:`physicskit.classical.plotting.animate` of a ``Rattleback`` run: the spin ``n3``
    against time, drawn as it goes; a reversal is the curve crossing zero."""
    return animate(system, result, stride=stride, fps=_fps(interval))
