"""Rigid bodies in 3-D: the heavy top's symmetry axis on the unit sphere, the Euler top's
polhodes (body-frame angular momentum) on the angular-momentum sphere."""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from ._data import as_results, given_labels
from ._labels import drawing_of
from ._mpl import new_axes, orbit_colours


def _sphere(ax: Any, radius: float) -> Any:
    u, v = np.meshgrid(np.linspace(0.0, 2.0 * np.pi, 41), np.linspace(0.0, np.pi, 21))
    return ax.plot_wireframe(radius * np.cos(u) * np.sin(v), radius * np.sin(u) * np.sin(v),
                             radius * np.cos(v), color="0.75", linewidth=0.4, alpha=0.6)


def axis_tip(system: Any, result: Any) -> np.ndarray:
    """The heavy top's symmetry-axis direction in space at each stored sample, shape
    ``(n, 3)``: the system's ``symmetry_axis`` of each sample's Euler angles."""
    return np.array([system.symmetry_axis(q) for q in result.q]).reshape(-1, 3)


def top_axis(system: Any, result: Any, *, ax: Any = None) -> Any:
    """The heavy symmetric top's axis tip on the unit sphere (3-D axes): precession around
    the vertical with nutation between two circles of latitude.

    Returns the tip's ``Line3D``.
    """
    if (drawing_of(system) or {}).get("kind") != "top_axis":
        raise ValueError(f"top_axis draws a heavy symmetric top, got {type(system).__name__}")
    ax = new_axes(ax, projection="3d")
    _sphere(ax, 1.0)
    tip = axis_tip(system, result)
    (line,) = ax.plot(tip[:, 0], tip[:, 1], tip[:, 2], color="C3", lw=1.0, label="axis tip")
    ax.plot([0, 0], [0, 0], [-1.1, 1.1], color="k", lw=0.6, ls=":")
    ax.scatter([tip[0, 0]], [tip[0, 1]], [tip[0, 2]], color="k", s=12, label="start")
    ax.set_xlabel("$x$ (unit sphere)")
    ax.set_ylabel("$y$ (unit sphere)")
    ax.set_zlabel("$z$, up (unit sphere)")
    ax.set_box_aspect((1, 1, 1))
    ax.legend(fontsize="small")
    return line


def polhodes(system: Any, results: Any, *, labels: Sequence[str] | None = None,
             ax: Any = None) -> list[Any]:
    """Polhodes: the body-frame angular momentum ``L = (I1 w1, I2 w2, I3 w3)`` (the system's
    ``body_angular_momentum``) of each run of an ``EulerTop`` on the sphere ``|L| = const``
    (its radius from the system's ``angular_momentum_squared`` at the first run's start).
    Closed loops round the largest and smallest axes, the separatrix through the
    intermediate one (the tennis-racket axis).

    Returns one ``Line3D`` per run.
    """
    if (drawing_of(system) or {}).get("kind") != "inertia_box":
        raise ValueError(f"polhodes draws a free rigid body (EulerTop), got {type(system).__name__}")
    runs = as_results(results)
    given = given_labels(labels, len(runs))
    names: list[str | None] = [None] * len(runs) if given is None else list(given)
    ax = new_axes(ax, projection="3d")
    radius = float(np.sqrt(system.angular_momentum_squared(runs[0].y[0])))
    _sphere(ax, radius)
    lines = []
    for r, c, name in zip(runs, orbit_colours(len(runs)), names):
        body_l = np.array([system.body_angular_momentum(s) for s in r.y]).reshape(-1, 3)
        (line,) = ax.plot(body_l[:, 0], body_l[:, 1], body_l[:, 2], color=c, lw=1.2,
                          label=name)
        lines.append(line)
    ax.set_xlabel(r"$L_1$ (kg m$^2$/s)")
    ax.set_ylabel(r"$L_2$ (kg m$^2$/s)")
    ax.set_zlabel(r"$L_3$ (kg m$^2$/s)")
    ax.set_box_aspect((1, 1, 1))
    if labels is not None:
        ax.legend(fontsize="small")
    return lines
