"""The one place matplotlib is imported, with the message a user sees when it is missing."""

from __future__ import annotations

from typing import Any

import numpy as np

INSTALL_HINT = (
    "physicskit.classical.plotting needs matplotlib (and pillow to save GIFs): "
    "pip install physicskit[plot]  (or: pip install matplotlib pillow)"
)


def pyplot() -> Any:
    """``matplotlib.pyplot``, or ImportError naming the extra to install."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:
        raise ImportError(INSTALL_HINT) from exc
    return plt


def new_axes(ax: Any = None, projection: str | None = None) -> Any:
    """``ax`` itself, or the axes of a new figure (3-D when ``projection="3d"``)."""
    if ax is not None:
        if projection == "3d" and getattr(ax, "name", "") != "3d":
            raise ValueError("ax must be a 3-D axes (fig.add_subplot(projection='3d'))")
        return ax
    fig = pyplot().figure(figsize=(6.0, 5.0) if projection == "3d" else (6.4, 4.2),
                          layout=None if projection == "3d" else "constrained")
    return fig.add_subplot(projection=projection)


def orbit_colours(n: int) -> list[Any]:
    """``n`` distinct colours: the cycle ``C0..C9`` up to ten, a viridis ramp beyond."""
    if n <= 10:
        return [f"C{k}" for k in range(n)]
    import matplotlib

    return list(matplotlib.colormaps["viridis"](np.linspace(0.0, 1.0, n)))
