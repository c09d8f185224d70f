"""Interactive plotly figures (the peer's ``visualizers.interactive``): a planar orbit and a
rigid body's polhode, to zoom and turn. Needs plotly: ``pip install physicskit[interactive]``
(imported when a function is called, not with this module)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["interactive_orbit", "interactive_so3_momentum_sphere"]

_HINT = ("physicskit.classical.visualizers.interactive needs plotly: "
         "pip install physicskit[interactive]  (or: pip install plotly)")


def _go() -> Any:
    try:
        import plotly.graph_objects as go  # type: ignore[import-not-found]
    except ImportError as exc:
        raise ImportError(_HINT) from exc
    return go


def interactive_orbit(result, system=None, title: str | None = None) -> Any:
    """The orbit ``result.q[:, :2]`` as a plotly figure, equal axes; with a ``system`` that
    has ``lrl_vector(q, p)`` (a ``KeplerSystem``), its Laplace–Runge–Lenz vector at the first
    and last sample drawn from the origin (a turned vector is apsidal precession)."""
    go = _go()
    q = np.asarray(result.q, dtype=float).reshape(len(result.t), -1)
    if q.shape[1] < 2:
        raise ValueError("interactive_orbit needs a planar run (q with two columns)")
    fig = go.Figure()
    fig.add_trace(go.Scatter(x=q[:, 0], y=q[:, 1], mode="lines", name="orbit"))
    fig.add_trace(go.Scatter(x=[0.0], y=[0.0], mode="markers", name="centre",
                             marker=dict(symbol="star", size=12, color="black")))
    lrl = getattr(system, "lrl_vector", None)
    if callable(lrl) and result.p is not None:
        p = np.asarray(result.p, dtype=float).reshape(len(result.t), -1)
        for i, name in ((0, "LRL vector, start"), (len(q) - 1, "LRL vector, end")):
            a = np.asarray(lrl(q[i], p[i]), dtype=float)
            fig.add_trace(go.Scatter(x=[0.0, a[0]], y=[0.0, a[1]], mode="lines+markers",
                                     name=name))
    fig.update_layout(title=title, xaxis_title="x", yaxis_title="y")
    fig.update_yaxes(scaleanchor="x", scaleratio=1)
    return fig


def interactive_so3_momentum_sphere(omega_trajectory: np.ndarray, I1: float, I2: float,
                                    I3: float, n_grid: int = 40,
                                    title: str | None = None) -> Any:
    """The body angular momentum of a rigid body's run on the sphere ``|L| = |L(0)|``, as a
    plotly 3-D figure; ``L`` from an ``EulerTop`` with moments ``I1, I2, I3``
    (``body_angular_momentum``), the sphere a wireframe of ``n_grid`` lines per angle."""
    from .._native import as_int
    from ..systems.rotations import EulerTop

    go = _go()
    n_grid = as_int("n_grid", n_grid, minimum=2)
    w = np.asarray(omega_trajectory, dtype=float)
    if w.ndim != 2 or w.shape[1] < 3 or len(w) == 0:
        raise ValueError(f"omega_trajectory must have shape (n_samples, 3), got {w.shape}")
    top = EulerTop(w[0, :3], I1=I1, I2=I2, I3=I3)
    state = np.zeros(7)
    state[3] = 1.0
    body_l = np.empty((len(w), 3))
    for i, row in enumerate(w):
        state[:3] = row[:3]
        body_l[i] = top.body_angular_momentum(state)
    radius = float(np.linalg.norm(body_l[0]))
    u, v = np.meshgrid(np.linspace(0.0, 2.0 * np.pi, n_grid), np.linspace(0.0, np.pi, n_grid))
    xs, ys, zs = (radius * np.cos(u) * np.sin(v), radius * np.sin(u) * np.sin(v),
                  radius * np.cos(v))
    fig = go.Figure()
    for k in range(n_grid):
        for grid in ((xs[k], ys[k], zs[k]), (xs[:, k], ys[:, k], zs[:, k])):
            fig.add_trace(go.Scatter3d(x=grid[0], y=grid[1], z=grid[2], mode="lines",
                                       line=dict(color="lightgray", width=1),
                                       hoverinfo="skip", showlegend=False))
    fig.add_trace(go.Scatter3d(x=body_l[:, 0], y=body_l[:, 1], z=body_l[:, 2], mode="lines",
                               line=dict(width=4), name="L(t)"))
    fig.update_layout(title=title, scene=dict(xaxis_title="L1", yaxis_title="L2",
                                              zaxis_title="L3", aspectmode="data"))
    return fig
