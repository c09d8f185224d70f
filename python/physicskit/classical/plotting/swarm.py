"""Liouville's theorem seen: a swarm's phase-space patch at several times, and its area."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._native import as_int
from ._labels import Labels
from ._mpl import pyplot
from .phase import draw_separatrix


def swarm_patch(system: Any, result: Any, *, times: int = 4, ax: Any = None,
                area_ax: Any = None, separatrix: bool = True) -> tuple[list[Any], Any]:
    """The swarm's points in ``(q, p)`` at ``times`` evenly spaced samples (colour = time),
    and the area of the patch (the system's ``phase_space_area``, a convex hull) against
    time.

    Parameters
    ----------
    system : PendulumSwarm
    result : its run
    times : int
        Number of snapshots.
    ax, area_ax : Axes, optional
        Where the snapshots and the area go; with neither, a new two-panel figure. With only
        ``ax``, the area is not drawn.
    separatrix : bool
        Draw the pendulum's separatrix behind the points.

    Returns
    -------
    (list of PathCollection, Line2D or None)
    """
    if not hasattr(system, "phase_space_area"):
        raise ValueError(f"{type(system).__name__} has no phase_space_area (use a PendulumSwarm)")
    times = as_int("times", times, minimum=1, maximum=1000)
    if ax is None and area_ax is None:
        _, (ax, area_ax) = pyplot().subplots(1, 2, figsize=(11.0, 4.2))
    elif ax is None:
        ax = pyplot().figure().add_subplot()
    idx = np.unique(np.linspace(0, len(result.t) - 1, times).round().astype(int))
    lab = Labels(system, 1)
    colours = pyplot().get_cmap("viridis")(np.linspace(0.0, 0.9, len(idx)))
    snaps = []
    for c, i in zip(colours, idx):
        snaps.append(ax.scatter(result.q[i], result.p[i], s=2, color=c, linewidths=0,
                                label=f"t = {result.t[i]:.3g}"))
    ax.set_xlabel(lab.q(0))
    ax.set_ylabel(lab.p(0))
    if separatrix:
        draw_separatrix(ax, system, linewidth=0.8)
    ax.legend(fontsize="small", markerscale=4, loc="upper right")
    line = None
    if area_ax is not None:
        area = np.array([system.phase_space_area(q, p) for q, p in zip(result.q, result.p)])
        (line,) = area_ax.plot(result.t, area, color="C0")
        area_ax.set_ylim(0.0, 1.3 * area.max())
        area_ax.set_xlabel(lab.t)
        area_ax.set_ylabel("convex-hull area (rad$^2$/s)")
        area_ax.set_title("area of the patch (convex hull)")
    return snaps, line
