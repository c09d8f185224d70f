"""Chains: the energy in each normal mode over time (lines, stacked areas, heatmap).

Modal energies are the system's own (``system.modal_energies(q, p)``, the sine transform of
the fixed-end harmonic chain), evaluated at each stored sample.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from ._data import has_qp
from ._labels import Labels
from ._mpl import new_axes, pyplot


def modal_history(system: Any, result: Any) -> np.ndarray:
    """``E_j`` at every stored sample, shape ``(n_samples, n_modes)``, from the system's
    ``modal_energies``."""
    if not hasattr(system, "modal_energies"):
        raise ValueError(f"{type(system).__name__} has no normal modes (modal_energies)")
    if not has_qp(result):
        raise ValueError("the result has no q and p")
    return np.array([system.modal_energies(q, p) for q, p in zip(result.q, result.p)])


def _energy_label(system: Any) -> str:
    unit = "energy" if Labels(system).time_unit != "s" else "J"
    return f"$E_j$ ({unit})"


def modal_energies(system: Any, result: Any, *, modes: Sequence[int] | None = None,
                   stacked: bool = False, ax: Any = None) -> list[Any]:
    """Energy of normal modes against time: one line per mode, or stacked areas
    (``stacked=True``: their sum is the harmonic part of the energy).

    Parameters
    ----------
    system : chain with ``modal_energies`` (``FPUTChain``, ``HarmonicChain``, ``SineGordonChain``)
    result : its run
    modes : sequence of int, optional
        Mode numbers ``j`` (1-based, as in the literature); default: the modes that ever hold
        more than 1% of the total, at most ten.
    stacked : bool
    ax : Axes, optional

    Returns
    -------
    list of ``Line2D`` (lines) or ``PolyCollection`` (stacked).
    """
    hist = modal_history(system, result)
    n_modes = hist.shape[1]
    if modes is None:
        share = hist.max(axis=0) / max(hist.sum(axis=1).max(), np.finfo(float).tiny)
        chosen = [int(j) + 1 for j in np.argsort(-share) if share[j] > 0.01][:10]
        modes = sorted(chosen) if chosen else [1]
    modes = [int(j) for j in modes]
    for j in modes:
        if not 1 <= j <= n_modes:
            raise ValueError(f"mode {j} is out of range 1..{n_modes}")
    ax = new_axes(ax)
    cols = [hist[:, j - 1] for j in modes]
    names = [f"mode {j}" for j in modes]
    if stacked:
        artists = list(ax.stackplot(result.t, *cols, labels=names))
    else:
        artists = [ax.plot(result.t, c, lw=1.0, label=n)[0] for c, n in zip(cols, names)]
    ax.set_xlabel(Labels(system).t)
    ax.set_ylabel(_energy_label(system))
    ax.legend(fontsize="small", ncol=2, loc="upper right")
    return artists


def modal_heatmap(system: Any, result: Any, *, log: bool = True, floor: float = 1e-10,
                  ax: Any = None) -> Any:
    """Heatmap of ``E_j(t)``: time across, mode number up, colour the energy (log scale
    by default, values below ``floor`` times the maximum clipped to it).

    Returns the ``QuadMesh`` (its colour bar is attached to the same figure).
    """
    from matplotlib.colors import LogNorm, Normalize

    hist = modal_history(system, result)
    ax = new_axes(ax)
    top = hist.max()
    norm: Any
    if log and top > 0:
        norm = LogNorm(vmin=top * floor, vmax=top)
        hist = np.maximum(hist, top * floor)
    else:
        norm = Normalize(vmin=0.0, vmax=top if top > 0 else 1.0)
    modes = np.arange(1, hist.shape[1] + 1)
    mesh = ax.pcolormesh(result.t, modes, hist.T, norm=norm, shading="nearest", cmap="magma")
    pyplot().colorbar(mesh, ax=ax, label=_energy_label(system))
    ax.set_xlabel(Labels(system).t)
    ax.set_ylabel("mode number $j$")
    return mesh
