"""Normal-mode energies of a chain as bars (the peer's ``visualizers.modal_analysis``), from
the system's own ``modal_energies``."""

from __future__ import annotations

import numpy as np

from .._native import as_int
from ..plotting._mpl import new_axes
from ..plotting.lattices import modal_history

__all__ = ["plot_modal_energy_bars", "animate_modal_energies"]


def plot_modal_energy_bars(system, q: np.ndarray, p: np.ndarray, ax=None, **kwargs):
    """Bar chart of the energy ``E_k`` of each normal mode ``k = 1..n`` of ``system`` (a chain
    with ``modal_energies(q, p)``) at the state ``(q, p)``; ``kwargs`` go to ``ax.bar``.
    Returns the axes."""
    if not hasattr(system, "modal_energies"):
        raise ValueError(f"{type(system).__name__} has no normal modes (modal_energies)")
    energies = np.asarray(system.modal_energies(q, p))
    ax = new_axes(ax)
    ax.bar(np.arange(1, len(energies) + 1), energies, **kwargs)
    ax.set_xlabel("mode $k$")
    ax.set_ylabel("$E_k$")
    return ax


def animate_modal_energies(system, result, stride: int = 1, interval: int = 30, fig=None,
                           ax=None):
    """A ``FuncAnimation`` of the modal-energy bars over ``result`` (every ``stride``-th
    sample, ``interval`` ms per frame)."""
    from matplotlib.animation import FuncAnimation

    stride = as_int("stride", stride, minimum=1)
    interval = as_int("interval", interval, minimum=1)
    hist = modal_history(system, result)[::stride]
    if ax is None:
        ax = fig.add_subplot() if fig is not None else new_axes()
    bars = ax.bar(np.arange(1, hist.shape[1] + 1), hist[0])
    ax.set_ylim(0.0, 1.05 * max(float(hist.max()), np.finfo(float).tiny))
    ax.set_xlabel("mode $k$")
    ax.set_ylabel("$E_k$")
    t = np.asarray(result.t)[::stride]
    title = ax.set_title("")

    def frame(k):
        for bar, h in zip(bars, hist[k]):
            bar.set_height(h)
        title.set_text(f"$t$ = {t[k]:.2f}")
        return list(bars) + [title]

    return FuncAnimation(ax.figure, frame, frames=len(hist), interval=interval, blit=False)
