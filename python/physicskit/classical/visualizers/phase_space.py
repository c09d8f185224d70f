"""Phase-space pictures on stored arrays (the peer's ``visualizers.phase_space``), drawn by
:mod:`physicskit.classical.plotting`. Each returns the axes it drew on."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import numpy as np

from .._native import as_int, as_scalar
from ..plotting import phase_portrait, poincare, polhodes
from ..plotting._mpl import new_axes

__all__ = [
    "plot_phase_portrait",
    "plot_phase_swarm",
    "poincare_section",
    "plot_poincare_section",
    "plot_so3_momentum_sphere",
]


def _columns(name: str, value: Any) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 1:
        arr = arr[:, None]
    if arr.ndim != 2 or len(arr) == 0:
        raise ValueError(f"{name} must be 1-D or 2-D (n_samples, ndof), got shape {arr.shape}")
    return arr


def plot_phase_portrait(q: np.ndarray, p: np.ndarray, ax=None, label=None, **kwargs):
    """One trajectory in the ``(q, p)`` plane: ``q``, ``p`` 1-D (one degree of freedom) or
    ``(n_samples, ndof)`` (one curve per column, labelled ``label [i]``). ``kwargs`` go to
    each line (``Line2D.set``). Returns the axes."""
    qa, pa = _columns("q", q), _columns("p", p)
    if qa.shape != pa.shape:
        raise ValueError(f"q and p must have the same shape, got {qa.shape} and {pa.shape}")
    # A stored run as the plotting layer reads it (``t`` and ``y`` mark it as one run).
    run = SimpleNamespace(t=np.arange(len(qa), dtype=float), y=np.hstack([qa, pa]), q=qa, p=pa)
    lines = phase_portrait(run, dof=None, separatrix=False, ax=ax)
    for i, line in enumerate(lines):
        if label is not None:
            line.set_label(label if len(lines) == 1 else f"{label} [{i}]")
        if kwargs:
            line.set(**kwargs)
    axes = lines[0].axes
    if label is not None:
        axes.legend(fontsize="small")
    return axes


def plot_phase_swarm(q: np.ndarray, p: np.ndarray, ax=None, s=4, **kwargs):
    """A cloud of phase points ``(q_i, p_i)`` (e.g. a ``PendulumSwarm`` state) as a scatter
    of marker size ``s``; ``kwargs`` go to ``ax.scatter``. Returns the axes."""
    qa = np.asarray(q, dtype=np.float64).ravel()
    pa = np.asarray(p, dtype=np.float64).ravel()
    if qa.shape != pa.shape:
        raise ValueError(f"q and p must have the same length, got {qa.size} and {pa.size}")
    ax = new_axes(ax)
    ax.scatter(qa, pa, s=as_scalar("s", s), **kwargs)
    ax.set_xlabel("$q$")
    ax.set_ylabel("$p$")
    return ax


def poincare_section(q: np.ndarray, p: np.ndarray, section_q: np.ndarray,
                     section_p: np.ndarray, value: float = 0.0, direction: int = 1):
    """Crossings of ``section_q`` through ``value`` (increasing for ``direction = 1``,
    decreasing for ``-1``) in a stored trajectory, and ``(q, p)`` there, linearly interpolated
    between the two samples around each crossing. All four arrays have one entry per sample
    (``section_p`` only its length is used: the section is ``section_q = value``). Returns
    ``(crossings_q, crossings_p)``.

    On stored samples this is first-order accurate in the sample spacing; ``poincare_section``
    of :mod:`physicskit.classical.chaos` locates crossings on the integrator's own steps
    (Hénon's trick) instead."""
    arrays = [np.asarray(a, dtype=np.float64).ravel() for a in (q, p, section_q, section_p)]
    n = len(arrays[0])
    if any(len(a) != n for a in arrays):
        raise ValueError("q, p, section_q and section_p must have the same length")
    direction = as_int("direction", direction, minimum=-1)
    if direction not in (1, -1):
        raise ValueError(f"direction must be 1 or -1, got {direction}")
    value = as_scalar("value", value)
    qa, pa, s, _sp = arrays
    d0, d1 = s[:-1] - value, s[1:] - value
    hit = (d0 < 0.0) & (d1 >= 0.0) if direction == 1 else (d0 > 0.0) & (d1 <= 0.0)
    i = np.nonzero(hit)[0]
    frac = d0[i] / (d0[i] - d1[i])
    return qa[i] + frac * (qa[i + 1] - qa[i]), pa[i] + frac * (pa[i + 1] - pa[i])


def plot_poincare_section(q, p, section_q, section_p, value=0.0, direction=1, ax=None,
                          **kwargs):
    """Scatter of :func:`poincare_section`'s crossings; ``kwargs`` go to the scatter
    (``PathCollection.set``). Returns the axes."""
    cq, cp = poincare_section(q, p, section_q, section_p, value, direction)
    size = as_scalar("s", kwargs.pop("s", 2.0))  # scatter's marker size, poincare's own
    (points,) = poincare(np.column_stack([cq, cp]), x=0, y=1, s=size, ax=ax)
    if kwargs:
        points.set(**kwargs)
    return points.axes


def plot_so3_momentum_sphere(omega_trajectory: np.ndarray, I1: float, I2: float, I3: float,
                             ax=None, n_grid: int = 40):
    """The body angular momentum ``L = (I1 w1, I2 w2, I3 w3)`` of a rigid body's run
    (``omega_trajectory`` of shape ``(n_samples, 3)``, e.g. an ``EulerTop`` run's
    ``result.y[:, :3]``) on the sphere ``|L| = |L(0)|``: the polhode. ``n_grid`` (>= 2) is
    checked; the sphere is drawn at :func:`physicskit.classical.plotting.polhodes`'s own
    resolution. Returns the 3-D axes."""
    from ..systems.rotations import EulerTop

    as_int("n_grid", n_grid, minimum=2)
    w = np.asarray(omega_trajectory, dtype=np.float64)
    if w.ndim != 2 or w.shape[1] < 3 or len(w) == 0:
        raise ValueError(f"omega_trajectory must have shape (n_samples, 3), got {w.shape}")
    top = EulerTop(w[0, :3], I1=I1, I2=I2, I3=I3)
    # The polhode reads only the angular velocity; the orientation columns are the identity.
    y = np.zeros((len(w), 7))
    y[:, :3] = w[:, :3]
    y[:, 3] = 1.0
    (line,) = polhodes(top, SimpleNamespace(t=np.arange(len(w), dtype=float), y=y), ax=ax)
    return line.axes
