"""Kepler orbits with their Laplace–Runge–Lenz vector: the perihelion direction and its
precession under a perturbed potential (``c_pn``, ``c_eps``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._native import as_int
from ._labels import Labels
from ._mpl import new_axes, pyplot


def lrl_history(system: Any, result: Any) -> np.ndarray:
    """The system's ``lrl_vector`` at each stored sample, shape ``(n_samples, 2)``."""
    if not hasattr(system, "lrl_vector"):
        raise ValueError(f"{type(system).__name__} has no lrl_vector (use a KeplerSystem)")
    return np.array([system.lrl_vector(q, p) for q, p in zip(result.q, result.p)])


def kepler_orbit(system: Any, result: Any, *, arrows: int = 6, ax: Any = None,
                 precession_ax: Any = None) -> tuple[Any, Any, Any]:
    """The orbit in the plane, the force centre, and the LRL vector ``A`` drawn from the
    centre at ``arrows`` evenly spaced times (colour = time; it points to the perihelion, so a
    fan of arrows is the precession). With ``precession_ax``, the direction of ``A`` (unwrapped,
    degrees) against time on that axes: a straight line whose slope is the precession rate.

    ``A`` is scaled to the orbit's size for display (its length is ``mu k e``).

    Returns
    -------
    (orbit Line2D, arrows Quiver, precession Line2D or None)
    """
    arrows = as_int("arrows", arrows, minimum=1, maximum=1000)
    a_vec = lrl_history(system, result)
    ax = new_axes(ax)
    lab = Labels(system, 2)
    (orbit,) = ax.plot(result.q[:, 0], result.q[:, 1], lw=0.7, color="C0", label="orbit")
    ax.plot([0.0], [0.0], marker="*", color="orange", ms=12, ls="", label="force centre")
    idx = np.unique(np.linspace(0, len(result.t) - 1, arrows).round().astype(int))
    size = np.abs(result.q).max()
    norm = np.linalg.norm(a_vec[idx], axis=1)
    scale = np.where(norm > 0, 0.9 * size / np.where(norm > 0, norm, 1.0), 0.0)
    u = a_vec[idx, 0] * scale
    v = a_vec[idx, 1] * scale
    colours = pyplot().get_cmap("plasma")(np.linspace(0.0, 0.85, len(idx)))
    quiver = ax.quiver(np.zeros(len(idx)), np.zeros(len(idx)), u, v, color=colours,
                       angles="xy", scale_units="xy", scale=1.0, width=0.006)
    ax.plot([], [], color=colours[-1], lw=2, label="LRL vector $A$ (direction)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(lab.q(0))
    ax.set_ylabel(lab.q(1))
    ax.legend(fontsize="small", loc="upper right")
    line = None
    if precession_ax is not None:
        angle = np.degrees(np.unwrap(np.arctan2(a_vec[:, 1], a_vec[:, 0])))
        (line,) = precession_ax.plot(result.t, angle - angle[0], color="C1")
        precession_ax.set_xlabel(lab.t)
        precession_ax.set_ylabel(r"perihelion advance $\Delta\varpi$ (deg)")
    return orbit, quiver, line
